//! `POST /api/plan`: waypoints + limits + method → the sampled trajectory, its limit check, and
//! the phase plane. The lesson "plan" of the page is a client of this endpoint.
//!
//! [`plan`] is the one place that calls the planners (the same library entry points as
//! `trajkit plan`: `topp::messy::plan_waypoints` + `topp::jerk::limit_jerk_sequence`,
//! `topp::plan_totg`, `poly::ViaTrajectory`); everything around it only translates JSON. When a
//! single library entry point for the main job exists, [`plan`]'s body becomes that call.
//!
//! Safety: the result is sampled at 1 kHz and checked with `trajkit::check` against every limit
//! it was planned for (jerk left out only for second-order methods without a jerk stage, and
//! the answer says so). A trajectory that fails the check is refused (422), never returned.

use super::caps;
use super::error::{ApiError, ApiResult};
use super::lessons::{series, Series};
use super::limits_in::{require, FileIn, LimitsIn};
use super::phase::{phase_plane, PhasePlane};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use trajkit::check::{check_samples, Tolerance};
use trajkit::io::Waypoints;
use trajkit::poly::{Degree, ViaTiming, ViaTrajectory, ViaVelocities};
use trajkit::topp::messy::{plan_waypoints, PathKind, PieceSolver, PlanOptions};
use trajkit::{Limits, Order, Trajectory};

/// Time-parameterization method (as `trajkit plan --method`).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// TOPP-RA on a spline through the waypoints, then the jerk stage.
    #[default]
    Toppra,
    /// Numerical integration in the phase plane on the same path, then the jerk stage.
    Ni,
    /// TOTG: straight segments and circular blends (C¹; jerk not bounded).
    Totg,
    /// Synchronized polynomial segments.
    Poly,
}

/// Path through the waypoints for `toppra` and `ni` (as `trajkit plan --path`).
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum PathIn {
    /// Natural cubic spline.
    #[default]
    Natural,
    /// Not-a-knot cubic spline.
    NotAKnot,
    /// Cubic spline with zero end slopes.
    Clamped,
    /// Polyline (stops at every corner).
    Linear,
}

/// Polynomial degree for `poly`.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "lowercase")]
pub enum DegreeIn {
    /// 3.
    Cubic,
    /// 5 (minimum jerk).
    #[default]
    Quintic,
    /// 7.
    Septic,
}

/// Velocities at interior waypoints for `poly`.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "lowercase")]
pub enum ViaIn {
    /// Continuous velocity, stop only where a joint turns around.
    #[default]
    Heuristic,
    /// Stop at every waypoint.
    Zero,
}

/// `POST /api/plan`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Request {
    /// Waypoints, one row per waypoint, one column per joint. Exactly one of `waypoints` and
    /// `waypoints_file`.
    pub waypoints: Option<Vec<Vec<f64>>>,
    /// Joint names of the `waypoints` columns (optional).
    pub joint_names: Option<Vec<String>>,
    /// A waypoints file: CSV (optional header of joint names) or JSON (`.json`), as for
    /// `trajkit plan --waypoints`.
    pub waypoints_file: Option<FileIn>,
    /// The limits.
    pub limits: LimitsIn,
    /// Method (default `toppra`).
    #[serde(default)]
    pub method: Method,
    /// Path for `toppra`/`ni` (default `natural`).
    #[serde(default)]
    pub path: PathIn,
    /// Gridpoint intervals per rest-to-rest piece for `toppra`/`ni`, 1..=20000 (default 1000).
    #[serde(default = "default_gridpoints")]
    pub gridpoints: usize,
    /// Bound the jerk after `toppra`/`ni` (default true; needs jerk limits).
    #[serde(default = "yes")]
    pub jerk_limit: bool,
    /// Largest deviation of a TOTG blend from its corner (default 0.1; `totg` only).
    pub max_deviation: Option<f64>,
    /// Degree for `poly` (default `quintic`).
    #[serde(default)]
    pub degree: DegreeIn,
    /// Interior velocities for `poly` (default `heuristic`).
    #[serde(default)]
    pub via_velocity: ViaIn,
    /// Sample rate of the returned samples, Hz (default 100).
    #[serde(default = "default_rate")]
    pub rate: f64,
    /// Also the phase plane (default true).
    #[serde(default = "yes")]
    pub phase_plane: bool,
}

