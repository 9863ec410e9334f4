//! Shared by the otg test binaries: seeded random problems by category, the invariant check
//! of every solved case, and the conversion to rsruckig's input.
#![allow(dead_code)]

use trajkit::otg::{
    ControlInterface, DurationDiscretization, FixedTrajectory, InputParameter, Synchronization,
};
use trajkit::rng::SplitMix64;

/// Problem categories of the random suites.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cat {
    RestToRest,
    General,
    BeyondLimits,
    TargetVelocity,
    TargetAtVmax,
    Tiny,
    Huge,
    Identical,
    Directional,
    BigLimits,
    SecondOrder,
    VelocityInterface,
    Phase,
    Discrete,
}

pub const ALL: [Cat; 14] = [
    Cat::RestToRest,
    Cat::General,
    Cat::BeyondLimits,
    Cat::TargetVelocity,
    Cat::TargetAtVmax,
    Cat::Tiny,
    Cat::Huge,
    Cat::Identical,
    Cat::Directional,
    Cat::BigLimits,
    Cat::SecondOrder,
    Cat::VelocityInterface,
    Cat::Phase,
    Cat::Discrete,
];

pub fn uni(r: &mut SplitMix64, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * r.next_f64()
}

fn logu(r: &mut SplitMix64, lo: f64, hi: f64) -> f64 {
    (lo.ln() + (hi.ln() - lo.ln()) * r.next_f64()).exp()
}

/// A random state (v, a) inside the limits, with v + a|a|/(2j) also inside.
fn inside(r: &mut SplitMix64, vmax: f64, vmin: f64, amax: f64, amin: f64, j: f64) -> (f64, f64) {
    for _ in 0..100 {
        let v = uni(r, vmin, vmax);
        let a = uni(r, amin, amax);
        let stop = v + a * a.abs() / (2.0 * j);
        let before = v - a * a.abs() / (2.0 * j);
        if stop <= vmax && stop >= vmin && before <= vmax && before >= vmin {
            return (v, a);
        }
    }
    (0.0, 0.0)
}

