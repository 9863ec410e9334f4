//! The calculated trajectory: one [`Profile`] per degree of freedom and a common duration.
//!
//! [`OtgTrajectory`] is generic over its storage: `[DofTrajectory; DOF]` for a compile-time
//! number of degrees of freedom (no allocation; [`FixedTrajectory`]) or `Vec<DofTrajectory>`
//! ([`DynTrajectory`]). Queries write into buffers the caller owns.
//!
//! Time policy: [`OtgTrajectory::at_time`] follows the online-generation convention — after the
//! end every degree of freedom continues from its final state with constant acceleration (zero
//! for a target at rest), before 0 it reports the start state. The [`crate::Trajectory`]
//! implementation follows trajkit's shared policy instead: time is clamped to `[0, duration]`.

use super::problem::Dof1;
use super::profile::Profile;
use super::result::OtgResult;
use super::step1::step1;
use crate::{Order, Trajectory};

/// One degree of freedom of a trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DofTrajectory {
    /// The motion.
    pub profile: Profile,
    /// The duration this degree of freedom would need on its own, when the calculation
    /// needed it; NaN when synchronization did without it (then `problem` holds what to
    /// compute it from).
    pub(crate) min_duration: f64,
    /// The problem of this degree of freedom, kept when `min_duration` is not known.
    pub(crate) problem: Option<Dof1>,
}

impl DofTrajectory {
    /// The duration this degree of freedom would need on its own (time-optimal, brake
    /// included); 0 for a disabled one.
    ///
    /// A synchronized calculation computes the time-optimal profile only of the degrees of
    /// freedom that determine the common duration; the others are planned for that duration
    /// directly. For those the minimum duration is computed here, on request (the same step-1
    /// solve the calculation would have run; no allocation). NaN only if that solve finds no
    /// profile.
    pub fn independent_min_duration(&self) -> f64 {
        if !self.min_duration.is_nan() {
            return self.min_duration;
        }
        self.problem
            .as_ref()
            .and_then(step1)
            .map_or(f64::NAN, |s| s.t_min())
    }
}

/// A multi-DOF trajectory from the online generator.
#[derive(Debug, PartialEq)]
pub struct OtgTrajectory<S> {
    pub(crate) dofs: S,
    pub(crate) duration: f64,
    /// Whether the calculation budget cut the search for the common duration short.
    pub(crate) interrupted: bool,
}

impl<S: Clone> Clone for OtgTrajectory<S> {
    fn clone(&self) -> Self {
        OtgTrajectory {
            dofs: self.dofs.clone(),
            duration: self.duration,
            interrupted: self.interrupted,
        }
    }

    /// Field by field, so that a `DynTrajectory` reuses its storage (no allocation when it
    /// already holds as many degrees of freedom).
    fn clone_from(&mut self, source: &Self) {
        self.dofs.clone_from(&source.dofs);
        self.duration = source.duration;
        self.interrupted = source.interrupted;
    }
}

impl DynTrajectory {
    /// A trajectory of `dof` degrees of freedom at rest at 0, of duration 0: storage for
    /// [`super::DynOtg::calculate_into`] to write into.
    pub fn new(dof: usize) -> Self {
        OtgTrajectory {
            dofs: vec![DofTrajectory::default(); dof],
            duration: 0.0,
            interrupted: false,
        }
    }
}

/// A trajectory with a compile-time number of degrees of freedom.
pub type FixedTrajectory<const DOF: usize> = OtgTrajectory<[DofTrajectory; DOF]>;
/// A trajectory with a run-time number of degrees of freedom.
pub type DynTrajectory = OtgTrajectory<Vec<DofTrajectory>>;

impl<const DOF: usize> Default for FixedTrajectory<DOF> {
    fn default() -> Self {
        OtgTrajectory {
            dofs: [DofTrajectory::default(); DOF],
            duration: 0.0,
            interrupted: false,
        }
    }
}

impl<S: AsRef<[DofTrajectory]>> OtgTrajectory<S> {
    /// Duration in seconds.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Whether the calculation budget (`interrupt_calculation_duration`) cut the search for
    /// the common duration short: the trajectory is valid (limits, target) but may be longer
    /// than the shortest synchronized one (Ruckig's `was_calculation_interrupted`). False
    /// without a budget.
    pub fn was_interrupted(&self) -> bool {
        self.interrupted
    }

    /// Number of degrees of freedom.
    pub fn dof(&self) -> usize {
        self.dofs.as_ref().len()
    }

    /// The per-DOF data.
    pub fn dofs(&self) -> &[DofTrajectory] {
        self.dofs.as_ref()
    }

