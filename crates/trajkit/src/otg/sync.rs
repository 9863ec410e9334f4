//! Synchronization: one duration for all degrees of freedom, then step 2 for each.
//!
//! After step 1 every enabled degree of freedom has its minimum duration and the durations of
//! all its other valid candidate profiles. A non-zero target velocity can make a range of
//! durations impossible for a degree of freedom (a *blocked interval*: it cannot be slowed down
//! a little, only a lot); its edges are durations of step-1 candidates. The synchronized
//! duration is found by trying, in increasing order, the largest minimum duration (and the
//! minimum duration option) and then every candidate duration above it, rounded up to a
//! multiple of the control period when the duration is discrete; the first duration at which
//! step 2 succeeds for every degree of freedom wins. If the candidates run out, durations
//! growing geometrically from the last one are tried, so a valid (if not provably shortest)
//! synchronized trajectory is still found whenever step 2 can produce one.
//!
//! Precision: every per-DOF profile passes step 1's or step 2's verification (target within
//! 1e-8 / 1e-10, limits within 1e-12 relative, duration within 1e-12 relative of the common
//! one). A duration found by bisection is the edge of the feasible range to 64 halvings (or to
//! adjacent floating-point numbers, or to one control period for discrete durations).
//!
//! Phase synchronization solves one path-coordinate problem s: 0 → 1 whose limits are the
//! tightest of the joints' limits divided by the joints' displacements, and scales it onto
//! every joint: the motion is a straight line in joint space. It applies when the start and
//! target velocities and accelerations are parallel to the displacement; otherwise time
//! synchronization is used.

use super::input::{DurationDiscretization, InputView, Synchronization};
use super::problem::{ControlInterface, Dof1};
use super::profile::{Profile, State1};
use super::result::OtgResult;
use super::step1::{step1, step1_into, verify, MAX_CANDIDATES};
use super::step2::{step2, step2_into};
use super::trajectory::DofTrajectory;

/// Per-DOF spare profile of the calculation: step 1's second working buffer, then the slot
/// the time-optimal profile is copied to before step 2 overwrites the output (see
/// `Scratch::step1_in_out`). Kept apart from [`Scratch`] and created on first use, so that a
/// calculation that never needs it neither initialises nor copies 700 bytes per DOF.
pub type Spare = Option<Profile>;

/// Per-DOF scratch space of the calculation (kept by the caller so that a compile-time number
/// of degrees of freedom needs no allocation).
#[derive(Debug, Clone, Copy)]
pub struct Scratch {
    pub(crate) dof: Dof1,
    pub(crate) cand: [f64; MAX_CANDIDATES],
    pub(crate) ncand: usize,
    pub(crate) t_min: f64,
    pub(crate) sync: bool,
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
}

impl Default for Scratch {
    fn default() -> Self {
        Scratch {
            dof: Dof1::rest_to_rest(0.0, 0.0, 1.0, 1.0, 1.0),
            cand: [0.0; MAX_CANDIDATES],
            ncand: 0,
            t_min: 0.0,
            sync: false,
            step1_in_out: false,
            step1_kept: false,
            brake: false,
        }
    }
}

