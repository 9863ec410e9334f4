//! Point-to-point polynomials: cubic, quintic (minimum-jerk) and septic moves, their peak
//! coefficients, the shortest duration within limits, and multi-waypoint piecewise polynomials.
//!
//! A rest-to-rest move from q₀ to q_T over T is `q(t) = q₀ + (q_T − q₀)·f(t/T)` with the unit
//! profile f of the chosen [`Degree`]:
//!
//! | degree | f(τ) | conditions at each end |
//! |---|---|---|
//! | cubic | 3τ² − 2τ³ | q, q̇ |
//! | quintic (minimum jerk, Flash & Hogan 1985) | 10τ³ − 15τ⁴ + 6τ⁵ | q, q̇, q̈ |
//! | septic | 35τ⁴ − 84τ⁵ + 70τ⁶ − 20τ⁷ | q, q̇, q̈, q⃛ |
//!
//! trajkit does not type these in: it solves the boundary-value problem
//! ([`Polynomial::from_boundary`]), which also handles arbitrary end states.
//!
//! # Precision contract
//! - Boundary conditions are met to 1e-12 relative to the size of the motion (tested on
//!   seeded random conditions over durations from 0.01 to 100 s).
//! - Peak values ([`Polynomial::peak_abs`], [`peak_coefficients`]) come from the real roots of
//!   the next derivative, bracketed to a few ulp: they are exact to ~1e-14 relative.
//! - [`min_duration_rest_to_rest`] is closed-form: the returned move reaches its binding limit
//!   to within 1e-12 relative and exceeds none.
//! - [`min_duration`] (general end states) bisects to 1e-10 relative on T; the returned move
//!   stays within the limits (to 1e-12 relative).

mod polynomial;
mod via;

// The roots module moved to the crate root (`crate::roots`); this alias keeps the call sites
// in `spline::bounded` and `topp::jerk_optimal::certify` compiling until they import it there.
pub(crate) use crate::roots;

pub use polynomial::Polynomial;
pub use via::{ViaTiming, ViaTrajectory, ViaVelocities};

use crate::error::{Error, Result};
use crate::limits::Limits;
use crate::traj::{Order, Trajectory};

/// Degree of a point-to-point polynomial.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Degree {
    /// Degree 3: position and velocity at both ends; acceleration jumps at the ends.
    Cubic,
    /// Degree 5: adds acceleration; the minimum-jerk motion. Jerk jumps at the ends.
    Quintic,
    /// Degree 7: adds jerk; continuous jerk.
    Septic,
}

impl Degree {
    /// All three, lowest first.
    pub const ALL: [Degree; 3] = [Degree::Cubic, Degree::Quintic, Degree::Septic];

    /// Number of boundary conditions at each end (2, 3, 4).
    pub fn conditions_per_end(self) -> usize {
        match self {
            Degree::Cubic => 2,
            Degree::Quintic => 3,
            Degree::Septic => 4,
        }
    }

    /// Polynomial degree (3, 5, 7).
    pub fn degree(self) -> usize {
        2 * self.conditions_per_end() - 1
    }

    /// Name: `"cubic"`, `"quintic"`, `"septic"`.
    pub fn name(self) -> &'static str {
        match self {
            Degree::Cubic => "cubic",
            Degree::Quintic => "quintic",
            Degree::Septic => "septic",
        }
    }

    /// Parses `"cubic"`, `"quintic"` (also `"min-jerk"`), `"septic"`, or `"3"`, `"5"`, `"7"`.
    pub fn parse(s: &str) -> Result<Degree> {
        match s.to_ascii_lowercase().as_str() {
            "cubic" | "3" => Ok(Degree::Cubic),
            "quintic" | "5" | "min-jerk" | "minimum-jerk" => Ok(Degree::Quintic),
            "septic" | "7" => Ok(Degree::Septic),
            _ => Err(Error::Parse {
                location: crate::error::Location {
                    source: "polynomial degree".into(),
                    line: 0,
                    field: "degree".into(),
                },
                message: format!("'{s}' is not cubic, quintic or septic"),
            }),
        }
    }

    /// The unit rest-to-rest profile f (0 → 1 over T = 1), solved from its boundary conditions.
    pub fn unit_profile(self) -> Polynomial {
        let m = self.conditions_per_end();
        let mut end = [0.0; 4];
        end[0] = 1.0;
        Polynomial::from_boundary(&[0.0; 4][..m], &end[..m], 1.0)
            .expect("unit boundary problem is regular")
    }
}

