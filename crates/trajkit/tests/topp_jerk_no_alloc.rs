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
