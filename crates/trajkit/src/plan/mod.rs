//! The main job in one call: waypoints and limits in, a trajectory that keeps every limit out.
//!
//! [`plan`] is what `trajkit plan` runs (and what bindings and servers call): it pairs the
//! waypoint columns with the limits (by joint name when both name their joints, else by
//! position), removes repeated waypoints, refuses waypoints outside the position ranges, times
//! the path with the chosen [`Method`], bounds jerk ([`JerkStage`]), holds joint torques
//! ([`PlanOptions::torque`]), samples the result at [`PlanOptions::sample_rate`] and checks the
//! samples exactly as [`crate::check`] (and `trajkit check`) does. It returns only what passes
//! that check: a [`Plan`] with the trajectory, its samples, the report and notes for people.
//!
//! # What is guaranteed
//! Every [`Plan`] holds every limit it was given, at its samples (the same check, tolerance
//! [`crate::check::Tolerance::default`]) and between them as each method's contract says:
//! - **position range**, every method. `toppra` and `ni` plan on a spline path that is kept
//!   inside the ranges exactly ([`crate::spline::BoundedSpline`]: extrema are roots of the
//!   derivative, a joint that leaves its range gets a reshaped C² path through the same
//!   waypoints) or on a polyline (a box is convex). `totg`'s path is straight segments joined
//!   by circular arcs; each arc is tangent to the two segments at points on them and lies in
//!   the triangle of those points and the corner waypoint, which lie in the box, so the arc
//!   does too. `poly` keeps each segment inside from its exact extrema
//!   ([`crate::poly::ViaTrajectory::within_limits`]). A waypoint outside its range is refused
//!   ([`Error::WaypointOutOfRange`]); no in-range path exists through it.
//! - **velocity, acceleration**: each method's precision contract (TOPP-RA checks between
//!   gridpoints and refines; NI and TOTG bound the excess between knots).
//! - **jerk**: bounded by the jerk stage for `toppra` and `ni`, by the polynomials' own
//!   extrema for `poly` (quintic, septic). The default stage ([`JerkStage::Auto`]) times a
//!   rest-to-rest piece along a straight line exactly ([`line_motion`]: the 1-D jerk-limited
//!   optimum, constant jerk per segment, limits checked at segment boundaries and velocity
//!   extrema) and filters the others ([`crate::topp::jerk`]: the time-scale factor is bounded
//!   analytically on every cubic segment of the filtered law, so velocity, acceleration and
//!   jerk hold at every instant, not only at samples). [`JerkStage::ThirdOrder`] results are
//!   slowed by the factor of their own 20 kHz check times 1 + [`THIRD_ORDER_MARGIN`]. Methods that cannot bound jerk (`totg`'s C¹ path,
//!   cubic polynomials, [`JerkStage::Off`]) refuse a finite jerk limit
//!   ([`Error::CannotHold`]): state the jerk as unlimited (infinite) to use them.
//! - **torque** (`toppra`, `ni` with [`PlanOptions::torque`]): within `±effort` at the
//!   samples of the final trajectory; after the jerk stage time is slowed down uniformly (up
//!   to [`MAX_TORQUE_SCALE`]) where needed.
//!
//! The final check can only fail by rounding-level amounts (or, for `ni` and `totg`, between
//! knots within their contracts); such an excess is removed by slowing down uniformly by the
//! factor the ratios call for, and said in the notes.
//!
//! # Sizes
//! Waypoints (at most [`MAX_WAYPOINTS`], and the memory they imply), gridpoints and samples
//! (duration × rate) are checked before anything is allocated ([`Error::TooLarge`]). Long runs
//! report progress through [`plan_with_progress`].
//!
//! ```
//! use trajkit::io::Waypoints;
//! use trajkit::plan::{plan, Method, PlanOptions};
//! use trajkit::Limits;
//! let w = Waypoints::from_csv(
//!     "panda_joint1,panda_joint2,panda_joint3,panda_joint4,panda_joint5,panda_joint6,panda_joint7\n\
//!      0,0,0,-1.5,0,1.5,0\n0.5,0.3,-0.2,-1.2,0.1,1.8,0.4\n1,-0.2,0.1,-2,0.3,1.2,0.8\n",
//!     "w.csv",
//! )?;
//! let p = plan(&w, &Limits::preset("panda")?, &PlanOptions::default())?;
//! assert!(p.report.passes(&trajkit::check::Tolerance::default()));
//! let totg = PlanOptions { method: Method::Totg, ..PlanOptions::default() };
//! // TOTG cannot bound jerk: the Panda's jerk limits must be stated unlimited first.
//! assert!(plan(&w, &Limits::preset("panda")?, &totg).is_err());
//! # Ok::<(), trajkit::Error>(())
//! ```

