//! Step 1: the time-optimal profile of one degree of freedom.
//!
//! Third order, position interface. After the brake pre-profile, the solver enumerates the
//! profile families of the time-optimal jerk-limited motion, in both directions (the negative
//! direction by mirroring the problem):
//!
//! | family      | acceleration path                          | free parameter |
//! |-------------|--------------------------------------------|----------------|
//! | none        | a₀ ↗ α₁ ↘ α₂ ↗ a_f                          | α₁             |
//! | acc0        | a₀ ↗ a_max (hold τ₁) ↘ α₂ ↗ a_f              | τ₁             |
//! | acc1        | a₀ ↗ α₁ ↘ a_min (hold τ₂) ↗ a_f              | α₁             |
//! | acc0_acc1   | a₀ ↗ a_max (τ₁) ↘ a_min (τ₂) ↗ a_f           | τ₁             |
//! | vel         | a₀ ↗ α₁ (plateau) ↘ 0, cruise at v_max, ↘ α₂ (plateau) ↗ a_f | closed form |
//! | peak        | fastest to (v_c, 0), fastest to (v_f, a_f) | v_c            |
//!
//! In each family the velocity equation gives the second unknown in closed form; the position
//! equation is then a polynomial of degree ≤ 4 in a suitable parameter (see
//! [`super::families`]), solved by [`crate::roots::poly_roots`]. The up-down-up-down shapes
//! (two velocity changes in the same direction through a velocity extremum with zero
//! acceleration) come from the same polynomials, tried only in the one direction where the
//! extremum can lie between the two kinks. When the closed forms give no valid profile, the
//! families are solved again by bracketing ([`crate::roots::find_roots`]) together with the
//! "peak" family over the whole velocity range (fallback for degenerate cases). Every root becomes a candidate profile that is **verified by
//! integration** (target within 1e-8 in position and 1e-10 in velocity and acceleration; limits
//! within 1e-12 relative at segment ends and interior velocity extrema); the fastest valid
//! candidate is the result, and the durations of all valid candidates are kept as candidate
//! durations for synchronization.
//!
//! Rest to rest (v₀ = a₀ = v_f = a_f = 0) has its own closed form (`rest_to_rest`): cruise or
//! not, acceleration plateau or not, decided from the distance, the ≤ 7 segments written
//! straight into the output and verified; only asymmetric acceleration limits without a cruise
//! go through the enumeration below.
//!
//! Shortcuts, each checked against the differential suite: towards a target at rest a valid
//! cruise at the velocity limit ends the search (nothing is faster), candidates that cannot be
//! the fastest are not verified, and the peak family runs only for a moving target (where its
//! durations bound the blocked intervals) or when nothing else was found. A plateau family
//! (and a two-change variant) is skipped, coefficients and polynomial alike, when a necessary
//! condition fails by far more than the acceptance tolerance over its whole parameter window:
//! its plateau duration is negative at the window's ends (the duration is convex in the
//! parameter), or velocity continuity cannot hold there. Such a family has no valid root, so
//! skipping it changes no result. Likewise the parameter window of a plateau family ends
//! where its velocity peak (closed form in the parameter) exceeds the limit by more than
//! 1e-9 relative, and a direction's closed families (or the two-change shapes) are skipped
//! when their velocity range, bounded by the start's dip and the target's approach, has no
//! velocity on the side of the displacement (`Collector::cannot_cover`).
//!
//! Fastest-only mode (`step1_fastest_into`): where the candidate durations are not needed,
//! candidates slower than the fastest so far are not verified, and a valid cruise at the
//! velocity limit in the direction of the displacement ends the search for a moving target
//! too, when neither the start nor the target is past the point of no return towards that
//! limit (`cruise_is_optimal`: no valid profile's velocity exceeds the cruise profile's
//! envelope, so a shorter one covers less distance) and the cruise is at least 10⁻⁴ of the
//! duration. (Shorter, a family without a cruise reaches nearly the same profile through a
//! root as imprecise as a tangent's, which may pass verification a few 1e-11 faster; the
//! search then continues as in the full mode.) The closed families go in the direction of
//! the displacement first, and a direction is skipped when covering the displacement at its
//! extreme velocity takes longer than the fastest so far.
//!
//! Candidates are built in place (`Collector`): in the caller's output profile and one spare
//! buffer, the fastest kept by swapping the two roles, so no profile is copied while the
//! families are enumerated.
//!
//! Second order uses the peak family (one acceleration switch) and the cruise family; first
//! order moves at the velocity limit. The velocity interface uses the fastest velocity change.

use super::brake::brake;
use super::families::two_changes;
use super::families_gen::{s1_acc0, s1_acc01, s1_acc1, s1_none};
use super::problem::{ControlInterface, Dof1, ProfileOrder};
use super::profile::{Profile, State1};
use super::velocity_change::{fastest, VelChange};
use super::zero::{coast_into, coasts};
use crate::roots::{find_roots_coarse, MAX_POLY, MAX_ROOTS};

/// Largest number of candidate durations kept per degree of freedom.
pub(crate) const MAX_CANDIDATES: usize = 24;

/// Position tolerance of the target (absolute) for motions of at least 1e-3; smaller motions
/// have a tolerance relative to their scale (1e-5 of it).
pub const TOL_POSITION: f64 = 1e-8;
/// Motions shorter than this have a position tolerance relative to their scale (see
/// [`position_tolerance`]).
const SMALL_MOTION: f64 = 1e-3;

/// The position tolerance of the target for profile `pr` of `dof`: [`TOL_POSITION`] for
/// motions of at least [`SMALL_MOTION`]; below, 1e-5 of the motion's scale S (the larger of
/// the displacement and the largest distance from the start at a segment boundary), plus 16
/// rounding units of the positions involved, so that a motion of 1e-11 arrives (to 1e-5 of
/// itself) instead of ending where it started.
pub(crate) fn position_tolerance(dof: &Dof1, pr: &Profile) -> f64 {
    let d = (dof.pf - dof.p0).abs();
    if d >= SMALL_MOTION {
        return TOL_POSITION;
    }
    let mut s = d;
    for k in 0..pr.segments() {
        if let Some((_, _, st, _)) = pr.segment(k) {
            s = s.max((st.p - dof.p0).abs());
        }
    }
    s = s.max((pr.end().p - dof.p0).abs());
    let ulps = 16.0 * f64::EPSILON * dof.p0.abs().max(dof.pf.abs()).max(s);
    TOL_POSITION.min(1e-5 * s) + ulps
}

/// Velocity and acceleration tolerance of the target (absolute).
pub const TOL_VELOCITY: f64 = 1e-10;
/// Relative tolerance of the limits.
pub const TOL_LIMIT: f64 = 1e-12;

/// The result of step 1 for one degree of freedom.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Step1 {
    /// The time-optimal profile (brake included).
    pub profile: Profile,
    /// Durations of all valid candidate profiles (brake included), unsorted.
    pub cand: [f64; MAX_CANDIDATES],
    /// Number of entries in `cand`.
    pub ncand: usize,
}

impl Step1 {
    /// The minimum duration.
    pub fn t_min(&self) -> f64 {
        self.profile.duration()
    }
}

/// Collects verified candidates and keeps the fastest.
///
/// Candidates are built in place in a spare buffer ([`Collector::scratch`], then
/// [`Collector::submit`]); the fastest valid one stays in the other buffer, so no profile is
/// copied while the families are enumerated. One of the two buffers is the caller's (where
/// the result is wanted), the other the collector's own; the second is created only when a
/// second candidate is built while a valid one is kept (most rest-to-rest problems never need
/// it, and so never pay for initialising it).
pub(crate) struct Collector<'a> {
    dof: &'a Dof1,
    /// Buffer 0.
    out: &'a mut Profile,
    /// Buffer 1, created on first use.
    own: &'a mut Option<Profile>,
    /// Which buffer holds the fastest valid candidate so far.
    best: Option<usize>,
    /// Only the fastest candidate is wanted: candidates that cannot beat it are neither
    /// verified nor recorded.
    fastest_only: bool,
    pub cand: [f64; MAX_CANDIDATES],
    pub ncand: usize,
}

