//! Certification between gridpoints: the exact worst value of every joint limit on every
//! middle interval, and where it is.
//!
//! Inside a middle interval (which lies inside one smooth piece of the path: the grid holds
//! the path's breakpoints) with δ = s − s_i:
//! x(δ) = x_i + 2u_iδ + v_iδ², u(δ) = u_i + v_iδ and, for a path that is a cubic polynomial
//! there, σ′ = a + bδ + cδ²/2, σ″ = b + cδ, σ‴ = c. Then
//! - q̇ = σ′·√x has its extrema where 2σ″x + σ′x′ = 0 (a cubic),
//! - q̈ = σ″x + σ′u is a cubic, extrema where its derivative (a quadratic) vanishes,
//! - q⃛ = √x·g with g = σ‴x + 3σ″u + σ′v (a quadratic) has its extrema where
//!   x′g + 2xg′ = 0 (a cubic),
//!
//! so the largest and smallest values are found exactly at the interval's ends and the real
//! roots of these polynomials ([`crate::poly::roots::roots_in`]). Whether the path is such a
//! cubic is checked per interval: the Taylor cubic from s_i must reproduce σ′, σ″ at s_{i+1}
//! and σ‴ at the midpoint to 1e-9 relative. Where it does not (a path of higher degree or not
//! polynomial), and for constraints given as rows (torque, user constraints), the interval is
//! sampled at [`SAMPLES`] interior points instead, each checked exactly.

use crate::poly::roots::{horner, roots_in, MAX_DEGREE};

/// Interior samples per interval for constraints checked by sampling.
pub(crate) const SAMPLES: usize = 16;

/// The worst relative excess found on one interval and where.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Excess {
    /// (value − limit)/limit, the largest over joints and limits (≤ 0 when all hold).
    pub(crate) ratio: f64,
    /// δ where it occurs.
    pub(crate) delta: f64,
}

/// Polynomial product (lowest order first), into a fixed array; returns the length.
fn mul(a: &[f64], b: &[f64], out: &mut [f64; 8]) -> usize {
    let len = a.len() + b.len() - 1;
    out[..len].iter_mut().for_each(|v| *v = 0.0);
    for (i, &ai) in a.iter().enumerate() {
        for (j, &bj) in b.iter().enumerate() {
            out[i + j] += ai * bj;
        }
    }
    len
}

/// Relative excess of `value` over the directional range `[lo, hi]` (limits ≥ 0 ≥ lo).
#[inline]
pub(crate) fn excess(value: f64, lo: f64, hi: f64) -> f64 {
    if value > 0.0 {
        if hi.is_finite() {
            if hi > 0.0 {
                value / hi - 1.0
            } else {
                f64::INFINITY
            }
        } else {
            -1.0
        }
    } else if value < 0.0 {
        if lo.is_finite() {
            if lo < 0.0 {
                value / lo - 1.0
            } else {
                f64::INFINITY
            }
        } else {
            -1.0
        }
    } else {
        -1.0
    }
}

/// Joint limits of one joint: velocity, acceleration range, jerk.
#[derive(Debug, Clone, Copy)]
pub(crate) struct JointRange {
    pub(crate) v: (f64, f64),
    pub(crate) a: (f64, f64),
    pub(crate) j: f64,
}

/// The interval's state: x_i, u_i, v_i and its length.
#[derive(Debug, Clone, Copy)]
pub(crate) struct IntervalState {
    pub(crate) x: f64,
    pub(crate) u: f64,
    pub(crate) v: f64,
    pub(crate) len: f64,
}

impl IntervalState {
    #[inline]
    pub(crate) fn x_at(&self, d: f64) -> f64 {
        self.x + 2.0 * self.u * d + self.v * d * d
    }
    #[inline]
    pub(crate) fn u_at(&self, d: f64) -> f64 {
        self.u + self.v * d
    }
}

