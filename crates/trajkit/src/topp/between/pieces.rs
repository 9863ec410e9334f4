//! The path's Taylor data on the intervals of a TOPP-RA grid (module `topp::between`): the
//! pieces the exact check and the sufficient rows between gridpoints read, and the Taylor
//! shifts that move one expansion per path piece to every point that needs it.
//!
//! Precision: the shifts are exact for polynomials of degree ≤ 5 up to rounding (tested against
//! the path's own evaluation); data computed when asked for equal the kept ones bit for bit.
//! Cost: one path evaluation per path piece, one Taylor shift (`6·dim` numbers) per gridpoint
//! and per interval read; memory: `6·dim` numbers per gridpoint only on grids within
//! [`STORE_BYTES`].

use super::super::constraint::{Constraint, CubicPiece};
use crate::Path;

/// The path's Taylor data on every interval of the grid: σ, σ′, …, σ⁽⁵⁾ at the interval's
/// start, from inside (`6·dim` numbers per interval; σ⁗ and σ⁽⁵⁾ zero on paths of degree ≤ 3),
/// for intervals where the exact check applies. On quintic paths the path is evaluated once per
/// path piece, at the piece's midpoint (so that no convention about which piece a breakpoint
/// belongs to matters), and the expansion moved to each interval's start ([`PieceAnchor`]). On
/// paths of degree ≤ 3, between ordinary gridpoints one cubic covers both ends: the gridpoint
/// values give σ, σ′, σ″ and (σ″(s_{i+1}) − σ″(s_i))/Δ gives σ‴; at a breakpoint the path is
/// evaluated at the interval's midpoint and the expansion moved to the start.
///
/// The data that need a path evaluation (intervals at breakpoints) are stored; on paths of
/// degree 4 or 5 the pass over the gridpoints keeps the data it moved to each gridpoint while
/// they take at most [`STORE_BYTES`]. The others are computed when asked for
/// ([`Pieces::piece`], into a [`PieceBuf`]): moved from the piece's anchor (the pass over the
/// gridpoints has found them finite) or taken from the gridpoint values, the same operations
/// on the same numbers, so the same bits, as a stored copy; on a long path that is one Taylor
/// shift per use instead of `6·dim` numbers (336 bytes at 7 joints) written per gridpoint.
#[derive(Default)]
pub(in crate::topp) struct Pieces {
    /// Per interval: whether the path is a polynomial of degree ≤ 5 on it.
    exact: Vec<bool>,
    /// Whether the path's pieces may have degree 4 or 5 (then only constraints that
    /// [`Constraint::handles_quintic`] get them).
    pub(in crate::topp) quintic: bool,
    /// Per interval: whether an end is a breakpoint of the path (where σ″ may jump, so the
    /// gridpoint's rows may belong to the neighbouring piece).
    pub(in crate::topp) at_break: Vec<bool>,
    /// Taylor data of the intervals computed when the grid is built (those that need a path
    /// evaluation), `6·dim` numbers each.
    data: Vec<f64>,
    /// Per interval: where its Taylor data start in `data`, or in `at_grid` when marked with
    /// [`FROM_GRID`]; or, marked with [`FROM_ANCHOR`], the index `b` of the path piece whose
    /// anchor they are moved from; or [`FROM_POINTS`]: from the values at the gridpoints.
    loc: Vec<usize>,
    /// The Taylor data σ, σ′, …, σ⁽⁵⁾ at the gridpoints (`6·dim` numbers each), moved from the
    /// anchor of the path piece that holds the gridpoint inside (see
    /// [`PieceAnchor::eval_full`]), on paths of degree 4 or 5: of every gridpoint when `store`
    /// (zeros at the others), else of the current one only.
    at_grid: Vec<f64>,
    /// Whether `at_grid` keeps every gridpoint's data.
    store: bool,
    /// Per gridpoint: the index `b` of the piece (ending at `breaks[b]`) whose anchor gave
    /// finite data there, `usize::MAX` where none did.
    pub(in crate::topp) grid_piece: Vec<usize>,
    /// `at_grid`, `store` and `grid_piece` of the previous pass over the gridpoints, for the
    /// points the next grid keeps ([`Pieces::copy_gridpoint`]).
    prev_at_grid: Vec<f64>,
    prev_store: bool,
    prev_grid_piece: Vec<usize>,
    /// The path's breakpoints (for the anchors of [`Pieces::piece`]).
    breaks: Vec<f64>,
    /// Whether the pass over the gridpoints marks `grid_piece`, and whether it evaluates σ.
    keep: bool,
    need_q: bool,
    /// Scratch: Taylor data at the midpoint of one path piece, and of one interval.
    pub(in crate::topp) buf: PieceBuf,
    dim: usize,
    pub(in crate::topp) built: bool,
}

