//! Synchronization: one duration for all degrees of freedom, then step 2 for each.
//!
//! Step 1 gives a degree of freedom its minimum duration and the durations of all its other
//! valid candidate profiles. A non-zero target velocity can make a range of durations
//! impossible for a degree of freedom (a *blocked interval*: it cannot be slowed down a little,
//! only a lot); its edges are durations of step-1 candidates. The synchronized duration is
//! found by trying, in increasing order, the largest minimum duration (and the minimum
//! duration option) and then every candidate duration above it, rounded up to a multiple of
//! the control period when the duration is discrete; the first duration at which step 2
//! succeeds for every degree of freedom wins. If the candidates run out, durations growing
//! geometrically from the last one are tried, so a valid (if not provably shortest)
//! synchronized trajectory is still found whenever step 2 can produce one.
//!
//! Under time (and phase) synchronization step 1 runs only where this search needs it (see
//! `calculate`): usually for one degree of freedom, in fastest-only mode; the others are
//! planned by step 2 alone, and the result is the duration the full search gives.
//!
//! Precision: every per-DOF profile passes step 1's or step 2's verification (target within
//! 1e-8 / 1e-10, limits within 1e-12 relative, duration within 1e-12 relative of the common
//! one). A duration found by bisection is the edge of the feasible range to 64 halvings (or to
//! adjacent floating-point numbers, or to one control period for discrete durations).
//!
//! Calculation budget (`interrupt_calculation_duration`, Ruckig Pro's name, microseconds):
//! the search checks the deadline before each attempt and returns `OtgError::Interrupted`
//! when it runs out before any duration worked; the bisection stops at the deadline and keeps
//! its shortest success (valid, possibly longer than the edge of the feasible range). The
//! closed-form solves inside an attempt are not interrupted: the budget's granularity is one
//! attempt (step 2 for every synchronized DOF), and step 1 (before the search) and the
//! single-DOF shortcut run to the end.
//!
//! Bounded mode (`calculate` with `Search::Bounded`, crate-private; the waypoint planner's
//! search uses it to rate candidate waypoint velocities): the same search, but it gives up
//! instead of walking durations past the last candidate (an error), and it keeps the first
//! success after a failure instead of bisecting below it. Its duration is therefore at least
//! the full search's (equal whenever the full search needs neither), and its cost is bounded
//! by the number of candidate durations, never by the 200 + 64 attempts of the full search.
//! It returns the duration only (except under phase synchronization, which reads every
//! profile): the profiles left in the output are unspecified. So a trial duration t needs no
//! profile of a DOF whose duration bound is at most t (t is feasible for it, see
//! `sync/bound.rs`), and for a DOF whose step 1 has not run step 2's closed forms
//! (`step2_closed_into`) go first: when one plans, t is feasible and step 1 is not needed;
//! otherwise step 1 and then the whole of step 2 decide, as in the full search. The duration
//! is the one the same search with every profile built gives, up to the rounding of the
//! durations it compares (it returns the trial duration itself, not the longest profile's,
//! which matches it to 1e-12 relative), provided step 2 plans every duration a bound
//! certifies (the lazy step 1 above relies on that too).
//!
//! Phase synchronization (Ruckig's) and trajkit's straight-line mode live in `phase.rs`.

use super::input::{DurationDiscretization, InputView, Synchronization};
use super::phase::{phase, straight_line, PhaseCtx};
use super::position::continuation_within;
use super::problem::Dof1;
use super::profile::{Profile, State1};
use super::result::OtgError;
use super::step1::{step1_fastest_into, step1_into, MAX_CANDIDATES};
use super::step2::{step2, step2_closed_into, step2_into};
use super::trajectory::DofTrajectory;
use super::zero::{at_rest, coasts, has_zero_limit};
use std::time::{Duration, Instant};

mod bound;
use bound::{duration_bound, starts_safe};

/// Per-DOF spare profile of the calculation: step 1's second working buffer, then the slot
/// the time-optimal profile is copied to before step 2 overwrites the output (see
/// `Scratch::step1_in_out`). Kept apart from [`Scratch`] and created on first use, so that a
/// calculation that never needs it neither initialises nor copies 700 bytes per DOF.
pub(crate) type Spare = Option<Profile>;

/// How much of step 1 a degree of freedom has run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Solved {
    /// Not run: synchronization has not needed this DOF's minimum duration (yet).
    #[default]
    No,
    /// The time-optimal profile is known; of the candidate durations only its own.
    Fastest,
    /// The time-optimal profile and every candidate duration are known.
    Full,
}

