//! One sweep over the knots: the backward integration (the envelope of the maximum velocity
//! curve and the backward curves, switching points found on the way) and the forward
//! integration at u_max up to it, with crossings located exactly and closed-form steps where
//! the constraints do not vary.

use super::rows::{is_break, Scratch, View};
use super::{largest_step, lp, Constraint, Stage, SwitchKind, SwitchingPoint, BOX, X_BIG};
use crate::error::{Error, Result};
use crate::num::clamp_in;
use crate::Path;

/// The curve of one sweep: x = ṡ² at the points `s` (the knots and located crossings).
pub(super) struct Sweep {
    pub(super) s: Vec<f64>,
    pub(super) x: Vec<f64>,
    /// For each output step, the knot step it lies in.
    pub(super) step: Vec<usize>,
    pub(super) switching: Vec<SwitchingPoint>,
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
#[allow(clippy::too_many_arguments)]
pub(super) fn sweep<P: Path + ?Sized>(
    path: &P,
    cons: &[Box<dyn Constraint + '_>],
    knots: &[f64],
    breaks: &[f64],
    rows: View<'_>,
    constant: &[bool],
    (v0, v1): (f64, f64),
    sc: &mut Scratch,
) -> Result<Sweep> {
    let (back, bound) = backward(knots, breaks, rows, v1)?;
    let x_start = v0 * v0;
    if x_start > back[0] * (1.0 + 1e-9) + 1e-300 {
        return Err(Error::Infeasible(format!(
            "the start path velocity ṡ = {v0} is too high: from s = {} the constraints and the end velocity allow at most ṡ = {}",
            knots[0],
            back[0].sqrt()
        )));
    }
    forward(
        path, cons, knots, rows, constant, &back, &bound, x_start, sc,
    )
}

/// The backward integration from the end velocity `v1`: per knot the largest x from which
/// the rest of the path can be followed, and what bounds it there (a switching point where
/// the maximum velocity curve does).
fn backward(
    knots: &[f64],
    breaks: &[f64],
    rows: View<'_>,
    v1: f64,
) -> Result<(Vec<f64>, Vec<Bound>)> {
    let n = knots.len() - 1;
    let x_end = v1 * v1;
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
        back[i] = clamp_in(best.v[1], xlo, xhi).ok_or_else(|| {
            Error::Infeasible(format!(
                "at s = {}: the admissible set of ṡ² is empty ([{xlo}, {xhi}])",
                knots[i]
            ))
        })?;
        let backward_row = stage.here.len() + stage.next.len();
        if !best.active.contains(&backward_row) {
            let at_break = i > 0 && is_break(breaks, knots[i]);
            bound[i] = Bound::Limit(switch_kind(&stage, &best, backward_row, at_break));
        }
    }
    Ok((back, bound))
}

/// The kind of switching point at a knot where the backward LP's optimum `best` is bounded by
/// the limit curve, not by the backward row (`backward_row`).
fn switch_kind(
    stage: &Stage<'_>,
    best: &lp::LpSolution,
    backward_row: usize,
    at_break: bool,
) -> SwitchKind {
    if at_break {
        SwitchKind::Discontinuity
    } else if best.active.iter().all(|&a| a == BOX) {
        SwitchKind::VelocityLimit
    } else {
        let singular = best.active.iter().any(|&a| {
            a < backward_row && {
                let [al, be, _] = lp::HalfPlanes::get(stage, a);
                al.abs() <= 1e-9 * be.abs() * (1.0 + best.v[1])
            }
        });
        if singular {
            SwitchKind::Singular
        } else {
            SwitchKind::Tangent
        }
    }
}

/// The forward integration at u_max from `x_start` under the backward curve `back`; where
/// it meets the curve inside a step, the crossing becomes a point of the sweep.
#[allow(clippy::too_many_arguments)]
fn forward<P: Path + ?Sized>(
    path: &P,
    cons: &[Box<dyn Constraint + '_>],
    knots: &[f64],
    rows: View<'_>,
    constant: &[bool],
    back: &[f64],
    bound: &[Bound],
    x_start: f64,
    sc: &mut Scratch,
) -> Result<Sweep> {
    let n = knots.len() - 1;
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
            record_crossing(knots, back, bound, i, x, uf, &mut out);
            back[i + 1]
        };
        let last = out.x[out.x.len() - 1];
        if next <= 0.0 && last <= 0.0 {
            return Err(stuck(path, cons, knots, i, sc));
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

/// Where the forward line from `x` at knot `i` (path acceleration `uf`) meets the backward
/// line of step `i` strictly inside the step, records the crossing as a point of the sweep.
fn record_crossing(
    knots: &[f64],
    back: &[f64],
    bound: &[Bound],
    i: usize,
    x: f64,
    uf: f64,
    out: &mut Sweep,
) {
    let delta = knots[i + 1] - knots[i];
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
}

/// The error for a path that cannot move from rest over knot step `i`, with the
/// constraints' joint-level reasons.
fn stuck<P: Path + ?Sized>(
    path: &P,
    cons: &[Box<dyn Constraint + '_>],
    knots: &[f64],
    i: usize,
    sc: &mut Scratch,
) -> Error {
    let mut why = sc.diagnose(path, cons, knots[i]);
    why.dedup();
    let why = if why.is_empty() {
        "the constraints allow no path acceleration from rest".to_string()
    } else {
        why.join("; ")
    };
    Error::Infeasible(format!(
        "the path cannot move between s = {} and s = {}: {why}",
        knots[i],
        knots[i + 1]
    ))
}

/// The forward curve over a step whose constraints do not vary along it (a straight segment):
/// u bounds and the velocity bound are the same everywhere on it, so the forward curve
/// min(x_cap, x + 2·u_acc·(s − s_i)) and the backward curve min(x_cap, x_end − 2·u_dec·(s_end − s))
/// are exact, and their minimum (concave, piecewise linear) is pushed as knots: acceleration,
/// cruise on the velocity limit, deceleration, in closed form. Pushes the interior knots only.
pub(super) fn constant_step(
    rows: View<'_>,
    knots: &[f64],
    i: usize,
    x: f64,
    x_end: f64,
    out: &mut Sweep,
) {
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
