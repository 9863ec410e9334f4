//! The solved timing law s(t) of the jerk-limited planner, evaluated exactly.
//!
//! Gridpoints s_0 < … < s_N carry x_i = ṡ² and u_i = s̈. Three kinds of interval:
//! - **first** `[s_0, s_1]`: constant path jerk in time from rest, s = s_0 + jτ³/6, so
//!   ṡ = jτ²/2, s̈ = jτ, s⃛ = j, reached at τ₁ = √(6Δ₀/u₁) with x₁ = 1.5·Δ₀·u₁;
//! - **middle**: s̈ linear in s, u(δ) = u_i + v_i·δ and x(δ) = x_i + 2u_i·δ + v_i·δ²
//!   (δ = s − s_i), path jerk s⃛ = v_i·ṡ. The time spent is ∫dδ/√x(δ) in closed form
//!   ([`interval_time`]); a time is mapped to δ by a safeguarded Newton iteration;
//! - **last** `[s_{N−1}, s_N]`: the mirror of the first, s = s_N − cτ³ with τ the time left,
//!   x_{N−1} = −1.5·Δ·u_{N−1}.
//!
//! # Precision contract
//! Evaluation is closed form up to the Newton solve of t(δ) = τ, which runs to a step below
//! 1e-15 of the interval (at most 60 iterations, bisection-safeguarded); s is clamped into its
//! interval, ṡ² ≥ 0. No allocation.

use crate::error::{Error, Result};
use crate::topp::rescale::TimeLaw;
use crate::traj::{clamp_time, find_piece};

/// Time to go from δ = 0 to δ on a middle interval with x(δ) = x0 + 2u·δ + v·δ² (x ≥ 0 on
/// the way): ∫₀^δ dσ/√x(σ), in a form without cancellation for small v and u.
pub(crate) fn interval_time(x0: f64, u: f64, v: f64, delta: f64) -> f64 {
    if delta <= 0.0 {
        return 0.0;
    }
    let x1 = (x0 + 2.0 * u * delta + v * delta * delta).max(0.0);
    let (r0, r1) = (x0.max(0.0).sqrt(), x1.sqrt());
    let rs = r0 + r1;
    if rs <= 0.0 {
        return f64::INFINITY;
    }
    // √x(δ) − √x0 without cancellation.
    let dr = delta * (2.0 * u + v * delta) / rs;
    if v == 0.0 {
        return 2.0 * delta / rs;
    }
    if v > 0.0 {
        let q = v.sqrt();
        if u >= 0.0 {
            let a = q * r0 + u;
            if a <= 0.0 {
                return f64::INFINITY;
            }
            ((q * dr + v * delta) / a).ln_1p() / q
        } else {
            // The conjugate form: (q√x − (vδ + u))·(q√x + vδ + u) = v·x0 − u² is constant.
            let a = q * r0 - u;
            -((q * dr - v * delta) / a).ln_1p() / q
        }
    } else {
        let w = -v;
        let q = w.sqrt();
        let num = q * (w * delta * r0 + u * dr);
        let den = w * r0 * r1 + u * (u - w * delta);
        num.atan2(den) / q
    }
}

/// The jerk-limited timing law: gridpoints, ṡ² and s̈ there, the slope v_i = du/ds of each
/// middle interval, and the time at which each gridpoint is reached.
#[derive(Debug, Clone, PartialEq)]
pub struct JerkProfile {
    s: Vec<f64>,
    x: Vec<f64>,
    u: Vec<f64>,
    v: Vec<f64>,
    t: Vec<f64>,
    /// Path jerk of the first interval (time domain).
    j0: f64,
    /// c of the last interval, s = s_N − c·τ³.
    c_end: f64,
    /// Uniform time scale k ≥ 1: the law is played k times slower.
    scale: f64,
    /// What the planner did.
    pub(crate) report: super::JerkReport,
}