/// Scratch of [`Pieces::piece`]: the anchor of the last path piece used and the Taylor data
/// of one interval.
#[derive(Default)]
pub(in crate::topp) struct PieceBuf {
    anchor: PieceAnchor,
    d: Vec<f64>,
}

impl Pieces {
    /// Bytes held (roughly).
    pub(in crate::topp) fn bytes(&self) -> usize {
        8 * (self.data.capacity()
            + self.at_grid.capacity()
            + self.prev_at_grid.capacity()
            + self.breaks.capacity())
            + std::mem::size_of::<usize>()
                * (self.loc.capacity()
                    + self.grid_piece.capacity()
                    + self.prev_grid_piece.capacity())
            + self.exact.capacity()
            + self.at_break.capacity()
    }

    /// Starts the pass over the gridpoints of a new grid of `points` gridpoints
    /// ([`Pieces::eval_gridpoint`]); `anchored`: whether the pass moves Taylor data from
    /// path pieces at all; `keep_previous`: whether the data of the last pass are kept for
    /// [`Pieces::copy_gridpoint`]. Returns whether it keeps the full data (paths of degree 4
    /// or 5): the intervals then need no values at the gridpoints.
    pub(in crate::topp) fn start_gridpoints<P: Path>(
        &mut self,
        path: &P,
        need_q: bool,
        anchored: bool,
        points: usize,
        keep_previous: bool,
    ) -> bool {
        self.keep = anchored && path.piecewise_degree().is_some_and(|d| d > 3);
        self.need_q = need_q;
        if keep_previous {
            std::mem::swap(&mut self.at_grid, &mut self.prev_at_grid);
            std::mem::swap(&mut self.grid_piece, &mut self.prev_grid_piece);
            self.prev_store = self.store;
        } else {
            self.prev_grid_piece.clear();
            self.prev_store = false;
        }
        self.grid_piece.clear();
        self.at_grid.clear();
        let per_point = 6 * path.dim();
        self.store = self.keep && 8 * per_point * points <= store_bytes();
        if self.store {
            self.at_grid.reserve(per_point * points);
        } else if self.keep {
            self.at_grid.resize(per_point, 0.0);
        }
        if self.keep {
            self.grid_piece.reserve(points);
        }
        self.keep
    }

    /// σ (when needed), σ′ and σ″ at the next gridpoint `s`, from the Taylor data of the
    /// path piece ending at `breaks[b]` when `inside` it (`at = (inside, b)`). On paths of
    /// degree 4 or 5 the full data are kept for the interval starting there, and returned
    /// (`6·dim` numbers, σ in them only when needed) when all finite; otherwise σ, σ′, σ″ are
    /// written into `out`. Returns whether the values come from the piece, and the full data.
    pub(in crate::topp) fn eval_gridpoint<P: Path>(
        &mut self,
        anchor: &mut PieceAnchor,
        path: &P,
        breaks: &[f64],
        (inside, b): (bool, usize),
        s: f64,
        out: [&mut [f64]; 3],
    ) -> (bool, Option<&[f64]>) {
        if !self.keep {
            let ok = inside && anchor.eval(path, breaks, b, s, self.need_q, out);
            return (ok, None);
        }
        let at = if self.store {
            let at = self.at_grid.len();
            self.at_grid.resize(at + 6 * path.dim(), 0.0);
            at
        } else {
            0
        };
        if !inside {
            self.grid_piece.push(usize::MAX);
            return (false, None);
        }
        let full = &mut self.at_grid[at..];
        let ok = anchor.eval_full(path, breaks, b, s, self.need_q, out, full);
        // Data that are not all finite are left to the intervals' own expansion (which finds
        // them so and leaves the interval to the sampled check).
        let finite = ok == Some(true);
        self.grid_piece.push(if finite { b } else { usize::MAX });
        (ok.is_some(), finite.then_some(&self.at_grid[at..]))
    }

