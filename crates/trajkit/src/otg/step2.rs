//! Step 2: a profile of one degree of freedom with a prescribed duration.
//!
//! When several degrees of freedom must finish together, every one of them except the slowest
//! has to be re-planned for a longer duration T. Position interface (second and third order):
//! the profile changes velocity as fast as possible to a cruise velocity v_c (with zero
//! acceleration), cruises for τ ≥ 0, and changes as fast as possible to the target velocity and
//! acceleration; τ = T − t₁(v_c) − t₂(v_c). For third order the position equation is a
//! polynomial (degree ≤ 6) per direction and plateau variant of the two changes (see
//! [`super::families`]); the bracketing solver of [`super::roots`] on the residual in v_c
//! remains the fallback and serves second order. Then the hold families (a zero-jerk hold at
//! the peak or the valley of a₀ ↗ α₁ ↘ α₂ ↗ a_f), four ramps, split ramps and a peak
//! followed by a hold, each bracketed in its free level on pieces that are valid or invalid
//! as a whole (`step2/windows.rs`: the edges in closed form; a valid range narrower than the
//! bracketing grid's step was missed before, and a synchronized duration with it). When no cruise profile fits, the
//! step-1 candidate profiles whose duration equals T are used (the caller tries those first).
//! First order: the constant velocity D/T. Velocity interface: the acceleration ramps to a level α, holds it, and ramps
//! to the target acceleration; the residual is the velocity change, free parameter α.
//!
//! Every profile is verified by integration exactly like step 1, plus |duration − T| ≤ 1e−12·T.

use super::bracket::{first_at_root, Grid};
use super::families::two_changes;
use super::problem::{ControlInterface, Dof1, ProfileOrder};
use super::profile::{integrate, Profile, State1};
use super::step1::{velocity_cap, velocity_window, verify, RestShape};
use super::velocity_change::{fastest, kink, push_change, via_velocity, VelChange};

mod windows;
use windows::{four_ramps_cuts, hold_window, peak_then_hold_cuts, split_ramp_cuts};

/// A verified profile for `dof` (whose start state is safe) lasting `t` seconds, if one of the
/// step-2 families has one.
pub(crate) fn step2(dof: &Dof1, t: f64) -> Option<Profile> {
    let mut pr = Profile::default();
    step2_into(dof, t, &mut pr).then_some(pr)
}

/// [`step2`] written into `out` (the rest-to-rest closed form, the common case of
/// synchronization, builds there without a copy); false (and `out` unspecified) when no family
/// has a profile.
pub(crate) fn step2_into(dof: &Dof1, t: f64, out: &mut Profile) -> bool {
    if !t.is_finite() || t < 0.0 {
        return false;
    }
    if super::zero::coasts(dof) {
        return super::zero::coast_into(dof, Some(t), out);
    }
    let ok = |pr: &Profile| verify(dof, pr) && (pr.duration() - t).abs() <= 1e-12 * t.max(1.0);
    if dof.interface == ControlInterface::Position
        && dof.order() != ProfileOrder::First
        && rest_to_rest(dof, t, &ok, out)
    {
        return true;
    }
    if dof.interface == ControlInterface::Position
        && dof.order() == ProfileOrder::Third
        && cruise_closed(dof, t, &ok, out)
    {
        return true;
    }
    match other_families(dof, t, &ok) {
        Some(p) => {
            *out = p;
            true
        }
        None => dof.has_position_limits() && super::position::wait_into(dof, t, out),
    }
}

/// The closed-form families of [`step2_into`] alone (third order, position interface): the
/// rest-to-rest closed form and the cruise family's position polynomials. True when one of
/// them plans a verified profile of duration `t` into `out` (the profile [`step2_into`]
/// would return: it tries them first, with the same check); false says nothing about the
/// other families. A cheap proof that `t` is feasible, for searches that rate durations.
pub(crate) fn step2_closed_into(dof: &Dof1, t: f64, out: &mut Profile) -> bool {
    if !t.is_finite()
        || t < 0.0
        || dof.interface != ControlInterface::Position
        || dof.order() != ProfileOrder::Third
        || super::zero::coasts(dof)
    {
        return false;
    }
    let ok = |pr: &Profile| verify(dof, pr) && (pr.duration() - t).abs() <= 1e-12 * t.max(1.0);
    rest_to_rest(dof, t, &ok, out) || cruise_closed(dof, t, &ok, out)
}

