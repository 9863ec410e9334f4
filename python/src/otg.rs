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
//! (`DynOutputParameter::was_calculation_interrupted`, `Trajectory.was_interrupted`).
//!
//! `Ruckig.update` is `trajkit::otg::DynOtg::update` (Ruckig's contract): it calculates when
//! the input differs from the one it last calculated for, then advances one control period and
//! writes the state there; the state it returns is written into its copy of the input, so
//! feeding it back (`pass_to_input`) does not cause a new calculation.

use pyo3::exceptions::PyIndexError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use trajkit::otg::{
    calculate_dyn, ControlInterface as CI, DurationDiscretization as DD, DynInputParameter,
    DynTrajectory, OtgError, Synchronization as Sync_,
};

use crate::convert::{bad, floats, Floats};

mod generator;
use crate::traj::eval_traj;
use generator::{PyOutput, PyRuckig};

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

fn sync_to(s: PySync) -> Sync_ {
    match s {
        PySync::Time => Sync_::Time,
        PySync::TimeIfNecessary => Sync_::TimeIfNecessary,
        PySync::Phase => Sync_::Phase,
        PySync::No => Sync_::None,
        PySync::StraightLine => Sync_::StraightLine,
    }
}

fn sync_from(s: Sync_) -> PySync {
    match s {
        Sync_::Time => PySync::Time,
        Sync_::TimeIfNecessary => PySync::TimeIfNecessary,
        Sync_::Phase => PySync::Phase,
        Sync_::None => PySync::No,
        Sync_::StraightLine => PySync::StraightLine,
    }
}

fn interface_from(c: CI) -> PyInterface {
    match c {
        CI::Velocity => PyInterface::Velocity,
        _ => PyInterface::Position,
    }
}

fn interface_to(c: PyInterface) -> CI {
    match c {
        PyInterface::Position => CI::Position,
        PyInterface::Velocity => CI::Velocity,
    }
}
/// Ruckig's `InputParameter(dofs)`: current and target state, limits, options.
#[pyclass(module = "trajkit.otg", name = "InputParameter", from_py_object)]
#[derive(Clone)]
pub struct PyInput {
    /// The library's input.
    pub inner: DynInputParameter,
}

impl PyInput {
    /// A fresh input for `dofs` degrees of freedom.
    pub fn with_dofs(dofs: usize) -> Self {
        PyInput {
            inner: DynInputParameter::new(dofs),
        }
    }
}

#[pymethods]
impl PyInput {
    /// `dofs` degrees of freedom: states zero, limits infinite (set them), all enabled.
    #[new]
    fn new(dofs: usize) -> Self {
        PyInput::with_dofs(dofs)
    }

    /// Number of degrees of freedom.
    #[getter]
    fn degrees_of_freedom(&self) -> usize {
        self.inner.dof()
    }

    /// `current_position`: a list, one value per DOF.
    #[getter]
    fn current_position(&self) -> Vec<f64> {
        self.inner.current_position.clone()
    }
    #[setter]
    fn set_current_position(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.current_position = floats(v, "current_position", None)?;
        Ok(())
    }

    /// `current_velocity`: a list, one value per DOF.
    #[getter]
    fn current_velocity(&self) -> Vec<f64> {
        self.inner.current_velocity.clone()
    }
    #[setter]
    fn set_current_velocity(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.current_velocity = floats(v, "current_velocity", None)?;
        Ok(())
    }

    /// `current_acceleration`: a list, one value per DOF.
    #[getter]
    fn current_acceleration(&self) -> Vec<f64> {
        self.inner.current_acceleration.clone()
    }
    #[setter]
    fn set_current_acceleration(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.current_acceleration = floats(v, "current_acceleration", None)?;
        Ok(())
    }

    /// `target_position`: a list, one value per DOF.
    #[getter]
    fn target_position(&self) -> Vec<f64> {
        self.inner.target_position.clone()
    }
    #[setter]
    fn set_target_position(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.target_position = floats(v, "target_position", None)?;
        Ok(())
    }

    /// `target_velocity`: a list, one value per DOF.
    #[getter]
    fn target_velocity(&self) -> Vec<f64> {
        self.inner.target_velocity.clone()
    }
    #[setter]
    fn set_target_velocity(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.target_velocity = floats(v, "target_velocity", None)?;
        Ok(())
    }

