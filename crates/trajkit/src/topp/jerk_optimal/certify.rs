//! Certification between gridpoints: the worst value of every joint limit on every middle
//! interval, and where it is.
//!
//! Inside a middle interval (which lies inside one smooth piece of the path: the grid holds
//! the path's breakpoints), with δ = s − s_i and the interval's shape ([`super::shape`]):
//! x(δ) = x_i + 2u_iδ + v(pδ² + qδ³/3) (a cubic), u(δ) = u_i + v(pδ + qδ²/2) (a quadratic),
//! θ′ = p + qδ. For a path that is a cubic polynomial there, σ′ = a + bδ + cδ²/2, σ″ = b + cδ,
//! σ‴ = c, so
//! - q̇² = σ′²·x is a polynomial of degree 7,
//! - q̈ = σ″x + σ′u of degree 4,
//! - q⃛ = √x·g with g = σ‴x + 3σ″u + σ′vθ′ of degree 3, and q⃛² = x·g² of degree 9.
//!
//! Each is first bounded by its **Bernstein coefficients** on the interval (a polynomial lies
//! within the range of its Bernstein coefficients; this settles every interval whose limit is
//! not nearly reached inside it, with no root finding). Only where that bound is inconclusive
//! are the extrema found **exactly**: at the interval's ends and the real roots of
//! 2σ″x + σ′x′ (velocity, degree 4), of q̈′ (degree 3), of x′g + 2xg′ (jerk, degree 5)
//! ([`crate::poly::roots::roots_in`]). x itself is checked to stay positive the same way.
//! Where the path is not such a cubic (the path says so through
//! [`crate::Path::piecewise_degree`]), and for constraints given as rows (torque, user
//! constraints), the interval is sampled at `SAMPLES` interior points instead.

use super::shape::Shape;
use crate::poly::roots::{horner, roots_in, MAX_DEGREE};

/// Interior samples per interval for constraints checked by sampling.
pub(crate) const SAMPLES: usize = 16;

/// Interior samples per interval when extra constraints (torque, user rows) are present: they
/// are checked by sampling only, and their excess between samples falls with the square of
/// the spacing.
pub(crate) const EXTRA_SAMPLES: usize = 48;

/// Which limit a finding is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    Velocity = 0,
    Acceleration = 1,
    Jerk = 2,
    /// x = ṡ² must stay positive inside a middle interval.
    Positive = 3,
    /// Rows of the extra constraints (checked by sampling).
    Extra = 4,
}

/// Joint limits of one joint: velocity range, acceleration range, jerk.
#[derive(Debug, Clone, Copy)]
pub(crate) struct JointRange {
    pub(crate) v: (f64, f64),
    pub(crate) a: (f64, f64),
    pub(crate) j: f64,
}

/// The state on one middle interval: x_i, u_i, v_i, its length and shape.
#[derive(Debug, Clone, Copy)]
pub(crate) struct IntervalState {
    pub(crate) x: f64,
    pub(crate) u: f64,
    pub(crate) v: f64,
    pub(crate) len: f64,
    pub(crate) shape: Shape,
}

impl IntervalState {
    #[inline]
    pub(crate) fn x_at(&self, d: f64) -> f64 {
        self.x + 2.0 * self.u * d + self.v * self.shape.psi2(d)
    }
    #[inline]
    pub(crate) fn u_at(&self, d: f64) -> f64 {
        self.u + self.v * self.shape.phi(d)
    }
    /// Path jerk divided by ṡ: v·θ′(δ).
    #[inline]
    pub(crate) fn w_at(&self, d: f64) -> f64 {
        self.v * self.shape.rate(d)
    }
    /// x as a polynomial in δ.
    pub(crate) fn x_poly(&self) -> [f64; 4] {
        let Shape { p, q } = self.shape;
        [self.x, 2.0 * self.u, self.v * p, self.v * q / 3.0]
    }
    /// u as a polynomial in δ.
    pub(crate) fn u_poly(&self) -> [f64; 3] {
        let Shape { p, q } = self.shape;
        [self.u, self.v * p, 0.5 * self.v * q]
    }
}

