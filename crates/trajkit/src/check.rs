//! Limit checking of any trajectory, sampled or continuous.
//!
//! [`check_samples`] reads a [`SampleTable`] (made by [`crate::sample`] or read from another
//! tool's output, where derivative columns may be missing) and reports, per joint:
//!
//! - the observed position range and the largest excursion outside the joint's position limits;
//! - for velocity, acceleration and jerk, the peak use of the limit, measured two ways:
//!   - **pointwise**: from the table's own column of that derivative, when present;
//!   - **finite difference**: the divided difference of the next-lower derivative between
//!     consecutive samples, `(x[i+1] - x[i]) / (t[i+1] - t[i])`, attributed to the interval
//!     midpoint. When the next-lower column is absent, its own finite-difference series is used,
//!     recursively down to positions, so a positions-only table still gets velocity,
//!     acceleration and jerk estimates.
//!
//! The two measures complement each other: a trajectory whose velocity jumps between two
//! samples can report a modest pointwise acceleration on both sides of the jump, while the
//! finite difference of the velocity shows the jump for what it is.
//!
//! When the table and the limits both name their joints, each column is checked against the
//! limits of its name, in any order ([`crate::limits::match_names`]); otherwise by position.
//!
//! Use of a limit is a ratio, computed with [`JointLimits::ratio`](crate::limits::JointLimits::ratio): `value / max` for
//! non-negative values and `value / min` for negative ones (so direction-dependent minima are
//! respected); 1.0 is exactly at the limit, and an unlimited (infinite) limit gives 0.
//!
//! ```
//! use trajkit::{check::{check_samples, Tolerance}, Limits, SampleTable};
//! // One joint moving at 1 rad/s for 1 s, sampled at 4 Hz, positions only.
//! let t = vec![0.0, 0.25, 0.5, 0.75, 1.0];
//! let table = SampleTable::new(1, t.clone(), [Some(t), None, None, None])?;
//! let report = check_samples(&table, &Limits::uniform(1, 2.0, 10.0, 100.0)?)?;
//! assert!((report.worst() - 0.5).abs() < 1e-12); // half the velocity limit
//! assert!(report.passes(&Tolerance::default()));
//! # Ok::<(), trajkit::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::limits::Limits;
use scan::{full_table_scan, Extremes, JointScan, PeakTracker, RowScan, ScanResult};
#[cfg(test)]
use scan::{PeakScan, DERIVATIVES};

mod scan;
use crate::sample::SampleTable;
use crate::traj::{Order, Trajectory};
#[cfg(feature = "serde")]
use serde_json::{json, Value};

/// The largest use of a limit found in one series of values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peak {
    /// `value / limit` with the directional limit of the value's sign (see
    /// [`JointLimits::ratio`](crate::limits::JointLimits::ratio)); 0 when the limit is unlimited.
    pub ratio: f64,
    /// The value at the peak (same unit as the derivative).
    pub value: f64,
    /// When it happens, in seconds (the interval midpoint for finite differences).
    pub time: f64,
}

/// The check of one derivative (velocity, acceleration or jerk) of one joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DerivativeCheck {
    /// Which derivative.
    pub order: Order,
    /// Peak of the table's own column of this derivative; `None` when the table has no such
    /// column.
    pub pointwise: Option<Peak>,
    /// Peak of the finite-difference estimate; `None` when there are too few samples to form
    /// one difference: 2 are needed when the table has the next-lower derivative, up to
    /// `order + 1` when that one is itself a finite difference.
    pub finite_difference: Option<Peak>,
}

impl DerivativeCheck {
    /// The larger of the pointwise and finite-difference ratios (0 when neither exists).
    pub fn worst(&self) -> f64 {
        [self.pointwise, self.finite_difference]
            .iter()
            .flatten()
            .map(|p| p.ratio)
            .fold(0.0, f64::max)
    }
}

/// Observed positions of one joint against its position range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PositionCheck {
    /// Lowest position reached.
    pub min: f64,
    /// Highest position reached.
    pub max: f64,
    /// Largest distance outside `[position_min, position_max]`; 0 when always inside.
    pub excursion: f64,
    /// When the position is closest to (or farthest beyond) a bound: the time of
    /// [`PositionCheck::excursion`] when it is positive. The first sample's time when the
    /// range is unbounded.
    pub time: f64,
}

/// Everything checked for one joint.
#[derive(Debug, Clone, PartialEq)]
pub struct JointReport {
    /// 0-based joint index (messages print it 1-based).
    pub joint: usize,
    /// Joint name: the table's, else the limits', else empty.
    pub name: String,
    /// Position range.
    pub position: PositionCheck,
    /// Velocity, acceleration and jerk, in that order.
    pub derivatives: [DerivativeCheck; 3],
}

impl JointReport {
    /// `joint 3 (panda_joint3)`, or `joint 3` when unnamed (1-based).
    fn label(&self) -> String {
        if self.name.is_empty() {
            format!("joint {}", self.joint + 1)
        } else {
            format!("joint {} ({})", self.joint + 1, self.name)
        }
    }

