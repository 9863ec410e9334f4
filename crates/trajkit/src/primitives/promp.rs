//! Probabilistic movement primitive (ProMP): a Gaussian distribution over trajectories.
//!
//! `y(t) = Ψ(z)ᵀ w`, `w ~ N(μ_w, Σ_w)`, with `z = t / T ∈ [0, 1]` the phase, `Ψ(z)` block-diagonal
//! with the normalized Gaussian basis `φ(z)` of [`GaussianBasis::promp`] in each joint's block
//! and `w` stacked joint by joint (`w[j·n + i]`: joint `j`, basis `i`).
//!
//! - **Fit** ([`ProMp::fit`]): each demonstration's phase is its own time normalized to `[0, 1]`;
//!   its weights solve the ridge regression `(ΦᵀΦ + λI) w = Φᵀ y` per joint; `μ_w` is their mean
//!   and `Σ_w` their sample covariance (full: joints are coupled) plus `σ²_prior · I`. `Σ_w` from
//!   `N` demonstrations has rank at most `N − 1`; the prior term makes it full rank, without
//!   which more constraints than `N − 1` (e.g. two 7-joint via points) cannot all be met.
//! - **Queries**: mean, covariance and variance of positions and of velocities in real time
//!   units (`dy/dt = Ψ'(z)ᵀ w / T`), and the mean's acceleration and jerk through
//!   [`Trajectory`].
//! - **Conditioning** ([`ProMp::condition`]): on several via points at once, positions or
//!   velocities, each with its own covariance (zero allowed):
//!   `L = Σ_w Hᵀ (Σ* + H Σ_w Hᵀ)⁻¹`, `μ⁺ = μ_w + L (y* − H μ_w)`, `Σ⁺ = Σ_w − L H Σ_w`.
//! - **Sampling** ([`ProMp::sample`]) with a seeded [`SplitMix64`], temporal scaling
//!   ([`ProMp::with_duration`]).
//!
//! # Precision contract
//! - Conditioning with zero via-point covariance passes through the via point to the accuracy
//!   of the `m × m` solve (tests: 1e-9 for one via point; two 7-joint via points from ten
//!   demonstrations both within 1e-3, in practice ~1e-9).
//! - If `Σ* + H Σ_w Hᵀ` is singular (e.g. two zero-noise via points at the same time), it is
//!   regularized by the smallest sufficient multiple of the identity (see
//!   [`crate::linalg::Cholesky::factor_regularized`]) and [`ProMp::last_jitter`] reports it.
//! - Evaluation allocates nothing. Time is clamped to `[0, T]`.

use crate::error::{Error, Result};
use crate::linalg::{mul_abt, Cholesky};
use crate::primitives::basis::GaussianBasis;
use crate::primitives::demo::check_demo;
use crate::primitives::ridge::ridge_fit;
use crate::rng::SplitMix64;
use crate::traj::{Order, Trajectory};

/// One demonstration: times (seconds, strictly increasing) and positions (row-major
/// `t.len() × dof`).
#[derive(Debug, Clone, Copy)]
pub struct Demo<'a> {
    /// Sample times.
    pub t: &'a [f64],
    /// Positions, row-major.
    pub q: &'a [f64],
}

/// Hyperparameters of a [`ProMp`].
#[derive(Debug, Clone, PartialEq)]
pub struct ProMpConfig {
    /// Basis functions per joint (default 20).
    pub n_basis: usize,
    /// Value of a basis function at its neighbour's center (default 0.7).
    pub overlap: f64,
    /// Ridge coefficient λ of the per-demonstration regression (default 1e-12, absolute).
    pub ridge: f64,
    /// Prior variance added to the diagonal of Σ_w (default 1e-6, in squared position units).
    pub prior_variance: f64,
}

impl Default for ProMpConfig {
    fn default() -> Self {
        ProMpConfig {
            n_basis: 20,
            overlap: 0.7,
            ridge: 1e-12,
            prior_variance: 1e-6,
        }
    }
}

/// A via point for [`ProMp::condition`]: at time `t`, the position (or velocity) is `value`
/// with covariance `cov` (row-major `dof × dof`; empty means zero, i.e. pass exactly).
#[derive(Debug, Clone, PartialEq)]
pub struct ViaPoint {
    /// Time in seconds.
    pub t: f64,
    /// [`Order::Position`] or [`Order::Velocity`] (per second).
    pub order: Order,
    /// Desired value, one entry per joint.
    pub value: Vec<f64>,
    /// Covariance, row-major `dof × dof`, or empty for zero.
    pub cov: Vec<f64>,
}

