//! Near-exact inverses of the KMP systems `A = K_t ⊗ I_d + λ Σ` from a low-rank factor of the
//! time kernel, used as preconditioners (the mean) and for iterative refinement (the
//! covariance expansion), so that a fit needs no `(N·d)³` factorization.
//!
//! The Gaussian kernel matrix `K_t` of `N` reference times has a rapidly decaying spectrum: a
//! pivoted Cholesky factorization `K_t = G Gᵀ + E_t` stopped when every left-out diagonal is at
//! most [`TOL`] has rank `r` far below `N` (27 for `h = 6` over 2 s, 200 points). With the
//! block-diagonal `D = λ Σ` (one `d × d` block per reference point) and `V = G ⊗ I_d`, the
//! Woodbury identity inverts the neighbouring matrix `Ã = D + V Vᵀ` exactly:
//!
//! ```text
//! Ã⁻¹ = D⁻¹ − D⁻¹ V S⁻¹ Vᵀ D⁻¹,   S = I + Vᵀ D⁻¹ V   (r·d × r·d, Cholesky)
//! ```
//!
//! # Precision contract
//! `A = Ã + E` with `E = E_t ⊗ I_d` positive semi-definite, `‖E‖ ≤ trace E_t` (known from the
//! factorization), and `Ã ⪰ D`, so `‖I − Ã⁻¹ A‖ = ‖Ã⁻¹ E‖ ≤ ρ = trace(E_t) · max_m ‖D_m⁻¹‖_F`
//! ([`LowRankInverse::contraction_bound`]). The result of a Woodbury application is never used
//! as a solution by itself (it cancels when `Σ` is small): the mean is solved by conjugate
//! gradients on the exact operator (residual criterion unchanged), and the covariance
//! expansion's `A X = B` by one step of iterative refinement, accepted only when `ρ ≤`
//! [`REFINE_RHO`], which leaves an error of at most `ρ² / (1 − ρ) ≤ 1e-16` of `‖X‖` beyond the
//! rounding of the residual (the same `O(κ(A) ε)` as a backward-stable direct solve).

use crate::linalg::Cholesky;

/// Largest diagonal left out of the low-rank factor of `K_t` (kernel values are at most 1; the
/// diagonal updates of the pivoted factorization are accurate to about 1e-16).
pub(crate) const TOL: f64 = 1e-15;

/// Largest contraction bound `ρ` for which one refinement step is accepted.
pub(crate) const REFINE_RHO: f64 = 1e-8;

/// `c += a b` for row-major `a` (`m × kd`), `b` (`kd × nc`), `c` (`m × nc`). Four rows of `a`
/// at a time are packed with each entry duplicated (`[a_0k, a_0k, a_1k, a_1k, …]`), so the
/// 4 × 4 register block's inner loop is plain vector loads and multiply-adds.
pub(crate) fn mul_add(a: &[f64], m: usize, kd: usize, b: &[f64], nc: usize, c: &mut [f64]) {
    const JB: usize = 4;
    let mut pack = vec![0.0; 8 * kd];
    let mut i = 0;
    while i < m {
        let ib = (m - i).min(4);
        if ib < 4 {
            for s in i..m {
                for k in 0..kd {
                    let x = a[s * kd + k];
                    crate::linalg::axpy(x, &b[k * nc..(k + 1) * nc], &mut c[s * nc..(s + 1) * nc]);
                }
            }
            break;
        }
        for k in 0..kd {
            for s in 0..4 {
                let v = a[(i + s) * kd + k];
                pack[k * 8 + 2 * s] = v;
                pack[k * 8 + 2 * s + 1] = v;
            }
        }
        let mut j = 0;
        while j < nc {
            let jb = (nc - j).min(JB);
            if jb == JB {
                let mut acc = [[0.0f64; JB]; 4];
                for (x, br) in pack.chunks_exact(8).zip(b[j..].chunks(nc)) {
                    let br = &br[..JB];
                    for s in 0..4 {
                        for q in 0..JB {
                            acc[s][q] += x[2 * s + (q & 1)] * br[q];
                        }
                    }
                }
                for s in 0..4 {
                    for (o, v) in c[(i + s) * nc + j..(i + s) * nc + j + JB]
                        .iter_mut()
                        .zip(acc[s])
                    {
                        *o += v;
                    }
                }
            } else {
                for s in i..i + 4 {
                    for k in 0..kd {
                        let x = a[s * kd + k];
                        crate::linalg::axpy(
                            x,
                            &b[k * nc + j..k * nc + j + jb],
                            &mut c[s * nc + j..s * nc + j + jb],
                        );
                    }
                }
            }
            j += jb;
        }
        i += 4;
    }
}

