//! # trajkit
//!
//! Robot paths in, trajectories out. A planner returns waypoints in joint space; a controller
//! needs position, velocity, acceleration and jerk at every instant, within the robot's limits.
//! trajkit does that step.
//!
//! ```
//! use trajkit::{poly::{Degree, PolyMove}, Limits, Order, Trajectory};
//!
//! // A minimum-jerk (quintic) move of a Panda's first two joints, as fast as the limits allow.
//! let limits = Limits::preset("panda")?;
//! let q0 = [0.0, 0.0];
//! let q1 = [1.0, -0.5];
//! let two = trajkit::Limits::new(limits.joints()[..2].to_vec())?;
//! let t = trajkit::poly::min_duration_rest_to_rest(Degree::Quintic, &q0, &q1, &two)?;
//! let mv = PolyMove::rest_to_rest(Degree::Quintic, &q0, &q1, t)?;
//! let mut qd = [0.0; 2];
//! mv.eval(t / 2.0, Order::Velocity, &mut qd); // peak velocity at mid-time
//! assert!(qd[0] <= 2.175 * (1.0 + 1e-12));
//! # Ok::<(), trajkit::Error>(())
//! ```
//!
//! ## Map
//! - [`plan()`]: the main job in one call: waypoints and limits in, a trajectory that keeps
//!   every limit (position range included) out, checked ([`mod@plan`] module).
//! - [`traj`]: the trajectory model ([`Trajectory`], [`Order`]), shared by every family.
//! - [`path`]: geometric paths σ(s), the input of time parameterization.
//! - [`limits`]: per-joint limits, robot presets, limits files and URDF.
//! - [`poly`]: point-to-point polynomials (cubic, quintic/minimum-jerk, septic) and
//!   multi-waypoint piecewise polynomials.
//! - [`otg`]: online jerk-limited generation, any state to any state, synchronized DOFs.
//! - [`linalg`]: small dense solvers (Cholesky, LU) on row-major slices.
//! - [`roots`]: real roots of polynomials on an interval (extrema of polynomials).
//! - [`sample`], [`check`], [`plot`], [`io`]: sampling into tables, limit checking, SVG plots,
//!   CSV/JSON reading and writing.
//!
//! - [`spline`]: splines and curves (cubic, Hermite, PCHIP, Akima, Catmull-Rom, Bézier,
//!   B-spline, NURBS, arc length, SO(3)); every curve is a [`Path`].
//! - [`topp`]: time-optimal path parameterization (TOPP-RA with general constraints, bounded-jerk
//!   output) and time rescaling of any path.
//! - [`dynamics`]: rigid-body inverse dynamics of a serial chain read from a URDF (for torque
//!   limits in [`topp`]).
//! - [`primitives`]: movement primitives learned from demonstrations: DMP, ProMP, KMP.
//!
//! See ARCHITECTURE.md in the repository for how data flows between them.

#![forbid(unsafe_code)]

// Unit tests that reuse the integration tests' helpers (written against `trajkit::`).
#[cfg(test)]
extern crate self as trajkit;

pub mod check;
#[cfg(feature = "urdf")]
pub mod dynamics;
pub mod error;
mod inverse_dynamics;
pub mod io;
pub mod limits;
pub mod linalg;
pub mod otg;
pub mod path;
pub mod plan;
pub mod plot;
pub mod poly;
pub mod primitives;
pub mod rng;
pub mod roots;
pub mod sample;
pub mod size;
pub mod spline;
pub mod topp;
pub mod traj;
#[cfg(feature = "urdf")]
pub mod urdf;

pub use error::{Error, Result};
pub use inverse_dynamics::InverseDynamics;
pub use limits::{JointLimits, Limits};
pub use path::{Path, PathAsTrajectory};
pub use plan::{plan, Plan, PlanOptions};
pub use sample::SampleTable;
pub use traj::{Order, State, Trajectory};

/// The README's code examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
