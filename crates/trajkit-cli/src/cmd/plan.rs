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
    /// Time-optimal trajectory generation (Kunz & Stilman): straight segments joined by circular
    /// blends within --max-deviation, timed in the phase plane with exact velocity and
    /// acceleration limits. The blended path is only C¹, so jerk is not bounded.
    Totg,
    /// Numerical integration in the phase plane (Bobrow / TOPP-NI) on the same spline path and
    /// constraints as toppra (--path, --gridpoints as initial knots, --torque-limits).
    Ni,
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
    after_help = "Examples:\n  trajkit plan                                  # embedded Panda path -> trajectory.csv\n  trajkit plan --waypoints path.csv --limits robot.urdf --fill-from panda --out traj.json\n  trajkit plan --method poly --degree septic --via-velocity zero --rate 500 --plot traj.svg\n  trajkit plan --path linear --gridpoints auto\n  trajkit plan --method totg --max-deviation 0.1 --out - | trajkit check --max-jerk inf\n  trajkit plan --waypoints path.csv --limits robot.urdf --torque-limits"
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
    /// Path through the waypoints (--method toppra, ni; totg blends straight segments instead,
    /// see --max-deviation). The robot stops where the path reverses exactly (and at every
    /// corner of a linear path).
    #[arg(long, value_enum, default_value = "natural")]
    pub path: PathArg,
    /// TOPP-RA gridpoints (NI: initial knots) per rest-to-rest piece: an interval count, or
    /// `auto` (from a 1e-4 chord tolerance). Limits are also checked between gridpoints and the
    /// grid refined there.
    #[arg(long, value_name = "N|auto", default_value = "1000", value_parser = parse_gridpoints)]
    pub gridpoints: trajkit::topp::Gridpoints,
    /// With --method toppra or ni: keep the raw phase-plane result (piecewise-constant path
    /// acceleration, unbounded jerk) instead of bounding its jerk.
    #[arg(long)]
    pub no_jerk_limit: bool,
    /// With --method toppra or ni: also hold each joint's torque within its `effort` limit, using the
    /// rigid-body dynamics of a URDF (see --dynamics). The torque is checked again after jerk
    /// bounding and time is slowed down uniformly (up to 4x) if needed.
    #[arg(long)]
    pub torque_limits: bool,
    /// URDF with the robot's chain and inertial parameters for --torque-limits. Default: the
    /// --limits argument when it is a .urdf file.
    #[arg(long, value_name = "FILE.urdf")]
    pub dynamics: Option<PathBuf>,
    /// Largest distance (joint units, Euclidean) between a waypoint and the circular blend that
    /// replaces its corner (--method totg; default 0.1). Must be a finite number > 0.
    #[arg(long, value_name = "RAD", allow_negative_numbers = true)]
    pub max_deviation: Option<f64>,
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

/// Largest uniform time-scale factor tried to bring jerk-bounded output back within torque
/// limits.
const MAX_TORQUE_SCALE: f64 = 4.0;

/// Relative torque excess accepted on samples (TOPP-RA's own tolerance between gridpoints).
const TORQUE_TOLERANCE: f64 = 1e-6;

/// The dynamics model and effort limits for `--torque-limits`.
struct TorqueSetup {
    chain: trajkit::dynamics::SerialChain,
    effort: Vec<f64>,
    source: String,
}

/// Resolves `--torque-limits`: the URDF model (from --dynamics or a .urdf --limits) and every
/// joint's effort limit.
fn torque_setup(a: &PlanArgs, limits: &Limits) -> CliResult<TorqueSetup> {
    if !matches!(a.method, Method::Toppra | Method::Ni) {
        return Err(CliError(
            "--torque-limits needs --method toppra or ni".to_string(),
        ));
    }
    let spec = &a.limits.limits;
    let is_urdf = std::path::Path::new(spec)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("urdf"));
    let path = match (&a.dynamics, is_urdf) {
        (Some(p), _) => p.clone(),
        (None, true) => PathBuf::from(spec),
        (None, false) => {
            return Err(CliError(format!(
                "--torque-limits needs a dynamics model: --limits '{spec}' is not a .urdf file, give --dynamics FILE.urdf"
            )))
        }
    };
    let chain = trajkit::dynamics::SerialChain::from_urdf_file(&path)?;
    let source = path.display().to_string();
    use trajkit::topp::constraint::InverseDynamics;
    if chain.dof() != limits.dof() {
        return Err(CliError(format!(
            "{source}: the dynamics model has {} joints, the limits have {}",
            chain.dof(),
            limits.dof()
        )));
    }
    let mut effort = Vec::with_capacity(limits.dof());
    for (j, jl) in limits.joints().iter().enumerate() {
        match jl.effort {
            Some(e) => effort.push(e),
            None => {
                return Err(CliError(format!(
                    "--torque-limits: joint {} ({}) has no effort limit in --limits '{spec}'",
                    j + 1,
                    jl.name
                )))
            }
        }
    }
    Ok(TorqueSetup {
        chain,
        effort,
        source,
    })
}

