//! The fastest change of velocity (and acceleration), the building block of every profile.
//!
//! Third order: from (v₀, a₀) to (v₁, a₁) under jerk limit J and acceleration limits
//! [a_min, a_max], the fastest motion ramps the acceleration to a peak α with jerk ±J and back
//! down to a₁ with ∓J, holding α = a_max (or a_min) in between when the peak would exceed it.
//! The peak follows in closed form from the velocity change: α² = ±J·Δv + (a₀² + a₁²)/2.
//! Second order: one constant-acceleration segment. First order: an instantaneous jump.
//!
//! Precision: durations are closed-form; negative round-off (≥ −1e−12 relative) is clamped to 0.

use super::problem::{Dof1, ProfileOrder};
use super::profile::{Profile, State1};

/// A velocity change of at most three segments: durations and jerks (third order), or one
/// constant-acceleration segment (second order, `accel` set).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct VelChange {
    /// Segment durations.
    pub d: [f64; 3],
    /// Segment jerks (third order).
    pub j: [f64; 3],
    /// Constant acceleration of the single segment (second order).
    pub accel: f64,
    /// Total duration.
    pub t: f64,
    /// Displacement during the change.
    pub dist: f64,
}

/// Fastest velocity change for the given order; `None` when no such change exists (e.g. the
/// start acceleration is outside the limits).
#[inline]
pub(crate) fn fastest(
    order: ProfileOrder,
    va: f64,
    aa: f64,
    vb: f64,
    ab: f64,
    j: f64,
    amax: f64,
    amin: f64,
) -> Option<VelChange> {
    match order {
        ProfileOrder::Third => fastest3(va, aa, vb, ab, j, amax, amin),
        ProfileOrder::Second => {
            let dv = vb - va;
            let a = if dv >= 0.0 { amax } else { amin };
            let t = if dv == 0.0 { 0.0 } else { dv / a };
            Some(VelChange {
                d: [t, 0.0, 0.0],
                j: [0.0; 3],
                accel: a,
                t,
                dist: (va + vb) / 2.0 * t,
            })
        }
        ProfileOrder::First => Some(VelChange::default()),
    }
}

/// Third-order fastest change from (va, aa) to (vb, ab).
pub(crate) fn fastest3(
    va: f64,
    aa: f64,
    vb: f64,
    ab: f64,
    j: f64,
    amax: f64,
    amin: f64,
) -> Option<VelChange> {
    // Both shapes (ramp up then down, or down then up) can be valid; the faster one wins.
    // (Each with the root of its peak's equation that lies beyond both ends: the other roots
    // of [`each_change3`] are never faster.)
    let up = up_down(va, aa, vb, ab, j, amax, true);
    let down = up_down(-va, -aa, -vb, -ab, j, -amin, true).map(|c| c.mirrored());
    match (up, down) {
        (Some(u), Some(d)) => Some(if d.t < u.t { d } else { u }),
        (u, d) => u.or(d),
    }
}

/// Every third-order two-ramp change from (va, aa) to (vb, ab): ramp up then down (peak
/// α ≥ a₀, a₁, α² = J·Δv + (a₀² + a₁²)/2) and down then up (valley), each with either root of
/// its quadratic that lies beyond both ends (the positive peak held at a_max when it exceeds
/// it). The fastest is [`fastest3`]'s; the others are the edges of the durations a velocity-
/// interface DOF cannot take (its blocked intervals), as in Ruckig's velocity step 1.
pub(crate) fn each_change3(
    va: f64,
    aa: f64,
    vb: f64,
    ab: f64,
    j: f64,
    amax: f64,
    amin: f64,
    mut f: impl FnMut(VelChange),
) {
    for main in [true, false] {
        if let Some(c) = up_down(va, aa, vb, ab, j, amax, main) {
            f(c);
        }
        if let Some(c) = up_down(-va, -aa, -vb, -ab, j, -amin, main) {
            f(c.mirrored());
        }
    }
}

