//! Hermite splines: cubic (values and velocities at the breaks, C¹) and quintic (values,
//! velocities and accelerations, C²).

use crate::error::Result;
use crate::spline::ppoly::PiecewisePolynomial;

/// The piecewise cubic with given values `y` and first derivatives `dydx` (both row-major
/// `n × dim`) at increasing breaks `x`. C¹; agrees with scipy's `CubicHermiteSpline`.
///
/// ```
/// use trajkit::{spline::CubicHermiteSpline, Path};
/// // One joint, stop-and-go through three points with a given velocity at the middle one.
/// let sp = CubicHermiteSpline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0], &[0.0, 0.5, 0.0], 1)?;
/// let mut v = [0.0];
/// sp.eval(1.0, 1, &mut v);
/// assert!((v[0] - 0.5).abs() < 1e-15);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CubicHermiteSpline {
    pp: PiecewisePolynomial,
}

impl CubicHermiteSpline {
    /// Values and velocities at the breaks; at least 2 breaks.
    pub fn new(x: &[f64], y: &[f64], dydx: &[f64], dim: usize) -> Result<Self> {
        Ok(CubicHermiteSpline {
            pp: PiecewisePolynomial::cubic_hermite(x, y, dydx, dim)?,
        })
    }
}

crate::spline::ppoly_backed!(CubicHermiteSpline);

/// The piecewise quintic with given values, first and second derivatives (row-major `n × dim`
/// each) at increasing breaks `x`. C²; on each piece it is the unique quintic with those six
/// end conditions (scipy's `BPoly.from_derivatives` with three orders per break).
///
/// ```
/// use trajkit::{spline::QuinticHermiteSpline, Path};
/// // Rest-to-rest 0 → 1 in 1 s: the minimum-jerk quintic, peak velocity 1.875 at mid-time.
/// let sp = QuinticHermiteSpline::new(&[0.0, 1.0], &[0.0, 1.0], &[0.0; 2], &[0.0; 2], 1)?;
/// let mut v = [0.0];
/// sp.eval(0.5, 1, &mut v);
/// assert!((v[0] - 1.875).abs() < 1e-14);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct QuinticHermiteSpline {
    pp: PiecewisePolynomial,
}

impl QuinticHermiteSpline {
    /// Values, velocities and accelerations at the breaks; at least 2 breaks.
    pub fn new(x: &[f64], y: &[f64], dydx: &[f64], d2ydx2: &[f64], dim: usize) -> Result<Self> {
        Ok(QuinticHermiteSpline {
            pp: PiecewisePolynomial::quintic_hermite(x, y, dydx, d2ydx2, dim)?,
        })
    }
}

crate::spline::ppoly_backed!(QuinticHermiteSpline);
