//! Path cells for [`super::bound`]: bounds of |σ′|, |σ″|, |σ‴| on short stretches of each
//! path piece, larger than the bound of any segment within, so that a segment (or one joint
//! of it) whose cheap bound from them cannot raise the time-scale factor is not bounded
//! further.
//!
//! # Precision contract
//! Each bound is at least the segment bound `sb` of [`super::bound`] for any segment whose
//! Taylor range fits in the cell, rounding included (margins below). Cost: one Taylor shift
//! and three sums per cell and joint, about four TOPP-RA grid intervals of s per cell.

use super::FilteredProfile;

/// Each path piece cut into equal cells (about four TOPP-RA grid intervals of s each) and,
/// per cell and joint, bounds of |σ⁽ᵏ⁾| (k = 1, 2, 3) on the cell: from σ⁽ᵐ⁾ at the cell's
/// middle c (Taylor from the piece's reference point, as `Sweep::derivative_bounds` of [`super::bound`]),
/// Σₘ |σ⁽ᵐ⁾(c)|·rᵐ⁻ᵏ/(m − k)! with r a little over the half width.
///
/// A segment bound `sb[k]` (Taylor from the segment's middle, at distance δ from c, over
/// the segment's reach e, δ + e ≤ r) is at most this: expanding each |σ⁽ᵐ⁾| at the segment's
/// middle from c and summing gives Σₙ |σ⁽ⁿ⁾(c)|(δ + e)ⁿ⁻ᵏ/(n − k)! (the binomial theorem).
/// For rounding, r is widened by 1e-6 relative, the bound raised by 1e-9 relative and by
/// 1e-12 of the whole piece's bound (the scale of the rounding of σ⁽ᵐ⁾ at points of the
/// piece computed from its reference point).
#[derive(Default)]
pub(super) struct Cells {
    /// Per piece: its start in s, its first cell's index, its cell count (a whole number)
    /// and cell width, and the width's reciprocal (to guess a segment's cell, see
    /// [`Cells::cell`]).
    start: Vec<f64>,
    first: Vec<usize>,
    count: Vec<f64>,
    width: Vec<f64>,
    inv_width: Vec<f64>,
    /// Index (cell·3 + k − 1)·dim + j.
    pub(super) bounds: Vec<f64>,
}

impl Cells {
    pub(super) fn new(
        breaks: &[f64],
        ref_s: &[f64],
        ref_der: &[f64],
        d: usize,
        dim: usize,
        law: &FilteredProfile,
    ) -> Self {
        let gs = law.profile().gridpoints();
        let span = (gs[gs.len() - 1] - gs[0]).abs();
        let target = 4.0 * span / gs.len().max(2) as f64;
        let mut cells = Cells::default();
        let mut sigma = vec![0.0; (d + 1) * dim];
        let mut b = vec![0.0; 3 * dim];
        for (p, pair) in breaks.windows(2).enumerate() {
            let len = pair[1] - pair[0];
            let n = if target > 0.0 && len > 0.0 {
                ((len / target).ceil() as usize).clamp(1, 1 << 16)
            } else {
                1
            };
            let width = len / n as f64;
            cells.start.push(pair[0]);
            cells.first.push(cells.bounds.len() / (3 * dim));
            cells.count.push(n as f64);
            cells.width.push(width);
            cells.inv_width.push(1.0 / width);
            let rd = &ref_der[p * (d + 1) * dim..(p + 1) * (d + 1) * dim];
            let mut whole = vec![0.0; 3 * dim];
            Self::bound(rd, 0.5 * len * (1.0 + 1e-6), d, dim, &mut whole);
            cells.bounds.reserve(n * 3 * dim);
            let r = 0.5 * width * (1.0 + 1e-6);
            for q in 0..n {
                let c = pair[0] + (q as f64 + 0.5) * width;
                let delta = c - ref_s[p];
                // The Taylor weights δʳ/r! for r < d, formed as each m's loop used to form
                // them (the same products and quotients for every m).
                let mut wq = [1.0f64; 8];
                for r in 1..d {
                    wq[r] = wq[r - 1] * (delta / r as f64);
                }
                sigma.fill(0.0);
                for m in 1..=d {
                    for nn in m..=d {
                        let w = wq[nn - m];
                        for j in 0..dim {
                            sigma[m * dim + j] += rd[nn * dim + j] * w;
                        }
                    }
                }
                Self::bound(&sigma, r, d, dim, &mut b);
                cells.bounds.extend(
                    b.iter()
                        .zip(&whole)
                        .map(|(b, w)| b * (1.0 + 1e-9) + 1e-12 * w),
                );
            }
        }
        cells
    }

    /// Σₘ |der[m]|·rᵐ⁻ᵏ/(m − k)! for k = 1, 2, 3 and every joint (index (k − 1)·dim + j; 0
    /// for k above the degree `d`) into `out` (length 3·dim).
    fn bound(der: &[f64], r: f64, d: usize, dim: usize, out: &mut [f64]) {
        out.fill(0.0);
        // r/i, the same quotients for every joint.
        let mut ri = [0.0; 8];
        for (i, x) in ri.iter_mut().enumerate().take(d + 1).skip(1) {
            *x = r / i as f64;
        }
        for k in 1..=3.min(d) {
            for j in 0..dim {
                let (mut b, mut w) = (0.0, 1.0);
                for m in k..d + 1 {
                    b += der[m * dim + j].abs() * w;
                    w *= ri[m - k + 1];
                }
                out[(k - 1) * dim + j] = b;
            }
        }
    }

    /// The cell of `piece` that holds `[sm − reach, sm + reach]`, if one does.
    #[inline]
    pub(super) fn cell(&self, piece: usize, sm: f64, reach: f64) -> Option<usize> {
        let (n, width) = (*self.count.get(piece)?, self.width[piece]);
        let lo = self.start[piece];
        // The cell index guessed with the reciprocal of the width (no division): a guess one
        // cell off near a cell's edge fails the containment test below or passes it, and
        // either way only decides whether a segment may be skipped, never a value. ⌊x⌋ ∈
        // [0, n) exactly when x ∈ [0, n) (n ≤ 2¹⁶ is an integer, NaN fails both), and there
        // ⌊x⌋ is the truncation: no call to `floor`, and exact through i64.
        let x = (sm - lo) * self.inv_width[piece];
        if !(x >= 0.0 && x < n && reach.is_finite()) {
            return None;
        }
        let q = x as i64;
        let c = lo + (q as f64 + 0.5) * width;
        ((sm - c).abs() + reach <= 0.5 * width).then_some(self.first[piece] + q as usize)
    }
}