    /// Position, velocity and acceleration at `t` into the caller's buffers (each at least
    /// `dof()` long; extra entries are left alone). After the end: constant-acceleration
    /// extrapolation (see the module documentation).
    pub fn at_time(&self, t: f64, p: &mut [f64], v: &mut [f64], a: &mut [f64]) {
        self.states_at(t, p, v, a, None);
    }

    /// Like [`OtgTrajectory::at_time`], also writing the jerk.
    pub fn at_time_with_jerk(
        &self,
        t: f64,
        p: &mut [f64],
        v: &mut [f64],
        a: &mut [f64],
        j: &mut [f64],
    ) {
        self.states_at(t, p, v, a, Some(j));
    }

    /// [`OtgTrajectory::at_time`], with the jerk when `j` is given.
    #[inline]
    fn states_at(
        &self,
        t: f64,
        p: &mut [f64],
        v: &mut [f64],
        a: &mut [f64],
        mut j: Option<&mut [f64]>,
    ) {
        for (i, d) in self.dofs.as_ref().iter().enumerate() {
            let (pi, vi, ai, ji) = d.profile.state_at(t);
            p[i] = pi;
            v[i] = vi;
            a[i] = ai;
            if let Some(j) = j.as_deref_mut() {
                j[i] = ji;
            }
        }
    }

    /// One control cycle along the trajectory (the common step of both generators'
    /// `update`): advances `time` by `dt`, writes the state there, and says whether the
    /// motion has finished: the new time is past the end (Ruckig's `time > duration`; a cycle
    /// landing exactly on the duration writes the target state and is still `Working`).
    pub(crate) fn step(
        &self,
        time: &mut f64,
        dt: f64,
        p: &mut [f64],
        v: &mut [f64],
        a: &mut [f64],
        j: &mut [f64],
    ) -> OtgResult {
        *time += dt;
        self.at_time_with_jerk(*time, p, v, a, j);
        if *time > self.duration {
            OtgResult::Finished
        } else {
            OtgResult::Working
        }
    }

    /// The duration each degree of freedom would need on its own, into `out` (see
    /// [`DofTrajectory::independent_min_duration`]: computed here for the degrees of freedom
    /// whose time-optimal profile the calculation did not need).
    pub fn independent_min_durations(&self, out: &mut [f64]) {
        for (o, d) in out.iter_mut().zip(self.dofs.as_ref()) {
            *o = d.independent_min_duration();
        }
    }

    /// Position extrema of degree of freedom `i` over `[0, duration]`:
    /// `(min, t_min, max, t_max)`. `None` for an index out of range.
    pub fn position_extrema(&self, i: usize) -> Option<(f64, f64, f64, f64)> {
        let d = self.dofs.as_ref().get(i)?;
        let (lo, tlo, hi, thi) = d.profile.position_extrema();
        // A profile that ends early holds (or extrapolates) until the common end.
        let end = d.profile.duration();
        if end < self.duration {
            let (p, ..) = d.profile.state_at(self.duration);
            let (mut lo, mut tlo, mut hi, mut thi) = (lo, tlo, hi, thi);
            if p < lo {
                (lo, tlo) = (p, self.duration);
            }
            if p > hi {
                (hi, thi) = (p, self.duration);
            }
            return Some((lo, tlo, hi, thi));
        }
        Some((lo, tlo, hi, thi))
    }

    /// The first time at which degree of freedom `i` is at position `p`, if it gets there
    /// within its profile.
    pub fn first_time_at_position(&self, i: usize, p: f64) -> Option<f64> {
        self.dofs.as_ref().get(i)?.profile.first_time_at_position(p)
    }

    /// The first time at or after `after` at which degree of freedom `i` is at position `p`,
    /// if it gets there within its profile (Ruckig's `time_after`).
    pub fn first_time_at_position_after(&self, i: usize, p: f64, after: f64) -> Option<f64> {
        self.dofs
            .as_ref()
            .get(i)?
            .profile
            .first_time_at_position_after(p, after)
    }
}

impl<S: AsRef<[DofTrajectory]>> Trajectory for OtgTrajectory<S> {
    fn dof(&self) -> usize {
        self.dofs.as_ref().len()
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        let t = crate::traj::clamp_time(t, self.duration);
        for (i, d) in self.dofs.as_ref().iter().enumerate() {
            let s = d.profile.state_at(t);
            out[i] = match order {
                Order::Position => s.0,
                Order::Velocity => s.1,
                Order::Acceleration => s.2,
                Order::Jerk => s.3,
            };
        }
    }
}
