//! The solved timing law s(t) of the jerk-limited planner.
//!
//! Gridpoints s_0 < … < s_N carry x_i = ṡ² and u_i = s̈. Three kinds of interval:
//! - **first** `[s_0, s_1]`: constant path jerk in time from rest, s = s_0 + jτ³/6, so
//!   ṡ = jτ²/2, s̈ = jτ, s⃛ = j, reached at τ₁ = √(6Δ₀/u₁) with x₁ = 1.5·Δ₀·u₁;
//! - **middle**: the interval's shape ([`super::shape`]): with δ = s − s_i,
//!   u(δ) = u_i + v_i·φ(δ), x(δ) = x_i + 2u_i·δ + 2v_i·ψ(δ) (a cubic), path jerk
//!   s⃛ = v_i·θ′(δ)·ṡ. The time spent is t(δ) = ∫₀^δ dσ/√x(σ);
//! - **last** `[s_{N−1}, s_N]`: the mirror of the first, s = s_N − cτ³ with τ the time left,
//!   x_{N−1} = −1.5·Δ·u_{N−1}.
//!
//! # Precision contract
//! x, u and the path jerk are evaluated in closed form at any s. The time of a middle
//! interval is an 8-point Gauss–Legendre quadrature of 1/√x on m equal panels, m doubled at
//! construction until two panel counts agree to 1e-14 relative (x > 0 on the interval is
//! checked by the planner before a law is built); the cumulative time of every panel is
//! stored. A time is mapped to δ inside its panel by a safeguarded Newton iteration on the
//! same quadrature (step below 1e-15 of the interval, at most 60 iterations), so ṡ = √x(δ(t))
//! is the derivative of s(t) to the quadrature's accuracy. s is clamped into its interval,
//! ṡ² ≥ 0. Evaluation allocates nothing.

use super::shape::Shape;
use crate::error::{Error, Result};
use crate::topp::rescale::TimeLaw;
use crate::traj::{clamp_time, find_piece};

// Gauss–Legendre nodes (positive half) and weights on [−1, 1], 8 points.
use crate::spline::arclen::{GW as GL_W, GX as GL_X};

/// Largest number of quadrature panels of one interval.
const MAX_PANELS: usize = 1024;

/// A middle interval's x(δ) = x0 + 2u·δ + v·(pδ² + qδ³/3).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cubic {
    pub(crate) x0: f64,
    pub(crate) u: f64,
    pub(crate) v: f64,
    pub(crate) shape: Shape,
}

impl Cubic {
    #[inline]
    pub(crate) fn x(&self, d: f64) -> f64 {
        self.x0 + 2.0 * self.u * d + self.v * self.shape.psi2(d)
    }

    /// ∫_a^b dδ/√x(δ) by one 8-point Gauss–Legendre panel (∞ when x ≤ 0 at a node).
    #[inline]
    pub(crate) fn panel(&self, a: f64, b: f64) -> f64 {
        let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
        let mut acc = 0.0;
        for k in 0..4 {
            let (xl, xr) = (self.x(c - h * GL_X[k]), self.x(c + h * GL_X[k]));
            if !(xl > 0.0 && xr > 0.0) {
                return f64::INFINITY;
            }
            acc += GL_W[k] * (1.0 / xl.sqrt() + 1.0 / xr.sqrt());
        }
        acc * h
    }

    /// ∫₀^len dδ/√x on m equal panels.
    pub(crate) fn time(&self, len: f64, m: usize) -> f64 {
        let w = len / m as f64;
        (0..m)
            .map(|k| self.panel(k as f64 * w, (k + 1) as f64 * w))
            .sum()
    }

    /// The interval's time and the panel count that reaches 1e-14 relative (at most
    /// [`MAX_PANELS`]).
    pub(crate) fn adaptive_time(&self, len: f64) -> (f64, usize) {
        let mut m = 1;
        let mut prev = self.time(len, 1);
        while m < MAX_PANELS {
            let next = self.time(len, 2 * m);
            m *= 2;
            if !next.is_finite() || (next - prev).abs() <= 1e-14 * next {
                return (next, m);
            }
            prev = next;
        }
        (prev, m)
    }
}

