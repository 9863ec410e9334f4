//! Phase synchronization: Ruckig's, and trajkit's fastest straight line.
//!
//! **`Synchronization::Phase`** is Ruckig's: the duration is the time-synchronized one (found
//! by [`super::sync`] exactly as for `Synchronization::Time`), and when the boundary states
//! are collinear — the same test as Ruckig's, on the displacement (or the first non-zero
//! boundary vector) with Ruckig's absolute tolerance of one machine epsilon — every
//! phase-synchronized DOF gets the limiting DOF's profile scaled by its share of the motion
//! (its displacement over the limiting DOF's). The limiting DOF is the one whose minimum
//! duration (or blocked-interval edge) is the synchronized duration. The scaled profiles are
//! accepted only if each passes the DOF's own verification (target, velocity and
//! acceleration limits) and its jerk stays within the DOF's jerk limit; otherwise, or when the
//! duration was set by `minimum_duration`, when a DOF starts with a brake, when the DOFs'
//! profile orders differ, or when some DOF is time-synchronized (Ruckig then re-plans every
//! DOF for the duration), the time-synchronized profiles stay. With discrete durations the
//! scaled profiles are the limiting DOF's time-optimal one, which ends before the rounded
//! duration and then holds the target state (as in Ruckig).
//!
//! **`Synchronization::StraightLine`** is trajkit's own: one path-coordinate problem
//! s: 0 → 1 whose limits are the tightest of the joints' limits divided by the joints'
//! displacements, scaled onto every joint. The motion is always a straight line in joint
//! space (when the boundary velocities and accelerations are parallel to the displacement;
//! otherwise time synchronization is used), and it is the fastest such line, which may take
//! longer than the time-synchronized optimum.
//!
//! Precision: every scaled profile passes the verification of [`super::step1::verify`].

use super::input::{DurationDiscretization, InputView, Synchronization};
use super::problem::{ControlInterface, Dof1};
use super::profile::Profile;
use super::result::OtgError;
use super::step1::{step1, verify};
use super::sync::{replan_into, Scratch, Solved};
use super::trajectory::DofTrajectory;

/// What phase synchronization reads besides the profiles.
pub(crate) struct PhaseCtx<'a, 'b> {
    pub view: &'a InputView<'b>,
    pub delta_time: f64,
    pub scratch: &'a [Scratch],
}

/// Ruckig's phase synchronization after time synchronization found duration `t` (the
/// profiles in `out`). Returns the trajectory's duration when it replaced the profiles of the
/// phase-synchronized DOFs by scaled copies of the limiting DOF's; `None` (with `out`
/// untouched) when it does not apply.
pub(crate) fn phase(ctx: &PhaseCtx<'_, '_>, out: &mut [DofTrajectory], t: f64) -> Option<f64> {
    let view = ctx.view;
    let n = view.dof();
    let sc = ctx.scratch;
    // Ruckig keeps phase profiles only when no DOF is time-synchronized.
    if (0..n).any(|i| {
        !matches!(
            view.sync_of(i),
            Synchronization::Phase | Synchronization::None
        )
    }) {
        return None;
    }
    let discrete = view.options.duration_discretization == DurationDiscretization::Discrete;
    let disc = |x: f64| {
        if discrete {
            (x / ctx.delta_time - 1e-9).ceil().max(0.0) * ctx.delta_time
        } else {
            x
        }
    };
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300);
    // The limiting DOF: its minimum duration, else one of its candidate durations, is t.
    let syncs = |i: usize| view.enabled[i] && view.sync_of(i) != Synchronization::None;
    let lim = (0..n)
        .find(|&i| syncs(i) && sc[i].solved != Solved::No && same(disc(sc[i].t_min), t))
        .or_else(|| {
            (0..n).find(|&i| {
                syncs(i)
                    && sc[i].solved == Solved::Full
                    && sc[i].cand[..sc[i].ncand].iter().any(|&c| same(disc(c), t))
            })
        })?;
    if view
        .options
        .minimum_duration
        .is_some_and(|m| m >= t && !same(disc(sc[lim].t_min), t))
    {
        return None;
    }
    let lambda = collinear_scales(view, lim)?;
    // The limiting DOF's profile: its time-optimal one when t is (the rounding of) its
    // minimum, else its profile at t.
    let at_min = same(disc(sc[lim].t_min), t);
    let lp = if at_min && !same(out[lim].profile.duration(), sc[lim].t_min) {
        step1(&sc[lim].dof)?.profile
    } else {
        out[lim].profile
    };
    let ld = &sc[lim].dof;
    if lp.brake_duration() > 0.0 {
        return None;
    }
    let phase_dof = |i: usize| view.enabled[i] && view.sync_of(i) == Synchronization::Phase;
    // Verify every scaled copy before writing any.
    for i in (0..n).filter(|&i| phase_dof(i) && i != lim) {
        let d = &sc[i].dof;
        if d.order() != ld.order() || d.interface != ld.interface || sc[i].brake {
            return None;
        }
        let q = scaled(&lp, lambda(i), d);
        if !jerk_within(&q, d.jmax) || !verify(d, &q) {
            return None;
        }
    }
    for i in (0..n).filter(|&i| phase_dof(i)) {
        let d = &sc[i].dof;
        out[i].profile = if i == lim {
            lp
        } else {
            scaled(&lp, lambda(i), d)
        };
    }
    Some(t)
}

