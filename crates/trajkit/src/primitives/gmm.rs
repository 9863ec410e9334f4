//! Gaussian mixture model (EM) and Gaussian mixture regression on time, used to build a KMP
//! reference distribution from demonstrations.
//!
//! Data points are `[t, q_1, …, q_d]`. [`Gmm::fit`] initializes the `k` components from `k`
//! equal slices of the data sorted by time (deterministic, no random restarts), then runs EM
//! with a diagonal regularization `reg` added to every covariance. [`Gmm::regress`] returns
//! the conditional mean and covariance of `q` given `t` (GMR).
//!
//! # Precision contract
//! - EM stops when the mean log-likelihood improves by less than `tol` (default 1e-9) or after
//!   `max_iter` iterations (default 200); the log-likelihood never decreases by more than
//!   roundoff (tests check monotonicity).
//! - Responsibilities use log-sum-exp, so far-away points never produce 0/0.
//! - GMR of a single component reproduces the Gaussian conditional exactly (tests).

use crate::error::{Error, Result};
use crate::linalg::Cholesky;

/// EM settings.
#[derive(Debug, Clone, PartialEq)]
pub struct GmmConfig {
    /// Number of components (default 8).
    pub components: usize,
    /// Maximum EM iterations (default 200).
    pub max_iter: usize,
    /// Stop when the mean log-likelihood improves by less than this (default 1e-9).
    pub tol: f64,
    /// Added to every covariance diagonal (default 1e-8).
    pub reg: f64,
}

impl Default for GmmConfig {
    fn default() -> Self {
        GmmConfig {
            components: 8,
            max_iter: 200,
            tol: 1e-9,
            reg: 1e-8,
        }
    }
}

/// A Gaussian mixture over `dim`-dimensional points.
#[derive(Debug, Clone)]
pub struct Gmm {
    dim: usize,
    priors: Vec<f64>,
    means: Vec<f64>,
    covs: Vec<f64>,
    log_likelihood: f64,
    iterations: usize,
}

fn log_gauss_all(x: &[f64], mean: &[f64], chol: &Cholesky, dim: usize, scratch: &mut [f64]) -> f64 {
    for i in 0..dim {
        scratch[i] = x[i] - mean[i];
    }
    chol.solve_lower_in_place(&mut scratch[..dim]);
    let m: f64 = scratch[..dim].iter().map(|v| v * v).sum();
    -0.5 * (m + chol.log_det() + dim as f64 * (2.0 * std::f64::consts::PI).ln())
}

/// Checks the data (a multiple of `dim` finite values, at least two samples per component)
/// and the regularization; returns the sample count.
fn check_data(data: &[f64], dim: usize, cfg: &GmmConfig) -> Result<usize> {
    let k = cfg.components;
    if dim == 0 || data.len() % dim != 0 {
        return Err(Error::DimensionMismatch {
            what: "GMM data entries (a multiple of the dimension)".into(),
            expected: dim.max(1) * (data.len() / dim.max(1) + 1),
            found: data.len(),
        });
    }
    let rows = data.len() / dim;
    if k == 0 || rows < 2 * k {
        return Err(Error::TooFewWaypoints {
            needed: 2 * k.max(1),
            found: rows,
        });
    }
    // Responsibilities: one per sample and component.
    crate::size::check_memory(
        "samples × GMM components",
        rows as f64 * k as f64,
        8.0,
        "a responsibility",
    )?;
    if let Some(i) = data.iter().position(|v| !v.is_finite()) {
        return Err(Error::InvalidValue {
            field: format!("GMM data point {} entry {}", i / dim, i % dim),
            value: data[i],
            reason: "is not a finite number",
        });
    }
    if !(cfg.reg.is_finite() && cfg.reg >= 0.0) {
        return Err(Error::InvalidValue {
            field: "GMM regularization".into(),
            value: cfg.reg,
            reason: "is not a non-negative finite number",
        });
    }
    Ok(rows)
}