/// [`mul_add`] for each of `d` joint blocks: `y_a += a · x_a` with `x_a` the `kd × nc` block
/// `a` of `x` and `y_a` the `m × nc` block `a` of `y`.
fn mul_add_per_joint(
    a: &[f64],
    m: usize,
    kd: usize,
    x: &[f64],
    nc: usize,
    y: &mut [f64],
    d: usize,
) {
    for j in 0..d {
        mul_add(
            a,
            m,
            kd,
            &x[j * kd * nc..(j + 1) * kd * nc],
            nc,
            &mut y[j * m * nc..(j + 1) * m * nc],
        );
    }
}

/// The time kernel matrix `K_t[i][j] = exp(−h (t_i − t_j)²)`, row-major `N × N`.
pub(crate) fn kernel_matrix(t: &[f64], h: f64) -> Vec<f64> {
    let n = t.len();
    let mut k = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..=i {
            let x = t[i] - t[j];
            let v = (-h * x * x).exp();
            k[i * n + j] = v;
            k[j * n + i] = v;
        }
    }
    k
}

/// `K_t ≈ G Gᵀ` by pivoted Cholesky: `G` row-major `N × r` and the trace of what is left out.
#[derive(Debug, Clone)]
pub(crate) struct KernelFactor {
    n: usize,
    r: usize,
    g: Vec<f64>,
    /// `Gᵀ`, row-major `r × N`.
    gt: Vec<f64>,
    left: f64,
}

impl KernelFactor {
    /// Factors the kernel matrix `kt` (`n × n`); `None` when the rank exceeds `n / 2`.
    pub(crate) fn new(kt: &[f64], n: usize) -> Option<KernelFactor> {
        let max_rank = n / 2;
        let mut g = vec![0.0; n * max_rank.max(1)];
        let mut diag: Vec<f64> = (0..n).map(|i| kt[i * n + i]).collect();
        let mut used = vec![false; n];
        let mut r = 0;
        loop {
            let mut p = usize::MAX;
            let mut dp = f64::NEG_INFINITY;
            for (i, &v) in diag.iter().enumerate() {
                if !used[i] && v > dp {
                    (p, dp) = (i, v);
                }
            }
            if p == usize::MAX || dp <= TOL {
                break;
            }
            if r == max_rank {
                return None;
            }
            used[p] = true;
            let piv = dp.sqrt();
            for i in 0..n {
                let v = if used[i] && i != p {
                    0.0
                } else {
                    let s = crate::linalg::dot(
                        &g[i * max_rank..i * max_rank + r],
                        &g[p * max_rank..p * max_rank + r],
                    );
                    (kt[i * n + p] - s) / piv
                };
                g[i * max_rank + r] = v;
                diag[i] -= v * v;
            }
            r += 1;
        }
        for i in 0..n {
            g.copy_within(i * max_rank..i * max_rank + r, i * r);
        }
        g.truncate(n * r);
        let mut gt = vec![0.0; r * n];
        for i in 0..n {
            for k in 0..r {
                gt[k * n + i] = g[i * r + k];
            }
        }
        let left = (0..n).filter(|&i| !used[i]).map(|i| diag[i].max(0.0)).sum();
        Some(KernelFactor { n, r, g, gt, left })
    }

    /// The rank `r`.
    pub(crate) fn rank(&self) -> usize {
        self.r
    }
}