/// Peak coefficients of the unit rest-to-rest profile: `[peak |q̇|·T/Δq, peak |q̈|·T²/Δq,
/// peak |q⃛|·T³/Δq]`. Computed from the profile's derivatives (cubic 1.5 / 6 / 12, quintic
/// 1.875 / 5.7735 / 60, septic 2.1875 / 7.5132 / 52.5).
///
/// For the cubic the jerk is the constant −12 (impulses at the ends aside); for the cubic and
/// quintic the highest finite derivative jumps at the ends, which the coefficient ignores.
pub fn peak_coefficients(degree: Degree) -> [f64; 3] {
    let f = degree.unit_profile();
    [f.peak_abs(1).0, f.peak_abs(2).0, f.peak_abs(3).0]
}

/// A synchronized point-to-point move of several joints: one [`Polynomial`] per joint, all of
/// the same duration.
///
/// ```
/// use trajkit::{poly::{Degree, PolyMove}, Order, Trajectory};
/// let mv = PolyMove::rest_to_rest(Degree::Septic, &[0.0], &[2.0], 4.0)?;
/// let mut v = [0.0];
/// mv.eval(2.0, Order::Velocity, &mut v);
/// // peak velocity = 2.1875 · Δq / T
/// assert!((v[0] - 2.1875 * 2.0 / 4.0).abs() < 1e-12);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PolyMove {
    joints: Vec<Polynomial>,
    duration: f64,
    table: JointTable,
}

/// Several joints' polynomials of one common duration, laid out for evaluation: for each half
/// (τ ≤ ½ in τ, else in u = 1 − τ) and order 0..=3, the coefficients are stored power-major
/// and joint-minor, so one Horner pass runs over all joints at once (independent chains the
/// CPU overlaps, and that the compiler can vectorize).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct JointTable {
    dof: usize,
    /// Coefficient count (degree + 1).
    len: usize,
    duration: f64,
    /// `[half][order]` blocks of `len × dof` values.
    data: Vec<f64>,
}

impl JointTable {
    /// From polynomials that all have `duration` and the same coefficient count.
    pub(crate) fn new(joints: &[Polynomial]) -> JointTable {
        let dof = joints.len();
        let len = joints.iter().map(|p| p.degree() + 1).max().unwrap_or(1);
        let duration = joints.first().map(|p| p.duration()).unwrap_or(1.0);
        let block = len * dof;
        let mut data = vec![0.0; 2 * 4 * block];
        for (h, first) in [true, false].into_iter().enumerate() {
            for k in 0..4 {
                for (j, p) in joints.iter().enumerate() {
                    if k > p.degree() {
                        continue;
                    }
                    for (i, &v) in p.table(k, first).iter().enumerate() {
                        data[(h * 4 + k) * block + i * dof + j] = v;
                    }
                }
            }
        }
        JointTable {
            dof,
            len,
            duration,
            data,
        }
    }