    /// `target_acceleration`: a list, one value per DOF.
    #[getter]
    fn target_acceleration(&self) -> Vec<f64> {
        self.inner.target_acceleration.clone()
    }
    #[setter]
    fn set_target_acceleration(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.target_acceleration = floats(v, "target_acceleration", None)?;
        Ok(())
    }

    /// `max_velocity`: a list, one value per DOF.
    #[getter]
    fn max_velocity(&self) -> Vec<f64> {
        self.inner.max_velocity.clone()
    }
    #[setter]
    fn set_max_velocity(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.max_velocity = floats(v, "max_velocity", None)?;
        Ok(())
    }

    /// `max_acceleration`: a list, one value per DOF.
    #[getter]
    fn max_acceleration(&self) -> Vec<f64> {
        self.inner.max_acceleration.clone()
    }
    #[setter]
    fn set_max_acceleration(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.max_acceleration = floats(v, "max_acceleration", None)?;
        Ok(())
    }

    /// `max_jerk`: a list, one value per DOF.
    #[getter]
    fn max_jerk(&self) -> Vec<f64> {
        self.inner.max_jerk.clone()
    }
    #[setter]
    fn set_max_jerk(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.max_jerk = floats(v, "max_jerk", None)?;
        Ok(())
    }

    /// Direction-dependent minimum velocity (negative), or `None` for `-max_velocity`.
    #[getter]
    fn min_velocity(&self) -> Option<Vec<f64>> {
        self.inner.min_velocity.clone()
    }
    #[setter]
    fn set_min_velocity(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        self.inner.min_velocity = v.map(|v| floats(&v, "min_velocity", None)).transpose()?;
        Ok(())
    }

    /// Direction-dependent minimum acceleration (negative), or `None` for `-max_acceleration`.
    #[getter]
    fn min_acceleration(&self) -> Option<Vec<f64>> {
        self.inner.min_acceleration.clone()
    }
    #[setter]
    fn set_min_acceleration(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        self.inner.min_acceleration = v
            .map(|v| floats(&v, "min_acceleration", None))
            .transpose()?;
        Ok(())
    }

    /// Ruckig Pro's `max_position`: the largest position of each DOF along the whole motion
    /// (a list, `inf` = none, the default).
    #[getter]
    fn max_position(&self) -> Vec<f64> {
        self.inner.max_position.clone()
    }
    #[setter]
    fn set_max_position(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.max_position = floats(v, "max_position", None)?;
        Ok(())
    }

    /// Ruckig Pro's `min_position`: the smallest position of each DOF along the whole motion
    /// (a list, `-inf` = none, the default).
    #[getter]
    fn min_position(&self) -> Vec<f64> {
        self.inner.min_position.clone()
    }
    #[setter]
    fn set_min_position(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.min_position = floats(v, "min_position", None)?;
        Ok(())
    }

    /// Ruckig Pro's calculation budget in microseconds, or `None` (no budget, the default):
    /// when it runs out the calculation returns the shortest valid trajectory found so far,
    /// or raises `RuckigError` with `kind == 'interrupted'` when it has none.
    #[getter]
    fn interrupt_calculation_duration(&self) -> Option<f64> {
        self.inner.options.interrupt_calculation_duration
    }
    #[setter]
    fn set_interrupt_calculation_duration(&mut self, v: Option<f64>) {
        self.inner.options.interrupt_calculation_duration = v;
    }

    /// Which DOFs are planned (a disabled one keeps its current acceleration).
    #[getter]
    fn enabled(&self) -> Vec<bool> {
        self.inner.enabled.clone()
    }
    #[setter]
    fn set_enabled(&mut self, v: Vec<bool>) {
        self.inner.enabled = v;
    }

    /// The trajectory lasts at least this long (seconds), or `None`.
    #[getter]
    fn minimum_duration(&self) -> Option<f64> {
        self.inner.options.minimum_duration
    }
    #[setter]
    fn set_minimum_duration(&mut self, v: Option<f64>) {
        self.inner.options.minimum_duration = v;
    }