/// `Ã⁻¹` for `Ã = λ Σ + V Vᵀ` (see the module docs). Vectors and blocks are joint-major:
/// row `a·N + m` is joint `a` at reference point `m`, with `nc` columns.
#[derive(Debug, Clone)]
pub(crate) struct LowRankInverse {
    d: usize,
    /// `(λ Σ_m)⁻¹`, `N` row-major `d × d` blocks.
    dinv: Vec<f64>,
    /// Cholesky factor of `S`, unknowns joint-major (`a·r + k`).
    s: Cholesky,
    rho: f64,
}

impl LowRankInverse {
    /// `None` when some `Σ_m` is not positive definite or `S` does not factor.
    pub(crate) fn new(f: &KernelFactor, cov: &[f64], d: usize, lam: f64) -> Option<Self> {
        let (n, r) = (f.n, f.r);
        let mut dinv = vec![0.0; n * d * d];
        let mut worst: f64 = 0.0;
        for m in 0..n {
            let blk: Vec<f64> = cov[m * d * d..(m + 1) * d * d]
                .iter()
                .map(|v| lam * v)
                .collect();
            let inv = Cholesky::factor(&blk, d).ok()?.inverse();
            worst = worst.max(inv.iter().map(|v| v * v).sum::<f64>().sqrt());
            dinv[m * d * d..(m + 1) * d * d].copy_from_slice(&inv);
        }
        // S = I + Vᵀ D⁻¹ V: entry ((a, k), (b, l)) = Σ_m G[m,k] G[m,l] D⁻¹_m[a,b]; the lower
        // block triangle (b ≤ a) is all the factorization reads.
        let rd = r * d;
        let mut s = vec![0.0; rd * rd];
        for m in 0..n {
            let gm = &f.g[m * r..(m + 1) * r];
            for a in 0..d {
                for b in 0..=a {
                    let c = dinv[m * d * d + a * d + b];
                    for (k, &gk) in gm.iter().enumerate() {
                        let at = (a * r + k) * rd + b * r;
                        crate::linalg::axpy(c * gk, gm, &mut s[at..at + r]);
                    }
                }
            }
        }
        for i in 0..rd {
            s[i * rd + i] += 1.0;
        }
        let s = Cholesky::factor(&s, rd).ok()?;
        Some(LowRankInverse {
            d,
            dinv,
            s,
            rho: f.left * worst,
        })
    }

    /// The bound `ρ ≥ ‖I − Ã⁻¹ A‖` of the module docs.
    pub(crate) fn contraction_bound(&self) -> f64 {
        self.rho
    }

    /// `y[a·N + m][..] = Σ_b M_m[a][b] x[b·N + m][..]` for the `d × d` blocks `M_m` of `blocks`,
    /// `nc` columns; `y` is overwritten (`sub`: `y −=` instead).
    fn block_diag(
        blocks: &[f64],
        n: usize,
        d: usize,
        x: &[f64],
        nc: usize,
        y: &mut [f64],
        sub: bool,
    ) {
        for m in 0..n {
            let bm = &blocks[m * d * d..(m + 1) * d * d];
            for a in 0..d {
                let out = &mut y[(a * n + m) * nc..(a * n + m + 1) * nc];
                if !sub {
                    out.iter_mut().for_each(|v| *v = 0.0);
                }
                for b in 0..d {
                    let c = if sub { -bm[a * d + b] } else { bm[a * d + b] };
                    crate::linalg::axpy(c, &x[(b * n + m) * nc..(b * n + m + 1) * nc], out);
                }
            }
        }
    }