mod line;
mod phase;
mod torque;
mod verify;

pub use line::{line_motion, LineMotion, LIMIT_MARGIN, LINE_TOLERANCE};

pub use phase::{PhasePiece, PhasePlane, PHASE_POINTS};
pub use torque::{TorqueReport, MAX_TORQUE_SCALE, TORQUE_TOLERANCE};

use crate::check::LimitReport;
use crate::error::{Error, Result};
use crate::io::Waypoints;
use crate::poly::{Degree, ViaTrajectory, ViaVelocities};
use crate::sample::SampleTable;
use crate::topp::messy::{self, PathKind, PiecePath, PieceSolver, Sequence, TorqueModel};
use crate::topp::{Gridpoints, Parametrized};
use crate::{Limits, Trajectory};

/// Most waypoints [`plan`] accepts (after removing repeats): each one adds a path piece and
/// gridpoints to the solve, and the work grows with them (a 10 000-waypoint random walk on the
/// Panda took 28 s without the jerk stage in a release build on a loaded 2-core machine,
/// 1000 waypoints 13 s with it; split longer paths).
pub const MAX_WAYPOINTS: usize = 10_000;

/// The time-parameterization method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// TOPP-RA on a C² spline (or polyline) through the waypoints, then the jerk stage.
    #[default]
    Toppra,
    /// Numerical integration in the phase plane (Bobrow / TOPP-NI) on the same path and
    /// constraints, then the jerk stage.
    Ni,
    /// Time-optimal trajectory generation (Kunz & Stilman): straight segments joined by
    /// circular blends within [`PlanOptions::max_deviation`]; the path is only C¹, so jerk is
    /// not bounded (every jerk limit must be infinite).
    Totg,
    /// Synchronized polynomial segments between waypoints, each as short as the limits allow
    /// ([`PlanOptions::degree`], [`PlanOptions::via_velocity`]).
    Poly,
}

impl Method {
    /// `toppra`, `ni`, `totg`, `poly`.
    pub fn name(self) -> &'static str {
        match self {
            Method::Toppra => "toppra",
            Method::Ni => "ni",
            Method::Totg => "totg",
            Method::Poly => "poly",
        }
    }
}

/// How the jerk of a phase-plane result (`toppra`, `ni`) is bounded. Every mode goes through
/// one internal function, so a new jerk-limited planner plugs in as one more variant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum JerkStage {
    /// The default. A rest-to-rest piece whose path is a straight segment (collinear
    /// waypoints in order) is timed exactly by the 1-D jerk-limited optimum along it
    /// ([`line_motion`]: trajkit's online generator, rest to rest); every other piece by the
    /// filter, and when the filter is more than [`LOCAL_ABOVE`] over raw TOPP-RA by the filter
    /// with a local slow-down ([`crate::topp::jerk_local`], never longer than
    /// [`JerkStage::Filter`]); every piece when torque limits are set by [`JerkStage::Filter`].
    #[default]
    Auto,
    /// Filter the timing law by a moving average and rescale time ([`crate::topp::jerk`]) on
    /// every piece, straight or not.
    Filter,
    /// [`JerkStage::Auto`], and on every piece that is not a straight line also the
    /// jerk-limited time-optimal planner by third-order reachability
    /// ([`crate::topp::jerk_optimal`]); the shorter of its result (slowed by its 20 kHz check's
    /// factor and [`THIRD_ORDER_MARGIN`]) and the filter's is kept, the filter's when it fails. Much shorter motions at low jerk limits (see BENCHMARKS.md),
    /// but seconds of computation per piece: not the default.
    ThirdOrder,
    /// Keep the raw result (piecewise-constant path acceleration: unbounded jerk); every
    /// joint's jerk limit must be infinite.
    Off,
}

/// Velocities at interior waypoints for [`Method::Poly`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ViaVelocity {
    /// Continuous-velocity heuristic ([`ViaVelocities::Heuristic`]), reduced where a joint
    /// would leave its range.
    #[default]
    Heuristic,
    /// Stop at every waypoint.
    Zero,
}

