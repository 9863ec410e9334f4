//! One solve on a fixed grid: the discretized problem, its rounds of linearization and
//! certification, and the rest intervals' bounds.
//!
//! # Rounds
//! A round builds every stage's rows from the current reference x̄ (the tangent point of the
//! jerk rows and the shape of every interval), runs the backward and forward passes and
//! certifies every middle interval ([`super::certify`]). Then x̄ becomes the new solution
//! and the next round starts, until the certification is clean and the duration has
//! settled. Each round's solution is feasible at its check points whatever x̄ is (the tangent
//! rows are conservative); x̄ only decides how much of the limit the rows can use.
//!
//! # What happens between check points
//! Every middle interval has rows at its two ends and its midpoint. A limit that is reached
//! at a check point can still be exceeded a little between them (by a relative amount of
//! second order in the interval's length). The certification measures, for each joint and
//! limit on each interval, the worst value on the interval (`ratio`) and the worst at the
//! check points (`check`), relative to the limit. Where the interval exceeds the limit:
//! - a **small bump** (ratio/check − 1 ≤ `BUMP`): the limit's rows on that interval are
//!   scaled by κ = check/ratio (with a quarter of the excess as margin), which removes the
//!   excess for the same shape of the constraint along the interval, without adding rows;
//! - otherwise a **cut**: the rows of that joint and limit are added at the worst point.
//!
//! x falling to zero inside an interval, and the extra constraints (checked by sampling),
//! are handled by cuts.

use super::certify::{self, Cubic, Finding, IntervalState, JointRange, Kind};
use super::discretize::{
    acceleration_rows, extra_rows, jerk_rows, joint_xmax, velocity_row, Points, Row,
};
use super::law::JerkProfile;
use super::mesh::Grid;
use super::polygon::Polygon;
use super::shape::{At, Shape};
use super::solve::{PassError, Passes, StageSource};
use crate::error::{Error, Result};
use crate::topp::constraint::{Constraint, ConstraintRows, PathPoint};
use crate::Path;

/// Limits at cuts are met with this relative margin, so that a cut placed at the worst point
/// of an interval also covers its neighbourhood after the next solve.
const CUT_SHRINK: f64 = 1.0 - 1e-6;

/// Relative excess accepted between gridpoints (rounding of the certification itself).
pub(crate) const CERT_TOL: f64 = 1e-9;

/// Where x = ṡ² fell to zero inside an interval, a cut requires x there to be at least this
/// fraction of x at both of the interval's ends (rows linear and homogeneous in the state: a
/// lower bound on x itself, taken from one round's solution, could contradict the next
/// round's tighter rows and empty the controllable sets).
const POSITIVE_FRACTION: f64 = 0.25;

/// Largest relative bump (interval maximum over check-point maximum, minus 1) removed by
/// scaling the limit rather than by a cut.
const BUMP: f64 = 1e-3;

/// A point inside an interval where one joint's limit (or the extra constraints, or x > 0)
/// gets rows.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cut {
    pub(crate) interval: usize,
    pub(crate) delta: f64,
    pub(crate) joint: usize,
    pub(crate) kind: Kind,
}

/// The problem on one grid.
pub(crate) struct Problem<'a, 'c, P: Path> {
    path: &'a P,
    /// Constraints other than joint velocity and acceleration (checked by sampling).
    extra: &'a [Box<dyn Constraint + 'c>],
    ranges: &'a [JointRange],
    /// Gridpoints, midpoints (one per interval) and cuts.
    g: Points,
    m: Points,
    c: Points,
    cuts: Vec<Cut>,
    /// Cuts of interval i: `cut_list[cut_off[i]..cut_off[i+1]]`.
    cut_off: Vec<usize>,
    cut_list: Vec<usize>,
    /// The reference x̄ at gridpoints, midpoints and cuts.
    xbar: Vec<f64>,
    xbar_m: Vec<f64>,
    xbar_c: Vec<f64>,
    /// Shape of every interval (from x̄).
    shape: Vec<Shape>,
    /// Limit scale of each (interval, joint): velocity, acceleration, jerk.
    kappa: Vec<[f64; 3]>,
    /// Taylor data of each joint at each interval's start, when the path is a cubic there.
    taylor: Vec<Cubic>,
    cubic: Vec<bool>,
    /// K_i before its stage: the box and the gridpoint's rows.
    start: Vec<Polygon>,
    /// Rows of each stage, rebuilt every round: `rows[row_off[i]..row_off[i+1]]`.
    rows: Vec<Row>,
    row_off: Vec<usize>,
    w_first: f64,
    w_last: f64,
}

