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
//! 2. **Scale.** The composed trajectory σ(s_w(t)) is slowed by the smallest factor
//!    k = max(r_v, √r_a, ∛r_j) that meets the velocity, acceleration and jerk limits, which
//!    scales velocity by 1/k, acceleration by 1/k² and jerk by 1/k³. The filtered law is a
//!    cubic polynomial in time between known kinks, so on a piecewise-polynomial path (every
//!    trajkit spline and polyline) [`bound::scale_bound`] bounds each joint's velocity,
//!    acceleration and jerk on every such segment analytically (a quadratic through three
//!    exact values plus a certified remainder): k holds at every instant, not only at
//!    samples, and costs a few evaluations per TOPP-RA gridpoint instead of dense sampling.
//!    Other paths are sampled at [`JerkOptions::check_rate`] as well.
//!
//! The window w is the smallest that brings the jerk of the switches alone,
//! |σ′ᵢ(s)·Δs̈|/w, within [`JerkOptions::budget`] of every joint's jerk limit at every switch
//! (including start and end); the scaling then absorbs the rest (the σ″, σ‴ terms).
//!
//! # Precision contract
//! Exact evaluation (closed form: the profile is evaluated at t and t − w, and ∫ s* over the
//! window is summed piece by piece, never as a difference of large running integrals).
//! On piecewise-polynomial paths of degree ≤ 6 the limits hold at every instant: the factor
//! is an upper bound of the exact one (see [`bound`] for the bound and its margin, about 1e-9
//! of the limits where they bind), raised by 1e-12 relative for rounding. On other paths they
//! hold to 1e-6 relative at every instant sampled at `check_rate` (default 20 kHz), at nine
//! points per segment and at the pieces' ends; between samples the excess is second order in
//! the sample spacing.
//! Boundary states: s = s*(0) and s*(T*) at rest with zero acceleration, to rounding.
//! Only rest-to-rest profiles are accepted.

use super::messy::Sequence;
use super::parametrized::{Parametrized, PhaseProfile as Profile};
use super::rescale::{min_time_scale, Retimed, Scaled, TimeLaw};
use crate::error::{Error, Result};
use crate::traj::find_piece;
use crate::{Limits, Order, Path};

pub mod bound;
mod cells;
mod segments;
pub use bound::{scale_bound, ScaleBound};

