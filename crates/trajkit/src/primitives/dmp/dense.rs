//! The rollout of a DMP as a [`Trajectory`]: the integrated states, dense by quintic Hermite
//! interpolation (see the precision contract of [`super`]).

use crate::traj::{Order, Trajectory};

/// A DMP rollout: the integrated states, dense via quintic Hermite interpolation.
#[derive(Debug, Clone)]
pub struct DmpRollout {
    dof: usize,
    t: Vec<f64>,
    y: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
}

impl DmpRollout {
    /// One joint's `order`-th derivative at `t` (clamped time; NaN for NaN).
    pub fn eval_joint(&self, t: f64, order: Order, j: usize) -> f64 {
        let dof = self.dof;
        if t.is_nan() {
            return f64::NAN;
        }
        let t = crate::traj::clamp_time(t, self.duration());
        let k = order.index();
        let src = [&self.y, &self.v, &self.a];
        if self.t.len() < 2 {
            return if k < 3 { src[k][j] } else { 0.0 };
        }
        let i = crate::traj::find_piece(&self.t, t);
        let (t0, t1) = (self.t[i], self.t[i + 1]);
        let h = t1 - t0;
        if h.is_nan() || h <= 0.0 {
            // Degenerate (zero-length) step: report the sample itself.
            return if k < 3 {
                src[k][(i + 1) * dof + j]
            } else {
                0.0
            };
        }
        let s = (t - t0) / h;
        let (p0, p1) = (self.y[i * dof + j], self.y[(i + 1) * dof + j]);
        let (v0, v1) = (self.v[i * dof + j] * h, self.v[(i + 1) * dof + j] * h);
        let (a0, a1) = (
            self.a[i * dof + j] * h * h,
            self.a[(i + 1) * dof + j] * h * h,
        );
        let d = p1 - p0;
        let c = [
            p0,
            v0,
            0.5 * a0,
            10.0 * d - 6.0 * v0 - 4.0 * v1 - 1.5 * a0 + 0.5 * a1,
            -15.0 * d + 8.0 * v0 + 7.0 * v1 + 1.5 * a0 - a1,
            6.0 * d - 3.0 * v0 - 3.0 * v1 - 0.5 * a0 + 0.5 * a1,
        ];
        // k-th derivative of Σ c_m s^m, divided by h^k.
        let mut acc = 0.0;
        for m in (k..6).rev() {
            let mut f = 1.0;
            for q in 0..k {
                f *= (m - q) as f64;
            }
            acc = acc * s + f * c[m];
        }
        acc / h.powi(k as i32)
    }

    /// Builds a rollout from integrated states (crate-internal: rhythmic DMPs reuse it).
    pub(crate) fn from_states(
        dof: usize,
        t: Vec<f64>,
        y: Vec<f64>,
        v: Vec<f64>,
        a: Vec<f64>,
    ) -> Self {
        DmpRollout { dof, t, y, v, a }
    }

    /// Integration times (seconds), starting at 0.
    pub fn times(&self) -> &[f64] {
        &self.t
    }
    /// Positions at the integration times, row-major `times × dof`.
    pub fn positions(&self) -> &[f64] {
        &self.y
    }
    /// Velocities (per second) at the integration times.
    pub fn velocities(&self) -> &[f64] {
        &self.v
    }
    /// Accelerations at the integration times.
    pub fn accelerations(&self) -> &[f64] {
        &self.a
    }
}

impl Trajectory for DmpRollout {
    fn dof(&self) -> usize {
        self.dof
    }

    fn duration(&self) -> f64 {
        *self.t.last().unwrap_or(&0.0)
    }

    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        for (j, o) in out[..self.dof].iter_mut().enumerate() {
            *o = self.eval_joint(t, order, j);
        }
    }
}
