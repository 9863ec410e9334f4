//! Bounded jerk for TOPP-RA output: a moving-average filter of the timing law, then the
//! smallest uniform time scaling that meets every limit.
//!
//! TOPP-RA's path acceleration s̈ is piecewise constant, so joint acceleration jumps at every
//! gridpoint and at the start and end of a rest-to-rest motion: unbounded jerk. trajkit bounds
//! it without giving up exactness:
//!
//! 1. **Filter.** The timing law s*(t) on `[0, T*]` (at rest before and after) is replaced by
//!    its moving average over a window w:
//!    `s_w(t) = (1/w)∫_{t−w}^{t} s*(τ) dτ` on `[0, T* + w]`. Differentiating under the integral,
//!    `ṡ_w = (s*(t) − s*(t−w))/w`, `s̈_w = (ṡ*(t) − ṡ*(t−w))/w`, `s⃛_w = (s̈*(t) − s̈*(t−w))/w`:
//!    s̈_w is continuous and s⃛_w bounded by max|Δs̈|/w. The filtered law starts at rest with
//!    zero acceleration at s*(0) and ends at rest with zero acceleration exactly at s*(T*): the
//!    path's end points are met exactly. Its velocity at any instant is an average of TOPP-RA's
//!    velocities over the window, so the filtered motion stays close to the time-optimal one
//!    (it is w longer).
//! 2. **Scale.** The composed trajectory σ(s_w(t)) is checked against the velocity,
//!    acceleration and jerk limits and slowed by the smallest factor
//!    k = max(r_v, √r_a, ∛r_j) ≥ 1 ([`crate::topp::min_time_scale`], sampled at
//!    [`JerkOptions::check_rate`]), which scales velocity by 1/k, acceleration by 1/k² and jerk
//!    by 1/k³.
//!
//! The window w is the smallest that brings the jerk of the switches alone,
//! |σ′ᵢ(s)·Δs̈|/w, within [`JerkOptions::budget`] of every joint's jerk limit at every switch
//! (including start and end); the scaling then absorbs the rest (the σ″, σ‴ terms).
//!
//! # Precision contract
//! Exact evaluation (closed form: the profile is evaluated at t and t − w, and ∫ s* over the
//! window is summed piece by piece, never as a difference of large running integrals).
//! Limits hold to 1e-6 relative at every instant sampled at `check_rate` (default 20 kHz) and
//! at the pieces' ends; between samples the excess is second order in the sample spacing.
//! Boundary states: s = s*(0) and s*(T*) at rest with zero acceleration, to rounding.
//! Only rest-to-rest profiles are accepted.

use super::messy::Sequence;
use super::parametrized::{Parametrized, PhaseProfile as Profile};
use super::rescale::{min_time_scale, Retimed, Scaled, TimeLaw};
use crate::error::{Error, Result};
use crate::traj::find_piece;
use crate::{Limits, Order, Path};

/// Settings of [`limit_jerk`].
#[derive(Debug, Clone, PartialEq)]
pub struct JerkOptions {
    /// Fraction of each joint's jerk limit the switches may use when choosing the window
    /// (0 < budget ≤ 1; the rest is left for the path-curvature terms).
    pub budget: f64,
    /// Sample rate (Hz) of the limit check that sets the time-scaling factor.
    pub check_rate: f64,
}

impl Default for JerkOptions {
    fn default() -> Self {
        JerkOptions {
            budget: 0.5,
            check_rate: 20_000.0,
        }
    }
}

/// A rest-to-rest TOPP-RA timing law smoothed by a moving average of width `window`.
#[derive(Debug, Clone, PartialEq)]
pub struct FilteredProfile {
    profile: Profile,
    window: f64,
}

impl FilteredProfile {
    /// Filters `profile` (which must start and end at rest) over `window` seconds (> 0).
    pub fn new(profile: Profile, window: f64) -> Result<Self> {
        crate::error::positive(|| "jerk filter window".into(), window)?;
        let sd = profile.velocities();
        if sd[0] != 0.0 || sd[sd.len() - 1] != 0.0 {
            return Err(Error::InvalidValue {
                field: "profile boundary path velocity".into(),
                value: if sd[0] != 0.0 {
                    sd[0]
                } else {
                    sd[sd.len() - 1]
                },
                reason: "is not zero: jerk filtering needs a rest-to-rest profile",
            });
        }
        Ok(FilteredProfile { profile, window })
    }

