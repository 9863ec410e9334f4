//! Evaluating a motion through waypoints allocates nothing: `at_time`, `at_time_with_jerk`
//! and the `Trajectory` model's `eval` run under a counting global allocator (planning
//! allocates; evaluation, the real-time path, does not).

mod alloc_counter;
use alloc_counter::{allocations, exercise};

use trajkit::otg::{plan_waypoints, DynInputParameter, Waypoints};
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