    /// Order `k` ≤ 3 at local time `t` (clamped to the table's duration) into `out[..dof]`.
    #[inline]
    pub(crate) fn eval(&self, t: f64, k: usize, out: &mut [f64]) {
        let out = &mut out[..self.dof];
        let tc = crate::traj::clamp_time(t, self.duration);
        if k >= self.len {
            out.fill(if tc.is_nan() { f64::NAN } else { 0.0 });
            return;
        }
        let tau = tc / self.duration;
        let first = tau <= 0.5;
        let x = if first {
            tau
        } else {
            (self.duration - tc) / self.duration
        };
        let h = if first { 0 } else { 1 };
        let block = self.len * self.dof;
        let base = (h * 4 + k) * block;
        let n = self.len - k;
        let top = &self.data[base + (n - 1) * self.dof..base + n * self.dof];
        out.copy_from_slice(top);
        for i in (0..n - 1).rev() {
            let row = &self.data[base + i * self.dof..base + (i + 1) * self.dof];
            for (o, &c) in out.iter_mut().zip(row) {
                *o = *o * x + c;
            }
        }
    }
}

/// A kinematic state of all joints at one end of a move. Missing derivatives are zero.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EndState {
    /// Positions.
    pub q: Vec<f64>,
    /// Velocities (empty = zero).
    pub qd: Vec<f64>,
    /// Accelerations (empty = zero).
    pub qdd: Vec<f64>,
    /// Jerks (empty = zero).
    pub qddd: Vec<f64>,
}

impl EndState {
    /// At rest at `q`.
    pub fn at_rest(q: &[f64]) -> Self {
        EndState {
            q: q.to_vec(),
            ..Default::default()
        }
    }

    /// Condition k (0 = position) of joint j; zero when that derivative is not given.
    fn get(&self, k: usize, j: usize) -> f64 {
        let v = [&self.q, &self.qd, &self.qdd, &self.qddd][k];
        v.get(j).copied().unwrap_or(0.0)
    }

    fn validate(&self, which: &str, dof: usize, degree: Degree) -> Result<()> {
        let m = degree.conditions_per_end();
        for (k, v) in [&self.q, &self.qd, &self.qdd, &self.qddd]
            .iter()
            .enumerate()
        {
            let name = Order::ALL[k].name();
            if k == 0 || !v.is_empty() {
                if v.len() != dof {
                    return Err(Error::DimensionMismatch {
                        what: format!("{which} {name} joint count"),
                        expected: dof,
                        found: v.len(),
                    });
                }
                for (j, &x) in v.iter().enumerate() {
                    crate::error::finite(|| format!("{which} {name} of joint {}", j + 1), x)?;
                    if k >= m && x != 0.0 {
                        return Err(Error::InvalidValue {
                            field: format!("{which} {name} of joint {}", j + 1),
                            value: x,
                            reason: "cannot be met by this degree (use a higher degree)",
                        });
                    }
                }
            }
        }
        Ok(())
    }
}

impl PolyMove {
    /// Rest-to-rest move from `q0` to `q1` over `duration`.
    pub fn rest_to_rest(degree: Degree, q0: &[f64], q1: &[f64], duration: f64) -> Result<Self> {
        PolyMove::between(
            degree,
            &EndState::at_rest(q0),
            &EndState::at_rest(q1),
            duration,
        )
    }

    /// Move between arbitrary end states (conditions beyond the degree's must be zero/absent).
    pub fn between(
        degree: Degree,
        start: &EndState,
        end: &EndState,
        duration: f64,
    ) -> Result<Self> {
        let dof = start.q.len();
        if dof == 0 {
            return Err(Error::DimensionMismatch {
                what: "start position joint count".into(),
                expected: 1,
                found: 0,
            });
        }
        start.validate("start", dof, degree)?;
        end.validate("end", dof, degree)?;
        crate::error::positive(|| "move duration".into(), duration)?;
        let m = degree.conditions_per_end();
        let joints = (0..dof)
            .map(|j| {
                let s: Vec<f64> = (0..m).map(|k| start.get(k, j)).collect();
                let e: Vec<f64> = (0..m).map(|k| end.get(k, j)).collect();
                Polynomial::from_boundary(&s, &e, duration)
            })
            .collect::<Result<Vec<_>>>()?;
        let table = JointTable::new(&joints);
        Ok(PolyMove {
            joints,
            duration,
            table,
        })
    }