impl Gmm {
    /// Fits a mixture to `data` (row-major `rows × dim`, first column = time).
    pub fn fit(data: &[f64], dim: usize, cfg: &GmmConfig) -> Result<Gmm> {
        let k = cfg.components;
        let rows = check_data(data, dim, cfg)?;
        // Initialization: equal slices in time.
        let mut order: Vec<usize> = (0..rows).collect();
        order.sort_by(|&a, &b| data[a * dim].total_cmp(&data[b * dim]));
        let mut resp = vec![0.0; rows * k];
        for (pos, &r) in order.iter().enumerate() {
            let c = (pos * k / rows).min(k - 1);
            resp[r * k + c] = 1.0;
        }
        let mut g = Gmm {
            dim,
            priors: vec![1.0 / k as f64; k],
            means: vec![0.0; k * dim],
            covs: vec![0.0; k * dim * dim],
            log_likelihood: f64::NEG_INFINITY,
            iterations: 0,
        };
        g.m_step(data, rows, &resp, cfg.reg);
        for it in 0..cfg.max_iter {
            let ll = g.e_step(data, rows, &mut resp)?;
            let improved = ll - g.log_likelihood;
            g.log_likelihood = ll;
            g.iterations = it + 1;
            g.m_step(data, rows, &resp, cfg.reg);
            if improved.abs() < cfg.tol {
                break;
            }
        }
        Ok(g)
    }

    /// The responsibilities of every component for every sample into `resp` (log-sum-exp);
    /// returns the mean log-likelihood.
    fn e_step(&self, data: &[f64], rows: usize, resp: &mut [f64]) -> Result<f64> {
        let (dim, k) = (self.dim, self.priors.len());
        let mut scratch = vec![0.0; dim];
        let mut logp = vec![0.0; k];
        let chols: Vec<Cholesky> = (0..k)
            .map(|c| {
                Cholesky::factor_regularized(&self.covs[c * dim * dim..(c + 1) * dim * dim], dim)
            })
            .collect::<Result<_>>()?;
        let mut ll = 0.0;
        for r in 0..rows {
            let x = &data[r * dim..(r + 1) * dim];
            let mut mx = f64::NEG_INFINITY;
            for c in 0..k {
                logp[c] = self.priors[c].max(1e-300).ln()
                    + log_gauss_all(
                        x,
                        &self.means[c * dim..(c + 1) * dim],
                        &chols[c],
                        dim,
                        &mut scratch,
                    );
                mx = mx.max(logp[c]);
            }
            let s: f64 = logp.iter().map(|l| (l - mx).exp()).sum();
            let lse = mx + s.ln();
            ll += lse;
            for c in 0..k {
                resp[r * k + c] = (logp[c] - lse).exp();
            }
        }
        Ok(ll / rows as f64)
    }

    fn m_step(&mut self, data: &[f64], rows: usize, resp: &[f64], reg: f64) {
        let (dim, k) = (self.dim, self.priors.len());
        for c in 0..k {
            let nk: f64 = (0..rows).map(|r| resp[r * k + c]).sum::<f64>().max(1e-300);
            self.priors[c] = nk / rows as f64;
            let mean = &mut self.means[c * dim..(c + 1) * dim];
            mean.iter_mut().for_each(|v| *v = 0.0);
            for r in 0..rows {
                crate::linalg::axpy(resp[r * k + c] / nk, &data[r * dim..(r + 1) * dim], mean);
            }
            let cov = &mut self.covs[c * dim * dim..(c + 1) * dim * dim];
            cov.iter_mut().for_each(|v| *v = 0.0);
            for r in 0..rows {
                let w = resp[r * k + c] / nk;
                if w == 0.0 {
                    continue;
                }
                let x = &data[r * dim..(r + 1) * dim];
                for i in 0..dim {
                    let di = w * (x[i] - mean[i]);
                    for j in 0..=i {
                        cov[i * dim + j] += di * (x[j] - mean[j]);
                    }
                }
            }
            for i in 0..dim {
                for j in 0..i {
                    cov[j * dim + i] = cov[i * dim + j];
                }
                cov[i * dim + i] += reg;
            }
        }
    }

    /// Point dimension (1 + joints).
    pub fn dim(&self) -> usize {
        self.dim
    }
    /// Mixture weights.
    pub fn priors(&self) -> &[f64] {
        &self.priors
    }
    /// Component means, row-major `k × dim`.
    pub fn means(&self) -> &[f64] {
        &self.means
    }
    /// Component covariances, `k` row-major `dim × dim` blocks.
    pub fn covariances(&self) -> &[f64] {
        &self.covs
    }
    /// Mean log-likelihood per point at the last E step.
    pub fn log_likelihood(&self) -> f64 {
        self.log_likelihood
    }
    /// EM iterations run.
    pub fn iterations(&self) -> usize {
        self.iterations
    }

