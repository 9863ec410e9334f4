//! Bounded jerk with a *local* slow-down: the filter of [`crate::topp::jerk`], applied to a
//! TOPP-RA law that is slowed only where the filtered motion would break a limit.
//!
//! The filter ([`crate::topp::jerk::limit_jerk`]) smooths the TOPP-RA law by a moving average
//! of width w and then slows the *whole* motion by one factor k. Two things make it long: w
//! is sized for half the jerk limit (the other half is left for the path-curvature terms), and
//! one local excess (a short path segment, a sharp bend) sets k for the whole motion.
//! [`limit_jerk_local`] removes both, keeping the filter's certified limits. For each of a
//! few window multiples f ([`LocalOptions::windows`]), independently:
//!
//! 1. **Window.** w = f·w₁, with w₁ the window that gives the switches of s̈ of the current law
//!    the *whole* jerk limit ([`crate::topp::jerk::filter_window`] with budget 1).
//! 2. **Certify.** The filtered law is sampled (twice per TOPP-RA interval) for the factor
//!    r = max(r_v, √r_a, ∛r_j) it uses; its sampled duration k̂·(T + w) (k̂ the largest r, a
//!    lower bound of the certified factor) is a lower bound of the certified duration, so the
//!    analytic bound runs only when that can beat the best result so far.
//! 3. **Local slow-down.** At every sample where r > 1, and at the certified bound's worst
//!    instant (which samples may miss), the TOPP-RA path velocities at the gridpoints that the
//!    moving average mixes into that instant (raw times in `[t − w, t]`) are divided by r
//!    (velocity, acceleration and jerk shrink about like those of a uniform slow-down by r,
//!    but only there). The lowered law is made consistent again by a backward and a forward
//!    pass that keep every joint's acceleration row of every interval (at both of its
//!    gridpoints, with the interval's constant s̈) within the limits, lowering velocities only.
//! 4. Repeat from 1 on the lowered law, until [`LocalOptions::rounds`] or three rounds without
//!    a shorter certified result for this multiple.
//!
//! The shortest certified result over all multiples and rounds is returned. Each multiple is
//! iterated on its own because the best window depends on how much local slow-down it needs
//! afterwards, which a single-round score cannot see (choosing the window per round by its
//! sampled duration favours large windows: 0.61–0.67× of the filter's overhead on three
//! seeded paths, against 0.33–0.56× now).
//!
//! Every candidate that is returned is a filtered law scaled by the analytic factor of
//! [`crate::topp::jerk::filter_with_window`]: steps 1–2 are heuristics that only choose *which*
//! law is filtered; whatever they choose, the limits are met by that factor. The filter's own
//! result (budget 0.5, raw law) is always among the candidates, so the result is never longer
//! than the filter's.
//!
//! # Precision contract
//! That of [`crate::topp::jerk`]: on piecewise-polynomial paths of degree ≤ 6 the velocity,
//! acceleration and jerk limits hold at every instant of the continuous trajectory (the scale
//! factor bounds each segment between kinks analytically, raised by 1e-12 relative); on other
//! paths they hold at `check_rate` samples and nine points per segment. Position ranges hold
//! because the played path parameter is non-decreasing from the path's start to its end.
//! The result starts and ends at rest with zero acceleration exactly at the path's ends.
//!
//! # Known limitations
//! Heuristic, not optimal: on the seeded random Panda paths of BENCHMARKS.md at 1 % of its
//! jerk the overhead over raw TOPP-RA is 0.33–0.56× the filter's and 1.6–2.6 % above a
//! fine-grid IPOPT reference; the path with 1e-3 rad segments at the Panda's limits is 1.95 %
//! over raw TOPP-RA (the filter: 101 %). The result depends erratically on the window
//! multiples tried (a 4-waypoint path scores 0.61× with the default ones). Each round samples
//! the filtered motion twice per TOPP-RA interval, and some run one analytic bound: tens to
//! hundreds of milliseconds per piece, about 10–80× the plain filter (BENCHMARKS.md).

use super::jerk::{filter_window, filter_with_window, JerkLimited, JerkOptions};
use super::parametrized::PhaseProfile as Profile;
use crate::error::Result;
use crate::{Limits, Order, Path, Trajectory};