/// Worst excess of the joint limits of one joint on a cubic interval, with σ′(δ) =
/// a + bδ + cδ²/2 (a, b, c = σ′, σ″, σ‴ at the interval's start).
pub(crate) fn cubic_joint(st: &IntervalState, a: f64, b: f64, c: f64, lim: &JointRange) -> Excess {
    let d = st.len;
    let xp = [st.x, 2.0 * st.u, st.v];
    let xd = [2.0 * st.u, 2.0 * st.v];
    let up = [st.u, st.v];
    let p1 = [a, b, 0.5 * c];
    let p2 = [b, c];
    let mut best = Excess {
        ratio: f64::NEG_INFINITY,
        delta: 0.0,
    };
    let mut consider = |r: f64, at: f64| {
        if r > best.ratio || r.is_nan() {
            best = Excess {
                ratio: if r.is_nan() { f64::INFINITY } else { r },
                delta: at,
            };
        }
    };
    let mut roots = [0.0; MAX_DEGREE];
    let (mut t1, mut t2) = ([0.0; 8], [0.0; 8]);
    // Velocity: f = σ′√x, critical points 2σ″x + σ′x′ = 0.
    if lim.v.0.is_finite() || lim.v.1.is_finite() {
        let l1 = mul(&p2, &xp, &mut t1);
        let l2 = mul(&p1, &xd, &mut t2);
        let mut crit = [0.0; 4];
        for k in 0..l1.max(l2) {
            crit[k] = 2.0 * if k < l1 { t1[k] } else { 0.0 } + if k < l2 { t2[k] } else { 0.0 };
        }
        let nr = roots_in(&crit[..l1.max(l2)], 0.0, d, &mut roots);
        let f = |z: f64| horner(&p1, z) * st.x_at(z).max(0.0).sqrt();
        for &z in roots[..nr].iter().chain([0.0, d].iter()) {
            consider(excess(f(z), lim.v.0, lim.v.1), z);
        }
    }
    // Acceleration: σ″x + σ′u (cubic).
    if lim.a.0.is_finite() || lim.a.1.is_finite() {
        let l1 = mul(&p2, &xp, &mut t1);
        let l2 = mul(&p1, &up, &mut t2);
        let mut acc = [0.0; 4];
        for k in 0..l1.max(l2) {
            acc[k] = if k < l1 { t1[k] } else { 0.0 } + if k < l2 { t2[k] } else { 0.0 };
        }
        let dacc = [acc[1], 2.0 * acc[2], 3.0 * acc[3]];
        let nr = roots_in(&dacc, 0.0, d, &mut roots);
        for &z in roots[..nr].iter().chain([0.0, d].iter()) {
            consider(excess(horner(&acc, z), lim.a.0, lim.a.1), z);
        }
    }
    // Jerk: √x·g, g = σ‴x + 3σ″u + σ′v; critical points x′g + 2xg′ = 0.
    if lim.j.is_finite() {
        let l1 = mul(&p2, &up, &mut t1);
        let mut g = [0.0; 3];
        for k in 0..3 {
            g[k] = c * xp[k] + 3.0 * if k < l1 { t1[k] } else { 0.0 } + p1[k] * st.v;
        }
        let dg = [g[1], 2.0 * g[2]];
        let l1 = mul(&xd, &g, &mut t1);
        let l2 = mul(&xp, &dg, &mut t2);
        let mut crit = [0.0; 4];
        for k in 0..l1.max(l2) {
            crit[k] = if k < l1 { t1[k] } else { 0.0 } + 2.0 * if k < l2 { t2[k] } else { 0.0 };
        }
        let nr = roots_in(&crit[..l1.max(l2)], 0.0, d, &mut roots);
        for &z in roots[..nr].iter().chain([0.0, d].iter()) {
            let val = st.x_at(z).max(0.0).sqrt() * horner(&g, z);
            consider(excess(val, -lim.j, lim.j), z);
        }
    }
    best
}

/// Worst excess of one joint's limits at a single point with derivatives d1, d2, d3 and state
/// (x, u, s⃛/ṡ = v).
pub(crate) fn point_joint(
    x: f64,
    u: f64,
    v: f64,
    d1: f64,
    d2: f64,
    d3: f64,
    lim: &JointRange,
) -> f64 {
    let sd = x.max(0.0).sqrt();
    let e1 = excess(d1 * sd, lim.v.0, lim.v.1);
    let e2 = excess(d2 * x + d1 * u, lim.a.0, lim.a.1);
    let e3 = if lim.j.is_finite() {
        excess(sd * (d3 * x + 3.0 * d2 * u + d1 * v), -lim.j, lim.j)
    } else {
        -1.0
    };
    e1.max(e2).max(e3)
}

/// The smallest x on the interval (x is a quadratic in δ) and where.
pub(crate) fn min_x(st: &IntervalState) -> (f64, f64) {
    let d = st.len;
    let mut best = (st.x, 0.0);
    let x1 = st.x_at(d);
    if x1 < best.0 {
        best = (x1, d);
    }
    if st.v > 0.0 {
        let z = -st.u / st.v;
        if z > 0.0 && z < d {
            let xz = st.x_at(z);
            if xz < best.0 {
                best = (xz, z);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_extrema_match_dense_sampling() {
        let mut rng = crate::rng::SplitMix64::new(11);
        for _ in 0..500 {
            let st = IntervalState {
                x: rng.uniform(0.1, 2.0),
                u: rng.uniform(-2.0, 2.0),
                v: rng.uniform(-20.0, 20.0),
                len: rng.uniform(0.01, 0.2),
            };
            if min_x(&st).0 < 0.01 {
                continue;
            }
            let (a, b, c) = (
                rng.uniform(-2.0, 2.0),
                rng.uniform(-5.0, 5.0),
                rng.uniform(-50.0, 50.0),
            );
            let lim = JointRange {
                v: (-rng.uniform(0.5, 2.0), rng.uniform(0.5, 2.0)),
                a: (-rng.uniform(1.0, 5.0), rng.uniform(1.0, 5.0)),
                j: rng.uniform(10.0, 100.0),
            };
            let exact = cubic_joint(&st, a, b, c, &lim);
            let mut dense = f64::NEG_INFINITY;
            for k in 0..=20000 {
                let z = st.len * k as f64 / 20000.0;
                let (d1, d2) = (a + b * z + 0.5 * c * z * z, b + c * z);
                dense = dense.max(point_joint(st.x_at(z), st.u_at(z), st.v, d1, d2, c, &lim));
            }
            // Exact is the true maximum: at least the dense one, and not above it by more than
            // the dense grid's resolution allows.
            assert!(exact.ratio >= dense - 1e-12, "{} < {dense}", exact.ratio);
            assert!(
                exact.ratio <= dense + 1e-6 * (1.0 + dense.abs()),
                "{} > {dense}",
                exact.ratio
            );
        }
    }
}
