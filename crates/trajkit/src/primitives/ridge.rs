//! Ridge regression of basis-function weights, shared by every primitive that learns a forcing
//! term or a weight vector from samples ([`super::Dmp`], [`super::ProMp`],
//! [`super::RhythmicDmp`], [`super::QuaternionDmp`]).
//!
//! The design rows are streamed into [`RidgeAccumulator`]: each row is given as its span of
//! non-zero basis values, rows are buffered [`RB`] at a time and added to `ΦᵀΦ` and `ΦᵀF` as a
//! rank-`RB` update with a register-blocked kernel, so no `rows × basis` matrix is stored and
//! the Gram matrix is read and written once per `RB` rows. The regularized normal equations
//! are solved by [`Cholesky::factor_regularized`].
//!
//! # Precision contract
//! The Gram matrix is accumulated in the order the rows are given (blocked, not compensated);
//! the solve is a Cholesky factorization of `ΦᵀΦ + λ' I`, with the smallest sufficient extra
//! diagonal added (and reported by the factor) when it is not positive definite to working
//! precision. The primitives' reproduction tests bound the end-to-end error of the fit.

use crate::error::Result;
use crate::linalg::Cholesky;

/// Solves the ridge regression `(ΦᵀΦ + λ' I) W = Φᵀ F` for `W` (`nb × cols`), returned
/// row-major `cols × nb` (one row per joint). `λ' = λ s` with `s` the mean diagonal of `ΦᵀΦ`
/// when `relative`, else `λ' = λ`. Each row of `phi` is passed to a [`RidgeAccumulator`] as
/// its span of non-zero entries.
pub(crate) fn ridge_fit(
    phi: &[f64],
    rows: usize,
    nb: usize,
    targets: &[f64],
    cols: usize,
    ridge: f64,
    relative: bool,
) -> Result<Vec<f64>> {
    let mut acc = RidgeAccumulator::new(nb, cols);
    for (r, f) in phi
        .chunks_exact(nb)
        .zip(targets.chunks_exact(cols))
        .take(rows)
    {
        let lo = r.iter().position(|&v| v != 0.0).unwrap_or(0);
        let hi = r.iter().rposition(|&v| v != 0.0).map_or(lo, |p| p + 1);
        acc.add_row(lo, &r[lo..hi], f);
    }
    acc.solve(ridge, relative)
}

/// Rows of the ridge regression's design matrix buffered per flush.
const RB: usize = 32;

/// Accumulates `ΦᵀΦ` (lower triangle) and `ΦᵀF` from design rows given as their span of
/// non-zero entries, [`RB`] rows at a time: each flush adds a rank-`RB` update over the union
/// of the buffered spans with a 2 × 4 register-blocked kernel, so the Gram matrix is read and
/// written once per `RB` rows and no `rows × nb` matrix is ever stored.
pub(crate) struct RidgeAccumulator {
    nb: usize,
    cols: usize,
    gram: Vec<f64>,
    rhs: Vec<f64>,
    /// Buffered rows, row `r` at `r·(nb + 4)` (zero outside its span and in the padding).
    p: Vec<f64>,
    /// Buffered targets, row `r` at `r·(cols + 4)` (zero padding).
    f: Vec<f64>,
    count: usize,
    lo: usize,
    hi: usize,
}

/// `out[s][c] = Σ_r a[r·sa + i + s] · b[r·sb + j + c]` over the [`RB`] buffered rows, for
/// `s < 2`, `c < 4`: two entries of `a`'s rows against four of `b`'s, so that the
/// accumulators are whole vectors and the loop vectorizes without shuffles.
#[inline(always)]
fn kernel_2x4(a: &[f64], sa: usize, i: usize, b: &[f64], sb: usize, j: usize) -> [[f64; 4]; 2] {
    let mut acc = [[0.0f64; 4]; 2];
    for (ar, br) in a.chunks_exact(sa).zip(b.chunks_exact(sb)).take(RB) {
        let x = &ar[i..i + 2];
        let y = &br[j..j + 4];
        for s in 0..2 {
            for c in 0..4 {
                acc[s][c] += x[s] * y[c];
            }
        }
    }
    acc
}