/// The step-2 families other than the closed forms (rest to rest, and the cruise family's
/// polynomials for third order and the position interface), which [`step2_into`] tries
/// first.
fn other_families(dof: &Dof1, t: f64, ok: &impl Fn(&Profile) -> bool) -> Option<Profile> {
    let start = State1 {
        p: dof.p0,
        v: dof.v0,
        a: dof.a0,
    };
    let order = dof.order();
    match (order, dof.interface) {
        (ProfileOrder::First, iface) => {
            let d = if iface == ControlInterface::Position {
                dof.pf - dof.p0
            } else {
                0.0
            };
            let mut pr = Profile::new(start);
            if t > 0.0 {
                let v = d / t;
                pr.push_with(t, v, 0.0, 0.0);
            } else if d != 0.0 {
                return None;
            }
            pr.set_final(dof.vf, 0.0);
            ok(&pr).then_some(pr)
        }
        (ProfileOrder::Second, ControlInterface::Velocity) => {
            let mut pr = Profile::new(start);
            if t > 0.0 {
                pr.push_with(t, dof.v0, (dof.vf - dof.v0) / t, 0.0);
            }
            pr.set_final(dof.vf, 0.0);
            ok(&pr).then_some(pr)
        }
        (ProfileOrder::Third, ControlInterface::Velocity) => {
            if let r @ Some(_) = velocity3_closed(dof, t, ok) {
                return r;
            }
            velocity3(dof, t, ok)
        }
        (ProfileOrder::Second, ControlInterface::Position) => cruise(dof, t, ok),
        (ProfileOrder::Third, ControlInterface::Position) => {
            // Early returns rather than an `or_else` chain, which moves the profile through
            // every remaining stage.
            for (mirror, at_valley) in [(false, false), (false, true), (true, false), (true, true)]
            {
                if let r @ Some(_) = hold(dof, t, mirror, at_valley, ok) {
                    return r;
                }
            }
            if let r @ Some(_) = cruise(dof, t, ok) {
                return r;
            }
            for mirror in [false, true] {
                if let r @ Some(_) = four_ramps(dof, t, mirror, ok) {
                    return r;
                }
                for plateau in [true, false] {
                    if let r @ Some(_) = split_ramp(dof, t, mirror, plateau, ok) {
                        return r;
                    }
                }
                for plateau in [false, true] {
                    if let r @ Some(_) = peak_then_hold(dof, t, mirror, plateau, ok) {
                        return r;
                    }
                }
            }
            None
        }
    }
}

/// The root of p(s) = k·s³ − t·s² + D on `[0, hi]` (the peak velocity's square root of a
/// synchronized rest-to-rest motion without acceleration plateaus), `None` when there is none.
///
/// With k, t, D > 0 and hi ≤ t/(2k) (the callers' window, t√j/4 with k = 2/√j), p falls
/// strictly on `[0, hi]` (p′ = s·(3k·s − 2t) < 0 there): at most one root, bracketed by
/// p(0) = D, positive, and p(hi) ≤ 0. Newton steps from the secant point, each kept inside
/// the shrinking bracket (bisection otherwise), reach it to a few rounding units in a few
/// iterations; [`crate::roots::roots_in`] (plain bisection, about 60 evaluations per root
/// and per level of its derivative recursion) gives the same root and remains the path for
/// anything outside that case (D = 0, a degenerate window, non-finite values).
fn rest_cubic_root(k: f64, t: f64, d: f64, hi: f64) -> Option<f64> {
    let p = |s: f64| (k * s - t) * s * s + d;
    let regular = d > 0.0 && k > 0.0 && t > 0.0 && hi > 0.0 && hi.is_finite() && hi <= 0.5 * t / k;
    if !regular {
        let mut roots = [0.0; crate::roots::MAX_DEGREE];
        let n = crate::roots::roots_in(&[d, 0.0, -t, k], 0.0, hi, &mut roots);
        return (n > 0).then_some(roots[0]);
    }
    let p_hi = p(hi);
    if p_hi > 0.0 {
        return None;
    }
    if p_hi == 0.0 {
        return Some(hi);
    }
    // Bracket [lo, up] with p(lo) > 0 > p(up).
    let (mut lo, mut up) = (0.0f64, hi);
    // Start from the linear interpolation of the ends (the secant through the bracket).
    let mut s = hi * d / (d - p_hi);
    for _ in 0..100 {
        let ps = p(s);
        if ps == 0.0 {
            return Some(s);
        }
        if ps > 0.0 {
            lo = s;
        } else {
            up = s;
        }
        let mut next = s - ps / (s * (3.0 * k * s - 2.0 * t));
        if !(next > lo && next < up) {
            next = 0.5 * (lo + up);
            if next <= lo || next >= up {
                // The bracket is two adjacent floating-point numbers.
                return Some(next);
            }
        }
        // A step of a few rounding units: Newton has converged (its next error is the
        // square of this one).
        if (next - s).abs() <= 2.0 * f64::EPSILON * s {
            return Some(next);
        }
        s = next;
    }
    Some(s)
}