    /// The filter window in seconds.
    pub fn window(&self) -> f64 {
        self.window
    }

    /// The unfiltered profile.
    pub fn profile(&self) -> &Profile {
        &self.profile
    }

    /// `[s, ṡ, s̈]` of the unfiltered law at any t (rest outside `[0, T*]`).
    fn raw(&self, t: f64) -> [f64; 3] {
        let p = &self.profile;
        let (s, times) = (p.gridpoints(), p.times());
        let n = s.len() - 1;
        if t <= 0.0 {
            return [s[0], 0.0, 0.0];
        }
        if t >= times[n] {
            return [s[n], 0.0, 0.0];
        }
        let i = find_piece(times, t);
        let tau = t - times[i];
        let u = p.accelerations()[i];
        let v0 = p.velocities()[i];
        [
            (s[i] + v0 * tau + 0.5 * u * tau * tau).clamp(s[i], s[i + 1]),
            (v0 + u * tau).max(0.0),
            u,
        ]
    }

    /// ∫ (s*(τ) − s_ref) dτ over `[a, b]`, piece by piece, relative to `s_ref` to avoid
    /// cancellation.
    fn integral(&self, a: f64, b: f64, s_ref: f64) -> f64 {
        let p = &self.profile;
        let (s, times) = (p.gridpoints(), p.times());
        let n = s.len() - 1;
        let big_t = times[n];
        let mut total = 0.0;
        // Before the start and after the end: constant positions.
        if a < 0.0 {
            total += (s[0] - s_ref) * (b.min(0.0) - a);
        }
        if b > big_t {
            total += (s[n] - s_ref) * (b - a.max(big_t));
        }
        let (lo, hi) = (a.max(0.0), b.min(big_t));
        if lo >= hi {
            return total;
        }
        let mut i = find_piece(times, lo);
        let mut t0 = lo;
        while t0 < hi && i < n {
            let t1 = hi.min(times[i + 1]);
            // s(τ) = s_i + v τ + u τ²/2 with τ = t − t_i: integrate from τ0 to τ1.
            let (v, u) = (p.velocities()[i], p.accelerations()[i]);
            let (x0, x1) = (t0 - times[i], t1 - times[i]);
            let base = s[i] - s_ref;
            total += base * (x1 - x0)
                + 0.5 * v * (x1 * x1 - x0 * x0)
                + u * (x1 * x1 * x1 - x0 * x0 * x0) / 6.0;
            t0 = t1;
            i += 1;
        }
        total
    }
}

impl TimeLaw for FilteredProfile {
    fn duration(&self) -> f64 {
        self.profile.duration() + self.window
    }
    fn eval(&self, t: f64) -> [f64; 4] {
        let t = crate::traj::clamp_time(t, self.duration());
        let w = self.window;
        let now = self.raw(t);
        let before = self.raw(t - w);
        // Relative to the position at t − w: the window integral is then of the size of the
        // motion within the window, and s comes out accurate to rounding of that.
        let s = before[0] + self.integral(t - w, t, before[0]) / w;
        [
            s,
            ((now[0] - before[0]) / w).max(0.0),
            (now[1] - before[1]) / w,
            (now[2] - before[2]) / w,
        ]
    }
}

