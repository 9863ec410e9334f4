//! The time-scale factor of a filtered law, bounded on the whole continuous trajectory.
//!
//! The moving average s_w of a TOPP-RA law s* (constant s̈* between gridpoint times T_i) is a
//! cubic polynomial in t between consecutive *kinks*: the times T_i, the times T_i + w, and the
//! times where s_w crosses a breakpoint of the path. On such a segment
//! `s⃛_w = (s̈*(t) − s̈*(t − w))/w` is constant, and where the path is a polynomial of degree
//! d ≤ 6 (every trajkit spline and polyline) each joint's q̇, q̈ and q⃛ is a polynomial in t.
//! [`scale_bound`] sweeps the segments in time order (the gridpoint indices of t and t − w are
//! known, so no value is taken from the wrong side of a kink) and bounds each of them:
//!
//! - the path is evaluated once per segment, at the middle of its s-range, for σ′..σ⁽ᵈ⁾; the
//!   derivatives at the segment's ends and middle follow from the Taylor expansion of the
//!   polynomial piece (exact, and one-sided at path breakpoints by construction);
//! - each of f = q̇ⱼ, q̈ⱼ, q⃛ⱼ is interpolated by the quadratic p through its values at the
//!   ends and the middle, and `|f − p| ≤ M₃·h³/(72√3)` on a segment of length h, where
//!   M₃ ≥ |f‴| is bounded by Faà di Bruno's formula with absolute values: q⁽ⁿ⁾ =
//!   Σₖ σ⁽ᵏ⁾(s)·Bₙ,ₖ(ṡ, s̈, s⃛, 0, …) (complete Bell polynomials; s⁽⁴⁾ = 0 on a segment), with
//!   |σ⁽ᵏ⁾| bounded on the segment's s-range from the Taylor coefficients and |ṡ|, |s̈|, |s⃛|
//!   bounded exactly (a quadratic, a line and a constant in t);
//! - so `max f ≤ max p + M₃h³/(72√3)` and `min f ≥ min p − M₃h³/(72√3)`, with the extremum of
//!   the quadratic in closed form. The segments are a few milliseconds long, so the margin
//!   is about 1e-9 of the limits where the limits bind.
//!
//! The factor is `k = max(r_v, √r_a, ∛r_j)` over these bounds (r: the fraction of the
//! directional limit used): played k times slower, the trajectory holds every velocity,
//! acceleration and jerk limit at every instant, up to rounding.
//!
//! Paths that are not piecewise polynomials of degree ≤ 6 ([`crate::Path::piecewise_degree`])
//! are evaluated directly at [`SAMPLED_POINTS`] points per segment instead, and the result is
//! marked as sampled ([`ScaleBound::certified`] false): no bound between those points.
//!
//! The sweep finds the segments in time order and keeps them (a few dozen bytes each); its
//! cost is linear in the number of TOPP-RA gridpoints (each gives at most two kinks). Two
//! shortcuts leave the factor bitwise unchanged: a joint whose cheap interval bound cannot
//! raise the running lower bound of the factor is not bounded further, and a segment where
//! that holds for every joint by the (larger) bounds of its path *cell* (`cells.rs`) is
//! skipped before its own derivative bounds are formed. The cell test runs per joint too:
//! a segment's derivative bounds are formed only for the joints it leaves (about a quarter
//! of them on the standard 7-waypoint problem at the Panda's limits, where almost no segment
//! is skipped whole), and the values at the three points only up to the highest order that
//! still needs them. To make the running lower bound large early, the
//! segments whose cell bounds are largest among every sixteenth one are bounded first (`SEEDS`
//! of them), then the rest in time order, each segment's law shape, cell and cell test
//! computed once: only which segments are skipped depends on the order, and a skipped
//! segment cannot change the result. Where the factor is close to 1 (the limits bind almost
//! everywhere along a time-optimal law) few segments can be skipped; with low jerk limits
//! most are.

use super::cells::Cells;
use super::segments::{Cubic, RawLaw};
use super::FilteredProfile;
use crate::topp::rescale::TimeLaw;
use crate::{Limits, Order, Path};

/// Points per segment on paths that are not piecewise polynomials (no bound between them).
pub const SAMPLED_POINTS: usize = 9;

/// Segments bounded first, those with the largest bounds from their path cells (see
/// `Sweep::bound_spans`).
const SEEDS: usize = 32;

/// Seeds are chosen among every `SEED_STRIDE`-th segment (neighbours have nearly the same
/// bounds), so that finding them costs a fraction of the sweep.
const SEED_STRIDE: usize = 16;

/// Highest path degree the certified bound handles (s⁽ⁿ⁾ and σ⁽ⁿ⁾ up to n = 6 appear).
const MAX_DEGREE: usize = 6;

/// What [`scale_bound`] found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScaleBound {
    /// The smallest uniform slow-down that meets every limit: `max(r_v, √r_a, ∛r_j)` over the
    /// bounds of every segment (an upper bound of the exact factor when `certified`).
    pub factor: f64,
    /// The same over the evaluated points only (a lower bound of the exact factor).
    pub sampled: f64,
    /// True when the path is a piecewise polynomial of degree ≤ 6, so that `factor` bounds
    /// the trajectory between the evaluated points too.
    pub certified: bool,
    /// Segments (pieces between kinks) examined.
    pub segments: usize,
    /// Where the factor is reached: time (of the unscaled law), joint, order.
    pub at: (f64, usize, Order),
}

/// Per-joint limit reciprocals: ratio = value·hi for value ≥ 0, value·lo below (0 when
/// unlimited).
struct Inverse {
    hi: [Vec<f64>; 3],
    lo: [Vec<f64>; 3],
    /// max(hi, −lo): the ratio of a magnitude against the smaller directional limit.
    sym: [Vec<f64>; 3],
}

