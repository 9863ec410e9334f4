//! Zero limits: a degree of freedom that cannot change its acceleration coasts.
//!
//! Ruckig accepts zero limits and gives them one meaning, which trajkit follows: a
//! third-order degree of freedom whose jerk limit, maximum acceleration or minimum
//! acceleration is zero (position interface; for the velocity interface a zero jerk limit),
//! and a second-order one whose velocity limits are both zero, keeps its current acceleration
//! (velocity, for second order) for the whole motion. Its profile is one segment of constant
//! acceleration, which must end in the target state: the target acceleration must equal the
//! current one, and the duration follows from the position (velocity interface: velocity)
//! equation. Such a degree of freedom that moves (non-zero velocity or acceleration) reaches
//! its target at one duration only, so a synchronized motion takes exactly that duration or
//! fails ([`super::OtgError::ZeroLimits`]); one at rest on its target stays there for any
//! duration. Other zero limits (one velocity bound zero, a second-order zero acceleration
//! limit) go through the ordinary solver, which either finds a profile within them or
//! reports the zero limits.
//!
//! Precision: the single segment is verified like every profile (target and limits).

use super::problem::{ControlInterface, Dof1, ProfileOrder};
use super::profile::{Profile, State1};
use super::step1::verify;

/// Whether `d` coasts (see the module documentation).
#[inline]
pub(crate) fn coasts(d: &Dof1) -> bool {
    match (d.order(), d.interface) {
        (ProfileOrder::Third, ControlInterface::Position) => {
            d.jmax == 0.0 || d.amax == 0.0 || d.amin == 0.0
        }
        (ProfileOrder::Third, ControlInterface::Velocity) => d.jmax == 0.0,
        (ProfileOrder::Second, ControlInterface::Position) => d.vmax == 0.0 && d.vmin == 0.0,
        _ => false,
    }
}

/// Whether any limit of `d` is zero.
pub(crate) fn has_zero_limit(d: &Dof1) -> bool {
    d.vmax == 0.0 || d.vmin == 0.0 || d.amax == 0.0 || d.amin == 0.0 || d.jmax == 0.0
}

/// Whether a coasting `d` stands still on its target (then any duration is feasible).
pub(crate) fn at_rest(d: &Dof1) -> bool {
    let still = d.v0 == 0.0 && (d.order() == ProfileOrder::Second || d.a0 == 0.0);
    still && (d.interface == ControlInterface::Velocity || d.p0 == d.pf) && d.vf == 0.0
}

/// The coasting profile of `d` into `out`: its only duration (any duration `t` when it is at
/// rest on its target and `t` is given). False when it does not end in the target state
/// within the limits.
pub(crate) fn coast_into(d: &Dof1, t: Option<f64>, out: &mut Profile) -> bool {
    let second = d.order() == ProfileOrder::Second;
    let a = if second { 0.0 } else { d.a0 };
    out.reset(State1 {
        p: d.p0,
        v: d.v0,
        a,
    });
    if !second && (d.af - a).abs() > f64::EPSILON {
        return false;
    }
    if at_rest(d) {
        let dur = t.unwrap_or(0.0);
        out.push(dur, 0.0);
        out.set_final(0.0, a);
        return verify(d, out) && (out.duration() - dur).abs() <= 1e-12 * dur.max(1.0);
    }
    for dur in durations(d, a) {
        if !(dur >= 0.0 && dur.is_finite()) {
            continue;
        }
        if t.is_some_and(|t| (t - dur).abs() > 1e-12 * t.max(1.0)) {
            continue;
        }
        out.reset(State1 {
            p: d.p0,
            v: d.v0,
            a,
        });
        out.push_with(t.unwrap_or(dur), d.v0, a, 0.0);
        if second {
            out.set_final(d.vf, 0.0);
        }
        if verify(d, out) {
            return true;
        }
    }
    false
}

/// The candidate durations of a coast with acceleration `a` (NaN for none).
fn durations(d: &Dof1, a: f64) -> [f64; 2] {
    if d.interface == ControlInterface::Velocity {
        let dv = d.vf - d.v0;
        return if a != 0.0 {
            [dv / a, f64::NAN]
        } else if dv == 0.0 {
            [0.0, f64::NAN]
        } else {
            [f64::NAN; 2]
        };
    }
    let pd = d.pf - d.p0;
    if a != 0.0 {
        // p0 + v0 t + a t²/2 = pf; the smaller non-negative root first.
        let q = (2.0 * a * pd + d.v0 * d.v0).sqrt();
        let (r1, r2) = ((-d.v0 + q) / a, -(d.v0 + q) / a);
        let (lo, hi) = (r1.min(r2), r1.max(r2));
        if lo >= 0.0 {
            [lo, hi]
        } else {
            [hi, f64::NAN]
        }
    } else if d.v0 != 0.0 {
        [pd / d.v0, f64::NAN]
    } else if pd == 0.0 {
        [0.0, f64::NAN]
    } else {
        [f64::NAN; 2]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dof(p0: f64, v0: f64, a0: f64, pf: f64, vf: f64, af: f64) -> Dof1 {
        let mut d = Dof1::rest_to_rest(p0, pf, 1.0, 1.0, 0.0);
        (d.v0, d.a0, d.vf, d.af) = (v0, a0, vf, af);
        d
    }

    #[test]
    fn coasting_durations_are_the_exact_ones() {
        let mut pr = Profile::default();
        // Constant velocity 0.5 over 1: 2 s.
        let d = dof(0.0, 0.5, 0.0, 1.0, 0.5, 0.0);
        assert!(coasts(&d) && coast_into(&d, None, &mut pr));
        assert_eq!(pr.duration(), 2.0);
        assert!(coast_into(&d, Some(2.0), &mut pr));
        assert!(!coast_into(&d, Some(2.5), &mut pr));
        // Constant acceleration 0.5 from 0 to 0.25 (v 0 → 0.5 in 1 s).
        let d = dof(0.0, 0.0, 0.5, 0.25, 0.5, 0.5);
        assert!(coast_into(&d, None, &mut pr));
        assert!((pr.duration() - 1.0).abs() < 1e-15);
        // The target velocity does not match the coast: no profile.
        let d = dof(0.0, 0.5, 0.0, 1.0, 0.4, 0.0);
        assert!(!coast_into(&d, None, &mut pr));
        // At rest on the target: any duration.
        let d = dof(0.3, 0.0, 0.0, 0.3, 0.0, 0.0);
        assert!(at_rest(&d) && coast_into(&d, None, &mut pr) && pr.duration() == 0.0);
        assert!(coast_into(&d, Some(1.7), &mut pr) && pr.duration() == 1.7);
        // Coasting past the velocity limit is refused.
        let d = dof(0.0, 0.5, 1.0, 10.0, 4.5, 1.0);
        assert!(!coast_into(&d, None, &mut pr));
    }
}
