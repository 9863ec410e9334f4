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

    /// [`Self::roots`], and an end of the window where P vanishes to round-off (below 1e-12
    /// of its terms' magnitude) counts as a root too: a family's valid range can end there
    /// at a double root (a ramp of length zero where P touches zero), which the isolation
    /// may not report. (Step 1's closed families: every candidate is verified.)
    #[inline]
    pub fn roots_with_ends(&self, lo: f64, hi: f64, out: &mut [f64; MAX_POLY]) -> usize {
        self.roots_with_ends_above(lo, hi, 0.0, out)
    }

    /// [`Self::roots_with_ends`] with an absolute `floor` added to the end test's round-off
    /// (|P| ≤ 1e-12 of its terms' magnitude + `floor`): for a P that is the position residual
    /// itself (step 1's plateau families), the rounding of the displacement p_f − p₀, which
    /// its coefficients do not carry.
    #[inline]
    pub fn roots_with_ends_above(
        &self,
        lo: f64,
        hi: f64,
        floor: f64,
        out: &mut [f64; MAX_POLY],
    ) -> usize {
        let p = &self.p[..self.np];
        let mut n = poly_roots(p, lo, hi, out);
        for e in [lo, hi] {
            if n == MAX_POLY || !e.is_finite() {
                break;
            }
            let (v, mag) = p
                .iter()
                .rev()
                .fold((0.0, 0.0), |(v, m), &c| (v * e + c, m * e.abs() + c.abs()));
            let seen = out[..n]
                .iter()
                .any(|&r| (r - e).abs() <= 1e-12 * (1.0 + e.abs()));
            if v.abs() <= 1e-12 * mag + floor && !seen {
                out[n] = e;
                n += 1;
                out[..n].sort_unstable_by(f64::total_cmp);
            }
        }
        n
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
/// polynomial (both plateaus, quadratic) to the dearest (no plateau, sextic): with a
/// prescribed duration the first valid profile ends the search, and the plateau variants are
/// the common ones at moderate limits. A variant whose plateau duration is clearly negative
/// over its whole window, or whose velocity continuity cannot hold there, is skipped.
pub(crate) fn two_changes(
    q: &Dof1,
    d1: f64,
    d2: f64,
    t: Option<f64>,
    vlo: f64,
    vhi: f64,
    take: &mut impl FnMut(&Profile) -> bool,
) -> bool {
    let al1 = if d1 > 0.0 { q.amax } else { q.amin };
    let al2 = if d2 > 0.0 { q.amax } else { q.amin };
    if !(al1.is_finite() && al2.is_finite() && q.jmax.is_finite()) {
        return false;
    }
    let tc = TwoChanges {
        q,
        d1,
        d2,
        al1,
        al2,
        t,
        vlo,
        vhi,
        tol: 1e-12 * (q.amax - q.amin),
    };
    let mut buf: Option<Profile> = None;
    let mut roots = [0.0; MAX_POLY];
    tc.both_plateaus(&mut buf, &mut roots, take)
        || tc.plateau_first(&mut buf, &mut roots, take)
        || tc.plateau_second(&mut buf, &mut roots, take)
        || tc.no_plateau(&mut buf, &mut roots, take)
}

/// The data of one [`two_changes`] call.
struct TwoChanges<'q> {
    q: &'q Dof1,
    d1: f64,
    d2: f64,
    /// The acceleration limit of each change's direction.
    al1: f64,
    al2: f64,
    t: Option<f64>,
    vlo: f64,
    vhi: f64,
    tol: f64,
}

