//! `trajkit plan`: waypoints + limits → sampled trajectory, summary, optional plot.
//!
//! Argument parsing and I/O only: the planning is [`trajkit::plan::plan_with_progress`].

use super::common::{complete, CliError, CliResult, LimitsArgs, OutputArgs, Outputs};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use trajkit::io::Waypoints;
use trajkit::plan::{
    JerkStage, Method as PlanMethod, Plan, PlanOptions, Progress, Stage, ViaVelocity,
};
use trajkit::poly::Degree;
use trajkit::{Limits, Order};

/// The embedded default path (7-joint Panda, 8 waypoints).
pub const DEFAULT_WAYPOINTS: &str = include_str!("../default_waypoints.csv");

/// The jerk stage of toppra and ni.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum JerkStageArg {
    /// Exact optimum on straight-line pieces, the filter elsewhere.
    Auto,
    /// The filter on every piece.
    Filter,
    /// `auto`, plus the third-order time-optimal planner on curved pieces (the shorter result
    /// is kept): shorter motions at low jerk limits, seconds of computation.
    ThirdOrder,
}

/// Time-parameterization method.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Time-optimal parameterization (TOPP-RA) of a C² spline through the waypoints, kept
    /// inside the position ranges, within the velocity and acceleration limits; then the jerk
    /// stage (--jerk-stage; none with --no-jerk-limit).
    Toppra,
    /// Synchronized polynomial segments between waypoints, each as short as the limits allow.
    Poly,
    /// Time-optimal trajectory generation (Kunz & Stilman): straight segments joined by circular
    /// blends within --max-deviation, timed in the phase plane with exact velocity and
    /// acceleration limits. The blended path is only C¹, so jerk is not bounded: needs
    /// --no-jerk-limit (or infinite jerk limits).
    Totg,
    /// Numerical integration in the phase plane (Bobrow / TOPP-NI) on the same spline path and
    /// constraints as toppra (--path, --gridpoints as initial knots, --torque-limits).
    Ni,
}

impl From<Method> for PlanMethod {
    fn from(m: Method) -> Self {
        match m {
            Method::Toppra => PlanMethod::Toppra,
            Method::Poly => PlanMethod::Poly,
            Method::Totg => PlanMethod::Totg,
            Method::Ni => PlanMethod::Ni,
        }
    }
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
    after_help = "Examples:\n  trajkit plan                                  # embedded Panda path -> trajectory.csv\n  trajkit plan --waypoints path.csv --limits ur5e.urdf --fill-from ur5e --out traj.json\n  trajkit plan --waypoints path.csv --limits robot.urdf --joint-limits joint_limits.yaml\n  trajkit plan --waypoints path.csv --max-velocity 1 --max-acceleration 2 --max-jerk 50 --position-range -3:3\n  trajkit plan --method poly --degree septic --via-velocity zero --rate 500 --plot traj.svg\n  trajkit plan --path linear --gridpoints auto\n  trajkit plan --method totg --no-jerk-limit --max-deviation 0.1 --out - | trajkit check --limits panda --max-jerk inf\n  trajkit plan --waypoints path.csv --limits robot.urdf --fill-from panda --fill-by index --torque-limits"
)]
pub struct PlanArgs {
    /// Waypoints: CSV (a row per waypoint, a column per joint, optional header of joint names)
    /// or JSON. Named columns take the limits of their name. Without it, an embedded 7-joint
    /// Panda path is used (with --limits panda unless given).
    #[arg(long, value_name = "FILE")]
    pub waypoints: Option<PathBuf>,
    #[command(flatten)]
    pub limits: LimitsArgs,
    /// Time-parameterization method.
    #[arg(long, value_enum, default_value = "toppra")]
    pub method: Method,
    /// Path through the waypoints (--method toppra, ni; totg blends straight segments instead,
    /// see --max-deviation). The robot stops where the path reverses exactly (and at every
    /// corner of a linear path). Splines are kept inside the position ranges.
    #[arg(long, value_enum, default_value = "natural")]
    pub path: PathArg,
    /// TOPP-RA gridpoints (NI: initial knots) per rest-to-rest piece: `auto` (the grid is
    /// refined until the duration is within 1e-4 relative of the converged optimum) or an
    /// interval count. Limits hold between gridpoints too (see the README).
    #[arg(long, value_name = "auto|N", default_value = "auto", value_parser = parse_gridpoints)]
    pub gridpoints: trajkit::topp::Gridpoints,
    /// Plan without jerk limits: every joint's jerk limit becomes unlimited, and toppra and ni
    /// keep their raw result (piecewise-constant path acceleration). `trajkit check` agrees
    /// with --max-jerk inf.
    #[arg(long, conflicts_with = "max_jerk")]
    pub no_jerk_limit: bool,
    /// How toppra and ni bound jerk. `auto`: a rest-to-rest piece along a straight line
    /// (collinear waypoints, no torque limits) takes the exact jerk-limited optimum along the
    /// line (the 1-D problem of the online generator); other pieces are filtered. `filter`:
    /// every piece's timing law is smoothed by a moving average and time is slowed uniformly
    /// until every limit holds at every instant. `third-order`: `auto`, and on curved pieces
    /// also the jerk-limited time-optimal planner (third-order reachability), keeping the
    /// shorter result (slow: seconds per piece).
    #[arg(
        long,
        value_enum,
        default_value = "auto",
        conflicts_with = "no_jerk_limit"
    )]
    pub jerk_stage: JerkStageArg,
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

