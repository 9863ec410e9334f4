//! TOPP-RA speed: 7-DOF Panda, natural cubic spline through 7 random waypoints (the
//! `standard_7wp_natural_N1000` fixture problem), velocity and acceleration limits.
//! tools/bench_topp_peer.py times PyPI toppra on the same input.
//!
//! - `toppra_solve/N`: N uniform intervals, limits at gridpoints only (`refine: false`,
//!   toppra's guarantee);
//! - `toppra_solve_refined/1000`: 1000 uniform intervals, limits guaranteed between gridpoints
//!   (the default `refine`);
//! - `toppra_solve_default`: `ToppraOptions::default()` (grid chosen from the 1e-4 duration
//!   tolerance, limits guaranteed between gridpoints);
//! - `toppra_scaling/W`: `ToppraOptions::default()` on natural splines through W seeded random Panda
//!   waypoints (W = 10, 100, 1000): the cost per waypoint should stay flat.
//!
//! Run: `cargo bench -p trajkit --bench topp`.

mod common;

use criterion::{criterion_group, BenchmarkId, Criterion};
use std::hint::black_box;
use trajkit::spline::CubicSpline;
use trajkit::topp::{Gridpoints, Toppra, ToppraOptions};
use trajkit::{Limits, Order, Trajectory};

fn standard_path() -> CubicSpline {
    let wp = common::standard_7wp_waypoints();
    let n = wp.len() / 7;
    let ss: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    CubicSpline::natural(&ss, &wp, 7).unwrap()
}

/// A natural spline through `n` seeded random Panda configurations (0.1 inside the position
/// range), at s = 0, 1, …, n − 1.
fn random_path(n: usize) -> CubicSpline {
    let wp = common::random_panda_waypoints(n);
    let ss: Vec<f64> = (0..n).map(|i| i as f64).collect();
    CubicSpline::natural(&ss, wp.points(), 7).unwrap()
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
                    .options(ToppraOptions {
                        gridpoints: Gridpoints::Uniform(n),
                        refine: false,
                        ..ToppraOptions::default()
                    });
                black_box(prob.solve_profile().unwrap().duration())
            })
        });
    }
    g.finish();
    let mut g = c.benchmark_group("toppra_solve_refined");
    g.bench_function("1000", |b| {
        b.iter(|| {
            let prob = Toppra::with_limits(&path, &limits)
                .unwrap()
                .gridpoints(Gridpoints::Uniform(1000));
            black_box(prob.solve_profile().unwrap().duration())
        })
    });
    g.finish();
    c.bench_function("toppra_solve_default", |b| {
        b.iter(|| {
            let prob = Toppra::with_limits(&path, &limits).unwrap();
            black_box(prob.solve_profile().unwrap().duration())
        })
    });
    let mut g = c.benchmark_group("toppra_scaling");
    g.sample_size(10);
    for w in [10usize, 100, 1000] {
        let p = random_path(w);
        g.bench_with_input(BenchmarkId::from_parameter(w), &w, |b, _| {
            b.iter(|| {
                let prob = Toppra::with_limits(&p, &limits).unwrap();
                black_box(prob.solve_profile().unwrap().duration())
            })
        });
    }
    g.finish();
    let traj = Toppra::with_limits(&path, &limits)
        .unwrap()
        .options(ToppraOptions {
            refine: false,
            ..ToppraOptions::default()
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
                    .options(ToppraOptions {
                        gridpoints: Gridpoints::Uniform(n),
                        refine: false,
                        ..ToppraOptions::default()
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
    for (name, grid) in [
        ("toppra_solve_refined/1000", Gridpoints::Uniform(1000)),
        ("toppra_solve_default", ToppraOptions::default().gridpoints),
    ] {
        let reps = 200;
        let mut times: Vec<f64> = (0..reps)
            .map(|_| {
                let t0 = std::time::Instant::now();
                let prob = Toppra::with_limits(&path, &limits)
                    .unwrap()
                    .gridpoints(grid.clone());
                black_box(prob.solve_profile().unwrap().duration());
                t0.elapsed().as_secs_f64()
            })
            .collect();
        times.sort_by(f64::total_cmp);
        println!(
            "plain timing {name}: min {:.1} us, median {:.1} us over {reps} solves",
            times[0] * 1e6,
            times[reps / 2] * 1e6
        );
    }
    // What the scaling runs solve: gridpoints and duration per waypoint count.
    for w in [10usize, 100, 1000] {
        let p = random_path(w);
        let prof = Toppra::with_limits(&p, &limits)
            .unwrap()
            .solve_profile()
            .unwrap();
        println!(
            "toppra_scaling/{w}: {} gridpoints, duration {:.6} s",
            prof.gridpoints().len(),
            prof.duration()
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
