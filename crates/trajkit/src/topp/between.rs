//! TOPP-RA between gridpoints: the check that makes the limits hold on the whole trajectory,
//! not only at gridpoints.
//!
//! The discretized problem enforces the constraints at gridpoints; between them the profile
//! has constant u = s̈ and x = ṡ² linear in s, and a constraint can be exceeded there. After
//! each solve every interval that changed is checked:
//! - **exactly** where the path is a polynomial of degree ≤ 5 on the interval
//!   ([`crate::Path::piecewise_degree`], no breakpoint inside; quintic pieces come from the
//!   range repair of [`crate::spline::BoundedSpline`]) and the constraint can bound itself on
//!   such a piece ([`Constraint::excess_on_cubic`]: joint velocity and joint acceleration, in
//!   closed form on cubic pieces, from the exactly isolated roots of the acceleration quartic
//!   or its derivative on quintic ones, [`Constraint::handles_quintic`]). An interval whose worst value exceeds the limit by more
//!   than [`EXACT_TOL`] relative gets that constraint's rows *at the worst point* added to its
//!   stage, written in (u, x_i) with x = x_i + 2u(s − s_i) — the same substitution the
//!   interpolation scheme makes at s_{i+1} — and the problem is solved again on the same grid.
//!   The added row holds the constraint exactly at the point that was worst; the new worst
//!   point moves by the (small) change of u and x, so the next excess is of second order and
//!   one or two rounds reach the tolerance. Only failing intervals pay, and only with rows.
//! - **at sample points** otherwise (any other path, user constraints such as torque or
//!   end-effector speed): the midpoint, the quarters and points approaching both ends
//!   geometrically (down to 4⁻⁷ of the length, [`REFINE_POINTS`]); an interval exceeding
//!   [`REFINE_TOL`] there is cut into equal parts (as many as the excess calls for: it shrinks
//!   as Δ²) and the problem evaluated and solved again.
//!
//! Intervals found clean and unchanged since (same ends, x within 1e-9 relative) are not
//! checked again.
//!
//! Files: this one holds the check and the rows between gridpoints; `between/pieces.rs` the
//! path's Taylor data on the intervals (computed when asked for on long grids).

mod pieces;

use super::constraint::{Constraint, CubicPiece, PathPoint};
use super::toppra::{Discretization, Workspace, MAX_REFINED_INTERVALS, REFINE_POINTS, REFINE_TOL};
use crate::Path;
pub(super) use pieces::{PieceAnchor, PieceBuf, Pieces};

/// Relative excess accepted where the check is exact (joint velocity and acceleration on
/// piecewise-cubic paths): the limits then hold everywhere within it, up to rounding.
pub(crate) const EXACT_TOL: f64 = 1e-8;

/// Rows of an interior point are kept when they are this close to active (relative excess
/// above minus this) at the worst point: the others cannot bind after a small change.
const NEAR_ACTIVE: f64 = 1e-3;

/// What a check round found.
pub(super) enum Check {
    /// Every interval within the limits.
    Clean,
    /// Rows were added to the stages of intervals `lo..=hi` (not necessarily all of them); the
    /// grid is unchanged.
    Tightened(usize, usize),
    /// Some intervals must be cut: the new grid.
    Split(Vec<f64>),
}

/// What the check of one interval found.
enum Interval {
    /// Within the limits.
    Clean,
    /// Rows were added to its stage.
    Tightened,
    /// It must be cut into this many equal parts.
    Split(usize),
}

impl Workspace {
    /// Forgets the interior rows and Taylor data (a new grid).
    pub(super) fn reset_between(&mut self) {
        self.mid.clear();
        self.mid_off.clear();
        self.mid_add.clear();
        self.pieces.built = false;
        self.clean = Default::default();
    }

