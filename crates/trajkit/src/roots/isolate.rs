//! Real roots of a polynomial of degree ≤ [`MAX_POLY`] in an interval, fast enough for the
//! online generator's real-time path.
//!
//! [`poly_roots`] solves the linear and quadratic cases in closed form ([`super::quadratic`]).
//! From degree 3 on it first isolates the roots with the Budan–Fourier bound (sign variations
//! of the Taylor coefficients at the two ends, with a round-off guard), bisecting the interval
//! up to two levels: a piece bounded by 0 has no root, a piece bounded by 1 has exactly one,
//! found by Newton's method safeguarded by bisection, and a piece with an even bound and the
//! same sign at both ends has none when a Taylor expansion at one end keeps the polynomial away
//! from zero over the piece. Whatever that does not settle goes to the derivative recursion:
//! the interval is split into monotone pieces at the roots of the derivative, each solved the
//! same way, so tangent roots at a critical point (|p| below 1e-13 of the largest term) are
//! found too. Leading coefficients below 1e-15 of the largest term on the interval are
//! dropped first.
//!
//! Precision: a root is returned when Newton's step no longer moves it by more than 2 ulp (or
//! its bracket is as narrow as f64 allows). The online generator verifies every profile built
//! from a root, so a missed or imprecise root can cost time-optimality but never correctness.

use super::{derivative, horner_d, quadratic};
use crate::num::clamp_in;

/// Highest polynomial degree [`poly_roots`] accepts.
pub const MAX_POLY: usize = 6;

/// Real roots of the polynomial `c` (lowest order first, degree ≤ [`MAX_POLY`]) in
/// `[lo, hi]`, increasing, written to `out`; returns how many. Leading coefficients that are
/// negligible on the interval (below 1e-15 of the largest term) are dropped. An identically
/// zero polynomial has no reported roots.
pub fn poly_roots(c: &[f64], lo: f64, hi: f64, out: &mut [f64; MAX_POLY]) -> usize {
    poly_roots_with(c, lo, hi, out, true)
}

/// [`poly_roots`] without the Budan–Fourier pre-test (for the derivatives inside the recursion,
/// whose pre-test would repeat work already done).
fn poly_roots_inner(c: &[f64], lo: f64, hi: f64, out: &mut [f64; MAX_POLY]) -> usize {
    poly_roots_with(c, lo, hi, out, false)
}

fn poly_roots_with(c: &[f64], lo: f64, hi: f64, out: &mut [f64; MAX_POLY], pretest: bool) -> usize {
    if lo.is_nan() || hi.is_nan() || lo > hi || !lo.is_finite() || !hi.is_finite() {
        return 0;
    }
    let r = lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE);
    let mut len = c.len().min(MAX_POLY + 1);
    let mut big = 0.0f64;
    // |c_k|·r^k, the size of each term on the interval.
    let mut term = [0.0f64; MAX_POLY + 1];
    let mut pw = 1.0;
    for (k, &ck) in c[..len].iter().enumerate() {
        term[k] = (ck * pw).abs();
        big = big.max(term[k]);
        pw *= r;
    }
    if !big.is_finite() || big == 0.0 {
        return 0;
    }
    while len > 1 && term[len - 1] <= 1e-15 * big {
        len -= 1;
    }
    let c = &c[..len];
    if pretest && len >= 4 {
        if let Some(n) = isolate(c, lo, hi, out) {
            return n;
        }
    }
    roots_rec(c, big, lo, hi, out)
}

