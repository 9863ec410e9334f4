//! Where the bracketed step-2 families' shapes are valid: the free parameter's valid range
//! (hold families) or the cut points at which validity can change (four ramps, split ramp,
//! peak then hold), all in closed form.
//!
//! A family's residual is `None` where its shape is invalid, and [`super::super::bracket`]
//! samples each piece between cut points on a fixed grid: a valid range strictly between two
//! samples was invisible, and with it every profile of that shape (the `per_dof_interface`
//! sweep reproducer: a hold shape valid on 6 % of its range, synchronized 0.38 % longer than
//! Ruckig). With every point where a validity condition changes as a cut, each piece is
//! valid or invalid as a whole, so the grid samples every valid piece inside and the
//! bracketing finds the exact edges. A cut that does not exist (no real root, a zero
//! denominator) is replaced by the piece's lower bound, an empty piece.
//!
//! Precision: the cuts are closed forms of a few operations each (rounding errors of a few
//! units of the levels' scale); a cut off by that much leaves a sliver of a piece with the
//! other validity, which the bracketing's edge search handles as before. The profiles built
//! from the roots are verified by the caller as always.
//!
//! Cost: a few arithmetic operations and square roots per family call; more pieces mean more
//! grid samples (23 per piece) where the cuts fall inside the parameter's range.

use super::super::problem::Dof1;

/// `x`, or `or` when `x` is not finite (a cut that does not exist).
fn finite_or(x: f64, or: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        or
    }
}

/// The real roots of x² + bx + c (NaN when there are none).
fn monic_roots(b: f64, c: f64) -> [f64; 2] {
    let d = b * b / 4.0 - c;
    if d < 0.0 {
        return [f64::NAN; 2];
    }
    let r = d.sqrt();
    [-b / 2.0 - r, -b / 2.0 + r]
}

/// The range of a hold family's free parameter x on which its shape is valid, widened by
/// `margin` plus a few rounding units (the bracketing then finds the exact edges from invalid
/// samples); `None` when the family is degenerate (k ≤ 0 or non-finite values: the caller
/// keeps its bounds), an empty range (lo > hi) when no x is valid.
///
/// With k = jT + a₀ − a_f and c = jΔv − (a_f² − a₀²)/2, the radicand of the velocity equation
/// is linear in x: r = c − kx at the valley (x = α₂, α₁ = x + √r), r = kx − c at the peak
/// (x = α₁, α₂ = x − √r). In s = √r the hold lasts T − (2s − a₀ + a_f)/j, so s ∈ [0, k/2],
/// and the level that x does not fix, as dep(s) = d/k + s − s²/k (dep = α₁ and d = c at the
/// valley, dep = −α₂ and d = −c at the peak), rises on [0, k/2]. Its bounds `dep` therefore
/// cut out one interval of s, and x = (c ∓ s²)/k is monotone in s: one interval of x.
pub(super) fn hold_window(
    k: f64,
    c: f64,
    at_valley: bool,
    dep: (f64, f64),
    margin: f64,
) -> Option<(f64, f64)> {
    if !(k > 0.0 && k.is_finite() && c.is_finite()) {
        return None;
    }
    let d = if at_valley { c } else { -c };
    let (dep0, dep1) = (d / k, d / k + k / 4.0);
    if dep.1 < dep0 || dep.0 > dep1 {
        return Some((f64::INFINITY, f64::NEG_INFINITY));
    }
    // The smaller root of s² − ks + (level·k − d) = 0, in the form without cancellation.
    let s_at = |level: f64| {
        if level <= dep0 {
            0.0
        } else if level >= dep1 {
            k / 2.0
        } else {
            let q = level * k - d;
            let disc = (k * k - 4.0 * q).max(0.0);
            (2.0 * q / (k + disc.sqrt())).clamp(0.0, k / 2.0)
        }
    };
    let (s0, s1) = (s_at(dep.0), s_at(dep.1));
    let (a, b) = if at_valley {
        ((c - s1 * s1) / k, (c - s0 * s0) / k)
    } else {
        ((c + s0 * s0) / k, (c + s1 * s1) / k)
    };
    let m = margin + 4.0 * f64::EPSILON * (a.abs() + b.abs());
    Some((a - m, b + m))
}

/// The cut points of [`super::four_ramps`]' free level α₂ = x ∈ [a_min, a_max]: 0, a₀, a_f, and
/// every x where the shape's validity can change, so that each piece is valid or invalid as
/// a whole and the bracketing grid samples every valid piece inside (a valid range between
/// two grid samples was missed otherwise).
///
/// With k₁ = (a₀ + a_f − jT)/2 and k₂ = (a₀² + a_f² − 2jΔv)/2, α₁ + α₃ = x + k₁ and
/// α₁α₃ = (2k₁x + k₁² − k₂)/2, so the radicand (α₁ − α₃)² = x² − 2k₁x + 2k₂ − k₁² vanishes at
/// x = k₁ ± √(2(k₁² − k₂)), and α₁ or α₃ equals a level c where c² − (x + k₁)c + α₁α₃ = 0,
/// linear in x: x = (c² − k₁c + (k₁² − k₂)/2)/(c − k₁), for c = a₀, a_f, a_min (α₁ = α₂ or
/// α₃ = α₂ does not depend on x).
pub(super) fn four_ramps_cuts(q: &Dof1, t: f64) -> [f64; 10] {
    let (lo, hi) = (q.amin, q.amax);
    let k1 = (q.a0 + q.af - q.jmax * t) / 2.0;
    let k2 = (q.a0 * q.a0 + q.af * q.af - 2.0 * q.jmax * (q.vf - q.v0)) / 2.0;
    let level = |c: f64| finite_or((c * c - k1 * c + (k1 * k1 - k2) / 2.0) / (c - k1), lo);
    let r = monic_roots(-2.0 * k1, 2.0 * k2 - k1 * k1);
    [
        lo,
        hi,
        0.0,
        q.a0,
        q.af,
        level(q.a0),
        level(q.af),
        level(lo),
        finite_or(r[0], lo),
        finite_or(r[1], lo),
    ]
}

