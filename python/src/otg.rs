//! `trajkit.otg`: Ruckig's Python API on trajkit's online generator.
//!
//! Class, attribute, enum and method names, argument orders and return conventions are those
//! of the `ruckig` wheel (lists out, `at_time` returning a tuple of lists, `Bound` extrema,
//! `RuckigError` raised on bad input), so a Ruckig script runs after changing its import.
//! `InputParameter` holds a `trajkit::otg::DynInputParameter` and hands it to the library as
//! it is (no conversion per call); `Ruckig` is the library's `trajkit::otg::DynOtg`, whose
//! storage is sized once, so neither `calculate` nor `update` allocates in the solver.
//!
//! Errors are raised as `RuckigError` (= `trajkit.TrajkitError`) with the library's message
//! and three attributes: `result` (the Ruckig `Result` member of the failure:
//! `ErrorInvalidInput`, `ErrorPositionalLimits`, `ErrorZeroLimits`,
//! `ErrorExecutionTimeCalculation`, `ErrorSynchronizationCalculation`), `kind`
//! (`trajkit::otg::OtgError::name`, e.g. `'position_limits'`, `'interrupted'`) and `dof`
//! (the DOF it is about, or `None`).
//!
//! Ruckig Pro's features: `InputParameter.min_position` / `max_position` (per DOF, ±inf by
//! default) and `interrupt_calculation_duration` (µs, `None` by default) are the library's
//! fields. A budget that runs out before any valid duration is known raises with `kind ==
//! 'interrupted'` (and `update` sets `was_calculation_interrupted` first); one that runs out
//! after gives the shortest valid trajectory found, and `update` reports
//! `was_calculation_interrupted = True` when the library says the budget cut its search short
//! (`DynOutputParameter::was_calculation_interrupted`, `Trajectory.was_interrupted`). With
//! intermediate waypoints the budget bounds the whole planning (`plan_waypoints` is an anytime
//! search) and `update` refines an interrupted motion in the following cycles (the
//! library's `WaypointOtg`, `generator.rs`).
//!
//! Ruckig Pro's intermediate waypoints: `InputParameter` also holds a
//! `trajkit::otg::Waypoints` (`intermediate_positions`, `per_section_max_velocity`,
//! `per_section_max_acceleration`, `per_section_max_jerk`, `per_section_minimum_duration`);
//! an input with waypoints is calculated by `trajkit::otg::plan_waypoints` and its
//! `Trajectory` holds the `WaypointTrajectory` (`trajectory.rs`). Ruckig Pro's fields the
//! library refuses (per-section minimum velocity and acceleration, per-section position
//! limits) raise `TrajkitError` naming them when set. `json.rs` reads and writes the JSON
//! problem format of `trajkit otg` through the library's reader.
//!
//! `Ruckig.update` is `trajkit::otg::DynOtg::update` (Ruckig's contract): it calculates when
//! the input differs from the one it last calculated for, then advances one control period and
//! writes the state there; the state it returns is written into its copy of the input, so
//! feeding it back (`pass_to_input`) does not cause a new calculation.

use pyo3::prelude::*;
use trajkit::otg::{ControlInterface as CI, OtgError, Synchronization as Sync_};

use crate::convert::bad;

mod generator;
mod input;
mod json;
mod trajectory;
use generator::{PyOutput, PyRuckig};
pub use input::PyInput;
pub use trajectory::{solve, PyOtgTrajectory, Solved};

