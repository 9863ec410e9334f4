//! Closed-form roots of the profile families' position residuals.
//!
//! Every jerk-limited profile family leaves one free parameter s once its velocity (and, with
//! a prescribed duration, its duration) equation is solved. The position residual is then a
//! polynomial in s, possibly with one more acceleration level w tied to s by w² = W(s). Its
//! coefficients come from `families_gen.rs`, derived symbolically by
//! `tools/otg_coefficients.py` (A + w·B, and P = A² − W·B² with the square root eliminated;
//! degree ≤ 4 for every step-1 family, ≤ 6 for two velocity changes in opposite directions
//! with a prescribed duration). [`Resid::roots`] solves P on the family's parameter window with
//! [`crate::roots::poly_roots`] and [`Resid::w_at`] recovers w with its sign.
//!
//! Precision: a root is a root of P to a few ulp of its parameter; every candidate profile
//! built from it is still checked against the target and the limits, and the bracketing
//! solver remains the fallback when the closed forms yield nothing.

use super::families_gen::{two_nn, two_nn_t, two_np, two_np_t, two_pn, two_pn_t, two_pp, two_pp_t};
use super::problem::Dof1;
use super::profile::{Profile, State1};
use crate::roots::{poly_roots, MAX_POLY};

/// A family's position residual r(s) = A(s) + w·B(s) with w² = W(s), and P(s) = A² − W·B²
/// (P = A when the family has no w).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Resid {
    pub a: [f64; 7],
    pub na: usize,
    pub b: [f64; 7],
    pub nb: usize,
    pub w: [f64; 3],
    pub p: [f64; 7],
    pub np: usize,
}

impl Resid {
    /// Roots of P in `[lo, hi]`, increasing; returns how many.
    #[inline]
    pub fn roots(&self, lo: f64, hi: f64, out: &mut [f64; MAX_POLY]) -> usize {
        poly_roots(&self.p[..self.np], lo, hi, out)
    }

    /// The second level w at a root s: ±√W(s), the sign that makes A + w·B vanish.
    #[inline]
    pub fn w_at(&self, s: f64) -> f64 {
        let ww = self.w[0] + s * (self.w[1] + s * self.w[2]);
        let m = ww.max(0.0).sqrt();
        let a = crate::roots::horner_d(&self.a[..self.na], s).0;
        let b = crate::roots::horner_d(&self.b[..self.nb], s).0;
        if (a + m * b).abs() <= (a - m * b).abs() {
            m
        } else {
            -m
        }
    }
}

/// Coefficients of a two-change family without a prescribed duration.
type TwoFree = fn(f64, f64, f64, f64, f64, f64, f64, f64, f64, f64) -> Resid;
/// Coefficients of a two-change family with a prescribed duration.
type TwoTimed = fn(f64, f64, f64, f64, f64, f64, f64, f64, f64, f64, f64) -> Resid;