impl ViaPoint {
    /// A position via point with an isotropic variance (0 = exact).
    pub fn position(t: f64, value: &[f64], variance: f64) -> ViaPoint {
        let d = value.len();
        let mut cov = vec![0.0; d * d];
        for i in 0..d {
            cov[i * d + i] = variance;
        }
        ViaPoint {
            t,
            order: Order::Position,
            value: value.to_vec(),
            cov,
        }
    }
}

/// A probabilistic movement primitive over `dof` joints.
///
/// ```
/// use trajkit::primitives::{Demo, ProMp, ProMpConfig, ViaPoint};
/// use trajkit::{Order, Trajectory};
/// // Three 1-joint demonstrations of different amplitude, 1 s each.
/// let t: Vec<f64> = (0..=100).map(|k| k as f64 / 100.0).collect();
/// let qs: Vec<Vec<f64>> = [0.9, 1.0, 1.1]
///     .iter()
///     .map(|a| t.iter().map(|&s| a * (3.0 * s).sin()).collect())
///     .collect();
/// let demos: Vec<Demo> = qs.iter().map(|q| Demo { t: &t, q }).collect();
/// let promp = ProMp::fit(&demos, 1, &ProMpConfig::default())?;
/// // Condition on passing through 0.5 at t = 0.4 s exactly.
/// let cond = promp.condition(&[ViaPoint::position(0.4, &[0.5], 0.0)])?;
/// let mut y = [0.0];
/// cond.eval(0.4, Order::Position, &mut y);
/// assert!((y[0] - 0.5).abs() < 1e-9);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct ProMp {
    basis: GaussianBasis,
    dof: usize,
    duration: f64,
    mean: Vec<f64>,
    cov: Vec<f64>,
    jitter: f64,
}

impl ProMp {
    /// Ridge-regression weights of one demonstration (phase = time normalized to `[0, 1]`),
    /// stacked joint by joint. The caller's arrays are only read.
    pub fn demo_weights(demo: &Demo<'_>, dof: usize, cfg: &ProMpConfig) -> Result<Vec<f64>> {
        let basis = GaussianBasis::promp(cfg.n_basis, cfg.overlap)?;
        Self::weights_with(&basis, demo, dof, cfg)
    }

    fn weights_with(
        basis: &GaussianBasis,
        demo: &Demo<'_>,
        dof: usize,
        cfg: &ProMpConfig,
    ) -> Result<Vec<f64>> {
        check_demo(demo.t, demo.q, dof, 2)?;
        if !(cfg.ridge.is_finite() && cfg.ridge >= 0.0) {
            return Err(Error::InvalidValue {
                field: "ridge".into(),
                value: cfg.ridge,
                reason: "is not a non-negative finite number",
            });
        }
        let n = basis.len();
        let rows = demo.t.len();
        let (t0, t1) = (demo.t[0], demo.t[rows - 1]);
        let mut phi = vec![0.0; rows * n];
        for k in 0..rows {
            let z = (demo.t[k] - t0) / (t1 - t0);
            basis.activations(z, 0, &mut phi[k * n..(k + 1) * n]);
        }
        ridge_fit(&phi, rows, n, demo.q, dof, cfg.ridge, false)
    }