/// The limiting profile `lp` scaled by `s` onto DOF `d`, from its own start state.
fn scaled(lp: &Profile, s: f64, d: &Dof1) -> Profile {
    let order = match d.order() {
        super::problem::ProfileOrder::First => 1,
        super::problem::ProfileOrder::Second => 2,
        super::problem::ProfileOrder::Third => 3,
    };
    let start = super::profile::State1 {
        p: d.p0,
        v: d.v0,
        a: d.a0,
    };
    lp.scaled_onto(s, start, order)
}

/// Whether every segment's jerk is within `jmax` (to Ruckig's slack of 1e-12 relative).
fn jerk_within(p: &Profile, jmax: f64) -> bool {
    (0..p.segments()).all(|k| {
        p.segment(k)
            .is_some_and(|(_, _, _, j)| j.abs() <= jmax * (1.0 + 1e-12))
    })
}

/// Ruckig's collinearity test of the phase-synchronized DOFs' boundary vectors; the scale of
/// each DOF relative to the limiting DOF `lim` (its component of the reference vector over
/// the limiting DOF's), or `None` when they are not collinear.
fn collinear_scales<'a>(view: &'a InputView<'_>, lim: usize) -> Option<impl Fn(usize) -> f64 + 'a> {
    const EPS: f64 = f64::EPSILON;
    let n = view.dof();
    let phase = |i: usize| view.sync_of(i) == Synchronization::Phase;
    let iface = |i: usize| view.iface.map_or(view.options.control_interface, |c| c[i]);
    let pd = |i: usize| view.tp[i] - view.cp[i];
    // The reference vector: the first non-zero of pd, v0, a0, vf, af at the first phase DOF
    // where one is non-zero.
    let vectors = |k: usize, i: usize| match k {
        0 => view.tp[i] - view.cp[i],
        1 => view.cv[i],
        2 => view.ca[i],
        3 => view.tv[i],
        _ => view.ta[i],
    };
    let mut reference = None;
    for i in (0..n).filter(|&i| phase(i)) {
        let k = if iface(i) == ControlInterface::Position && pd(i).abs() > EPS {
            Some(0)
        } else {
            (1..5).find(|&k| vectors(k, i).abs() > EPS)
        };
        if let Some(k) = k {
            reference = Some((k, i));
            break;
        }
    }
    let (k, s) = reference?;
    let vec = move |i: usize| vectors(k, i);
    let scale = vec(s);
    let pd_scale = pd(s) / scale;
    let v0_scale = view.cv[s] / scale;
    let vf_scale = view.tv[s] / scale;
    let a0_scale = view.ca[s] / scale;
    let af_scale = view.ta[s] / scale;
    let scale_lim = vec(lim);
    for i in (0..n).filter(|&i| phase(i)) {
        let c = vec(i);
        if (iface(i) == ControlInterface::Position && (pd(i) - pd_scale * c).abs() > EPS)
            || (view.cv[i] - v0_scale * c).abs() > EPS
            || (view.ca[i] - a0_scale * c).abs() > EPS
            || (view.tv[i] - vf_scale * c).abs() > EPS
            || (view.ta[i] - af_scale * c).abs() > EPS
        {
            return None;
        }
    }
    Some(move |i: usize| vec(i) / scale_lim)
}