/// A random problem of category `cat`.
pub fn problem<const N: usize>(r: &mut SplitMix64, cat: Cat) -> InputParameter<N> {
    let mut inp = InputParameter::<N>::new();
    let big = cat == Cat::BigLimits;
    for i in 0..N {
        let (vmax, amax, jmax) = if big {
            (logu(r, 1.0, 1e6), logu(r, 1.0, 1e6), logu(r, 1.0, 1e6))
        } else {
            (logu(r, 0.1, 5.0), logu(r, 0.1, 10.0), logu(r, 0.1, 100.0))
        };
        let (vmin, amin) = if cat == Cat::Directional {
            (-logu(r, 0.1, 5.0), -logu(r, 0.1, 10.0))
        } else {
            (-vmax, -amax)
        };
        inp.max_velocity[i] = vmax;
        inp.max_acceleration[i] = amax;
        inp.max_jerk[i] = jmax;
        if cat == Cat::Directional {
            inp.min_velocity.get_or_insert([0.0; N])[i] = vmin;
            inp.min_acceleration.get_or_insert([0.0; N])[i] = amin;
        }
        inp.current_position[i] = uni(r, -5.0, 5.0);
        inp.target_position[i] = uni(r, -5.0, 5.0);
        match cat {
            Cat::RestToRest | Cat::BigLimits | Cat::Directional if r.next_f64() < 0.5 => {}
            Cat::RestToRest => {}
            Cat::General
            | Cat::BigLimits
            | Cat::Directional
            | Cat::Discrete
            | Cat::VelocityInterface => {
                // Large limits: keep the states where stopping takes at most ~1e3 units of
                // distance, so that 1e-8 absolute position accuracy stays representable in f64
                // (a 1e9-unit detour cannot end within 1e-8 of its target).
                let (vmax, vmin) = if big {
                    let cap = (2.0 * amax * 1e3).sqrt().min((jmax * 1e6).cbrt());
                    (vmax.min(cap), vmin.max(-cap))
                } else {
                    (vmax, vmin)
                };
                let (v, a) = inside(r, vmax, vmin, amax, amin, jmax);
                inp.current_velocity[i] = v;
                inp.current_acceleration[i] = a;
                let (v, a) = inside(r, vmax, vmin, amax, amin, jmax);
                inp.target_velocity[i] = v;
                inp.target_acceleration[i] = a;
            }
            Cat::BeyondLimits => {
                inp.current_velocity[i] = uni(r, -2.0, 2.0) * vmax;
                inp.current_acceleration[i] = uni(r, -2.0, 2.0) * amax;
                if r.next_f64() < 0.5 {
                    let (v, a) = inside(r, vmax, vmin, amax, amin, jmax);
                    inp.target_velocity[i] = v;
                    inp.target_acceleration[i] = a;
                }
            }
            Cat::TargetVelocity => {
                inp.target_velocity[i] = uni(r, vmin, vmax);
            }
            Cat::TargetAtVmax => {
                inp.target_velocity[i] = if r.next_f64() < 0.5 { vmax } else { vmin };
            }
            Cat::Tiny => {
                let d = logu(r, 1e-12, 1e-4) * if r.next_f64() < 0.5 { -1.0 } else { 1.0 };
                inp.target_position[i] = inp.current_position[i] + d;
                if r.next_f64() < 0.5 {
                    inp.current_velocity[i] = uni(r, -1.0, 1.0) * logu(r, 1e-20, 1e-10);
                    inp.target_velocity[i] = uni(r, -1.0, 1.0) * logu(r, 1e-20, 1e-10);
                }
            }
            Cat::Huge => {
                inp.target_position[i] = uni(r, -1e4, 1e4);
            }
            Cat::Identical => {
                inp.target_position[i] = inp.current_position[i];
                if r.next_f64() < 0.5 {
                    let (v, a) = inside(r, vmax, vmin, amax, amin, jmax);
                    inp.current_velocity[i] = v;
                    inp.target_velocity[i] = v;
                    inp.current_acceleration[i] = a;
                    inp.target_acceleration[i] = a;
                }
            }
            Cat::SecondOrder => {
                inp.max_jerk[i] = f64::INFINITY;
                inp.current_velocity[i] = uni(r, vmin, vmax);
                if r.next_f64() < 0.5 {
                    inp.target_velocity[i] = uni(r, vmin, vmax);
                }
            }
            Cat::Phase => {}
        }
    }
    if cat == Cat::Phase {
        // Collinear boundary states: rest or proportional velocities.
        let s = uni(r, -0.2, 0.2);
        for i in 0..N {
            let u = inp.target_position[i] - inp.current_position[i];
            inp.current_velocity[i] = s
                * u
                * inp
                    .max_velocity
                    .iter()
                    .fold(f64::INFINITY, |m, &v| m.min(v))
                / 10.0;
        }
        inp.options.synchronization = Synchronization::Phase;
    }
    if cat == Cat::VelocityInterface {
        inp.options.control_interface = ControlInterface::Velocity;
    }
    if cat == Cat::Discrete {
        inp.options.duration_discretization = DurationDiscretization::Discrete;
    }
    inp
}

/// Worst violations of a solved case.
#[derive(Debug, Default, Clone, Copy)]
pub struct Violation {
    pub position: f64,
    pub velocity: f64,
    pub acceleration: f64,
    /// Largest relative limit excess (0 when within).
    pub limit: f64,
}