/// [`poly_roots`] after trimming and the pre-test: the derivative recursion.
fn roots_rec(c: &[f64], big: f64, lo: f64, hi: f64, out: &mut [f64; MAX_POLY]) -> usize {
    let len = c.len();
    let mut n = 0;
    let mut push = |x: f64, out: &mut [f64; MAX_POLY]| {
        if x >= lo && x <= hi && n < MAX_POLY && (n == 0 || x > out[n - 1]) {
            out[n] = x;
            n += 1;
        }
    };
    match len {
        0 | 1 => {}
        2 => push(-c[0] / c[1], out),
        3 => {
            let (k, q) = quadratic(c[0], c[1], c[2]);
            for &x in &q[..k] {
                push(x, out);
            }
        }
        _ => {
            // Critical points split [lo, hi] into monotone pieces.
            let mut d = [0.0; MAX_POLY];
            derivative(c, &mut d);
            let mut crit = [0.0; MAX_POLY];
            let nc = poly_roots_inner(&d[..len - 1], lo, hi, &mut crit);
            let mut a = lo;
            let mut fa = horner_d(c, a).0;
            if fa == 0.0 {
                push(a, out);
            }
            for k in 0..=nc {
                let b = if k < nc { crit[k] } else { hi };
                if b <= a && k < nc {
                    continue;
                }
                let fb = horner_d(c, b).0;
                if fb == 0.0 {
                    push(b, out);
                } else if fa != 0.0 && (fa < 0.0) != (fb < 0.0) {
                    push(monotone_root(c, a, b, fa, fb), out);
                } else if k < nc && fb.abs() <= 1e-13 * big {
                    // Tangent root at a critical point.
                    push(b, out);
                }
                a = b;
                fa = fb;
            }
        }
    }
    n
}

/// Taylor coefficients of a polynomial at a point, with the Budan–Fourier count there.
#[derive(Clone, Copy)]
struct Taylor<const N: usize> {
    x: f64,
    /// Sign variations of (p, p′, p″/2, …) at x.
    var: u32,
    /// p(x + h) = Σ t[k]·h^k.
    t: [f64; N],
    /// The same for |c| at |x|: bounds the size of the terms each t[k] sums.
    m: [f64; N],
}

/// Taylor coefficients of `c` at `x` by repeated synthetic division (t[0] is Horner's p(x));
/// `None` when a coefficient is zero or small enough for round-off to have flipped its sign.
#[inline(always)]
fn taylor<const N: usize>(c: &[f64], x: f64) -> Option<Taylor<N>> {
    let mut t = [0.0; N];
    let mut m = [0.0; N];
    for i in 0..N {
        t[i] = c[i];
        m[i] = c[i].abs();
    }
    let ax = x.abs();
    for k in 0..N {
        for i in (k..N - 1).rev() {
            t[i] += x * t[i + 1];
            m[i] += ax * m[i + 1];
        }
    }
    let mut ok = true;
    let mut var = 0u32;
    for k in 0..N {
        ok &= t[k].abs() > 1e-12 * m[k];
        if k > 0 {
            var += ((t[k - 1] < 0.0) != (t[k] < 0.0)) as u32;
        }
    }
    ok.then_some(Taylor { x, var, t, m })
}

/// Budan–Fourier bound: the number of roots of `c` in `[lo, hi]` is at most the difference of
/// the sign variations of (p, p′, p″, …) at the two ends (and has its parity). `None` when
/// no bound is available at an end.
#[cfg(test)]
fn root_bound(c: &[f64], lo: f64, hi: f64) -> Option<u32> {
    fn at<const N: usize>(c: &[f64], lo: f64, hi: f64) -> Option<u32> {
        Some(
            taylor::<N>(c, lo)?
                .var
                .saturating_sub(taylor::<N>(c, hi)?.var),
        )
    }
    match c.len() {
        4 => at::<4>(c, lo, hi),
        5 => at::<5>(c, lo, hi),
        6 => at::<6>(c, lo, hi),
        7 => at::<7>(c, lo, hi),
        _ => None,
    }
}

/// Root isolation for degrees 3 to 6 (see the module documentation); `None` when it does not
/// settle the roots and the caller must use the derivative recursion.
fn isolate(c: &[f64], lo: f64, hi: f64, out: &mut [f64; MAX_POLY]) -> Option<usize> {
    // One unrolled instance per length (the common ones: quartics and sextics).
    match c.len() {
        4 => isolate_n::<4>(c, lo, hi, out),
        5 => isolate_n::<5>(c, lo, hi, out),
        6 => isolate_n::<6>(c, lo, hi, out),
        7 => isolate_n::<7>(c, lo, hi, out),
        _ => None,
    }
}

