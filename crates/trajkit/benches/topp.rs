//! TOPP-RA speed: 7-DOF Panda, natural cubic spline through 7 random waypoints (the
//! `standard_7wp_natural_N1000` fixture problem), velocity and acceleration limits.
//! tools/bench_topp_peer.py times PyPI toppra on the same input.
//!
//! Run: `cargo bench -p trajkit --bench topp`.

mod common;

use criterion::{criterion_group, BenchmarkId, Criterion};
use std::hint::black_box;
use trajkit::spline::CubicSpline;
use trajkit::topp::{Gridpoints, Options, Toppra};
use trajkit::{Limits, Order, Trajectory};

fn standard_path() -> CubicSpline {
    let wp = common::standard_7wp_waypoints();
    let n = wp.len() / 7;
    let ss: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    CubicSpline::natural(&ss, &wp, 7).unwrap()
}

fn bench(c: &mut Criterion) {
    let path = standard_path();
    let limits = Limits::preset("panda").unwrap();
    let mut g = c.benchmark_group("toppra_solve");
    for n in [100usize, 1000, 10000] {
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter(|| {
                let prob = Toppra::with_limits(&path, &limits)
                    .unwrap()
                    .options(Options {
                        gridpoints: Gridpoints::Uniform(n),
                        refine: false,
                        ..Options::default()
                    });
                black_box(prob.solve_profile().unwrap().duration())
            })
        });
    }
    g.finish();
    let mut g = c.benchmark_group("toppra_solve_refined");
    g.sample_size(10);
    g.bench_function("1000", |b| {
        b.iter(|| {
            let prob = Toppra::with_limits(&path, &limits)
                .unwrap()
                .gridpoints(Gridpoints::Uniform(1000));
            black_box(prob.solve_profile().unwrap().duration())
        })
    });
    g.finish();
    let traj = Toppra::with_limits(&path, &limits)
        .unwrap()
        .options(Options {
            refine: false,
            ..Options::default()
        })
        .solve()
        .unwrap();
    c.bench_function("toppra_eval_state_1000_times", |b| {
        let mut q = [0.0; 7];
        let t_end = traj.duration();
        b.iter(|| {
            for k in 0..1000 {
                let t = t_end * k as f64 / 1000.0;
                for o in Order::ALL {
                    traj.eval(black_box(t), o, &mut q);
                }
            }
            black_box(q[0])
        })
    });
}

/// Back-to-back solves timed with `Instant`, reporting the minimum (the machine's unloaded
/// speed) and the median, next to criterion's statistics, because the shared benchmark machine
/// is often loaded by other jobs.
fn plain_timing() {
    let path = standard_path();
    let limits = Limits::preset("panda").unwrap();
    for n in [100usize, 1000, 10000] {
        let reps = if n == 10000 { 50 } else { 200 };
        let mut times: Vec<f64> = (0..reps)
            .map(|_| {
                let t0 = std::time::Instant::now();
                let prob = Toppra::with_limits(&path, &limits)
                    .unwrap()
                    .options(Options {
                        gridpoints: Gridpoints::Uniform(n),
                        refine: false,
                        ..Options::default()
                    });
                black_box(prob.solve_profile().unwrap().duration());
                t0.elapsed().as_secs_f64()
            })
            .collect();
        times.sort_by(f64::total_cmp);
        println!(
            "plain timing toppra_solve/{n}: min {:.1} us, median {:.1} us over {reps} solves",
            times[0] * 1e6,
            times[reps / 2] * 1e6
        );
    }
}

criterion_group!(benches, bench);

fn main() {
    benches();
    criterion::Criterion::default()
        .configure_from_args()
        .final_summary();
    plain_timing();
}
