//! One solve on a fixed grid: the discretized problem, its rounds of linearization and
//! certification, and the rest intervals' bounds.

use super::certify::{self, Excess, IntervalState, JointRange};
use super::discretize::{jerk_rows, second_order_rows, Points, Row};
use super::law::JerkProfile;
use super::polygon::{Polygon, Pt};
use super::solve::{PassError, Passes, StageSource};
use crate::error::{Error, Result};
use crate::topp::constraint::Constraint;
use crate::Path;

/// Limits at cuts are met with this relative margin, so that a cut placed at the worst point
/// of an interval also covers its neighbourhood after the next solve.
const CUT_SHRINK: f64 = 1.0 - 1e-6;

/// Relative excess accepted between gridpoints (rounding of the certification itself).
pub(crate) const CERT_TOL: f64 = 1e-7;

/// Rounds of linearization and certification at most.
pub(crate) const MAX_ROUNDS: usize = 12;

/// The problem on one grid.
pub(crate) struct Problem<'a, 'c, P: Path> {
    pub(crate) path: &'a P,
    pub(crate) cons: &'a [Box<dyn Constraint + 'c>],
    /// Constraints that are neither joint velocity nor joint acceleration (checked by sampling).
    pub(crate) extra: &'a [Box<dyn Constraint + 'c>],
    pub(crate) jerk: &'a [f64],
    pub(crate) ranges: &'a [JointRange],
    pub(crate) g: Points,
    /// Cuts: points inside intervals, with their interval and offset δ.
    pub(crate) c: Points,
    pub(crate) cut_at: Vec<(usize, f64)>,
    /// Cuts of interval i: `cut_list[cut_off[i]..cut_off[i+1]]`.
    cut_off: Vec<usize>,
    cut_list: Vec<usize>,
    pub(crate) xbar: Vec<f64>,
    pub(crate) xbar_cut: Vec<f64>,
    pub(crate) xbox: Vec<f64>,
    pub(crate) ubox: f64,
    w_first: f64,
    w_last: f64,
    /// Whether each interval is a cubic in s (exact certification).
    cubic: Vec<bool>,
}

/// What one solve found.
pub(crate) struct Solved {
    pub(crate) profile: JerkProfile,
    pub(crate) rounds: usize,
    pub(crate) worst: f64,
    pub(crate) cuts: usize,
    pub(crate) sampled_intervals: usize,
}

