//! Closed-form bounds that let synchronization skip step 1: an upper bound of a degree of
//! freedom's minimum duration from a valid profile built in closed form (stop, move rest to
//! rest, start), and whether a start state needs no brake pre-profile.
//!
//! Precision: the bound is the duration of a profile whose every piece is a closed-form fastest
//! change (no root finding); from rest to rest with symmetric acceleration limits it equals the
//! minimum to round-off. Both functions are conservative: an infinite bound or a `false` only
//! costs a step 1.

use super::super::problem::{ControlInterface, Dof1, ProfileOrder};
use super::super::velocity_change::fastest3;

/// An upper bound of a DOF's minimum duration, from a valid profile built in closed form:
/// stop (fastest change to rest), move rest to rest (with a cruise if the velocity limit is
/// reached), then the fastest change from rest to the target state; for first order the
/// cruise alone. Exact from rest to rest with symmetric acceleration limits (and always for
/// first order). Infinite where it does not apply (the velocity interface) or where a
/// third-order stop or start would leave the velocity limits.
///
/// Every duration from the bound on is feasible too: the profile can wait at rest between the
/// stop and the move, so no blocked interval lies above the bound.
///
/// Synchronization uses it twice: the DOF with the largest bound runs step 1 first (it most
/// likely sets the duration), and a DOF whose bound is at most the trial duration t needs no
/// step 1 at all: t is feasible for it, and step 2 plans it.
pub(super) fn duration_bound(d: &Dof1) -> f64 {
    if d.interface != ControlInterface::Position {
        return f64::INFINITY;
    }
    let t = match d.order() {
        ProfileOrder::Third => bound_third(d),
        ProfileOrder::Second => bound_second(d),
        ProfileOrder::First => {
            let x = d.pf - d.p0;
            x.abs() / if x >= 0.0 { d.vmax } else { -d.vmin }
        }
    };
    if t.is_finite() {
        t
    } else {
        f64::INFINITY
    }
}

/// [`duration_bound`] for second order: constant-acceleration changes (their velocities stay
/// between their ends, inside the limits).
fn bound_second(d: &Dof1) -> f64 {
    let a = d.amax.min(-d.amin);
    let (ts, ds) = (d.v0.abs() / a, d.v0 * d.v0.abs() / (2.0 * a));
    let (te, de) = (d.vf.abs() / a, d.vf * d.vf.abs() / (2.0 * a));
    let dist = d.pf - d.p0 - ds - de;
    let vl = if dist >= 0.0 { d.vmax } else { -d.vmin };
    let x = dist.abs();
    // Peak velocity without a cruise: x = v²/a.
    let vp = (x * a).sqrt();
    let tm = if vp <= vl {
        2.0 * vp / a
    } else {
        2.0 * vl / a + (x - vl * vl / a) / vl
    };
    ts + tm + te
}

/// [`duration_bound`] for third order.
fn bound_third(d: &Dof1) -> f64 {
    let (j, a) = (d.jmax, d.amax.min(-d.amin));
    // Duration and displacement of the fastest change, if it stays within the velocity
    // limits: its velocity extremes are its ends and where its acceleration crosses zero.
    let change = |va: f64, aa: f64, vb: f64, ab: f64| -> Option<(f64, f64)> {
        if va == vb && aa == ab {
            return Some((0.0, 0.0));
        }
        if aa == 0.0 && ab == 0.0 {
            return Some(flat_change(va, vb, j, d.amax, d.amin));
        }
        let c = fastest3(va, aa, vb, ab, j, d.amax, d.amin)?;
        let (mut v, mut acc) = (va, aa);
        for k in 0..3 {
            let (dk, jk) = (c.d[k], c.j[k]);
            let r = -acc / jk;
            if jk != 0.0 && r > 0.0 && r < dk {
                let vx = v + r * (acc + r * jk / 2.0);
                if vx > d.vmax || vx < d.vmin {
                    return None;
                }
            }
            v += dk * (acc + dk * jk / 2.0);
            acc += dk * jk;
        }
        Some((c.t, c.dist))
    };
    let (Some((ts, ds)), Some((te, de))) =
        (change(d.v0, d.a0, 0.0, 0.0), change(0.0, 0.0, d.vf, d.af))
    else {
        return f64::INFINITY;
    };
    let dist = d.pf - d.p0 - ds - de;
    let vl = if dist >= 0.0 { d.vmax } else { -d.vmin };
    let x = dist.abs();
    let knee = a * a / j;
    // Duration of the change from rest to v (and of the one back).
    let t1 = |v: f64| {
        if v <= knee {
            2.0 * (v / j).sqrt()
        } else {
            v / a + a / j
        }
    };
    // A cruise at the limit when the two changes to it and back cover at most x (t1 grows
    // with v, so this is "peak velocity ≥ v_l"); otherwise the peak velocity v_p without a
    // cruise: x = v_p·t1(v_p). (Decided first: the cube root is needed only without a
    // cruise.)
    let tl = t1(vl);
    let tm = if x >= vl * tl {
        2.0 * tl + (x - vl * tl) / vl
    } else {
        let tri = (x * x * j / 4.0).cbrt();
        let vp = if tri <= knee {
            tri
        } else {
            let k = a / j;
            (-k + (k * k + 4.0 * x / a).sqrt()) * a / 2.0
        };
        2.0 * t1(vp)
    };
    ts + tm + te
}

/// Duration and displacement of the fastest change from velocity `va` to `vb ≠ va`, both at
/// zero acceleration (the common case of the stop and start changes): [`fastest3`]'s change
/// in closed form without building its segments. The acceleration ramps to a peak of
/// √(J·|Δv|) (or holds the limit in between) and back, so the velocity is monotone (no
/// interior extreme to check) and point-symmetric about the middle: the displacement is
/// the mean velocity times the duration.
pub(super) fn flat_change(va: f64, vb: f64, j: f64, amax: f64, amin: f64) -> (f64, f64) {
    let dv = (vb - va).abs();
    let a = if vb > va { amax } else { -amin };
    let peak = (j * dv).sqrt();
    let t = if peak <= a {
        2.0 * peak / j
    } else {
        dv / a + a / j
    };
    (t, 0.5 * (va + vb) * t)
}

/// Whether the start state needs no brake pre-profile: acceleration and velocity within their
/// limits, and so is the velocity where ramping the acceleration to zero with full jerk lands
/// (then no side of [`super::super::brake`] brakes). Conservative: false only costs a step 1.
pub(super) fn starts_safe(d: &Dof1) -> bool {
    let (vmax, vmin) = match d.interface {
        ControlInterface::Position => (d.vmax, d.vmin),
        ControlInterface::Velocity => (f64::INFINITY, f64::NEG_INFINITY),
    };
    let v_in = |v: f64| v <= vmax && v >= vmin;
    match d.order() {
        ProfileOrder::First => true,
        ProfileOrder::Second => v_in(d.v0),
        ProfileOrder::Third => {
            d.a0 <= d.amax
                && d.a0 >= d.amin
                && v_in(d.v0)
                && v_in(d.v0 + d.a0 * d.a0.abs() / (2.0 * d.jmax))
        }
    }
}
