//! Jerk-limited time-optimal path parameterization: third-order reachability in the path
//! domain.
//!
//! Given a path σ(s) (C², e.g. a cubic spline; σ‴ may jump at its breakpoints) and joint
//! limits on velocity, acceleration and jerk (plus optionally any second-order
//! [`Constraint`], e.g. [`crate::topp::JointTorque`]), [`JerkOptimal`] finds a rest-to-rest
//! timing s(t) that is as fast as the limits allow, and returns ξ(t) = σ(s(t)).
//!
//! # Method
//! TOPP-RA generalised by one order. The state at gridpoint i is (x_i, u_i) = (ṡ², s̈); on a
//! middle interval s̈ is linear in a reference time θ (not in s) with slope v_i, the control:
//! u = u_i + v_i·φ(δ), x = x_i + 2u_i·δ + 2v_i·ψ(δ), where θ′ = dθ/ds interpolates 1/√x̄ of a
//! reference solution x̄ ([`shape`]). Then v_i is the path jerk in time, nearly constant over
//! the interval, so a jerk ramp is not lost at the slow end of an interval (the first-order
//! loss of s̈ linear in s). Joint j moves with q̇ = σ′ṡ, q̈ = σ″x + σ′u,
//! q⃛ = ṡ(σ‴x + 3σ″u + σ′v·θ′).
//! - **Rows** ([`discretize`]): velocity and every second-order constraint are linear in
//!   (x, u) at any point of an interval, hence linear in (x_i, u_i, v_i); they are enforced at
//!   both ends and the midpoint of every interval. The jerk limit
//!   |σ‴x + 3σ″u + σ′v·θ′| ≤ J/√x is non-convex only through J/√x, which is convex: it is
//!   replaced by its tangent at x̄, which lies below it, so the rows are conservative.
//! - **Rest** ([`law`]): u linear in s from (0, 0) never leaves s = 0, so the first interval
//!   starts with constant path jerk in time, s = jt³/6, which puts gridpoint 1 on the ray
//!   x = 1.5Δ₀u; the last interval mirrors it.
//! - **Backward pass** ([`solve`]): controllable sets K_i ⊂ (x, u) are convex polygons, the
//!   projection over v of the stage rows and K_{i+1}; **forward pass**: from the largest u₁
//!   on the start ray, the largest v at every stage (it maximises x_{i+1} and u_{i+1}).
//! - **Rounds** ([`problem`]): the first reference x̄ is the raw TOPP-RA velocity (no jerk
//!   limit, on a grid of at least 400 steps and 8 per path segment) capped by the largest
//!   rest ramps;
//!   then x̄ ← the last solution, until the duration settles (at most 16 rounds on the first
//!   grid, 8 on the next). Each round certifies every interval ([`certify`]): a small excess
//!   between check points scales that limit's rows on that interval, a larger one adds the
//!   worst point as a cut (rows enforced there).
//! - **Grid** ([`mesh`]): even in the time of the reference (raw TOPP-RA, then the previous
//!   grid's solution), with the path's breakpoints and geometric refinement at both ends; it
//!   starts at 100 + 4 per path segment steps and doubles until the estimated distance to the
//!   converged duration ([`JerkReport::error_estimate`], a third of the last change: the
//!   error is of second order in the step) is at most [`JerkOptions::tolerance`], or 65536
//!   steps. If the passes break down on a finer grid, the last grid's result is kept; on the
//!   first grid, a finer one is tried.
//!
//! # Precision contract
//! - Joint velocity, acceleration and jerk hold **along the continuous trajectory**, to
//!   1e-9 relative (rounding), on paths that are cubic polynomials between breakpoints (every
//!   cubic spline, linear paths): on every middle interval their extrema are bounded
//!   (Bernstein form) and, where the bound is inconclusive, computed exactly (polynomial
//!   roots) after the last solve; the rest intervals meet them by construction (each term
//!   bounded by its largest value on the interval). On other paths the intervals are checked
//!   at the gridpoints, the cuts and `certify::SAMPLES` interior points each.
//!   [`JerkReport::worst_excess`] is the largest relative excess found, and
//!   [`JerkReport::sampled_intervals`] counts intervals checked by sampling only.
//! - Other constraints (torque, user rows) hold at gridpoints, midpoints, cuts and
//!   `certify::EXTRA_SAMPLES` points per interval, to 1e-9 relative; between those, the
//!   excess is that of a smooth function between samples (second order in the sample spacing).
//! - If the certification still finds an excess after the last round, the trajectory is
//!   slowed down uniformly by the smallest factor that removes it (velocity scales by 1/k,
//!   acceleration 1/k², jerk 1/k³); [`JerkReport::time_scale`] says by how much (1 when not;
//!   measured: up to 1.5e-5 on straight lines and the standard problem, 7e-4 on a seeded
//!   100-waypoint path).
//! - The duration is within about [`JerkOptions::tolerance`] (relative) of the method's
//!   converged duration when the grid cap allows it ([`JerkReport::error_estimate`] says how
//!   far it is estimated to be). The time law is evaluated exactly ([`law`]).
//!
//! # Known limitations
//! Seconds per solve on the 7-waypoint standard problem (not milliseconds): the grid needed
//! for a 1e-4 tolerance has thousands to tens of thousands of points; certification often
//! ends with a small uniform slow-down instead of settling.
//!
//! ```
//! use trajkit::topp::jerk_optimal::{JerkOptimal, JerkOptions};
//! use trajkit::topp::LinearPath;
//! use trajkit::{Limits, Trajectory};
//!
//! // A straight line of one joint: the 1-D jerk-limited problem, optimum 1.7 s
//! // (1 rad, v = 1, a = 2, j = 10: 0.2 s jerk ramps, 0.3 s at a = 2, 0.5 s cruise).
//! // Today's filter (`topp::jerk`) takes 1.9 s.
//! let limits = Limits::uniform(1, 1.0, 2.0, 10.0)?;
//! let path = LinearPath::new(&[0.0, 1.0], 1)?;
//! let options = JerkOptions { steps: Some(200), ..JerkOptions::default() };
//! let traj = JerkOptimal::new(path, &limits)?.options(options).solve()?;
//! assert!(traj.duration() > 1.7 && traj.duration() < 1.76);
//! // What the planner did: grid size, rounds, certification (worst excess found between
//! // gridpoints, and the uniform slow-down applied if it was above 1e-7).
//! let report = traj.law().report();
//! assert!(report.gridpoints > 200 && report.time_scale >= 1.0);
//! # Ok::<(), trajkit::Error>(())
//! ```