/// Worst |τ_j| / effort_j over samples at 1 kHz and at `rate` Hz, and the joint where it
/// occurs.
fn worst_torque_ratio(traj: &dyn Trajectory, t: &TorqueSetup, rate: f64) -> (f64, usize) {
    use trajkit::topp::constraint::InverseDynamics;
    use trajkit::Order;
    let n = traj.dof();
    let (mut q, mut qd, mut qdd, mut tau) =
        (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut worst, mut joint) = (0.0_f64, 0);
    let duration = traj.duration();
    for step in [1e-3, 1.0 / rate] {
        if !(step.is_finite() && step > 0.0) {
            continue;
        }
        let count = (duration / step).ceil() as usize;
        for k in 0..=count {
            let time = (k as f64 * step).min(duration);
            traj.eval(time, Order::Position, &mut q);
            traj.eval(time, Order::Velocity, &mut qd);
            traj.eval(time, Order::Acceleration, &mut qdd);
            t.chain.torque(&q, &qd, &qdd, &mut tau);
            for j in 0..n {
                let r = tau[j].abs() / t.effort[j];
                if r > worst || r.is_nan() {
                    worst = if r.is_nan() { f64::INFINITY } else { r };
                    joint = j;
                }
            }
        }
    }
    (worst, joint)
}

/// The smallest uniform time-scale factor k ∈ [1, MAX_TORQUE_SCALE] keeping the sampled torque
/// within the efforts, by bisection. Slowing down by k leaves τ = g(q) + (M q̈ + C q̇)/k²: for
/// each path point the torque moves along a segment towards the static torque, so once within
/// the limits it stays within them for every larger k, which makes bisection valid.
fn torque_time_scale(
    traj: Box<dyn Trajectory>,
    t: &TorqueSetup,
    rate: f64,
) -> CliResult<(Box<dyn Trajectory>, f64, f64, usize)> {
    use trajkit::topp::Scaled;
    let ok = |r: f64| r <= 1.0 + TORQUE_TOLERANCE;
    let (r1, j1) = worst_torque_ratio(&*traj, t, rate);
    if ok(r1) {
        return Ok((traj, 1.0, r1, j1));
    }
    let at = |k: f64| -> CliResult<(f64, usize)> {
        let s = Scaled::new(&*traj, k)?;
        Ok(worst_torque_ratio(&s, t, rate))
    };
    let (rmax, jmax) = at(MAX_TORQUE_SCALE)?;
    if !ok(rmax) {
        return Err(CliError(format!(
            "--torque-limits: after jerk bounding the torque exceeds the effort limits (worst ratio {r1:.4}) and slowing down {MAX_TORQUE_SCALE}x still leaves ratio {rmax:.4} at joint {}; use --no-jerk-limit or check the efforts in {}",
            jmax + 1,
            t.source
        )));
    }
    let (mut lo, mut hi, mut best) = (1.0, MAX_TORQUE_SCALE, (rmax, jmax));
    while hi - lo > 1e-4 {
        let mid = 0.5 * (lo + hi);
        let r = at(mid)?;
        if ok(r.0) {
            hi = mid;
            best = r;
        } else {
            lo = mid;
        }
    }
    Ok((Box::new(Scaled::new(traj, hi)?), hi, best.0, best.1))
}

/// The jerk stage shared by the phase-plane methods: filter the timing law and rescale time
/// when `limited`, otherwise keep the raw result and say so in `note`.
fn jerk_stage<P: trajkit::Path + Clone + 'static>(
    raw: trajkit::topp::messy::Sequence<trajkit::topp::Parametrized<P>>,
    limits: &Limits,
    limited: bool,
    name: &str,
    note: &mut String,
) -> CliResult<Box<dyn Trajectory>> {
    if limited {
        let jl = trajkit::topp::jerk::limit_jerk_sequence(
            &raw,
            limits,
            &trajkit::topp::jerk::JerkOptions::default(),
        )?;
        *note = format!(
            "jerk: bounded ({name} {:.6} s, filtered and rescaled +{:.2}%)",
            raw.duration(),
            100.0 * (jl.duration() / raw.duration() - 1.0)
        );
        Ok(Box::new(jl))
    } else {
        *note = format!("jerk: not limited (--no-jerk-limit or no jerk limits): {name}'s path acceleration is piecewise constant");
        Ok(Box::new(raw))
    }
}

