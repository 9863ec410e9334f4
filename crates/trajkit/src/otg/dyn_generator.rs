//! The online generator with a run-time number of degrees of freedom: [`DynOtg`], the
//! counterpart of [`super::Otg`] for bindings and configuration-driven callers.
//!
//! It owns its per-DOF scratch space, the last input and its trajectory, all sized once (at
//! construction, or when an input with more degrees of freedom arrives): after that neither
//! [`DynOtg::calculate_into`] nor [`DynOtg::update`] allocates (the counting-allocator test
//! `tests/otg_no_alloc.rs` checks both). Results equal [`super::calculate_dyn`]'s exactly: the
//! same solver runs on the same input.

use super::input::DynInputParameter;
use super::result::{OtgError, OtgResult};
use super::sync::{calculate_status, Scratch, Spare};
use super::trajectory::{DofTrajectory, DynTrajectory};
use std::time::Instant;

/// The output of one [`DynOtg::update`] (vectors of the input's number of degrees of freedom).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DynOutputParameter {
    /// Position at the new time.
    pub new_position: Vec<f64>,
    /// Velocity at the new time.
    pub new_velocity: Vec<f64>,
    /// Acceleration at the new time.
    pub new_acceleration: Vec<f64>,
    /// Jerk at the new time.
    pub new_jerk: Vec<f64>,
    /// Time since the trajectory was calculated, in seconds.
    pub time: f64,
    /// Whether this update calculated a new trajectory.
    pub new_calculation: bool,
    /// Whether the calculation of this update was cut short by the calculation budget
    /// (`interrupt_calculation_duration`): the trajectory is valid but may be longer than the
    /// shortest (see [`DynTrajectory::was_interrupted`]). False when nothing was calculated.
    pub was_calculation_interrupted: bool,
    /// Wall-clock time of this `update` in microseconds, Ruckig's `calculation_duration`:
    /// from the call to the new state written (before it is copied into the generator's
    /// input), the calculation included when there was one; so a cycle that only follows
    /// the trajectory reports the cost of sampling it. An error leaves it unchanged, as in
    /// Ruckig.
    pub calculation_duration_us: f64,
    /// Duration of the current trajectory.
    pub duration: f64,
}

impl DynOutputParameter {
    /// An output for `dof` degrees of freedom, all zero.
    pub fn new(dof: usize) -> Self {
        DynOutputParameter {
            new_position: vec![0.0; dof],
            new_velocity: vec![0.0; dof],
            new_acceleration: vec![0.0; dof],
            new_jerk: vec![0.0; dof],
            ..Default::default()
        }
    }

    /// Copies the new state into the input's current state (the usual control loop; lengths
    /// follow the output's).
    pub fn pass_to_input(&self, input: &mut DynInputParameter) {
        input.current_position.clone_from(&self.new_position);
        input.current_velocity.clone_from(&self.new_velocity);
        input
            .current_acceleration
            .clone_from(&self.new_acceleration);
    }

    /// Resizes the state vectors to `n` entries (no allocation when they are long enough).
    pub(crate) fn fit(&mut self, n: usize) {
        for v in [
            &mut self.new_position,
            &mut self.new_velocity,
            &mut self.new_acceleration,
            &mut self.new_jerk,
        ] {
            v.resize(n, 0.0);
        }
    }
}

/// The online trajectory generator for a run-time number of degrees of freedom.
///
/// ```
/// use trajkit::otg::{DynInputParameter, DynOtg, DynOutputParameter, OtgResult};
/// let mut otg = DynOtg::new(2, 0.01);
/// let mut input = DynInputParameter::new(2);
/// input.target_position = vec![1.0, -0.5];
/// input.max_velocity = vec![1.0, 1.0];
/// input.max_acceleration = vec![2.0, 2.0];
/// input.max_jerk = vec![10.0, 10.0];
/// let mut out = DynOutputParameter::new(2);
/// let mut cycles = 0;
/// while otg.update(&input, &mut out)? == OtgResult::Working {
///     out.pass_to_input(&mut input);
///     cycles += 1;
/// }
/// assert!((out.new_position[0] - 1.0).abs() < 1e-8);
/// assert!(cycles > 100 && cycles < 300);
/// # Ok::<(), trajkit::otg::OtgError>(())
/// ```
#[derive(Debug, Clone)]
pub struct DynOtg {
    /// Control period in seconds (used by `update` and by discrete durations).
    pub delta_time: f64,
    /// The input of the last calculation of `update`, with the state it advanced to; valid
    /// only while `has_last`.
    last: DynInputParameter,
    has_last: bool,
    traj: DynTrajectory,
    scratch: Vec<Scratch>,
    spare: Vec<Spare>,
    time: f64,
}