impl RidgeAccumulator {
    /// An empty accumulator for `nb` basis functions and `cols` target columns.
    pub(crate) fn new(nb: usize, cols: usize) -> Self {
        RidgeAccumulator {
            nb,
            cols,
            gram: vec![0.0; nb * nb],
            rhs: vec![0.0; nb * cols],
            p: vec![0.0; (nb + 4) * RB],
            f: vec![0.0; (cols + 4) * RB],
            count: 0,
            lo: nb,
            hi: 0,
        }
    }

    /// Adds the design row whose non-zero entries are `phi` at basis indices `lo..lo +
    /// phi.len()`, with targets `f` (`cols` entries).
    pub(crate) fn add_row(&mut self, lo: usize, phi: &[f64], f: &[f64]) {
        let r = self.count;
        let (sp, sf) = (self.nb + 4, self.cols + 4);
        self.p[r * sp + lo..r * sp + lo + phi.len()].copy_from_slice(phi);
        self.f[r * sf..r * sf + self.cols].copy_from_slice(&f[..self.cols]);
        if !phi.is_empty() {
            self.lo = self.lo.min(lo);
            self.hi = self.hi.max(lo + phi.len());
        }
        self.count += 1;
        if self.count == RB {
            self.flush();
        }
    }

    fn flush(&mut self) {
        let (nb, cols) = (self.nb, self.cols);
        let (sp, sf) = (nb + 4, cols + 4);
        let (lo, hi) = (self.lo, self.hi);
        let (p, f) = (&self.p, &self.f);
        // Two Gram rows at a time, four columns at a time (entries above the diagonal of the
        // last column block are computed and dropped).
        let mut i = lo;
        while i < hi {
            let rows = (hi - i).min(2);
            let mut j = lo;
            while j < i + rows {
                let d = kernel_2x4(p, sp, i, p, sp, j);
                for s in 0..rows {
                    let end = (j + 4).min(i + s + 1);
                    let g = &mut self.gram[(i + s) * nb..(i + s) * nb + end];
                    for (g, v) in g[j..].iter_mut().zip(d[s]) {
                        *g += v;
                    }
                }
                j += 4;
            }
            let mut c = 0;
            while c < cols {
                let d = kernel_2x4(p, sp, i, f, sf, c);
                let end = (c + 4).min(cols);
                for s in 0..rows {
                    let r = &mut self.rhs[(i + s) * cols..(i + s) * cols + end];
                    for (r, v) in r[c..].iter_mut().zip(d[s]) {
                        *r += v;
                    }
                }
                c += 4;
            }
            i += 2;
        }
        if lo < hi {
            for r in 0..self.count {
                self.p[r * sp + lo..r * sp + hi]
                    .iter_mut()
                    .for_each(|v| *v = 0.0);
            }
        }
        self.f.iter_mut().for_each(|v| *v = 0.0);
        self.count = 0;
        self.lo = nb;
        self.hi = 0;
    }

    /// Solves `(ΦᵀΦ + λ' I) W = Φᵀ F` as [`ridge_fit`] describes; `W` row-major `cols × nb`.
    pub(crate) fn solve(mut self, ridge: f64, relative: bool) -> Result<Vec<f64>> {
        self.flush();
        let (nb, cols) = (self.nb, self.cols);
        let mut gram = self.gram;
        for i in 0..nb {
            for j in 0..i {
                gram[j * nb + i] = gram[i * nb + j];
            }
        }
        let s = (0..nb).map(|i| gram[i * nb + i]).sum::<f64>() / nb as f64;
        let lam = if relative && s > 0.0 {
            ridge * s
        } else {
            ridge
        };
        for i in 0..nb {
            gram[i * nb + i] += lam;
        }
        let c = Cholesky::factor_regularized(&gram, nb)?;
        let mut rhs = self.rhs;
        c.solve_matrix_in_place(&mut rhs, cols);
        let mut w = vec![0.0; cols * nb];
        for i in 0..nb {
            for j in 0..cols {
                w[j * nb + i] = rhs[i * cols + j];
            }
        }
        Ok(w)
    }
}