/// Runs `trajkit plan`.
pub fn run(a: &PlanArgs) -> CliResult<u8> {
    let (w, src, removed) = load_waypoints(&a.waypoints)?;
    let limits = a.limits.load()?;
    limits
        .expect_dof(w.dof(), "the waypoints")
        .map_err(|e| CliError(format!("{src}: {e}")))?;
    check_waypoints_in_range(&w, &limits, &src)?;
    let torque = if a.torque_limits {
        Some(torque_setup(a, &limits)?)
    } else if a.dynamics.is_some() {
        return Err(CliError(
            "--dynamics is used only with --torque-limits".to_string(),
        ));
    } else {
        None
    };
    if a.max_deviation.is_some() && a.method != Method::Totg {
        return Err(CliError(
            "--max-deviation is used only with --method totg".to_string(),
        ));
    }
    let has_jerk = limits.joints().iter().any(|j| j.jerk.is_finite());
    let phase_plane = matches!(a.method, Method::Toppra | Method::Ni | Method::Totg);
    // TOTG's blended path is only C¹: its curvature jumps where arcs meet segments, so joint
    // acceleration jumps there at any timing and no retiming bounds jerk.
    let jerk_limited =
        matches!(a.method, Method::Toppra | Method::Ni) && has_jerk && !a.no_jerk_limit;
    let mut note = String::new();
    let traj: Box<dyn Trajectory> = match a.method {
        Method::Totg => {
            let opts = trajkit::topp::TotgOptions {
                max_deviation: a.max_deviation.unwrap_or(0.1),
                ..Default::default()
            };
            let raw = trajkit::topp::plan_totg(w.points(), w.dof(), &limits, &opts)?;
            note = format!(
                "jerk: not bounded: the blended path (max deviation {}) is only C¹, joint acceleration jumps where arcs meet segments; checked for velocity and acceleration",
                opts.max_deviation
            );
            Box::new(raw)
        }
        Method::Toppra | Method::Ni => {
            use trajkit::topp::messy::{plan_waypoints, PieceSolver, PlanOptions};
            let opts = PlanOptions {
                solver: if a.method == Method::Ni {
                    PieceSolver::Ni
                } else {
                    PieceSolver::Toppra
                },
                kind: a.path.into(),
                toppra: trajkit::topp::Options {
                    gridpoints: a.gridpoints.clone(),
                    ..Default::default()
                },
                torque: torque
                    .as_ref()
                    .map(|t| trajkit::topp::messy::TorqueModel::new(t.chain.clone())),
                ..Default::default()
            };
            let raw = plan_waypoints(w.points(), w.dof(), &limits, &opts)?;
            let name = if a.method == Method::Ni {
                "NI"
            } else {
                "TOPP-RA"
            };
            jerk_stage(raw, &limits, jerk_limited, name, &mut note)?
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
    let mut torque_note = String::new();
    let traj = match &torque {
        None => traj,
        Some(t) => {
            let (traj, k, ratio, joint) = torque_time_scale(traj, t, a.output.rate)?;
            let verdict = if ratio <= 1.0 + TORQUE_TOLERANCE {
                "within effort limits"
            } else {
                "EFFORT EXCEEDED"
            };
            torque_note = format!(
                "torque: worst ratio {ratio:.6} (joint {}) — {verdict}; dynamics from {}",
                joint + 1,
                t.source
            );
            if k > 1.0 {
                torque_note +=
                    &format!("; time slowed down x{k:.4} after jerk bounding to hold the torque");
            }
            traj
        }
    };
    let names: Vec<String> = w.names().to_vec();
    let table = trajkit::sample::sample(&*traj, a.output.rate)?.with_names(names.clone())?;
    // Raw phase-plane output (TOPP-RA, NI, TOTG) is second order (piecewise-constant path
    // acceleration): its verdict leaves jerk out and says so. Every other result is checked against every limit.
    let checked_limits = if phase_plane && !jerk_limited {
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
    if !torque_note.is_empty() {
        let _ = writeln!(s, "{torque_note}");
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
    super::common::print_summary(&a.out, &s);
    Ok(0)
}
