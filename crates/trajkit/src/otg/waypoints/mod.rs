//! Motions through intermediate waypoints (Ruckig Pro's `intermediate_positions`, with
//! per-section limits and minimum durations), computed locally.
//!
//! [`plan_waypoints`] takes the usual [`DynInputParameter`] (current state, target state,
//! limits, options) and a [`Waypoints`] (the positions to pass through on the way and the
//! per-section settings) and returns a [`WaypointTrajectory`]: one time-synchronized,
//! jerk-limited trajectory per section, chained. Evaluating it allocates nothing.
//!
//! ```
//! use trajkit::otg::{plan_waypoints, DynInputParameter, Waypoints};
//! let mut input = DynInputParameter::new(2);
//! input.target_position = vec![2.0, 2.0];
//! input.max_velocity = vec![1.0, 1.0];
//! input.max_acceleration = vec![2.0, 2.0];
//! input.max_jerk = vec![10.0, 10.0];
//! let wp = Waypoints::new(vec![vec![1.0, 0.5]]);
//! let traj = plan_waypoints(&input, &wp, 0.001)?;
//! // Never slower than stopping at the waypoint, here clearly faster.
//! assert!(traj.duration() < 0.9 * traj.stop_at_every_waypoint_duration());
//! // It passes through the waypoint at the end of the first section.
//! let (mut p, mut v, mut a) = ([0.0; 2], [0.0; 2], [0.0; 2]);
//! traj.at_time(traj.section_start_times()[1], &mut p, &mut v, &mut a);
//! assert!((p[0] - 1.0).abs() < 1e-8 && (p[1] - 0.5).abs() < 1e-8);
//! # Ok::<(), trajkit::otg::OtgError>(())
//! ```
//!
//! Online, once per control cycle: [`WaypointOtg::update`] (`online.rs`: plans on a changed
//! input, follows the motion with its section index, and refines a motion the calculation
//! budget cut short).
//!
//! # Method
//! The waypoints split the motion into sections: current state → waypoint 1 → … → target
//! state. The state at each waypoint is chosen (its position is given; its acceleration is
//! 0; its velocity is the unknown), and every section is then an ordinary state-to-state
//! problem solved by the generator's own time-synchronized solver, with that section's
//! limits and minimum duration. Each section therefore ends exactly at its waypoint (to the
//! generator's target tolerance), holds its limits, and the sections join with continuous
//! position, velocity and acceleration (the jerk is bounded: it may jump at a waypoint, as
//! it does between the segments of any profile).
//!
//! The waypoint velocities are chosen in three steps (`plan.rs`):
//! 1. **Stop at every waypoint**: all waypoint velocities zero. Its section durations are the
//!    reference (and the fallback: it is returned whenever it is not beaten).
//! 2. **Direction**: per joint, 0 where the joint reverses or stops at the waypoint
//!    (incoming and outgoing displacements not of the same sign), else the finite-difference
//!    tangent over non-uniform times (the two sections' average velocities from step 1,
//!    weighted by the other section's duration), limited to three times the smaller average
//!    velocity (Fritsch–Carlson's monotonicity bound: no joint is pushed past its
//!    neighbours).
//! 3. **Speed**: each waypoint's velocity is its direction times a scale `s ≥ 0`, at most the
//!    largest scale that keeps every joint within both adjacent sections' velocity limits.
//!    Coordinate descent over the waypoints: for each one a golden-section search over its
//!    scale minimizes the sum of the durations of its two adjacent sections (each evaluation
//!    = two section solves in the synchronization's bounded mode, see Cost; a section it
//!    cannot plan counts as infinitely long, so only feasible velocities are kept). Two
//!    sweeps: the whole range first, then a window around the first sweep's choice.
//!
//! The result is the shorter of the descent's motion and stopping at every waypoint.
//!
//! # What is optimal about it, and what is not
//! - Each section is time-optimal for its boundary states (the generator's synchronized
//!   minimum), so the motion is optimal among motions that pass the waypoints with the chosen
//!   velocities and zero acceleration, all joints together.
//! - The total is never longer than stopping at every waypoint (that motion is a candidate).
//! - The waypoint velocities are a local optimum of a one-parameter-per-waypoint family
//!   (direction fixed by step 2), found by a bounded number of evaluations: not the global
//!   optimum over all waypoint states. Non-zero accelerations at the waypoints and directions
//!   other than the tangent are not explored, so a path-parameterization optimum (TOPP with
//!   jerk limits along the same corners) can be shorter.
//!
//! # Cost
//! About `22 × waypoints + 3 × sections` section solves, most of them microseconds. The
//! search rates candidates with the synchronization's bounded mode: a section whose
//! synchronized duration lies above every DOF's own minimum (a DOF with a non-zero waypoint
//! velocity that cannot be slowed a little: a blocked interval) would send the full search
//! into a bisection of about 1.5 ms; the bounded mode keeps the first candidate duration that
//! works (or rates the section ∞ when none does), so such velocities, poor anyway, are rated
//! long rather than exactly. Only the reference and the chosen sections get full solves.
//! A rating wants the duration alone, so it builds only the profiles that decide it: a DOF
//! whose closed-form duration bound is at most the trial duration gets none, and a DOF whose
//! step 1 has not run is tried with step 2's closed forms first (when they plan, its step 1
//! is skipped). The golden search does not rate a candidate's second section when the first
//! alone is longer than the other inner point's total (same steps, same choice).
//!
//! # Precision contract
//! Every section is a generator result: it ends at its waypoint (and the last one at the
//! target state) within the generator's tolerance (1e-8 for motions of at least 1e-3,
//! relative to the motion below), with velocity and acceleration within 1e-10 of the chosen
//! waypoint state (so the joins are continuous to that tolerance), and holds its section's
//! velocity and acceleration limits to 1e-12 relative and its jerk limit exactly (its
//! segments' jerks are the limits or between them). Waypoint velocities lie within both
//! adjacent sections' velocity limits and accelerations are 0, so every section starts
//! inside its limits (no brake pre-profile except in the first section).
//!
//! # What is supported
//! Time and phase synchronization (every joint reaches each waypoint at the same time), the
//! position interface, continuous or discrete durations, global position limits (every
//! section keeps them; waypoints outside them are refused), direction-dependent minimum
//! velocity and acceleration (global). Refused with a typed error: disabled DOFs, the velocity
//! interface, per-DOF synchronization or control interface, synchronization `none`,
//! `time_if_necessary` or `straight_line` and a global `minimum_duration` (use
//! `per_section_minimum_duration`).
//!
//! # Calculation budget
//! `options.interrupt_calculation_duration` (µs, Ruckig Pro's field) bounds the wall-clock
//! time of the whole planning, validation included. The method is an anytime algorithm:
//! stopping at every waypoint (step 1) is a valid motion as soon as it is solved and is
//! kept, steps 2–3 only improve on it. Every section solve is timed. With a budget the search
//! stops when what is left would not pay for its next step (two ratings, timed by the longest
//! solve so far), the final build (twice the latest measured solve of every section, plus
//! what keeping a section's trajectory took in step 1) and a tail of 5 % of the budget; each
//! rating, and each section of the final build, gets as its own deadline what is left less the
//! tail and what must follow it (the build; the build's later sections), so a section's
//! bisection gives way to the sections after it. The result is the best valid motion found,
//! marked [`WaypointTrajectory::was_interrupted`] when the budget cut anything short. A final
//! build that runs out of time gives way to the kept stop-at-every-waypoint motion. When even
//! step 1 does not fit, the error is [`OtgError::Interrupted`].
//!
//! The bound: every solve checks the deadline before each attempt of the synchronization
//! (and of its bisection), so the planner's own work past the deadline is one uninterruptible
//! piece (a section's closed-form step 1 for every DOF and one step-2 attempt, or the end of
//! a bisection) and assembling the kept motion; the 5 % tail is there to absorb it. It is not
//! a hard real-time guarantee: the budget is wall-clock time, so a thread preempted past the
//! deadline (or a virtual CPU the host takes away) overruns by the preemption, and a piece
//! longer than the tail (a small budget on a slow machine) shows as an overrun. Measured
//! 2026-11-26 12:07 UTC (release, load 3.3–3.5, `cargo test --release -p trajkit --test
//! otg_budget -- --ignored --nocapture budget_overrun`: 30 seeded 7 DOF × 30 waypoint bent
//! paths, 300 calls per budget, each call's time the least of 3 repeats not preempted), three
//! runs: the most any call used of a 300 / 1000 / 3000 µs budget was 0.57–0.84× / 0.98–1.01×
//! / 0.96–0.97× (before these reserves, the same runs: 0.92–0.98× / 1.03–1.12× / 1.02×, and
//! the 3000 µs builds gave way to stopping at every waypoint in at least half of the calls:
//! median duration
//! 1.00× against 0.62–0.66× now). `tests/otg_budget.rs` checks every call on six 30-waypoint
//! paths under three budgets (the least of three unpreempted repeats ≤ 1.1× the budget). An
//! ample budget changes nothing (same motion, bit for bit).

