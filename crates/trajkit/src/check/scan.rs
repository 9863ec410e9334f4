//! The scans behind [`super::check_samples`]: the peak of each velocity, acceleration and
//! jerk series (pointwise and finite difference) of one joint, and the position range.
//!
//! [`PeakTracker`] is the definition, value by value (one division each). [`Extremes`] keeps
//! only the first largest and first smallest value, which decide the peak when every value is
//! finite and no limit is 0 (a correctly rounded division by a constant is monotone); when
//! that does not hold the caller scans again with [`PeakTracker`]. [`JointScan`] runs one
//! joint over the rows (any missing column: the finite difference of the order below stands
//! in for it); [`full_table_scan`] runs a table with every column block by block with the
//! joints side by side ([`RowScan`]: summaries without division, then the definition's
//! arithmetic on the few blocks that can hold each peak). Every path gives the definition's
//! result exactly (same series, same arithmetic, same tie rules), which the tests of
//! [`super`] check against it.

use super::{DerivativeCheck, Peak, PositionCheck};
use crate::limits::{ratio_in, JointLimits, Limits};
use crate::sample::SampleTable;
use crate::traj::Order;

/// A running peak of a series of (time, value) against the directional limits of one
/// order: largest ratio, ties (e.g. all zero for an unlimited joint) broken by the largest
/// magnitude, then by the earliest time.
pub(super) trait PeakScan: Sized {
    /// Empty, for limits `(lo, hi)` (see [`JointLimits::range`]).
    fn new(lo: f64, hi: f64) -> Self;
    /// The next element (times increase).
    fn push(&mut self, time: f64, value: f64);
    /// The peak so far; valid only when [`PeakScan::exact`].
    fn peak(&self) -> Option<Peak>;
    /// True when [`PeakScan::peak`] is the peak the definition gives.
    fn exact(&self) -> bool;
}

/// The definition, element by element (one division each).
#[derive(Debug, Clone, Copy)]
pub(super) struct PeakTracker {
    lo: f64,
    hi: f64,
    pub(super) best: Option<Peak>,
}

impl PeakScan for PeakTracker {
    fn new(lo: f64, hi: f64) -> Self {
        PeakTracker { lo, hi, best: None }
    }

    #[inline]
    fn push(&mut self, time: f64, value: f64) {
        let ratio = ratio_in(self.lo, self.hi, value);
        let better = match &self.best {
            None => true,
            // A NaN ratio (only from overflowing differences) wins, so that it gets reported.
            Some(b) if b.ratio.is_nan() => false,
            Some(b) => {
                ratio.is_nan()
                    || ratio > b.ratio
                    || (ratio == b.ratio && value.abs() > b.value.abs())
            }
        };
        if better {
            self.best = Some(Peak { ratio, value, time });
        }
    }

    fn peak(&self) -> Option<Peak> {
        self.best
    }

    fn exact(&self) -> bool {
        true
    }
}

/// The first largest and the first smallest value and their times: comparisons only.
///
/// When every value is finite and neither limit is 0, a ratio is never NaN, and a correctly
/// rounded division by a constant is monotone: among non-negative values the largest ratio,
/// then the largest magnitude, belongs to the largest value, among negative ones to the
/// smallest value. The peak is then the better of these two candidates by the definition's
/// rule (the earlier one on a full tie), found with two divisions instead of one per value.
/// Otherwise [`PeakScan::exact`] is false and the caller scans again with [`PeakTracker`].
#[derive(Debug, Clone, Copy)]
pub(super) struct Extremes {
    lo: f64,
    hi: f64,
    /// (value, time) of the first largest and the first smallest value; `None` when empty.
    max: Option<(f64, f64)>,
    min: (f64, f64),
    finite: bool,
}

impl Extremes {
    /// The series' first largest and first smallest (value, time), found by the caller, for
    /// limits `(lo, hi)`.
    fn found(lo: f64, hi: f64, max: (f64, f64), min: (f64, f64)) -> Self {
        Extremes {
            lo,
            hi,
            max: Some(max),
            min,
            finite: lo != 0.0 && hi != 0.0,
        }
    }
}

impl PeakScan for Extremes {
    fn new(lo: f64, hi: f64) -> Self {
        Extremes {
            lo,
            hi,
            max: None,
            min: (f64::NAN, f64::NAN),
            finite: lo != 0.0 && hi != 0.0,
        }
    }

