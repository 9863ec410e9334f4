//! The calculation budget (`interrupt_calculation_duration`): an ample budget changes
//! nothing; one that runs out before the synchronization search finds a duration gives
//! `OtgError::Interrupted` without overrunning the budget by more than 10 %.

use std::time::Instant;
use trajkit::otg::{InputParameter, Otg, OtgError};

/// A 3-DOF problem whose synchronization search is long: DOF 0 cannot be stretched to the
/// minimum duration inside its position limit (it cannot stop before the limit), so the
/// search tries every candidate and then 200 growing durations before it gives up.
fn long_search() -> InputParameter<3> {
    let mut inp = InputParameter::<3>::new();
    inp.current_velocity = [1.5052868477203276, 1.069302129223893, -0.20536259010296953];
    inp.current_acceleration = [
        -0.45794839804429144,
        1.6754754057174406,
        -2.1294953970846375,
    ];
    inp.target_position = [
        0.9112454133064538,
        0.34250832334693637,
        -0.07706923937099508,
    ];
    inp.target_velocity = [0.7251994035178897, -0.1986253319450888, 0.0];
    inp.target_acceleration = [0.9233801267137105, -3.064593223658846, 0.0];
    inp.max_velocity = [1.6869254840427321, 1.6719104227130273, 0.9623265352871956];
    inp.max_acceleration = [1.2566316483312043, 4.503537514887711, 4.616952592476525];
    inp.max_jerk = [34.66577999732044, 32.3309576830224, 5.9009321786831945];
    inp.max_position = [0.9123026435976187, f64::INFINITY, f64::INFINITY];
    inp.options.minimum_duration = Some(1.4256679756558468);
    inp
}

/// A seeded 3-DOF problem with a moving target (v_max 1, a_max 2, j_max 10): velocities
/// within ±`v`, the current acceleration within ±`a` (not drawn when `a` is 0).
fn moving_target(r: &mut trajkit::rng::SplitMix64, v: f64, a: f64) -> InputParameter<3> {
    let mut inp = InputParameter::<3>::new();
    for i in 0..3 {
        inp.current_velocity[i] = r.uniform(-v, v);
        if a != 0.0 {
            inp.current_acceleration[i] = r.uniform(-a, a);
        }
        inp.target_position[i] = r.uniform(-1.0, 1.0);
        inp.target_velocity[i] = r.uniform(-v, v);
        inp.max_velocity[i] = 1.0;
        inp.max_acceleration[i] = 2.0;
        inp.max_jerk[i] = 10.0;
    }
    inp
}

#[test]
fn an_ample_budget_changes_nothing() {
    let otg = Otg::<3>::new(0.001);
    let mut r = trajkit::rng::SplitMix64::new(5);
    for _ in 0..200 {
        let mut inp = moving_target(&mut r, 0.5, 0.0);
        let free = otg.calculate(&inp);
        inp.options.interrupt_calculation_duration = Some(1e6);
        let budgeted = otg.calculate(&inp);
        assert_eq!(free.map(|t| t.duration()), budgeted.map(|t| t.duration()));
    }
}

#[test]
fn a_budget_that_runs_out_interrupts_in_time() {
    let otg = Otg::<3>::new(0.001);
    let mut inp = long_search();
    // Without a budget: the search gives up (the minimum duration is out of reach).
    let mut full = f64::INFINITY;
    for _ in 0..3 {
        let t0 = Instant::now();
        let r = otg.calculate(&inp);
        full = full.min(t0.elapsed().as_secs_f64() * 1e6);
        assert!(
            matches!(r, Err(OtgError::PositionLimits { dof: 0 })),
            "{r:?}"
        );
    }
    // A quarter of that: interrupted, in time. The budget is wall-clock time, so a thread
    // that is preempted past its deadline overruns by the preemption (as any such budget
    // does); on a loaded machine the least of up to 20 runs measures the budget's own
    // granularity.
    let budget = full / 4.0;
    inp.options.interrupt_calculation_duration = Some(budget);
    let mut least = f64::INFINITY;
    for _ in 0..20 {
        if least <= 1.1 * budget {
            break;
        }
        let t0 = Instant::now();
        let r = otg.calculate(&inp);
        least = least.min(t0.elapsed().as_secs_f64() * 1e6);
        match r {
            Err(OtgError::Interrupted { budget_us }) => assert_eq!(budget_us, budget),
            other => panic!("{other:?}"),
        }
    }
    eprintln!("full search {full:.0} µs, budget {budget:.0} µs, interrupted after {least:.0} µs");
    assert!(
        least <= 1.1 * budget,
        "{least} µs for a budget of {budget} µs"
    );
}

#[test]
fn a_bad_budget_is_refused_by_name() {
    let otg = Otg::<3>::new(0.001);
    for b in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let mut inp = long_search();
        inp.options.interrupt_calculation_duration = Some(b);
        match otg.calculate(&inp) {
            Err(OtgError::InvalidInput { field, .. }) => {
                assert_eq!(field, "interrupt_calculation_duration")
            }
            other => panic!("{b}: {other:?}"),
        }
    }
}

#[test]
fn the_trajectory_says_when_the_budget_cut_the_search() {
    // Moving targets (blocked intervals, so some searches bisect) under budgets from 0.5 µs to
    // 4 ms: a result the flag does not mark is the unbudgeted optimum exactly; a marked one is
    // valid and never shorter. Without a budget nothing is marked.
    let otg = Otg::<3>::new(0.001);
    let mut r = trajkit::rng::SplitMix64::new(23);
    let (mut marked, mut exact) = (0, 0);
    for k in 0..400 {
        let mut inp = moving_target(&mut r, 0.8, 1.0);
        let Ok(free) = otg.calculate(&inp) else {
            continue;
        };
        assert!(!free.was_interrupted());
        inp.options.interrupt_calculation_duration = Some(0.5 * 2f64.powi(k % 14));
        match otg.calculate(&inp) {
            Ok(t) if t.was_interrupted() => {
                marked += 1;
                assert!(t.duration() >= free.duration() * (1.0 - 1e-12));
                let mut p = [0.0; 3];
                t.at_time(t.duration(), &mut p, &mut [0.0; 3], &mut [0.0; 3]);
                for i in 0..3 {
                    assert!((p[i] - inp.target_position[i]).abs() < 1e-8);
                }
            }
            Ok(t) => {
                exact += 1;
                assert_eq!(t.duration(), free.duration(), "problem {k}");
            }
            Err(e) => assert!(matches!(e, OtgError::Interrupted { .. }), "{e:?}"),
        }
    }
    eprintln!("{marked} marked as interrupted, {exact} complete");
    assert!(exact > 0);
}
