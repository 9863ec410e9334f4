//! One module per lesson of the page: its request and response types and one function
//! `handle(Request) -> ApiResult<Response>` that validates the request, calls the library and
//! shapes the answer. No algorithm lives here: every number comes from a trajkit call.

pub mod bspline;
pub mod catmull_rom;
pub mod polynomials;
pub mod primitives;
pub mod profiles;

use super::error::{ApiError, ApiResult};
use serde::Serialize;
use trajkit::{Order, Trajectory};

/// A trajectory sampled at given times: position, velocity, acceleration and jerk, one array
/// per joint (`q[j][k]` is joint j at `t[k]`).
#[derive(Debug, Serialize)]
pub struct Series {
    /// Sample times, seconds.
    pub t: Vec<f64>,
    /// Positions per joint.
    pub q: Vec<Vec<f64>>,
    /// Velocities per joint.
    pub qd: Vec<Vec<f64>>,
    /// Accelerations per joint.
    pub qdd: Vec<Vec<f64>>,
    /// Jerks per joint.
    pub qddd: Vec<Vec<f64>>,
}

/// `count` equally spaced times from 0 to `duration` (both included; `count` ≥ 2); just `[0]`
/// for a motion of zero duration.
pub fn uniform_times(duration: f64, count: usize) -> Vec<f64> {
    if duration <= 0.0 || count < 2 {
        return vec![0.0];
    }
    let last = (count - 1) as f64;
    (0..count)
        .map(|k| {
            if k + 1 == count {
                duration
            } else {
                duration * k as f64 / last
            }
        })
        .collect()
}

/// Samples `traj` at `times` (through [`trajkit::sample::sample_at`]) into a [`Series`].
pub fn series<T: Trajectory + ?Sized>(traj: &T, times: Vec<f64>) -> ApiResult<Series> {
    let table =
        trajkit::sample::sample_at(traj, times).map_err(|e| ApiError::from_lib("samples", e))?;
    let columns = |order: Order| -> Vec<Vec<f64>> {
        let n = table.dof();
        let m = table.matrix(order).unwrap_or(&[]);
        (0..n)
            .map(|j| m.iter().skip(j).step_by(n).copied().collect())
            .collect()
    };
    Ok(Series {
        q: columns(Order::Position),
        qd: columns(Order::Velocity),
        qdd: columns(Order::Acceleration),
        qddd: columns(Order::Jerk),
        t: table.times().to_vec(),
    })
}

/// Rows of a row-major matrix with `dim` columns, for JSON.
pub fn to_rows(flat: &[f64], dim: usize) -> Vec<Vec<f64>> {
    flat.chunks(dim).map(<[f64]>::to_vec).collect()
}

fn default_samples() -> usize {
    201
}