/// Closed-form cruise velocity for a rest-to-rest move with symmetric acceleration limits (the
/// common case of synchronization): with t₁ the time of each velocity change and D the distance,
/// v_c·(t − t₁(v_c)) = D. Without an acceleration plateau t₁ = 2√(v_c/j), a cubic in √v_c;
/// with one t₁ = v_c/a + a/j, a quadratic. Third order writes the segments straight from
/// those durations (no velocity-change construction). False (the general family takes over)
/// when the case does not apply or the profile fails verification. Builds in `pr`; returns
/// whether it left a verified profile there.
fn rest_to_rest(dof: &Dof1, t: f64, ok: &impl Fn(&Profile) -> bool, pr: &mut Profile) -> bool {
    if dof.v0 != 0.0 || dof.a0 != 0.0 || dof.vf != 0.0 || dof.af != 0.0 || dof.amax != -dof.amin {
        return false;
    }
    let order = dof.order();
    let d = (dof.pf - dof.p0).abs();
    let (a, j) = (dof.amax, dof.jmax);
    let sgn = if dof.pf >= dof.p0 { 1.0 } else { -1.0 };
    let vc = match order {
        // v_c² / a − t·v_c + D = 0, smaller root.
        ProfileOrder::Second => {
            let disc = t * t - 4.0 * d / a;
            if disc < 0.0 {
                return false;
            }
            2.0 * d / (t + disc.sqrt())
        }
        ProfileOrder::Third => {
            // Each change: ramps r and a plateau h; the segments are written directly.
            let tp = t - a / j;
            let disc = tp * tp - 4.0 * d / a;
            let plateau = if disc >= 0.0 {
                2.0 * d / (tp + disc.sqrt())
            } else {
                f64::NAN
            };
            let (vc, r, h) = if plateau >= a * a / j {
                (plateau, a / j, (plateau / a - a / j).max(0.0))
            } else {
                // (2/√j)·s³ − t·s² + D = 0 for s = √v_c on [0, min(t√j/4, a/√j)]; r = s/√j.
                let sj = j.sqrt();
                let hi = (t * sj / 4.0).min(a / sj);
                let Some(s) = rest_cubic_root(2.0 / sj, t, d, hi) else {
                    return false;
                };
                (s * s, s / sj, 0.0)
            };
            let tau = t - 2.0 * (2.0 * r + h);
            let shape = RestShape {
                r1: r,
                h1: h,
                r2: r,
                h2: h,
                vp: vc,
                cruise: tau,
            };
            return tau >= 0.0 && shape.write(pr, dof.p0, sgn, j) && ok(pr);
        }
        ProfileOrder::First => return false,
    };
    let vc = sgn * vc;
    let (Some(c1), Some(c2)) = (
        fastest(order, 0.0, 0.0, vc, 0.0, j, dof.amax, dof.amin),
        fastest(order, vc, 0.0, 0.0, 0.0, j, dof.amax, dof.amin),
    ) else {
        return false;
    };
    let tau = t - c1.t - c2.t;
    if tau < 0.0 {
        return false;
    }
    pr.reset(State1 {
        p: dof.p0,
        v: 0.0,
        a: 0.0,
    });
    push_change(pr, order, &c1, 0.0);
    pr.push_cruise(tau, vc);
    push_change(pr, order, &c2, vc);
    pr.set_final(0.0, 0.0);
    ok(pr)
}

/// Cruise family with a free cruise velocity (third order), from the roots of its position
/// polynomials: for each direction of the two velocity changes and each plateau variant
/// (see [`two_changes`]). The directions that the mean velocity D/t suggests go first; the
/// first valid profile wins, copied into `out` (true; false and `out` untouched otherwise).
fn cruise_closed(dof: &Dof1, t: f64, ok: &impl Fn(&Profile) -> bool, out: &mut Profile) -> bool {
    let j = dof.jmax;
    let guess = if t > 0.0 { (dof.pf - dof.p0) / t } else { 0.0 };
    let k0 = kink(ProfileOrder::Third, dof.v0, dof.a0, j, 1.0);
    let kf = kink(ProfileOrder::Third, dof.vf, dof.af, j, -1.0);
    let g1 = if guess >= k0 { 1.0 } else { -1.0 };
    let g2 = if guess <= kf { 1.0 } else { -1.0 };
    let (vlo, vhi) = velocity_window(dof);
    for (d1, d2) in [(g1, g2), (-g1, g2), (g1, -g2), (-g1, -g2)] {
        if two_changes(dof, d1, d2, Some(t), vlo, vhi, &mut |pr| {
            let good = ok(pr);
            if good {
                *out = *pr;
            }
            good
        }) {
            return true;
        }
    }
    false
}

/// Cruise family with a free cruise velocity, by bracketing (the fallback of
/// [`cruise_closed`]; also second order).
fn cruise(dof: &Dof1, t: f64, ok: &impl Fn(&Profile) -> bool) -> Option<Profile> {
    let order = dof.order();
    let d = dof.pf - dof.p0;
    let start = State1 {
        p: dof.p0,
        v: dof.v0,
        a: dof.a0,
    };
    let hi = velocity_cap(dof, start);
    let lo = -velocity_cap(
        &dof.mirrored(),
        State1 {
            p: -dof.p0,
            v: -dof.v0,
            a: -dof.a0,
        },
    );
    // τ < 0 (the two changes alone take longer than t) is outside the family; the residual
    // continues there with τ = 0 so that it stays continuous and no domain edge has to be
    // searched. Roots found there are rejected by the duration check.
    let parts = |vc: f64| -> Option<(VelChange, VelChange, f64)> {
        let c1 = fastest(order, dof.v0, dof.a0, vc, 0.0, dof.jmax, dof.amax, dof.amin)?;
        let c2 = fastest(order, vc, 0.0, dof.vf, dof.af, dof.jmax, dof.amax, dof.amin)?;
        let tau = t - c1.t - c2.t;
        Some((c1, c2, tau))
    };
    let build = |vc: f64| -> Option<Profile> {
        let (c1, c2, tau) = parts(vc)?;
        if tau < 0.0 {
            return None;
        }
        Some(via_velocity(dof, order, &c1, vc, Some(tau), &c2))
    };
    let f = |vc: f64| parts(vc).map(|(c1, c2, tau)| c1.dist + c2.dist + vc * tau.max(0.0) - d);
    let guess = if t > 0.0 { d / t } else { 0.0 };
    let [z0, z1, z2] = cruise_vanishes(order, dof, lo, hi, &parts);
    let cuts = [
        lo,
        hi,
        0.0,
        guess,
        kink(order, dof.v0, dof.a0, dof.jmax, 1.0),
        kink(order, dof.vf, dof.af, dof.jmax, -1.0),
        z0,
        z1,
        z2,
    ];
    first_at_root(cuts, Grid::Coarse, f, |vc| build(vc).filter(|pr| ok(pr)))
}

