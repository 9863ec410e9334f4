//! The motion through waypoints: one generator trajectory per section, chained in time.
//!
//! Evaluation finds the section by binary search over the section start times and evaluates
//! that section's profiles: no allocation. Time policy as for the generator's trajectories:
//! [`WaypointTrajectory::at_time`] reports the start state before 0 and extrapolates the final
//! state after the end; the [`crate::Trajectory`] implementation clamps time to
//! `[0, duration]`.

use super::{section_inputs, Waypoints};
use crate::otg::check::{check, SolutionCheck};
use crate::otg::input::DynInputParameter;
use crate::otg::result::OtgError;
use crate::otg::trajectory::DynTrajectory;
use crate::{Order, Trajectory};

/// A motion through intermediate waypoints ([`super::plan_waypoints`]).
#[derive(Debug, Clone, PartialEq)]
pub struct WaypointTrajectory {
    pub(crate) sections: Vec<DynTrajectory>,
    pub(crate) starts: Vec<f64>,
    pub(crate) duration: f64,
    pub(crate) stop_duration: f64,
    pub(crate) velocities: Vec<f64>,
    pub(crate) interrupted: bool,
}

impl WaypointTrajectory {
    /// Duration in seconds (the sum of the sections' durations).
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Number of degrees of freedom.
    pub fn dof(&self) -> usize {
        self.sections[0].dof()
    }

    /// The sections (waypoints + 1), each a generator trajectory starting at time 0.
    pub fn sections(&self) -> &[DynTrajectory] {
        &self.sections
    }

    /// The time at which each section starts; section `k > 0` starts at waypoint `k − 1`.
    pub fn section_start_times(&self) -> &[f64] {
        &self.starts
    }

    /// The duration of stopping at every waypoint (computed as the reference; the motion is
    /// never longer).
    pub fn stop_at_every_waypoint_duration(&self) -> f64 {
        self.stop_duration
    }

    /// Whether the calculation budget (`interrupt_calculation_duration`) cut the planning
    /// short: the motion is valid (it passes every waypoint within the limits) and never
    /// longer than stopping at every waypoint, but may be longer than the motion planned
    /// without a budget.
    pub fn was_interrupted(&self) -> bool {
        self.interrupted
    }

    /// The velocity chosen at each waypoint, one value per DOF per waypoint, flattened
    /// (waypoint `k`'s are `[k·dof, (k+1)·dof)`); accelerations there are 0.
    pub fn waypoint_velocities(&self) -> &[f64] {
        &self.velocities
    }

    /// The section that contains `t` and the time within it.
    fn locate(&self, t: f64) -> (&DynTrajectory, f64) {
        let k = self
            .starts
            .partition_point(|&s| s <= t)
            .saturating_sub(1)
            .min(self.sections.len() - 1);
        (&self.sections[k], t - self.starts[k])
    }

    /// Position, velocity and acceleration at `t` into the caller's buffers (each at least
    /// `dof()` long). Before 0: the start state; after the end: the final state extrapolated
    /// with constant acceleration.
    pub fn at_time(&self, t: f64, p: &mut [f64], v: &mut [f64], a: &mut [f64]) {
        let (sec, local) = self.locate(t);
        sec.at_time(local, p, v, a);
    }

    /// Like [`WaypointTrajectory::at_time`], also writing the jerk.
    pub fn at_time_with_jerk(
        &self,
        t: f64,
        p: &mut [f64],
        v: &mut [f64],
        a: &mut [f64],
        j: &mut [f64],
    ) {
        let (sec, local) = self.locate(t);
        sec.at_time_with_jerk(local, p, v, a, j);
    }
}

impl Trajectory for WaypointTrajectory {
    fn dof(&self) -> usize {
        WaypointTrajectory::dof(self)
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        let (sec, local) = self.locate(crate::traj::clamp_time(t, self.duration));
        Trajectory::eval(sec, local, order, out);
    }
}

/// What [`check_waypoints`] found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaypointCheck {
    /// Every section checked against its own input ([`crate::otg::check`]), the largest of
    /// each field: `final_error` is the largest distance of a section's end from its planned
    /// end state (a waypoint with its chosen velocity and zero acceleration, or the target).
    pub solution: SolutionCheck,
    /// Largest distance of a section's end position from its waypoint.
    pub waypoint_error: f64,
}

/// Checks a motion through waypoints against the problem it was planned for: each section
/// against its limits and planned end state (exact profile reading, as
/// [`crate::otg::check`]). Errors: the problem's validation errors, and
/// [`OtgError::Waypoints`] when the trajectory has another number of sections or DOFs.
pub fn check_waypoints(
    input: &DynInputParameter,
    waypoints: &Waypoints,
    trajectory: &WaypointTrajectory,
) -> Result<WaypointCheck, OtgError> {
    super::validate::validate(input, waypoints, 1.0)?;
    let (n, m) = (input.dof(), waypoints.intermediate_positions.len());
    if trajectory.sections.len() != m + 1 || trajectory.velocities.len() != m * n {
        return Err(OtgError::Waypoints {
            index: 0,
            dof: None,
            field: "intermediate_positions",
            value: m as f64,
            reason: "does not match the trajectory's sections",
        });
    }
    let inputs = section_inputs(input, waypoints, trajectory.waypoint_velocities());
    let mut out = WaypointCheck {
        solution: SolutionCheck {
            final_error: [0.0; 3],
            worst_limit_ratio: 0.0,
            position_excess: 0.0,
        },
        waypoint_error: 0.0,
    };
    let last = inputs.len() - 1;
    for (s, (si, tr)) in inputs.iter().zip(trajectory.sections()).enumerate() {
        let c = check(si, tr);
        let o = &mut out.solution;
        for (e, x) in o.final_error.iter_mut().zip(c.final_error) {
            *e = e.max(x);
        }
        o.worst_limit_ratio = o.worst_limit_ratio.max(c.worst_limit_ratio);
        o.position_excess = o.position_excess.max(c.position_excess);
        if s < last {
            out.waypoint_error = out.waypoint_error.max(c.final_error[0]);
        }
    }
    Ok(out)
}
