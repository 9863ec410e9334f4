//! Evaluating a motion through waypoints allocates nothing: `at_time`, `at_time_with_jerk`
//! and the `Trajectory` model's `eval` run under a counting global allocator (planning
//! allocates; evaluation, the real-time path, does not). Nor does a cycle of the online loop
//! (`WaypointOtg::update` and `WaypointOutput::pass_to_input`) that does not calculate
//! (neither a new input nor the refinement of a motion the budget cut short).

mod alloc_counter;
use alloc_counter::{allocations, exercise};

use trajkit::otg::{
    plan_waypoints, DynInputParameter, OtgResult, WaypointOtg, WaypointOutput, Waypoints,
};
use trajkit::{Order, Trajectory};

#[test]
fn evaluation_allocates_nothing() {
    let mut input = DynInputParameter::new(3);
    input.target_position = vec![2.0, 2.0, -1.0];
    input.max_velocity = vec![1.0; 3];
    input.max_acceleration = vec![2.0; 3];
    input.max_jerk = vec![10.0; 3];
    let wp = Waypoints::new(vec![vec![0.5, 0.3, -0.2], vec![1.2, 1.0, -0.6]]);
    let tr = plan_waypoints(&input, &wp, 0.001).unwrap();
    let (mut p, mut v, mut a, mut j) = ([0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]);
    let t_end = tr.duration();
    let n = allocations(|| {
        for k in 0..=1000 {
            let t = -0.1 + (t_end + 0.2) * k as f64 / 1000.0;
            tr.at_time(t, &mut p, &mut v, &mut a);
            tr.at_time_with_jerk(t, &mut p, &mut v, &mut a, &mut j);
            for order in [
                Order::Position,
                Order::Velocity,
                Order::Acceleration,
                Order::Jerk,
            ] {
                tr.eval(t, order, &mut p);
            }
        }
        // Every order at 1001 times, clamping and NaN included.
        std::hint::black_box(exercise(&tr, 1000));
    });
    assert_eq!(n, 0);
    // The counter counts: planning allocates.
    assert!(allocations(|| drop(plan_waypoints(&input, &wp, 0.001))) > 0);
}

/// The online loop through waypoints: every cycle that does not calculate (follow, section
/// change, state and passed waypoint back into the generator's copy and the caller's input)
/// allocates nothing; cycles that calculate (the first, and the refinements of a motion the
/// budget cut short) may.
fn follow_counting(mut input: DynInputParameter, mut wp: Waypoints, dt: f64) -> (usize, usize) {
    let wp_len = wp.intermediate_positions.len();
    let mut otg = WaypointOtg::new(dt);
    let mut out = WaypointOutput::new(input.dof());
    let (mut calculating, mut following, mut passed) = (0, 0, 0);
    loop {
        let refining = otg.is_refining();
        let mut r = Ok(OtgResult::Working);
        let n = allocations(|| {
            r = otg.update(&input, &wp, &mut out);
            out.pass_to_input(&mut input, &mut wp);
        });
        let Ok(r) = r else {
            // A budget refused on a busy machine before any motion: try again.
            assert_eq!(calculating + following, 0);
            continue;
        };
        if out.output.new_calculation || refining {
            calculating += 1;
        } else {
            assert_eq!(n, 0, "cycle {} allocated", calculating + following);
            following += 1;
        }
        passed += usize::from(out.did_section_change);
        if r == OtgResult::Finished {
            break;
        }
    }
    assert_eq!(passed, wp_len + 1);
    (calculating, following)
}

#[test]
fn the_online_loop_allocates_nothing_when_it_does_not_calculate() {
    let mut input = DynInputParameter::new(3);
    input.max_velocity = vec![1.0; 3];
    input.max_acceleration = vec![2.0; 3];
    input.max_jerk = vec![10.0; 3];
    // 30 waypoints along a bent path, per-section limits (their lists shrink as waypoints
    // are passed).
    let wps: Vec<Vec<f64>> = (1..=30)
        .map(|k| {
            let k = k as f64;
            vec![0.3 * k, 0.1 * k + 0.05 * (k * 0.7).sin(), -0.2 * k]
        })
        .collect();
    input.target_position = vec![9.5, 3.2, -6.4];
    let mut wp = Waypoints::new(wps);
    wp.per_section_max_velocity = Some(vec![vec![0.9; 3]; 31]);
    let (calculating, following) = follow_counting(input.clone(), wp.clone(), 0.004);
    assert_eq!(calculating, 1);
    assert!(following > 1000);
    // With a budget that cuts the planning short, the cycles between refinements too (10
    // waypoints and a long control period: while refining, every cycle plans).
    wp.intermediate_positions.truncate(10);
    wp.per_section_max_velocity = Some(vec![vec![0.9; 3]; 11]);
    input.target_position = vec![3.5, 1.3, -2.4];
    let t0 = std::time::Instant::now();
    drop(plan_waypoints(&input, &wp, 0.01));
    input.options.interrupt_calculation_duration = Some(t0.elapsed().as_secs_f64() * 1e6 / 3.0);
    let (calculating, following) = follow_counting(input, wp, 0.01);
    assert!(
        calculating >= 1 && following > 100,
        "{calculating} {following}"
    );
}
