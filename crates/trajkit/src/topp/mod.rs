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
//!
//! # Implementation notes
//!
//! `topp/` mirrors the algorithm. `constraint.rs` turns each constraint at a path point into
//! half-planes `α·s̈ + β·ṡ² ≤ γ` and bounds on ṡ² (joint velocity, directional acceleration,
//! torque through a user `InverseDynamics`, end-effector speed through a user `Jacobian`).
//! `grid.rs` chooses gridpoints (always with the path's breakpoints; the default `Auto` grades
//! the grid, refining where the duration is sensitive until its error estimate is within 1e-4;
//! `toppra/auto.rs` runs the rounds); `lp.rs` is an exact
//! two-variable Seidel LP; `toppra.rs` runs the backward (controllable sets) and forward passes,
//! returning a `PhaseProfile` (`parametrized.rs`); its `stage.rs` reads a stage's half-planes
//! straight from the gridpoint rows and takes the greedy forward step (shared with `ni/`), its
//! `explain.rs` names the constraints in an infeasibility error. `between.rs` (with the path's Taylor data
//! per interval in `between/pieces.rs`) makes the limits hold between gridpoints: on paths that are polynomials of degree ≤ 5 between breakpoints
//! (`Path::piecewise_degree`) each stage gets the interior Bernstein coefficients of joint
//! velocity and acceleration along its interval as extra rows (`Constraint::hold_on_cubic`), so
//! one solve holds them everywhere; an exact check (`Constraint::excess_on_cubic`, closed-form
//! extrema) covers breakpoints and collocation, a failing interval gets rows at its worst point
//! and is re-solved incrementally (backward pass until the controllable sets settle, forward
//! pass until x meets the old one); other paths and constraints are sampled and their
//! intervals cut. `rescale.rs` composes any `Path` with any `TimeLaw` (`Retimed`: TOPP-RA's
//! output is `Retimed<P, Profile>`, exact, never refitted) and scales time (`Scaled`,
//! `min_time_scale`). `jerk.rs` bounds jerk: moving-average filter of the law, then the smallest
//! exact time scaling. `jerk_optimal/` is the jerk-limited time-optimal planner (third-order
//! reachability): `discretize.rs` (rows in (x_i, u_i, v_i) at gridpoints and cuts, conservative
//! tangent of J/√x), `polygon.rs` (convex controllable sets), `solve.rs` (backward projection by
//! lazy Fourier–Motzkin, greedy forward pass), `certify.rs` (exact extrema between gridpoints),
//! `problem.rs` (rounds of re-linearization and cuts), `mesh.rs` (grid even in raw TOPP-RA time,
//! ends refined), `law.rs` (closed-form s(t), a `TimeLaw`). `messy.rs` takes raw waypoints
//! (dedup, range check, stops at reversals, a range-safe spline per piece via `BoundedSpline`, a
//! `Sequence` of pieces; `piece_paths` / `time_pieces` split path construction from timing);
//! `paths.rs` is the polyline path. `mvc.rs` evaluates the maximum velocity curve of a problem at
//! given points (the point's rows with s̈ eliminated exactly, Fourier–Motzkin), for phase-plane
//! pictures. `blend.rs` is TOTG's path
//! (segments + circular blends within a max deviation, C¹, junctions as breakpoints,
//! `eval_left` for the side that ends at a junction). `ni.rs` is phase-plane numerical
//! integration for any path and any constraints: backward envelope (one exact LP per knot on the
//! shared `Stage`) whose knots on the limit curve are the switching points, forward integration
//! at the largest step (`largest_step`, shared with TOPP-RA's forward pass) with crossings
//! located exactly, closed-form steps where the constraints are constant, event checks between
//! knots with bounded refinement; output is the same `PhaseProfile`. Bounded steps (TOTG's arcs) are
//! cut where their excess bound exceeds the problem's cut threshold τ (`tighten_max`: from the
//! first sweep's share of time on varying steps), else their knots are tightened by twice the
//! bound; refinement rounds reuse the rows of kept knots. After convergence `loss_estimate`
//! integrates again on every third knot (rows read through `View`, no copy) and returns
//! (T(3h) − T(h))/2 plus the tightening's cost; above 0.9·`LOSS_BUDGET` (7e-5) τ is lowered by
//! (0.8·budget/estimate)² and the problem integrated again (at most two corrections, the last
//! converged solution as fallback). `totg.rs` = `BlendedPath` +
//! joint velocity/acceleration constraints + `ni` with TOTG's knots; arc knots hold limits
//! tightened by the analytic bound of the excess between knots (initial arc step 0.04 rad); `plan_totg` splits waypoints at stops into a `Sequence`. Flow: waypoints → messy (dedup,
//! stops) → `Path` + `Limits` → constraints → `Toppra` | `ni` | (blend → totg) → `PhaseProfile` →
//! `Retimed` → jerk → `Trajectory`. The solver's hot loop evaluates σ′ and σ″ together
//! (`Path::eval_derivatives`) and scans each stage's rows in place (`HalfPlanes::first_violated`).

mod between;
mod blend;
mod constraint;
mod grid;
pub mod jerk;
pub mod jerk_local;
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