    /// GMR: mean (`dim − 1`) and covariance (`(dim − 1)²`, row-major) of the other coordinates
    /// given the first one equals `t`.
    pub fn regress(&self, t: f64, mean: &mut [f64], cov: &mut [f64]) {
        let dim = self.dim;
        let d = dim - 1;
        let k = self.priors.len();
        // Responsibilities in t.
        let mut mx = f64::NEG_INFINITY;
        let logh: Vec<f64> = (0..k)
            .map(|c| {
                let s = self.covs[c * dim * dim];
                let r = t - self.means[c * dim];
                let l = self.priors[c].max(1e-300).ln() - 0.5 * (r * r / s + s.ln());
                mx = mx.max(l);
                l
            })
            .collect();
        let tot: f64 = logh.iter().map(|l| (l - mx).exp()).sum();
        mean[..d].iter_mut().for_each(|v| *v = 0.0);
        cov[..d * d].iter_mut().for_each(|v| *v = 0.0);
        let mut mu = vec![0.0; d];
        for c in 0..k {
            let h = (logh[c] - mx).exp() / tot;
            let base = c * dim * dim;
            let s = self.covs[base];
            let r = t - self.means[c * dim];
            for i in 0..d {
                mu[i] = self.means[c * dim + 1 + i] + self.covs[base + (1 + i) * dim] / s * r;
            }
            for i in 0..d {
                mean[i] += h * mu[i];
                for j in 0..d {
                    let sij = self.covs[base + (1 + i) * dim + 1 + j]
                        - self.covs[base + (1 + i) * dim] * self.covs[base + (1 + j) * dim] / s;
                    cov[i * d + j] += h * (sij + mu[i] * mu[j]);
                }
            }
        }
        for i in 0..d {
            for j in 0..d {
                cov[i * d + j] -= mean[i] * mean[j];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    #[test]
    fn single_component_gmr_is_the_gaussian_conditional() {
        let mut rng = SplitMix64::new(1);
        let n = 4000;
        let mut data = Vec::new();
        for _ in 0..n {
            let t = rng.normal();
            let e = rng.normal();
            data.extend_from_slice(&[t, 2.0 * t + 0.5 * e + 1.0]);
        }
        let g = Gmm::fit(
            &data,
            2,
            &GmmConfig {
                components: 1,
                ..Default::default()
            },
        )
        .unwrap();
        let (mut m, mut c) = ([0.0], [0.0]);
        g.regress(0.5, &mut m, &mut c);
        assert!((m[0] - 2.0).abs() < 0.05, "{}", m[0]);
        assert!((c[0] - 0.25).abs() < 0.02, "{}", c[0]);
    }

    #[test]
    fn em_separates_two_clusters_and_likelihood_increases() {
        let mut rng = SplitMix64::new(2);
        let mut data = Vec::new();
        for i in 0..400 {
            let t = i as f64 / 400.0;
            let y = if t < 0.5 { 0.0 } else { 3.0 };
            data.extend_from_slice(&[t, y + 0.1 * rng.normal()]);
        }
        let mut last = f64::NEG_INFINITY;
        for it in [1, 3, 10, 50] {
            let g = Gmm::fit(
                &data,
                2,
                &GmmConfig {
                    components: 2,
                    max_iter: it,
                    tol: 0.0,
                    ..Default::default()
                },
            )
            .unwrap();
            assert!(g.log_likelihood() >= last - 1e-9);
            last = g.log_likelihood();
        }
        let g = Gmm::fit(
            &data,
            2,
            &GmmConfig {
                components: 2,
                ..Default::default()
            },
        )
        .unwrap();
        let (mut m, mut c) = ([0.0], [0.0]);
        g.regress(0.1, &mut m, &mut c);
        assert!(m[0].abs() < 0.05);
        g.regress(0.9, &mut m, &mut c);
        assert!((m[0] - 3.0).abs() < 0.05);
        assert!(Gmm::fit(&data[..6], 2, &GmmConfig::default()).is_err());
    }
}
