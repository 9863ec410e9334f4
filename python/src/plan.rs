//! `trajkit.plan`: the main job in one call, `trajkit::plan::plan`.
//!
//! Waypoints (an `(n, dof)` array with optional `joint_names`, or a CSV/JSON file as
//! `trajkit plan --waypoints` reads it) and limits in any form (a preset, a file, a dict, a
//! `trajkit.Limits`, completed by the CLI's keyword arguments: [`LimitsArgs`]); the limits the
//! method needs are `PlanOptions::needs()`, and a missing one is a `TrajkitError` naming the
//! joint and field. The result is a `trajkit.Plan`, a `trajkit.Trajectory` with the plan's
//! report, notes and samples; it pickles by the call that made it. `jerk_stage` is
//! `trajkit plan --jerk-stage` (`'auto'`, `'filter'`, `'third-order'`: `trajkit::plan::JerkStage`);
//! `jerk_limit=False` is `JerkStage::Off`.

use std::path::PathBuf;
use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use trajkit::io::Waypoints;
use trajkit::plan::{JerkStage, Method, PlanOptions, ViaVelocity};
use trajkit::poly::Degree;
use trajkit::topp::messy::{PathKind, TorqueModel};
use trajkit::topp::Gridpoints;
use trajkit::Order;

use crate::convert::{bad, table, Floats, IntoPy};
use crate::limits::{complete, LimitsArgs, PyLimits};
use crate::traj::PyTrajectory;

/// The result of `trajkit.plan`: a trajectory that keeps every limit it was given (checked
/// at `sample_rate` exactly as `trajkit check` checks), with the plan's report and notes.
#[pyclass(module = "trajkit", name = "Plan", extends = PyTrajectory, frozen)]
pub struct PyPlan {
    record: PlanRecord,
}

fn method(name: &str) -> PyResult<Method> {
    Ok(match name {
        "toppra" => Method::Toppra,
        "ni" => Method::Ni,
        "totg" => Method::Totg,
        "poly" => Method::Poly,
        other => {
            return Err(bad(format!(
                "method = '{other}' is not 'toppra', 'ni', 'totg' or 'poly'"
            )))
        }
    })
}

fn gridpoints(g: &Bound<'_, PyAny>) -> PyResult<Gridpoints> {
    if let Ok(s) = g.extract::<String>() {
        if s == "auto" {
            return Ok(PlanOptions::default().gridpoints);
        }
    } else if let Ok(n) = g.extract::<usize>() {
        if n > 0 {
            return Ok(Gridpoints::Uniform(n));
        }
    }
    Err(bad(format!(
        "gridpoints = {}: expected 'auto' or a positive interval count",
        g.repr()?
    )))
}

/// The jerk stage of `toppra` and `ni` (`trajkit plan --jerk-stage`); `None` is `'auto'`,
/// the library's default. `jerk_limit=False` is [`JerkStage::Off`] and takes no stage.
fn jerk_stage(name: Option<&str>, jerk_limit: bool) -> PyResult<JerkStage> {
    if !jerk_limit {
        return match name {
            None => Ok(JerkStage::Off),
            Some(s) => Err(bad(format!(
                "jerk_stage = '{s}' bounds jerk, jerk_limit=False states it unlimited: give one of them"
            ))),
        };
    }
    Ok(match name {
        None | Some("auto") => JerkStage::Auto,
        Some("filter") => JerkStage::Filter,
        Some("third-order") => JerkStage::ThirdOrder,
        Some(other) => {
            return Err(bad(format!(
                "jerk_stage = '{other}' is not 'auto', 'filter' or 'third-order'"
            )))
        }
    })
}

fn degree(name: &str) -> PyResult<Degree> {
    Ok(match name {
        "cubic" => Degree::Cubic,
        "quintic" => Degree::Quintic,
        "septic" => Degree::Septic,
        other => {
            return Err(bad(format!(
                "degree = '{other}' is not 'cubic', 'quintic' or 'septic'"
            )))
        }
    })
}

fn via_velocity(name: &str) -> PyResult<ViaVelocity> {
    Ok(match name {
        "heuristic" => ViaVelocity::Heuristic,
        "zero" => ViaVelocity::Zero,
        other => {
            return Err(bad(format!(
                "via_velocity = '{other}' is not 'heuristic' or 'zero'"
            )))
        }
    })
}