/// Settings of [`plan`]: plain data, every field with a documented default.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanOptions {
    /// The method. Default [`Method::Toppra`].
    pub method: Method,
    /// Path through the waypoints for `toppra` and `ni`. Default [`PathKind::NaturalCubic`].
    pub path: PathKind,
    /// TOPP-RA gridpoints (NI: initial knots) per rest-to-rest piece. Default
    /// `Gridpoints::Auto { tolerance: 1e-4 }` (a duration within 1e-4 relative of the
    /// converged optimum).
    pub gridpoints: Gridpoints,
    /// The jerk stage of `toppra` and `ni`. Default [`JerkStage::Auto`].
    pub jerk: JerkStage,
    /// Largest distance (joint units, Euclidean) between a waypoint and its blend, for `totg`.
    /// Default 0.1.
    pub max_deviation: f64,
    /// Polynomial degree for `poly`. Default [`Degree::Quintic`].
    pub degree: Degree,
    /// Velocities at interior waypoints for `poly`. Default [`ViaVelocity::Heuristic`].
    pub via_velocity: ViaVelocity,
    /// Hold every joint's torque within `±effort` (of the limits) for this inverse-dynamics
    /// model (`toppra`, `ni` only). Default `None`.
    pub torque: Option<TorqueModel>,
    /// Sample rate (Hz) of [`Plan::samples`], the samples that are checked. Default 1000.
    pub sample_rate: f64,
    /// Also return the phase plane of path methods ([`Plan::phase_plane`]). Default false.
    pub phase_plane: bool,
}

impl PlanOptions {
    /// The limits these options need given for every joint ([`crate::limits::Needs`]):
    /// position range, velocity and acceleration always; jerk where the method bounds it
    /// (`toppra` and `ni` with a jerk stage, `poly` of degree 5 or 7).
    pub fn needs(&self) -> crate::limits::Needs {
        let bounds_jerk = match self.method {
            Method::Toppra | Method::Ni => self.jerk != JerkStage::Off,
            Method::Poly => self.degree != Degree::Cubic,
            Method::Totg => false,
        };
        crate::limits::Needs {
            jerk: bounds_jerk,
            ..crate::limits::Needs::ALL
        }
    }
}

impl Default for PlanOptions {
    fn default() -> Self {
        PlanOptions {
            method: Method::Toppra,
            path: PathKind::NaturalCubic,
            gridpoints: Gridpoints::Auto { tolerance: 1e-4 },
            jerk: JerkStage::Auto,
            max_deviation: 0.1,
            degree: Degree::Quintic,
            via_velocity: ViaVelocity::Heuristic,
            torque: None,
            sample_rate: 1000.0,
            phase_plane: false,
        }
    }
}

/// Where the range repair of a spline path changed one joint.
#[derive(Debug, Clone, PartialEq)]
pub struct RangeRepair {
    /// The joint (0-based).
    pub joint: usize,
    /// How far the unrepaired spline left the range.
    pub excursion: f64,
    /// It did so between these two waypoints (indices in the input).
    pub between: (usize, usize),
    /// How many waypoints got a new slope and curvature for this joint.
    pub waypoints_changed: usize,
}

/// A stage of [`plan_with_progress`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Building the paths.
    Path,
    /// Timing the rest-to-rest pieces (`done` of `total`).
    Timing,
    /// Bounding jerk.
    Jerk,
    /// Holding torques.
    Torque,
    /// Sampling and checking.
    Verifying,
}

/// Progress of [`plan_with_progress`]: `done` of `total` units of `stage`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// The stage.
    pub stage: Stage,
    /// Units done.
    pub done: usize,
    /// Units in the stage.
    pub total: usize,
}

/// The result of [`plan`].
pub struct Plan {
    /// The trajectory (exact evaluation of q, q̇, q̈, q⃛ into caller buffers, no allocation).
    pub trajectory: Box<dyn Trajectory + Send + Sync>,
    /// Its samples at [`PlanOptions::sample_rate`], with the joint names.
    pub samples: SampleTable,
    /// The check of [`Plan::samples`] against [`Plan::limits`]: it passes.
    pub report: LimitReport,
    /// The limits used, one per waypoint column in the waypoints' order.
    pub limits: Limits,
    /// Joint names: the waypoints', else the limits', else empty.
    pub names: Vec<String>,
    /// Waypoints planned through (after removing consecutive repeats).
    pub waypoints: usize,
    /// Consecutive repeated waypoints removed.
    pub repeats_removed: usize,
    /// Rest-to-rest pieces (the robot stops between them).
    pub pieces: usize,
    /// Duration of the method's own result, before the jerk stage, torque and check
    /// slow-downs (seconds).
    pub raw_duration: f64,
    /// Where spline paths were reshaped to stay inside the position ranges.
    pub range_repairs: Vec<RangeRepair>,
    /// Torque check, when [`PlanOptions::torque`] was set.
    pub torque: Option<TorqueReport>,
    /// Uniform slow-down applied by the final check (1 when none was needed).
    pub check_scale: f64,
    /// Lines for people: what the jerk stage did, joints of the limits not used, repairs.
    pub notes: Vec<String>,
    /// The phase plane of `toppra`, `ni` and `totg` when [`PlanOptions::phase_plane`] asked
    /// for it.
    pub phase_plane: Option<PhasePlane>,
}