/// Computes all profiles; returns the trajectory duration.
pub(crate) fn calculate(
    view: &InputView<'_>,
    delta_time: f64,
    out: &mut [DofTrajectory],
    scratch: &mut [Scratch],
    spare: &mut [Spare],
) -> Result<f64, OtgResult> {
    view.check_shape(delta_time)?;
    let n = view.dof();
    if out.len() < n || scratch.len() < n || spare.len() < n {
        return Err(OtgResult::InvalidInput {
            dof: usize::MAX,
            field: "current_position",
            value: n as f64,
            reason: "is the length of this vector, larger than the output storage",
        });
    }
    for i in 0..n {
        scratch[i].dof = view.dof_problem(i)?;
    }
    let opts = view.options;
    let discrete = opts.duration_discretization == DurationDiscretization::Discrete;
    let disc = |t: f64| {
        if discrete {
            (t / delta_time - 1e-9).ceil().max(0.0) * delta_time
        } else {
            t
        }
    };
    let min_dur = opts.minimum_duration.unwrap_or(0.0);

    // Step 1 for every enabled DOF.
    let mut t_lead = 0.0f64;
    for i in 0..n {
        let d = scratch[i].dof;
        if !view.enabled[i] {
            out[i] = DofTrajectory {
                profile: Profile::new(State1 {
                    p: d.p0,
                    v: d.v0,
                    a: d.a0,
                }),
                independent_min_duration: 0.0,
            };
            scratch[i].sync = false;
            continue;
        }
        let sc = &mut scratch[i];
        // The spare profile is free while the step-1 profile is in the output.
        sc.ncand = step1_into(&d, &mut out[i].profile, &mut spare[i], &mut sc.cand)
            .ok_or(OtgResult::CalculationFailed { dof: i })?;
        sc.step1_in_out = true;
        sc.step1_kept = false;
        sc.brake = out[i].profile.brake_duration() != 0.0;
        sc.t_min = out[i].profile.duration();
        sc.sync = match opts.synchronization {
            Synchronization::Time | Synchronization::Phase => true,
            Synchronization::TimeIfNecessary => d.vf != 0.0 || d.af != 0.0,
            Synchronization::None => false,
        };
        out[i].independent_min_duration = sc.t_min;
        t_lead = t_lead.max(sc.t_min);
    }

    if opts.synchronization == Synchronization::Phase && phase(view, delta_time, out, scratch)? {
        return Ok(duration_of(&out[..n]));
    }

    // Degrees of freedom that are not synchronized still honour the minimum duration and the
    // discretization on their own.
    for i in 0..n {
        if view.enabled[i] && !scratch[i].sync {
            let t = disc(scratch[i].t_min.max(min_dur));
            if t > scratch[i].t_min
                && !replan_into(&mut scratch[i], &mut spare[i], t, &mut out[i].profile)
            {
                return Err(OtgResult::SynchronizationFailed {
                    dof: i,
                    duration: t,
                });
            }
        }
    }

    if scratch[..n].iter().any(|s| s.sync) {
        let t_lead = if opts.synchronization == Synchronization::TimeIfNecessary {
            t_lead
        } else {
            scratch[..n]
                .iter()
                .filter(|s| s.sync)
                .fold(0.0f64, |m, s| m.max(s.t_min))
        };
        let mut t = disc(t_lead.max(min_dur));
        let mut failed = 0;
        let mut grow = 0;
        let mut last_fail: Option<f64> = None;
        for _attempt in 0..200 {
            if !(t.is_finite() && t < 1e300) {
                break;
            }
            match try_all(scratch, spare, out, n, t) {
                Ok(()) => {
                    // A missing candidate could hide a shorter feasible duration between the
                    // last failure and t: bisect for the edge of the feasible range.
                    if let Some(mut lo) = last_fail {
                        let mut hi = t;
                        let mut last_ok = true;
                        for _ in 0..64 {
                            let mid = disc(0.5 * (lo + hi));
                            if mid <= lo || mid >= hi {
                                break;
                            }
                            last_ok = try_all(scratch, spare, out, n, mid).is_ok();
                            if last_ok {
                                hi = mid;
                            } else {
                                lo = mid;
                            }
                        }
                        // A failed attempt leaves `out` partly written: redo the last success.
                        if !last_ok && try_all(scratch, spare, out, n, hi).is_err() {
                            return Err(OtgResult::SynchronizationFailed {
                                dof: failed,
                                duration: hi,
                            });
                        }
                    }
                    return Ok(duration_of(&out[..n]));
                }
                Err(i) => {
                    failed = i;
                    last_fail = Some(t);
                }
            }
            // Next candidate duration above t.
            let mut next = f64::INFINITY;
            for s in scratch[..n].iter().filter(|s| s.sync) {
                for &c in &s.cand[..s.ncand] {
                    let c = disc(c);
                    if c > t && c < next {
                        next = c;
                    }
                }
            }
            if next.is_infinite() {
                grow += 1;
                next = disc(t * (1.0 + 1e-6 * 4f64.powi(grow.min(20))));
                if next <= t {
                    next = t + if discrete {
                        delta_time
                    } else {
                        t.max(1e-9) * 1e-6
                    };
                }
            }
            t = next;
        }
        return Err(OtgResult::SynchronizationFailed {
            dof: failed,
            duration: t,
        });
    }
    Ok(duration_of(&out[..n]))
}

