//! Small dense linear algebra on row-major slices: Cholesky (with reported regularization),
//! LU with partial pivoting, triangular solves and inverses.
//!
//! Matrices are `&[f64]` of length `n * n`, row-major (`a[i * n + j]` is row `i`, column `j`).
//! Right-hand sides with several columns are row-major `n × m`. Nothing here allocates except
//! the constructors that return a factorization.
//!
//! # Precision contract
//! - [`Cholesky::factor`] succeeds exactly when every pivot is positive and finite; the solve
//!   is backward stable: for a well-conditioned SPD matrix the residual `‖A x − b‖` is a few
//!   units of roundoff times `‖A‖ ‖x‖` (tests check `1e-12` relative on random SPD matrices).
//! - [`Cholesky::factor_regularized`] adds `δ·I` with the smallest `δ` of the sequence
//!   `0, 1e-12·s, 1e-11·s, …, 1e-2·s` (`s` = mean diagonal) that makes the factorization succeed
//!   and reports `δ` in [`Cholesky::jitter`]: a caller always knows whether it solved `A` or
//!   `A + δI`.
//! - [`Lu::factor`] refuses a matrix with an exactly zero pivot (singular to working precision).
//!
//! ```
//! use trajkit::linalg::Cholesky;
//! let a = [4.0, 2.0, 2.0, 3.0];
//! let c = Cholesky::factor(&a, 2)?;
//! let mut b = [2.0, 1.0];
//! c.solve_in_place(&mut b);
//! assert!((4.0 * b[0] + 2.0 * b[1] - 2.0).abs() < 1e-14);
//! assert_eq!(c.jitter(), 0.0);
//! # Ok::<(), trajkit::Error>(())
//! ```

use crate::error::{Error, Result};

fn check_square(a: &[f64], n: usize, what: &str) -> Result<()> {
    if n == 0 {
        return Err(Error::DimensionMismatch {
            what: format!("{what} size"),
            expected: 1,
            found: 0,
        });
    }
    if a.len() != n * n {
        return Err(Error::DimensionMismatch {
            what: format!("{what} entries ({n} × {n})"),
            expected: n * n,
            found: a.len(),
        });
    }
    if let Some(i) = a.iter().position(|v| !v.is_finite()) {
        return Err(Error::InvalidValue {
            field: format!("{what} entry ({}, {})", i / n, i % n),
            value: a[i],
            reason: "is not a finite number",
        });
    }
    Ok(())
}

/// Dot product with four independent accumulators (lets the compiler vectorize).
#[inline]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 4];
    let ca = a.chunks_exact(4);
    let cb = b.chunks_exact(4);
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        acc[0] += x[0] * y[0];
        acc[1] += x[1] * y[1];
        acc[2] += x[2] * y[2];
        acc[3] += x[3] * y[3];
    }
    let mut s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for (x, y) in ra.iter().zip(rb) {
        s += x * y;
    }
    s
}

/// Four dot products of `a` with `b[0..4]` (all of `a`'s length), reading `a` once.
#[inline(always)]
fn dot4(a: &[f64], b: [&[f64]; 4]) -> [f64; 4] {
    let mut acc = [[0.0f64; 2]; 4];
    let ca = a.chunks_exact(2);
    let tail = ca.remainder().len();
    for (((x, y0), (y1, y2)), y3) in ca
        .zip(b[0].chunks_exact(2))
        .zip(b[1].chunks_exact(2).zip(b[2].chunks_exact(2)))
        .zip(b[3].chunks_exact(2))
    {
        for (c, y) in [y0, y1, y2, y3].into_iter().enumerate() {
            acc[c][0] += x[0] * y[0];
            acc[c][1] += x[1] * y[1];
        }
    }
    let mut out = [0.0; 4];
    for c in 0..4 {
        out[c] = acc[c][0] + acc[c][1];
        if tail == 1 {
            let k = a.len() - 1;
            out[c] += a[k] * b[c][k];
        }
    }
    out
}