impl std::fmt::Debug for Plan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Plan")
            .field("duration", &self.trajectory.duration())
            .field("samples", &self.samples.len())
            .field("names", &self.names)
            .field("waypoints", &self.waypoints)
            .field("pieces", &self.pieces)
            .field("raw_duration", &self.raw_duration)
            .field("range_repairs", &self.range_repairs)
            .field("torque", &self.torque)
            .field("check_scale", &self.check_scale)
            .field("notes", &self.notes)
            .finish()
    }
}

impl Plan {
    /// The trajectory's duration in seconds.
    pub fn duration(&self) -> f64 {
        self.trajectory.duration()
    }
}

/// Plans a trajectory through `waypoints` within `limits` (see the module documentation).
///
/// Errors (typed, naming joint, field, value and time where they exist):
/// [`Error::JointNames`], [`Error::DimensionMismatch`] (pairing columns with limits);
/// [`Error::TooFewWaypoints`]; [`Error::WaypointOutOfRange`]; [`Error::CannotHold`] (a finite
/// jerk limit with a method that cannot bound jerk, a torque the slow-down cannot fix);
/// [`Error::MissingLimit`] (torque limits without an effort); [`Error::TooLarge`];
/// [`Error::InvalidValue`] (options); [`Error::Infeasible`] (the solvers'); and, never expected,
/// [`Error::OutOfRange`] / [`Error::LimitExceeded`] from the final check.
pub fn plan(waypoints: &Waypoints, limits: &Limits, options: &PlanOptions) -> Result<Plan> {
    plan_with_progress(waypoints, limits, options, &mut |_| {})
}

/// [`plan`], calling `progress` as the stages advance (for a progress line on long runs).
pub fn plan_with_progress(
    waypoints: &Waypoints,
    limits: &Limits,
    options: &PlanOptions,
    progress: &mut dyn FnMut(Progress),
) -> Result<Plan> {
    let Prepared {
        w,
        limits,
        names,
        repeats_removed,
        mut notes,
    } = prepare(waypoints, limits, options)?;
    progress(Progress {
        stage: Stage::Path,
        done: 0,
        total: 1,
    });
    let timed = time_with(&w, &limits, options, progress)?;
    notes.extend(timed.notes);
    let mut phase_plane = timed.phase;
    let (traj, torque) = match &options.torque {
        None => (timed.traj, None),
        Some(model) => {
            progress(Progress {
                stage: Stage::Torque,
                done: 0,
                total: 1,
            });
            let (traj, report) =
                torque::torque_time_scale(timed.traj, model, &limits, options.sample_rate)?;
            (traj, Some(report))
        }
    };
    progress(Progress {
        stage: Stage::Verifying,
        done: 0,
        total: 1,
    });
    let (trajectory, samples, report, check_scale) =
        verify::verified_samples(traj, &limits, &names, options.sample_rate)?;
    if let Some(plane) = &mut phase_plane {
        let torque_scale = torque.as_ref().map_or(1.0, |t: &TorqueReport| t.scale);
        phase::slow_down(plane, torque_scale * check_scale);
    }
    if check_scale > 1.0 {
        notes.push(format!(
            "the final check found a rounding-level excess and slowed the motion down ×{check_scale:.9}"
        ));
    }
    progress(Progress {
        stage: Stage::Verifying,
        done: 1,
        total: 1,
    });
    Ok(Plan {
        trajectory,
        samples,
        report,
        limits,
        names,
        waypoints: w.len(),
        repeats_removed,
        pieces: timed.pieces,
        raw_duration: timed.raw_duration,
        range_repairs: timed.repairs,
        torque,
        check_scale,
        notes,
        phase_plane,
    })
}

/// The waypoints and limits [`plan_with_progress`] works with.
struct Prepared {
    /// Without consecutive repeats.
    w: Waypoints,
    /// One per waypoint column, in the waypoints' order.
    limits: Limits,
    names: Vec<String>,
    repeats_removed: usize,
    notes: Vec<String>,
}