    /// The polynomial of joint `j`.
    pub fn joint(&self, j: usize) -> &Polynomial {
        &self.joints[j]
    }

    /// Peak |derivative `order`| per joint over the move.
    pub fn peaks(&self, order: Order) -> Vec<f64> {
        self.joints
            .iter()
            .map(|p| p.peak_abs(order.index()).0)
            .collect()
    }

    /// The largest ratio of any joint's velocity, acceleration or jerk to its limit (exact:
    /// from the polynomials' extrema, directional limits respected).
    pub fn worst_limit_ratio(&self, limits: &Limits) -> Result<f64> {
        limits.expect_dof(self.dof(), "polynomial move")?;
        Ok(worst_ratio_of(&self.joints, limits))
    }
}

/// Exact worst ratio over joints and orders 1..=3 of a set of polynomials (one per joint).
pub(crate) fn worst_ratio_of(joints: &[Polynomial], limits: &Limits) -> f64 {
    let mut worst: f64 = 0.0;
    for (j, p) in joints.iter().enumerate() {
        let jl = limits.joint(j);
        for order in [Order::Velocity, Order::Acceleration, Order::Jerk] {
            let k = order.index();
            // Signed extrema: check both the max and the min of the derivative.
            let (lo, hi) = signed_range(p, k);
            worst = worst.max(jl.ratio(order, hi)).max(jl.ratio(order, lo));
        }
    }
    worst
}

/// Smallest and largest value of the k-th derivative over [0, T].
fn signed_range(p: &Polynomial, k: usize) -> (f64, f64) {
    // Build the k-th derivative as its own polynomial and use its position range.
    let c = p.normalized_coefficients();
    if k >= c.len() {
        return (0.0, 0.0);
    }
    let mut d = [0.0; 8];
    let n = c.len() - k;
    for j in 0..n {
        let f: f64 = ((j + 1)..=(j + k)).fold(1.0, |a, x| a * x as f64);
        d[j] = c[j + k] * f;
    }
    let scale = p.duration().powi(-(k as i32));
    let q = Polynomial::from_normalized(&d[..n], p.duration()).expect("finite coefficients");
    let (lo, hi) = q.position_range();
    (lo * scale, hi * scale)
}

impl Trajectory for PolyMove {
    fn dof(&self) -> usize {
        self.joints.len()
    }
    fn duration(&self) -> f64 {
        self.duration
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        self.table.eval(t, order.index(), out);
    }
}

/// The shortest duration of a rest-to-rest move q0 → q1 of the given degree for which every
/// joint stays within its velocity, acceleration and jerk limits, all joints arriving together.
///
/// Closed form from the peak coefficients: per joint
/// `T = max(c_v·Δq/v_max, √(c_a·Δq/a_max), ∛(c_j·Δq/j_max))` (directional limits: the tighter
/// side, since a rest-to-rest profile uses both signs of acceleration and jerk, and the sign of
/// Δq for velocity); the move takes the largest joint's T. Joints that do not move need no time.
/// The cubic's jerk is ignored: its infinite jerk at the ends cannot be limited.
///
/// Errors: dimension mismatch; a moving joint with no finite limit at all (no duration would
/// be implied); all joints at rest (Δq = 0 everywhere gives duration 0, which is returned).
pub fn min_duration_rest_to_rest(
    degree: Degree,
    q0: &[f64],
    q1: &[f64],
    limits: &Limits,
) -> Result<f64> {
    if q0.len() != q1.len() {
        return Err(Error::DimensionMismatch {
            what: "end position joint count".into(),
            expected: q0.len(),
            found: q1.len(),
        });
    }
    limits.expect_dof(q0.len(), "rest-to-rest move")?;
    let [cv, ca, cj] = peak_coefficients(degree);
    let mut t: f64 = 0.0;
    for j in 0..q0.len() {
        crate::error::finite(|| format!("start position of joint {}", j + 1), q0[j])?;
        crate::error::finite(|| format!("end position of joint {}", j + 1), q1[j])?;
        let dq = q1[j] - q0[j];
        if dq == 0.0 {
            continue;
        }
        let jl = limits.joint(j);
        let (vlo, vhi) = jl.range(Order::Velocity);
        let v = if dq > 0.0 { vhi } else { -vlo };
        let a = jl.symmetric_limit(Order::Acceleration);
        let jk = jl.symmetric_limit(Order::Jerk);
        let d = dq.abs();
        let tv = cv * d / v;
        let ta = (ca * d / a).sqrt();
        let tj = if degree == Degree::Cubic {
            0.0
        } else {
            (cj * d / jk).cbrt()
        };
        let tj_joint = tv.max(ta).max(tj);
        if tj_joint == 0.0 {
            return Err(Error::Infeasible(format!(
                "joint {} must move by {dq} but has no finite velocity, acceleration or jerk limit",
                j + 1
            )));
        }
        t = t.max(tj_joint);
    }
    Ok(t)
}

