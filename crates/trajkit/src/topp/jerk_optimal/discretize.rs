//! The discretized problem: path data and constraint rows at gridpoints and at extra points
//! inside intervals ("cuts"), and the rows of each stage in the variables (x_i, u_i, v_i).
//!
//! At a point δ into middle interval i, x(δ) = x_i + 2δ·u_i + δ²·v_i and u(δ) = u_i + δ·v_i
//! are linear in (x_i, u_i, v_i), so every constraint becomes linear rows there:
//! - second-order rows α·u + β·x ≤ γ of a [`Constraint`] (joint acceleration, torque, …) and the
//!   velocity bound x ≤ x_max: `β·x_i + (α + 2βδ)·u_i + (αδ + βδ²)·v_i ≤ γ`;
//! - joint jerk `|σ‴x + 3σ″u + σ′v|·√x ≤ J`, written `|g| ≤ J/√x` with g linear and the
//!   convex right-hand side replaced by its tangent at a linearization point x̄ > 0,
//!   `J/√x ≥ (J/√x̄)·(3/2 − x/(2x̄))`. The tangent lies below the curve, so the rows are
//!   conservative: a point that meets them meets the jerk limit.
//!
//! A row is `[a_x, a_u, a_v, c]`: `a_x·x + a_u·u + a_v·v ≤ c`.

use crate::error::Result;
use crate::topp::constraint::{Constraint, ConstraintRows, PathPoint};
use crate::Path;

/// A stage row: `a_x·x + a_u·u + a_v·v ≤ c`.
pub(crate) type Row = [f64; 4];

/// Path derivatives and constraint rows at a list of points.
#[derive(Default)]
pub(crate) struct Points {
    pub(crate) n: usize,
    pub(crate) s: Vec<f64>,
    /// σ′, σ″ (flat, `n` per point).
    pub(crate) d1: Vec<f64>,
    pub(crate) d2: Vec<f64>,
    /// σ‴ on the right of the point (the interval that starts there) and on its left.
    pub(crate) d3r: Vec<f64>,
    pub(crate) d3l: Vec<f64>,
    /// Upper bound on x from the constraints.
    pub(crate) xmax: Vec<f64>,
    /// Lower bound on x from the constraints.
    pub(crate) xmin: Vec<f64>,
    /// Second-order rows (α, β, γ): α·u + β·x ≤ γ, of point k in `rows[off[k]..off[k+1]]`.
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

    /// Appends the point s; `left` is a parameter just left of s inside the same smooth piece
    /// as the interval that ends at s (for σ‴'s left value), or `None` at the path's start.
    pub(crate) fn push<P: Path>(
        &mut self,
        path: &P,
        cons: &[Box<dyn Constraint + '_>],
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
                let (a, b) = self.d3l.split_at_mut(k * n);
                let _ = a;
                b[..n].copy_from_slice(&self.d3r[r.clone()]);
            }
        }
        if cons.iter().any(|c| c.uses_position()) {
            path.eval(s, 0, &mut self.q);
        }
        crate::topp::toppra::check_path_values(
            s,
            &self.q,
            &self.d1[r.clone()],
            &self.d2[r.clone()],
        )?;
        if let Some(j) = self.d3r[r.clone()].iter().position(|v| !v.is_finite()) {
            return Err(crate::Error::InvalidValue {
                field: format!("path third derivative of joint {} at s = {s}", j + 1),
                value: self.d3r[k * n + j],
                reason: "is not a finite number",
            });
        }
        let p = PathPoint {
            s,
            q: &self.q,
            dq: &self.d1[r.clone()],
            ddq: &self.d2[r],
        };
        let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
        self.cr.clear();
        for c in cons {
            self.cr.clear_bounds();
            c.write(&p, &mut self.cr);
            self.cr.check(&**c, s)?;
            lo = lo.max(self.cr.x_min);
            hi = hi.min(self.cr.x_max);
        }
        self.rows.extend_from_slice(&self.cr.rows);
        self.off.push(self.rows.len());
        self.xmin.push(lo);
        self.xmax.push(hi);
        Ok(())
    }

    /// Second-order rows of point k.
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

/// Appends the jerk rows of one point, δ into the interval, to `out`: for every joint with a
/// finite jerk limit, `±g + c·x(δ) ≤ 1.5·J/√x̄` with `c = J/(2x̄^{3/2})`. `shrink` scales the
/// limits (1 for gridpoints, slightly below 1 at cuts).
#[allow(clippy::too_many_arguments)]
pub(crate) fn jerk_rows(
    d1: &[f64],
    d2: &[f64],
    d3: &[f64],
    jerk: &[f64],
    delta: f64,
    xbar: f64,
    shrink: f64,
    out: &mut Vec<Row>,
) {
    let xbar = xbar.max(f64::MIN_POSITIVE.sqrt());
    let rs = xbar.sqrt();
    let (e1, e2) = (2.0 * delta, delta * delta);
    for j in 0..d1.len() {
        let lim = jerk[j] * shrink;
        if !lim.is_finite() {
            continue;
        }
        let gx = d3[j];
        let gu = e1 * d3[j] + 3.0 * d2[j];
        let gv = e2 * d3[j] + 3.0 * delta * d2[j] + d1[j];
        let rhs = 1.5 * lim / rs;
        let c = 0.5 * lim / (xbar * rs);
        out.push([gx + c, gu + e1 * c, gv + e2 * c, rhs]);
        out.push([-gx + c, -gu + e1 * c, -gv + e2 * c, rhs]);
    }
}

/// Appends the second-order rows and the velocity bound of point `k` of `pts`, δ into the
/// interval, to `out`; limits scaled by `shrink` (right-hand sides that are positive, and
/// x_max by shrink²).
pub(crate) fn second_order_rows(
    pts: &Points,
    k: usize,
    delta: f64,
    shrink: f64,
    out: &mut Vec<Row>,
) {
    let (e1, e2) = (2.0 * delta, delta * delta);
    for &[al, be, ga] in pts.rows_of(k) {
        let g = if ga > 0.0 { ga * shrink } else { ga };
        out.push([be, al + e1 * be, al * delta + be * e2, g]);
    }
    let xm = pts.xmax[k];
    if xm.is_finite() {
        out.push([1.0, e1, e2, xm * shrink * shrink]);
    }
    if pts.xmin[k] > 0.0 {
        out.push([-1.0, -e1, -e2, -pts.xmin[k]]);
    }
}