    /// Takes the data of gridpoint `p` of the previous pass over the gridpoints (of the same
    /// path, at the same s: the same numbers [`Pieces::eval_gridpoint`] would compute) as the
    /// next gridpoint of this pass. Returns false, with nothing taken, when the previous pass
    /// did not keep what this one needs (then the caller evaluates the point).
    pub(in crate::topp) fn copy_gridpoint(&mut self, p: usize, dim: usize) -> bool {
        if !self.keep {
            return true;
        }
        let Some(&piece) = self.prev_grid_piece.get(p) else {
            return false;
        };
        if self.store {
            let n = 6 * dim;
            let Some(d) = (self.prev_store)
                .then(|| self.prev_at_grid.get(p * n..(p + 1) * n))
                .flatten()
            else {
                return false;
            };
            self.at_grid.extend_from_slice(d);
        }
        self.grid_piece.push(piece);
        true
    }

    pub(in crate::topp) fn build<P: Path>(&mut self, path: &P, grid: &[f64], need_q: bool) {
        let n = grid.len() - 1;
        let dim = path.dim();
        self.dim = dim;
        self.need_q = need_q;
        self.exact.clear();
        self.at_break.clear();
        self.loc.clear();
        self.built = true;
        self.buf.anchor.reset(dim);
        self.buf.d.clear();
        self.buf.d.resize(6 * dim, 0.0);
        let degree = path.piecewise_degree();
        if degree.is_none_or(|d| d > 5) {
            self.exact.resize(n, false);
            self.at_break.resize(n, true);
            return;
        }
        self.quintic = degree.is_some_and(|d| d > 3);
        self.breaks = path.breakpoints();
        let breaks = std::mem::take(&mut self.breaks);
        // Every entry of an exact interval is written below (σ only when needed, σ⁗ and σ⁽⁵⁾
        // only on quintic paths: zeros then).
        self.data.clear();
        let from_grid = self.quintic && self.grid_piece.len() == n + 1;
        // Quintic paths: the Taylor data of the path piece that holds the current interval, at
        // the piece's midpoint (evaluated once per piece, moved to each interval's start).
        let mut anchor = std::mem::take(&mut self.buf.anchor);
        let mut b = 0;
        for i in 0..n {
            let (s0, s1) = (grid[i], grid[i + 1]);
            while b < breaks.len() && breaks[b] < s0 {
                b += 1;
            }
            let starts_at_break = b < breaks.len() && breaks[b] == s0;
            if starts_at_break {
                b += 1;
            }
            let inside = b < breaks.len() && breaks[b] < s1;
            let ends_at_break = b < breaks.len() && breaks[b] == s1;
            self.exact.push(!inside);
            self.at_break.push(starts_at_break || ends_at_break);
            if inside {
                self.loc.push(0);
                continue;
            }
            if from_grid && self.grid_piece[i] == b {
                // This piece's anchor moved to s0 (what the branch below computes), found
                // finite by the pass over the gridpoints: kept there, or moved again when
                // asked for.
                self.loc.push(if self.store {
                    (i * 6 * dim) | FROM_GRID
                } else {
                    b | FROM_ANCHOR
                });
                continue;
            }
            let at_break = starts_at_break || ends_at_break;
            if !self.quintic && !at_break {
                self.loc.push(FROM_POINTS);
                continue;
            }
            let off = self.data.len();
            self.loc.push(off);
            self.data.resize(off + 6 * dim, 0.0);
            let d = &mut self.data[off..];
            if self.quintic {
                let ok = if b >= 1 && b < breaks.len() {
                    anchor
                        .piece(path, &breaks, b, need_q)
                        .is_some_and(|(sm, a)| {
                            shift_taylor(a, s0 - sm, d);
                            d.iter().all(|v| v.is_finite())
                        })
                } else {
                    quintic_taylor(path, s0, s1, need_q, d)
                };
                if !ok {
                    self.exact[i] = false;
                }
                continue;
            }
            if !cubic_taylor_at_break(path, (s0, s1), need_q, d) {
                self.exact[i] = false;
            }
        }
        self.buf.anchor = anchor;
        self.breaks = breaks;
    }