/// Second order: the cruise velocities where the cruise of [`cruise`] vanishes (τ = 0), as
/// cuts of its bracketing (`lo` where there is none). τ(v_c) = T − t₁ − t₂ is linear in v_c
/// below, between and above v₀ and v_f, so each zero is one linear solve. The residual's
/// continuation with τ = 0 meets the family there with a zero of its own, and the family's
/// root lies next to it when T is just below the longest duration without a velocity
/// reversal: both within one grid step, no sign change was seen, and the synchronized
/// duration jumped past the DOF's blocked interval (a 3-DOF `second_order` problem: 4.93 s
/// where 2.149 s is feasible). Third order has its closed forms ([`cruise_closed`]) first.
fn cruise_vanishes<C>(
    order: ProfileOrder,
    dof: &Dof1,
    lo: f64,
    hi: f64,
    parts: &impl Fn(f64) -> Option<(C, C, f64)>,
) -> [f64; 3] {
    let mut z = [lo; 3];
    if order != ProfileOrder::Second || !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return z;
    }
    let (b1, b2) = (dof.v0.min(dof.vf), dof.v0.max(dof.vf));
    let pieces = [(lo, b1.min(hi)), (b1.max(lo), b2.min(hi)), (b2.max(lo), hi)];
    for (zk, (x0, x1)) in z.iter_mut().zip(pieces) {
        if x0 >= x1 {
            continue;
        }
        if let (Some((_, _, t0)), Some((_, _, t1))) = (parts(x0), parts(x1)) {
            if (t0 < 0.0) != (t1 < 0.0) {
                *zk = x0 + (x1 - x0) * (t0 / (t0 - t1));
            }
        }
    }
    z
}

/// Hold families (third order): a₀ ↗ α₁ ↘ α₂ ↗ a_f with a zero-jerk hold at the peak α₁
/// (`at_valley` false) or at the valley α₂ (true); the negative direction by mirroring. The
/// duration and velocity equations give the other level in closed form; free parameter: the
/// level that holds, bracketed on its valid interval ([`hold_window`]).
fn hold(
    dof: &Dof1,
    t: f64,
    mirror: bool,
    at_valley: bool,
    ok: &impl Fn(&Profile) -> bool,
) -> Option<Profile> {
    let q = if mirror { dof.mirrored() } else { *dof };
    let (j, a0, af, v0) = (q.jmax, q.a0, q.af, q.v0);
    let dv = q.vf - q.v0;
    let (amax, a2) = (q.amax, -q.amin);
    let tol = 1e-12 * (amax + a2);
    let levels = |x: f64| -> Option<(f64, f64, f64)> {
        // Returns (α1, α2, hold).
        let (al1, al2) = if !at_valley {
            let al1 = x;
            let c = al1 * (t - (2.0 * al1 - a0 + af) / j)
                + (2.0 * al1 * al1 - a0 * a0 + af * af) / (2.0 * j)
                - dv;
            let rad = al1 * al1 + j * c;
            if rad < 0.0 {
                return None;
            }
            (al1, al1 - rad.sqrt())
        } else {
            let al2 = x;
            let c = al2 * (t + (a0 + 2.0 * al2 - af) / j)
                + (af * af - a0 * a0 - 2.0 * al2 * al2) / (2.0 * j)
                - dv;
            let rad = al2 * al2 - j * c;
            if rad < 0.0 {
                return None;
            }
            (al2 + rad.sqrt(), al2)
        };
        let h = t - (2.0 * al1 - a0 - 2.0 * al2 + af) / j;
        let valid = h >= 0.0
            && al1 >= a0 - tol
            && al1 >= al2 - tol
            && al2 <= af + tol
            && al1 <= amax + tol
            && al2 >= -a2 - tol;
        valid.then_some((al1, al2, h))
    };
    let start = State1 {
        p: q.p0,
        v: v0,
        a: a0,
    };
    let segs = |x: f64| -> Option<[(f64, f64); 4]> {
        let (al1, al2, h) = levels(x)?;
        let up = (((al1 - a0) / j).max(0.0), j);
        let down = (((al1 - al2) / j).max(0.0), -j);
        let last = (((af - al2) / j).max(0.0), j);
        Some(if at_valley {
            [up, down, (h, 0.0), last]
        } else {
            [up, (h, 0.0), down, last]
        })
    };
    let build = |x: f64| segs(x).map(|s| segments_profile(start, &s, mirror));
    let d = dof.pf - dof.p0;
    let sgn = if mirror { -1.0 } else { 1.0 };
    let f = |x: f64| segs(x).map(|s| sgn * (segments_end_p(start, &s, mirror) - dof.pf) + 0.0 * d);
    let (lo, hi) = if at_valley { (-a2, af) } else { (a0, amax) };
    // The shape is valid on one interval of the free parameter, known in closed form: the
    // bracketing works there (a valid range narrower than its grid's spacing was missed).
    let dep = if at_valley {
        (a0 - tol, amax + tol)
    } else {
        (-af - tol, a2 + tol)
    };
    let k = j * t + a0 - af;
    let c = j * dv - (af * af - a0 * a0) / 2.0;
    let (lo, hi) = match hold_window(k, c, at_valley, dep, tol) {
        Some((wlo, whi)) => (lo.max(wlo), hi.min(whi)),
        None => (lo, hi),
    };
    let cuts = [lo, hi, 0.0, if at_valley { a0.min(af) } else { af.max(a0) }];
    first_root(cuts, f, &build, ok)
}

