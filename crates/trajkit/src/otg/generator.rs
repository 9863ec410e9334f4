//! The online generator: `calculate` once, or `update` every control cycle.
//!
//! [`Otg`] holds the control period and, for [`Otg::update`], the last input and its
//! trajectory. `update` re-plans only when the input differs from the last one (the new state it
//! returned is written back into its copy of the input, so a caller that feeds the output back
//! as the next current state does not cause a re-plan), then advances one period and returns
//! the state there. With a compile-time number of degrees of freedom neither call allocates.

use super::input::{DynInputParameter, InputParameter};
use super::result::{OtgError, OtgResult};
use super::sync::{calculate_single, calculate_status, Scratch, Spare};
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
    /// Wall-clock time of this `update` in microseconds, Ruckig's `calculation_duration`:
    /// from the call to the new state written (before it is copied into the generator's
    /// input), the calculation included when there was one; so a cycle that only follows
    /// the trajectory reports the cost of sampling it. An error leaves it unchanged, as in
    /// Ruckig.
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
        let view = input.view();
        if let [one] = &mut traj.dofs[..] {
            if let Some(r) = calculate_single(&view, self.delta_time, one) {
                traj.duration = r?;
                traj.interrupted = false;
                return Ok(());
            }
        }
        let mut scratch = [Scratch::default(); DOF];
        let mut spare: [Spare; DOF] = [None; DOF];
        let c = calculate_status(
            &view,
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
    /// state. Returns `Working`, `Finished` (the new time is past the end, Ruckig's rule: the cycle
    /// that lands exactly on the duration is `Working`) or the error
    /// of the calculation (then `out` keeps its previous state and the next update calculates
    /// again).
    pub fn update(
        &mut self,
        input: &InputParameter<DOF>,
        out: &mut OutputParameter<DOF>,
    ) -> Result<OtgResult, OtgError> {
        out.new_calculation = false;
        out.was_calculation_interrupted = false;
        let start = Instant::now();
        if self.last.as_ref() != Some(input) {
            let r = calculate_status(
                &input.view(),
                self.delta_time,
                &mut self.traj.dofs,
                &mut self.scratch,
                &mut self.spare,
            );
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
        out.calculation_duration_us = start.elapsed().as_secs_f64() * 1e6;
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

#[cfg(test)]
mod tests {
    use super::super::input::{ControlInterface, DurationDiscretization};
    use super::*;
    use crate::rng::SplitMix64;

    /// The general calculation of `input`, without the single-DOF shortcut of `calculate_into`.
    fn general(input: &InputParameter<1>) -> Result<FixedTrajectory<1>, OtgError> {
        let mut traj = FixedTrajectory::<1>::default();
        let c = calculate_status(
            &input.view(),
            0.001,
            &mut traj.dofs,
            &mut [Scratch::default()],
            &mut [None],
        )?;
        traj.duration = c.duration;
        traj.interrupted = c.interrupted;
        Ok(traj)
    }

    #[test]
    fn single_dof_shortcut_matches_the_general_calculation() {
        // Seeded random one-DOF inputs (rest to rest, general states, position limits, zero
        // and asymmetric limits, the velocity interface, invalid values, a disabled DOF, a
        // minimum duration, discrete durations, a budget): the same trajectory bit for bit,
        // or the same error.
        let otg = Otg::<1>::new(0.001);
        let mut r = SplitMix64::new(16);
        let mut traj = FixedTrajectory::<1>::default();
        let (mut ok, mut err) = (0, 0);
        for k in 0..4000 {
            let mut p = InputParameter::<1>::new();
            p.current_position = [r.uniform(-2.0, 2.0)];
            p.target_position = [r.uniform(-2.0, 2.0)];
            p.max_velocity = [r.uniform(0.1, 3.0)];
            p.max_acceleration = [r.uniform(0.5, 15.0)];
            p.max_jerk = [r.uniform(1.0, 8000.0)];
            if k % 2 == 1 {
                p.current_velocity = [r.uniform(-0.5, 0.5) * p.max_velocity[0]];
                p.current_acceleration = [r.uniform(-0.5, 0.5) * p.max_acceleration[0]];
                p.target_velocity = [r.uniform(-0.5, 0.5) * p.max_velocity[0]];
            }
            match r.below(12) {
                0 => {
                    p.max_position = [p.current_position[0].max(p.target_position[0]) + 0.01];
                    p.min_position = [p.current_position[0].min(p.target_position[0]) - 0.01];
                }
                1 => p.max_jerk = [0.0],
                2 => {
                    p.min_velocity = Some([-r.uniform(0.1, 3.0)]);
                    p.min_acceleration = Some([-r.uniform(0.5, 15.0)]);
                }
                3 => p.options.control_interface = ControlInterface::Velocity,
                4 => p.max_velocity = [[-1.0, f64::NAN, f64::INFINITY][k % 3]],
                5 => p.enabled = [false],
                6 => p.options.minimum_duration = Some(r.uniform(0.0, 4.0)),
                7 => p.options.duration_discretization = DurationDiscretization::Discrete,
                8 => p.options.interrupt_calculation_duration = Some([1e6, -1.0][k % 2]),
                9 => p.target_position = p.current_position,
                _ => {}
            }
            let fast = otg.calculate_into(&p, &mut traj).map(|()| traj.clone());
            match (fast, general(&p)) {
                (Ok(a), Ok(b)) => {
                    ok += 1;
                    assert_eq!(a.duration.to_bits(), b.duration.to_bits(), "{p:?}");
                    assert_eq!(a.interrupted, b.interrupted);
                    let (a, b) = (&a.dofs[0], &b.dofs[0]);
                    assert_eq!(a.profile, b.profile, "{p:?}");
                    assert_eq!(a.min_duration.to_bits(), b.min_duration.to_bits());
                    assert_eq!(a.problem, b.problem);
                }
                (Err(a), Err(b)) => {
                    err += 1;
                    assert_eq!(format!("{a:?}"), format!("{b:?}"), "{p:?}");
                }
                (a, b) => panic!("{p:?}: {a:?} vs {b:?}"),
            }
        }
        assert!(ok > 3000 && err > 100, "{ok} {err}");
    }
}
