//! KMP covariance queries from a Chebyshev expansion in time, precomputed at fit time.
//!
//! The covariance at time `s` needs `Q_ab(s) = k_a(s)ᵀ A⁻¹ k_b(s)` with `A = K + λ_c Σ` and
//! `k_a(s)` the kernel vector of joint `a` (entries `k(s, t_m)` in joint `a`'s block). Over the
//! reference span `[t_0, t_{N−1}]`, with `u = (s − mid)/half ∈ [−1, 1]`, the kernel vector is
//! expanded as `k_t(s) = Σ_{k≤p} T_k(u) c_k` (Chebyshev polynomials `T_k`, coefficient vectors
//! `c_k ∈ R^N` from the values at the `p + 1` Chebyshev points), so
//!
//! ```text
//! Q_ab(s) = Σ_{k,k'} T_k(u) T_k'(u) C_ab[k, k'],   C_ab[k, k'] = (e_a ⊗ c_k)ᵀ A⁻¹ (e_b ⊗ c_k')
//! ```
//!
//! and the velocity form uses `T_k'(u) / half` instead of `T_k(u)`. Either `C = Bᵀ X` with
//! `X = A⁻¹ B`, `B = [e_a ⊗ c_k]`, from the low-rank refinement of module `kmp_lowrank`
//! ([`ChebCov::from_solver`]), or `C = Wᵀ W` with `W = L⁻¹ B` (one blocked forward
//! substitution with `(p + 1)·d` right-hand sides that skips the leading zero blocks,
//! [`ChebCov::new`]); a query is `d(d+1)/2` quadratic forms of size `p + 1` instead of `d`
//! forward substitutions through the whole factor.
//!
//! # Precision contract
//! The degree `p` is the smallest (odd) for which the a-priori Bernstein-ellipse bounds on the
//! truncation error of every kernel-vector entry are at most [`TOL`] for positions and
//! `TOL·√(2h)` for velocities (the kernel is entire; on the ellipse `E_ρ` its modulus is at most
//! `M = exp(h·half²·((ρ − 1/ρ)/2)²)`, its Chebyshev coefficients at most `2Mρ^{−k}`, so the
//! interpolant errs by at most `4Mρ^{−p}/(ρ − 1)` and its derivative by at most
//! `(4M/half) Σ_{k>p} k² ρ^{−k}`, minimized over `ρ`): truncation is at most about one rounding
//! of a kernel value (47 for `h = 6` over 2 s). What dominates is rounding: the coefficients and the recurrences perturb each kernel entry by about
//! `p·ε` (2e-15 measured, against ~1e-16 for a direct evaluation), and the quadratic forms in
//! the coefficient basis sum terms larger than their result when `A` is ill-conditioned. Tests
//! compare [`crate::primitives::Kmp::covariance`] with a straightforward dense evaluation
//! (LU of the point-major `K ⊗ I + λ_c Σ`), positions and velocities, across the span: relative
//! error (largest entry error over largest entry) 4e-13 on a 40-point 3-joint problem and
//! 6.6e-11 on the benchmark's 200-point 7-joint problem (low-rank refinement; 1.1e-10 through
//! the factor), where the exact per-query substitution itself is 5.8e-11 from the dense
//! formula; 1e-9 is asserted. If no
//! `p ≤` [`MAX_DEGREE`] suffices (a span of many kernel widths), the KMP keeps the exact
//! per-query substitution.

/// Bound on the truncation error of each position kernel-vector entry: about one rounding of a
/// kernel value near 1, and below the expansion's own rounding (~2e-15).
pub(crate) const TOL: f64 = 1e-16;

/// Largest expansion degree used (odd); beyond it covariance queries stay exact substitutions.
pub(crate) const MAX_DEGREE: usize = 95;

/// Right-hand-side columns per register block of the forward substitution.
const CB: usize = 4;

/// `(B, nc) ↦ A⁻¹ B` for `nc` right-hand-side columns, or `None` to decline.
pub(crate) type BlockSolver<'a> = dyn FnMut(&[f64], usize) -> Option<Vec<f64>> + 'a;