    /// Time synchronization of the DOFs.
    #[getter]
    fn synchronization(&self) -> PySync {
        sync_from(self.inner.options.synchronization)
    }
    #[setter]
    fn set_synchronization(&mut self, s: PySync) {
        self.inner.options.synchronization = sync_to(s);
    }

    /// Synchronization per DOF (Ruckig's `per_dof_synchronization`; None: `synchronization`
    /// for all). `StraightLine` is for all DOFs only.
    #[getter]
    fn per_dof_synchronization(&self) -> Option<Vec<PySync>> {
        self.inner
            .per_dof_synchronization
            .as_ref()
            .map(|v| v.iter().map(|&s| sync_from(s)).collect())
    }
    #[setter]
    fn set_per_dof_synchronization(&mut self, v: Option<Vec<PySync>>) {
        self.inner.per_dof_synchronization = v.map(|v| v.into_iter().map(sync_to).collect());
    }

    /// Control interface per DOF (Ruckig's `per_dof_control_interface`; None:
    /// `control_interface` for all).
    #[getter]
    fn per_dof_control_interface(&self) -> Option<Vec<PyInterface>> {
        self.inner
            .per_dof_control_interface
            .as_ref()
            .map(|v| v.iter().map(|&c| interface_from(c)).collect())
    }
    #[setter]
    fn set_per_dof_control_interface(&mut self, v: Option<Vec<PyInterface>>) {
        self.inner.per_dof_control_interface = v.map(|v| v.into_iter().map(interface_to).collect());
    }

    /// Position or velocity control.
    #[getter]
    fn control_interface(&self) -> PyInterface {
        interface_from(self.inner.options.control_interface)
    }
    #[setter]
    fn set_control_interface(&mut self, c: PyInterface) {
        self.inner.options.control_interface = interface_to(c);
    }

    /// Continuous duration, or a multiple of the control period.
    #[getter]
    fn duration_discretization(&self) -> PyDiscretization {
        match self.inner.options.duration_discretization {
            DD::Discrete => PyDiscretization::Discrete,
            _ => PyDiscretization::Continuous,
        }
    }
    #[setter]
    fn set_duration_discretization(&mut self, d: PyDiscretization) {
        self.inner.options.duration_discretization = match d {
            PyDiscretization::Continuous => DD::Continuous,
            PyDiscretization::Discrete => DD::Discrete,
        };
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }

    fn __getnewargs__(&self) -> (usize,) {
        (self.inner.dof(),)
    }

