//! Backward pass (controllable sets as convex polygons in (x, u)) and greedy forward pass.
//!
//! Stage i (middle interval i) has rows in (x_i, u_i, v_i) ([`super::discretize`]) and the
//! requirement that the next state (x_i + 2Δu_i + E·v_i, u_i + F·v_i) lies in K_{i+1}, with
//! E = 2ψ(Δ) and F = φ(Δ) of the interval's shape ([`super::shape`]). K_i is
//! the projection of that 3-D polytope onto (x, u), intersected with the gridpoint's own
//! second-order rows. The projection eliminates v (Fourier–Motzkin) lazily: each row bounds v
//! from above (U_k(x, u)) or below (L_l(x, u)); min_k U_k − max_l L_l is concave, so it is
//! non-negative on the polygon when it is at every vertex. A vertex where it is negative names
//! the pair (k, l) whose combination U_k ≥ L_l cuts it off; the polygon is clipped by it and
//! the test repeated. Only the pairs that shape the result are ever formed.
//!
//! The last middle stage lands on the ray of the final rest interval (x = −1.5Δ·u), which fixes
//! v: it is substituted instead of projected. Gridpoint 1 lies on the ray of the first rest
//! interval (x = 1.5Δ₀·u).
//!
//! Forward pass: from (x₁, u₁) with the largest u₁ on that ray inside K₁, each stage takes the
//! largest v (which maximises both x_{i+1} and u_{i+1}) that meets the stage rows and lands in
//! K_{i+1}.

use super::discretize::Row;
use super::polygon::{Polygon, Pt};

/// What the passes need from the problem for one stage.
pub(crate) trait StageSource {
    /// Number of intervals N (gridpoints 0..=N).
    fn intervals(&self) -> usize;
    /// Δ_i = s_{i+1} − s_i.
    fn delta(&self, i: usize) -> f64;
    /// (E, F) of middle stage i: x_{i+1} = x_i + 2Δu_i + E·v_i, u_{i+1} = u_i + F·v_i.
    fn transition(&self, i: usize) -> (f64, f64);
    /// The box and the gridpoint's own rows, as a polygon (K_i before the stage).
    fn start_set(&self, i: usize) -> &Polygon;
    /// The rows of middle stage i in (x_i, u_i, v_i).
    fn stage_rows(&self, i: usize) -> &[Row];
    /// Largest |u| at gridpoint 1 allowed by the first rest interval.
    fn first_rest(&self) -> f64;
    /// Largest |u| at gridpoint N−1 allowed by the last rest interval.
    fn last_rest(&self) -> f64;
}

/// Why a pass failed: the gridpoint where the controllable set became empty.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum PassError {
    /// K_i is empty.
    Empty(usize),
    /// The motion cannot start (K₁ meets the start ray only at rest).
    NoStart,
    /// The forward pass left the controllable sets at gridpoint i (numerical breakdown).
    Lost(usize),
}

/// Buffers of the passes, reused between rounds.
#[derive(Default)]
pub(crate) struct Passes {
    pub(crate) k: Vec<Polygon>,
    rows: Vec<Row>,
    up: Vec<Row>,
    lo: Vec<Row>,
    scratch: Vec<Pt>,
    used: Vec<bool>,
    act_u: Vec<usize>,
    act_l: Vec<usize>,
    /// Largest relative violation of a stage row accepted by the forward pass.
    pub(crate) forward_slack: f64,
}