/// Per-DOF scratch space of the calculation (kept by the caller so that a compile-time number
/// of degrees of freedom needs no allocation).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Scratch {
    pub(crate) dof: Dof1,
    pub(crate) cand: [f64; MAX_CANDIDATES],
    pub(crate) ncand: usize,
    pub(crate) t_min: f64,
    pub(crate) sync: bool,
    /// How much of step 1 has run; `t_min`, `cand`, `step1_in_out`, `step1_kept` and `brake`
    /// are meaningful only once it has.
    pub(crate) solved: Solved,
    /// Whether the output profile of this DOF still holds the step-1 profile (step 1 writes
    /// there).
    pub(crate) step1_in_out: bool,
    /// Whether the DOF's spare profile (see [`Spare`]) holds the step-1 profile. It is copied there only when it starts with a
    /// brake (step 2 re-plans after the brake); without one it is not kept, and on the rare
    /// way back to the minimum duration after step 2 it is calculated again (step 1 is
    /// deterministic: the same profile).
    pub(crate) step1_kept: bool,
    /// Whether the step-1 profile starts with a brake.
    pub(crate) brake: bool,
    /// An upper bound of the minimum duration ([`duration_bound`]), while step 1 has not run.
    pub(crate) bound: f64,
}

impl Default for Scratch {
    fn default() -> Self {
        Scratch {
            dof: Dof1::rest_to_rest(0.0, 0.0, 1.0, 1.0, 1.0),
            cand: [0.0; MAX_CANDIDATES],
            ncand: 0,
            t_min: 0.0,
            sync: false,
            solved: Solved::No,
            step1_in_out: false,
            step1_kept: false,
            brake: false,
            bound: f64::INFINITY,
        }
    }
}

/// Runs step 1 for one DOF into its output profile (`full`: every candidate duration too,
/// otherwise only the fastest is needed); false when it finds no profile.
fn solve(sc: &mut Scratch, spare: &mut Spare, out: &mut Profile, full: bool) -> bool {
    if full {
        let Some(ncand) = step1_into(&sc.dof, out, spare, &mut sc.cand) else {
            return false;
        };
        sc.ncand = ncand;
        sc.solved = Solved::Full;
    } else {
        if step1_fastest_into(&sc.dof, out, spare).is_none() {
            return false;
        }
        sc.cand[0] = out.duration();
        sc.ncand = 1;
        sc.solved = Solved::Fastest;
    }
    sc.step1_in_out = true;
    sc.step1_kept = false;
    sc.brake = out.brake_duration() != 0.0;
    sc.t_min = out.duration();
    true
}

/// Computes all profiles (in [`Search::Bounded`] mode only those the duration needs);
/// returns the trajectory duration.
///
/// Under time (and phase) synchronization step 1 runs only where synchronization needs it:
/// for the degrees of freedom that start with a brake, and for the one whose estimated
/// minimum duration ([`duration_bound`]) is the largest. Every other synchronized degree of
/// freedom whose duration bound ([`duration_bound`], a valid profile's duration) is at most the
/// trial duration t goes straight to step 2 at t: t is feasible for it (at least its minimum,
/// above any blocked interval), so the duration found is the one a full step 1 for every
/// degree of freedom would give. Otherwise (bound above t, or step 2 misses) step 1 runs for
/// it: if its minimum exceeds t it becomes the new trial duration, otherwise its candidate
/// durations join the search (t lies in one of its blocked intervals).
///
/// The generators call [`calculate_status`] (which also reports whether the calculation budget
/// cut the search short); this is the entry point the other online-generation modules use,
/// in either [`Search`] mode.
pub(crate) fn calculate(
    view: &InputView<'_>,
    delta_time: f64,
    out: &mut [DofTrajectory],
    scratch: &mut [Scratch],
    spare: &mut [Spare],
    search: Search,
) -> Result<f64, OtgError> {
    match search {
        Search::Full => calculate_status(view, delta_time, out, scratch, spare).map(|c| c.duration),
        Search::Bounded => {
            calculate_profiles(view, delta_time, out, scratch, spare, search).map(|c| c.duration)
        }
    }
}