    /// Largest ratio over velocity, acceleration and jerk, pointwise and finite difference.
    pub fn worst(&self) -> f64 {
        self.derivatives
            .iter()
            .map(DerivativeCheck::worst)
            .fold(0.0, f64::max)
    }
}

/// The result of checking a trajectory against limits.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitReport {
    /// One report per joint, in joint order.
    pub joints: Vec<JointReport>,
    /// Number of samples checked.
    pub samples: usize,
    /// Time span of the samples in seconds.
    pub duration: f64,
}

/// How far beyond a limit still counts as within it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Allowed relative excess: a check passes when every ratio is `<= 1 + ratio`.
    pub ratio: f64,
    /// Allowed position excursion beyond the position range (joint units).
    pub position: f64,
}

impl Default for Tolerance {
    /// `ratio = 1e-6`, `position = 1e-9`: room for rounding, nothing more.
    fn default() -> Self {
        Tolerance {
            ratio: 1e-6,
            position: 1e-9,
        }
    }
}

/// Formats a number with up to `digits` significant digits, without trailing zeros.
fn sig(x: f64, digits: usize) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    let mag = x.abs().log10().floor() as i64;
    if !(-4..=9).contains(&mag) {
        return format!("{:.*e}", digits.saturating_sub(1), x);
    }
    let decimals = (digits as i64 - 1 - mag).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A ratio for people: more digits when it is close to 1, where they matter.
fn fmt_ratio(r: f64) -> String {
    if (r - 1.0).abs() < 1e-3 {
        sig(r, 9)
    } else {
        sig(r, 3)
    }
}

impl LimitReport {
    /// Largest ratio over all joints, orders, pointwise and finite difference (0 for no
    /// joints).
    pub fn worst(&self) -> f64 {
        self.joints
            .iter()
            .map(JointReport::worst)
            .fold(0.0, f64::max)
    }

    /// Largest ratio of joint `j` (0-based); 0 when there is no such joint.
    pub fn worst_for_joint(&self, j: usize) -> f64 {
        self.joints.get(j).map_or(0.0, JointReport::worst)
    }

    /// One line per violated item, for people, e.g.
    /// `joint 2 (panda_joint2) acceleration (finite difference) 1.23 × limit at t = 0.512 s
    /// (value -9.23)`. Empty when everything is within `tol`.
    pub fn violations(&self, tol: &Tolerance) -> Vec<String> {
        let mut out = Vec::new();
        for jr in &self.joints {
            let p = &jr.position;
            if p.excursion > tol.position {
                out.push(format!(
                    "{} position outside its range by {} at t = {} s (reached [{}, {}])",
                    jr.label(),
                    sig(p.excursion, 4),
                    sig(p.time, 6),
                    sig(p.min, 6),
                    sig(p.max, 6)
                ));
            }
            for d in &jr.derivatives {
                for (kind, peak) in [
                    ("pointwise", d.pointwise),
                    ("finite difference", d.finite_difference),
                ] {
                    if let Some(pk) = peak {
                        if pk.ratio.is_nan() || pk.ratio > 1.0 + tol.ratio {
                            out.push(format!(
                                "{} {} ({}) {} × limit at t = {} s (value {})",
                                jr.label(),
                                d.order.name(),
                                kind,
                                fmt_ratio(pk.ratio),
                                sig(pk.time, 6),
                                sig(pk.value, 6)
                            ));
                        }
                    }
                }
            }
        }
        out
    }

    /// True when [`LimitReport::violations`] is empty.
    pub fn passes(&self, tol: &Tolerance) -> bool {
        self.violations(tol).is_empty()
    }

    /// An aligned text table: one row per joint with the position range used and, for
    /// velocity, acceleration and jerk, `pointwise / finite-difference` ratios (`-` where not
    /// available), followed by the worst ratio.
    pub fn to_text(&self) -> String {
        let header = [
            "joint".to_string(),
            "position range used".to_string(),
            "velocity (pw / fd)".to_string(),
            "acceleration (pw / fd)".to_string(),
            "jerk (pw / fd)".to_string(),
        ];
        let mut rows: Vec<[String; 5]> = vec![header];
        for jr in &self.joints {
            let p = &jr.position;
            let mut pos = format!("[{}, {}]", sig(p.min, 4), sig(p.max, 4));
            if p.excursion > 0.0 {
                pos.push_str(&format!(" OUT by {}", sig(p.excursion, 3)));
            }
            let cell = |d: &DerivativeCheck| {
                let f = |pk: Option<Peak>| pk.map_or("-".to_string(), |pk| fmt_ratio(pk.ratio));
                format!("{} / {}", f(d.pointwise), f(d.finite_difference))
            };
            let name = if jr.name.is_empty() {
                format!("{}", jr.joint + 1)
            } else {
                format!("{} {}", jr.joint + 1, jr.name)
            };
            rows.push([
                name,
                pos,
                cell(&jr.derivatives[0]),
                cell(&jr.derivatives[1]),
                cell(&jr.derivatives[2]),
            ]);
        }
        let mut widths = [0usize; 5];
        for r in &rows {
            for (w, c) in widths.iter_mut().zip(r.iter()) {
                *w = (*w).max(c.chars().count());
            }
        }
        let mut s = format!(
            "{} samples over {} s; ratios are value / limit (1 = at the limit)\n",
            self.samples,
            sig(self.duration, 6)
        );
        for r in &rows {
            let mut line = String::new();
            for (k, (c, w)) in r.iter().zip(widths.iter()).enumerate() {
                if k > 0 {
                    line.push_str("  ");
                }
                let pad = w - c.chars().count();
                line.push_str(c);
                line.push_str(&" ".repeat(pad));
            }
            s.push_str(line.trim_end());
            s.push('\n');
        }
        s.push_str(&format!("worst: {} × limit\n", fmt_ratio(self.worst())));
        s
    }

