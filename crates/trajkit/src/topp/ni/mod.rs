//! Numerical integration in the phase plane (Bobrow's method, TOPP-NI) on any path.
//!
//! The problem is TOPP-RA's ([`Toppra`]: a [`Path`], the same [`Constraint`]s — joint velocity,
//! directional joint acceleration, torque through [`crate::topp::InverseDynamics`], end-effector
//! speed — and boundary path velocities); only the solution method differs. In the phase plane
//! (s, x = ṡ²), every constraint bounds the path acceleration u = s̈ = ½·dx/ds between
//! u_min(s, x) and u_max(s, x), and the *maximum velocity curve* (MVC) x_mvc(s) is the largest
//! x for which that range is not empty (the velocity limit curve and the acceleration limit
//! curve of TOTG together). The time-optimal x(s) follows u_max (forward integration) until it
//! would leave the admissible region, then the curve obtained by integrating u_min *backwards*
//! from the next *switching point* on the MVC, and so on; the end is reached by integrating
//! u_min backwards from the end velocity.
//!
//! trajkit integrates on *knots* (the path's breakpoints plus a subdivision, refined where
//! needed) with u constant between consecutive knots, x linear in s. Each step is solved
//! exactly for its knots, holding the constraints at both ends of the step:
//! 1. **Backward integration** from the end: at each knot the largest x from which a step with
//!    admissible u reaches no higher than the curve at the next knot (an exact two-variable
//!    program, `topp/lp.rs`). Where the MVC is below the integrated curve the result is
//!    the MVC itself: such a knot *starts* a new backward integration — it is a switching point
//!    ([`SwitchKind`]: a discontinuity of the path's curvature, a velocity-limit point, or a
//!    tangent/singular point of the acceleration limit curve). Doing the envelope in one sweep
//!    finds every switching point on the knots without searching; integration never passes a
//!    discontinuity with the wrong side's constraints (knots carry the constraints of both
//!    sides of a breakpoint).
//! 2. **Forward integration** at u_max; where it meets the backward curve inside a step, the
//!    crossing is located exactly (two straight lines in (s, x)) and becomes a knot, so the
//!    switch from acceleration to deceleration happens at the right place, not at a grid
//!    point (only where the backward curve is certified at the step's start, i.e. its LP
//!    reached the next knot's value; below a point of the limit curve the step goes straight
//!    to the backward curve's next knot, admissible because the admissible s̈ at a knot form
//!    an interval). Where the caller knows the constraints do not vary along a step (TOTG's straight
//!    segments of a [`crate::topp::BlendedPath`]), the step is solved in closed form
//!    (accelerate, cruise on the velocity limit, decelerate: the exact trapezoid/triangle).
//! 3. **Event check**: every step is checked at interior points (or, where the path gives one,
//!    by a rigorous analytic bound b on the excess over the chord between knots, as on the arcs
//!    of [`crate::topp::BlendedPath`]: there the knots' limits are tightened by ε ≥ b, so the
//!    profile between knots stays within the true limits; knots at breakpoints are not
//!    tightened and their neighbours take 4b, see [`crate::topp::Totg`]); steps where a
//!    constraint is exceeded by more than 3e-7 relative (bound: 9e-7 beyond the tightening,
//!    or a bound above the cut threshold: 2e-6 of the limits, up to 5e-5 where the bounded
//!    steps are a small share of the duration, see [`crate::topp::Totg`]) are cut (as many parts
//!    as the excess calls for, the excess shrinking with the square of the step) and the
//!    problem integrated again, at most [`crate::topp::MAX_REFINE_ROUNDS`] times and up
//!    to [`crate::topp::MAX_REFINED_INTERVALS`] knots (TOPP-RA's caps and check
//!    points); beyond that the solver returns [`Error::Infeasible`] saying how far the limits
//!    are exceeded: the work is bounded for every input. Steps found clean and unchanged are
//!    not checked again, and knots kept from the previous round keep their evaluated
//!    constraints.
//! 4. **Loss estimate** (where steps are bounded analytically, TOTG's arcs): once the
//!    refinement converges, the problem is integrated again on every third knot of each
//!    stretch between breakpoints (the kept knots' rows as they are, nothing evaluated), and
//!    the duration's loss estimated from the difference (Richardson; the loss is first order
//!    in the spacing) plus the tightening's cost ([`PhaseSolution::loss_estimate`]). Above
//!    0.9·[`LOSS_BUDGET`], the cut threshold is lowered by the first-order model and the steps
//!    above it cut: one more round, estimated again, at most twice; if such a round cannot
//!    finish within the caps, the last converged solution is returned.
//!
//! The result is a [`PhaseProfile`] (x at knots, constant u between), evaluated exactly by
//! [`crate::topp::Retimed`].
//!
//! Path breakpoints where σ″ jumps are handled by evaluating the step that ends there on its
//! own side: [`crate::topp::BlendedPath::eval_left`] for blended paths, `s − 1e-12·(1 + |s|)`
//! for any other path.
//!
//! # Precision contract
//! - At every knot, every constraint holds for the step's u on both sides within 1e-9
//!   relative (the LP tolerance; tightened knots hold the tightened limits); between knots,
//!   at the checked points, within 3e-7 relative, or everywhere within 9e-7 where an analytic
//!   bound is used (the tests check 1e-6 on 1 ms
//!   samples, pointwise and by finite differences).
//! - On steps whose constraints do not vary (TOTG's straight segments) the result is the
//!   closed form, exact up to rounding.
//! - The duration converges to the continuous optimum as the knots are refined; on the same
//!   path it agrees with TOPP-RA within 0.1% (tested both ways).
//! - With an analytic step bound (TOTG), the duration's loss against the converged optimum
//!   is estimated a posteriori and kept within [`LOSS_BUDGET`] where the estimate holds (see
//!   [`crate::topp::Totg`]'s precision contract).
//! - Positive lower bounds on ṡ² from a user constraint are enforced at knots only.
//!
//! # Files
//! `mod.rs`: the public API, the tuning constants and the refinement driver ([`solve_profile`]
//! → `integrate`); `rows.rs`: the constraint rows of every knot and their tightening;
//! `sweep.rs`: one backward and one forward integration; `refine.rs`: the event check, the
//! cut of steps, the cut threshold and the loss estimate.

