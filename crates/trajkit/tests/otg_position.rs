//! Position limits of the online generator (`min_position`/`max_position`): seeded random
//! problems whose unconstrained motion overshoots, checked by dense independent sampling, and
//! the durations compared with a brute-force reference (`tools/otg_position_reference.py`, a
//! fine-grid linear program).

use trajkit::otg::{InputParameter, Otg};
use trajkit::rng::SplitMix64;

fn one(p0: f64, v0: f64, a0: f64, pf: f64) -> InputParameter<1> {
    let mut inp = InputParameter::<1>::new();
    inp.current_position = [p0];
    inp.current_velocity = [v0];
    inp.current_acceleration = [a0];
    inp.target_position = [pf];
    inp.max_velocity = [1.0];
    inp.max_acceleration = [2.0];
    inp.max_jerk = [10.0];
    inp
}

/// Largest excess over the position limits and largest final-state error of `tr`, sampled
/// every `dt` (and at the end) by evaluating the trajectory: independent of the profiles'
/// own extrema.
fn sampled<const N: usize>(
    inp: &InputParameter<N>,
    tr: &trajkit::otg::FixedTrajectory<N>,
    samples: usize,
) -> (f64, f64) {
    let t_end = tr.duration();
    let (mut p, mut v, mut a) = ([0.0; N], [0.0; N], [0.0; N]);
    let mut excess = 0.0f64;
    for k in 0..=samples {
        tr.at_time(t_end * k as f64 / samples as f64, &mut p, &mut v, &mut a);
        for i in (0..N).filter(|&i| inp.enabled[i]) {
            excess = excess
                .max(p[i] - inp.max_position[i])
                .max(inp.min_position[i] - p[i]);
        }
    }
    tr.at_time(t_end, &mut p, &mut v, &mut a);
    let mut err = 0.0f64;
    for i in (0..N).filter(|&i| inp.enabled[i]) {
        err = err
            .max((p[i] - inp.target_position[i]).abs())
            .max((v[i] - inp.target_velocity[i]).abs())
            .max((a[i] - inp.target_acceleration[i]).abs());
    }
    (excess, err)
}

#[test]
fn limits_out_of_the_way_change_nothing() {
    let otg = Otg::<1>::new(0.001);
    let mut r = SplitMix64::new(3);
    for _ in 0..300 {
        let mut inp = one(
            0.0,
            r.uniform(-0.9, 0.9),
            r.uniform(-1.0, 1.0),
            r.uniform(-1.0, 1.0),
        );
        inp.target_velocity = [r.uniform(-0.5, 0.5)];
        let Ok(free) = otg.calculate(&inp) else {
            continue;
        };
        let (lo, _, hi, _) = free.position_extrema(0).unwrap();
        inp.max_position = [hi + r.uniform(0.0, 0.1)];
        inp.min_position = [lo - r.uniform(0.0, 0.1)];
        let limited = otg.calculate(&inp).unwrap();
        assert_eq!(limited.duration(), free.duration(), "{inp:?}");
    }
}

/// A random 3-DOF problem: general states, some targets moving, random limits.
fn random3(r: &mut SplitMix64) -> InputParameter<3> {
    let mut inp = InputParameter::<3>::new();
    for i in 0..3 {
        let (vmax, amax, jmax) = (
            r.uniform(0.5, 2.0),
            r.uniform(1.0, 5.0),
            r.uniform(5.0, 50.0),
        );
        inp.max_velocity[i] = vmax;
        inp.max_acceleration[i] = amax;
        inp.max_jerk[i] = jmax;
        let inside = |r: &mut SplitMix64| loop {
            let (v, a) = (r.uniform(-vmax, vmax), r.uniform(-amax, amax));
            let w = a * a.abs() / (2.0 * jmax);
            if (v + w).abs() <= vmax && (v - w).abs() <= vmax {
                return (v, a);
            }
        };
        (inp.current_velocity[i], inp.current_acceleration[i]) = inside(r);
        if r.uniform(0.0, 1.0) < 0.6 {
            (inp.target_velocity[i], inp.target_acceleration[i]) = inside(r);
        }
        inp.target_position[i] = r.uniform(-1.0, 1.0);
    }
    inp
}