/// How [`calculate`] searches for the common duration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Search {
    /// The full search, as the generators run it ([`calculate_status`]).
    Full,
    /// Bounded mode (see the module docs): no bisection and no durations past the last
    /// candidate. The duration is at least the full search's (equal when that search needs
    /// neither); `Err` where the full search would have walked past the candidates. A cheap,
    /// never optimistic rating of an input, for searches that call the generator many times:
    /// only the duration, the profiles left in the output are unspecified (except under
    /// phase synchronization).
    Bounded,
}

/// What a calculation reports besides its profiles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Calculated {
    /// The trajectory's duration.
    pub(crate) duration: f64,
    /// Whether the calculation budget cut the search short: the result is valid but may be
    /// longer than the shortest common duration.
    pub(crate) interrupted: bool,
}

/// [`calculate`] in full mode, also reporting whether the calculation budget cut the search
/// short.
pub(crate) fn calculate_status(
    view: &InputView<'_>,
    delta_time: f64,
    out: &mut [DofTrajectory],
    scratch: &mut [Scratch],
    spare: &mut [Spare],
) -> Result<Calculated, OtgError> {
    let n = view.dof();
    let c = calculate_profiles(view, delta_time, out, scratch, spare, Search::Full)
        .map_err(|e| limits_error(e, &scratch[..n.min(scratch.len())], view))?;
    let d = c.duration;
    for i in 0..n {
        if !view.enabled[i] {
            continue;
        }
        if !continuation_within(&scratch[i].dof, &out[i].profile, d) {
            return Err(OtgError::PositionLimits { dof: i });
        }
        let (m, p) = if scratch[i].solved == Solved::No {
            (f64::NAN, Some(scratch[i].dof))
        } else {
            (scratch[i].t_min, None)
        };
        out[i].min_duration = m;
        out[i].problem = p;
    }
    Ok(c)
}

/// The single-DOF shortcut of [`calculate_status`] for a caller whose input has exactly one
/// degree of freedom, without its per-DOF scratch and spare storage: the same validation,
/// then that DOF's time-optimal profile into `out` (as [`calculate_status`] writes it:
/// minimum duration known, no problem kept). `None` when the shortcut does not apply (a
/// disabled DOF, a minimum duration, discrete durations) or step 1 finds no profile: the
/// caller then runs [`calculate_status`], which plans the input or names the failure.
///
/// It exists for speed: on a one-DOF rest-to-rest motion the general entry's fixed cost (a
/// zero-filled [`Scratch`], the synchronization plumbing) is about a third of the calculation.
#[inline]
pub(crate) fn calculate_single(
    view: &InputView<'_>,
    delta_time: f64,
    out: &mut DofTrajectory,
) -> Option<Result<f64, OtgError>> {
    // The order of `calculate_profiles`: shape, the DOF's problem, then the shortcut's
    // conditions, so that an invalid input gets the same error.
    if let Err(e) = view.check_shape(delta_time) {
        return Some(Err(e));
    }
    if view.dof() != 1 {
        return None;
    }
    let dof = match view.dof_problem(0) {
        Ok(d) => d,
        Err(e) => return Some(Err(e)),
    };
    let opts = view.options;
    if !view.enabled[0]
        || opts.minimum_duration.is_some()
        || opts.duration_discretization != DurationDiscretization::Continuous
    {
        return None;
    }
    let mut spare: Spare = None;
    step1_fastest_into(&dof, &mut out.profile, &mut spare)?;
    // The common duration is this DOF's own: no continuation to check.
    let t = out.profile.duration();
    out.min_duration = t;
    out.problem = None;
    Some(Ok(t))
}

/// A failure caused by a degree of freedom with a zero limit is reported as such (Ruckig's
/// `ErrorZeroLimits`): step 1 of that DOF, or synchronization when any synchronized DOF has
/// one. A step-1 failure of a DOF with position limits, or a synchronization failure of
/// one (no motion of the common duration stays inside its limits), is `PositionLimits`
/// (Ruckig's `ErrorPositionalLimits`).
#[cold]
fn limits_error(e: OtgError, scratch: &[Scratch], view: &InputView<'_>) -> OtgError {
    let zero = |i: usize| view.enabled[i] && has_zero_limit(&scratch[i].dof);
    match e {
        OtgError::CalculationFailed { dof } if zero(dof) => OtgError::ZeroLimits { dof },
        OtgError::CalculationFailed { dof } if scratch[dof].dof.has_position_limits() => {
            OtgError::PositionLimits { dof }
        }
        OtgError::SynchronizationFailed { dof, .. } => {
            match (0..scratch.len()).find(|&i| zero(i)) {
                Some(dof) => OtgError::ZeroLimits { dof },
                None => match dof {
                    Some(i) if scratch[i].dof.has_position_limits() => {
                        OtgError::PositionLimits { dof: i }
                    }
                    _ => e,
                },
            }
        }
        e => e,
    }
}