/// Settings of [`limit_jerk`].
#[derive(Debug, Clone, PartialEq)]
pub struct JerkOptions {
    /// Fraction of each joint's jerk limit the switches may use when choosing the window
    /// (0 < budget ≤ 1; the rest is left for the path-curvature terms).
    pub budget: f64,
    /// Sample rate (Hz) of the limit check that sets the time-scaling factor on paths that are
    /// not piecewise polynomials (on polynomial ones the factor is bounded analytically).
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
    /// Per interval i of the profile, the terms of its whole integral that do not depend on
    /// the reference position (see [`FilteredProfile::integral`]): its length hᵢ, ṡᵢhᵢ²/2 and
    /// s̈ᵢhᵢ³/6, each rounded exactly as the partial-interval formula rounds it.
    whole: Vec<[f64; 3]>,
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
        let (times, v, u) = (
            profile.times(),
            profile.velocities(),
            profile.accelerations(),
        );
        let whole = (0..u.len())
            .map(|i| {
                // The partial-interval formula's terms with x0 = 0 and x1 = hᵢ.
                let (x0, x1) = (0.0, times[i + 1] - times[i]);
                [
                    x1 - x0,
                    0.5 * v[i] * (x1 * x1 - x0 * x0),
                    u[i] * (x1 * x1 * x1 - x0 * x0 * x0) / 6.0,
                ]
            })
            .collect();
        Ok(FilteredProfile {
            profile,
            window,
            whole,
        })
    }

    /// The filter window in seconds.
    pub fn window(&self) -> f64 {
        self.window
    }

    /// The unfiltered profile.
    pub fn profile(&self) -> &Profile {
        &self.profile
    }

    /// The piece of the unfiltered profile that holds `t` ([`find_piece`] on its times),
    /// searched first forward from piece `hint` (a few pieces: sorted sweeps), else by
    /// bisection; `hint` out of range goes straight to bisection.
    #[inline]
    fn piece_from(&self, t: f64, hint: usize) -> usize {
        let times = self.profile.times();
        let n = times.len() - 1;
        if hint < n && times[hint] <= t {
            for i in hint..(hint + 8).min(n) {
                if i + 1 == n || times[i + 1] > t {
                    return i;
                }
            }
        }
        find_piece(times, t)
    }

    /// `[s, ṡ, s̈]` of the unfiltered law at any t (rest outside `[0, T*]`); `hint` is the
    /// piece to search from, updated to the piece found.
    #[inline(always)]
    fn raw(&self, t: f64, hint: &mut usize) -> [f64; 3] {
        let p = &self.profile;
        let (s, times) = (p.gridpoints(), p.times());
        let n = s.len() - 1;
        if t <= 0.0 {
            return [s[0], 0.0, 0.0];
        }
        if t >= times[n] {
            return [s[n], 0.0, 0.0];
        }
        let i = self.piece_from(t, *hint);
        *hint = i;
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
    /// cancellation; the first piece is searched from `hint`. An interval covered whole takes
    /// its terms from `whole` (the same values: its τ-range is exactly `[0, hᵢ]`), so only the
    /// term of `s_ref` is computed per call.
    #[inline(always)]
    fn integral(&self, a: f64, b: f64, s_ref: f64, hint: usize) -> f64 {
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
        let mut i = self.piece_from(lo, hint);
        let mut t0 = lo;
        while t0 < hi && i < n {
            if t0 == times[i] && times[i + 1] <= hi {
                let [h, quad, cubic] = self.whole[i];
                total += (s[i] - s_ref) * h + quad + cubic;
                t0 = times[i + 1];
                i += 1;
                continue;
            }
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

    /// [`TimeLaw::eval`] with the pieces of t − w and t searched from `hints` (updated).
    #[inline(always)]
    fn eval_from(&self, t: f64, hints: &mut [usize; 2]) -> [f64; 4] {
        let t = crate::traj::clamp_time(t, self.duration());
        let w = self.window;
        let now = self.raw(t, &mut hints[1]);
        let before = self.raw(t - w, &mut hints[0]);
        // Relative to the position at t − w: the window integral is then of the size of the
        // motion within the window, and s comes out accurate to rounding of that.
        let s = before[0] + self.integral(t - w, t, before[0], hints[0]) / w;
        [
            s,
            ((now[0] - before[0]) / w).max(0.0),
            (now[1] - before[1]) / w,
            (now[2] - before[2]) / w,
        ]
    }
}

impl TimeLaw for FilteredProfile {
    fn duration(&self) -> f64 {
        self.profile.duration() + self.window
    }
    fn eval(&self, t: f64) -> [f64; 4] {
        self.eval_from(t, &mut [usize::MAX; 2])
    }
    /// The pieces of t and t − w are searched from the previous time's: O(1) per time on a
    /// sorted sweep (plus the window integral's pieces), bitwise equal to `eval`.
    fn eval_many(&self, times: &[f64], out: &mut [[f64; 4]]) {
        let mut hints = [0; 2];
        for (&t, o) in times.iter().zip(out.iter_mut()) {
            *o = self.eval_from(t, &mut hints);
        }
    }
}

/// The filter window for `profile` on `path`: the smallest w with
/// `|σ′ⱼ(s)·Δs̈| / w ≤ budget · jerk_limitⱼ` at every switch of s̈ (including the jump from rest
/// at the start and to rest at the end). Joints without a jerk limit do not count; returns
/// `None` when no joint has one. σ′ comes from [`Path::eval_many`] (bitwise what `eval` gives
/// on piecewise polynomials and polylines; to rounding on paths whose batch evaluation differs).
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
    let jl: Vec<f64> = (0..n)
        .map(|j| limits.joint(j).symmetric_limit(Order::Jerk))
        .collect();
    // Per joint the largest numerator |σ′ⱼ|·|Δs̈|, divided once at the end: a correctly
    // rounded division by a positive constant is monotone, so the largest quotient is the
    // quotient of the largest numerator, bit for bit (NaN numerators are ignored by `max`
    // either way).
    let mut top = vec![0.0f64; n];
    let u = profile.accelerations();
    let s = profile.gridpoints();
    // The switches, a block at a time: their s and |Δs̈|, then σ′ at all of them with one
    // `eval_many` (each row what `eval` gives on trajkit's splines and polylines).
    const BLOCK: usize = 64;
    let (mut at, mut jump) = ([0.0; BLOCK], [0.0; BLOCK]);
    let mut d1 = vec![0.0; BLOCK * n];
    let mut w: f64 = 0.0;
    let mut i = 0;
    while i < s.len() {
        let mut m = 0;
        while m < BLOCK && i < s.len() {
            let before = if i == 0 { 0.0 } else { u[i - 1] };
            let after = if i == u.len() { 0.0 } else { u[i] };
            let du = (after - before).abs();
            if du != 0.0 {
                (at[m], jump[m]) = (s[i], du);
                m += 1;
            }
            i += 1;
        }
        path.eval_many(&at[..m], 1, &mut d1[..m * n]);
        for (row, &du) in d1.chunks_exact(n).zip(&jump[..m]) {
            for (t, d) in top.iter_mut().zip(row) {
                *t = t.max(d.abs() * du);
            }
        }
    }
    for (&t, &jl) in top.iter().zip(&jl) {
        if jl.is_finite() {
            w = w.max(t / (budget * jl));
        }
    }
    Ok(Some(w.max(1e-9)))
}

/// A TOPP-RA result with bounded jerk: the filtered law, slowed by the smallest factor that
/// meets every limit. See the module documentation.
pub type JerkLimited<P> = Scaled<Retimed<P, FilteredProfile>>;

/// The filtered law of `profile` with window `w` on `path`, scaled by the factor of
/// [`scale_bound`] (certified on piecewise-polynomial paths; on other paths also sampled at
/// `check_rate` Hz), and that bound.
pub fn filter_with_window<P: Path>(
    path: P,
    profile: Profile,
    limits: &Limits,
    w: f64,
    check_rate: f64,
) -> Result<(JerkLimited<P>, ScaleBound)> {
    limits.expect_dof(path.dim(), "jerk filtering")?;
    let law = FilteredProfile::new(profile, w)?;
    let bound = scale_bound(&path, &law, limits);
    if !bound.factor.is_finite() {
        return Err(Error::InvalidValue {
            field: format!(
                "joint {} {} of the filtered trajectory at t = {}",
                bound.at.1 + 1,
                bound.at.2.name(),
                bound.at.0
            ),
            value: bound.factor,
            reason: "is not a finite number",
        });
    }
    let traj = Retimed::new(path, law)?;
    let mut factor = bound.factor;
    if !bound.certified {
        factor = factor.max(min_time_scale(&traj, limits, check_rate)?);
    }
    // A hair of margin for rounding; a trajectory that never moves is left as it is.
    let k = if factor > 0.0 {
        factor * (1.0 + 1e-12)
    } else {
        1.0
    };
    Ok((Scaled::new(traj, k)?, bound))
}

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
    Ok(filter_with_window(path, profile, limits, w, options.check_rate)?.0)
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

    /// Batched rows ([`Trajectory::eval_rows`]: the filtered law swept with cursors, the path
    /// by `eval_many`, pieces and scaling in blocks) are bitwise what `eval` gives, on sorted
    /// sweeps and on shuffled and out-of-range times.
    #[test]
    fn batched_rows_equal_eval_bitwise() {
        use crate::topp::messy::{plan_waypoints, PlanOptions};
        use crate::topp::Scaled;
        let limits = Limits::preset("panda").unwrap();
        let w = [
            0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, //
            0.21, -0.52, 0.13, -2.10, 0.05, 1.69, 0.92, //
            0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, // back: a reversal, two pieces
            0.83, -0.18, 0.22, -1.64, 0.41, 1.62, 1.35, //
            1.02, 0.05, 0.05, -1.49, 0.63, 1.48, 1.21,
        ];
        let raw = plan_waypoints(&w, 7, &limits, &PlanOptions::default()).unwrap();
        let jl = limit_jerk_sequence(&raw, &limits, &JerkOptions::default()).unwrap();
        assert!(jl.pieces().len() >= 2);
        let traj = Scaled::new(jl, 1.0 + 1e-7).unwrap();
        let d = traj.duration();
        let mut times: Vec<f64> = (0..=(d * 1000.0) as usize)
            .map(|i| i as f64 / 1000.0)
            .collect();
        times.push(d);
        let mut rng = crate::rng::SplitMix64::new(7);
        let mut shuffled: Vec<f64> = (0..200).map(|_| rng.uniform(-0.5, d + 0.5)).collect();
        shuffled.extend([0.0, d, -1.0, d + 1.0, d * 0.5]);
        for ts in [&times, &shuffled] {
            let mut cols = [0; 4].map(|_| vec![0.0; ts.len() * 7]);
            {
                let [a, b, c, e] = &mut cols;
                traj.eval_rows(ts, [a, b, c, e]);
            }
            let mut one = [0.0; 7];
            for (i, &t) in ts.iter().enumerate() {
                for (k, order) in Order::ALL.into_iter().enumerate() {
                    traj.eval(t, order, &mut one);
                    let row = &cols[k][i * 7..(i + 1) * 7];
                    assert!(
                        row.iter()
                            .zip(&one)
                            .all(|(a, b)| a.to_bits() == b.to_bits()),
                        "t = {t} {order:?}: {row:?} vs {one:?}"
                    );
                }
            }
        }
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