/// The filter window for `profile` on `path`: the smallest w with
/// `|σ′ⱼ(s)·Δs̈| / w ≤ budget · jerk_limitⱼ` at every switch of s̈ (including the jump from rest
/// at the start and to rest at the end). Joints without a jerk limit do not count; returns
/// `None` when no joint has one.
pub fn filter_window<P: Path + ?Sized>(
    profile: &Profile,
    path: &P,
    limits: &Limits,
    budget: f64,
) -> Result<Option<f64>> {
    limits.expect_dof(path.dim(), "jerk filtering")?;
    if !(budget > 0.0 && budget <= 1.0) {
        return Err(Error::InvalidValue {
            field: "jerk budget".into(),
            value: budget,
            reason: "is not in (0, 1]",
        });
    }
    let n = path.dim();
    if limits.joints().iter().all(|j| j.jerk.is_infinite()) {
        return Ok(None);
    }
    let u = profile.accelerations();
    let s = profile.gridpoints();
    let mut d1 = vec![0.0; n];
    let mut w: f64 = 0.0;
    for i in 0..s.len() {
        let before = if i == 0 { 0.0 } else { u[i - 1] };
        let after = if i == u.len() { 0.0 } else { u[i] };
        let du = (after - before).abs();
        if du == 0.0 {
            continue;
        }
        path.eval(s[i], 1, &mut d1);
        for j in 0..n {
            let jl = limits.joint(j).symmetric_limit(Order::Jerk);
            if jl.is_finite() {
                w = w.max(d1[j].abs() * du / (budget * jl));
            }
        }
    }
    Ok(Some(w.max(1e-9)))
}

/// A TOPP-RA result with bounded jerk: the filtered law, slowed by the smallest factor that
/// meets every limit. See the module documentation.
pub type JerkLimited<P> = Scaled<Retimed<P, FilteredProfile>>;

/// Bounds the jerk of a rest-to-rest TOPP-RA result (`path` timed by `profile`) and returns a
/// trajectory within every velocity, acceleration and jerk limit of `limits`.
///
/// Errors: a profile that does not start and end at rest; dimension mismatch; no joint with a
/// finite jerk limit (nothing to bound: use the TOPP-RA result as it is).
pub fn limit_jerk<P: Path>(
    path: P,
    profile: Profile,
    limits: &Limits,
    options: &JerkOptions,
) -> Result<JerkLimited<P>> {
    let w = filter_window(&profile, &path, limits, options.budget)?.ok_or_else(|| {
        Error::InvalidValue {
            field: "jerk limits".into(),
            value: f64::INFINITY,
            reason: "are absent on every joint: nothing to bound",
        }
    })?;
    let law = FilteredProfile::new(profile, w)?;
    let traj = Retimed::new(path, law)?;
    let sampled = min_time_scale(&traj, limits, options.check_rate)?;
    let k = sampled.max(scale_needed(&traj, limits));
    // Never speed up TOPP-RA's result; a hair of margin for rounding.
    let k = (k * (1.0 + 1e-9)).max(1.0);
    Scaled::new(traj, k)
}