    #[inline]
    fn push(&mut self, time: f64, value: f64) {
        self.finite &= value.is_finite();
        match self.max {
            None => {
                self.max = Some((value, time));
                self.min = (value, time);
            }
            Some((m, _)) => {
                if value > m {
                    self.max = Some((value, time));
                }
                if value < self.min.0 {
                    self.min = (value, time);
                }
            }
        }
    }

    fn peak(&self) -> Option<Peak> {
        let (max, t_max) = self.max?;
        let (min, t_min) = self.min;
        let peak = |(value, time): (f64, f64)| Peak {
            ratio: ratio_in(self.lo, self.hi, value),
            value,
            time,
        };
        let candidates = [
            (max >= 0.0).then(|| peak((max, t_max))),
            (min < 0.0).then(|| peak((min, t_min))),
        ];
        let (first, second) = match candidates {
            [Some(a), Some(b)] if b.time < a.time => (b, Some(a)),
            [Some(a), b] => (a, b),
            [None, b] => (b?, None),
        };
        Some(match second {
            Some(b)
                if b.ratio > first.ratio
                    || (b.ratio == first.ratio && b.value.abs() > first.value.abs()) =>
            {
                b
            }
            _ => first,
        })
    }

    fn exact(&self) -> bool {
        self.finite
    }
}

/// One joint's check in one pass over the rows: its position range, and per derivative
/// order the pointwise and finite-difference peaks, with the last element of each order's
/// series (the table's column, or the finite difference of the order below when the column
/// is absent).
pub(super) struct JointScan<S: PeakScan> {
    position_min: f64,
    position_max: f64,
    min: f64,
    max: f64,
    /// Signed distance beyond the nearest bound: negative inside the range.
    beyond: f64,
    time: f64,
    pointwise: [S; 3],
    finite_difference: [S; 3],
    /// The previous element (time, value) of the series of position, velocity, acceleration.
    prev: [Option<(f64, f64)>; 3],
}

pub(super) const DERIVATIVES: [Order; 3] = [Order::Velocity, Order::Acceleration, Order::Jerk];

impl<S: PeakScan> JointScan<S> {
    fn new(jl: &JointLimits, t0: f64) -> Self {
        let scan = |o: Order| {
            let (lo, hi) = jl.range(o);
            S::new(lo, hi)
        };
        JointScan {
            position_min: jl.position_min,
            position_max: jl.position_max,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            beyond: f64::NEG_INFINITY,
            time: t0,
            pointwise: DERIVATIVES.map(scan),
            finite_difference: DERIVATIVES.map(scan),
            prev: [None; 3],
        }
    }

    /// Takes one sample: time `t`, position `q`, and the table's velocity, acceleration and
    /// jerk where present. The divided difference of two consecutive elements of a series,
    /// `(x₁ − x₀)/(t₁ − t₀)`, is attributed to the midpoint of their times.
    #[inline]
    fn push(&mut self, t: f64, q: f64, own: [Option<f64>; 3]) {
        self.position(t, q);
        let mut elem = Some((t, q));
        for k in 0..3 {
            let fd = match (elem, self.prev[k]) {
                (Some(e), Some(p)) => Some((0.5 * (p.0 + e.0), (e.1 - p.1) / (e.0 - p.0))),
                _ => None,
            };
            if elem.is_some() {
                self.prev[k] = elem;
            }
            if let Some((ft, fv)) = fd {
                self.finite_difference[k].push(ft, fv);
            }
            elem = match own[k] {
                Some(v) => {
                    self.pointwise[k].push(t, v);
                    Some((t, v))
                }
                None => fd,
            };
        }
    }

    /// The position range part of [`JointScan::push`]. The range keeps the first smallest and
    /// first largest value (a NaN is skipped, as `f64::min` and `f64::max` skip it; on a tie
    /// of −0 and +0 the earlier one stays), so that [`RowScan`] can take it from its blocks'
    /// extremes.
    #[inline]
    fn position(&mut self, t: f64, q: f64) {
        if q < self.min {
            self.min = q;
        }
        if q > self.max {
            self.max = q;
        }
        let d = (self.position_min - q).max(q - self.position_max);
        if d > self.beyond {
            self.beyond = d;
            self.time = t;
        }
    }