    fn __getstate__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let i = &self.inner;
        let o = &i.options;
        (
            (
                i.current_position.clone(),
                i.current_velocity.clone(),
                i.current_acceleration.clone(),
                i.target_position.clone(),
                i.target_velocity.clone(),
                i.target_acceleration.clone(),
            ),
            (
                i.max_velocity.clone(),
                i.max_acceleration.clone(),
                i.max_jerk.clone(),
                i.min_velocity.clone(),
                i.min_acceleration.clone(),
                i.enabled.clone(),
            ),
            (
                o.minimum_duration,
                sync_from(o.synchronization) as i64,
                matches!(o.control_interface, CI::Velocity),
                matches!(o.duration_discretization, DD::Discrete),
            ),
            (
                self.per_dof_synchronization()
                    .map(|v| v.into_iter().map(|s| s as i64).collect::<Vec<_>>()),
                i.per_dof_control_interface.as_ref().map(|v| {
                    v.iter()
                        .map(|c| matches!(c, CI::Velocity))
                        .collect::<Vec<_>>()
                }),
            ),
            (
                i.min_position.clone(),
                i.max_position.clone(),
                o.interrupt_calculation_duration,
            ),
        )
            .into_pyobject(py)
    }

    fn __setstate__(&mut self, state: &Bound<'_, PyTuple>) -> PyResult<()> {
        type States = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);
        type Limits = (
            Vec<f64>,
            Vec<f64>,
            Vec<f64>,
            Option<Vec<f64>>,
            Option<Vec<f64>>,
            Vec<bool>,
        );
        type PerDof = (Option<Vec<i64>>, Option<Vec<bool>>);
        type Options = (Option<f64>, i64, bool, bool);
        type Pro = (Vec<f64>, Vec<f64>, Option<f64>);
        let (s, l, o, d, pro): (States, Limits, Options, PerDof, Pro) = state.extract()?;
        let i = &mut self.inner;
        (
            i.current_position,
            i.current_velocity,
            i.current_acceleration,
            i.target_position,
            i.target_velocity,
            i.target_acceleration,
        ) = s;
        (
            i.max_velocity,
            i.max_acceleration,
            i.max_jerk,
            i.min_velocity,
            i.min_acceleration,
            i.enabled,
        ) = l;
        i.options.minimum_duration = o.0;
        let sync_of = |k: i64| {
            sync_to(match k {
                1 => PySync::TimeIfNecessary,
                2 => PySync::Phase,
                3 => PySync::No,
                4 => PySync::StraightLine,
                _ => PySync::Time,
            })
        };
        let iface_of = |v: bool| if v { CI::Velocity } else { CI::Position };
        i.options.synchronization = sync_of(o.1);
        i.options.control_interface = iface_of(o.2);
        i.options.duration_discretization = if o.3 { DD::Discrete } else { DD::Continuous };
        i.per_dof_synchronization = d.0.map(|v| v.into_iter().map(sync_of).collect());
        i.per_dof_control_interface = d.1.map(|v| v.into_iter().map(iface_of).collect());
        (
            i.min_position,
            i.max_position,
            i.options.interrupt_calculation_duration,
        ) = pro;
        Ok(())
    }

    fn __repr__(&self) -> String {
        let i = &self.inner;
        let mut s = String::new();
        for (name, v) in [
            ("current_position", &i.current_position),
            ("current_velocity", &i.current_velocity),
            ("current_acceleration", &i.current_acceleration),
            ("target_position", &i.target_position),
            ("target_velocity", &i.target_velocity),
            ("target_acceleration", &i.target_acceleration),
            ("max_velocity", &i.max_velocity),
            ("max_acceleration", &i.max_acceleration),
            ("max_jerk", &i.max_jerk),
            ("min_position", &i.min_position),
            ("max_position", &i.max_position),
        ] {
            s.push_str(&format!("inp.{name} = {v:?}\n"));
        }
        s
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
    fn of(pr: &trajkit::otg::Profile) -> Self {
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
    min: f64,
    /// Largest position.
    max: f64,
    /// Time of the smallest position.
    t_min: f64,
    /// Time of the largest position.
    t_max: f64,
}

#[pymethods]
impl PyBound {
    fn __repr__(&self) -> String {
        format!("[{:.6}, {:.6}]", self.min, self.max)
    }
}

/// Ruckig's `Trajectory(dofs)`: filled by `Ruckig.calculate`.
#[pyclass(module = "trajkit.otg", name = "Trajectory")]
#[derive(Clone)]
pub struct PyOtgTrajectory {
    dofs: usize,
    traj: Option<DynTrajectory>,
    /// The input and control period it was calculated from (for pickling).
    source: Option<(DynInputParameter, f64)>,
}

impl PyOtgTrajectory {
    fn get(&self) -> PyResult<&DynTrajectory> {
        self.traj
            .as_ref()
            .ok_or_else(|| bad("this trajectory has not been calculated yet"))
    }

    /// A calculated trajectory (for batches).
    pub fn calculated(input: DynInputParameter, delta_time: f64, traj: DynTrajectory) -> Self {
        PyOtgTrajectory {
            dofs: traj.dof(),
            traj: Some(traj),
            source: Some((input, delta_time)),
        }
    }
}

#[pymethods]
impl PyOtgTrajectory {
    #[new]
    fn new(dofs: usize) -> Self {
        PyOtgTrajectory {
            dofs,
            traj: None,
            source: None,
        }
    }

    /// Duration in seconds (0 before a calculation).
    #[getter]
    fn duration(&self) -> f64 {
        self.traj.as_ref().map_or(0.0, |t| t.duration())
    }

    /// True when the calculation budget (`interrupt_calculation_duration`) cut the search
    /// for the common duration short: the trajectory is valid but may be longer than the
    /// shortest (False before a calculation and without a budget).
    #[getter]
    fn was_interrupted(&self) -> bool {
        self.traj.as_ref().is_some_and(|t| t.was_interrupted())
    }

    /// Number of degrees of freedom.
    #[getter]
    fn degrees_of_freedom(&self) -> usize {
        self.dofs
    }

    /// `(position, velocity, acceleration)` lists at `time`; after the end each DOF continues
    /// with constant acceleration (Ruckig's convention). `return_section=True` appends the
    /// section index (always 0: no intermediate waypoints).
    #[pyo3(signature = (time, return_section = false))]
    fn at_time<'py>(
        &self,
        py: Python<'py>,
        time: f64,
        return_section: bool,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let t = self.get()?;
        let n = t.dof();
        let (mut p, mut v, mut a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        t.at_time(time, &mut p, &mut v, &mut a);
        if return_section {
            (p, v, a, 0usize).into_pyobject(py)
        } else {
            (p, v, a).into_pyobject(py)
        }
    }

    /// The duration each DOF would need on its own.
    #[getter]
    fn independent_min_durations(&self) -> PyResult<Vec<f64>> {
        let t = self.get()?;
        let mut out = vec![0.0; t.dof()];
        t.independent_min_durations(&mut out);
        Ok(out)
    }

    /// Position extrema per DOF (`Bound` objects with `min`, `max`, `t_min`, `t_max`).
    #[getter]
    fn position_extrema(&self) -> PyResult<Vec<PyBound>> {
        let t = self.get()?;
        Ok((0..t.dof())
            .filter_map(|i| t.position_extrema(i))
            .map(|(min, t_min, max, t_max)| PyBound {
                min,
                max,
                t_min,
                t_max,
            })
            .collect())
    }

    /// The first time at or after `time_after` at which DOF `dof` is at `position`, or `None`.
    #[pyo3(signature = (dof, position, time_after = 0.0))]
    fn get_first_time_at_position(
        &self,
        dof: usize,
        position: f64,
        time_after: f64,
    ) -> PyResult<Option<f64>> {
        if time_after.is_nan() {
            return Err(bad("time_after = NaN: expected a time in seconds"));
        }
        let t = self.get()?;
        if dof >= t.dof() {
            return Err(PyIndexError::new_err(format!(
                "dof = {dof} is not below the number of DOFs ({})",
                t.dof()
            )));
        }
        Ok(t.first_time_at_position_after(dof, position, time_after))
    }

    /// Duration of each section (one section: no intermediate waypoints), Ruckig's
    /// `intermediate_durations`.
    #[getter]
    fn intermediate_durations(&self) -> PyResult<Vec<f64>> {
        Ok(vec![self.get()?.duration()])
    }

    /// The profiles, read-only: one list per section (one section), each with one
    /// `Profile` per DOF.
    #[getter]
    fn profiles(&self) -> PyResult<Vec<Vec<PyProfile>>> {
        let t = self.get()?;
        Ok(vec![t
            .dofs()
            .iter()
            .map(|d| PyProfile::of(&d.profile))
            .collect()])
    }

    /// trajkit's vectorized evaluation: the `order`-th derivative (0..3) at every time of `t`
    /// (any shape), shape `t.shape + (dofs,)`, time clamped to `[0, duration]`.
    #[pyo3(signature = (t, order = 0))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        t: Floats<'py>,
        order: i64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let traj = self.get()?;
        eval_traj(py, traj, &t, order)
    }

    fn __getnewargs__(&self) -> (usize,) {
        (self.dofs,)
    }

    fn __getstate__(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        match &self.source {
            None => Ok(py.None()),
            Some((input, dt)) => {
                let inp = Py::new(
                    py,
                    PyInput {
                        inner: input.clone(),
                    },
                )?;
                Ok((inp, *dt).into_pyobject(py)?.into_any().unbind())
            }
        }
    }

    fn __setstate__(&mut self, state: &Bound<'_, PyAny>) -> PyResult<()> {
        if state.is_none() {
            return Ok(());
        }
        let (inp, dt): (PyInput, f64) = state.extract()?;
        let traj = calculate_dyn(&inp.inner, dt).map_err(otg_err)?;
        self.traj = Some(traj);
        self.source = Some((inp.inner, dt));
        Ok(())
    }

    fn __repr__(&self) -> String {
        format!(
            "trajkit.otg.Trajectory(dofs={}, duration={})",
            self.dofs,
            self.duration()
        )
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
    Ok(())
}