impl<'a> Collector<'a> {
    pub fn new(
        dof: &'a Dof1,
        out: &'a mut Profile,
        own: &'a mut Option<Profile>,
        fastest_only: bool,
    ) -> Self {
        Collector {
            dof,
            out,
            own,
            best: None,
            fastest_only,
            cand: [0.0; MAX_CANDIDATES],
            ncand: 0,
        }
    }

    #[inline]
    fn buf(&self, k: usize) -> &Profile {
        match (k, self.own.as_ref()) {
            (1, Some(own)) => own,
            // Buffer 1 is created (by `buf_mut`) before it is first read: only k = 0 gets here.
            _ => self.out,
        }
    }

    #[inline]
    fn buf_mut(&mut self, k: usize) -> &mut Profile {
        if k == 0 {
            self.out
        } else {
            self.own.get_or_insert_with(Profile::default)
        }
    }

    /// The fastest valid candidate so far.
    #[inline]
    pub fn best(&self) -> Option<&Profile> {
        self.best.map(|k| self.buf(k))
    }

    /// Which buffer holds the fastest valid candidate (0: the caller's).
    pub fn best_index(&self) -> Option<usize> {
        self.best
    }

    /// Leaves the fastest valid candidate in the caller's buffer.
    pub fn settle(&mut self) {
        if let (Some(1), Some(own)) = (self.best, self.own.as_ref()) {
            *self.out = *own;
            self.best = Some(0);
        }
    }

    #[inline]
    fn spare(&self) -> usize {
        match self.best {
            Some(0) => 1,
            _ => 0,
        }
    }

    /// Whether every valid candidate matters (the target moves, so every valid duration
    /// bounds a blocked interval, and all candidates are wanted).
    #[inline]
    fn wants_all(&self) -> bool {
        !self.fastest_only && (self.dof.vf != 0.0 || self.dof.af != 0.0)
    }

    /// Whether a candidate of duration `t` can still matter: it could be the fastest, or
    /// every candidate is wanted.
    #[inline]
    pub fn wants(&self, t: f64) -> bool {
        self.wants_all() || self.best().is_none_or(|b| t < b.duration())
    }

    /// Whether a family whose profiles keep their velocity within `[v_low, v_high]` (with a
    /// margin of 1e-9 relative) can be skipped for displacement `d`: covering `d` (to the
    /// position tolerance) takes at least |d|/|v| at the velocity bound v on its side. It is
    /// skipped when no valid profile can cover `d` (both modes: nothing valid is lost), or, in
    /// fastest-only mode, when covering it takes longer than the fastest so far.
    #[inline]
    pub fn cannot_cover(&self, d: f64, v_low: f64, v_high: f64) -> bool {
        let need = d.abs() - TOL_POSITION;
        if need.is_nan() || need <= 0.0 {
            return false;
        }
        let slack = 1e-9 * (v_low.abs().min(1e300) + v_high.abs().min(1e300));
        let v = if d > 0.0 {
            v_high + slack
        } else {
            slack - v_low
        };
        if v.is_nan() {
            return false;
        }
        if v <= 0.0 {
            return true;
        }
        match self.best() {
            Some(b) if self.fastest_only => need / v > b.duration() * (1.0 + 1e-9),
            _ => false,
        }
    }

    /// The spare buffer, emptied and starting at `s`, to build a candidate in.
    #[inline]
    pub fn scratch(&mut self, s: State1) -> &mut Profile {
        let k = self.spare();
        let b = self.buf_mut(k);
        b.reset(s);
        b
    }

    /// Offers the candidate built in the spare buffer; returns whether it was valid.
    pub fn submit(&mut self) -> bool {
        let k = self.spare();
        let t = self.buf(k).duration();
        if !self.wants(t) || !verify(self.dof, self.buf(k)) {
            return false;
        }
        self.record(t);
        if self.best().is_none_or(|b| t < b.duration()) {
            self.best = Some(k);
        }
        true
    }

    /// Offers a main profile (starting after the brake); returns whether it was valid.
    pub fn offer(&mut self, main: &Profile) -> bool {
        if !self.wants(main.duration()) || !verify(self.dof, main) {
            return false;
        }
        let t = main.duration();
        self.record(t);
        if self.best().is_none_or(|b| t < b.duration()) {
            let k = self.spare();
            *self.buf_mut(k) = *main;
            self.best = Some(k);
        }
        true
    }

    #[inline]
    fn record(&mut self, t: f64) {
        if !self.fastest_only
            && self.ncand < MAX_CANDIDATES
            && !self.cand[..self.ncand].contains(&t)
        {
            self.cand[self.ncand] = t;
            self.ncand += 1;
        }
    }
}

/// Checks a main profile (no brake) against the target and the limits of `dof`.
pub(crate) fn verify(dof: &Dof1, pr: &Profile) -> bool {
    let e = pr.end();
    let order = dof.order();
    let within = |x: f64, tol: f64| x.abs() <= tol;
    if dof.interface == ControlInterface::Position
        && !within(e.p - dof.pf, position_tolerance(dof, pr))
    {
        return false;
    }
    if order != ProfileOrder::First && !within(e.v - dof.vf, TOL_VELOCITY) {
        return false;
    }
    if order == ProfileOrder::Third && !within(e.a - dof.af, TOL_VELOCITY) {
        return false;
    }
    if !pr.duration().is_finite() {
        return false;
    }
    // Half the contract's tolerance, so that an independent re-evaluation (with its own
    // round-off) still finds the limits within TOL_LIMIT.
    let widen = |lim: f64| lim + 0.5 * TOL_LIMIT * lim;
    let (vmax, vmin) = (widen(dof.vmax), widen(dof.vmin));
    let (amax, amin) = (widen(dof.amax), widen(dof.amin));
    let check_v = dof.interface == ControlInterface::Position;
    let check_a = order != ProfileOrder::First;
    // A start state that the brake left outside a limit (on its way back) may stay outside
    // only until it first comes inside, and never go further out than it started.
    let s = pr.start();
    let mut v_in = !check_v || (s.v <= vmax && s.v >= vmin);
    let mut a_in = !check_a || (s.a <= amax && s.a >= amin);
    if v_in && a_in {
        // The common case: starting inside, every value must stay inside (the loop below
        // reduces to this when nothing starts outside).
        let (vmax, vmin) = if check_v {
            (vmax, vmin)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        };
        let (amax, amin) = if check_a {
            (amax, amin)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        };
        for k in 0..pr.segments() {
            let Some((_, d, st, j)) = pr.segment(k) else {
                break;
            };
            let aend = st.a + d * j;
            if st.a > amax || st.a < amin || aend > amax || aend < amin {
                return false;
            }
            let vend = st.v + d * (st.a + d * j / 2.0);
            if st.v > vmax || st.v < vmin || vend > vmax || vend < vmin {
                return false;
            }
            // The interior velocity extremum, at r = −a/j when 0 < r < d. The division is
            // skipped where r > 0 cannot hold (acceleration zero or of the jerk's sign).
            if (st.a > 0.0 && j < 0.0) || (st.a < 0.0 && j > 0.0) {
                let r = -st.a / j;
                if r > 0.0 && r < d {
                    let vmid = st.v + r * (st.a + r * j / 2.0);
                    if vmid > vmax || vmid < vmin {
                        return false;
                    }
                }
            }
        }
        return true;
    }
    let (v_hi, v_lo) = (vmax.max(s.v), vmin.min(s.v));
    let (a_hi, a_lo) = (amax.max(s.a), amin.min(s.a));
    for k in 0..pr.segments() {
        let Some((_, d, st, j)) = pr.segment(k) else {
            break;
        };
        // The end state as stored (a closed-form step may have snapped it to its exact
        // value, removing round-off of the size of the largest velocity passed through).
        let vend = st.v + d * (st.a + d * j / 2.0);
        let aend = st.a + d * j;
        let mut vs = [st.v, st.v, vend];
        if j != 0.0 {
            let r = -st.a / j;
            if r > 0.0 && r < d {
                vs[1] = st.v + r * (st.a + r * j / 2.0);
            }
        }
        if check_v {
            for v in vs {
                if v_in {
                    if v > vmax || v < vmin {
                        return false;
                    }
                } else if v > v_hi || v < v_lo {
                    return false;
                } else if v <= vmax && v >= vmin {
                    v_in = true;
                }
            }
        }
        if check_a {
            for a in [st.a, aend] {
                if a_in {
                    if a > amax || a < amin {
                        return false;
                    }
                } else if a > a_hi || a < a_lo {
                    return false;
                } else if a <= amax && a >= amin {
                    a_in = true;
                }
            }
        }
    }
    true
}