/// The sampled factor the local slow-down aims at (a little below 1: the certified factor
/// also covers the motion between samples).
const TARGET: f64 = 1.0;

/// Settings of [`limit_jerk_local`].
#[derive(Debug, Clone, PartialEq)]
pub struct LocalOptions {
    /// Rounds of local slow-down per window multiple (0: the raw law only).
    pub rounds: usize,
    /// Window multiples, each iterated on its own: multiples of the window that gives the
    /// switches of s̈ the whole jerk limit (2: the filter's default budget of one half).
    pub windows: Vec<f64>,
    /// Samples of the filtered motion per TOPP-RA interval used to score windows and locate
    /// excesses (heuristic only: the returned factor is certified independently).
    pub samples_per_interval: usize,
    /// Most samples of the filtered motion per round, summed over the window multiples
    /// (bounds the cost on long paths: their samples get sparser).
    pub samples_per_round: usize,
    /// The filter's settings (its budget gives the baseline window; its check rate is used on
    /// paths that are not piecewise polynomials).
    pub filter: JerkOptions,
}

impl Default for LocalOptions {
    fn default() -> Self {
        LocalOptions {
            rounds: 6,
            windows: vec![1.2, 1.45, 1.7],
            samples_per_interval: 2,
            samples_per_round: 100_000,
            filter: JerkOptions::default(),
        }
    }
}

/// What [`limit_jerk_local`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct LocalReport {
    /// Duration of the plain filter's result (the baseline).
    pub filter_duration: f64,
    /// Duration of the returned result (≤ `filter_duration`).
    pub duration: f64,
    /// Duration of the unfiltered TOPP-RA law given (a lower bound).
    pub raw_duration: f64,
    /// Round (0: raw law) of the returned result within its window multiple; `None` when the
    /// plain filter won.
    pub round: Option<usize>,
    /// Filter window of the returned result (s).
    pub window: f64,
    /// Certified uniform time-scale factor of the returned result.
    pub factor: f64,
    /// Certified candidates evaluated (each one analytic bound), the plain filter included.
    pub certified: usize,
}

/// Per-gridpoint σ′ and σ″ of the path (row-major, `dim` per gridpoint), and the limits.
struct Rows {
    dim: usize,
    d1: Vec<f64>,
    d2: Vec<f64>,
    a_lo: Vec<f64>,
    a_hi: Vec<f64>,
}

impl Rows {
    fn new<P: Path>(path: &P, s: &[f64], limits: &Limits) -> Self {
        let dim = path.dim();
        let mut d1 = vec![0.0; s.len() * dim];
        let mut d2 = vec![0.0; s.len() * dim];
        for (i, &si) in s.iter().enumerate() {
            path.eval(si, 1, &mut d1[i * dim..(i + 1) * dim]);
            path.eval(si, 2, &mut d2[i * dim..(i + 1) * dim]);
        }
        let (mut a_lo, mut a_hi) = (Vec::with_capacity(dim), Vec::with_capacity(dim));
        for j in limits.joints() {
            let (lo, hi) = j.range(Order::Acceleration);
            a_lo.push(lo);
            a_hi.push(hi);
        }
        Rows {
            dim,
            d1,
            d2,
            a_lo,
            a_hi,
        }
    }

    /// The largest x_free ≤ `cap` (≥ 0) such that every joint's acceleration
    /// σ″(s_g)·x_g + σ′(s_g)·(x_{i+1} − x_i)/(2Δ) at gridpoint g ∈ {i, i + 1} of interval i is
    /// within limits, where `x_fixed` is the other end's x and `free_is_start` says which end
    /// is free. Returns `cap` when the rows cannot be met below it (left to the scale factor).
    fn largest(&self, i: usize, delta: f64, x_fixed: f64, cap: f64, free_is_start: bool) -> f64 {
        let mut hi = cap;
        let mut lo = 0.0_f64;
        let h = 1.0 / (2.0 * delta);
        for g in [i, i + 1] {
            for j in 0..self.dim {
                let (a1, a2) = (self.d1[g * self.dim + j], self.d2[g * self.dim + j]);
                // Row value = c·x_free + e.
                let at_free = (g == i) == free_is_start;
                let sign = if free_is_start { -1.0 } else { 1.0 };
                let c = sign * a1 * h + if at_free { a2 } else { 0.0 };
                let e = -sign * a1 * h * x_fixed + if at_free { 0.0 } else { a2 * x_fixed };
                let (l, u) = (self.a_lo[j] - e, self.a_hi[j] - e);
                if c > 0.0 {
                    hi = hi.min(u / c);
                    lo = lo.max(l / c);
                } else if c < 0.0 {
                    hi = hi.min(l / c);
                    lo = lo.max(u / c);
                }
            }
        }
        if hi >= lo && hi >= 0.0 {
            hi
        } else {
            cap
        }
    }