/// `y += a * x`.
#[inline]
pub(crate) fn axpy(a: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// Cholesky factorization `A = L Lᵀ` of a symmetric positive definite matrix.
#[derive(Debug, Clone)]
pub struct Cholesky {
    n: usize,
    /// Lower factor, row-major, upper triangle zero.
    l: Vec<f64>,
    jitter: f64,
}

/// Panel width of the blocked factorization.
const NB: usize = 64;

/// `c[r][s] = Σ_k a_r[k] b_s[k]` for four rows `a` and two rows `b` of equal length, with
/// independent accumulators so that the loop vectorizes.
#[inline(always)]
fn kernel4x2(a: [&[f64]; 4], b: [&[f64]; 2]) -> [[f64; 2]; 4] {
    let len = a[0].len();
    let mut acc = [[0.0f64; 8]; 4];
    let a0 = a[0].chunks_exact(2);
    let tail = a0.remainder().len();
    for ((((x0, x1), (x2, x3)), y0), y1) in a0
        .zip(a[1].chunks_exact(2))
        .zip(a[2].chunks_exact(2).zip(a[3].chunks_exact(2)))
        .zip(b[0].chunks_exact(2))
        .zip(b[1].chunks_exact(2))
    {
        for (r, x) in [x0, x1, x2, x3].into_iter().enumerate() {
            acc[r][0] += x[0] * y0[0];
            acc[r][1] += x[1] * y0[1];
            acc[r][2] += x[0] * y1[0];
            acc[r][3] += x[1] * y1[1];
        }
    }
    let mut out = [[0.0; 2]; 4];
    for r in 0..4 {
        out[r][0] = acc[r][0] + acc[r][1];
        out[r][1] = acc[r][2] + acc[r][3];
        if tail == 1 {
            out[r][0] += a[r][len - 1] * b[0][len - 1];
            out[r][1] += a[r][len - 1] * b[1][len - 1];
        }
    }
    out
}

/// Factors `a` (lower triangle read, upper ignored) into `l` in place. Returns the index of the
/// first non-positive pivot on failure.
fn cholesky_in_place(l: &mut [f64], n: usize) -> std::result::Result<(), usize> {
    // Right-looking, blocked by panels of NB columns: factor the panel with row dot products,
    // then subtract its outer product from the trailing lower triangle with a 4×2 kernel.
    let mut k0 = 0;
    let mut panel: Vec<f64> = Vec::with_capacity(n * NB);
    while k0 < n {
        let k1 = (k0 + NB).min(n);
        for i in k0..n {
            let jmax = if i < k1 { i } else { k1 - 1 };
            for j in k0..=jmax {
                let (ri, rj) = (i * n, j * n);
                let s = l[ri + j] - dot(&l[ri + k0..ri + j], &l[rj + k0..rj + j]);
                if i == j {
                    if s.is_nan() || s <= 0.0 || s.is_infinite() {
                        return Err(i);
                    }
                    l[ri + i] = s.sqrt();
                } else {
                    l[ri + j] = s / l[rj + j];
                }
            }
        }
        // Trailing update of rows/columns k1..n from a packed copy of the panel, blocked so
        // that a block of JB panel rows stays in L1 while all rows below stream past it.
        let w = k1 - k0;
        let rows = n - k1;
        panel.clear();
        for r in k1..n {
            panel.extend_from_slice(&l[r * n + k0..r * n + k1]);
        }
        let prow = |r: usize| &panel[(r - k1) * w..(r - k1 + 1) * w];
        const JB: usize = 32;
        let mut jb0 = k1;
        while jb0 < n {
            let jb1 = (jb0 + JB).min(n);
            let mut i = jb0;
            while i < n {
                let ib = (n - i).min(4);
                let mut j = jb0;
                let jend = jb1.min(i + ib);
                while j < jend {
                    let jb = (jend - j).min(2);
                    if ib == 4 && jb == 2 && j + 1 < i + 1 && j < i {
                        let c = kernel4x2(
                            [prow(i), prow(i + 1), prow(i + 2), prow(i + 3)],
                            [prow(j), prow(j + 1)],
                        );
                        for r in 0..4 {
                            for s in 0..2 {
                                l[(i + r) * n + j + s] -= c[r][s];
                            }
                        }
                    } else {
                        for r in i..i + ib {
                            for s in j..(j + jb).min(r + 1) {
                                l[r * n + s] -= dot(prow(r), prow(s));
                            }
                        }
                    }
                    j += jb;
                }
                i += ib;
            }
            jb0 = jb1;
        }
        let _ = rows;
        k0 = k1;
    }
    for i in 0..n {
        for j in i + 1..n {
            l[i * n + j] = 0.0;
        }
    }
    Ok(())
}

impl Cholesky {
    /// Factors the symmetric positive definite `n × n` matrix `a` (only its lower triangle is
    /// read). Fails with [`Error::Infeasible`] naming the pivot if `a` is not positive definite.
    pub fn factor(a: &[f64], n: usize) -> Result<Cholesky> {
        check_square(a, n, "matrix")?;
        let mut l = a.to_vec();
        cholesky_in_place(&mut l, n).map_err(|i| {
            Error::Infeasible(format!(
                "matrix is not positive definite (pivot {i} of {n})"
            ))
        })?;
        Ok(Cholesky { n, l, jitter: 0.0 })
    }

    /// Factors `a + δ I` with the smallest `δ` of `0, 1e-12·s, …, 1e-2·s` (`s` = mean absolute
    /// diagonal, or 1 if that is zero) that succeeds; `δ` is reported by [`Cholesky::jitter`].
    pub fn factor_regularized(a: &[f64], n: usize) -> Result<Cholesky> {
        check_square(a, n, "matrix")?;
        let mut s = (0..n).map(|i| a[i * n + i].abs()).sum::<f64>() / n as f64;
        if s == 0.0 {
            s = 1.0;
        }
        let mut l = a.to_vec();
        if cholesky_in_place(&mut l, n).is_ok() {
            return Ok(Cholesky { n, l, jitter: 0.0 });
        }
        for e in -12..=-2 {
            let d = s * 10f64.powi(e);
            l.copy_from_slice(a);
            for i in 0..n {
                l[i * n + i] += d;
            }
            if cholesky_in_place(&mut l, n).is_ok() {
                return Ok(Cholesky { n, l, jitter: d });
            }
        }
        Err(Error::Infeasible(format!(
            "matrix is not positive definite even with {:e} added to its diagonal",
            s * 1e-2
        )))
    }

    /// Size `n`.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The `δ` added to the diagonal (0 when the matrix factored as given).
    pub fn jitter(&self) -> f64 {
        self.jitter
    }

    /// The lower factor `L`, row-major `n × n`.
    pub fn l(&self) -> &[f64] {
        &self.l
    }

    /// `log det A` (of the regularized matrix when [`Cholesky::jitter`] is non-zero).
    pub fn log_det(&self) -> f64 {
        2.0 * (0..self.n)
            .map(|i| self.l[i * self.n + i].ln())
            .sum::<f64>()
    }

    /// Solves `L y = b` in place (`b` has `n` entries).
    pub fn solve_lower_in_place(&self, b: &mut [f64]) {
        let n = self.n;
        for i in 0..n {
            let r = &self.l[i * n..i * n + i];
            b[i] = (b[i] - dot(r, &b[..i])) / self.l[i * n + i];
        }
    }

    /// Solves `Lᵀ x = y` in place.
    pub fn solve_upper_in_place(&self, b: &mut [f64]) {
        let n = self.n;
        for i in (0..n).rev() {
            b[i] /= self.l[i * n + i];
            let bi = b[i];
            // Column i of Lᵀ above the diagonal is row i of L left of the diagonal.
            axpy(-bi, &self.l[i * n..i * n + i], &mut b[..i]);
        }
    }

    /// Solves `A x = b` in place (`b` has `n` entries).
    pub fn solve_in_place(&self, b: &mut [f64]) {
        self.solve_lower_in_place(b);
        self.solve_upper_in_place(b);
    }

    /// Solves `A X = B` in place for a row-major `n × m` right-hand side.
    pub fn solve_matrix_in_place(&self, b: &mut [f64], m: usize) {
        let n = self.n;
        // Forward: row i of X depends on rows < i.
        for i in 0..n {
            let (done, rest) = b.split_at_mut(i * m);
            let bi = &mut rest[..m];
            for k in 0..i {
                let lik = self.l[i * n + k];
                if lik != 0.0 {
                    axpy(-lik, &done[k * m..k * m + m], bi);
                }
            }
            let d = 1.0 / self.l[i * n + i];
            bi.iter_mut().for_each(|v| *v *= d);
        }
        for i in (0..n).rev() {
            let d = 1.0 / self.l[i * n + i];
            let (head, tail) = b.split_at_mut(i * m);
            let bi = &mut tail[..m];
            bi.iter_mut().for_each(|v| *v *= d);
            for k in 0..i {
                let lik = self.l[i * n + k];
                if lik != 0.0 {
                    axpy(-lik, bi, &mut head[k * m..k * m + m]);
                }
            }
        }
    }

    /// The transpose of `L⁻¹`, row-major: row `j` holds column `j` of `L⁻¹`, non-zero from
    /// entry `j` on. With it, `vᵀ A⁻¹ v = ‖L⁻¹ v‖²` and `L⁻¹ v = Σ_j v_j · row_j`.
    pub fn inverse_factor_transposed(&self) -> Vec<f64> {
        const G: usize = 32;
        let n = self.n;
        let l = &self.l;
        // Column j of L⁻¹ solves L x = e_j and is zero above j. G columns per group (their
        // solutions fit in L2), each row segment of L dotted with four of them at a time.
        let mut out = vec![0.0; n * n];
        let mut x = vec![0.0; G * n];
        let mut j0 = 0;
        while j0 < n {
            let nc = (n - j0).min(G);
            x.iter_mut().for_each(|v| *v = 0.0);
            for c in 0..nc {
                let j = j0 + c;
                x[c * n + j] = 1.0 / l[j * n + j];
            }
            for i in j0 + 1..n {
                let d = 1.0 / l[i * n + i];
                let row = &l[i * n + j0..i * n + i];
                let mut c0 = 0;
                while c0 < nc {
                    if c0 + 4 <= nc {
                        let s = {
                            let v = |c: usize| &x[(c0 + c) * n + j0..(c0 + c) * n + i];
                            dot4(row, [v(0), v(1), v(2), v(3)])
                        };
                        for c in 0..4 {
                            if i > j0 + c0 + c {
                                x[(c0 + c) * n + i] = -s[c] * d;
                            }
                        }
                        c0 += 4;
                    } else {
                        if i > j0 + c0 {
                            let s = dot(row, &x[c0 * n + j0..c0 * n + i]);
                            x[c0 * n + i] = -s * d;
                        }
                        c0 += 1;
                    }
                }
            }
            for c in 0..nc {
                let j = j0 + c;
                out[j * n + j..j * n + n].copy_from_slice(&x[c * n + j..c * n + n]);
            }
            j0 += nc;
        }
        out
    }

    /// `A⁻¹`, row-major `n × n`.
    pub fn inverse(&self) -> Vec<f64> {
        let n = self.n;
        let mut inv = vec![0.0; n * n];
        for i in 0..n {
            inv[i * n + i] = 1.0;
        }
        self.solve_matrix_in_place(&mut inv, n);
        inv
    }
}

/// LU factorization with partial (row) pivoting, `P A = L U`.
#[derive(Debug, Clone)]
pub struct Lu {
    n: usize,
    lu: Vec<f64>,
    perm: Vec<usize>,
    sign: f64,
}

impl Lu {
    /// Factors the square `n × n` matrix `a`. Fails with [`Error::Infeasible`] if a pivot is
    /// exactly zero.
    pub fn factor(a: &[f64], n: usize) -> Result<Lu> {
        check_square(a, n, "matrix")?;
        let mut lu = a.to_vec();
        let mut perm: Vec<usize> = (0..n).collect();
        let mut sign = 1.0;
        for k in 0..n {
            let (mut p, mut best) = (k, lu[k * n + k].abs());
            for i in k + 1..n {
                let v = lu[i * n + k].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if best == 0.0 {
                return Err(Error::Infeasible(format!(
                    "matrix is singular (column {k} of {n} has no pivot)"
                )));
            }
            if p != k {
                for j in 0..n {
                    lu.swap(k * n + j, p * n + j);
                }
                perm.swap(k, p);
                sign = -sign;
            }
            let d = 1.0 / lu[k * n + k];
            for i in k + 1..n {
                let f = lu[i * n + k] * d;
                lu[i * n + k] = f;
                if f != 0.0 {
                    let (top, bottom) = lu.split_at_mut(i * n);
                    axpy(-f, &top[k * n + k + 1..k * n + n], &mut bottom[k + 1..n]);
                }
            }
        }
        Ok(Lu { n, lu, perm, sign })
    }

    /// Solves `A x = b`; `b` has `n` entries and is overwritten with `x`.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let n = self.n;
        let pb: Vec<f64> = self.perm.iter().map(|&p| b[p]).collect();
        b[..n].copy_from_slice(&pb);
        for i in 0..n {
            b[i] -= dot(&self.lu[i * n..i * n + i], &b[..i]);
        }
        for i in (0..n).rev() {
            let s = dot(&self.lu[i * n + i + 1..i * n + n], &b[i + 1..n]);
            b[i] = (b[i] - s) / self.lu[i * n + i];
        }
    }

    /// Determinant of `A`.
    pub fn det(&self) -> f64 {
        (0..self.n)
            .map(|i| self.lu[i * self.n + i])
            .product::<f64>()
            * self.sign
    }
}

/// `C = A Bᵀ` for row-major `A` (`m × k`) and `B` (`n × k`); `C` is `m × n`.
pub(crate) fn mul_abt(a: &[f64], b: &[f64], m: usize, n: usize, k: usize, c: &mut [f64]) {
    for i in 0..m {
        let ra = &a[i * k..i * k + k];
        for j in 0..n {
            c[i * n + j] = dot(ra, &b[j * k..j * k + k]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    fn random_spd(n: usize, rng: &mut SplitMix64) -> Vec<f64> {
        let g: Vec<f64> = (0..n * n).map(|_| rng.normal()).collect();
        let mut a = vec![0.0; n * n];
        mul_abt(&g, &g, n, n, n, &mut a);
        for i in 0..n {
            a[i * n + i] += n as f64;
        }
        a
    }

    fn matvec(a: &[f64], x: &[f64], n: usize) -> Vec<f64> {
        (0..n).map(|i| dot(&a[i * n..i * n + n], x)).collect()
    }

    #[test]
    fn cholesky_random_suite() {
        let mut rng = SplitMix64::new(11);
        for &n in &[1usize, 2, 3, 7, 47, 48, 49, 100, 130] {
            let a = random_spd(n, &mut rng);
            let c = Cholesky::factor(&a, n).unwrap();
            assert_eq!(c.jitter(), 0.0);
            // L Lᵀ = A
            let mut llt = vec![0.0; n * n];
            mul_abt(c.l(), c.l(), n, n, n, &mut llt);
            let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (x, y) in llt.iter().zip(&a) {
                assert!((x - y).abs() <= 1e-13 * scale, "n={n}");
            }
            let b: Vec<f64> = (0..n).map(|_| rng.normal()).collect();
            let mut x = b.clone();
            c.solve_in_place(&mut x);
            let r = matvec(&a, &x, n);
            for (ri, bi) in r.iter().zip(&b) {
                assert!((ri - bi).abs() < 1e-12 * scale, "n={n}");
            }
            // Multi-column solve agrees with single solves.
            let m = 3;
            let bm: Vec<f64> = (0..n * m).map(|_| rng.normal()).collect();
            let mut xm = bm.clone();
            c.solve_matrix_in_place(&mut xm, m);
            for col in 0..m {
                let mut xc: Vec<f64> = (0..n).map(|i| bm[i * m + col]).collect();
                c.solve_in_place(&mut xc);
                for i in 0..n {
                    assert!((xc[i] - xm[i * m + col]).abs() < 1e-10);
                }
            }
            // Inverse factor: vᵀA⁻¹v = ‖L⁻¹v‖².
            let rt = c.inverse_factor_transposed();
            let mut w = vec![0.0; n];
            for j in 0..n {
                axpy(b[j], &rt[j * n..j * n + n], &mut w);
            }
            let q1 = dot(&w, &w);
            let q2 = dot(&b, &x);
            assert!((q1 - q2).abs() < 1e-10 * q2.abs().max(1.0), "n={n}");
            let inv = c.inverse();
            let e = matvec(&inv, &b, n);
            for i in 0..n {
                assert!((e[i] - x[i]).abs() < 1e-10);
            }
        }
    }

    #[test]
    fn cholesky_rejects_and_regularizes() {
        // Rank-1 PSD matrix: plain factor fails, regularized succeeds and reports δ.
        let v = [1.0, 2.0, 3.0];
        let a: Vec<f64> = (0..9).map(|k| v[k / 3] * v[k % 3]).collect();
        assert!(matches!(Cholesky::factor(&a, 3), Err(Error::Infeasible(_))));
        let c = Cholesky::factor_regularized(&a, 3).unwrap();
        assert!(c.jitter() > 0.0 && c.jitter() < 1e-6);
        assert!(Cholesky::factor(&[1.0, f64::NAN, 0.0, 1.0], 2).is_err());
        assert!(Cholesky::factor(&[1.0, 0.0, 0.0], 2).is_err());
        assert!(Cholesky::factor_regularized(&[-1.0], 1).is_err());
        let c = Cholesky::factor(&[4.0], 1).unwrap();
        assert!((c.log_det() - 4f64.ln()).abs() < 1e-15);
    }

    #[test]
    fn lu_random_suite() {
        let mut rng = SplitMix64::new(5);
        for &n in &[1usize, 2, 5, 20, 60] {
            let a: Vec<f64> = (0..n * n).map(|_| rng.normal()).collect();
            let lu = Lu::factor(&a, n).unwrap();
            let b: Vec<f64> = (0..n).map(|_| rng.normal()).collect();
            let mut x = b.clone();
            lu.solve_in_place(&mut x);
            let r = matvec(&a, &x, n);
            let xn = x.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1.0);
            for (ri, bi) in r.iter().zip(&b) {
                assert!((ri - bi).abs() < 1e-11 * xn * n as f64, "n={n}");
            }
        }
        let lu = Lu::factor(&[0.0, 2.0, 3.0, 1.0], 2).unwrap();
        assert!((lu.det() + 6.0).abs() < 1e-14);
        assert!(Lu::factor(&[1.0, 2.0, 2.0, 4.0], 2).is_err());
    }
}