fn default_gridpoints() -> usize {
    1000
}
fn default_rate() -> f64 {
    100.0
}
fn yes() -> bool {
    true
}

/// What `?format=` asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// The JSON answer of the lesson ([`Response`]).
    #[default]
    Summary,
    /// The sample table as CSV (`trajkit plan --out x.csv`).
    Csv,
    /// The sample table as JSON (`trajkit plan --out x.json`).
    Json,
}

/// The query string of `POST /api/plan`.
#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Query {
    /// `summary` (default), `csv` or `json`.
    #[serde(default)]
    pub format: Format,
}

/// The answer.
#[derive(Debug, Serialize)]
pub struct Response {
    /// The method used.
    pub method: Method,
    /// Duration, seconds.
    pub duration: f64,
    /// Joint names.
    pub joint_names: Vec<String>,
    /// Waypoints planned through (after removing consecutive duplicates).
    pub waypoints: Vec<Vec<f64>>,
    /// How many consecutive duplicate waypoints were removed.
    pub removed_duplicates: usize,
    /// The limits per joint, for drawing.
    pub limits: Vec<JointLimitsOut>,
    /// What was done (jerk stage, TOTG blends, ...), one sentence each.
    pub notes: Vec<String>,
    /// The limit check of the 1 kHz samples (`trajkit check`'s JSON report).
    pub check: Value,
    /// Sample rate of `check`, Hz.
    pub check_rate: f64,
    /// The samples at `rate`.
    pub samples: Series,
    /// The phase plane (path methods only).
    pub phase_plane: Option<PhasePlane>,
}

/// One joint's limits as ranges `[min, max]` (`null` for unbounded).
#[derive(Debug, Serialize)]
pub struct JointLimitsOut {
    /// Joint name.
    pub name: String,
    /// Position range.
    pub position: [f64; 2],
    /// Velocity range.
    pub velocity: [f64; 2],
    /// Acceleration range.
    pub acceleration: [f64; 2],
    /// Jerk range.
    pub jerk: [f64; 2],
}