/// The library's error as `trajkit.TrajkitError` (exported as `trajkit.otg.RuckigError` too)
/// with its message and the attributes `result` (the Ruckig `Result` member), `kind` and
/// `dof` (see the module documentation).
pub fn otg_err(e: OtgError) -> PyErr {
    let err = bad(e.to_string());
    let result = match e {
        OtgError::InvalidInput { .. } => PyResult_::ErrorInvalidInput,
        OtgError::PositionLimits { .. } => PyResult_::ErrorPositionalLimits,
        OtgError::ZeroLimits { .. } => PyResult_::ErrorZeroLimits,
        OtgError::CalculationFailed { .. } | OtgError::Interrupted { .. } => {
            PyResult_::ErrorExecutionTimeCalculation
        }
        OtgError::SynchronizationFailed { .. } => PyResult_::ErrorSynchronizationCalculation,
        // A failure added to the library later: Ruckig's generic error.
        _ => PyResult_::Error,
    };
    Python::attach(|py| {
        let value = err.value(py);
        // Setting attributes on a fresh exception instance cannot fail short of memory
        // exhaustion; the error itself is what the caller needs either way.
        let _ = value.setattr("result", result);
        let _ = value.setattr("kind", e.name());
        let _ = value.setattr("dof", e.dof());
    });
    err
}

/// Ruckig's `Result`: the status of `calculate` and `update` (errors are raised as
/// `RuckigError`; the error members exist for code that compares against them).
#[pyclass(module = "trajkit.otg", name = "Result", eq, eq_int, frozen)]
#[derive(Clone, Copy, PartialEq)]
pub enum PyResult_ {
    /// The trajectory is being followed.
    Working = 0,
    /// The target has been reached.
    Finished = 1,
    /// Any error.
    Error = -1,
    /// Invalid input.
    ErrorInvalidInput = -100,
    /// A DOF cannot reach its target inside `[min_position, max_position]`.
    ErrorPositionalLimits = -102,
    /// A DOF with a zero limit cannot reach its target (at the duration the others need).
    ErrorZeroLimits = -104,
    /// Calculation failed.
    ErrorExecutionTimeCalculation = -110,
    /// Synchronization failed.
    ErrorSynchronizationCalculation = -111,
}

/// Ruckig's `Synchronization` (`No` is trajkit's `None`).
#[pyclass(
    module = "trajkit.otg",
    name = "Synchronization",
    from_py_object,
    eq,
    eq_int,
    frozen
)]
#[derive(Clone, Copy, PartialEq)]
pub enum PySync {
    /// All DOFs finish together.
    Time = 0,
    /// Only DOFs with a non-zero target velocity or acceleration are synchronized.
    TimeIfNecessary = 1,
    /// Straight line in joint space where the boundary states allow it.
    Phase = 2,
    /// Every DOF as fast as it can.
    No = 3,
    /// trajkit's fastest straight line in joint space (all DOFs; not in Ruckig).
    StraightLine = 4,
}

/// Ruckig's `ControlInterface`.
#[pyclass(
    module = "trajkit.otg",
    name = "ControlInterface",
    from_py_object,
    eq,
    eq_int,
    frozen
)]
#[derive(Clone, Copy, PartialEq)]
pub enum PyInterface {
    /// Position target (and velocity, acceleration).
    Position = 0,
    /// Velocity target (and acceleration) only.
    Velocity = 1,
}

/// Ruckig's `DurationDiscretization`.
#[pyclass(
    module = "trajkit.otg",
    name = "DurationDiscretization",
    from_py_object,
    eq,
    eq_int,
    frozen
)]
#[derive(Clone, Copy, PartialEq)]
pub enum PyDiscretization {
    /// Any duration.
    Continuous = 0,
    /// A multiple of the control period.
    Discrete = 1,
}

pub(crate) fn sync_to(s: PySync) -> Sync_ {
    match s {
        PySync::Time => Sync_::Time,
        PySync::TimeIfNecessary => Sync_::TimeIfNecessary,
        PySync::Phase => Sync_::Phase,
        PySync::No => Sync_::None,
        PySync::StraightLine => Sync_::StraightLine,
    }
}

pub(crate) fn sync_from(s: Sync_) -> PySync {
    match s {
        Sync_::Time => PySync::Time,
        Sync_::TimeIfNecessary => PySync::TimeIfNecessary,
        Sync_::Phase => PySync::Phase,
        Sync_::None => PySync::No,
        Sync_::StraightLine => PySync::StraightLine,
    }
}

