//! Time-optimal path parameterization (TOPP-RA, TOTG, numerical integration) and time rescaling.
//!
//! Keep a path's geometry σ(s), choose its timing s(t) so that every instant respects the
//! robot's limits, as fast as possible. The pieces mirror the algorithm:
//! - [`constraint`]: constraints in the general form a(s)·s̈ + b(s)·ṡ² + c(s) ∈ {F v ≤ g} plus
//!   bounds on ṡ² (joint velocity, joint acceleration, torque through user inverse dynamics,
//!   end-effector speed through a user Jacobian);
//! - [`lp`]: the exact two-variable linear program solved at every stage;
//! - [`grid`]: gridpoints (automatic from a duration tolerance, uniform, chord tolerance,
//!   given), always including path breakpoints;
//! - [`toppra`]: the backward (controllable sets) and forward (greedy) passes; its private
//!   `between` module holds the limits between gridpoints (Bernstein rows and exact checks on
//!   piecewise-cubic paths, sampled checks elsewhere);
//! - [`parametrized`]: the solved [`PhaseProfile`] and the exact output trajectory;
//! - [`rescale`]: any path composed with any timing law, uniform time scaling;
//! - [`paths`]: piecewise-linear paths;
//! - [`blend`]: TOTG's path, straight segments joined by circular blends;
//! - [`ni`]: numerical integration in the phase plane (Bobrow / TOPP-NI) on any path, with the
//!   same constraints;
//! - [`totg`]: time-optimal trajectory generation (Kunz & Stilman) on a blended path;
//! - [`messy`]: planner output as it comes: duplicates, reversals, rest-to-rest pieces;
//! - [`mvc`]: the maximum velocity curve of a problem (the phase-plane limit above a profile).
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
pub mod blend;
pub mod constraint;
pub mod grid;
pub mod jerk;
pub mod jerk_optimal;
pub mod lp;
pub mod messy;
pub mod mvc;
pub mod ni;
pub mod parametrized;
pub mod paths;
pub mod rescale;
pub mod toppra;
pub mod totg;

pub use blend::BlendedPath;
pub use constraint::{
    Constraint, ConstraintRows, CubicPiece, EndEffectorSpeed, InverseDynamics, Jacobian,
    JointAcceleration, JointTorque, JointVelocity, PathPoint,
};
pub use grid::Gridpoints;
pub use parametrized::{Parametrized, PhaseProfile};
pub use paths::LinearPath;
pub use rescale::{min_time_scale, LinearLaw, QuinticLaw, Retimed, Scaled, TimeLaw};
pub use toppra::{Discretization, Toppra, ToppraOptions};
pub use totg::{plan_totg, Totg, TotgOptions};
