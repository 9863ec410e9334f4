//! The online loop through waypoints (`otg::WaypointOtg`, Ruckig Pro's `update` with
//! `intermediate_positions`): the loop reaches the target through every waypoint in order,
//! reports one section change per waypoint (and one at the target), writes the followed
//! trajectory's own states and passes them back, replans when the input changes, and, with a
//! calculation budget, refines an interrupted motion only to motions that arrive at least one
//! control period sooner. Bad input is a typed error that keeps the motion being followed.

use std::time::Instant;
use trajkit::otg::{
    check_waypoints, plan_waypoints, DynInputParameter, OtgError, OtgResult, WaypointOtg,
    WaypointOutput, WaypointTrajectory, Waypoints,
};

/// Ruckig's example 04: 3 DOF, four waypoints, a moving target.
fn example_04() -> (DynInputParameter, Waypoints) {
    let mut inp = DynInputParameter::new(3);
    inp.current_position = vec![0.2, 0.0, -0.3];
    inp.current_velocity = vec![0.0, 0.2, 0.0];
    inp.current_acceleration = vec![0.0, 0.6, 0.0];
    inp.target_position = vec![0.5, 1.0, 0.0];
    inp.target_velocity = vec![0.2, 0.0, 0.3];
    inp.target_acceleration = vec![0.0, 0.1, -0.1];
    inp.max_velocity = vec![1.0, 2.0, 1.0];
    inp.max_acceleration = vec![3.0, 2.0, 2.0];
    inp.max_jerk = vec![6.0, 10.0, 20.0];
    let wp = Waypoints::new(vec![
        vec![1.4, -1.6, 1.0],
        vec![-0.6, -0.5, 0.4],
        vec![-0.4, -0.35, 0.0],
        vec![0.8, 1.8, -0.1],
    ]);
    (inp, wp)
}

/// A 7-DOF path (Franka Panda limits) through `m` waypoints, at rest at both ends: joint
/// `i` moves by `step(k) = 0.3 + 0.15·(sin(1.3(k+1) + i + phase) − sin(1.3k + i + phase))`
/// (always positive) in section `k`, up for even joints and down for odd ones, so the path
/// bends at every waypoint and no joint reverses.
fn bent_path(phase: f64, m: usize) -> (DynInputParameter, Waypoints) {
    let lim = trajkit::Limits::preset("panda").unwrap();
    let joints: Vec<_> = (0..7).map(|i| lim.joint(i)).collect();
    let mut p = DynInputParameter::new(7);
    p.max_velocity = joints.iter().map(|j| j.velocity).collect();
    p.max_acceleration = joints.iter().map(|j| j.acceleration).collect();
    p.max_jerk = joints.iter().map(|j| j.jerk).collect();
    let at = |k: usize| -> Vec<f64> {
        (0..7)
            .map(|i| {
                let (k, f) = (k as f64, i as f64);
                let dir = if i % 2 == 0 { 1.0 } else { -1.0 };
                dir * (0.3 * k + 0.15 * (1.3 * k + f + phase).sin()) - 0.5 * dir
            })
            .collect()
    };
    p.current_position = at(0);
    p.target_position = at(m + 1);
    (p, Waypoints::new((1..=m).map(at).collect()))
}

/// The trajectory's state at `t` (position, velocity, acceleration, jerk).
fn state(tr: &WaypointTrajectory, t: f64) -> [Vec<f64>; 4] {
    let n = tr.dof();
    let [mut p, mut v, mut a, mut j] = [0; 4].map(|_| vec![0.0; n]);
    tr.at_time_with_jerk(t, &mut p, &mut v, &mut a, &mut j);
    [p, v, a, j]
}