    /// Scans joint `j` of `table`: its position check and derivative checks, and whether
    /// every peak is exact (see [`Extremes`]).
    pub(super) fn run(
        table: &SampleTable,
        jl: &JointLimits,
        j: usize,
    ) -> (PositionCheck, [DerivativeCheck; 3], bool) {
        let (dof, times) = (table.dof(), table.times());
        let q = table.matrix(Order::Position).unwrap_or_default();
        let own = DERIVATIVES.map(|o| table.matrix(o));
        let mut scan = Self::new(jl, times[0]);
        for (i, &t) in times.iter().enumerate() {
            let at = i * dof + j;
            let x = q.get(at).copied().unwrap_or(f64::NAN);
            scan.push(t, x, own.map(|m| m.map(|m| m[at])));
        }
        scan.report()
    }

    /// The position check and derivative checks so far, and whether every peak is exact.
    fn report(&self) -> (PositionCheck, [DerivativeCheck; 3], bool) {
        let scan = self;
        let exact = scan
            .pointwise
            .iter()
            .chain(&scan.finite_difference)
            .all(S::exact);
        let position = PositionCheck {
            min: scan.min,
            max: scan.max,
            excursion: scan.beyond.max(0.0),
            time: scan.time,
        };
        let derivatives = [0, 1, 2].map(|k| DerivativeCheck {
            order: DERIVATIVES[k],
            pointwise: scan.pointwise[k].peak(),
            finite_difference: scan.finite_difference[k].peak(),
        });
        (position, derivatives, exact)
    }
}

/// [`check_samples`] on a table with every column, block by block with the joints side by side
/// ([`RowScan`]): the same series, definitions and arithmetic as [`JointScan`]. `None` when a
/// value or a divided difference is not finite or a limit is 0 (then [`JointScan`] decides,
/// value by value where needed).
pub(super) fn full_table_scan(table: &SampleTable, limits: &Limits) -> Option<Vec<ScanResult>> {
    let (dof, times) = (table.dof(), table.times());
    let m = Order::ALL.map(|o| table.matrix(o));
    let [Some(q), Some(v), Some(a), Some(j)] = m else {
        return None;
    };
    let mut scan = RowScan::new(limits, dof);
    scan.push_rows(times, [q, v, a, j]);
    scan.finish(times, [q, v, a, j])
}

/// One joint's position check and velocity, acceleration and jerk checks.
pub(crate) type ScanResult = (PositionCheck, [DerivativeCheck; 3]);

/// Rows per block of [`RowScan`]'s summaries.
const SUMMARY_ROWS: usize = 128;

/// Series per block summary: the divided-difference numerators of position, velocity and
/// acceleration, then the pointwise velocity, acceleration and jerk.
const SERIES: usize = 6;

/// [`full_table_scan`] fed block by block while the rows are made (the sampling of
/// [`super::sample_and_check`]), then finished on the whole table.
///
/// Pushing a block only summarizes it, with comparisons and subtractions (no division): per
/// joint the largest and smallest pointwise value of each order, of each divided-difference
/// numerator `x₁ − x₀` and of the position (the block's largest position excursion follows
/// from the last two, [`excursion`]), and the smallest and largest time step.
/// [`RowScan::finish`] then finds each peak exactly: a pointwise peak in the first block whose
/// extreme equals the series' extreme; a divided-difference peak among the blocks whose upper
/// bound (numerator extreme over the time-step extremes: a correctly rounded division is
/// monotone in each operand) reaches the largest of the blocks' lower bounds, which the other
/// blocks cannot hold. Those blocks are scanned with the definition's arithmetic and tie rule
/// (first largest, first smallest), so the result is [`JointScan`]'s exactly and does not
/// depend on the block sizes; about one block per series is divided instead of every row.
pub(crate) struct RowScan<'a> {
    limits: &'a Limits,
    dof: usize,
    /// Rows seen so far.
    rows: usize,
    /// The previous row's time and its position, velocity and acceleration (3·dof values).
    prev_t: f64,
    prev: Vec<f64>,
    /// Per block: its rows (from, to).
    blocks: Vec<(usize, usize)>,
    /// Per block: smallest and largest time step of its divided differences (∞, −∞ when it
    /// has none: the first row alone).
    steps: Vec<(f64, f64)>,
    /// Per block, per series ([`SERIES`]): largest values (dof), then smallest (dof).
    extremes: Vec<f64>,
    /// Per block and joint: the largest position excursion `max(lo − q, q − hi)`, from the
    /// block's smallest and largest position ([`excursion`]).
    beyond: Vec<f64>,
    /// Per joint: the running position minimum and maximum, from the blocks' (the first
    /// smallest and first largest, as [`JointScan`] keeps them).
    q_min: Vec<f64>,
    q_max: Vec<f64>,
    /// Every time step seen is positive and finite.
    steps_ok: bool,
    /// Every value seen (the first row and positions included) is finite.
    all_finite: bool,
}

