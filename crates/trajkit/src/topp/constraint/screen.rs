//! The block screen of [`super::Constraint::screen_block`] for joint velocity and
//! acceleration: one test per joint over a block of consecutive intervals of one path piece
//! that proves [`super::Constraint::hold_on_cubic`] would write no row for that joint on any
//! interval of the block, so the per-interval work is skipped for it.
//!
//! # Precision contract
//! The screen only skips joints whose per-interval tests would skip them too: it rests on the
//! subdivision property of Bernstein coefficients (those of a polynomial on a sub-interval lie
//! within the range of those on the whole block) and bounds every per-interval quantity by the
//! block's. The block's bounds are widened by [`MARGIN`] times the size of the coefficients
//! they come from, far above the rounding of either computation (≈ 1e-15 relative), so the
//! rows written are the same as without the screen.

use super::{CubicPiece, JointAcceleration, JointVelocity};

/// Relative widening of the block's bounds (and narrowing of the limits) against rounding.
const MARGIN: f64 = 1e-9;

/// Joint j's σ′ and σ″ over a whole block: `(lo, hi, m2)` with |σ′| ≥ `lo` (zero when σ′ may
/// vanish), |σ′| ≤ `hi` and |σ″| ≤ `m2` on every sub-interval's Bernstein coefficients (degree
/// 2 and 1 on a cubic piece, 4 and 3 otherwise, the degrees the per-interval tests use), each
/// widened by [`MARGIN`]. The sign of σ′ on the block: +1, −1 or 0 (may change).
#[derive(Clone, Copy)]
struct Hull {
    lo: f64,
    hi: f64,
    m2: f64,
    sign: f64,
}

/// `cubic`: whether the block is a cubic piece ([`CubicPiece::is_cubic`], asked once per
/// block).
fn hull(block: &CubicPiece<'_>, cubic: bool, j: usize) -> Option<Hull> {
    let l = block.s1 - block.s0;
    let (d1, d2, d3) = (block.d1[j], block.d2[j], block.d3[j]);
    let (d4, d5) = (block.d4[j], block.d5[j]);
    // Power coefficients in θ ∈ [0, 1] of σ′ and σ″, then their Bernstein coefficients.
    let p = [
        d1,
        d2 * l,
        0.5 * d3 * l * l,
        d4 / 6.0 * l * l * l,
        d5 / 24.0 * l * l * l * l,
    ];
    let q = [d2, d3 * l, 0.5 * d4 * l * l, d5 / 6.0 * l * l * l];
    let (b1, b2): (&[f64], &[f64]);
    let (c1, c2);
    if cubic {
        c1 = [d1, d1 + 0.5 * p[1], d1 + p[1] + p[2], 0.0, 0.0];
        c2 = [q[0], q[0] + q[1], 0.0, 0.0];
        (b1, b2) = (&c1[..3], &c2[..2]);
    } else {
        c1 = super::quintic::power_to_bernstein4(p);
        c2 = [
            q[0],
            q[0] + q[1] / 3.0,
            q[0] + 2.0 * q[1] / 3.0 + q[2] / 3.0,
            q[0] + q[1] + q[2] + q[3],
        ];
        (b1, b2) = (&c1[..], &c2[..]);
    }
    let tol1 = MARGIN * p.iter().map(|v| v.abs()).sum::<f64>();
    let tol2 = MARGIN * q.iter().map(|v| v.abs()).sum::<f64>();
    let hi = b1.iter().fold(0.0f64, |m, v| m.max(v.abs())) + tol1;
    let min = b1.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    let max = b1.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    let (lo, sign) = if min - tol1 > 0.0 {
        (min - tol1, 1.0)
    } else if max + tol1 < 0.0 {
        (-max - tol1, -1.0)
    } else {
        (0.0, 0.0)
    };
    let m2 = b2.iter().fold(0.0f64, |m, v| m.max(v.abs())) + tol2;
    [lo, hi, m2]
        .iter()
        .all(|v| v.is_finite())
        .then_some(Hull { lo, hi, m2, sign })
}

impl JointVelocity {
    /// Marks the joints whose quick test (max |σ′|² · x ≤ limit², see
    /// [`JointVelocity`]'s `hold_on_cubic`) passes on every interval of the block. Returns
    /// whether any was marked.
    pub(super) fn screen(&self, block: &CubicPiece<'_>, x_max: f64, skip: &mut [bool]) -> bool {
        if skip.len() < self.hi.len() {
            return false;
        }
        let cubic = block.is_cubic();
        let mut any = false;
        for j in 0..self.hi.len() {
            skip[j] = false;
            let Some(h) = hull(block, cubic, j) else {
                continue;
            };
            // The per-interval limit is at least this one (the larger side only when σ′ keeps
            // its sign on the whole block).
            let limit = if h.sign > 0.0 {
                self.hi[j]
            } else if h.sign < 0.0 {
                -self.lo[j]
            } else {
                self.hi[j].min(-self.lo[j])
            };
            let l = limit * (1.0 - MARGIN);
            if h.hi * h.hi * x_max <= l * l {
                skip[j] = true;
                any = true;
            }
        }
        any
    }
}