/// A span that some motion of DOF `i` of `inp` covers, and that motion's duration: start,
/// target, where the fastest stop from the start lands and where the fastest start towards
/// the target state begins (the time-reversed stop from the target). The witness motion
/// stops, moves from rest to rest monotonically, then runs the time-reversed stop into the
/// target state; it can wait at rest, so with position limits that hold the span every
/// duration from the witness's on is feasible.
fn witness<const N: usize>(otg: &Otg<N>, inp: &InputParameter<N>, i: usize) -> (f64, f64, f64) {
    let mut stop = *inp;
    stop.options.control_interface = trajkit::otg::ControlInterface::Velocity;
    stop.options.minimum_duration = None;
    stop.max_position = [f64::INFINITY; N];
    stop.min_position = [f64::NEG_INFINITY; N];
    stop.target_velocity = [0.0; N];
    stop.target_acceleration = [0.0; N];
    stop.enabled = [false; N];
    stop.enabled[i] = true;
    let st = otg.calculate(&stop).unwrap();
    let (lo, _, hi, _) = st.position_extrema(i).unwrap();
    let mut back = stop;
    back.current_position = inp.target_position;
    for k in 0..N {
        back.current_velocity[k] = -inp.target_velocity[k];
    }
    back.current_acceleration = inp.target_acceleration;
    let bt = otg.calculate(&back).unwrap();
    let (blo, _, bhi, _) = bt.position_extrema(i).unwrap();
    let (mut p1, mut p2) = ([0.0; N], [0.0; N]);
    let (mut v, mut a) = ([0.0; N], [0.0; N]);
    st.at_time(st.duration(), &mut p1, &mut v, &mut a);
    bt.at_time(bt.duration(), &mut p2, &mut v, &mut a);
    let mut middle = stop;
    middle.options.control_interface = trajkit::otg::ControlInterface::Position;
    middle.current_position = p1;
    middle.current_velocity = [0.0; N];
    middle.current_acceleration = [0.0; N];
    middle.target_position = p2;
    let mt = otg.calculate(&middle).unwrap();
    let t = st.duration() + mt.duration() + bt.duration();
    (lo.min(blo), hi.max(bhi), t)
}

/// Seeded random 1- and 3-DOF synchronized problems, given position limits that hold the
/// span of a witness motion ([`witness`]) and cut into the unconstrained motion's excursion
/// where it leaves that span: the shortest ones (no minimum duration) and stretched ones (a
/// minimum duration from the witnesses' on, where the unconstrained step-2 profiles often
/// wander out). Every one is solved, stays inside along the whole motion (dense sampling),
/// reaches its target and takes at least the unconstrained duration.
#[test]
fn seeded_limited_motions_stay_inside() {
    let otg = Otg::<3>::new(0.001);
    let mut r = SplitMix64::new(7);
    let (mut cases, mut binding) = (0, 0);
    for k in 0..600 {
        let mut inp = random3(&mut r);
        if k % 3 == 0 {
            inp.enabled = [true, false, false];
        }
        let mut spans = [(0.0, 0.0); 3];
        let mut t_witness = 0.0f64;
        for i in (0..3).filter(|&i| inp.enabled[i]) {
            let (lo, hi, t) = witness(&otg, &inp, i);
            spans[i] = (lo, hi);
            t_witness = t_witness.max(t);
        }
        let Ok(fastest) = otg.calculate(&inp) else {
            continue;
        };
        if k % 2 == 1 {
            let t = t_witness.max(fastest.duration()) * r.uniform(1.0, 2.0);
            inp.options.minimum_duration = Some(t);
        }
        let Ok(free) = otg.calculate(&inp) else {
            continue;
        };
        for i in (0..3).filter(|&i| inp.enabled[i]) {
            let (lo, _, hi, _) = free.position_extrema(i).unwrap();
            let (bottom, top) = spans[i];
            inp.max_position[i] = top + r.uniform(0.0, 1.0) * (hi - top).max(0.0);
            inp.min_position[i] = bottom - r.uniform(0.0, 1.0) * (bottom - lo).max(0.0);
        }
        cases += 1;
        let tr = otg
            .calculate(&inp)
            .unwrap_or_else(|e| panic!("{e} {inp:?}"));
        let (excess, err) = sampled(&inp, &tr, 4000);
        let (excess_free, _) = sampled(&inp, &free, 4000);
        if excess_free > 1e-9 {
            binding += 1;
        }
        assert!(excess <= 1e-12, "{excess:e} {inp:?}");
        assert!(err <= 1e-8, "{err:e} {inp:?}");
        assert!(tr.duration() >= free.duration() * (1.0 - 1e-12), "{inp:?}");
        if excess_free <= 0.0 {
            assert_eq!(tr.duration(), free.duration(), "{inp:?}");
        }
    }
    // (The unconstrained motion rarely leaves a witness's span: where limits bind and the
    // duration changes, `reference_durations` compares with a brute-force optimum.)
    eprintln!("{cases} cases, {binding} where the limits bind");
    assert!(cases > 500, "{cases}");
}