impl Passes {
    /// Computes K_1..K_{N−1}.
    pub(crate) fn backward<S: StageSource>(&mut self, src: &S) -> Result<(), PassError> {
        let n = src.intervals();
        self.k.resize(n + 1, Polygon::default());
        // K_{N−1}: the final rest ray, within the gridpoint's own rows.
        let dl = src.delta(n - 1);
        let w = src.last_rest();
        let seg = src.start_set(n - 1);
        let mut ray = Polygon {
            v: vec![[0.0, 0.0], [1.5 * dl * w, -w]],
        };
        if !w.is_finite() {
            ray.v[1] = [1.5 * dl, -1.0];
            let (ex, _) = seg.extent();
            ray.v[1] = [ex, -ex / (1.5 * dl)];
        }
        // Clip the ray by the edges of the start set.
        for (a, c) in edges(seg) {
            ray.clip(a, c, &mut self.scratch);
        }
        if ray.v.len() < 2 {
            return Err(PassError::Empty(n - 1));
        }
        self.k[n - 1] = ray;
        self.k[n] = Polygon {
            v: vec![[0.0, 0.0]],
        };
        for i in (1..n - 1).rev() {
            let mut p = src.start_set(i).clone();
            self.rows.clear();
            self.rows.extend_from_slice(src.stage_rows(i));
            let d = src.delta(i);
            let (e, f) = src.transition(i);
            if i == n - 2 {
                // v = ex·x + eu·u lands on the final ray; substitute it.
                let (ex, eu) = forced_v(d, e, f, dl);
                let u_lo = self.k[n - 1]
                    .v
                    .iter()
                    .map(|q| q[1])
                    .fold(f64::INFINITY, f64::min);
                let u_hi = self.k[n - 1]
                    .v
                    .iter()
                    .map(|q| q[1])
                    .fold(f64::NEG_INFINITY, f64::max);
                for r in &self.rows {
                    let [ax, au, av, c] = *r;
                    p.clip([ax + av * ex, au + av * eu], c, &mut self.scratch);
                }
                // u' = u + F·v within the ray's range.
                p.clip([f * ex, 1.0 + f * eu], u_hi, &mut self.scratch);
                p.clip([-f * ex, -1.0 - f * eu], -u_lo, &mut self.scratch);
            } else {
                for (a, c) in edges(&self.k[i + 1]) {
                    // a·(x + 2Δu + E·v, u + F·v) ≤ c.
                    self.rows
                        .push([a[0], 2.0 * d * a[0] + a[1], e * a[0] + f * a[1], c]);
                }
                self.project(&mut p);
            }
            if p.is_empty() {
                return Err(PassError::Empty(i));
            }
            p.simplify();
            self.k[i] = p;
        }
        Ok(())
    }

    /// Eliminates v from `self.rows` into `p` (see the module documentation). Rows are
    /// normalized by the polygon's extent; a pair (k, l) of an upper and a lower bound on v is
    /// combined without dividing by either coefficient of v, `|a_v,l|·r_k + a_v,k·r_l ≤ 0`, so
    /// that a row almost free of v keeps its own scale (and its own tolerance).
    fn project(&mut self, p: &mut Polygon) {
        self.split_rows(p);
        if self.up.is_empty() || self.lo.is_empty() || p.is_empty() {
            return;
        }
        let (nu, nl) = (self.up.len(), self.lo.len());
        self.used.clear();
        self.used.resize(nu * nl, false);
        // Active rows: those binding at some vertex. The clipping works on them only (most
        // rows never bind near the polygon); a full check at every vertex then brings in the
        // binding rows the clips missed, until no vertex is cut off by any unused pair. That
        // is the same end condition as with every row active.
        self.act_u.clear();
        self.act_l.clear();
        let mut budget = nu * nl;
        loop {
            if !self.activate_binding(p, nl) {
                return;
            }
            while budget > 0 {
                budget -= 1;
                let mut worst: Option<(f64, usize, usize)> = None;
                for q in &p.v {
                    let (umin, ku) = binding(&self.up, Some(&self.act_u), q, true);
                    let (lmax, kl) = binding(&self.lo, Some(&self.act_l), q, false);
                    if lmax <= umin || self.used[ku * nl + kl] {
                        continue;
                    }
                    if let Some(gap) = gap_of(&self.up[ku], &self.lo[kl], q) {
                        if worst.is_none_or(|w| gap > w.0) {
                            worst = Some((gap, ku, kl));
                        }
                    }
                }
                let Some((_, ku, kl)) = worst else { break };
                self.used[ku * nl + kl] = true;
                let (ru, rl) = (self.up[ku], self.lo[kl]);
                let (wu, wl) = (-rl[2], ru[2]);
                p.clip(
                    [wu * ru[0] + wl * rl[0], wu * ru[1] + wl * rl[1]],
                    wu * ru[3] + wl * rl[3],
                    &mut self.scratch,
                );
                if p.is_empty() {
                    return;
                }
            }
            if budget == 0 {
                return;
            }
        }
    }

