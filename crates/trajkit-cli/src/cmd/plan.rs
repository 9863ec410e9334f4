//! `trajkit plan`: waypoints + limits → sampled trajectory, summary, optional plot.

use super::common::{CliError, CliResult, LimitsArgs, OutputArgs, Outputs};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use trajkit::check::{check_samples, Tolerance};
use trajkit::io::Waypoints;
use trajkit::poly::{Degree, ViaTiming, ViaTrajectory, ViaVelocities};
use trajkit::{Limits, Trajectory};

/// The embedded default path (7-joint Panda, 8 waypoints).
pub const DEFAULT_WAYPOINTS: &str = include_str!("../default_waypoints.csv");

/// Time-parameterization method.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Time-optimal parameterization (TOPP-RA) of a C² spline through the waypoints, within the
    /// velocity and acceleration limits; then jerk bounded by filtering the timing law and
    /// rescaling time (unless --no-jerk-limit or no joint has a jerk limit).
    Toppra,
    /// Synchronized polynomial segments between waypoints, each as short as the limits allow.
    Poly,
}

/// Geometric path through the waypoints for `--method toppra`.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathArg {
    /// Natural cubic spline (C², zero curvature at the ends), chord-length parameterized.
    Natural,
    /// Not-a-knot cubic spline (C²).
    NotAKnot,
    /// Cubic spline with zero end slopes (C²).
    Clamped,
    /// Straight segments; the robot stops at every corner.
    Linear,
}

impl From<PathArg> for trajkit::topp::messy::PathKind {
    fn from(p: PathArg) -> Self {
        use trajkit::topp::messy::PathKind;
        match p {
            PathArg::Natural => PathKind::NaturalCubic,
            PathArg::NotAKnot => PathKind::NotAKnotCubic,
            PathArg::Clamped => PathKind::ClampedCubic,
            PathArg::Linear => PathKind::Linear,
        }
    }
}

/// Parses `--gridpoints`: a positive interval count or `auto`.
fn parse_gridpoints(s: &str) -> Result<trajkit::topp::Gridpoints, String> {
    use trajkit::topp::Gridpoints;
    if s == "auto" {
        return Ok(Gridpoints::Auto { tolerance: 1e-4 });
    }
    match s.parse::<usize>() {
        Ok(n) if n > 0 => Ok(Gridpoints::Uniform(n)),
        _ => Err(format!("'{s}' is not a positive interval count or 'auto'")),
    }
}

/// Polynomial degree for `--method poly`.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum DegreeArg {
    /// Degree 3 (acceleration jumps at waypoints; jerk not limited).
    Cubic,
    /// Degree 5, minimum jerk.
    Quintic,
    /// Degree 7, continuous jerk.
    Septic,
}

impl From<DegreeArg> for Degree {
    fn from(d: DegreeArg) -> Degree {
        match d {
            DegreeArg::Cubic => Degree::Cubic,
            DegreeArg::Quintic => Degree::Quintic,
            DegreeArg::Septic => Degree::Septic,
        }
    }
}

/// Velocities at interior waypoints for `--method poly`.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViaArg {
    /// Continuous-velocity heuristic (stop only where a joint turns around).
    Heuristic,
    /// Stop at every waypoint.
    Zero,
}