/// A limit found exceeded (or tight) on an interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Finding {
    pub(crate) interval: usize,
    pub(crate) joint: usize,
    pub(crate) kind: Kind,
    /// Largest value over limit on the interval (1 = at the limit).
    pub(crate) ratio: f64,
    /// Largest value over limit at the interval's check points (ends, midpoint, cuts).
    pub(crate) check: f64,
    /// δ of the worst point.
    pub(crate) delta: f64,
}

/// Relative value of `value` against the directional range `[lo, hi]` (lo ≤ 0 ≤ hi): 1 at a
/// limit, ∞ past a zero limit, −∞ for an unlimited direction.
#[inline]
pub(crate) fn ratio(value: f64, lo: f64, hi: f64) -> f64 {
    let lim = if value > 0.0 {
        hi
    } else if value < 0.0 {
        lo
    } else {
        return 0.0;
    };
    if lim.is_infinite() {
        f64::NEG_INFINITY
    } else if lim == 0.0 {
        f64::INFINITY
    } else {
        value / lim
    }
}

/// Polynomial product (lowest order first) into `out`; returns the length.
fn mul(a: &[f64], b: &[f64], out: &mut [f64]) -> usize {
    let len = a.len() + b.len() - 1;
    out[..len].iter_mut().for_each(|v| *v = 0.0);
    for (i, &ai) in a.iter().enumerate() {
        for (j, &bj) in b.iter().enumerate() {
            out[i + j] += ai * bj;
        }
    }
    len
}

/// Binomial coefficients C(n, k) for n < 16.
const BINOM: [[u32; 16]; 16] = {
    let mut t = [[0u32; 16]; 16];
    let mut n = 0;
    while n < 16 {
        t[n][0] = 1;
        let mut k = 1;
        while k <= n {
            t[n][k] = t[n - 1][k - 1] + if k < n { t[n - 1][k] } else { 0 };
            k += 1;
        }
        n += 1;
    }
    t
};

/// The smallest and largest Bernstein coefficient of the polynomial `c` (degree < 16) on
/// `[0, len]`: bounds of its range there.
pub(crate) fn bernstein_range(c: &[f64], len: f64) -> (f64, f64) {
    let n = c.len() - 1;
    let mut a = [0.0; 16];
    let mut sc = 1.0;
    for k in 0..=n {
        a[k] = c[k] * sc;
        sc *= len;
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for j in 0..=n {
        let mut b = 0.0;
        for k in 0..=j {
            b += BINOM[j][k] as f64 / BINOM[n][k] as f64 * a[k];
        }
        lo = lo.min(b);
        hi = hi.max(b);
    }
    (lo, hi)
}

/// Taylor data of one joint of a cubic path at the interval's start: σ′ = a + bδ + cδ²/2.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cubic {
    pub(crate) a: f64,
    pub(crate) b: f64,
    pub(crate) c: f64,
}

impl Cubic {
    #[inline]
    fn d1(&self) -> [f64; 3] {
        [self.a, self.b, 0.5 * self.c]
    }
    #[inline]
    fn d2(&self) -> [f64; 2] {
        [self.b, self.c]
    }
    /// (σ′, σ″, σ‴) at δ (the tests' sampled reference).
    #[cfg(test)]
    pub(crate) fn at(&self, d: f64) -> [f64; 3] {
        [
            self.a + d * (self.b + 0.5 * self.c * d),
            self.b + self.c * d,
            self.c,
        ]
    }
}

/// Relative tolerance of the Bernstein shortcut (a bound within it counts as certified).
const BOUND_TOL: f64 = 1e-12;

