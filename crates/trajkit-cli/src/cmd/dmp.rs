//! `trajkit dmp`: learn a DMP from one demonstration, reproduce it with a new start, goal or
//! duration. Also the demonstration and via-point helpers shared by `promp` and `kmp`.

use super::common::{finite_list, CliError, CliResult, OutputArgs, Outputs};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};
use trajkit::primitives::{BoundedDmp, Dmp, DmpConfig, ForcingScaling, RolloutOptions};
use trajkit::{Order, SampleTable, Trajectory};

/// A demonstration read from a table file (CSV with columns t, q1..qn, or trajkit JSON).
pub struct DemoFile {
    /// Source name for messages.
    pub src: String,
    /// Times.
    pub t: Vec<f64>,
    /// Positions, row-major.
    pub q: Vec<f64>,
    /// Joint count.
    pub dof: usize,
    /// Joint names (`q1..qn` when the table has none).
    pub names: Vec<String>,
    /// True when the table named its joints.
    pub named: bool,
}

/// Reads a demonstration table.
pub fn read_demo(path: &Path) -> CliResult<DemoFile> {
    let table = trajkit::io::table_from_file(path)?;
    let src = path.display().to_string();
    let q = table
        .matrix(Order::Position)
        .ok_or_else(|| CliError(format!("{src}: no position columns")))?
        .to_vec();
    Ok(DemoFile {
        src,
        t: table.times().to_vec(),
        q,
        dof: table.dof(),
        named: table.names().iter().all(|n| !n.is_empty()),
        names: super::common::display_names(table.names()),
    })
}

/// Reads several demonstrations and checks that their joint counts agree.
pub fn read_demos(paths: &[PathBuf]) -> CliResult<Vec<DemoFile>> {
    let demos: Vec<DemoFile> = paths
        .iter()
        .map(|p| read_demo(p))
        .collect::<CliResult<_>>()?;
    for d in &demos[1..] {
        if d.dof != demos[0].dof {
            return Err(CliError(format!(
                "{}: {} joints, but {} has {}",
                d.src, d.dof, demos[0].src, demos[0].dof
            )));
        }
    }
    Ok(demos)
}

/// A parsed `--via T:Q1,Q2,..` argument.
pub fn parse_via(s: &str, dof: usize) -> CliResult<(f64, Vec<f64>)> {
    let bad = |why: &str| CliError(format!("--via '{s}': {why} (expected T:Q1,Q2,..)"));
    let (t, q) = s.split_once(':').ok_or_else(|| bad("missing ':'"))?;
    let t: f64 = t.trim().parse().map_err(|_| bad("time is not a number"))?;
    if !t.is_finite() {
        return Err(bad("time is not finite"));
    }
    let q: Vec<f64> = q
        .split(',')
        .map(|v| v.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad("a position is not a number"))?;
    if q.len() != dof {
        return Err(bad(&format!("{} positions for {dof} joints", q.len())));
    }
    finite_list("via", &q)?;
    Ok((t, q))
}

/// CSV of a mean and a ±k·σ band: columns t, then per joint `qJ`, `qJ_lo`, `qJ_hi`.
pub fn band_csv(names: &[String], t: &[f64], mean: &[f64], sd: &[f64], k: f64) -> String {
    let dof = names.len();
    let mut s = String::from("t");
    for n in names {
        s.push_str(&format!(",{n},{n}_lo,{n}_hi"));
    }
    s.push('\n');
    for (i, ti) in t.iter().enumerate() {
        s.push_str(&format!("{ti}"));
        for j in 0..dof {
            let (m, d) = (mean[i * dof + j], sd[i * dof + j]);
            s.push_str(&format!(",{m},{},{}", m - k * d, m + k * d));
        }
        s.push('\n');
    }
    s
}

/// Output flags of a probabilistic model (`promp`, `kmp`): the mean table and an optional
/// ±k·σ band.
#[derive(Args, Debug)]
pub struct MeanBandArgs {
    /// Mean trajectory table (CSV or JSON by extension; '-' for standard output).
    #[arg(long, short, value_name = "FILE", default_value = "trajectory.csv")]
    pub out: PathBuf,
    /// Also write the mean and ±k·σ band of positions as CSV (t, qJ, qJ_lo, qJ_hi).
    #[arg(long, value_name = "FILE.csv")]
    pub band: Option<PathBuf>,
    /// Width of the band in standard deviations.
    #[arg(
        long,
        value_name = "K",
        default_value_t = 2.0,
        allow_hyphen_values = true
    )]
    pub sigma: f64,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// Demonstrations and via points of a probabilistic model (`promp`, `kmp`).
#[derive(Args, Debug)]
pub struct DemosArgs {
    /// Demonstrations: CSV with columns t,q1..qn, or trajkit JSON tables (promp: at least
    /// two).
    #[arg(long, value_name = "FILE", required = true)]
    pub demo: Vec<PathBuf>,
    /// Via point: time in seconds from the start, then one position per joint. Repeatable.
    #[arg(long, value_name = "T:Q1,Q2,..", allow_hyphen_values = true)]
    pub via: Vec<String>,
}

