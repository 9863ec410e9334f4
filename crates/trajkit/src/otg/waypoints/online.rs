//! The online loop through waypoints: [`WaypointOtg`], Ruckig Pro's `update` with
//! `intermediate_positions`, called once per control cycle.
//!
//! ```
//! use trajkit::otg::{DynInputParameter, OtgResult, WaypointOtg, WaypointOutput, Waypoints};
//! let mut input = DynInputParameter::new(2);
//! input.target_position = vec![2.0, 2.0];
//! input.max_velocity = vec![1.0, 1.0];
//! input.max_acceleration = vec![2.0, 2.0];
//! input.max_jerk = vec![10.0, 10.0];
//! let mut waypoints = Waypoints::new(vec![vec![1.0, 0.5]]);
//! let mut otg = WaypointOtg::new(0.01);
//! let mut out = WaypointOutput::new(2);
//! let (mut cycles, mut passed) = (0, 0);
//! while otg.update(&input, &waypoints, &mut out)? == OtgResult::Working {
//!     passed += usize::from(out.did_section_change);
//!     // The state goes back into the input, the passed waypoint leaves the list.
//!     out.pass_to_input(&mut input, &mut waypoints);
//!     cycles += 1;
//! }
//! assert_eq!(passed, 1);
//! assert!(waypoints.intermediate_positions.is_empty());
//! assert!((out.output.new_position[0] - 2.0).abs() < 1e-8);
//! assert!(cycles > 100 && cycles < 400);
//! # Ok::<(), trajkit::otg::OtgError>(())
//! ```
//!
//! # Method
//! Each [`WaypointOtg::update`]:
//! 1. **Plans on a changed input.** When the input or the waypoints differ from the
//!    generator's copy of the last ones, [`super::plan_waypoints`] plans from the input's
//!    current state through every waypoint to the target (`new_calculation`; the time and the
//!    section restart at 0). A failed calculation returns its error and keeps the motion being
//!    followed, as it was.
//! 2. **Follows.** The time advances by `delta_time`; the state there (position, velocity,
//!    acceleration, jerk) is the trajectory's; `new_section` is Ruckig's section index at that
//!    time (the number of sections that have ended, [`WaypointTrajectory::section_index_at`])
//!    and `did_section_change` says that it grew in this cycle.
//! 3. **Passes the state back** into its own copy of the input (and, when a section ended,
//!    removes the first waypoint from its copy of the waypoints,
//!    [`Waypoints::pass_first_waypoint`]), exactly what [`WaypointOutput::pass_to_input`]
//!    does to the caller's: an input fed back does not cause a new calculation.
//! 4. **Refines an interrupted motion.** With a calculation budget
//!    (`options.interrupt_calculation_duration`), a motion whose planning the budget cut short
//!    ([`WaypointTrajectory::was_interrupted`]) is planned again in each following cycle, from
//!    the current state through the waypoints still ahead, with the same budget. The new
//!    motion replaces the followed one (`new_calculation`, time and section restart at 0) only
//!    when it arrives at least one control period sooner than the rest of the followed motion:
//!    smaller gains would not arrive a cycle sooner, only restart the motion every cycle. A
//!    failed refinement keeps the followed motion. Refinement ends when a planning completes
//!    within the budget.
//!
//! `Finished` is returned once the time is past the duration. As in Ruckig Pro, one cycle
//! that ends two sections (a section shorter than `delta_time`) reports one change and
//! [`WaypointOutput::pass_to_input`] removes one waypoint.
//!
//! # Precision contract
//! The states written are the followed [`WaypointTrajectory`]'s at the generator's time
//! ([`WaypointTrajectory::at_time_with_jerk`], bit for bit), so the motion's contract holds
//! (`waypoints/`: every waypoint within the generator's target tolerance, limits to 1e-12
//! relative). The time is the sum of the control periods since the last calculation.
//!
//! # Cost and allocation
//! A cycle that does not calculate compares the input with the copy (O(DOF × waypoints)),
//! evaluates one section (binary search over the section start times) and copies the state:
//! it allocates nothing once the output holds the input's number of DOFs
//! (`tests/otg_waypoints_no_alloc.rs`). A cycle that calculates costs one
//! [`super::plan_waypoints`] (and allocates, as that does); with an interrupted motion every
//! cycle calculates until a planning completes in time. `calculation_duration_us` is the
//! wall-clock time of the whole `update` up to the new state (Ruckig's, as in
//! [`crate::otg::DynOtg::update`]), calculating or not; an error leaves it unchanged.

use super::{plan_waypoints, WaypointTrajectory, Waypoints};
use crate::otg::dyn_generator::DynOutputParameter;
use crate::otg::input::DynInputParameter;
use crate::otg::result::{OtgError, OtgResult};
use std::time::Instant;