use super::constraint::{Constraint, ConstraintRows, PathPoint};
use super::lp::{self, BOX};
use super::parametrized::{Parametrized, PhaseProfile};
use super::rescale::Retimed;
use super::toppra::{
    check_path_values, largest_step, CleanSteps, Stage, MAX_REFINED_INTERVALS as MAX_KNOTS,
    MAX_REFINE_ROUNDS as MAX_ROUNDS, REFINE_POINTS as CHECK_POINTS, REFINE_TOL as CHECK_TOL,
};
use super::Toppra;
use crate::error::{Error, Result};
use crate::Path;

mod refine;
mod rows;
mod sweep;

use refine::{check_steps, cut_knots, loss_estimate, tighten_max, Check};
use rows::{Rows, Scratch, View};
use sweep::sweep;

/// Largest rigorous bound on the excess between knots that is accepted without cutting: a
/// bound holds everywhere between the knots, and the knots themselves hold to 1e-9, so the
/// limits hold within 1e-6 relative.
const BOUND_TOL: f64 = 9e-7;

/// Smallest *cut threshold*: a bounded step whose bound is at most the problem's threshold
/// (between this and [`TIGHTEN_CAP`], see [`tighten_max`]) has the limits at its free knots
/// tightened by the bound; a step whose bound exceeds it is cut (into parts whose bound is
/// about half the threshold). The threshold sets the knot spacing on arcs, Δθ ∝ √threshold.
const TIGHTEN_MAX: f64 = 2e-6;

/// Largest cut threshold (see [`tighten_max`]): the tightening it allows costs at most about
/// half of it (2.5e-5) of the time spent on varying steps, and knots next to a junction take
/// four times the bound.
const TIGHTEN_CAP: f64 = 5e-5;

/// The cut threshold per squared ratio (whole duration / time on varying steps), see
/// [`tighten_max`].
const TIGHTEN_SHARE: f64 = 1.6e-7;

/// Tightening above the bound (ε = (1 + margin)·b), so that the next round's step still fits:
/// its u and x differ (the parts of a cut step do not share its u). Doubling costs at most
/// about b/2 more of the time on bounded steps and spares most second refinement rounds.
const TIGHTEN_MARGIN: f64 = 1.0;

