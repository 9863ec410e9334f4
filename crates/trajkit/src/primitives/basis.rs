//! Normalized Gaussian basis functions over a phase variable, with exact derivatives.
//!
//! `ψ_i(z) = exp(−h_i (z − c_i)²)`, `φ_i(z) = ψ_i(z) / Σ_j ψ_j(z)`. DMPs use it over the
//! exponentially decaying phase `x`, ProMPs over the normalized time `z = t / T ∈ [0, 1]`.
//!
//! # Precision contract
//! - The normalization is computed with the largest activation scaled to 1, so `Σ φ_i = 1` to
//!   roundoff at every `z`, including far outside the centers (no 0/0).
//! - Terms smaller than `e⁻⁴⁰ ≈ 4·10⁻¹⁸` of the largest one are skipped: the result differs from
//!   the full sum by less than `n · 4·10⁻¹⁸ · max|w|`.
//! - Derivatives with respect to `z` (orders 1–3) are analytic (quotient rule on the sums);
//!   tests compare them with finite differences.
//! - Evaluation allocates nothing.

use crate::error::{Error, Result};

/// Largest exponent gap kept, relative to the dominant basis function.
const CUT: f64 = 40.0;

/// Basis functions processed per stack block in the order-0 fast paths.
pub(crate) const BLOCK: usize = 64;

/// `exp(−e)` for `e ∈ [0, CUT]`: `e/ln 2` split into the nearest integer `k` and a remainder
/// `r` (`|r| ≤ ln 2/2`, Cody–Waite reduction with a two-part `ln 2`), `exp(−e) = 2^k · exp(r)`
/// with `exp(r)` from its degree-13 Taylor polynomial (truncation below 5e-18, Estrin's scheme) and `2^k` built
/// from the exponent bits. Relative error below 5e-16 (tested against `f64::exp`); no table and
/// no conversion instruction, so loops over it vectorize, and the result is the same on every
/// platform.
#[inline(always)]
pub(crate) fn exp_neg(e: f64) -> f64 {
    // fdlibm's split of ln 2: k · LN2_HI is exact for |k| < 2^20.
    const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
    const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
    // 1.5·2⁵²: adding it rounds to an integer, which then sits in the low mantissa bits.
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    let x = -e.min(CUT);
    let big = x * std::f64::consts::LOG2_E + SHIFT;
    let kf = big - SHIFT;
    let r = (x - kf * LN2_HI) - kf * LN2_LO;
    const C: [f64; 14] = [
        1.0,
        1.0,
        1.0 / 2.0,
        1.0 / 6.0,
        1.0 / 24.0,
        1.0 / 120.0,
        1.0 / 720.0,
        1.0 / 5040.0,
        1.0 / 40320.0,
        1.0 / 362880.0,
        1.0 / 3628800.0,
        1.0 / 39916800.0,
        1.0 / 479001600.0,
        1.0 / 6227020800.0,
    ];
    // Estrin's scheme: a short dependency chain, so consecutive calls overlap.
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let q = |i: usize| C[i] + C[i + 1] * r;
    let lo = (q(0) + r2 * q(2)) + r4 * (q(4) + r2 * q(6));
    let hi = (q(8) + r2 * q(10)) + r4 * q(12);
    let p = lo + r8 * hi;
    // k = big − SHIFT as an integer (two's complement), biased into the exponent field.
    let k = big.to_bits().wrapping_sub(SHIFT.to_bits());
    p * f64::from_bits(k.wrapping_add(1023) << 52)
}

/// Most basis functions per joint: every fit solves a dense system of this size (its
/// factorization takes n³/3 operations; 2000 functions: about 2.7e9, a few seconds), and 50 to
/// 100 already reproduce a demonstration to 1e-4.
pub const MAX_BASIS: usize = 2000;

/// Refuses more than [`MAX_BASIS`] basis functions before anything is allocated.
pub(crate) fn check_basis_count(n: usize) -> Result<()> {
    crate::size::check(
        "basis function count",
        n as f64,
        MAX_BASIS as f64,
        "each fit factorizes a dense n × n system (n³/3 operations)",
    )?;
    Ok(())
}

/// A set of Gaussian basis functions, normalized to sum to one.
///
/// ```
/// use trajkit::primitives::GaussianBasis;
/// let b = GaussianBasis::promp(10, 0.7)?;
/// let mut phi = vec![0.0; 10];
/// b.activations(0.3, 0, &mut phi);
/// assert!((phi.iter().sum::<f64>() - 1.0).abs() < 1e-14);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct GaussianBasis {
    centers: Vec<f64>,
    widths: Vec<f64>,
}

