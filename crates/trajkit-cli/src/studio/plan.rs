//! `POST /api/plan`: waypoints + limits + method → the sampled trajectory, its limit check, and
//! the phase plane. The lesson "plan" of the page is a client of this endpoint.
//!
//! [`plan`] is the one place that calls the planner: `trajkit::plan`, the library call that
//! `trajkit plan` makes too; everything around it only translates JSON.
//!
//! Safety: `trajkit::plan` returns only trajectories whose 1 kHz samples pass `trajkit::check`
//! against every limit they were planned for; with `jerk_limit: false` (and for `totg`, whose
//! path is only C¹) the jerk limits are stated unlimited first, and the answer says so.

use super::caps;
use super::error::{ApiError, ApiResult};
use super::lessons::{series, Series};
use super::limits_in::{complete, FileIn, LimitsIn};
use super::phase::PhasePlane;
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use trajkit::io::Waypoints;
use trajkit::plan::{JerkStage, PlanOptions, ViaVelocity};
use trajkit::poly::Degree;
use trajkit::topp::messy::PathKind;
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

/// Gridpoints per rest-to-rest piece: `"auto"` (the default: refined until the duration is
/// within 1e-4 relative of the converged optimum, as `trajkit plan`) or an interval count.
#[derive(Debug, Clone, Deserialize, PartialEq, Eq)]
#[serde(untagged)]
pub enum GridIn {
    /// An interval count, 1..=20000.
    Count(usize),
    /// `"auto"`.
    Word(String),
}

impl Default for GridIn {
    fn default() -> Self {
        GridIn::Word("auto".into())
    }
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
    #[serde(default)]
    pub gridpoints: GridIn,
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
    /// The library's plan (trajectory, checked samples, report, notes).
    pub plan: trajkit::plan::Plan,
}

/// The planner options of a request, checked.
pub struct Options {
    method: Method,
    options: PlanOptions,
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
        // TOTG's path is only C¹: it plans with the jerk limits stated unlimited, as
        // `trajkit plan --method totg --no-jerk-limit` does.
        let jerk_limit = r.jerk_limit && r.method != Method::Totg;
        let options = PlanOptions {
            method: match r.method {
                Method::Toppra => trajkit::plan::Method::Toppra,
                Method::Ni => trajkit::plan::Method::Ni,
                Method::Totg => trajkit::plan::Method::Totg,
                Method::Poly => trajkit::plan::Method::Poly,
            },
            path: match r.path {
                PathIn::Natural => PathKind::NaturalCubic,
                PathIn::NotAKnot => PathKind::NotAKnotCubic,
                PathIn::Clamped => PathKind::ClampedCubic,
                PathIn::Linear => PathKind::Linear,
            },
            gridpoints: match &r.gridpoints {
                GridIn::Count(n) => trajkit::topp::Gridpoints::Uniform(caps::count(
                    "gridpoints",
                    *n,
                    1,
                    caps::MAX_GRIDPOINTS,
                )?),
                GridIn::Word(w) if w == "auto" => {
                    trajkit::topp::Gridpoints::Auto { tolerance: 1e-4 }
                }
                GridIn::Word(w) => {
                    return Err(ApiError::bad(
                        "gridpoints",
                        json!(w),
                        "is not \"auto\" or an interval count",
                    ))
                }
            },
            jerk: if jerk_limit {
                JerkStage::Auto
            } else {
                JerkStage::Off
            },
            max_deviation: r
                .max_deviation
                .map_or(Ok(0.1), |d| caps::positive("max_deviation", d))?,
            degree: match r.degree {
                DegreeIn::Cubic => Degree::Cubic,
                DegreeIn::Quintic => Degree::Quintic,
                DegreeIn::Septic => Degree::Septic,
            },
            via_velocity: match r.via_velocity {
                ViaIn::Heuristic => ViaVelocity::Heuristic,
                ViaIn::Zero => ViaVelocity::Zero,
            },
            torque: None,
            sample_rate: 1000.0,
            phase_plane: r.phase_plane,
        };
        Ok(Options {
            method: r.method,
            options,
        })
    }

    /// Whether the jerk limits are stated unlimited before planning (no jerk stage, or a
    /// method that cannot bound jerk).
    fn jerk_unlimited(&self) -> bool {
        !self.options.needs().jerk
    }
}

/// Plans `w` under `limits` with `o`: the library call of `trajkit plan`.
pub fn plan(w: &Waypoints, limits: &Limits, o: &Options) -> ApiResult<Planned> {
    let plan = trajkit::plan::plan(w, limits, &o.options).map_err(|e| {
        let status = match e {
            trajkit::Error::Infeasible(_)
            | trajkit::Error::CannotHold { .. }
            | trajkit::Error::OutOfRange { .. }
            | trajkit::Error::LimitExceeded { .. } => axum::http::StatusCode::UNPROCESSABLE_ENTITY,
            _ => axum::http::StatusCode::BAD_REQUEST,
        };
        ApiError::plain(status, e.to_string())
    })?;
    Ok(Planned { plan })
}

/// The request's waypoints: rows or a file, within the caps.
fn waypoints(r: &Request) -> ApiResult<Waypoints> {
    let lib = |field: &'static str| move |e| ApiError::from_lib(field, e);
    let w = match (&r.waypoints, &r.waypoints_file) {
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
    Ok(w)
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
    let lib = |field: &'static str| move |e| ApiError::from_lib(field, e);
    let rate = caps::positive("rate", req.rate)?;
    if rate > 10_000.0 {
        return Err(ApiError::bad(
            "rate",
            json!(rate),
            "exceeds the cap of 10000 Hz",
        ));
    }
    let options = Options::from_request(&req)?;
    let w = waypoints(&req)?;
    let (mut partial, _unused) = req.limits.load(w.given_names())?;
    if options.jerk_unlimited() {
        partial = partial
            .with_override(Order::Jerk, &[f64::INFINITY])
            .map_err(lib("limits"))?;
    }
    let limits = complete(&partial, options.options.needs())?;
    limits
        .expect_dof(w.dof(), "the waypoints")
        .map_err(lib("limits"))?;
    // Refused here, before waiting for a planning worker: fewer than two distinct waypoints,
    // waypoints outside the position ranges.
    let mut distinct = w.clone();
    let removed = distinct.dedup(0.0);
    if distinct.len() < 2 {
        return Err(ApiError::from_lib(
            "waypoints",
            trajkit::Error::TooFewWaypoints {
                needed: 2,
                found: distinct.len(),
            },
        ));
    }
    limits
        .check_waypoints(w.points(), None)
        .map_err(lib("waypoints"))?;
    Ok(Prepared {
        limits,
        waypoints: w,
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
    let plan = &planned.plan;
    let traj = &*plan.trajectory;
    let mut notes = plan.notes.clone();
    if options.jerk_unlimited() && options.method != Method::Poly {
        notes.push(
            "jerk limits stated unlimited for this method (jerk_limit false, or totg's C¹ path): jerk is not checked"
                .to_string(),
        );
    }
    let names = plan.names.clone();
    let limits = &plan.limits;
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
        notes,
        check: plan.report.to_json(),
        check_rate: options.options.sample_rate,
        samples: series(traj, times)?,
        phase_plane: plan.phase_plane.as_ref().map(PhasePlane::from),
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