/// Checks the options, pairs the limits with the waypoint columns, removes repeated
/// waypoints and refuses too few, too many or out-of-range ones.
fn prepare(waypoints: &Waypoints, limits: &Limits, options: &PlanOptions) -> Result<Prepared> {
    check_options(options, waypoints.dof())?;
    let (limits, unused) = limits.for_joints("waypoint", waypoints.given_names())?;
    limits.expect_dof(waypoints.dof(), "the waypoints")?;
    let names = output_names(waypoints, &limits);
    let mut w = waypoints.clone();
    let repeats_removed = w.dedup(0.0);
    if w.len() < 2 {
        return Err(Error::TooFewWaypoints {
            needed: 2,
            found: w.len(),
        });
    }
    check_waypoint_count(w.len(), w.dof())?;
    limits.check_waypoints(waypoints.points(), None)?;
    let mut notes = Vec::new();
    if !unused.is_empty() {
        notes.push(format!(
            "limits of {} not used: no waypoint column has that name",
            unused.join(", ")
        ));
    }
    Ok(Prepared {
        w,
        limits,
        names,
        repeats_removed,
        notes,
    })
}

/// Option values that no method accepts, and sizes they imply.
fn check_options(o: &PlanOptions, dof: usize) -> Result<()> {
    crate::error::positive(|| "sample rate (Hz)".into(), o.sample_rate)?;
    if o.method == Method::Totg {
        crate::error::positive(|| "max deviation".into(), o.max_deviation)?;
    }
    if o.torque.is_some() && !matches!(o.method, Method::Toppra | Method::Ni) {
        return Err(Error::InvalidValue {
            field: format!("torque limits with method {}", o.method.name()),
            value: f64::NAN,
            reason: "are available with the toppra and ni methods only",
        });
    }
    let grid = match &o.gridpoints {
        Gridpoints::Uniform(n) => *n as f64,
        Gridpoints::Given(v) => v.len() as f64,
        Gridpoints::Auto { .. } | Gridpoints::Chord { .. } => 0.0,
    };
    // Per gridpoint: constraint rows (velocity and acceleration of every joint, a, b, c),
    // controllable and reachable sets, the profile.
    crate::size::check_memory(
        "gridpoints",
        grid,
        64.0 * dof as f64 + 128.0,
        &format!("a gridpoint of {dof} joint(s)"),
    )?;
    Ok(())
}

/// Refuses more waypoints than [`MAX_WAYPOINTS`] or than the memory budget allows.
fn check_waypoint_count(count: usize, dof: usize) -> Result<()> {
    let per = 120.0 * dof as f64 + 256.0;
    let limit = crate::size::max_count(per).min(MAX_WAYPOINTS as f64);
    crate::size::check(
        "waypoint count",
        count as f64,
        limit,
        &format!(
            "each waypoint of {dof} joint(s) adds a path piece and gridpoints (about {} of planning data) and solver work; split longer paths",
            crate::size::human_bytes(per)
        ),
    )?;
    Ok(())
}

/// The names of the output columns: the waypoints' when given, else the limits' when every
/// joint has one, else empty.
fn output_names(w: &Waypoints, limits: &Limits) -> Vec<String> {
    if let Some(n) = w.given_names() {
        return n.to_vec();
    }
    let l: Vec<String> = limits.joints().iter().map(|j| j.name.clone()).collect();
    if l.iter().all(|n| !n.is_empty()) {
        l
    } else {
        vec![String::new(); w.dof()]
    }
}

/// Every joint's jerk limit must be infinite, else [`Error::CannotHold`] with `why`.
fn require_unlimited_jerk(limits: &Limits, why: &str) -> Result<()> {
    for (j, jl) in limits.joints().iter().enumerate() {
        if jl.jerk.is_finite() {
            return Err(Error::CannotHold {
                joint: j,
                name: jl.name.clone(),
                field: "jerk",
                value: jl.jerk,
                reason: format!(
                    "{why}; state the jerk limit as unlimited (infinite) to plan without one"
                ),
            });
        }
    }
    Ok(())
}

/// A method's result before torque and the final check.
struct Timed {
    traj: Box<dyn Trajectory + Send + Sync>,
    raw_duration: f64,
    pieces: usize,
    repairs: Vec<RangeRepair>,
    notes: Vec<String>,
    phase: Option<PhasePlane>,
}