/// Loads waypoints (file or embedded default).
pub fn load_waypoints(path: &Option<PathBuf>) -> CliResult<(Waypoints, String)> {
    Ok(match path {
        Some(p) => (Waypoints::from_file(p)?, p.display().to_string()),
        None => (
            Waypoints::from_csv(DEFAULT_WAYPOINTS, "<embedded default>")?,
            "<embedded default: 7-joint Panda, 8 waypoints>".to_string(),
        ),
    })
}

/// The inverse-dynamics model for `--torque-limits`: the URDF of --dynamics or of a .urdf
/// --limits, whose joints must be the waypoint columns in order.
fn torque_model(
    a: &PlanArgs,
    limits: &Limits,
) -> CliResult<Option<(trajkit::topp::messy::TorqueModel, String)>> {
    if !a.torque_limits {
        if a.dynamics.is_some() {
            return Err(CliError(
                "--dynamics is used only with --torque-limits".to_string(),
            ));
        }
        return Ok(None);
    }
    if !matches!(a.method, Method::Toppra | Method::Ni) {
        return Err(CliError(
            "--torque-limits needs --method toppra or ni".to_string(),
        ));
    }
    let spec = a.limits.limits.clone().unwrap_or_default();
    let is_urdf = std::path::Path::new(&spec)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("urdf"));
    let path = match (&a.dynamics, is_urdf) {
        (Some(p), _) => p.clone(),
        (None, true) => PathBuf::from(&spec),
        (None, false) => {
            return Err(CliError(format!(
                "--torque-limits needs a dynamics model: --limits '{spec}' is not a .urdf file, give --dynamics FILE.urdf"
            )))
        }
    };
    let chain = trajkit::dynamics::SerialChain::from_urdf_file(&path)?;
    let source = path.display().to_string();
    let model: Vec<String> = chain.joint_names().iter().map(|s| s.to_string()).collect();
    let cols: Vec<String> = limits.joints().iter().map(|j| j.name.clone()).collect();
    let unnamed = cols.iter().all(String::is_empty);
    if model.len() != cols.len() || (!unnamed && model != cols) {
        return Err(CliError(format!(
            "{source}: the dynamics model's joints [{}] must be the waypoint columns [{}], in order",
            model.join(", "),
            cols.join(", ")
        )));
    }
    for (j, jl) in limits.joints().iter().enumerate() {
        if jl.effort.is_none() {
            return Err(CliError(format!(
                "--torque-limits: {} has no effort limit in the limits given",
                trajkit::error::joint_label(j, &jl.name)
            )));
        }
    }
    Ok(Some((
        trajkit::topp::messy::TorqueModel::new(chain),
        source,
    )))
}

