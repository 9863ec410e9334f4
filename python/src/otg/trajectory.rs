//! `trajkit.otg.Trajectory`: a calculated motion, the generator's (one section) or one
//! through intermediate waypoints (the library's `WaypointTrajectory`, one section per
//! waypoint + 1), behind Ruckig's attribute names.
//!
//! Sections follow Ruckig's conventions: `intermediate_durations` are the times at which each
//! section ends (cumulative, the last one the duration), and the section index that
//! `at_time(t, return_section=True)` reports is the number of sections that have ended at `t`
//! (the number of sections once `t` reaches the duration).

use pyo3::exceptions::PyIndexError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use trajkit::otg::{
    calculate_dyn, plan_waypoints, DynInputParameter, DynTrajectory, OtgError, WaypointTrajectory,
    Waypoints,
};
use trajkit::Trajectory;

use super::{otg_err, PyBound, PyInput, PyProfile};
use crate::convert::{bad, Floats};
use crate::traj::eval_traj;

/// A calculated motion.
#[derive(Clone)]
pub enum Solved {
    /// The generator's trajectory (no waypoints).
    Plain(DynTrajectory),
    /// A motion through intermediate waypoints.
    Waypoints(WaypointTrajectory),
}

const ZERO: [f64; 1] = [0.0];

impl Solved {
    /// The motion as a library trajectory (evaluation clamps time to `[0, duration]`).
    pub fn as_traj(&self) -> &(dyn Trajectory + Send + Sync) {
        match self {
            Solved::Plain(t) => t,
            Solved::Waypoints(w) => w,
        }
    }

    pub fn duration(&self) -> f64 {
        self.as_traj().duration()
    }

    /// Whether the calculation budget cut the calculation short (the library's
    /// `was_interrupted` of either kind of motion).
    pub fn was_interrupted(&self) -> bool {
        match self {
            Solved::Plain(t) => t.was_interrupted(),
            Solved::Waypoints(w) => w.was_interrupted(),
        }
    }

    fn dof(&self) -> usize {
        self.as_traj().dof()
    }

    /// The sections, each a generator trajectory starting at its own time 0.
    pub fn sections(&self) -> &[DynTrajectory] {
        match self {
            Solved::Plain(t) => std::slice::from_ref(t),
            Solved::Waypoints(w) => w.sections(),
        }
    }

    /// The time at which each section starts.
    fn starts(&self) -> &[f64] {
        match self {
            Solved::Plain(_) => &ZERO,
            Solved::Waypoints(w) => w.section_start_times(),
        }
    }

    /// Ruckig's section index at `t`: the number of sections that have ended (the
    /// library's `WaypointTrajectory::section_index_at`; one section without waypoints).
    pub fn section_at(&self, t: f64) -> usize {
        match self {
            Solved::Plain(tr) => usize::from(t >= tr.duration()),
            Solved::Waypoints(w) => w.section_index_at(t),
        }
    }

    /// Position, velocity, acceleration and jerk at `t` (before 0 the start state, after the
    /// end the final state extrapolated with constant acceleration, as in Ruckig).
    pub fn at_time(&self, t: f64, p: &mut [f64], v: &mut [f64], a: &mut [f64], j: &mut [f64]) {
        match self {
            Solved::Plain(tr) => tr.at_time_with_jerk(t, p, v, a, j),
            Solved::Waypoints(w) => w.at_time_with_jerk(t, p, v, a, j),
        }
    }
}

/// Calculates `input` (through its waypoints when it has any: the library's
/// `plan_waypoints`; else `calculate_dyn`) with control period `delta_time`.
pub fn solve(
    input: &DynInputParameter,
    waypoints: Option<&Waypoints>,
    delta_time: f64,
) -> Result<Solved, OtgError> {
    match waypoints {
        Some(w) => plan_waypoints(input, w, delta_time).map(Solved::Waypoints),
        None => calculate_dyn(input, delta_time).map(Solved::Plain),
    }
}

/// Ruckig's `Trajectory(dofs)`: filled by `Ruckig.calculate`.
#[pyclass(module = "trajkit.otg", name = "Trajectory")]
#[derive(Clone)]
pub struct PyOtgTrajectory {
    pub(crate) dofs: usize,
    pub(crate) traj: Option<Solved>,
    /// The input and control period it was calculated from (for pickling).
    pub(crate) source: Option<(PyInput, f64)>,
}

impl PyOtgTrajectory {
    fn get(&self) -> PyResult<&Solved> {
        self.traj
            .as_ref()
            .ok_or_else(|| bad("this trajectory has not been calculated yet"))
    }

    /// A trajectory not calculated yet.
    pub fn empty(dofs: usize) -> Self {
        PyOtgTrajectory {
            dofs,
            traj: None,
            source: None,
        }
    }

    /// A calculated trajectory (for batches).
    pub fn calculated(input: PyInput, delta_time: f64, traj: Solved) -> Self {
        PyOtgTrajectory {
            dofs: traj.dof(),
            traj: Some(traj),
            source: Some((input, delta_time)),
        }
    }
}

/// Records in `slot` the input and control period a trajectory was calculated from (for
/// pickling), reusing its storage.
pub fn set_source(slot: &mut Option<(PyInput, f64)>, input: &PyInput, dt: f64) {
    match slot {
        Some((inp, d)) => {
            inp.inner.clone_from(&input.inner);
            inp.wp.clone_from(&input.wp);
            *d = dt;
        }
        None => *slot = Some((input.clone(), dt)),
    }
}