/// The precomputed expansion: `C_ab` for `a ≥ b`.
#[derive(Debug, Clone)]
pub(crate) struct ChebCov {
    mid: f64,
    half: f64,
    /// Degree `p`; `p + 1` coefficients.
    deg: usize,
    /// Block `(a, b)`, `a ≥ b`, row-major `(p+1) × (p+1)` at `(a(a+1)/2 + b)·(p+1)²`.
    c: Vec<f64>,
}

/// `(4M/ρ^p/(ρ−1), (4M/half) Σ_{k>p} k² ρ^{−k})` minimized over a grid of `ρ`, for the kernel
/// `exp(−h x²)` on a span of half-width `half`.
fn error_bounds(h: f64, half: f64, p: usize) -> (f64, f64) {
    let (mut b0, mut b1) = (f64::INFINITY, f64::INFINITY);
    let mut rho = 1.05;
    while rho < 200.0 {
        let beta = 0.5 * (rho - 1.0 / rho);
        let log_m = h * half * half * beta * beta;
        if log_m > 700.0 {
            break;
        }
        // In logarithms: ρ^{−p} underflows long before the bound is uninteresting.
        let lr = rho.ln();
        let e0 = (4.0f64).ln() + log_m - p as f64 * lr - (rho - 1.0).ln();
        b0 = b0.min(e0.exp());
        // Σ_{k>p} k² ρ^{−k} = ρ^{−(p+1)} Σ_{j≥0} (a + j)² x^j with a = p + 1, x = 1/ρ, in
        // closed form.
        let (a, x) = ((p + 1) as f64, 1.0 / rho);
        let s =
            a * a / (1.0 - x) + 2.0 * a * x / (1.0 - x).powi(2) + x * (1.0 + x) / (1.0 - x).powi(3);
        let e1 = (4.0f64).ln() + log_m - (p + 1) as f64 * lr + s.ln() - half.ln();
        b1 = b1.min(e1.exp());
        rho += 0.05 * rho.max(1.0);
    }
    (b0, b1)
}

/// The smallest odd degree (an even number of coefficients, which the blocked kernels pair up)
/// meeting the precision contract, if any up to [`MAX_DEGREE`].
pub(crate) fn degree(h: f64, half: f64) -> Option<usize> {
    (4..=MAX_DEGREE)
        .find(|&p| {
            let (b0, b1) = error_bounds(h, half, p);
            b0 <= TOL && b1 <= TOL * (2.0 * h).sqrt()
        })
        .map(|p| p | 1)
}

/// Solves `L X = B` in place for the rows `start..n` of a row-major `n × n` lower factor `l`,
/// where `B` (and so `X`) is zero above row `start`. `x` holds rows `start..n` of `nblk`
/// column blocks of [`CB`] columns, block-major (block `q`, row `r`, column `c` at
/// `(q·rows + r)·CB + c`), so that each pass over the solved rows reads contiguous memory.
/// Two rows × [`CB`] columns per register block.
fn forward_block(l: &[f64], n: usize, start: usize, x: &mut [f64], nblk: usize) {
    let rows = n - start;
    let mut i = 0;
    while i < rows {
        let two = i + 1 < rows;
        let gi = start + i;
        let li = &l[gi * n + start..gi * n + gi];
        let li1 = if two {
            &l[(gi + 1) * n + start..(gi + 1) * n + gi]
        } else {
            li
        };
        let d0 = 1.0 / l[gi * n + gi];
        let (l10, d1) = if two {
            (l[(gi + 1) * n + gi], 1.0 / l[(gi + 1) * n + gi + 1])
        } else {
            (0.0, 0.0)
        };
        for blk in x.chunks_exact_mut(rows * CB).take(nblk) {
            let (done, rest) = blk.split_at_mut(i * CB);
            let mut acc = [[0.0f64; CB]; 2];
            for ((xr, &a0), &a1) in done.chunks_exact(CB).zip(li).zip(li1) {
                for c in 0..CB {
                    acc[0][c] += a0 * xr[c];
                    acc[1][c] += a1 * xr[c];
                }
            }
            for c in 0..CB {
                let xi = (rest[c] - acc[0][c]) * d0;
                rest[c] = xi;
                if two {
                    rest[CB + c] = (rest[CB + c] - acc[1][c] - l10 * xi) * d1;
                }
            }
        }
        i += 2;
    }
}