/// trajkit's straight-line synchronization; `Ok(false)` when it does not apply (the caller
/// falls back to time synchronization).
pub(crate) fn straight_line(
    view: &InputView<'_>,
    delta_time: f64,
    out: &mut [DofTrajectory],
    scratch: &[Scratch],
) -> Result<bool, OtgError> {
    let n = view.dof();
    if view.options.control_interface != ControlInterface::Position {
        return Ok(false);
    }
    let Some(lam) = line_scales(view, scratch) else {
        return Ok(false);
    };
    let Some(sp) = path_profile(view, delta_time, &path_problem(view, scratch, lam)) else {
        return Ok(false);
    };
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

/// The boundary vectors of the enabled DOFs as multiples λ of their displacement u (v₀, a₀,
/// v_f, a_f = λ·u, one λ each for all DOFs), or `None` when they are not collinear or nothing
/// moves.
fn line_scales(view: &InputView<'_>, scratch: &[Scratch]) -> Option<[f64; 4]> {
    let n = view.dof();
    let moves = (0..n).any(|i| view.enabled[i] && scratch[i].dof.pf != scratch[i].dof.p0);
    if !moves {
        return None;
    }
    let mut lam = [0.0f64; 4];
    let mut lam_set = [false; 4];
    for i in (0..n).filter(|&i| view.enabled[i]) {
        let d = &scratch[i].dof;
        let u = d.pf - d.p0;
        for (k, x) in [d.v0, d.a0, d.vf, d.af].into_iter().enumerate() {
            if u == 0.0 {
                if x != 0.0 {
                    return None;
                }
                continue;
            }
            let l = x / u;
            if lam_set[k] {
                if (l - lam[k]).abs() > 1e-12 * (l.abs().max(lam[k].abs())).max(1e-300) {
                    return None;
                }
            } else {
                lam[k] = l;
                lam_set[k] = true;
            }
        }
    }
    Some(lam)
}

/// The path-coordinate problem s: 0 → 1 (displacement u_i = pf_i − p0_i of each DOF): the
/// tightest of the joints' limits divided by their displacements, boundary states `lam`.
fn path_problem(view: &InputView<'_>, scratch: &[Scratch], lam: [f64; 4]) -> Dof1 {
    let (mut vmax, mut vmin, mut amax, mut amin, mut jmax) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
    );
    for i in 0..view.dof() {
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
    Dof1 {
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
    }
}

/// The path coordinate's profile: time-optimal, or of the minimum or discretized duration
/// the options ask for; `None` when there is none or it starts with a brake.
fn path_profile(view: &InputView<'_>, delta_time: f64, s: &Dof1) -> Option<Profile> {
    let s1 = step1(s)?;
    let discrete = view.options.duration_discretization == DurationDiscretization::Discrete;
    let mut t = s1.t_min().max(view.options.minimum_duration.unwrap_or(0.0));
    if discrete {
        t = (t / delta_time - 1e-9).ceil().max(0.0) * delta_time;
    }
    let mut sc = Scratch {
        dof: *s,
        cand: s1.cand,
        ncand: s1.ncand,
        t_min: s1.t_min(),
        sync: true,
        solved: Solved::Full,
        step1_in_out: false,
        step1_kept: true,
        brake: s1.profile.brake_duration() != 0.0,
        bound: f64::INFINITY,
    };
    let mut sp = Profile::default();
    if !replan_into(&mut sc, &mut Some(s1.profile), t, &mut sp) || sp.brake_duration() > 0.0 {
        return None;
    }
    Some(sp)
}