/// The change that ramps the acceleration up with jerk J to a peak α ≥ a₀, a₁ and down to a₁
/// (held at `amax` in between when the peak exceeds it). `main`: the positive root of the
/// peak's quadratic (the only one that can exceed `amax`); otherwise the negative one, taken
/// only when it is below `amax` and distinct. The down-then-up shape is this one mirrored.
#[inline(always)]
fn up_down(va: f64, aa: f64, vb: f64, ab: f64, j: f64, amax: f64, main: bool) -> Option<VelChange> {
    let dv = vb - va;
    let base = (aa * aa + ab * ab) / 2.0;
    // The tolerance (a square root) only matters near the edges of the shape: computed when a
    // comparison is not settled without it.
    let tol = || 1e-12 * (aa.abs() + ab.abs() + (j * dv.abs()).sqrt()) + 1e-300;
    let ru = j * dv + base;
    if !(ru >= 0.0 || ru >= -tol() * tol()) {
        return None;
    }
    let root = ru.max(0.0).sqrt();
    let alpha = if main { root } else { -root };
    let hi = aa.max(ab);
    if !(alpha >= hi || alpha >= hi - tol()) || (!main && (root == 0.0 || alpha > amax)) {
        return None;
    }
    let alpha = alpha.max(hi);
    if alpha <= amax {
        Some(build(
            va,
            aa,
            [(alpha - aa) / j, 0.0, (alpha - ab) / j],
            [j, 0.0, -j],
        ))
    } else if aa <= amax * (1.0 + 1e-12) && ab <= amax * (1.0 + 1e-12) {
        let tau = (dv - (2.0 * amax * amax - aa * aa - ab * ab) / (2.0 * j)) / amax;
        Some(build(
            va,
            aa,
            [(amax - aa) / j, tau, (amax - ab) / j],
            [j, 0.0, -j],
        ))
    } else {
        None
    }
}

impl VelChange {
    /// The same change for negated velocities and accelerations.
    #[inline(always)]
    fn mirrored(self) -> VelChange {
        VelChange {
            d: self.d,
            // (0 − x: a zero stays +0.)
            j: [-self.j[0], 0.0 - self.j[1], -self.j[2]],
            accel: 0.0 - self.accel,
            t: self.t,
            dist: -self.dist,
        }
    }
}

#[inline]
fn build(va: f64, aa: f64, d: [f64; 3], jk: [f64; 3]) -> VelChange {
    let d = [d[0].max(0.0), d[1].max(0.0), d[2].max(0.0)];
    let (mut p, mut v, mut a) = (0.0, va, aa);
    for k in 0..3 {
        (p, v, a) = super::profile::integrate(p, v, a, jk[k], d[k]);
    }
    let _ = (v, a);
    VelChange {
        d,
        j: jk,
        accel: 0.0,
        t: d[0] + d[1] + d[2],
        dist: p,
    }
}

/// Appends a velocity change to a profile.
pub(crate) fn push_change(pr: &mut Profile, order: ProfileOrder, c: &VelChange, va: f64) {
    match order {
        ProfileOrder::Third => {
            for k in 0..3 {
                pr.push(c.d[k], c.j[k]);
            }
        }
        ProfileOrder::Second => {
            if c.t > 0.0 {
                pr.push_with(c.t, va, c.accel, 0.0);
            }
        }
        ProfileOrder::First => {}
    }
}

/// The velocity where the fastest change from (v, a) to zero acceleration lands (`dir` = 1),
/// or from which it reaches (v, a) (`dir` = −1).
pub(crate) fn kink(order: ProfileOrder, v: f64, a: f64, j: f64, dir: f64) -> f64 {
    match order {
        ProfileOrder::Third => v + dir * a * a.abs() / (2.0 * j),
        _ => v,
    }
}