impl GaussianBasis {
    /// A basis from explicit centers `c_i` and widths `h_i` (`ψ_i = exp(−h_i (z − c_i)²)`).
    /// At most [`MAX_BASIS`] functions.
    pub fn new(centers: Vec<f64>, widths: Vec<f64>) -> Result<Self> {
        check_basis_count(centers.len())?;
        if centers.is_empty() {
            return Err(Error::DimensionMismatch {
                what: "basis function count".into(),
                expected: 1,
                found: 0,
            });
        }
        if widths.len() != centers.len() {
            return Err(Error::DimensionMismatch {
                what: "basis widths".into(),
                expected: centers.len(),
                found: widths.len(),
            });
        }
        for (i, &c) in centers.iter().enumerate() {
            crate::error::finite(|| format!("basis center {i}"), c)?;
        }
        for (i, &h) in widths.iter().enumerate() {
            crate::error::positive(|| format!("basis width {i}"), h)?;
        }
        Ok(GaussianBasis { centers, widths })
    }

    /// The DMP basis over the phase `x = exp(−α_x t/τ)`: centers at the phases of `n` equally
    /// spaced times in `[0, τ]`, each width chosen so that a function has value `overlap` at the
    /// next center (the last width repeats the previous one).
    pub fn dmp(n: usize, alpha_x: f64, overlap: f64) -> Result<Self> {
        check_basis_count(n)?;
        if n < 2 {
            return Err(Error::DimensionMismatch {
                what: "DMP basis function count (at least 2)".into(),
                expected: 2,
                found: n,
            });
        }
        crate::error::positive(|| "alpha_x".into(), alpha_x)?;
        check_overlap(overlap)?;
        let centers: Vec<f64> = (0..n)
            .map(|i| (-alpha_x * i as f64 / (n - 1) as f64).exp())
            .collect();
        let mut widths = vec![0.0; n];
        for i in 0..n - 1 {
            let d = centers[i + 1] - centers[i];
            widths[i] = -overlap.ln() / (d * d);
        }
        widths[n - 1] = widths[n - 2];
        Self::new(centers, widths)
    }

    /// The ProMP basis over `z ∈ [0, 1]`: `n` centers equally spaced in `[0, 1]`, one common
    /// width `h = −4 n² ln(overlap)`.
    pub fn promp(n: usize, overlap: f64) -> Result<Self> {
        check_basis_count(n)?;
        if n < 1 {
            return Err(Error::DimensionMismatch {
                what: "ProMP basis function count".into(),
                expected: 1,
                found: 0,
            });
        }
        check_overlap(overlap)?;
        let centers: Vec<f64> = if n == 1 {
            vec![0.5]
        } else {
            (0..n).map(|i| i as f64 / (n - 1) as f64).collect()
        };
        let h = -4.0 * (n * n) as f64 * overlap.ln();
        Self::new(centers, vec![h; n])
    }

    /// Number of basis functions.
    pub fn len(&self) -> usize {
        self.centers.len()
    }

    /// Always false (a basis has at least one function).
    pub fn is_empty(&self) -> bool {
        self.centers.is_empty()
    }

    /// Centers `c_i`.
    pub fn centers(&self) -> &[f64] {
        &self.centers
    }

    /// Widths `h_i`.
    pub fn widths(&self) -> &[f64] {
        &self.widths
    }

    /// For `n ≤ BLOCK`: writes `ψ_i(z) · e^m` (the largest scaled to 1) into `buf` and returns
    /// the index range outside which every term is below `e^−CUT` (those entries are left
    /// unspecified). One pass for the exponents, then branch-free exponentials.
    #[inline]
    pub(crate) fn window(&self, z: f64, buf: &mut [f64; BLOCK]) -> (usize, usize) {
        let n = self.len();
        for ((b, c), h) in buf[..n].iter_mut().zip(&self.centers).zip(&self.widths) {
            let r = z - c;
            *b = h * r * r;
        }
        // Minimum in two lanes (vectorizes); the exponents are finite or +inf, never NaN
        // for a finite z.
        let mut m2 = [f64::INFINITY; 2];
        let pairs = buf[..n].chunks_exact(2);
        let last = pairs.remainder().first().copied().unwrap_or(f64::INFINITY);
        for p in pairs {
            for q in 0..2 {
                m2[q] = if p[q] < m2[q] { p[q] } else { m2[q] };
            }
        }
        let m = m2[0].min(m2[1]).min(last);
        let lo = buf[..n].iter().position(|&e| e - m <= CUT).unwrap_or(0);
        let hi = buf[..n]
            .iter()
            .rposition(|&e| e - m <= CUT)
            .map_or(n, |p| p + 1);
        for b in buf[lo..hi].iter_mut() {
            let e = *b - m;
            *b = if e <= CUT { exp_neg(e) } else { 0.0 };
        }
        (lo, hi)
    }