impl JerkProfile {
    /// A law from gridpoints (at least 4, increasing), x = ṡ² and u = s̈ at each. x₀ = u₀ = 0,
    /// x_N = u_N = 0; the first and last intervals are the rest pieces of the module
    /// documentation (x₁ = 1.5Δ₀u₁, x_{N−1} = −1.5Δ_{N−1}u_{N−1}), the middle ones take
    /// v_i = (u_{i+1} − u_i)/Δ_i.
    pub(crate) fn new(s: Vec<f64>, x: Vec<f64>, u: Vec<f64>) -> Result<Self> {
        let n = s.len() - 1;
        if n < 3 || x.len() != n + 1 || u.len() != n + 1 {
            return Err(Error::DimensionMismatch {
                what: "jerk-limited profile gridpoints".into(),
                expected: 4,
                found: s.len(),
            });
        }
        let mut v = vec![0.0; n];
        let mut t = vec![0.0; n + 1];
        let d0 = s[1] - s[0];
        if u[1].is_nan() || u[1] <= 0.0 {
            return Err(Error::Infeasible(format!(
                "the path cannot start moving from s = {} (path acceleration {} at s = {})",
                s[0], u[1], s[1]
            )));
        }
        let t1 = (6.0 * d0 / u[1]).sqrt();
        let j0 = u[1] / t1;
        t[1] = t1;
        for i in 1..n - 1 {
            let d = s[i + 1] - s[i];
            v[i] = (u[i + 1] - u[i]) / d;
            let dt = interval_time(x[i], u[i], v[i], d);
            if !dt.is_finite() {
                return Err(Error::Infeasible(format!(
                    "the path velocity vanishes between s = {} and s = {}",
                    s[i],
                    s[i + 1]
                )));
            }
            t[i + 1] = t[i] + dt;
        }
        let dl = s[n] - s[n - 1];
        if u[n - 1].is_nan() || u[n - 1] >= 0.0 {
            return Err(Error::Infeasible(format!(
                "the path cannot come to rest at s = {} (path acceleration {} at s = {})",
                s[n],
                u[n - 1],
                s[n - 1]
            )));
        }
        let tl = (6.0 * dl / -u[n - 1]).sqrt();
        let c_end = -u[n - 1] / (6.0 * tl);
        t[n] = t[n - 1] + tl;
        Ok(JerkProfile {
            s,
            x,
            u,
            v,
            t,
            j0,
            c_end,
            scale: 1.0,
            report: super::JerkReport::default(),
        })
    }

    /// Gridpoints s_i.
    pub fn gridpoints(&self) -> &[f64] {
        &self.s
    }

    /// ṡ² at the gridpoints.
    pub fn velocities_squared(&self) -> &[f64] {
        &self.x
    }

    /// s̈ at the gridpoints.
    pub fn accelerations(&self) -> &[f64] {
        &self.u
    }

    /// du/ds of each interval (zero for the first and last, which are timed differently).
    pub fn slopes(&self) -> &[f64] {
        &self.v
    }

    /// Times at which the gridpoints are reached.
    pub fn times(&self) -> &[f64] {
        &self.t
    }

    /// Plays the law `k` times slower (k ≥ 1): ṡ/k, s̈/k², s⃛/k³.
    pub(crate) fn set_scale(&mut self, k: f64) {
        self.scale = k;
    }

    /// The duration (including the time scale).
    pub fn duration(&self) -> f64 {
        self.t[self.t.len() - 1] * self.scale
    }

    /// x = ṡ² at path position s (unscaled law).
    pub(crate) fn x_at(&self, s: f64) -> f64 {
        let n = self.s.len() - 1;
        let i = find_piece(&self.s, s);
        let d = (s - self.s[i]).clamp(0.0, self.s[i + 1] - self.s[i]);
        if i == 0 {
            // s = jτ³/6, ṡ = jτ²/2: x = (j/2)²·(6d/j)^(4/3).
            let tau = (6.0 * d / self.j0).cbrt();
            let sd = 0.5 * self.j0 * tau * tau;
            return sd * sd;
        }
        if i == n - 1 {
            let tau = ((self.s[n] - s).max(0.0) / self.c_end).cbrt();
            let sd = 3.0 * self.c_end * tau * tau;
            return sd * sd;
        }
        (self.x[i] + 2.0 * self.u[i] * d + self.v[i] * d * d).max(0.0)
    }