    /// Backward then forward pass over x = ṡ², lowering only.
    fn make_consistent(&self, s: &[f64], x: &mut [f64]) {
        let n = s.len() - 1;
        for i in (0..n).rev() {
            x[i] = self.largest(i, s[i + 1] - s[i], x[i + 1], x[i], true);
        }
        for i in 0..n {
            x[i + 1] = self.largest(i, s[i + 1] - s[i], x[i], x[i + 1], false);
        }
    }
}

/// The moving average of a TOPP-RA law, evaluated for sampling only: s from a running
/// integral of s* (a difference of two large integrals, accurate to about 1e-12 of the path
/// length: enough to locate excesses, never used for the returned trajectory), so that a
/// sample costs two binary searches instead of a sum over the window.
struct FastLaw<'a> {
    profile: &'a Profile,
    window: f64,
    /// ∫₀^{t_i} s*(τ) dτ at the gridpoint times.
    prefix: Vec<f64>,
}

impl<'a> FastLaw<'a> {
    fn new(profile: &'a Profile, window: f64) -> Self {
        let (s, t, v, u) = (
            profile.gridpoints(),
            profile.times(),
            profile.velocities(),
            profile.accelerations(),
        );
        let mut prefix = Vec::with_capacity(s.len());
        prefix.push(0.0);
        for i in 0..s.len() - 1 {
            let h = t[i + 1] - t[i];
            prefix.push(prefix[i] + s[i] * h + v[i] * h * h / 2.0 + u[i] * h * h * h / 6.0);
        }
        FastLaw {
            profile,
            window,
            prefix,
        }
    }

    fn duration(&self) -> f64 {
        self.profile.duration() + self.window
    }

    /// s*, ṡ*, s̈* and ∫₀ᵗ s* at t (rest outside the profile); `hint` is the piece of the
    /// previous, not later, time (the search moves forward from it: O(1) per time on a sweep,
    /// the same piece as a binary search).
    fn raw(&self, t: f64, hint: &mut usize) -> [f64; 4] {
        let p = self.profile;
        let (s, times) = (p.gridpoints(), p.times());
        let n = s.len() - 1;
        if t <= 0.0 {
            return [s[0], 0.0, 0.0, s[0] * t];
        }
        if t >= times[n] {
            return [s[n], 0.0, 0.0, self.prefix[n] + s[n] * (t - times[n])];
        }
        let mut i = *hint;
        while i + 1 < n && times[i + 1] <= t {
            i += 1;
        }
        *hint = i;
        let h = t - times[i];
        let (v, u) = (p.velocities()[i], p.accelerations()[i]);
        [
            s[i] + v * h + 0.5 * u * h * h,
            v + u * h,
            u,
            self.prefix[i] + s[i] * h + v * h * h / 2.0 + u * h * h * h / 6.0,
        ]
    }

    /// [s, ṡ, s̈, s⃛] of the filtered law at t, with the pieces of the previous, not later,
    /// time (`hints`: of t and of t − w).
    fn eval(&self, t: f64, hints: &mut [usize; 2]) -> [f64; 4] {
        let w = self.window;
        let [h0, h1] = hints;
        let (now, before) = (self.raw(t, h0), self.raw(t - w, h1));
        [
            (now[3] - before[3]) / w,
            (now[0] - before[0]) / w,
            (now[1] - before[1]) / w,
            (now[2] - before[2]) / w,
        ]
    }
}

