//! `trajkit.otg`'s generator: `Ruckig` (the library's `DynOtg`) and `OutputParameter` (its
//! `DynOutputParameter`). See the parent module for the API contract.

use pyo3::prelude::*;
use trajkit::otg::{
    DynInputParameter, DynOtg, DynOutputParameter, DynTrajectory, OtgError, OtgResult,
};

use super::{otg_err, PyInput, PyOtgTrajectory, PyResult_};
use crate::convert::bad;

/// Ruckig's `OutputParameter(dofs)`: the state after an `update` (the library's
/// `DynOutputParameter`, which `trajkit::otg::DynOtg::update` writes in place).
#[pyclass(module = "trajkit.otg", name = "OutputParameter")]
pub struct PyOutput {
    inner: DynOutputParameter,
    /// Number of degrees of freedom.
    #[pyo3(get)]
    degrees_of_freedom: usize,
    /// Section index (always 0: no intermediate waypoints).
    #[pyo3(get)]
    new_section: usize,
    /// Always False (no intermediate waypoints).
    #[pyo3(get)]
    did_section_change: bool,
    /// The trajectory being followed.
    #[pyo3(get)]
    trajectory: Py<PyOtgTrajectory>,
}

#[pymethods]
impl PyOutput {
    #[new]
    fn new(py: Python<'_>, dofs: usize) -> PyResult<Self> {
        Ok(PyOutput {
            inner: DynOutputParameter::new(dofs),
            degrees_of_freedom: dofs,
            new_section: 0,
            did_section_change: false,
            trajectory: Py::new(py, PyOtgTrajectory::new(dofs))?,
        })
    }

    /// Position at the new time.
    #[getter]
    fn new_position(&self) -> Vec<f64> {
        self.inner.new_position.clone()
    }

    /// Velocity at the new time.
    #[getter]
    fn new_velocity(&self) -> Vec<f64> {
        self.inner.new_velocity.clone()
    }

    /// Acceleration at the new time.
    #[getter]
    fn new_acceleration(&self) -> Vec<f64> {
        self.inner.new_acceleration.clone()
    }

    /// Jerk at the new time.
    #[getter]
    fn new_jerk(&self) -> Vec<f64> {
        self.inner.new_jerk.clone()
    }

