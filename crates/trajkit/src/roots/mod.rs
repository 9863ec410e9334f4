//! Real roots of polynomials and scalar residuals on an interval, without allocation: the
//! one home of trajkit's root finders.
//!
//! Three solvers, each where it is the right tool:
//!
//! | solver | used by | method | degree | precision |
//! |---|---|---|---|---|
//! | [`roots_in`], [`max_abs_in`] | extrema of polynomials (`poly`, spline bounds, TOPP certificates, `otg` trajectory queries) | derivative recursion, bisection in each monotone piece | ≤ [`MAX_DEGREE`] | roots bracketed to 4 ulp |
//! | `poly_roots` (crate-internal) | the online generator's profile families, on its real-time path | Budan–Fourier isolation and safeguarded Newton, derivative recursion where that does not settle | ≤ 6 | Newton to 2 ulp; negligible leading terms dropped |
//! | `find_roots`, `find_roots_coarse` (crate-internal) | the online generator's fallback families, whose residual is not a polynomial or is defined on part of the interval | sampling, Illinois regula falsi, bisection for the domain's edges | — | adjacent floating-point numbers |
//!
//! The general solver brackets every root by bisection (robust, about 60 evaluations per
//! root); the fast one isolates the roots first and converges quadratically, at the price of a
//! round-off guard that may hand a hard case to the recursion. Both evaluate by Horner's rule
//! ([`horner`]; `horner_d` with the derivative) and share the derivative and the quadratic
//! formula.
//!
//! Every interval is closed; coefficients are lowest order first. Nothing here allocates.

mod bracket;
mod isolate;
mod recursion;

pub(crate) use bracket::{find_roots, find_roots_coarse, for_each_piece, MAX_ROOTS};
pub(crate) use isolate::{poly_roots, MAX_POLY};
pub use recursion::{max_abs_in, roots_in, MAX_DEGREE};

/// Evaluates `c[0] + c[1] x + ... ` by Horner's rule.
#[inline]
pub fn horner(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ci| acc * x + ci)
}

/// Evaluates the polynomial `c` (lowest order first) and its derivative at `x`.
#[inline]
pub(crate) fn horner_d(c: &[f64], x: f64) -> (f64, f64) {
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
pub(crate) fn quadratic(c0: f64, c1: f64, c2: f64) -> (usize, [f64; 2]) {
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

/// Writes the derivative's coefficients of `c` into `d` (at least `c.len() - 1` long); returns
/// their number.
#[inline]
pub(crate) fn derivative(c: &[f64], d: &mut [f64]) -> usize {
    let n = c.len().saturating_sub(1);
    for i in 0..n {
        d[i] = c[i + 1] * (i + 1) as f64;
    }
    n
}