impl<'a> RowScan<'a> {
    /// An empty scan of `dof` joints against `limits` (`limits.dof()` equals `dof`).
    pub(crate) fn new(limits: &'a Limits, dof: usize) -> Self {
        RowScan {
            limits,
            dof,
            rows: 0,
            prev_t: f64::NAN,
            prev: vec![0.0; 3 * dof],
            blocks: Vec::new(),
            steps: Vec::new(),
            extremes: Vec::new(),
            beyond: Vec::new(),
            q_min: vec![f64::INFINITY; dof],
            q_max: vec![f64::NEG_INFINITY; dof],
            steps_ok: true,
            all_finite: true,
        }
    }

    /// True when every value pushed so far, times excluded, is finite.
    pub(crate) fn all_finite(&self) -> bool {
        self.all_finite
    }

    /// The next rows: `times` and, per order (position..jerk), `times.len() × dof` values
    /// row-major.
    pub(crate) fn push_rows(&mut self, times: &[f64], cols: [&[f64]; 4]) {
        let (dof, n) = (self.dof, times.len());
        for c in cols {
            self.all_finite &= all_finite(&c[..n * dof]);
        }
        let mut from = 0;
        while from < n {
            let to = (from + SUMMARY_ROWS).min(n);
            let block = cols.map(|c| &c[from * dof..to * dof]);
            self.push_block(&times[from..to], block);
            from = to;
        }
    }

    /// One block's summary (see [`RowScan`]).
    fn push_block(&mut self, times: &[f64], cols: [&[f64]; 4]) {
        match self.dof {
            1 => self.summarize::<1>(times, cols),
            2 => self.summarize::<2>(times, cols),
            3 => self.summarize::<3>(times, cols),
            4 => self.summarize::<4>(times, cols),
            5 => self.summarize::<5>(times, cols),
            6 => self.summarize::<6>(times, cols),
            7 => self.summarize::<7>(times, cols),
            8 => self.summarize::<8>(times, cols),
            _ => self.summarize_any(times, cols),
        }
    }

    /// [`RowScan::push_block`] for exactly `D` joints: one pass per series over the block with
    /// its running extremes in fixed-size arrays (registers), the same values as
    /// [`RowScan::summarize_any`].
    fn summarize<const D: usize>(&mut self, times: &[f64], cols: [&[f64]; 4]) {
        let m = times.len();
        let rows = |k: usize| cols[k][..m * D].chunks_exact(D).map(fixed::<D>);
        let first = usize::from(self.rows == 0);
        let mut ext = [[f64::NEG_INFINITY; D]; 2 * SERIES];
        for k in 0..3 {
            let (mut mx, mut mn) = (ext[2 * k], ext[2 * k + 1]);
            let mut prev = if first == 1 {
                *fixed::<D>(&cols[k][..D])
            } else {
                *fixed::<D>(&self.prev[k * D..(k + 1) * D])
            };
            mn = mn.map(|_| f64::INFINITY);
            for x in rows(k).skip(first) {
                for j in 0..D {
                    let n = x[j] - prev[j];
                    mx[j] = if n > mx[j] { n } else { mx[j] };
                    mn[j] = if n < mn[j] { n } else { mn[j] };
                }
                prev = *x;
            }
            (ext[2 * k], ext[2 * k + 1]) = (mx, mn);
        }
        for k in 1..4 {
            let (mut mx, mut mn) = (ext[4 + 2 * k], [f64::INFINITY; D]);
            for x in rows(k) {
                for j in 0..D {
                    mx[j] = if x[j] > mx[j] { x[j] } else { mx[j] };
                    mn[j] = if x[j] < mn[j] { x[j] } else { mn[j] };
                }
            }
            (ext[4 + 2 * k], ext[5 + 2 * k]) = (mx, mn);
        }
        let joints = self.limits.joints();
        let lo: [f64; D] = std::array::from_fn(|j| joints[j].position_min);
        let hi: [f64; D] = std::array::from_fn(|j| joints[j].position_max);
        let (mut q_hi, mut q_lo) = ([f64::NEG_INFINITY; D], [f64::INFINITY; D]);
        for q in rows(0) {
            for j in 0..D {
                q_hi[j] = if q[j] > q_hi[j] { q[j] } else { q_hi[j] };
                q_lo[j] = if q[j] < q_lo[j] { q[j] } else { q_lo[j] };
            }
        }
        let beyond: [f64; D] = std::array::from_fn(|j| excursion(lo[j], hi[j], q_lo[j], q_hi[j]));
        self.extend_range(&q_lo, &q_hi);
        self.beyond.extend_from_slice(&beyond);
        self.extremes.extend(ext.iter().flatten());
        self.finish_block(times, cols);
    }