    /// Builds the Taylor data of the intervals and, where the path is a polynomial of degree
    /// ≤ 3 on an interval, writes every constraint's sufficient rows
    /// ([`Constraint::hold_on_cubic`], which leaves out rows that cannot bind within the
    /// velocity bounds `xhi` at both ends) into the interval's stage.
    pub(super) fn prepare_between<P: Path>(
        &mut self,
        path: &P,
        cons: &[Box<dyn Constraint + '_>],
        grid: &[f64],
        xhi: &[f64],
        at_points: &[f64],
    ) {
        let n = grid.len() - 1;
        let need_q = cons.iter().any(|c| c.uses_position());
        let mut pieces = std::mem::take(&mut self.pieces);
        pieces.build(path, grid, need_q);
        let mut buf = std::mem::take(&mut pieces.buf);
        self.mid.clear();
        self.mid_off.clear();
        self.mid_add.clear();
        self.mid_off.push(0);
        self.proved.clear();
        self.proved.resize(cons.len(), false);
        // The constraints append straight to the interior rows: lend them to the collector.
        let own = std::mem::replace(&mut self.cr.rows, std::mem::take(&mut self.mid));
        let cr = &mut self.cr;
        for i in 0..n {
            let Some(piece) = pieces.piece(path, grid, i, at_points, &mut buf) else {
                self.mid_off.push(cr.rows.len());
                continue;
            };
            let x_max = [xhi[i], xhi[i + 1]];
            for (k, c) in cons.iter().enumerate() {
                if pieces.quintic && !c.handles_quintic() {
                    continue;
                }
                cr.clear_bounds();
                if !c.hold_on_cubic(&piece, x_max, cr) {
                    cr.rows.truncate(cr.start);
                    continue;
                }
                self.proved[k] = true;
            }
            self.mid_off.push(cr.rows.len());
        }
        self.mid = std::mem::replace(&mut cr.rows, own);
        self.cr.clear();
        pieces.buf = buf;
        self.pieces = pieces;
    }

    /// Checks every interval that changed since the last round (see the module documentation).
    /// Where the interpolation scheme holds a constraint's rows at both ends and its sufficient
    /// rows were prepared on a piece whose ends are not breakpoints, the constraint holds on the
    /// interval by construction and is not checked again.
    pub(super) fn check_between<P: Path>(
        &mut self,
        path: &P,
        cons: &[Box<dyn Constraint + '_>],
        grid: &[f64],
        x: &[f64],
        disc: Discretization,
    ) -> Check {
        let n = grid.len() - 1;
        let need_q = cons.iter().any(|c| c.uses_position());
        if !self.pieces.built {
            self.pieces.build(path, grid, need_q);
        }
        let mut split: Vec<usize> = Vec::new();
        let mut tightened: Option<(usize, usize)> = None;
        self.clean.start_round();
        let mut pieces = std::mem::take(&mut self.pieces);
        let mut buf = std::mem::take(&mut pieces.buf);
        // Intervals where every constraint holds by construction (see `check_interval`): no
        // check, and no record of a clean step (32 bytes per interval and round).
        let all_proved = disc == Discretization::Interpolation
            && (cons.iter().enumerate()).all(|(k, c)| {
                self.proved.get(k) == Some(&true) && (!pieces.quintic || c.handles_quintic())
            });
        for i in 0..n {
            if all_proved && pieces.inside_piece(i) {
                continue;
            }
            let step = [grid[i], grid[i + 1], x[i], x[i + 1]];
            if self.clean.unchanged(step) {
                continue;
            }
            match self.check_interval(path, cons, (&pieces, &mut buf), grid, x, i, disc) {
                Interval::Split(parts) => {
                    if split.is_empty() {
                        split.resize(n, 1);
                    }
                    split[i] = parts;
                }
                Interval::Tightened => {
                    tightened = Some(tightened.map_or((i, i), |(lo, _)| (lo, i)));
                }
                Interval::Clean => self.clean.mark(step),
            }
        }
        pieces.buf = buf;
        self.pieces = pieces;
        self.merge_added(n);
        if !split.is_empty() {
            let total: usize = split.iter().sum();
            if total <= MAX_REFINED_INTERVALS {
                return Check::Split(self.cut(grid, &split));
            }
        }
        match tightened {
            Some((lo, hi)) => Check::Tightened(lo, hi),
            None => Check::Clean,
        }
    }

    /// Checks interval i against every constraint: exactly where a piece bound exists (adding
    /// the rows at the worst point when it is exceeded), at sample points otherwise.
    #[allow(clippy::too_many_arguments)]
    fn check_interval<P: Path>(
        &mut self,
        path: &P,
        cons: &[Box<dyn Constraint + '_>],
        (pieces, buf): (&Pieces, &mut PieceBuf),
        grid: &[f64],
        x: &[f64],
        i: usize,
        disc: Discretization,
    ) -> Interval {
        let delta = grid[i + 1] - grid[i];
        let u = (x[i + 1] - x[i]) / (2.0 * delta);
        let mut sampled = false;
        let mut failed = false;
        self.sample.clear();
        let proved_here = disc == Discretization::Interpolation && !pieces.at_break[i];
        let proved = |k: usize, c: &dyn Constraint| {
            proved_here && pieces.has_piece_for(i, c) && self.proved.get(k) == Some(&true)
        };
        // The interval's Taylor data, computed once for the constraints that read them.
        let wanted = (cons.iter().enumerate())
            .any(|(k, c)| pieces.has_piece_for(i, &**c) && !proved(k, &**c));
        let piece = if wanted {
            pieces.piece(path, grid, i, &self.pts.at_points, buf)
        } else {
            None
        };
        for (k, c) in cons.iter().enumerate() {
            if proved_here && pieces.has_piece_for(i, &**c) && self.proved.get(k) == Some(&true) {
                self.sample.push(false);
                continue;
            }
            let piece = piece.filter(|_| pieces.has_piece_for(i, &**c));
            match piece.and_then(|p| c.excess_on_cubic(&p, u, x[i])) {
                Some((e, s)) => {
                    self.sample.push(false);
                    if e > EXACT_TOL {
                        self.add_rows_at(&**c, piece.as_ref(), path, grid, i, s, u, x[i]);
                        failed = true;
                    }
                }
                None => {
                    self.sample.push(true);
                    sampled = true;
                }
            }
        }
        let need_q = cons.iter().any(|c| c.uses_position());
        let worst = if sampled {
            self.sampled_excess(path, cons, grid, i, u, x[i], need_q)
        } else {
            0.0
        };
        if worst > REFINE_TOL {
            // The excess of a smooth constraint shrinks with the square of the interval
            // length: cut into enough parts to bring it a few times below the tolerance.
            let parts = (worst / (0.5 * REFINE_TOL)).sqrt().ceil();
            Interval::Split(if parts.is_finite() {
                (parts as usize).clamp(2, 64)
            } else {
                64
            })
        } else if failed {
            Interval::Tightened
        } else {
            Interval::Clean
        }
    }

    /// The largest relative excess of the constraints that have no exact bound on this interval
    /// (marked in `self.sample`), at [`REFINE_POINTS`].
    #[allow(clippy::too_many_arguments)]
    fn sampled_excess<P: Path>(
        &mut self,
        path: &P,
        cons: &[Box<dyn Constraint + '_>],
        grid: &[f64],
        i: usize,
        u: f64,
        x0: f64,
        need_q: bool,
    ) -> f64 {
        let delta = grid[i + 1] - grid[i];
        let mut worst = f64::NEG_INFINITY;
        for theta in REFINE_POINTS {
            let s = grid[i] + delta * theta;
            if !(s > grid[i] && s < grid[i + 1]) {
                continue;
            }
            let xs = (x0 + 2.0 * u * (s - grid[i])).max(0.0);
            if need_q {
                path.eval(s, 0, &mut self.q);
            }
            path.eval_derivatives(s, &mut self.dq, &mut self.ddq);
            let p = PathPoint {
                s,
                q: &self.q,
                dq: &self.dq,
                ddq: &self.ddq,
            };
            for (c, &sample) in cons.iter().zip(&self.sample) {
                if !sample {
                    continue;
                }
                self.cr.clear();
                c.write(&p, &mut self.cr);
                worst = worst.max(self.cr.relative_excess(u, xs));
            }
        }
        worst
    }

    /// Adds constraint `c`'s rows at the interior point `s` of interval i to the interval's
    /// stage, written in (u, x_i): a row α·u + β·x(s) ≤ γ with x(s) = x_i + 2u(s − s_i) becomes
    /// (α + 2(s − s_i)β)·u + β·x_i ≤ γ. Rows far from active at (u, x) are left out.
    #[allow(clippy::too_many_arguments)]
    fn add_rows_at<P: Path>(
        &mut self,
        c: &dyn Constraint,
        piece: Option<&CubicPiece<'_>>,
        path: &P,
        grid: &[f64],
        i: usize,
        s: f64,
        u: f64,
        x0: f64,
    ) {
        match piece {
            Some(p) => p.eval_into(s, &mut self.q, &mut self.dq, &mut self.ddq),
            None => {
                path.eval(s, 0, &mut self.q);
                path.eval_derivatives(s, &mut self.dq, &mut self.ddq);
            }
        }
        let point = PathPoint {
            s,
            q: &self.q,
            dq: &self.dq,
            ddq: &self.ddq,
        };
        self.cr.clear();
        c.write(&point, &mut self.cr);
        let two_t = 2.0 * (s - grid[i]);
        let xs = (x0 + two_t * u).max(0.0);
        let rows = &mut self.mid_add;
        for &[a, b, g] in self.cr.half_planes() {
            let scale = g.abs().max((a * u).abs()).max((b * xs).abs());
            if scale > 0.0 && (a * u + b * xs - g) / scale > -NEAR_ACTIVE {
                rows.push((i, [a + two_t * b, b, g]));
            }
        }
        let (x_min, x_max) = self.cr.x_bounds();
        if x_max.is_finite() && xs >= x_max * (1.0 - 2.0 * NEAR_ACTIVE) {
            rows.push((i, [two_t, 1.0, x_max]));
        }
        if x_min > 0.0 {
            rows.push((i, [-two_t, -1.0, -x_min]));
        }
    }

    /// Moves the rows found by a check round (`mid_add`, in interval order) into `mid`.
    fn merge_added(&mut self, n: usize) {
        if self.mid_add.is_empty() {
            return;
        }
        let mut mid = Vec::with_capacity(self.mid.len() + self.mid_add.len());
        let mut off = Vec::with_capacity(n + 1);
        off.push(0);
        let mut a = 0;
        for i in 0..n {
            mid.extend_from_slice(self.mid_rows(i));
            while a < self.mid_add.len() && self.mid_add[a].0 == i {
                mid.push(self.mid_add[a].1);
                a += 1;
            }
            off.push(mid.len());
        }
        self.mid = mid;
        self.mid_off = off;
        self.mid_add.clear();
    }

    /// The grid with interval i cut into `split[i]` equal parts. Interior rows are dropped (the
    /// caller prepares the new grid's).
    fn cut(&mut self, grid: &[f64], split: &[usize]) -> Vec<f64> {
        let next = super::grid::subdivide(grid, split);
        self.mid.clear();
        self.mid_off.clear();
        self.mid_add.clear();
        self.pieces.built = false;
        self.pieces.grid_piece.clear();
        next
    }
}