/// `out[k][k'] += Σ_r a[r][k] b[r][k']` for `k, k' < p1`, with `a` and `b` block-major as in
/// [`forward_block`] (`ra`, `rb` rows per block; `b`'s rows `off..off + ra` pair with `a`'s),
/// two `k` × [`CB`] `k'` per register block; `out` row-major `p1 × p1`.
fn gram_block(a: &[f64], ra: usize, b: &[f64], rb: usize, off: usize, p1: usize, out: &mut [f64]) {
    let nblk = p1.div_ceil(CB);
    for k in (0..p1).step_by(2) {
        let (ka, kk) = (k / CB, k % CB);
        let ablk = &a[ka * ra * CB..(ka + 1) * ra * CB];
        for q in 0..nblk {
            let bblk = &b[(q * rb + off) * CB..(q * rb + off + ra) * CB];
            let mut acc = [[0.0f64; CB]; 2];
            for (ar, br) in ablk.chunks_exact(CB).zip(bblk.chunks_exact(CB)) {
                let x = &ar[kk..kk + 2];
                for s in 0..2 {
                    for c in 0..CB {
                        acc[s][c] += x[s] * br[c];
                    }
                }
            }
            let c0 = q * CB;
            let end = (c0 + CB).min(p1);
            for s in 0..2.min(p1 - k) {
                for (o, v) in out[(k + s) * p1 + c0..(k + s) * p1 + end]
                    .iter_mut()
                    .zip(acc[s])
                {
                    *o += v;
                }
            }
        }
    }
}

/// The Chebyshev expansion of the kernel vectors over the span of `t`:
/// `(mid, half, p, mp, coef)` with `coef` row-major `N × mp` (row `m` holds `c_0..c_p` at
/// reference point `m`, zero padding to `mp`, a multiple of [`CB`]). `None` when no degree up
/// to [`MAX_DEGREE`] meets the contract.
fn expansion(t: &[f64], h: f64) -> Option<(f64, f64, usize, usize, Vec<f64>)> {
    let n = t.len();
    let (t0, t1) = (t[0], t[n - 1]);
    let mid = 0.5 * (t0 + t1);
    let half = 0.5 * (t1 - t0);
    if half.is_nan() || half <= 0.0 {
        return None;
    }
    let p = degree(h, half)?;
    let p1 = p + 1;
    // Columns padded to whole register blocks (p1 is even, so coefficient pairs fit).
    let mp = p1.div_ceil(CB) * CB;
    // Values at the Chebyshev points u_j = cos(jπ/p), then coefficients
    // c_k = (2/p) Σ''_j f(u_j) cos(jkπ/p), halved for k = 0 and k = p.
    let cosines: Vec<f64> = (0..2 * p)
        .map(|i| (std::f64::consts::PI * i as f64 / p as f64).cos())
        .collect();
    let mut vals = vec![0.0; p1 * n];
    for j in 0..p1 {
        let s = mid + half * cosines[j];
        for (m, &tm) in t.iter().enumerate() {
            let r = s - tm;
            vals[j * n + m] = (-h * r * r).exp();
        }
    }
    // Right-hand sides of joint 0's block: row m holds (c_0..c_p)[m], zero padding.
    let mut coef = vec![0.0; n * mp];
    for k in 0..p1 {
        let edge_k = if k == 0 || k == p { 0.5 } else { 1.0 };
        for j in 0..p1 {
            let edge_j = if j == 0 || j == p { 0.5 } else { 1.0 };
            let w = 2.0 / p as f64 * edge_k * edge_j * cosines[(j * k) % (2 * p)];
            for m in 0..n {
                coef[m * mp + k] += w * vals[j * n + m];
            }
        }
    }
    Some((mid, half, p, mp, coef))
}