pub(crate) fn interface_from(c: CI) -> PyInterface {
    match c {
        CI::Velocity => PyInterface::Velocity,
        _ => PyInterface::Position,
    }
}

pub(crate) fn interface_to(c: PyInterface) -> CI {
    match c {
        PyInterface::Position => CI::Position,
        PyInterface::Velocity => CI::Velocity,
    }
}
/// One DOF's motion (Ruckig's `Profile`, read-only): jerk segments from a start state,
/// a brake first when the start state was outside the limits.
#[pyclass(module = "trajkit.otg", name = "Profile", frozen, get_all)]
#[derive(Clone)]
pub struct PyProfile {
    /// Segment durations (seconds).
    t: Vec<f64>,
    /// Segment end times (cumulative durations).
    t_sum: Vec<f64>,
    /// Jerk of each segment.
    j: Vec<f64>,
    /// Acceleration at each segment start, then at the end.
    a: Vec<f64>,
    /// Velocity at each segment start, then at the end.
    v: Vec<f64>,
    /// Position at each segment start, then at the end.
    p: Vec<f64>,
    /// Final position.
    pf: f64,
    /// Final velocity.
    vf: f64,
    /// Final acceleration.
    af: f64,
    /// Duration of the brake before the profile proper (0 when none).
    brake_duration: f64,
}

impl PyProfile {
    pub(crate) fn of(pr: &trajkit::otg::Profile) -> Self {
        let n = pr.segments();
        let mut out = PyProfile {
            t: Vec::with_capacity(n),
            t_sum: Vec::with_capacity(n),
            j: Vec::with_capacity(n),
            a: Vec::with_capacity(n + 1),
            v: Vec::with_capacity(n + 1),
            p: Vec::with_capacity(n + 1),
            pf: 0.0,
            vf: 0.0,
            af: 0.0,
            brake_duration: pr.brake_duration(),
        };
        for (t0, d, s, j) in (0..n).filter_map(|k| pr.segment(k)) {
            out.t.push(d);
            out.t_sum.push(t0 + d);
            out.j.push(j);
            out.p.push(s.p);
            out.v.push(s.v);
            out.a.push(s.a);
        }
        let e = pr.end();
        (out.pf, out.vf, out.af) = (e.p, e.v, e.a);
        out.p.push(e.p);
        out.v.push(e.v);
        out.a.push(e.a);
        out
    }
}

#[pymethods]
impl PyProfile {
    fn __repr__(&self) -> String {
        format!(
            "trajkit.otg.Profile(segments={}, duration={}, pf={}, vf={}, af={})",
            self.t.len(),
            self.t_sum.last().copied().unwrap_or(0.0),
            self.pf,
            self.vf,
            self.af
        )
    }
}

/// Ruckig's `Bound`: a DOF's position extrema over the trajectory and their times.
#[pyclass(module = "trajkit.otg", name = "Bound", frozen, get_all)]
#[derive(Clone)]
pub struct PyBound {
    /// Smallest position.
    pub(crate) min: f64,
    /// Largest position.
    pub(crate) max: f64,
    /// Time of the smallest position.
    pub(crate) t_min: f64,
    /// Time of the largest position.
    pub(crate) t_max: f64,
}

#[pymethods]
impl PyBound {
    fn __repr__(&self) -> String {
        format!("[{:.6}, {:.6}]", self.min, self.max)
    }
}

/// Registers the online-generation classes.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyResult_>()?;
    m.add_class::<PySync>()?;
    m.add_class::<PyInterface>()?;
    m.add_class::<PyDiscretization>()?;
    m.add_class::<PyInput>()?;
    m.add_class::<PyOutput>()?;
    m.add_class::<PyOtgTrajectory>()?;
    m.add_class::<PyBound>()?;
    m.add_class::<PyProfile>()?;
    m.add_class::<PyRuckig>()?;
    m.add_function(wrap_pyfunction!(json::read_problem, m)?)?;
    Ok(())
}