/// Runs the method.
fn time_with(
    w: &Waypoints,
    limits: &Limits,
    o: &PlanOptions,
    progress: &mut dyn FnMut(Progress),
) -> Result<Timed> {
    match o.method {
        Method::Toppra | Method::Ni => phase_plane(w, limits, o, progress),
        Method::Totg => {
            require_unlimited_jerk(
                limits,
                "totg's blended path is only C¹ (joint acceleration jumps where arcs meet segments), so no timing bounds its jerk",
            )?;
            let opts = crate::topp::TotgOptions {
                max_deviation: o.max_deviation,
                ..Default::default()
            };
            progress(Progress {
                stage: Stage::Timing,
                done: 0,
                total: 1,
            });
            let raw = crate::topp::plan_totg(w.points(), w.dof(), limits, &opts)?;
            let phase = o
                .phase_plane
                .then(|| phase::of_raw(&raw, limits))
                .transpose()?;
            let note = format!(
                "jerk: not bounded (the blended path, max deviation {}, is only C¹; the jerk limits are infinite)",
                o.max_deviation
            );
            Ok(Timed {
                raw_duration: raw.duration(),
                pieces: raw.pieces().len(),
                traj: Box::new(raw),
                repairs: Vec::new(),
                notes: vec![note],
                phase,
            })
        }
        Method::Poly => {
            if o.degree == Degree::Cubic {
                require_unlimited_jerk(
                    limits,
                    "cubic segments jump in acceleration at every waypoint (unbounded jerk)",
                )?;
            }
            let vel = match o.via_velocity {
                ViaVelocity::Heuristic => ViaVelocities::Heuristic,
                ViaVelocity::Zero => ViaVelocities::Zero,
            };
            progress(Progress {
                stage: Stage::Timing,
                done: 0,
                total: 1,
            });
            let (tr, zeroed) =
                ViaTrajectory::within_limits(w.points(), w.dof(), o.degree, vel, limits)?;
            let mut notes = Vec::new();
            if zeroed > 0 {
                notes.push(format!(
                    "position range: {zeroed} via-point velocit{} set to 0 so that no joint leaves its range",
                    if zeroed == 1 { "y" } else { "ies" }
                ));
            }
            Ok(Timed {
                raw_duration: tr.duration(),
                pieces: 1,
                traj: Box::new(tr),
                repairs: Vec::new(),
                notes,
                phase: None,
            })
        }
    }
}

/// `toppra` and `ni`: range-safe paths per rest-to-rest piece, timing, then the jerk stage.
fn phase_plane(
    w: &Waypoints,
    limits: &Limits,
    o: &PlanOptions,
    progress: &mut dyn FnMut(Progress),
) -> Result<Timed> {
    let mopts = messy::PlanOptions {
        kind: o.path,
        toppra: crate::topp::ToppraOptions {
            gridpoints: o.gridpoints.clone(),
            ..Default::default()
        },
        torque: o.torque.clone(),
        solver: if o.method == Method::Ni {
            PieceSolver::Ni
        } else {
            PieceSolver::Toppra
        },
        ..Default::default()
    };
    let paths = messy::piece_paths(w.points(), w.dof(), limits, &mopts)?;
    let repairs = range_repairs(&paths);
    let mut notes = Vec::new();
    if !repairs.is_empty() {
        let names: Vec<String> = repairs
            .iter()
            .map(|r| crate::error::joint_label(r.joint, &limits.joint(r.joint).name))
            .collect();
        notes.push(format!(
            "position range: the spline path was reshaped for {} (C², through every waypoint) so that it stays inside",
            names.join(", ")
        ));
    }
    let total = paths.pieces.len();
    progress(Progress {
        stage: Stage::Timing,
        done: 0,
        total,
    });
    let raw = messy::time_pieces(paths, limits, &mopts, &mut |done, total| {
        progress(Progress {
            stage: Stage::Timing,
            done,
            total,
        })
    })?;
    let raw_duration = raw.duration();
    progress(Progress {
        stage: Stage::Jerk,
        done: 0,
        total: 1,
    });
    let name = if o.method == Method::Ni {
        "NI"
    } else {
        "TOPP-RA"
    };
    let mut phase = o
        .phase_plane
        .then(|| phase::of_raw(&raw, limits))
        .transpose()?;
    let (traj, note) = jerk_stage(
        raw,
        limits,
        o.jerk,
        o.torque.is_some(),
        name,
        phase.as_mut(),
    )?;
    notes.insert(0, note);
    Ok(Timed {
        traj,
        raw_duration,
        pieces: total,
        repairs,
        notes,
        phase,
    })
}

