//! What every candidate profile must satisfy: the target state within the precision
//! contract's tolerances, and the limits at every segment boundary and interior velocity
//! extremum (with the exemption of a start state the brake left outside a limit).

use super::super::problem::{ControlInterface, Dof1, ProfileOrder};
use super::super::profile::{Profile, State1};

/// Position tolerance of the target (absolute) for motions of at least 1e-3; smaller motions
/// have a tolerance relative to their scale (1e-5 of it).
pub const TOL_POSITION: f64 = 1e-8;
/// Motions shorter than this have a position tolerance relative to their scale (see
/// [`position_tolerance`]).
const SMALL_MOTION: f64 = 1e-3;

/// The position tolerance of the target for profile `pr` of `dof`: [`TOL_POSITION`] for
/// motions of at least [`SMALL_MOTION`]; below, 1e-5 of the motion's scale S (the larger of
/// the displacement and the largest distance from the start at a segment boundary), plus 16
/// rounding units of the positions involved, so that a motion of 1e-11 arrives (to 1e-5 of
/// itself) instead of ending where it started.
pub(crate) fn position_tolerance(dof: &Dof1, pr: &Profile) -> f64 {
    let d = (dof.pf - dof.p0).abs();
    if d >= SMALL_MOTION {
        return TOL_POSITION;
    }
    let mut s = d;
    for k in 0..pr.segments() {
        if let Some((_, _, st, _)) = pr.segment(k) {
            s = s.max((st.p - dof.p0).abs());
        }
    }
    s = s.max((pr.end().p - dof.p0).abs());
    let ulps = 16.0 * f64::EPSILON * dof.p0.abs().max(dof.pf.abs()).max(s);
    TOL_POSITION.min(1e-5 * s) + ulps
}

/// Velocity and acceleration tolerance of the target (absolute).
pub const TOL_VELOCITY: f64 = 1e-10;
/// Relative tolerance of the limits.
pub const TOL_LIMIT: f64 = 1e-12;

/// Checks a main profile (no brake) against the target and the limits of `dof`.
pub(crate) fn verify(dof: &Dof1, pr: &Profile) -> bool {
    let e = pr.end();
    let order = dof.order();
    let within = |x: f64, tol: f64| x.abs() <= tol;
    if dof.interface == ControlInterface::Position
        && !within(e.p - dof.pf, position_tolerance(dof, pr))
    {
        return false;
    }
    if order != ProfileOrder::First && !within(e.v - dof.vf, TOL_VELOCITY) {
        return false;
    }
    if order == ProfileOrder::Third && !within(e.a - dof.af, TOL_VELOCITY) {
        return false;
    }
    if !pr.duration().is_finite() {
        return false;
    }
    limits_hold(dof, pr)
}

/// Velocity and acceleration bounds of a check (infinite where a limit is not checked).
#[derive(Clone, Copy)]
struct Bounds {
    vmax: f64,
    vmin: f64,
    amax: f64,
    amin: f64,
}

/// Whether `pr` keeps the velocity (position interface) and acceleration (second and third
/// order) limits of `dof` at every segment boundary and interior velocity extremum.
#[inline]
fn limits_hold(dof: &Dof1, pr: &Profile) -> bool {
    // Half the contract's tolerance, so that an independent re-evaluation (with its own
    // round-off) still finds the limits within TOL_LIMIT.
    let widen = |lim: f64| lim + 0.5 * TOL_LIMIT * lim;
    let check_v = dof.interface == ControlInterface::Position;
    let check_a = dof.order() != ProfileOrder::First;
    let (vmax, vmin) = if check_v {
        (widen(dof.vmax), widen(dof.vmin))
    } else {
        (f64::INFINITY, f64::NEG_INFINITY)
    };
    let (amax, amin) = if check_a {
        (widen(dof.amax), widen(dof.amin))
    } else {
        (f64::INFINITY, f64::NEG_INFINITY)
    };
    let b = Bounds {
        vmax,
        vmin,
        amax,
        amin,
    };
    let s = pr.start();
    if s.v <= b.vmax && s.v >= b.vmin && s.a <= b.amax && s.a >= b.amin {
        stays_inside(pr, &b)
    } else {
        comes_back_inside(pr, &b)
    }
}