impl ChebCov {
    /// Builds the expansion for reference times `t` (`n` points), `d` joints, kernel width
    /// `h`, from the joint-major lower factor `l` of `A` (`nd × nd`). `None` when no degree up
    /// to [`MAX_DEGREE`] meets the contract.
    pub(crate) fn new(t: &[f64], d: usize, h: f64, l: &[f64]) -> Option<ChebCov> {
        let n = t.len();
        let nd = n * d;
        let (mid, half, p, mp, coef) = expansion(t, h)?;
        let p1 = p + 1;
        // W_a = L⁻¹ (e_a ⊗ [c_k]) from row a·N on, block-major.
        let nblk = mp / CB;
        let mut w: Vec<Vec<f64>> = Vec::with_capacity(d);
        for a in 0..d {
            let rows = nd - a * n;
            let mut x = vec![0.0; rows * mp];
            for q in 0..nblk {
                for m in 0..n {
                    x[(q * rows + m) * CB..(q * rows + m + 1) * CB]
                        .copy_from_slice(&coef[m * mp + q * CB..m * mp + (q + 1) * CB]);
                }
            }
            forward_block(l, nd, a * n, &mut x, nblk);
            w.push(x);
        }
        // C_ab = W_aᵀ W_b over the rows where both are non-zero (from a·N, a ≥ b).
        let mut c = vec![0.0; d * (d + 1) / 2 * p1 * p1];
        for a in 0..d {
            for b in 0..=a {
                let off = (a * (a + 1) / 2 + b) * p1 * p1;
                let (ra, rb) = (nd - a * n, nd - b * n);
                gram_block(
                    &w[a],
                    ra,
                    &w[b],
                    rb,
                    (a - b) * n,
                    p1,
                    &mut c[off..off + p1 * p1],
                );
            }
        }
        Some(ChebCov {
            mid,
            half,
            deg: p,
            c,
        })
    }

    /// Builds the expansion like [`ChebCov::new`], with `A⁻¹ B` from `solve(B, nc)`: `B` has
    /// `N·d` joint-major rows (joint `a`, point `m` at row `a·N + m`) and `nc = d(p+1)` columns
    /// (`e_b ⊗ c_k` at column `b(p+1) + k`). `None` when no degree meets the contract or the
    /// solver declines.
    pub(crate) fn from_solver(
        t: &[f64],
        d: usize,
        h: f64,
        solve: &mut BlockSolver<'_>,
    ) -> Option<ChebCov> {
        let n = t.len();
        let (mid, half, p, mp, coef) = expansion(t, h)?;
        let p1 = p + 1;
        let nc = d * p1;
        let mut b = vec![0.0; n * d * nc];
        for a in 0..d {
            for m in 0..n {
                let at = (a * n + m) * nc + a * p1;
                b[at..at + p1].copy_from_slice(&coef[m * mp..m * mp + p1]);
            }
        }
        let x = solve(&b, nc)?;
        // C_a· = [c_k]ᵀ X_a (p1 × nc); block (a, b) for b ≤ a.
        let mut coef_t = vec![0.0; p1 * n];
        for m in 0..n {
            for k in 0..p1 {
                coef_t[k * n + m] = coef[m * mp + k];
            }
        }
        let mut c = vec![0.0; d * (d + 1) / 2 * p1 * p1];
        let mut row = vec![0.0; p1 * nc];
        for a in 0..d {
            row.iter_mut().for_each(|v| *v = 0.0);
            crate::primitives::kmp_lowrank::mul_add(
                &coef_t,
                p1,
                n,
                &x[a * n * nc..(a + 1) * n * nc],
                nc,
                &mut row,
            );
            for bj in 0..=a {
                let off = (a * (a + 1) / 2 + bj) * p1 * p1;
                for k in 0..p1 {
                    c[off + k * p1..off + (k + 1) * p1]
                        .copy_from_slice(&row[k * nc + bj * p1..k * nc + (bj + 1) * p1]);
                }
            }
        }
        Some(ChebCov {
            mid,
            half,
            deg: p,
            c,
        })
    }