/// Checks a solved trajectory: final state vs target (position interface: position too) and
/// limits at every segment boundary and interior velocity extremum after the brake.
pub fn check<const N: usize>(inp: &InputParameter<N>, tr: &FixedTrajectory<N>) -> Violation {
    let mut w = Violation::default();
    let t = tr.duration();
    let (mut p, mut v, mut a) = ([0.0; N], [0.0; N], [0.0; N]);
    tr.at_time(t, &mut p, &mut v, &mut a);
    let vel_if = inp.options.control_interface == ControlInterface::Velocity;
    for i in 0..N {
        if !inp.enabled[i] {
            continue;
        }
        let prof = &tr.dofs()[i].profile;
        let second = inp.max_jerk[i].is_infinite();
        let e = prof.end();
        // Final state of the DOF's own profile (it may end earlier with synchronization none).
        if !vel_if {
            w.position = w.position.max((e.p - inp.target_position[i]).abs());
        }
        w.velocity = w.velocity.max((e.v - inp.target_velocity[i]).abs());
        if !second {
            w.acceleration = w.acceleration.max((e.a - inp.target_acceleration[i]).abs());
        }
        let _ = (&p, &v, &a);
        let vmax = inp.max_velocity[i];
        let vmin = inp.min_velocity.map_or(-vmax, |m| m[i]);
        let amax = inp.max_acceleration[i];
        let amin = inp.min_acceleration.map_or(-amax, |m| m[i]);
        let tb = prof.brake_duration();
        // The state where the brake ended may still be outside a limit (on its way back).
        let (_, vb, ab, _) = prof.state_at(tb);
        let (vmax, vmin) = if tb > 0.0 {
            (vmax.max(vb), vmin.min(vb))
        } else {
            (vmax, vmin)
        };
        let (amax, amin) = if tb > 0.0 {
            (amax.max(ab), amin.min(ab))
        } else {
            (amax, amin)
        };
        for k in 0..prof.segments() {
            let (t0, d, s, j) = prof.segment(k).unwrap();
            if t0 + d <= tb + 1e-15 {
                continue;
            }
            let vend = s.v + d * (s.a + d * j / 2.0);
            let aend = s.a + d * j;
            let mut vs = [s.v, vend, s.v];
            if j != 0.0 {
                let r = -s.a / j;
                if r > 0.0 && r < d {
                    vs[2] = s.v + r * (s.a + r * j / 2.0);
                }
            }
            if !vel_if {
                for vv in vs {
                    w.limit = w.limit.max((vv - vmax) / vmax).max((vv - vmin) / vmin);
                }
            }
            for aa in [s.a, aend] {
                w.limit = w.limit.max((aa - amax) / amax).max((aa - amin) / amin);
            }
        }
    }
    w
}

pub fn within_contract(w: &Violation) -> bool {
    w.position <= 1e-8 && w.velocity <= 1e-10 && w.acceleration <= 1e-10 && w.limit <= 1e-12
}

/// rsruckig's duration for the same input; `None` when it fails.
pub fn ruckig_duration<const N: usize>(inp: &InputParameter<N>, dt: f64) -> Option<f64> {
    ruckig_states(inp, dt, &[]).map(|(t, _)| t)
}

fn sync_of(s: Synchronization) -> rsruckig::prelude::Synchronization {
    match s {
        Synchronization::Time => rsruckig::prelude::Synchronization::Time,
        Synchronization::TimeIfNecessary => rsruckig::prelude::Synchronization::TimeIfNecessary,
        // (Ruckig has no straight-line mode: its phase mode is the nearest.)
        Synchronization::Phase | Synchronization::StraightLine => {
            rsruckig::prelude::Synchronization::Phase
        }
        Synchronization::None => rsruckig::prelude::Synchronization::None,
    }
}

fn iface_of(c: ControlInterface) -> rsruckig::prelude::ControlInterface {
    match c {
        ControlInterface::Position => rsruckig::prelude::ControlInterface::Position,
        ControlInterface::Velocity => rsruckig::prelude::ControlInterface::Velocity,
    }
}