/// Samples of a filtered (unscaled) law: the time and the factor r = max(r_v, √r_a, ∛r_j).
struct Sampler<'a, P: Path> {
    path: &'a P,
    inv: [Vec<(f64, f64)>; 3],
    buf: [Vec<f64>; 3],
}

impl<'a, P: Path> Sampler<'a, P> {
    fn new(path: &'a P, limits: &Limits) -> Self {
        let inv = [Order::Velocity, Order::Acceleration, Order::Jerk].map(|o| {
            limits
                .joints()
                .iter()
                .map(|j| {
                    let (l, h) = j.range(o);
                    let f = |x: f64| if x.is_finite() { 1.0 / x } else { 0.0 };
                    (f(l), f(h))
                })
                .collect()
        });
        let d = path.dim();
        Sampler {
            path,
            inv,
            buf: [vec![0.0; d], vec![0.0; d], vec![0.0; d]],
        }
    }

    /// r = max(r_v, √r_a, ∛r_j) of the law at time t (`hints`: see [`FastLaw::eval`]).
    fn ratio(&mut self, law: &FastLaw<'_>, t: f64, hints: &mut [usize; 2]) -> f64 {
        let [s, v, a, j] = law.eval(t, hints);
        for (k, b) in self.buf.iter_mut().enumerate() {
            self.path.eval(s, k + 1, b);
        }
        let [d1, d2, d3] = &self.buf;
        let mut r = [0.0_f64; 3];
        for q in 0..d1.len() {
            let vals = [
                d1[q] * v,
                d2[q] * v * v + d1[q] * a,
                d3[q] * v * v * v + 3.0 * d2[q] * v * a + d1[q] * j,
            ];
            for o in 0..3 {
                let (lo, hi) = self.inv[o][q];
                r[o] = r[o].max((vals[o] * hi).max(vals[o] * lo));
            }
        }
        r[0].max(r[1].sqrt()).max(r[2].cbrt())
    }

    /// Sampled factors at `m` + 1 evenly spaced times of the filtered law.
    fn profile(&mut self, law: &FastLaw<'_>, m: usize) -> Vec<f64> {
        let big_t = law.duration();
        let mut hints = [0; 2];
        (0..=m)
            .map(|k| self.ratio(law, big_t * k as f64 / m as f64, &mut hints))
            .collect()
    }
}

/// Lowers the caps `c` (per gridpoint, at the raw `times`) to 1/r where a factor r > 1 of the
/// law filtered over `w` at time t mixes that gridpoint in (t − w − dt ≤ time ≤ t + dt).
/// `samples` are sorted by time: a sliding maximum over them, O(gridpoints + samples).
fn lower_caps(times: &[f64], samples: &[(f64, f64)], w: f64, dt: f64, c: &mut [f64]) {
    // Indices of samples in the current range, their factors decreasing.
    let mut window = std::collections::VecDeque::new();
    let mut next = 0;
    for (&ti, ci) in times.iter().zip(c.iter_mut()) {
        while next < samples.len() && samples[next].0 - w - dt <= ti {
            while window
                .back()
                .is_some_and(|&b: &usize| samples[b].1 <= samples[next].1)
            {
                window.pop_back();
            }
            window.push_back(next);
            next += 1;
        }
        while window.front().is_some_and(|&f| samples[f].0 + dt < ti) {
            window.pop_front();
        }
        if let Some(&f) = window.front() {
            if samples[f].1 > TARGET {
                *ci = ci.min(TARGET / samples[f].1);
            }
        }
    }
}

/// Lowers the path velocities of `profile` where the sampled factors `r` (pairs of a time of
/// the law filtered over `w` and the factor there, sorted by time; `dt` their spacing) or the
/// certified one `worst` exceed 1, then restores consistency; `None` when nothing exceeds.
fn lowered(
    profile: &Profile,
    rows: &Rows,
    r: &[(f64, f64)],
    worst: Option<(f64, f64)>,
    w: f64,
    dt: f64,
) -> Option<Vec<f64>> {
    let (s, times) = (profile.gridpoints(), profile.times());
    if r.iter().chain(&worst).all(|&(_, rk)| rk <= TARGET) {
        return None;
    }
    let mut c = vec![1.0_f64; s.len()];
    lower_caps(times, r, w, dt, &mut c);
    if let Some(extra) = worst {
        lower_caps(times, &[extra], w, dt, &mut c);
    }
    let mut x: Vec<f64> = profile
        .velocities()
        .iter()
        .zip(&c)
        .map(|(v, ci)| (v * ci.max(0.05)).powi(2))
        .collect();
    rows.make_consistent(s, &mut x);
    Some(x.iter().map(|x| x.max(0.0).sqrt()).collect())
}