    /// Learns a ProMP from demonstrations (at least 2, same joint count). The duration `T` is
    /// the mean of the demonstrations' durations.
    pub fn fit(demos: &[Demo<'_>], dof: usize, cfg: &ProMpConfig) -> Result<ProMp> {
        if demos.len() < 2 {
            return Err(Error::TooFewWaypoints {
                needed: 2,
                found: demos.len(),
            });
        }
        crate::error::finite(|| "prior_variance".into(), cfg.prior_variance)?;
        if cfg.prior_variance < 0.0 {
            return Err(Error::InvalidValue {
                field: "prior_variance".into(),
                value: cfg.prior_variance,
                reason: "is negative",
            });
        }
        let basis = GaussianBasis::promp(cfg.n_basis, cfg.overlap)?;
        let nw = dof * basis.len();
        check_weight_count(nw)?;
        for d in demos {
            crate::size::check_memory(
                "demonstration samples × basis functions",
                d.t.len() as f64 * basis.len() as f64,
                8.0,
                "a design-matrix entry",
            )?;
        }
        let mut ws = Vec::with_capacity(demos.len() * nw);
        let mut duration = 0.0;
        for (i, d) in demos.iter().enumerate() {
            let w = Self::weights_with(&basis, d, dof, cfg).map_err(|e| in_demo(i, e))?;
            ws.extend_from_slice(&w);
            duration += d.t[d.t.len() - 1] - d.t[0];
        }
        let m = demos.len();
        duration /= m as f64;
        let mut mean = vec![0.0; nw];
        for k in 0..m {
            crate::linalg::axpy(1.0 / m as f64, &ws[k * nw..(k + 1) * nw], &mut mean);
        }
        // Centered weights, transposed to nw × m so that Σ = C Cᵀ / (m − 1).
        let mut c = vec![0.0; nw * m];
        for k in 0..m {
            for i in 0..nw {
                c[i * m + k] = ws[k * nw + i] - mean[i];
            }
        }
        let mut cov = vec![0.0; nw * nw];
        mul_abt(&c, &c, nw, nw, m, &mut cov);
        let f = 1.0 / (m - 1) as f64;
        cov.iter_mut().for_each(|v| *v *= f);
        for i in 0..nw {
            cov[i * nw + i] += cfg.prior_variance;
        }
        Ok(ProMp {
            basis,
            dof,
            duration,
            mean,
            cov,
            jitter: 0.0,
        })
    }

    /// A ProMP from a given weight distribution (`mean`: `dof·n`, `cov`: `(dof·n)²` row-major).
    pub fn from_weight_distribution(
        cfg: &ProMpConfig,
        dof: usize,
        duration: f64,
        mean: &[f64],
        cov: &[f64],
    ) -> Result<ProMp> {
        let basis = GaussianBasis::promp(cfg.n_basis, cfg.overlap)?;
        crate::error::positive(|| "duration".into(), duration)?;
        let nw = dof * basis.len();
        if nw == 0 || mean.len() != nw {
            return Err(Error::DimensionMismatch {
                what: "weight mean length".into(),
                expected: nw.max(1),
                found: mean.len(),
            });
        }
        if cov.len() != nw * nw {
            return Err(Error::DimensionMismatch {
                what: "weight covariance entries".into(),
                expected: nw * nw,
                found: cov.len(),
            });
        }
        for (i, &v) in mean.iter().chain(cov).enumerate() {
            crate::error::finite(|| format!("weight distribution entry {i}"), v)?;
        }
        Ok(ProMp {
            basis,
            dof,
            duration,
            mean: mean.to_vec(),
            cov: cov.to_vec(),
            jitter: 0.0,
        })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }
    /// Basis functions per joint.
    pub fn n_basis(&self) -> usize {
        self.basis.len()
    }
    /// Weight mean μ_w (`dof · n`).
    pub fn weight_mean(&self) -> &[f64] {
        &self.mean
    }
    /// Weight covariance Σ_w, row-major.
    pub fn weight_cov(&self) -> &[f64] {
        &self.cov
    }
    /// The regularization added by the last conditioning's solve (0 when none was needed).
    pub fn last_jitter(&self) -> f64 {
        self.jitter
    }

    /// The same distribution over a new duration `T` (temporal scaling: velocities scale by
    /// `T_old / T`).
    pub fn with_duration(&self, duration: f64) -> Result<ProMp> {
        crate::error::positive(|| "duration".into(), duration)?;
        Ok(ProMp {
            duration,
            ..self.clone()
        })
    }

    fn phase(&self, t: f64) -> f64 {
        crate::traj::clamp_time(t, self.duration) / self.duration
    }

    /// The row `Ψ` of one joint for a derivative order, per second^order (length n).
    fn psi_row(&self, t: f64, order: usize, out: &mut [f64]) {
        self.basis.activations(self.phase(t), order, out);
        let f = self.duration.powi(-(order as i32));
        out.iter_mut().for_each(|v| *v *= f);
    }

    /// Covariance of the `order`-th derivative (0 = positions, 1 = velocities per second) at
    /// `t`, row-major `dof × dof` into `out`. Allocates only a basis-sized scratch.
    ///
    /// # Panics
    /// If `out` has fewer than `dof²` entries.
    pub fn covariance(&self, t: f64, order: Order, out: &mut [f64]) {
        let n = self.basis.len();
        let nw = self.dof * n;
        let mut psi = vec![0.0; n];
        self.psi_row(t, order.index(), &mut psi);
        let mut tmp = vec![0.0; n];
        for a in 0..self.dof {
            for b in 0..=a {
                // φᵀ Σ[a-block, b-block] φ
                for i in 0..n {
                    let row = &self.cov[(a * n + i) * nw + b * n..(a * n + i) * nw + b * n + n];
                    tmp[i] = crate::linalg::dot(row, &psi);
                }
                let v = crate::linalg::dot(&tmp, &psi);
                out[a * self.dof + b] = v;
                out[b * self.dof + a] = v;
            }
        }
    }

    /// Variances (diagonal of [`ProMp::covariance`]) into `out` (`dof` entries).
    ///
    /// # Panics
    /// If `out` has fewer than `dof` entries.
    pub fn variance(&self, t: f64, order: Order, out: &mut [f64]) {
        let n = self.basis.len();
        let nw = self.dof * n;
        let mut psi = vec![0.0; n];
        self.psi_row(t, order.index(), &mut psi);
        for a in 0..self.dof {
            let mut s = 0.0;
            for i in 0..n {
                let row = &self.cov[(a * n + i) * nw + a * n..(a * n + i) * nw + a * n + n];
                s += psi[i] * crate::linalg::dot(row, &psi);
            }
            out[a] = s.max(0.0);
        }
    }

    /// Conditions on via points (all at once). Returns the posterior ProMP; `self` is unchanged.
    ///
    /// Errors: a via point time outside `[0, duration]` (the movement has no value there to
    /// condition) or non-finite values ([`Error::InvalidValue`]); wrong sizes; more via values
    /// than the memory budget allows ([`Error::TooLarge`]).
    pub fn condition(&self, via: &[ViaPoint]) -> Result<ProMp> {
        let (dof, n) = (self.dof, self.basis.len());
        let nw = dof * n;
        if via.is_empty() {
            return Ok(self.clone());
        }
        crate::size::check_memory(
            "via values (via points × joints)",
            (via.len() * dof) as f64,
            8.0 * (nw + via.len() * dof) as f64,
            "a via value's rows of the gain and innovation matrices",
        )?;
        for (k, v) in via.iter().enumerate() {
            self.check_via(k, v)?;
        }
        let m = via.len() * dof;
        // H: m × nw, sparse by joint blocks; store the n-vector per via point.
        let mut psis = vec![0.0; via.len() * n];
        for (k, v) in via.iter().enumerate() {
            self.psi_row(v.t, v.order.index(), &mut psis[k * n..(k + 1) * n]);
        }
        let b = self.cross_covariance(&psis);
        let chol = Cholesky::factor_regularized(&self.innovation(via, &psis, &b), m)?;
        // Residual y* − H μ.
        let mut res = vec![0.0; m];
        for (k, v) in via.iter().enumerate() {
            let psi = &psis[k * n..(k + 1) * n];
            for a in 0..dof {
                res[k * dof + a] =
                    v.value[a] - crate::linalg::dot(psi, &self.mean[a * n..a * n + n]);
            }
        }
        chol.solve_in_place(&mut res);
        // μ⁺ = μ + Bᵀ G⁻¹ r ; Σ⁺ = Σ − Bᵀ G⁻¹ B.
        let mut mean = self.mean.clone();
        for r in 0..m {
            crate::linalg::axpy(res[r], &b[r * nw..(r + 1) * nw], &mut mean);
        }
        // X = G⁻¹ B (m × nw), then Σ⁺ = Σ − Bᵀ X.
        let mut x = b.clone();
        chol.solve_matrix_in_place(&mut x, nw);
        let mut cov = self.cov.clone();
        for r in 0..m {
            let br = &b[r * nw..(r + 1) * nw];
            let xr = &x[r * nw..(r + 1) * nw];
            for i in 0..nw {
                if br[i] != 0.0 {
                    crate::linalg::axpy(-br[i], xr, &mut cov[i * nw..(i + 1) * nw]);
                }
            }
        }
        symmetrize(&mut cov, nw);
        Ok(ProMp {
            basis: self.basis.clone(),
            dof,
            duration: self.duration,
            mean,
            cov,
            jitter: chol.jitter(),
        })
    }

    /// Checks via point `k` (0-based): time inside the movement, position or velocity, sizes,
    /// finite values.
    fn check_via(&self, k: usize, v: &ViaPoint) -> Result<()> {
        let dof = self.dof;
        crate::error::finite(|| format!("via point {} time", k + 1), v.t)?;
        if v.t < 0.0 || v.t > self.duration * (1.0 + 1e-12) {
            return Err(Error::InvalidValue {
                field: format!(
                    "via point {} time (the movement lasts {} s)",
                    k + 1,
                    self.duration
                ),
                value: v.t,
                reason: "is outside the movement (0 to its duration)",
            });
        }
        if !matches!(v.order, Order::Position | Order::Velocity) {
            return Err(Error::InvalidValue {
                field: format!("via point {} derivative order", k + 1),
                value: v.order.index() as f64,
                reason: "is not 0 (position) or 1 (velocity)",
            });
        }
        if v.value.len() != dof {
            return Err(Error::DimensionMismatch {
                what: format!("via point {} joint count", k + 1),
                expected: dof,
                found: v.value.len(),
            });
        }
        if !v.cov.is_empty() && v.cov.len() != dof * dof {
            return Err(Error::DimensionMismatch {
                what: format!("via point {} covariance entries", k + 1),
                expected: dof * dof,
                found: v.cov.len(),
            });
        }
        for (i, &x) in v.value.iter().chain(&v.cov).enumerate() {
            crate::error::finite(|| format!("via point {} entry {}", k + 1, i + 1), x)?;
        }
        Ok(())
    }

    /// `B = H Σ_w` (`m × nw`, `m` = via points × joints) for the via points' basis rows
    /// `psis`: row (k, a) is `φ_kᵀ Σ[a-block rows, :]`.
    fn cross_covariance(&self, psis: &[f64]) -> Vec<f64> {
        let (dof, n) = (self.dof, self.basis.len());
        let nw = dof * n;
        let vias = psis.len() / n;
        let mut b = vec![0.0; vias * dof * nw];
        for k in 0..vias {
            let psi = &psis[k * n..(k + 1) * n];
            for a in 0..dof {
                let r = &mut b[(k * dof + a) * nw..(k * dof + a + 1) * nw];
                for i in 0..n {
                    let srow = &self.cov[(a * n + i) * nw..(a * n + i + 1) * nw];
                    crate::linalg::axpy(psi[i], srow, r);
                }
            }
        }
        b
    }

    /// The innovation covariance `G = B Hᵀ + Σ*` (`m × m`, symmetrized against roundoff).
    fn innovation(&self, via: &[ViaPoint], psis: &[f64], b: &[f64]) -> Vec<f64> {
        let (dof, n) = (self.dof, self.basis.len());
        let nw = dof * n;
        let m = via.len() * dof;
        let mut g = vec![0.0; m * m];
        for r in 0..m {
            for k2 in 0..via.len() {
                let psi = &psis[k2 * n..(k2 + 1) * n];
                for a2 in 0..dof {
                    let c = k2 * dof + a2;
                    g[r * m + c] =
                        crate::linalg::dot(&b[r * nw + a2 * n..r * nw + a2 * n + n], psi);
                }
            }
        }
        for (k, v) in via.iter().enumerate() {
            if !v.cov.is_empty() {
                for a in 0..dof {
                    for c in 0..dof {
                        g[(k * dof + a) * m + k * dof + c] += v.cov[a * dof + c];
                    }
                }
            }
        }
        symmetrize(&mut g, m);
        g
    }

    /// The mean trajectory as a standalone [`WeightTrajectory`].
    pub fn mean_trajectory(&self) -> WeightTrajectory {
        WeightTrajectory {
            basis: self.basis.clone(),
            dof: self.dof,
            duration: self.duration,
            weights: self.mean.clone(),
        }
    }

    /// Draws one trajectory `w ~ N(μ_w, Σ_w)` with the seeded generator (factors Σ_w each
    /// call; use [`ProMp::sampler`] for many draws).
    pub fn sample(&self, rng: &mut SplitMix64) -> Result<WeightTrajectory> {
        Ok(self.sampler()?.sample(rng))
    }

    /// A sampler that factors Σ_w once (regularized if it is singular, see
    /// [`ProMpSampler::jitter`]).
    pub fn sampler(&self) -> Result<ProMpSampler> {
        let chol = Cholesky::factor_regularized(&self.cov, self.mean.len())?;
        Ok(ProMpSampler {
            promp: self.clone(),
            chol,
        })
    }
}

/// Draws trajectories from a [`ProMp`] with a cached factor of Σ_w.
#[derive(Debug, Clone)]
pub struct ProMpSampler {
    promp: ProMp,
    chol: Cholesky,
}

impl ProMpSampler {
    /// The regularization added to Σ_w to factor it (0 when it was positive definite).
    pub fn jitter(&self) -> f64 {
        self.chol.jitter()
    }

