//! `trajkit.otg`'s generator: `Ruckig` (the library's `DynOtg`, and `WaypointOtg` for
//! motions through intermediate waypoints) and `OutputParameter` (the library's
//! `WaypointOutput`). See the parent module for the API contract.
//!
//! With intermediate waypoints, `update` is the library's `WaypointOtg::update` (Ruckig
//! Pro's loop: it plans when the input differs from its copy of the last one, follows the
//! motion, reports the section, passes the state back into its copy, and refines a motion
//! whose calculation the budget cut short in the following cycles; see its documentation).
//! An input without waypoints that is not the one being followed goes to `DynOtg::update`.

use pyo3::prelude::*;
use trajkit::otg::{DynOtg, DynTrajectory, OtgError, OtgResult, WaypointOtg, WaypointOutput};

use super::trajectory::set_source;
use super::{otg_err, PyInput, PyOtgTrajectory, PyResult_, Solved};
use crate::convert::bad;

/// Ruckig's `OutputParameter(dofs)`: the state after an `update` (the library's
/// `WaypointOutput`: its `DynOutputParameter`, which `DynOtg::update` writes in place, and
/// the section that `WaypointOtg::update` writes).
#[pyclass(module = "trajkit.otg", name = "OutputParameter")]
pub struct PyOutput {
    inner: WaypointOutput,
    /// Number of degrees of freedom.
    #[pyo3(get)]
    degrees_of_freedom: usize,
    /// The trajectory being followed.
    #[pyo3(get)]
    trajectory: Py<PyOtgTrajectory>,
}

#[pymethods]
impl PyOutput {
    /// The output for `dofs` degrees of freedom (`max_number_of_waypoints`, Ruckig Pro's
    /// storage hint, is accepted and unused).
    #[new]
    #[pyo3(signature = (dofs, max_number_of_waypoints = 0))]
    fn new(py: Python<'_>, dofs: usize, max_number_of_waypoints: usize) -> PyResult<Self> {
        let _ = max_number_of_waypoints;
        Ok(PyOutput {
            inner: WaypointOutput::new(dofs),
            degrees_of_freedom: dofs,
            trajectory: Py::new(py, PyOtgTrajectory::empty(dofs))?,
        })
    }

    /// Section index at the new time (Ruckig's: the number of sections passed; always 0
    /// without waypoints).
    #[getter]
    fn new_section(&self) -> usize {
        self.inner.new_section
    }

    /// Whether the last `update` passed a waypoint (then `pass_to_input` removes it from the
    /// input).
    #[getter]
    fn did_section_change(&self) -> bool {
        self.inner.did_section_change
    }

    /// Position at the new time.
    #[getter]
    fn new_position(&self) -> Vec<f64> {
        self.inner.output.new_position.clone()
    }

    /// Velocity at the new time.
    #[getter]
    fn new_velocity(&self) -> Vec<f64> {
        self.inner.output.new_velocity.clone()
    }

    /// Acceleration at the new time.
    #[getter]
    fn new_acceleration(&self) -> Vec<f64> {
        self.inner.output.new_acceleration.clone()
    }

    /// Jerk at the new time.
    #[getter]
    fn new_jerk(&self) -> Vec<f64> {
        self.inner.output.new_jerk.clone()
    }

    /// Time since the trajectory was calculated.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.output.time
    }

    /// Whether this update calculated a new trajectory.
    #[getter]
    fn new_calculation(&self) -> bool {
        self.inner.output.new_calculation
    }

    /// True when the calculation budget (`interrupt_calculation_duration`) cut this update's
    /// calculation short, as the library reports it: the trajectory is then the shortest valid
    /// one found within the budget (or, when none was found, `update` raised `RuckigError` with
    /// `kind == 'interrupted'`). False without a budget and when nothing was calculated.
    #[getter]
    fn was_calculation_interrupted(&self) -> bool {
        self.inner.output.was_calculation_interrupted
    }

    /// Wall-clock duration of the last `update` in microseconds, as Ruckig's: the whole
    /// cycle up to the new state, the calculation included when there was one (a cycle that
    /// only follows the trajectory reports the cost of sampling it); an error leaves it
    /// unchanged.
    #[getter]
    fn calculation_duration(&self) -> f64 {
        self.inner.output.calculation_duration_us
    }

    /// Copies the new state into `input`'s current state (the usual control loop); when the
    /// last update passed a waypoint, removes it from `input.intermediate_positions` (and the
    /// first entry of each per-section list, so one entry per section remains).
    fn pass_to_input(&self, input: &mut PyInput) {
        self.inner.pass_to_input(&mut input.inner, &mut input.wp);
    }

    /// A copy with its own trajectory (Ruckig's `copy(out)`, to keep an output of the loop).
    fn __copy__(&self, py: Python<'_>) -> PyResult<Self> {
        Ok(PyOutput {
            inner: self.inner.clone(),
            degrees_of_freedom: self.degrees_of_freedom,
            trajectory: Py::new(py, self.trajectory.borrow(py).clone())?,
        })
    }

    fn __deepcopy__(&self, py: Python<'_>, _memo: &Bound<'_, PyAny>) -> PyResult<Self> {
        self.__copy__(py)
    }

    fn __repr__(&self) -> String {
        let o = &self.inner.output;
        format!(
            "out.new_position = {:?}\nout.new_velocity = {:?}\nout.new_acceleration = {:?}\nout.new_jerk = {:?}\nout.time = {}\nout.calculation_duration = {}\n",
            o.new_position,
            o.new_velocity,
            o.new_acceleration,
            o.new_jerk,
            o.time,
            o.calculation_duration_us
        )
    }
}