/// A velocity bound that the optimal profile never needs to exceed, used to bound parameter
/// ranges when the velocity limit is infinite.
pub(crate) fn velocity_cap(dof: &Dof1, s: State1) -> f64 {
    if dof.vmax.is_finite() {
        return dof.vmax;
    }
    let a = dof.amax.max(-dof.amin);
    let a = if a.is_finite() { a } else { 0.0 };
    let d = (dof.pf - s.p).abs();
    let cap = 2.0 * (s.v.abs() + dof.vf.abs())
        + (s.a * s.a + dof.af * dof.af) / dof.jmax
        + 2.0 * (2.0 * a * d).sqrt()
        + 2.0 * a * a / dof.jmax;
    4.0 * cap.max(1e-300)
}

/// Step 1 for one degree of freedom. `None` when no valid profile was found.
pub(crate) fn step1(dof: &Dof1) -> Option<Step1> {
    let mut s = Step1 {
        profile: Profile::default(),
        cand: [0.0; MAX_CANDIDATES],
        ncand: 0,
    };
    let mut spare = None;
    s.ncand = step1_into(dof, &mut s.profile, &mut spare, &mut s.cand)?;
    Some(s)
}

/// Step 1 written into the caller's storage (no copy of the result): the time-optimal profile
/// into `profile`, the candidate durations into `cand`, with `spare` as working space (created
/// when needed, left unspecified); returns how many candidates, or `None` when no valid profile was found (then
/// `profile` is unspecified).
pub(crate) fn step1_into(
    dof: &Dof1,
    profile: &mut Profile,
    spare: &mut Option<Profile>,
    cand: &mut [f64; MAX_CANDIDATES],
) -> Option<usize> {
    step1_run(dof, profile, spare, Some(cand))
}

/// Step 1 in fastest-only mode: only the time-optimal profile, into `profile` (with `spare`
/// as working space, created when needed, left unspecified); no candidate durations. `None`
/// when no valid profile was found (then `profile` is unspecified).
///
/// Contract: the result is the profile [`step1_into`] returns for `dof`, or one of the same
/// duration to 1e-12 relative that passes the same verification; it is `None` exactly when
/// [`step1_into`] is (checked on 1.2·10⁵ random problems of every category in
/// `step1_modes_tests`). What it saves: candidates that cannot beat the fastest so far are
/// not verified, and a valid cruise at the velocity limit ends the search for a moving
/// target too when `cruise_is_optimal` proves that nothing is faster. Use it where the
/// candidate durations are not needed (one DOF, or a DOF whose blocked intervals cannot
/// matter); [`step1_into`] gives them.
pub(crate) fn step1_fastest_into(
    dof: &Dof1,
    profile: &mut Profile,
    spare: &mut Option<Profile>,
) -> Option<()> {
    step1_run(dof, profile, spare, None).map(|_| ())
}

/// Step 1 (brake, then the main profile's families) into `profile`; with `cand`, the
/// candidate durations (brake included) go there and their number is returned (the full
/// mode), without it only the fastest profile is wanted (fastest-only mode; returns 0).
/// Inlined into both callers, so that each mode's code is specialised.
///
/// Two cases come first: a degree of freedom that coasts ([`super::zero`]) has one profile,
/// and one whose state already is its target state (exactly) needs no time: duration 0, the
/// fastest of its candidates (the others, in the full mode, still bound its blocked
/// intervals: a moving state cannot stay on its target for a short while).
#[inline(always)]
fn step1_run(
    dof: &Dof1,
    profile: &mut Profile,
    spare: &mut Option<Profile>,
    mut cand: Option<&mut [f64; MAX_CANDIDATES]>,
) -> Option<usize> {
    // The common rest-to-rest case first (it never applies to the two cases below: it needs a
    // displacement, and a coasting DOF's closed form does not pass verification).
    if rest_to_rest(dof, profile).is_some() {
        return Some(match cand.as_deref_mut() {
            Some(c) => {
                c[0] = profile.duration();
                1
            }
            None => 0,
        });
    }
    if coasts(dof) {
        if !coast_into(dof, None, profile) {
            return None;
        }
        return Some(match cand {
            Some(c) => {
                c[0] = profile.duration();
                1
            }
            None => 0,
        });
    }
    if is_on_target(dof) {
        let n = match cand {
            None => 0,
            Some(c) => {
                // The other candidates (durations of loops back to the target state), for the
                // blocked intervals.
                let n = step1_enumerate(dof, profile, spare, Some(c)).unwrap_or(0);
                let n = n.min(MAX_CANDIDATES - 1);
                c.copy_within(0..n, 1);
                c[0] = 0.0;
                n + 1
            }
        };
        profile.reset(State1 {
            p: dof.p0,
            v: dof.v0,
            a: dof.a0,
        });
        if dof.order() == ProfileOrder::Second {
            profile.set_final(dof.vf, 0.0);
        }
        return Some(n);
    }
    step1_enumerate(dof, profile, spare, cand)
}

/// Whether the start state is the target state, exactly (position only for the position
/// interface; acceleration only for third order).
#[inline]
pub(crate) fn is_on_target(dof: &Dof1) -> bool {
    let order = dof.order();
    (dof.interface == ControlInterface::Velocity || dof.p0 == dof.pf)
        && (order == ProfileOrder::First || dof.v0 == dof.vf)
        && (order != ProfileOrder::Third || dof.a0 == dof.af)
}

/// [`step1_run`] for the ordinary case (after the rest-to-rest closed form): the brake and
/// the enumeration of the families.
#[inline(always)]
fn step1_enumerate(
    dof: &Dof1,
    profile: &mut Profile,
    spare: &mut Option<Profile>,
    cand: Option<&mut [f64; MAX_CANDIDATES]>,
) -> Option<usize> {
    let fastest_only = cand.is_none();
    profile.reset(State1 {
        p: dof.p0,
        v: dof.v0,
        a: dof.a0,
    });
    brake(dof, profile);
    let s = profile.end();
    let mut main_dof = *dof;
    main_dof.p0 = s.p;
    main_dof.v0 = s.v;
    main_dof.a0 = s.a;
    let tb = profile.duration();
    // The collector builds its candidates in `profile` (and its own buffer): without a brake
    // the result needs no copy when the fastest candidate was built there.
    let brake_pr = (profile.segments() > 0).then_some(*profile);
    let mut col = Collector::new(&main_dof, profile, spare, fastest_only);
    solve_main(&main_dof, &mut col);
    col.best_index()?;
    let ncand = col.ncand;
    if let Some(cand) = cand {
        for (c, &t) in cand.iter_mut().zip(&col.cand[..ncand]) {
            *c = t + tb;
        }
    }
    match brake_pr {
        None => col.settle(),
        Some(b) => {
            let best = *col.best()?;
            *profile = b;
            if !profile.append(&best) {
                return None;
            }
        }
    }
    Some(ncand)
}