    /// `z = Ã⁻¹ x` for `nc` columns (`x`, `z`: `N·d × nc`, joint-major rows); `w` is scratch of
    /// `r·d × nc`.
    pub(crate) fn apply(
        &self,
        f: &KernelFactor,
        x: &[f64],
        nc: usize,
        z: &mut [f64],
        w: &mut [f64],
    ) {
        let (n, r, d) = (f.n, f.r, self.d);
        // z = D⁻¹ x; w = Vᵀ z (per joint: Gᵀ z_a); w = S⁻¹ w.
        Self::block_diag(&self.dinv, n, d, x, nc, z, false);
        w[..r * d * nc].iter_mut().for_each(|v| *v = 0.0);
        mul_add_per_joint(&f.gt, r, n, z, nc, w, d);
        self.s.solve_matrix_in_place(&mut w[..r * d * nc], nc);
        // z −= D⁻¹ V w, with (V w)_a = G w_a.
        let mut u = vec![0.0; n * d * nc];
        mul_add_per_joint(&f.g, n, r, w, nc, &mut u, d);
        Self::block_diag(&self.dinv, n, d, &u, nc, z, true);
    }
}

/// `y = (K_t ⊗ I_d + λ Σ) x` for `nc` columns, joint-major rows (`kt` row-major `N × N`,
/// `cov` the `N` covariance blocks).
pub(crate) fn apply_system(
    kt: &[f64],
    cov: &[f64],
    n: usize,
    d: usize,
    lam: f64,
    x: &[f64],
    nc: usize,
    y: &mut [f64],
) {
    y[..n * d * nc].iter_mut().for_each(|v| *v = 0.0);
    mul_add_per_joint(kt, n, n, x, nc, y, d);
    for m in 0..n {
        let sm = &cov[m * d * d..(m + 1) * d * d];
        for a in 0..d {
            let (lo, hi) = ((a * n + m) * nc, (a * n + m + 1) * nc);
            for b in 0..d {
                let c = lam * sm[a * d + b];
                if c != 0.0 {
                    let xb = &x[(b * n + m) * nc..(b * n + m + 1) * nc];
                    crate::linalg::axpy(c, xb, &mut y[lo..hi]);
                }
            }
        }
    }
}