    /// The Taylor data of interval i (none where the path is not a polynomial of degree ≤ 5
    /// there), stored or computed into `buf` (`at_points`: σ, σ′, σ″ at the gridpoints, read on
    /// paths of degree ≤ 3).
    #[inline]
    pub(in crate::topp) fn piece<'a, P: Path>(
        &'a self,
        path: &P,
        grid: &[f64],
        i: usize,
        at_points: &[f64],
        buf: &'a mut PieceBuf,
    ) -> Option<CubicPiece<'a>> {
        if !self.exact[i] {
            return None;
        }
        let dim = self.dim;
        let at = self.loc[i];
        let d: &[f64] = if at & FROM_ANCHOR != 0 {
            let b = at & !FROM_ANCHOR;
            let (sm, a) = buf.anchor.piece(path, &self.breaks, b, self.need_q)?;
            shift_taylor(a, grid[i] - sm, &mut buf.d);
            &buf.d
        } else if at == FROM_POINTS {
            cubic_from_points(at_points, dim, i, grid[i + 1] - grid[i], &mut buf.d);
            &buf.d
        } else if at & FROM_GRID != 0 {
            let off = at & !FROM_GRID;
            &self.at_grid[off..off + 6 * dim]
        } else {
            &self.data[at..at + 6 * dim]
        };
        Some(CubicPiece {
            s0: grid[i],
            s1: grid[i + 1],
            d0: &d[..dim],
            d1: &d[dim..2 * dim],
            d2: &d[2 * dim..3 * dim],
            d3: &d[3 * dim..4 * dim],
            d4: &d[4 * dim..5 * dim],
            d5: &d[5 * dim..],
        })
    }

    /// Whether interval i lies inside one path piece of degree ≤ 5 and touches no breakpoint:
    /// the sufficient rows prepared there hold every constraint that
    /// [`Pieces::has_piece_for`] serves on the whole interval (`topp::between`).
    pub(in crate::topp) fn inside_piece(&self, i: usize) -> bool {
        self.exact[i] && !self.at_break[i]
    }

    /// Whether constraint `c` gets interval i's piece: the path is a polynomial of degree ≤ 5
    /// there, and of degree ≤ 3 unless `c` handles quintics.
    pub(in crate::topp) fn has_piece_for(&self, i: usize, c: &dyn Constraint) -> bool {
        self.exact[i] && (!self.quintic || c.handles_quintic())
    }
}

/// Joints up to which [`PieceAnchor::eval`] moves the data in a buffer on the stack.
const EVAL_DIM: usize = 16;

/// Marks an interval's data (in [`Pieces`]) as moved from the anchor of the path piece whose
/// index the other bits hold.
const FROM_ANCHOR: usize = 1 << (usize::BITS - 1);

/// Marks an interval's data (in [`Pieces`]) as taken from the values at its gridpoints.
const FROM_POINTS: usize = 1 << (usize::BITS - 2);

/// Marks an interval's data offset (in [`Pieces`]) as one into the gridpoints' data.
const FROM_GRID: usize = 1 << (usize::BITS - 3);

/// Largest size of the Taylor data kept at every gridpoint (16 MB: 50 000 gridpoints at 7
/// joints); a larger grid moves them again when asked for. Small grids save the second
/// shift; large ones save the memory, which a solve beyond the workspace kept between solves
/// pays in fresh pages.
pub(in crate::topp) const STORE_BYTES: usize = 16 << 20;

#[cfg(test)]
thread_local! {
    /// [`STORE_BYTES`] in the tests, which try both ways.
    static STORE_LIMIT: std::cell::Cell<usize> = const { std::cell::Cell::new(STORE_BYTES) };
}

/// [`STORE_BYTES`] (changed by the tests on their thread).
fn store_bytes() -> usize {
    #[cfg(test)]
    return STORE_LIMIT.with(|c| c.get());
    #[cfg(not(test))]
    STORE_BYTES
}

/// The Taylor data σ, σ′, …, σ⁽⁵⁾ (`6·dim` numbers) of one piece of a path that is a
/// polynomial of degree ≤ 5 between breakpoints, at the piece's midpoint: evaluated once per
/// piece and moved by [`shift_taylor`] to every point of the piece that needs it, instead of
/// evaluating the path again there.
#[derive(Default)]
pub(in crate::topp) struct PieceAnchor {
    data: Vec<f64>,
    /// The piece's index (its end is `breaks[b]`), its midpoint, and whether the data are
    /// finite.
    of: Option<(usize, f64, bool)>,
}