    #[inline]
    fn min_exponent(&self, z: f64) -> f64 {
        let mut m = f64::INFINITY;
        for (c, h) in self.centers.iter().zip(&self.widths) {
            let r = z - c;
            m = m.min(h * r * r);
        }
        m
    }

    /// Scaled `ψ_i` and its derivatives up to `order` at `z` (scale common to all i), or `None`
    /// when negligible.
    #[inline]
    fn psi(&self, i: usize, z: f64, m: f64, order: usize) -> Option<[f64; 4]> {
        let h = self.widths[i];
        let r = z - self.centers[i];
        let e = h * r * r - m;
        if e > CUT {
            return None;
        }
        let p = exp_neg(e);
        let mut d = [p, 0.0, 0.0, 0.0];
        if order >= 1 {
            d[1] = -2.0 * h * r * p;
        }
        if order >= 2 {
            d[2] = (4.0 * h * h * r * r - 2.0 * h) * p;
        }
        if order >= 3 {
            d[3] = (-8.0 * h * h * h * r * r * r + 12.0 * h * h * r) * p;
        }
        Some(d)
    }

    /// Writes `dᵏφ_i/dzᵏ (z)` for every basis function into `out` (`k = order ≤ 3`; `out` has
    /// [`GaussianBasis::len`] entries).
    ///
    /// # Panics
    /// If `out` is shorter than [`GaussianBasis::len`] (a programming error, like a short buffer
    /// given to [`crate::Trajectory::eval`]).
    pub fn activations(&self, z: f64, order: usize, out: &mut [f64]) {
        let order = order.min(3);
        if order == 0 && self.len() <= BLOCK {
            let mut buf = [0.0f64; BLOCK];
            let (lo, hi) = self.window(z, &mut buf);
            let inv = 1.0 / buf[lo..hi].iter().sum::<f64>();
            out[..self.len()].iter_mut().for_each(|v| *v = 0.0);
            for (o, b) in out[lo..hi].iter_mut().zip(&buf[lo..hi]) {
                *o = b * inv;
            }
            return;
        }
        let m = self.min_exponent(z);
        let mut s = [0.0; 4];
        for i in 0..self.len() {
            if let Some(d) = self.psi(i, z, m, order) {
                for k in 0..=order {
                    s[k] += d[k];
                }
            }
        }
        for i in 0..self.len() {
            out[i] = match self.psi(i, z, m, order) {
                Some(d) => quotient(&d, &s, order)[order],
                None => 0.0,
            };
        }
    }

    /// `out[r] = Σ_i dᵏφ_i/dzᵏ(z) · w[r·n + i]` for `rows` rows of row-major weights
    /// (`k = order ≤ 3`, `n` = [`GaussianBasis::len`]). Allocates nothing.
    ///
    /// # Panics
    /// If `w` has fewer than `rows · n` entries or `out` fewer than `rows`.
    pub fn combine(&self, z: f64, order: usize, w: &[f64], rows: usize, out: &mut [f64]) {
        const CHUNK: usize = 16;
        let order = order.min(3);
        let n = self.len();
        if order == 0 && rows <= CHUNK && n <= BLOCK {
            let mut buf = [0.0f64; BLOCK];
            let (lo, hi) = self.window(z, &mut buf);
            let b = &buf[lo..hi];
            let inv = 1.0 / b.iter().sum::<f64>();
            for (o, wr) in out[..rows].iter_mut().zip(w.chunks_exact(n)) {
                *o = crate::linalg::dot(b, &wr[lo..hi]) * inv;
            }
            return;
        }
        let m = self.min_exponent(z);
        let mut r0 = 0;
        while r0 < rows {
            let nr = (rows - r0).min(CHUNK);
            let mut s = [0.0; 4];
            let mut f = [[0.0f64; 4]; CHUNK];
            for i in 0..n {
                if let Some(d) = self.psi(i, z, m, order) {
                    for k in 0..=order {
                        s[k] += d[k];
                    }
                    for r in 0..nr {
                        let wi = w[(r0 + r) * n + i];
                        for k in 0..=order {
                            f[r][k] += d[k] * wi;
                        }
                    }
                }
            }
            for r in 0..nr {
                out[r0 + r] = quotient(&f[r], &s, order)[order];
            }
            r0 += nr;
        }
    }
}