/// What one solve found.
pub(crate) struct Solved {
    pub(crate) profile: JerkProfile,
    pub(crate) rounds: usize,
    pub(crate) worst: f64,
    pub(crate) cuts: usize,
    pub(crate) tightened: usize,
    pub(crate) sampled_intervals: usize,
}

/// The reference a problem starts from: x̄ at gridpoints and midpoints.
pub(crate) struct Reference {
    pub(crate) grid: Vec<f64>,
    pub(crate) mid: Vec<f64>,
}

impl<'a, 'c, P: Path> Problem<'a, 'c, P> {
    /// Evaluates the path and the constraints on `grid`; `reference` is the first x̄, `xbox`
    /// bounds x at each gridpoint and `ubox` bounds |u|.
    pub(crate) fn new(
        path: &'a P,
        extra: &'a [Box<dyn Constraint + 'c>],
        ranges: &'a [JointRange],
        grid: &Grid,
        reference: Reference,
        xbox: &[f64],
        ubox: f64,
    ) -> Result<Self> {
        let n = path.dim();
        let s = &grid.s;
        let nn = s.len() - 1;
        let mut g = Points::new(n);
        for (i, &si) in s.iter().enumerate() {
            let left = (i > 0 && grid.brk[i]).then(|| si - 1e-9 * (si - s[i - 1]));
            g.push(path, extra, si, left)?;
        }
        let mut m = Points::new(n);
        for i in 0..nn {
            m.push(path, extra, 0.5 * (s[i] + s[i + 1]), None)?;
        }
        let polynomial = path.piecewise_degree().is_some_and(|d| d <= 3);
        let mut taylor = Vec::with_capacity(nn * n);
        for i in 0..nn {
            let h = 0.5 * (s[i + 1] - s[i]);
            let (d1, d2, d3) = (m.d1(i), m.d2(i), m.d3r(i));
            for j in 0..n {
                taylor.push(Cubic {
                    a: d1[j] - d2[j] * h + 0.5 * d3[j] * h * h,
                    b: d2[j] - d3[j] * h,
                    c: d3[j],
                });
            }
        }
        let shape = (0..nn)
            .map(|i| Shape::new(reference.grid[i], reference.grid[i + 1], s[i + 1] - s[i]))
            .collect();
        let mut p = Problem {
            path,
            extra,
            ranges,
            g,
            m,
            c: Points::new(n),
            cuts: Vec::new(),
            cut_off: vec![0; nn + 1],
            cut_list: Vec::new(),
            xbar: reference.grid,
            xbar_m: reference.mid,
            xbar_c: Vec::new(),
            shape,
            kappa: vec![[1.0; 3]; nn * n],
            taylor,
            cubic: vec![polynomial; nn],
            start: Vec::with_capacity(nn + 1),
            rows: Vec::new(),
            row_off: Vec::new(),
            w_first: 0.0,
            w_last: 0.0,
        };
        for i in 0..=nn {
            let set = p.start_polygon(i, xbox[i], ubox);
            p.start.push(set);
        }
        p.w_first = p.rest_bound(true);
        p.w_last = p.rest_bound(false);
        Ok(p)
    }

    fn nint(&self) -> usize {
        self.g.len() - 1
    }

    fn len(&self, i: usize) -> f64 {
        self.g.s[i + 1] - self.g.s[i]
    }

    /// The box, joint velocity and acceleration and the extra rows at gridpoint i.
    fn start_polygon(&self, i: usize, xbox: f64, ubox: f64) -> Polygon {
        let mut scratch = Vec::new();
        let mut p = Polygon::rect(0.0, xbox, -ubox, ubox);
        let (d1, d2) = (self.g.d1(i), self.g.d2(i));
        let mut xmax = self.g.xmax[i];
        for (j, lim) in self.ranges.iter().enumerate() {
            xmax = xmax.min(joint_xmax(d1[j], lim, 1.0));
        }
        let mut rows = Vec::new();
        for (j, lim) in self.ranges.iter().enumerate() {
            acceleration_rows(d1[j], d2[j], lim, 1.0, &At::start(1.0), &mut rows);
        }
        for [ax, au, _, c] in rows {
            p.clip([ax, au], c, &mut scratch);
        }
        for &[al, be, ga] in self.g.rows_of(i) {
            p.clip([be, al], ga, &mut scratch);
        }
        if xmax.is_finite() {
            p.clip([1.0, 0.0], xmax, &mut scratch);
        }
        if self.g.xmin[i] > 0.0 {
            p.clip([-1.0, 0.0], -self.g.xmin[i], &mut scratch);
        }
        p
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
        let mut order: Vec<usize> = (0..self.cuts.len()).collect();
        order.sort_by_key(|&a| self.cuts[a].interval);
        self.cut_off.clear();
        self.cut_off.resize(nn + 1, 0);
        for &k in &order {
            self.cut_off[self.cuts[k].interval + 1] += 1;
        }
        for i in 0..nn {
            self.cut_off[i + 1] += self.cut_off[i];
        }
        self.cut_list = order;
    }

    /// Adds a cut (x̄ there from the current solution).
    fn add_cut(&mut self, cut: Cut, xbar: f64) -> Result<()> {
        let s = self.g.s[cut.interval] + cut.delta;
        self.c.push(self.path, self.extra, s, None)?;
        self.cuts.push(cut);
        self.xbar_c.push(xbar);
        Ok(())
    }

    /// Rebuilds the rows of every middle stage from the current x̄, shapes, κ and cuts.
    fn build_rows(&mut self) {
        let nn = self.nint();
        let n = self.g.n;
        let mut rows = std::mem::take(&mut self.rows);
        rows.clear();
        self.row_off.clear();
        self.row_off.resize(nn + 1, 0);
        for i in 1..nn - 1 {
            self.row_off[i] = rows.len();
            let len = self.len(i);
            let sh = self.shape[i];
            let (a0, am, a1) = (sh.at(0.0), sh.at(0.5 * len), sh.at(len));
            let (g, m) = (&self.g, &self.m);
            let mut xm_mid = m.xmax[i];
            for (j, lim) in self.ranges.iter().enumerate() {
                let [kv, ka, kj] = self.kappa[i * n + j];
                let d0 = [g.d1(i)[j], g.d2(i)[j], g.d3r(i)[j]];
                let dm = [m.d1(i)[j], m.d2(i)[j], m.d3r(i)[j]];
                let d1 = [g.d1(i + 1)[j], g.d2(i + 1)[j], g.d3l(i + 1)[j]];
                jerk_rows(d0, lim.j, kj, &a0, self.xbar[i], &mut rows);
                jerk_rows(dm, lim.j, kj, &am, self.xbar_m[i], &mut rows);
                jerk_rows(d1, lim.j, kj, &a1, self.xbar[i + 1], &mut rows);
                acceleration_rows(dm[0], dm[1], lim, ka, &am, &mut rows);
                if ka < 1.0 {
                    acceleration_rows(d0[0], d0[1], lim, ka, &a0, &mut rows);
                    acceleration_rows(d1[0], d1[1], lim, ka, &a1, &mut rows);
                }
                xm_mid = xm_mid.min(joint_xmax(dm[0], lim, kv));
                if kv < 1.0 {
                    velocity_row(d0[0], lim, kv, &a0, &mut rows);
                    velocity_row(d1[0], lim, kv, &a1, &mut rows);
                }
            }
            if xm_mid.is_finite() {
                rows.push([1.0, am.e1, am.e2, xm_mid]);
            }
            if !self.extra.is_empty() {
                extra_rows(m, i, 1.0, &am, &mut rows);
            }
            for &k in &self.cut_list[self.cut_off[i]..self.cut_off[i + 1]] {
                let cut = self.cuts[k];
                let at = sh.at(cut.delta);
                let c = &self.c;
                let j = cut.joint;
                let lim = &self.ranges[j];
                let [kv, ka, kj] = self.kappa[i * n + j];
                match cut.kind {
                    Kind::Jerk => {
                        let d = [c.d1(k)[j], c.d2(k)[j], c.d3r(k)[j]];
                        jerk_rows(d, lim.j, kj * CUT_SHRINK, &at, self.xbar_c[k], &mut rows);
                    }
                    Kind::Acceleration => {
                        let (d1, d2) = (c.d1(k)[j], c.d2(k)[j]);
                        acceleration_rows(d1, d2, lim, ka * CUT_SHRINK, &at, &mut rows);
                    }
                    Kind::Velocity => {
                        velocity_row(c.d1(k)[j], lim, kv * CUT_SHRINK, &at, &mut rows);
                    }
                    Kind::Extra => extra_rows(c, k, CUT_SHRINK, &at, &mut rows),
                    Kind::Positive => {
                        // x(δ) ≥ f·x_i and x(δ) ≥ f·x_{i+1}: homogeneous, so rest stays
                        // feasible and the controllable sets cannot become empty.
                        let f = POSITIVE_FRACTION;
                        rows.push([f - 1.0, -at.e1, -at.e2, 0.0]);
                        rows.push([f - 1.0, f * a1.e1 - at.e1, f * a1.e2 - at.e2, 0.0]);
                    }
                }
            }
        }
        self.row_off[nn - 1] = rows.len();
        self.row_off[nn] = rows.len();
        self.rows = rows;
    }

    /// The state of middle interval i in a solution.
    fn state(&self, x: &[f64], u: &[f64], v: &[f64], i: usize) -> IntervalState {
        IntervalState {
            x: x[i],
            u: u[i],
            v: v[i],
            len: self.len(i),
            shape: self.shape[i],
        }
    }

    /// The check points of interval i for (joint, kind): ends, midpoint and its cuts.
    fn check_ratio(&self, st: &IntervalState, i: usize, j: usize, kind: Kind) -> f64 {
        let o = kind as usize;
        let lim = &self.ranges[j];
        let (g, m) = (&self.g, &self.m);
        let at = |d: f64, der: [f64; 3]| {
            certify::point_joint(st.x_at(d), st.u_at(d), st.w_at(d), der, lim)[o]
        };
        let mut r = at(0.0, [g.d1(i)[j], g.d2(i)[j], g.d3r(i)[j]])
            .max(at(0.5 * st.len, [m.d1(i)[j], m.d2(i)[j], m.d3r(i)[j]]))
            .max(at(
                st.len,
                [g.d1(i + 1)[j], g.d2(i + 1)[j], g.d3l(i + 1)[j]],
            ));
        for &k in &self.cut_list[self.cut_off[i]..self.cut_off[i + 1]] {
            let cut = &self.cuts[k];
            if cut.joint == j && cut.kind == kind {
                let c = &self.c;
                r = r.max(at(cut.delta, [c.d1(k)[j], c.d2(k)[j], c.d3r(k)[j]]));
            }
        }
        r
    }

    /// The findings of middle interval i (limits above 1 + [`CERT_TOL`]) appended to `out`;
    /// returns the worst ratio − 1 and whether the interval was sampled.
    fn certify_interval(
        &self,
        st: &IntervalState,
        i: usize,
        buf: &mut Scratch,
        out: &mut Vec<Finding>,
    ) -> (f64, bool) {
        let n = self.g.n;
        let (xm, at) = certify::min_x(st);
        if xm.is_nan() || xm <= 0.0 {
            out.push(Finding {
                interval: i,
                joint: 0,
                kind: Kind::Positive,
                ratio: f64::INFINITY,
                check: 0.0,
                delta: at,
            });
            return (f64::INFINITY, false);
        }
        let mut worst = f64::NEG_INFINITY;
        let sampled = !self.cubic[i];
        let mut push = |j: usize, o: usize, r: f64, delta: f64, out: &mut Vec<Finding>| {
            worst = worst.max(r - 1.0);
            if r > 1.0 + CERT_TOL {
                let kind = [Kind::Velocity, Kind::Acceleration, Kind::Jerk][o];
                out.push(Finding {
                    interval: i,
                    joint: j,
                    kind,
                    ratio: r,
                    check: self.check_ratio(st, i, j, kind),
                    delta,
                });
            }
        };
        if !sampled {
            for j in 0..n {
                let r = certify::cubic_joint(st, &self.taylor[i * n + j], &self.ranges[j]);
                for (o, (ratio, delta)) in r.into_iter().enumerate() {
                    push(j, o, ratio, delta, out);
                }
            }
        }
        if sampled || !self.extra.is_empty() {
            let (best, extra_worst) = self.sample_interval(st, i, sampled, buf);
            for (k, &(r, delta)) in best.iter().enumerate() {
                push(k / 3, k % 3, r, delta, out);
            }
            if !self.extra.is_empty() {
                worst = worst.max(extra_worst.0);
                if extra_worst.0 > CERT_TOL {
                    out.push(Finding {
                        interval: i,
                        joint: 0,
                        kind: Kind::Extra,
                        ratio: 1.0 + extra_worst.0,
                        check: 0.0,
                        delta: extra_worst.1,
                    });
                }
            }
        }
        (worst, sampled)
    }

    /// Samples middle interval i: the largest ratio to each (joint, limit) and where it
    /// occurs, `3 · joint + order` (only when `sampled`, i.e. the path is not a cubic there),
    /// and the largest relative excess of the extra constraints and where (none when there
    /// are none).
    fn sample_interval(
        &self,
        st: &IntervalState,
        i: usize,
        sampled: bool,
        buf: &mut Scratch,
    ) -> (Vec<(f64, f64)>, (f64, f64)) {
        let n = self.g.n;
        buf.resize(n);
        let mut best = vec![(f64::NEG_INFINITY, 0.0); if sampled { 3 * n } else { 0 }];
        let mut extra_worst = (f64::NEG_INFINITY, 0.0);
        let samples = if self.extra.is_empty() {
            certify::SAMPLES
        } else {
            certify::EXTRA_SAMPLES
        };
        for k in 0..=samples + 1 {
            let delta = st.len * k as f64 / (samples + 1) as f64;
            let s = self.g.s[i] + delta;
            let (xs, us) = (st.x_at(delta), st.u_at(delta));
            self.path.eval_derivatives(s, &mut buf.d1, &mut buf.d2);
            if sampled {
                self.path.eval(s, 3, &mut buf.d3);
                for j in 0..n {
                    let d = [buf.d1[j], buf.d2[j], buf.d3[j]];
                    let r = certify::point_joint(xs, us, st.w_at(delta), d, &self.ranges[j]);
                    for o in 0..3 {
                        if r[o] > best[3 * j + o].0 {
                            best[3 * j + o] = (r[o], delta);
                        }
                    }
                }
            }
            if !self.extra.is_empty() && k > 0 && k <= samples {
                self.path.eval(s, 0, &mut buf.q);
                let p = PathPoint {
                    s,
                    q: &buf.q,
                    dq: &buf.d1,
                    ddq: &buf.d2,
                };
                for c in self.extra {
                    buf.cr.clear();
                    c.write(&p, &mut buf.cr);
                    let e = buf.cr.relative_excess(us, xs);
                    if e > extra_worst.0 {
                        extra_worst = (e, delta);
                    }
                }
            }
        }
        (best, extra_worst)
    }

    /// Rounds of backward/forward passes, certification and re-linearization on this grid,
    /// until every interval is certified and the duration has settled (relative change ≤
    /// `settle`), at most `max_rounds`.
    pub(crate) fn solve(&mut self, settle: f64, max_rounds: usize) -> Result<Solved> {
        let mut passes = Passes::default();
        let (mut x, mut u, mut v) = (Vec::new(), Vec::new(), Vec::new());
        let mut last_t = f64::INFINITY;
        let mut buf = Scratch::default();
        let mut findings = Vec::new();
        let mut tightened = 0;
        for round in 1..=max_rounds {
            self.index_cuts();
            self.build_rows();
            passes.backward(self).map_err(|e| self.explain(e))?;
            passes
                .forward(self, &mut x, &mut u, &mut v)
                .map_err(|e| self.explain(e))?;
            findings.clear();
            let (worst, sampled, big_t) = self.certify_all(&x, &u, &v, &mut buf, &mut findings);
            let settled = (last_t - big_t).abs() <= settle * big_t;
            if (findings.is_empty() && settled) || round == max_rounds {
                let has_gap = findings.iter().any(|f| f.kind == Kind::Positive);
                if !has_gap {
                    let profile = JerkProfile::new(
                        self.g.s.clone(),
                        x.clone(),
                        u.clone(),
                        v.clone(),
                        self.shape.clone(),
                    )?;
                    return Ok(Solved {
                        profile,
                        rounds: round,
                        worst,
                        cuts: self.cuts.len(),
                        tightened,
                        sampled_intervals: sampled,
                    });
                }
                if round == max_rounds {
                    return Err(Error::Infeasible(format!(
                        "the path velocity vanishes inside an interval after {round} rounds"
                    )));
                }
            }
            last_t = big_t;
            // Limits that failed: scale or cut (on the solution's own shapes).
            let fs = std::mem::take(&mut findings);
            for f in &fs {
                tightened += self.handle(f, &x, &u, &v)? as usize;
            }
            findings = fs;
            self.relinearize(&x, &u, &v);
        }
        unreachable!("the loop returns in its last round")
    }

    /// Certifies every middle interval of a solution, appending the findings to `out`;
    /// returns the worst ratio − 1, the number of sampled intervals and the duration of the
    /// middle intervals.
    fn certify_all(
        &self,
        x: &[f64],
        u: &[f64],
        v: &[f64],
        buf: &mut Scratch,
        out: &mut Vec<Finding>,
    ) -> (f64, usize, f64) {
        let nn = self.nint();
        let mut worst: f64 = f64::NEG_INFINITY;
        let mut sampled = 0;
        let mut big_t = 0.0;
        for i in 1..nn - 1 {
            let st = self.state(x, u, v, i);
            let (e, smp) = self.certify_interval(&st, i, buf, out);
            sampled += smp as usize;
            worst = worst.max(e);
            big_t += super::law::Cubic {
                x0: st.x,
                u: st.u,
                v: st.v,
                shape: st.shape,
            }
            .time(st.len, 2);
        }
        (worst, sampled, big_t)
    }

    /// Re-linearizes at a solution: the references x̄ at gridpoints, midpoints and cuts and
    /// the interval shapes follow it.
    fn relinearize(&mut self, x: &[f64], u: &[f64], v: &[f64]) {
        let nn = self.nint();
        for i in 0..nn {
            let len = self.len(i);
            if (1..nn - 1).contains(&i) {
                let st = self.state(x, u, v, i);
                // Not below the smaller end: x dipping towards zero inside an interval
                // would put the jerk rows' tangent there, which then forbids any x above
                // three times that dip (the velocity would have to vanish).
                self.xbar_m[i] = st.x_at(0.5 * len).max(x[i].min(x[i + 1])).max(1e-300);
            } else {
                self.xbar_m[i] = 0.5 * (x[i] + x[i + 1]);
            }
        }
        for k in 0..self.cuts.len() {
            let cut = self.cuts[k];
            let st = self.state(x, u, v, cut.interval);
            let ends = x[cut.interval].min(x[cut.interval + 1]);
            self.xbar_c[k] = st.x_at(cut.delta).max(ends).max(1e-300);
        }
        self.xbar.copy_from_slice(x);
        for i in 1..nn - 1 {
            self.shape[i] = Shape::new(x[i], x[i + 1], self.len(i));
        }
    }

    /// Acts on one finding: scales the limit (returns true) or adds a cut.
    fn handle(&mut self, f: &Finding, x: &[f64], u: &[f64], v: &[f64]) -> Result<bool> {
        let n = self.g.n;
        let i = f.interval;
        let st = self.state(x, u, v, i);
        let len = st.len;
        let d = f.delta.clamp(1e-6 * len, (1.0 - 1e-6) * len);
        // The tangent point of the cut's jerk rows: not below the smaller end (see `solve`).
        let xbar = st.x_at(d).max(x[i].min(x[i + 1])).max(1e-300);
        match f.kind {
            Kind::Positive => {
                self.add_cut(
                    Cut {
                        interval: i,
                        delta: d,
                        joint: 0,
                        kind: Kind::Positive,
                    },
                    xbar,
                )?;
                Ok(false)
            }
            Kind::Extra => {
                self.add_cut(
                    Cut {
                        interval: i,
                        delta: d,
                        joint: 0,
                        kind: Kind::Extra,
                    },
                    xbar,
                )?;
                Ok(false)
            }
            kind => {
                let o = kind as usize;
                let bump = if f.check > 0.0 {
                    f.ratio / f.check - 1.0
                } else {
                    f64::INFINITY
                };
                let k = &mut self.kappa[i * n + f.joint][o];
                if bump <= BUMP {
                    // The checks then hold κ, the interval κ·(1 + bump) < 1.
                    *k = k.min((1.0 - CERT_TOL) / (1.0 + 1.25 * bump));
                    Ok(true)
                } else {
                    self.add_cut(
                        Cut {
                            interval: i,
                            delta: d,
                            joint: f.joint,
                            kind,
                        },
                        xbar,
                    )?;
                    Ok(false)
                }
            }
        }
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
    cr: ConstraintRows,
}

impl Scratch {
    fn resize(&mut self, n: usize) {
        self.q.resize(n, 0.0);
        self.d1.resize(n, 0.0);
        self.d2.resize(n, 0.0);
        self.d3.resize(n, 0.0);
    }
}

impl<P: Path> StageSource for Problem<'_, '_, P> {
    fn intervals(&self) -> usize {
        self.nint()
    }

    fn delta(&self, i: usize) -> f64 {
        self.len(i)
    }

    fn transition(&self, i: usize) -> (f64, f64) {
        let len = self.len(i);
        let sh = &self.shape[i];
        (sh.psi2(len), sh.phi(len))
    }

    fn start_set(&self, i: usize) -> &Polygon {
        &self.start[i]
    }

    fn stage_rows(&self, i: usize) -> &[Row] {
        &self.rows[self.row_off[i]..self.row_off[i + 1]]
    }

    fn first_rest(&self) -> f64 {
        self.w_first
    }

    fn last_rest(&self) -> f64 {
        self.w_last
    }
}
