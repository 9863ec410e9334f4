//! Real roots of a one-parameter residual on an interval, without allocation.
//!
//! Every profile family of the solver leaves one free parameter after the velocity (and, in
//! step 2, the duration) equations have been solved in closed form; the remaining position
//! equation is a scalar residual r(x) that is only defined where the family's shape is valid
//! (durations ≥ 0, accelerations within the limits). [`find_roots`] samples r on a grid that is
//! dense near both ends (small motions live there), refines every sign change by the Illinois
//! variant of regula falsi down to adjacent floating-point numbers, and locates the edges of the
//! valid domain by bisection so that roots sitting on an edge are not lost.
//!
//! [`poly_roots`] finds the real roots of a polynomial of degree ≤ [`MAX_POLY`] in an interval
//! (closed-form linear and quadratic cases). From degree 3 on it first isolates the roots with
//! the Budan–Fourier bound (sign variations of the Taylor coefficients at the two ends, with a
//! round-off guard), bisecting the interval up to two levels: a piece bounded by 0 has no
//! root, a piece bounded by 1 has exactly one, found by Newton's method safeguarded by
//! bisection, and a piece with an even bound and the same sign at both ends has none when a
//! Taylor expansion at one end keeps the polynomial away from zero over the piece. Whatever that does not settle goes to the derivative recursion: the interval is
//! split into monotone pieces at the roots of the derivative, each solved the same way, so
//! tangent roots at a critical point are found too. The closed-form profile families use it; the
//! bracketing solver above stays as the fallback for degenerate cases.
//!
//! Precision: a root is returned when its bracket is as narrow as f64 allows (or after 200
//! iterations); the solver then verifies the resulting profile by integration, so a missed or
//! imprecise root can cost time-optimality but never correctness.

/// Largest number of roots reported per call.
pub const MAX_ROOTS: usize = 8;

/// Relative sample positions in [0, 1]: geometric near both ends, uniform in between.
const GRID: [f64; 23] = [
    0.0, 1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 0.01, 0.03, 0.07, 0.13, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8,
    0.87, 0.93, 0.97, 0.99, 0.999, 1.0,
];

/// A coarser grid for residuals whose valid domain is known in closed form (no edges to find).
const COARSE: [f64; 13] = [
    0.0, 1e-9, 1e-5, 1e-3, 0.03, 0.12, 0.27, 0.45, 0.63, 0.8, 0.93, 0.99, 1.0,
];

/// Roots of `f` in `[lo, hi]`. `f` returns `None` where the parameter is outside its family's
/// valid domain. Writes up to [`MAX_ROOTS`] roots into `out` and returns how many.
pub fn find_roots(
    f: &mut impl FnMut(f64) -> Option<f64>,
    lo: f64,
    hi: f64,
    out: &mut [f64; MAX_ROOTS],
) -> usize {
    find_roots_on(&GRID, f, lo, hi, out)
}

/// Like [`find_roots`] on the coarse grid, for a residual that is valid on all of `[lo, hi]`.
pub fn find_roots_coarse(
    f: &mut impl FnMut(f64) -> Option<f64>,
    lo: f64,
    hi: f64,
    out: &mut [f64; MAX_ROOTS],
) -> usize {
    find_roots_on(&COARSE, f, lo, hi, out)
}

fn find_roots_on(
    grid: &[f64],
    f: &mut impl FnMut(f64) -> Option<f64>,
    lo: f64,
    hi: f64,
    out: &mut [f64; MAX_ROOTS],
) -> usize {
    let mut n = 0;
    if !(lo.is_finite() && hi.is_finite()) || hi < lo {
        return 0;
    }
    let push = |x: f64, out: &mut [f64; MAX_ROOTS], n: &mut usize| {
        if *n > 0 && out[*n - 1] == x {
            return;
        }
        if *n < MAX_ROOTS {
            out[*n] = x;
            *n += 1;
        }
    };
    if hi == lo {
        if let Some(r) = f(lo) {
            if r == 0.0 {
                push(lo, out, &mut n);
            }
        }
        return n;
    }
    let w = hi - lo;
    let mut px = lo;
    let mut py = f(lo);
    if py == Some(0.0) {
        push(lo, out, &mut n);
    }
    for &g in &grid[1..] {
        let x = if g == 1.0 { hi } else { lo + w * g };
        if x <= px {
            continue;
        }
        let y = f(x);
        match (py, y) {
            (Some(a), Some(b)) => {
                if b == 0.0 {
                    push(x, out, &mut n);
                } else if a != 0.0 && (a < 0.0) != (b < 0.0) {
                    push(refine(f, px, x, a, b), out, &mut n);
                }
            }
            (Some(a), None) => {
                // Valid on the left, invalid on the right: find the edge.
                let (e, fe) = edge(f, px, x, true);
                if fe == 0.0 {
                    push(e, out, &mut n);
                } else if a != 0.0 && (a < 0.0) != (fe < 0.0) {
                    push(refine(f, px, e, a, fe), out, &mut n);
                } else if is_tiny(fe, a) {
                    push(e, out, &mut n);
                }
            }
            (None, Some(b)) => {
                let (e, fe) = edge(f, px, x, false);
                if fe == 0.0 || is_tiny(fe, b) {
                    push(e, out, &mut n);
                } else if b != 0.0 && (b < 0.0) != (fe < 0.0) {
                    push(refine(f, e, x, fe, b), out, &mut n);
                }
                if b == 0.0 {
                    push(x, out, &mut n);
                }
            }
            (None, None) => {}
        }
        px = x;
        py = y;
    }
    n
}

fn is_tiny(v: f64, scale: f64) -> bool {
    v.abs() <= 1e-15 * scale.abs().max(f64::MIN_POSITIVE)
}

