//! Sampling a trajectory at a fixed rate into a table, and the table type itself.
//!
//! A [`SampleTable`] holds rows `(t, q, q̇, q̈, q⃛)` for `dof` joints. It is what trajkit writes
//! (CSV, JSON: see [`crate::io`]) and what [`crate::check`] reads, including tables produced by
//! other tools, where the derivative columns may be missing.
//!
//! Sampling includes both ends: with duration T and rate f the times are `k/f` for
//! `k = 0..floor(T·f)`, plus `T` itself when `T` is not on that grid (the last interval is then
//! shorter). Every sample is an exact evaluation of the trajectory.

use crate::error::{Error, Result};
use crate::traj::{Order, Trajectory};

/// A sampled trajectory: times and, per derivative order, a row-major `rows × dof` matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleTable {
    dof: usize,
    /// Sample times, non-decreasing.
    t: Vec<f64>,
    /// The present derivative matrices (row-major, `rows × dof` each), one after the other
    /// in one allocation: a large table is then one block of memory, which the allocator
    /// reuses from one table to the next instead of mapping fresh pages for each column.
    values: Vec<f64>,
    /// Where derivative order k (position..jerk) starts in `values`, or `None` if absent.
    offsets: [Option<usize>; 4],
    /// Joint names (may be empty strings).
    names: Vec<String>,
}

impl SampleTable {
    /// Builds a table from times and per-order row-major columns (`rows × dof` each). Positions
    /// are required; missing derivatives are `None`. Checks sizes, finiteness and that time
    /// increases strictly.
    pub fn new(dof: usize, t: Vec<f64>, data: [Option<Vec<f64>>; 4]) -> Result<Self> {
        if dof == 0 {
            return Err(Error::DimensionMismatch {
                what: "sample table joint count".into(),
                expected: 1,
                found: 0,
            });
        }
        let rows = t.len();
        if data[0].is_none() {
            return Err(Error::InvalidValue {
                field: "sample table positions".into(),
                value: f64::NAN,
                reason: "are missing",
            });
        }
        for (k, col) in data.iter().enumerate() {
            if let Some(c) = col {
                if c.len() != rows * dof {
                    return Err(Error::DimensionMismatch {
                        what: format!("sample table {} entries", Order::ALL[k].name()),
                        expected: rows * dof,
                        found: c.len(),
                    });
                }
                if let Some(i) = c.iter().position(|v| !v.is_finite()) {
                    return Err(Error::InvalidValue {
                        field: format!(
                            "sample {} {} of joint {}",
                            i / dof,
                            Order::ALL[k].name(),
                            i % dof + 1
                        ),
                        value: c[i],
                        reason: "is not a finite number",
                    });
                }
            }
        }
        for i in 0..rows {
            if !t[i].is_finite() {
                return Err(Error::InvalidValue {
                    field: format!("sample {i} time"),
                    value: t[i],
                    reason: "is not a finite number",
                });
            }
            if i > 0 && t[i] <= t[i - 1] {
                return Err(Error::InvalidValue {
                    field: format!("sample {i} time"),
                    value: t[i],
                    reason: "does not increase",
                });
            }
        }
        let present = data.iter().filter(|c| c.is_some()).count();
        let mut offsets = [None; 4];
        let mut values = Vec::new();
        for (k, col) in data.into_iter().enumerate() {
            if let Some(c) = col {
                offsets[k] = Some(values.len());
                if present == 1 {
                    values = c;
                } else {
                    values.reserve_exact(present * rows * dof - values.len());
                    values.extend_from_slice(&c);
                }
            }
        }
        Ok(SampleTable {
            dof,
            t,
            values,
            offsets,
            names: vec![String::new(); dof],
        })
    }

    /// A table of every derivative, `values` holding the four `rows × dof` matrices one after
    /// the other (position first), already known to be finite, with times known to increase
    /// strictly (made by sampling): [`SampleTable::new`] without its checks and copies.
    pub(crate) fn from_sampled(dof: usize, t: Vec<f64>, values: Vec<f64>) -> Self {
        let n = t.len() * dof;
        debug_assert_eq!(values.len(), 4 * n);
        debug_assert!(t.windows(2).all(|w| w[1] > w[0]));
        SampleTable {
            dof,
            t,
            values,
            offsets: [0, 1, 2, 3].map(|k| Some(k * n)),
            names: vec![String::new(); dof],
        }
    }