/// [`calculate`] without the error translation: validation, the single-DOF shortcut, step 1
/// where it is needed ([`Planner::prepare`]), the straight-line mode, the DOFs that are not
/// synchronized, and the search for the common duration ([`Planner::synchronize`]) in mode
/// `search`.
fn calculate_profiles(
    view: &InputView<'_>,
    delta_time: f64,
    out: &mut [DofTrajectory],
    scratch: &mut [Scratch],
    spare: &mut [Spare],
    search: Search,
) -> Result<Calculated, OtgError> {
    let done = |duration: f64| Calculated {
        duration,
        interrupted: false,
    };
    view.check_shape(delta_time)?;
    let n = view.dof();
    if out.len() < n || scratch.len() < n || spare.len() < n {
        return Err(OtgError::InvalidInput {
            dof: None,
            field: "current_position",
            value: n as f64,
            reason: "is the length of this vector, larger than the output storage",
        });
    }
    for i in 0..n {
        scratch[i].dof = view.dof_problem(i)?;
    }
    let opts = view.options;
    // One DOF, nothing to synchronize with: its time-optimal profile (as in Ruckig).
    if n == 1
        && view.enabled[0]
        && opts.minimum_duration.is_none()
        && opts.duration_discretization == DurationDiscretization::Continuous
    {
        let sc = &mut scratch[0];
        sc.sync = false;
        if !solve(sc, &mut spare[0], &mut out[0].profile, false) {
            return Err(OtgError::CalculationFailed { dof: 0 });
        }
        return Ok(done(sc.t_min));
    }
    let mut p = Planner {
        view,
        delta_time,
        out,
        scratch,
        spare,
        n,
        discrete: opts.duration_discretization == DurationDiscretization::Discrete,
        min_dur: opts.minimum_duration.unwrap_or(0.0),
        budget: opts.interrupt_calculation_duration.map(Budget::start),
        interrupted: false,
        bounded: search == Search::Bounded,
        // (Phase synchronization reads every profile.)
        unbuilt: search == Search::Bounded && !view.any_sync(Synchronization::Phase),
    };
    let (t_lead, lazy) = p.prepare()?;
    if opts.synchronization == Synchronization::StraightLine
        && straight_line(view, delta_time, p.out, p.scratch)?
    {
        return Ok(done(duration_of(&p.out[..n])));
    }
    p.finish_unsynchronized()?;
    if p.scratch[..n].iter().any(|s| s.sync) {
        let duration = p.synchronize(t_lead, lazy)?;
        return Ok(Calculated {
            duration,
            interrupted: p.interrupted,
        });
    }
    Ok(done(duration_of(&p.out[..n])))
}

/// The state of one synchronized calculation.
struct Planner<'a, 'v> {
    view: &'a InputView<'v>,
    delta_time: f64,
    out: &'a mut [DofTrajectory],
    scratch: &'a mut [Scratch],
    spare: &'a mut [Spare],
    n: usize,
    discrete: bool,
    min_dur: f64,
    /// The calculation budget (`interrupt_calculation_duration`), when one is given.
    budget: Option<Budget>,
    /// Whether the budget stopped the bisection before the edge of the feasible range.
    interrupted: bool,
    /// Bounded mode (module docs): no bisection, no durations past the last candidate.
    bounded: bool,
    /// Bounded mode without phase synchronization: only the duration is wanted, profiles
    /// that do not decide it are not built ([`try_each`]'s `rate`).
    unbuilt: bool,
}

/// A calculation budget: its deadline and its size in microseconds.
#[derive(Clone, Copy)]
struct Budget {
    deadline: Instant,
    us: f64,
}

impl Budget {
    /// A budget of `us` microseconds from now (`us` was validated: positive and finite).
    #[cold]
    fn start(us: f64) -> Budget {
        let now = Instant::now();
        let deadline = now
            .checked_add(Duration::from_secs_f64((us * 1e-6).min(1e9)))
            .unwrap_or(now);
        Budget { deadline, us }
    }