/// Enumerates the main-profile candidates of a problem whose start state is safe. (Inlined
/// into each mode's step 1, as it was into the one step 1 before the fastest-only mode.)
#[inline(always)]
fn solve_main(dof: &Dof1, col: &mut Collector<'_>) {
    let start = State1 {
        p: dof.p0,
        v: dof.v0,
        a: dof.a0,
    };
    match (dof.order(), dof.interface) {
        (ProfileOrder::First, ControlInterface::Position) => {
            let d = dof.pf - dof.p0;
            let mut pr = Profile::new(start);
            if d != 0.0 {
                let v = if d > 0.0 { dof.vmax } else { dof.vmin };
                pr.push_with(d / v, v, 0.0, 0.0);
            }
            pr.set_final(dof.vf, 0.0);
            col.offer(&pr);
        }
        (ProfileOrder::First, ControlInterface::Velocity) => {
            let mut pr = Profile::new(start);
            pr.set_final(dof.vf, 0.0);
            col.offer(&pr);
        }
        (order, ControlInterface::Velocity) => {
            if let Some(c) = fastest(
                order, dof.v0, dof.a0, dof.vf, dof.af, dof.jmax, dof.amax, dof.amin,
            ) {
                let mut pr = Profile::new(start);
                push_change(&mut pr, order, &c, dof.v0);
                if order == ProfileOrder::Second {
                    pr.set_final(dof.vf, 0.0);
                }
                col.offer(&pr);
            }
        }
        (ProfileOrder::Second, ControlInterface::Position) => {
            peak_family(dof, col);
            cruise_family(dof, col);
        }
        (ProfileOrder::Third, ControlInterface::Position) => {
            // Towards a target at rest, a valid cruise at the velocity limit is time-optimal:
            // the other families need not be tried.
            let mut cruise = false;
            // From rest to rest, `rest_to_rest` (run by `step1_run` first) has already
            // decided the cruise in closed form: it gets here only when no cruise fits (or
            // its profile failed verification, as this family's would).
            let rest = dof.v0 == 0.0 && dof.a0 == 0.0 && dof.vf == 0.0 && dof.af == 0.0;
            // In fastest-only mode the direction of the displacement first (a valid cruise
            // there ends the search).
            let dirs = if col.fastest_only && dof.pf < dof.p0 {
                [true, false]
            } else {
                [false, true]
            };
            if !rest {
                for mirror in dirs {
                    let q = if mirror { dof.mirrored() } else { *dof };
                    let share = vel_family(&q, mirror, col);
                    cruise |= share.is_some();
                    // (Not when the cruise is so short that a family without one reaches the
                    // same profile, with a root as imprecise as a tangent's.)
                    if share.is_some_and(|c| c > 1e-4) && col.fastest_only && cruise_is_optimal(&q)
                    {
                        return;
                    }
                }
            }
            if cruise && dof.vf == 0.0 && dof.af == 0.0 {
                return;
            }
            let moving = dof.vf != 0.0 || dof.af != 0.0;
            for mirror in dirs {
                let q = if mirror { dof.mirrored() } else { *dof };
                closed_families(&q, mirror, col);
                // The up-down-up-down shapes (two velocity changes in the same direction).
                // Towards a target at rest they are never faster than the families above
                // (checked against rsruckig on every random category), so they are only
                // needed when the target moves (where their durations bound the blocked
                // intervals).
                // Both changes go up only when v_c can lie between the velocity where the
                // start's acceleration reaches zero and the one from which the target's is
                // reached: at most one of the two directions qualifies.
                let k0 = kink(ProfileOrder::Third, q.v0, q.a0, q.jmax, 1.0);
                let kf = kink(ProfileOrder::Third, q.vf, q.af, q.jmax, -1.0);
                let slack = 1e-9 * (k0.abs() + kf.abs()) + 1e-300;
                // Both changes go up: the velocity stays between the start's dip and the
                // target's approach from above.
                let j2 = 2.0 * q.jmax;
                let v_low = q.v0 - q.a0.min(0.0).powi(2) / j2;
                let v_high = q.vf + q.af.min(0.0).powi(2) / j2;
                if moving && k0 <= kf + slack && !col.cannot_cover(q.pf - q.p0, v_low, v_high) {
                    let (vlo, vhi) = velocity_window(&q);
                    two_changes(&q, 1.0, 1.0, None, vlo, vhi, &mut |pr| {
                        let mut pr = *pr;
                        if mirror {
                            pr.mirror();
                        }
                        col.offer(&pr);
                        false
                    });
                }
            }
            if col.best().is_some() {
                return;
            }
            // Fallback for degenerate cases the closed forms miss: the bracketing solver on
            // the same families, and the peak family over the whole velocity range.
            for mirror in [false, true] {
                let q = if mirror { dof.mirrored() } else { *dof };
                third_families(&q, mirror, col);
            }
            peak_family(dof, col);
        }
    }
}

/// Whether a valid cruise at the velocity limit of `q` (positive direction of the possibly
/// mirrored problem) is time-optimal also when the target moves; then the other families
/// can only add candidate durations.
///
/// Why: when no state of a valid profile can be past the point of no return (the start can
/// be reached from below the limit, v₀ + min(a₀, 0)²/(2j) ≤ v_max, and the target stays below
/// it, v_f + max(a_f, 0)²/(2j) ≤ v_max), the velocity of a valid profile of duration T is at
/// most the envelope min(R(t), F(T − t)), R the cruise profile's rise from the start and F
/// its fall to the target read backwards (the largest velocities reachable after t and
/// before T − t). The envelope's area A(T) equals the displacement d at the cruise
/// profile's duration T*, and dA/dT is the envelope's peak velocity wherever a profile of
/// duration T can reach the target velocity at all: A grows with T while the peak is
/// positive, and is negative where it is not. So with d > 0 no T < T* covers d.
fn cruise_is_optimal(q: &Dof1) -> bool {
    let j2 = 2.0 * q.jmax;
    q.pf > q.p0
        && q.v0 + q.a0.min(0.0).powi(2) / j2 <= q.vmax
        && q.vf + q.af.max(0.0).powi(2) / j2 <= q.vmax
}

/// Rest to rest (third order, position interface, v₀ = a₀ = v_f = a_f = 0) in closed form,
/// written straight into `pr`: the time-optimal profile changes velocity as fast as possible
/// from rest to a peak velocity v_p in the direction of the displacement D and straight back,
/// cruising at the velocity limit V in between when the two changes alone do not cover D.
///
/// A change between rest and v under jerk J and acceleration limit A ramps for r = √(v/J)
/// (no plateau, when J·v ≤ A²) or for r = A/J with a plateau h = v/A − A/J, and covers
/// v·(2r + h)/2 (its velocity is point-symmetric about its midpoint). With v = V the cruise
/// lasts D/V − (t₁ + t₂)/2; when that is negative, v_p < V covers D exactly:
/// D = 2J·r³ without plateaus (r = ∛(D/(2J))), or D = v_p·(v_p/A + A/J) with them, a
/// quadratic in v_p. The limits are those of the direction (V = v_max or −v_min, the first
/// change accelerating with a_max or −a_min and the second braking with the other).
///
/// The profile is built by integrating its segments and verified like every candidate. Its
/// duration is the only candidate (nothing else is valid and faster, and towards rest the
/// candidates serve only the minimum). Returns `None`, leaving `pr` to the general
/// enumeration, when the problem is not rest to rest, the displacement is zero or not finite,
/// the acceleration limits are asymmetric and no cruise fits, or verification fails.
fn rest_to_rest(dof: &Dof1, pr: &mut Profile) -> Option<()> {
    if dof.v0 != 0.0
        || dof.a0 != 0.0
        || dof.vf != 0.0
        || dof.af != 0.0
        || dof.interface != ControlInterface::Position
        || dof.order() != ProfileOrder::Third
    {
        return None;
    }
    let dist = dof.pf - dof.p0;
    if dist == 0.0 || !dist.is_finite() {
        return None;
    }
    let (s, d, v, a_up, a_down) = if dist > 0.0 {
        (1.0, dist, dof.vmax, dof.amax, -dof.amin)
    } else {
        (-1.0, -dist, -dof.vmin, -dof.amin, dof.amax)
    };
    let j = dof.jmax;
    let shape = if v.is_finite() {
        let (r1, h1) = rest_change(v, a_up, j);
        let (r2, h2) = rest_change(v, a_down, j);
        let cruise = d / v - (2.0 * (r1 + r2) + h1 + h2) / 2.0;
        if cruise >= 0.0 {
            RestShape {
                r1,
                h1,
                r2,
                h2,
                vp: v,
                cruise,
            }
        } else {
            peak(d, j, a_up, a_down)?
        }
    } else {
        peak(d, j, a_up, a_down)?
    };
    if !shape.write(pr, dof.p0, s, j) || !verify(dof, pr) {
        return None;
    }
    Some(())
}

