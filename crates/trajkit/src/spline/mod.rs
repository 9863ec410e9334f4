//! Splines and curves: piecewise polynomials, cubic/Hermite/PCHIP/Akima, Catmull-Rom, Bézier,
//! B-spline, NURBS, arc length and orientation interpolation.
//!
//! Every curve here is vector-valued: points are given row-major, `n × dim`, and evaluation
//! writes `dim` values into a caller buffer without allocating. Every curve implements
//! [`crate::Path`], so it can be handed to time parameterization as σ(s), or used directly as a
//! trajectory through [`crate::PathAsTrajectory`].
//!
//! # Vocabulary
//! Piecewise polynomials have **breaks** (piece boundaries) and per-piece **coefficients**;
//! B-splines and NURBS have **knots** and **control points**. Interpolating constructors take the
//! parameters `x` at which the curve passes through the points `y`.
//!
//! # Out-of-range parameters: clamped
//! One policy holds for every curve in this module, the same as [`crate::Path`] and
//! [`crate::Trajectory`]: **the parameter is clamped to the curve's interval**. For `s` below
//! the interval every curve reports its value *and derivatives* at the start, above it at the
//! end (derivatives are those of the end piece at the end point, not zero). There is no
//! extrapolation. A NaN parameter gives NaN outputs. Evaluation never panics for any `s`; the
//! only programming error is an output buffer shorter than `dim`.
//!
//! # Precision contract
//! - Interpolating splines reproduce their data points to within a few ulps of the data, and
//!   agree with scipy.interpolate's reference values within 1e-12 relative (fixtures under
//!   `tests/fixtures/spline/`).
//! - Derivatives of every order are evaluated analytically (no differencing) and agree with
//!   finite differences of the values to the accuracy finite differences allow.
//!
//! # Map
//! - [`PiecewisePolynomial`] (ppoly.rs): breaks + coefficients, the representation every
//!   interpolating spline is built on.
//! - [`CubicSpline`] (cubic.rs): natural, clamped, not-a-knot and periodic cubic splines, one
//!   O(n) banded solve.

mod banded;
mod cubic;
mod ppoly;
mod validate;

pub use cubic::CubicSpline;
pub use ppoly::PiecewisePolynomial;
