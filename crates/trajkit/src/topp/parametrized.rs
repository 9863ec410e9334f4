//! The solved timing: path velocity at every gridpoint, constant path acceleration between.
//!
//! A [`PhaseProfile`] holds gridpoints s_i, path velocities ṡ_i and the constant path acceleration
//! u_i = (ṡ_{i+1}² − ṡ_i²) / (2Δ_i) of each interval. In time, interval i lasts
//! Δt_i = 2Δ_i / (ṡ_i + ṡ_{i+1}) and, with τ = t − t_i,
//! `ṡ = ṡ_i + u_i·τ`, `s = s_i + ṡ_i·τ + u_i·τ²/2`, s⃛ = 0 inside the interval.
//!
//! [`Parametrized`] is the path composed with that profile ([`crate::topp::Retimed`]): the
//! output trajectory ξ(t) = σ(s(t)) of TOPP-RA, evaluated exactly (q̇ = σ′ṡ,
//! q̈ = σ″ṡ² + σ′s̈, q⃛ = σ‴ṡ³ + 3σ″ṡs̈), never refitted by another spline.
//!
//! # Precision contract
//! PhaseProfile evaluation is exact up to rounding; at the end of an interval s reaches s_{i+1}
//! up to rounding, and s is clamped into `[s_i, s_{i+1}]`. Position is continuous, velocity is
//! continuous, path acceleration is piecewise constant, so joint jerk contains the jumps of s̈
//! as impulses that [`crate::Trajectory::eval`] does not show (it reports the jerk inside the
//! interval).

use super::rescale::{Retimed, TimeLaw};
use crate::error::{Error, Result};
use crate::traj::{clamp_time, find_piece};

/// TOPP-RA's output trajectory: a path timed by a [`PhaseProfile`].
pub type Parametrized<P> = Retimed<P, PhaseProfile>;

/// A phase-plane profile: the path velocity ṡ at gridpoints over the path position s, and the
/// constant path acceleration between them. (`otg::Profile` is a different thing: one DOF's
/// online jerk-limited profile.)
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseProfile {
    s: Vec<f64>,
    sd: Vec<f64>,
    sdd: Vec<f64>,
    t: Vec<f64>,
}

/// Whether the gridpoints `s` (as many as `sd`) are finite and strictly increasing and the
/// velocities `sd` finite and ≥ 0: one pass without early exits, the common case.
fn valid_points(s: &[f64], sd: &[f64]) -> bool {
    // s_0 finite (then every later s_i is, when it is finite and above s_{i−1}: checked as
    // s_{i−1} < s_i < ∞); NaN fails every comparison.
    let mut ok = s[0].is_finite();
    for w in s.windows(2) {
        ok &= (w[0] < w[1]) & (w[1] < f64::INFINITY);
    }
    for &v in sd {
        ok &= (0.0..f64::INFINITY).contains(&v);
    }
    ok
}

impl PhaseProfile {
    /// A profile from gridpoints (strictly increasing) and path velocities `sd` (≥ 0, finite,
    /// one per gridpoint). Two consecutive zero velocities would take infinite time and are
    /// refused.
    pub fn new(s: &[f64], sd: &[f64]) -> Result<Self> {
        Self::from_vecs(s.to_vec(), sd.to_vec())
    }

    /// [`PhaseProfile::new`] taking the gridpoints and velocities as they are (no copies).
    pub(crate) fn from_vecs(s: Vec<f64>, sd: Vec<f64>) -> Result<Self> {
        Self::check_points(&s, &sd)?;
        let (sdd, t) = Self::timing(&s, &sd)?;
        Ok(PhaseProfile { s, sd, sdd, t })
    }

    /// The checks of [`PhaseProfile::new`] on its arguments.
    fn check_points(s: &[f64], sd: &[f64]) -> Result<()> {
        if s.len() < 2 {
            return Err(Error::DimensionMismatch {
                what: "profile gridpoint count".into(),
                expected: 2,
                found: s.len(),
            });
        }
        if sd.len() != s.len() {
            return Err(Error::DimensionMismatch {
                what: "profile velocity count".into(),
                expected: s.len(),
                found: sd.len(),
            });
        }
        if !valid_points(s, sd) {
            Self::explain_points(s, sd)?;
        }
        Ok(())
    }

