//! Real roots of polynomials of degree ≤ [`MAX_DEGREE`] on an interval by derivative
//! recursion: the general solver, for extrema of polynomials.
//!
//! Method: between consecutive roots of p′ the polynomial p is monotone, so each such interval
//! holds at most one root of p, found by bisection on a sign change. Recursing down to degree 1
//! isolates every root of odd multiplicity. Roots of even multiplicity (tangent roots, no sign
//! change) are reported only when |p| there is below `1e-14 · scale`; they do not matter for
//! finding extrema, which is what trajkit uses this for.
//!
//! Precision: each root is bracketed to a width of at most 4 ulp of the interval's larger end
//! (bisection runs until the midpoint no longer moves).

use super::{derivative, horner};

/// Largest polynomial degree [`roots_in`] and [`max_abs_in`] accept.
pub const MAX_DEGREE: usize = 8;

/// Real roots of the polynomial with coefficients `c` (lowest order first, degree ≤
/// [`MAX_DEGREE`]) in the closed interval `[a, b]`, written increasing into `out`; returns how
/// many. Duplicates closer than the bracketing width are merged.
///
/// Returns 0 for a polynomial that is identically zero, or for a degree above `MAX_DEGREE`.
pub fn roots_in(c: &[f64], a: f64, b: f64, out: &mut [f64; MAX_DEGREE]) -> usize {
    // Trim trailing zero coefficients.
    let mut len = c.len();
    while len > 0 && c[len - 1] == 0.0 {
        len -= 1;
    }
    if len <= 1 || len > MAX_DEGREE + 1 || a.is_nan() || b.is_nan() || a > b {
        return 0;
    }
    let c = &c[..len];
    if len == 2 {
        let r = -c[0] / c[1];
        if r >= a && r <= b {
            out[0] = r;
            return 1;
        }
        return 0;
    }
    // Critical points: roots of the derivative.
    let mut d = [0.0; MAX_DEGREE + 1];
    let dl = derivative(c, &mut d);
    let mut crit = [0.0; MAX_DEGREE];
    let nc = roots_in(&d[..dl], a, b, &mut crit);
    // Monotone pieces: a, crit..., b.
    let mut pts = [0.0; MAX_DEGREE + 2];
    pts[0] = a;
    pts[1..=nc].copy_from_slice(&crit[..nc]);
    pts[nc + 1] = b;
    let scale = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut count = 0;
    let push = |r: f64, out: &mut [f64; MAX_DEGREE], count: &mut usize| {
        if *count > 0 && (r - out[*count - 1]).abs() <= 4.0 * f64::EPSILON * r.abs().max(1.0) {
            return;
        }
        if *count < MAX_DEGREE {
            out[*count] = r;
            *count += 1;
        }
    };
    for k in 0..=nc {
        let (lo, hi) = (pts[k], pts[k + 1]);
        let flo = horner(c, lo);
        let fhi = horner(c, hi);
        if flo == 0.0 {
            push(lo, out, &mut count);
            continue;
        }
        if fhi == 0.0 {
            if k == nc {
                push(hi, out, &mut count);
            }
            continue;
        }
        if (flo > 0.0) == (fhi > 0.0) {
            // No sign change: a tangent root sits at a critical point if p is ~0 there.
            if k > 0 && flo.abs() <= 1e-14 * scale {
                push(lo, out, &mut count);
            }
            continue;
        }
        push(bisect(c, lo, hi, flo), out, &mut count);
    }
    count
}