    /// Clips `p` by the rows free of v and sorts the others, normalized by the polygon's
    /// extent, into upper (`self.up`) and lower (`self.lo`) bounds on v.
    fn split_rows(&mut self, p: &mut Polygon) {
        self.up.clear();
        self.lo.clear();
        let (ex, eu) = p.extent();
        for r in &self.rows {
            let [ax, au, av, c] = *r;
            if av == 0.0 {
                p.clip([ax, au], c, &mut self.scratch);
                continue;
            }
            let m = ax.abs() * ex + au.abs() * eu + c.abs();
            let m = if m > 0.0 && m.is_finite() {
                1.0 / m
            } else {
                1.0
            };
            let row = [ax * m, au * m, av * m, c * m];
            if av > 0.0 {
                self.up.push(row);
            } else {
                self.lo.push(row);
            }
        }
    }

    /// Makes active the unused pair of rows binding at each vertex of `p` that it cuts off
    /// (checked against every row, `nl` lower rows); returns whether any row was added.
    fn activate_binding(&mut self, p: &Polygon, nl: usize) -> bool {
        let mut added = false;
        for q in &p.v {
            let (umin, ku) = binding(&self.up, None, q, true);
            let (lmax, kl) = binding(&self.lo, None, q, false);
            if lmax <= umin || self.used[ku * nl + kl] {
                continue;
            }
            if gap_of(&self.up[ku], &self.lo[kl], q).is_none() {
                continue;
            }
            for (act, k) in [(&mut self.act_u, ku), (&mut self.act_l, kl)] {
                if !act.contains(&k) {
                    act.push(k);
                    added = true;
                }
            }
        }
        added
    }

    /// The greedy forward pass; returns x and u at every gridpoint and v of every interval.
    pub(crate) fn forward<S: StageSource>(
        &mut self,
        src: &S,
        x: &mut Vec<f64>,
        u: &mut Vec<f64>,
        v: &mut Vec<f64>,
    ) -> Result<(), PassError> {
        let n = src.intervals();
        x.clear();
        x.resize(n + 1, 0.0);
        u.clear();
        u.resize(n + 1, 0.0);
        v.clear();
        v.resize(n, 0.0);
        self.forward_slack = 0.0;
        let d0 = src.delta(0);
        let dl = src.delta(n - 1);
        let (_, hi) = self.k[1]
            .line_range_robust([0.0, 0.0], [1.5 * d0, 1.0])
            .ok_or(PassError::NoStart)?;
        let u1 = hi.min(src.first_rest());
        if u1.is_nan() || u1 <= 0.0 {
            return Err(PassError::NoStart);
        }
        u[1] = u1;
        x[1] = 1.5 * d0 * u1;
        for i in 1..n - 1 {
            let d = src.delta(i);
            let (e, f) = src.transition(i);
            let (xi, ui) = (x[i], u[i]);
            let (mut vlo, mut vhi) = (f64::NEG_INFINITY, f64::INFINITY);
            for r in src.stage_rows(i) {
                let [ax, au, av, c] = *r;
                let rhs = c - ax * xi - au * ui;
                if av > 0.0 {
                    vhi = vhi.min(rhs / av);
                } else if av < 0.0 {
                    vlo = vlo.max(rhs / av);
                }
            }
            let vi = if i == n - 2 {
                let (ex, eu) = forced_v(d, e, f, dl);
                ex * xi + eu * ui
            } else {
                let Some((klo, khi)) =
                    self.k[i + 1].line_range_robust([xi + 2.0 * d * ui, ui], [e, f])
                else {
                    return Err(PassError::Lost(i + 1));
                };
                // Staying controllable comes first: a state a hair outside K_i (rounding) may
                // leave the rows no room; the certification then measures the excess.
                vhi.min(khi).max(klo)
            };
            if vi > vhi || vi < vlo {
                let scale = vhi.abs().max(vlo.abs()).max(vi.abs());
                let viol = (vi - vhi).max(vlo - vi) / scale;
                self.forward_slack = self.forward_slack.max(viol);
            }
            v[i] = vi;
            x[i + 1] = (xi + 2.0 * d * ui + e * vi).max(0.0);
            u[i + 1] = ui + f * vi;
        }
        if i_last_bad(x, u, n, dl) {
            return Err(PassError::Lost(n - 1));
        }
        Ok(())
    }
}