    /// Time since the trajectory was calculated.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time
    }

    /// Whether this update calculated a new trajectory.
    #[getter]
    fn new_calculation(&self) -> bool {
        self.inner.new_calculation
    }

    /// True when the calculation budget (`interrupt_calculation_duration`) cut this update's
    /// calculation short, as the library reports it: the trajectory is then the shortest valid
    /// one found within the budget (or, when none was found, `update` raised `RuckigError` with
    /// `kind == 'interrupted'`). False without a budget and when nothing was calculated.
    #[getter]
    fn was_calculation_interrupted(&self) -> bool {
        self.inner.was_calculation_interrupted
    }

    /// Wall-clock duration of the calculation in microseconds.
    #[getter]
    fn calculation_duration(&self) -> f64 {
        self.inner.calculation_duration_us
    }

    /// Copies the new state into `input`'s current state (the usual control loop).
    fn pass_to_input(&self, input: &mut PyInput) {
        self.inner.pass_to_input(&mut input.inner);
    }

    fn __repr__(&self) -> String {
        let o = &self.inner;
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

/// Records in `slot` the input and control period a trajectory was calculated from (for
/// pickling), reusing its storage.
fn set_source(slot: &mut Option<(DynInputParameter, f64)>, input: &DynInputParameter, dt: f64) {
    match slot {
        Some((inp, d)) => {
            inp.clone_from(input);
            *d = dt;
        }
        None => *slot = Some((input.clone(), dt)),
    }
}

#[pymethods]
impl PyRuckig {
    /// A generator for `dofs` degrees of freedom with control period `delta_time` (seconds;
    /// needed by `update` and by discrete durations). `max_number_of_waypoints` must be 0.
    #[new]
    #[pyo3(signature = (dofs, delta_time = 0.0, max_number_of_waypoints = 0))]
    fn new(dofs: usize, delta_time: f64, max_number_of_waypoints: usize) -> PyResult<Self> {
        if max_number_of_waypoints != 0 {
            return Err(bad(format!(
                "max_number_of_waypoints = {max_number_of_waypoints}: intermediate waypoints are not supported"
            )));
        }
        Ok(PyRuckig {
            degrees_of_freedom: dofs,
            otg: DynOtg::new(dofs, delta_time),
            spare_traj: None,
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
    }

    /// Calculates the trajectory for `input` into `trajectory`; returns `Result.Working`.
    /// Raises `RuckigError` (= `trajkit.TrajkitError`) with trajkit's message on failure
    /// (then `trajectory` is left as it was).
    fn calculate(
        &mut self,
        input: PyRef<'_, PyInput>,
        mut trajectory: PyRefMut<'_, PyOtgTrajectory>,
    ) -> PyResult<PyResult_> {
        let n = input.inner.dof();
        self.check_dofs(n, "the input")?;
        let mut t = self
            .spare_traj
            .take()
            .unwrap_or_else(|| DynTrajectory::new(n));
        if let Err(e) = self.otg.calculate_into(&input.inner, &mut t) {
            self.spare_traj = Some(t);
            return Err(otg_err(e));
        }
        self.spare_traj = trajectory.traj.replace(t);
        trajectory.dofs = n;
        set_source(&mut trajectory.source, &input.inner, self.otg.delta_time);
        Ok(PyResult_::Working)
    }

    /// One control cycle (the library's `DynOtg::update`): calculate if `input` changed,
    /// advance by `delta_time`, write the new state into `output`. Returns `Result.Working` or
    /// `Result.Finished`.
    fn update(
        &mut self,
        py: Python<'_>,
        input: PyRef<'_, PyInput>,
        mut output: PyRefMut<'_, PyOutput>,
    ) -> PyResult<PyResult_> {
        self.check_dofs(input.inner.dof(), "the input")?;
        let out = &mut *output;
        let r = match self.otg.update(&input.inner, &mut out.inner) {
            Ok(r) => r,
            Err(e) => {
                // No valid trajectory within the budget: the budget cut the calculation.
                out.inner.was_calculation_interrupted = matches!(e, OtgError::Interrupted { .. });
                return Err(otg_err(e));
            }
        };
        if out.inner.new_calculation {
            let mut ot = out.trajectory.borrow_mut(py);
            let src = self.otg.trajectory();
            match ot.traj.as_mut() {
                Some(t) => t.clone_from(src),
                None => ot.traj = Some(src.clone()),
            }
            ot.dofs = src.dof();
            set_source(&mut ot.source, &input.inner, self.otg.delta_time);
        }
        Ok(match r {
            OtgResult::Finished => PyResult_::Finished,
            _ => PyResult_::Working,
        })
    }

    /// Ruckig's `validate_input`: True when `input` can be calculated (lengths, options,
    /// finite values, signs of the limits) and, as asked, the current / target velocity and
    /// acceleration are within the limits; else raises `RuckigError` naming the field, the
    /// DOF and the value.
    #[pyo3(signature = (input, check_current_state_within_limits = false, check_target_state_within_limits = true))]
    fn validate_input(
        &self,
        input: PyRef<'_, PyInput>,
        check_current_state_within_limits: bool,
        check_target_state_within_limits: bool,
    ) -> PyResult<bool> {
        self.check_dofs(input.inner.dof(), "the input")?;
        input
            .inner
            .validate(
                self.otg.delta_time,
                check_current_state_within_limits,
                check_target_state_within_limits,
            )
            .map_err(otg_err)?;
        Ok(true)
    }

    /// Forgets the last input: the next `update` calculates anew.
    fn reset(&mut self) {
        self.otg.reset();
    }
}
