//! The brake pre-profile: bringing a state that is outside the limits back inside.
//!
//! The current state may violate the limits (a robot that was pushed, a limit that was just
//! lowered). Before the time-optimal profile can start, the state must be *safe*: velocity and
//! acceleration within their limits, and the velocity reached when the acceleration is ramped
//! to zero with full jerk, v + a·|a|/(2J), within the velocity limits too (otherwise a
//! violation is unavoidable later). The brake applies full jerk against the violation until the
//! state is safe or the acceleration reaches its opposite limit, then (if still needed) holds
//! that acceleration until the velocity is back at its limit: at most two segments per side (the positive side may run twice: before and after the
//! negative side has ramped back an acceleration beyond its limit).
//! Second order: the opposite acceleration limit until the velocity is back inside. First
//! order: nothing (velocity jumps).
//!
//! Precision: brake durations are closed-form; the end state is safe within 1e-12 relative.

use super::problem::{ControlInterface, Dof1, ProfileOrder};
use super::profile::Profile;

/// Appends the brake segments for `dof` to `pr` (which holds the start state) and marks them as
/// the brake pre-profile.
pub(crate) fn brake(dof: &Dof1, pr: &mut Profile) {
    let (vmax, vmin) = match dof.interface {
        ControlInterface::Position => (dof.vmax, dof.vmin),
        ControlInterface::Velocity => (f64::INFINITY, f64::NEG_INFINITY),
    };
    match dof.order() {
        ProfileOrder::First => {}
        ProfileOrder::Second => {
            let s = pr.end();
            if s.v > vmax {
                pr.push_with((s.v - vmax) / -dof.amin, s.v, dof.amin, 0.0);
            } else if s.v < vmin {
                pr.push_with((vmin - s.v) / dof.amax, s.v, dof.amax, 0.0);
            }
            if pr.segments() > 0 {
                let e = pr.end();
                pr.set_final(e.v, 0.0);
            }
        }
        ProfileOrder::Third => {
            // A state with zero acceleration and its velocity within the limits (every state
            // at rest) is safe: no side below would brake it.
            let s = pr.end();
            if s.a == 0.0 && dof.amax >= 0.0 && dof.amin <= 0.0 && s.v <= vmax && s.v >= vmin {
                pr.mark_brake();
                return;
            }
            // An acceleration beyond its limit is ramped back first (the side that owns it),
            // then the velocity of either side is braked.
            side(pr, vmax, vmin, dof.amax, dof.amin, dof.jmax, 1.0);
            side(pr, -vmin, -vmax, -dof.amin, -dof.amax, dof.jmax, -1.0);
            side(pr, vmax, vmin, dof.amax, dof.amin, dof.jmax, 1.0);
        }
    }
    pr.mark_brake();
}

/// Brakes against a violation on the positive side, in a frame multiplied by `sgn`. The brake
/// never goes so far that ramping the acceleration back to zero would land below `vmin`.
fn side(pr: &mut Profile, vmax: f64, vmin: f64, amax: f64, amin: f64, j: f64, sgn: f64) {
    let e = pr.end();
    let (v0, a0) = (sgn * e.v, sgn * e.a);
    if a0 < amin {
        // The acceleration violates the other side's limit: that side ramps it back first.
        return;
    }
    let stop = v0 + a0 * a0.abs() / (2.0 * j);
    let over_a = a0 > amax;
    let over_v = v0 > vmax || (a0 > 0.0 && stop > vmax);
    if !over_a && !over_v {
        return;
    }
    let t_a = if over_a { (a0 - amax) / j } else { 0.0 };
    let t_v = if over_v {
        // Later root of v0 + a0 t − j t²/2 = vmax (velocity decreasing there).
        let rad = a0 * a0 + 2.0 * j * (v0 - vmax);
        (a0 + rad.max(0.0).sqrt()) / j
    } else {
        0.0
    };
    let t_full = (a0 - amin) / j;
    // Time at which v − a²/(2J), the landing velocity of a reversal, reaches vmin.
    // Stopped a little early (1e-12 relative) so that round-off cannot put the landing
    // velocity past the opposite limit.
    let t_opp = if vmin.is_finite() {
        let t = (a0 + (a0 * a0 / 2.0 + j * (v0 - vmin)).max(0.0).sqrt()) / j;
        t - 1e-12 * t.abs().max(1.0)
    } else {
        f64::INFINITY
    };
    let t1 = t_a.max(t_v).min(t_full).min(t_opp.max(t_a)).max(0.0);
    pr.push(t1, -sgn * j);
    let e = pr.end();
    let (v1, a1) = (sgn * e.v, sgn * e.a);
    if over_v && v1 > vmax && a1 < 0.0 && t1 >= t_full {
        let t_to_vmax = (v1 - vmax) / -a1;
        let t_to_opp = (v1 - a1 * a1 / (2.0 * j) - vmin) / -a1;
        pr.push(t_to_vmax.min(t_to_opp).max(0.0), 0.0);
    }
}