    /// [`RowScan::push_block`] for any number of joints.
    fn summarize_any(&mut self, times: &[f64], cols: [&[f64]; 4]) {
        let (dof, m) = (self.dof, times.len());
        let base = self.extremes.len();
        for _ in 0..SERIES {
            let grow = [f64::NEG_INFINITY, f64::INFINITY].into_iter();
            self.extremes
                .extend(grow.flat_map(|v| std::iter::repeat_n(v, dof)));
        }
        let ext = &mut self.extremes[base..];
        let (mut q_hi, mut q_lo) = (vec![f64::NEG_INFINITY; dof], vec![f64::INFINITY; dof]);
        let row = |k: usize, i: usize| &cols[k][i * dof..(i + 1) * dof];
        for i in 0..m {
            if self.rows + i > 0 {
                for k in 0..3 {
                    let x0 = if i == 0 {
                        &self.prev[k * dof..(k + 1) * dof]
                    } else {
                        row(k, i - 1)
                    };
                    let (mx, mn) = ext[2 * k * dof..2 * (k + 1) * dof].split_at_mut(dof);
                    track(mx, mn, row(k, i).iter().zip(x0).map(|(&x1, &x0)| x1 - x0));
                }
            }
            for k in 1..4 {
                let s = 2 + k;
                let (mx, mn) = ext[2 * s * dof..2 * (s + 1) * dof].split_at_mut(dof);
                track(mx, mn, row(k, i).iter().copied());
            }
            track(&mut q_hi, &mut q_lo, row(0, i).iter().copied());
        }
        let joints = self.limits.joints();
        self.beyond.extend(
            joints
                .iter()
                .zip(q_lo.iter().zip(&q_hi))
                .map(|(jl, (&mn, &mx))| excursion(jl.position_min, jl.position_max, mn, mx)),
        );
        self.extend_range(&q_lo, &q_hi);
        self.finish_block(times, cols);
    }

    /// Widens the running position range by a block's smallest and largest positions (the
    /// first smallest and first largest stay, as in [`JointScan`]).
    fn extend_range(&mut self, q_lo: &[f64], q_hi: &[f64]) {
        for (m, &x) in self.q_max.iter_mut().zip(q_hi) {
            *m = if x > *m { x } else { *m };
        }
        for (m, &x) in self.q_min.iter_mut().zip(q_lo) {
            *m = if x < *m { x } else { *m };
        }
    }

    /// The end of a block's summary (its extremes pushed): its time steps, the previous row
    /// for the next block, its rows.
    fn finish_block(&mut self, times: &[f64], cols: [&[f64]; 4]) {
        let (dof, m) = (self.dof, times.len());
        let (mut step_min, mut step_max) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut t0 = if self.rows == 0 {
            times[0]
        } else {
            self.prev_t
        };
        for &t in &times[usize::from(self.rows == 0)..] {
            let dt = t - t0;
            self.steps_ok &= dt > 0.0 && dt.is_finite();
            step_min = if dt < step_min { dt } else { step_min };
            step_max = if dt > step_max { dt } else { step_max };
            t0 = t;
        }
        for (k, p) in self.prev.chunks_exact_mut(dof).enumerate() {
            p.copy_from_slice(&cols[k][(m - 1) * dof..m * dof]);
        }
        self.prev_t = times[m - 1];
        self.blocks.push((self.rows, self.rows + m));
        self.steps.push((step_min, step_max));
        self.rows += m;
    }