impl DynOtg {
    /// A generator for `dof` degrees of freedom (its storage is sized for them) with control
    /// period `delta_time` (seconds).
    pub fn new(dof: usize, delta_time: f64) -> Self {
        DynOtg {
            delta_time,
            last: DynInputParameter::new(dof),
            has_last: false,
            traj: DynTrajectory::new(dof),
            scratch: vec![Scratch::default(); dof],
            spare: vec![None; dof],
            time: 0.0,
        }
    }

    /// Calculates the trajectory for `input` into `traj` (resized to the input's number of
    /// degrees of freedom, reusing its storage): no allocation when the generator and `traj`
    /// already hold that many. On success `traj` equals [`super::calculate_dyn`]'s result; on
    /// error its contents are unspecified (but valid to query).
    pub fn calculate_into(
        &mut self,
        input: &DynInputParameter,
        traj: &mut DynTrajectory,
    ) -> Result<(), OtgError> {
        calculate_with(
            input,
            self.delta_time,
            traj,
            &mut self.scratch,
            &mut self.spare,
        )
    }

    /// One control cycle: re-plan if the input changed (the new state it returned is written
    /// back into its copy of the input, so feeding the output back as the next current state
    /// does not re-plan), advance by `delta_time`, write the new state into `out` (resized to
    /// the input's number of degrees of freedom). Returns `Working`, `Finished` (the new time is
    /// past the end, Ruckig's rule: the cycle that lands exactly on the duration is `Working`)
    /// or the error of the calculation (then `out` keeps its previous
    /// state and the next update calculates again). No allocation once the sizes fit.
    pub fn update(
        &mut self,
        input: &DynInputParameter,
        out: &mut DynOutputParameter,
    ) -> Result<OtgResult, OtgError> {
        out.new_calculation = false;
        out.was_calculation_interrupted = false;
        let start = Instant::now();
        if !self.has_last || self.last != *input {
            let r = calculate_with(
                input,
                self.delta_time,
                &mut self.traj,
                &mut self.scratch,
                &mut self.spare,
            );
            if let Err(e) = r {
                self.has_last = false;
                return Err(e);
            }
            self.last.clone_from(input);
            self.has_last = true;
            self.time = 0.0;
            out.new_calculation = true;
            out.was_calculation_interrupted = self.traj.interrupted;
        }
        out.fit(self.traj.dof());
        let r = self.traj.step(
            &mut self.time,
            self.delta_time,
            &mut out.new_position,
            &mut out.new_velocity,
            &mut out.new_acceleration,
            &mut out.new_jerk,
        );
        out.time = self.time;
        out.duration = self.traj.duration;
        out.calculation_duration_us = start.elapsed().as_secs_f64() * 1e6;
        out.pass_to_input(&mut self.last);
        Ok(r)
    }

    /// The trajectory of the last `update` (empty of motion before the first).
    pub fn trajectory(&self) -> &DynTrajectory {
        &self.traj
    }

    /// Time since the last calculation of `update`, in seconds.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Forgets the last input: the next `update` calculates anew.
    pub fn reset(&mut self) {
        self.has_last = false;
        self.time = 0.0;
    }
}

/// The calculation of [`DynOtg`]: sizes the per-DOF storage for the input (allocating only to
/// grow) and runs the solver into `traj`.
fn calculate_with(
    input: &DynInputParameter,
    delta_time: f64,
    traj: &mut DynTrajectory,
    scratch: &mut Vec<Scratch>,
    spare: &mut Vec<Spare>,
) -> Result<(), OtgError> {
    let n = input.dof();
    if scratch.len() < n {
        scratch.resize(n, Scratch::default());
        spare.resize(n, None);
    }
    traj.dofs.resize(n, DofTrajectory::default());
    let c = calculate_status(&input.view(), delta_time, &mut traj.dofs, scratch, spare)?;
    traj.duration = c.duration;
    traj.interrupted = c.interrupted;
    Ok(())
}
