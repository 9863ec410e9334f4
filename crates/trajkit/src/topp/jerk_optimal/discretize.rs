//! The discretized problem: path data at gridpoints and at points inside intervals
//! (midpoints and "cuts"), and the rows of each stage in the variables (x_i, u_i, v_i).
//!
//! At a point δ into middle interval i, x(δ) = x_i + e1·u_i + e2·v_i and u(δ) = u_i + f·v_i
//! (`shape::At`) are linear in (x_i, u_i, v_i), so every constraint becomes linear
//! rows there:
//! - joint velocity: x(δ) ≤ x_max(δ) = min_j (V_j/σ′_j)² (direction of σ′_j);
//! - joint acceleration: A⁻_j ≤ σ″_j·x(δ) + σ′_j·u(δ) ≤ A⁺_j;
//! - second-order rows α·u + β·x ≤ γ of any other [`Constraint`] (torque, …);
//! - joint jerk `|σ‴x + 3σ″u + σ′·θ′·v|·√x ≤ J`, written `|g| ≤ J/√x` with g linear and the
//!   convex right-hand side replaced by its tangent at a linearization point x̄ > 0,
//!   `J/√x ≥ (J/√x̄)·(3/2 − x/(2x̄))`. The tangent lies below the curve, so the rows are
//!   conservative: a point that meets them meets the jerk limit, whatever x̄ is.
//!
//! Every limit of a joint on an interval can be scaled by a factor κ ≤ 1 (see
//! [`super::problem`]): the rows then hold it with room for what happens between the points.
//!
//! A row is `[a_x, a_u, a_v, c]`: `a_x·x + a_u·u + a_v·v ≤ c`.

use super::certify::JointRange;
use super::shape::At;
use crate::error::Result;
use crate::topp::constraint::{Constraint, ConstraintRows, PathPoint};
use crate::Path;

/// A stage row: `a_x·x + a_u·u + a_v·v ≤ c`.
pub(crate) type Row = [f64; 4];

/// Path derivatives and the rows of the extra (non-joint) constraints at a list of points.
#[derive(Default)]
pub(crate) struct Points {
    pub(crate) n: usize,
    pub(crate) s: Vec<f64>,
    /// σ′, σ″ (flat, `n` per point).
    pub(crate) d1: Vec<f64>,
    pub(crate) d2: Vec<f64>,
    /// σ‴ on the right of the point (the interval that starts there) and on its left; they
    /// differ only at breakpoints of the path.
    pub(crate) d3r: Vec<f64>,
    pub(crate) d3l: Vec<f64>,
    /// Bounds on x from the extra constraints.
    pub(crate) xmax: Vec<f64>,
    pub(crate) xmin: Vec<f64>,
    /// Second-order rows (α, β, γ) of the extra constraints: α·u + β·x ≤ γ, of point k in
    /// `rows[off[k]..off[k+1]]`.
    pub(crate) rows: Vec<[f64; 3]>,
    pub(crate) off: Vec<usize>,
    q: Vec<f64>,
    cr: ConstraintRows,
}

impl Points {
    /// Empty, for paths of `n` joints.
    pub(crate) fn new(n: usize) -> Self {
        Points {
            n,
            off: vec![0],
            q: vec![0.0; n],
            cr: ConstraintRows::new(),
            ..Default::default()
        }
    }

    /// Number of points.
    pub(crate) fn len(&self) -> usize {
        self.s.len()
    }