pub mod certify;
pub mod discretize;
pub mod law;
pub mod mesh;
pub mod polygon;
pub mod problem;
pub mod shape;
pub mod solve;

pub use law::JerkProfile;

use crate::error::{Error, Result};
use crate::topp::constraint::{
    Constraint, ConstraintRows, JointAcceleration, JointTorque, JointVelocity, PathPoint,
};
use crate::topp::messy::{Sequence, TorqueModel};
use crate::topp::rescale::Retimed;
use crate::topp::{Gridpoints, PhaseProfile as Profile, Toppra, ToppraOptions as Options};
use crate::{Limits, Order, Path};
use certify::JointRange;

/// Settings of [`JerkOptimal`]. `JerkOptions::default()`: tolerance 1e-4, grid chosen by it.
#[derive(Debug, Clone, PartialEq)]
pub struct JerkOptions {
    /// Relative duration tolerance: the grid is refined until doubling it changes the duration
    /// by at most this (0 < tolerance ≤ 0.1).
    pub tolerance: f64,
    /// A fixed number of time steps for the grid instead of choosing it from the tolerance.
    pub steps: Option<usize>,
}

impl Default for JerkOptions {
    fn default() -> Self {
        JerkOptions {
            tolerance: 1e-4,
            steps: None,
        }
    }
}

/// What the planner did: grid, rounds, certification.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct JerkReport {
    /// Gridpoints of the final grid.
    pub gridpoints: usize,
    /// Time steps the final grid was built from.
    pub steps: usize,
    /// Rounds (backward + forward pass + certification) on the final grid.
    pub rounds: usize,
    /// Rounds over all grids tried.
    pub total_rounds: usize,
    /// Points inside intervals where one joint's rows were added after a failed
    /// certification.
    pub cuts: usize,
    /// Limits of one joint on one interval scaled down (by a relative amount of second order
    /// in the step) because the certification found them exceeded between check points.
    pub tightened: usize,
    /// The largest relative excess of any limit found by the final certification (≤ 1e-9 when
    /// certified; negative when every limit has room).
    pub worst_excess: f64,
    /// Intervals certified by sampling (the path is not a cubic there).
    pub sampled_intervals: usize,
    /// Uniform slow-down applied after certification (1 when none was needed).
    pub time_scale: f64,
    /// Duration of the raw TOPP-RA timing on the same constraints without jerk limits (a lower
    /// bound of the jerk-limited optimum, up to its discretization).
    pub raw_duration: f64,
    /// Relative duration change at the last grid refinement (∞ when only one grid was solved).
    pub grid_change: f64,
    /// Estimated relative distance of the duration above the converged value of the method
    /// (the discretization error is of second order in the step: a third of `grid_change`).
    pub error_estimate: f64,
}