/// The common case of [`limits_hold`]: starting inside, every value must stay inside
/// ([`comes_back_inside`] reduces to this when nothing starts outside).
#[inline]
fn stays_inside(pr: &Profile, b: &Bounds) -> bool {
    for k in 0..pr.segments() {
        let Some((_, d, st, j)) = pr.segment(k) else {
            break;
        };
        let aend = st.a + d * j;
        if st.a > b.amax || st.a < b.amin || aend > b.amax || aend < b.amin {
            return false;
        }
        let vend = st.v + d * (st.a + d * j / 2.0);
        if st.v > b.vmax || st.v < b.vmin || vend > b.vmax || vend < b.vmin {
            return false;
        }
        // The interior velocity extremum, at r = −a/j when 0 < r < d. The division is
        // skipped where r > 0 cannot hold (acceleration zero or of the jerk's sign).
        if (st.a > 0.0 && j < 0.0) || (st.a < 0.0 && j > 0.0) {
            let r = -st.a / j;
            if r > 0.0 && r < d {
                let vmid = st.v + r * (st.a + r * j / 2.0);
                if vmid > b.vmax || vmid < b.vmin {
                    return false;
                }
            }
        }
    }
    true
}

/// [`limits_hold`] for a start state that the brake left outside a limit (on its way back):
/// each value may stay outside only until it first comes inside, and never go further out
/// than it started.
#[cold]
fn comes_back_inside(pr: &Profile, b: &Bounds) -> bool {
    let s = pr.start();
    let mut v_in = s.v <= b.vmax && s.v >= b.vmin;
    let mut a_in = s.a <= b.amax && s.a >= b.amin;
    let (v_hi, v_lo) = (b.vmax.max(s.v), b.vmin.min(s.v));
    let (a_hi, a_lo) = (b.amax.max(s.a), b.amin.min(s.a));
    // One value against its bounds; false when it breaks them.
    let step = |x: f64, inside: &mut bool, hi: f64, lo: f64, max: f64, min: f64| {
        if *inside {
            x <= max && x >= min
        } else if x > hi || x < lo {
            false
        } else {
            *inside = x <= max && x >= min;
            true
        }
    };
    for k in 0..pr.segments() {
        let Some((_, d, st, j)) = pr.segment(k) else {
            break;
        };
        // The end state as stored (a closed-form step may have snapped it to its exact
        // value, removing round-off of the size of the largest velocity passed through).
        let vend = st.v + d * (st.a + d * j / 2.0);
        let aend = st.a + d * j;
        let mut vs = [st.v, st.v, vend];
        if j != 0.0 {
            let r = -st.a / j;
            if r > 0.0 && r < d {
                vs[1] = st.v + r * (st.a + r * j / 2.0);
            }
        }
        for v in vs {
            if !step(v, &mut v_in, v_hi, v_lo, b.vmax, b.vmin) {
                return false;
            }
        }
        for a in [st.a, aend] {
            if !step(a, &mut a_in, a_hi, a_lo, b.amax, b.amin) {
                return false;
            }
        }
    }
    true
}

/// A velocity bound that the optimal profile never needs to exceed, used to bound parameter
/// ranges when the velocity limit is infinite.
pub(crate) fn velocity_cap(dof: &Dof1, s: State1) -> f64 {
    if dof.vmax.is_finite() {
        return dof.vmax;
    }
    let a = dof.amax.max(-dof.amin);
    let a = if a.is_finite() { a } else { 0.0 };
    let d = (dof.pf - s.p).abs();
    let cap = 2.0 * (s.v.abs() + dof.vf.abs())
        + (s.a * s.a + dof.af * dof.af) / dof.jmax
        + 2.0 * (2.0 * a * d).sqrt()
        + 2.0 * a * a / dof.jmax;
    4.0 * cap.max(1e-300)
}

/// The range of cruise velocities worth considering for `q`: its velocity limits, or the caps
/// of [`velocity_cap`] where they are infinite.
pub(crate) fn velocity_window(q: &Dof1) -> (f64, f64) {
    let hi = velocity_cap(
        q,
        State1 {
            p: q.p0,
            v: q.v0,
            a: q.a0,
        },
    );
    let lo = -velocity_cap(
        &q.mirrored(),
        State1 {
            p: -q.p0,
            v: -q.v0,
            a: -q.a0,
        },
    );
    (lo, hi)
}