/// Ruckig's `Ruckig(dofs, delta_time)`: the online trajectory generator (the library's
/// `DynOtg`, whose storage is sized once: `calculate` and `update` reuse it).
#[pyclass(module = "trajkit.otg", name = "Ruckig")]
pub struct PyRuckig {
    /// Number of degrees of freedom.
    #[pyo3(get)]
    degrees_of_freedom: usize,
    otg: DynOtg,
    /// Storage `calculate` writes into before swapping it with the target trajectory's (so a
    /// failed calculation leaves that trajectory as it was).
    spare_traj: Option<DynTrajectory>,
    /// Ruckig Pro's `max_number_of_waypoints` (a storage hint; not a limit here).
    #[pyo3(get)]
    max_number_of_waypoints: usize,
    /// The generator of motions through waypoints (`update` with waypoints).
    wotg: WaypointOtg,
}

impl PyRuckig {
    fn check_dofs(&self, n: usize, what: &str) -> PyResult<()> {
        if n != self.degrees_of_freedom {
            return Err(bad(format!(
                "{what} has {n} degrees of freedom, the generator {}",
                self.degrees_of_freedom
            )));
        }
        Ok(())
    }
}

impl PyRuckig {
    /// `update` on a motion through waypoints: the library's `WaypointOtg::update`; a new
    /// calculation is copied into the output's trajectory.
    fn update_waypoints(
        &mut self,
        py: Python<'_>,
        input: &PyInput,
        out: &mut PyOutput,
    ) -> PyResult<PyResult_> {
        let r = self
            .wotg
            .update(&input.inner, &input.wp, &mut out.inner)
            .map_err(otg_err)?;
        if out.inner.output.new_calculation {
            // The library's generator must calculate anew when an input without waypoints
            // follows.
            self.otg.reset();
            if let Some(traj) = self.wotg.trajectory() {
                let mut ot = out.trajectory.borrow_mut(py);
                ot.traj = Some(Solved::Waypoints(traj.clone()));
                ot.dofs = self.degrees_of_freedom;
                set_source(&mut ot.source, input, self.otg.delta_time);
            }
        }
        Ok(match r {
            OtgResult::Finished => PyResult_::Finished,
            _ => PyResult_::Working,
        })
    }
}

#[pymethods]
impl PyRuckig {
    /// A generator for `dofs` degrees of freedom with control period `delta_time` (seconds;
    /// needed by `update` and by discrete durations). `max_number_of_waypoints` is Ruckig
    /// Pro's storage hint: accepted, not a limit (trajkit sizes storage per calculation).
    #[new]
    #[pyo3(signature = (dofs, delta_time = 0.0, max_number_of_waypoints = 0))]
    fn new(dofs: usize, delta_time: f64, max_number_of_waypoints: usize) -> PyResult<Self> {
        Ok(PyRuckig {
            degrees_of_freedom: dofs,
            otg: DynOtg::new(dofs, delta_time),
            spare_traj: None,
            max_number_of_waypoints,
            wotg: WaypointOtg::new(delta_time),
        })
    }

    /// Control period in seconds.
    #[getter]
    fn delta_time(&self) -> f64 {
        self.otg.delta_time
    }

    #[setter]
    fn set_delta_time(&mut self, dt: f64) {
        self.otg.delta_time = dt;
        self.wotg.delta_time = dt;
    }

