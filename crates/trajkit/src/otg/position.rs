//! Position limits (Ruckig Pro's `min_position`/`max_position`): the motion of a degree of
//! freedom stays within [p_min, p_max] along the whole trajectory.
//!
//! **How it is guaranteed.** Every profile of a DOF with a finite position limit passes, on
//! top of the usual verification, a check of its exact position extrema (segment boundaries
//! and the interior zeros of the velocity, [`super::Profile::position_extrema`]) against the
//! limits; nothing is sampled. A profile that fails is never used. The brake pre-profile is
//! checked too (a start that cannot be braked inside the limits is an error), and so is the
//! constant-acceleration continuation of a DOF that finishes before the others.
//!
//! **Time-optimal when the limits are not in the way.** Step 1 runs as usual (without the
//! limits); when its fastest profile stays inside, it is the result (the unconstrained
//! optimum, so the duration is the same as without position limits), at the cost of one
//! extrema check (and, when the synchronization search asks for candidate durations, the
//! waiting threshold below).
//!
//! **When they are in the way** (the unconstrained optimum overshoots), any valid motion
//! either stays strictly inside or touches a limit. Strictly inside, it is an extremal of the
//! unconstrained problem, i.e. one of step 1's candidate profiles: the fastest candidate
//! inside the limits is kept. Touching the upper limit at time t_c, the state there is
//! (p_max, 0, a_c) with a_c ≤ 0 (a maximum of the position; the lower limit mirrored), and
//! the motion splits into two state-to-state problems, start → (p_max, 0, a_c) and
//! (p_max, 0, a_c) → target, each of which step 1 solves exactly. The fastest motion through
//! that contact is the best over a_c of the sum of the two minima: for second order a_c does
//! not exist (the contact is at rest) and the result is exact; for third order a_c is found by
//! a 1-D search (9 samples of its admissible range, then 24 golden-section steps around the
//! best sample), so the duration is optimal up to that search, and the legs' own candidates
//! are restricted to the limits. Motions that would need two contacts (one per limit) are
//! not searched: the legs are solved with the limits in their verification, so such a case
//! ends with the best single-contact or inside motion, or with
//! [`super::OtgError::PositionLimits`].
//!
//! **Longer durations** (synchronization): the step-2 families are tried with the position
//! check; when none fits, a waiting profile — stop (where the fastest stop lands, or at rest
//! on a limit), wait, go — takes any duration from its two legs' sum on. That sum is added to
//! the DOF's candidate durations, so the synchronization search always finds a duration.
//!
//! Size: a contact or waiting profile is two legs of up to 7 segments each (and a wait); one
//! that does not fit in [`super::MAX_SEGMENTS`] together with its brake is not used (the
//! profile size is kept for the speed of the unlimited path), so after a long brake such a
//! motion may be refused with `PositionLimits` although it exists.
//!
//! Precision: positions within the limits to 1e-12 of the motion's position scale (the
//! largest of |p₀|, |p_f|, the finite limits' magnitudes and the motion's extent); the
//! rest of the contract as for every profile. The contact search costs a few dozen step-1
//! solves, only for DOFs whose unconstrained optimum leaves the limits.

use super::brake::brake;
use super::problem::{Dof1, ProfileOrder};
use super::profile::{Profile, State1};
use super::step1::{positions_within, step1_run, verify, MAX_CANDIDATES};
use super::velocity_change::{fastest, push_change};

/// Step 1 for a DOF with a finite position limit (see the module documentation); the same
/// contract as the step-1 entry points.
#[cold]
pub(crate) fn step1_limited(
    dof: &Dof1,
    profile: &mut Profile,
    spare: &mut Option<Profile>,
    mut cand: Option<&mut [f64; MAX_CANDIDATES]>,
) -> Option<usize> {
    // A brake that leaves the limits cannot be helped.
    after_brake(dof)?;
    // The unconstrained optimum: when it stays inside, it is the result (time-optimal), and
    // one step-1 solve and one extrema check is all a DOF whose limits are out of the way
    // costs.
    let mut n = step1_run(
        &dof.without_position_limits(),
        profile,
        spare,
        cand.as_deref_mut(),
    );
    let t_free = n.map(|_| profile.duration());
    if n.is_some() && positions_within(dof, profile) {
        return with_wait_candidate(dof, n, cand);
    }
    // Candidates inside the limits (verification checks the positions).
    n = step1_run(dof, profile, spare, cand.as_deref_mut());
    let t_inside = n.map(|_| profile.duration());
    let optimal = matches!((t_inside, t_free), (Some(a), Some(b)) if a <= b * (1.0 + 1e-12));
    if !optimal {
        if let Some(c) = contact_profile(dof) {
            if t_inside.is_none_or(|t| c.duration() < t) {
                *profile = c;
                n = Some(match cand.as_deref_mut() {
                    Some(cs) => {
                        let k = n.unwrap_or(0).min(MAX_CANDIDATES - 1);
                        cs[k] = c.duration();
                        k + 1
                    }
                    None => 0,
                });
            }
        }
    }
    with_wait_candidate(dof, n, cand)
}