/// A path timed by the jerk-limited planner.
pub type JerkTimed<P> = Retimed<P, JerkProfile>;

/// A jerk-limited time-optimal path parameterization problem (see the module documentation).
pub struct JerkOptimal<'c, P: Path> {
    path: P,
    limits: Limits,
    /// Joint velocity, joint acceleration, then the extra constraints.
    cons: Vec<Box<dyn Constraint + 'c>>,
    options: JerkOptions,
}

/// Lends a boxed constraint to a TOPP-RA problem.
struct ByRef<'a, 'c>(&'a (dyn Constraint + 'c));

impl Constraint for ByRef<'_, '_> {
    fn name(&self) -> String {
        self.0.name()
    }
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn write(&self, p: &PathPoint<'_>, out: &mut ConstraintRows) {
        self.0.write(p, out)
    }
    fn uses_position(&self) -> bool {
        self.0.uses_position()
    }
    fn diagnose(&self, p: &PathPoint<'_>) -> Option<String> {
        self.0.diagnose(p)
    }
}

impl<'c, P: Path> JerkOptimal<'c, P> {
    /// A problem on `path` with the velocity, acceleration and jerk limits of `limits`. At
    /// least one joint needs a finite jerk limit (otherwise use [`Toppra`]).
    pub fn new(path: P, limits: &Limits) -> Result<Self> {
        limits.expect_dof(path.dim(), "the path")?;
        if limits.joints().iter().all(|j| j.jerk.is_infinite()) {
            return Err(Error::InvalidValue {
                field: "jerk limits".into(),
                value: f64::INFINITY,
                reason: "are absent on every joint: nothing to bound (use TOPP-RA)",
            });
        }
        Ok(JerkOptimal {
            path,
            limits: limits.clone(),
            cons: vec![
                Box::new(JointVelocity::from_limits(limits)),
                Box::new(JointAcceleration::from_limits(limits)),
            ],
            options: JerkOptions::default(),
        })
    }

    /// Adds a second-order constraint (its joint count must equal the path's dimension).
    pub fn constraint(mut self, c: impl Constraint + 'c) -> Result<Self> {
        if c.dof() != self.path.dim() {
            return Err(Error::DimensionMismatch {
                what: format!("{} joint count", c.name()),
                expected: self.path.dim(),
                found: c.dof(),
            });
        }
        self.cons.push(Box::new(c));
        Ok(self)
    }

    /// Replaces the options.
    pub fn options(mut self, options: JerkOptions) -> Self {
        self.options = options;
        self
    }

    /// The path.
    pub fn path(&self) -> &P {
        &self.path
    }

    /// Solves and returns the trajectory ξ(t) = σ(s(t)).
    pub fn solve(self) -> Result<JerkTimed<P>> {
        let profile = self.solve_profile()?;
        Retimed::new(self.path, profile)
    }

    /// The raw TOPP-RA timing (velocity, acceleration and extra constraints, no jerk limit).
    fn raw_profile(&self, steps: usize) -> Result<Profile> {
        let mut t = Toppra::new(&self.path);
        for c in &self.cons {
            t = t.constraint(ByRef(&**c))?;
        }
        t.options(Options {
            gridpoints: Gridpoints::Uniform(steps),
            refine: false,
            ..Options::default()
        })
        .solve_profile()
    }

