//! Online trajectory generation: time-optimal, jerk-limited motion from any state to any
//! target state, for one or many degrees of freedom, fast enough to run every control cycle.
//!
//! Data in, data out: an [`InputParameter`] (current state, target state, limits, options)
//! goes through [`Otg::calculate`] (or [`Otg::calculate_into`], into a trajectory the caller
//! reuses) or, once per control cycle, [`Otg::update`] ([`DynOtg`] is the same generator for a
//! run-time number of degrees of freedom: storage sized once, then no allocation), and comes out
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
//! # Ruckig Pro's features
//! Position limits (`min_position`/`max_position`): positions stay within them along the
//! whole motion, checked at the profiles' exact position extrema (to 1e-12 of the motion's
//! position scale); the unconstrained optimum is kept whenever it stays inside; a target that
//! cannot be reached inside is [`OtgError::PositionLimits`]. Method and what is optimal about
//! it: `position.rs`. A calculation budget (`options.interrupt_calculation_duration`, µs)
//! bounds the synchronization search: [`OtgError::Interrupted`] when no duration has worked
//! yet, the shortest valid result otherwise (`sync.rs`), marked by
//! [`OtgTrajectory::was_interrupted`] (and `was_calculation_interrupted` of the update outputs)
//! when the budget cut the search short. Intermediate waypoints
//! (`intermediate_positions`) with per-section limits and minimum durations:
//! [`plan_waypoints`] (method, what is optimal about it and precision: `waypoints/`), with the
//! calculation budget too (an anytime search: the best valid motion found in time, stopping
//! at every waypoint at worst; [`OtgError::Interrupted`] when even that does not fit) and
//! [`Waypoints::validate`] as their `validate_input`, and [`WaypointOtg`] as their `update`
//! loop (plan on a changed input, follow, sections, refine a motion the budget cut short;
//! allocation-free when it does not calculate); Ruckig Pro's per-section minimum velocity and acceleration and per-section position
//! limits are refused by the JSON reader.
//!
//! # The update loops
//! [`Otg::update`], [`DynOtg::update`] and [`WaypointOtg::update`] follow Ruckig's
//! `Ruckig::update`: the time advances by `delta_time` after any calculation, the state
//! written is the trajectory's at that time, and the result is `Finished` only when that time
//! is past the duration (`time > duration`): the cycle landing exactly on the duration writes
//! the target state and is still `Working`, the next one is `Finished`. The outputs'
//! `calculation_duration_us` is Ruckig's `calculation_duration`: the wall-clock time of the
//! whole `update` up to the new state (the calculation included when there is one, so a
//! cycle that only follows reports the sampling's cost); an error leaves it, like the
//! state, unchanged (as Ruckig does).
//!
//! # Files (one per step)
//! `json.rs` the Ruckig-style JSON reader (public: [`json`]) · `input.rs` the input types
//! and their validation · `problem.rs` one DOF's problem · `profile.rs` the segment list of
//! one DOF · `velocity_change.rs` fastest velocity changes · `brake.rs` the brake
//! pre-profile · `zero.rs` zero limits · `step1/` time-optimal profile families (the
//! collector, verification, the rest-to-rest closed form, the closed-form and fallback
//! families) · `families.rs` + `families_gen.rs` the families' position polynomials ·
//! `step2.rs` profiles of a given duration (`step2/windows.rs` where its bracketed families
//! are valid) · `bracket.rs` the bracketed solve of the families
//! without a closed form (both steps) · `sync.rs` the common duration (`sync/bound.rs` its
//! closed-form duration bounds) · `phase.rs`
//! Ruckig's phase synchronization and the straight-line mode · `result.rs`, `trajectory.rs`,
//! `generator.rs`, `dyn_generator.rs` ([`DynOtg`]), `check.rs` · `position.rs` position
//! limits · `waypoints/` intermediate waypoints. Polynomial and scalar roots come from
//! [`crate::roots`].
//!
//! # Public API
//! Everything a user needs is re-exported here; the files are private.
//!
//! # Implementation notes
//!
//! `otg/` — online generation, one file per step, data in / data out: `json.rs` (the strict
//! Ruckig-style JSON reader every front end calls) → `input.rs` (validation naming field, DOF,
//! value; per-DOF synchronization and control interface) → `sync.rs` (per DOF `brake.rs`
//! pre-profile and `step1/` time-optimal profile; a common duration from the candidates,
//! each tried with `step2.rs`; `zero.rs`: DOFs with zero limits coast and fix the duration;
//! `phase.rs`: Ruckig's phase synchronization after the time-synchronized duration, and
//! trajkit's straight-line mode as a path problem) → `trajectory.rs` (fixed-size profiles,
//! `Trajectory`), with `generator.rs` (`Otg::update`) around it; `result.rs` holds the status
//! (`OtgResult`) and the `Copy` error (`OtgError`, DOF as `Option<usize>`, inside
//! `trajkit::Error::Otg`). Step 2's families, in order: the rest-to-rest closed form, cruise
//! (closed form, then bracketing), holds at an extremum, four ramps without a hold, a ramp
//! split by a hold; the velocity interface tries Ruckig's closed-form shapes in Ruckig's
//! order first (so synchronized velocity DOFs make Ruckig's motion). `tools/otg_sweep.py`
//! checks all of it against the Ruckig wheel with an independent integrator. Synchronization runs step 1 only where it needs
//! it: a closed-form upper bound of each DOF's minimum duration (`duration_bound`: stop, rest
//! to rest, start) picks the DOF that most likely sets the duration, which runs step 1 in
//! fastest-only mode (`step1_fastest_into`: no candidates); a DOF whose bound is at most the
//! trial duration goes straight to step 2 (that duration is feasible for it: the bound's
//! profile can wait at rest after its stop, so no blocked interval lies above it); the
//! others run step 1 when reached, and a DOF at which a trial duration fails gets its full
//! candidate list before the next candidate is chosen. Minimum durations of DOFs never solved
//! are computed on request (`DofTrajectory::independent_min_duration`). `Otg::calculate_into`
//! writes into the caller's `FixedTrajectory` (no copy of the result). Step 1 has two modes:
//! `step1_into` (the fastest profile and every valid candidate's duration, the edges of a moving
//! target's blocked intervals) and `step1_fastest_into` (slower candidates are not verified, a
//! valid cruise at the velocity limit ends the search when `cruise_is_optimal` proves nothing
//! is faster, directions that cannot cover the displacement in time are skipped);
//! `step1/modes_tests.rs` compares them on the suite's categories. Rest to rest (third order,
//! position interface) bypasses the enumeration in both steps: `step1::rest_to_rest` and
//! `step2::rest_to_rest` decide cruise and plateaus in closed form and write the segments
//! through `RestShape` (`Profile::push_run`), still checked by `verify`. Every profile family
//! leaves one free parameter whose position equation is a polynomial: `families_gen.rs` (generated by
//! `tools/otg_coefficients.py`) gives its coefficients, `families.rs` solves it (`two_changes`:
//! two fastest velocity changes through a zero-acceleration extremum, with a cruise when the
//! duration is prescribed), and `crate::roots` holds `poly_roots` (Budan–Fourier root isolation
//! with a Taylor-bound exclusion and up to two bisection levels, the derivative recursion for
//! what that leaves, safeguarded Newton) and, as the fallback for degenerate cases, the
//! bracketing solver. Step 1 builds candidates in place (`Collector`: the DOF's output profile
//! and one spare buffer, created on first use, the fastest kept by swapping; the per-DOF spare
//! `sync::Spare` is also where step 1's profile is kept before step 2 overwrites the output,
//! only when it starts with a brake — otherwise the rare return to the minimum duration
//! recalculates it) and skips families that a necessary
//! condition rules out over their whole parameter window (plateau duration negative at both
//! ends, velocity continuity impossible). Every candidate `profile.rs` is accepted only after
//! `verify` integrates it.