impl Waypoints {
    /// Ruckig Pro's `pass_to_input` for the waypoints: removes the first waypoint (the motion
    /// has passed it) and, from each per-section list that still has one entry per section of
    /// the motion before, its first entry (the section just completed), so the lists keep one
    /// entry per section. Nothing when there is no waypoint left.
    pub fn pass_first_waypoint(&mut self) {
        if self.intermediate_positions.is_empty() {
            return;
        }
        self.intermediate_positions.remove(0);
        let sections = self.sections();
        for list in [
            &mut self.per_section_max_velocity,
            &mut self.per_section_max_acceleration,
            &mut self.per_section_max_jerk,
        ]
        .into_iter()
        .flatten()
        {
            if list.len() > sections {
                list.remove(0);
            }
        }
        if let Some(d) = &mut self.per_section_minimum_duration {
            if d.len() > sections {
                d.remove(0);
            }
        }
    }
}

impl WaypointTrajectory {
    /// Ruckig's section index at `t`: the number of sections that have ended (0 in the first
    /// section, the number of sections from the duration on).
    pub fn section_index_at(&self, t: f64) -> usize {
        if t >= self.duration {
            return self.sections.len();
        }
        self.starts[1..].partition_point(|&s| s <= t)
    }
}

/// The output of one [`WaypointOtg::update`]: the state as [`DynOutputParameter`] and the
/// section (Ruckig Pro's `new_section`, `did_section_change`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WaypointOutput {
    /// The state at the new time, the time since the last calculation, whether this update
    /// calculated (or refined), whether the budget cut that calculation short, the wall-clock
    /// time of the update and the duration of the motion followed.
    pub output: DynOutputParameter,
    /// Section index at the new time: the number of sections of the followed motion that
    /// have ended (0 until its first waypoint).
    pub new_section: usize,
    /// Whether this update ended a section (passed a waypoint, or reached the target):
    /// [`WaypointOutput::pass_to_input`] then removes the first waypoint.
    pub did_section_change: bool,
}

impl WaypointOutput {
    /// An output for `dof` degrees of freedom, all zero.
    pub fn new(dof: usize) -> Self {
        WaypointOutput {
            output: DynOutputParameter::new(dof),
            ..Default::default()
        }
    }

    /// Ruckig Pro's `pass_to_input`: copies the new state into the input's current state and,
    /// when this update ended a section, removes the passed waypoint
    /// ([`Waypoints::pass_first_waypoint`]). No allocation.
    pub fn pass_to_input(&self, input: &mut DynInputParameter, waypoints: &mut Waypoints) {
        self.output.pass_to_input(input);
        if self.did_section_change {
            waypoints.pass_first_waypoint();
        }
    }
}

/// The motion being followed, with the generator's copy of the input it follows (advanced
/// by each update as the caller's is by [`WaypointOutput::pass_to_input`]).
#[derive(Debug, Clone)]
struct Run {
    input: DynInputParameter,
    waypoints: Waypoints,
    traj: WaypointTrajectory,
}

impl Run {
    fn is_for(&self, input: &DynInputParameter, waypoints: &Waypoints) -> bool {
        self.input == *input && self.waypoints == *waypoints
    }
}

/// The online generator through intermediate waypoints (Ruckig Pro's `update` with
/// `intermediate_positions`; method, precision and cost in the module documentation of
/// `otg::waypoints::online`).
///
/// Without waypoints (an empty list and no per-section fields) it plans one section through
/// [`super::plan_waypoints`], with its restrictions; [`crate::otg::DynOtg`] is the generator for
/// such inputs.
#[derive(Debug, Clone)]
pub struct WaypointOtg {
    /// Control period in seconds (finite, > 0): `update` advances by it; also the period of
    /// discrete durations.
    pub delta_time: f64,
    run: Option<Run>,
    /// Time since the last calculation (or switch).
    time: f64,
    /// Section index after the last update.
    section: usize,
    /// Whether the followed motion is to be refined (its planning was interrupted and no
    /// complete planning has been made since).
    refine: bool,
}

impl WaypointOtg {
    /// A generator with control period `delta_time` (seconds).
    pub fn new(delta_time: f64) -> Self {
        WaypointOtg {
            delta_time,
            run: None,
            time: 0.0,
            section: 0,
            refine: false,
        }
    }