/// The worst point of `f` over the candidate points `pts` (with the ends): (ratio, δ).
fn worst_of(f: impl Fn(f64) -> f64, crit: &[f64], len: f64) -> (f64, f64) {
    let mut best = (f64::NEG_INFINITY, 0.0);
    for &z in crit.iter().chain([0.0, len].iter()) {
        let r = f(z);
        if r > best.0 || r.is_nan() {
            best = (if r.is_nan() { f64::INFINITY } else { r }, z);
        }
    }
    best
}

/// The smallest x on the interval, exactly, and where.
pub(crate) fn min_x(st: &IntervalState) -> (f64, f64) {
    let xp = st.x_poly();
    let (lo, _) = bernstein_range(&xp, st.len);
    if lo > 0.0 {
        return (lo, 0.0);
    }
    let dx = [xp[1], 2.0 * xp[2], 3.0 * xp[3]];
    let mut roots = [0.0; MAX_DEGREE];
    let nr = roots_in(&dx, 0.0, st.len, &mut roots);
    let (r, at) = worst_of(|z| -horner(&xp, z), &roots[..nr], st.len);
    (-r, at)
}

/// The worst ratio of each limit of one joint on a cubic interval: `[velocity,
/// acceleration, jerk]` as (ratio, δ); a limit whose Bernstein bound settles it reports the
/// bound (≤ 1) and δ = NaN.
pub(crate) fn cubic_joint(st: &IntervalState, cu: &Cubic, lim: &JointRange) -> [(f64, f64); 3] {
    let mut out = [(f64::NEG_INFINITY, f64::NAN); 3];
    if lim.v.0.is_finite() || lim.v.1.is_finite() {
        out[0] = cubic_velocity(st, cu, lim);
    }
    if lim.a.0.is_finite() || lim.a.1.is_finite() {
        out[1] = cubic_acceleration(st, cu, lim);
    }
    if lim.j.is_finite() {
        out[2] = cubic_jerk(st, cu, lim);
    }
    out
}

/// The worst velocity ratio of [`cubic_joint`] (some velocity limit finite):
/// q̇² = σ′²x against the limit of σ′'s sign.
fn cubic_velocity(st: &IntervalState, cu: &Cubic, lim: &JointRange) -> (f64, f64) {
    let d = st.len;
    let xp = st.x_poly();
    let (mut t1, mut t2) = ([0.0; 16], [0.0; 16]);
    let mut roots = [0.0; MAX_DEGREE];
    let xd = [xp[1], 2.0 * xp[2], 3.0 * xp[3]];
    let p1 = cu.d1();
    let p2 = cu.d2();
    let (slo, shi) = bernstein_range(&p1, d);
    let vl = if slo >= 0.0 {
        lim.v.1
    } else if shi <= 0.0 {
        -lim.v.0
    } else {
        lim.v.1.min(-lim.v.0)
    };
    let l1 = mul(&p1, &p1, &mut t1);
    let l2 = mul(&t1[..l1], &xp, &mut t2);
    let (_, hi) = bernstein_range(&t2[..l2], d);
    if vl.is_finite() && vl > 0.0 && hi <= vl * vl * (1.0 + BOUND_TOL) {
        ((hi.max(0.0)).sqrt() / vl, f64::NAN)
    } else {
        // Critical points of σ′√x: 2σ″x + σ′x′ = 0.
        let l1 = mul(&p2, &xp, &mut t1);
        let l2 = mul(&p1, &xd, &mut t2);
        let mut crit = [0.0; 8];
        for k in 0..l1.max(l2) {
            crit[k] = 2.0 * if k < l1 { t1[k] } else { 0.0 } + if k < l2 { t2[k] } else { 0.0 };
        }
        let nr = roots_in(&crit[..l1.max(l2)], 0.0, d, &mut roots);
        worst_of(
            |z| {
                ratio(
                    horner(&p1, z) * st.x_at(z).max(0.0).sqrt(),
                    lim.v.0,
                    lim.v.1,
                )
            },
            &roots[..nr],
            d,
        )
    }
}