/// The best certified result found by [`limit_jerk_local`] so far, with its report.
struct Best<P: Path> {
    traj: JerkLimited<P>,
    report: LocalReport,
}

/// What one window multiple needs: the path, its rows and sampler, the limits and settings.
struct Context<'a, P: Path> {
    path: &'a P,
    limits: &'a Limits,
    rows: &'a Rows,
    sampler: Sampler<'a, P>,
    /// Samples per scoring.
    m: usize,
    /// Fallback window (the filter's).
    w0: f64,
    rounds: usize,
    rate: f64,
}

impl<P: Path + Clone> Context<'_, P> {
    /// Rounds of local slow-down with the window `f` times the budget-1 window of the current
    /// law, starting from `profile`; certified results shorter than `best` replace it.
    fn iterate(&mut self, profile: &Profile, f: f64, best: &mut Best<P>) -> Result<()> {
        let mut current = profile.clone();
        let mut own_best = f64::INFINITY;
        // Rounds since this window's best last improved.
        let mut stale = 0;
        for round in 0..=self.rounds {
            let w = f * filter_window(&current, self.path, self.limits, 1.0)?.unwrap_or(self.w0);
            let law = FastLaw::new(&current, w);
            let factors = self.sampler.profile(&law, self.m);
            let big_t = law.duration();
            let dt = big_t / self.m as f64;
            let r: Vec<(f64, f64)> = factors
                .iter()
                .enumerate()
                .map(|(k, &rk)| (big_t * k as f64 / self.m as f64, rk))
                .collect();
            let mut worst = None;
            stale += 1;
            // The sampled duration is a lower bound of the certified one: certify only a
            // law that can win.
            let sampled = factors.iter().fold(0.0_f64, |a, &b| a.max(b)) * big_t;
            if sampled < own_best.min(best.traj.duration()) {
                let certified = filter_with_window(
                    self.path.clone(),
                    current.clone(),
                    self.limits,
                    w,
                    self.rate,
                );
                if let Ok((traj, b)) = certified {
                    best.report.certified += 1;
                    if traj.duration() < own_best {
                        own_best = traj.duration();
                        stale = 0;
                    }
                    if traj.duration() < best.traj.duration() {
                        best.report.round = Some(round);
                        best.report.window = w;
                        best.report.factor = b.factor;
                        best.report.duration = traj.duration();
                        best.traj = traj;
                    }
                    // The certified bound's worst instant, which samples may miss.
                    worst = Some((b.at.0, b.factor));
                }
            }
            if round == self.rounds || stale > 2 {
                break;
            }
            let Some(sd) = lowered(&current, self.rows, &r, worst, w, dt) else {
                break;
            };
            match Profile::new(current.gridpoints(), &sd) {
                Ok(p) => current = p,
                Err(_) => break,
            }
        }
        Ok(())
    }
}