    /// Whether the budget has run out.
    #[inline]
    fn spent(&self) -> bool {
        Instant::now() >= self.deadline
    }
}

impl Planner<'_, '_> {
    /// The budget's error when it has run out (no valid result is known yet).
    #[inline]
    fn check_budget(&self) -> Result<(), OtgError> {
        match self.budget {
            Some(b) if b.spent() => Err(OtgError::Interrupted { budget_us: b.us }),
            _ => Ok(()),
        }
    }

    /// `t` rounded up to a multiple of the control period when durations are discrete.
    #[inline]
    fn disc(&self, t: f64) -> f64 {
        if self.discrete {
            (t / self.delta_time - 1e-9).ceil().max(0.0) * self.delta_time
        } else {
            t
        }
    }

    /// Step 1 for every enabled DOF that is not synchronized or starts with a brake; the
    /// other synchronized DOFs wait until synchronization needs them. Returns the largest
    /// minimum duration found and how many DOFs wait.
    #[inline]
    fn prepare(&mut self) -> Result<(f64, usize), OtgError> {
        let mut t_lead = 0.0f64;
        let mut lazy = 0usize;
        for i in 0..self.n {
            let d = self.scratch[i].dof;
            if !self.view.enabled[i] {
                self.out[i] = DofTrajectory {
                    profile: Profile::new(State1 {
                        p: d.p0,
                        v: d.v0,
                        a: d.a0,
                    }),
                    min_duration: 0.0,
                    problem: None,
                };
                self.scratch[i].sync = false;
                self.scratch[i].solved = Solved::Full;
                continue;
            }
            let sc = &mut self.scratch[i];
            let mode = self.view.sync_of(i);
            sc.sync = match mode {
                Synchronization::Time | Synchronization::Phase | Synchronization::StraightLine => {
                    true
                }
                Synchronization::TimeIfNecessary => d.vf != 0.0 || d.af != 0.0,
                Synchronization::None => false,
            };
            // Phase synchronization needs every minimum duration (the limiting DOF).
            // (A DOF with position limits always runs step 1: the duration bound does not
            // know them.)
            if sc.sync
                && mode != Synchronization::Phase
                && starts_safe(&d)
                && !has_zero_limit(&d)
                && !d.has_position_limits()
            {
                sc.solved = Solved::No;
                sc.ncand = 0;
                sc.step1_in_out = false;
                sc.step1_kept = false;
                sc.brake = false;
                lazy += 1;
                continue;
            }
            // (No bound: its step 1 has run; bounded mode skips only DOFs with a bound.)
            sc.bound = f64::INFINITY;
            if !solve(sc, &mut self.spare[i], &mut self.out[i].profile, false) {
                return Err(OtgError::CalculationFailed { dof: i });
            }
            t_lead = t_lead.max(sc.t_min);
        }
        Ok((t_lead, lazy))
    }

    /// Degrees of freedom that are not synchronized still honour the minimum duration and
    /// the discretization on their own.
    #[inline]
    fn finish_unsynchronized(&mut self) -> Result<(), OtgError> {
        for i in 0..self.n {
            if self.view.enabled[i] && !self.scratch[i].sync {
                let t = self.disc(self.scratch[i].t_min.max(self.min_dur));
                if t > self.scratch[i].t_min
                    && !replan_into(
                        &mut self.scratch[i],
                        &mut self.spare[i],
                        t,
                        &mut self.out[i].profile,
                    )
                {
                    return Err(OtgError::SynchronizationFailed {
                        dof: Some(i),
                        duration: t,
                    });
                }
            }
        }
        Ok(())
    }

    /// The common duration of the synchronized DOFs and their profiles at it.
    #[inline]
    fn synchronize(&mut self, t_lead: f64, lazy: usize) -> Result<f64, OtgError> {
        let t_lead = if lazy > 0 {
            self.lead_step1(t_lead, lazy == 1)?
        } else {
            t_lead
        };
        let t = self.disc(t_lead.max(self.min_dur));
        // A synchronized DOF that coasts (zero limits) and moves reaches its target at one
        // duration only: that is the duration, or there is none.
        if let Some(i) = (0..self.n).find(|&i| {
            let sc = &self.scratch[i];
            sc.sync && coasts(&sc.dof) && !at_rest(&sc.dof)
        }) {
            return self.coasting(i, t);
        }
        self.search(t)
    }