/// The worst acceleration ratio of [`cubic_joint`] (some acceleration limit finite):
/// σ″x + σ′u (degree 4).
fn cubic_acceleration(st: &IntervalState, cu: &Cubic, lim: &JointRange) -> (f64, f64) {
    let d = st.len;
    let xp = st.x_poly();
    let (mut t1, mut t2) = ([0.0; 16], [0.0; 16]);
    let mut roots = [0.0; MAX_DEGREE];
    let up = st.u_poly();
    let p1 = cu.d1();
    let p2 = cu.d2();
    let l1 = mul(&p2, &xp, &mut t1);
    let l2 = mul(&p1, &up, &mut t2);
    let mut acc = [0.0; 5];
    for k in 0..l1.max(l2) {
        acc[k] = if k < l1 { t1[k] } else { 0.0 } + if k < l2 { t2[k] } else { 0.0 };
    }
    let (lo, hi) = bernstein_range(&acc, d);
    let r = ratio(hi, lim.a.0, lim.a.1).max(ratio(lo, lim.a.0, lim.a.1));
    if r <= 1.0 + BOUND_TOL {
        (r, f64::NAN)
    } else {
        let dacc = [acc[1], 2.0 * acc[2], 3.0 * acc[3], 4.0 * acc[4]];
        let nr = roots_in(&dacc, 0.0, d, &mut roots);
        worst_of(
            |z| ratio(horner(&acc, z), lim.a.0, lim.a.1),
            &roots[..nr],
            d,
        )
    }
}

/// The worst jerk ratio of [`cubic_joint`] (the jerk limit finite):
/// √x·g, g = σ‴x + 3σ″u + σ′vθ′ (degree 3); q⃛² = x·g² (degree 9).
fn cubic_jerk(st: &IntervalState, cu: &Cubic, lim: &JointRange) -> (f64, f64) {
    let d = st.len;
    let xp = st.x_poly();
    let (mut t1, mut t2) = ([0.0; 16], [0.0; 16]);
    let mut roots = [0.0; MAX_DEGREE];
    let up = st.u_poly();
    let xd = [xp[1], 2.0 * xp[2], 3.0 * xp[3]];
    let p1 = cu.d1();
    let p2 = cu.d2();
    let l1 = mul(&p2, &up, &mut t1);
    let th = [st.v * st.shape.p, st.v * st.shape.q];
    let l2 = mul(&p1, &th, &mut t2);
    let mut g = [0.0; 4];
    for k in 0..4 {
        g[k] = cu.c * xp[k]
            + 3.0 * if k < l1 { t1[k] } else { 0.0 }
            + if k < l2 { t2[k] } else { 0.0 };
    }
    let l1 = mul(&g, &g, &mut t1);
    let l2 = mul(&t1[..l1], &xp, &mut t2);
    let (_, hi) = bernstein_range(&t2[..l2], d);
    let jl = lim.j;
    if jl > 0.0 && hi <= jl * jl * (1.0 + BOUND_TOL) {
        (hi.max(0.0).sqrt() / jl, f64::NAN)
    } else {
        // Critical points: x′g + 2xg′ = 0 (degree 5).
        let dg = [g[1], 2.0 * g[2], 3.0 * g[3]];
        let l1 = mul(&xd, &g, &mut t1);
        let l2 = mul(&xp, &dg, &mut t2);
        let mut crit = [0.0; 8];
        for k in 0..l1.max(l2) {
            crit[k] = if k < l1 { t1[k] } else { 0.0 } + 2.0 * if k < l2 { t2[k] } else { 0.0 };
        }
        let nr = roots_in(&crit[..l1.max(l2)], 0.0, d, &mut roots);
        worst_of(
            |z| ratio(st.x_at(z).max(0.0).sqrt() * horner(&g, z), -jl, jl),
            &roots[..nr],
            d,
        )
    }
}