fn isolate_n<const N: usize>(
    c: &[f64],
    lo: f64,
    hi: f64,
    out: &mut [f64; MAX_POLY],
) -> Option<usize> {
    let a = taylor::<N>(c, lo)?;
    // Most windows hold no root and p keeps its sign from the start: one expansion settles it.
    if a.t[0] != 0.0 && away_from_zero(&a, hi - lo, 1.0) {
        return Some(0);
    }
    let b = taylor::<N>(c, hi)?;
    let mut n = 0;
    isolate_piece(c, &a, &b, 2, out, &mut n)?;
    Some(n)
}

/// One piece `[a.x, b.x]` of [`isolate`]: appends its roots to `out`. A piece bounded by 0
/// has no root; bounded by 1, exactly one (parity), with a sign change at the ends. A larger
/// even bound with the same sign at both ends is often a complex pair: the piece has no root
/// when the Taylor expansion at either end keeps p away from zero over the whole piece;
/// otherwise it is bisected (up to `depth` more levels).
fn isolate_piece<const N: usize>(
    c: &[f64],
    a: &Taylor<N>,
    b: &Taylor<N>,
    depth: u32,
    out: &mut [f64; MAX_POLY],
    n: &mut usize,
) -> Option<()> {
    let (fa, fb) = (a.t[0], b.t[0]);
    let bound = a.var.saturating_sub(b.var);
    if bound == 0 {
        return Some(());
    }
    if bound == 1 {
        if fa == 0.0 || fb == 0.0 || (fa < 0.0) == (fb < 0.0) || *n >= MAX_POLY {
            return None;
        }
        out[*n] = monotone_root(c, a.x, b.x, fa, fb);
        *n += 1;
        return Some(());
    }
    let w = b.x - a.x;
    if bound % 2 == 0
        && fa != 0.0
        && (fa < 0.0) == (fb < 0.0)
        && (away_from_zero(a, w, 1.0) || away_from_zero(b, w, -1.0))
    {
        return Some(());
    }
    let mid = 0.5 * (a.x + b.x);
    if depth == 0 || mid <= a.x || mid >= b.x {
        return None;
    }
    let m = taylor::<N>(c, mid)?;
    isolate_piece(c, a, &m, depth - 1, out, n)?;
    isolate_piece(c, &m, b, depth - 1, out, n)
}

/// Whether p(x + s·h) keeps the sign of p(x) for all h in [0, w] (s = ±1), by the lower bound
/// |p(x)| − Σ (terms of the wrong sign)·w^k, with a margin for the round-off of the Taylor
/// coefficients (a few ulp of the sizes `m`).
#[inline]
fn away_from_zero<const N: usize>(p: &Taylor<N>, w: f64, s: f64) -> bool {
    let sg = if p.t[0] < 0.0 { -1.0 } else { 1.0 };
    let mut worst = 0.0;
    let mut err = p.m[0];
    let (mut wk, mut sk) = (1.0, 1.0);
    for k in 1..N {
        wk *= w;
        sk *= s;
        let term = sg * sk * p.t[k] * wk;
        if term < 0.0 {
            worst -= term;
        }
        err += p.m[k] * wk;
    }
    sg * p.t[0] - worst > 64.0 * f64::EPSILON * N as f64 * err
}