/// The jerk stage, the one place where a phase-plane result gets its jerk bounded.
fn jerk_stage(
    raw: Sequence<Parametrized<PiecePath>>,
    limits: &Limits,
    stage: JerkStage,
    torque: bool,
    name: &str,
    phase: Option<&mut PhasePlane>,
) -> Result<(Box<dyn Trajectory + Send + Sync>, String)> {
    let unlimited = limits.joints().iter().all(|j| j.jerk.is_infinite());
    match stage {
        JerkStage::Off => {
            require_unlimited_jerk(
                limits,
                "without the jerk stage the path acceleration is piecewise constant (unbounded jerk)",
            )?;
            let note = format!(
                "jerk: not bounded (no jerk stage; {name}'s path acceleration is piecewise constant; the jerk limits are infinite)"
            );
            Ok((Box::new(raw), note))
        }
        JerkStage::Filter | JerkStage::Auto | JerkStage::ThirdOrder if unlimited => {
            let note = format!(
                "jerk: not bounded (every joint's jerk limit is infinite; {name}'s raw result)"
            );
            Ok((Box::new(raw), note))
        }
        JerkStage::Filter | JerkStage::Auto | JerkStage::ThirdOrder => {
            let lines_allowed = stage != JerkStage::Filter && !torque;
            let raw_duration = raw.duration();
            let pieces = raw
                .into_pieces()
                .into_iter()
                .map(|p| jerk_piece(p, limits, stage, lines_allowed))
                .collect::<Result<Vec<_>>>()?;
            let jl = Sequence::new(pieces)?;
            let note = format!(
                "jerk: bounded ({name} {raw_duration:.6} s; pieces: {}; +{:.2}%)",
                piece_kinds(jl.pieces()),
                100.0 * (jl.duration() / raw_duration - 1.0)
            );
            if let Some(plane) = phase {
                phase::add_played(plane, &jl);
            }
            Ok((Box::new(jl), note))
        }
    }
}

/// The filter's overhead over raw TOPP-RA (relative duration) above which [`JerkStage::Auto`]
/// runs the local slow-down ([`crate::topp::jerk_local`]) on a curved piece. Below it the
/// local stage gains at most this much (measured: +0.04–0.12 % → +0.02–0.08 % on random Panda
/// paths at the Panda's limits) for 10–80× the filter's cost (measured on std7 and the seeded
/// curved paths); above it (low jerk limits, short segments: +10 % to +100 %) it halves the
/// overhead or better.
pub const LOCAL_ABOVE: f64 = 0.005;

/// One rest-to-rest piece through the jerk stage `stage` (not [`JerkStage::Off`]): the exact
/// line motion when `lines_allowed` and the path is a straight segment, else the filter, or
/// the third-order planner's result when asked for and shorter.
fn jerk_piece(
    p: Parametrized<PiecePath>,
    limits: &Limits,
    stage: JerkStage,
    lines_allowed: bool,
) -> Result<JerkPiece> {
    if let Some(m) = lines_allowed
        .then(|| line_motion(p.path(), limits))
        .flatten()
    {
        return Ok(JerkPiece::Line(Box::new(m)));
    }
    let optimal = (stage == JerkStage::ThirdOrder)
        .then(|| {
            crate::topp::jerk_optimal::JerkOptimal::new(p.path().clone(), limits)
                .and_then(|prob| prob.solve())
                .ok()
        })
        .flatten()
        .and_then(|o| third_order_margin(o, limits));
    let raw_duration = p.duration();
    let (path, law) = p.into_parts();
    let options = crate::topp::jerk::JerkOptions::default();
    // The path and law move into the filter; the rare local stage takes copies back from it.
    let filtered = crate::topp::jerk::limit_jerk(path, law, limits, &options)?;
    // Not `Filter`, no torque rows, and the filter costs noticeably more than raw TOPP-RA: the
    // filter with a local slow-down (never longer than the filter, but 10–80× its cost).
    let filtered = if lines_allowed && filtered.duration() > raw_duration * (1.0 + LOCAL_ABOVE) {
        let retimed = filtered.inner();
        crate::topp::jerk_local::limit_jerk_local(
            retimed.path().clone(),
            retimed.law().profile().clone(),
            limits,
            &crate::topp::jerk_local::LocalOptions::default(),
        )?
        .0
    } else {
        filtered
    };
    Ok(match optimal {
        Some(o) if o.duration() < filtered.duration() => JerkPiece::ThirdOrder(Box::new(o)),
        _ => JerkPiece::Filtered(Box::new(filtered)),
    })
}