/// Budget of the duration's loss (relative to the whole duration, against the converged
/// optimum on the same path) on problems with bounded steps: the a-posteriori estimate
/// ([`PhaseSolution::loss_estimate`]) is compared with 0.9 of it (the estimate's own error)
/// after the refinement converges, and a corrective round follows above that. The tested
/// criterion is 1e-4 against TOPP-RA at 1e5 gridpoints. TOTG's profile holds the limits
/// everywhere, so its duration is never below the optimum T*: against a TOPP-RA duration
/// T* + δ the difference is at most max(loss − δ, −δ). TOPP-RA at 1e5 gridpoints was measured
/// 6.5e-5 above T* (the 7-waypoint bench input) and 0.9e-5 above (trajkit's default path), never
/// below; 7e-5 leaves 3e-5 for a TOPP-RA below T* (it holds the limits at gridpoints only).
/// The default path's loss, 6.0e-5 at the spacing the arcs' share sets, is within it.
pub const LOSS_BUDGET: f64 = 7e-5;

/// Where a corrective round aims, as a share of [`LOSS_BUDGET`]: the new cut threshold comes
/// from the first-order model (loss ∝ √threshold), which the measured losses follow within
/// about 15 % (they fall a little faster than it).
const LOSS_AIM: f64 = 0.8;

/// Corrective rounds (a lower cut threshold when the estimate exceeds the budget) at most.
const MAX_CORRECTIONS: usize = 2;

/// Smallest cut threshold a corrective round sets (knots ∝ 1/√threshold: at most 10× the
/// knots of [`TIGHTEN_MAX`]).
const TIGHTEN_FLOOR: f64 = 2e-8;

/// The loss estimate's coarsening: it integrates again on every `COARSEN`-th knot of each
/// stretch between breakpoints; with a first-order loss, T(mh) − T(h) ≈ (m − 1)·loss. 3 costs
/// about a third of a sweep (measured: +17 % of the solve on the bench inputs; 2: +24 %),
/// the estimate within 5 % of the reference loss on the tested paths (4: within 13 %).
const COARSEN: usize = 3;

/// A converged solution is accepted when its loss estimate is at most this share of
/// [`LOSS_BUDGET`]: the margin for the estimate's own error (within 5 % measured).
const LOSS_ACCEPT: f64 = 0.9;

/// Stand-in for "no finite bound" on x.
const X_BIG: f64 = 1e30;

/// What kind of switching point the optimal curve meets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SwitchKind {
    /// At a path breakpoint where the constraints jump (e.g. a segment/arc junction of a
    /// blended path, where σ″ jumps).
    Discontinuity,
    /// On the velocity limit curve (a bound on ṡ alone, e.g. joint velocity).
    VelocityLimit,
    /// On the acceleration limit curve, where the binding constraint depends on s̈ (a tangent
    /// point of the curve).
    Tangent,
    /// On the acceleration limit curve where the binding constraint does not depend on s̈
    /// (its coefficient of s̈ vanishes: a singular point).
    Singular,
}

/// A point where the optimal curve touches the maximum velocity curve and a backward
/// integration starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwitchingPoint {
    /// Path parameter.
    pub s: f64,
    /// Path velocity ṡ there.
    pub sd: f64,
    /// Kind.
    pub kind: SwitchKind,
}

/// The result of phase-plane integration.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseSolution {
    /// The timing: x at knots (including located crossings), constant u between.
    pub profile: PhaseProfile,
    /// Switching points met by the optimal curve, in path order.
    pub switching_points: Vec<SwitchingPoint>,
    /// Event-check rounds that cut steps.
    pub rounds: usize,
    /// A-posteriori estimate of the duration's loss relative to the converged optimum on the
    /// same path (see [`crate::topp::Totg`]'s precision contract): half the change of the
    /// duration when only every third knot inside the bounded (varying) stretches is kept
    /// (the discretization loss is first order in the knot spacing, so tripling the spacing
    /// adds about twice the loss), plus the tightening's cost. `None` where no step is bounded
    /// analytically (no estimate is made) or the coarse integration fails.
    pub loss_estimate: Option<f64>,
}