impl JointAcceleration {
    /// Marks the joints whose interior rows cannot reach their limits on any interval of the
    /// block: with |σ′_k| ≥ lo_k and |σ″_k| ≤ m2_k on the block, every interval's bound on |u|
    /// is at most U = min_k (max(hi_k, −lo_k) + m2_k·X)/lo_k, and every interior Bernstein
    /// coefficient (a, b) of joint j's acceleration rows has |a| ≤ hi_j + 2·h_max·m2_j (σ′ plus
    /// 2(s − s0)·σ″) and |b| ≤ m2_j. Returns whether any joint was marked.
    pub(super) fn screen(
        &self,
        block: &CubicPiece<'_>,
        h_max: f64,
        x_max: f64,
        skip: &mut [bool],
    ) -> bool {
        let n = self.hi.len();
        if skip.len() < n {
            return false;
        }
        skip[..n].iter_mut().for_each(|v| *v = false);
        let mut u_max = f64::INFINITY;
        let mut hulls: [Option<Hull>; 16] = [None; 16];
        if n > hulls.len() {
            return false;
        }
        let cubic = block.is_cubic();
        for k in 0..n {
            hulls[k] = hull(block, cubic, k);
            let Some(h) = hulls[k] else {
                return false;
            };
            if h.lo > 0.0 {
                let u = (self.hi[k].max(-self.lo[k]) + h.m2 * x_max) / h.lo;
                u_max = u_max.min(u * (1.0 + MARGIN));
            }
        }
        let mut any = false;
        for j in 0..n {
            let Some(h) = hulls[j] else {
                continue;
            };
            let reach = (h.hi + 2.0 * h_max * h.m2) * u_max + h.m2 * x_max;
            if reach <= self.hi[j].min(-self.lo[j]) * (1.0 - MARGIN) {
                skip[j] = true;
                any = true;
            }
        }
        any
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Constraint, ConstraintRows};
    use super::*;
    use crate::rng::SplitMix64;

    /// Taylor data (orders 1..5, block k holding order k + 1) moved by `t`.
    fn shift(d: &[[f64; 5]], t: f64) -> Vec<[f64; 5]> {
        d.iter()
            .map(|v| {
                std::array::from_fn(|m| {
                    let (mut acc, mut f) = (0.0, 1.0);
                    for (n, k) in (m..5).enumerate() {
                        if n > 0 {
                            f *= t / n as f64;
                        }
                        acc += v[k] * f;
                    }
                    acc
                })
            })
            .collect()
    }

    fn piece_of<'a>(s0: f64, s1: f64, cols: &'a [Vec<f64>; 6]) -> CubicPiece<'a> {
        CubicPiece {
            s0,
            s1,
            d0: &cols[0],
            d1: &cols[1],
            d2: &cols[2],
            d3: &cols[3],
            d4: &cols[4],
            d5: &cols[5],
        }
    }

    fn columns(d: &[[f64; 5]]) -> [Vec<f64>; 6] {
        std::array::from_fn(|k| {
            if k == 0 {
                vec![0.0; d.len()]
            } else {
                d.iter().map(|v| v[k - 1]).collect()
            }
        })
    }

    /// On random cubic and quintic blocks, the rows written with the screen's skips equal the
    /// rows written without them, interval by interval; the screen skips joints and rows are
    /// still written (the comparison is not vacuous).
    #[test]
    fn screened_rows_equal_unscreened_rows() {
        let mut rng = SplitMix64::new(7);
        let dim = 7;
        let (mut skipped, mut rows) = (0usize, 0usize);
        for case in 0..400 {
            let degree = if case % 2 == 0 { 3 } else { 5 };
            let d: Vec<[f64; 5]> = (0..dim)
                .map(|_| {
                    std::array::from_fn(|k| {
                        if k < degree {
                            rng.uniform(-3.0, 3.0)
                        } else {
                            0.0
                        }
                    })
                })
                .collect();
            let scale = 10f64.powf(rng.uniform(-1.0, 1.5));
            let lim = |rng: &mut SplitMix64| scale * 10f64.powf(rng.uniform(-1.0, 1.0));
            let hi: Vec<f64> = (0..dim).map(|_| lim(&mut rng)).collect();
            let lo: Vec<f64> = (0..dim).map(|_| -lim(&mut rng)).collect();
            let cons: [Box<dyn Constraint>; 2] = [
                Box::new(JointVelocity::new(&lo, &hi).unwrap()),
                Box::new(JointAcceleration::new(&lo, &hi).unwrap()),
            ];
            let n = 16;
            let h = rng.uniform(0.001, 0.05);
            let xs: Vec<f64> = (0..=n).map(|_| rng.uniform(0.0, 2.0)).collect();
            let x_block = xs.iter().fold(0.0f64, |m, &v| m.max(v));
            let block_cols = columns(&d);
            let block = piece_of(0.0, n as f64 * h, &block_cols);
            for c in &cons {
                let mut skip = vec![false; dim];
                if !c.screen_block(&block, h, x_block, &mut skip) {
                    continue;
                }
                skipped += skip.iter().filter(|&&v| v).count();
                for i in 0..n {
                    let cols = columns(&shift(&d, i as f64 * h));
                    let piece = piece_of(i as f64 * h, (i + 1) as f64 * h, &cols);
                    let x_max = [xs[i], xs[i + 1]];
                    let (mut all, mut some) = (ConstraintRows::new(), ConstraintRows::new());
                    assert!(c.hold_on_cubic(&piece, x_max, &mut all));
                    assert!(c.hold_on_screened(&piece, x_max, &skip, &mut some));
                    assert_eq!(all.half_planes(), some.half_planes(), "case {case}");
                    rows += all.half_planes().len();
                }
            }
        }
        assert!(
            skipped > 100 && rows > 100,
            "{skipped} skipped, {rows} rows"
        );
    }
}