/// Bounds the jerk of a rest-to-rest TOPP-RA result (`path` timed by `profile`) like
/// [`crate::topp::jerk::limit_jerk`], with the window chosen and the law slowed locally (see
/// the module documentation); never longer than `limit_jerk`'s result.
///
/// Errors: those of `limit_jerk` (a profile that does not start and end at rest; dimension
/// mismatch; no joint with a finite jerk limit).
pub fn limit_jerk_local<P: Path + Clone>(
    path: P,
    profile: Profile,
    limits: &Limits,
    options: &LocalOptions,
) -> Result<(JerkLimited<P>, LocalReport)> {
    let rate = options.filter.check_rate;
    let w0 = filter_window(&profile, &path, limits, options.filter.budget)?.ok_or_else(|| {
        crate::Error::InvalidValue {
            field: "jerk limits".into(),
            value: f64::INFINITY,
            reason: "are absent on every joint: nothing to bound",
        }
    })?;
    let raw_duration = profile.duration();
    let (traj, bound) = filter_with_window(path.clone(), profile.clone(), limits, w0, rate)?;
    let mut best = Best {
        report: LocalReport {
            filter_duration: traj.duration(),
            duration: traj.duration(),
            raw_duration,
            round: None,
            window: w0,
            factor: bound.factor,
            certified: 1,
        },
        traj,
    };
    let rows = Rows::new(&path, profile.gridpoints(), limits);
    // Samples per scoring: per TOPP-RA interval, within the per-round budget shared by the
    // window multiples.
    let m = (options.samples_per_interval.max(1) * profile.gridpoints().len() + 16)
        .min(options.samples_per_round / options.windows.len().max(1))
        .max(16);
    let mut context = Context {
        path: &path,
        limits,
        rows: &rows,
        sampler: Sampler::new(&path, limits),
        m,
        w0,
        rounds: options.rounds,
        rate,
    };
    for &f in &options.windows {
        context.iterate(&profile, f, &mut best)?;
    }
    Ok((best.traj, best.report))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topp::{LinearPath, Toppra};

    fn bent() -> LinearPath {
        LinearPath::new(&[0.0, 0.0, 1.0, 0.2, 1.5, 1.0], 2).unwrap()
    }

    #[test]
    fn bad_input_is_refused() {
        let free = Limits::uniform(2, 1.0, 2.0, f64::INFINITY).unwrap();
        let p = Profile::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0]).unwrap();
        assert!(limit_jerk_local(bent(), p, &free, &LocalOptions::default()).is_err());
        let moving = Profile::new(&[0.0, 1.0], &[1.0, 1.0]).unwrap();
        let l = Limits::uniform(2, 1.0, 2.0, 20.0).unwrap();
        assert!(limit_jerk_local(bent(), moving, &l, &LocalOptions::default()).is_err());
    }

    #[test]
    fn consistency_pass_only_lowers_and_meets_the_acceleration_rows() {
        let limits = Limits::uniform(2, 1.0, 2.0, 20.0).unwrap();
        let raw = Toppra::with_limits(bent(), &limits)
            .unwrap()
            .solve()
            .unwrap();
        let (s, sd) = (raw.law().gridpoints(), raw.law().velocities());
        let rows = Rows::new(&bent(), s, &limits);
        let before: Vec<f64> = sd.iter().map(|v| v * v).collect();
        let mut x = before.clone();
        let mid = s.len() / 2;
        x[mid] *= 0.04;
        rows.make_consistent(s, &mut x);
        assert!(x.iter().zip(&before).all(|(a, b)| *a <= *b));
        assert!(x[mid] <= 0.04 * before[mid]);
        for i in 0..s.len() - 1 {
            let u = (x[i + 1] - x[i]) / (2.0 * (s[i + 1] - s[i]));
            for g in [i, i + 1] {
                for j in 0..2 {
                    let a = rows.d2[g * 2 + j] * x[g] + rows.d1[g * 2 + j] * u;
                    assert!(a.abs() <= 2.0 * (1.0 + 1e-9), "interval {i}: {a}");
                }
            }
        }
    }

    #[test]
    fn sliding_caps_equal_the_direct_definition() {
        let mut rng = crate::rng::SplitMix64::new(5);
        let mut times = vec![0.0];
        for _ in 0..300 {
            let last = *times.last().unwrap();
            times.push(last + rng.uniform(1e-4, 0.02));
        }
        let (w, m) = (0.07, 500);
        let big_t = times[300] + w;
        let dt = big_t / m as f64;
        let samples: Vec<(f64, f64)> = (0..=m)
            .map(|k| (big_t * k as f64 / m as f64, rng.uniform(0.5, 1.5)))
            .collect();
        let mut c = vec![1.0; times.len()];
        lower_caps(&times, &samples, w, dt, &mut c);
        for (i, &ti) in times.iter().enumerate() {
            let direct = samples
                .iter()
                .filter(|&&(t, r)| r > TARGET && t - w - dt <= ti && ti <= t + dt)
                .fold(1.0_f64, |ci, &(_, r)| ci.min(TARGET / r));
            assert_eq!(c[i], direct, "gridpoint {i}");
        }
    }
}