/// Whether the state at N−1 is off the final ray by more than rounding.
fn i_last_bad(x: &[f64], u: &[f64], n: usize, dl: f64) -> bool {
    let want = -1.5 * dl * u[n - 1];
    u[n - 1].is_nan()
        || u[n - 1] >= 0.0
        || (x[n - 1] - want).abs() > 1e-6 * want.abs().max(x[n - 1].abs())
}

/// The v of the last middle stage (length Δ, transition E, F) that lands on the final rest
/// ray (length Δ_L): x + 2Δu + E·v = −1.5Δ_L·(u + F·v) ⇒ v = ex·x + eu·u.
pub(crate) fn forced_v(d: f64, e: f64, f: f64, dl: f64) -> (f64, f64) {
    let den = e + 1.5 * dl * f;
    (-1.0 / den, -(2.0 * d + 1.5 * dl) / den)
}

/// The half-planes `a·q ≤ c` of a polygon (both sides and the end caps for a segment, a small
/// box for a point).
pub(crate) fn edges(p: &Polygon) -> Vec<([f64; 2], f64)> {
    let n = p.v.len();
    let mut out = Vec::with_capacity(n.max(4));
    match n {
        0 => out.push(([0.0, 0.0], -1.0)),
        1 => {
            let q = p.v[0];
            out.push(([1.0, 0.0], q[0]));
            out.push(([-1.0, 0.0], -q[0]));
            out.push(([0.0, 1.0], q[1]));
            out.push(([0.0, -1.0], -q[1]));
        }
        2 => {
            let (a, b) = (p.v[0], p.v[1]);
            let nrm = [b[1] - a[1], a[0] - b[0]];
            let c = nrm[0] * a[0] + nrm[1] * a[1];
            let (ex, eu) = p.extent();
            let tol = 1e-10 * (nrm[0].abs() * ex + nrm[1].abs() * eu);
            out.push((nrm, c + tol));
            out.push(([-nrm[0], -nrm[1]], -c + tol));
            let t = [b[0] - a[0], b[1] - a[1]];
            out.push((t, t[0] * b[0] + t[1] * b[1]));
            out.push(([-t[0], -t[1]], -(t[0] * a[0] + t[1] * a[1])));
        }
        _ => {
            for k in 0..n {
                let a = p.v[k];
                let b = p.v[(k + 1) % n];
                let nrm = [b[1] - a[1], a[0] - b[0]];
                out.push((nrm, nrm[0] * a[0] + nrm[1] * a[1]));
            }
        }
    }
    out
}

/// v bound of a row at q: (c − ax·x − au·u)/av.
#[inline]
fn bound(r: &Row, q: &Pt) -> f64 {
    (r[3] - r[0] * q[0] - r[1] * q[1]) / r[2]
}

/// The tightest bound on v at q among `rows` (all of them, or those listed in `only`): the
/// smallest for upper bounds (`upper`), the largest for lower ones; with its row index.
#[inline]
fn binding(rows: &[Row], only: Option<&[usize]>, q: &Pt, upper: bool) -> (f64, usize) {
    let mut best = (
        if upper {
            f64::INFINITY
        } else {
            f64::NEG_INFINITY
        },
        0,
    );
    let mut consider = |k: usize| {
        let b = bound(&rows[k], q);
        if (upper && b < best.0) || (!upper && b > best.0) {
            best = (b, k);
        }
    };
    match only {
        Some(list) => list.iter().for_each(|&k| consider(k)),
        None => (0..rows.len()).for_each(consider),
    }
    best
}

/// How far q lies outside the combination of an upper row `ru` and a lower row `rl` (scaled
/// without dividing by either coefficient of v), when beyond rounding.
#[inline]
fn gap_of(ru: &Row, rl: &Row, q: &Pt) -> Option<f64> {
    let (wu, wl) = (-rl[2], ru[2]);
    let val = |r: &Row| r[0] * q[0] + r[1] * q[1] - r[3];
    let mag = |r: &Row| (r[0] * q[0]).abs() + (r[1] * q[1]).abs() + r[3].abs();
    let gap = wu * val(ru) + wl * val(rl);
    let tol = 1e-12 * (wu * mag(ru) + wl * mag(rl));
    (gap > tol).then_some(gap)
}