/// The no-cruise case of [`rest_to_rest`] for symmetric acceleration limits; `None` for
/// asymmetric ones.
fn peak(d: f64, j: f64, a_up: f64, a_down: f64) -> Option<RestShape> {
    if a_up != a_down {
        return None;
    }
    let a = a_up;
    let ramp_max = a / j;
    let r = (d / (2.0 * j)).cbrt();
    let (r, h, vp) = if r <= ramp_max {
        (r, 0.0, j * r * r)
    } else {
        // v_p²/A + v_p·A/J − D = 0, positive root, as v_p/A.
        let k = ramp_max;
        let vpa = 0.5 * (-k + (k * k + 4.0 * d / a).sqrt());
        (k, (vpa - k).max(0.0), a * vpa)
    };
    Some(RestShape {
        r1: r,
        h1: h,
        r2: r,
        h2: h,
        vp,
        cruise: 0.0,
    })
}

/// Ramp and plateau durations of the fastest change between rest and velocity `v` > 0 under
/// jerk limit `j` and acceleration limit `a`: (√(v/j), 0) when j·v ≤ a², otherwise
/// (a/j, v/a − a/j). (The same values as [`fastest`] between (0, 0) and (v, 0).)
#[inline]
fn rest_change(v: f64, a: f64, j: f64) -> (f64, f64) {
    let alpha = (j * v).sqrt();
    if alpha <= a {
        (alpha / j, 0.0)
    } else {
        (a / j, (v / a - a / j).max(0.0))
    }
}

/// A motion from rest to rest in one direction: ramp r₁, plateau h₁, ramp r₁ up to the peak
/// velocity v_p, a cruise there, then r₂, h₂, r₂ back to rest (steps 1 and 2).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RestShape {
    /// Ramp duration of the change up to the peak velocity.
    pub r1: f64,
    /// Acceleration plateau of the change up (0 without one).
    pub h1: f64,
    /// Ramp duration of the change back to rest.
    pub r2: f64,
    /// Acceleration plateau of the change back to rest (0 without one).
    pub h2: f64,
    /// Peak (cruise) velocity, > 0.
    pub vp: f64,
    /// Cruise duration at the peak velocity (0 without a cruise).
    pub cruise: f64,
}

impl RestShape {
    /// Writes the shape into `pr` (emptied first), from rest at `p0` in direction `s` (±1)
    /// with jerk limit `j`, integrating its segments; false when a duration is refused (then
    /// `pr` is unspecified).
    pub(crate) fn write(&self, pr: &mut Profile, p0: f64, s: f64, j: f64) -> bool {
        let js = s * j;
        pr.reset(State1 {
            p: p0,
            v: 0.0,
            a: 0.0,
        });
        if !pr.push_run(&[(self.r1, js), (self.h1, 0.0), (self.r1, -js)]) {
            return false;
        }
        // The exact peak velocity (removing the integration's round-off before the cruise).
        pr.snap(s * self.vp, 0.0);
        pr.push_run(&[
            (self.cruise, 0.0),
            (self.r2, -js),
            (self.h2, 0.0),
            (self.r2, js),
        ])
    }
}

/// Appends a velocity change to a profile.
pub(crate) fn push_change(pr: &mut Profile, order: ProfileOrder, c: &VelChange, va: f64) {
    match order {
        ProfileOrder::Third => {
            for k in 0..3 {
                pr.push(c.d[k], c.j[k]);
            }
        }
        ProfileOrder::Second => {
            if c.t > 0.0 {
                pr.push_with(c.t, va, c.accel, 0.0);
            }
        }
        ProfileOrder::First => {}
    }
}

/// Peak family: fastest change to (v_c, 0), then fastest change to the target; residual in
/// position, free parameter v_c.
fn peak_family(dof: &Dof1, col: &mut Collector<'_>) {
    let order = dof.order();
    let d = dof.pf - dof.p0;
    let vcap = velocity_cap(
        dof,
        State1 {
            p: dof.p0,
            v: dof.v0,
            a: dof.a0,
        },
    );
    let vcap_neg = velocity_cap(
        &dof.mirrored(),
        State1 {
            p: -dof.p0,
            v: -dof.v0,
            a: -dof.a0,
        },
    );
    let (lo, hi) = (-vcap_neg, vcap);
    let parts = |vc: f64| -> Option<(VelChange, VelChange)> {
        let c1 = fastest(order, dof.v0, dof.a0, vc, 0.0, dof.jmax, dof.amax, dof.amin)?;
        let c2 = fastest(order, vc, 0.0, dof.vf, dof.af, dof.jmax, dof.amax, dof.amin)?;
        Some((c1, c2))
    };
    let mut f = |vc: f64| parts(vc).map(|(c1, c2)| c1.dist + c2.dist - d);
    let mut roots = [0.0; MAX_ROOTS];
    let mut cuts = [
        lo,
        hi,
        0.0,
        kink(order, dof.v0, dof.a0, dof.jmax, 1.0),
        kink(order, dof.vf, dof.af, dof.jmax, -1.0),
    ];
    for_each_piece(&mut cuts, |a, b| {
        let n = find_roots_coarse(&mut f, a, b, &mut roots);
        for &vc in &roots[..n] {
            if let Some((c1, c2)) = parts(vc) {
                let mut pr = Profile::new(State1 {
                    p: dof.p0,
                    v: dof.v0,
                    a: dof.a0,
                });
                push_change(&mut pr, order, &c1, dof.v0);
                pr.snap(vc, 0.0);
                push_change(&mut pr, order, &c2, vc);
                if order == ProfileOrder::Second {
                    pr.set_final(dof.vf, 0.0);
                }
                col.offer(&pr);
            }
        }
    });
}

/// The velocity where the fastest change from (v, a) to zero acceleration lands (`dir` = 1),
/// or from which it reaches (v, a) (`dir` = −1).
pub(crate) fn kink(order: ProfileOrder, v: f64, a: f64, j: f64, dir: f64) -> f64 {
    match order {
        ProfileOrder::Third => v + dir * a * a.abs() / (2.0 * j),
        _ => v,
    }
}

/// Sorts the cut points, clips them to [cuts[0], cuts[1]] and calls `f` on each piece.
pub(crate) fn for_each_piece<const N: usize>(cuts: &mut [f64; N], mut f: impl FnMut(f64, f64)) {
    let (lo, hi) = (cuts[0], cuts[1]);
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return;
    }
    for c in cuts.iter_mut() {
        *c = c.clamp(lo, hi);
    }
    cuts.sort_by(|a, b| a.total_cmp(b));
    for k in 0..N - 1 {
        if cuts[k + 1] > cuts[k] || (k == 0 && lo == hi) {
            f(cuts[k], cuts[k + 1]);
        }
    }
}

