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
//! [`super::families`]), solved by [`crate::roots::poly_roots`]. In the none family
//! (α₁² − α₂² = K) the parameter is the level of smaller magnitude (α₂, through the
//! time-reversed problem, when K ≥ 0), since the other level carries the parameter's rounding
//! error amplified by their ratio; a root that still misses the target by more than a quarter
//! of the tolerance is polished by Newton steps in the middle ramp's duration, and α₂ just
//! past a_f or a_min is snapped to it. At K = 0 the single ramp a₀ ↗ a_f is a candidate (the
//! polynomial vanishes identically on that branch), and a window end where a closed family's
//! polynomial vanishes to round-off counts as a root (a double root at a zero-length ramp). Where
//! round-off still loses the none family's fastest root (levels next to each other, to a
//! bound or to zero), two rescues offer what beats the fastest so far: the profiles with a
//! level on a bound of its window (α₁ = a₀ or a_max, α₂ = a_f or a_min, the other level in
//! closed form, polished in the middle ramp's duration where that form is ill-conditioned and
//! misses), and, when a boundary level lies within 1e-3 of the acceleration range from
//! a bound, zero or the other (or K nearly vanishes), the family solved again in the middle
//! ramp's duration t, in which both levels are single-valued and the duration 2t + (a_f −
//! a₀)/j is linear, by sampling and refining its integrated position residual (sign changes
//! and tangent roots, `scan.rs`). The plateau families' roots (acc0, acc1) are put on their
//! window when just past it and polished by Newton steps on the integrated residual when it
//! is above round-off, so that a near-double root's imprecision does not cost a few 1e-9 of
//! the duration; an end of their window where the polynomial (the position residual itself)
//! is within the rounding of p_f − p₀ of zero counts as a root too (that rounding can move the
//! root just past it). The up-down-up-down shapes
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
//! when their velocity range, bounded by the start's dip and the target's approach (and the
//! start and target velocities themselves), has no velocity on the side of the displacement
//! (`Collector::cannot_cover`).
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

mod closed;
mod collector;
mod fallback;
#[cfg(test)]
mod modes_tests;
mod rest;
mod scan;
mod verify;

use super::brake::brake;
use super::families::two_changes;
use super::problem::{ControlInterface, Dof1, ProfileOrder};
use super::profile::{Profile, State1};
use super::velocity_change::{each_change3, fastest, kink, push_change};
use super::zero::{coast_into, coasts};
use closed::{closed_families, vel_family};
use fallback::{cruise_family, peak_family, third_families};
use rest::rest_to_rest;

pub(crate) use collector::Collector;
pub(crate) use rest::RestShape;
pub(crate) use verify::{positions_within, velocity_cap, velocity_window, verify};
pub use verify::{TOL_LIMIT, TOL_POSITION, TOL_VELOCITY};

/// Largest number of candidate durations kept per degree of freedom.
pub(crate) const MAX_CANDIDATES: usize = 24;

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
    if dof.has_position_limits() {
        return super::position::step1_limited(dof, profile, spare, Some(cand));
    }
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
    if dof.has_position_limits() {
        return super::position::step1_limited(dof, profile, spare, None).map(|_| ());
    }
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
pub(crate) fn step1_run(
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
        (ProfileOrder::Third, ControlInterface::Velocity) => {
            // Every two-ramp change: the fastest is the minimum, the others bound the
            // durations this DOF cannot take (blocked intervals), for synchronization.
            each_change3(
                dof.v0,
                dof.a0,
                dof.vf,
                dof.af,
                dof.jmax,
                dof.amax,
                dof.amin,
                |c| {
                    let mut pr = Profile::new(start);
                    push_change(&mut pr, ProfileOrder::Third, &c, dof.v0);
                    col.offer(&pr);
                },
            );
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
        (ProfileOrder::Third, ControlInterface::Position) => third_position(dof, col),
    }
}

/// Third order, position interface: the cruise family first (in fastest-only mode the
/// direction of the displacement first; a valid cruise can end the search), then the closed
/// families and the two-change shapes ([`closed_and_two_changes`]), and the bracketing
/// fallback when those find nothing.
#[inline(always)]
fn third_position(dof: &Dof1, col: &mut Collector<'_>) {
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
            if share.is_some_and(|c| c > 1e-4) && col.fastest_only && cruise_is_optimal(&q) {
                return;
            }
        }
    }
    if cruise && dof.vf == 0.0 && dof.af == 0.0 {
        return;
    }
    closed_and_two_changes(dof, dirs, col);
    if col.best().is_some() {
        return;
    }
    // Fallback for degenerate cases the closed forms miss: the bracketing solver on the same
    // families, and the peak family over the whole velocity range.
    for mirror in [false, true] {
        let q = if mirror { dof.mirrored() } else { *dof };
        third_families(&q, mirror, col);
    }
    peak_family(dof, col);
}

/// The closed families of both directions (in the order `dirs`), and the two-change shapes
/// where the target moves.
#[inline(always)]
fn closed_and_two_changes(dof: &Dof1, dirs: [bool; 2], col: &mut Collector<'_>) {
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
        // Both changes go up: the velocity stays between the start's dip (or the target
        // velocity, reached from above when a_f < 0 after a change up of next to nothing)
        // and the target's approach from above (or the start velocity, left downwards when
        // a₀ < 0).
        let j2 = 2.0 * q.jmax;
        let v_low = (q.v0 - q.a0.min(0.0).powi(2) / j2).min(q.vf);
        let v_high = (q.vf + q.af.min(0.0).powi(2) / j2).max(q.v0);
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

#[cfg(test)]
mod tests {
    use super::*;

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