impl Inverse {
    fn new(limits: &Limits) -> Self {
        let inv = |x: f64| if x.is_finite() { 1.0 / x } else { 0.0 };
        let mut hi: [Vec<f64>; 3] = Default::default();
        let mut lo: [Vec<f64>; 3] = Default::default();
        for (o, order) in [Order::Velocity, Order::Acceleration, Order::Jerk]
            .into_iter()
            .enumerate()
        {
            for j in limits.joints() {
                let (l, h) = j.range(order);
                hi[o].push(inv(h));
                lo[o].push(inv(l));
            }
        }
        let sym =
            [0, 1, 2].map(|o: usize| hi[o].iter().zip(&lo[o]).map(|(h, l)| h.max(-l)).collect());
        Inverse { hi, lo, sym }
    }

    /// The fraction of the limit used by values in `[lo, hi]`.
    #[inline]
    fn ratio(&self, o: usize, j: usize, lo: f64, hi: f64) -> f64 {
        (hi * self.hi[o][j]).max(lo * self.lo[o][j])
    }
}

/// The sweep's scratch buffers and running maxima.
struct Sweep<'a, P: Path> {
    path: &'a P,
    inv: Inverse,
    dim: usize,
    degree: Option<usize>,
    breaks: Vec<f64>,
    /// Per path piece: its middle s, then σ⁽ᵐ⁾ there for m = 0..=degree (index
    /// (piece·(degree + 1) + m)·dim + j).
    ref_s: Vec<f64>,
    ref_der: Vec<f64>,
    /// Bounds of |σ′|, |σ″|, |σ‴| on short cells of the path pieces, each at least the
    /// segment bound `sb` of any segment within the cell ([`Cells`]): a segment where no
    /// joint's cheap bound from these can raise the factor is skipped before its own bounds
    /// are computed (see [`Sweep::bound_spans`]).
    cells: Cells,
    /// Whether that test runs, the same test per joint, and [`Sweep::joint_derivatives`]
    /// (only for joints that pass it) stands in for [`Sweep::derivative_bounds`] (always,
    /// except in the test that shows that none of this changes anything).
    shortcuts: bool,
    /// Segments skipped whole that way.
    skipped: usize,
    /// The segments found by the sweep, bounded afterwards (see [`Sweep::bound_spans`]).
    spans: Vec<Span>,
    /// The path piece of the current segment.
    piece: usize,
    /// Per segment, σ⁽ᵐ⁾ at its middle and bounds of |σ⁽ᵐ⁾| on it (index m·dim + j).
    md: Vec<f64>,
    sb: Vec<f64>,
    /// Largest certified ratio per order (velocity, acceleration, jerk), where it occurs.
    bound: [f64; 3],
    at: [(f64, usize); 3],
    /// Largest factor max(r_v, √r_a, ∛r_j) at evaluated points (a lower bound of the result),
    /// and its powers 1, 2, 3: a joint and order whose bound stays below are skipped.
    k_low: f64,
    threshold: [f64; 3],
    segments: usize,
}

/// One segment between kinks as the sweep finds it: the law on it (τ from the cubic's
/// origin), its τ-range, the law's time at τ = 0 and the path piece that holds it.
#[derive(Debug, Clone, Copy)]
struct Span {
    cub: Cubic,
    t0: f64,
    t1: f64,
    time: f64,
    piece: usize,
}

/// The law's state on a segment `[t0, t1]` of a [`Cubic`].
struct Shape {
    /// The middle τ.
    tm: f64,
    /// ṡ and s̈ at the start, middle and end.
    sd: [f64; 3],
    sdd: [f64; 3],
    /// Bounds of |ṡ|, |s̈|, |s⃛| on the segment.
    x: [f64; 3],
    /// s at the start, middle and end, and the larger distance of the ends from the middle.
    s: [f64; 3],
    reach: f64,
}

impl Shape {
    #[inline]
    fn new(cub: &Cubic, t0: f64, t1: f64) -> Self {
        let tm = 0.5 * (t0 + t1);
        let sddd = cub.c[3];
        let times = [t0, tm, t1];
        let sd = times.map(|t| cub.sd(t));
        let sdd = times.map(|t| cub.sdd(t));
        // |ṡ|, |s̈| on the segment (s̈ linear, ṡ quadratic with its vertex at s̈ = 0).
        let x2 = sdd[0].abs().max(sdd[2].abs());
        let mut x1 = sd[0].abs().max(sd[2].abs());
        if sddd != 0.0 {
            let tv = -cub.c[2] / sddd;
            if tv > t0 && tv < t1 {
                x1 = x1.max(cub.sd(tv).abs());
            }
        }
        let s = times.map(|t| cub.s(t));
        let reach = (s[0] - s[1]).abs().max((s[2] - s[1]).abs());
        Shape {
            tm,
            sd,
            sdd,
            x: [x1, x2, sddd.abs()],
            s,
            reach,
        }
    }
}

/// What every joint of one segment shares in [`Sweep::poly_segment`].
struct Segment {
    /// Taylor weights dⁱ/i! (see `poly_segment`).
    wts: [[f64; MAX_DEGREE + 1]; 5],
    /// ṡ and s̈ at the start, middle and end; the constant s⃛.
    sd: [f64; 3],
    sdd: [f64; 3],
    sddd: f64,
    /// Bounds of |ṡ|, |s̈|, |s⃛| on the segment.
    x: [f64; 3],
    /// h³/(72√3): the remainder factor of the quadratic interpolation.
    rem: f64,
    /// The law's time at the middle.
    at: f64,
}