/// Waypoints from an array (with optional names) or a file path.
fn waypoints(w: &Bound<'_, PyAny>, joint_names: Option<Vec<String>>) -> PyResult<Waypoints> {
    if let Ok(p) = w.extract::<PathBuf>() {
        if joint_names.is_some() {
            return Err(bad(
                "joint_names: a waypoint file names its joints in its header",
            ));
        }
        return Waypoints::from_file(&p).py();
    }
    let a: Floats<'_> = w
        .extract()
        .map_err(|e| bad(format!("waypoints: not an array of numbers ({e})")))?;
    let t = table(&a, "waypoints")?;
    if t.was_1d {
        return Err(bad(format!(
            "waypoints: expected shape (n, dof), found ({},)",
            t.rows
        )));
    }
    Waypoints::new(t.data.into_owned(), t.dim, joint_names.unwrap_or_default()).py()
}

/// The dynamics model for torque limits: `dynamics` (a URDF), else the limits when they are a
/// URDF path. Its joints must be the columns, in order.
fn torque_model(
    dynamics: Option<PathBuf>,
    limits: Option<&Bound<'_, PyAny>>,
    names: &[String],
) -> PyResult<TorqueModel> {
    let spec = limits.and_then(|l| l.extract::<PathBuf>().ok());
    let is_urdf = |p: &PathBuf| {
        p.extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("urdf"))
    };
    let path = match (dynamics, spec) {
        (Some(p), _) => p,
        (None, Some(p)) if is_urdf(&p) => p,
        _ => {
            return Err(bad(
                "torque_limits=True needs a dynamics model: dynamics='robot.urdf' (or limits given as a .urdf path)",
            ))
        }
    };
    let chain = trajkit::dynamics::SerialChain::from_urdf_file(&path).py()?;
    let model: Vec<String> = chain.joint_names().iter().map(|s| s.to_string()).collect();
    let unnamed = names.iter().all(String::is_empty);
    if model.len() != names.len() || (!unnamed && model != names) {
        return Err(bad(format!(
            "{}: the dynamics model's joints [{}] must be the waypoint columns [{}], in order",
            path.display(),
            model.join(", "),
            names.join(", ")
        )));
    }
    Ok(TorqueModel::new(chain))
}