/// Runs `f` with a progress callback; when standard error is a terminal, a line there shows
/// the stage and the elapsed time from the first second on (refreshed four times a second by
/// a helper thread, so a long single solve shows it is alive), and is cleared at the end.
fn with_progress<T>(f: impl FnOnce(&mut dyn FnMut(Progress)) -> T) -> T {
    use std::io::IsTerminal;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Mutex;
    if !std::io::stderr().is_terminal() {
        return f(&mut |_| {});
    }
    let state = Mutex::new(Progress {
        stage: Stage::Path,
        done: 0,
        total: 1,
    });
    let finished = AtomicBool::new(false);
    let start = std::time::Instant::now();
    std::thread::scope(|scope| {
        let ticker = scope.spawn(|| {
            let mut shown = false;
            while !finished.load(Ordering::Relaxed) {
                std::thread::sleep(std::time::Duration::from_millis(250));
                let secs = start.elapsed().as_secs_f64();
                if secs < 1.0 || finished.load(Ordering::Relaxed) {
                    continue;
                }
                let p = *state.lock().unwrap_or_else(|e| e.into_inner());
                let stage = match p.stage {
                    Stage::Path => "building the path".to_string(),
                    Stage::Timing => format!("timing piece {} of {}", p.done + 1, p.total),
                    Stage::Jerk => "bounding jerk".to_string(),
                    Stage::Torque => "holding torques".to_string(),
                    Stage::Verifying => "sampling and checking".to_string(),
                };
                eprint!("\r\x1b[Kplanning: {stage} ({secs:.0} s)");
                shown = true;
            }
            if shown {
                eprint!("\r\x1b[K");
            }
        });
        let out = f(&mut |p| *state.lock().unwrap_or_else(|e| e.into_inner()) = p);
        finished.store(true, Ordering::Relaxed);
        let _ = ticker.join();
        out
    })
}

/// Adds the way out to errors whose fix is a flag.
fn with_hint(e: trajkit::Error) -> CliError {
    match &e {
        trajkit::Error::CannotHold { field: "jerk", .. } => {
            CliError(format!("{e} (--no-jerk-limit, or --max-jerk inf)"))
        }
        _ => CliError(e.to_string()),
    }
}

/// The library's options from the arguments (no torque model yet).
fn plan_options(a: &PlanArgs) -> PlanOptions {
    PlanOptions {
        method: a.method.into(),
        path: a.path.into(),
        gridpoints: a.gridpoints.clone(),
        jerk: if a.no_jerk_limit {
            JerkStage::Off
        } else {
            match a.jerk_stage {
                JerkStageArg::Auto => JerkStage::Auto,
                JerkStageArg::Filter => JerkStage::Filter,
                JerkStageArg::ThirdOrder => JerkStage::ThirdOrder,
            }
        },
        max_deviation: a.max_deviation.unwrap_or(0.1),
        degree: a.degree.into(),
        via_velocity: match a.via_velocity {
            ViaArg::Heuristic => ViaVelocity::Heuristic,
            ViaArg::Zero => ViaVelocity::Zero,
        },
        torque: None,
        sample_rate: a.output.rate,
        phase_plane: false,
    }
}

/// Runs `trajkit plan`.
pub fn run(a: &PlanArgs) -> CliResult<u8> {
    let (w, src) = load_waypoints(&a.waypoints)?;
    let mut distinct = w.clone();
    distinct.dedup(0.0);
    if distinct.len() < 2 {
        let e = trajkit::Error::TooFewWaypoints {
            needed: 2,
            found: distinct.len(),
        };
        return Err(CliError(format!("{src}: {e}")));
    }
    if a.max_deviation.is_some() && a.method != Method::Totg {
        return Err(CliError(
            "--max-deviation is used only with --method totg".to_string(),
        ));
    }
    let default = a.waypoints.is_none().then_some("panda");
    let resolved = a
        .limits
        .resolve("waypoint", w.given_names(), w.dof(), default)
        .map_err(|e| CliError(format!("{src}: {e}")))?;
    let mut partial = resolved.limits;
    if a.no_jerk_limit {
        partial = partial.with_override(Order::Jerk, &[f64::INFINITY])?;
    }
    let mut options = plan_options(a);
    let limits = complete(&partial, options.needs())?;
    let torque = torque_model(a, &limits)?;
    options.torque = torque.as_ref().map(|(m, _)| m.clone());
    let plan = with_progress(|p| trajkit::plan::plan_with_progress(&w, &limits, &options, p))
        .map_err(|e| match e {
            trajkit::Error::WaypointOutOfRange { .. } | trajkit::Error::JointNames { .. } => {
                CliError(format!("{src}: {e}"))
            }
            e => with_hint(e),
        })?;
    let mut outputs = Outputs::default();
    outputs.add(&a.out, a.output.render(&plan.samples, &a.out));
    if let Some(p) = &a.output.plot {
        let opts = trajkit::plot::PlotOptions {
            title: format!(
                "trajkit plan ({}) — {src}",
                a.method.to_possible_value_name()
            ),
            ..Default::default()
        };
        outputs.add(
            p,
            trajkit::plot::svg(&plan.samples, Some(&plan.limits), &opts)?,
        );
    }
    outputs.commit()?;
    let summary = summary(
        a,
        &plan,
        &src,
        &resolved.unused,
        torque.as_ref().map(|t| &t.1),
    );
    super::common::print_summary(&a.out, &summary);
    Ok(0)
}