/// Cruise family: fastest change to (v_max, 0), cruise, fastest change to the target (both
/// signs of the cruise velocity).
fn cruise_family(dof: &Dof1, col: &mut Collector<'_>) {
    let order = dof.order();
    let d = dof.pf - dof.p0;
    for vc in [dof.vmax, dof.vmin] {
        if !vc.is_finite() || vc == 0.0 {
            continue;
        }
        let Some(c1) = fastest(order, dof.v0, dof.a0, vc, 0.0, dof.jmax, dof.amax, dof.amin) else {
            continue;
        };
        let Some(c2) = fastest(order, vc, 0.0, dof.vf, dof.af, dof.jmax, dof.amax, dof.amin) else {
            continue;
        };
        let tau = (d - c1.dist - c2.dist) / vc;
        if tau.is_nan() || tau < 0.0 {
            continue;
        }
        let mut pr = Profile::new(State1 {
            p: dof.p0,
            v: dof.v0,
            a: dof.a0,
        });
        push_change(&mut pr, order, &c1, dof.v0);
        pr.snap(vc, 0.0);
        pr.push_with(tau, vc, 0.0, 0.0);
        push_change(&mut pr, order, &c2, vc);
        if order == ProfileOrder::Second {
            pr.set_final(dof.vf, 0.0);
        }
        col.offer(&pr);
    }
}

/// A sequence of up to 7 constant-jerk segments.
#[derive(Clone, Copy)]
struct Seq {
    n: usize,
    d: [f64; 7],
    j: [f64; 7],
}

impl Seq {
    fn new() -> Seq {
        Seq {
            n: 0,
            d: [0.0; 7],
            j: [0.0; 7],
        }
    }
    #[inline]
    fn add(&mut self, d: f64, j: f64) {
        self.d[self.n] = d.max(0.0);
        self.j[self.n] = j;
        self.n += 1;
    }
    /// Offers the sequence, started from `q`'s start state (mirrored back when `mirror`), to
    /// the collector unless it cannot matter.
    fn offer(&self, q: &Dof1, mirror: bool, col: &mut Collector<'_>) {
        if !col.wants(self.d[..self.n].iter().sum()) {
            return;
        }
        let pr = col.scratch(State1 {
            p: q.p0,
            v: q.v0,
            a: q.a0,
        });
        for k in 0..self.n {
            pr.push(self.d[k], self.j[k]);
        }
        if mirror {
            pr.mirror();
        }
        col.submit();
    }
    #[inline]
    fn displacement(&self, v0: f64, a0: f64) -> f64 {
        let (mut p, mut v, mut a) = (0.0, v0, a0);
        for k in 0..self.n {
            (p, v, a) = super::profile::integrate(p, v, a, self.j[k], self.d[k]);
        }
        p
    }
}

/// The cruise family (vel) in the positive direction of the (possibly mirrored) problem `q`:
/// fastest change to (v_max, 0), cruise, fastest change to the target. When it offered a
/// valid profile, returns the cruise's share of its duration.
fn vel_family(q: &Dof1, mirror: bool, col: &mut Collector<'_>) -> Option<f64> {
    let j = q.jmax;
    let (a0, v0, af, vf) = (q.a0, q.v0, q.af, q.vf);
    let amax = q.amax;
    let a2 = -q.amin;
    let d = q.pf - q.p0;
    // vel: cruise at v_max.
    if q.vmax.is_finite() {
        let c1 = super::velocity_change::fastest3(v0, a0, q.vmax, 0.0, j, amax, -a2);
        let c2 = super::velocity_change::fastest3(q.vmax, 0.0, vf, af, j, amax, -a2);
        if let (Some(c1), Some(c2)) = (c1, c2) {
            let tau = (d - c1.dist - c2.dist) / q.vmax;
            if tau >= 0.0 {
                let pr = col.scratch(State1 {
                    p: q.p0,
                    v: v0,
                    a: a0,
                });
                push_change(pr, ProfileOrder::Third, &c1, v0);
                pr.snap(q.vmax, 0.0);
                pr.push_with(tau, q.vmax, 0.0, 0.0);
                push_change(pr, ProfileOrder::Third, &c2, q.vmax);
                if mirror {
                    pr.mirror();
                }
                let share = tau / pr.duration();
                return col.submit().then_some(share);
            }
        }
    }
    None
}

/// The range of cruise velocities worth considering for `q`: its velocity limits, or the caps
/// of [`velocity_cap`] where they are infinite.
pub(crate) fn velocity_window(q: &Dof1) -> (f64, f64) {
    let hi = velocity_cap(
        q,
        State1 {
            p: q.p0,
            v: q.v0,
            a: q.a0,
        },
    );
    let lo = -velocity_cap(
        &q.mirrored(),
        State1 {
            p: -q.p0,
            v: -q.v0,
            a: -q.a0,
        },
    );
    (lo, hi)
}