/// Plans a trajectory through `waypoints` within `limits` (see the module documentation).
///
/// `jerk_stage` (toppra and ni, as `trajkit plan --jerk-stage`): `'auto'` (the default, also
/// `None`: the exact jerk-limited optimum on straight-line pieces, the filter elsewhere),
/// `'filter'` (the filter on every piece) or `'third-order'` (`'auto'` plus the third-order
/// time-optimal planner on curved pieces, the shorter result kept; seconds per piece).
/// `jerk_limit=False` plans without a jerk stage and takes no `jerk_stage`.
///
/// Longer than trajkit's usual 80 lines on purpose: it is the Python signature itself
/// (25 keyword arguments, each converted once) plus the pickling recipe that must name every
/// one of them again; the work is in the library's [`trajkit::plan::plan`] and the shared
/// limit helpers.
#[pyfunction]
#[pyo3(signature = (
    waypoints, limits = None, *, method = "toppra", joint_names = None, path = "natural",
    gridpoints = None, jerk_limit = true, jerk_stage = None, max_deviation = 0.1, degree = "quintic",
    via_velocity = "heuristic", sample_rate = 1000.0, torque_limits = false, dynamics = None,
    joint_limits = None, fill_from = None, fill_by = "name", max_velocity = None,
    max_acceleration = None, max_jerk = None, position_range = None, velocity_scale = 1.0,
    acceleration_scale = 1.0, jerk_scale = 1.0
))]
#[allow(clippy::too_many_arguments)]
fn plan<'py>(
    py: Python<'py>,
    waypoints: Bound<'py, PyAny>,
    limits: Option<Bound<'py, PyAny>>,
    method: &str,
    joint_names: Option<Vec<String>>,
    path: &str,
    gridpoints: Option<Bound<'py, PyAny>>,
    jerk_limit: bool,
    jerk_stage: Option<&str>,
    max_deviation: f64,
    degree: &str,
    via_velocity: &str,
    sample_rate: f64,
    torque_limits: bool,
    dynamics: Option<PathBuf>,
    joint_limits: Option<PathBuf>,
    fill_from: Option<Bound<'py, PyAny>>,
    fill_by: &str,
    max_velocity: Option<Bound<'py, PyAny>>,
    max_acceleration: Option<Bound<'py, PyAny>>,
    max_jerk: Option<Bound<'py, PyAny>>,
    position_range: Option<Bound<'py, PyAny>>,
    velocity_scale: f64,
    acceleration_scale: f64,
    jerk_scale: f64,
) -> PyResult<Bound<'py, PyPlan>> {
    let (names_arg, dynamics_arg, joint_limits_arg) =
        (joint_names.clone(), dynamics.clone(), joint_limits.clone());
    let w = self::waypoints(&waypoints, joint_names)?;
    let m = self::method(method)?;
    let stage = self::jerk_stage(jerk_stage, jerk_limit)?;
    if !jerk_limit && max_jerk.is_some() {
        return Err(bad(
            "jerk_limit=False states every jerk limit unlimited; do not give max_jerk too",
        ));
    }
    let args = LimitsArgs::read(
        joint_limits,
        fill_from.as_ref(),
        fill_by,
        max_velocity.as_ref(),
        max_acceleration.as_ref(),
        max_jerk.as_ref(),
        position_range.as_ref(),
        (velocity_scale, acceleration_scale, jerk_scale),
    )?;
    let (mut partial, _unused) =
        args.resolve(limits.as_ref(), "waypoint", w.given_names(), w.dof())?;
    if !jerk_limit {
        partial = partial.with_override(Order::Jerk, &[f64::INFINITY]).py()?;
    }
    let mut options = PlanOptions {
        method: m,
        path: PathKind::parse(path).py()?,
        gridpoints: match &gridpoints {
            None => PlanOptions::default().gridpoints,
            Some(g) => self::gridpoints(g)?,
        },
        jerk: stage,
        max_deviation,
        degree: self::degree(degree)?,
        via_velocity: self::via_velocity(via_velocity)?,
        torque: None,
        sample_rate,
        phase_plane: false,
    };
    let lim = complete(&partial, options.needs())?;
    if torque_limits {
        let names: Vec<String> = lim.joints().iter().map(|j| j.name.clone()).collect();
        options.torque = Some(torque_model(dynamics, limits.as_ref(), &names)?);
    } else if dynamics.is_some() {
        return Err(bad("dynamics= is used only with torque_limits=True"));
    }
    let p = py
        .detach(|| trajkit::plan::plan(&w, &lim, &options))
        .map_err(|e| match &e {
            trajkit::Error::CannotHold { field: "jerk", .. } => {
                bad(format!("{e} (jerk_limit=False, or max_jerk=float('inf'))"))
            }
            _ => crate::convert::err(e),
        })?;
    // The recipe that rebuilds the plan when unpickled: the same call.
    let kwargs = PyDict::new(py);
    macro_rules! keep {
        ($($name:ident),*) => {
            $(kwargs.set_item(stringify!($name), &$name)?;)*
        };
    }
    keep!(
        method,
        path,
        gridpoints,
        jerk_limit,
        jerk_stage,
        max_deviation,
        degree,
        via_velocity,
        sample_rate,
        torque_limits,
        fill_from,
        fill_by,
        max_velocity,
        max_acceleration,
        max_jerk,
        position_range,
        velocity_scale,
        acceleration_scale,
        jerk_scale
    );
    kwargs.set_item("joint_names", names_arg)?;
    kwargs.set_item("dynamics", dynamics_arg)?;
    kwargs.set_item("joint_limits", joint_limits_arg)?;
    let recipe = PyTuple::new(
        py,
        [
            waypoints.clone(),
            limits.clone().unwrap_or_else(|| py.None().into_bound(py)),
            kwargs.into_any(),
        ],
    )?;
    let traj: Arc<dyn trajkit::Trajectory + Send + Sync> = Arc::from(p.trajectory);
    let record = PlanRecord {
        method: m.name(),
        samples: p.samples,
        report: p.report,
        limits: p.limits,
        names: p.names,
        waypoints: p.waypoints,
        repeats_removed: p.repeats_removed,
        pieces: p.pieces,
        raw_duration: p.raw_duration,
        range_repairs: p.range_repairs,
        torque: p.torque,
        check_scale: p.check_scale,
        notes: p.notes,
    };
    let t = PyTrajectory::new(traj);
    let obj = Bound::new(
        py,
        PyClassInitializer::from(t).add_subclass(PyPlan { record }),
    )?;
    let rebuild = py.import("trajkit")?.getattr("_replan")?;
    obj.call_method1("_set_recipe", (rebuild, recipe))?;
    Ok(obj)
}