impl PieceAnchor {
    /// Forgets the piece; sized for `dim` joints.
    pub(in crate::topp) fn reset(&mut self, dim: usize) {
        self.data.clear();
        self.data.resize(6 * dim, 0.0);
        self.of = None;
    }

    /// The midpoint and Taylor data there of the piece `[breaks[b − 1], breaks[b]]` (`b ≥ 1`),
    /// or `None` when they are not finite.
    pub(in crate::topp) fn piece<P: Path>(
        &mut self,
        path: &P,
        breaks: &[f64],
        b: usize,
        need_q: bool,
    ) -> Option<(f64, &[f64])> {
        let (sm, ok) = match self.of {
            Some((key, sm, ok)) if key == b => (sm, ok),
            _ => {
                let sm = 0.5 * (breaks[b - 1] + breaks[b]);
                let ok = quintic_taylor(path, sm, sm, need_q, &mut self.data);
                self.of = Some((b, sm, ok));
                (sm, ok)
            }
        };
        ok.then_some((sm, &self.data[..]))
    }

    /// σ (when `need_q`), σ′ and σ″ at `s`, strictly inside the piece ending at `breaks[b]`,
    /// from the piece's Taylor data. Returns false (nothing written) when they are not finite.
    #[allow(clippy::too_many_arguments)]
    pub(in crate::topp) fn eval<P: Path>(
        &mut self,
        path: &P,
        breaks: &[f64],
        b: usize,
        s: f64,
        need_q: bool,
        out: [&mut [f64]; 3],
    ) -> bool {
        let Some((sm, a)) = self.piece(path, breaks, b, need_q) else {
            return false;
        };
        let dim = a.len() / 6;
        let t = s - sm;
        let [q, dq, ddq] = out;
        if dim > EVAL_DIM {
            for j in 0..dim {
                let m = shift_one(std::array::from_fn(|k| a[k * dim + j]), t);
                if need_q {
                    q[j] = m[0];
                }
                dq[j] = m[1];
                ddq[j] = m[2];
            }
            return true;
        }
        let mut moved = [0.0; 3 * EVAL_DIM];
        let moved = &mut moved[..3 * dim];
        shift_orders::<3>(a, t, moved);
        copy_values(moved, dim, need_q, [q, dq, ddq]);
        true
    }

    /// σ, σ′, …, σ⁽⁵⁾ at `s` into `full` (`6·dim` numbers, block k the k-th derivative; σ
    /// moved from the anchor's, zeros there unless `need_q`): the Taylor data of an interval
    /// starting at `s`. Returns `None` (nothing written) when the piece's data are not finite,
    /// else whether all of `full` is finite; when not, σ (if `need_q`), σ′ and σ″ are also
    /// written into `out`, as [`PieceAnchor::eval`] would.
    #[allow(clippy::too_many_arguments)]
    pub(in crate::topp) fn eval_full<P: Path>(
        &mut self,
        path: &P,
        breaks: &[f64],
        b: usize,
        s: f64,
        need_q: bool,
        out: [&mut [f64]; 3],
        full: &mut [f64],
    ) -> Option<bool> {
        let (sm, a) = self.piece(path, breaks, b, need_q)?;
        let dim = a.len() / 6;
        let full = &mut full[..6 * dim];
        shift_taylor(a, s - sm, full);
        // x·0 is 0 for finite x and NaN otherwise: eight running sums, no branch.
        let mut probe = [0.0; 8];
        for chunk in full.chunks(8) {
            for (p, &v) in probe.iter_mut().zip(chunk) {
                *p += v * 0.0;
            }
        }
        if probe.iter().all(|&p| p == 0.0) {
            return Some(true);
        }
        copy_values(full, dim, need_q, out);
        Some(false)
    }
}

/// Copies σ (when `need_q`), σ′ and σ″ of `dim` joints from Taylor data in blocks (`moved`,
/// block k the k-th derivative) into `out`.
fn copy_values(moved: &[f64], dim: usize, need_q: bool, [q, dq, ddq]: [&mut [f64]; 3]) {
    if need_q {
        q.copy_from_slice(&moved[..dim]);
    }
    dq.copy_from_slice(&moved[dim..2 * dim]);
    ddq.copy_from_slice(&moved[2 * dim..3 * dim]);
}