mod budget;
mod online;
mod plan;
mod trajectory;
mod validate;

pub use online::{WaypointOtg, WaypointOutput};
pub use trajectory::{check_waypoints, WaypointCheck, WaypointTrajectory};

use super::input::DynInputParameter;
use super::result::OtgError;

/// Intermediate waypoints and per-section settings (Ruckig Pro's field names).
///
/// With `m` waypoints there are `m + 1` sections: current state → waypoint 0, waypoint 0 →
/// waypoint 1, …, waypoint `m − 1` → target state. Each per-section field, when given, has
/// one entry per section (and each entry one value per DOF); a per-section limit replaces the
/// input's limit in its section (the input's `min_velocity`/`min_acceleration`, when given,
/// still apply; otherwise the minima are the negated section maxima).
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct Waypoints {
    /// The positions to pass through, in order (each one value per DOF).
    pub intermediate_positions: Vec<Vec<f64>>,
    /// Velocity limit per section and DOF (> 0 or ∞).
    pub per_section_max_velocity: Option<Vec<Vec<f64>>>,
    /// Acceleration limit per section and DOF (> 0 or ∞).
    pub per_section_max_acceleration: Option<Vec<Vec<f64>>>,
    /// Jerk limit per section and DOF (> 0 or ∞).
    pub per_section_max_jerk: Option<Vec<Vec<f64>>>,
    /// Minimum duration per section in seconds (≥ 0).
    pub per_section_minimum_duration: Option<Vec<f64>>,
}