/// The families a₀ ↗ α₁ ↘ α₂ ↗ a_f (with or without plateaus at a_max and a_min) in the
/// positive direction of the (possibly mirrored) problem `q`, each from the roots of its
/// position polynomial (see [`super::families`]).
fn closed_families(q: &Dof1, mirror: bool, col: &mut Collector<'_>) {
    let j = q.jmax;
    let (a0, v0, af, vf) = (q.a0, q.v0, q.af, q.vf);
    let (amax, amin) = (q.amax, q.amin);
    let dv = vf - v0;
    let d = q.pf - q.p0;
    let tol = 1e-12 * (amax - amin);
    if a0 > amax + tol || !(amax.is_finite() && amin.is_finite()) {
        return;
    }
    let a0c = a0.min(amax);
    // Every family here ramps the acceleration up, down, up (a₀ ↗ α₁ ↘ α₂ ↗ a_f): the
    // velocity never falls below the start's dip or the target's approach from below.
    let v_low = (v0 - a0.min(0.0).powi(2) / (2.0 * j)).min(vf - af.max(0.0).powi(2) / (2.0 * j));
    if col.cannot_cover(d, v_low, q.vmax.max(v0)) {
        return;
    }
    let emit = |seq: &Seq, col: &mut Collector<'_>| seq.offer(q, mirror, col);
    // Durations may come out negative at round-off level on a family's edge.
    let okd = |x: f64, scale: f64| x >= -1e-12 * scale.max(1e-300);
    let mut roots = [0.0; MAX_POLY];
    // none: s = α₁, α₂ = w.
    // (Coefficients only when a window is not empty.)
    let mut none = None;
    // α₂² = α₁² − K with α₂ ∈ [a_min, a_f]: α₁² ∈ [K (+a_f² when a_f < 0), K + max(a_f², a_min²)].
    let k = j * dv + (a0 * a0 - af * af) / 2.0;
    let l = k + if af < 0.0 { af * af } else { 0.0 };
    let af_pos = if af >= 0.0 { af * af } else { 0.0 };
    let u = k + af_pos.max(amin * amin);
    for (lo, hi) in square_window(l.max(0.0), u, a0c, amax, true, tol) {
        let r = none.get_or_insert_with(|| s1_none(a0, af, v0, vf, d, j));
        let n = r.roots(lo, hi, &mut roots);
        for &x in &roots[..n] {
            let al2 = r.w_at(x);
            if al2 > x + tol || al2 > af + tol || al2 < amin - tol {
                continue;
            }
            let mut s = Seq::new();
            s.add((x - a0) / j, j);
            s.add((x - al2) / j, -j);
            s.add((af - al2) / j, j);
            emit(&s, col);
        }
    }
    // The plateau families' plateau duration is convex in their parameter, so its largest
    // value over the parameter window is at one of the window's ends. When it is clearly
    // negative at both (beyond the tolerance of `okd`, with a margin far above round-off), no
    // root can give a valid profile and the family is skipped: neither its coefficients nor
    // its polynomial are computed.
    let dscale = (amax - amin) / j;
    let hopeless = |t: f64, size: f64| t < -1e-12 * dscale.max(1e-300) - 1e-9 * size;
    // Where a plateau family passes a velocity peak (the acceleration turning from positive
    // to negative), the peak must not exceed v_max (or the start's velocity, when the brake
    // left it above): a necessary condition that narrows the parameter windows below, with
    // a margin far above round-off (verification accepts 0.5e-12 relative). The peak
    // velocity is a function of the parameter in closed form.
    let vtop = q.vmax.max(v0) + 1e-9 * (q.vmax.abs().min(1e300) + v0.abs() + vf.abs());
    // acc0: s = α₂, plateau τ₁ at a_max. For α₂ < 0 the peak is v_f + (2α₂² − a_f²)/(2j).
    let c0 = amax * amax + (af * af - a0 * a0) / 2.0 - j * dv;
    let peak_lo = -(af * af / 2.0 + j * (vtop - vf)).max(0.0).sqrt();
    let (xlo, xhi) = ((amin - tol).max(peak_lo - tol), amax.min(af) + tol);
    let t1_at = |x: f64| (x * x - c0) / (j * amax);
    let t1_size = |x: f64| (x * x + c0.abs()) / (j * amax);
    let n = if xlo > xhi
        || (hopeless(t1_at(xlo), t1_size(xlo)) && hopeless(t1_at(xhi), t1_size(xhi)))
    {
        0
    } else {
        s1_acc0(a0, af, v0, vf, d, j, amax).roots(xlo, xhi, &mut roots)
    };
    for &x in &roots[..n] {
        let t1 = (x * x - c0) / (j * amax);
        if !okd(t1, (amax - amin) / j) {
            continue;
        }
        let mut s = Seq::new();
        s.add((amax - a0) / j, j);
        s.add(t1, 0.0);
        s.add((amax - x) / j, -j);
        s.add((af - x) / j, j);
        emit(&s, col);
    }
    if af < amin - tol {
        return;
    }
    // acc1: s = α₁, plateau τ₂ at a_min.
    let t2_of =
        |x: f64| ((2.0 * x * x - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j) - dv) / -amin;
    let t2_size = |x: f64| {
        ((2.0 * x * x + a0 * a0 + 2.0 * amin * amin + af * af) / (2.0 * j) + dv.abs()) / -amin
    };
    // For α₁ > 0 the peak is v₀ + (2α₁² − a₀²)/(2j).
    let peak_hi = (j * (vtop - v0) + a0 * a0 / 2.0).max(0.0).sqrt();
    let (xlo, xhi) = (a0c - tol, amax.min(peak_hi) + tol);
    let n = if xlo > xhi
        || (hopeless(t2_of(xlo), t2_size(xlo)) && hopeless(t2_of(xhi), t2_size(xhi)))
    {
        0
    } else {
        s1_acc1(a0, af, v0, vf, d, j, amin).roots(xlo, xhi, &mut roots)
    };
    for &x in &roots[..n] {
        let t2 = t2_of(x);
        if !okd(t2, (amax - amin) / j) {
            continue;
        }
        let mut s = Seq::new();
        s.add((x - a0) / j, j);
        s.add((x - amin) / j, -j);
        s.add(t2, 0.0);
        s.add((af - amin) / j, j);
        emit(&s, col);
    }
    // acc0_acc1: s = τ₁ (τ₂ grows with τ₁: its largest value is at the window's end).
    let (vlo, vhi) = velocity_window(q);
    // The peak is v₀ + (2a_max² − a₀²)/(2j) + a_max·τ₁.
    let t1_peak = (vtop - v0 - (2.0 * amax * amax - a0 * a0) / (2.0 * j)) / amax;
    let t1_hi = (((vhi - vlo).abs() + dv.abs()) / amax).min(t1_peak);
    let k01 = (2.0 * amax * amax - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j);
    let t2_at = |x: f64| (k01 + amax * x - dv) / -amin;
    let size = (k01.abs() + amax * t1_hi + dv.abs()) / -amin;
    let n = if t1_hi < 0.0 || hopeless(t2_at(t1_hi), size) {
        0
    } else {
        s1_acc01(a0, af, v0, vf, d, j, amax, amin).roots(0.0, t1_hi, &mut roots)
    };
    for &x in &roots[..n] {
        let t2 = ((2.0 * amax * amax - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j)
            + amax * x
            - dv)
            / -amin;
        if !okd(t2, (amax - amin) / j) {
            continue;
        }
        let mut s = Seq::new();
        s.add((amax - a0) / j, j);
        s.add(x, 0.0);
        s.add((amax - amin) / j, -j);
        s.add(t2, 0.0);
        s.add((af - amin) / j, j);
        emit(&s, col);
    }
}

/// The third-order families in the positive direction of the (possibly mirrored) problem `q`,
/// by bracketing (the fallback of [`closed_families`]).
fn third_families(q: &Dof1, mirror: bool, col: &mut Collector<'_>) {
    let j = q.jmax;
    let (a0, v0, af, vf) = (q.a0, q.v0, q.af, q.vf);
    let amax = q.amax;
    let a2 = -q.amin;
    let dv = vf - v0;
    let d = q.pf - q.p0;
    let vlim = if q.vmax.is_finite() {
        q.vmax
    } else {
        velocity_cap(
            q,
            State1 {
                p: q.p0,
                v: v0,
                a: a0,
            },
        )
    };
    let tol = 1e-12 * (amax + a2);
    let emit = |seq: &Seq, col: &mut Collector<'_>| seq.offer(q, mirror, col);
    let mut roots = [0.0; MAX_ROOTS];
    if a0 > amax + tol {
        return;
    }
    let a0c = a0.min(amax);
    let tau_hi = (vlim - v0 - (amax * amax - a0 * a0) / (2.0 * j)) / amax;
    for sign in [1.0, -1.0] {
        // none: parameter α1.
        let none = |x: f64| -> Option<Seq> {
            let rad = x * x + (af * af - a0 * a0) / 2.0 - j * dv;
            if rad < -tol * tol {
                return None;
            }
            let al2 = sign * rad.max(0.0).sqrt();
            if al2 > x + tol || al2 > af + tol || al2 < -a2 - tol {
                return None;
            }
            let mut s = Seq::new();
            s.add((x - a0) / j, j);
            s.add((x - al2) / j, -j);
            s.add((af - al2) / j, j);
            Some(s)
        };
        let mut f = |x: f64| none(x).map(|s| s.displacement(v0, a0) - d);
        // Valid domain: x² ∈ [l, u] (and the sign conditions), computed in closed form so that
        // narrow windows are not missed by sampling.
        let k = (af * af - a0 * a0) / 2.0 - j * dv;
        let (l, u, neg_ok) = if sign > 0.0 {
            if af < -tol || k > tol * tol {
                (1.0, 0.0, false)
            } else {
                ((-k).max(0.0), af.max(0.0) * af.max(0.0) - k, false)
            }
        } else {
            let l = (-k).max(0.0).max(if af < 0.0 { af * af - k } else { 0.0 });
            (l, a2 * a2 - k, k >= -tol * tol)
        };
        for (lo, hi) in square_window(l, u, a0c, amax, neg_ok, tol) {
            let n = find_roots_coarse(&mut f, lo, hi, &mut roots);
            for &x in &roots[..n] {
                if let Some(s) = none(x) {
                    emit(&s, col);
                }
            }
        }
        // acc0: parameter τ1.
        if tau_hi >= 0.0 {
            let acc0 = |t1: f64| -> Option<Seq> {
                let rad = amax * amax + (af * af - a0 * a0) / 2.0 + j * amax * t1 - j * dv;
                if rad < -tol * tol {
                    return None;
                }
                let al2 = sign * rad.max(0.0).sqrt();
                if al2 > amax + tol || al2 > af + tol || al2 < -a2 - tol {
                    return None;
                }
                let mut s = Seq::new();
                s.add((amax - a0) / j, j);
                s.add(t1, 0.0);
                s.add((amax - al2) / j, -j);
                s.add((af - al2) / j, j);
                Some(s)
            };
            let mut f = |x: f64| acc0(x).map(|s| s.displacement(v0, a0) - d);
            // rad = c0 + j·amax·τ1 must lie in [l, u].
            let c0 = amax * amax + (af * af - a0 * a0) / 2.0 - j * dv;
            let (l, u) = if sign > 0.0 {
                (0.0, if af < 0.0 { -1.0 } else { amax.min(af).powi(2) })
            } else {
                (if af < 0.0 { af * af } else { 0.0 }, a2 * a2)
            };
            let lo = ((l - c0) / (j * amax)).max(0.0);
            let hi = ((u - c0) / (j * amax)).min(tau_hi);
            let n = if lo <= hi {
                find_roots_coarse(&mut f, lo, hi, &mut roots)
            } else {
                0
            };
            for &x in &roots[..n] {
                if let Some(s) = acc0(x) {
                    emit(&s, col);
                }
            }
        }
    }
    // acc1: parameter α1.
    let acc1 = |x: f64| -> Option<Seq> {
        let t2 = ((2.0 * x * x - a0 * a0 - 2.0 * a2 * a2 + af * af) / (2.0 * j) - dv) / a2;
        if t2 < 0.0 || af < -a2 - tol {
            return None;
        }
        let mut s = Seq::new();
        s.add((x - a0) / j, j);
        s.add((x + a2) / j, -j);
        s.add(t2, 0.0);
        s.add((af + a2) / j, j);
        Some(s)
    };
    let mut f = |x: f64| acc1(x).map(|s| s.displacement(v0, a0) - d);
    // τ2 ≥ 0 ⇔ x² ≥ l.
    let l = (2.0 * j * dv + a0 * a0 + 2.0 * a2 * a2 - af * af) / 2.0;
    for (lo, hi) in square_window(l.max(0.0), f64::INFINITY, a0c, amax, true, tol) {
        let n = find_roots_coarse(&mut f, lo, hi, &mut roots);
        for &x in &roots[..n] {
            if let Some(s) = acc1(x) {
                emit(&s, col);
            }
        }
    }
    // acc0_acc1: parameter τ1.
    if tau_hi >= 0.0 {
        let acc01 = |t1: f64| -> Option<Seq> {
            let t2 = ((2.0 * amax * amax - a0 * a0 - 2.0 * a2 * a2 + af * af) / (2.0 * j)
                + amax * t1
                - dv)
                / a2;
            if t2 < 0.0 {
                return None;
            }
            let mut s = Seq::new();
            s.add((amax - a0) / j, j);
            s.add(t1, 0.0);
            s.add((amax + a2) / j, -j);
            s.add(t2, 0.0);
            s.add((af + a2) / j, j);
            Some(s)
        };
        let mut f = |x: f64| acc01(x).map(|s| s.displacement(v0, a0) - d);
        let lo = ((dv - (2.0 * amax * amax - a0 * a0 - 2.0 * a2 * a2 + af * af) / (2.0 * j))
            / amax)
            .max(0.0);
        let n = if lo <= tau_hi {
            find_roots_coarse(&mut f, lo, tau_hi, &mut roots)
        } else {
            0
        };
        for &x in &roots[..n] {
            if let Some(s) = acc01(x) {
                emit(&s, col);
            }
        }
    }
}