    /// Appends the point s; `left` is a parameter just left of s inside the smooth piece of
    /// the interval that ends at s (for σ‴'s left value at a breakpoint), `None` elsewhere.
    /// `extra` are the constraints other than joint velocity and acceleration.
    pub(crate) fn push<P: Path>(
        &mut self,
        path: &P,
        extra: &[Box<dyn Constraint + '_>],
        s: f64,
        left: Option<f64>,
    ) -> Result<()> {
        let n = self.n;
        let k = self.s.len();
        self.s.push(s);
        self.d1.resize((k + 1) * n, 0.0);
        self.d2.resize((k + 1) * n, 0.0);
        self.d3r.resize((k + 1) * n, 0.0);
        self.d3l.resize((k + 1) * n, 0.0);
        let r = k * n..(k + 1) * n;
        path.eval_derivatives(s, &mut self.d1[r.clone()], &mut self.d2[r.clone()]);
        path.eval(s, 3, &mut self.d3r[r.clone()]);
        match left {
            Some(sl) => path.eval(sl, 3, &mut self.d3l[r.clone()]),
            None => {
                for j in r.clone() {
                    self.d3l[j] = self.d3r[j];
                }
            }
        }
        let need_q = extra.iter().any(|c| c.uses_position());
        if need_q {
            path.eval(s, 0, &mut self.q);
        }
        crate::topp::toppra::check_path_values(
            s,
            &self.q,
            &self.d1[r.clone()],
            &self.d2[r.clone()],
        )?;
        for d3 in [&self.d3r, &self.d3l] {
            if let Some(j) = d3[r.clone()].iter().position(|v| !v.is_finite()) {
                return Err(crate::Error::InvalidValue {
                    field: format!("path third derivative of joint {} at s = {s}", j + 1),
                    value: d3[k * n + j],
                    reason: "is not a finite number",
                });
            }
        }
        let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
        if !extra.is_empty() {
            let p = PathPoint {
                s,
                q: &self.q,
                dq: &self.d1[r.clone()],
                ddq: &self.d2[r],
            };
            self.cr.clear();
            for c in extra {
                self.cr.clear_bounds();
                c.write(&p, &mut self.cr);
                self.cr.check(&**c, s)?;
                lo = lo.max(self.cr.x_min);
                hi = hi.min(self.cr.x_max);
            }
            self.rows.extend_from_slice(&self.cr.rows);
        }
        self.off.push(self.rows.len());
        self.xmin.push(lo);
        self.xmax.push(hi);
        Ok(())
    }

    /// Extra rows of point k.
    #[inline]
    pub(crate) fn rows_of(&self, k: usize) -> &[[f64; 3]] {
        &self.rows[self.off[k]..self.off[k + 1]]
    }

    #[inline]
    pub(crate) fn d1(&self, k: usize) -> &[f64] {
        &self.d1[k * self.n..(k + 1) * self.n]
    }
    #[inline]
    pub(crate) fn d2(&self, k: usize) -> &[f64] {
        &self.d2[k * self.n..(k + 1) * self.n]
    }
    #[inline]
    pub(crate) fn d3r(&self, k: usize) -> &[f64] {
        &self.d3r[k * self.n..(k + 1) * self.n]
    }
    #[inline]
    pub(crate) fn d3l(&self, k: usize) -> &[f64] {
        &self.d3l[k * self.n..(k + 1) * self.n]
    }
}

/// The largest x = ṡ² joint j's velocity limit allows at a point with σ′_j = `d1`, scaled by
/// κ (∞ when σ′_j = 0).
#[inline]
pub(crate) fn joint_xmax(d1: f64, lim: &JointRange, kappa: f64) -> f64 {
    let v = if d1 > 0.0 {
        lim.v.1 / d1
    } else if d1 < 0.0 {
        lim.v.0 / d1
    } else {
        return f64::INFINITY;
    };
    let v = v * kappa;
    v * v
}

/// Appends the velocity row of one joint at a point (skipped when it does not bound x).
#[inline]
pub(crate) fn velocity_row(d1: f64, lim: &JointRange, kappa: f64, at: &At, out: &mut Vec<Row>) {
    let xm = joint_xmax(d1, lim, kappa);
    if xm.is_finite() {
        out.push([1.0, at.e1, at.e2, xm]);
    }
}

/// Appends the two acceleration rows of one joint at a point: A⁻·κ ≤ σ″x + σ′u ≤ A⁺·κ.
#[inline]
pub(crate) fn acceleration_rows(
    d1: f64,
    d2: f64,
    lim: &JointRange,
    kappa: f64,
    at: &At,
    out: &mut Vec<Row>,
) {
    if d1 == 0.0 && d2 == 0.0 {
        return;
    }
    let r = [d2, d2 * at.e1 + d1, d2 * at.e2 + d1 * at.f];
    if lim.a.1.is_finite() {
        out.push([r[0], r[1], r[2], lim.a.1 * kappa]);
    }
    if lim.a.0.is_finite() {
        out.push([-r[0], -r[1], -r[2], -lim.a.0 * kappa]);
    }
}

/// Appends the two jerk rows of one joint at a point: `±g + c·x(δ) ≤ 1.5·J/√x̄` with
/// `c = J/(2x̄^{3/2})` and J = κ·jerk limit (nothing when the limit is infinite).
#[inline]
pub(crate) fn jerk_rows(
    d: [f64; 3],
    jerk: f64,
    kappa: f64,
    at: &At,
    xbar: f64,
    out: &mut Vec<Row>,
) {
    let lim = jerk * kappa;
    if !lim.is_finite() {
        return;
    }
    let [d1, d2, d3] = d;
    let xbar = xbar.max(1e-150);
    let rs = xbar.sqrt();
    let gx = d3;
    let gu = at.e1 * d3 + 3.0 * d2;
    let gv = at.e2 * d3 + 3.0 * at.f * d2 + at.th * d1;
    let rhs = 1.5 * lim / rs;
    let c = 0.5 * lim / (xbar * rs);
    let cx = [c, at.e1 * c, at.e2 * c];
    out.push([gx + cx[0], gu + cx[1], gv + cx[2], rhs]);
    out.push([-gx + cx[0], -gu + cx[1], -gv + cx[2], rhs]);
}

/// Appends the extra constraints' rows of point `k` of `pts` (with x bounds), limits scaled
/// by `shrink` (positive right-hand sides only).
pub(crate) fn extra_rows(pts: &Points, k: usize, shrink: f64, at: &At, out: &mut Vec<Row>) {
    for &[al, be, ga] in pts.rows_of(k) {
        let g = if ga > 0.0 { ga * shrink } else { ga };
        out.push([be, al + at.e1 * be, al * at.f + be * at.e2, g]);
    }
    let xm = pts.xmax[k];
    if xm.is_finite() {
        out.push([1.0, at.e1, at.e2, xm * shrink * shrink]);
    }
    if pts.xmin[k] > 0.0 {
        out.push([-1.0, -at.e1, -at.e2, -pts.xmin[k]]);
    }
}