    /// Solves and returns the timing law only.
    pub fn solve_profile(&self) -> Result<JerkProfile> {
        let tol = self.options.tolerance;
        self.check_options()?;
        let breaks = self.path.breakpoints();
        let segments = breaks.len().saturating_sub(1).max(1);
        let raw = self.raw_profile(RAW_STEPS.max(RAW_PER_SEGMENT * segments))?;
        let ranges = self.joint_ranges();
        let jerk: Vec<f64> = ranges.iter().map(|r| r.j).collect();
        let umax = raw
            .accelerations()
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let ubox = 10.0 * umax + 1e-9;
        let (a, b) = self.path.interval();
        let rest_curve = (
            RestCurve::new(&self.path, a, &jerk),
            RestCurve::new(&self.path, b, &jerk),
        );
        let extra = &self.cons[2..];
        let mut steps = self
            .options
            .steps
            .unwrap_or(INITIAL_STEPS + INITIAL_PER_SEGMENT * segments);
        let (mut ref_s, mut ref_t) = (raw.gridpoints().to_vec(), raw.times().to_vec());
        let mut previous: Option<JerkProfile> = None;
        let mut total_rounds = 0;
        loop {
            let grid = mesh::time_grid(&ref_s, &ref_t, &breaks, steps, END_LEVELS);
            let (reference, xbox) = grid_seed(&grid, previous.as_ref(), &raw, &rest_curve, (a, b));
            let mut prob =
                problem::Problem::new(&self.path, extra, &ranges, &grid, reference, &xbox, ubox)?;
            let max_rounds = if previous.is_some() { 8 } else { 16 };
            let solved = match prob.solve(SETTLE * tol, max_rounds) {
                Ok(solved) => solved,
                Err(e) => {
                    // The passes broke down on this grid: keep the last grid's certified
                    // result, or try a finer grid when there is none yet.
                    if let Some(p) = previous {
                        return Ok(p);
                    }
                    if self.options.steps.is_none() && 2 * steps <= MAX_AUTO_STEPS {
                        steps *= 2;
                        continue;
                    }
                    return Err(e);
                }
            };
            total_rounds += solved.rounds;
            let round = RoundInfo {
                gridpoints: grid.s.len(),
                steps,
                total_rounds,
                raw_duration: raw.duration(),
            };
            let profile = finish_round(solved, previous.as_ref(), round);
            let estimate = profile.report.error_estimate;
            let done =
                self.options.steps.is_some() || estimate <= tol || 2 * steps > MAX_AUTO_STEPS;
            if done {
                return Ok(profile);
            }
            ref_s = profile.gridpoints().to_vec();
            ref_t = profile.times().to_vec();
            previous = Some(profile);
            steps *= 2;
        }
    }

    /// Checks the duration tolerance and the fixed grid steps of the options.
    fn check_options(&self) -> Result<()> {
        let tol = self.options.tolerance;
        if !(tol > 0.0 && tol <= 0.1) {
            return Err(Error::InvalidValue {
                field: "jerk planner duration tolerance".into(),
                value: tol,
                reason: "is not in (0, 0.1]",
            });
        }
        if let Some(st) = self.options.steps {
            if !(3..=MAX_STEPS).contains(&st) {
                return Err(Error::InvalidValue {
                    field: "jerk planner grid steps".into(),
                    value: st as f64,
                    reason: "is not in 3..=1048576",
                });
            }
        }
        Ok(())
    }

    /// The velocity and acceleration ranges and the symmetric jerk limit of each joint.
    fn joint_ranges(&self) -> Vec<JointRange> {
        self.limits
            .joints()
            .iter()
            .map(|j| JointRange {
                v: j.range(Order::Velocity),
                a: j.range(Order::Acceleration),
                j: j.symmetric_limit(Order::Jerk),
            })
            .collect()
    }
}

/// The first x̄ of a grid's problem and the box on x at its gridpoints: x̄ follows the last
/// (coarser) grid's result when there is one, else the raw TOPP-RA timing capped by the rest
/// curves at the ends `(a, b)`; the box is twice the raw x.
fn grid_seed(
    grid: &mesh::Grid,
    previous: Option<&JerkProfile>,
    raw: &Profile,
    rest_curve: &(RestCurve, RestCurve),
    (a, b): (f64, f64),
) -> (problem::Reference, Vec<f64>) {
    let nn = grid.s.len() - 1;
    let mids: Vec<f64> = (0..nn).map(|i| 0.5 * (grid.s[i] + grid.s[i + 1])).collect();
    let guess = |s: f64| match previous {
        Some(p) => p.x_at(s),
        None => raw_x(raw, s)
            .min(rest_curve.0.x(s - a))
            .min(rest_curve.1.x(b - s)),
    };
    let reference = problem::Reference {
        grid: grid.s.iter().map(|&s| guess(s)).collect(),
        mid: mids.iter().map(|&s| guess(s)).collect(),
    };
    let xbox: Vec<f64> = grid
        .s
        .iter()
        .map(|&s| 2.0 * raw_x(raw, s) + 1e-300)
        .collect();
    (reference, xbox)
}

/// What the report of one grid's round records besides the solve itself.
struct RoundInfo {
    gridpoints: usize,
    steps: usize,
    total_rounds: usize,
    raw_duration: f64,
}