/// The profile of constant-jerk segments `(duration, jerk)` from `start`, mirrored (every
/// state and jerk negated) when `mirror`: the shape of a bracketed family at one value of its
/// free parameter. A segment that [`Profile::push`] refuses (a negative or non-finite
/// duration) is left out, as are zero durations.
fn segments_profile(start: State1, segs: &[(f64, f64)], mirror: bool) -> Profile {
    let mut pr = Profile::new(start);
    for &(d, j) in segs {
        pr.push(d, j);
    }
    if mirror {
        pr.mirror();
    }
    pr
}

/// The end position of [`segments_profile`] without building the profile. The bracketed
/// families evaluate their position residual dozens of times per step-2 call (a call where
/// no family fits, as inside a blocked interval during the synchronization's bisection, runs
/// them all), and writing a whole profile per evaluation was most of its cost. The same
/// segments are integrated by the same [`integrate`] in the same order, and mirroring only
/// negates, so the value is bit for bit the profile's `end().p`.
fn segments_end_p(start: State1, segs: &[(f64, f64)], mirror: bool) -> f64 {
    let (mut p, mut v, mut a) = (start.p, start.v, start.a);
    for &(d, j) in segs {
        // What `Profile::push` skips: refused and zero durations (five segments never reach
        // its segment limit).
        if !(0.0..=f64::MAX).contains(&d) || d == 0.0 {
            continue;
        }
        (p, v, a) = integrate(p, v, a, j, d);
    }
    if mirror {
        -p
    } else {
        p
    }
}

/// The first profile, built by `build` at a root of `f` (bracketed on the pieces between
/// `cuts`, in increasing order), that `ok` accepts.
fn first_root<const N: usize>(
    cuts: [f64; N],
    f: impl FnMut(f64) -> Option<f64>,
    build: &impl Fn(f64) -> Option<Profile>,
    ok: &impl Fn(&Profile) -> bool,
) -> Option<Profile> {
    first_at_root(cuts, Grid::Fine, f, |x| build(x).filter(|pr| ok(pr)))
}

/// Four ramps without a hold (third order): a₀ ↘ α₁ ↗ α₂ ↘ α₃ ↗ a_f under full jerk (the
/// negative direction by mirroring), the shape of a synchronized profile that swings twice
/// and has neither a cruise nor a plateau. With the middle level α₂ as free parameter the
/// duration gives α₁ + α₃ = (a₀ + a_f + 2α₂ − jT)/2 and the velocity change
/// α₁² + α₃² = (a₀² + a_f² + 2α₂² − 2jΔv)/2, so α₁ and α₃ are the two roots of a quadratic
/// (either order); the position residual is then bracketed in α₂.
fn four_ramps(dof: &Dof1, t: f64, mirror: bool, ok: &impl Fn(&Profile) -> bool) -> Option<Profile> {
    let q = if mirror { dof.mirrored() } else { *dof };
    let (j, a0, af) = (q.jmax, q.a0, q.af);
    let dv = q.vf - q.v0;
    let tol = 1e-12 * (q.amax - q.amin);
    let levels = |a2: f64, first_low: bool| -> Option<(f64, f64)> {
        let sum = (a0 + af + 2.0 * a2 - j * t) / 2.0;
        let sq = (a0 * a0 + af * af + 2.0 * a2 * a2 - 2.0 * j * dv) / 2.0;
        let rad = 2.0 * sq - sum * sum;
        if rad < 0.0 {
            return None;
        }
        let r = rad.sqrt();
        let (lo, hi) = ((sum - r) / 2.0, (sum + r) / 2.0);
        let (a1, a3) = if first_low { (lo, hi) } else { (hi, lo) };
        let valid = a1 <= a0 + tol
            && a1 <= a2 + tol
            && a3 <= a2 + tol
            && a3 <= af + tol
            && a1 >= q.amin - tol
            && a3 >= q.amin - tol
            && a2 <= q.amax + tol;
        valid.then_some((a1, a3))
    };
    let start = State1 {
        p: q.p0,
        v: q.v0,
        a: a0,
    };
    let segs = |a2: f64, first_low: bool| -> Option<[(f64, f64); 4]> {
        let (a1, a3) = levels(a2, first_low)?;
        Some([
            (((a0 - a1) / j).max(0.0), -j),
            (((a2 - a1) / j).max(0.0), j),
            (((a2 - a3) / j).max(0.0), -j),
            (((af - a3) / j).max(0.0), j),
        ])
    };
    let sgn = if mirror { -1.0 } else { 1.0 };
    for first_low in [true, false] {
        let b = |x: f64| segs(x, first_low).map(|s| segments_profile(start, &s, mirror));
        let f =
            |x: f64| segs(x, first_low).map(|s| sgn * (segments_end_p(start, &s, mirror) - dof.pf));
        if let r @ Some(_) = first_root(four_ramps_cuts(&q, t), f, &b, ok) {
            return r;
        }
    }
    None
}

