//! The scans behind [`super::check_samples`]: the peak of each velocity, acceleration and
//! jerk series (pointwise and finite difference) of one joint, and the position range.
//!
//! [`PeakTracker`] is the definition, value by value (one division each). [`Extremes`] keeps
//! only the first largest and first smallest value, which decide the peak when every value is
//! finite and no limit is 0 (a correctly rounded division by a constant is monotone); when
//! that does not hold the caller scans again with [`PeakTracker`]. [`JointScan`] runs one
//! joint over the rows (any missing column: the finite difference of the order below stands
//! in for it); [`full_table_scan`] runs a table with every column row by row with the joints
//! side by side. Every path gives the definition's result exactly (same series, same
//! arithmetic, same tie rules), which the tests of [`super`] check against it.

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

    /// The position range part of [`JointScan::push`].
    #[inline]
    fn position(&mut self, t: f64, q: f64) {
        self.min = self.min.min(q);
        self.max = self.max.max(q);
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

/// Running first-largest and first-smallest values (with their times) of one series per
/// joint, joints side by side (index j), for [`full_table_scan`].
pub(super) struct ExtremesRow {
    max: Vec<f64>,
    t_max: Vec<f64>,
    min: Vec<f64>,
    t_min: Vec<f64>,
}

impl ExtremesRow {
    /// Starts every joint's series with its first element (`values` at `time`).
    fn first(time: f64, values: &[f64]) -> Self {
        ExtremesRow {
            max: values.to_vec(),
            t_max: vec![time; values.len()],
            min: values.to_vec(),
            t_min: vec![time; values.len()],
        }
    }

    /// The next element of every joint's series (the caller checks that they are finite).
    #[inline]
    fn push(&mut self, time: f64, values: &[f64]) {
        let it = self.max.iter_mut().zip(&mut self.t_max);
        let it = it.zip(self.min.iter_mut().zip(&mut self.t_min));
        for (((mx, tmx), (mn, tmn)), &v) in it.zip(values) {
            let (up, down) = (v > *mx, v < *mn);
            *mx = if up { v } else { *mx };
            *tmx = if up { time } else { *tmx };
            *mn = if down { v } else { *mn };
            *tmn = if down { time } else { *tmn };
        }
    }

    /// Joint `j`'s series as [`Extremes`] for limits `(lo, hi)`.
    fn joint(&self, j: usize, (lo, hi): (f64, f64)) -> Extremes {
        Extremes {
            lo,
            hi,
            max: Some((self.max[j], self.t_max[j])),
            min: (self.min[j], self.t_min[j]),
            finite: lo != 0.0 && hi != 0.0,
        }
    }
}

/// [`check_samples`] on a table with every column, row by row with the joints side by side
/// (the divided differences of a row share its time step, so they vectorize): the same
/// series, definitions and arithmetic as [`JointScan`]. `None` when a value is not finite or
/// a limit is 0 (then [`JointScan`] decides, value by value where needed).
pub(super) fn full_table_scan(table: &SampleTable, limits: &Limits) -> Option<Vec<ScanResult>> {
    let (dof, times) = (table.dof(), table.times());
    let m = Order::ALL.map(|o| table.matrix(o));
    let [Some(q), Some(v), Some(a), Some(j)] = m else {
        return None;
    };
    let mut scan = RowScan::new(limits, dof);
    scan.push_rows(times, [q, v, a, j]);
    scan.finish()
}

/// One joint's position check and velocity, acceleration and jerk checks.
pub(crate) type ScanResult = (PositionCheck, [DerivativeCheck; 3]);

/// [`full_table_scan`] fed block by block while the rows are made (the sampling of
/// [`super::sample_and_check`]), so that each block is checked while it is in cache: every
/// column present, the rows of a block as consecutive row-major slices. The state between
/// blocks is the previous row, so that the result does not depend on the block sizes and is
/// [`full_table_scan`]'s exactly.
pub(crate) struct RowScan<'a> {
    limits: &'a Limits,
    dof: usize,
    /// Rows seen so far.
    rows: usize,
    /// The previous row's time and its position, velocity and acceleration (3·dof values).
    prev_t: f64,
    prev: Vec<f64>,
    /// Pointwise series of velocity, acceleration, jerk; finite-difference series of
    /// position, velocity, acceleration (from the second row on).
    pointwise: Option<[ExtremesRow; 3]>,
    fd: Option<[ExtremesRow; 3]>,
    /// Per joint: the position part of [`JointScan`].
    position: Vec<JointScan<Extremes>>,
    diff: Vec<f64>,
    /// Every divided difference seen is finite.
    finite: bool,
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
            pointwise: None,
            fd: None,
            position: Vec::with_capacity(dof),
            diff: vec![0.0; 3 * dof],
            finite: true,
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
        if n == 0 {
            return;
        }
        for c in cols {
            self.all_finite &= c[..n * dof].iter().fold(true, |f, v| f & v.is_finite());
        }
        let row = |k: usize, i: usize| &cols[k][i * dof..(i + 1) * dof];
        let mut from = 0;
        if self.rows == 0 {
            let t = times[0];
            self.pointwise = Some([1, 2, 3].map(|k| ExtremesRow::first(t, row(k, 0))));
            self.position = (0..dof)
                .map(|j| JointScan::new(self.limits.joint(j), t))
                .collect();
            from = 1;
        }
        let pointwise = self.pointwise.as_mut().expect("set on the first row");
        for i in from..n {
            let (t0, prev) = if i == 0 {
                let p = &self.prev;
                (self.prev_t, [0, 1, 2].map(|k| &p[k * dof..(k + 1) * dof]))
            } else {
                (times[i - 1], [0, 1, 2].map(|k| row(k, i - 1)))
            };
            let t1 = times[i];
            let (dt, mid) = (t1 - t0, 0.5 * (t0 + t1));
            for (k, d) in self.diff.chunks_exact_mut(dof).enumerate() {
                for ((d, &x1), &x0) in d.iter_mut().zip(row(k, i)).zip(prev[k]) {
                    *d = (x1 - x0) / dt;
                }
                pointwise[k].push(t1, row(k + 1, i));
            }
            let diff = &self.diff;
            self.finite &= diff.iter().fold(true, |f, d| f & d.is_finite());
            let diffs = |k: usize| &diff[k * dof..(k + 1) * dof];
            match &mut self.fd {
                Some(f) => {
                    for (k, f) in f.iter_mut().enumerate() {
                        f.push(mid, diffs(k));
                    }
                }
                None => {
                    self.fd = Some([0, 1, 2].map(|k| ExtremesRow::first(mid, diffs(k))));
                }
            }
        }
        for (j, scan) in self.position.iter_mut().enumerate() {
            for (i, &t) in times.iter().enumerate() {
                scan.position(t, cols[0][i * dof + j]);
            }
        }
        for (k, p) in self.prev.chunks_exact_mut(dof).enumerate() {
            p.copy_from_slice(row(k, n - 1));
        }
        self.prev_t = times[n - 1];
        self.rows += n;
    }

    /// Per joint, its checks; `None` when no row was pushed, a value or a difference is not
    /// finite or a limit is 0 (see [`full_table_scan`]).
    pub(crate) fn finish(self) -> Option<Vec<ScanResult>> {
        if !(self.finite && self.all_finite) {
            return None;
        }
        let pointwise = self.pointwise?;
        let out = self.position.into_iter().enumerate().map(|(j, mut scan)| {
            let jl = self.limits.joint(j);
            for k in 0..3 {
                let range = jl.range(DERIVATIVES[k]);
                scan.pointwise[k] = pointwise[k].joint(j, range);
                if let Some(f) = &self.fd {
                    scan.finite_difference[k] = f[k].joint(j, range);
                }
            }
            scan.report()
        });
        let out: Vec<_> = out.collect();
        out.iter()
            .all(|r| r.2)
            .then(|| out.into_iter().map(|r| (r.0, r.1)).collect())
    }
}