/// The profile of `dof` through velocity `vc`: from its start state the fastest change `c1` to
/// (v_c, 0), a cruise of `tau` seconds (none when `None`), then the fastest change `c2` to the
/// target (second order ends with its final velocity set exactly). The shape of the peak and
/// cruise families of step 1 and of step 2's bracketed cruise.
pub(crate) fn via_velocity(
    dof: &Dof1,
    order: ProfileOrder,
    c1: &VelChange,
    vc: f64,
    tau: Option<f64>,
    c2: &VelChange,
) -> Profile {
    let mut pr = Profile::new(State1 {
        p: dof.p0,
        v: dof.v0,
        a: dof.a0,
    });
    push_change(&mut pr, order, c1, dof.v0);
    match tau {
        Some(tau) => {
            pr.push_cruise(tau, vc);
        }
        None => pr.snap(vc, 0.0),
    }
    push_change(&mut pr, order, c2, vc);
    if order == ProfileOrder::Second {
        pr.set_final(dof.vf, 0.0);
    }
    pr
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_two_ramp_change_arrives_and_the_fastest_is_fastest3() {
        // Seeded: each change of `each_change3` reaches (v_b, a_b) inside the acceleration
        // limits, and none is faster than `fastest3`'s (which is one of them).
        let mut r = crate::rng::SplitMix64::new(16);
        let (mut extra, mut cases) = (0, 0);
        for _ in 0..20000 {
            let j = 10f64.powf(r.uniform(-1.0, 2.0));
            let (amax, amin) = (r.uniform(0.1, 5.0), -r.uniform(0.1, 5.0));
            let (aa, ab) = (r.uniform(amin, amax), r.uniform(amin, amax));
            let (va, vb) = (r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0));
            let best = fastest3(va, aa, vb, ab, j, amax, amin);
            let mut n = 0usize;
            each_change3(va, aa, vb, ab, j, amax, amin, |c| {
                let (mut p, mut v, mut a) = (0.0, va, aa);
                for k in 0..3 {
                    (p, v, a) = crate::otg::profile::integrate(p, v, a, c.j[k], c.d[k]);
                    assert!(a <= amax * (1.0 + 1e-9) && a >= amin * (1.0 + 1e-9));
                }
                let sv = 1.0 + j * c.t;
                assert!((v - vb).abs() <= 1e-9 * sv, "{va} {aa} {vb} {ab} {j}: {v}");
                assert!((a - ab).abs() <= 1e-9 * (1.0 + amax - amin));
                assert!((p - c.dist).abs() <= 1e-9 * (1.0 + c.t));
                let b = best.expect("a change exists, so the fastest does");
                assert!(b.t <= c.t * (1.0 + 1e-12), "{} > {}", b.t, c.t);
                n += 1;
            });
            assert_eq!(n > 0, best.is_some());
            extra += n.saturating_sub(2);
            cases += 1;
        }
        // The negative roots do occur (the blocked-interval edges of the velocity interface).
        assert!(extra > 100, "{extra} of {cases}");
    }

    #[test]
    fn reaches_the_target_velocity() {
        for &(va, aa, vb, ab) in &[
            (0.0, 0.0, 1.0, 0.0),
            (0.0, 0.5, 0.01, 0.0),
            (1.0, 0.0, -2.0, 0.3),
            (0.3, -0.2, 0.3, -0.2),
            (0.0, 0.0, 100.0, 0.0),
        ] {
            let c = fastest3(va, aa, vb, ab, 2.0, 1.0, -1.5).unwrap();
            let (mut p, mut v, mut a) = (0.0, va, aa);
            for k in 0..3 {
                (p, v, a) = crate::otg::profile::integrate(p, v, a, c.j[k], c.d[k]);
            }
            assert!((v - vb).abs() < 1e-12, "{va} {aa} {vb} {ab}: v {v}");
            assert!((a - ab).abs() < 1e-12);
            assert!((p - c.dist).abs() < 1e-12);
        }
    }
}