fn duration_of(out: &[DofTrajectory]) -> f64 {
    out.iter().fold(0.0f64, |m, d| m.max(d.profile.duration()))
}

/// Re-plans one DOF for total duration `t` (brake kept) into `out`, its output profile; the
/// step-1 profile when `t` is its minimum. False (and `out` unspecified) when no profile was
/// found.
fn replan_into(s: &mut Scratch, spare: &mut Spare, t: f64, out: &mut Profile) -> bool {
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

/// Step 2 for every synchronized DOF at duration `t`, written into `out`; the failing DOF on
/// error (then the synchronized entries of `out` are partly overwritten).
fn try_all(
    scratch: &mut [Scratch],
    spare: &mut [Spare],
    out: &mut [DofTrajectory],
    n: usize,
    t: f64,
) -> Result<(), usize> {
    for i in 0..n {
        if !scratch[i].sync {
            continue;
        }
        if t < scratch[i].t_min {
            return Err(i);
        }
        if !replan_into(&mut scratch[i], &mut spare[i], t, &mut out[i].profile) {
            return Err(i);
        }
    }
    Ok(())
}

/// Phase synchronization; `Ok(false)` when it does not apply (the caller falls back to time
/// synchronization).
fn phase(
    view: &InputView<'_>,
    delta_time: f64,
    out: &mut [DofTrajectory],
    scratch: &[Scratch],
) -> Result<bool, OtgResult> {
    let n = view.dof();
    if view.options.control_interface != ControlInterface::Position {
        return Ok(false);
    }
    // Reference direction: the displacement.
    let mut norm = 0.0f64;
    for i in 0..n {
        if view.enabled[i] {
            let d = &scratch[i].dof;
            norm = norm.max((d.pf - d.p0).abs());
        }
    }
    if norm == 0.0 {
        return Ok(false);
    }
    // Collinearity: each boundary vector must be λ·u with one λ for all DOFs.
    let mut lam = [0.0f64; 4];
    let mut lam_set = [false; 4];
    let mut lead = usize::MAX;
    for i in 0..n {
        if !view.enabled[i] {
            continue;
        }
        let d = &scratch[i].dof;
        let u = d.pf - d.p0;
        if lead == usize::MAX || u.abs() > (scratch[lead].dof.pf - scratch[lead].dof.p0).abs() {
            lead = i;
        }
        for (k, x) in [d.v0, d.a0, d.vf, d.af].into_iter().enumerate() {
            if u == 0.0 {
                if x != 0.0 {
                    return Ok(false);
                }
                continue;
            }
            let l = x / u;
            if lam_set[k] {
                if (l - lam[k]).abs() > 1e-12 * (l.abs().max(lam[k].abs())).max(1e-300) {
                    return Ok(false);
                }
            } else {
                lam[k] = l;
                lam_set[k] = true;
            }
        }
    }
    // The path-coordinate problem s: 0 → 1 (displacement u_i = pf_i − p0_i).
    let (mut vmax, mut vmin, mut amax, mut amin, mut jmax) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
    );
    for i in 0..n {
        let d = &scratch[i].dof;
        let u = d.pf - d.p0;
        if !view.enabled[i] || u == 0.0 {
            continue;
        }
        let (vp, vn, ap, an) = if u > 0.0 {
            (d.vmax / u, d.vmin / u, d.amax / u, d.amin / u)
        } else {
            (d.vmin / u, d.vmax / u, d.amin / u, d.amax / u)
        };
        vmax = vmax.min(vp);
        vmin = vmin.max(vn);
        amax = amax.min(ap);
        amin = amin.max(an);
        jmax = jmax.min(d.jmax / u.abs());
    }
    let s = Dof1 {
        p0: 0.0,
        v0: lam[0],
        a0: lam[1],
        pf: 1.0,
        vf: lam[2],
        af: lam[3],
        vmax,
        vmin,
        amax,
        amin,
        jmax,
        interface: ControlInterface::Position,
    };
    let Some(s1) = step1(&s) else {
        return Ok(false);
    };
    let discrete = view.options.duration_discretization == DurationDiscretization::Discrete;
    let mut t = s1.t_min().max(view.options.minimum_duration.unwrap_or(0.0));
    if discrete {
        t = (t / delta_time - 1e-9).ceil().max(0.0) * delta_time;
    }
    let mut sc = Scratch {
        dof: s,
        cand: s1.cand,
        ncand: s1.ncand,
        t_min: s1.t_min(),
        sync: true,
        step1_in_out: false,
        step1_kept: true,
        brake: s1.profile.brake_duration() != 0.0,
    };
    let mut sp = Profile::default();
    if !replan_into(&mut sc, &mut Some(s1.profile), t, &mut sp) {
        return Ok(false);
    }
    if sp.brake_duration() > 0.0 {
        return Ok(false);
    }
    // Scale onto every DOF and verify each.
    for i in 0..n {
        if !view.enabled[i] {
            continue;
        }
        let d = &scratch[i].dof;
        if !verify(d, &sp.scaled_from(d.pf - d.p0, d.p0)) {
            return Ok(false);
        }
    }
    for i in 0..n {
        if view.enabled[i] {
            let d = &scratch[i].dof;
            out[i].profile = sp.scaled_from(d.pf - d.p0, d.p0);
        }
    }
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Step 1 into an output profile, as `calculate` does; returns the scratch, the spare and
    /// a copy of the step-1 profile.
    fn setup(d: Dof1, out: &mut Profile) -> (Scratch, Spare, Profile) {
        let mut s = Scratch {
            dof: d,
            ..Scratch::default()
        };
        let mut spare = None;
        s.ncand = step1_into(&d, out, &mut spare, &mut s.cand).unwrap();
        s.step1_in_out = true;
        s.step1_kept = false;
        s.brake = out.brake_duration() != 0.0;
        s.t_min = out.duration();
        s.sync = true;
        (s, spare, *out)
    }

    #[test]
    fn back_at_the_minimum_duration_the_step1_profile_returns() {
        // Without a brake (the step-1 profile is not kept but calculated again) and with one
        // (it is copied aside before step 2).
        let rest = Dof1::rest_to_rest(0.1, 1.3, 1.0, 2.0, 10.0);
        let mut braking = Dof1::rest_to_rest(0.1, 1.3, 1.0, 2.0, 10.0);
        braking.v0 = 1.6;
        braking.a0 = 0.5;
        for (d, has_brake) in [(rest, false), (braking, true)] {
            let mut out = Profile::default();
            let (mut s, mut spare, first) = setup(d, &mut out);
            assert_eq!(s.brake, has_brake);
            let t = 1.5 * s.t_min;
            assert!(replan_into(&mut s, &mut spare, t, &mut out));
            assert!((out.duration() - t).abs() <= 1e-12 * t);
            assert!(out != first);
            if has_brake {
                assert_eq!(out.brake_duration(), first.brake_duration());
            }
            let t_min = s.t_min;
            assert!(replan_into(&mut s, &mut spare, t_min, &mut out));
            assert_eq!(out, first);
            // And step 2 again from there.
            assert!(replan_into(&mut s, &mut spare, t, &mut out));
            assert!((out.duration() - t).abs() <= 1e-12 * t);
        }
    }
}
