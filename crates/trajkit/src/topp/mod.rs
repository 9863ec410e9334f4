//! Time-optimal path parameterization (TOPP-RA, TOTG, numerical integration) and time rescaling.
//!
//! Keep a path's geometry σ(s), choose its timing s(t) so that every instant respects the
//! robot's limits, as fast as possible. The pieces mirror the algorithm (private files,
//! their items re-exported here):
//! - constraints (constraint.rs) in the general form a(s)·s̈ + b(s)·ṡ² + c(s) ∈ {F v ≤ g}
//!   plus bounds on ṡ² ([`Constraint`]): [`JointVelocity`], [`JointAcceleration`],
//!   [`JointTorque`] through user [`InverseDynamics`], [`EndEffectorSpeed`] through a user
//!   [`Jacobian`];
//! - the exact two-variable linear program solved at every stage (lp.rs, crate-internal);
//! - gridpoints ([`Gridpoints`], grid.rs): automatic from a duration tolerance, uniform, chord
//!   tolerance, given, always including path breakpoints;
//! - [`Toppra`] (toppra.rs, options [`ToppraOptions`]): the backward (controllable sets) and
//!   forward (greedy) passes; between.rs holds the limits between gridpoints (Bernstein rows
//!   and exact checks on piecewise-cubic paths, sampled checks elsewhere);
//! - the solved [`PhaseProfile`] and the exact output trajectory [`Parametrized`]
//!   (parametrized.rs);
//! - [`Retimed`] (rescale.rs): any path composed with any [`TimeLaw`], and uniform time
//!   scaling ([`Scaled`], [`min_time_scale`]);
//! - [`LinearPath`] (paths.rs): piecewise-linear paths;
//! - [`BlendedPath`] (blend.rs): TOTG's path, straight segments joined by circular blends;
//! - [`Totg`] / [`plan_totg`] (totg.rs): time-optimal trajectory generation (Kunz & Stilman)
//!   on a blended path;
//! - [`max_velocity_curve`] (mvc.rs): the phase-plane limit above a profile.
//!
//! Four submodules are public namespaces, because their names would collide here:
//! - [`ni`]: numerical integration in the phase plane (Bobrow / TOPP-NI) on any path, with the
//!   same constraints ([`ni::solve`], [`ni::solve_profile`]);
//! - [`messy`]: planner output as it comes: duplicates, reversals, rest-to-rest pieces
//!   ([`messy::plan_waypoints`], [`messy::PlanOptions`]);
//! - [`jerk`]: the jerk-bounding stage after TOPP-RA;
//! - [`jerk_optimal`]: jerk-limited time-optimal parameterization by third-order reachability.
//!
//! ```
//! use trajkit::topp::{Gridpoints, LinearPath, Toppra};
//! use trajkit::{Limits, Order, Trajectory};
//!
//! // A straight move of all 7 Panda joints by 0.5 rad, as fast as the Panda's limits allow.
//! let limits = Limits::preset("panda")?;
//! let mut waypoints = vec![0.0; 7];
//! waypoints.extend([0.5; 7]);
//! let path = LinearPath::new(&waypoints, 7)?;
//! let traj = Toppra::with_limits(path, &limits)?
//!     .gridpoints(Gridpoints::Uniform(200))
//!     .solve()?;
//! let mut q = [0.0; 7];
//! traj.eval(traj.duration(), Order::Position, &mut q);
//! assert!(q.iter().all(|&v| (v - 0.5).abs() < 1e-12));
//! // Joint 2 has the smallest acceleration limit (7.5 rad/s²): it sets the pace.
//! // 0.5 rad with v = 2.175, a = 7.5: triangle (0.5 < v²/a), T = 2·√(0.5/7.5).
//! assert!((traj.duration() - 2.0 * (0.5f64 / 7.5).sqrt()).abs() < 1e-9);
//! # Ok::<(), trajkit::Error>(())
//! ```

mod between;
mod blend;
mod constraint;
mod grid;
pub mod jerk;
pub mod jerk_optimal;
mod lp;
pub mod messy;
mod mvc;
pub mod ni;
mod parametrized;
mod paths;
mod rescale;
mod toppra;
mod totg;

pub use blend::{BlendedPath, COLLINEAR_ANGLE, REPEAT_DISTANCE, REVERSAL_ANGLE};
pub use constraint::{
    Constraint, ConstraintRows, CubicPiece, EndEffectorSpeed, InverseDynamics, Jacobian,
    JointAcceleration, JointTorque, JointVelocity, PathPoint,
};
pub use grid::{Gridpoints, AUTO_START, MAX_AUTO_INTERVALS};
pub use mvc::max_velocity_curve;
pub use parametrized::{Parametrized, PhaseProfile};
pub use paths::LinearPath;
pub use rescale::{min_time_scale, LinearLaw, QuinticLaw, Retimed, Scaled, TimeLaw, MAX_DOF};
pub use toppra::{Discretization, Toppra, ToppraOptions, MAX_REFINED_INTERVALS, MAX_REFINE_ROUNDS};
pub use totg::{plan_totg, Totg, TotgOptions};
