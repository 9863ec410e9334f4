//! The calculation budget (`interrupt_calculation_duration`): an ample budget changes
//! nothing; one that runs out before the synchronization search finds a duration gives
//! `OtgError::Interrupted` without overrunning the budget by more than 10 %. The same for
//! motions through waypoints (`plan_waypoints`, an anytime search): an ample budget changes
//! nothing, a short one gives the best valid motion found in time (marked interrupted, never
//! longer than stopping at every waypoint), one shorter than the reference an error.

use std::time::Instant;
use trajkit::otg::{
    check_waypoints, plan_waypoints, DynInputParameter, InputParameter, Otg, OtgError, Waypoints,
};

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

/// A 7-DOF bent path (Franka Panda limits) through `m` waypoints, at rest at both ends: every
/// joint keeps its direction, so the search has a velocity to choose at every waypoint.
fn bent_path(r: &mut trajkit::rng::SplitMix64, m: usize) -> (DynInputParameter, Waypoints) {
    let lim = trajkit::Limits::preset("panda").unwrap();
    let mut p = DynInputParameter::new(7);
    for i in 0..7 {
        let j = lim.joint(i);
        p.max_velocity[i] = j.velocity;
        p.max_acceleration[i] = j.acceleration;
        p.max_jerk[i] = j.jerk;
    }
    let sign: Vec<f64> = (0..7).map(|_| r.uniform(-1.0, 1.0).signum()).collect();
    let mut x: Vec<f64> = (0..7).map(|_| r.uniform(-1.0, 1.0)).collect();
    p.current_position.clone_from(&x);
    let mut wps = Vec::new();
    for _ in 0..=m {
        for i in 0..7 {
            x[i] += sign[i] * r.uniform(0.05, 0.6);
        }
        wps.push(x.clone());
    }
    p.target_position = wps.pop().unwrap();
    (p, Waypoints::new(wps))
}

/// The least wall-clock time of `runs` calls of `f`, in microseconds, with the last result.
fn least_us<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut least = f64::INFINITY;
    let mut last = None;
    for _ in 0..runs {
        let t0 = Instant::now();
        let r = f();
        least = least.min(t0.elapsed().as_secs_f64() * 1e6);
        last = Some(r);
    }
    (least, last.unwrap())
}

#[test]
fn waypoints_with_an_ample_budget_change_nothing() {
    let mut r = trajkit::rng::SplitMix64::new(41);
    for k in 0..20 {
        let (mut inp, wp) = bent_path(&mut r, 1 + k % 8);
        let free = plan_waypoints(&inp, &wp, 0.001).unwrap();
        inp.options.interrupt_calculation_duration = Some(1e7);
        let budgeted = plan_waypoints(&inp, &wp, 0.001).unwrap();
        assert!(!free.was_interrupted() && !budgeted.was_interrupted());
        assert_eq!(free.duration(), budgeted.duration(), "case {k}");
        assert_eq!(free.waypoint_velocities(), budgeted.waypoint_velocities());
    }
}

#[test]
fn waypoints_under_a_short_budget_give_the_best_motion_found_in_time() {
    // 30 waypoints: the search takes milliseconds, stopping at every waypoint far less. Every
    // call (6 paths, 3 budgets) within 1.1× its budget: the least of 5 unpreempted repeats
    // (up to 40 runs) measures the planner's own overrun.
    let mut r = trajkit::rng::SplitMix64::new(7);
    let mut cut = 0;
    for _ in 0..6 {
        let (inp, wp) = bent_path(&mut r, 30);
        cut += short_budgets(inp, &wp);
    }
    assert!(cut > 0, "no budget cut the search");
}

/// [`waypoints_under_a_short_budget_give_the_best_motion_found_in_time`] for one path: the
/// number of results the budget cut.
fn short_budgets(mut inp: DynInputParameter, wp: &Waypoints) -> usize {
    let (full_us, free) = least_us(3, || plan_waypoints(&inp, wp, 0.001).unwrap());
    assert!(!free.was_interrupted());
    let stop = free.stop_at_every_waypoint_duration();
    let mut cut = 0;
    for fraction in [0.1, 0.3, 0.6] {
        let budget = full_us * fraction;
        inp.options.interrupt_calculation_duration = Some(budget);
        let (us, res, _) = unpreempted_us(5, 40, || plan_waypoints(&inp, wp, 0.001));
        {
            match res {
                Ok(t) => {
                    cut += usize::from(t.was_interrupted());
                    assert!(t.was_interrupted() || t.duration() == free.duration());
                    assert!(t.duration() <= stop * (1.0 + 1e-12));
                    let c = check_waypoints(&inp, wp, &t).unwrap();
                    assert!(c.waypoint_error <= 1e-8, "{c:?}");
                    assert!(c.solution.worst_limit_ratio <= 1.0 + 1e-9, "{c:?}");
                    assert!(c.solution.final_error.iter().all(|&e| e <= 1e-8), "{c:?}");
                }
                Err(OtgError::Interrupted { budget_us }) => assert_eq!(budget_us, budget),
                Err(e) => panic!("{e:?}"),
            }
        }
        eprintln!("full {full_us:.0} µs, budget {budget:.0} µs: {us:.0} µs");
        assert!(us <= 1.1 * budget, "{us} µs for {budget} µs");
    }
    cut
}