/// The parts of `[lo, hi]` where x² ∈ [l, u]: up to two intervals (the negative one only
/// when `neg_ok`). Bounds are widened by `tol` so that edge roots survive round-off.
fn square_window(
    l: f64,
    u: f64,
    lo: f64,
    hi: f64,
    neg_ok: bool,
    tol: f64,
) -> impl Iterator<Item = (f64, f64)> {
    let mut out = [(1.0, 0.0); 2];
    if l <= u && u >= 0.0 {
        let (r0, r1) = (l.max(0.0).sqrt(), u.sqrt());
        let (a, b) = ((r0 - tol).max(lo), (r1 + tol).min(hi));
        if a <= b {
            out[0] = (a, b);
        }
        if neg_ok {
            let (a, b) = ((-r1 - tol).max(lo), (-r0 + tol).min(hi));
            if a <= b {
                out[1] = (a, b);
            }
        }
    }
    out.into_iter().filter(|(a, b)| a <= b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rest_to_rest_closed_form_matches_the_enumeration() {
        // The closed form against the families it replaces (cruise and the closed families,
        // both directions), on seeded random limits and distances, direction-dependent
        // limits included.
        let mut r = crate::rng::SplitMix64::new(17);
        let (mut cruise, mut peak, mut plateau, mut fell_back) = (0, 0, 0, 0);
        for k in 0..6000 {
            let vmax = r.uniform(0.05, 3.0);
            let amax = r.uniform(0.2, 20.0);
            let jmax = 10f64.powf(r.uniform(-1.0, 4.5));
            let dist = r.uniform(-2.0, 2.0) * 10f64.powf(r.uniform(-4.0, 1.0));
            let mut d = Dof1::rest_to_rest(0.3, 0.3 + dist, vmax, amax, jmax);
            if k % 2 == 1 {
                d.vmin = -r.uniform(0.05, 3.0);
            }
            if k % 4 >= 2 {
                d.amin = -r.uniform(0.2, 20.0);
            }
            let mut pr = Profile::default();
            let fast = rest_to_rest(&d, &mut pr);
            let (mut out, mut own) = (Profile::default(), None);
            let mut col = Collector::new(&d, &mut out, &mut own, false);
            let mut cruised = false;
            for mirror in [false, true] {
                let q = if mirror { d.mirrored() } else { d };
                cruised |= vel_family(&q, mirror, &mut col).is_some();
                closed_families(&q, mirror, &mut col);
            }
            let t_enum = col
                .best()
                .expect("the enumeration finds a profile")
                .duration();
            let Some(()) = fast else {
                // Only asymmetric acceleration limits without a cruise are left to the
                // enumeration.
                assert!(d.amax != -d.amin && !cruised, "{d:?}");
                fell_back += 1;
                continue;
            };
            assert!(verify(&d, &pr));
            let t = pr.duration();
            assert!(
                (t - t_enum).abs() <= 1e-12 * t_enum,
                "{d:?}: {t} vs {t_enum}"
            );
            let (lo, hi) = pr.velocity_range();
            let v_peak = if dist > 0.0 { hi } else { -lo };
            let v_lim = if dist > 0.0 { d.vmax } else { -d.vmin };
            if cruised {
                cruise += 1;
                assert!((v_peak - v_lim).abs() <= 1e-12 * v_lim);
            } else {
                peak += 1;
                assert!(v_peak < v_lim);
                let (alo, ahi) = pr.acceleration_range();
                if ahi.max(-alo) >= d.amax * (1.0 - 1e-12) {
                    plateau += 1;
                }
            }
        }
        // Every case was exercised.
        assert!(cruise > 500 && peak > 500 && plateau > 100 && fell_back > 100);
        assert!(peak > plateau);
    }

    #[test]
    fn seed_example_trapezoid_and_scurve() {
        let tr = step1(&Dof1::rest_to_rest(0.0, 1.0, 0.6, 1.0, f64::INFINITY)).unwrap();
        assert!(
            (tr.t_min() - (1.0 / 0.6 + 0.6)).abs() < 1e-12,
            "{}",
            tr.t_min()
        );
        let sc = step1(&Dof1::rest_to_rest(0.0, 1.0, 0.6, 1.0, 4.0)).unwrap();
        assert!(
            (sc.t_min() - (1.0 / 0.6 + 0.6 + 0.25)).abs() < 1e-12,
            "{}",
            sc.t_min()
        );
        let fo = step1(&Dof1::rest_to_rest(0.0, 1.0, 0.6, f64::INFINITY, 4.0)).unwrap();
        assert!((fo.t_min() - 1.0 / 0.6).abs() < 1e-12);
    }
}