    /// One control cycle (see the module documentation): plan if `input` or `waypoints`
    /// changed, refine an interrupted motion, advance by `delta_time`, write the new state
    /// and section into `out` (resized to the motion's number of DOFs). Returns `Working`, or
    /// `Finished` once the new time is past the duration.
    ///
    /// Errors: [`OtgError::InvalidInput`] for a `delta_time` that is not finite and > 0
    /// (field `delta_time`), and the errors of [`super::plan_waypoints`] (the input's fields,
    /// [`OtgError::Waypoints`], [`OtgError::Interrupted`] when not even stopping at every
    /// waypoint fits the budget; then `out.output.was_calculation_interrupted` is true). On
    /// error the motion being followed is kept, and so is the state in `out` (with
    /// `new_calculation` false).
    pub fn update(
        &mut self,
        input: &DynInputParameter,
        waypoints: &Waypoints,
        out: &mut WaypointOutput,
    ) -> Result<OtgResult, OtgError> {
        let start = Instant::now();
        let dt = self.delta_time;
        let o = &mut out.output;
        o.new_calculation = false;
        o.was_calculation_interrupted = false;
        if !(dt.is_finite() && dt > 0.0) {
            return Err(OtgError::InvalidInput {
                dof: None,
                field: "delta_time",
                value: dt,
                reason: "is not a finite number > 0 (the control period update advances by)",
            });
        }
        let run = match self.run.as_mut().filter(|r| r.is_for(input, waypoints)) {
            Some(run) => {
                if self.refine {
                    if let Some(better) = refined(run, self.time, dt, &mut self.refine) {
                        run.traj = better;
                        (self.time, self.section) = (0.0, 0);
                        o.new_calculation = true;
                        o.was_calculation_interrupted = self.refine;
                    }
                }
                run
            }
            None => {
                let traj = plan_waypoints(input, waypoints, dt).inspect_err(|e| {
                    o.was_calculation_interrupted = matches!(e, OtgError::Interrupted { .. });
                })?;
                (self.time, self.section) = (0.0, 0);
                self.refine = traj.was_interrupted();
                o.new_calculation = true;
                o.was_calculation_interrupted = self.refine;
                self.run.insert(Run {
                    input: input.clone(),
                    waypoints: waypoints.clone(),
                    traj,
                })
            }
        };
        self.time += dt;
        let (t, traj) = (self.time, &run.traj);
        o.fit(traj.dof());
        traj.at_time_with_jerk(
            t,
            &mut o.new_position,
            &mut o.new_velocity,
            &mut o.new_acceleration,
            &mut o.new_jerk,
        );
        let section = traj.section_index_at(t);
        out.did_section_change = section > self.section;
        out.new_section = section;
        self.section = section;
        o.time = t;
        o.duration = traj.duration();
        o.calculation_duration_us = start.elapsed().as_secs_f64() * 1e6;
        out.pass_to_input(&mut run.input, &mut run.waypoints);
        Ok(if t > out.output.duration {
            OtgResult::Finished
        } else {
            OtgResult::Working
        })
    }

    /// Whether `input` and `waypoints` equal the generator's copy of the last ones (as the
    /// updates advanced it): then `update` follows the motion it has instead of planning.
    /// False before the first calculation and after [`WaypointOtg::reset`].
    pub fn follows(&self, input: &DynInputParameter, waypoints: &Waypoints) -> bool {
        self.run
            .as_ref()
            .is_some_and(|r| r.is_for(input, waypoints))
    }

    /// The motion being followed (`None` before the first calculation and after
    /// [`WaypointOtg::reset`]).
    pub fn trajectory(&self) -> Option<&WaypointTrajectory> {
        self.run.as_ref().map(|r| &r.traj)
    }

    /// Whether the followed motion is being refined: its planning was cut short by the budget
    /// and no planning has completed in time since, so the next `update` with the input fed
    /// back plans again (see the module documentation).
    pub fn is_refining(&self) -> bool {
        self.refine && self.run.is_some()
    }

    /// Time since the last calculation (or switch to a refined motion), in seconds.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Forgets the motion and the last input: the next `update` plans anew.
    pub fn reset(&mut self) {
        self.run = None;
        (self.time, self.section, self.refine) = (0.0, 0, false);
    }
}

/// Plans `run` again from its current state (its copy of the input, at `time` on its
/// motion); the new motion when it arrives at least one control period `dt` sooner than the
/// rest of the followed one. Clears `refine` when the new planning completed in time and
/// gives nothing better (a failed planning, out of budget say, keeps refining).
fn refined(run: &Run, time: f64, dt: f64, refine: &mut bool) -> Option<WaypointTrajectory> {
    let left = run.traj.duration() - time;
    let new = plan_waypoints(&run.input, &run.waypoints, dt).ok()?;
    if new.duration() <= left - dt {
        *refine = new.was_interrupted();
        return Some(new);
    }
    if !new.was_interrupted() {
        *refine = false;
    }
    None
}