/// A ramp split by a hold (third order): a₀ ↘ α (hold τ) ↘ β (hold h) ↗ a_f under full jerk,
/// the negative direction by mirroring; the hold at α is at a level that is not a limit and
/// not an extremum. `plateau`: β is the acceleration limit and h ≥ 0 (then τ + h is fixed by
/// the duration and τ follows from the velocity change); otherwise h = 0 and β follows from
/// the duration and the velocity change (a quadratic). Free parameter α ∈ [β, a₀], the
/// position residual bracketed.
fn split_ramp(
    dof: &Dof1,
    t: f64,
    mirror: bool,
    plateau: bool,
    ok: &impl Fn(&Profile) -> bool,
) -> Option<Profile> {
    let q = if mirror { dof.mirrored() } else { *dof };
    let (j, a0, af, m) = (q.jmax, q.a0, q.af, q.amin);
    let dv = q.vf - q.v0;
    // Returns (τ, β, h).
    let levels = |al: f64| -> Option<(f64, f64, f64)> {
        let (tau, beta, h) = if plateau {
            let rest = t - (a0 - m) / j - (af - m) / j;
            let k = (a0 * a0 - 2.0 * m * m + af * af) / (2.0 * j);
            let tau = (dv - k - m * rest) / (al - m);
            (tau, m, rest - tau)
        } else {
            let c = al * t * j - al * (a0 + af) - j * dv + (a0 * a0 + af * af) / 2.0;
            let rad = al * al + c;
            if rad < 0.0 {
                return None;
            }
            let beta = al - rad.sqrt();
            (t - (a0 + af - 2.0 * beta) / j, beta, 0.0)
        };
        let valid = tau >= 0.0
            && h >= 0.0
            && beta >= m * (1.0 + 1e-12)
            && beta <= al
            && al <= a0
            && beta <= af
            && al <= q.amax;
        valid.then_some((tau, beta, h))
    };
    let start = State1 {
        p: q.p0,
        v: q.v0,
        a: a0,
    };
    let segs = |al: f64| -> Option<[(f64, f64); 5]> {
        let (tau, beta, h) = levels(al)?;
        Some([
            (((a0 - al) / j).max(0.0), -j),
            (tau, 0.0),
            (((al - beta) / j).max(0.0), -j),
            (h, 0.0),
            (((af - beta) / j).max(0.0), j),
        ])
    };
    let build = |x: f64| segs(x).map(|s| segments_profile(start, &s, mirror));
    let sgn = if mirror { -1.0 } else { 1.0 };
    let f = |x: f64| segs(x).map(|s| sgn * (segments_end_p(start, &s, mirror) - dof.pf));
    first_root(split_ramp_cuts(&q, t, plateau), f, &build, ok)
}

/// A peak, then a hold on the way down (third order): a₀ ↗ α₁ ↘ α₂ (hold τ) ↘ a_f under full
/// jerk, the negative direction by mirroring (the time reversal of [`split_ramp`]). Without a
/// plateau the duration gives τ = T − (2α₁ − a₀ − a_f)/j and the velocity change
/// α₂ = (Δv − (2α₁² − a₀² − a_f²)/(2j))/τ, free parameter α₁ ∈ [max(a₀, a_f), a_max]; with a
/// plateau at α₁ = a_max (lasting h) the duration fixes h + τ and the velocity change gives
/// τ, free parameter α₂ ∈ [a_f, a_max]. The position residual is bracketed. (Ruckig plans a
/// DOF this way, for example, when its target is at the velocity limit or it must pass a
/// plateau first, and it is synchronized to a slightly longer duration.)
fn peak_then_hold(
    dof: &Dof1,
    t: f64,
    mirror: bool,
    plateau: bool,
    ok: &impl Fn(&Profile) -> bool,
) -> Option<Profile> {
    let q = if mirror { dof.mirrored() } else { *dof };
    let (j, a0, af, amax) = (q.jmax, q.a0, q.af, q.amax);
    let dv = q.vf - q.v0;
    // Returns (α₁, h, α₂, τ) from the free parameter.
    let levels = |x: f64| -> Option<(f64, f64, f64, f64)> {
        let (a1, h, a2, tau) = if plateau {
            let (a1, a2) = (amax, x);
            let rest = t - (2.0 * a1 - a0 - af) / j;
            let k = (2.0 * a1 * a1 - a0 * a0 - af * af) / (2.0 * j);
            let tau = (dv - k - a1 * rest) / (a2 - a1);
            (a1, rest - tau, a2, tau)
        } else {
            let a1 = x;
            let tau = t - (2.0 * a1 - a0 - af) / j;
            let a2 = (dv - (2.0 * a1 * a1 - a0 * a0 - af * af) / (2.0 * j)) / tau;
            (a1, 0.0, a2, tau)
        };
        let valid = tau >= 0.0 && h >= 0.0 && a1 >= a0 && a1 >= a2 && a2 >= af && a1 <= amax;
        valid.then_some((a1, h, a2, tau))
    };
    let start = State1 {
        p: q.p0,
        v: q.v0,
        a: a0,
    };
    let segs = |x: f64| -> Option<[(f64, f64); 5]> {
        let (a1, h, a2, tau) = levels(x)?;
        Some([
            (((a1 - a0) / j).max(0.0), j),
            (h, 0.0),
            (((a1 - a2) / j).max(0.0), -j),
            (tau, 0.0),
            (((a2 - af) / j).max(0.0), -j),
        ])
    };
    let build = |x: f64| segs(x).map(|s| segments_profile(start, &s, mirror));
    let sgn = if mirror { -1.0 } else { 1.0 };
    let f = |x: f64| segs(x).map(|s| sgn * (segments_end_p(start, &s, mirror) - dof.pf));
    first_root(peak_then_hold_cuts(&q, t, plateau), f, &build, ok)
}