/// Complete Bell polynomials B_{n,k}(x1, x2, x3, 0, 0, 0) for n = 4, 5, 6 and k = 2..=6 (x4 and
/// above vanish: s is a cubic in t on a segment).
fn bell(n: usize, x1: f64, x2: f64, x3: f64) -> [f64; 7] {
    let (x1s, x2s) = (x1 * x1, x2 * x2);
    match n {
        4 => [
            0.0,
            0.0,
            4.0 * x1 * x3 + 3.0 * x2s,
            6.0 * x1s * x2,
            x1s * x1s,
            0.0,
            0.0,
        ],
        5 => [
            0.0,
            0.0,
            10.0 * x2 * x3,
            10.0 * x1s * x3 + 15.0 * x1 * x2s,
            10.0 * x1s * x1 * x2,
            x1s * x1s * x1,
            0.0,
        ],
        _ => [
            0.0,
            0.0,
            10.0 * x3 * x3,
            60.0 * x1 * x2 * x3 + 15.0 * x2s * x2,
            20.0 * x1s * x1 * x3 + 45.0 * x1s * x2s,
            15.0 * x1s * x1s * x2,
            x1s * x1s * x1s,
        ],
    }
}

/// Raises each of `acc` to `x` where `x` is larger; NaN propagates (a NaN in `x` is kept, and
/// a NaN in `acc` stays).
#[inline]
fn max_nan(acc: &mut [f64; 3], x: [f64; 3]) {
    for (a, x) in acc.iter_mut().zip(x) {
        if x.is_nan() || x > *a {
            *a = x;
        }
    }
}