/// Bisects for the edge of the valid domain between a valid and an invalid point; returns the
/// last valid point and its residual.
fn edge(f: &mut impl FnMut(f64) -> Option<f64>, a: f64, b: f64, valid_left: bool) -> (f64, f64) {
    let (mut good, mut bad) = if valid_left { (a, b) } else { (b, a) };
    let mut fg = f(good).unwrap_or(f64::NAN);
    for _ in 0..80 {
        let m = 0.5 * (good + bad);
        if m == good || m == bad {
            break;
        }
        match f(m) {
            Some(v) => {
                good = m;
                fg = v;
            }
            None => bad = m,
        }
    }
    (good, fg)
}

/// Illinois regula falsi on a bracket with f(a)·f(b) < 0; falls back to bisection when a
/// trial point is invalid.
fn refine(
    f: &mut impl FnMut(f64) -> Option<f64>,
    mut a: f64,
    mut b: f64,
    mut fa: f64,
    mut fb: f64,
) -> f64 {
    let mut side = 0i8;
    let mut prev = f64::NAN;
    for _ in 0..200 {
        let mut m = (a * fb - b * fa) / (fb - fa);
        if !(m > a && m < b) {
            m = 0.5 * (a + b);
        }
        if m <= a || m >= b {
            break;
        }
        // Converged: two successive estimates agree to a few ulp.
        if (m - prev).abs() <= 4.0 * f64::EPSILON * m.abs() {
            return m;
        }
        prev = m;
        let Some(fm) = f(m) else {
            // Should not happen inside a valid bracket; bisect instead.
            let mid = 0.5 * (a + b);
            if mid <= a || mid >= b {
                break;
            }
            match f(mid) {
                Some(v) if (v < 0.0) == (fa < 0.0) => {
                    a = mid;
                    fa = v;
                }
                Some(v) => {
                    b = mid;
                    fb = v;
                }
                None => break,
            }
            continue;
        };
        if fm == 0.0 {
            return m;
        }
        if (fm < 0.0) == (fa < 0.0) {
            a = m;
            fa = fm;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = m;
            fb = fm;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
        if b - a <= 2.0 * f64::EPSILON * a.abs().max(b.abs()) {
            break;
        }
    }
    if fa.abs() < fb.abs() {
        a
    } else {
        b
    }
}

/// Highest polynomial degree [`poly_roots`] accepts.
pub const MAX_POLY: usize = 6;

/// Evaluates the polynomial `c` (lowest order first) and its derivative at `x`.
#[inline]
pub fn horner_d(c: &[f64], x: f64) -> (f64, f64) {
    // Unrolled for the lengths the solver uses (same operations in the same order).
    match c.len() {
        3 => horner_n::<3>(c, x),
        4 => horner_n::<4>(c, x),
        5 => horner_n::<5>(c, x),
        6 => horner_n::<6>(c, x),
        7 => horner_n::<7>(c, x),
        _ => horner_any(c, x),
    }
}

#[inline(always)]
fn horner_n<const N: usize>(c: &[f64], x: f64) -> (f64, f64) {
    let mut p = 0.0;
    let mut dp = 0.0;
    for k in (0..N).rev() {
        dp = dp * x + p;
        p = p * x + c[k];
    }
    (p, dp)
}

#[inline]
fn horner_any(c: &[f64], x: f64) -> (f64, f64) {
    let mut p = 0.0;
    let mut dp = 0.0;
    for &k in c.iter().rev() {
        dp = dp * x + p;
        p = p * x + k;
    }
    (p, dp)
}

/// Real roots of the quadratic c₀ + c₁x + c₂x² (c₂ ≠ 0), without cancellation; returns how
/// many (0 or 2, a double root twice), increasing.
#[inline]
pub fn quadratic(c0: f64, c1: f64, c2: f64) -> (usize, [f64; 2]) {
    let disc = c1 * c1 - 4.0 * c2 * c0;
    if disc < 0.0 {
        // Tangent within round-off: report the vertex.
        if disc >= -1e-14 * (c1 * c1).max((4.0 * c2 * c0).abs()) {
            let x = -c1 / (2.0 * c2);
            return (2, [x, x]);
        }
        return (0, [0.0; 2]);
    }
    let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
    let (r1, r2) = if q == 0.0 {
        (0.0, 0.0)
    } else {
        (q / c2, c0 / q)
    };
    (2, if r1 <= r2 { [r1, r2] } else { [r2, r1] })
}

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
            for k in 1..len {
                d[k - 1] = c[k] * k as f64;
            }
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
    let mut x = (a + w * (fa / (fa - fb))).clamp(a + w / 64.0, b - w / 64.0);
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

    #[test]
    fn cubic_roots_and_domain_edges() {
        let mut out = [0.0; MAX_ROOTS];
        let mut f = |x: f64| Some((x - 0.1) * (x - 0.5) * (x - 0.9));
        let n = find_roots(&mut f, 0.0, 1.0, &mut out);
        assert_eq!(n, 3);
        for (r, e) in out[..3].iter().zip([0.1, 0.5, 0.9]) {
            assert!((r - e).abs() < 1e-15);
        }
        // Defined only on [0, 0.3]; root exactly at the edge.
        let mut g = |x: f64| (x <= 0.3).then_some(x - 0.3);
        let n = find_roots(&mut g, 0.0, 1.0, &mut out);
        assert_eq!(n, 1);
        assert!((out[0] - 0.3).abs() < 1e-15);
        // Tiny root near the left end of a wide interval.
        let mut h = |x: f64| Some(x - 1e-7);
        let n = find_roots(&mut h, 0.0, 1e6, &mut out);
        assert_eq!(n, 1);
        assert!((out[0] - 1e-7).abs() < 1e-20);
    }
}