/// Solves `problem` by numerical integration (see the module documentation). Its gridpoints
/// are the initial knots.
///
/// ```
/// use trajkit::topp::{ni, LinearPath, Toppra};
/// use trajkit::Limits;
/// let path = LinearPath::new(&[0.0, 1.0], 1)?;
/// let limits = Limits::uniform(1, 1.0, 2.0, f64::INFINITY)?;
/// let sol = ni::solve_profile(&Toppra::with_limits(&path, &limits)?)?;
/// // Triangle (peak ṡ = √(a·D) = 1.41 > v: trapezoid, T = D/v + v/a = 1.5), within the
/// // knots' resolution: NI does not know the constraints are constant along the line.
/// assert!((sol.profile.duration() - 1.5).abs() < 1e-3);
/// # Ok::<(), trajkit::Error>(())
/// ```
pub fn solve_profile<P: Path>(problem: &Toppra<'_, P>) -> Result<PhaseSolution> {
    let o = problem.options_ref();
    let knots = o.gridpoints.points(problem.path())?;
    let path = problem.path();
    let breaks = path.breakpoints();
    let left =
        |s: f64, order: usize, out: &mut [f64]| path.eval(s - 1e-12 * (1.0 + s.abs()), order, out);
    integrate(
        path,
        &left,
        problem.constraints_ref(),
        knots,
        &breaks,
        None,
        (o.start_velocity, o.end_velocity),
    )
}

/// Solves `problem` by numerical integration and returns the timed trajectory.
pub fn solve<P: Path>(problem: Toppra<'_, P>) -> Result<Parametrized<P>> {
    let sol = solve_profile(&problem)?;
    Retimed::new(problem.into_path(), sol.profile)
}

/// A rigorous bound on the relative excess of the constraints inside a step, known from the
/// path's geometry: called with the step's ends `s0`, `s1`, its constant u and the larger x
/// at its ends; returns an upper bound of the relative excess between the knots beyond what
/// holds at the knots (0 where the constraints do not vary along the step), or `∞` when
/// unknown (the step is then checked by sampling). A finite bound must shrink with the square
/// of the step: steps above the tolerance are cut by it without sampling.
pub(crate) type StepBound<'a> = &'a dyn Fn(f64, f64, f64, f64) -> f64;