/// Range of the quadratic through (0, f0), (½, fm), (1, f1) on [0, 1].
///
/// The vertex x = −b/(2c) is formed only when it can lie in (0, 1): b and c of opposite
/// signs and |b| < |2c| (otherwise x ≤ 0, x ≥ 1 after rounding too, or NaN, and the test
/// below fails anyway), which saves the division on most segments.
#[inline]
fn quadratic_range(f0: f64, fm: f64, f1: f64) -> (f64, f64) {
    let c = 2.0 * (f0 + f1) - 4.0 * fm;
    let b = f1 - f0 - c;
    let (mut lo, mut hi) = (f0.min(f1).min(fm), f0.max(f1).max(fm));
    let inside = ((b < 0.0 && c > 0.0) || (b > 0.0 && c < 0.0)) && b.abs() < (2.0 * c).abs();
    if inside {
        let x = -b / (2.0 * c);
        if x > 0.0 && x < 1.0 {
            let v = f0 + x * (b + c * x);
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    (lo, hi)
}

impl<P: Path> Sweep<'_, P> {
    /// Bounds one segment `[t0, t1]` (τ relative to the cubic's origin) that lies within one
    /// piece of the path; `time` is the law's time at τ = 0; `sh`: the law's [`Shape`] on it.
    /// With a `cell` (the segment's path cell, [`Cells::cell`]), the joints are first tested
    /// on its bounds; `open`: the joints (bit j) that test leaves, `u64::MAX` when it has
    /// not run ([`Sweep::cell_test`]).
    fn segment(&mut self, span: &Span, sh: &Shape, cell: Option<usize>, open: u64) {
        let Span {
            ref cub,
            t0,
            t1,
            time,
            piece,
        } = *span;
        self.piece = piece;
        match self.degree {
            Some(1) => self.poly_segment::<1>(span, sh, cell, open),
            Some(2) => self.poly_segment::<2>(span, sh, cell, open),
            Some(3) => self.poly_segment::<3>(span, sh, cell, open),
            Some(4) => self.poly_segment::<4>(span, sh, cell, open),
            Some(5) => self.poly_segment::<5>(span, sh, cell, open),
            Some(_) => self.poly_segment::<6>(span, sh, cell, open),
            None => self.sampled_segment(cub, t0, t1, time),
        }
    }

    /// A value of order `o` found at a point: raises the lower bound of the factor.
    #[inline]
    fn sampled(&mut self, o: usize, r: f64) {
        if r > self.threshold[o] {
            let k = match o {
                0 => r,
                1 => r.sqrt(),
                _ => r.cbrt(),
            };
            if k > self.k_low {
                self.k_low = k;
                self.threshold = [k, k * k, k * k * k];
            }
        }
    }

    /// [`Sweep::segment`] on a path of degree ≤ `D`. With the shortcuts, joint by joint:
    /// a joint whose cheap bound from the path cell cannot raise the factor is skipped before
    /// its own derivative bounds are formed (they could not raise it either: [`Cells`]), the
    /// others get them one joint at a time ([`Sweep::joint_derivatives`]); without, every
    /// joint's at once ([`Sweep::derivative_bounds`]). Same values, same decisions, in joint
    /// order.
    fn poly_segment<const D: usize>(
        &mut self,
        span: &Span,
        sh: &Shape,
        cell: Option<usize>,
        open: u64,
    ) {
        let Span {
            ref cub,
            t0,
            t1,
            time,
            ..
        } = *span;
        let h = t1 - t0;
        let &Shape {
            tm,
            sd,
            sdd,
            x,
            s: [s0, sm, s1],
            reach,
        } = sh;
        let sddd = cub.c[3];
        // Taylor weights dⁱ/i! of: the middle's offset from the piece's reference point, the
        // three points' offsets from the middle, and the largest of those. Only i < D is
        // used (a shift of a degree-D polynomial, or a bound of its derivatives 1..=D).
        let offsets = [sm - self.ref_s[self.piece], s0 - sm, 0.0, s1 - sm, reach];
        let mut wts = [[0.0f64; MAX_DEGREE + 1]; 5];
        for (q, (wt, &d)) in wts.iter_mut().zip(&offsets).enumerate() {
            wt[0] = 1.0;
            // The middle's own offset is 0: its weights are 1, 0, 0, … (as the loop gives).
            if q == 2 {
                continue;
            }
            for i in 1..D {
                wt[i] = wt[i - 1] * d / i as f64;
            }
        }
        let seg = Segment {
            wts,
            sd,
            sdd,
            sddd,
            x,
            rem: h * h * h / (72.0 * 3f64.sqrt()),
            at: time + tm,
        };
        let mut bells = None;
        let dim = self.dim;
        if !self.shortcuts {
            self.derivative_bounds::<D>(&seg.wts);
            for j in 0..dim {
                let md = std::array::from_fn(|m| self.md[m * dim + j]);
                let sb = std::array::from_fn(|k| self.sb[k * dim + j]);
                self.poly_joint::<D>(&seg, j, &md, &sb, &mut bells);
            }
            return;
        }
        // Joints the cell test leaves (the thresholds only grow: a joint it skips now stays
        // skippable; the others are decided on their own bounds, as without it).
        for j in 0..dim {
            if j < 64 && open & (1 << j) == 0 {
                continue;
            }
            if let (Some(c), true) = (cell, open == u64::MAX) {
                let pb = &self.cells.bounds[c * 3 * dim..(c + 1) * 3 * dim];
                let cheap = self.cheap(j, [pb[j], pb[dim + j], pb[2 * dim + j]], x);
                if (0..3).all(|o| cheap[o] <= self.threshold[o]) {
                    continue;
                }
            }
            let (md, sb) = self.joint_derivatives::<D>(&seg.wts, j);
            self.poly_joint::<D>(&seg, j, &md, &sb, &mut bells);
        }
    }

    /// σ⁽ᵐ⁾ of joint `j` at the segment's middle and bounds of |σ⁽ᵏ⁾| on the segment
    /// (index m, k): the sums of [`Sweep::derivative_bounds`] for one joint, in the same
    /// order (bitwise the same values).
    #[inline]
    fn joint_derivatives<const D: usize>(
        &self,
        wts: &[[f64; MAX_DEGREE + 1]; 5],
        j: usize,
    ) -> ([f64; MAX_DEGREE + 1], [f64; MAX_DEGREE + 1]) {
        let dim = self.dim;
        let base = self.piece * (D + 1) * dim + j;
        let rd: [f64; MAX_DEGREE + 1] = std::array::from_fn(|m| {
            if m <= D {
                self.ref_der[base + m * dim]
            } else {
                0.0
            }
        });
        let mut md = [0.0f64; MAX_DEGREE + 1];
        for m in 1..D + 1 {
            let mut acc = 0.0;
            for mm in m..D + 1 {
                acc += rd[mm] * wts[0][mm - m];
            }
            md[m] = acc;
        }
        let mut sb = [0.0f64; MAX_DEGREE + 1];
        for k in 1..D + 1 {
            let mut acc = 0.0;
            for m in k..D + 1 {
                acc += md[m].abs() * wts[4][m - k];
            }
            sb[k] = acc;
        }
        (md, sb)
    }

    /// σ⁽ᵐ⁾ at the segment's middle from the piece's reference point (exact for a
    /// polynomial) into `md`, and bounds of |σ⁽ᵏ⁾| on the segment into `sb`, for every joint
    /// at once (index m·dim + j; joints innermost: independent sums that vectorize, each
    /// joint's in the same order as one joint at a time).
    #[inline]
    fn derivative_bounds<const D: usize>(&mut self, wts: &[[f64; MAX_DEGREE + 1]; 5]) {
        let dim = self.dim;
        let base = self.piece * (D + 1) * dim;
        let rd = &self.ref_der[base..base + (D + 1) * dim];
        let (md, sb) = (&mut self.md[..(D + 1) * dim], &mut self.sb[..(D + 1) * dim]);
        md.fill(0.0);
        sb.fill(0.0);
        for m in 1..=D {
            let dst = &mut md[m * dim..(m + 1) * dim];
            for mm in m..=D {
                let w = wts[0][mm - m];
                for (d, &r) in dst.iter_mut().zip(&rd[mm * dim..(mm + 1) * dim]) {
                    *d += r * w;
                }
            }
        }
        for k in 1..=D {
            let dst = &mut sb[k * dim..(k + 1) * dim];
            for m in k..=D {
                let w = wts[4][m - k];
                for (d, &x) in dst.iter_mut().zip(&md[m * dim..(m + 1) * dim]) {
                    *d += x.abs() * w;
                }
            }
        }
    }

    /// One joint `j` of [`Sweep::poly_segment`], from its σ⁽ᵐ⁾ at the middle `md` and
    /// bounds `sb` of |σ⁽ᵏ⁾| on the segment: a cheap interval bound that skips the joint when
    /// it cannot raise the factor, else the quadratic range plus the certified remainder per
    /// order (values formed only up to the highest order that needs them).
    /// `bells` (the segment's Bell polynomials) is computed on first need.
    #[inline]
    fn poly_joint<const D: usize>(
        &mut self,
        seg: &Segment,
        j: usize,
        md: &[f64; MAX_DEGREE + 1],
        sb: &[f64; MAX_DEGREE + 1],
        bells: &mut Option<[[f64; 7]; 3]>,
    ) {
        let wts = &seg.wts;
        let [x1, x2, x3] = seg.x;
        // Interval bounds of |q̇|, |q̈|, |q⃛|: skip the joint when none can matter (NaN does).
        let cheap = self.cheap(j, [sb[1], sb[2], sb[3]], seg.x);
        let needed = |o: usize| cheap[o] > self.threshold[o] || cheap[o].is_nan();
        let Some(top) = (0..3).rev().find(|&o| needed(o)) else {
            return;
        };
        let value = |p: usize| -> [f64; 3] {
            let wt = &wts[p + 1];
            let mut d = [0.0f64; 3];
            for (k, dk) in d.iter_mut().enumerate().take(top + 1) {
                for m in (k + 1)..D + 1 {
                    *dk += md[m] * wt[m - k - 1];
                }
            }
            let (v, a) = (seg.sd[p], seg.sdd[p]);
            [
                d[0] * v,
                d[1] * v * v + d[0] * a,
                d[2] * v * v * v + 3.0 * d[1] * v * a + d[0] * seg.sddd,
            ]
        };
        let f = [value(0), value(1), value(2)];
        let bells = bells.get_or_insert_with(|| {
            [
                bell(4, x1, x2, x3),
                bell(5, x1, x2, x3),
                bell(6, x1, x2, x3),
            ]
        });
        for o in 0..=top {
            if cheap[o] <= self.threshold[o] {
                continue;
            }
            let (mut lo, mut hi) = quadratic_range(f[0][o], f[1][o], f[2][o]);
            let r = self.inv.ratio(o, j, lo, hi);
            self.sampled(o, r);
            let b = &bells[o];
            let mut m3 = 0.0;
            for k in 2..D.min(o + 4) + 1 {
                m3 += sb[k] * b[k];
            }
            let e = m3 * seg.rem;
            lo -= e;
            hi += e;
            let r = self.inv.ratio(o, j, lo, hi);
            if r > self.bound[o] {
                self.bound[o] = r;
                self.at[o] = (seg.at, j);
            }
        }
    }

    /// The cell test of a segment with law shape `sh` in path cell `cell`: per order the
    /// largest cheap bound ([`Sweep::cheap`]) of any joint from the cell's bounds (each at
    /// least the segment's own, see [`Cells`]; infinite when there is no cell or a bound is
    /// NaN), and the joints (bit j) whose cheap bound exceeds a running threshold in some order
    /// (`u64::MAX`: no cell, or not 6 or 7 joints; [`Sweep::poly_segment`] then tests joint by
    /// joint, the same arithmetic).
    #[inline]
    fn cell_test(&self, sh: &Shape, cell: Option<usize>) -> ([f64; 3], u64) {
        let Some(c) = cell else {
            return ([f64::INFINITY; 3], u64::MAX);
        };
        let (reach, open) = match self.dim {
            6 => self.cell_test_n::<6, true>(c, sh.x),
            7 => self.cell_test_n::<7, true>(c, sh.x),
            dim => {
                let pb = &self.cells.bounds[c * 3 * dim..(c + 1) * 3 * dim];
                let mut reach = [0.0f64; 3];
                for j in 0..dim {
                    let cheap = self.cheap(j, [pb[j], pb[dim + j], pb[2 * dim + j]], sh.x);
                    max_nan(&mut reach, cheap);
                }
                (reach, u64::MAX)
            }
        };
        if reach.iter().any(|v| v.is_nan()) {
            ([f64::INFINITY; 3], open)
        } else {
            (reach, open)
        }
    }

    /// [`Sweep::cell_test`] of cell `c` for `N` joints in fixed-size arrays, before its NaN
    /// test (the arithmetic of [`Sweep::cheap`]: the same values as joint by joint). Without
    /// `REACH` only the open joints are found (the reach stays 0): what [`Sweep::visit`]
    /// needs.
    #[inline(always)]
    fn cell_test_n<const N: usize, const REACH: bool>(
        &self,
        c: usize,
        [x1, x2, x3]: [f64; 3],
    ) -> ([f64; 3], u64) {
        let pb = &self.cells.bounds[c * 3 * N..(c + 1) * 3 * N];
        let row = |v: &[f64]| -> [f64; N] { std::array::from_fn(|j| v[j]) };
        let (b0, b1, b2) = (row(&pb[..N]), row(&pb[N..2 * N]), row(&pb[2 * N..]));
        let sym: [[f64; N]; 3] = std::array::from_fn(|o| row(&self.inv.sym[o]));
        let t = self.threshold;
        let (mut reach, mut open) = ([0.0f64; 3], 0u64);
        for j in 0..N {
            let cheap = [
                b0[j] * x1 * sym[0][j],
                (b1[j] * x1 * x1 + b0[j] * x2) * sym[1][j],
                (b2[j] * x1 * x1 * x1 + 3.0 * b1[j] * x1 * x2 + b0[j] * x3) * sym[2][j],
            ];
            let skip = (cheap[0] <= t[0]) & (cheap[1] <= t[1]) & (cheap[2] <= t[2]);
            open |= u64::from(!skip) << j;
            if REACH {
                max_nan(&mut reach, cheap);
            }
        }
        (reach, open)
    }

    /// Interval bounds of |q̇ⱼ|, |q̈ⱼ|, |q⃛ⱼ| as fractions of the limit, from bounds `b` of
    /// |σ′ⱼ|, |σ″ⱼ|, |σ‴ⱼ| and `x` of |ṡ|, |s̈|, |s⃛| (non-negative: the result does not decrease
    /// when a bound grows, rounding included).
    #[inline]
    fn cheap(&self, j: usize, b: [f64; 3], [x1, x2, x3]: [f64; 3]) -> [f64; 3] {
        [
            b[0] * x1 * self.inv.sym[0][j],
            (b[1] * x1 * x1 + b[0] * x2) * self.inv.sym[1][j],
            (b[2] * x1 * x1 * x1 + 3.0 * b[1] * x1 * x2 + b[0] * x3) * self.inv.sym[2][j],
        ]
    }

    /// [`Sweep::segment`] on a path that is not a piecewise polynomial: direct evaluation at
    /// [`SAMPLED_POINTS`] points, no bound between them.
    fn sampled_segment(&mut self, cub: &Cubic, t0: f64, t1: f64, time: f64) {
        let dim = self.dim;
        let sddd = cub.c[3];
        let mut buf = [0.0; 3 * crate::topp::rescale::MAX_DOF];
        for p in 0..SAMPLED_POINTS {
            let t = t0 + (t1 - t0) * p as f64 / (SAMPLED_POINTS - 1) as f64;
            let (s, sd, sdd) = (cub.s(t), cub.sd(t), cub.sdd(t));
            for m in 1..=3 {
                self.path.eval(s, m, &mut buf[(m - 1) * dim..m * dim]);
            }
            for j in 0..dim {
                let (d1, d2, d3) = (buf[j], buf[dim + j], buf[2 * dim + j]);
                let v = [
                    d1 * sd,
                    d2 * sd * sd + d1 * sdd,
                    d3 * sd * sd * sd + 3.0 * d2 * sd * sdd + d1 * sddd,
                ];
                for o in 0..3 {
                    let r = self.inv.ratio(o, j, v[o], v[o]);
                    self.sampled(o, r);
                    if r > self.bound[o] {
                        self.bound[o] = r;
                        self.at[o] = (time + t, j);
                    }
                }
            }
        }
    }
}

/// The time-scale factor of `law` on `path` under `limits` (see the module documentation).
/// `path` and `limits` must have the law's dimension (checked by the caller).
pub fn scale_bound<P: Path>(path: &P, law: &FilteredProfile, limits: &Limits) -> ScaleBound {
    let mut sw = Sweep::new(path, limits);
    sw.sweep(law);
    sw.result()
}

impl<'a, P: Path> Sweep<'a, P> {
    /// The sweep's buffers: limit reciprocals, and on a piecewise polynomial of degree ≤ 6
    /// the derivatives at the middle of every path piece.
    fn new(path: &'a P, limits: &Limits) -> Self {
        let dim = path.dim();
        let degree = path.piecewise_degree().filter(|&d| d <= MAX_DEGREE);
        let breaks = path.breakpoints();
        let (mut ref_s, mut ref_der) = (Vec::new(), Vec::new());
        if let Some(d) = degree {
            let pieces = breaks.len().saturating_sub(1);
            ref_s.reserve(pieces);
            ref_der.resize(pieces * (d + 1) * dim, 0.0);
            for (p, pair) in breaks.windows(2).enumerate() {
                let mid = 0.5 * (pair[0] + pair[1]);
                ref_s.push(mid);
                for m in 1..=d {
                    let at = (p * (d + 1) + m) * dim;
                    path.eval(mid, m, &mut ref_der[at..at + dim]);
                }
            }
        }
        Sweep {
            path,
            inv: Inverse::new(limits),
            dim,
            degree,
            breaks,
            ref_s,
            ref_der,
            cells: Cells::default(),
            shortcuts: true,
            skipped: 0,
            spans: Vec::new(),
            piece: 0,
            md: vec![0.0; (MAX_DEGREE + 1) * dim],
            sb: vec![0.0; (MAX_DEGREE + 1) * dim],
            bound: [0.0; 3],
            at: [(0.0, 0); 3],
            k_low: 0.0,
            threshold: [0.0; 3],
            segments: 0,
        }
    }

    /// Bounds every segment of `law` ([`Sweep::bound_spans`]), found in time order: the kinks are the gridpoint times T_i
    /// (index `i` of the raw interval at t) and T_i + w (index `k` at t − w), and the
    /// segments between them are cut where s crosses a path breakpoint.
    fn sweep(&mut self, law: &FilteredProfile) {
        if let Some(d) = self.degree {
            self.cells = Cells::new(&self.breaks, &self.ref_s, &self.ref_der, d, self.dim, law);
        }
        let raw = RawLaw::new(law);
        let (gs, n, w) = (raw.p.gridpoints(), raw.n, raw.w);
        let end = raw.p.times()[n] + w;
        // At most two kinks per gridpoint, plus the path breakpoints crossed.
        self.spans.reserve(2 * n + self.breaks.len() + 4);
        let (mut i, mut k) = (0isize, -1isize);
        let mut a = 0.0;
        let mut s_at_a = gs[0];
        // First path breakpoint above the current s.
        let mut bp = self.breaks.partition_point(|&b| b <= s_at_a);
        let mut count = 0usize;
        loop {
            let b = raw.next_i(i).min(raw.next_k(k)).min(end);
            if b > a {
                if count % 256 == 0 && a > 0.0 {
                    // Re-anchor the propagated s on the exact moving average.
                    s_at_a = law.eval(a)[0];
                }
                count += 1;
                let cub = raw.cubic(i, k, a, s_at_a);
                let s_end = cub.s(b - a).clamp(gs[0], gs[n]);
                self.cut_at_breakpoints(&cub, b - a, s_end, a, &mut bp);
                s_at_a = s_end;
            }
            if b >= end {
                break;
            }
            if raw.next_i(i) <= b {
                i += 1;
            }
            if raw.next_k(k) <= b {
                k += 1;
            }
            a = b;
        }
        self.bound_spans();
    }

    /// Records the segment `[0, h]` of `cub` (the law from time `a` on), cut where s crosses
    /// the path breakpoints from index `bp` on (advanced past them) up to `s_end`.
    fn cut_at_breakpoints(&mut self, cub: &Cubic, h: f64, s_end: f64, a: f64, bp: &mut usize) {
        let mut t_prev = 0.0;
        let last_piece = self.breaks.len().saturating_sub(2);
        let span = |t0: f64, t1: f64, bp: usize| Span {
            cub: *cub,
            t0,
            t1,
            time: a,
            piece: bp.saturating_sub(1).min(last_piece),
        };
        while *bp < self.breaks.len() && self.breaks[*bp] < s_end {
            let tc = cub.time_at(self.breaks[*bp], t_prev, h);
            if tc > t_prev {
                self.spans.push(span(t_prev, tc, *bp));
                t_prev = tc;
            }
            *bp += 1;
        }
        self.spans.push(span(t_prev, h, *bp));
    }

    /// Bounds the segments found by [`Sweep::sweep`]. With the shortcuts on a piecewise
    /// polynomial, the [`SEEDS`] segments with the largest cheap bounds ([`Sweep::cheap`])
    /// that any joint could reach from the bounds of their path cells
    /// ([`Sweep::cell_test`]), among every [`SEED_STRIDE`]-th segment, are bounded first, so
    /// the running lower bound of the factor is near its final value before the others are
    /// visited; then every other segment in time order, skipped whole when no order's cell
    /// reach exceeds the running threshold ([`Sweep::visit`]).
    /// Only skip decisions change with the order, never a value: the factor is the same, bit
    /// for bit, as in time order without any skip.
    fn bound_spans(&mut self) {
        let spans = std::mem::take(&mut self.spans);
        self.segments += spans.len();
        if !(self.shortcuts && self.degree.is_some()) {
            for sp in &spans {
                self.segment(sp, &Shape::new(&sp.cub, sp.t0, sp.t1), None, u64::MAX);
            }
            return;
        }
        // Seeds: the largest first-order estimates of the factor the cell reaches allow
        // (√x ≤ (1 + x)/2 and ∛x ≤ (2 + x)/3, tight near 1 where factors are); segments that
        // fit no cell are visited in time order anyway.
        let estimate = |c: &[f64; 3]| {
            if c[0].is_finite() {
                c[0].max(0.5 * (1.0 + c[1])).max((2.0 + c[2]) / 3.0)
            } else {
                f64::NEG_INFINITY
            }
        };
        let mut order: Vec<(f64, usize)> = (0..spans.len())
            .step_by(SEED_STRIDE)
            .map(|i| {
                let sp = &spans[i];
                let sh = Shape::new(&sp.cub, sp.t0, sp.t1);
                let cell = self.cells.cell(sp.piece, sh.s[1], sh.reach);
                (estimate(&self.cell_test(&sh, cell).0), i)
            })
            .collect();
        let seeds = SEEDS.min(order.len());
        if seeds > 0 && seeds < order.len() {
            order.select_nth_unstable_by(seeds - 1, |a, b| b.0.total_cmp(&a.0));
        }
        let mut seeded = vec![false; spans.len()];
        for &(_, i) in &order[..seeds] {
            seeded[i] = true;
            self.visit(&spans[i]);
        }
        for (sp, done) in spans.iter().zip(seeded) {
            if !done {
                self.visit(sp);
            }
        }
    }

    /// Bounds the segment unless, by its cell test ([`Sweep::cell_test`]), no joint's cheap
    /// bound exceeds the running thresholds: then every joint of the segment would be skipped
    /// by [`Sweep::poly_joint`] too, and the segment changes nothing.
    ///
    /// On 6 and 7 joints in a cell the test is whether any joint is open: every order's
    /// reach is at most its threshold exactly when every joint's cheap bounds are (a NaN
    /// fails both), so the reach itself is not formed.
    #[inline]
    fn visit(&mut self, sp: &Span) {
        let sh = Shape::new(&sp.cub, sp.t0, sp.t1);
        let cell = self.cells.cell(sp.piece, sh.s[1], sh.reach);
        let (skip, open) = match (cell, self.dim) {
            (Some(c), 6) => {
                let open = self.cell_test_n::<6, false>(c, sh.x).1;
                (open == 0, open)
            }
            (Some(c), 7) => {
                let open = self.cell_test_n::<7, false>(c, sh.x).1;
                (open == 0, open)
            }
            _ => {
                let (c, open) = self.cell_test(&sh, cell);
                ((0..3).all(|o| c[o] <= self.threshold[o]), open)
            }
        };
        if skip {
            self.skipped += 1;
        } else {
            self.segment(sp, &sh, cell, open);
        }
    }

    /// The factor and where it is reached.
    fn result(&self) -> ScaleBound {
        let roots = |r: [f64; 3]| r[0].max(r[1].sqrt()).max(r[2].cbrt());
        let certified = roots(self.bound);
        let factor = certified.max(self.k_low);
        let which = if factor == self.bound[0] {
            0
        } else if factor == self.bound[1].sqrt() {
            1
        } else {
            2
        };
        let (t_at, j_at) = self.at[which];
        ScaleBound {
            factor,
            sampled: self.k_low,
            certified: self.degree.is_some(),
            segments: self.segments,
            at: (
                t_at,
                j_at,
                [Order::Velocity, Order::Acceleration, Order::Jerk][which],
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`scale_bound`] with the whole-segment and per-joint cell skips and the per-joint
    /// bounds on or off, and
    /// the segments skipped.
    fn scale_bound_skipping<P: Path>(
        path: &P,
        law: &FilteredProfile,
        limits: &Limits,
        shortcuts: bool,
    ) -> (ScaleBound, usize) {
        let mut sw = Sweep::new(path, limits);
        sw.shortcuts = shortcuts;
        sw.sweep(law);
        (sw.result(), sw.skipped)
    }

    /// Skipping whole segments by the bounds of their cell (seeded order included), and the
    /// per-joint cell skip and derivative bounds, change nothing, bit for bit, on seeded random
    /// Panda paths (7 joints, the first 6, the first 3) at the Panda's limits and at low jerk
    /// limits, and do skip many segments
    /// (about half here: few at the Panda's limits, where the factor is near 1, most at low
    /// jerk limits).
    #[test]
    fn skipping_whole_segments_changes_nothing() {
        use crate::topp::messy::{plan_waypoints, PlanOptions};
        let mut rng = crate::rng::SplitMix64::new(5);
        let (mut total, mut skipped) = (0, 0);
        // 7 and 6 joints: the cell test of all joints at once; 3: one joint at a time.
        for (case, dim) in [7, 7, 7, 7, 7, 7, 6, 6, 3, 3].into_iter().enumerate() {
            let panda =
                Limits::new(Limits::preset("panda").unwrap().joints()[..dim].to_vec()).unwrap();
            let mut low = panda.joints().to_vec();
            low.iter_mut().for_each(|j| j.jerk *= 0.01);
            let low = Limits::new(low).unwrap();
            let w: Vec<f64> = (0..5)
                .flat_map(|_| panda.joints().to_vec())
                .map(|j| rng.uniform(j.position_min + 0.2, j.position_max - 0.2))
                .collect();
            let limits = if case % 2 == 0 { &panda } else { &low };
            let raw = plan_waypoints(&w, dim, limits, &PlanOptions::default()).unwrap();
            for piece in raw.pieces() {
                let win = filter_window(piece.law(), piece.path(), limits, 0.5)
                    .unwrap()
                    .unwrap();
                let law = FilteredProfile::new(piece.law().clone(), win).unwrap();
                let (on, n) = scale_bound_skipping(piece.path(), &law, limits, true);
                let (off, none) = scale_bound_skipping(piece.path(), &law, limits, false);
                assert_eq!(none, 0);
                assert_eq!(format!("{on:?}"), format!("{off:?}"), "case {case}");
                assert_eq!(on.factor.to_bits(), off.factor.to_bits());
                assert_eq!(on, scale_bound(piece.path(), &law, limits));
                total += on.segments;
                skipped += n;
            }
        }
        println!("skipped {skipped} of {total} segments");
        assert!(skipped * 4 > total, "skipped {skipped} of {total}");
    }
    /// The vertex test without the division's pre-test gives the same range, bit for bit,
    /// on random, tiny, huge, signed-zero, infinite and NaN values.
    #[test]
    fn quadratic_range_pretest_changes_nothing() {
        fn plain(f0: f64, fm: f64, f1: f64) -> (f64, f64) {
            let c = 2.0 * (f0 + f1) - 4.0 * fm;
            let b = f1 - f0 - c;
            let (mut lo, mut hi) = (f0.min(f1).min(fm), f0.max(f1).max(fm));
            if c != 0.0 {
                let x = -b / (2.0 * c);
                if x > 0.0 && x < 1.0 {
                    let v = f0 + x * (b + c * x);
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            }
            (lo, hi)
        }
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            0.25,
            1e-310,
            -1e-310,
            1e300,
            -1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        let mut rng = crate::rng::SplitMix64::new(11);
        let mut cases: Vec<[f64; 3]> = Vec::new();
        for &a in &special {
            for &b in &special {
                for &c in &special {
                    cases.push([a, b, c]);
                }
            }
        }
        for _ in 0..200_000 {
            let scale = 10f64.powi((rng.uniform(-8.0, 8.0)) as i32);
            let f0 = rng.uniform(-1.0, 1.0) * scale;
            // Near-linear, near-symmetric and generic middles.
            let fm = match cases.len() % 3 {
                0 => 0.5 * (f0 + rng.uniform(-1.0, 1.0) * scale),
                1 => f0 + rng.uniform(-1e-12, 1e-12) * scale,
                _ => rng.uniform(-1.0, 1.0) * scale,
            };
            cases.push([f0, fm, rng.uniform(-1.0, 1.0) * scale]);
        }
        for [f0, fm, f1] in cases {
            let (a, b) = (quadratic_range(f0, fm, f1), plain(f0, fm, f1));
            assert_eq!(
                (a.0.to_bits(), a.1.to_bits()),
                (b.0.to_bits(), b.1.to_bits()),
                "{f0} {fm} {f1}"
            );
        }
    }

    use crate::spline::CubicSpline;
    use crate::topp::jerk::filter_window;
    use crate::topp::rescale::{min_time_scale, Retimed};
    use crate::topp::Toppra;

    /// The analytic factor bounds dense sampling from above, and closely.
    #[test]
    fn factor_bounds_dense_sampling_tightly() {
        let s = [0.0, 0.4, 0.9, 1.3, 2.0];
        let w = [
            0.0, 0.0, 0.0, //
            0.3, -0.2, 0.1, //
            0.5, 0.1, 0.4, //
            0.2, 0.5, 0.6, //
            0.6, 0.3, 1.0,
        ];
        let path = CubicSpline::natural(&s, &w, 3).unwrap();
        for jerk in [50.0, 2000.0] {
            let limits = Limits::uniform(3, 1.0, 3.0, jerk).unwrap();
            let raw = Toppra::with_limits(path.clone(), &limits)
                .unwrap()
                .solve()
                .unwrap();
            let win = filter_window(raw.law(), &path, &limits, 0.5)
                .unwrap()
                .unwrap();
            let law = FilteredProfile::new(raw.law().clone(), win).unwrap();
            let b = scale_bound(&path, &law, &limits);
            assert!(b.certified && b.segments > 10, "{b:?}");
            let traj = Retimed::new(&path, law).unwrap();
            let dense = min_time_scale(&traj, &limits, 200_000.0).unwrap();
            assert!(
                b.factor >= dense * (1.0 - 1e-12),
                "bound {} below sampled {dense}",
                b.factor
            );
            assert!(
                b.factor <= dense * (1.0 + 1e-5),
                "bound {} loose against {dense}",
                b.factor
            );
            assert!(b.sampled <= b.factor);
        }
    }
}