    /// The four `rows × dof` matrices of `values` (position..jerk, one after the other), as
    /// [`SampleTable::from_sampled`] takes them.
    pub(crate) fn split_matrices(values: &mut [f64], rows: usize, dof: usize) -> [&mut [f64]; 4] {
        let n = rows * dof;
        let (q, rest) = values.split_at_mut(n);
        let (v, rest) = rest.split_at_mut(n);
        let (a, j) = rest.split_at_mut(n);
        [q, v, a, &mut j[..n]]
    }

    /// Sets joint names (used as column headers); `names.len()` must equal `dof`.
    pub fn with_names(mut self, names: Vec<String>) -> Result<Self> {
        if names.len() != self.dof {
            return Err(Error::DimensionMismatch {
                what: "joint name count".into(),
                expected: self.dof,
                found: names.len(),
            });
        }
        self.names = names;
        Ok(self)
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// True when there are no samples.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Sample times.
    pub fn times(&self) -> &[f64] {
        &self.t
    }

    /// Joint names (possibly empty strings).
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// True when derivative `order` is present.
    pub fn has(&self, order: Order) -> bool {
        self.offsets[order.index()].is_some()
    }

    /// Row `i` of derivative `order` (`dof` values), if that derivative is present.
    pub fn row(&self, order: Order, i: usize) -> Option<&[f64]> {
        self.matrix(order)
            .map(|c| &c[i * self.dof..(i + 1) * self.dof])
    }

    /// Value of derivative `order` for joint `j` at sample `i`, if present.
    pub fn value(&self, order: Order, i: usize, j: usize) -> Option<f64> {
        self.matrix(order).map(|c| c[i * self.dof + j])
    }

    /// The whole row-major matrix of derivative `order`, if present.
    pub fn matrix(&self, order: Order) -> Option<&[f64]> {
        let n = self.t.len() * self.dof;
        self.offsets[order.index()].map(|o| &self.values[o..o + n])
    }

    /// Duration: last time minus first time (0 for fewer than two samples).
    pub fn duration(&self) -> f64 {
        match (self.t.first(), self.t.last()) {
            (Some(a), Some(b)) => b - a,
            _ => 0.0,
        }
    }
}

/// The sample times for a duration and a rate (see the module docs).
pub fn sample_times(duration: f64, rate_hz: f64) -> Result<Vec<f64>> {
    crate::error::positive(|| "sample rate (Hz)".into(), rate_hz)?;
    if !(duration.is_finite() && duration >= 0.0) {
        return Err(Error::InvalidValue {
            field: "trajectory duration".into(),
            value: duration,
            reason: "is not a finite non-negative number",
        });
    }
    let n = (duration * rate_hz).floor();
    let n = crate::size::check_memory(
        "sample count (duration × rate)",
        n + 1.0,
        8.0,
        "a sample time",
    )? - 1;
    let mut t: Vec<f64> = (0..=n).map(|k| k as f64 / rate_hz).collect();
    // Drop a grid time that rounding put (almost) on the end; then add the end itself.
    while t.len() > 1 && *t.last().unwrap() >= duration - 1e-9 / rate_hz {
        t.pop();
    }
    if duration > 0.0 || t.is_empty() {
        t.push(duration);
    }
    t.dedup();
    Ok(t)
}

/// Samples `traj` at `rate_hz` (both ends included), evaluating position through jerk exactly.
///
/// ```
/// use trajkit::{poly::{Degree, PolyMove}, sample::sample};
/// let mv = PolyMove::rest_to_rest(Degree::Cubic, &[0.0], &[1.0], 1.0)?;
/// let table = sample(&mv, 100.0)?;
/// assert_eq!(table.len(), 101);
/// # Ok::<(), trajkit::Error>(())
/// ```
///
/// The sample count is checked against [`crate::size::MEMORY_BUDGET`] before anything is
/// allocated ([`Error::TooLarge`]).
pub fn sample<T: Trajectory + ?Sized>(traj: &T, rate_hz: f64) -> Result<SampleTable> {
    check_sample_count(traj.duration(), rate_hz, traj.dof())?;
    let times = sample_times(traj.duration(), rate_hz)?;
    sample_at(traj, times)
}

/// Refuses a sampling of `duration` seconds at `rate_hz` for `dof` joints whose table (time,
/// position, velocity, acceleration, jerk) would exceed [`crate::size::MEMORY_BUDGET`].
pub fn check_sample_count(duration: f64, rate_hz: f64, dof: usize) -> Result<usize> {
    check_sample_memory(duration, rate_hz, dof, 8.0, "")
}

/// [`check_sample_count`] for `bytes_per_value` bytes per number (8 for the table, more when
/// its text is kept too, which `what` then says, e.g. `" with its text"`).
pub fn check_sample_memory(
    duration: f64,
    rate_hz: f64,
    dof: usize,
    bytes_per_value: f64,
    what: &str,
) -> Result<usize> {
    crate::error::positive(|| "sample rate (Hz)".into(), rate_hz)?;
    crate::size::check_memory(
        "sample count (duration × rate)",
        (duration * rate_hz).floor() + 2.0,
        bytes_per_value * (1.0 + 4.0 * dof as f64),
        &format!("a sample of {dof} joint(s){what}"),
    )
}

/// Refuses a table of `rows` samples of `dof` joints (time, position, velocity,
/// acceleration, jerk) that would exceed [`crate::size::MEMORY_BUDGET`].
pub(crate) fn check_table_memory(rows: usize, dof: usize) -> Result<()> {
    crate::size::check_memory(
        "sample count",
        rows as f64,
        8.0 * (1.0 + 4.0 * dof as f64),
        &format!("a sample of {dof} joint(s)"),
    )?;
    Ok(())
}

/// Samples `traj` at the given increasing times ([`Trajectory::eval_rows`]: every row what
/// [`Trajectory::eval`] gives).
pub fn sample_at<T: Trajectory + ?Sized>(traj: &T, times: Vec<f64>) -> Result<SampleTable> {
    let dof = traj.dof();
    let rows = times.len();
    check_table_memory(rows, dof)?;
    let mut cols = [0; 4].map(|_| vec![0.0; rows * dof]);
    {
        let [q, v, a, j] = &mut cols;
        traj.eval_rows(&times, [q, v, a, j]);
    }
    SampleTable::new(dof, times, cols.map(Some))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_include_both_ends() {
        assert_eq!(
            sample_times(1.0, 4.0).unwrap(),
            vec![0.0, 0.25, 0.5, 0.75, 1.0]
        );
        let t = sample_times(1.1, 4.0).unwrap();
        assert_eq!(t.len(), 6);
        assert_eq!(*t.last().unwrap(), 1.1);
        assert_eq!(sample_times(0.0, 10.0).unwrap(), vec![0.0]);
        // 2.3 * 1000 is not exact in binary: no near-duplicate last sample.
        let t = sample_times(2.3, 1000.0).unwrap();
        assert_eq!(t.len(), 2301);
        assert!(t.windows(2).all(|w| w[1] - w[0] > 0.5e-3));
        assert!(sample_times(1.0, 0.0).is_err());
        assert!(sample_times(f64::INFINITY, 1.0).is_err());
        // Far too many samples: refused with the limit before anything is allocated.
        let e = check_sample_count(3600.0 * 24.0 * 365.0, 1e6, 7).unwrap_err();
        assert!(matches!(e, Error::TooLarge { .. }), "{e}");
        assert!(
            e.to_string().contains("sample count (duration × rate)"),
            "{e}"
        );
    }

    #[test]
    fn table_validation() {
        let ok = SampleTable::new(1, vec![0.0, 1.0], [Some(vec![0.0, 1.0]), None, None, None]);
        assert!(ok.is_ok());
        let bad = SampleTable::new(1, vec![0.0, 0.0], [Some(vec![0.0, 1.0]), None, None, None]);
        assert!(bad.unwrap_err().to_string().contains("does not increase"));
        let bad = SampleTable::new(2, vec![0.0], [Some(vec![0.0]), None, None, None]);
        assert!(bad.is_err());
        let bad = SampleTable::new(1, vec![0.0], [Some(vec![f64::NAN]), None, None, None]);
        assert!(bad.unwrap_err().to_string().contains("position of joint 1"));
    }
}