    /// One draw `w = μ_w + L ξ`, `ξ ~ N(0, I)` from `rng`.
    pub fn sample(&self, rng: &mut SplitMix64) -> WeightTrajectory {
        let p = &self.promp;
        let nw = p.mean.len();
        let z: Vec<f64> = (0..nw).map(|_| rng.normal()).collect();
        let l = self.chol.l();
        let weights: Vec<f64> = (0..nw)
            .map(|i| p.mean[i] + crate::linalg::dot(&l[i * nw..i * nw + i + 1], &z[..i + 1]))
            .collect();
        WeightTrajectory {
            basis: p.basis.clone(),
            dof: p.dof,
            duration: p.duration,
            weights,
        }
    }
}

impl Trajectory for ProMp {
    fn dof(&self) -> usize {
        self.dof
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    /// The mean trajectory.
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        eval_weights(
            &self.basis,
            self.dof,
            self.duration,
            &self.mean,
            t,
            order,
            out,
        )
    }
}

/// Replaces the square `a` (`n × n`, row-major) by `(a + aᵀ)/2`.
fn symmetrize(a: &mut [f64], n: usize) {
    for r in 0..n {
        for c in 0..r {
            let s = 0.5 * (a[r * n + c] + a[c * n + r]);
            a[r * n + c] = s;
            a[c * n + r] = s;
        }
    }
}

/// `e` with the demonstration (0-based `i`) named in its field.
fn in_demo(i: usize, e: Error) -> Error {
    match e {
        Error::InvalidValue {
            field,
            value,
            reason,
        } => Error::InvalidValue {
            field: format!("demonstration {}: {field}", i + 1),
            value,
            reason,
        },
        Error::DimensionMismatch {
            what,
            expected,
            found,
        } => Error::DimensionMismatch {
            what: format!("demonstration {}: {what}", i + 1),
            expected,
            found,
        },
        other => other,
    }
}

fn eval_weights(
    basis: &GaussianBasis,
    dof: usize,
    duration: f64,
    w: &[f64],
    t: f64,
    order: Order,
    out: &mut [f64],
) {
    if t.is_nan() {
        out[..dof].iter_mut().for_each(|v| *v = f64::NAN);
        return;
    }
    let z = crate::traj::clamp_time(t, duration) / duration;
    let k = order.index();
    basis.combine(z, k, w, dof, &mut out[..dof]);
    if k > 0 {
        let f = duration.powi(-(k as i32));
        out[..dof].iter_mut().for_each(|v| *v *= f);
    }
}

/// A trajectory `y(t) = Ψ(t/T)ᵀ w` for fixed weights: a ProMP's mean or one of its samples.
#[derive(Debug, Clone)]
pub struct WeightTrajectory {
    basis: GaussianBasis,
    dof: usize,
    duration: f64,
    weights: Vec<f64>,
}

impl WeightTrajectory {
    /// The weights, stacked joint by joint.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }
}

impl Trajectory for WeightTrajectory {
    fn dof(&self) -> usize {
        self.dof
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        eval_weights(
            &self.basis,
            self.dof,
            self.duration,
            &self.weights,
            t,
            order,
            out,
        )
    }
}

/// Most weights (joints × basis functions) of a ProMP: the weight covariance is a dense
/// square of this size (128 MiB at the limit) that conditioning multiplies and factorizes.
pub const MAX_WEIGHTS: usize = 4096;

/// Refuses more than [`MAX_WEIGHTS`] weights before anything is allocated.
fn check_weight_count(nw: usize) -> Result<()> {
    crate::size::check(
        "ProMP weights (joints × basis functions)",
        nw as f64,
        MAX_WEIGHTS as f64,
        "the weight covariance is a dense square of this size",
    )?;
    Ok(())
}
