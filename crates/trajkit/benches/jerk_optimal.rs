//! Jerk-limited planner speed: the 7-waypoint standard problem (natural cubic spline through
//! the `standard_7wp_natural_N1000` fixture waypoints at s = 0, 1/6, …, 1, Panda velocity,
//! acceleration and jerk limits), default options; today's filter (`topp::jerk`, on a
//! TOPP-RA N = 1000 result) on the same input; and seeded random Panda paths of 10 and 100
//! waypoints for the growth with path length. tools/bench_topp_peer.py times toppra (Python)
//! on the same path.
//!
//! Run: `cargo bench -p trajkit --bench jerk_optimal`.

mod common;
#[path = "../tests/jerk_common/mod.rs"]
mod jerk_common;

use criterion::{criterion_group, Criterion};
use std::hint::black_box;
use trajkit::spline::CubicSpline;
use trajkit::topp::jerk::{limit_jerk, JerkOptions as FilterOptions};
use trajkit::topp::jerk_optimal::JerkOptimal;
use trajkit::topp::{Gridpoints, Toppra, ToppraOptions};
use trajkit::{Limits, Trajectory};

fn standard_path() -> CubicSpline {
    let wp = common::standard_7wp_waypoints();
    let n = wp.len() / 7;
    let ss: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    CubicSpline::natural(&ss, &wp, 7).unwrap()
}

fn bench(c: &mut Criterion) {
    let limits = Limits::preset("panda").unwrap();
    let path = standard_path();
    let mut g = c.benchmark_group("jerk_limited_standard_7wp");
    g.sample_size(10);
    g.bench_function("jerk_optimal_default", |b| {
        b.iter(|| {
            let traj = JerkOptimal::new(&path, &limits).unwrap().solve().unwrap();
            black_box(traj.duration())
        })
    });
    g.bench_function("filter_on_toppra_n1000", |b| {
        b.iter(|| {
            let raw = Toppra::with_limits(&path, &limits)
                .unwrap()
                .options(ToppraOptions {
                    gridpoints: Gridpoints::Uniform(1000),
                    refine: false,
                    ..ToppraOptions::default()
                })
                .solve()
                .unwrap();
            let f = limit_jerk(&path, raw.law().clone(), &limits, &FilterOptions::default());
            black_box(f.unwrap().duration())
        })
    });
    g.finish();
    let mut g = c.benchmark_group("jerk_optimal_waypoints");
    g.sample_size(10);
    for count in [10usize, 100] {
        let p = jerk_common::random_path(2026, count);
        g.bench_function(count.to_string(), |b| {
            b.iter(|| {
                let traj = JerkOptimal::new(&p, &limits).unwrap().solve().unwrap();
                black_box(traj.duration())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);

fn main() {
    benches();
    criterion::Criterion::default()
        .configure_from_args()
        .final_summary();
}