    /// The path accelerations and gridpoint times of checked gridpoints and velocities.
    fn timing(s: &[f64], sd: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
        let n = s.len() - 1;
        let mut sdd = Vec::with_capacity(n);
        let mut t = Vec::with_capacity(n + 1);
        let mut ti = 0.0;
        t.push(ti);
        for (sw, vw) in s.windows(2).zip(sd.windows(2)) {
            let d = sw[1] - sw[0];
            let v = vw[0] + vw[1];
            if v <= 0.0 {
                return Err(Error::Infeasible(format!(
                    "the path velocity is zero on [{}, {}]: the motion would take forever",
                    sw[0], sw[1]
                )));
            }
            sdd.push((vw[1] - vw[0]) * v / (2.0 * d));
            ti += 2.0 * d / v;
            t.push(ti);
        }
        if !ti.is_finite() {
            return Err(Error::Infeasible(
                "the duration is not finite (path velocity too close to zero)".into(),
            ));
        }
        Ok((sdd, t))
    }

    /// The error for the first gridpoint or velocity that [`valid_points`] refuses (none
    /// when all are valid).
    fn explain_points(s: &[f64], sd: &[f64]) -> Result<()> {
        for i in 0..s.len() {
            crate::error::finite(|| format!("profile gridpoint {i}"), s[i])?;
            if i > 0 && s[i].partial_cmp(&s[i - 1]) != Some(std::cmp::Ordering::Greater) {
                return Err(Error::InvalidValue {
                    field: format!("profile gridpoint {i}"),
                    value: s[i],
                    reason: "does not increase",
                });
            }
            if !(sd[i] >= 0.0 && sd[i].is_finite()) {
                return Err(Error::InvalidValue {
                    field: format!("profile path velocity {i}"),
                    value: sd[i],
                    reason: "is not a finite number >= 0",
                });
            }
        }
        Ok(())
    }

    /// Gridpoints s_i.
    pub fn gridpoints(&self) -> &[f64] {
        &self.s
    }

    /// Path velocities ṡ_i at the gridpoints.
    pub fn velocities(&self) -> &[f64] {
        &self.sd
    }

    /// Path accelerations u_i, one per interval.
    pub fn accelerations(&self) -> &[f64] {
        &self.sdd
    }

    /// Times t_i at which the gridpoints are reached (t_0 = 0).
    pub fn times(&self) -> &[f64] {
        &self.t
    }

    /// Total duration.
    pub fn duration(&self) -> f64 {
        self.t[self.t.len() - 1]
    }
}

impl TimeLaw for PhaseProfile {
    fn duration(&self) -> f64 {
        PhaseProfile::duration(self)
    }
    fn eval(&self, t: f64) -> [f64; 4] {
        let t = clamp_time(t, PhaseProfile::duration(self));
        let n = self.sdd.len();
        if t >= self.t[n] {
            // The end state exactly (rest stays rest).
            return [self.s[n], self.sd[n], self.sdd[n - 1], 0.0];
        }
        self.in_interval(find_piece(&self.t, t), t)
    }

    /// [`TimeLaw::eval`] at each time, the interval found by walking forward from the previous
    /// time's (increasing times, as sampling gives) instead of a binary search; the same
    /// interval as [`find_piece`] (a time before the previous one searches again), so the same
    /// values.
    fn eval_many(&self, times: &[f64], out: &mut [[f64; 4]]) {
        let n = self.sdd.len();
        let end = PhaseProfile::duration(self);
        let mut i = 0;
        for (&t, o) in times.iter().zip(out.iter_mut()) {
            let t = clamp_time(t, end);
            if t >= self.t[n] {
                *o = [self.s[n], self.sd[n], self.sdd[n - 1], 0.0];
                continue;
            }
            if i > 0 && (t.is_nan() || self.t[i] > t) {
                i = find_piece(&self.t, t);
            } else {
                // Every break up to t[i] is ≤ t: count the following ones, as find_piece.
                while i + 1 < n && self.t[i + 1] <= t {
                    i += 1;
                }
            }
            *o = self.in_interval(i, t);
        }
    }
}