#[test]
fn waypoints_with_a_budget_shorter_than_the_reference_are_interrupted() {
    let mut r = trajkit::rng::SplitMix64::new(9);
    let (mut inp, wp) = bent_path(&mut r, 30);
    inp.options.interrupt_calculation_duration = Some(1.0);
    match plan_waypoints(&inp, &wp, 0.001) {
        Err(OtgError::Interrupted { budget_us }) => assert_eq!(budget_us, 1.0),
        other => panic!("{other:?}"),
    }
    inp.options.interrupt_calculation_duration = Some(-1.0);
    assert!(matches!(
        plan_waypoints(&inp, &wp, 0.001),
        Err(OtgError::InvalidInput {
            field: "interrupt_calculation_duration",
            ..
        })
    ));
}

/// The number of times the calling thread has been scheduled onto a CPU (Linux
/// `/proc/thread-self/schedstat`, third field), `None` where it is not available: a call
/// during which it does not change ran without being preempted, so its wall-clock time is
/// the planner's own.
fn timeslices() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    s.split_whitespace().nth(2)?.parse().ok()
}

/// The least wall-clock time of `want` runs of `f` that were not preempted, in microseconds,
/// with the result of that run (out of at most `tries` runs; when fewer were clean, the least
/// of all, and `false`). The budget is wall-clock time: a thread preempted past its deadline
/// overruns by the preemption (and a virtual CPU the host takes away is not seen as
/// preempted), so the least of a few clean repeats measures the planner's own overrun.
fn unpreempted_us<T>(want: usize, tries: usize, mut f: impl FnMut() -> T) -> (f64, T, bool) {
    let (mut best, mut clean): (Option<(f64, T, bool)>, usize) = (None, 0);
    for _ in 0..tries {
        let before = timeslices();
        let t0 = Instant::now();
        let r = f();
        let us = t0.elapsed().as_secs_f64() * 1e6;
        let ok = before.is_some() && timeslices() == before;
        clean += usize::from(ok);
        let better = best.as_ref().is_none_or(|b| (ok, -us) > (b.2, -b.0));
        if better {
            best = Some((us, r, ok));
        }
        if clean >= want {
            break;
        }
    }
    let (us, r, ok) = best.unwrap();
    (us, r, ok)
}

/// 300 calls per budget of 300, 1000 and 3000 µs on 30 seeded 7-DOF × 30-waypoint bent
/// paths: the time of every call (the least of 3 unpreempted repeats) against its budget,
/// and the median duration found. Run with
/// `cargo test --release -p trajkit --test otg_budget -- --ignored --nocapture budget_overrun`.
#[test]
#[ignore]
fn budget_overrun_of_every_call() {
    let calls: usize = std::env::var("TRAJKIT_BUDGET_CALLS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(300);
    let mut r = trajkit::rng::SplitMix64::new(20261126);
    let mut probs: Vec<_> = (0..30).map(|_| bent_path(&mut r, 30)).collect();
    for budget in [300.0, 1000.0, 3000.0] {
        let (mut ratios, mut refused, mut cut, mut preempted) = (Vec::new(), 0, 0, 0);
        let mut gain = Vec::new();
        for k in 0..calls {
            let (inp, wp) = &mut probs[k % 30];
            inp.options.interrupt_calculation_duration = Some(budget);
            let (us, res, clean) = unpreempted_us(3, 20, || plan_waypoints(inp, wp, 0.001));
            preempted += usize::from(!clean);
            match res {
                Ok(t) => {
                    cut += usize::from(t.was_interrupted());
                    gain.push(t.duration() / t.stop_at_every_waypoint_duration());
                }
                Err(_) => refused += 1,
            }
            ratios.push(us / budget);
        }
        ratios.sort_by(f64::total_cmp);
        let over = ratios.iter().filter(|&&x| x > 1.1).count();
        gain.sort_by(f64::total_cmp);
        let gain = gain.get(gain.len() / 2).copied().unwrap_or(f64::NAN);
        eprintln!(
            "budget {budget:5.0} µs: max {:.3}× p99 {:.3}× median {:.3}×, >1.1× in {over} of {calls}, \
             cut {cut}, refused {refused}, always preempted {preempted}; median duration {gain:.3}× \
             stopping at every waypoint",
            ratios[calls - 1],
            ratios[calls * 99 / 100],
            ratios[calls / 2]
        );
    }
}