    /// The report as JSON: `{samples, duration, worst, joints: [{joint, name, worst,
    /// position: {min, max, excursion, time}, velocity|acceleration|jerk: {pointwise,
    /// finite_difference}}]}` where each peak is `{ratio, value, time}` or `null`.
    /// Non-finite numbers become `null`.
    #[cfg(feature = "serde")]
    pub fn to_json(&self) -> Value {
        let peak = |p: Option<Peak>| match p {
            Some(p) => json!({"ratio": p.ratio, "value": p.value, "time": p.time}),
            None => Value::Null,
        };
        let joints: Vec<Value> = self
            .joints
            .iter()
            .map(|jr| {
                let mut o = json!({
                    "joint": jr.joint,
                    "name": jr.name,
                    "worst": jr.worst(),
                    "position": {
                        "min": jr.position.min,
                        "max": jr.position.max,
                        "excursion": jr.position.excursion,
                        "time": jr.position.time,
                    },
                });
                for d in &jr.derivatives {
                    o[d.order.name()] = json!({
                        "pointwise": peak(d.pointwise),
                        "finite_difference": peak(d.finite_difference),
                    });
                }
                o
            })
            .collect();
        json!({
            "samples": self.samples,
            "duration": self.duration,
            "worst": self.worst(),
            "joints": joints,
        })
    }
}

/// Checks a sample table against limits (see the module documentation).
///
/// When the table and the limits both name their joints, columns take the limits of their
/// name, in any order (limit joints no column names are not used); otherwise they pair by
/// position ([`crate::limits::match_names`]).
///
/// One pass over the rows (row by row with the joints side by side when every column is
/// present), comparisons only per value: the first largest and smallest values decide each
/// peak; a series with a non-finite difference, or a zero limit, is scanned again value by
/// value. Nothing is allocated per row.
///
/// Errors: [`Error::JointNames`] for a named column without limits of its name;
/// [`Error::DimensionMismatch`] when unnamed tables and limits have different joint counts;
/// [`Error::InvalidValue`] for a table without samples.
pub fn check_samples(table: &SampleTable, limits: &Limits) -> Result<LimitReport> {
    let limits = table_limits(table.names(), table.dof(), table.len(), limits)?;
    let full = full_table_scan(table, &limits);
    Ok(assemble(table, &limits, full))
}

/// The limits of each column of a table with these `names`, `dof` columns and `rows` rows
/// (the pairing and refusals of [`check_samples`]).
fn table_limits(names: &[String], dof: usize, rows: usize, limits: &Limits) -> Result<Limits> {
    let named = names.iter().all(|n| !n.is_empty());
    let (limits, _) = limits.for_joints("table", named.then_some(names))?;
    limits.expect_dof(dof, "the sample table")?;
    if rows == 0 {
        return Err(Error::InvalidValue {
            field: "sample table row count".into(),
            value: 0.0,
            reason: "is too small to check (at least 1 sample is needed)",
        });
    }
    Ok(limits)
}

/// The report of `table` against its column `limits`, from the one-pass scan `full` when it
/// decided, else joint by joint ([`JointScan`], value by value where needed).
fn assemble(table: &SampleTable, limits: &Limits, full: Option<Vec<ScanResult>>) -> LimitReport {
    let joints = (0..table.dof())
        .map(|j| {
            let jl = limits.joint(j);
            let (position, derivatives) = match &full {
                Some(f) => f[j],
                None => {
                    let (p, d, exact) = JointScan::<Extremes>::run(table, jl, j);
                    if exact {
                        (p, d)
                    } else {
                        let (p, d, _) = JointScan::<PeakTracker>::run(table, jl, j);
                        (p, d)
                    }
                }
            };
            let name = match table.names().get(j) {
                Some(n) if !n.is_empty() => n.clone(),
                _ => jl.name.clone(),
            };
            JointReport {
                joint: j,
                name,
                position,
                derivatives,
            }
        })
        .collect();
    LimitReport {
        joints,
        samples: table.len(),
        duration: table.duration(),
    }
}

