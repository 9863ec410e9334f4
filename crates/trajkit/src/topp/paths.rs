//! Piecewise-linear paths through waypoints.
//!
//! [`LinearPath`] joins waypoints by straight segments, parameterized by arc length in joint
//! space (s = cumulative Euclidean distance), so ‖σ′‖ = 1 and σ″ = σ‴ = 0 on each segment.
//! Its breakpoints are the waypoints. At an interior waypoint where the direction changes, the
//! velocity σ′ jumps: a robot can pass such a corner only at rest, so the planning helpers in
//! [`crate::topp::messy`] split a linear path at its corners into rest-to-rest pieces.
//!
//! # Precision contract
//! σ is evaluated as `w_i + (s − s_i)/L_i·(w_{i+1} − w_i)`: exact at the waypoints (up to the
//! rounding of s_i), with σ′ constant per segment. At a breakpoint the segment that starts there
//! is used (the last segment at the end).

use crate::error::{Error, Result};
use crate::traj::find_piece;
use crate::Path;

/// A polyline through waypoints, parameterized by arc length.
///
/// ```
/// use trajkit::{topp::LinearPath, Path};
/// // Three waypoints in 2-D (row-major).
/// let p = LinearPath::new(&[0.0, 0.0, 3.0, 4.0, 3.0, 5.0], 2)?;
/// assert_eq!(p.breakpoints(), vec![0.0, 5.0, 6.0]);
/// let mut q = [0.0; 2];
/// p.eval(2.5, 0, &mut q);
/// assert_eq!(q, [1.5, 2.0]);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct LinearPath {
    dim: usize,
    waypoints: Vec<f64>,
    s: Vec<f64>,
}

impl LinearPath {
    /// Waypoints row-major (`count × dim`); at least two, finite, no two consecutive equal.
    pub fn new(waypoints: &[f64], dim: usize) -> Result<Self> {
        let count = check_waypoints(waypoints, dim)?;
        let mut s = vec![0.0; count];
        for i in 1..count {
            let len = seg_len(waypoints, dim, i - 1);
            if len == 0.0 {
                return Err(Error::DuplicateWaypoint { index: i });
            }
            s[i] = s[i - 1] + len;
        }
        Ok(LinearPath {
            dim,
            waypoints: waypoints.to_vec(),
            s,
        })
    }

    /// The waypoints, row-major.
    pub fn waypoints(&self) -> &[f64] {
        &self.waypoints
    }
}

/// Checks a row-major waypoint array; returns the waypoint count.
pub(crate) fn check_waypoints(waypoints: &[f64], dim: usize) -> Result<usize> {
    if dim == 0 {
        return Err(Error::DimensionMismatch {
            what: "waypoint dimension".into(),
            expected: 1,
            found: 0,
        });
    }
    if waypoints.len() % dim != 0 {
        return Err(Error::DimensionMismatch {
            what: format!("waypoint array length (a multiple of {dim})"),
            expected: (waypoints.len() / dim + 1) * dim,
            found: waypoints.len(),
        });
    }
    let count = waypoints.len() / dim;
    if count < 2 {
        return Err(Error::TooFewWaypoints {
            needed: 2,
            found: count,
        });
    }
    if let Some(k) = waypoints.iter().position(|v| !v.is_finite()) {
        return Err(Error::InvalidValue {
            field: format!("waypoint {} joint {}", k / dim, k % dim + 1),
            value: waypoints[k],
            reason: "is not a finite number",
        });
    }
    Ok(count)
}

/// Euclidean length of segment `i` (waypoint i to i + 1).
pub(crate) fn seg_len(w: &[f64], dim: usize, i: usize) -> f64 {
    let mut sq = 0.0;
    for j in 0..dim {
        let d = w[(i + 1) * dim + j] - w[i * dim + j];
        sq += d * d;
    }
    sq.sqrt()
}

impl Path for LinearPath {
    fn dim(&self) -> usize {
        self.dim
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, self.s[self.s.len() - 1])
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        let (a, b) = self.interval();
        let s = s.clamp(a, b);
        let i = find_piece(&self.s, s);
        let n = self.dim;
        let w0 = &self.waypoints[i * n..(i + 1) * n];
        let w1 = &self.waypoints[(i + 1) * n..(i + 2) * n];
        let len = self.s[i + 1] - self.s[i];
        match order {
            0 => {
                let f = (s - self.s[i]) / len;
                for j in 0..n {
                    out[j] = w0[j] + f * (w1[j] - w0[j]);
                }
            }
            1 => {
                for j in 0..n {
                    out[j] = (w1[j] - w0[j]) / len;
                }
            }
            _ => out[..n].iter_mut().for_each(|v| *v = 0.0),
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.s.clone()
    }
    fn piecewise_degree(&self) -> Option<usize> {
        Some(1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arc_length_and_errors() {
        let p = LinearPath::new(&[0.0, 0.0, 3.0, 4.0, 3.0, 5.0], 2).unwrap();
        let mut d = [0.0; 2];
        p.eval(1.0, 1, &mut d);
        assert_eq!(d, [0.6, 0.8]);
        p.eval(5.5, 1, &mut d);
        assert_eq!(d, [0.0, 1.0]);
        p.eval(9.0, 0, &mut d);
        assert_eq!(d, [3.0, 5.0]);
        assert_eq!(
            LinearPath::new(&[1.0, 1.0, 1.0, 1.0], 2).unwrap_err(),
            Error::DuplicateWaypoint { index: 1 }
        );
        assert!(LinearPath::new(&[1.0, 2.0, 3.0], 2).is_err());
        assert!(LinearPath::new(&[1.0, 2.0], 2).is_err());
        let e = LinearPath::new(&[0.0, 1.0, f64::NAN, 2.0], 2).unwrap_err();
        assert!(e.to_string().contains("waypoint 1 joint 1 = NaN"), "{e}");
    }
}