    /// The waiting DOF most likely to set the duration (the largest bound) runs step 1 now,
    /// unless a solved DOF already needs at least as long (`t_lead`). Returns the largest
    /// minimum duration known then.
    #[inline]
    fn lead_step1(&mut self, t_lead: f64, only_one: bool) -> Result<f64, OtgError> {
        let mut lead = usize::MAX;
        let mut b_max = f64::NEG_INFINITY;
        for i in 0..self.n {
            let sc = &mut self.scratch[i];
            if sc.sync && sc.solved == Solved::No {
                sc.bound = if only_one {
                    f64::INFINITY
                } else {
                    duration_bound(&sc.dof)
                };
                if lead == usize::MAX || sc.bound > b_max {
                    (lead, b_max) = (i, sc.bound);
                }
            }
        }
        if b_max <= t_lead {
            return Ok(t_lead);
        }
        if !solve(
            &mut self.scratch[lead],
            &mut self.spare[lead],
            &mut self.out[lead].profile,
            false,
        ) {
            return Err(OtgError::CalculationFailed { dof: lead });
        }
        Ok(t_lead.max(self.scratch[lead].t_min))
    }

    /// Synchronization to the one duration of coasting DOF `i` (at least `t` is needed).
    #[cold]
    fn coasting(&mut self, i: usize, t: f64) -> Result<f64, OtgError> {
        let tc = self.scratch[i].t_min;
        if t > tc * (1.0 + 1e-12) || self.disc(tc) != tc {
            return Err(OtgError::ZeroLimits { dof: i });
        }
        match try_each(self.scratch, self.spare, self.out, tc, 0..self.n, false) {
            Ok(()) => finish(self.view, self.delta_time, self.out, self.scratch, tc),
            Err(Miss::At(k) | Miss::Below(k) | Miss::Unsolvable(k)) => Err(OtgError::ZeroLimits {
                dof: if has_zero_limit(&self.scratch[k].dof) {
                    k
                } else {
                    i
                },
            }),
        }
    }

    /// Tries durations from `t` on: the candidate durations in increasing order, then
    /// geometrically growing ones, until step 2 succeeds for every synchronized DOF; after a
    /// failure the feasible range's edge is bisected ([`Planner::bisect`]).
    #[inline]
    fn search(&mut self, mut t: f64) -> Result<f64, OtgError> {
        let mut failed = 0;
        let mut grow = 0;
        let mut last_fail: Option<f64> = None;
        for _attempt in 0..200 {
            if !(t.is_finite() && t < 1e300) {
                break;
            }
            self.check_budget()?;
            match try_each(
                self.scratch,
                self.spare,
                self.out,
                t,
                0..self.n,
                self.unbuilt,
            ) {
                Ok(()) if self.unbuilt => return Ok(self.rated(t)),
                Ok(()) => {
                    if let Some(lo) = last_fail.filter(|_| !self.bounded) {
                        t = self.bisect(lo, t, failed)?;
                    }
                    return finish(self.view, self.delta_time, self.out, self.scratch, t);
                }
                Err(Miss::Unsolvable(i)) => return Err(OtgError::CalculationFailed { dof: i }),
                Err(Miss::Below(i)) => {
                    // A DOF solved just now needs longer than t: no duration up to its
                    // minimum is feasible.
                    failed = i;
                    last_fail = None;
                    t = self.disc(self.scratch[i].t_min.max(self.min_dur));
                    continue;
                }
                Err(Miss::At(i)) => {
                    failed = i;
                    last_fail = Some(t);
                    // t lies in a blocked interval of DOF i: its candidates bound it.
                    if self.scratch[i].solved != Solved::Full
                        && !solve(
                            &mut self.scratch[i],
                            &mut self.spare[i],
                            &mut self.out[i].profile,
                            true,
                        )
                    {
                        return Err(OtgError::CalculationFailed { dof: i });
                    }
                }
            }
            t = self.next_duration(t, &mut grow);
            if grow > 0 && self.bounded {
                break;
            }
        }
        Err(OtgError::SynchronizationFailed {
            dof: Some(failed),
            duration: t,
        })
    }

