//! Real roots of a scalar residual that is not a polynomial, or is defined only on part of an
//! interval (the fallback of online generation's profile families).
//!
//! Every profile family of the online generator leaves one free parameter after the velocity
//! (and, in step 2, the duration) equations have been solved in closed form; the remaining
//! position equation is a scalar residual r(x) that is only defined where the family's shape
//! is valid (durations ≥ 0, accelerations within the limits). [`find_roots`] samples r on a
//! grid that is dense near both ends (small motions live there), refines every sign change by
//! the Illinois variant of regula falsi down to adjacent floating-point numbers, and locates
//! the edges of the valid domain by bisection so that roots sitting on an edge are not lost.
//!
//! Precision: a root is returned when its bracket is as narrow as f64 allows (or after 200
//! iterations). The callers verify what they build from a root, so a missed or imprecise root
//! can cost optimality but never correctness.

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

/// Sorts the cut points, clips them to [cuts[0], cuts[1]] and calls `f` on each piece.
pub(crate) fn for_each_piece<const N: usize>(cuts: &mut [f64; N], mut f: impl FnMut(f64, f64)) {
    let (lo, hi) = (cuts[0], cuts[1]);
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return;
    }
    for c in cuts.iter_mut() {
        *c = c.clamp(lo, hi);
    }
    cuts.sort_by(|a, b| a.total_cmp(b));
    for k in 0..N - 1 {
        if cuts[k + 1] > cuts[k] || (k == 0 && lo == hi) {
            f(cuts[k], cuts[k + 1]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