    /// `[s, ṡ, s̈, s⃛]` at time τ into middle interval i.
    fn middle(&self, i: usize, tau: f64) -> [f64; 4] {
        let (x0, u, v) = (self.x[i], self.u[i], self.v[i]);
        let d = self.s[i + 1] - self.s[i];
        let total = self.t[i + 1] - self.t[i];
        let tau = tau.clamp(0.0, total);
        // Taylor guess in time, then Newton on t(δ) = τ bracketed in [lo, hi].
        let sd0 = x0.max(0.0).sqrt();
        let mut delta =
            (sd0 * tau + 0.5 * u * tau * tau + v * sd0 * tau * tau * tau / 6.0).clamp(0.0, d);
        let (mut lo, mut hi) = (0.0, d);
        for _ in 0..60 {
            let f = interval_time(x0, u, v, delta) - tau;
            if f > 0.0 {
                hi = delta;
            } else {
                lo = delta;
            }
            let xd = (x0 + 2.0 * u * delta + v * delta * delta).max(0.0);
            let mut next = delta - f * xd.sqrt();
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            let step = (next - delta).abs();
            delta = next;
            if step <= 1e-15 * d || hi - lo <= 1e-15 * d {
                break;
            }
        }
        let xd = (x0 + 2.0 * u * delta + v * delta * delta).max(0.0);
        let sd = xd.sqrt();
        [
            (self.s[i] + delta).clamp(self.s[i], self.s[i + 1]),
            sd,
            u + v * delta,
            v * sd,
        ]
    }
}

impl TimeLaw for JerkProfile {
    fn duration(&self) -> f64 {
        JerkProfile::duration(self)
    }

    fn eval(&self, t: f64) -> [f64; 4] {
        if self.scale == 1.0 {
            return self.eval_unscaled(t);
        }
        let k = self.scale;
        let [s, sd, sdd, sddd] = self.eval_unscaled(t / k);
        [s, sd / k, sdd / (k * k), sddd / (k * k * k)]
    }
}