/// Solves `(K_t ⊗ I_d + λ Σ) X = B` (joint-major rows, `nc` columns) by `X₀ = Ã⁻¹ B` and one
/// refinement step `X = X₀ + Ã⁻¹ (B − A X₀)`; `None` unless `ρ ≤` [`REFINE_RHO`].
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_refined(
    f: &KernelFactor,
    inv: &LowRankInverse,
    kt: &[f64],
    cov: &[f64],
    lam: f64,
    b: &[f64],
    nc: usize,
) -> Option<Vec<f64>> {
    // A NaN bound (from a non-finite covariance) declines as well.
    if inv.contraction_bound().is_nan() || inv.contraction_bound() > REFINE_RHO {
        return None;
    }
    let (n, d, r) = (f.n, inv.d, f.r);
    let mut w = vec![0.0; r * d * nc];
    let mut x = vec![0.0; n * d * nc];
    inv.apply(f, b, nc, &mut x, &mut w);
    let mut res = vec![0.0; n * d * nc];
    apply_system(kt, cov, n, d, lam, &x, nc, &mut res);
    for (rv, bv) in res.iter_mut().zip(b) {
        *rv = bv - *rv;
    }
    let mut dx = vec![0.0; n * d * nc];
    inv.apply(f, &res, nc, &mut dx, &mut w);
    for (xv, dv) in x.iter_mut().zip(&dx) {
        *xv += dv;
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// `n` random SPD `d × d` blocks `G Gᵀ + diag·I` (`G` entries normal with σ = 0.1).
#[cfg(test)]
pub(crate) fn random_cov_blocks(
    rng: &mut crate::rng::SplitMix64,
    n: usize,
    d: usize,
    diag: f64,
) -> Vec<f64> {
    let mut cov = vec![0.0; n * d * d];
    for m in 0..n {
        let g: Vec<f64> = (0..d * d).map(|_| 0.1 * rng.normal()).collect();
        for a in 0..d {
            for b in 0..d {
                let s: f64 = (0..d).map(|c| g[a * d + c] * g[b * d + c]).sum();
                cov[m * d * d + a * d + b] = s + if a == b { diag } else { 0.0 };
            }
        }
    }
    cov
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    #[test]
    fn kernel_factor_leaves_out_what_it_reports() {
        let t: Vec<f64> = (0..120).map(|i| 2.0 * i as f64 / 119.0).collect();
        let kt = kernel_matrix(&t, 6.0);
        let f = KernelFactor::new(&kt, t.len()).unwrap();
        assert!(f.rank() < 40, "{}", f.rank());
        let n = t.len();
        let mut worst: f64 = 0.0;
        for i in 0..n {
            for j in 0..n {
                let g =
                    crate::linalg::dot(&f.g[i * f.r..(i + 1) * f.r], &f.g[j * f.r..(j + 1) * f.r]);
                worst = worst.max((kt[i * n + j] - g).abs());
            }
        }
        // |E_ij| ≤ √(E_ii E_jj) ≤ TOL, plus rounding.
        assert!(worst < 1e-14, "{worst}");
        assert!(f.left <= n as f64 * TOL);
        // Too many kernel widths for a low rank.
        let t: Vec<f64> = (0..60).map(|i| 30.0 * i as f64 / 59.0).collect();
        assert!(KernelFactor::new(&kernel_matrix(&t, 6.0), 60).is_none());
    }

    #[test]
    fn mul_add_matches_naive_product() {
        let mut rng = SplitMix64::new(3);
        for &(m, kd, nc) in &[(9, 7, 13), (4, 5, 8), (1, 3, 2), (12, 1, 5)] {
            let a: Vec<f64> = (0..m * kd).map(|_| rng.normal()).collect();
            let b: Vec<f64> = (0..kd * nc).map(|_| rng.normal()).collect();
            let mut c: Vec<f64> = (0..m * nc).map(|_| rng.normal()).collect();
            let mut want = c.clone();
            for i in 0..m {
                for j in 0..nc {
                    for k in 0..kd {
                        want[i * nc + j] += a[i * kd + k] * b[k * nc + j];
                    }
                }
            }
            mul_add(&a, m, kd, &b, nc, &mut c);
            for (x, y) in c.iter().zip(&want) {
                assert!((x - y).abs() < 1e-12 * (1.0 + y.abs()));
            }
        }
    }

    #[test]
    fn refined_solve_matches_direct_solve() {
        // 100 points over 2 s, 3 joints with random SPD covariances (smallest eigenvalue
        // ~1e-4), several right-hand sides.
        let mut rng = SplitMix64::new(9);
        let (n, d, nc) = (100, 3, 5);
        let t: Vec<f64> = (0..n).map(|i| 2.0 * i as f64 / (n - 1) as f64).collect();
        let cov = random_cov_blocks(&mut rng, n, d, 1e-4);
        let kt = kernel_matrix(&t, 6.0);
        let f = KernelFactor::new(&kt, n).unwrap();
        let lam = 60.0;
        let inv = LowRankInverse::new(&f, &cov, d, lam).unwrap();
        assert!(inv.contraction_bound() <= REFINE_RHO);
        let b: Vec<f64> = (0..n * d * nc).map(|_| rng.normal()).collect();
        let x = solve_refined(&f, &inv, &kt, &cov, lam, &b, nc).unwrap();
        // Dense joint-major system, one column at a time.
        let nd = n * d;
        let mut a = vec![0.0; nd * nd];
        for i in 0..n {
            for j in 0..n {
                for c in 0..d {
                    a[(c * n + i) * nd + c * n + j] = kt[i * n + j];
                }
            }
            for p in 0..d {
                for q in 0..d {
                    a[(p * n + i) * nd + q * n + i] += lam * cov[i * d * d + p * d + q];
                }
            }
        }
        let chol = Cholesky::factor(&a, nd).unwrap();
        for col in 0..nc {
            let mut want: Vec<f64> = (0..nd).map(|i| b[i * nc + col]).collect();
            chol.solve_in_place(&mut want);
            let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for i in 0..nd {
                assert!((x[i * nc + col] - want[i]).abs() < 1e-10 * scale);
            }
        }
    }
}