/// [`crate::sample::sample`] of `traj` at `rate_hz` named `names`, and [`check_samples`] of
/// that table against `limits`, in one pass: the rows are made a block at a time into the
/// table (allocated once, with its final size) and scanned while in cache. The table and the report are exactly those of the two calls (same
/// rows, same scan; a non-finite value takes the same paths and errors).
pub(crate) fn sample_and_check<T: Trajectory + ?Sized>(
    traj: &T,
    rate_hz: f64,
    names: Vec<String>,
    limits: &Limits,
) -> Result<(SampleTable, LimitReport)> {
    crate::sample::check_sample_count(traj.duration(), rate_hz, traj.dof())?;
    let times = crate::sample::sample_times(traj.duration(), rate_hz)?;
    let dof = traj.dof();
    crate::sample::check_table_memory(times.len(), dof)?;
    let col_limits = table_limits(&names, dof, times.len(), limits);
    let mut scan = col_limits.as_ref().ok().map(|l| RowScan::new(l, dof));
    let rows = times.len();
    let mut values = vec![0.0; 4 * rows * dof];
    {
        let mut cols = SampleTable::split_matrices(&mut values, rows, dof);
        for (b, chunk) in times.chunks(SCAN_BLOCK).enumerate() {
            let (from, to) = (b * SCAN_BLOCK * dof, (b * SCAN_BLOCK + chunk.len()) * dof);
            let [q, v, a, j] = &mut cols;
            let block = [q, v, a, j].map(|c| &mut c[from..to]);
            traj.eval_rows(chunk, block);
            if let Some(s) = &mut scan {
                s.push_rows(chunk, cols.each_ref().map(|c| &c[from..to]));
            }
        }
    }
    let valid = dof > 0
        && scan.as_ref().is_some_and(RowScan::all_finite)
        && times.iter().all(|t| t.is_finite())
        && times.windows(2).all(|w| w[1] > w[0]);
    let full = scan.and_then(|s| {
        let n = rows * dof;
        s.finish(&times, [0, 1, 2, 3].map(|k| &values[k * n..(k + 1) * n]))
    });
    let table = if valid {
        // Joints, every value finite, times finite and strictly increasing: what
        // `SampleTable::new` checks.
        SampleTable::from_sampled(dof, times, values)
    } else {
        let n = rows * dof;
        let cols = [0, 1, 2, 3].map(|k| Some(values[k * n..(k + 1) * n].to_vec()));
        SampleTable::new(dof, times, cols)?
    };
    let table = table.with_names(names)?;
    let limits = col_limits?;
    let report = assemble(&table, &limits, full);
    Ok((table, report))
}

/// Rows per block of [`sample_and_check`]: the four blocks of a 7-joint trajectory (28 KiB)
/// stay in the first-level cache between their evaluation and their scan.
const SCAN_BLOCK: usize = 128;