impl PhaseProfile {
    /// The state at time `t` (before the end) in interval `i`.
    #[inline]
    fn in_interval(&self, i: usize, t: f64) -> [f64; 4] {
        let tau = t - self.t[i];
        let u = self.sdd[i];
        let sd = self.sd[i] + u * tau;
        let s =
            (self.s[i] + self.sd[i] * tau + 0.5 * u * tau * tau).clamp(self.s[i], self.s[i + 1]);
        [s, sd.max(0.0), u, 0.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_acceleration_pieces() {
        // From rest, u = 1 on [0, 0.5]: ṡ₁ = 1, t₁ = 1; then constant speed on [0.5, 1.5].
        let p = PhaseProfile::new(&[0.0, 0.5, 1.5], &[0.0, 1.0, 1.0]).unwrap();
        assert_eq!(p.accelerations(), &[1.0, 0.0]);
        assert_eq!(p.times(), &[0.0, 1.0, 2.0]);
        let [s, sd, sdd, _] = p.eval(0.5);
        assert!((s - 0.125).abs() < 1e-15 && (sd - 0.5).abs() < 1e-15 && sdd == 1.0);
        assert_eq!(p.eval(5.0)[0], 1.5);
        assert!(PhaseProfile::new(&[0.0, 1.0, 2.0], &[1.0, 0.0, 0.0]).is_err());
        assert!(PhaseProfile::new(&[0.0, 1.0], &[1.0, -1.0]).is_err());
        assert!(PhaseProfile::new(&[0.0, 0.0], &[1.0, 1.0]).is_err());
    }

    /// The one-pass screen refuses exactly what the point-by-point checks name, and the
    /// error names the first offending gridpoint or velocity.
    #[test]
    fn invalid_points_are_named() {
        let (inf, nan) = (f64::INFINITY, f64::NAN);
        let field = |s: &[f64], sd: &[f64]| match PhaseProfile::new(s, sd) {
            Err(Error::InvalidValue { field, .. }) => Some(field),
            Ok(_) => None,
            Err(e) => panic!("{e}"),
        };
        let sd = [1.0; 4];
        for (s, want) in [
            ([-inf, 0.0, 1.0, 2.0], "profile gridpoint 0"),
            ([nan, 0.0, 1.0, 2.0], "profile gridpoint 0"),
            ([0.0, 1.0, 2.0, inf], "profile gridpoint 3"),
            ([0.0, 1.0, nan, 2.0], "profile gridpoint 2"),
            ([0.0, 1.0, 1.0, 2.0], "profile gridpoint 2"),
            ([0.0, 2.0, 1.0, 3.0], "profile gridpoint 2"),
        ] {
            assert!(!valid_points(&s, &sd), "{s:?}");
            assert_eq!(field(&s, &sd).as_deref(), Some(want), "{s:?}");
        }
        let s = [0.0, 1.0, 2.0, 3.0];
        for (sd, want) in [
            ([1.0, -1e-300, 1.0, 1.0], Some("profile path velocity 1")),
            ([1.0, 1.0, 1.0, inf], Some("profile path velocity 3")),
            ([nan, 1.0, 1.0, 1.0], Some("profile path velocity 0")),
            ([-0.0, 1.0, 0.0, 1.0], None),
        ] {
            assert_eq!(valid_points(&s, &sd), want.is_none(), "{sd:?}");
            assert_eq!(field(&s, &sd).as_deref(), want, "{sd:?}");
        }
        // Points are checked in order, each for all it must meet.
        let f = field(&[0.0, 1.0, 0.5, 2.0], &[1.0, -1.0, 1.0, 1.0]);
        assert_eq!(f.as_deref(), Some("profile path velocity 1"));
        let f = field(&[0.0, 0.5, 0.5, 2.0], &[1.0, 1.0, 1.0, -1.0]);
        assert_eq!(f.as_deref(), Some("profile gridpoint 2"));
    }

    /// `eval_many` (forward walk) gives `eval`'s values bit for bit: increasing times on and
    /// between the interval ends, repeats, a time going back, NaN, times outside.
    #[test]
    fn eval_many_equals_eval() {
        let mut rng = crate::rng::SplitMix64::new(3);
        let s: Vec<f64> = (0..50).map(|i| i as f64 * 0.1).collect();
        let sd: Vec<f64> = (0..50)
            .map(|i| if i == 0 { 0.0 } else { rng.uniform(0.2, 2.0) })
            .collect();
        let p = PhaseProfile::new(&s, &sd).unwrap();
        let d = p.duration();
        let mut times: Vec<f64> = (0..=400).map(|i| d * i as f64 / 400.0).collect();
        times.extend_from_slice(&p.times()[..10]);
        times.extend_from_slice(&[
            0.3 * d,
            0.3 * d,
            0.1 * d,
            f64::NAN,
            0.5 * d,
            -1.0,
            2.0 * d,
            d,
        ]);
        let mut many = vec![[0.0; 4]; times.len()];
        p.eval_many(&times, &mut many);
        for (&t, m) in times.iter().zip(&many) {
            assert_eq!(m.map(f64::to_bits), p.eval(t).map(f64::to_bits), "t = {t}");
        }
    }
}