mod bracket;
mod brake;
mod check;
mod dyn_generator;
mod families;
mod families_gen;
mod generator;
mod input;
#[cfg(feature = "serde")]
pub mod json;
mod phase;
mod position;
mod problem;
mod profile;
mod result;
mod step1;
mod step2;
mod sync;
mod trajectory;
mod velocity_change;
mod waypoints;
mod zero;

pub use check::{check, SolutionCheck};
pub use dyn_generator::{DynOtg, DynOutputParameter};
pub use generator::{calculate_dyn, Otg, OutputParameter};
pub use input::{
    ControlInterface, DurationDiscretization, DynInputParameter, InputParameter, OtgOptions,
    Synchronization,
};
pub use profile::{Profile, State1, MAX_SEGMENTS};
pub use result::{FieldName, OtgError, OtgResult};
pub use step1::{TOL_LIMIT, TOL_POSITION, TOL_VELOCITY};
pub use trajectory::{DofTrajectory, DynTrajectory, FixedTrajectory, OtgTrajectory};
pub use waypoints::{
    check_waypoints, plan_waypoints, WaypointCheck, WaypointOtg, WaypointOutput,
    WaypointTrajectory, Waypoints,
};

/// One DOF's problem (limits, start, target), used by `plan`'s exact straight lines.
pub(crate) use problem::Dof1;

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
