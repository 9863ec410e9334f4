//! Learning a DMP from one demonstration: forcing targets from the demonstration's
//! derivatives, streamed into the ridge regression of the weights.

use super::{extent_of, Dmp, DmpConfig, ForcingScaling};
use crate::error::Result;
use crate::primitives::basis::GaussianBasis;
use crate::primitives::demo::{check_demo, demo_derivatives};
use crate::primitives::ridge::RidgeAccumulator;

impl Dmp {
    /// Learns a DMP from one demonstration: times `t` (seconds, strictly increasing, at least 3)
    /// and positions `q` (row-major `t.len() × dof`). τ is the demonstration's duration, the
    /// start and goal its first and last positions, the start velocity its first velocity.
    /// The caller's arrays are only read.
    pub fn fit(t: &[f64], q: &[f64], dof: usize, cfg: &DmpConfig) -> Result<Dmp> {
        cfg.validate()?;
        check_demo(t, q, dof, 3)?;
        let basis = GaussianBasis::dmp(cfg.n_basis, cfg.alpha_x, cfg.overlap)?;
        let rows = t.len();
        let t0 = t[0];
        let tau = t[rows - 1] - t0;
        let ts: Vec<f64> = t.iter().map(|&v| v - t0).collect();
        let start = q[..dof].to_vec();
        let goal = q[(rows - 1) * dof..].to_vec();

        // Velocities and accelerations of the demonstration.
        let (vel, acc) = demo_derivatives(&ts, q, dof);
        let start_velocity = vel[..dof].to_vec();
        let amplitude = amplitudes(q, dof, &start, &goal);
        let demo = Demonstration {
            ts: &ts,
            q,
            vel: &vel,
            acc: &acc,
            dof,
            tau,
            start: &start,
            goal: &goal,
            amplitude: &amplitude,
        };
        let weights = demo.weights(&basis, cfg)?;
        Ok(Dmp {
            cfg: cfg.clone(),
            basis,
            dof,
            tau,
            start,
            start_velocity,
            goal,
            amplitude,
            weights,
            extent: extent_of(q, dof),
        })
    }
}

/// The demonstrated amplitude `g − y₀` per joint, for the Ijspeert scaling: 0 (learned
/// unscaled) where it is within 1e-12 of the joint's range (or exactly zero).
fn amplitudes(q: &[f64], dof: usize, start: &[f64], goal: &[f64]) -> Vec<f64> {
    let rows = q.len() / dof;
    (0..dof)
        .map(|j| {
            let (lo, hi) = (0..rows).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), k| {
                let v = q[k * dof + j];
                (lo.min(v), hi.max(v))
            });
            let a = goal[j] - start[j];
            if a.abs() <= 1e-12 * (hi - lo).max(f64::MIN_POSITIVE) || a == 0.0 {
                0.0
            } else {
                a
            }
        })
        .collect()
}

/// A demonstration with its derivatives, times from 0.
struct Demonstration<'a> {
    ts: &'a [f64],
    q: &'a [f64],
    vel: &'a [f64],
    acc: &'a [f64],
    dof: usize,
    tau: f64,
    start: &'a [f64],
    goal: &'a [f64],
    amplitude: &'a [f64],
}

impl Demonstration<'_> {
    /// The forcing targets `F` of every joint at sample `k` into `target`: what the
    /// transformation system lacks to reproduce the demonstrated acceleration.
    fn targets(&self, cfg: &DmpConfig, k: usize, x: f64, target: &mut [f64]) {
        let (az, bz, tau, dof) = (cfg.alpha_z, cfg.beta_z, self.tau, self.dof);
        let (goal, start) = (self.goal, self.start);
        for j in 0..dof {
            let (y, v, a) = (
                self.q[k * dof + j],
                self.vel[k * dof + j],
                self.acc[k * dof + j],
            );
            let spring = az * (bz * (goal[j] - y) - tau * v);
            target[j] = match cfg.scaling {
                ForcingScaling::Hoffmann2009 => {
                    tau * tau * a - spring + az * bz * (goal[j] - start[j]) * x
                }
                ForcingScaling::Ijspeert2013 => {
                    let amp = if self.amplitude[j] == 0.0 {
                        1.0
                    } else {
                        self.amplitude[j]
                    };
                    (tau * tau * a - spring) / amp
                }
            };
        }
    }

    /// The forcing weights (row-major `dof × n_basis`): forcing targets and design rows Φ
    /// (each row's span of non-zero basis values) streamed into the regression's normal
    /// equations.
    fn weights(&self, basis: &GaussianBasis, cfg: &DmpConfig) -> Result<Vec<f64>> {
        let nb = basis.len();
        let mut ridge = RidgeAccumulator::new(nb, self.dof);
        let mut target = vec![0.0; self.dof];
        let mut buf = [0.0f64; crate::primitives::basis::BLOCK];
        let mut dense = vec![0.0; if nb > buf.len() { nb } else { 0 }];
        for (k, &tk) in self.ts.iter().enumerate() {
            let x = (-cfg.alpha_x * tk / self.tau).exp();
            self.targets(cfg, k, x, &mut target);
            if dense.is_empty() {
                let (lo, hi) = basis.window(x, &mut buf);
                let row = &mut buf[lo..hi];
                let scale = x / row.iter().sum::<f64>();
                row.iter_mut().for_each(|v| *v *= scale);
                ridge.add_row(lo, row, &target);
            } else {
                basis.activations(x, 0, &mut dense);
                dense.iter_mut().for_each(|v| *v *= x);
                ridge.add_row(0, &dense, &target);
            }
        }
        ridge.solve(cfg.ridge, true)
    }
}