#[pymethods]
impl PyOtgTrajectory {
    /// An empty trajectory for `dofs` degrees of freedom (`max_number_of_waypoints`, Ruckig
    /// Pro's storage hint, is accepted and unused).
    #[new]
    #[pyo3(signature = (dofs, max_number_of_waypoints = 0))]
    fn new(dofs: usize, max_number_of_waypoints: usize) -> Self {
        let _ = max_number_of_waypoints;
        PyOtgTrajectory::empty(dofs)
    }

    /// Duration in seconds (0 before a calculation).
    #[getter]
    fn duration(&self) -> f64 {
        self.traj.as_ref().map_or(0.0, |t| t.duration())
    }

    /// True when the calculation budget (`interrupt_calculation_duration`) cut the
    /// calculation short: the trajectory is valid but may be longer than the one calculated
    /// without a budget (the search for the common duration; with waypoints, the search over
    /// the waypoint velocities, never longer than stopping at every waypoint). False before a
    /// calculation and without a budget.
    #[getter]
    fn was_interrupted(&self) -> bool {
        self.traj.as_ref().is_some_and(Solved::was_interrupted)
    }

    /// Number of degrees of freedom.
    #[getter]
    fn degrees_of_freedom(&self) -> usize {
        self.dofs
    }

    /// `(position, velocity, acceleration)` lists at `time`; after the end each DOF continues
    /// with constant acceleration (Ruckig's convention). `return_section=True` appends the
    /// section index (Ruckig's: the number of sections that have ended at `time`).
    #[pyo3(signature = (time, return_section = false))]
    fn at_time<'py>(
        &self,
        py: Python<'py>,
        time: f64,
        return_section: bool,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let t = self.get()?;
        let n = t.dof();
        let (mut p, mut v, mut a, mut j) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        t.at_time(time, &mut p, &mut v, &mut a, &mut j);
        if return_section {
            (p, v, a, t.section_at(time)).into_pyobject(py)
        } else {
            (p, v, a).into_pyobject(py)
        }
    }

    /// The duration each DOF would need on its own (with waypoints: summed over the sections,
    /// each between the same waypoint states).
    #[getter]
    fn independent_min_durations(&self) -> PyResult<Vec<f64>> {
        let t = self.get()?;
        let n = t.dof();
        let (mut out, mut one) = (vec![0.0; n], vec![0.0; n]);
        for s in t.sections() {
            s.independent_min_durations(&mut one);
            for (o, x) in out.iter_mut().zip(&one) {
                *o += x;
            }
        }
        Ok(out)
    }

    /// Position extrema per DOF over the whole motion (`Bound` objects with `min`, `max`,
    /// `t_min`, `t_max`).
    #[getter]
    fn position_extrema(&self) -> PyResult<Vec<PyBound>> {
        let t = self.get()?;
        let mut out: Vec<PyBound> = Vec::with_capacity(t.dof());
        for (s, start) in t.sections().iter().zip(t.starts()) {
            for i in 0..t.dof() {
                let Some((min, t_min, max, t_max)) = s.position_extrema(i) else {
                    continue;
                };
                let b = PyBound {
                    min,
                    max,
                    t_min: start + t_min,
                    t_max: start + t_max,
                };
                match out.get_mut(i) {
                    None => out.push(b),
                    Some(o) => {
                        if b.min < o.min {
                            (o.min, o.t_min) = (b.min, b.t_min);
                        }
                        if b.max > o.max {
                            (o.max, o.t_max) = (b.max, b.t_max);
                        }
                    }
                }
            }
        }
        Ok(out)
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
        for (s, &start) in t.sections().iter().zip(t.starts()) {
            if time_after > start + s.duration() {
                continue;
            }
            let local = (time_after - start).max(0.0);
            if let Some(x) = s.first_time_at_position_after(dof, position, local) {
                return Ok(Some(start + x));
            }
        }
        Ok(None)
    }

    /// Ruckig's `intermediate_durations`: the time at which each section ends (cumulative;
    /// one section per waypoint + 1, the last one ends at the duration).
    #[getter]
    fn intermediate_durations(&self) -> PyResult<Vec<f64>> {
        let t = self.get()?;
        let mut out = t.starts()[1..].to_vec();
        out.push(t.duration());
        Ok(out)
    }

    /// The profiles, read-only: one list per section, each with one `Profile` per DOF.
    #[getter]
    fn profiles(&self) -> PyResult<Vec<Vec<PyProfile>>> {
        let t = self.get()?;
        Ok(t.sections()
            .iter()
            .map(|s| s.dofs().iter().map(|d| PyProfile::of(&d.profile)).collect())
            .collect())
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
        eval_traj(py, self.get()?.as_traj(), &t, order)
    }

    fn __getnewargs__(&self) -> (usize,) {
        (self.dofs,)
    }

    fn __getstate__(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        match &self.source {
            None => Ok(py.None()),
            Some((input, dt)) => {
                let inp = Py::new(py, input.clone())?;
                Ok((inp, *dt).into_pyobject(py)?.into_any().unbind())
            }
        }
    }

    fn __setstate__(&mut self, state: &Bound<'_, PyAny>) -> PyResult<()> {
        if state.is_none() {
            return Ok(());
        }
        let (inp, dt): (PyInput, f64) = state.extract()?;
        let traj = solve(&inp.inner, inp.waypoints(), dt).map_err(otg_err)?;
        self.dofs = traj.dof();
        self.traj = Some(traj);
        self.source = Some((inp, dt));
        Ok(())
    }

    fn __repr__(&self) -> String {
        let sections = self.traj.as_ref().map_or(0, |t| t.sections().len());
        format!(
            "trajkit.otg.Trajectory(dofs={}, duration={}, sections={sections})",
            self.dofs,
            self.duration()
        )
    }
}