/// Two fastest velocity changes through (v_c, 0), the first ramping the acceleration in
/// direction `d1` (±1) towards a peak α, the second in direction `d2` towards a peak β, each
/// with a plateau at the acceleration limit or without, and between them a cruise at v_c of
/// `t − (other durations)` when a duration `t` is prescribed (none otherwise). For each of the
/// four plateau variants the position residual is a polynomial in one parameter; every root
/// that gives non-negative durations becomes a profile handed to `take`, which returns true to
/// stop. `vlo`/`vhi` bound v_c (velocity limits or caps). The variants go from the cheapest
/// polynomial (both plateaus, quadratic) to the dearest (no plateau, sextic); a variant whose
/// plateau duration is clearly negative over its whole window, or whose velocity continuity
/// cannot hold there, is skipped.
pub(crate) fn two_changes(
    q: &Dof1,
    d1: f64,
    d2: f64,
    t: Option<f64>,
    vlo: f64,
    vhi: f64,
    take: &mut impl FnMut(&Profile) -> bool,
) -> bool {
    let (a0, af, v0, vf, j) = (q.a0, q.af, q.v0, q.vf, q.jmax);
    let d = q.pf - q.p0;
    let al1 = if d1 > 0.0 { q.amax } else { q.amin };
    let al2 = if d2 > 0.0 { q.amax } else { q.amin };
    if !(al1.is_finite() && al2.is_finite() && j.is_finite()) {
        return false;
    }
    let tol = 1e-12 * (q.amax - q.amin);
    // Peak windows: α between the start acceleration (or 0) and the limit, β likewise.
    let win = |dk: f64, a: f64, lim: f64| {
        if dk > 0.0 {
            (a.max(0.0) - tol, lim + tol)
        } else {
            (lim - tol, a.min(0.0) + tol)
        }
    };
    let (alo, ahi) = win(d1, a0, al1);
    let (blo, bhi) = win(d2, af, al2);
    let vc_of_alpha = |x: f64| v0 + d1 * (2.0 * x * x - a0 * a0) / (2.0 * j);
    let vc_of_beta = |x: f64| vf - d2 * (2.0 * x * x - af * af) / (2.0 * j);
    let tau1_of = |vc: f64| (vc - v0 - d1 * (2.0 * al1 * al1 - a0 * a0) / (2.0 * j)) / al1;
    let tau2_of = |vc: f64| (vf - vc - d2 * (2.0 * al2 * al2 - af * af) / (2.0 * j)) / al2;
    // Builds and offers the profile for (α, τ₁, β, τ₂); false when a duration is negative.
    // (One buffer, emptied for each candidate.)
    let mut buf: Option<Profile> = None;
    let mut offer = |alpha: f64, tau1: f64, beta: f64, tau2: f64, vc: f64| -> bool {
        let segs = [
            ((alpha - a0) * d1 / j, d1 * j),
            (tau1, 0.0),
            (alpha * d1 / j, -d1 * j),
            (beta * d2 / j, d2 * j),
            (tau2, 0.0),
            ((beta - af) * d2 / j, -d2 * j),
        ];
        let scale = 1e-12 * (segs.iter().map(|s| s.0.abs()).sum::<f64>() + t.unwrap_or(0.0));
        if segs.iter().any(|s| s.0.is_nan() || s.0 < -scale) {
            return false;
        }
        let busy: f64 = segs.iter().map(|s| s.0.max(0.0)).sum();
        let tau = match t {
            Some(t) => {
                let tau = t - busy;
                if tau < -scale {
                    return false;
                }
                tau.max(0.0)
            }
            None => 0.0,
        };
        let pr = buf.get_or_insert_with(Profile::default);
        pr.reset(State1 {
            p: q.p0,
            v: v0,
            a: a0,
        });
        for s in &segs[..3] {
            pr.push(s.0.max(0.0), s.1);
        }
        pr.snap(vc, 0.0);
        pr.push_with(tau, vc, 0.0, 0.0);
        for s in &segs[3..] {
            pr.push(s.0.max(0.0), s.1);
        }
        take(pr)
    };
    let mut roots = [0.0; MAX_POLY];
    let args = (a0, af, v0, vf, d, j, d1, d2, al1, al2);
    let pick = |f: TwoFree, g: TwoTimed| {
        let (a, b, c, e, h, k, l, m, n, o) = args;
        match t {
            Some(t) => g(a, b, c, e, h, k, l, m, n, o, t),
            None => f(a, b, c, e, h, k, l, m, n, o),
        }
    };
    // Cheapest polynomial first (both plateaus: quadratic; one plateau: quartic; none:
    // sextic): with a prescribed duration the first valid profile ends the search, and the
    // plateau variants are the common ones at moderate limits.
    // A plateau variant whose plateau duration is clearly negative over its whole parameter
    // window (far beyond the tolerance of `offer`) is skipped. The durations are linear in
    // v_c, and v_c is a parabola in α or β with its vertex at 0: the largest value is at an
    // end of the window or at 0.
    let size = t.unwrap_or(0.0)
        + (vlo.abs() + vhi.abs() + v0.abs() + vf.abs()) / al1.abs().min(al2.abs())
        + (a0.abs() + af.abs() + al1.abs() + al2.abs()) / j;
    let hopeless = |f: &dyn Fn(f64) -> f64, lo: f64, hi: f64| {
        let neg = |x: f64| f(x) < -1e-6 * size;
        neg(lo) && neg(hi) && (!(lo < 0.0 && hi > 0.0) || neg(0.0))
    };
    // Both plateaus: s = v_c.
    let n = if hopeless(&tau1_of, vlo, vhi) || hopeless(&tau2_of, vlo, vhi) {
        0
    } else {
        pick(two_pp, two_pp_t).roots(vlo, vhi, &mut roots)
    };
    for &vc in &roots[..n] {
        if offer(al1, tau1_of(vc), al2, tau2_of(vc), vc) {
            return true;
        }
    }
    // Plateau in change 1: s = β.
    let n = if hopeless(&|x| tau1_of(vc_of_beta(x)), blo, bhi) {
        0
    } else {
        pick(two_pn, two_pn_t).roots(blo, bhi, &mut roots)
    };
    for &x in &roots[..n] {
        let vc = vc_of_beta(x);
        if offer(al1, tau1_of(vc), x, 0.0, vc) {
            return true;
        }
    }
    // Plateau in change 2: s = α.
    let n = if hopeless(&|x| tau2_of(vc_of_alpha(x)), alo, ahi) {
        0
    } else {
        pick(two_np, two_np_t).roots(alo, ahi, &mut roots)
    };
    for &x in &roots[..n] {
        let vc = vc_of_alpha(x);
        if offer(x, 0.0, al2, tau2_of(vc), vc) {
            return true;
        }
    }
    // No plateau: s = α, β = ±√W. Both changes meet at v_c: d₁α² + d₂β² = K. When K lies
    // clearly outside the range that α's and β's windows allow, the variant (a sextic) is
    // skipped.
    let squares = |lo: f64, hi: f64, dk: f64| {
        let (a, b) = (lo * lo, hi * hi);
        let mn = if lo <= 0.0 && hi >= 0.0 {
            0.0
        } else {
            a.min(b)
        };
        let mx = a.max(b);
        if dk > 0.0 {
            (mn, mx)
        } else {
            (-mx, -mn)
        }
    };
    let (sa, ta) = squares(alo, ahi, d1);
    let (sb, tb) = squares(blo, bhi, d2);
    let kk = j * (vf - v0) + (d1 * a0 * a0 + d2 * af * af) / 2.0;
    let margin = 1e-9 * (kk.abs() + ta.abs().max(sa.abs()) + tb.abs().max(sb.abs()));
    // (Written so that NaN does not skip.)
    if kk < sa + sb - margin || kk > ta + tb + margin {
        return false;
    }
    let r = pick(two_nn, two_nn_t);
    let n = r.roots(alo, ahi, &mut roots);
    for &x in &roots[..n] {
        let beta = r.w_at(x);
        if beta * d2 >= -tol && offer(x, 0.0, beta, 0.0, vc_of_alpha(x)) {
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::super::families_gen::*;
    use super::super::profile::integrate;

    fn displacement(v0: f64, a0: f64, segs: &[(f64, f64)]) -> (f64, f64, f64) {
        let (mut p, mut v, mut a) = (0.0, v0, a0);
        for &(t, jk) in segs {
            (p, v, a) = integrate(p, v, a, jk, t);
        }
        (p, v, a)
    }

    #[test]
    fn generated_residuals_match_integration() {
        // s1_none at an arbitrary α1 with α2 from the velocity equation: A + w·B equals the
        // integrated displacement minus d, and P vanishes where that residual does.
        let (a0, af, v0, vf, d, j) = (0.3, -0.2, 0.1, 0.4, 0.7, 2.0);
        let r = s1_none(a0, af, v0, vf, d, j);
        let s = 0.9;
        let k = j * (vf - v0) + (a0 * a0 - af * af) / 2.0;
        let w = -(s * s - k).sqrt();
        let (p, v, a) = displacement(
            v0,
            a0,
            &[((s - a0) / j, j), ((s - w) / j, -j), ((af - w) / j, j)],
        );
        assert!((v - vf).abs() < 1e-14 && (a - af).abs() < 1e-14);
        let h = |c: &[f64]| crate::roots::horner_d(c, s).0;
        let res = h(&r.a[..r.na]) + w * h(&r.b[..r.nb]);
        assert!((res - (p - d)).abs() < 1e-13, "{res} vs {}", p - d);
        let pp = h(&r.p[..r.np]);
        let ww = h(&r.w);
        let q = h(&r.a[..r.na]).powi(2) - ww * h(&r.b[..r.nb]).powi(2);
        assert!((pp - q).abs() < 1e-12 * q.abs().max(1.0), "{pp} vs {q}");
        // two_pp_t: both plateaus, cruise for the rest of t; s = v_c.
        let (al1, al2, t) = (1.5, -1.2, 6.0);
        let r = two_pp_t(a0, af, v0, vf, d, j, 1.0, -1.0, al1, al2, t);
        let vc = 2.5;
        let t1 = (vc - v0 - (2.0 * al1 * al1 - a0 * a0) / (2.0 * j)) / al1;
        let t2 = (vf - vc + (2.0 * al2 * al2 - af * af) / (2.0 * j)) / al2;
        let segs = [
            ((al1 - a0) / j, j),
            (t1, 0.0),
            (al1 / j, -j),
            (0.0, 0.0),
            (-al2 / j, -j),
            (t2, 0.0),
            ((af - al2) / j, j),
        ];
        let tau = t - segs.iter().map(|s| s.0).sum::<f64>();
        let mut all = segs;
        all[3] = (tau, 0.0);
        let (p, v, a) = displacement(v0, a0, &all);
        assert!((v - vf).abs() < 1e-12 && (a - af).abs() < 1e-12);
        let res = crate::roots::horner_d(&r.a[..r.na], vc).0;
        assert!((res - (p - d)).abs() < 1e-11, "{res} vs {}", p - d);
    }
}