/// `2 straight (exact jerk-limited optimum), 1 filtered and rescaled`: how the pieces were
/// bounded, for the note.
fn piece_kinds(pieces: &[JerkPiece]) -> String {
    let count = |f: fn(&JerkPiece) -> bool| pieces.iter().filter(|p| f(p)).count();
    [
        (
            count(|p| matches!(p, JerkPiece::Line(_))),
            "straight (exact jerk-limited optimum)",
        ),
        (
            count(|p| matches!(p, JerkPiece::ThirdOrder(_))),
            "third-order time-optimal",
        ),
        (
            count(|p| matches!(p, JerkPiece::Filtered(_))),
            "filtered and rescaled",
        ),
    ]
    .iter()
    .filter(|(n, _)| *n > 0)
    .map(|(n, what)| format!("{n} {what}"))
    .collect::<Vec<_>>()
    .join(", ")
}

/// One rest-to-rest piece after the jerk stage.
pub(crate) enum JerkPiece {
    /// Filtered and rescaled (boxed: its law carries per-interval tables).
    Filtered(Box<crate::topp::jerk::JerkLimited<PiecePath>>),
    /// A straight segment at its exact 1-D optimum (boxed: its profile is large).
    Line(Box<LineMotion>),
    /// The third-order time-optimal planner's result, with [`third_order_margin`].
    ThirdOrder(Box<crate::topp::Scaled<crate::topp::jerk_optimal::JerkTimed<PiecePath>>>),
}

/// Relative slow-down added to the third-order planner's result on top of the factor its
/// 20 kHz check calls for: room for excesses between the check's samples (50 kHz checks found
/// up to 1e-7 relative in acceleration where that planner's contract states 1e-9).
pub const THIRD_ORDER_MARGIN: f64 = 1e-6;

/// The third-order result slowed by its sampled factor (at least 1) times
/// 1 + [`THIRD_ORDER_MARGIN`]; `None` when the check fails.
fn third_order_margin(
    traj: crate::topp::jerk_optimal::JerkTimed<PiecePath>,
    limits: &Limits,
) -> Option<crate::topp::Scaled<crate::topp::jerk_optimal::JerkTimed<PiecePath>>> {
    let k = crate::topp::min_time_scale(&traj, limits, 20_000.0).ok()?;
    crate::topp::Scaled::new(traj, k.max(1.0) * (1.0 + THIRD_ORDER_MARGIN)).ok()
}

impl JerkPiece {
    /// The played path parameter and its rate at time `t`.
    pub(crate) fn path_state(&self, t: f64) -> (f64, f64) {
        use crate::topp::TimeLaw;
        match self {
            JerkPiece::Filtered(p) => {
                let v = p.inner().law().eval(t / p.factor());
                (v[0], v[1] / p.factor())
            }
            JerkPiece::Line(m) => m.path_state(t),
            JerkPiece::ThirdOrder(o) => {
                let v = o.inner().law().eval(t / o.factor());
                (v[0], v[1] / o.factor())
            }
        }
    }
}

impl Trajectory for JerkPiece {
    fn dof(&self) -> usize {
        match self {
            JerkPiece::Filtered(p) => p.dof(),
            JerkPiece::Line(m) => m.dof(),
            JerkPiece::ThirdOrder(o) => o.dof(),
        }
    }
    fn duration(&self) -> f64 {
        match self {
            JerkPiece::Filtered(p) => p.duration(),
            JerkPiece::Line(m) => m.duration(),
            JerkPiece::ThirdOrder(o) => o.duration(),
        }
    }
    fn eval(&self, t: f64, order: crate::Order, out: &mut [f64]) {
        match self {
            JerkPiece::Filtered(p) => p.eval(t, order, out),
            JerkPiece::Line(m) => m.eval(t, order, out),
            JerkPiece::ThirdOrder(o) => o.eval(t, order, out),
        }
    }
    fn eval_rows(&self, times: &[f64], out: [&mut [f64]; 4]) {
        match self {
            JerkPiece::Filtered(p) => p.eval_rows(times, out),
            JerkPiece::Line(m) => m.eval_rows(times, out),
            JerkPiece::ThirdOrder(o) => o.eval_rows(times, out),
        }
    }
}

/// What the range repair changed, per piece and joint, with input waypoint indices.
fn range_repairs(paths: &messy::PiecePaths) -> Vec<RangeRepair> {
    let mut out = Vec::new();
    for piece in &paths.pieces {
        let PiecePath::Bounded(b) = &piece.path else {
            continue;
        };
        let breaks = b.breaks();
        for r in b.repairs() {
            let k = crate::traj::find_piece(breaks, r.at).min(breaks.len() - 2);
            out.push(RangeRepair {
                joint: r.component,
                excursion: r.excursion,
                between: (paths.kept[piece.from + k], paths.kept[piece.from + k + 1]),
                waypoints_changed: r.breaks_changed,
            });
        }
    }
    out
}