/// Every duration from the waiting threshold on is feasible: with candidates requested, it
/// joins the `n` candidate durations (for the synchronization search).
fn with_wait_candidate(
    dof: &Dof1,
    n: Option<usize>,
    cand: Option<&mut [f64; MAX_CANDIDATES]>,
) -> Option<usize> {
    if let (Some(k), Some(cs)) = (n, cand) {
        if let Some(w) = wait_threshold(dof) {
            if k < MAX_CANDIDATES && !cs[..k].contains(&w) {
                cs[k] = w;
                return Some(k + 1);
            }
        }
    }
    n
}

/// The brake pre-profile of `dof` and the problem that follows it; `None` when the brake
/// leaves the position limits.
fn after_brake(dof: &Dof1) -> Option<(Profile, Dof1)> {
    let mut b = Profile::new(State1 {
        p: dof.p0,
        v: dof.v0,
        a: dof.a0,
    });
    brake(dof, &mut b);
    if b.segments() > 0 && !positions_within(dof, &b) {
        return None;
    }
    let e = b.end();
    let mut main = *dof;
    (main.p0, main.v0, main.a0) = (e.p, e.v, e.a);
    Some((b, main))
}

/// The largest |a_c| of a contact state (p_lim, 0, a_c): within the acceleration limit of
/// its sign, reachable with zero velocity from inside the velocity limits, and a safe start
/// (no brake) for the leg that leaves it: a_c²/(2j) within both velocity limits.
fn contact_acceleration_range(d: &Dof1, side: f64) -> f64 {
    if d.order() != ProfileOrder::Third {
        return 0.0;
    }
    let a = if side > 0.0 { -d.amin } else { d.amax };
    let v = d.vmax.min(-d.vmin);
    a.min((2.0 * d.jmax * v).sqrt()) * (1.0 - 1e-9)
}

/// The two legs through the contact state (p_lim, 0, a_c) in `legs`; their total duration,
/// or `None` when either has no profile inside the limits (or the second would need a brake).
fn legs_through(
    main: &Dof1,
    p_lim: f64,
    a_c: f64,
    legs: &mut [Profile; 2],
    spare: &mut Option<Profile>,
) -> Option<f64> {
    let first = Dof1 {
        pf: p_lim,
        vf: 0.0,
        af: a_c,
        ..*main
    };
    step1_run(&first, &mut legs[0], spare, None)?;
    let e = legs[0].end();
    let second = Dof1 {
        p0: e.p,
        v0: e.v,
        a0: e.a,
        ..*main
    };
    step1_run(&second, &mut legs[1], spare, None)?;
    (legs[1].brake_duration() == 0.0).then(|| legs[0].duration() + legs[1].duration())
}

/// The fastest motion of `dof` that touches one of its finite position limits (brake
/// included), verified as a whole; `None` when there is none.
fn contact_profile(dof: &Dof1) -> Option<Profile> {
    let (brake_pr, main) = after_brake(dof)?;
    let mut legs = [Profile::default(), Profile::default()];
    let mut spare = None;
    let mut best: Option<(f64, f64, f64)> = None; // (duration, p_lim, a_c)
    for (side, p_lim) in [(1.0, main.pmax), (-1.0, main.pmin)] {
        if !p_lim.is_finite() {
            continue;
        }
        let range = contact_acceleration_range(&main, side);
        let mut eval = |x: f64| {
            let a_c = -side * x;
            legs_through(&main, p_lim, a_c, &mut legs, &mut spare).unwrap_or(f64::INFINITY)
        };
        let (x, t) = minimize(&mut eval, range);
        if t.is_finite() && best.is_none_or(|b| t < b.0) {
            best = Some((t, p_lim, -side * x));
        }
    }
    let (_, p_lim, a_c) = best?;
    legs_through(&main, p_lim, a_c, &mut legs, &mut spare)?;
    // The two legs as one main profile, verified as a whole, after the brake.
    let mut m = legs[0];
    let mut pr = brake_pr;
    (m.append(&legs[1]) && verify(&main, &m) && pr.append(&m)).then_some(pr)
}