/// Velocity interface, third order, in closed form and in Ruckig's order of preference (so
/// that a DOF synchronized to a longer duration makes Ruckig's motion, not just one of the
/// same duration): in the direction of the velocity change first, the shapes
/// a₀ ↗ α (hold) ↘ a_f, a₀ ↗ α (hold) ↗ a_f, a₀ (hold) ↗ a_f, then a₀ → a_f with a reduced
/// jerk followed by a hold at a_f (or a plain hold when nothing changes). The first valid
/// profile wins; `None` leaves the bracketing family ([`velocity3`]) to try.
fn velocity3_closed(dof: &Dof1, t: f64, ok: &impl Fn(&Profile) -> bool) -> Option<Profile> {
    let (a0, af) = (dof.a0, dof.af);
    let vd = dof.vf - dof.v0;
    let ad = af - a0;
    let start = State1 {
        p: dof.p0,
        v: dof.v0,
        a: a0,
    };
    // Segments (duration, jerk); None when a duration is negative or not finite.
    let build = |segs: &[(f64, f64)]| -> Option<Profile> {
        let mut pr = Profile::new(start);
        for &(d, j) in segs {
            if d.is_nan() || d < 0.0 || !pr.push(d, if d > 0.0 { j } else { 0.0 }) {
                return None;
            }
        }
        ok(&pr).then_some(pr)
    };
    let dirs = if vd > 0.0 {
        [dof.jmax, -dof.jmax]
    } else {
        [-dof.jmax, dof.jmax]
    };
    for j in dirs {
        // Up, hold, down.
        let h1 = ((-ad * ad + 2.0 * j * ((a0 + af) * t - 2.0 * vd)) / (j * j) + t * t).sqrt();
        let t0 = ad / (2.0 * j) + (t - h1) / 2.0;
        if h1 >= f64::EPSILON {
            if let r @ Some(_) = build(&[(t0, j), (h1, 0.0), (t - (t0 + h1), -j)]) {
                return r;
            }
        }
        // Up, hold, up.
        let h = -ad + j * t;
        let t0 = -ad * ad / (2.0 * j * h) + (vd - a0 * t) / h;
        let t1 = -ad / j + t;
        if t1 >= f64::EPSILON {
            if let r @ Some(_) = build(&[(t0, j), (t1, 0.0), (t - (t0 + t1), j)]) {
                return r;
            }
            // Hold, up.
            if let r @ Some(_) = build(&[(t1, 0.0), (ad / j, j)]) {
                return r;
            }
        }
        // Nothing to change: hold.
        if a0.abs() < f64::EPSILON && af.abs() < f64::EPSILON && vd.abs() < f64::EPSILON {
            if let r @ Some(_) = build(&[(t, 0.0)]) {
                return r;
            }
        }
        // A ramp with a reduced jerk to a_f, then a hold there.
        let h = 2.0 * (af * t - vd);
        let (t0, jf) = (h / ad, ad * ad / h);
        if jf.abs() < j.abs() + 1e-12 {
            if let r @ Some(_) = build(&[(t0, jf), (t - t0, 0.0)]) {
                return r;
            }
        }
    }
    None
}