/// The profile of one grid's solve, slowed down uniformly by its certified excess, with its
/// report; the grid change and error estimate compare it with `previous` (the coarser grid).
fn finish_round(
    solved: problem::Solved,
    previous: Option<&JerkProfile>,
    round: RoundInfo,
) -> JerkProfile {
    let mut profile = solved.profile;
    let scale = time_scale_for(solved.worst);
    profile.set_scale(scale);
    let t_new = profile.duration();
    let change = previous.map_or(f64::INFINITY, |p| (p.duration() - t_new).abs() / t_new);
    // Second order in the step: the finer result is off by about a third of the change.
    let estimate = change / 3.0;
    profile.report = JerkReport {
        gridpoints: round.gridpoints,
        steps: round.steps,
        rounds: solved.rounds,
        total_rounds: round.total_rounds,
        cuts: solved.cuts,
        tightened: solved.tightened,
        worst_excess: solved.worst,
        sampled_intervals: solved.sampled_intervals,
        time_scale: scale,
        raw_duration: round.raw_duration,
        grid_change: change,
        error_estimate: estimate,
    };
    profile
}

/// TOPP-RA intervals of the raw timing that seeds the planner (at least, and per path
/// segment).
const RAW_STEPS: usize = 400;
const RAW_PER_SEGMENT: usize = 8;
/// Time steps of the first grid: a base and per path segment.
const INITIAL_STEPS: usize = 100;
const INITIAL_PER_SEGMENT: usize = 4;
/// Largest number of time steps.
const MAX_STEPS: usize = 1 << 20;
/// Largest number of time steps the automatic grid doubles to.
const MAX_AUTO_STEPS: usize = 1 << 16;
/// Halvings of the first and last intervals.
const END_LEVELS: usize = 8;
/// Rounds on one grid stop when the duration changes by less than this fraction of the
/// tolerance.
const SETTLE: f64 = 0.1;

/// x = ṡ² when the path starts (or ends) with the largest constant path jerk its jerk limits
/// allow at that end (σ′ only): s = jt³/6 gives x = (j/2)^{2/3}·(6d)^{4/3}/… — an upper
/// estimate of the jerk-limited velocity near the ends, where the raw TOPP-RA velocity is far
/// too high to linearize the jerk rows at.
struct RestCurve {
    coef: f64,
}

impl RestCurve {
    fn new<P: Path>(path: &P, s: f64, jerk: &[f64]) -> Self {
        let mut d1 = vec![0.0; path.dim()];
        path.eval(s, 1, &mut d1);
        let j = d1
            .iter()
            .zip(jerk)
            .filter(|(d, _)| **d != 0.0)
            .map(|(d, jl)| jl / d.abs())
            .fold(f64::INFINITY, f64::min);
        // s = jτ³/6, ṡ = jτ²/2 ⇒ x = (j/2)²·(6d/j)^{4/3} = 9^{2/3}/4^{…}: computed directly.
        let coef = if j.is_finite() {
            0.25 * j * j * (6.0 / j).powf(4.0 / 3.0)
        } else {
            f64::INFINITY
        };
        RestCurve { coef }
    }

    fn x(&self, d: f64) -> f64 {
        self.coef * d.max(0.0).powf(4.0 / 3.0)
    }
}

/// x = ṡ² of a TOPP-RA profile at s (linear in s on each of its intervals).
fn raw_x(p: &Profile, s: f64) -> f64 {
    let g = p.gridpoints();
    let i = crate::traj::find_piece(g, s);
    let sd = p.velocities()[i];
    (sd * sd + 2.0 * p.accelerations()[i] * (s - g[i])).max(0.0)
}

/// The uniform slow-down that removes a relative excess `worst` of velocity, acceleration or
/// jerk (the strongest need: velocity, k = 1 + e), 1 when certified.
fn time_scale_for(worst: f64) -> f64 {
    if worst <= problem::CERT_TOL {
        1.0
    } else {
        (1.0 + worst) * (1.0 + 1e-12)
    }
}

/// The jerk-limited planner on each rest-to-rest piece of a sequence (e.g. the paths of
/// [`crate::topp::messy::plan_waypoints`]'s pieces), with the torque limits of `limits` for
/// `torque` when given.
pub fn plan_sequence<P: Path>(
    paths: Vec<P>,
    limits: &Limits,
    torque: Option<&TorqueModel>,
    options: &JerkOptions,
) -> Result<Sequence<JerkTimed<P>>> {
    let mut pieces = Vec::with_capacity(paths.len());
    for (k, path) in paths.into_iter().enumerate() {
        let mut prob = JerkOptimal::new(path, limits)?.options(options.clone());
        if let Some(model) = torque {
            prob = prob.constraint(JointTorque::from_limits(model.clone(), limits)?)?;
        }
        let traj = prob.solve().map_err(|e| match e {
            Error::Infeasible(m) => Error::Infeasible(format!("path piece {}: {m}", k + 1)),
            e => e,
        })?;
        pieces.push(traj);
    }
    Sequence::new(pieces)
}

impl JerkProfile {
    /// What the planner did to get this profile.
    pub fn report(&self) -> &JerkReport {
        &self.report
    }
}