/// The durations of `tools/otg_position_reference.py` (a fine-grid linear program over
/// piecewise-constant jerk, shortest duration found by scanning and bisection): where the
/// reference finds no motion inside the limits (up to 4× the unconstrained duration) trajkit
/// refuses with `PositionLimits`; where it finds one, trajkit's motion is valid and its
/// duration agrees with the reference to the grid's accuracy (recorded in the fixture).
#[test]
#[cfg(feature = "serde")]
fn reference_durations() {
    use trajkit::otg::{calculate_dyn, json::parse_problem, OtgError};
    let text = include_str!("fixtures/otg/position_reference.json");
    let v: serde_json::Value = serde_json::from_str(text).unwrap();
    let cases = v["cases"].as_array().unwrap();
    assert!(cases.len() >= 20);
    let (mut feasible, mut worst) = (0, 0.0f64);
    for (k, c) in cases.iter().enumerate() {
        let pr = parse_problem(&c["problem"].to_string(), "position_reference.json", k).unwrap();
        let got = calculate_dyn(&pr.input, pr.delta_time);
        match c["reference_duration"].as_f64() {
            None => assert!(
                matches!(got, Err(OtgError::PositionLimits { dof: 0 })),
                "case {k}: the reference finds no motion, trajkit {got:?}"
            ),
            Some(t_ref) => {
                feasible += 1;
                let tr = got.unwrap_or_else(|e| panic!("case {k}: {e}"));
                let rel = tr.duration() / t_ref - 1.0;
                worst = worst.max(rel.abs());
                assert!(rel.abs() <= 2e-3, "case {k}: {} vs {t_ref}", tr.duration());
                let chk = trajkit::otg::check(&pr.input, &tr);
                assert!(
                    chk.final_error.iter().all(|&e| e <= 1e-8),
                    "case {k}: {chk:?}"
                );
                let (lo, _, hi, _) = tr.position_extrema(0).unwrap();
                assert!(lo >= pr.input.min_position[0] - 1e-12, "case {k}");
                assert!(hi <= pr.input.max_position[0] + 1e-12, "case {k}");
            }
        }
    }
    eprintln!("{feasible} feasible cases, worst relative difference {worst:.1e}");
}