/// The root of `c` in `[a, b]` where it is monotone with a sign change (f(a) = `fa`): Newton
/// steps from the secant point (f(b) = `fb`), bisection whenever a step leaves the bracket.
fn monotone_root(c: &[f64], mut a: f64, mut b: f64, fa: f64, fb: f64) -> f64 {
    let neg = fa < 0.0;
    // Start at the secant point, kept off the bracket's ends.
    let w = b - a;
    let secant = a + w * (fa / (fa - fb));
    let mut x = clamp_in(secant, a + w / 64.0, b - w / 64.0).unwrap_or(0.5 * (a + b));
    for _ in 0..100 {
        let (f, df) = horner_d(c, x);
        if f == 0.0 {
            return x;
        }
        if (f < 0.0) == neg {
            a = x;
        } else {
            b = x;
        }
        let mut nx = x - f / df;
        if !(nx > a && nx < b) {
            nx = 0.5 * (a + b);
        }
        if (nx - x).abs() <= 2.0 * f64::EPSILON * x.abs() || nx == a || nx == b {
            return nx;
        }
        x = nx;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// Coefficients of the monic polynomial with the given roots times `scale`.
    fn from_roots(roots: &[f64], scale: f64) -> Vec<f64> {
        let mut c = vec![scale];
        for &r in roots {
            let mut n = vec![0.0; c.len() + 1];
            for (k, &ck) in c.iter().enumerate() {
                n[k + 1] += ck;
                n[k] -= r * ck;
            }
            c = n;
        }
        c
    }

    #[test]
    fn random_polynomials_with_known_roots() {
        let mut rng = SplitMix64::new(11);
        for trial in 0..20000 {
            let deg = 1 + trial % MAX_POLY;
            let mut roots: Vec<f64> = (0..deg).map(|_| rng.uniform(-10.0, 10.0)).collect();
            roots.sort_by(f64::total_cmp);
            // Keep roots apart so that each is well conditioned.
            if roots.windows(2).any(|w| w[1] - w[0] < 0.2) {
                continue;
            }
            let scale =
                10f64.powf(rng.uniform(-6.0, 6.0)) * if trial % 2 == 0 { 1.0 } else { -1.0 };
            let c = from_roots(&roots, scale);
            let mut out = [0.0; MAX_POLY];
            let n = poly_roots(&c, -11.0, 11.0, &mut out);
            assert_eq!(n, deg, "{roots:?} -> {:?}", &out[..n]);
            for (r, e) in out[..n].iter().zip(&roots) {
                assert!(
                    (r - e).abs() < 1e-9 * e.abs().max(1.0),
                    "{roots:?}: {r} vs {e}"
                );
            }
            // A window holding only some of the roots.
            let n = poly_roots(&c, 0.0, 11.0, &mut out);
            assert_eq!(n, roots.iter().filter(|&&r| r >= 0.0).count());
        }
    }

    #[test]
    fn double_roots_and_degenerate_leading_terms() {
        let mut out = [0.0; MAX_POLY];
        // (x − 1)²(x + 2): tangent root at 1.
        let n = poly_roots(&from_roots(&[1.0, 1.0, -2.0], 1.0), -5.0, 5.0, &mut out);
        assert_eq!(&out[..n], &[-2.0, 1.0]);
        // Quadratic with a double root.
        let (k, q) = quadratic(1.0, -2.0, 1.0);
        assert_eq!((k, q), (2, [1.0, 1.0]));
        // A leading coefficient at round-off level is ignored: 2x − 1 (+1e-30 x³).
        let n = poly_roots(&[-1.0, 2.0, 0.0, 1e-30], -1.0, 1.0, &mut out);
        assert_eq!(n, 1);
        assert_eq!(out[0], 0.5);
        // Same sign at both ends with roots inside (the Budan–Fourier pre-test must not skip
        // it), and a window without roots.
        let c = from_roots(&[1.0, 2.0, 3.0, 4.0], 1.0);
        assert_eq!(poly_roots(&c, 0.5, 4.5, &mut out), 4);
        assert_eq!(root_bound(&c, 4.5, 10.0), Some(0));
        assert_eq!(root_bound(&c, 0.5, 1.5), Some(1));
        assert_eq!(poly_roots(&c, 4.5, 10.0, &mut out), 0);
        // No roots, constant, zero polynomial.
        assert_eq!(poly_roots(&[1.0, 0.0, 1.0], -3.0, 3.0, &mut out), 0);
        assert_eq!(poly_roots(&[2.0], -3.0, 3.0, &mut out), 0);
        assert_eq!(poly_roots(&[0.0, 0.0], -3.0, 3.0, &mut out), 0);
    }
}