/// Velocity interface, third order: a₀ → α (hold) → a_f in exactly t.
fn velocity3(dof: &Dof1, t: f64, ok: &impl Fn(&Profile) -> bool) -> Option<Profile> {
    let j = dof.jmax;
    let start = State1 {
        p: dof.p0,
        v: dof.v0,
        a: dof.a0,
    };
    let build = |al: f64| -> Option<Profile> {
        let t1 = (al - dof.a0).abs() / j;
        let t3 = (dof.af - al).abs() / j;
        let tau = t - t1 - t3;
        if tau < 0.0 {
            return None;
        }
        let mut pr = Profile::new(start);
        pr.push(t1, if al >= dof.a0 { j } else { -j });
        pr.push(tau, 0.0);
        pr.push(t3, if dof.af >= al { j } else { -j });
        Some(pr)
    };
    let f = |al: f64| build(al).map(|pr| pr.end().v - dof.vf);
    // τ ≥ 0 ⇔ |α − a₀| + |a_f − α| ≤ j·t: an explicit window around [a₀, a_f].
    let w_lo = ((dof.a0 + dof.af - j * t) / 2.0).max(dof.amin);
    let w_hi = ((dof.a0 + dof.af + j * t) / 2.0).min(dof.amax);
    first_root([w_lo, w_hi, dof.a0, dof.af, 0.0], f, &build, ok)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rest_cubic_root_is_the_bisection_root() {
        // Against plain bisection (roots_in) on seeded windows of the callers' shape: the same
        // root to a few rounding units, and the same verdict when there is none.
        let mut r = crate::rng::SplitMix64::new(41);
        let (mut found, mut none) = (0, 0);
        for _ in 0..20000 {
            let j = 10f64.powf(r.uniform(-1.0, 4.5));
            let a = r.uniform(0.2, 20.0);
            let t = 10f64.powf(r.uniform(-3.0, 1.5));
            let d = 10f64.powf(r.uniform(-9.0, 1.0));
            let sj = j.sqrt();
            let hi = (t * sj / 4.0).min(a / sj);
            let k = 2.0 / sj;
            let mut roots = [0.0; crate::roots::MAX_DEGREE];
            let n = crate::roots::roots_in(&[d, 0.0, -t, k], 0.0, hi, &mut roots);
            match rest_cubic_root(k, t, d, hi) {
                Some(x) => {
                    assert!(n == 1, "{k} {t} {d} {hi}");
                    assert!(
                        (x - roots[0]).abs() <= 8.0 * f64::EPSILON * x,
                        "{x} vs {} ({k} {t} {d} {hi})",
                        roots[0]
                    );
                    found += 1;
                }
                None => {
                    assert_eq!(n, 0, "{k} {t} {d} {hi}");
                    none += 1;
                }
            }
        }
        assert!(found > 2000 && none > 2000, "{found} {none}");
        // Outside the regular case (D = 0) the bisection path answers.
        assert_eq!(rest_cubic_root(1.0, 1.0, 0.0, 0.25), Some(0.0));
    }

    #[test]
    fn the_end_position_without_a_profile_is_the_profiles_bit_for_bit() {
        // Seeded segment lists like the bracketed families' (five at most), with zero,
        // negative and non-finite durations (which the profile leaves out), both mirrors.
        let mut r = crate::rng::SplitMix64::new(16);
        for _ in 0..20000 {
            let start = State1 {
                p: r.uniform(-5.0, 5.0),
                v: r.uniform(-3.0, 3.0),
                a: r.uniform(-20.0, 20.0),
            };
            let n = 1 + (r.next_u64() % 5) as usize;
            let mut segs = [(0.0, 0.0); 5];
            for s in &mut segs[..n] {
                let d = match r.next_u64() % 8 {
                    0 => 0.0,
                    1 => -r.uniform(0.0, 0.1),
                    2 => f64::NAN,
                    3 => f64::INFINITY,
                    _ => 10f64.powf(r.uniform(-9.0, 0.0)),
                };
                *s = (
                    d,
                    r.uniform(-1.0, 1.0).signum() * 10f64.powf(r.uniform(2.0, 4.0)),
                );
            }
            for mirror in [false, true] {
                let want = segments_profile(start, &segs[..n], mirror).end().p;
                let got = segments_end_p(start, &segs[..n], mirror);
                assert_eq!(got.to_bits(), want.to_bits(), "{start:?} {segs:?} {mirror}");
            }
        }
    }

    #[test]
    fn rest_to_rest_closed_form_hits_both_cases() {
        let ok = |pr: &Profile| pr.duration() > 0.0;
        let mut pr = Profile::default();
        // Plateau: a²/j = 0.25 < v_c.
        let d = Dof1::rest_to_rest(0.0, 1.0, 0.6, 1.0, 4.0);
        assert!(rest_to_rest(&d, 3.0, &ok, &mut pr));
        assert!((pr.duration() - 3.0).abs() < 1e-12 && (pr.end().p - 1.0).abs() < 1e-12);
        assert!(verify(&d, &pr));
        // No plateau: large jerk limit... small: a²/j = 1/0.5 = 2 > v_c.
        let d = Dof1::rest_to_rest(0.0, -0.3, 1.0, 1.0, 0.5);
        assert!(rest_to_rest(&d, 6.0, &ok, &mut pr));
        assert!((pr.duration() - 6.0).abs() < 1e-12 && (pr.end().p + 0.3).abs() < 1e-12);
        assert!(verify(&d, &pr));
        // Second order.
        let d = Dof1::rest_to_rest(1.0, 2.0, 1.0, 1.0, f64::INFINITY);
        assert!(rest_to_rest(&d, 4.0, &ok, &mut pr));
        assert!((pr.duration() - 4.0).abs() < 1e-12 && (pr.end().p - 2.0).abs() < 1e-12);
        // Not rest-to-rest: not this path.
        let mut d = Dof1::rest_to_rest(0.0, 1.0, 1.0, 1.0, 1.0);
        d.v0 = 0.1;
        assert!(!rest_to_rest(&d, 5.0, &ok, &mut pr));
        assert!(step2(&d, 5.0).is_some());
    }
}