    /// A missing candidate could hide a shorter feasible duration between the last failure
    /// `lo` and the success `hi`: bisects for the edge of the feasible range and leaves the
    /// profiles of the shortest success in `out`. Each attempt tries DOF `failed` (the one
    /// that failed at `lo`) first ([`try_all_from`]): only whether an attempt succeeds steers
    /// the bisection, and inside a blocked interval of that DOF a failed attempt then costs
    /// one step 2.
    #[cold]
    fn bisect(&mut self, mut lo: f64, mut hi: f64, failed: usize) -> Result<f64, OtgError> {
        let mut last_ok = true;
        for _ in 0..64 {
            // Out of budget: the shortest success so far is the result.
            if self.budget.is_some_and(|b| b.spent()) {
                self.interrupted = true;
                break;
            }
            let mid = self.disc(0.5 * (lo + hi));
            if mid <= lo || mid >= hi {
                break;
            }
            last_ok = try_all_from(self.scratch, self.spare, self.out, self.n, mid, failed).is_ok();
            if last_ok {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        // A failed attempt leaves `out` partly written: redo the last success.
        if !last_ok && try_each(self.scratch, self.spare, self.out, hi, 0..self.n, false).is_err() {
            return Err(OtgError::SynchronizationFailed {
                dof: Some(failed),
                duration: hi,
            });
        }
        Ok(hi)
    }

    /// Bounded mode's duration once `t` works for every synchronized DOF (whose profiles
    /// [`try_each`] may have left unbuilt, see [`Planner::unbuilt`]): `t`, or longer where a
    /// DOF that is not synchronized needs longer.
    #[inline]
    fn rated(&self, t: f64) -> f64 {
        let n = self.n;
        let mut d = t;
        for i in (0..n).filter(|&i| self.view.enabled[i] && !self.scratch[i].sync) {
            d = d.max(self.out[i].profile.duration());
        }
        d
    }

    /// The next candidate duration above `t`, or (when none is left) a geometrically growing
    /// step above it.
    #[inline]
    fn next_duration(&self, t: f64, grow: &mut i32) -> f64 {
        let mut next = f64::INFINITY;
        for s in self.scratch[..self.n].iter().filter(|s| s.sync) {
            for &c in &s.cand[..s.ncand] {
                let c = self.disc(c);
                if c > t && c < next {
                    next = c;
                }
            }
        }
        if next.is_infinite() {
            *grow += 1;
            next = self.disc(t * (1.0 + 1e-6 * 4f64.powi((*grow).min(20))));
            if next <= t {
                next = t + if self.discrete {
                    self.delta_time
                } else {
                    t.max(1e-9) * 1e-6
                };
            }
        }
        next
    }
}

/// The synchronized profiles at duration `t` are in `out`: Ruckig's phase synchronization
/// replaces them by scaled copies of the limiting DOF's profile where it applies
/// (`phase.rs`); returns the trajectory's duration.
#[inline]
fn finish(
    view: &InputView<'_>,
    delta_time: f64,
    out: &mut [DofTrajectory],
    scratch: &[Scratch],
    t: f64,
) -> Result<f64, OtgError> {
    let n = view.dof();
    let phase_any = match view.sync {
        None => view.options.synchronization == Synchronization::Phase,
        Some(_) => view.any_sync(Synchronization::Phase),
    };
    if phase_any {
        let ctx = PhaseCtx {
            view,
            delta_time,
            scratch,
        };
        if let Some(d) = phase(&ctx, out, t) {
            return Ok(d.max(duration_of(&out[..n])));
        }
    }
    Ok(duration_of(&out[..n]))
}

fn duration_of(out: &[DofTrajectory]) -> f64 {
    out.iter().fold(0.0f64, |m, d| m.max(d.profile.duration()))
}

/// Re-plans one DOF for total duration `t` (brake kept) into `out`, its output profile; the
/// step-1 profile when `t` is its minimum. False (and `out` unspecified) when no profile was
/// found.
pub(crate) fn replan_into(s: &mut Scratch, spare: &mut Spare, t: f64, out: &mut Profile) -> bool {
    // At (numerically) the minimum duration the step-1 profile is the answer; the residual of
    // step 2 is at round-off level there.
    if (t - s.t_min).abs() <= 1e-13 * t.max(1.0) {
        if !s.step1_in_out {
            match (s.step1_kept, spare.as_ref()) {
                (true, Some(p)) => *out = *p,
                _ => {
                    let mut cand = [0.0; MAX_CANDIDATES];
                    if step1_into(&s.dof, out, spare, &mut cand).is_none() {
                        return false;
                    }
                    s.step1_kept = false;
                }
            }
            s.step1_in_out = true;
        }
        return true;
    }
    if s.step1_in_out {
        if s.brake {
            match spare {
                Some(p) => *p = *out,
                None => *spare = Some(*out),
            }
            s.step1_kept = true;
        }
        s.step1_in_out = false;
    }
    if !s.brake {
        return step2_into(&s.dof, t, out);
    }
    let Some(step1) = spare.as_ref().filter(|_| s.step1_kept) else {
        return false;
    };
    *out = step1.brake_part();
    let e = out.end();
    let mut d = s.dof;
    d.p0 = e.p;
    d.v0 = e.v;
    d.a0 = e.a;
    match step2(&d, t - out.duration()) {
        Some(main) => out.append(&main),
        None => false,
    }
}

/// Why a synchronized duration failed.
#[derive(Debug, Clone, Copy)]
enum Miss {
    /// No profile of DOF i at this duration (it lies in a blocked interval, or step 2 missed).
    At(usize),
    /// DOF i, solved during the attempt, needs longer than this duration.
    Below(usize),
    /// Step 1 of DOF i found no profile.
    Unsolvable(usize),
}

/// [`try_each`] with DOF `first` tried before the others: whether it succeeds is the same
/// (every synchronized DOF must succeed; which DOF a failure names may differ). The
/// bisection uses it with the DOF that failed at its lower end, which usually fails again,
/// so a failed attempt costs one step 2 instead of one per DOF before it.
fn try_all_from(
    scratch: &mut [Scratch],
    spare: &mut [Spare],
    out: &mut [DofTrajectory],
    n: usize,
    t: f64,
    first: usize,
) -> Result<(), Miss> {
    let order = std::iter::once(first)
        .filter(|&f| f < n)
        .chain((0..n).filter(|&i| i != first));
    try_each(scratch, spare, out, t, order, false)
}

/// Step 2 for every synchronized DOF at duration `t`, written into `out`; why it failed
/// otherwise (then the synchronized entries of `out` are partly overwritten). A DOF whose
/// step 1 has not run goes straight to step 2; only if that fails does step 1 run for it.
/// The DOFs are tried in the order `order` gives (each synchronized DOF once; the search's
/// candidates depend on which DOF it reports, so its ordinary order is `0..n`). With `rate`
/// (bounded mode's ratings) only whether `t` works matters: a DOF whose bound certifies `t`
/// is not planned, and one whose step 1 has not run tries step 2's closed forms before
/// step 1; the entries of `out` are then unspecified.
#[inline]
fn try_each(
    scratch: &mut [Scratch],
    spare: &mut [Spare],
    out: &mut [DofTrajectory],
    t: f64,
    order: impl Iterator<Item = usize>,
    rate: bool,
) -> Result<(), Miss> {
    for i in order {
        let sc = &mut scratch[i];
        if !sc.sync {
            continue;
        }
        // t is feasible for it (see `duration_bound`; only DOFs whose step 1 has not run in
        // `prepare` have a bound): rating needs no profile.
        let certified = sc.bound <= t;
        if rate && certified {
            continue;
        }
        if sc.solved == Solved::No {
            // Certified, step 2 plans it. (No brake, see `calculate`: step 2 from the start
            // state.)
            if certified && step2_into(&sc.dof, t, &mut out[i].profile) {
                continue;
            }
            // Rating, step 2's closed forms are tried first: when they plan, t is feasible
            // (so at least the DOF's minimum) and step 1 is not needed; when they do not,
            // step 1 says whether t is below its minimum, before the costlier families run.
            if rate && step2_closed_into(&sc.dof, t, &mut out[i].profile) {
                continue;
            }
            // Certified, every duration from the bound on is feasible for it (the bound's
            // profile can wait at rest after its stop), so step 2 failing is a miss of step 2
            // (or t is numerically its minimum): handled like a failure of a solved DOF, with
            // its candidates.
            if !solve(sc, &mut spare[i], &mut out[i].profile, certified) {
                return Err(Miss::Unsolvable(i));
            }
            let at_min = (t - sc.t_min).abs() <= 1e-13 * t.max(1.0);
            if t < sc.t_min && !at_min {
                return Err(Miss::Below(i));
            }
            if certified && !at_min {
                // Step 2 has already failed at t.
                return Err(Miss::At(i));
            }
        } else if t < sc.t_min && (t - sc.t_min).abs() > 1e-13 * t.max(1.0) {
            return Err(Miss::At(i));
        }
        if !replan_into(sc, &mut spare[i], t, &mut out[i].profile) {
            return Err(Miss::At(i));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