/// The ratios of one joint's limits at a single point with derivatives `d` = (σ′, σ″, σ‴) and
/// state x, u, w = s⃛/ṡ: `[velocity, acceleration, jerk]`.
#[inline]
pub(crate) fn point_joint(x: f64, u: f64, w: f64, d: [f64; 3], lim: &JointRange) -> [f64; 3] {
    let sd = x.max(0.0).sqrt();
    let [d1, d2, d3] = d;
    [
        ratio(d1 * sd, lim.v.0, lim.v.1),
        ratio(d2 * x + d1 * u, lim.a.0, lim.a.1),
        if lim.j.is_finite() {
            ratio(sd * (d3 * x + 3.0 * d2 * u + d1 * w), -lim.j, lim.j)
        } else {
            f64::NEG_INFINITY
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bernstein_range_encloses_the_polynomial() {
        let mut rng = crate::rng::SplitMix64::new(5);
        for _ in 0..200 {
            let deg = 1 + rng.below(9) as usize;
            let c: Vec<f64> = (0..=deg).map(|_| rng.uniform(-3.0, 3.0)).collect();
            let len = rng.uniform(0.1, 2.0);
            let (lo, hi) = bernstein_range(&c, len);
            for k in 0..=200 {
                let z = len * k as f64 / 200.0;
                let v = horner(&c, z);
                assert!(v >= lo - 1e-12 * (1.0 + lo.abs()) && v <= hi + 1e-12 * (1.0 + hi.abs()));
            }
        }
    }

    #[test]
    fn cubic_extrema_match_dense_sampling() {
        let mut rng = crate::rng::SplitMix64::new(11);
        let mut checked = 0;
        for _ in 0..800 {
            let len = rng.uniform(0.01, 0.2);
            let x0: f64 = rng.uniform(0.1, 2.0);
            let x1: f64 = rng.uniform(0.1, 2.0);
            let st = IntervalState {
                x: x0,
                u: rng.uniform(-2.0, 2.0),
                v: rng.uniform(-20.0, 20.0),
                len,
                shape: Shape::new(x0, x1, len),
            };
            if min_x(&st).0 < 0.01 {
                continue;
            }
            let cu = Cubic {
                a: rng.uniform(-2.0, 2.0),
                b: rng.uniform(-5.0, 5.0),
                c: rng.uniform(-50.0, 50.0),
            };
            // Limits near the values, so that both the bound and the exact path are taken.
            let lim = JointRange {
                v: (-rng.uniform(0.2, 2.0), rng.uniform(0.2, 2.0)),
                a: (-rng.uniform(0.5, 5.0), rng.uniform(0.5, 5.0)),
                j: rng.uniform(2.0, 100.0),
            };
            let exact = cubic_joint(&st, &cu, &lim);
            let mut dense = [f64::NEG_INFINITY; 3];
            for k in 0..=20000 {
                let z = st.len * k as f64 / 20000.0;
                let r = point_joint(st.x_at(z), st.u_at(z), st.w_at(z), cu.at(z), &lim);
                for o in 0..3 {
                    dense[o] = dense[o].max(r[o]);
                }
            }
            for o in 0..3 {
                let (e, at) = exact[o];
                if at.is_nan() {
                    // Settled by the bound: the bound is ≥ the true maximum.
                    assert!(
                        e <= 1.0 + 1e-9 && dense[o] <= e + 1e-9,
                        "{o}: {e} {}",
                        dense[o]
                    );
                } else {
                    checked += 1;
                    assert!(e >= dense[o] - 1e-12, "{o}: {e} < {}", dense[o]);
                    assert!(
                        e <= dense[o] + 1e-6 * (1.0 + dense[o].abs()),
                        "{o}: {e} > {}",
                        dense[o]
                    );
                }
            }
        }
        assert!(checked > 100, "{checked}");
    }
}
