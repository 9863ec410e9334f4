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

/// Evaluates the path at a breakpoint on the side of the piece that ends there.
type SideEval<'a> = &'a dyn Fn(f64, usize, &mut [f64]);

/// Constraint rows of both sides of every knot, with the tightening applied.
#[derive(Default)]
struct Rows {
    rows: Vec<[f64; 3]>,
    /// The untightened γ of every row.
    gamma: Vec<f64>,
    /// Per knot: [start, end) of the right-side rows, then of the left-side rows.
    range: Vec<[usize; 4]>,
    /// Per knot: x bounds, right then left side (`xhi` tightened, `xhi0` not).
    xlo: Vec<[f64; 2]>,
    xhi: Vec<[f64; 2]>,
    xhi0: Vec<[f64; 2]>,
    /// Per knot: the tightening applied to its rows.
    applied: Vec<f64>,
}

/// Marks a knot that is not in the previous round's knots.
const NEW_KNOT: usize = usize::MAX;

struct Scratch {
    q: Vec<f64>,
    dq: Vec<f64>,
    ddq: Vec<f64>,
    cr: ConstraintRows,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Scratch {
            q: vec![0.0; n],
            dq: vec![0.0; n],
            ddq: vec![0.0; n],
            cr: ConstraintRows::new(),
        }
    }

    /// Evaluates the path (`left` side or not) at `s` and appends all constraint rows to
    /// `rows`; returns the x bounds.
    fn write<P: Path + ?Sized>(
        &mut self,
        path: &P,
        left: Option<SideEval<'_>>,
        cons: &[Box<dyn Constraint + '_>],
        s: f64,
        rows: &mut Vec<[f64; 3]>,
    ) -> Result<(f64, f64)> {
        let need_q = cons.iter().any(|c| c.uses_position());
        match left {
            Some(f) => {
                if need_q {
                    f(s, 0, &mut self.q);
                }
                f(s, 1, &mut self.dq);
                f(s, 2, &mut self.ddq);
            }
            None => {
                if need_q {
                    path.eval(s, 0, &mut self.q);
                }
                path.eval_derivatives(s, &mut self.dq, &mut self.ddq);
            }
        }
        check_path_values(s, &self.q, &self.dq, &self.ddq)?;
        let (p, cr) = self.point(s);
        // The constraints append to `rows` directly (no copy).
        std::mem::swap(rows, &mut cr.rows);
        let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
        let mut result = Ok(());
        for c in cons {
            cr.clear_bounds();
            c.write(&p, cr);
            result = cr.check(&**c, s);
            if result.is_err() {
                break;
            }
            lo = lo.max(cr.x_min);
            hi = hi.min(cr.x_max);
        }
        std::mem::swap(rows, &mut cr.rows);
        result.map(|()| (lo, hi.max(lo)))
    }

    /// Evaluates σ, σ′, σ″ at `s` into the scratch buffers.
    fn at<P: Path + ?Sized>(&mut self, path: &P, s: f64) {
        path.eval(s, 0, &mut self.q);
        path.eval_derivatives(s, &mut self.dq, &mut self.ddq);
    }

    /// The path point held in the scratch buffers, and the rows buffer.
    fn point(&mut self, s: f64) -> (PathPoint<'_>, &mut ConstraintRows) {
        let p = PathPoint {
            s,
            q: &self.q,
            dq: &self.dq,
            ddq: &self.ddq,
        };
        (p, &mut self.cr)
    }

    /// The largest relative excess of any constraint at `s` for u, x.
    fn excess<P: Path + ?Sized>(
        &mut self,
        path: &P,
        cons: &[Box<dyn Constraint + '_>],
        s: f64,
        u: f64,
        x: f64,
    ) -> f64 {
        self.at(path, s);
        let (p, cr) = self.point(s);
        let mut worst = f64::NEG_INFINITY;
        for c in cons {
            cr.clear();
            c.write(&p, cr);
            worst = worst.max(cr.relative_excess(u, x));
        }
        worst
    }

    /// Joint-level reasons, from the constraints, why the path cannot move at `s`.
    fn diagnose<P: Path + ?Sized>(
        &mut self,
        path: &P,
        cons: &[Box<dyn Constraint + '_>],
        s: f64,
    ) -> Vec<String> {
        self.at(path, s);
        let (p, _) = self.point(s);
        cons.iter().filter_map(|c| c.diagnose(&p)).collect()
    }
}

/// The rows of a subset of the knots, without copying: knot i of the view is knot `map[i]`
/// of `rows` (all of them in order without a map).
#[derive(Clone, Copy)]
struct View<'a> {
    rows: &'a Rows,
    map: Option<&'a [usize]>,
}

impl<'a> View<'a> {
    fn all(rows: &'a Rows) -> Self {
        View { rows, map: None }
    }
    fn at(&self, i: usize) -> usize {
        self.map.map_or(i, |m| m[i])
    }
    fn right(&self, i: usize) -> &'a [[f64; 3]] {
        self.rows.right(self.at(i))
    }
    fn left(&self, i: usize) -> &'a [[f64; 3]] {
        self.rows.left(self.at(i))
    }
    fn xhi(&self, i: usize) -> [f64; 2] {
        self.rows.xhi[self.at(i)]
    }
    fn xlo(&self, i: usize) -> [f64; 2] {
        self.rows.xlo[self.at(i)]
    }
}