    /// Per joint, its checks, from the summaries and the whole table (`times` and the four
    /// row-major columns that were pushed); `None` when no row was pushed, a value or a
    /// divided difference is not finite (or may not be) or a limit is 0 (see
    /// [`full_table_scan`]).
    pub(crate) fn finish(self, times: &[f64], cols: [&[f64]; 4]) -> Option<Vec<ScanResult>> {
        if self.rows == 0 || !(self.steps_ok && self.all_finite) {
            return None;
        }
        let mut out = Vec::with_capacity(self.dof);
        for j in 0..self.dof {
            let jl = self.limits.joint(j);
            let mut scan = JointScan::<Extremes>::new(jl, times[0]);
            scan.min = self.q_min[j];
            scan.max = self.q_max[j];
            if let Some(b) = first_block_max(self.beyond.iter().skip(j).step_by(self.dof).copied())
            {
                let excursion = |i: usize| {
                    let q = cols[0][i * self.dof + j];
                    (jl.position_min - q).max(q - jl.position_max)
                };
                let (from, to) = self.blocks[b];
                let peak = self.beyond[b * self.dof + j];
                let i = (from..to).find(|&i| excursion(i) == peak)?;
                (scan.beyond, scan.time) = (excursion(i), times[i]);
            }
            for k in 0..3 {
                let (lo, hi) = jl.range(DERIVATIVES[k]);
                let (mx, mn) = self.pointwise(k + 1, j, times, cols[k + 1])?;
                scan.pointwise[k] = Extremes::found(lo, hi, mx, mn);
                if self.rows > 1 {
                    let (mx, mn) = self.divided(k, j, times, cols[k])?;
                    scan.finite_difference[k] = Extremes::found(lo, hi, mx, mn);
                }
            }
            let (p, d, exact) = scan.report();
            if !exact {
                return None;
            }
            out.push((p, d));
        }
        Some(out)
    }

    /// The block summary's (largest, smallest) of series `s` for joint `j` in block `b`.
    fn summary(&self, b: usize, s: usize, j: usize) -> (f64, f64) {
        let at = (b * SERIES + s) * 2 * self.dof + j;
        (self.extremes[at], self.extremes[at + self.dof])
    }

    /// The first largest and first smallest (value, time) of order `k`'s pointwise series of
    /// joint `j` (`col` its column): found in the first block whose extreme is the series'.
    fn pointwise(
        &self,
        k: usize,
        j: usize,
        times: &[f64],
        col: &[f64],
    ) -> Option<((f64, f64), (f64, f64))> {
        let s = 2 + k;
        let blocks = 0..self.blocks.len();
        let hi = first_block_max(blocks.clone().map(|b| self.summary(b, s, j).0))?;
        let lo = first_block_max(blocks.map(|b| -self.summary(b, s, j).1))?;
        let find = |b: usize, peak: f64| {
            let (from, to) = self.blocks[b];
            let i = (from..to).find(|&i| col[i * self.dof + j] == peak)?;
            Some((col[i * self.dof + j], times[i]))
        };
        Some((
            find(hi, self.summary(hi, s, j).0)?,
            find(lo, self.summary(lo, s, j).1)?,
        ))
    }