/// Whether two motions through waypoints are the same plan: durations, section start times
/// and waypoint velocities bit for bit (the profiles hold NaN placeholders, so `==` on the
/// trajectories says no).
fn same(a: &WaypointTrajectory, b: &WaypointTrajectory) -> bool {
    a.duration() == b.duration()
        && a.section_start_times() == b.section_start_times()
        && a.waypoint_velocities() == b.waypoint_velocities()
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The largest distance one DOF travels in `dt` at its velocity limit.
fn cycle_travel(inp: &DynInputParameter, dt: f64) -> f64 {
    inp.max_velocity.iter().fold(0.0, |m: f64, v| m.max(v * dt))
}

#[test]
fn the_loop_passes_every_waypoint_in_order_and_reaches_the_target() {
    let dt = 0.01;
    let (mut inp, mut wp) = example_04();
    let wps = wp.intermediate_positions.clone();
    let reference = plan_waypoints(&inp, &wp, dt).unwrap();
    let starts = reference.section_start_times().to_vec();
    let mut otg = WaypointOtg::new(dt);
    let mut out = WaypointOutput::new(3);
    let (mut steps, mut calculations, mut changes) = (0, 0, Vec::new());
    loop {
        let r = otg.update(&inp, &wp, &mut out).unwrap();
        steps += 1;
        calculations += usize::from(out.output.new_calculation);
        let t = out.output.time;
        assert_eq!(otg.time(), t);
        // The state written is the followed trajectory's, bit for bit (one calculation: the
        // reference's).
        let [p, v, a, j] = state(&reference, t);
        assert_eq!(out.output.new_position, p);
        assert_eq!(out.output.new_velocity, v);
        assert_eq!(out.output.new_acceleration, a);
        assert_eq!(out.output.new_jerk, j);
        assert_eq!(out.new_section, reference.section_index_at(t));
        if out.did_section_change {
            let k = out.new_section;
            changes.push((k, wp.intermediate_positions.len()));
            // The section ended in this cycle, and the state is within one cycle's travel of
            // the waypoint (or the target) it passed.
            assert!(t >= starts.get(k).copied().unwrap_or(reference.duration()));
            assert!(t - dt < starts.get(k).copied().unwrap_or(reference.duration()));
            let goal = wps.get(k - 1).unwrap_or(&inp.target_position);
            assert!(dist(&p, goal) <= cycle_travel(&inp, dt), "section {k}");
        }
        // The state passed back is the trajectory's; the generator follows it without a
        // calculation.
        out.pass_to_input(&mut inp, &mut wp);
        assert_eq!(inp.current_position, p);
        assert_eq!(inp.current_velocity, v);
        assert_eq!(inp.current_acceleration, a);
        assert!(otg.follows(&inp, &wp));
        if r == OtgResult::Finished {
            break;
        }
        assert!(steps < 100_000);
    }
    assert_eq!(calculations, 1);
    assert_eq!(steps, (reference.duration() / dt).floor() as usize + 1);
    // One change per waypoint and one at the target, in order; each passed waypoint left
    // the input.
    assert_eq!(changes, vec![(1, 4), (2, 3), (3, 2), (4, 1), (5, 0)]);
    assert!(wp.intermediate_positions.is_empty());
    assert_eq!(out.output.duration, reference.duration());
    assert!(same(otg.trajectory().unwrap(), &reference));
    // Each waypoint lies on the followed motion (to the generator's tolerance).
    for (k, w) in wps.iter().enumerate() {
        assert!(dist(&state(&reference, starts[k + 1])[0], w) <= 1e-8);
    }
    assert!(dist(&out.output.new_position, &inp.target_position) <= cycle_travel(&inp, dt));
}

#[test]
fn a_changed_input_replans_from_the_current_state() {
    let dt = 0.004;
    let (mut inp, mut wp) = bent_path(0.4, 4);
    let mut otg = WaypointOtg::new(dt);
    let mut out = WaypointOutput::new(7);
    // Follow until two waypoints are passed.
    while wp.intermediate_positions.len() > 2 {
        assert_eq!(otg.update(&inp, &wp, &mut out).unwrap(), OtgResult::Working);
        out.pass_to_input(&mut inp, &mut wp);
    }
    assert_eq!(out.new_section, 2);
    for change in 0..3 {
        match change {
            0 => inp.target_position[3] += 0.1,
            1 => wp.intermediate_positions[0][1] -= 0.05,
            _ => inp.max_velocity[0] *= 0.9,
        }
        let fresh = plan_waypoints(&inp, &wp, dt).unwrap();
        assert_eq!(otg.update(&inp, &wp, &mut out).unwrap(), OtgResult::Working);
        assert!(out.output.new_calculation && !out.output.was_calculation_interrupted);
        assert_eq!((out.output.time, out.new_section), (dt, 0));
        assert!(!out.did_section_change);
        assert!(same(otg.trajectory().unwrap(), &fresh), "change {change}");
        assert_eq!(out.output.new_position, state(&fresh, dt)[0]);
        out.pass_to_input(&mut inp, &mut wp);
        // Fed back: followed, not planned again.
        otg.update(&inp, &wp, &mut out).unwrap();
        assert!(!out.output.new_calculation && out.output.time == 2.0 * dt);
        out.pass_to_input(&mut inp, &mut wp);
    }
    // Reset forgets the motion: the same input is planned again.
    otg.reset();
    assert!(!otg.follows(&inp, &wp) && otg.trajectory().is_none());
    otg.update(&inp, &wp, &mut out).unwrap();
    assert!(out.output.new_calculation);
}

#[test]
fn per_section_fields_shrink_with_the_waypoints() {
    let dt = 0.002;
    let (mut inp, mut wp) = bent_path(1.1, 3);
    let vmax: Vec<Vec<f64>> = (0..4)
        .map(|s| {
            inp.max_velocity
                .iter()
                .map(|v| v * (0.6 + 0.1 * s as f64))
                .collect()
        })
        .collect();
    wp.per_section_max_velocity = Some(vmax.clone());
    wp.per_section_minimum_duration = Some(vec![0.0, 1.5, 0.0, 0.0]);
    let reference = plan_waypoints(&inp, &wp, dt).unwrap();
    let mut otg = WaypointOtg::new(dt);
    let mut out = WaypointOutput::new(7);
    let mut calculations = 0;
    while otg.update(&inp, &wp, &mut out).unwrap() == OtgResult::Working {
        calculations += usize::from(out.output.new_calculation);
        out.pass_to_input(&mut inp, &mut wp);
        let sections = wp.sections();
        assert_eq!(
            wp.per_section_max_velocity.as_ref().unwrap().len(),
            sections
        );
        assert_eq!(
            wp.per_section_max_velocity.as_ref().unwrap()[0],
            vmax[4 - sections]
        );
        assert_eq!(
            wp.per_section_minimum_duration.as_ref().unwrap().len(),
            sections
        );
    }
    assert_eq!(calculations, 1);
    assert!(out.output.time > reference.duration());
    let ends = reference.section_start_times();
    assert!(ends[2] - ends[1] >= 1.5 - 1e-9);
    // With no waypoint left, passing one changes nothing.
    let before = wp.clone();
    wp.pass_first_waypoint();
    assert_eq!(wp, before);
}

#[test]
fn bad_input_is_a_typed_error_and_keeps_the_motion() {
    let (mut inp, mut wp) = example_04();
    let mut out = WaypointOutput::new(3);
    for dt in [0.0, -0.01, f64::NAN, f64::INFINITY] {
        let e = WaypointOtg::new(dt)
            .update(&inp, &wp, &mut out)
            .unwrap_err();
        assert!(
            matches!(e, OtgError::InvalidInput { field: "delta_time", dof: None, value, .. }
                if value.to_bits() == dt.to_bits()),
            "{e:?}"
        );
    }
    let mut otg = WaypointOtg::new(0.01);
    for _ in 0..10 {
        otg.update(&inp, &wp, &mut out).unwrap();
        out.pass_to_input(&mut inp, &mut wp);
    }
    let kept = out.clone();
    let mut bad = wp.clone();
    bad.intermediate_positions[1][2] = f64::NAN;
    let e = otg.update(&inp, &bad, &mut out).unwrap_err();
    assert!(matches!(
        e,
        OtgError::Waypoints {
            index: 1,
            dof: Some(2),
            field: "intermediate_positions",
            ..
        }
    ));
    assert_eq!(out, kept);
    let mut short = inp.clone();
    short.max_jerk.pop();
    assert!(matches!(
        otg.update(&short, &wp, &mut out),
        Err(OtgError::InvalidInput { .. })
    ));
    // The good input fed back: the motion continues where it was, no calculation.
    otg.update(&inp, &wp, &mut out).unwrap();
    assert!(!out.output.new_calculation);
    assert!((out.output.time - 11.0 * 0.01).abs() < 1e-12);
}

/// Runs the loop to the end (retrying a first calculation the budget refused: wall-clock
/// time on a busy machine); returns the trajectories of the calculations, each with the
/// input it was planned for and the time left on the motion it replaced, the cycles, and
/// the sections passed.
#[allow(clippy::type_complexity)]
fn follow(
    mut inp: DynInputParameter,
    mut wp: Waypoints,
    dt: f64,
) -> (
    Vec<(DynInputParameter, Waypoints, WaypointTrajectory, f64, bool)>,
    usize,
    usize,
    WaypointOutput,
) {
    let mut otg = WaypointOtg::new(dt);
    let mut out = WaypointOutput::new(inp.dof());
    let (mut plans, mut cycles, mut passed) = (Vec::new(), 0, 0);
    let mut left = f64::INFINITY;
    let mut attempts = 0;
    loop {
        let r = match otg.update(&inp, &wp, &mut out) {
            Err(OtgError::Interrupted { .. }) if cycles == 0 && attempts < 5 => {
                assert!(out.output.was_calculation_interrupted);
                attempts += 1;
                continue;
            }
            r => r.unwrap(),
        };
        cycles += 1;
        if out.output.new_calculation {
            let tr = otg.trajectory().unwrap().clone();
            let interrupted = out.output.was_calculation_interrupted;
            assert_eq!(interrupted, tr.was_interrupted());
            // A complete calculation ends the refinement; an interrupted one starts it.
            assert_eq!(otg.is_refining(), interrupted);
            plans.push((inp.clone(), wp.clone(), tr, left, interrupted));
        }
        left = out.output.duration - out.output.time;
        passed += usize::from(out.did_section_change);
        out.pass_to_input(&mut inp, &mut wp);
        if r == OtgResult::Finished {
            break;
        }
        assert!(cycles < 1_000_000);
    }
    (plans, cycles, passed, out)
}

#[test]
fn without_a_budget_one_calculation_and_no_refinement() {
    let (inp, wp) = bent_path(2.0, 12);
    let free = plan_waypoints(&inp, &wp, 0.004).unwrap();
    let (plans, cycles, passed, out) = follow(inp.clone(), wp.clone(), 0.004);
    assert_eq!(plans.len(), 1);
    assert!(!plans[0].4);
    assert!(same(&plans[0].2, &free));
    assert_eq!(passed, 13);
    assert_eq!(cycles, (free.duration() / 0.004).floor() as usize + 1);
    assert!(dist(&out.output.new_position, &inp.target_position) <= 1e-8);
}

#[test]
fn an_interrupted_motion_is_refined_only_to_one_arriving_a_period_sooner() {
    // 10 waypoints: the search takes far longer than stopping at every waypoint, so a budget
    // of a third of the full planning (measured here) cuts it short with a valid motion.
    // (While refining, every cycle plans: a long control period keeps the test short.)
    let dt = 0.01;
    let (mut inp, wp) = bent_path(0.7, 10);
    let mut full_us = f64::INFINITY;
    for _ in 0..3 {
        let t0 = Instant::now();
        assert!(!plan_waypoints(&inp, &wp, dt).unwrap().was_interrupted());
        full_us = full_us.min(t0.elapsed().as_secs_f64() * 1e6);
    }
    inp.options.interrupt_calculation_duration = Some(full_us / 3.0);
    let (plans, cycles, passed, out) = follow(inp.clone(), wp.clone(), dt);
    assert_eq!(passed, 11);
    assert!(dist(&out.output.new_position, &inp.target_position) <= 1e-8);
    let first = &plans[0].2;
    assert!(plans[0].4, "the first calculation was not interrupted");
    assert!(first.duration() <= first.stop_at_every_waypoint_duration() * (1.0 + 1e-12));
    for (k, (pi, pw, tr, left, _)) in plans.iter().enumerate() {
        // Every motion followed is valid for the state and waypoints it was planned from.
        let c = check_waypoints(pi, pw, tr).unwrap();
        assert!(c.waypoint_error <= 1e-8, "plan {k}: {c:?}");
        assert!(
            c.solution.worst_limit_ratio <= 1.0 + 1e-9,
            "plan {k}: {c:?}"
        );
        if k > 0 {
            // A switch arrives at least one control period sooner than the motion it replaces,
            // and only an interrupted motion is replaced.
            assert!(tr.duration() <= left - dt, "plan {k}");
            assert!(plans[k - 1].4, "plan {k} replaced a complete motion");
        }
    }
    // The loop ends no later than the first motion would have.
    assert!(cycles as f64 * dt <= first.duration() + dt + 1e-9);
    eprintln!(
        "budget {:.0} µs: {} calculations, first motion {:.3} s, arrival after {:.3} s",
        full_us / 3.0,
        plans.len(),
        first.duration(),
        cycles as f64 * dt
    );
}
