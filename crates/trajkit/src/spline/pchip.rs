//! PCHIP: the shape-preserving piecewise cubic Hermite interpolant of Fritsch and Carlson,
//! with the Fritsch–Butland weighted harmonic mean for the slopes.

use crate::error::Result;
use crate::spline::ppoly::PiecewisePolynomial;
use crate::spline::validate;

/// A C¹ piecewise cubic through `y` (row-major `n × dim`) at increasing `x` that is monotone
/// wherever the data are and has no overshoot: between two waypoints each component stays
/// within their values. Slopes are zero at local extrema and at flats. Agrees with scipy's
/// `PchipInterpolator` (same one-sided three-point end slopes).
///
/// ```
/// use trajkit::{spline::PchipSpline, Path};
/// let sp = PchipSpline::new(&[0.0, 1.0, 2.0, 3.0], &[0.0, 1.0, 1.0, 2.0], 1)?;
/// let mut q = [0.0];
/// sp.eval(1.5, 0, &mut q); // flat between equal waypoints
/// assert_eq!(q[0], 1.0);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PchipSpline {
    pp: PiecewisePolynomial,
}

#[inline]
fn sign(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// One-sided three-point end slope, limited to keep the shape.
fn edge(h0: f64, h1: f64, m0: f64, m1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
    if sign(d) != sign(m0) {
        0.0
    } else if sign(m0) != sign(m1) && d.abs() > 3.0 * m0.abs() {
        3.0 * m0
    } else {
        d
    }
}

impl PchipSpline {
    /// Through `y` at `x`; at least 2 points (2 give the straight line).
    pub fn new(x: &[f64], y: &[f64], dim: usize) -> Result<Self> {
        validate::interpolation_data(x, y, dim, 2)?;
        let n = x.len();
        let h: Vec<f64> = (0..n - 1).map(|i| x[i + 1] - x[i]).collect();
        let mut dk = vec![0.0; n * dim];
        for d in 0..dim {
            let m = |i: usize| (y[(i + 1) * dim + d] - y[i * dim + d]) / h[i];
            if n == 2 {
                dk[d] = m(0);
                dk[dim + d] = m(0);
                continue;
            }
            for i in 1..n - 1 {
                let (ma, mb) = (m(i - 1), m(i));
                dk[i * dim + d] = if sign(ma) != sign(mb) || ma == 0.0 || mb == 0.0 {
                    0.0
                } else {
                    let w1 = 2.0 * h[i] + h[i - 1];
                    let w2 = h[i] + 2.0 * h[i - 1];
                    1.0 / ((w1 / ma + w2 / mb) / (w1 + w2))
                };
            }
            dk[d] = edge(h[0], h[1], m(0), m(1));
            dk[(n - 1) * dim + d] = edge(h[n - 2], h[n - 3], m(n - 2), m(n - 3));
        }
        Ok(PchipSpline {
            pp: PiecewisePolynomial::cubic_hermite_unchecked(x, y, &dk, dim),
        })
    }
}

crate::spline::ppoly_backed!(PchipSpline);
