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
//! `json.rs` the Ruckig-style JSON reader (public: [`json`]) · `input.rs` the input types
//! and their validation · `problem.rs` one DOF's problem · `profile.rs` the segment list of
//! one DOF · `velocity_change.rs` fastest velocity changes · `brake.rs` the brake
//! pre-profile · `zero.rs` zero limits · `step1/` time-optimal profile families (the
//! collector, verification, the rest-to-rest closed form, the closed-form and fallback
//! families) · `families.rs` + `families_gen.rs` the families' position polynomials ·
//! `step2.rs` profiles of a given duration · `sync.rs` the common duration · `phase.rs`
//! Ruckig's phase synchronization and the straight-line mode · `result.rs`, `trajectory.rs`,
//! `generator.rs`, `check.rs`. Polynomial and scalar roots come from [`crate::roots`].
//!
//! # Public API
//! Everything a user needs is re-exported here; the files are private.

mod brake;
mod check;
mod families;
mod families_gen;
mod generator;
mod input;
#[cfg(feature = "serde")]
pub mod json;
mod phase;
mod problem;
mod profile;
mod result;
mod step1;
mod step2;
mod sync;
mod trajectory;
mod velocity_change;
mod zero;

pub use check::{check, SolutionCheck};
pub use generator::{calculate_dyn, Otg, OutputParameter};
pub use input::{
    ControlInterface, DurationDiscretization, DynInputParameter, InputParameter, OtgOptions,
    Synchronization,
};
pub use profile::{Profile, State1, MAX_SEGMENTS};
pub use result::{FieldName, OtgError, OtgResult};
pub use step1::{TOL_LIMIT, TOL_POSITION, TOL_VELOCITY};
pub use trajectory::{DofTrajectory, DynTrajectory, FixedTrajectory, OtgTrajectory};

#[cfg(test)]
use problem::Dof1;

#[cfg(test)]
/// Time-optimal profile of one degree of freedom (brake pre-profile included), or `None` when
/// the solver finds no valid profile.
pub(crate) fn time_optimal(dof: &Dof1) -> Option<Profile> {
    let mut pr = Profile::default();
    step1::step1_fastest_into(dof, &mut pr, &mut None)?;
    Some(pr)
}

#[cfg(test)]
/// A profile of one degree of freedom lasting exactly `duration` seconds (brake pre-profile
/// included), or `None` when `duration` is shorter than the minimum, inside a blocked interval,
/// or not found by the step-2 families.
pub(crate) fn with_duration(dof: &Dof1, duration: f64) -> Option<Profile> {
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