/// What a plan reports besides its trajectory.
struct PlanRecord {
    method: &'static str,
    samples: trajkit::sample::SampleTable,
    report: trajkit::check::LimitReport,
    limits: trajkit::Limits,
    names: Vec<String>,
    waypoints: usize,
    repeats_removed: usize,
    pieces: usize,
    raw_duration: f64,
    range_repairs: Vec<trajkit::plan::RangeRepair>,
    torque: Option<trajkit::plan::TorqueReport>,
    check_scale: f64,
    notes: Vec<String>,
}

#[pymethods]
impl PyPlan {
    /// The method: `'toppra'`, `'ni'`, `'totg'` or `'poly'`.
    #[getter]
    fn method(&self) -> &'static str {
        self.record.method
    }

    /// Joint names: the waypoints', else the limits', else empty strings.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.record.names.clone()
    }

    /// The limits used, one joint per waypoint column in the columns' order (complete).
    #[getter]
    fn limits(&self) -> PyLimits {
        PyLimits {
            inner: self.record.limits.clone().into(),
        }
    }

    /// The samples that were checked, at `sample_rate`: `(t, q, qd, qdd, qddd)`.
    #[getter]
    fn samples<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        crate::traj::table_tuple(py, &self.record.samples)
    }

    /// The check of the samples against the limits (`trajkit check`'s JSON as a dict:
    /// `samples`, `duration`, `worst`, per joint the worst ratio per order and where). It
    /// passes: a plan whose check fails is never returned.
    #[getter]
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = self.record.report.to_json().to_string();
        py.import("json")?.call_method1("loads", (text,))
    }

    /// The check as the text table `trajkit check` prints.
    #[getter]
    fn report_text(&self) -> String {
        self.record.report.to_text()
    }

    /// The largest ratio of any checked quantity to its limit (≤ 1 up to the check's
    /// tolerance).
    #[getter]
    fn worst_ratio(&self) -> f64 {
        self.record.report.worst()
    }

    /// Lines for people: what the jerk stage did, limits not used, range repairs, slow-downs.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.record.notes.clone()
    }

    /// Waypoints planned through (after removing consecutive repeats).
    #[getter]
    fn waypoints(&self) -> usize {
        self.record.waypoints
    }

    /// Consecutive repeated waypoints removed.
    #[getter]
    fn repeats_removed(&self) -> usize {
        self.record.repeats_removed
    }

    /// Rest-to-rest pieces (the robot stops between them).
    #[getter]
    fn pieces(&self) -> usize {
        self.record.pieces
    }

    /// Duration of the method's own result, before the jerk stage and slow-downs (seconds).
    #[getter]
    fn raw_duration(&self) -> f64 {
        self.record.raw_duration
    }

    /// Uniform slow-down applied by the final check (1 when none was needed).
    #[getter]
    fn check_scale(&self) -> f64 {
        self.record.check_scale
    }

    /// Where the spline path was reshaped to stay inside a position range: dicts with
    /// `joint`, `excursion`, `between` (waypoint indices) and `waypoints_changed`.
    #[getter]
    fn range_repairs<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.record
            .range_repairs
            .iter()
            .map(|r| {
                let d = PyDict::new(py);
                d.set_item("joint", r.joint)?;
                d.set_item("excursion", r.excursion)?;
                d.set_item("between", r.between)?;
                d.set_item("waypoints_changed", r.waypoints_changed)?;
                Ok(d)
            })
            .collect()
    }

    /// With `torque_limits=True`: `{'worst', 'joint', 'scale'}` (worst |τ|/effort over the
    /// samples, its joint, the uniform slow-down applied); else None.
    #[getter]
    fn torque<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        self.record
            .torque
            .as_ref()
            .map(|t| {
                let d = PyDict::new(py);
                d.set_item("worst", t.worst)?;
                d.set_item("joint", t.joint)?;
                d.set_item("scale", t.scale)?;
                Ok(d)
            })
            .transpose()
    }

    fn __repr__(slf: &Bound<'_, Self>) -> String {
        let t = slf.as_super().get();
        format!(
            "trajkit.Plan(method='{}', dof={}, duration={})",
            slf.get().record.method,
            t.inner.dof(),
            t.inner.duration()
        )
    }
}

/// Registers `plan` and `Plan`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyPlan>()?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    Ok(())
}