impl<'a, 'c, P: Path> Problem<'a, 'c, P> {
    /// Evaluates the path and the constraints on `grid`; `xbar` (one per gridpoint) is the
    /// first linearization point and `xbox` bounds x at each gridpoint.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        path: &'a P,
        cons: &'a [Box<dyn Constraint + 'c>],
        extra: &'a [Box<dyn Constraint + 'c>],
        jerk: &'a [f64],
        ranges: &'a [JointRange],
        grid: &[f64],
        xbar: Vec<f64>,
        xbox: Vec<f64>,
        ubox: f64,
    ) -> Result<Self> {
        let n = path.dim();
        let mut g = Points::new(n);
        for (i, &s) in grid.iter().enumerate() {
            let left = (i > 0).then(|| s - 1e-9 * (s - grid[i - 1]));
            g.push(path, cons, s, left)?;
        }
        let mut p = Problem {
            path,
            cons,
            extra,
            jerk,
            ranges,
            g,
            c: Points::new(n),
            cut_at: Vec::new(),
            cut_off: vec![0; grid.len()],
            cut_list: Vec::new(),
            xbar,
            xbar_cut: Vec::new(),
            xbox,
            ubox,
            w_first: 0.0,
            w_last: 0.0,
            cubic: Vec::new(),
        };
        p.w_first = p.rest_bound(true);
        p.w_last = p.rest_bound(false);
        p.cubic = (0..grid.len() - 1)
            .map(|i| p.is_cubic(i))
            .collect::<Result<_>>()?;
        Ok(p)
    }

    fn nint(&self) -> usize {
        self.g.len() - 1
    }

    /// Whether the Taylor cubic of the path from s_i reproduces σ′, σ″ at s_{i+1} and σ‴ at the
    /// midpoint (1e-9 relative).
    fn is_cubic(&self, i: usize) -> Result<bool> {
        let n = self.g.n;
        let d = self.g.s[i + 1] - self.g.s[i];
        let (a, b, c) = (self.g.d1(i), self.g.d2(i), self.g.d3r(i));
        let (a1, b1, c1) = (self.g.d1(i + 1), self.g.d2(i + 1), self.g.d3l(i + 1));
        let mut mid = vec![0.0; n];
        self.path.eval(self.g.s[i] + 0.5 * d, 3, &mut mid);
        for j in 0..n {
            let scale = a[j].abs() + b[j].abs() * d + c[j].abs() * d * d + 1e-300;
            let e1 = (a[j] + b[j] * d + 0.5 * c[j] * d * d - a1[j]).abs() / scale;
            let s2 = b[j].abs() + c[j].abs() * d + 1e-300;
            let e2 = (b[j] + c[j] * d - b1[j]).abs() / s2;
            let s3 = c[j].abs().max(1e-300) + b[j].abs() / d.max(1e-300) * 1e-3;
            let e3 = (c1[j] - c[j]).abs().max((mid[j] - c[j]).abs()) / s3;
            if e1 > 1e-9 || e2 > 1e-9 || e3 > 1e-9 {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// Largest |u| at gridpoint 1 (first) or N−1 (last) for which the rest interval keeps
    /// every limit: each term of q̇, q̈, q⃛ bounded by its largest value on the interval
    /// (ṡ, |s̈| and the path jerk are monotone in time there).
    fn rest_bound(&self, first: bool) -> f64 {
        let nn = self.nint();
        let (k0, k1) = if first { (0, 1) } else { (nn - 1, nn) };
        let d = self.g.s[k1] - self.g.s[k0];
        let h = 1.5 * d;
        let mut w = f64::INFINITY;
        for (j, lim) in self.ranges.iter().enumerate() {
            let (a0, a1) = (self.g.d1(k0)[j], self.g.d1(k1)[j]);
            let d3 = self.g.d3r(k0)[j].abs().max(self.g.d3l(k1)[j].abs());
            let dev = d3 * d * d / 8.0;
            let (d1lo, d1hi) = (a0.min(a1) - dev, a0.max(a1) + dev);
            let (b0, b1) = (self.g.d2(k0)[j], self.g.d2(k1)[j]);
            let (d2lo, d2hi) = (b0.min(b1) - 0.5 * d3 * d, b0.max(b1) + 0.5 * d3 * d);
            // Velocity: ṡ ≤ √(h·w).
            if d1hi > 0.0 {
                w = w.min(lim.v.1 * lim.v.1 / (h * d1hi * d1hi));
            }
            if d1lo < 0.0 {
                w = w.min(lim.v.0 * lim.v.0 / (h * d1lo * d1lo));
            }
            // Acceleration: σ″ṡ² + σ′s̈ with ṡ² ∈ [0, h·w], s̈ between 0 and ±w.
            let (push_hi, push_lo) = if first {
                (d1hi.max(0.0), (-d1lo).max(0.0))
            } else {
                ((-d1lo).max(0.0), d1hi.max(0.0))
            };
            let up = h * d2hi.max(0.0) + push_hi;
            if up > 0.0 {
                w = w.min(lim.a.1 / up);
            }
            let down = -h * d2lo.min(0.0) + push_lo;
            if down > 0.0 {
                w = w.min(-lim.a.0 / down);
            }
            // Jerk: |σ‴|ṡ³ + 3|σ″|ṡ|s̈| + |σ′||s⃛| ≤ w^1.5·B.
            if lim.j.is_finite() {
                let d1m = d1lo.abs().max(d1hi.abs());
                let d2m = d2lo.abs().max(d2hi.abs());
                let bb = d3 * h.powf(1.5) + 3.0 * d2m * h.sqrt() + d1m / (6.0 * d).sqrt();
                if bb > 0.0 {
                    w = w.min((lim.j / bb).powf(2.0 / 3.0));
                }
            }
        }
        // Other second-order rows at both ends of the interval, at the corners of the box of
        // (ṡ², s̈) the interval sweeps.
        for k in [k0, k1] {
            for &[al, be, ga] in self.g.rows_of(k) {
                if ga < 0.0 {
                    return 0.0;
                }
                let coef = h * be.max(0.0) + if first { al.max(0.0) } else { (-al).max(0.0) };
                if coef > 0.0 {
                    w = w.min(ga / coef);
                }
            }
            if self.g.xmax[k].is_finite() {
                w = w.min(self.g.xmax[k] / h);
            }
        }
        w
    }

    /// Rebuilds the per-interval cut index.
    fn index_cuts(&mut self) {
        let nn = self.nint();
        let mut order: Vec<usize> = (0..self.cut_at.len()).collect();
        order.sort_by(|&a, &b| {
            self.cut_at[a]
                .0
                .cmp(&self.cut_at[b].0)
                .then(self.cut_at[a].1.total_cmp(&self.cut_at[b].1))
        });
        self.cut_off.clear();
        self.cut_off.resize(nn + 1, 0);
        for &k in &order {
            self.cut_off[self.cut_at[k].0 + 1] += 1;
        }
        for i in 0..nn {
            self.cut_off[i + 1] += self.cut_off[i];
        }
        self.cut_list = order;
    }

    /// Adds a cut at δ into interval i (x̄ there from the current solution).
    fn add_cut(&mut self, i: usize, delta: f64, xbar: f64) -> Result<()> {
        let s = self.g.s[i] + delta;
        self.c.push(self.path, self.cons, s, Some(s))?;
        self.cut_at.push((i, delta));
        self.xbar_cut.push(xbar);
        Ok(())
    }

    /// The state of middle interval i in a solution.
    fn state(&self, x: &[f64], u: &[f64], i: usize) -> IntervalState {
        let d = self.g.s[i + 1] - self.g.s[i];
        IntervalState {
            x: x[i],
            u: u[i],
            v: (u[i + 1] - u[i]) / d,
            len: d,
        }
    }

    /// The worst excess on middle interval i.
    fn certify_interval(&self, st: &IntervalState, i: usize, buf: &mut Scratch) -> (Excess, bool) {
        let n = self.g.n;
        let mut worst = Excess {
            ratio: f64::NEG_INFINITY,
            delta: 0.0,
        };
        let (xm, at) = certify::min_x(st);
        if xm <= 0.0 {
            return (
                Excess {
                    ratio: f64::INFINITY,
                    delta: at,
                },
                false,
            );
        }
        let sampled = !self.cubic[i];
        if !sampled {
            let (a, b, c) = (self.g.d1(i), self.g.d2(i), self.g.d3r(i));
            for j in 0..n {
                let e = certify::cubic_joint(st, a[j], b[j], c[j], &self.ranges[j]);
                if e.ratio > worst.ratio {
                    worst = e;
                }
            }
        }
        if sampled || !self.extra.is_empty() {
            buf.q.resize(n, 0.0);
            buf.d1.resize(n, 0.0);
            buf.d2.resize(n, 0.0);
            buf.d3.resize(n, 0.0);
            for k in 1..=certify::SAMPLES {
                let delta = st.len * k as f64 / (certify::SAMPLES + 1) as f64;
                let s = self.g.s[i] + delta;
                let (xs, us) = (st.x_at(delta), st.u_at(delta));
                if sampled {
                    self.path.eval_derivatives(s, &mut buf.d1, &mut buf.d2);
                    self.path.eval(s, 3, &mut buf.d3);
                    for j in 0..n {
                        let e = certify::point_joint(
                            xs,
                            us,
                            st.v,
                            buf.d1[j],
                            buf.d2[j],
                            buf.d3[j],
                            &self.ranges[j],
                        );
                        if e > worst.ratio {
                            worst = Excess { ratio: e, delta };
                        }
                    }
                }
                if !self.extra.is_empty() {
                    self.path.eval(s, 0, &mut buf.q);
                    self.path.eval_derivatives(s, &mut buf.d1, &mut buf.d2);
                    let p = crate::topp::constraint::PathPoint {
                        s,
                        q: &buf.q,
                        dq: &buf.d1,
                        ddq: &buf.d2,
                    };
                    for c in self.extra {
                        buf.cr.clear();
                        c.write(&p, &mut buf.cr);
                        let e = buf.cr.relative_excess(us, xs);
                        if e > worst.ratio {
                            worst = Excess { ratio: e, delta };
                        }
                    }
                }
            }
        }
        (worst, sampled)
    }

    /// Rounds of backward/forward passes, certification (cuts) and re-linearization on this
    /// grid, until every interval is certified and the duration has settled.
    pub(crate) fn solve(&mut self, settle: f64) -> Result<Solved> {
        let mut passes = Passes::default();
        let (mut x, mut u) = (Vec::new(), Vec::new());
        let mut last_t = f64::INFINITY;
        let mut buf = Scratch::default();
        let nn = self.nint();
        for round in 1..=MAX_ROUNDS {
            self.index_cuts();
            passes.backward(self).map_err(|e| self.explain(e))?;
            passes
                .forward(self, &mut x, &mut u)
                .map_err(|e| self.explain(e))?;
            let profile = JerkProfile::new(self.g.s.clone(), x.clone(), u.clone())?;
            let big_t = crate::topp::rescale::TimeLaw::duration(&profile);
            let mut worst: f64 = f64::NEG_INFINITY;
            let mut sampled = 0;
            let mut new_cuts: Vec<(usize, f64, f64)> = Vec::new();
            for i in 1..nn - 1 {
                let st = self.state(&x, &u, i);
                let (e, smp) = self.certify_interval(&st, i, &mut buf);
                sampled += smp as usize;
                worst = worst.max(e.ratio);
                if e.ratio > CERT_TOL {
                    new_cuts.push((i, e.delta, st.x_at(e.delta)));
                }
            }
            let settled = (last_t - big_t).abs() <= settle * big_t;
            if new_cuts.is_empty() && (settled || round == MAX_ROUNDS) {
                return Ok(Solved {
                    profile,
                    rounds: round,
                    worst,
                    cuts: self.cut_at.len(),
                    sampled_intervals: sampled,
                });
            }
            if round == MAX_ROUNDS {
                return Ok(Solved {
                    profile,
                    rounds: round,
                    worst,
                    cuts: self.cut_at.len(),
                    sampled_intervals: sampled,
                });
            }
            last_t = big_t;
            // Re-linearize at the new solution.
            self.xbar.copy_from_slice(&x);
            for k in 0..self.cut_at.len() {
                let (i, d) = self.cut_at[k];
                let st = self.state(&x, &u, i);
                self.xbar_cut[k] = st.x_at(d).max(1e-300);
            }
            for (i, d, xs) in new_cuts {
                // A cut on an interval end is a gridpoint already: move it inside.
                let len = self.g.s[i + 1] - self.g.s[i];
                let d = d.clamp(1e-6 * len, (1.0 - 1e-6) * len);
                self.add_cut(i, d, xs.max(1e-300))?;
                // An interval that keeps failing (its worst point moves from round to round)
                // gets its rows at a few more points.
                if round >= 3 {
                    let st = self.state(&x, &u, i);
                    for f in [0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875] {
                        self.add_cut(i, f * len, st.x_at(f * len).max(1e-300))?;
                    }
                }
            }
        }
        unreachable!("the loop returns in its last round")
    }

    /// An `Error::Infeasible` naming where a pass failed.
    fn explain(&self, e: PassError) -> Error {
        let at = |i: usize| self.g.s[i.min(self.nint())];
        match e {
            PassError::Empty(i) => Error::Infeasible(format!(
                "at s = {} (gridpoint {i} of {}): the joint velocity, acceleration and jerk limits (and any other constraint) leave no path velocity and acceleration from which the end can be reached",
                at(i),
                self.nint()
            )),
            PassError::NoStart => Error::Infeasible(format!(
                "the path cannot start moving at s = {}: the jerk and acceleration limits allow no path acceleration from rest",
                at(0)
            )),
            PassError::Lost(i) => Error::Infeasible(format!(
                "at s = {}: the forward pass left the controllable set (gridpoint {i}); the limits are too tight for the grid",
                at(i)
            )),
        }
    }
}

/// Scratch buffers of the certification.
#[derive(Default)]
struct Scratch {
    q: Vec<f64>,
    d1: Vec<f64>,
    d2: Vec<f64>,
    d3: Vec<f64>,
    cr: crate::topp::constraint::ConstraintRows,
}

impl<P: Path> StageSource for Problem<'_, '_, P> {
    fn intervals(&self) -> usize {
        self.nint()
    }

    fn delta(&self, i: usize) -> f64 {
        self.g.s[i + 1] - self.g.s[i]
    }

    fn start_set(&self, i: usize, scratch: &mut Vec<Pt>) -> Polygon {
        let mut p = Polygon::rect(0.0, self.xbox[i], -self.ubox, self.ubox);
        for &[al, be, ga] in self.g.rows_of(i) {
            p.clip([be, al], ga, scratch);
        }
        if self.g.xmax[i].is_finite() {
            p.clip([1.0, 0.0], self.g.xmax[i], scratch);
        }
        if self.g.xmin[i] > 0.0 {
            p.clip([-1.0, 0.0], -self.g.xmin[i], scratch);
        }
        p
    }

    fn stage_rows(&self, i: usize, out: &mut Vec<Row>) {
        let d = self.delta(i);
        let g = &self.g;
        jerk_rows(
            g.d1(i),
            g.d2(i),
            g.d3r(i),
            self.jerk,
            0.0,
            self.xbar[i],
            1.0,
            out,
        );
        jerk_rows(
            g.d1(i + 1),
            g.d2(i + 1),
            g.d3l(i + 1),
            self.jerk,
            d,
            self.xbar[i + 1],
            1.0,
            out,
        );
        for &k in &self.cut_list[self.cut_off[i]..self.cut_off[i + 1]] {
            let delta = self.cut_at[k].1;
            second_order_rows(&self.c, k, delta, CUT_SHRINK, out);
            jerk_rows(
                self.c.d1(k),
                self.c.d2(k),
                self.c.d3r(k),
                self.jerk,
                delta,
                self.xbar_cut[k],
                CUT_SHRINK,
                out,
            );
        }
    }

    fn first_rest(&self) -> f64 {
        self.w_first
    }

    fn last_rest(&self) -> f64 {
        self.w_last
    }
}