/// Phase-plane integration on `knots` (strictly increasing, containing every breakpoint of
/// `breaks`). `left` evaluates the path on the side of a breakpoint that ends there.
/// `step_bound` (if any) spares the sampled check of steps it bounds below the tolerance.
/// `velocities` are ṡ at start and end.
///
/// The refinement driver (about 130 lines, kept in one piece on purpose): every round
/// evaluates the rows of new knots, sweeps, checks the steps ([`check_steps`]) and cuts them
/// ([`cut_knots`]); a converged round is accepted or, with an analytic step bound, corrected
/// by the loss estimate. The state that the rounds share (knots, rows and their origin, the
/// tightening, the thresholds, the fallback solution) lives here, where every transition of
/// it can be read in order.
pub(crate) fn integrate<P: Path + ?Sized>(
    path: &P,
    left: &dyn Fn(f64, usize, &mut [f64]),
    cons: &[Box<dyn Constraint + '_>],
    mut knots: Vec<f64>,
    breaks: &[f64],
    step_bound: Option<StepBound<'_>>,
    velocities: (f64, f64),
) -> Result<PhaseSolution> {
    check_velocities(velocities)?;
    let mut sc = Scratch::new(path.dim());
    let mut rows = Rows::default();
    // The previous knots' rows, and per knot where it was in the previous knots
    // (`NEW_KNOT` for a new one): kept knots reuse their rows.
    let mut old_rows = Rows::default();
    let mut origin: Vec<usize> = Vec::new();
    let mut clean = CleanSteps::default();
    // Per knot: the relative tightening of its constraints (0 at the ends and at breakpoints,
    // so closed-form steps and junction switching points keep the exact limits), and whether
    // the rows of the current knots are evaluated.
    let mut eps = vec![0.0; knots.len()];
    let mut evaluated = false;
    // Per knot step: its constraints do not vary along it (closed-form step).
    let mut constant: Vec<bool> = Vec::new();
    let mut round = 0;
    // The largest tightening of a bounded step (set from the first sweep, lowered by a
    // corrective round).
    let mut tmax = TIGHTEN_MAX;
    // During a corrective round's event check: bounded steps above it are cut even when
    // their knots' tightening covers them.
    let mut cut_above = f64::INFINITY;
    let mut corrections = 0;
    // The last converged solution, returned if the rounds after a correction fail.
    let mut fallback: Option<PhaseSolution> = None;
    loop {
        if !evaluated {
            std::mem::swap(&mut rows, &mut old_rows);
            let old = (!origin.is_empty()).then_some((&old_rows, &origin[..]));
            if let Err(e) = rows.evaluate(path, left, cons, &knots, breaks, old, &mut sc) {
                return fallback.ok_or(e);
            }
            evaluated = true;
            constant.clear();
            match step_bound {
                Some(b) => {
                    constant.extend(knots.windows(2).map(|k| b(k[0], k[1], 1.0, 1.0) == 0.0))
                }
                None => constant.resize(knots.len() - 1, false),
            }
        }
        rows.tighten(&eps);
        let all = View::all(&rows);
        let sweep = match sweep(
            path, cons, &knots, breaks, all, &constant, velocities, &mut sc,
        ) {
            Ok(sw) => sw,
            Err(e) => return fallback.ok_or(e),
        };
        if round == 0 && step_bound.is_some() {
            tmax = tighten_max(&sweep, &constant);
        }
        let n = knots.len() - 1;
        // Event check between knots; repeated (same sweep) after a loss estimate above the
        // budget, with the lowered threshold.
        let mut check: Check = loop {
            let check = check_steps(
                path,
                cons,
                &sweep,
                &knots,
                breaks,
                &eps,
                step_bound,
                (tmax, cut_above),
                &mut clean,
                &mut sc,
            );
            if check.worst.0 > 0.0 || check.forced {
                break check;
            }
            let profile = match profile_of(&sweep.s, &sweep.x) {
                Ok(p) => p,
                Err(e) => return fallback.ok_or(e),
            };
            let mut sol = PhaseSolution {
                profile,
                switching_points: sweep.switching.clone(),
                rounds: round,
                loss_estimate: None,
            };
            if step_bound.is_none() {
                return Ok(sol);
            }
            sol.loss_estimate = loss_estimate(
                path, cons, &knots, breaks, &constant, &rows, &sweep, velocities, &mut sc,
            );
            match sol.loss_estimate {
                Some(l)
                    if l > LOSS_ACCEPT * LOSS_BUDGET
                        && corrections < MAX_CORRECTIONS
                        && round < MAX_ROUNDS =>
                {
                    // First order: the loss scales with the spacing, i.e. with √threshold.
                    corrections += 1;
                    tmax = (tmax * (LOSS_AIM * LOSS_BUDGET / l).powi(2)).max(TIGHTEN_FLOOR);
                    cut_above = tmax;
                    fallback = Some(sol);
                }
                _ => return Ok(sol),
            }
        };
        cut_above = f64::INFINITY;
        let total: usize = check.parts.iter().sum();
        if round == MAX_ROUNDS || total > MAX_KNOTS {
            if let Some(sol) = fallback {
                return Ok(sol);
            }
            return Err(Error::Infeasible(format!(
                "phase-plane integration: a constraint is still exceeded by {:.3e} (relative) near s = {} after {round} refinement rounds and {} knots",
                check.worst.0, check.worst.1, knots.len()
            )));
        }
        if total > n {
            (knots, eps) = cut_knots(&knots, breaks, &mut check, total, &mut origin);
            evaluated = false;
        } else {
            eps = check.next_eps;
        }
        round += 1;
    }
}

/// Checks the boundary path velocities: finite and ≥ 0.
fn check_velocities(velocities: (f64, f64)) -> Result<()> {
    for (name, v) in [
        ("start path velocity", velocities.0),
        ("end path velocity", velocities.1),
    ] {
        if !(v >= 0.0 && v.is_finite()) {
            return Err(Error::InvalidValue {
                field: name.into(),
                value: v,
                reason: "is not a finite number >= 0",
            });
        }
    }
    Ok(())
}

fn profile_of(s: &[f64], x: &[f64]) -> Result<PhaseProfile> {
    let sd: Vec<f64> = x.iter().map(|v| v.max(0.0).sqrt()).collect();
    PhaseProfile::new(s, &sd)
}
