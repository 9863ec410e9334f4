//! Akima splines: C¹ piecewise cubics whose slopes are weighted averages of neighbouring secant
//! slopes, so that an outlier moves the curve only nearby and flat runs stay flat.

use crate::error::Result;
use crate::spline::ppoly::PiecewisePolynomial;
use crate::spline::validate;

/// Akima's interpolant through `y` (row-major `n × dim`) at increasing `x`, in the original
/// (1970) form or the modified one ("makima", which also weights by the secant magnitudes and
/// so does not overshoot on flat runs next to a step). Secant slopes are extended past the
/// ends linearly, as in scipy's `Akima1DInterpolator`, which it agrees with.
///
/// ```
/// use trajkit::{spline::AkimaSpline, Path};
/// let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
/// let y = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]; // a step
/// let sp = AkimaSpline::modified(&x, &y, 1)?;
/// let mut q = [0.0];
/// sp.eval(1.5, 0, &mut q); // stays flat before the step
/// assert!(q[0].abs() < 1e-15);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct AkimaSpline {
    pp: PiecewisePolynomial,
}

impl AkimaSpline {
    /// Akima's original weights |m_{i+1} − m_i|. At least 2 points.
    pub fn original(x: &[f64], y: &[f64], dim: usize) -> Result<Self> {
        Self::build(x, y, dim, false)
    }

    /// The modified Akima weights |m_{i+1} − m_i| + |m_{i+1} + m_i| / 2. At least 2 points.
    pub fn modified(x: &[f64], y: &[f64], dim: usize) -> Result<Self> {
        Self::build(x, y, dim, true)
    }

    fn build(x: &[f64], y: &[f64], dim: usize, modified: bool) -> Result<Self> {
        validate::interpolation_data(x, y, dim, 2)?;
        let n = x.len();
        let mut t = vec![0.0; n * dim];
        if n == 2 {
            for d in 0..dim {
                let m = (y[dim + d] - y[d]) / (x[1] - x[0]);
                t[d] = m;
                t[dim + d] = m;
            }
        } else {
            // Extended secants m[0..n+3], weights per point, one component at a time; the
            // cut-off for "both weights vanish" is relative to the largest weight over all
            // points and components.
            let mut m = vec![0.0; (n + 3) * dim];
            let mut f1 = vec![0.0; n * dim];
            let mut f2 = vec![0.0; n * dim];
            let mut mmax = f64::NEG_INFINITY;
            for d in 0..dim {
                let mm = |i: usize| i * dim + d;
                for i in 0..n - 1 {
                    m[mm(i + 2)] = (y[(i + 1) * dim + d] - y[i * dim + d]) / (x[i + 1] - x[i]);
                }
                m[mm(1)] = 2.0 * m[mm(2)] - m[mm(3)];
                m[mm(0)] = 2.0 * m[mm(1)] - m[mm(2)];
                m[mm(n + 1)] = 2.0 * m[mm(n)] - m[mm(n - 1)];
                m[mm(n + 2)] = 2.0 * m[mm(n + 1)] - m[mm(n)];
                let w = |j: usize| {
                    let dm = (m[mm(j + 1)] - m[mm(j)]).abs();
                    if modified {
                        dm + 0.5 * (m[mm(j + 1)] + m[mm(j)]).abs()
                    } else {
                        dm
                    }
                };
                for i in 0..n {
                    f1[i * dim + d] = w(i + 2);
                    f2[i * dim + d] = w(i);
                    mmax = mmax.max(f1[i * dim + d] + f2[i * dim + d]);
                    t[i * dim + d] = 0.5 * (m[mm(i + 3)] + m[mm(i)]);
                }
            }
            for d in 0..dim {
                let mm = |i: usize| i * dim + d;
                for i in 0..n {
                    let (a, b) = (f1[i * dim + d], f2[i * dim + d]);
                    let f12 = a + b;
                    if f12 > 1e-9 * mmax {
                        t[i * dim + d] = m[mm(i + 1)] + (b / f12) * (m[mm(i + 2)] - m[mm(i + 1)]);
                    }
                }
            }
        }
        Ok(AkimaSpline {
            pp: PiecewisePolynomial::cubic_hermite_unchecked(x, y, &t, dim),
        })
    }
}

crate::spline::ppoly_backed!(AkimaSpline);