impl Waypoints {
    /// The given waypoints, no per-section settings.
    pub fn new(intermediate_positions: Vec<Vec<f64>>) -> Self {
        Waypoints {
            intermediate_positions,
            ..Default::default()
        }
    }

    /// Number of sections (waypoints + 1).
    pub fn sections(&self) -> usize {
        self.intermediate_positions.len() + 1
    }

    /// Ruckig's `validate_input` for a motion through these waypoints: every check
    /// [`plan_waypoints`] makes before planning (the input's own fields, the options that
    /// waypoints do not support, and the waypoints and per-section fields: sizes, finite
    /// values, signs, duplicates, position limits), with the same errors; and optionally that
    /// the current (`current_within_limits`) and target (`target_within_limits`) velocity and
    /// acceleration lie within the limits of the first and last section (the per-section
    /// limits where given, else the input's), as [`DynInputParameter::validate`] checks them.
    ///
    /// ```
    /// use trajkit::otg::{DynInputParameter, OtgError, Waypoints};
    /// let mut input = DynInputParameter::new(2);
    /// input.target_position = vec![2.0, 2.0];
    /// input.max_velocity = vec![1.0, 1.0];
    /// input.max_acceleration = vec![2.0, 2.0];
    /// input.max_jerk = vec![10.0, 10.0];
    /// let mut wp = Waypoints::new(vec![vec![1.0, 0.5]]);
    /// assert!(wp.validate(&input, 0.001, true, true).is_ok());
    /// wp.intermediate_positions[0][1] = f64::NAN;
    /// assert!(matches!(
    ///     wp.validate(&input, 0.001, false, true),
    ///     Err(OtgError::Waypoints { index: 0, dof: Some(1), field: "intermediate_positions", .. })
    /// ));
    /// ```
    pub fn validate(
        &self,
        input: &DynInputParameter,
        delta_time: f64,
        current_within_limits: bool,
        target_within_limits: bool,
    ) -> Result<(), OtgError> {
        validate::validate(input, self, delta_time)?;
        let last = self.intermediate_positions.len();
        plan::section_template(input, self, 0).validate(
            delta_time,
            current_within_limits,
            false,
        )?;
        plan::section_template(input, self, last).validate(delta_time, false, target_within_limits)
    }
}

/// Plans the motion from `input`'s current state through every waypoint of `waypoints` to
/// `input`'s target state (see the module documentation of `otg::waypoints` for the method
/// and what is optimal about it). `delta_time` is the control period (for discrete
/// durations). Errors: [`OtgError::InvalidInput`] for the input's own fields,
/// [`OtgError::Waypoints`] for waypoints and per-section fields (wrong sizes, non-finite
/// values, duplicates, waypoints outside the position limits) and for a section that cannot
/// be planned (e.g. its minimum duration cannot be met).
pub fn plan_waypoints(
    input: &DynInputParameter,
    waypoints: &Waypoints,
    delta_time: f64,
) -> Result<WaypointTrajectory, OtgError> {
    let clock = input
        .options
        .interrupt_calculation_duration
        .map(budget::Clock::start);
    validate::validate(input, waypoints, delta_time)?;
    let mut planner = plan::Planner::new(input, waypoints, delta_time, clock);
    planner.plan()
}

/// The per-section inputs of a problem (limits, options and boundary states of every
/// section for the given waypoint velocities, accelerations 0): what each section of a
/// [`WaypointTrajectory`] was planned for. `velocities` holds one value per DOF for each
/// waypoint, flattened.
pub(crate) fn section_inputs(
    input: &DynInputParameter,
    waypoints: &Waypoints,
    velocities: &[f64],
) -> Vec<DynInputParameter> {
    let n = input.dof();
    let m = waypoints.intermediate_positions.len();
    (0..=m)
        .map(|s| {
            let mut si = plan::section_template(input, waypoints, s);
            if s > 0 {
                si.current_position = waypoints.intermediate_positions[s - 1].clone();
                si.current_velocity = velocities[(s - 1) * n..s * n].to_vec();
                si.current_acceleration = vec![0.0; n];
            }
            if s < m {
                si.target_position = waypoints.intermediate_positions[s].clone();
                si.target_velocity = velocities[s * n..(s + 1) * n].to_vec();
                si.target_acceleration = vec![0.0; n];
            }
            si
        })
        .collect()
}
