//! TOPP-RA, TOTG and NI output, retimed paths, scaled trajectories and rest-to-rest sequences
//! evaluate without allocating (counting global allocator, as in no_alloc.rs).

mod alloc_counter;
use alloc_counter::{allocations, exercise};

use trajkit::spline::CubicSpline;
use trajkit::topp::messy::{plan_waypoints, PlanOptions};
use trajkit::topp::{Gridpoints, QuinticLaw, Retimed, Scaled, Toppra, ToppraOptions};
use trajkit::{Limits, Trajectory};

#[test]
fn topp_outputs_evaluate_without_allocating() {
    let lim = Limits::preset("panda").unwrap();
    let wp: Vec<f64> = (0..5)
        .flat_map(|i| {
            (0..7).map(move |j| {
                // Inside the Panda's ranges (joint 4 negative, joint 6 positive).
                let offset = [0.0, 0.0, 0.0, -1.5, 0.0, 1.0, 0.0][j];
                0.3 * ((i * 7 + j) as f64).sin() + offset
            })
        })
        .collect();
    let ss: Vec<f64> = (0..5).map(|i| i as f64 / 4.0).collect();
    let path = CubicSpline::natural(&ss, &wp, 7).unwrap();
    let opts = ToppraOptions {
        gridpoints: Gridpoints::Uniform(100),
        refine: false,
        ..ToppraOptions::default()
    };
    let traj = Toppra::with_limits(&path, &lim)
        .unwrap()
        .options(opts.clone())
        .solve()
        .unwrap();
    let retimed = Retimed::new(&path, QuinticLaw::new(0.0, 1.0, 3.0).unwrap()).unwrap();
    let scaled = Scaled::new(&traj, 1.7).unwrap();
    let seq = plan_waypoints(
        &wp,
        7,
        &lim,
        &PlanOptions {
            toppra: opts,
            ..PlanOptions::default()
        },
    )
    .unwrap();
    let totg = trajkit::topp::plan_totg(&wp, 7, &lim, &Default::default()).unwrap();
    let ni_opts = PlanOptions {
        solver: trajkit::topp::messy::PieceSolver::Ni,
        ..PlanOptions::default()
    };
    let ni = plan_waypoints(&wp, 7, &lim, &ni_opts).unwrap();
    for tr in [
        &traj as &dyn Trajectory,
        &retimed,
        &scaled,
        &seq,
        &totg,
        &ni,
    ] {
        let mut s = 0.0;
        let n = allocations(|| s = exercise(tr, 2000));
        assert!(s.is_finite());
        assert_eq!(n, 0, "evaluation allocated {n} times");
    }
}