/// The root of `c` in `[lo, hi]`, where `c` is monotone with a sign change and `flo` = p(lo) ≠ 0:
/// bisection until the midpoint no longer moves (a bracket of a few ulp), its midpoint returned.
fn bisect(c: &[f64], mut lo: f64, mut hi: f64, mut flo: f64) -> f64 {
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let fm = horner(c, mid);
        if fm == 0.0 {
            return mid;
        }
        if (fm > 0.0) == (flo > 0.0) {
            lo = mid;
            flo = fm;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The largest |p(x)| over `[a, b]` and where it occurs (the first place, scanning from `a`).
pub fn max_abs_in(c: &[f64], a: f64, b: f64) -> (f64, f64) {
    let mut best = (horner(c, a).abs(), a);
    let fb = horner(c, b).abs();
    if fb > best.0 {
        best = (fb, b);
    }
    if c.len() <= 2 {
        return best;
    }
    let mut d = [0.0; MAX_DEGREE + 1];
    let dl = derivative(c, &mut d);
    let mut crit = [0.0; MAX_DEGREE];
    let n = roots_in(&d[..dl], a, b, &mut crit);
    for &x in &crit[..n] {
        let v = horner(c, x).abs();
        if v > best.0 {
            best = (v, x);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    #[test]
    fn analytic_roots() {
        let mut r = [0.0; MAX_DEGREE];
        // (x-0.2)(x-0.5)(x-0.9) = x^3 - 1.6x^2 + 0.73x - 0.09
        let n = roots_in(&[-0.09, 0.73, -1.6, 1.0], 0.0, 1.0, &mut r);
        assert_eq!(n, 3);
        for (got, want) in r[..3].iter().zip([0.2, 0.5, 0.9]) {
            assert!((got - want).abs() < 1e-14, "{got} {want}");
        }
        // Double root at 0.5: (x-0.5)^2 — tangent, reported.
        let n = roots_in(&[0.25, -1.0, 1.0], 0.0, 1.0, &mut r);
        assert_eq!(n, 1);
        assert!((r[0] - 0.5).abs() < 1e-12);
        // No real roots.
        assert_eq!(roots_in(&[1.0, 0.0, 1.0], -5.0, 5.0, &mut r), 0);
        // Zero polynomial and constant.
        assert_eq!(roots_in(&[0.0, 0.0], 0.0, 1.0, &mut r), 0);
        assert_eq!(roots_in(&[3.0], 0.0, 1.0, &mut r), 0);
        // Root at the interval end.
        assert_eq!(roots_in(&[-1.0, 1.0], 0.0, 1.0, &mut r), 1);
        assert_eq!(r[0], 1.0);
    }

    #[test]
    fn random_products_of_linear_factors() {
        let mut g = SplitMix64::new(42);
        for _ in 0..2000 {
            let deg = 1 + g.below(7) as usize;
            let mut roots: Vec<f64> = (0..deg).map(|_| g.uniform(-0.95, 0.95)).collect();
            roots.sort_by(f64::total_cmp);
            if roots.windows(2).any(|w| w[1] - w[0] < 1e-3) {
                continue;
            }
            // Expand prod (x - r).
            let mut c = vec![1.0];
            for &rt in &roots {
                let mut nc = vec![0.0; c.len() + 1];
                for (i, &ci) in c.iter().enumerate() {
                    nc[i + 1] += ci;
                    nc[i] -= rt * ci;
                }
                c = nc;
            }
            let mut r = [0.0; MAX_DEGREE];
            let n = roots_in(&c, -1.0, 1.0, &mut r);
            assert_eq!(n, deg, "{roots:?} -> {:?}", &r[..n]);
            for (got, want) in r[..n].iter().zip(&roots) {
                assert!((got - want).abs() < 1e-9, "{got} vs {want}");
            }
        }
    }

    #[test]
    fn max_abs() {
        // 3x^2 - 2x^3 has derivative 6x - 6x^2: max |.| on [0,1] of the derivative is 1.5 at 0.5.
        let (v, x) = max_abs_in(&[0.0, 6.0, -6.0], 0.0, 1.0);
        assert!((v - 1.5).abs() < 1e-15 && (x - 0.5).abs() < 1e-12);
        let (v, x) = max_abs_in(&[0.0, 6.0, -6.0], 0.0, 2.0);
        assert_eq!((v, x), (12.0, 2.0));
    }
}