    /// The first largest and first smallest (value, midpoint time) of the divided differences
    /// of joint `j` in order `k`'s column `col`, scanning only the blocks whose bounds may hold
    /// them (see [`RowScan`]); `None` when a bound is not finite.
    fn divided(
        &self,
        k: usize,
        j: usize,
        times: &[f64],
        col: &[f64],
    ) -> Option<((f64, f64), (f64, f64))> {
        let dof = self.dof;
        // Per block with divided differences: (lower, upper) bounds of its largest and of its
        // smallest element.
        let mut bounds = Vec::with_capacity(self.blocks.len());
        let (mut max_floor, mut min_ceiling) = (f64::NEG_INFINITY, f64::INFINITY);
        for (b, &(dt_min, dt_max)) in self.steps.iter().enumerate() {
            if dt_min > dt_max {
                bounds.push(None);
                continue;
            }
            let (n_max, n_min) = self.summary(b, k, j);
            let (a, c) = (n_max / dt_min, n_max / dt_max);
            let (e, f) = (n_min / dt_min, n_min / dt_max);
            if !(a.is_finite() && c.is_finite() && e.is_finite() && f.is_finite()) {
                return None;
            }
            let (hi, lo) = ((a.min(c), a.max(c)), (e.min(f), e.max(f)));
            max_floor = max_floor.max(hi.0);
            min_ceiling = min_ceiling.min(lo.1);
            bounds.push(Some((hi, lo)));
        }
        let mut best_max: Option<(f64, f64)> = None;
        let mut best_min: Option<(f64, f64)> = None;
        for (b, bound) in bounds.iter().enumerate() {
            let Some((hi, lo)) = bound else { continue };
            let (want_max, want_min) = (hi.1 >= max_floor, lo.0 <= min_ceiling);
            if !(want_max || want_min) {
                continue;
            }
            let (from, to) = self.blocks[b];
            for i in from.max(1)..to {
                let (t0, t1) = (times[i - 1], times[i]);
                let d = (col[i * dof + j] - col[(i - 1) * dof + j]) / (t1 - t0);
                let mid = 0.5 * (t0 + t1);
                if want_max && best_max.is_none_or(|m| d > m.0) {
                    best_max = Some((d, mid));
                }
                if want_min && best_min.is_none_or(|m| d < m.0) {
                    best_min = Some((d, mid));
                }
            }
        }
        Some((best_max?, best_min?))
    }
}

/// Running largest and smallest per joint: `mx[j]` and `mn[j]` replaced by a strictly larger
/// (smaller) value only, as the definition's first-largest rule.
#[inline]
fn track(mx: &mut [f64], mn: &mut [f64], values: impl Iterator<Item = f64>) {
    for ((mx, mn), v) in mx.iter_mut().zip(mn.iter_mut()).zip(values) {
        *mx = if v > *mx { v } else { *mx };
        *mn = if v < *mn { v } else { *mn };
    }
}

/// Independent sums of [`all_finite`]: enough that the additions of one chunk do not wait for
/// the previous chunk's (eight two-lane vector registers).
const FINITE_LANES: usize = 16;

/// True when every value of `values` is finite: [`FINITE_LANES`] independent lanes (`x · 0` is
/// 0 for a finite `x`, NaN otherwise, and a NaN stays in its lane's sum), so that the test runs
/// in vector registers without a branch per value.
fn all_finite(values: &[f64]) -> bool {
    let mut lanes = [0.0f64; FINITE_LANES];
    let chunks = values.chunks_exact(FINITE_LANES);
    let tail = chunks.remainder();
    for c in chunks {
        let c = fixed::<FINITE_LANES>(c);
        for (l, &x) in lanes.iter_mut().zip(c) {
            *l += x * 0.0;
        }
    }
    lanes.iter().chain(tail).all(|x| x.is_finite())
}

/// The largest position excursion `max(lo − q, q − hi)` of a block from its smallest and
/// largest position `q_lo`, `q_hi`: a correctly rounded subtraction is monotone in each
/// operand, so `lo − q` is largest at the smallest q and `q − hi` at the largest, and this is
/// the largest of the rows' own excursions, bit for bit (every value finite).
#[inline]
fn excursion(lo: f64, hi: f64, q_lo: f64, q_hi: f64) -> f64 {
    (lo - q_lo).max(q_hi - hi)
}

/// A row (or chunk) of exactly `D` values.
#[inline]
fn fixed<const D: usize>(row: &[f64]) -> &[f64; D] {
    row.try_into().expect("a row of D values")
}

/// The index of the first strictly largest value; `None` when empty or none exceeds −∞.
fn first_block_max(values: impl Iterator<Item = f64>) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (b, v) in values.enumerate() {
        if v > best.map_or(f64::NEG_INFINITY, |x| x.1) {
            best = Some((b, v));
        }
    }
    best.map(|x| x.0)
}

#[cfg(test)]
mod tests {
    use super::all_finite;

    #[test]
    fn all_finite_finds_each_non_finite_value_in_any_lane_or_the_tail() {
        for len in [0, 1, 7, 8, 9, 15, 16, 17, 23, 31, 32, 33, 47] {
            let v: Vec<f64> = (0..len).map(|i| (i as f64 - 5.0) * 1e300).collect();
            assert!(all_finite(&v), "len {len}");
            for at in 0..len {
                for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    let mut w = v.clone();
                    w[at] = bad;
                    assert!(!all_finite(&w), "len {len}, {bad} at {at}");
                }
            }
        }
    }
}