/// The time-scaling factor the filtered trajectory needs, max over t of
/// max(r_v, √r_a, ∛r_j), found piece by piece: the filtered law is smooth between its kinks
/// (the profile's switch times t_i and t_i + w, and the times where s crosses a path
/// breakpoint), so each piece is evaluated just inside both ends (one-sided values at the
/// jumps of the jerk) and at interior points, and the pieces whose value comes within 1e-3 of
/// the largest are refined by golden-section search.
fn scale_needed<P: Path>(traj: &Retimed<P, FilteredProfile>, limits: &Limits) -> f64 {
    use crate::Trajectory;
    let n = traj.dof();
    let law = traj.law();
    let w = law.window();
    let big_t = law.duration();
    let mut buf = vec![0.0; n];
    let mut kval = |t: f64| -> f64 {
        let mut k: f64 = 0.0;
        for (order, root) in [
            (Order::Velocity, 1),
            (Order::Acceleration, 2),
            (Order::Jerk, 3),
        ] {
            traj.eval(t, order, &mut buf);
            for (j, &v) in buf.iter().enumerate() {
                let r = limits.joint(j).ratio(order, v);
                let f = match root {
                    1 => r,
                    2 => r.sqrt(),
                    _ => r.cbrt(),
                };
                if f > k {
                    k = f;
                }
            }
        }
        k
    };
    // Kinks of the filtered law.
    let mut kinks: Vec<f64> = Vec::with_capacity(2 * law.profile().times().len() + 16);
    for &ti in law.profile().times() {
        kinks.push(ti);
        kinks.push(ti + w);
    }
    for sb in traj.path().breakpoints() {
        // s_w is non-decreasing: bisection for the time it reaches sb.
        let (mut lo, mut hi) = (0.0, big_t);
        if law.eval(hi)[0] < sb || law.eval(lo)[0] >= sb {
            continue;
        }
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if law.eval(mid)[0] < sb {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        kinks.push(hi);
    }
    kinks.push(0.0);
    kinks.push(big_t);
    kinks.retain(|t| (0.0..=big_t).contains(t));
    kinks.sort_by(f64::total_cmp);
    kinks.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * big_t.max(1.0));
    let mut best: f64 = 0.0;
    let mut candidates: Vec<(f64, f64, f64)> = Vec::new(); // (value, a, b)
    for pair in kinks.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let eps = 1e-9 * (b - a);
        let mut piece_best: f64 = 0.0;
        let mut interior_best = (0.0f64, a);
        for (i, f) in [0.0, 0.25, 0.5, 0.75, 1.0].iter().enumerate() {
            let t = (a + f * (b - a)).clamp(a + eps, b - eps);
            let v = kval(t);
            piece_best = piece_best.max(v);
            if i > 0 && i < 4 && v > interior_best.0 {
                interior_best = (v, t);
            }
        }
        best = best.max(piece_best);
        candidates.push((interior_best.0, a, b));
    }
    for &(v, a, b) in &candidates {
        if v < best * (1.0 - 1e-3) {
            continue;
        }
        // Golden-section search for the interior maximum.
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let (mut lo, mut hi) = (a, b);
        let mut x1 = hi - g * (hi - lo);
        let mut x2 = lo + g * (hi - lo);
        let (mut f1, mut f2) = (kval(x1), kval(x2));
        for _ in 0..60 {
            if f1 > f2 {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - g * (hi - lo);
                f1 = kval(x1);
            } else {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + g * (hi - lo);
                f2 = kval(x2);
            }
        }
        best = best.max(f1).max(f2);
    }
    best
}

