//! The constraint rows of every knot (both sides of a breakpoint), their tightening, and the
//! path evaluations that produce them.

use super::{check_path_values, Constraint, ConstraintRows, PathPoint};
use crate::error::Result;
use crate::Path;

/// Evaluates the path at a breakpoint on the side of the piece that ends there.
pub(super) type SideEval<'a> = &'a dyn Fn(f64, usize, &mut [f64]);

/// Constraint rows of both sides of every knot, with the tightening applied.
#[derive(Default)]
pub(super) struct Rows {
    pub(super) rows: Vec<[f64; 3]>,
    /// The untightened γ of every row.
    pub(super) gamma: Vec<f64>,
    /// Per knot: [start, end) of the right-side rows, then of the left-side rows.
    pub(super) range: Vec<[usize; 4]>,
    /// Per knot: x bounds, right then left side (`xhi` tightened, `xhi0` not).
    pub(super) xlo: Vec<[f64; 2]>,
    pub(super) xhi: Vec<[f64; 2]>,
    pub(super) xhi0: Vec<[f64; 2]>,
    /// Per knot: the tightening applied to its rows.
    pub(super) applied: Vec<f64>,
}

/// Marks a knot that is not in the previous round's knots.
pub(super) const NEW_KNOT: usize = usize::MAX;

pub(super) struct Scratch {
    q: Vec<f64>,
    dq: Vec<f64>,
    ddq: Vec<f64>,
    cr: ConstraintRows,
}

impl Scratch {
    pub(super) fn new(n: usize) -> Self {
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
    pub(super) fn excess<P: Path + ?Sized>(
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
    pub(super) fn diagnose<P: Path + ?Sized>(
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
pub(super) struct View<'a> {
    pub(super) rows: &'a Rows,
    pub(super) map: Option<&'a [usize]>,
}

impl<'a> View<'a> {
    pub(super) fn all(rows: &'a Rows) -> Self {
        View { rows, map: None }
    }
    pub(super) fn at(&self, i: usize) -> usize {
        self.map.map_or(i, |m| m[i])
    }
    pub(super) fn right(&self, i: usize) -> &'a [[f64; 3]] {
        self.rows.right(self.at(i))
    }
    pub(super) fn left(&self, i: usize) -> &'a [[f64; 3]] {
        self.rows.left(self.at(i))
    }
    pub(super) fn xhi(&self, i: usize) -> [f64; 2] {
        self.rows.xhi[self.at(i)]
    }
    pub(super) fn xlo(&self, i: usize) -> [f64; 2] {
        self.rows.xlo[self.at(i)]
    }
}

impl Rows {
    pub(super) fn right(&self, k: usize) -> &[[f64; 3]] {
        &self.rows[self.range[k][0]..self.range[k][1]]
    }
    pub(super) fn left(&self, k: usize) -> &[[f64; 3]] {
        &self.rows[self.range[k][2]..self.range[k][3]]
    }
}

/// Whether `s` is an interior breakpoint (where the two sides of a knot differ).
pub(super) fn is_break(breaks: &[f64], s: f64) -> bool {
    breaks.len() > 2
        && breaks[1..breaks.len() - 1]
            .binary_search_by(|b| b.total_cmp(&s))
            .is_ok()
}

impl Rows {
    /// Tightens the limits at every knot k whose applied tightening is not `eps[k]`
    /// (relative), in place: every row γ → γ₀ − ε·|γ₀|, x_max → x₀·(1 − ε), from the
    /// untightened values.
    pub(super) fn tighten(&mut self, eps: &[f64]) {
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
    pub(super) fn evaluate<P: Path + ?Sized>(
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