/// Samples `traj` at `rate_hz` with [`crate::sample::sample`] (both ends included, exact
/// derivatives) and checks the samples against `limits`.
pub fn check_trajectory<T: Trajectory + ?Sized>(
    traj: &T,
    limits: &Limits,
    rate_hz: f64,
) -> Result<LimitReport> {
    limits.expect_dof(traj.dof(), "the trajectory")?;
    let table = crate::sample::sample(traj, rate_hz)?;
    check_samples(&table, limits)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::JointLimits;

    fn table(dof: usize, t: Vec<f64>, cols: [Option<Vec<f64>>; 4]) -> SampleTable {
        SampleTable::new(dof, t, cols).unwrap()
    }

    fn grid(n: usize, dt: f64) -> Vec<f64> {
        (0..n).map(|i| i as f64 * dt).collect()
    }

    #[test]
    fn constant_velocity_fd_ratio_is_exact() {
        let t = grid(11, 0.1);
        let q: Vec<f64> = t.iter().map(|&t| 0.5 * t).collect();
        let tb = table(1, t, [Some(q), None, None, None]);
        let lim = Limits::uniform(1, 2.0, 1.0, 1.0).unwrap();
        let r = check_samples(&tb, &lim).unwrap();
        let v = r.joints[0].derivatives[0];
        assert_eq!(v.order, Order::Velocity);
        assert!(v.pointwise.is_none());
        let fd = v.finite_difference.unwrap();
        assert!((fd.ratio - 0.25).abs() < 1e-12, "{fd:?}");
        // Positions only: FD acceleration and jerk exist and are (nearly) zero.
        let a = r.joints[0].derivatives[1].finite_difference.unwrap();
        let j = r.joints[0].derivatives[2].finite_difference.unwrap();
        assert!(a.ratio.abs() < 1e-9 && j.ratio.abs() < 1e-6);
        assert!(r.passes(&Tolerance::default()));
        assert_eq!(r.samples, 11);
        assert!((r.duration - 1.0).abs() < 1e-12);
    }

    #[test]
    fn velocity_jump_is_caught_by_fd_acceleration() {
        // Velocity 0 then 1 from t = 0.5 on, accelerations reported as 0 everywhere: the
        // pointwise column hides the jump, the finite difference shows it.
        let t = grid(11, 0.1);
        let v: Vec<f64> = t
            .iter()
            .map(|&t| if t < 0.45 { 0.0 } else { 1.0 })
            .collect();
        let q: Vec<f64> = t.iter().map(|&t| (t - 0.5).max(0.0)).collect();
        let a = vec![0.0; 11];
        let tb = table(1, t, [Some(q), Some(v), Some(a), None]);
        let lim = Limits::uniform(1, 2.0, 5.0, 1000.0).unwrap();
        let r = check_samples(&tb, &lim).unwrap();
        let acc = r.joints[0].derivatives[1];
        assert_eq!(acc.pointwise.unwrap().ratio, 0.0);
        let fd = acc.finite_difference.unwrap();
        assert!((fd.value - 10.0).abs() < 1e-9, "{fd:?}");
        assert!((fd.ratio - 2.0).abs() < 1e-9);
        assert!((fd.time - 0.45).abs() < 1e-12);
        let tol = Tolerance::default();
        assert!(!r.passes(&tol));
        let v = r.violations(&tol);
        assert!(
            v.iter().any(
                |l| l.contains("joint 1 acceleration (finite difference) 2 × limit")
                    && l.contains("t = 0.45 s")
            ),
            "{v:?}"
        );
        assert!((r.worst() - 2.0).abs() < 1e-9);
        assert!((r.worst_for_joint(0) - 2.0).abs() < 1e-9);
        assert_eq!(r.worst_for_joint(5), 0.0);
    }

    #[test]
    fn position_excursion_and_time() {
        let t = grid(5, 0.25);
        let q = vec![0.0, 0.5, 1.3, 0.9, -0.2];
        let tb = table(1, t, [Some(q), None, None, None]);
        let mut jl = JointLimits::symmetric(100.0, 100.0, 1e6);
        jl.position_min = -1.0;
        jl.position_max = 1.0;
        jl.name = "elbow".into();
        let r = check_samples(&tb, &Limits::new(vec![jl]).unwrap()).unwrap();
        let p = r.joints[0].position;
        assert_eq!((p.min, p.max), (-0.2, 1.3));
        assert!((p.excursion - 0.3).abs() < 1e-12);
        assert_eq!(p.time, 0.5);
        assert_eq!(r.joints[0].name, "elbow");
        let v = r.violations(&Tolerance::default());
        assert_eq!(v.len(), 1, "{v:?}");
        assert!(v[0].starts_with("joint 1 (elbow) position outside its range by 0.3 at t = 0.5 s"));
        assert!(r.passes(&Tolerance {
            ratio: 1e-6,
            position: 0.31
        }));
    }

    #[test]
    fn directional_minima_are_respected() {
        // Velocity -1.5 pointwise; max 2, min -1: ratio 1.5 (negative side).
        let t = grid(3, 1.0);
        let q = vec![0.0, -1.5, -3.0];
        let v = vec![-1.5; 3];
        let tb = table(1, t, [Some(q), Some(v), None, None]);
        let mut jl = JointLimits::symmetric(2.0, 10.0, 100.0);
        jl.min_velocity = Some(-1.0);
        let r = check_samples(&tb, &Limits::new(vec![jl.clone()]).unwrap()).unwrap();
        let d = r.joints[0].derivatives[0];
        assert!((d.pointwise.unwrap().ratio - 1.5).abs() < 1e-12);
        assert!((d.finite_difference.unwrap().ratio - 1.5).abs() < 1e-12);
        // Same magnitude forward is within the limits.
        let tb = table(
            1,
            grid(3, 1.0),
            [Some(vec![0.0, 1.5, 3.0]), Some(vec![1.5; 3]), None, None],
        );
        let r = check_samples(&tb, &Limits::new(vec![jl]).unwrap()).unwrap();
        assert!((r.worst() - 0.75).abs() < 1e-12);
    }

    #[test]
    fn positions_only_table_gets_all_fd_orders() {
        // q = t³: jerk 6 everywhere; third divided difference on a uniform grid is exact.
        let t = grid(21, 0.05);
        let q: Vec<f64> = t.iter().map(|&t| t * t * t).collect();
        let tb = table(1, t, [Some(q), None, None, None]);
        let r = check_samples(&tb, &Limits::uniform(1, 10.0, 10.0, 12.0).unwrap()).unwrap();
        let jerk = r.joints[0].derivatives[2];
        assert!(jerk.pointwise.is_none());
        let fd = jerk.finite_difference.unwrap();
        assert!((fd.value - 6.0).abs() < 1e-6, "{fd:?}");
        assert!((fd.ratio - 0.5).abs() < 1e-6);
        let text = r.to_text();
        assert!(text.contains("- / 0.5"), "{text}");
        #[cfg(feature = "serde")]
        {
            let js = r.to_json();
            assert!(js["joints"][0]["jerk"]["pointwise"].is_null());
            assert!(
                (js["joints"][0]["jerk"]["finite_difference"]["ratio"]
                    .as_f64()
                    .unwrap()
                    - 0.5)
                    .abs()
                    < 1e-6
            );
        }
    }

    #[test]
    fn unlimited_gives_zero_ratio_and_short_tables() {
        let tb = table(1, vec![0.0], [Some(vec![1.0]), Some(vec![3.0]), None, None]);
        let lim = Limits::new(vec![JointLimits::default()]).unwrap();
        let r = check_samples(&tb, &lim).unwrap();
        let d = r.joints[0].derivatives[0];
        assert_eq!(d.pointwise.unwrap().ratio, 0.0);
        assert_eq!(d.pointwise.unwrap().value, 3.0);
        assert!(d.finite_difference.is_none());
        assert_eq!(r.worst(), 0.0);
        let empty = table(1, vec![], [Some(vec![]), None, None, None]);
        assert!(check_samples(&empty, &lim).is_err());
    }

    #[test]
    fn dof_mismatch_is_an_error() {
        let tb = table(2, vec![0.0, 1.0], [Some(vec![0.0; 4]), None, None, None]);
        let e = check_samples(&tb, &Limits::uniform(3, 1.0, 1.0, 1.0).unwrap()).unwrap_err();
        assert!(matches!(
            e,
            Error::DimensionMismatch {
                expected: 2,
                found: 3,
                ..
            }
        ));
    }

    struct Ramp;
    impl Trajectory for Ramp {
        fn dof(&self) -> usize {
            2
        }
        fn duration(&self) -> f64 {
            1.0
        }
        fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
            let t = crate::traj::clamp_time(t, 1.0);
            let (a, b) = match order {
                Order::Position => (t, -2.0 * t),
                Order::Velocity => (1.0, -2.0),
                _ => (0.0, 0.0),
            };
            out[0] = a;
            out[1] = b;
        }
    }

    #[test]
    fn trajectory_check_and_text() {
        let mut lim = Limits::preset("panda").unwrap().joints()[..2].to_vec();
        lim[1].min_velocity = Some(-1.0);
        let lim = Limits::new(lim).unwrap();
        let r = check_trajectory(&Ramp, &lim, 100.0).unwrap();
        assert_eq!(r.samples, 101);
        assert_eq!(r.joints[1].name, "panda_joint2");
        assert!((r.joints[1].derivatives[0].pointwise.unwrap().ratio - 2.0).abs() < 1e-12);
        let v = r.violations(&Tolerance::default());
        // Joint 2 leaves its range (-1.7628) and uses twice its negative velocity limit.
        assert_eq!(v.len(), 3, "{v:?}");
        assert!(v[0].contains("(reached [-2, 0])"), "{v:?}");
        assert!(v[1].starts_with("joint 2 (panda_joint2) velocity (pointwise) 2 × limit"));
        let text = r.to_text();
        assert!(
            text.contains("panda_joint1") && text.contains("worst: 2 × limit"),
            "{text}"
        );
        assert!(
            check_trajectory(&Ramp, &Limits::uniform(3, 1.0, 1.0, 1.0).unwrap(), 10.0).is_err()
        );
        assert!(check_trajectory(&Ramp, &lim, 0.0).is_err());
    }

    /// A seeded random smooth motion of 3 joints with a NaN or an infinity where asked.
    struct Wave {
        amp: [[f64; 3]; 3],
        bad_at: Option<(f64, f64)>,
        duration: f64,
    }
    impl Trajectory for Wave {
        fn dof(&self) -> usize {
            3
        }
        fn duration(&self) -> f64 {
            self.duration
        }
        fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
            for (j, o) in out[..3].iter_mut().enumerate() {
                let [a, w, p] = self.amp[j];
                let x = w * t + p;
                *o = a
                    * w.powi(order.index() as i32)
                    * match order.index() {
                        0 => x.sin(),
                        1 => x.cos(),
                        2 => -x.sin(),
                        _ => -x.cos(),
                    };
            }
            if let Some((at, value)) = self.bad_at {
                if (t - at).abs() < 1e-12 && order == Order::Jerk {
                    out[1] = value;
                }
            }
        }
    }

    /// The one-pass sampling and check gives bitwise the table and the report of sampling
    /// and then checking, on random motions, durations off the grid, a single sample, named
    /// and unnamed columns, and with a NaN or an infinity in the first, a middle and the last row
    /// (the same error or report).
    #[test]
    fn one_pass_sampling_and_check_equals_the_two_calls() {
        let mut rng = crate::rng::SplitMix64::new(11);
        let lim = Limits::preset("panda").unwrap().joints()[..3].to_vec();
        let named = Limits::new(lim).unwrap();
        let unnamed = Limits::uniform(3, 2.0, 5.0, 40.0).unwrap();
        for case in 0..40 {
            let duration = match case {
                0 => 0.0,
                1 => 0.0004,
                _ => rng.uniform(0.01, 2.0),
            };
            let amp = [0; 3].map(|_| {
                [
                    rng.uniform(0.1, 1.0),
                    rng.uniform(0.5, 8.0),
                    rng.uniform(-3.0, 3.0),
                ]
            });
            let rate = [1000.0, 250.0, 333.0][case % 3];
            let times = crate::sample::sample_times(duration, rate).unwrap();
            let bad_at = match case % 5 {
                1 => Some((times[0], f64::NAN)),
                2 => Some((times[times.len() / 2], f64::INFINITY)),
                3 => Some((*times.last().unwrap(), f64::NAN)),
                _ => None,
            };
            let traj = Wave {
                amp,
                bad_at,
                duration,
            };
            let (limits, names) = if case % 2 == 0 {
                let n = named.joints().iter().map(|j| j.name.clone()).collect();
                (&named, n)
            } else {
                (&unnamed, vec![String::new(); 3])
            };
            let two = crate::sample::sample(&traj, rate)
                .and_then(|t| t.with_names(names.clone()))
                .and_then(|t| check_samples(&t, limits).map(|r| (t, r)));
            let one = sample_and_check(&traj, rate, names, limits);
            match (one, two) {
                (Ok((t1, r1)), Ok((t2, r2))) => {
                    assert_eq!(t1, t2, "case {case}");
                    assert_eq!(format!("{r1:?}"), format!("{r2:?}"), "case {case}");
                }
                (Err(e1), Err(e2)) => assert_eq!(e1.to_string(), e2.to_string()),
                (a, b) => panic!("case {case}: {:?} vs {:?}", a.err(), b.err()),
            }
        }
    }

    #[test]
    fn named_columns_take_the_limits_of_their_name() {
        // Joint "b" moves at 1.5 rad/s; "a" is still. Limits list "a" (1.0) then "b" (2.0).
        let t = grid(3, 1.0);
        let q = vec![0.0, 0.0, 0.0, 1.5, 0.0, 3.0];
        let tb = table(2, t, [Some(q), None, None, None])
            .with_names(vec!["a".into(), "b".into()])
            .unwrap();
        let mut a = JointLimits::symmetric(1.0, 10.0, 100.0);
        a.name = "a".into();
        let mut b = JointLimits::symmetric(2.0, 10.0, 100.0);
        b.name = "b".into();
        let mut c = JointLimits::symmetric(2.0, 10.0, 100.0);
        c.name = "c".into();
        // In the limits' order the columns are (b, a): b at 1.5 of 2.0 is 0.75.
        let r = check_samples(
            &tb,
            &Limits::new(vec![c.clone(), b.clone(), a.clone()]).unwrap(),
        )
        .unwrap();
        assert!((r.worst() - 0.75).abs() < 1e-12);
        assert_eq!(r.joints[1].name, "b");
        // A column whose name the limits do not have.
        let e = check_samples(&tb, &Limits::new(vec![a, c]).unwrap()).unwrap_err();
        assert!(matches!(e, Error::JointNames { .. }), "{e}");
    }

    /// The definition, series by series: the peak of each (time, value) series by one ratio
    /// per value, finite differences as whole series.
    fn reference(
        table: &SampleTable,
        limits: &Limits,
    ) -> Vec<(PositionCheck, [DerivativeCheck; 3])> {
        let peak_of = |jl: &JointLimits, order: Order, times: &[f64], values: &[f64]| {
            let mut t = PeakTracker::new(jl.range(order).0, jl.range(order).1);
            for (&time, &value) in times.iter().zip(values) {
                t.push(time, value);
            }
            t.best
        };
        let diff = |times: &[f64], values: &[f64]| -> (Vec<f64>, Vec<f64>) {
            (1..times.len())
                .map(|i| {
                    let dt = times[i] - times[i - 1];
                    (
                        0.5 * (times[i - 1] + times[i]),
                        (values[i] - values[i - 1]) / dt,
                    )
                })
                .unzip()
        };
        let (dof, rows, times) = (table.dof(), table.len(), table.times());
        let column = |o: Order, j: usize| {
            table
                .matrix(o)
                .map(|m| (0..rows).map(|i| m[i * dof + j]).collect::<Vec<f64>>())
        };
        (0..dof)
            .map(|j| {
                let jl = limits.joint(j);
                let q = column(Order::Position, j).unwrap();
                let mut position = PositionCheck {
                    min: f64::INFINITY,
                    max: f64::NEG_INFINITY,
                    excursion: f64::NEG_INFINITY,
                    time: times[0],
                };
                for (&t, &x) in times.iter().zip(&q) {
                    // The first smallest and first largest (a tie of −0 and +0 keeps the
                    // earlier).
                    if x < position.min {
                        position.min = x;
                    }
                    if x > position.max {
                        position.max = x;
                    }
                    let d = (jl.position_min - x).max(x - jl.position_max);
                    if d > position.excursion {
                        position.excursion = d;
                        position.time = t;
                    }
                }
                position.excursion = position.excursion.max(0.0);
                let mut lower = (times.to_vec(), q);
                let derivatives = DERIVATIVES.map(|order| {
                    let own = column(order, j);
                    let fd = diff(&lower.0, &lower.1);
                    let d = DerivativeCheck {
                        order,
                        pointwise: own.as_ref().and_then(|v| peak_of(jl, order, times, v)),
                        finite_difference: peak_of(jl, order, &fd.0, &fd.1),
                    };
                    lower = match own {
                        Some(v) => (times.to_vec(), v),
                        None => fd,
                    };
                    d
                });
                (position, derivatives)
            })
            .collect()
    }

    /// The one-pass check equals the definition exactly on seeded random tables: missing
    /// columns, directional and unlimited limits, repeated extremes (ties, within and across
    /// the scan's blocks), overflowing differences, uniform and random time steps.
    #[test]
    fn one_pass_check_equals_the_definition() {
        let mut rng = crate::rng::SplitMix64::new(14);
        for case in 0..300 {
            // Nine joints: the scan's general path (fixed-size arrays up to eight).
            let dof = if case % 10 == 9 { 9 } else { 1 + case % 3 };
            // Longer tables span several of the one-pass scan's blocks.
            let rows = 1 + (rng.next_u64() % if case % 2 == 0 { 40 } else { 400 }) as usize;
            let mut t = 0.0;
            let times: Vec<f64> = (0..rows)
                .map(|i| {
                    t += rng.uniform(1e-3, 0.1);
                    // A uniform grid (equal time steps up to rounding) or random steps.
                    if case % 4 == 3 {
                        i as f64 / 1000.0
                    } else {
                        t
                    }
                })
                .collect();
            // Few distinct values: ties between samples and between signs.
            let levels = [-2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0, -1e307, 1e307];
            let span = if case % 5 == 0 { 9 } else { 7 };
            let mut col = || -> Vec<f64> {
                (0..rows * dof)
                    .map(|_| levels[(rng.next_u64() % span) as usize])
                    .collect()
            };
            let present = case % 8;
            let data = [
                Some(col()),
                (present & 1 != 0).then(&mut col),
                (present & 2 != 0).then(&mut col),
                (present & 4 != 0).then(&mut col),
            ];
            let table = SampleTable::new(dof, times, data).unwrap();
            let joints = (0..dof)
                .map(|j| {
                    let mut jl = JointLimits::symmetric(1.5, 1.0, 2.0);
                    jl.position_min = -1.0;
                    jl.position_max = 1.0;
                    match (case + j) % 4 {
                        0 => jl.min_velocity = Some(-0.75),
                        1 => jl.jerk = f64::INFINITY,
                        2 => jl.min_acceleration = Some(-2.0),
                        _ => {}
                    }
                    jl
                })
                .collect();
            let limits = Limits::new(joints).unwrap();
            let got = check_samples(&table, &limits).unwrap();
            let want = reference(&table, &limits);
            for (jr, (position, derivatives)) in got.joints.iter().zip(&want) {
                assert_eq!(
                    format!("{:?}", jr.position),
                    format!("{position:?}"),
                    "case {case}"
                );
                assert_eq!(
                    format!("{:?}", jr.derivatives),
                    format!("{derivatives:?}"),
                    "case {case}"
                );
            }
        }
    }

    /// The position range keeps the first smallest and first largest value, so a tie of −0
    /// and +0 reports the earlier one's sign, the same on every path of the scan (full
    /// tables block by block, tables with a missing column joint by joint), whether the two
    /// are in one block or in different ones.
    #[test]
    fn position_range_keeps_the_earlier_of_signed_zeros() {
        let rows = 300;
        let times: Vec<f64> = (0..rows).map(|i| i as f64 / 1000.0).collect();
        let limits = Limits::uniform(1, 10.0, 10.0, 10.0).unwrap();
        for (first, second) in [(10, 20), (10, 200), (200, 250)] {
            for zero_first in [0.0, -0.0] {
                for sign in [1.0, -1.0] {
                    // Positions 0.5·sign but at `first` and `second`: the extreme on the side of
                    // 0 is a tie of zero_first and its negation.
                    let mut q = vec![0.5 * sign; rows];
                    q[first] = zero_first;
                    q[second] = -zero_first;
                    let zeros = vec![0.0; rows];
                    for full in [true, false] {
                        let jerk = full.then(|| zeros.clone());
                        let data = [
                            Some(q.clone()),
                            Some(zeros.clone()),
                            Some(zeros.clone()),
                            jerk,
                        ];
                        let table = SampleTable::new(1, times.clone(), data).unwrap();
                        let p = check_samples(&table, &limits).unwrap().joints[0].position;
                        let got = if sign > 0.0 { p.min } else { p.max };
                        assert_eq!(got, 0.0);
                        assert_eq!(
                            got.is_sign_negative(),
                            zero_first.is_sign_negative(),
                            "rows {first}, {second}, first zero {zero_first}, sign {sign}, full {full}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn number_formatting() {
        assert_eq!(sig(1.23456, 3), "1.23");
        assert_eq!(sig(2.0, 3), "2");
        assert_eq!(sig(0.000123, 3), "0.000123");
        assert_eq!(fmt_ratio(1.0000012), "1.0000012");
        assert_eq!(sig(-12345.0, 3), "-12345");
    }
}