/// The cubic Taylor data (σ, σ′, σ″, σ‴ at s_i) of interval i (length `h`) of a cubic path
/// that touches no breakpoint into `d` (blocks 4 and 5 untouched): from the values at the
/// gridpoints `at_points` (`3·dim` numbers each), σ‴ by differencing σ″.
fn cubic_from_points(at_points: &[f64], dim: usize, i: usize, h: f64, d: &mut [f64]) {
    let (d0, rest) = d.split_at_mut(dim);
    let (d1, rest) = rest.split_at_mut(dim);
    let (d2, rest) = rest.split_at_mut(dim);
    let d3 = &mut rest[..dim];
    let here = &at_points[3 * dim * i..3 * dim * (i + 1)];
    let next_ddq = &at_points[3 * dim * (i + 1) + 2 * dim..3 * dim * (i + 2)];
    d0.copy_from_slice(&here[..dim]);
    d1.copy_from_slice(&here[dim..2 * dim]);
    d2.copy_from_slice(&here[2 * dim..]);
    for j in 0..dim {
        d3[j] = (next_ddq[j] - d2[j]) / h;
    }
}

/// The cubic Taylor data (σ, σ′, σ″, σ‴ at s0) of interval \[s0, s1\] of a cubic path at a
/// breakpoint into `d`: expanded from the midpoint's derivatives (σ zero unless `need_q`).
/// Returns whether all are finite.
fn cubic_taylor_at_break<P: Path>(
    path: &P,
    (s0, s1): (f64, f64),
    need_q: bool,
    d: &mut [f64],
) -> bool {
    let dim = path.dim();
    let (d0, rest) = d.split_at_mut(dim);
    let (d1, rest) = rest.split_at_mut(dim);
    let (d2, rest) = rest.split_at_mut(dim);
    let d3 = &mut rest[..dim];
    let sm = 0.5 * (s0 + s1);
    if need_q {
        path.eval(sm, 0, d0);
    } else {
        d0.iter_mut().for_each(|v| *v = 0.0);
    }
    path.eval_derivatives(sm, d1, d2);
    path.eval(sm, 3, d3);
    // From the midpoint to s0: t = −h/2.
    let t = s0 - sm;
    for j in 0..dim {
        let (a, b, c) = (d1[j], d2[j], d3[j]);
        if need_q {
            d0[j] += t * (a + t * (0.5 * b + t * c / 6.0));
        }
        d1[j] = a + t * (b + 0.5 * t * c);
        d2[j] = b + t * c;
    }
    d.iter().all(|v| v.is_finite())
}

/// Taylor data σ, σ′, …, σ⁽⁵⁾ of a polynomial of degree ≤ 5 (`src`, `6·dim` numbers, block k
/// holding the k-th derivative of every joint) moved by `t` along the parameter into `dst`:
/// each derivative by its Taylor series, exact up to rounding.
fn shift_taylor(src: &[f64], t: f64, dst: &mut [f64]) {
    shift_orders::<6>(src, t, dst);
}

/// Orders `0..M` of the Taylor data `src` (as in [`shift_taylor`]) moved by `t` into `dst`
/// (block m the m-th derivative of every joint): the same operations as [`shift_one`], on
/// four or two joints at a time (fixed-size lanes, which the compiler vectorizes), the last
/// odd joint alone.
#[inline]
fn shift_orders<const M: usize>(src: &[f64], t: f64, dst: &mut [f64]) {
    let dim = src.len() / 6;
    let mut j0 = 0;
    while j0 + 4 <= dim {
        shift_lanes::<M, 4>(src, t, dst, j0);
        j0 += 4;
    }
    if j0 + 2 <= dim {
        shift_lanes::<M, 2>(src, t, dst, j0);
        j0 += 2;
    }
    if j0 < dim {
        let m = shift_one(std::array::from_fn(|k| src[k * dim + j0]), t);
        for (k, mk) in m.into_iter().take(M).enumerate() {
            dst[k * dim + j0] = mk;
        }
    }
}

/// [`shift_orders`] for the joints `j0..j0 + L`.
#[inline(always)]
fn shift_lanes<const M: usize, const L: usize>(src: &[f64], t: f64, dst: &mut [f64], j0: usize) {
    let dim = src.len() / 6;
    let v: [[f64; L]; 6] = std::array::from_fn(|k| {
        let mut lane = [0.0; L];
        lane.copy_from_slice(&src[k * dim + j0..k * dim + j0 + L]);
        lane
    });
    for m in 0..M {
        let mut acc = [0.0; L];
        for k in (m..6).rev() {
            let f = SHIFT_INV[k - m + 1];
            for l in 0..L {
                acc[l] = v[k][l] + acc[l] * t * f;
            }
        }
        dst[m * dim + j0..m * dim + j0 + L].copy_from_slice(&acc);
    }
}