impl JerkProfile {
    /// `[s, ṡ, s̈, s⃛]` of the law before time scaling.
    fn eval_unscaled(&self, t: f64) -> [f64; 4] {
        let n = self.s.len() - 1;
        let big_t = self.t[n];
        let t = clamp_time(t, big_t);
        if t.is_nan() {
            return [f64::NAN; 4];
        }
        let i = find_piece(&self.t, t);
        if i == 0 {
            let j = self.j0;
            let s = (self.s[0] + j * t * t * t / 6.0).clamp(self.s[0], self.s[1]);
            return [s, 0.5 * j * t * t, j * t, j];
        }
        if i == n - 1 {
            let c = self.c_end;
            let tau = (big_t - t).max(0.0);
            let s = (self.s[n] - c * tau * tau * tau).clamp(self.s[n - 1], self.s[n]);
            return [s, 3.0 * c * tau * tau, -6.0 * c * tau, 6.0 * c];
        }
        self.middle(i, t - self.t[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Simpson quadrature of ∫dδ/√x on a fine grid, for x bounded away from zero.
    fn quad(x0: f64, u: f64, v: f64, d: f64) -> f64 {
        let m = 20000;
        let h = d / m as f64;
        let f = |z: f64| 1.0 / (x0 + 2.0 * u * z + v * z * z).sqrt();
        let mut acc = f(0.0) + f(d);
        for k in 1..m {
            acc += f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        acc * h / 3.0
    }

    #[test]
    fn interval_time_matches_quadrature() {
        let mut rng = crate::rng::SplitMix64::new(3);
        for _ in 0..300 {
            let x0 = rng.uniform(0.05, 4.0);
            let u = rng.uniform(-3.0, 3.0);
            let d = rng.uniform(0.001, 0.5);
            let v = rng.uniform(-50.0, 50.0) * [1.0, 1e-6, 1e-12][rng.below(3) as usize];
            let x1 = x0 + 2.0 * u * d + v * d * d;
            let xmin = if v > 0.0 && -u / v > 0.0 && -u / v < d {
                x0 - u * u / v
            } else {
                x0.min(x1)
            };
            if xmin < 0.02 {
                continue;
            }
            let a = interval_time(x0, u, v, d);
            let b = quad(x0, u, v, d);
            assert!((a - b).abs() <= 1e-9 * b, "{x0} {u} {v} {d}: {a} vs {b}");
        }
        // Exact: constant acceleration and constant speed.
        assert!((interval_time(1.0, 0.0, 0.0, 2.0) - 2.0).abs() < 1e-15);
        assert!((interval_time(0.0, 0.5, 0.0, 1.0) - 2.0).abs() < 1e-15);
    }

    #[test]
    fn law_derivatives_match_finite_differences() {
        // Rest → accelerate → cruise → decelerate → rest, all intervals in use.
        let s = vec![0.0, 0.01, 0.3, 0.7, 0.99, 1.0];
        let u = vec![0.0, 2.0, 1.0, -1.0, -2.0, 0.0];
        let mut x = vec![0.0; 6];
        x[1] = 1.5 * 0.01 * 2.0;
        for i in 1..4 {
            let d: f64 = s[i + 1] - s[i];
            let v = (u[i + 1] - u[i]) / d;
            x[i + 1] = x[i] + 2.0 * d * u[i] + d * d * v;
        }
        // The last interval's ray fixes x_4; adjust u_4 to land on it.
        let dl = 0.01;
        let target = -1.5 * dl * u[4];
        assert!((x[4] - target).abs() < 0.05, "{} {target}", x[4]);
        let mut u = u;
        // Solve u_4 so that x_4 (from interval 3) equals −1.5·Δ·u_4.
        let d3: f64 = 0.29;
        // x4 = x3 + 2 d u3 + d (u4 − u3) = x3 + d (u3 + u4) = −1.5 dl u4.
        u[4] = -(x[3] + d3 * u[3]) / (d3 + 1.5 * dl);
        x[4] = -1.5 * dl * u[4];
        let p = JerkProfile::new(s, x, u).unwrap();
        let big_t = p.duration();
        let h = 1e-6;
        for k in 1..400 {
            let t = big_t * k as f64 / 400.0;
            if p.times().iter().any(|&ti| (t - ti).abs() < 1e-4) {
                continue;
            }
            let [_, sd, sdd, sddd] = p.eval(t);
            let num = |k: usize| (p.eval(t + h)[k] - p.eval(t - h)[k]) / (2.0 * h);
            assert!((num(0) - sd).abs() < 1e-7, "t={t}: {} vs {sd}", num(0));
            assert!((num(1) - sdd).abs() < 1e-6, "t={t}");
            assert!((num(2) - sddd).abs() < 1e-4, "t={t}: {} vs {sddd}", num(2));
        }
        // Continuity of s, ṡ, s̈ across gridpoint times.
        for &ti in &p.times()[1..5] {
            let a = p.eval(ti - 1e-9);
            let b = p.eval(ti + 1e-9);
            for k in 0..3 {
                assert!((a[k] - b[k]).abs() < 1e-6, "{ti} {k}: {a:?} {b:?}");
            }
        }
        assert_eq!(p.eval(0.0)[..3], [0.0, 0.0, 0.0]);
        let end = p.eval(big_t);
        assert!(end[0] == 1.0 && end[1] == 0.0 && end[2].abs() < 1e-12);
    }
}