/// rsruckig's duration and its positions at the fractions `at` of the duration; `None`
/// when it fails.
pub fn ruckig_states<const N: usize>(
    inp: &InputParameter<N>,
    dt: f64,
    at: &[f64],
) -> Option<(f64, Vec<[f64; N]>)> {
    use rsruckig::prelude::{IgnoreErrorHandler, Ruckig, RuckigResult};
    let mut otg = Ruckig::<N, IgnoreErrorHandler>::new(None, dt);
    let mut ri = rsruckig::prelude::InputParameter::<N>::new(None);
    for i in 0..N {
        ri.current_position[i] = inp.current_position[i];
        ri.current_velocity[i] = inp.current_velocity[i];
        ri.current_acceleration[i] = inp.current_acceleration[i];
        ri.target_position[i] = inp.target_position[i];
        ri.target_velocity[i] = inp.target_velocity[i];
        ri.target_acceleration[i] = inp.target_acceleration[i];
        ri.max_velocity[i] = inp.max_velocity[i];
        ri.max_acceleration[i] = inp.max_acceleration[i];
        ri.max_jerk[i] = inp.max_jerk[i];
        ri.enabled[i] = inp.enabled[i];
    }
    if let Some(m) = inp.min_velocity {
        let mut x = ri.max_velocity.clone();
        for i in 0..N {
            x[i] = m[i];
        }
        ri.min_velocity = Some(x);
    }
    if let Some(m) = inp.min_acceleration {
        let mut x = ri.max_acceleration.clone();
        for i in 0..N {
            x[i] = m[i];
        }
        ri.min_acceleration = Some(x);
    }
    ri.synchronization = sync_of(inp.options.synchronization);
    ri.control_interface = iface_of(inp.options.control_interface);
    if let Some(s) = inp.per_dof_synchronization {
        let mut x = rsruckig::prelude::DataArrayOrVec::new(None, sync_of(s[0]));
        for i in 0..N {
            x[i] = sync_of(s[i]);
        }
        ri.per_dof_synchronization = Some(x);
    }
    if let Some(c) = inp.per_dof_control_interface {
        let mut x = rsruckig::prelude::DataArrayOrVec::new(None, iface_of(c[0]));
        for i in 0..N {
            x[i] = iface_of(c[i]);
        }
        ri.per_dof_control_interface = Some(x);
    }
    ri.duration_discretization = match inp.options.duration_discretization {
        trajkit::otg::DurationDiscretization::Continuous => {
            rsruckig::prelude::DurationDiscretization::Continuous
        }
        trajkit::otg::DurationDiscretization::Discrete => {
            rsruckig::prelude::DurationDiscretization::Discrete
        }
    };
    ri.minimum_duration = inp.options.minimum_duration;
    let mut tr = rsruckig::prelude::Trajectory::<N>::new(None);
    match otg.calculate(&ri, &mut tr) {
        Ok(RuckigResult::Working) | Ok(RuckigResult::Finished) => {}
        _ => return None,
    }
    let d = tr.get_duration();
    let states = at
        .iter()
        .map(|f| {
            let mut p = rsruckig::prelude::DataArrayOrVec::<f64, N>::new(None, 0.0);
            tr.at_time(
                f * d,
                &mut Some(&mut p),
                &mut None,
                &mut None,
                &mut None,
                &mut None,
            );
            let mut q = [0.0; N];
            for i in 0..N {
                q[i] = p[i];
            }
            q
        })
        .collect();
    Some((d, states))
}

/// Phases `(duration, jerk)` from `(v0, a0)`, integrated exactly; returns the end state
/// `(p, v, a)` and the largest |v| on the way (at the phase ends and where a crosses zero).
pub fn integrate_phases(v0: f64, a0: f64, phases: &[(f64, f64)]) -> ((f64, f64, f64), f64) {
    let (mut p, mut v, mut a) = (0.0, v0, a0);
    let mut vpeak = v0.abs();
    for &(d, j) in phases {
        if j != 0.0 && (a / j) < 0.0 && -a / j < d {
            let s = -a / j;
            vpeak = vpeak.max((v + a * s + j * s * s / 2.0).abs());
        }
        p += d * (v + d * (a / 2.0 + d * j / 6.0));
        v += d * (a + d * j / 2.0);
        a += d * j;
        vpeak = vpeak.max(v.abs());
    }
    ((p, v, a), vpeak)
}

/// The phases `(duration, jerk)` that ramp (full jerk) from `a0` through each level of
/// `steps` and hold it for the given time (0: no hold).
pub fn level_phases(a0: f64, steps: &[(f64, f64)], j: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut a = a0;
    for &(level, hold) in steps {
        out.push(((level - a).abs() / j, j.copysign(level - a)));
        if hold > 0.0 {
            out.push((hold, 0.0));
        }
        a = level;
    }
    out
}