/// The shortest duration for a move between general end states (non-zero velocities,
/// accelerations) that keeps every joint within its velocity, acceleration and jerk limits.
///
/// Feasibility is checked exactly from the polynomials' extrema. The search scans T upward
/// geometrically (factor 1.05) from a lower bound — the largest |Δq|/v_max — to the first
/// feasible duration, then bisects to 1e-10 relative between it and the last infeasible one.
/// If the feasible set of durations is an interval [T*, ∞) (always so at rest; typical
/// otherwise) the result is T*. The scan stops at 10⁶ × the lower bound with
/// [`Error::Infeasible`] (e.g. an end velocity beyond the velocity limit).
pub fn min_duration(
    degree: Degree,
    start: &EndState,
    end: &EndState,
    limits: &Limits,
) -> Result<f64> {
    let dof = start.q.len();
    limits.expect_dof(dof, "polynomial move")?;
    start.validate("start", dof, degree)?;
    end.validate("end", dof, degree)?;
    let m = degree.conditions_per_end();
    let ignore_jerk = degree == Degree::Cubic;
    let feasible = |t: f64| -> Result<bool> {
        let mut joints = Vec::with_capacity(dof);
        for j in 0..dof {
            let s: Vec<f64> = (0..m).map(|k| start.get(k, j)).collect();
            let e: Vec<f64> = (0..m).map(|k| end.get(k, j)).collect();
            joints.push(Polynomial::from_boundary(&s, &e, t)?);
        }
        let mut ok = true;
        for (j, p) in joints.iter().enumerate() {
            let jl = limits.joint(j);
            for order in [Order::Velocity, Order::Acceleration, Order::Jerk] {
                if ignore_jerk && order == Order::Jerk {
                    continue;
                }
                let (lo, hi) = signed_range(p, order.index());
                if jl.ratio(order, hi) > 1.0 || jl.ratio(order, lo) > 1.0 {
                    ok = false;
                }
            }
        }
        Ok(ok)
    };
    // Lower bound: average velocity cannot exceed the limit.
    let mut lower: f64 = 0.0;
    let mut moving = false;
    for j in 0..dof {
        let dq = end.q[j] - start.q[j];
        let any_motion =
            dq != 0.0 || (1..m).any(|k| start.get(k, j) != 0.0 || end.get(k, j) != 0.0);
        moving |= any_motion;
        let v = limits.joint(j).symmetric_limit(Order::Velocity);
        if v.is_finite() {
            lower = lower.max(dq.abs() / v);
        }
    }
    if !moving {
        return Ok(0.0);
    }
    if lower == 0.0 {
        lower = 1e-6;
    }
    let mut bad = lower * 0.999_999;
    let mut t = lower;
    let cap = lower * 1e6;
    while !feasible(t)? {
        bad = t;
        t *= 1.05;
        if t > cap {
            return Err(Error::Infeasible(format!(
                "no {} move up to {cap:.3e} s keeps these end states within the limits",
                degree.name()
            )));
        }
    }
    let mut good = t;
    while (good - bad) > 1e-10 * good {
        let mid = 0.5 * (good + bad);
        if feasible(mid)? {
            good = mid;
        } else {
            bad = mid;
        }
    }
    Ok(good)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joint_table_matches_each_polynomial() {
        let mut g = crate::rng::SplitMix64::new(5);
        for d in Degree::ALL {
            let q0: Vec<f64> = (0..5).map(|_| g.uniform(-2.0, 2.0)).collect();
            let q1: Vec<f64> = (0..5).map(|_| g.uniform(-2.0, 2.0)).collect();
            let start = EndState {
                q: q0,
                qd: (0..5).map(|_| g.uniform(-1.0, 1.0)).collect(),
                ..Default::default()
            };
            let mv = PolyMove::between(d, &start, &EndState::at_rest(&q1), 1.7).unwrap();
            let mut out = [0.0; 5];
            for i in 0..=100 {
                let t = -0.1 + 1.9 * i as f64 / 100.0;
                for o in Order::ALL {
                    mv.eval(t, o, &mut out);
                    for j in 0..5 {
                        let want = mv.joint(j).eval(t, o.index());
                        assert!(
                            (out[j] - want).abs() <= 1e-12 * (1.0 + want.abs()),
                            "{d:?} {o:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn seed_peak_coefficient_table() {
        let want = [
            (Degree::Cubic, [1.5, 6.0, 12.0]),
            (Degree::Quintic, [1.875, 5.7735, 60.0]),
            (Degree::Septic, [2.1875, 7.5132, 52.5]),
        ];
        for (d, w) in want {
            let got = peak_coefficients(d);
            for k in 0..3 {
                assert!(
                    (got[k] - w[k]).abs() < 5e-5,
                    "{} coefficient {k}: {} vs {}",
                    d.name(),
                    got[k],
                    w[k]
                );
            }
        }
        // Exact values where they are known in closed form.
        let q = peak_coefficients(Degree::Quintic);
        assert!((q[1] - 10.0 / 3f64.sqrt()).abs() < 1e-13);
        assert!((peak_coefficients(Degree::Septic)[0] - 35.0 / 16.0).abs() < 1e-14);
    }

    #[test]
    fn scaling_to_any_motion() {
        // q0 -> qT over T: peaks scale as Δq/T^k.
        for d in Degree::ALL {
            let c = peak_coefficients(d);
            let mv = PolyMove::rest_to_rest(d, &[1.0], &[-2.0], 3.0).unwrap();
            for (k, order) in [Order::Velocity, Order::Acceleration, Order::Jerk]
                .iter()
                .enumerate()
            {
                let want = c[k] * 3.0 / 3f64.powi(k as i32 + 1);
                let got = mv.peaks(*order)[0];
                assert!((got - want).abs() < 1e-12 * want.max(1.0), "{got} {want}");
            }
        }
    }

    #[test]
    fn seed_example_cubic_needs_15_rad_per_s() {
        // Δq = 5 rad in T = 0.5 s with a cubic: peak velocity 1.5·5/0.5 = 15 rad/s.
        let mv = PolyMove::rest_to_rest(Degree::Cubic, &[0.0], &[5.0], 0.5).unwrap();
        assert!((mv.peaks(Order::Velocity)[0] - 15.0).abs() < 1e-12);
    }

    #[test]
    fn min_duration_is_tight_for_every_limit() {
        let limits = Limits::preset("panda").unwrap();
        let q0 = [0.0, -0.5, 0.3, -2.0, 0.0, 1.5, 0.7];
        let q1 = [1.5, 0.2, -0.4, -1.0, 0.01, 2.0, -0.3];
        for d in Degree::ALL {
            let t = min_duration_rest_to_rest(d, &q0, &q1, &limits).unwrap();
            let mv = PolyMove::rest_to_rest(d, &q0, &q1, t).unwrap();
            let w = mv.worst_limit_ratio(&limits).unwrap();
            let w = if d == Degree::Cubic {
                // jerk not limited for cubics
                let mut worst: f64 = 0.0;
                for j in 0..7 {
                    for o in [Order::Velocity, Order::Acceleration] {
                        worst = worst.max(limits.joint(j).ratio(o, mv.peaks(o)[j]));
                    }
                }
                worst
            } else {
                w
            };
            assert!((w - 1.0).abs() < 1e-12, "{}: worst ratio {w}", d.name());
            // A slightly shorter move violates a limit.
            let faster = PolyMove::rest_to_rest(d, &q0, &q1, t * (1.0 - 1e-6)).unwrap();
            assert!(faster.worst_limit_ratio(&limits).unwrap() > 1.0);
        }
        // Long moves are velocity-limited: T = c_v Δq / v.
        let l = Limits::uniform(1, 1.0, 100.0, 1e5).unwrap();
        let t = min_duration_rest_to_rest(Degree::Quintic, &[0.0], &[10.0], &l).unwrap();
        assert!((t - 18.75).abs() < 1e-12);
    }

    #[test]
    fn general_min_duration_respects_limits() {
        let limits = Limits::uniform(2, 2.0, 10.0, 100.0).unwrap();
        let start = EndState {
            q: vec![0.0, 1.0],
            qd: vec![1.0, -0.5],
            ..Default::default()
        };
        let end = EndState {
            q: vec![1.0, 0.0],
            qd: vec![0.5, 0.0],
            ..Default::default()
        };
        for d in [Degree::Quintic, Degree::Septic] {
            let t = min_duration(d, &start, &end, &limits).unwrap();
            let mv = PolyMove::between(d, &start, &end, t).unwrap();
            let w = mv.worst_limit_ratio(&limits).unwrap();
            assert!(w <= 1.0 + 1e-12 && w > 1.0 - 1e-6, "{w}");
        }
        // End velocity beyond the limit: infeasible, with a clear error (no hang).
        let end_fast = EndState {
            q: vec![1.0, 0.0],
            qd: vec![3.0, 0.0],
            ..Default::default()
        };
        assert!(matches!(
            min_duration(Degree::Quintic, &start, &end_fast, &limits),
            Err(Error::Infeasible(_))
        ));
    }

    #[test]
    fn bad_input() {
        let l = Limits::uniform(2, 1.0, 1.0, 1.0).unwrap();
        assert!(min_duration_rest_to_rest(Degree::Quintic, &[0.0], &[1.0, 2.0], &l).is_err());
        assert!(
            min_duration_rest_to_rest(Degree::Quintic, &[0.0, 0.0], &[1.0, f64::NAN], &l).is_err()
        );
        let free = Limits::uniform(1, f64::INFINITY, f64::INFINITY, f64::INFINITY).unwrap();
        assert!(matches!(
            min_duration_rest_to_rest(Degree::Quintic, &[0.0], &[1.0], &free),
            Err(Error::Infeasible(_))
        ));
        assert!(PolyMove::rest_to_rest(Degree::Quintic, &[], &[], 1.0).is_err());
        assert!(PolyMove::rest_to_rest(Degree::Quintic, &[0.0], &[1.0], 0.0).is_err());
        let s = EndState {
            q: vec![0.0],
            qdd: vec![1.0],
            ..Default::default()
        };
        let e = PolyMove::between(Degree::Cubic, &s, &EndState::at_rest(&[1.0]), 1.0).unwrap_err();
        assert!(
            e.to_string().contains("start acceleration of joint 1"),
            "{e}"
        );
        assert_eq!(Degree::parse("min-jerk").unwrap(), Degree::Quintic);
        assert!(Degree::parse("nonic").is_err());
    }
}