impl DemosArgs {
    /// The `--via` points for `dof` joints, each made by `make(t, q)`.
    pub fn vias<V>(&self, dof: usize, make: impl Fn(f64, Vec<f64>) -> V) -> CliResult<Vec<V>> {
        self.via
            .iter()
            .map(|s| parse_via(s, dof).map(|(t, q)| make(t, q)))
            .collect()
    }
}

impl MeanBandArgs {
    /// Prints the summary: `head`, how close the model passes each via point `(t, q)`, and
    /// the `wrote` line of [`MeanBandArgs::write`].
    pub fn print_summary(
        &self,
        head: &str,
        model: &dyn Trajectory,
        vias: &[(f64, &[f64])],
        wrote: &str,
    ) {
        let s = format!(
            "{head}{}\n{wrote}",
            super::common::via_point_report(model, vias)
        );
        super::common::print_summary(&self.out, &s);
    }

    /// Samples the model's mean, queues table, plot and (with `--band`) the band, whose
    /// per-joint standard deviations `sd(t, out)` writes, and writes everything. Returns the
    /// "wrote …" line of the summary.
    pub fn write(
        &self,
        model: &dyn Trajectory,
        names: &[String],
        title: String,
        mut sd: impl FnMut(f64, &mut [f64]),
    ) -> CliResult<String> {
        let mut outputs = Outputs::default();
        let table = queue_table(model, names, &self.out, &self.output, title, &mut outputs)?;
        if let Some(b) = &self.band {
            let dof = model.dof();
            let t = table.times();
            let mut mean = vec![0.0; t.len() * dof];
            let mut dev = vec![0.0; t.len() * dof];
            for (i, &ti) in t.iter().enumerate() {
                model.eval(ti, Order::Position, &mut mean[i * dof..(i + 1) * dof]);
                sd(ti, &mut dev[i * dof..(i + 1) * dof]);
            }
            outputs.add(b, band_csv(names, t, &mean, &dev, self.sigma));
        }
        outputs.commit()?;
        let mut s = format!("wrote {}", self.out.display());
        for p in [&self.band, &self.output.plot].into_iter().flatten() {
            s.push_str(&format!(" and {}", p.display()));
        }
        Ok(s)
    }
}

/// Samples a trajectory, names its joints and queues table and plot.
pub fn queue_table(
    traj: &dyn Trajectory,
    names: &[String],
    out: &Path,
    output: &OutputArgs,
    title: String,
    outputs: &mut Outputs,
) -> CliResult<SampleTable> {
    let table = trajkit::sample::sample(traj, output.rate)?.with_names(names.to_vec())?;
    outputs.add(out, output.render(&table, out));
    if let Some(p) = &output.plot {
        let opts = trajkit::plot::PlotOptions {
            title,
            ..Default::default()
        };
        outputs.add(p, trajkit::plot::svg(&table, None, &opts)?);
    }
    Ok(table)
}

/// Forcing-term scaling.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScalingArg {
    /// Hoffmann/Pastor 2009 (no blow-up when goal = start).
    Hoffmann,
    /// Ijspeert 2013, f · (g − y0).
    Ijspeert,
}