fn check_overlap(overlap: f64) -> Result<()> {
    if overlap.is_finite() && overlap > 0.0 && overlap < 1.0 {
        Ok(())
    } else {
        Err(Error::InvalidValue {
            field: "basis overlap".into(),
            value: overlap,
            reason: "is not in (0, 1)",
        })
    }
}

/// Derivatives of `F / S` up to `order` from those of `F` and `S` (Leibniz rule).
#[inline]
fn quotient(f: &[f64; 4], s: &[f64; 4], order: usize) -> [f64; 4] {
    let mut g = [0.0; 4];
    g[0] = f[0] / s[0];
    if order >= 1 {
        g[1] = (f[1] - g[0] * s[1]) / s[0];
    }
    if order >= 2 {
        g[2] = (f[2] - 2.0 * g[1] * s[1] - g[0] * s[2]) / s[0];
    }
    if order >= 3 {
        g[3] = (f[3] - 3.0 * g[2] * s[1] - 3.0 * g[1] * s[2] - g[0] * s[3]) / s[0];
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_of_unity_and_far_field() {
        let b = GaussianBasis::dmp(50, -(0.01f64.ln()), 0.8).unwrap();
        let mut phi = vec![0.0; 50];
        for &z in &[1.0, 0.5, 0.01, 0.0, -3.0, 40.0] {
            b.activations(z, 0, &mut phi);
            let s: f64 = phi.iter().sum();
            assert!((s - 1.0).abs() < 1e-13, "z={z} sum={s}");
            for k in 1..=3 {
                b.activations(z, k, &mut phi);
                let s: f64 = phi.iter().sum();
                assert!(
                    s.abs() < 1e-6 * b.widths()[0].powi(k as i32 / 2 + 1),
                    "z={z}"
                );
            }
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let b = GaussianBasis::promp(8, 0.7).unwrap();
        let w: Vec<f64> = (0..16).map(|i| ((i * 7) % 5) as f64 - 2.0).collect();
        let (mut y0, mut y1, mut y2) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        for &z in &[0.05, 0.33, 0.71, 1.0] {
            let e = 1e-6;
            for k in 0..3 {
                b.combine(z - e, k, &w, 2, &mut y0);
                b.combine(z + e, k, &w, 2, &mut y1);
                b.combine(z, k + 1, &w, 2, &mut y2);
                for r in 0..2 {
                    let fd = (y1[r] - y0[r]) / (2.0 * e);
                    let scale = 1.0 + y2[r].abs();
                    assert!(
                        (fd - y2[r]).abs() < 1e-5 * scale * 10f64.powi(k as i32),
                        "z={z} k={k}: {fd} vs {}",
                        y2[r]
                    );
                }
            }
            // combine agrees with activations.
            let mut phi = [0.0; 8];
            for k in 0..4 {
                b.activations(z, k, &mut phi);
                let direct: f64 = phi.iter().zip(&w[8..]).map(|(a, b)| a * b).sum();
                b.combine(z, k, &w, 2, &mut y0);
                assert!((direct - y0[1]).abs() < 1e-9 * (1.0 + direct.abs()));
            }
        }
    }

    #[test]
    fn fast_exp_is_accurate() {
        let mut worst: f64 = 0.0;
        for k in 0..=400_000 {
            let e = CUT * k as f64 / 400_000.0;
            let (a, b) = (exp_neg(e), (-e).exp());
            worst = worst.max(((a - b) / b).abs());
        }
        assert!(worst < 5e-16, "{worst}");
    }

    #[test]
    fn bad_input() {
        assert!(GaussianBasis::promp(5, 1.0).is_err());
        assert!(GaussianBasis::dmp(1, 4.6, 0.5).is_err());
        assert!(GaussianBasis::new(vec![0.0], vec![-1.0]).is_err());
        assert!(GaussianBasis::new(vec![f64::NAN], vec![1.0]).is_err());
    }
}