/// [`limit_jerk`] applied to every rest-to-rest piece of a planned sequence
/// ([`crate::topp::messy::plan_waypoints`]).
pub fn limit_jerk_sequence<P: Path + Clone>(
    sequence: &Sequence<Parametrized<P>>,
    limits: &Limits,
    options: &JerkOptions,
) -> Result<Sequence<JerkLimited<P>>> {
    let pieces = sequence
        .pieces()
        .iter()
        .map(|p| limit_jerk(p.path().clone(), p.law().clone(), limits, options))
        .collect::<Result<Vec<_>>>()?;
    Sequence::new(pieces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topp::{LinearPath, Toppra};
    use crate::Trajectory;

    fn line() -> LinearPath {
        LinearPath::new(&[0.0, 0.0, 1.0, 0.5], 2).unwrap()
    }

    #[test]
    fn filtered_law_derivatives_match_finite_differences() {
        // Bang-bang rest to rest on s ∈ [0, 2]: u = 1 then −1.
        let p = Profile::new(&[0.0, 1.0, 2.0], &[0.0, 2f64.sqrt(), 0.0]).unwrap();
        let f = FilteredProfile::new(p, 0.1).unwrap();
        let h = 1e-6;
        for i in 1..60 {
            let t = f.duration() * i as f64 / 60.0;
            let [_, sd, sdd, sddd] = f.eval(t);
            let num = |k: usize| (f.eval(t + h)[k] - f.eval(t - h)[k]) / (2.0 * h);
            assert!((num(0) - sd).abs() < 1e-7, "t={t}");
            assert!((num(1) - sdd).abs() < 1e-6, "t={t}");
            // s⃛ is piecewise constant: compare away from its jumps.
            let near_jump = [
                0.0,
                0.1,
                2f64.sqrt(),
                2f64.sqrt() + 0.1,
                2.0 * 2f64.sqrt(),
                2.0 * 2f64.sqrt() + 0.1,
            ]
            .iter()
            .any(|&j| (t - j).abs() < 1e-4);
            if !near_jump {
                assert!((num(2) - sddd).abs() < 1e-4, "t={t} {} {sddd}", num(2));
            }
        }
        // Rest with zero acceleration at both ends, exactly at the path's ends.
        assert_eq!(f.eval(0.0), [0.0; 4]);
        let end = f.eval(f.duration());
        assert!(
            (end[0] - 2.0).abs() < 1e-15 && end[1] == 0.0 && end[2] == 0.0,
            "{end:?}"
        );
    }

    #[test]
    fn jerk_limited_toppra_meets_every_limit_pointwise_and_by_finite_differences() {
        let limits = Limits::uniform(2, 1.0, 2.0, 20.0).unwrap();
        let raw = Toppra::with_limits(line(), &limits)
            .unwrap()
            .solve()
            .unwrap();
        let profile = raw.law().clone();
        let t_opt = raw.duration();
        let jl = limit_jerk(line(), profile, &limits, &JerkOptions::default()).unwrap();
        let report = crate::check::check_trajectory(&jl, &limits, 1000.0).unwrap();
        assert!(
            report.passes(&crate::check::Tolerance::default()),
            "{}",
            report.to_text()
        );
        // Close to time-optimal: the filter and scaling cost little here.
        assert!(
            jl.duration() > t_opt && jl.duration() < 1.5 * t_opt,
            "{} vs {t_opt}",
            jl.duration()
        );
        // Ends exactly at the path's end, at rest.
        let mut q = [0.0; 2];
        jl.eval(jl.duration(), Order::Position, &mut q);
        assert!(
            (q[0] - 1.0).abs() < 1e-12 && (q[1] - 0.5).abs() < 1e-12,
            "{q:?}"
        );
        jl.eval(0.0, Order::Acceleration, &mut q);
        assert_eq!(q, [0.0, 0.0]);
    }

    #[test]
    fn panda_plan_with_bounded_jerk() {
        use crate::topp::messy::{plan_waypoints, PlanOptions};
        let limits = Limits::preset("panda").unwrap();
        let w = [
            0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, //
            0.21, -0.52, 0.13, -2.10, 0.05, 1.69, 0.92, //
            0.55, -0.31, 0.28, -1.87, 0.18, 1.83, 1.12, //
            0.83, -0.18, 0.22, -1.64, 0.41, 1.62, 1.35, //
            1.02, 0.05, 0.05, -1.49, 0.63, 1.48, 1.21,
        ];
        let raw = plan_waypoints(&w, 7, &limits, &PlanOptions::default()).unwrap();
        let jl = limit_jerk_sequence(&raw, &limits, &JerkOptions::default()).unwrap();
        let report = crate::check::check_trajectory(&jl, &limits, 1000.0).unwrap();
        assert!(
            report.passes(&crate::check::Tolerance::default()),
            "{}",
            report.to_text()
        );
        let ratio = jl.duration() / raw.duration();
        for p in jl.pieces() {
            println!(
                "window {:.5} s, scale {:.5}",
                p.inner().law().window(),
                p.factor()
            );
        }
        println!(
            "raw {:.5} s, jerk-limited {:.5} s, ratio {ratio:.4}",
            raw.duration(),
            jl.duration()
        );
        assert!(ratio > 1.0 && ratio < 1.3, "jerk limiting costs {ratio}");
    }

    #[test]
    fn bad_input() {
        let moving = Profile::new(&[0.0, 1.0], &[1.0, 1.0]).unwrap();
        assert!(FilteredProfile::new(moving, 0.1).is_err());
        let p = Profile::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0]).unwrap();
        assert!(FilteredProfile::new(p.clone(), 0.0).is_err());
        assert!(FilteredProfile::new(p.clone(), f64::NAN).is_err());
        let free = Limits::uniform(2, 1.0, 2.0, f64::INFINITY).unwrap();
        assert!(limit_jerk(line(), p.clone(), &free, &JerkOptions::default()).is_err());
        let l = Limits::uniform(2, 1.0, 2.0, 20.0).unwrap();
        assert!(filter_window(&p, &line(), &l, 0.0).is_err());
        assert!(filter_window(
            &p,
            &line(),
            &Limits::uniform(3, 1.0, 1.0, 1.0).unwrap(),
            0.5
        )
        .is_err());
    }
}
