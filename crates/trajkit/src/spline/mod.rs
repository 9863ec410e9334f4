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
//! Checked by the tests under `tests/spline_*.rs`:
//! - Interpolating splines reproduce their data to rounding (1e-12 relative in the tests).
//! - Against scipy.interpolate (CubicSpline with every end condition, CubicHermiteSpline,
//!   BPoly.from_derivatives, PchipInterpolator, Akima1DInterpolator, make_interp_spline,
//!   make_lsq_spline, BSpline derivatives, insert_knot, design_matrix) and geomdl (NURBS and
//!   its derivatives, Bézier degree elevation): within 1e-12 relative to the largest value of
//!   each derivative order (fixtures in `tests/fixtures/spline/`; observed ≤ 2e-14).
//! - Derivatives of every order are analytic and agree with finite differences.
//! - The 9-point NURBS unit circle has radius 1 within 1e-14 (observed 2.2e-16).
//! - [`ArcLength`]: length, inverse and reparameterized positions within the requested
//!   absolute tolerance; the reparameterized speed is 1 to rounding.
//! - [`SO3Spline`] passes through its keyframes within 1e-12 rad.
//!
//! # Map
//! - [`PiecewisePolynomial`] (ppoly.rs): breaks + coefficients, the representation every
//!   interpolating spline is built on.
//! - [`CubicSpline`] (cubic.rs): natural, clamped, not-a-knot and periodic cubic splines, one
//!   O(n) banded solve.
//! - [`CubicHermiteSpline`], [`QuinticHermiteSpline`] (hermite.rs): given velocities (and
//!   accelerations) at the breaks.
//! - [`BSpline`] (bspline.rs, fitting in bspline/fit.rs, basis functions in basis.rs): any
//!   degree up to [`MAX_DEGREE`], knot insertion, degree elevation, interpolation with
//!   end-derivative conditions ([`BSpline::minimum_jerk`], [`BSpline::minimum_snap`]), least
//!   squares, [`DesignMatrix`].
//! - [`CatmullRom`] (catmull_rom.rs): uniform, centripetal, chordal ([`CatmullRomKind`]).
//! - [`Bezier`] (bezier.rs): de Casteljau, hodograph, subdivision, degree elevation.
//! - [`Nurbs`] (nurbs.rs): weights, rational derivatives, exact circles and arcs.
//! - [`ArcLength`] (arclen.rs): length, inverse and arc-length reparameterization of any
//!   [`crate::Path`] to a requested tolerance.
//! - [`Quat`] and [`SO3Spline`] (quat.rs): slerp and a C² interpolating orientation spline
//!   with angular velocity and acceleration.
//! - [`PchipSpline`] (pchip.rs) and [`AkimaSpline`] (akima.rs): shape-preserving C¹ cubics, no
//!   overshoot between waypoints.
//! - [`BoundedSpline`] (bounded.rs): a C² spline repaired to stay inside per-component bounds
//!   (joint position ranges), verified exactly; the planner's path.
//!
//! # Implementation notes
//!
//! `spline/` — one curve type per file, all implementing `Path`. Interpolating splines
//! (`cubic`, `hermite`, `pchip`, `akima`, `catmull_rom`) compute slopes at the breaks and hand
//! them to `ppoly.rs` (`PiecewisePolynomial`), which does all evaluation. Global systems go
//! through `banded.rs` (banded LU; periodic by Sherman–Morrison), so construction is O(n).
//! `basis.rs` (Cox–de Boor in stack buffers) serves `bspline.rs` (evaluation, design matrix,
//! knot insertion, elevation; its `fit.rs` does interpolation incl. minimum-jerk/snap and
//! least squares by banded Givens QR) and `nurbs.rs`;
//! `bezier.rs` is de Casteljau; `arclen.rs` wraps any `Path`; `quat.rs` is SO(3) (slerp,
//! cumulative B-spline). `validate.rs` holds the shared input checks. `bounded.rs`
//! (`BoundedSpline`) repairs a C² spline so that each component stays inside its bounds
//! (joint ranges), verified exactly: piece extrema from the derivative's roots, offending
//! joints' slope and curvature at the neighbouring breaks reduced step by step (quintic Hermite,
//! C²), ending at rest where needed (monotone pieces).

/// Accessors and the [`crate::Path`] implementation of a curve that is a
/// [`PiecewisePolynomial`] in a field `pp`.
macro_rules! ppoly_backed {
    ($t:ident) => {
        impl $t {
            /// The curve as a piecewise polynomial (its breaks are the interpolation
            /// parameters).
            pub fn as_ppoly(&self) -> &$crate::spline::PiecewisePolynomial {
                &self.pp
            }

            /// Consumes the curve, returning its piecewise polynomial.
            pub fn into_ppoly(self) -> $crate::spline::PiecewisePolynomial {
                self.pp
            }

            /// The breaks (the interpolation parameters `x`).
            pub fn breaks(&self) -> &[f64] {
                self.pp.breaks()
            }
        }

        impl $crate::Path for $t {
            fn dim(&self) -> usize {
                self.pp.dim()
            }
            fn interval(&self) -> (f64, f64) {
                $crate::Path::interval(&self.pp)
            }
            fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
                self.pp.eval(s, order, out)
            }
            fn eval_derivatives(&self, s: f64, first: &mut [f64], second: &mut [f64]) {
                self.pp.eval_derivatives(s, first, second)
            }
            fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
                self.pp.eval_many(s, order, out)
            }
            fn eval_many_orders(&self, s: &[f64], out: [&mut [f64]; 4]) {
                self.pp.eval_many_orders(s, out)
            }
            fn breakpoints(&self) -> Vec<f64> {
                self.pp.breaks().to_vec()
            }
            fn piecewise_degree(&self) -> Option<usize> {
                Some(self.pp.degree())
            }
        }
    };
}
pub(crate) use ppoly_backed;

mod akima;
pub(crate) mod arclen;
mod banded;
mod basis;
mod bezier;
mod bounded;
mod bspline;
mod catmull_rom;
mod cubic;
mod hermite;
mod nurbs;
mod pchip;
mod ppoly;
mod quat;
mod validate;

pub use akima::AkimaSpline;
pub use arclen::ArcLength;
pub use bezier::Bezier;
pub use bounded::{BoundRepair, BoundedSpline, MAX_HALVINGS};
pub use bspline::{BSpline, DesignMatrix, EndDerivative, MAX_DEGREE};
pub use catmull_rom::{CatmullRom, CatmullRomKind};
pub use cubic::CubicSpline;
pub use hermite::{CubicHermiteSpline, QuinticHermiteSpline};
pub use nurbs::{Nurbs, NURBS_MAX_ORDER};
pub use pchip::PchipSpline;
pub use ppoly::PiecewisePolynomial;
pub use quat::{Quat, SO3Spline};

/// Small 3-vector helpers shared with the orientation DMP.
pub(crate) use quat::cross;
