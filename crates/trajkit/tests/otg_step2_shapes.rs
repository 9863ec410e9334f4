//! Step 2 finds every duration that a profile of one of its shapes makes feasible.
//!
//! Seeded property test of the mechanism behind the `per_dof_interface` sweep reproducer
//! (a position-interface DOF synchronized to 11.2038 s went to 11.2462 s: the hold family's
//! valid parameter range lay between two samples of the bracketing grid). Each case builds a
//! profile of a step-2 shape from random levels and phase durations inside the limits, makes
//! its end state the target and asks for a one-DOF motion with its duration as the minimum
//! duration: the duration must be exactly that one (step 2 plans it), whatever profile step 2
//! picks.

mod otg_common;
use otg_common::{forward_input, forward_profile, uni};
use trajkit::otg::Otg;
use trajkit::rng::SplitMix64;

/// Levels of a shape: each step ramps (full jerk) to the level, then holds it for the given
/// time (0: no hold).
type Steps = Vec<(f64, f64)>;

/// The step-2 shapes (the negative direction by mirroring the whole problem).
const SHAPES: [&str; 7] = [
    "hold at the valley",
    "hold at the peak",
    "four ramps",
    "split ramp",
    "split ramp with a plateau",
    "peak then hold",
    "plateau, then hold",
];

/// A random shape `kind` of [`SHAPES`] with levels inside ±a_max; returns (a₀, steps).
fn shape(r: &mut SplitMix64, amax: f64, j: f64, kind: usize) -> (f64, Steps) {
    // Short ramps (a level next to its neighbour) half of the time: the narrow parameter
    // ranges of the families live there.
    let near = |r: &mut SplitMix64, from: f64, to: f64| {
        if r.next_f64() < 0.5 {
            from + (to - from) * 10f64.powf(uni(r, -5.0, -1.0))
        } else {
            uni(r, from, to)
        }
    };
    let hold = |r: &mut SplitMix64| amax / j * 10f64.powf(uni(r, -2.0, 1.5));
    match kind {
        0 | 1 => {
            // a₀ ↗ α₁ ↘ α₂ ↗ a_f, the hold at α₂ or at α₁. (The reproducer: a₀ and α₁ both
            // next to a_max, the valid range of α₂ narrower than the bracketing grid's step.)
            let al1 = near(r, amax, -amax);
            let a0 = near(r, al1, -amax);
            let al2 = near(r, al1, -amax);
            let af = near(r, al2, amax);
            let h = hold(r);
            let (h1, h2) = if kind == 0 { (0.0, h) } else { (h, 0.0) };
            (a0, vec![(al1, h1), (al2, h2), (af, 0.0)])
        }
        2 => {
            // a₀ ↘ α₁ ↗ α₂ ↘ α₃ ↗ a_f.
            let al2 = uni(r, -amax, amax);
            let al1 = near(r, al2, -amax);
            let al3 = near(r, al2, -amax);
            let a0 = near(r, al1, amax);
            let af = near(r, al3, amax);
            (a0, vec![(al1, 0.0), (al2, 0.0), (al3, 0.0), (af, 0.0)])
        }
        3 | 4 => {
            // a₀ ↘ α (hold) ↘ β (plateau at −a_max, or none) ↗ a_f.
            let a0 = uni(r, -amax, amax);
            let beta = if kind == 4 { -amax } else { uni(r, -amax, a0) };
            let al = near(r, a0, beta);
            let af = near(r, beta, amax);
            let plateau = if kind == 4 { hold(r) } else { 0.0 };
            (a0, vec![(al, hold(r)), (beta, plateau), (af, 0.0)])
        }
        _ => {
            // a₀ ↗ α₁ (plateau at a_max, or none) ↘ α₂ (hold) ↘ a_f.
            let af = uni(r, -amax, amax);
            let al1 = if kind == 6 { amax } else { uni(r, af, amax) };
            let a0 = near(r, al1, -amax);
            let al2 = near(r, af, al1);
            let plateau = if kind == 6 { hold(r) } else { 0.0 };
            (a0, vec![(al1, plateau), (al2, hold(r)), (af, 0.0)])
        }
    }
}

#[test]
fn step2_shapes_are_planned_at_their_duration() {
    let otg = Otg::<1>::new(0.001);
    let mut r = SplitMix64::new(20261129);
    let (mut missed, mut tried) = (Vec::new(), 0);
    for case in 0..20000 {
        let kind = case % SHAPES.len();
        let f = forward_profile(&mut r, -1.0, |r, amax, j| shape(r, amax, j, kind));
        let (j, a0, (p, _, a), vpeak, t) = (f.j, f.a0, f.end, f.vpeak, f.t);
        if vpeak > 100.0 || p.abs() > 1e4 {
            // Outside the absolute position accuracy's useful range (1e-8 on 1e4).
            continue;
        }
        tried += 1;
        let sign = if r.next_f64() < 0.5 { 1.0 } else { -1.0 };
        let mut inp = forward_input(&f, sign, 1.0);
        // Room for the braking of the start and target states too.
        let stop = (a0 * a0).max(a * a) / (2.0 * j);
        inp.max_velocity = [(vpeak + stop) * uni(&mut r, 1.0, 2.0) + 1e-3];
        inp.options.minimum_duration = Some(t);
        match otg.calculate(&inp) {
            Ok(tr) if (tr.duration() - t).abs() <= 1e-9 * t.max(1.0) => {}
            Ok(tr) => missed.push(format!(
                "case {case} ({}): {} vs {t}: {inp:?}",
                SHAPES[kind],
                tr.duration()
            )),
            Err(e) => missed.push(format!("case {case} ({}): {e}: {inp:?}", SHAPES[kind])),
        }
    }
    for m in &missed {
        eprintln!("{m}");
    }
    assert!(missed.is_empty(), "{} missed of {tried}", missed.len());
    assert!(tried >= 15000, "{tried}");
}