/// Arguments of `trajkit plan`.
#[derive(Args, Debug)]
#[command(
    after_help = "Examples:\n  trajkit plan                                  # embedded Panda path -> trajectory.csv\n  trajkit plan --waypoints path.csv --limits robot.urdf --fill-from panda --out traj.json\n  trajkit plan --method poly --degree septic --via-velocity zero --rate 500 --plot traj.svg\n  trajkit plan --path linear --gridpoints auto"
)]
pub struct PlanArgs {
    /// Waypoints: CSV (a row per waypoint, a column per joint, optional header) or JSON.
    /// Without it, an embedded 7-joint Panda path is used.
    #[arg(long, value_name = "FILE")]
    pub waypoints: Option<PathBuf>,
    #[command(flatten)]
    pub limits: LimitsArgs,
    /// Time-parameterization method.
    #[arg(long, value_enum, default_value = "toppra")]
    pub method: Method,
    /// Path through the waypoints (--method toppra). The robot stops where the path reverses
    /// exactly (and at every corner of a linear path).
    #[arg(long, value_enum, default_value = "natural")]
    pub path: PathArg,
    /// TOPP-RA gridpoints per rest-to-rest piece: an interval count, or `auto` (from a 1e-4
    /// chord tolerance). Limits are also checked between gridpoints and the grid refined there.
    #[arg(long, value_name = "N|auto", default_value = "1000", value_parser = parse_gridpoints)]
    pub gridpoints: trajkit::topp::Gridpoints,
    /// With --method toppra: keep TOPP-RA's raw result (piecewise-constant path acceleration,
    /// unbounded jerk) instead of bounding its jerk.
    #[arg(long)]
    pub no_jerk_limit: bool,
    /// Polynomial degree of each segment (--method poly).
    #[arg(long, value_enum, default_value = "quintic")]
    pub degree: DegreeArg,
    /// Velocities at interior waypoints (--method poly).
    #[arg(long, value_enum, default_value = "heuristic")]
    pub via_velocity: ViaArg,
    /// Output table (CSV or JSON by extension; '-' for standard output).
    #[arg(long, short, value_name = "FILE", default_value = "trajectory.csv")]
    pub out: PathBuf,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// Loads waypoints (file or embedded default) and removes consecutive duplicates.
pub fn load_waypoints(path: &Option<PathBuf>) -> CliResult<(Waypoints, String, usize)> {
    let (mut w, src) = match path {
        Some(p) => (Waypoints::from_file(p)?, p.display().to_string()),
        None => (
            Waypoints::from_csv(DEFAULT_WAYPOINTS, "<embedded default>")?,
            "<embedded default: 7-joint Panda, 8 waypoints>".to_string(),
        ),
    };
    let removed = w.dedup(0.0);
    if w.len() < 2 {
        return Err(CliError(format!(
            "{src}: {}",
            trajkit::Error::TooFewWaypoints {
                needed: 2,
                found: w.len()
            }
        )));
    }
    Ok((w, src, removed))
}

/// Refuses waypoints outside the joints' position ranges.
pub fn check_waypoints_in_range(w: &Waypoints, limits: &Limits, src: &str) -> CliResult<()> {
    for i in 0..w.len() {
        for (j, &q) in w.point(i).iter().enumerate() {
            let jl = limits.joint(j);
            if q < jl.position_min || q > jl.position_max {
                return Err(CliError(format!(
                    "{src}: waypoint {i} joint {} ({}) = {q} is outside the position range [{}, {}]",
                    j + 1,
                    w.names()[j],
                    jl.position_min,
                    jl.position_max
                )));
            }
        }
    }
    Ok(())
}

/// Runs `trajkit plan`.
pub fn run(a: &PlanArgs) -> CliResult<u8> {
    let (w, src, removed) = load_waypoints(&a.waypoints)?;
    let limits = a.limits.load()?;
    limits
        .expect_dof(w.dof(), "the waypoints")
        .map_err(|e| CliError(format!("{src}: {e}")))?;
    check_waypoints_in_range(&w, &limits, &src)?;
    let has_jerk = limits.joints().iter().any(|j| j.jerk.is_finite());
    let jerk_limited = a.method == Method::Toppra && has_jerk && !a.no_jerk_limit;
    let mut note = String::new();
    let traj: Box<dyn Trajectory> = match a.method {
        Method::Toppra => {
            use trajkit::topp::messy::{plan_waypoints, PlanOptions};
            let opts = PlanOptions {
                kind: a.path.into(),
                toppra: trajkit::topp::Options {
                    gridpoints: a.gridpoints.clone(),
                    ..Default::default()
                },
                ..Default::default()
            };
            let raw = plan_waypoints(w.points(), w.dof(), &limits, &opts)?;
            if jerk_limited {
                let jl = trajkit::topp::jerk::limit_jerk_sequence(
                    &raw,
                    &limits,
                    &trajkit::topp::jerk::JerkOptions::default(),
                )?;
                note = format!(
                    "jerk: bounded (TOPP-RA {:.6} s, filtered and rescaled +{:.2}%)",
                    raw.duration(),
                    100.0 * (jl.duration() / raw.duration() - 1.0)
                );
                Box::new(jl)
            } else {
                note = "jerk: not limited (--no-jerk-limit or no jerk limits): TOPP-RA's path acceleration is piecewise constant".into();
                Box::new(raw)
            }
        }
        Method::Poly => {
            let vel = match a.via_velocity {
                ViaArg::Heuristic => ViaVelocities::Heuristic,
                ViaArg::Zero => ViaVelocities::Zero,
            };
            Box::new(ViaTrajectory::new(
                w.points(),
                w.dof(),
                a.degree.into(),
                vel,
                ViaTiming::Limits(&limits),
            )?)
        }
    };
    let names: Vec<String> = w.names().to_vec();
    let table = trajkit::sample::sample(&*traj, a.output.rate)?.with_names(names.clone())?;
    // Raw TOPP-RA is second order (piecewise-constant path acceleration): its verdict leaves
    // jerk out and says so. Every other result is checked against every limit.
    let checked_limits = if a.method == Method::Toppra && !jerk_limited {
        limits
            .clone()
            .with_override(trajkit::Order::Jerk, &[f64::INFINITY])?
    } else {
        limits.clone()
    };
    let report = check_samples(&table, &checked_limits)?;
    let mut outputs = Outputs::default();
    outputs.add(&a.out, a.output.render(&table, &a.out));
    if let Some(p) = &a.output.plot {
        let opts = trajkit::plot::PlotOptions {
            title: format!("trajkit plan ({:?}) — {src}", a.method).to_lowercase(),
            ..Default::default()
        };
        outputs.add(p, trajkit::plot::svg(&table, Some(&limits), &opts)?);
    }
    outputs.commit()?;
    // Summary (to stderr when the table went to stdout).
    let mut s = String::new();
    use std::fmt::Write;
    let _ = writeln!(s, "waypoints: {} ({} joints) from {src}", w.len(), w.dof());
    if removed > 0 {
        let _ = writeln!(s, "removed {removed} duplicate waypoint(s)");
    }
    let _ = writeln!(
        s,
        "method: {:?}, duration: {:.6} s, {} samples at {} Hz",
        a.method,
        traj.duration(),
        table.len(),
        a.output.rate
    );
    if !note.is_empty() {
        let _ = writeln!(s, "{note}");
    }
    let _ = writeln!(s, "worst limit ratio per joint (velocity / acceleration / jerk, pointwise and finite-difference):");
    for (j, jr) in report.joints.iter().enumerate() {
        let r = |k: usize| jr.derivatives[k].worst();
        let _ = writeln!(
            s,
            "  {:>2} {:<14} {:.4} / {:.4} / {:.4}   position {:+.4} .. {:+.4} (range {:+.4} .. {:+.4})",
            j + 1,
            names[j],
            r(0),
            r(1),
            r(2),
            jr.position.min,
            jr.position.max,
            limits.joint(j).position_min,
            limits.joint(j).position_max
        );
    }
    let tol = Tolerance::default();
    let verdict = if report.passes(&tol) {
        "within limits".to_string()
    } else {
        format!("LIMITS EXCEEDED: {}", report.violations(&tol).join("; "))
    };
    let _ = writeln!(s, "worst: {:.6} — {verdict}", report.worst());
    let _ = write!(s, "wrote {}", a.out.display());
    if let Some(p) = &a.output.plot {
        let _ = write!(s, " and {}", p.display());
    }
    if a.out.as_os_str() == "-" {
        eprintln!("{s}");
    } else {
        println!("{s}");
    }
    Ok(0)
}