/// Arguments of `trajkit dmp`.
#[derive(Args, Debug)]
#[command(
    after_help = "Examples:\n  trajkit dmp --demo demo.csv                          # reproduce the demonstration\n  trajkit dmp --demo demo.csv --goal 0.5,0.2 --duration 3 --plot dmp.svg\n  trajkit dmp --demo demo.csv --start 0,0 --scaling ijspeert --out rollout.json"
)]
pub struct DmpArgs {
    /// Demonstration: CSV with columns t,q1..qn (or a trajkit JSON table).
    #[arg(long, value_name = "FILE")]
    pub demo: PathBuf,
    /// New goal, one value per joint.
    #[arg(
        long,
        value_name = "G[,G..]",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub goal: Option<Vec<f64>>,
    /// New start, one value per joint.
    #[arg(
        long,
        value_name = "Y[,Y..]",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub start: Option<Vec<f64>>,
    /// Movement duration τ in seconds (default: the demonstration's).
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub tau: Option<f64>,
    /// Rollout length in seconds (default: τ).
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub duration: Option<f64>,
    /// Forcing-term scaling.
    #[arg(long, value_enum, default_value = "hoffmann")]
    pub scaling: ScalingArg,
    /// Basis functions per joint.
    #[arg(long, value_name = "N", default_value_t = 50)]
    pub basis: usize,
    /// Keep the rollout strictly inside these joints' position limits (robot preset or limits
    /// file, as for `plan --limits`); the demonstration, start and goal must lie inside them.
    #[arg(long, value_name = "PRESET|FILE")]
    pub within: Option<String>,
    /// Output table (CSV or JSON by extension; '-' for standard output).
    #[arg(long, short, value_name = "FILE", default_value = "trajectory.csv")]
    pub out: PathBuf,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// The position limits of `--within spec` for the demonstration's joints (by name when it
/// names them).
fn within_limits(demo: &DemoFile, spec: &str) -> CliResult<trajkit::Limits> {
    let named = demo.named.then_some(&demo.names[..]);
    let (limits, _) = trajkit::limits::load::from_spec(spec)?
        .for_joints("table", named)
        .map_err(|e| CliError(format!("{}: --within {spec}: {e}", demo.src)))?;
    if limits.dof() != demo.dof {
        return Err(CliError(format!(
            "{}: --within {spec} has {} joints, the demonstration {}",
            demo.src,
            limits.dof(),
            demo.dof
        )));
    }
    let position = trajkit::limits::Needs {
        position: true,
        ..trajkit::limits::Needs::NONE
    };
    super::common::complete(&limits, position)
        .map_err(|e| CliError(format!("--within {spec}: {e}")))
}

/// The rollout's RMS error against the demonstration, relative to each joint's range (absolute
/// for a joint that does not move); the worst joint's.
fn reproduction_error(demo: &DemoFile, roll: &dyn Trajectory) -> f64 {
    let mut y = vec![0.0; demo.dof];
    let mut worst: f64 = 0.0;
    for j in 0..demo.dof {
        let (mut se, mut lo, mut hi) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
        for (k, &tk) in demo.t.iter().enumerate() {
            roll.eval(tk - demo.t[0], Order::Position, &mut y);
            let qk = demo.q[k * demo.dof + j];
            se += (y[j] - qk).powi(2);
            lo = lo.min(qk);
            hi = hi.max(qk);
        }
        let rms = (se / demo.t.len() as f64).sqrt();
        worst = worst.max(if hi > lo { rms / (hi - lo) } else { rms });
    }
    worst
}

/// Runs `trajkit dmp`.
pub fn run(a: &DmpArgs) -> CliResult<u8> {
    let demo = read_demo(&a.demo)?;
    for (flag, v) in [("goal", &a.goal), ("start", &a.start)] {
        if let Some(v) = v {
            finite_list(flag, v)?;
            if v.len() != demo.dof {
                return Err(CliError(format!(
                    "--{flag}: {} values for the {} joints of {}",
                    v.len(),
                    demo.dof,
                    demo.src
                )));
            }
        }
    }
    let cfg = DmpConfig {
        n_basis: a.basis,
        scaling: match a.scaling {
            ScalingArg::Hoffmann => ForcingScaling::Hoffmann2009,
            ScalingArg::Ijspeert => ForcingScaling::Ijspeert2013,
        },
        ..Default::default()
    };
    let opts = RolloutOptions {
        goal: a.goal.clone(),
        start: a.start.clone(),
        tau: a.tau,
        duration: a.duration,
        ..Default::default()
    };
    let (roll, tau): (Box<dyn Trajectory>, f64) = match &a.within {
        None => {
            let dmp = Dmp::fit(&demo.t, &demo.q, demo.dof, &cfg)
                .map_err(|e| CliError(format!("{}: {e}", demo.src)))?;
            (Box::new(dmp.rollout(&opts)?), dmp.tau())
        }
        Some(spec) => {
            let limits = within_limits(&demo, spec)?;
            let dmp = BoundedDmp::fit(&demo.t, &demo.q, demo.dof, &cfg, &limits)
                .map_err(|e| CliError(format!("{}: {e}", demo.src)))?;
            (Box::new(dmp.rollout(&opts)?), dmp.inner().tau())
        }
    };
    let roll = &*roll;
    let mut outputs = Outputs::default();
    let title = format!("trajkit dmp ({}) — {}", cfg.scaling.name(), demo.src);
    let table = queue_table(roll, &demo.names, &a.out, &a.output, title, &mut outputs)?;
    outputs.commit()?;
    let mut s = format!(
        "demonstration: {} samples, {} joints, τ = {:.6} s from {}\nrollout: {:.6} s, {} samples at {} Hz, scaling {}",
        demo.t.len(),
        demo.dof,
        tau,
        demo.src,
        roll.duration(),
        table.len(),
        a.output.rate,
        cfg.scaling.name()
    );
    if let Some(spec) = &a.within {
        s.push_str(&format!(
            "\nkept strictly inside the position limits of {spec}"
        ));
    }
    if a.goal.is_none() && a.start.is_none() && a.tau.is_none() {
        s.push_str(&format!(
            "\nreproduction RMS error: {:.3e} of the joint's range (worst joint)",
            reproduction_error(&demo, roll)
        ));
    }
    s.push_str(&format!("\nwrote {}", a.out.display()));
    if let Some(p) = &a.output.plot {
        s.push_str(&format!(" and {}", p.display()));
    }
    super::common::print_summary(&a.out, &s);
    Ok(0)
}
