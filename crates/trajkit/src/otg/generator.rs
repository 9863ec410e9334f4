//! The online generator: `calculate` once, or `update` every control cycle.
//!
//! [`Otg`] holds the control period and, for [`Otg::update`], the last input and its
//! trajectory. `update` re-plans only when the input differs from the last one (the new state it
//! returned is written back into its copy of the input, so a caller that feeds the output back
//! as the next current state does not cause a re-plan), then advances one period and returns
//! the state there. With a compile-time number of degrees of freedom neither call allocates.

use super::input::{DynInputParameter, InputParameter};
use super::result::{OtgError, OtgResult};
use super::sync::{calculate_status, Scratch, Spare};
use super::trajectory::{DofTrajectory, DynTrajectory, FixedTrajectory, OtgTrajectory};
use std::time::Instant;

/// The output of one [`Otg::update`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputParameter<const DOF: usize> {
    /// Position at the new time.
    pub new_position: [f64; DOF],
    /// Velocity at the new time.
    pub new_velocity: [f64; DOF],
    /// Acceleration at the new time.
    pub new_acceleration: [f64; DOF],
    /// Jerk at the new time.
    pub new_jerk: [f64; DOF],
    /// Time since the trajectory was calculated, in seconds.
    pub time: f64,
    /// Whether this update calculated a new trajectory.
    pub new_calculation: bool,
    /// Whether the calculation of this update was cut short by the calculation budget
    /// (`interrupt_calculation_duration`): the trajectory is valid but may be longer than the
    /// shortest (see [`OtgTrajectory::was_interrupted`]). False when nothing was calculated.
    pub was_calculation_interrupted: bool,
    /// Wall-clock time of the calculation in microseconds (0 when none was needed).
    pub calculation_duration_us: f64,
    /// Duration of the current trajectory.
    pub duration: f64,
}

impl<const DOF: usize> Default for OutputParameter<DOF> {
    fn default() -> Self {
        OutputParameter {
            new_position: [0.0; DOF],
            new_velocity: [0.0; DOF],
            new_acceleration: [0.0; DOF],
            new_jerk: [0.0; DOF],
            time: 0.0,
            new_calculation: false,
            was_calculation_interrupted: false,
            calculation_duration_us: 0.0,
            duration: 0.0,
        }
    }
}

impl<const DOF: usize> OutputParameter<DOF> {
    /// Copies the new state into the input's current state (the usual control loop).
    pub fn pass_to_input(&self, input: &mut InputParameter<DOF>) {
        input.current_position = self.new_position;
        input.current_velocity = self.new_velocity;
        input.current_acceleration = self.new_acceleration;
    }
}

/// The online trajectory generator for `DOF` degrees of freedom.
///
/// ```
/// use trajkit::otg::{InputParameter, Otg, OtgResult, OutputParameter};
/// let mut otg = Otg::<2>::new(0.01);
/// let mut input = InputParameter::<2>::new();
/// input.target_position = [1.0, -0.5];
/// input.max_velocity = [1.0, 1.0];
/// input.max_acceleration = [2.0, 2.0];
/// input.max_jerk = [10.0, 10.0];
/// let mut out = OutputParameter::<2>::default();
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
pub struct Otg<const DOF: usize> {
    /// Control period in seconds (used by `update` and by discrete durations).
    pub delta_time: f64,
    last: Option<InputParameter<DOF>>,
    traj: FixedTrajectory<DOF>,
    scratch: [Scratch; DOF],
    spare: [Spare; DOF],
    time: f64,
}

impl<const DOF: usize> Otg<DOF> {
    /// A generator with control period `delta_time` (seconds).
    pub fn new(delta_time: f64) -> Self {
        Otg {
            delta_time,
            last: None,
            traj: FixedTrajectory::default(),
            scratch: [Scratch::default(); DOF],
            spare: [None; DOF],
            time: 0.0,
        }
    }

    /// Calculates the trajectory for `input` (no allocation). Returns it by value; a caller
    /// that calculates repeatedly can reuse one trajectory with [`Otg::calculate_into`].
    pub fn calculate(&self, input: &InputParameter<DOF>) -> Result<FixedTrajectory<DOF>, OtgError> {
        let mut traj = FixedTrajectory::<DOF>::default();
        self.calculate_into(input, &mut traj)?;
        Ok(traj)
    }