/// Minimizes `f` over [0, `range`]: 9 samples, then golden-section steps around the best
/// sample. Returns the argument and value of the best evaluation.
fn minimize(f: &mut impl FnMut(f64) -> f64, range: f64) -> (f64, f64) {
    if range <= 0.0 {
        return (0.0, f(0.0));
    }
    const SAMPLES: usize = 9;
    let mut best = (0.0, f64::INFINITY);
    let mut vals = [f64::INFINITY; SAMPLES];
    for (k, v) in vals.iter_mut().enumerate() {
        let x = range * k as f64 / (SAMPLES - 1) as f64;
        *v = f(x);
        if *v < best.1 {
            best = (x, *v);
        }
    }
    if !best.1.is_finite() {
        return best;
    }
    let k = (best.0 / range * (SAMPLES - 1) as f64).round() as usize;
    let h = range / (SAMPLES - 1) as f64;
    let (mut a, mut b) = (
        (k as f64 - 1.0).max(0.0) * h,
        ((k + 1) as f64 * h).min(range),
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..24 {
        for (x, v) in [(c, fc), (d, fd)] {
            if v < best.1 {
                best = (x, v);
            }
        }
        if fc <= fd {
            (b, d, fd) = (d, c, fc);
            c = b - g * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    for (x, v) in [(c, fc), (d, fd)] {
        if v < best.1 {
            best = (x, v);
        }
    }
    best
}

/// The smallest duration from which `dof` has a waiting profile (stop, wait, go), brake
/// included; `None` when it has none inside the limits.
pub(crate) fn wait_threshold(dof: &Dof1) -> Option<f64> {
    let (b, main) = after_brake(dof)?;
    let mut legs = [Profile::default(), Profile::default()];
    waiting_legs(&main, f64::INFINITY, &mut legs).map(|t| t + b.duration())
}

/// The legs of the first waiting profile of `main` (no brake) whose legs last at most `t`
/// together: stop where the fastest stop lands, or at rest on a finite position limit; their
/// total duration.
fn waiting_legs(main: &Dof1, t: f64, legs: &mut [Profile; 2]) -> Option<f64> {
    let mut spare = None;
    let mut best: Option<f64> = None;
    // Stop where the fastest change to rest lands.
    let order = main.order();
    if let Some(c) = fastest(
        order, main.v0, main.a0, 0.0, 0.0, main.jmax, main.amax, main.amin,
    ) {
        let mut stop = Profile::new(State1 {
            p: main.p0,
            v: main.v0,
            a: main.a0,
        });
        push_change(&mut stop, order, &c, main.v0);
        stop.snap(0.0, 0.0);
        let e = stop.end();
        let go = Dof1 {
            p0: e.p,
            v0: 0.0,
            a0: 0.0,
            ..*main
        };
        let mut go_pr = Profile::default();
        if positions_within(main, &stop) && step1_run(&go, &mut go_pr, &mut spare, None).is_some() {
            let total = stop.duration() + go_pr.duration();
            if total <= t {
                legs[0] = stop;
                legs[1] = go_pr;
                best = Some(total);
            }
        }
    }
    if best.is_some() {
        return best;
    }
    // Stop at rest on a limit.
    for p_lim in [main.pmax, main.pmin] {
        if p_lim.is_finite() {
            if let Some(total) = legs_through(main, p_lim, 0.0, legs, &mut spare) {
                if total <= t {
                    return Some(total);
                }
            }
        }
    }
    None
}

/// Step 2's last resort for a DOF with a finite position limit (after the brake): a waiting
/// profile of duration `t` into `out`; false when there is none.
#[cold]
pub(crate) fn wait_into(main: &Dof1, t: f64, out: &mut Profile) -> bool {
    let mut legs = [Profile::default(), Profile::default()];
    let Some(total) = waiting_legs(main, t, &mut legs) else {
        return false;
    };
    // The wait at rest (exactly: the first leg ends at rest to round-off).
    *out = legs[0];
    if !(out.push_with(t - total, 0.0, 0.0, 0.0) && out.append(&legs[1])) {
        return false;
    }
    verify(main, out) && (out.duration() - t).abs() <= 1e-12 * t.max(1.0)
}

/// Whether a DOF whose profile `pr` ends before the trajectory's end `t_end` stays within
/// its position limits while it continues with constant acceleration until then. A profile
/// that ends within round-off of `t_end` (a synchronized one: its duration and the common
/// one agree to 1e-12 relative) does not continue.
pub(crate) fn continuation_within(dof: &Dof1, pr: &Profile, t_end: f64) -> bool {
    let t0 = pr.duration();
    if !dof.has_position_limits() || t_end - t0 <= 1e-12 * t_end.max(1.0) {
        return true;
    }
    let mut tail = Profile::new(pr.end());
    let e = pr.end();
    tail.push_with(t_end - t0, e.v, e.a, 0.0);
    positions_within(dof, &tail)
}