/// The summary printed after a successful run.
fn summary(
    a: &PlanArgs,
    plan: &Plan,
    src: &str,
    unused: &[String],
    torque_source: Option<&String>,
) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let dof = plan.limits.dof();
    let _ = writeln!(s, "waypoints: {} ({dof} joints) from {src}", plan.waypoints);
    if plan.repeats_removed > 0 {
        let _ = writeln!(s, "removed {} duplicate waypoint(s)", plan.repeats_removed);
    }
    if !unused.is_empty() {
        let _ = writeln!(
            s,
            "limits of {} not used (no waypoint column of that name)",
            unused.join(", ")
        );
    }
    let _ = writeln!(
        s,
        "method: {}, duration: {:.6} s, {} samples at {} Hz",
        a.method.to_possible_value_name(),
        plan.duration(),
        plan.samples.len(),
        a.output.rate
    );
    for n in &plan.notes {
        let _ = writeln!(s, "{n}");
    }
    if let (Some(t), Some(source)) = (&plan.torque, torque_source) {
        let _ = write!(
            s,
            "torque: worst ratio {:.6} (joint {}) — within effort limits; dynamics from {source}",
            t.worst,
            t.joint + 1
        );
        if t.scale > 1.0 {
            let _ = write!(
                s,
                "; time slowed down x{:.4} after jerk bounding to hold the torque",
                t.scale
            );
        }
        s.push('\n');
    }
    s.push_str(&joint_lines(plan));
    let unlimited: Vec<&str> = [
        (Order::Velocity, "velocity"),
        (Order::Acceleration, "acceleration"),
        (Order::Jerk, "jerk"),
    ]
    .into_iter()
    .filter(|(o, _)| {
        plan.limits
            .joints()
            .iter()
            .any(|jl| jl.range(*o).1.is_infinite())
    })
    .map(|(_, n)| n)
    .collect();
    let _ = write!(
        s,
        "worst: {:.6} — within limits (checked as `trajkit check` does",
        plan.report.worst()
    );
    if !unlimited.is_empty() {
        let _ = write!(s, "; unlimited: {}", unlimited.join(", "));
    }
    let _ = writeln!(s, ")");
    let _ = write!(s, "wrote {}", a.out.display());
    if let Some(p) = &a.output.plot {
        let _ = write!(s, " and {}", p.display());
    }
    s
}

/// The per-joint lines of the summary: worst ratios and the position range used.
fn joint_lines(plan: &Plan) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(s, "worst limit ratio per joint (velocity / acceleration / jerk, pointwise and finite-difference):");
    let names = super::common::display_names(plan.samples.names());
    let width = names
        .iter()
        .map(|n| n.chars().count())
        .max()
        .unwrap_or(0)
        .max(14);
    for (j, jr) in plan.report.joints.iter().enumerate() {
        let r = |k: usize| jr.derivatives[k].worst();
        let jl = plan.limits.joint(j);
        let _ = writeln!(
            s,
            "  {:>2} {:<width$} {:.4} / {:.4} / {:.4}   position {:+.4} .. {:+.4} (range {:+.4} .. {:+.4})",
            j + 1,
            names[j],
            r(0),
            r(1),
            r(2),
            jr.position.min,
            jr.position.max,
            jl.position_min,
            jl.position_max
        );
    }
    s
}

impl Method {
    /// The command-line name.
    fn to_possible_value_name(self) -> &'static str {
        PlanMethod::from(self).name()
    }
}