/// The cut points of [`super::split_ramp`]'s free level α ∈ [a_min, a₀]: those it had (0,
/// a_f clamped) and where a validity condition changes.
///
/// Without a plateau, with K = jT − a₀ − a_f and C₀ = (a₀² + a_f²)/2 − jΔv, β = α − √r with
/// r = α² + Kα + C₀: r vanishes at the roots of α² + Kα + C₀, and β equals a level c where
/// r = (α − c)², linear in α: α = (c² − C₀)/(K + 2c), for c = a_min and a_f (τ ≥ 0 and β ≤ α
/// do not depend on α). With a plateau at a_min, τ = A/(α − a_min) with
/// A = Δv − (a₀² − 2a_min² + a_f²)/(2j) − a_min·R and R the time left after the ramps; the
/// hold h = R − τ changes sign at α = a_min + A/R.
pub(super) fn split_ramp_cuts(q: &Dof1, t: f64, plateau: bool) -> [f64; 8] {
    let (j, a0, af, m) = (q.jmax, q.a0, q.af, q.amin);
    let dv = q.vf - q.v0;
    let mut cuts = [m; 8];
    cuts[1] = a0;
    cuts[2] = 0.0;
    cuts[3] = af.max(m.min(a0)).min(a0.max(m));
    if plateau {
        let rest = t - (a0 - m) / j - (af - m) / j;
        let k = (a0 * a0 - 2.0 * m * m + af * af) / (2.0 * j);
        cuts[4] = finite_or(m + (dv - k - m * rest) / rest, m);
    } else {
        let kk = j * t - a0 - af;
        let c0 = (a0 * a0 + af * af) / 2.0 - j * dv;
        let level = |c: f64| finite_or((c * c - c0) / (kk + 2.0 * c), m);
        let r = monic_roots(kk, c0);
        cuts[4] = level(m);
        cuts[5] = level(af);
        cuts[6] = finite_or(r[0], m);
        cuts[7] = finite_or(r[1], m);
    }
    cuts
}

/// The cut points of [`super::peak_then_hold`]'s free level (α₁ without a plateau, α₂ with
/// one): its bounds, 0, and where a validity condition changes.
///
/// Without a plateau (x = α₁, S = jT + a₀ + a_f): τ = (S − 2x)/j vanishes at x = S/2;
/// α₂ = (Δv − (2x² − a₀² − a_f²)/(2j))/τ equals a_f at the roots of
/// x² − 2a_f x + a_f(jT + a₀ + a_f) − jΔv − (a₀² + a_f²)/2, and equals α₁ at the roots of
/// x² − Sx + jΔv + (a₀² + a_f²)/2. With a plateau at a_max (x = α₂), τ = A/(x − a_max) with
/// A = Δv − (2a_max² − a₀² − a_f²)/(2j) − a_max·R and R the time left after the ramps; the
/// plateau h = R − τ changes sign at x = a_max + A/R.
pub(super) fn peak_then_hold_cuts(q: &Dof1, t: f64, plateau: bool) -> [f64; 8] {
    let (j, a0, af, amax) = (q.jmax, q.a0, q.af, q.amax);
    let dv = q.vf - q.v0;
    let lo = if plateau { af } else { a0.max(af) };
    let hi = amax.max(lo);
    let mut cuts = [lo; 8];
    cuts[1] = hi;
    cuts[2] = 0.0f64.max(lo).min(hi);
    let sq = (a0 * a0 + af * af) / 2.0;
    if plateau {
        let rest = t - (2.0 * amax - a0 - af) / j;
        let k = (2.0 * amax * amax - a0 * a0 - af * af) / (2.0 * j);
        cuts[3] = finite_or(amax + (dv - k - amax * rest) / rest, lo);
    } else {
        let s = j * t + a0 + af;
        let to_af = monic_roots(-2.0 * af, af * s - j * dv - sq);
        let to_peak = monic_roots(-s, j * dv + sq);
        cuts[3] = finite_or(s / 2.0, lo);
        cuts[4] = finite_or(to_af[0], lo);
        cuts[5] = finite_or(to_af[1], lo);
        cuts[6] = finite_or(to_peak[0], lo);
        cuts[7] = finite_or(to_peak[1], lo);
    }
    cuts
}
