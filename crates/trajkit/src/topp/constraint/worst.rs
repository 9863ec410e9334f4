//! The worst value of joint velocity or acceleration over a path piece, shared by the cubic
//! and quintic checks: the value sampled at the candidate points (the ends and the roots
//! the callers find) and the relative excess of an enclosure.
//!
//! # Precision contract
//! Values are computed from the piece's Taylor data exactly as the formulas state (no
//! approximation beyond rounding); the callers' candidates make the maximum exact.

use super::CubicPiece;

/// The excess of a value v over a limit l as v/l − 1 (relative), −1 for a zero or infinite
/// limit (nothing to measure against).
fn limit_ratio(v: f64, l: f64) -> f64 {
    if l == 0.0 || l.is_infinite() {
        -1.0
    } else {
        v / l - 1.0
    }
}

/// The relative excess of an acceleration enclosed in `[amin, amax]` (which lies within the
/// limits `[lo, hi]`) over those limits: an upper bound ≤ 0 of the worst value.
pub(super) fn enclosed_excess(amin: f64, amax: f64, lo: f64, hi: f64) -> f64 {
    limit_ratio(amax.max(0.0), hi).max(limit_ratio(amin.min(0.0), lo))
}

/// Raises `worst` (value, where) to `value(σ′_j, σ″_j, x)` at the offsets `ts` from the
/// piece's start, with x = max(x0 + 2u·t, 0): the sampling loop of the joint velocity and
/// acceleration checks at their candidate points (`value` is joint j's, from
/// `JointVelocity::squared_ratio` or `JointAcceleration::excess_at`).
pub(super) fn worst_over(
    piece: &CubicPiece<'_>,
    u: f64,
    x0: f64,
    ts: &[f64],
    worst: &mut (f64, f64),
    (j, value): (usize, impl Fn(f64, f64, f64) -> f64),
) {
    for &t in ts {
        let x = (x0 + 2.0 * u * t).max(0.0);
        let (d1, d2) = piece.derivatives(j, piece.s0 + t);
        let e = value(d1, d2, x);
        if e > worst.0 {
            *worst = (e, piece.s0 + t);
        }
    }
}