/// A one-DOF profile built forward from a random start: the limits drawn for it, its levels,
/// its phases and the end state they reach.
pub struct Forward {
    /// Jerk limit (10^U(log_j_lo, 2)).
    pub j: f64,
    /// Acceleration limit (10^U(−1, 1)).
    pub amax: f64,
    /// Start acceleration.
    pub a0: f64,
    /// The levels and holds given by the shape builder.
    pub steps: Vec<(f64, f64)>,
    /// The phases `(duration, jerk)` of [`level_phases`].
    pub phases: Vec<(f64, f64)>,
    /// Start velocity (U(−2, 2)).
    pub v0: f64,
    /// End state `(p − p₀, v, a)`.
    pub end: (f64, f64, f64),
    /// Largest |v| on the way.
    pub vpeak: f64,
    /// The profile's duration.
    pub t: f64,
}

/// Draws the limits, calls `build(r, amax, j)` for `(a0, steps)`, draws the start velocity
/// and integrates: the seeded head shared by the forward-built property tests (the draws
/// come in this order, so the cases stay those the tests pin by number).
pub fn forward_profile(
    r: &mut SplitMix64,
    log_j_lo: f64,
    build: impl FnOnce(&mut SplitMix64, f64, f64) -> (f64, Vec<(f64, f64)>),
) -> Forward {
    let j = 10f64.powf(uni(r, log_j_lo, 2.0));
    let amax = 10f64.powf(uni(r, -1.0, 1.0));
    let (a0, steps) = build(r, amax, j);
    let phases = level_phases(a0, &steps, j);
    let v0 = uni(r, -2.0, 2.0);
    let (end, vpeak) = integrate_phases(v0, a0, &phases);
    let t = phases.iter().map(|x| x.0).sum();
    Forward {
        j,
        amax,
        a0,
        steps,
        phases,
        v0,
        end,
        vpeak,
        t,
    }
}

/// The problem from `p0` along `f` (mirrored when `sign` is −1): start and target states,
/// acceleration and jerk limits; the caller sets the velocity limit and options.
pub fn forward_input(f: &Forward, sign: f64, p0: f64) -> InputParameter<1> {
    let (p, v, a) = f.end;
    let mut inp = InputParameter::<1>::new();
    inp.current_position = [sign * p0];
    inp.current_velocity = [sign * f.v0];
    inp.current_acceleration = [sign * f.a0];
    inp.target_position = [sign * (p0 + p)];
    inp.target_velocity = [sign * v];
    inp.target_acceleration = [sign * a];
    inp.max_acceleration = [f.amax];
    inp.max_jerk = [f.j];
    inp
}

/// A `step1_property` problem (the generator of tests/otg_step1_shapes.rs): a profile of step-1
/// family `kind` of [`FAMILIES`] built forward ([`forward_profile`], log₁₀ j from −1.5), its
/// end state the target, mirrored half of the time, the velocity limit just above the
/// cruise (cruise family) or with room for both ends' braking. Returns the problem and the
/// constructed profile's duration, or `None` for a draw outside the useful range (the draws
/// come in this order, so the cases stay those the tests pin by number).
pub fn step1_property(r: &mut SplitMix64, kind: usize) -> Option<(InputParameter<1>, f64)> {
    let f = forward_profile(r, -1.5, |r, amax, j| family(r, amax, j, kind));
    let (j, a0, (p, _, a), vpeak, t) = (f.j, f.a0, f.end, f.vpeak, f.t);
    let vmax = if kind == 4 {
        // The cruise is at the velocity limit: nothing else may pass it.
        let n1 = f.phases.len() - if f.steps[2].1 > 0.0 { 4 } else { 3 };
        let vc = integrate_phases(f.v0, a0, &f.phases[..n1]).0 .1;
        if !(vc > 0.0 && vpeak <= vc * (1.0 + 1e-13)) {
            return None;
        }
        vc * (1.0 + 1e-13)
    } else {
        // Room for the braking of the start and target states too.
        let stop = (a0 * a0).max(a * a) / (2.0 * j);
        (vpeak + stop) * uni(r, 1.0, 2.0) + 1e-3
    };
    if vpeak > 300.0 || p.abs() > 1e4 {
        // Outside the absolute position accuracy's useful range (1e-8 on 1e4).
        return None;
    }
    let sign = if r.next_f64() < 0.5 { 1.0 } else { -1.0 };
    let p0 = uni(r, -100.0, 100.0);
    let mut inp = forward_input(&f, sign, p0);
    inp.max_velocity = [vmax];
    Some((inp, t))
}