impl TwoChanges<'_> {
    /// Peak window of a change: between the boundary acceleration (or 0) and the limit.
    fn window(&self, dk: f64, a: f64, lim: f64) -> (f64, f64) {
        if dk > 0.0 {
            (a.max(0.0) - self.tol, lim + self.tol)
        } else {
            (lim - self.tol, a.min(0.0) + self.tol)
        }
    }

    fn vc_of_alpha(&self, x: f64) -> f64 {
        let q = self.q;
        q.v0 + self.d1 * (2.0 * x * x - q.a0 * q.a0) / (2.0 * q.jmax)
    }

    fn vc_of_beta(&self, x: f64) -> f64 {
        let q = self.q;
        q.vf - self.d2 * (2.0 * x * x - q.af * q.af) / (2.0 * q.jmax)
    }

    fn tau1_of(&self, vc: f64) -> f64 {
        let (q, al1) = (self.q, self.al1);
        (vc - q.v0 - self.d1 * (2.0 * al1 * al1 - q.a0 * q.a0) / (2.0 * q.jmax)) / al1
    }

    fn tau2_of(&self, vc: f64) -> f64 {
        let (q, al2) = (self.q, self.al2);
        (q.vf - vc - self.d2 * (2.0 * al2 * al2 - q.af * q.af) / (2.0 * q.jmax)) / al2
    }

    /// The residual's coefficients of a variant (with or without a prescribed duration).
    fn pick(&self, f: TwoFree, g: TwoTimed) -> Resid {
        let q = self.q;
        let (a, b, c, e, h, k) = (q.a0, q.af, q.v0, q.vf, q.pf - q.p0, q.jmax);
        let (l, m, n, o) = (self.d1, self.d2, self.al1, self.al2);
        match self.t {
            Some(t) => g(a, b, c, e, h, k, l, m, n, o, t),
            None => f(a, b, c, e, h, k, l, m, n, o),
        }
    }

    /// Whether a plateau duration `f` is clearly negative over the whole window `[lo, hi]`
    /// (far beyond the tolerance of [`TwoChanges::offer`]). The durations are linear in v_c,
    /// and v_c is a parabola in α or β with its vertex at 0: the largest value is at an end of
    /// the window or at 0.
    fn hopeless(&self, f: &dyn Fn(f64) -> f64, lo: f64, hi: f64) -> bool {
        let q = self.q;
        let size = self.t.unwrap_or(0.0)
            + (self.vlo.abs() + self.vhi.abs() + q.v0.abs() + q.vf.abs())
                / self.al1.abs().min(self.al2.abs())
            + (q.a0.abs() + q.af.abs() + self.al1.abs() + self.al2.abs()) / q.jmax;
        let neg = |x: f64| f(x) < -1e-6 * size;
        neg(lo) && neg(hi) && (!(lo < 0.0 && hi > 0.0) || neg(0.0))
    }

    /// Builds the profile for (α, τ₁, β, τ₂) in `buf` and hands it to `take`; false when a
    /// duration is negative (or `take` declines).
    fn offer(
        &self,
        buf: &mut Option<Profile>,
        take: &mut impl FnMut(&Profile) -> bool,
        (alpha, tau1, beta, tau2, vc): (f64, f64, f64, f64, f64),
    ) -> bool {
        let (q, d1, d2, j) = (self.q, self.d1, self.d2, self.q.jmax);
        let segs = [
            ((alpha - q.a0) * d1 / j, d1 * j),
            (tau1, 0.0),
            (alpha * d1 / j, -d1 * j),
            (beta * d2 / j, d2 * j),
            (tau2, 0.0),
            ((beta - q.af) * d2 / j, -d2 * j),
        ];
        let scale = 1e-12 * (segs.iter().map(|s| s.0.abs()).sum::<f64>() + self.t.unwrap_or(0.0));
        if segs.iter().any(|s| s.0.is_nan() || s.0 < -scale) {
            return false;
        }
        let busy: f64 = segs.iter().map(|s| s.0.max(0.0)).sum();
        let tau = match self.t {
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
            v: q.v0,
            a: q.a0,
        });
        for s in &segs[..3] {
            pr.push(s.0.max(0.0), s.1);
        }
        pr.push_cruise(tau, vc);
        for s in &segs[3..] {
            pr.push(s.0.max(0.0), s.1);
        }
        take(pr)
    }

    /// Both plateaus: s = v_c (a quadratic).
    fn both_plateaus(
        &self,
        buf: &mut Option<Profile>,
        roots: &mut [f64; MAX_POLY],
        take: &mut impl FnMut(&Profile) -> bool,
    ) -> bool {
        let (vlo, vhi) = (self.vlo, self.vhi);
        if self.hopeless(&|v| self.tau1_of(v), vlo, vhi)
            || self.hopeless(&|v| self.tau2_of(v), vlo, vhi)
        {
            return false;
        }
        let n = self.pick(two_pp, two_pp_t).roots(vlo, vhi, roots);
        roots[..n].iter().any(|&vc| {
            let durations = (self.al1, self.tau1_of(vc), self.al2, self.tau2_of(vc), vc);
            self.offer(buf, take, durations)
        })
    }

    /// Plateau in change 1: s = β (a quartic).
    fn plateau_first(
        &self,
        buf: &mut Option<Profile>,
        roots: &mut [f64; MAX_POLY],
        take: &mut impl FnMut(&Profile) -> bool,
    ) -> bool {
        let (blo, bhi) = self.window(self.d2, self.q.af, self.al2);
        if self.hopeless(&|x| self.tau1_of(self.vc_of_beta(x)), blo, bhi) {
            return false;
        }
        let n = self.pick(two_pn, two_pn_t).roots(blo, bhi, roots);
        roots[..n].iter().any(|&x| {
            let vc = self.vc_of_beta(x);
            self.offer(buf, take, (self.al1, self.tau1_of(vc), x, 0.0, vc))
        })
    }

    /// Plateau in change 2: s = α (a quartic).
    fn plateau_second(
        &self,
        buf: &mut Option<Profile>,
        roots: &mut [f64; MAX_POLY],
        take: &mut impl FnMut(&Profile) -> bool,
    ) -> bool {
        let (alo, ahi) = self.window(self.d1, self.q.a0, self.al1);
        if self.hopeless(&|x| self.tau2_of(self.vc_of_alpha(x)), alo, ahi) {
            return false;
        }
        let n = self.pick(two_np, two_np_t).roots(alo, ahi, roots);
        roots[..n].iter().any(|&x| {
            let vc = self.vc_of_alpha(x);
            self.offer(buf, take, (x, 0.0, self.al2, self.tau2_of(vc), vc))
        })
    }

    /// No plateau: s = α, β = ±√W (a sextic). Both changes meet at v_c: d₁α² + d₂β² = K.
    /// When K lies clearly outside the range that α's and β's windows allow, the variant is
    /// skipped.
    fn no_plateau(
        &self,
        buf: &mut Option<Profile>,
        roots: &mut [f64; MAX_POLY],
        take: &mut impl FnMut(&Profile) -> bool,
    ) -> bool {
        let q = self.q;
        let (alo, ahi) = self.window(self.d1, q.a0, self.al1);
        let (blo, bhi) = self.window(self.d2, q.af, self.al2);
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
        let (sa, ta) = squares(alo, ahi, self.d1);
        let (sb, tb) = squares(blo, bhi, self.d2);
        let kk = q.jmax * (q.vf - q.v0) + (self.d1 * q.a0 * q.a0 + self.d2 * q.af * q.af) / 2.0;
        let margin = 1e-9 * (kk.abs() + ta.abs().max(sa.abs()) + tb.abs().max(sb.abs()));
        // (Written so that NaN does not skip.)
        if kk < sa + sb - margin || kk > ta + tb + margin {
            return false;
        }
        let r = self.pick(two_nn, two_nn_t);
        let n = r.roots(alo, ahi, roots);
        roots[..n].iter().any(|&x| {
            let beta = r.w_at(x);
            beta * self.d2 >= -self.tol
                && self.offer(buf, take, (x, 0.0, beta, 0.0, self.vc_of_alpha(x)))
        })
    }
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