    /// Calculates the trajectory for `input` into `trajectory` (through its intermediate
    /// waypoints when it has any); returns `Result.Working`. Raises `RuckigError`
    /// (= `trajkit.TrajkitError`) with trajkit's message on failure (then `trajectory` is
    /// left as it was).
    fn calculate(
        &mut self,
        input: PyRef<'_, PyInput>,
        mut trajectory: PyRefMut<'_, PyOtgTrajectory>,
    ) -> PyResult<PyResult_> {
        let n = input.inner.dof();
        self.check_dofs(n, "the input")?;
        let dt = self.otg.delta_time;
        if let Some(w) = input.waypoints() {
            let solved = super::solve(&input.inner, Some(w), dt).map_err(otg_err)?;
            if let Some(Solved::Plain(old)) = trajectory.traj.replace(solved) {
                self.spare_traj = Some(old);
            }
            trajectory.dofs = n;
            set_source(&mut trajectory.source, &input, dt);
            return Ok(PyResult_::Working);
        }
        let mut t = self
            .spare_traj
            .take()
            .unwrap_or_else(|| DynTrajectory::new(n));
        if let Err(e) = self.otg.calculate_into(&input.inner, &mut t) {
            self.spare_traj = Some(t);
            return Err(otg_err(e));
        }
        if let Some(Solved::Plain(old)) = trajectory.traj.replace(Solved::Plain(t)) {
            self.spare_traj = Some(old);
        }
        trajectory.dofs = n;
        set_source(&mut trajectory.source, &input, dt);
        Ok(PyResult_::Working)
    }

    /// One control cycle (the library's `DynOtg::update`; with waypoints, the same steps on
    /// the motion through them): calculate if `input` changed, advance by `delta_time`, write
    /// the new state (and section) into `output`. Returns `Result.Working`, or
    /// `Result.Finished` once the new time is past the duration (Ruckig's rule: the cycle
    /// landing exactly on the duration is still `Working`).
    fn update(
        &mut self,
        py: Python<'_>,
        input: PyRef<'_, PyInput>,
        mut output: PyRefMut<'_, PyOutput>,
    ) -> PyResult<PyResult_> {
        self.check_dofs(input.inner.dof(), "the input")?;
        let out = &mut *output;
        if self.wotg.follows(&input.inner, &input.wp) || input.waypoints().is_some() {
            return self.update_waypoints(py, &input, out);
        }
        self.wotg.reset();
        out.inner.new_section = 0;
        out.inner.did_section_change = false;
        let r = match self.otg.update(&input.inner, &mut out.inner.output) {
            Ok(r) => r,
            Err(e) => {
                // No valid trajectory within the budget: the budget cut the calculation.
                out.inner.output.was_calculation_interrupted =
                    matches!(e, OtgError::Interrupted { .. });
                return Err(otg_err(e));
            }
        };
        if out.inner.output.new_calculation {
            let mut ot = out.trajectory.borrow_mut(py);
            let src = self.otg.trajectory();
            match ot.traj.as_mut() {
                Some(Solved::Plain(t)) => t.clone_from(src),
                _ => ot.traj = Some(Solved::Plain(src.clone())),
            }
            ot.dofs = src.dof();
            set_source(&mut ot.source, &input, self.otg.delta_time);
        }
        Ok(match r {
            OtgResult::Finished => PyResult_::Finished,
            _ => PyResult_::Working,
        })
    }

    /// Ruckig's `validate_input`: True when `input` can be calculated (lengths, options,
    /// finite values, signs of the limits; with intermediate waypoints also the waypoints and
    /// per-section fields: sizes, finite values, signs, duplicates, position limits, and the
    /// options waypoints do not support) and, as asked, the current / target velocity and
    /// acceleration are within the limits (with per-section limits, those of the first / last
    /// section); else raises `RuckigError` naming the field, the DOF (and waypoint or
    /// section) and the value, with the message `calculate` would give.
    #[pyo3(signature = (input, check_current_state_within_limits = false, check_target_state_within_limits = true))]
    fn validate_input(
        &self,
        input: PyRef<'_, PyInput>,
        check_current_state_within_limits: bool,
        check_target_state_within_limits: bool,
    ) -> PyResult<bool> {
        self.check_dofs(input.inner.dof(), "the input")?;
        let (dt, cur, tgt) = (
            self.otg.delta_time,
            check_current_state_within_limits,
            check_target_state_within_limits,
        );
        match input.waypoints() {
            Some(w) => w.validate(&input.inner, dt, cur, tgt),
            None => input.inner.validate(dt, cur, tgt),
        }
        .map_err(otg_err)?;
        Ok(true)
    }

    /// Forgets the last input: the next `update` calculates anew.
    fn reset(&mut self) {
        self.otg.reset();
        self.wotg.reset();
    }
}