    /// Calculates the trajectory for `input` into `traj`, a trajectory the caller owns and
    /// may reuse from call to call: no temporary trajectory is built and nothing is copied
    /// out (no allocation either). On success `traj` holds exactly what
    /// [`Otg::calculate`] would return; on error its contents are unspecified (but valid to
    /// query).
    ///
    /// ```
    /// use trajkit::otg::{FixedTrajectory, InputParameter, Otg, OtgError};
    /// let otg = Otg::<1>::new(0.001);
    /// let mut input = InputParameter::<1>::new();
    /// input.max_velocity = [0.6];
    /// input.max_acceleration = [1.0];
    /// input.max_jerk = [4.0];
    /// let mut traj = FixedTrajectory::<1>::default();
    /// for target in [1.0, -0.5, 2.0] {
    ///     input.target_position = [target];
    ///     otg.calculate_into(&input, &mut traj)?;
    ///     assert_eq!(traj, otg.calculate(&input)?);
    /// }
    /// let mut p = [0.0];
    /// traj.at_time(traj.duration(), &mut p, &mut [0.0], &mut [0.0]);
    /// assert!((p[0] - 2.0).abs() < 1e-8);
    /// input.max_jerk = [-1.0];
    /// assert!(matches!(
    ///     otg.calculate_into(&input, &mut traj),
    ///     Err(OtgError::InvalidInput { field: "max_jerk", .. })
    /// ));
    /// # Ok::<(), OtgError>(())
    /// ```
    pub fn calculate_into(
        &self,
        input: &InputParameter<DOF>,
        traj: &mut FixedTrajectory<DOF>,
    ) -> Result<(), OtgError> {
        let mut scratch = [Scratch::default(); DOF];
        let mut spare: [Spare; DOF] = [None; DOF];
        let c = calculate_status(
            &input.view(),
            self.delta_time,
            &mut traj.dofs,
            &mut scratch,
            &mut spare,
        )?;
        traj.duration = c.duration;
        traj.interrupted = c.interrupted;
        Ok(())
    }

    /// One control cycle: re-plan if the input changed, advance by `delta_time`, write the new
    /// state. Returns `Working`, `Finished` (the new time is at or past the end) or the error
    /// of the calculation (then `out` keeps its previous state and the next update calculates
    /// again).
    pub fn update(
        &mut self,
        input: &InputParameter<DOF>,
        out: &mut OutputParameter<DOF>,
    ) -> Result<OtgResult, OtgError> {
        out.new_calculation = false;
        out.was_calculation_interrupted = false;
        out.calculation_duration_us = 0.0;
        if self.last.as_ref() != Some(input) {
            let start = Instant::now();
            let r = calculate_status(
                &input.view(),
                self.delta_time,
                &mut self.traj.dofs,
                &mut self.scratch,
                &mut self.spare,
            );
            out.calculation_duration_us = start.elapsed().as_secs_f64() * 1e6;
            match r {
                Ok(c) => {
                    self.traj.duration = c.duration;
                    self.traj.interrupted = c.interrupted;
                    out.was_calculation_interrupted = c.interrupted;
                }
                Err(e) => {
                    self.last = None;
                    return Err(e);
                }
            }
            self.last = Some(*input);
            self.time = 0.0;
            out.new_calculation = true;
        }
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
        if let Some(last) = self.last.as_mut() {
            out.pass_to_input(last);
        }
        Ok(r)
    }

    /// The trajectory of the last `update`.
    pub fn trajectory(&self) -> &FixedTrajectory<DOF> {
        &self.traj
    }
}

/// Calculates the trajectory of a run-time-sized input (allocates its result).
pub fn calculate_dyn(
    input: &DynInputParameter,
    delta_time: f64,
) -> Result<DynTrajectory, OtgError> {
    let n = input.dof();
    let mut dofs = vec![DofTrajectory::default(); n];
    let mut scratch = vec![Scratch::default(); n];
    let mut spare = vec![None; n];
    let c = calculate_status(
        &input.view(),
        delta_time,
        &mut dofs,
        &mut scratch,
        &mut spare,
    )?;
    Ok(OtgTrajectory {
        dofs,
        duration: c.duration,
        interrupted: c.interrupted,
    })
}