/// The step-1 families (the negative direction by mirroring the whole problem).
pub const FAMILIES: [&str; 5] = ["none", "acc0", "acc1", "acc0_acc1", "vel"];

/// A level in `[lo, hi]`: uniform, next to one end (10⁻⁷ to 10⁻¹ of the range away) or, when
/// the range holds it, next to zero (10⁻⁷ to 10⁻¹ of the range), a third of the time each.
fn pick(r: &mut SplitMix64, lo: f64, hi: f64) -> f64 {
    let w = hi - lo;
    let off = w * 10f64.powf(uni(r, -7.0, -1.0));
    let u = r.next_f64();
    let x = if u < 1.0 / 3.0 {
        uni(r, lo, hi)
    } else if u < 2.0 / 3.0 {
        if r.next_f64() < 0.5 {
            lo + off
        } else {
            hi - off
        }
    } else if lo < 0.0 && hi > 0.0 {
        off.copysign(uni(r, -1.0, 1.0))
    } else {
        uni(r, lo, hi)
    };
    x.clamp(lo, hi)
}

/// A random profile of family `kind` of [`FAMILIES`] with levels inside ±a_max; returns
/// (a₀, steps). In the cruise family the level 0 held is the cruise.
fn family(r: &mut SplitMix64, amax: f64, j: f64, kind: usize) -> (f64, Vec<(f64, f64)>) {
    let hold = |r: &mut SplitMix64| amax / j * 10f64.powf(uni(r, -4.0, 1.0));
    match kind {
        0 => {
            // a₀ ↗ α₁ ↘ α₂ ↗ a_f.
            let al1 = pick(r, -amax, amax);
            let a0 = pick(r, -amax, al1);
            let al2 = pick(r, -amax, al1);
            let af = pick(r, al2, amax);
            (a0, vec![(al1, 0.0), (al2, 0.0), (af, 0.0)])
        }
        1 => {
            // a₀ ↗ a_max (hold) ↘ α₂ ↗ a_f.
            let a0 = pick(r, -amax, amax);
            let al2 = pick(r, -amax, amax);
            let af = pick(r, al2, amax);
            (a0, vec![(amax, hold(r)), (al2, 0.0), (af, 0.0)])
        }
        2 => {
            // a₀ ↗ α₁ ↘ −a_max (hold) ↗ a_f.
            let al1 = pick(r, -amax, amax);
            let a0 = pick(r, -amax, al1);
            let af = pick(r, -amax, amax);
            (a0, vec![(al1, 0.0), (-amax, hold(r)), (af, 0.0)])
        }
        3 => {
            // a₀ ↗ a_max (hold) ↘ −a_max (hold) ↗ a_f.
            let a0 = pick(r, -amax, amax);
            let af = pick(r, -amax, amax);
            (a0, vec![(amax, hold(r)), (-amax, hold(r)), (af, 0.0)])
        }
        _ => {
            // a₀ ↗ α₁ (plateau at a_max, or none) ↘ 0, cruise, ↘ α₂ (plateau at −a_max, or
            // none) ↗ a_f.
            let a0 = pick(r, -amax, amax);
            let plateau1 = r.next_f64() < 0.5;
            let al1 = if plateau1 {
                amax
            } else {
                pick(r, a0.max(0.0), amax)
            };
            let plateau2 = r.next_f64() < 0.5;
            let al2 = if plateau2 { -amax } else { pick(r, -amax, 0.0) };
            let af = pick(r, al2, amax);
            let h1 = if plateau1 { hold(r) } else { 0.0 };
            let h2 = if plateau2 { hold(r) } else { 0.0 };
            (a0, vec![(al1, h1), (0.0, hold(r)), (al2, h2), (af, 0.0)])
        }
    }
}