    /// Degree of the expansion.
    pub(crate) fn degree(&self) -> usize {
        self.deg
    }

    /// `Q_ab(s)` for all `a, b` into `q` (row-major `d × d`): `order` 0 for positions, 1 for
    /// velocities. `s` must lie in the reference span. Allocates nothing.
    pub(crate) fn quadratic_forms(&self, s: f64, order: usize, d: usize, q: &mut [f64]) {
        let p1 = self.deg + 1;
        let u = ((s - self.mid) / self.half).clamp(-1.0, 1.0);
        // T_k(u), or T_k'(u)/half = k U_{k−1}(u)/half; both by their three-term recurrences.
        let mut tau = [0.0f64; MAX_DEGREE + 1];
        if order == 0 {
            tau[0] = 1.0;
            if p1 > 1 {
                tau[1] = u;
            }
            for k in 2..p1 {
                tau[k] = 2.0 * u * tau[k - 1] - tau[k - 2];
            }
        } else {
            let (mut um2, mut um1) = (0.0, 1.0); // U_{-1}, U_0
            for k in 1..p1 {
                tau[k] = k as f64 * um1 / self.half;
                let next = 2.0 * u * um1 - um2;
                um2 = um1;
                um1 = next;
            }
        }
        let tau = &tau[..p1];
        for a in 0..d {
            for b in 0..=a {
                let off = (a * (a + 1) / 2 + b) * p1 * p1;
                let blk = &self.c[off..off + p1 * p1];
                let mut v = 0.0;
                for (row, &tk) in blk.chunks_exact(p1).zip(tau) {
                    v += tk * crate::linalg::dot(row, tau);
                }
                q[a * d + b] = v;
                q[b * d + a] = v;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expansion_of_kernel_vectors_is_within_the_bound() {
        // The a-priori bound holds for the computed expansion (evaluated like a query).
        let h = 6.0;
        let t: Vec<f64> = (0..40).map(|i| 2.0 * i as f64 / 39.0).collect();
        let (mid, half) = (1.0, 1.0);
        let p = degree(h, half).unwrap();
        assert!((40..=70).contains(&p), "{p}");
        let p1 = p + 1;
        let cosines: Vec<f64> = (0..2 * p)
            .map(|i| (std::f64::consts::PI * i as f64 / p as f64).cos())
            .collect();
        let mut worst: f64 = 0.0;
        for &tm in &t {
            let f = |s: f64| (-h * (s - tm) * (s - tm)).exp();
            let mut c = vec![0.0; p1];
            for (k, ck) in c.iter_mut().enumerate() {
                for j in 0..p1 {
                    let e = |i: usize| if i == 0 || i == p { 0.5 } else { 1.0 };
                    *ck += 2.0 / p as f64
                        * e(k)
                        * e(j)
                        * cosines[(j * k) % (2 * p)]
                        * f(mid + half * cosines[j]);
                }
            }
            for i in 0..=500 {
                let u = -1.0 + 2.0 * i as f64 / 500.0;
                let (mut t0, mut t1, mut v) = (1.0, u, c[0] + c[1] * u);
                for ck in &c[2..] {
                    let t2 = 2.0 * u * t1 - t0;
                    v += ck * t2;
                    t0 = t1;
                    t1 = t2;
                }
                worst = worst.max((v - f(mid + half * u)).abs());
            }
        }
        // Truncation is below 1e-16; the rest is the rounding of the coefficients and the
        // recurrence, about p·ε (2e-15 measured).
        assert!(worst < 1e-14, "{worst}");
    }

    #[test]
    fn degree_grows_with_the_span() {
        let a = degree(6.0, 0.5).unwrap();
        let b = degree(6.0, 1.0).unwrap();
        assert!(a < b);
        assert!(degree(6.0, 100.0).is_none());
    }
}
