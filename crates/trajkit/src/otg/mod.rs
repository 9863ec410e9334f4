//! Online trajectory generation: time-optimal, jerk-limited motion from any state to any
//! target state, for one or many degrees of freedom, fast enough to run every control cycle.
//!
//! Data in, data out: an [`InputParameter`] (current state, target state, limits, options)
//! goes through [`Otg::calculate`] (or [`Otg::calculate_into`], into a trajectory the caller
//! reuses) or, once per control cycle, [`Otg::update`], and comes out
//! as an [`OtgTrajectory`] or an [`OutputParameter`], with an [`OtgResult`] status (`Working`,
//! `Finished`) or an [`OtgError`]. Nothing on that path allocates when the number of degrees
//! of freedom is a compile-time constant, and no input makes it panic: non-finite numbers are
//! an `InvalidInput` error naming the field, the degree of freedom and the value.
//!
//! ```
//! use trajkit::otg::{InputParameter, Otg};
//! // The seed example: D = 1, v_max = 0.6, a_max = 1, j_max = 4.
//! let mut input = InputParameter::<1>::new();
//! input.target_position = [1.0];
//! input.max_velocity = [0.6];
//! input.max_acceleration = [1.0];
//! input.max_jerk = [4.0];
//! let otg = Otg::<1>::new(0.001);
//! assert!((otg.calculate(&input)?.duration() - 2.5166666666666667).abs() < 1e-12);
//! input.max_jerk = [f64::INFINITY]; // trapezoidal
//! assert!((otg.calculate(&input)?.duration() - 2.2666666666666667).abs() < 1e-12);
//! # Ok::<(), trajkit::otg::OtgError>(())
//! ```
//!
//! # Precision contract
//! Every profile is verified by integrating it before it is accepted: the final position is
//! within 1e-8 of the target for motions of at least 1e-3, and within 1e-5 of the motion's
//! scale (plus 16 rounding units of the positions) below that, so that a motion of 1e-11
//! arrives; velocity and acceleration within 1e-10. Velocity and acceleration stay within
//! their limits to 1e-12 relative, checked at every segment boundary and at every interior
//! velocity extremum, not at samples. The brake pre-profile, which brings a state that starts
//! outside the limits back inside, is exempt from the limits it repairs. A start state equal to
//! the target state (exactly) gives a trajectory of duration 0.
//!
//! # Files (one per step)
//! [`json`] the Ruckig-style JSON reader · [`input`] validation · [`profile`] the segment list
//! of one DOF · [`velocity_change`] fastest velocity changes · [`brake`] the brake
//! pre-profile · [`zero`] zero limits · [`step1`] time-optimal profile families · [`step2`]
//! profiles of a given duration · [`sync`] the common duration · `phase` Ruckig's phase
//! synchronization and the straight-line mode · [`roots`] polynomial and scalar root
//! finding · [`result`], [`trajectory`], [`generator`].

pub mod brake;
pub mod check;
mod families;
mod families_gen;
pub mod generator;
pub mod input;
pub mod json;
mod phase;
pub mod problem;
pub mod profile;
pub mod result;
pub mod step1;
#[cfg(test)]
mod step1_modes_tests;
pub mod step2;
pub mod sync;
pub mod trajectory;
pub mod velocity_change;
pub mod zero;

pub use generator::{calculate_dyn, Otg, OutputParameter};
pub use input::{
    ControlInterface, DurationDiscretization, DynInputParameter, InputParameter, Options,
    Synchronization,
};
pub use problem::{Dof1, ProfileOrder};
pub use profile::{Profile, State1};
pub use result::{OtgError, OtgResult};
pub use trajectory::{DofTrajectory, DynTrajectory, FixedTrajectory, OtgTrajectory};

/// Time-optimal profile of one degree of freedom (brake pre-profile included), or `None` when
/// the solver finds no valid profile.
pub fn time_optimal(dof: &Dof1) -> Option<Profile> {
    let mut pr = Profile::default();
    step1::step1_fastest_into(dof, &mut pr, &mut None)?;
    Some(pr)
}

/// A profile of one degree of freedom lasting exactly `duration` seconds (brake pre-profile
/// included), or `None` when `duration` is shorter than the minimum, inside a blocked interval,
/// or not found by the step-2 families.
pub fn with_duration(dof: &Dof1, duration: f64) -> Option<Profile> {
    let mut pr = Profile::new(State1 {
        p: dof.p0,
        v: dof.v0,
        a: dof.a0,
    });
    brake::brake(dof, &mut pr);
    let e = pr.end();
    let mut d = *dof;
    d.p0 = e.p;
    d.v0 = e.v;
    d.a0 = e.a;
    let main = step2::step2(&d, duration - pr.duration())?;
    pr.append(&main).then_some(pr)
}