/// The jerk-limited timing law: gridpoints, ṡ² and s̈ there, the shape and v of each middle
/// interval, and the time at which each gridpoint is reached.
#[derive(Debug, Clone, PartialEq)]
pub struct JerkProfile {
    s: Vec<f64>,
    x: Vec<f64>,
    u: Vec<f64>,
    v: Vec<f64>,
    shape: Vec<Shape>,
    t: Vec<f64>,
    /// Quadrature panels of interval i: `pan_t[pan_off[i]..pan_off[i + 1]]`, the time from
    /// s_i to the end of each (equal) panel.
    pan_off: Vec<usize>,
    pan_t: Vec<f64>,
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
    /// A law from gridpoints (at least 4, increasing), x = ṡ² and u = s̈ at each, and v and the
    /// shape of each interval (the first and last are the rest pieces of the module
    /// documentation: x₁ = 1.5Δ₀u₁, x_{N−1} = −1.5Δ_{N−1}u_{N−1}; their v and shape are unused).
    pub(crate) fn new(
        s: Vec<f64>,
        x: Vec<f64>,
        u: Vec<f64>,
        v: Vec<f64>,
        shape: Vec<Shape>,
    ) -> Result<Self> {
        let n = s.len() - 1;
        if n < 3 || x.len() != n + 1 || u.len() != n + 1 || v.len() != n || shape.len() != n {
            return Err(Error::DimensionMismatch {
                what: "jerk-limited profile gridpoints".into(),
                expected: 4,
                found: s.len(),
            });
        }
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
        let (pan_off, pan_t) = middle_panels(&s, &x, &u, &v, &shape, &mut t)?;
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
            shape,
            t,
            pan_off,
            pan_t,
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

    /// v_i of each interval: s̈ = u_i + v_i·φ(δ) inside it, so v_i is the path jerk in the
    /// interval's reference time (zero for the first and last intervals, which are timed
    /// differently).
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

    fn cubic(&self, i: usize) -> Cubic {
        Cubic {
            x0: self.x[i],
            u: self.u[i],
            v: self.v[i],
            shape: self.shape[i],
        }
    }

    /// x = ṡ² at path position s (unscaled law).
    pub(crate) fn x_at(&self, s: f64) -> f64 {
        let n = self.s.len() - 1;
        let i = find_piece(&self.s, s);
        let d = (s - self.s[i]).clamp(0.0, self.s[i + 1] - self.s[i]);
        if i == 0 {
            // s = jτ³/6, ṡ = jτ²/2.
            let tau = (6.0 * d / self.j0).cbrt();
            let sd = 0.5 * self.j0 * tau * tau;
            return sd * sd;
        }
        if i == n - 1 {
            let tau = ((self.s[n] - s).max(0.0) / self.c_end).cbrt();
            let sd = 3.0 * self.c_end * tau * tau;
            return sd * sd;
        }
        self.cubic(i).x(d).max(0.0)
    }

    /// `[s, ṡ, s̈, s⃛]` at time τ into middle interval i.
    fn middle(&self, i: usize, tau: f64) -> [f64; 4] {
        let cu = self.cubic(i);
        let d = self.s[i + 1] - self.s[i];
        let pans = &self.pan_t[self.pan_off[i]..self.pan_off[i + 1]];
        let m = pans.len();
        let w = d / m as f64;
        let tau = tau.clamp(0.0, pans[m - 1]);
        // The panel that holds τ, then Newton on t(δ) = τ bracketed in it.
        let k = pans.partition_point(|&e| e < tau).min(m - 1);
        let (a, t_a) = (k as f64 * w, if k == 0 { 0.0 } else { pans[k - 1] });
        let b = if k + 1 == m { d } else { (k + 1) as f64 * w };
        let (mut lo, mut hi) = (a, b);
        let frac = if pans[k] > t_a {
            (tau - t_a) / (pans[k] - t_a)
        } else {
            0.0
        };
        let mut delta = a + frac * (b - a);
        for _ in 0..60 {
            let f = t_a + cu.panel(a, delta) - tau;
            if f > 0.0 {
                hi = delta;
            } else {
                lo = delta;
            }
            let xd = cu.x(delta).max(0.0);
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
        let sd = cu.x(delta).max(0.0).sqrt();
        [
            (self.s[i] + delta).clamp(self.s[i], self.s[i + 1]),
            sd,
            cu.u + cu.v * cu.shape.phi(delta),
            cu.v * cu.shape.rate(delta) * sd,
        ]
    }

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

/// The times of the middle intervals (1..n − 1) into `t` from t\[1\] on, and their panels:
/// the cumulative time of each panel and, per interval, where its panels start
/// (`pan_off`, n + 1 entries).
fn middle_panels(
    s: &[f64],
    x: &[f64],
    u: &[f64],
    v: &[f64],
    shape: &[Shape],
    t: &mut [f64],
) -> Result<(Vec<usize>, Vec<f64>)> {
    let n = s.len() - 1;
    let mut pan_off = Vec::with_capacity(n + 1);
    let mut pan_t = Vec::with_capacity(2 * n);
    pan_off.extend([0, 0]);
    for i in 1..n - 1 {
        let d = s[i + 1] - s[i];
        let cu = Cubic {
            x0: x[i],
            u: u[i],
            v: v[i],
            shape: shape[i],
        };
        let (dt, m) = cu.adaptive_time(d);
        if !dt.is_finite() {
            return Err(Error::Infeasible(format!(
                "the path velocity vanishes between s = {} and s = {}",
                s[i],
                s[i + 1]
            )));
        }
        let w = d / m as f64;
        let mut acc = 0.0;
        for k in 0..m {
            acc += cu.panel(k as f64 * w, (k + 1) as f64 * w);
            pan_t.push(acc);
        }
        pan_off.push(pan_t.len());
        t[i + 1] = t[i] + acc;
    }
    pan_off.push(pan_t.len());
    Ok((pan_off, pan_t))
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Simpson quadrature of ∫dδ/√x on a fine grid, for x bounded away from zero.
    fn simpson(cu: &Cubic, d: f64) -> f64 {
        let m = 20000;
        let h = d / m as f64;
        let f = |z: f64| 1.0 / cu.x(z).sqrt();
        let mut acc = f(0.0) + f(d);
        for k in 1..m {
            acc += f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        acc * h / 3.0
    }

    #[test]
    fn interval_time_matches_simpson_and_closed_forms() {
        let mut rng = crate::rng::SplitMix64::new(3);
        let mut done = 0;
        for _ in 0..400 {
            let d = rng.uniform(0.001, 0.5);
            let (x0, x1) = (rng.uniform(0.05, 4.0), rng.uniform(0.05, 4.0));
            let cu = Cubic {
                x0,
                u: rng.uniform(-3.0, 3.0),
                v: rng.uniform(-50.0, 50.0) * [1.0, 1e-6, 0.0][rng.below(3) as usize],
                shape: Shape::new(x0, x1, d),
            };
            let xmin = (0..=1000)
                .map(|k| cu.x(d * k as f64 / 1000.0))
                .fold(f64::INFINITY, f64::min);
            if xmin < 0.02 {
                continue;
            }
            done += 1;
            let (a, _) = cu.adaptive_time(d);
            let b = simpson(&cu, d);
            assert!((a - b).abs() <= 1e-9 * b, "{cu:?} {d}: {a} vs {b}");
        }
        assert!(done > 100);
        // Constant speed, and constant acceleration from rest (x = 2uδ: t = √(2δ/u)).
        let flat = Cubic {
            x0: 1.0,
            u: 0.0,
            v: 0.0,
            shape: Shape::default(),
        };
        assert!((flat.adaptive_time(2.0).0 - 2.0).abs() < 1e-14);
        let acc = Cubic {
            x0: 0.01,
            u: 0.5,
            v: 0.0,
            shape: Shape::default(),
        };
        let (t, m) = acc.adaptive_time(1.0);
        let exact = 2.0 * (1.01f64.sqrt() - 0.1);
        assert!((t - exact).abs() < 1e-14, "{t} {exact} {m}");
    }

    /// A law through rest → accelerate → decelerate → rest with every interval in use.
    fn example() -> JerkProfile {
        let s = vec![0.0, 0.01, 0.3, 0.7, 0.99, 1.0];
        let mut u = vec![0.0, 2.0, 1.0, -1.0, 0.0, 0.0];
        let mut x = vec![0.0; 6];
        x[1] = 1.5 * 0.01 * 2.0;
        let mut v = vec![0.0; 5];
        let mut shape = vec![Shape::default(); 5];
        // Shapes from a made-up reference.
        let xr = [0.0, 0.03, 0.5, 0.6, 0.03, 0.0];
        for i in 1..4 {
            let d = s[i + 1] - s[i];
            shape[i] = Shape::new(xr[i], xr[i + 1], d);
        }
        for i in 1..3 {
            let d = s[i + 1] - s[i];
            v[i] = (u[i + 1] - u[i]) / shape[i].phi(d);
            x[i + 1] = x[i] + 2.0 * d * u[i] + shape[i].psi2(d) * v[i];
        }
        // The last middle interval lands on the final rest ray x₄ = −1.5·Δ₄·u₄.
        let (d, dl) = (s[4] - s[3], s[5] - s[4]);
        let sh = shape[3];
        let den = sh.psi2(d) + 1.5 * dl * sh.phi(d);
        v[3] = -(x[3] + (2.0 * d + 1.5 * dl) * u[3]) / den;
        u[4] = u[3] + sh.phi(d) * v[3];
        x[4] = x[3] + 2.0 * d * u[3] + sh.psi2(d) * v[3];
        assert!(u[4] < 0.0 && (x[4] + 1.5 * dl * u[4]).abs() < 1e-12);
        JerkProfile::new(s, x, u, v, shape).unwrap()
    }

    #[test]
    fn law_derivatives_match_finite_differences() {
        let p = example();
        let big_t = p.duration();
        let h = 1e-6;
        for k in 1..400 {
            let t = big_t * k as f64 / 400.0;
            if p.times().iter().any(|&ti| (t - ti).abs() < 1e-4) {
                continue;
            }
            let [_, sd, sdd, sddd] = p.eval(t);
            let num = |k: usize| (p.eval(t + h)[k] - p.eval(t - h)[k]) / (2.0 * h);
            assert!((num(0) - sd).abs() < 1e-8, "t={t}: {} vs {sd}", num(0));
            assert!((num(1) - sdd).abs() < 1e-7, "t={t}");
            assert!((num(2) - sddd).abs() < 1e-5, "t={t}: {} vs {sddd}", num(2));
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
        // x_at agrees with the evaluated ṡ².
        for k in 1..50 {
            let [s, sd, _, _] = p.eval(big_t * k as f64 / 50.0);
            assert!((p.x_at(s) - sd * sd).abs() < 1e-9, "{s}");
        }
    }
}