impl Rows {
    fn right(&self, k: usize) -> &[[f64; 3]] {
        &self.rows[self.range[k][0]..self.range[k][1]]
    }
    fn left(&self, k: usize) -> &[[f64; 3]] {
        &self.rows[self.range[k][2]..self.range[k][3]]
    }
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
pub(crate) fn integrate<P: Path + ?Sized>(
    path: &P,
    left: &dyn Fn(f64, usize, &mut [f64]),
    cons: &[Box<dyn Constraint + '_>],
    mut knots: Vec<f64>,
    breaks: &[f64],
    step_bound: Option<StepBound<'_>>,
    velocities: (f64, f64),
) -> Result<PhaseSolution> {
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
    let mut sc = Scratch::new(path.dim());
    let mut rows = Rows::default();
    // The previous knots' rows, and per knot where it was in the previous knots
    // ([`NEW_KNOT`] for a new one): kept knots reuse their rows.
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
        let sweep = match sweep(
            path,
            cons,
            &knots,
            breaks,
            View::all(&rows),
            &constant,
            velocities,
            &mut sc,
        ) {
            Ok(sw) => sw,
            Err(e) => return fallback.ok_or(e),
        };
        if round == 0 && step_bound.is_some() {
            tmax = tighten_max(&sweep, &constant);
        }
        let n = knots.len() - 1;
        let fixed_knot = |k: usize| k == 0 || k == n || is_break(breaks, knots[k]);
        // Event check between knots; repeated (same sweep) after a loss estimate above the
        // budget, with the lowered threshold.
        let (parts, mut next_eps, cut_bound, worst) = loop {
            clean.start_round();
            let mut parts = vec![1usize; n];
            let mut next_eps = eps.clone();
            let mut cut_bound = vec![0.0f64; n];
            let mut worst = (0.0f64, 0.0f64);
            let mut forced = false;
            let (s, x) = (&sweep.s, &sweep.x);
            for j in 0..s.len() - 1 {
                let i = sweep.step[j];
                let d = s[j + 1] - s[j];
                let u = (x[j + 1] - x[j]) / (2.0 * d);
                if let Some(b) = step_bound {
                    // The step's u holds at both ends of the knot step it lies in (crossings
                    // are inside knot steps): bound over the whole knot step.
                    let (k0, k1) = (knots[i], knots[i + 1]);
                    let xa = x[j] + 2.0 * u * (k0 - s[j]);
                    let xb = x[j] + 2.0 * u * (k1 - s[j]);
                    let bound = b(k0, k1, u, xa.max(xb).max(0.0));
                    let (e0, e1) = (eps[i], eps[i + 1]);
                    let excess = excess_between(bound, e0, e1);
                    if excess <= BOUND_TOL && bound <= cut_above {
                        continue;
                    }
                    if bound.is_finite() {
                        // A rigorous bound that shrinks with the square of the step: tighten the
                        // limits at the step's free knots by it, or cut the step where that would
                        // cost more than TIGHTEN_MAX of the limits. No sampling needed.
                        if excess > worst.0 {
                            worst = (excess, s[j]);
                        }
                        let free = [fixed_knot(i), fixed_knot(i + 1)].map(|f| !f);
                        let need = if free[0] && free[1] {
                            bound
                        } else {
                            4.0 * bound
                        };
                        if bound <= tmax && (free[0] || free[1]) {
                            for (k, f) in [(i, free[0]), (i + 1, free[1])] {
                                if f {
                                    next_eps[k] = next_eps[k].max(need * (1.0 + TIGHTEN_MARGIN));
                                }
                            }
                        } else {
                            let m = (need / (0.5 * tmax)).sqrt().ceil();
                            parts[i] = parts[i].max(if m.is_finite() {
                                (m as usize).clamp(2, 64)
                            } else {
                                64
                            });
                            cut_bound[i] = cut_bound[i].max(bound);
                            forced |= bound > cut_above;
                        }
                        continue;
                    }
                }
                let step = [s[j], s[j + 1], x[j], x[j + 1]];
                if clean.unchanged(step) {
                    continue;
                }
                let mut e = CHECK_TOL;
                for f in CHECK_POINTS {
                    let si = s[j] + f * d;
                    if !(si > s[j] && si < s[j + 1]) {
                        continue;
                    }
                    let xs = (x[j] + 2.0 * u * f * d).max(0.0);
                    e = e.max(sc.excess(path, cons, si, u, xs));
                }
                if e > CHECK_TOL {
                    if e > worst.0 {
                        worst = (e, s[j]);
                    }
                    parts[i] = parts[i].max(parts_for(e));
                } else {
                    clean.mark(step);
                }
            }
            if worst.0 > 0.0 || forced {
                break (parts, next_eps, cut_bound, worst);
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
        let total: usize = parts.iter().sum();
        if round == MAX_ROUNDS || total > MAX_KNOTS {
            if let Some(sol) = fallback {
                return Ok(sol);
            }
            return Err(Error::Infeasible(format!(
                "phase-plane integration: a constraint is still exceeded by {:.3e} (relative) near s = {} after {round} refinement rounds and {} knots",
                worst.0, worst.1, knots.len()
            )));
        }
        if total > n {
            // The new knots of a cut step start tightened by its bound shrunk by the square
            // of the cut (four times that next to a fixed knot), and so do its free end knots
            // (an untightened end would leave the end parts above the limits: one more round).
            for i in 0..n {
                if parts[i] > 1 {
                    let per = cut_bound[i] / (parts[i] * parts[i]) as f64 * (1.0 + TIGHTEN_MARGIN);
                    for k in [i, i + 1] {
                        if !fixed_knot(k) {
                            next_eps[k] = next_eps[k].max(per);
                        }
                    }
                }
            }
            let mut next = Vec::with_capacity(total + 1);
            let mut next_e = Vec::with_capacity(total + 1);
            origin.clear();
            for i in 0..n {
                next.push(knots[i]);
                next_e.push(next_eps[i]);
                origin.push(i);
                let per = cut_bound[i] / (parts[i] * parts[i]) as f64 * (1.0 + TIGHTEN_MARGIN);
                for k in 1..parts[i] {
                    let si = knots[i] + (knots[i + 1] - knots[i]) * (k as f64 / parts[i] as f64);
                    if si > next[next.len() - 1] && si < knots[i + 1] {
                        let edge =
                            (k == 1 && fixed_knot(i)) || (k + 1 == parts[i] && fixed_knot(i + 1));
                        next.push(si);
                        next_e.push(if edge { 4.0 * per } else { per });
                        origin.push(NEW_KNOT);
                    }
                }
            }
            next.push(knots[n]);
            next_e.push(next_eps[n]);
            origin.push(n);
            knots = next;
            eps = next_e;
            evaluated = false;
        } else {
            eps = next_eps;
        }
        round += 1;
    }
}

/// The cut threshold of bounded steps for this problem (see [`TIGHTEN_MAX`]), from the first
/// sweep: [`TIGHTEN_SHARE`]·(T/T_v)², T the whole duration and T_v the time spent on varying
/// (not closed-form) steps, clamped to [[`TIGHTEN_MAX`], [`TIGHTEN_CAP`]].
///
/// Why: with s̈ constant between knots the duration loss on varying steps is first order in
/// the knot spacing, about C·(T_v/T)·√threshold relative to the whole duration (C measured
/// 0.06–0.15 on Panda paths). Where the varying steps are a small share of the duration (long
/// straight segments, short blends) their loss is diluted by it, and a coarser spacing keeps
/// the same relative loss: C·√TIGHTEN_SHARE ≤ 6e-5 once scaled; paths that spend more than
/// √(TIGHTEN_SHARE/TIGHTEN_MAX) ≈ 28 % of their time on arcs keep [`TIGHTEN_MAX`].
fn tighten_max(sweep: &Sweep, constant: &[bool]) -> f64 {
    let (mut all, mut varying) = (0.0, 0.0);
    for (j, dt) in step_times(sweep) {
        all += dt;
        if !constant[sweep.step[j]] {
            varying += dt;
        }
    }
    if varying > 0.0 && all.is_finite() {
        (TIGHTEN_SHARE * (all / varying).powi(2)).clamp(TIGHTEN_MAX, TIGHTEN_CAP)
    } else {
        TIGHTEN_MAX
    }
}

/// The duration of every output step of `sweep` (x linear in s: Δt = 2Δs/(√x₀ + √x₁)), with
/// its index; steps with ṡ = 0 at both ends are skipped.
fn step_times(sweep: &Sweep) -> impl Iterator<Item = (usize, f64)> + '_ {
    (0..sweep.s.len() - 1).filter_map(|j| {
        let root = sweep.x[j].max(0.0).sqrt() + sweep.x[j + 1].max(0.0).sqrt();
        (root > 0.0).then(|| (j, 2.0 * (sweep.s[j + 1] - sweep.s[j]) / root))
    })
}

/// A-posteriori estimate of the duration's loss against the converged optimum, relative to
/// the duration of `fine` (the converged sweep on `knots` with `rows`):
/// - **discretization**: the same problem integrated again on every [`COARSEN`]-th knot (m)
///   inside each stretch between fixed knots (breakpoints, the ends; the kept knots' rows
///   are used as they are, with their tightening: no path evaluation, no copy). With s̈
///   constant between knots the loss is first order in the spacing, so
///   T(mh) − T(h) ≈ (m − 1)·(T(h) − T(0)) (Richardson);
/// - **tightening**: the knots' limits are tightened by ε, which slows the motion where they
///   bind by at most about ε/2 of the time: Σ Δt·max(ε₀, ε₁)/2 over the steps.
///
/// `None` where nothing can be dropped (no varying stretch with interior knots) or the coarse
/// integration fails.
#[allow(clippy::too_many_arguments)]
fn loss_estimate<P: Path + ?Sized>(
    path: &P,
    cons: &[Box<dyn Constraint + '_>],
    knots: &[f64],
    breaks: &[f64],
    constant: &[bool],
    rows: &Rows,
    fine: &Sweep,
    velocities: (f64, f64),
    sc: &mut Scratch,
) -> Option<f64> {
    let n = knots.len() - 1;
    let mut sub = Vec::with_capacity(n / 2 + 2);
    let mut run = 0usize;
    for k in 0..=n {
        if k == 0 || k == n || is_break(breaks, knots[k]) {
            run = 0;
        } else {
            run += 1;
        }
        if run % COARSEN == 0 {
            sub.push(k);
        }
    }
    if sub.len() == knots.len() {
        return None;
    }
    let coarse: Vec<f64> = sub.iter().map(|&k| knots[k]).collect();
    let coarse_constant: Vec<bool> = sub
        .windows(2)
        .map(|w| w[1] == w[0] + 1 && constant[w[0]])
        .collect();
    let view = View {
        rows,
        map: Some(&sub),
    };
    let wide = sweep(
        path,
        cons,
        &coarse,
        breaks,
        view,
        &coarse_constant,
        velocities,
        sc,
    )
    .ok()?;
    let (mut t_fine, mut tight) = (0.0, 0.0);
    for (j, dt) in step_times(fine) {
        let i = fine.step[j];
        t_fine += dt;
        tight += dt * 0.5 * rows.applied[i].max(rows.applied[i + 1]);
    }
    let t_wide: f64 = step_times(&wide).map(|(_, dt)| dt).sum();
    let est = (t_wide / t_fine - 1.0).max(0.0) / (COARSEN - 1) as f64 + tight / t_fine;
    est.is_finite().then_some(est)
}

/// The largest relative excess over the true limits between two knots whose limits are
/// tightened by `e0` and `e1`, for a step whose excess over the chord is at most `bound`: the
/// chord sits at −(e0·(1 − t) + e1·t) and the excess over it at most 4·bound·t·(1 − t)
/// (t ∈ [0, 1] along the step; the largest value of t(1 − t) is 1/4).
fn excess_between(bound: f64, e0: f64, e1: f64) -> f64 {
    if bound <= 0.0 {
        return -e0.min(e1);
    }
    let t = ((4.0 * bound + e0 - e1) / (8.0 * bound)).clamp(0.0, 1.0);
    4.0 * bound * t * (1.0 - t) - e0 * (1.0 - t) - e1 * t
}

/// Into how many equal parts to cut a step whose excess `e` shrinks with the square of its
/// length, to bring it a few times below the tolerance.
fn parts_for(e: f64) -> usize {
    let m = (e / (0.5 * CHECK_TOL)).sqrt().ceil();
    if m.is_finite() {
        (m as usize).clamp(2, 64)
    } else {
        64
    }
}

fn profile_of(s: &[f64], x: &[f64]) -> Result<PhaseProfile> {
    let sd: Vec<f64> = x.iter().map(|v| v.max(0.0).sqrt()).collect();
    PhaseProfile::new(s, &sd)
}

/// The forward curve over a step whose constraints do not vary along it (a straight segment):
/// u bounds and the velocity bound are the same everywhere on it, so the forward curve
/// min(x_cap, x + 2·u_acc·(s − s_i)) and the backward curve min(x_cap, x_end − 2·u_dec·(s_end − s))
/// are exact, and their minimum (concave, piecewise linear) is pushed as knots: acceleration,
/// cruise on the velocity limit, deceleration, in closed form. Pushes the interior knots only.
fn constant_step(rows: View<'_>, knots: &[f64], i: usize, x: f64, x_end: f64, out: &mut Sweep) {
    let (s0, s1) = (knots[i], knots[i + 1]);
    let here = rows.right(i);
    // b = 0 on such a step: the u bounds do not depend on x.
    let (mut u_acc, mut u_dec) = (f64::INFINITY, f64::NEG_INFINITY);
    for &[a, b, g] in here {
        let rhs = g - b * x;
        if a > 0.0 {
            u_acc = u_acc.min(rhs / a);
        } else if a < 0.0 {
            u_dec = u_dec.max(rhs / a);
        }
    }
    let x_cap = rows.xhi(i)[0].min(rows.xhi(i + 1)[1]);
    let fwd = |s: f64| {
        if u_acc > 0.0 {
            (x + 2.0 * u_acc * (s - s0)).min(x_cap)
        } else {
            x
        }
    };
    let bwd = |s: f64| {
        if u_dec < 0.0 {
            (x_end - 2.0 * u_dec * (s1 - s)).min(x_cap)
        } else {
            x_end
        }
    };
    let mut cand = [f64::NAN; 3];
    if u_acc > 0.0 && u_acc.is_finite() {
        cand[0] = s0 + (x_cap - x) / (2.0 * u_acc);
    }
    if u_dec < 0.0 && u_dec.is_finite() {
        cand[1] = s1 - (x_cap - x_end) / (-2.0 * u_dec);
        if u_acc > 0.0 && u_acc.is_finite() {
            // x + 2·u_acc·(s − s0) = x_end − 2·u_dec·(s1 − s)
            cand[2] = (x_end - 2.0 * u_dec * s1 - x + 2.0 * u_acc * s0) / (2.0 * (u_acc - u_dec));
        }
    }
    cand.sort_by(|a, b| a.total_cmp(b));
    let tiny = 1e-12 * (s1 - s0);
    let mut prev = s0;
    for c in cand {
        if c.is_finite() && c > prev + tiny && c < s1 - tiny {
            out.s.push(c);
            out.x.push(fwd(c).min(bwd(c)).max(0.0));
            out.step.push(i);
            prev = c;
        }
    }
}

/// Whether `s` is an interior breakpoint (where the two sides of a knot differ).
fn is_break(breaks: &[f64], s: f64) -> bool {
    breaks.len() > 2
        && breaks[1..breaks.len() - 1]
            .binary_search_by(|b| b.total_cmp(&s))
            .is_ok()
}

impl Rows {
    /// Tightens the limits at every knot k whose applied tightening is not `eps[k]`
    /// (relative), in place: every row γ → γ₀ − ε·|γ₀|, x_max → x₀·(1 − ε), from the
    /// untightened values.
    fn tighten(&mut self, eps: &[f64]) {
        for (k, r) in self.range.iter().enumerate() {
            let e = eps[k];
            if e == self.applied[k] {
                continue;
            }
            self.applied[k] = e;
            let shared = r[0] == r[2];
            for (a, b) in [(r[0], r[1]), (r[2], r[3])]
                .into_iter()
                .take(if shared { 1 } else { 2 })
            {
                for (row, &g) in self.rows[a..b].iter_mut().zip(&self.gamma[a..b]) {
                    row[2] = g - e * g.abs();
                }
            }
            for side in 0..2 {
                self.xhi[k][side] = (self.xhi0[k][side] * (1.0 - e)).max(self.xlo[k][side]);
            }
        }
    }

    /// Evaluates the rows of every knot, untightened; with `old`, the previous knots' rows
    /// and where each knot was among them, a kept knot copies its rows (and their
    /// tightening) instead.
    #[allow(clippy::too_many_arguments)]
    fn evaluate<P: Path + ?Sized>(
        &mut self,
        path: &P,
        left: &dyn Fn(f64, usize, &mut [f64]),
        cons: &[Box<dyn Constraint + '_>],
        knots: &[f64],
        breaks: &[f64],
        old: Option<(&Rows, &[usize])>,
        sc: &mut Scratch,
    ) -> Result<()> {
        self.rows.clear();
        self.gamma.clear();
        self.range.clear();
        self.xlo.clear();
        self.xhi.clear();
        self.xhi0.clear();
        self.applied.clear();
        let n = knots.len() - 1;
        for (k, &s) in knots.iter().enumerate() {
            let a = self.rows.len();
            let kept = old.and_then(|(o, origin)| Some((o, *origin.get(k)?)));
            let (range, xlo, xhi, xhi0, applied) = match kept {
                Some((o, i)) if i != NEW_KNOT => {
                    let r = o.range[i];
                    let copy = |rows: &mut Vec<[f64; 3]>, gamma: &mut Vec<f64>, (p, q)| {
                        rows.extend_from_slice(&o.rows[p..q]);
                        gamma.extend_from_slice(&o.gamma[p..q]);
                    };
                    copy(&mut self.rows, &mut self.gamma, (r[0], r[1]));
                    let b = self.rows.len();
                    let range = if r[0] == r[2] {
                        [a, b, a, b]
                    } else {
                        copy(&mut self.rows, &mut self.gamma, (r[2], r[3]));
                        [a, b, b, self.rows.len()]
                    };
                    (range, o.xlo[i], o.xhi[i], o.xhi0[i], o.applied[i])
                }
                _ => {
                    let (lo, hi) = sc.write(path, None, cons, s, &mut self.rows)?;
                    let b = self.rows.len();
                    let (range, xlo, xhi) = if k > 0 && k < n && is_break(breaks, s) {
                        let (llo, lhi) = sc.write(path, Some(left), cons, s, &mut self.rows)?;
                        ([a, b, b, self.rows.len()], [lo, llo], [hi, lhi])
                    } else {
                        ([a, b, a, b], [lo, lo], [hi, hi])
                    };
                    let new = &self.rows[a..];
                    self.gamma.extend(new.iter().map(|r| r[2]));
                    (range, xlo, xhi, xhi, 0.0)
                }
            };
            self.range.push(range);
            self.xlo.push(xlo);
            self.xhi.push(xhi);
            self.xhi0.push(xhi0);
            self.applied.push(applied);
            if k == 0 {
                // Every knot and the left side of every breakpoint: no regrowth (each one
                // copies all rows so far).
                let m = self.rows.len() * (knots.len() + breaks.len());
                self.rows.reserve(m);
                self.gamma.reserve(m);
                self.range.reserve(knots.len());
                self.xlo.reserve(knots.len());
                self.xhi.reserve(knots.len());
                self.xhi0.reserve(knots.len());
                self.applied.reserve(knots.len());
            }
        }
        Ok(())
    }
}

struct Sweep {
    s: Vec<f64>,
    x: Vec<f64>,
    /// For each output step, the knot step it lies in.
    step: Vec<usize>,
    switching: Vec<SwitchingPoint>,
}

/// What bounds the backward curve at a knot.
#[derive(Clone, Copy, PartialEq)]
enum Bound {
    /// The backward integration from the next knot.
    Integrated,
    /// The maximum velocity curve, and which kind.
    Limit(SwitchKind),
}

/// One backward and one forward integration over the knots.
fn sweep<P: Path + ?Sized>(
    path: &P,
    cons: &[Box<dyn Constraint + '_>],
    knots: &[f64],
    breaks: &[f64],
    rows: View<'_>,
    constant: &[bool],
    (v0, v1): (f64, f64),
    sc: &mut Scratch,
) -> Result<Sweep> {
    let n = knots.len() - 1;
    let (x_start, x_end) = (v0 * v0, v1 * v1);
    let mut back = vec![0.0; n + 1];
    let mut bound = vec![Bound::Integrated; n + 1];
    if x_end > rows.xhi(n)[1] * (1.0 + 1e-9) || x_end < rows.xlo(n)[1] * (1.0 - 1e-9) {
        return Err(Error::Infeasible(format!(
            "the end path velocity ṡ = {v1} is outside what the constraints allow at s = {} (ṡ ≤ {})",
            knots[n],
            rows.xhi(n)[1].sqrt()
        )));
    }
    back[n] = x_end;
    let mut hint = [BOX, BOX];
    for i in (0..n).rev() {
        let delta = knots[i + 1] - knots[i];
        let (khi, klo) = (back[i + 1], rows.xlo(i + 1)[1]);
        let stage = Stage {
            here: rows.right(i),
            next: rows.left(i + 1),
            mid: &[],
            two_delta: 2.0 * delta,
            khi,
            klo,
        };
        let xhi = rows.xhi(i)[0].min(X_BIG);
        let xlo = rows.xlo(i)[0];
        let lo = [(klo - xhi) / (2.0 * delta), xlo];
        let hi = [(khi - xlo) / (2.0 * delta), xhi];
        let tol = 1e-10 * (1.0 + khi);
        let Some(best) = lp::maximize([0.0, 1.0], &stage, lo, hi, hint, tol) else {
            return Err(Error::Infeasible(format!(
                "at s = {} (between knots {i} and {}): the constraints leave no admissible path acceleration that reaches ṡ ≤ {} at s = {}",
                knots[i],
                i + 1,
                khi.sqrt(),
                knots[i + 1]
            )));
        };
        if best.v[1] >= X_BIG * 0.5 {
            return Err(Error::Infeasible(format!(
                "no constraint bounds the path velocity near s = {} (the path does not move there, or nothing limits it)",
                knots[i]
            )));
        }
        hint = best.active;
        back[i] = best.v[1].clamp(xlo, xhi);
        let h = stage.here.len();
        let backward_row = h + stage.next.len();
        if !best.active.contains(&backward_row) {
            let kind = if i > 0 && is_break(breaks, knots[i]) {
                SwitchKind::Discontinuity
            } else if best.active.iter().all(|&a| a == BOX) {
                SwitchKind::VelocityLimit
            } else {
                let singular = best.active.iter().any(|&a| {
                    a < backward_row && {
                        let [al, be, _] = lp::HalfPlanes::get(&stage, a);
                        al.abs() <= 1e-9 * be.abs() * (1.0 + best.v[1])
                    }
                });
                if singular {
                    SwitchKind::Singular
                } else {
                    SwitchKind::Tangent
                }
            };
            bound[i] = Bound::Limit(kind);
        }
    }
    if x_start > back[0] * (1.0 + 1e-9) + 1e-300 {
        return Err(Error::Infeasible(format!(
            "the start path velocity ṡ = {v0} is too high: from s = {} the constraints and the end velocity allow at most ṡ = {}",
            knots[0],
            back[0].sqrt()
        )));
    }
    // Forward integration.
    let mut out = Sweep {
        s: Vec::with_capacity(n + 8),
        x: Vec::with_capacity(n + 8),
        step: Vec::with_capacity(n + 8),
        switching: Vec::new(),
    };
    let mut x = x_start.min(back[0]);
    out.s.push(knots[0]);
    out.x.push(x);
    let mut on_limit = false;
    // Knot index and kind of the last switching point recorded.
    let mut last_switch: Option<(usize, SwitchKind)> = None;
    for i in 0..n {
        let delta = knots[i + 1] - knots[i];
        let cap = (rows.xhi(i + 1)[1].min(X_BIG) - x) / (2.0 * delta);
        let uf = largest_step(rows.right(i), rows.left(i + 1), 2.0 * delta, x, cap);
        let xf = x + 2.0 * delta * uf;
        let next = if constant[i] {
            constant_step(rows, knots, i, x, back[i + 1], &mut out);
            back[i + 1].min(x + 2.0 * delta * uf.max(0.0)).max(0.0)
        } else if xf <= back[i + 1] {
            xf.max(0.0)
        } else {
            let ub = (back[i + 1] - back[i]) / (2.0 * delta);
            // The backward line from knot i is certified by the LP only where its backward
            // row is active there (back[i] + 2Δu* = back[i + 1]); below a point of the limit
            // curve the step is the plain one to back[i + 1], admissible by convexity.
            if uf > ub && x < back[i] && bound[i] == Bound::Integrated {
                let tau = (back[i] - x) / (2.0 * (uf - ub));
                if tau > 1e-9 * delta && tau < delta * (1.0 - 1e-9) {
                    out.s.push(knots[i] + tau);
                    out.x.push(x + 2.0 * uf * tau);
                    out.step.push(i);
                }
            }
            back[i + 1]
        };
        let last = out.x[out.x.len() - 1];
        if next <= 0.0 && last <= 0.0 {
            let mut why = sc.diagnose(path, cons, knots[i]);
            why.dedup();
            let why = if why.is_empty() {
                "the constraints allow no path acceleration from rest".to_string()
            } else {
                why.join("; ")
            };
            return Err(Error::Infeasible(format!(
                "the path cannot move between s = {} and s = {}: {why}",
                knots[i],
                knots[i + 1]
            )));
        }
        out.s.push(knots[i + 1]);
        out.x.push(next);
        out.step.push(i);
        // A switching point: the curve reaches the MVC at a knot where a backward integration
        // starts (entry into a stretch on the limit curve).
        let touches = next >= back[i + 1] * (1.0 - 1e-12);
        if let (true, Bound::Limit(kind)) = (touches, bound[i + 1]) {
            // A return to the limit curve two knots after leaving it, of the same kind, is the
            // same switching point seen through the knots, not a new one.
            let repeat = last_switch.is_some_and(|(k, what)| what == kind && i < k + 2);
            if !on_limit && i + 1 < n && !repeat {
                out.switching.push(SwitchingPoint {
                    s: knots[i + 1],
                    sd: next.sqrt(),
                    kind,
                });
            }
            if !on_limit {
                last_switch = Some((i + 1, kind));
            }
            on_limit = true;
        } else {
            on_limit = false;
        }
        x = next;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::{excess_between, tighten_max, Sweep, TIGHTEN_CAP, TIGHTEN_MAX, TIGHTEN_SHARE};

    /// A sweep at ṡ = 1 over steps of the given lengths (one knot step each).
    fn unit_speed(lengths: &[f64]) -> Sweep {
        let mut s = vec![0.0];
        for l in lengths {
            s.push(s[s.len() - 1] + l);
        }
        Sweep {
            x: vec![1.0; s.len()],
            step: (0..lengths.len()).collect(),
            s,
            switching: Vec::new(),
        }
    }

    /// The cut threshold against hand-computed durations (ṡ = 1: time = length).
    #[test]
    fn cut_threshold_scales_with_the_share_of_varying_steps() {
        // 10 s straight, 1 s varying: (11/1)² times the share.
        let t = tighten_max(&unit_speed(&[10.0, 1.0]), &[true, false]);
        assert!((t - TIGHTEN_SHARE * 121.0).abs() < 1e-18, "{t}");
        // Mostly varying: the floor; almost all straight: the cap; nothing varying: the floor.
        assert_eq!(
            tighten_max(&unit_speed(&[1.0, 1.0]), &[true, false]),
            TIGHTEN_MAX
        );
        assert_eq!(
            tighten_max(&unit_speed(&[100.0, 1.0]), &[true, false]),
            TIGHTEN_CAP
        );
        assert_eq!(
            tighten_max(&unit_speed(&[1.0, 1.0]), &[true, true]),
            TIGHTEN_MAX
        );
        // Time, not length: a varying step at ṡ² going 0 → 4 over length 1 lasts
        // 2·1/(0 + 2) = 1 s; a straight one of length 9 at ṡ = 2 lasts 4.5 s.
        let mut sw = unit_speed(&[1.0, 9.0]);
        sw.x = vec![0.0, 4.0, 4.0];
        let t = tighten_max(&sw, &[false, true]);
        assert!((t - TIGHTEN_SHARE * 5.5 * 5.5).abs() < 1e-18, "{t}");
    }

    /// The closed form against a dense scan of 4b·t(1 − t) − e₀(1 − t) − e₁·t over t ∈ [0, 1].
    #[test]
    fn excess_between_matches_a_scan() {
        let b = 1e-5;
        for (e0, e1) in [
            (0.0, 0.0),
            (b, b),
            (0.0, 4.0 * b),
            (0.0, 2.0 * b),
            (3e-6, 4e-5),
            (5e-5, 0.0),
        ] {
            let scan = (0..=100_000)
                .map(|k| {
                    let t = k as f64 / 100_000.0;
                    4.0 * b * t * (1.0 - t) - e0 * (1.0 - t) - e1 * t
                })
                .fold(f64::NEG_INFINITY, f64::max);
            let closed = excess_between(b, e0, e1);
            assert!(
                (closed - scan).abs() < 1e-14,
                "{e0} {e1}: {closed} vs {scan}"
            );
        }
        // Equal tightening by the bound leaves no excess; none either next to an untightened
        // knot when the other takes 4b.
        assert!(excess_between(b, b, b).abs() < 1e-18);
        assert!(excess_between(b, 0.0, 4.0 * b) <= 0.0);
        assert!(excess_between(b, 0.0, b) > 0.0);
    }
}
