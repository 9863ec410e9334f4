//! The jerk-limited planner's output (one piece, a time-scaled piece and a sequence) evaluates
//! without allocating (counting global allocator, as in no_alloc.rs).

mod alloc_counter;
use alloc_counter::{allocations, exercise};

use trajkit::spline::CubicSpline;
use trajkit::topp::jerk_optimal::{plan_sequence, JerkOptimal, JerkOptions};
use trajkit::topp::LinearPath;
use trajkit::{Limits, Trajectory};

#[test]
fn jerk_limited_outputs_evaluate_without_allocating() {
    let lim = Limits::preset("panda").unwrap();
    let wp: Vec<f64> = (0..3)
        .flat_map(|i| {
            (0..7).map(move |j| 0.3 * ((i * 7 + j) as f64).sin() - if j == 3 { 1.5 } else { 0.0 })
        })
        .collect();
    let path = CubicSpline::natural(&[0.0, 0.5, 1.0], &wp, 7).unwrap();
    let opts = JerkOptions {
        steps: Some(40),
        ..JerkOptions::default()
    };
    let one = JerkOptimal::new(&path, &lim)
        .unwrap()
        .options(opts.clone())
        .solve()
        .unwrap();
    // There and back: two rest-to-rest pieces.
    let there = LinearPath::new(&wp[..14], 7).unwrap();
    let back: Vec<f64> = wp[7..14].iter().chain(&wp[..7]).copied().collect();
    let back = LinearPath::new(&back, 7).unwrap();
    let seq = plan_sequence(vec![there, back], &lim, None, &opts).unwrap();
    for tr in [&one as &dyn Trajectory, &seq] {
        let mut s = 0.0;
        let n = allocations(|| s = exercise(tr, 2000));
        assert!(s.is_finite());
        assert_eq!(n, 0, "evaluation allocated {n} times");
    }
}

/// The filter's output, scaled and in a sequence behind a trait object (as `plan` holds it),
/// fills sample rows in blocks (`Trajectory::eval_rows`, what sampling calls) without
/// allocating, on sorted and on shuffled times.
#[test]
fn filtered_rows_evaluate_without_allocating() {
    use trajkit::topp::jerk::{limit_jerk_sequence, JerkOptions as FilterOptions};
    use trajkit::topp::messy::{plan_waypoints, PlanOptions};
    use trajkit::topp::Scaled;
    let lim = Limits::preset("panda").unwrap();
    let wp = [
        0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, //
        0.21, -0.52, 0.13, -2.10, 0.05, 1.69, 0.92, //
        0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, //
        0.55, -0.31, 0.28, -1.87, 0.18, 1.83, 1.12,
    ];
    let raw = plan_waypoints(&wp, 7, &lim, &PlanOptions::default()).unwrap();
    let seq = limit_jerk_sequence(&raw, &lim, &FilterOptions::default()).unwrap();
    let tr: Box<dyn Trajectory> = Box::new(Scaled::new(seq, 1.0 + 1e-7).unwrap());
    let d = tr.duration();
    let sorted: Vec<f64> = (0..=2000)
        .map(|i| -0.1 + (d + 0.2) * i as f64 / 2000.0)
        .collect();
    let shuffled: Vec<f64> = (0..2000)
        .map(|i| d * ((i * 7919) % 2000) as f64 / 2000.0)
        .collect();
    let mut cols = [0; 4].map(|_| vec![0.0; 2001 * 7]);
    for times in [&sorted, &shuffled] {
        let [a, b, c, e] = &mut cols;
        let n = allocations(|| tr.eval_rows(times, [a, b, c, e]));
        assert_eq!(n, 0, "eval_rows allocated {n} times");
    }
    assert!(cols.iter().flatten().all(|v| v.is_finite()));
}