/// 1/1 … 1/6: multiplications instead of divisions in the Taylor shifts.
const SHIFT_INV: [f64; 7] = [0.0, 1.0, 0.5, 1.0 / 3.0, 0.25, 0.2, 1.0 / 6.0];

/// One joint's derivatives `v` (orders 0..5) of a quintic moved by `t`.
#[inline]
fn shift_one(v: [f64; 6], t: f64) -> [f64; 6] {
    std::array::from_fn(|m| {
        // Σ_{k ≥ m} v_k t^{k−m}/(k−m)!, by Horner from the top.
        let mut acc = 0.0;
        for k in (m..6).rev() {
            acc = v[k] + acc * t * SHIFT_INV[k - m + 1];
        }
        acc
    })
}

/// The Taylor data σ, σ′, …, σ⁽⁵⁾ at `s0` (into `d`, `6·dim` numbers) of a path that is a
/// polynomial of degree ≤ 5 on [s0, s1]: evaluated at the midpoint (so that no convention
/// about which piece a breakpoint belongs to matters) and moved to s0. σ is written only when
/// `need_q` (zeros otherwise). Returns whether every value is finite.
fn quintic_taylor<P: Path>(path: &P, s0: f64, s1: f64, need_q: bool, d: &mut [f64]) -> bool {
    let dim = path.dim();
    let sm = 0.5 * (s0 + s1);
    {
        let (q, rest) = d.split_at_mut(dim);
        let (d1, rest) = rest.split_at_mut(dim);
        let (d2, rest) = rest.split_at_mut(dim);
        if need_q {
            path.eval(sm, 0, q);
        }
        path.eval_derivatives(sm, d1, d2);
        // Derivatives above the path's degree are zero (not asked of the path).
        let degree = path.piecewise_degree().unwrap_or(5);
        for k in 3..6 {
            let out = &mut rest[(k - 3) * dim..(k - 2) * dim];
            if k <= degree {
                path.eval(sm, k, out);
            } else {
                out.iter_mut().for_each(|v| *v = 0.0);
            }
        }
    }
    // From the midpoint to s0: t = −h/2 (exact for a quintic).
    let t = s0 - sm;
    for j in 0..dim {
        let moved = shift_one(std::array::from_fn(|k| d[k * dim + j]), t);
        for (k, m) in moved.into_iter().enumerate() {
            d[k * dim + j] = m;
        }
    }
    if !need_q {
        d[..dim].iter_mut().for_each(|v| *v = 0.0);
    }
    d.iter().all(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use crate::spline::PiecewisePolynomial;

    /// The Taylor shift on lanes of joints gives every joint exactly (bit for bit) what the
    /// one-joint shift gives, for every joint count (lanes of four, two and one).
    #[test]
    fn lane_shift_equals_joint_shift() {
        let mut rng = SplitMix64::new(3);
        for dim in 1..=11usize {
            for _ in 0..50 {
                let src: Vec<f64> = (0..6 * dim).map(|_| rng.uniform(-3.0, 3.0)).collect();
                let t = rng.uniform(-0.7, 0.7);
                let mut moved = vec![0.0; 6 * dim];
                shift_taylor(&src, t, &mut moved);
                let mut three = vec![0.0; 3 * dim];
                shift_orders::<3>(&src, t, &mut three);
                for j in 0..dim {
                    let m = shift_one(std::array::from_fn(|k| src[k * dim + j]), t);
                    for k in 0..6 {
                        assert_eq!(
                            moved[k * dim + j].to_bits(),
                            m[k].to_bits(),
                            "{dim} {j} {k}"
                        );
                        if k < 3 {
                            assert_eq!(three[k * dim + j].to_bits(), m[k].to_bits());
                        }
                    }
                }
            }
        }
    }

    /// A random piecewise polynomial of `(dim, pieces, degree)`, piece lengths in `lengths`,
    /// coefficients within ±`c`; and its breakpoints.
    fn random_path(
        rng: &mut SplitMix64,
        (dim, pieces, degree): (usize, usize, usize),
        lengths: (f64, f64),
        c: f64,
    ) -> (Vec<f64>, PiecewisePolynomial) {
        let mut breaks = vec![0.0];
        for _ in 0..pieces {
            let last = breaks[breaks.len() - 1];
            breaks.push(last + rng.uniform(lengths.0, lengths.1));
        }
        let coeffs: Vec<f64> = (0..pieces * dim * (degree + 1))
            .map(|_| rng.uniform(-c, c))
            .collect();
        let path = PiecewisePolynomial::new(breaks.clone(), dim, degree, coeffs).unwrap();
        (breaks, path)
    }

    /// The intervals' Taylor data computed when asked for give the same solve, bit for bit, as
    /// the data kept at every gridpoint, on quintic paths (moved from the pieces' anchors),
    /// with both discretizations.
    #[test]
    fn computed_taylor_data_equal_kept_ones() {
        use crate::topp::{Discretization, Gridpoints, Toppra, ToppraOptions};
        use crate::Limits;
        let mut rng = SplitMix64::new(29);
        let dim = 3;
        let (_, path) = random_path(&mut rng, (dim, 5, 5), (0.3, 1.5), 1.0);
        let limits = Limits::uniform(dim, 1.0, 2.0, f64::INFINITY).unwrap();
        for discretization in [Discretization::Interpolation, Discretization::Collocation] {
            for gridpoints in [
                Gridpoints::Uniform(400),
                Gridpoints::Auto { tolerance: 1e-3 },
            ] {
                let options = ToppraOptions {
                    gridpoints,
                    discretization,
                    ..ToppraOptions::default()
                };
                let solve = |limit: usize| {
                    STORE_LIMIT.with(|c| c.set(limit));
                    let problem = Toppra::with_limits(&path, &limits).unwrap();
                    let p = problem.options(options.clone()).solve_profile().unwrap();
                    STORE_LIMIT.with(|c| c.set(STORE_BYTES));
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    (bits(p.gridpoints()), bits(p.velocities()))
                };
                let kept = solve(usize::MAX);
                assert!(kept.0.len() > 400);
                assert_eq!(kept, solve(0));
            }
        }
    }

    /// σ, σ′, σ″ from a piece's Taylor data (what the solver uses at gridpoints inside a
    /// piece) equal the path's own evaluation up to rounding, on random piecewise polynomials
    /// of degree 1 to 5; and the interval data moved from the piece's midpoint equal the
    /// expansion at the interval's own midpoint.
    #[test]
    fn piece_expansion_matches_path_evaluation() {
        let mut rng = SplitMix64::new(11);
        for degree in 1..=5usize {
            let dim = 3;
            let (breaks, path) = random_path(&mut rng, (dim, 4, degree), (0.2, 2.0), 2.0);
            let mut anchor = PieceAnchor::default();
            anchor.reset(dim);
            let (mut q, mut dq, mut ddq) = (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]);
            let (mut q0, mut dq0, mut ddq0) = (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]);
            for b in 1..breaks.len() {
                for k in 1..10 {
                    let s = breaks[b - 1] + (breaks[b] - breaks[b - 1]) * k as f64 / 10.0;
                    let out = [&mut q[..], &mut dq[..], &mut ddq[..]];
                    assert!(anchor.eval(&path, &breaks, b, s, true, out));
                    path.eval(s, 0, &mut q0);
                    path.eval_derivatives(s, &mut dq0, &mut ddq0);
                    for j in 0..dim {
                        for (a, e) in [(q[j], q0[j]), (dq[j], dq0[j]), (ddq[j], ddq0[j])] {
                            assert!((a - e).abs() <= 1e-12 * (1.0 + e.abs()), "{a} vs {e}");
                        }
                    }
                    // Interval [s, s + h]: moved from the piece's midpoint vs from its own.
                    let h = 0.05 * (breaks[b] - breaks[b - 1]);
                    let mut own = vec![0.0; 6 * dim];
                    assert!(quintic_taylor(&path, s, s + h, true, &mut own));
                    let (sm, a) = anchor.piece(&path, &breaks, b, true).unwrap();
                    let mut moved = vec![0.0; 6 * dim];
                    shift_taylor(a, s - sm, &mut moved);
                    for (m, o) in moved.iter().zip(&own) {
                        assert!((m - o).abs() <= 1e-10 * (1.0 + o.abs()), "{m} vs {o}");
                    }
                }
            }
        }
    }
}
