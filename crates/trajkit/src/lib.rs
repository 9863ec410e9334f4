//! # trajkit
//!
//! Robot paths in, trajectories out. A planner returns waypoints in joint space; a controller
//! needs position, velocity, acceleration and jerk at every instant, within the robot's limits.
//! trajkit does that step: time-optimal path parameterization, polynomials and splines, online
//! jerk-limited generation and movement primitives, each producing a [`Trajectory`] that can
//! be sampled, checked against the limits and plotted.
//!
//! ## The main job
//! Waypoints and limits in, a trajectory that keeps every limit (position range included) out,
//! checked on the very samples it returns:
//!
//! ```
//! use trajkit::{io::Waypoints, plan, Limits, Order, PlanOptions, Trajectory};
//!
//! // Three waypoints of a Panda's seven joints (row-major), named as in the Panda's limits.
//! let names = (1..=7).map(|j| format!("panda_joint{j}")).collect();
//! let w = Waypoints::new(
//!     vec![
//!         0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0, //
//!         0.5, 0.3, -0.2, -1.2, 0.1, 1.8, 0.4, //
//!         1.0, -0.2, 0.1, -2.0, 0.3, 1.2, 0.8,
//!     ],
//!     7,
//!     names,
//! )?;
//! let limits = Limits::preset("panda")?;
//! // TOPP-RA on a range-safe spline, then the jerk stage; every limit is checked.
//! let p = plan(&w, &limits, &PlanOptions::default())?;
//! assert!(p.report.passes(&trajkit::check::Tolerance::default()));
//! let mut qd = [0.0; 7];
//! p.trajectory.eval(p.trajectory.duration() / 2.0, Order::Velocity, &mut qd);
//! assert!(qd[0].abs() <= 2.175 * (1.0 + 1e-9));
//! # Ok::<(), trajkit::Error>(())
//! ```
//!
//! ## Map
//! - [`plan()`]: the main job in one call ([`mod@plan`]: methods, guarantees, sizes).
//! - [`traj`]: the trajectory model ([`Trajectory`], [`Order`], [`State`]), shared by every
//!   family; [`path`]: geometric paths σ(s) ([`Path`]), the input of time parameterization.
//! - [`limits`]: per-joint [`Limits`], robot presets, limits files ([`limits::load`]), and
//!   [`limits::LimitsSpec`], the one recipe from a front end's settings to the limits of its
//!   data.
//! - Families that build trajectories:
//!   - [`poly`]: point-to-point polynomials (cubic, quintic/minimum-jerk, septic), shortest
//!     durations within limits, piecewise polynomials through waypoints.
//!   - [`spline`]: splines and curves (cubic, Hermite, PCHIP, Akima, Catmull-Rom, Bézier,
//!     B-spline, NURBS, arc length, SO(3)); every curve is a [`Path`].
//!   - [`topp`]: time-optimal path parameterization (TOPP-RA with general constraints,
//!     numerical integration, TOTG, bounded jerk) and time rescaling of any path.
//!   - [`otg`]: online jerk-limited generation, any state to any state, synchronized DOFs.
//!   - [`primitives`]: movement primitives learned from demonstrations: DMP, ProMP, KMP.
//! - [`InverseDynamics`]: the model behind torque limits in [`topp`]; `dynamics` implements
//!   it for a serial chain read from a URDF (`urdf`, the one URDF reader; feature `urdf`).
//! - [`sample`], [`check`], [`plot`], [`io`]: sampling into tables, limit checking, SVG plots,
//!   waypoints and tables in CSV (and JSON, feature `serde`).
//! - [`error`]: the one [`Error`] type; [`size`]: the memory budget; [`linalg`], [`roots`] (real roots of polynomials), [`rng`].
//!
//! ARCHITECTURE.md in the repository is the one-page map of modules and data flow.
//!
//! ## Cargo features
//! All on by default; `default-features = false` leaves the core (trajectory model, poly,
//! spline, otg, topp, primitives, plan, CSV) without serde, YAML or XML.
//! - `serde`: JSON limits files, waypoints and tables, otg's JSON problems, check reports.
//! - `yaml` (implies `serde`): trajkit YAML limits files and MoveIt `joint_limits.yaml`.
//! - `urdf`: URDF limits, the `urdf` reader and `dynamics` (roxmltree).
//!
//! ## Precision contracts
//! Every module states its precision in its documentation and its tests check it, e.g.
//! [`poly`] (each end's boundary conditions met to rounding, shortest durations bisected to
//! 1e-10 relative), [`topp`] (limits held between gridpoints, the automatic grid refined until
//! the duration settles within 1e-4), [`otg`] (a profile is accepted only after integrating
//! it verifies it), [`check`] (the tolerance of a limit check). A result never breaks a limit
//! it was given.
//!
//! ## Conventions
//! - Units are the joint's: rad or m, per second, per second², per second³.
//! - Public signatures take plain slices: `&[f64]` row-major with a `dof` (one row per
//!   waypoint or sample, one column per joint); no linear-algebra crate types.
//! - A limit of `f64::INFINITY` means "unlimited", stated on purpose; an absent limit is an
//!   error where it is needed ([`Error::MissingLimit`]), never "unlimited".
//! - Bad input gets a typed [`Error`] naming the field and the value; the library never
//!   panics on user input. Sizes a caller controls are checked before allocating.
//! - Evaluation ([`Trajectory::eval`]) and the online update ([`otg::Otg`]) allocate nothing.
//! - Each family is a public module whose root re-exports the items users need;
//!   implementation files are private (see ARCHITECTURE.md, "Public API convention").

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
mod num;
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