/// What the endpoint returns: the JSON answer or a table file.
pub enum Output {
    /// `?format=summary`.
    Summary(Box<Response>),
    /// `?format=csv|json`: content type and text.
    Table(&'static str, String),
}

/// A planned trajectory and what the page shows about it.
pub struct Planned {
    /// The trajectory.
    pub traj: Box<dyn Trajectory>,
    /// Whether jerk is bounded (and so checked).
    pub jerk_checked: bool,
    /// Notes for the summary.
    pub notes: Vec<String>,
    /// The phase plane, when asked and the method has one.
    pub phase: Option<PhasePlane>,
}

/// The planner options of a request, checked.
pub struct Options {
    method: Method,
    path: PathKind,
    gridpoints: usize,
    jerk_limit: bool,
    max_deviation: f64,
    degree: Degree,
    via: ViaVelocities,
    phase_plane: bool,
}

impl Options {
    fn from_request(r: &Request) -> ApiResult<Self> {
        if r.max_deviation.is_some() && r.method != Method::Totg {
            return Err(ApiError::bad(
                "max_deviation",
                json!(r.max_deviation),
                "is used only with method totg",
            ));
        }
        Ok(Options {
            method: r.method,
            path: match r.path {
                PathIn::Natural => PathKind::NaturalCubic,
                PathIn::NotAKnot => PathKind::NotAKnotCubic,
                PathIn::Clamped => PathKind::ClampedCubic,
                PathIn::Linear => PathKind::Linear,
            },
            gridpoints: caps::count("gridpoints", r.gridpoints, 1, caps::MAX_GRIDPOINTS)?,
            jerk_limit: r.jerk_limit,
            max_deviation: r
                .max_deviation
                .map_or(Ok(0.1), |d| caps::positive("max_deviation", d))?,
            degree: match r.degree {
                DegreeIn::Cubic => Degree::Cubic,
                DegreeIn::Quintic => Degree::Quintic,
                DegreeIn::Septic => Degree::Septic,
            },
            via: match r.via_velocity {
                ViaIn::Heuristic => ViaVelocities::Heuristic,
                ViaIn::Zero => ViaVelocities::Zero,
            },
            phase_plane: r.phase_plane,
        })
    }
}

/// The phase plane when the request asks for it.
fn maybe_phase<P: trajkit::Path + Clone>(
    o: &Options,
    raw: &trajkit::topp::messy::Sequence<trajkit::topp::Parametrized<P>>,
    played: Option<&trajkit::topp::messy::Sequence<trajkit::topp::jerk::JerkLimited<P>>>,
    limits: &Limits,
) -> ApiResult<Option<PhasePlane>> {
    o.phase_plane
        .then(|| phase_plane(raw, played, limits))
        .transpose()
}

/// Plans `w` under `limits` with `o`: the library calls of `trajkit plan`.
pub fn plan(w: &Waypoints, limits: &Limits, o: &Options) -> ApiResult<Planned> {
    let lib = |e| ApiError::from_lib("", e);
    let jerked = matches!(o.method, Method::Toppra | Method::Ni) && o.jerk_limit;
    if jerked || o.method == Method::Poly {
        let why = if jerked {
            "the jerk stage (set jerk_limit false to skip it)"
        } else {
            "method poly"
        };
        require(limits, Order::Jerk, why)?;
    }
    let mut notes = Vec::new();
    let (traj, phase): (Box<dyn Trajectory>, _) = match o.method {
        Method::Toppra | Method::Ni => {
            let opts = PlanOptions {
                kind: o.path,
                solver: if o.method == Method::Ni {
                    PieceSolver::Ni
                } else {
                    PieceSolver::Toppra
                },
                toppra: trajkit::topp::Options {
                    gridpoints: trajkit::topp::Gridpoints::Uniform(o.gridpoints),
                    ..Default::default()
                },
                ..Default::default()
            };
            let raw = plan_waypoints(w.points(), w.dof(), limits, &opts).map_err(lib)?;
            let name = if o.method == Method::Ni {
                "NI"
            } else {
                "TOPP-RA"
            };
            if jerked {
                let jl = trajkit::topp::jerk::limit_jerk_sequence(
                    &raw,
                    limits,
                    &trajkit::topp::jerk::JerkOptions::default(),
                )
                .map_err(lib)?;
                notes.push(format!(
                    "jerk: bounded ({name} {:.6} s, timing law filtered and time rescaled by +{:.2} %)",
                    raw.duration(),
                    100.0 * (jl.duration() / raw.duration() - 1.0)
                ));
                let phase = maybe_phase(o, &raw, Some(&jl), limits)?;
                (Box::new(jl), phase)
            } else {
                notes.push(format!("jerk: not bounded (jerk_limit false): {name}'s path acceleration is piecewise constant; jerk is not checked"));
                let phase = maybe_phase(o, &raw, None, limits)?;
                (Box::new(raw), phase)
            }
        }
        Method::Totg => {
            let opts = trajkit::topp::TotgOptions {
                max_deviation: o.max_deviation,
                ..Default::default()
            };
            let raw = trajkit::topp::plan_totg(w.points(), w.dof(), limits, &opts).map_err(lib)?;
            notes.push(format!("jerk: not bounded: the blended path (max deviation {}) is only C¹, so joint acceleration jumps where arcs meet segments; jerk is not checked", o.max_deviation));
            let phase = maybe_phase(o, &raw, None, limits)?;
            (Box::new(raw), phase)
        }
        Method::Poly => {
            let v = ViaTrajectory::new(
                w.points(),
                w.dof(),
                o.degree,
                o.via.clone(),
                ViaTiming::Limits(limits),
            )
            .map_err(lib)?;
            notes.push(format!(
                "{} segments between waypoints, each as short as the limits allow; no phase plane (not a path parameterization)",
                o.degree.name()
            ));
            (Box::new(v), None)
        }
    };
    Ok(Planned {
        traj,
        jerk_checked: jerked || o.method == Method::Poly,
        notes,
        phase,
    })
}

/// The request's waypoints: rows or a file; consecutive duplicates removed (their count
/// returned), at least 2 left, every one within the position range.
fn waypoints(r: &Request, limits: &Limits) -> ApiResult<(Waypoints, usize)> {
    let lib = |field: &'static str| move |e| ApiError::from_lib(field, e);
    let mut w = match (&r.waypoints, &r.waypoints_file) {
        (Some(rows), None) => {
            let (flat, dof) =
                caps::rows("waypoints", rows, 1, caps::MAX_WAYPOINTS, caps::MAX_JOINTS)?;
            Waypoints::new(flat, dof, r.joint_names.clone().unwrap_or_default())
                .map_err(lib("joint_names"))?
        }
        (None, Some(f)) => {
            if r.joint_names.is_some() {
                return Err(ApiError::bad(
                    "joint_names",
                    json!(r.joint_names),
                    "is used only with waypoints (a file names its own columns)",
                ));
            }
            let w = if f.name.to_ascii_lowercase().ends_with(".json") {
                Waypoints::from_json(&f.text, &f.name)
            } else {
                Waypoints::from_csv(&f.text, &f.name)
            }
            .map_err(lib("waypoints_file"))?;
            caps::count(
                "waypoints_file (waypoint count)",
                w.len(),
                1,
                caps::MAX_WAYPOINTS,
            )?;
            caps::count("waypoints_file (joint count)", w.dof(), 1, caps::MAX_JOINTS)?;
            w
        }
        _ => {
            return Err(ApiError::bad(
                "waypoints",
                json!(if r.waypoints.is_some() {
                    "waypoints and waypoints_file"
                } else {
                    "neither waypoints nor waypoints_file"
                }),
                "is not allowed: give exactly one of waypoints and waypoints_file",
            ))
        }
    };
    let removed = w.dedup(0.0);
    if w.len() < 2 {
        return Err(ApiError::from_lib(
            "waypoints",
            trajkit::Error::TooFewWaypoints {
                needed: 2,
                found: w.len(),
            },
        ));
    }
    limits
        .expect_dof(w.dof(), "the waypoints")
        .map_err(lib("limits"))?;
    crate::cmd::plan::check_waypoints_in_range(&w, limits, "waypoints").map_err(|e| {
        ApiError::plain(axum::http::StatusCode::BAD_REQUEST, e.0).field("waypoints")
    })?;
    Ok((w, removed))
}

/// The sample times at `rate`, within the caps on rows and values.
fn sample_times(traj: &dyn Trajectory, rate: f64) -> ApiResult<Vec<f64>> {
    let rows = traj.duration() * rate;
    let cap = caps::MAX_SAMPLE_ROWS.min(caps::MAX_SAMPLE_VALUES / (4 * traj.dof()));
    if rows > cap as f64 {
        return Err(ApiError::bad(
            "rate",
            json!(rate),
            format!(
                "gives {rows:.0} samples for a {:.3} s trajectory of {} joints (cap {cap}): lower the rate",
                traj.duration(),
                traj.dof()
            ),
        ));
    }
    trajkit::sample::sample_times(traj.duration(), rate).map_err(|e| ApiError::from_lib("rate", e))
}

/// The sample table at `rate` (capped), with the joint names.
fn sample_table(
    traj: &dyn Trajectory,
    rate: f64,
    names: &[String],
) -> ApiResult<trajkit::SampleTable> {
    trajkit::sample::sample_at(traj, sample_times(traj, rate)?)
        .and_then(|t| t.with_names(names.to_vec()))
        .map_err(|e| ApiError::from_lib("rate", e))
}

/// A plan request read and checked, ready to plan: everything [`run`] needs.
pub struct Prepared {
    limits: Limits,
    waypoints: Waypoints,
    removed: usize,
    options: Options,
    rate: f64,
}

/// Reads and checks a plan request (limits, waypoints, options, caps): cheap, so that bad
/// requests are refused without waiting for a planning worker.
pub fn prepare(req: Request) -> ApiResult<Prepared> {
    let limits = req.limits.load()?;
    require(&limits, Order::Velocity, "planning")?;
    require(&limits, Order::Acceleration, "planning")?;
    let rate = caps::positive("rate", req.rate)?;
    if rate > 10_000.0 {
        return Err(ApiError::bad(
            "rate",
            json!(rate),
            "exceeds the cap of 10000 Hz",
        ));
    }
    let options = Options::from_request(&req)?;
    let (waypoints, removed) = waypoints(&req, &limits)?;
    Ok(Prepared {
        limits,
        waypoints,
        removed,
        options,
        rate,
    })
}

/// Plans a prepared request and answers it in `format`.
pub fn run(p: Prepared, format: Format) -> ApiResult<Output> {
    let Prepared {
        limits,
        waypoints: w,
        removed,
        options,
        rate,
    } = p;
    let planned = plan(&w, &limits, &options)?;
    let traj = &*planned.traj;
    // The check: every limit the trajectory was planned for, at 1 kHz (fewer samples for very
    // long motions, so that the check stays within the sample cap; the rate is reported).
    let check_rate = 1000.0_f64.min(caps::MAX_SAMPLE_ROWS as f64 / traj.duration().max(1e-9));
    let checked = if planned.jerk_checked {
        limits.clone()
    } else {
        limits
            .clone()
            .with_override(Order::Jerk, &[f64::INFINITY])
            .map_err(|e| ApiError::from_lib("limits", e))?
    };
    let fine = trajkit::sample::sample(traj, check_rate).map_err(|e| ApiError::from_lib("", e))?;
    let report = check_samples(&fine, &checked).map_err(|e| ApiError::from_lib("", e))?;
    let tol = Tolerance::default();
    if !report.passes(&tol) {
        return Err(ApiError::plain(
            axum::http::StatusCode::UNPROCESSABLE_ENTITY,
            format!(
                "the planned trajectory exceeds its limits ({}); nothing is returned: try another method or path",
                report.violations(&tol).join("; ")
            ),
        ));
    }
    let names = w.names().to_vec();
    match format {
        Format::Csv => {
            let t = sample_table(traj, rate, &names)?;
            return Ok(Output::Table("text/csv", trajkit::io::table_to_csv(&t)));
        }
        Format::Json => {
            let t = sample_table(traj, rate, &names)?;
            return Ok(Output::Table(
                "application/json",
                trajkit::io::table_to_json(&t),
            ));
        }
        Format::Summary => {}
    }
    let times = sample_times(traj, rate)?;
    let limits_out = limits
        .joints()
        .iter()
        .map(|j| {
            let range = |o| <[f64; 2]>::from(j.range(o));
            JointLimitsOut {
                name: j.name.clone(),
                position: [j.position_min, j.position_max],
                velocity: range(Order::Velocity),
                acceleration: range(Order::Acceleration),
                jerk: range(Order::Jerk),
            }
        })
        .collect();
    Ok(Output::Summary(Box::new(Response {
        method: options.method,
        duration: traj.duration(),
        joint_names: names,
        waypoints: super::lessons::to_rows(w.points(), w.dof()),
        removed_duplicates: removed,
        limits: limits_out,
        notes: planned.notes,
        check: report.to_json(),
        check_rate,
        samples: series(traj, times)?,
        phase_plane: planned.phase,
    })))
}

/// `GET /api/plan/defaults`: the embedded default path (the same as `trajkit plan`'s) and the
/// presets.
pub fn defaults() -> Value {
    json!({
        "waypoints_csv": crate::cmd::plan::DEFAULT_WAYPOINTS,
        "waypoints_name": "default_waypoints.csv",
        "presets": trajkit::limits::presets::NAMES.split(", ").collect::<Vec<_>>(),
        "methods": ["toppra", "ni", "totg", "poly"],
        "paths": ["natural", "not-a-knot", "clamped", "linear"],
    })
}