/// Position limits that are not numbers, cross, leave out the current or target position,
/// or are given to a velocity-interface DOF are refused, naming the field and the value.
#[test]
fn bad_position_limits_are_refused_by_name() {
    let otg = Otg::<1>::new(0.001);
    let cases: [(f64, f64, f64, f64, &str); 6] = [
        // (min, max, current, target, field)
        (f64::NEG_INFINITY, f64::NAN, 0.0, 0.5, "max_position"),
        (f64::NAN, 1.0, 0.0, 0.5, "min_position"),
        (0.8, 0.2, 0.5, 0.5, "min_position"),
        (0.1, 1.0, 0.0, 0.5, "current_position"),
        (-1.0, 0.4, 0.0, 0.5, "target_position"),
        (-1.0, f64::INFINITY, 0.0, 1.5, "NONE"),
    ];
    for (lo, hi, p0, pf, field) in cases {
        let mut inp = one(p0, 0.0, 0.0, pf);
        inp.min_position = [lo];
        inp.max_position = [hi];
        match otg.calculate(&inp) {
            Err(trajkit::otg::OtgError::InvalidInput {
                field: f,
                value,
                dof,
                ..
            }) => {
                assert_eq!((f, dof), (field, Some(0)));
                let expected = match f {
                    "max_position" => hi,
                    "min_position" => lo,
                    "current_position" => p0,
                    _ => pf,
                };
                assert!(value == expected || (value.is_nan() && expected.is_nan()));
            }
            Ok(tr) => assert_eq!(field, "NONE", "{tr:?}"),
            Err(e) => panic!("{e}"),
        }
    }
    let mut inp = one(0.0, 0.0, 0.0, 0.0);
    inp.options.control_interface = trajkit::otg::ControlInterface::Velocity;
    inp.target_velocity = [0.5];
    inp.max_position = [1.0];
    let e = otg.calculate(&inp).unwrap_err();
    assert!(e.to_string().contains("max_position"), "{e}");
}

/// A start whose brake (or fastest stop) already leaves the limits cannot be helped: a clear
/// error, never a motion outside.
#[test]
fn a_start_that_cannot_stop_inside_is_refused() {
    let otg = Otg::<1>::new(0.001);
    // 0.9 m/s towards a limit 0.05 away: the fastest stop needs about 0.29.
    let mut inp = one(0.0, 0.9, 0.0, 0.0);
    inp.max_position = [0.05];
    let e = otg.calculate(&inp).unwrap_err();
    assert!(
        matches!(e, trajkit::otg::OtgError::PositionLimits { dof: 0 }),
        "{e}"
    );
    assert_eq!(e.name(), "position_limits");
    // With room for that stop: solved, inside.
    inp.max_position = [0.3];
    let tr = otg.calculate(&inp).unwrap();
    let (_, _, hi, _) = tr.position_extrema(0).unwrap();
    assert!(hi <= 0.3, "{hi}");
}

/// Seeded 3-DOF synchronized problems (general states, some moving targets, some minimum
/// durations): position limits that hold the unconstrained motion (at its extrema exactly,
/// or a little outside) keep its time-optimal duration (to 1e-12 relative).
#[test]
fn limits_that_hold_the_unconstrained_motion_keep_its_duration() {
    let otg = Otg::<3>::new(0.001);
    let mut r = SplitMix64::new(16);
    let mut n = 0;
    for case in 0..2000 {
        let mut inp = random3(&mut r);
        if case % 3 == 0 {
            inp.options.minimum_duration = Some(r.uniform(0.0, 4.0));
        }
        let Ok(free) = otg.calculate(&inp) else {
            continue;
        };
        for i in 0..3 {
            // (The extrema of the motion, and the target: the motion ends within round-off
            // of it, on either side.)
            let (lo, _, hi, _) = free.position_extrema(i).unwrap();
            let (lo, hi) = (
                lo.min(inp.target_position[i]),
                hi.max(inp.target_position[i]),
            );
            let gap = if case % 2 == 0 {
                0.0
            } else {
                r.uniform(0.0, 0.05)
            };
            inp.max_position[i] = hi + gap;
            inp.min_position[i] = lo - gap;
        }
        let limited = otg
            .calculate(&inp)
            .unwrap_or_else(|e| panic!("case {case}: {e} {inp:?}"));
        // (A DOF with position limits always runs step 1, which may reach the same duration
        // by another path: equal to round-off.)
        let (tl, tf) = (limited.duration(), free.duration());
        assert!(
            (tl - tf).abs() <= 1e-12 * tf,
            "case {case}: {tl} vs {tf}; {inp:?}"
        );
        n += 1;
    }
    assert!(n > 1500, "{n}");
}
