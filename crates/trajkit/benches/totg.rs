//! TOTG speed: 7-DOF Panda, 7 waypoints (the waypoints of the `standard_7wp_natural_N1000`
//! TOPP-RA fixture problem), max deviation 0.1, velocity and acceleration limits, exact limits
//! (the full solve: blended path, integration, checks). Also: the same with every limit slowed
//! so the motion lasts 10× longer (the cost must not grow with the duration), a coarser arc
//! step, and NI on the natural spline of the TOPP-RA bench. tools/bench_totg_peer.py times the
//! original TOTG (tesseract-robotics) on the same inputs.
//!
//! Run: `cargo bench -p trajkit --bench totg`.

mod common;

use criterion::{criterion_group, Criterion};
use std::hint::black_box;
use trajkit::topp::{ni, plan_totg, Gridpoints, Toppra, TotgOptions};
use trajkit::{Limits, Trajectory};

/// The Panda's limits with velocity ÷ 10 and acceleration ÷ 100: the same optimal timing
/// stretched 10× in time.
fn slow_panda() -> Limits {
    let lim = Limits::preset("panda").unwrap();
    Limits::new(
        lim.joints()
            .iter()
            .map(|j| trajkit::JointLimits {
                velocity: j.velocity / 10.0,
                acceleration: j.acceleration / 100.0,
                ..j.clone()
            })
            .collect(),
    )
    .unwrap()
}

fn bench(c: &mut Criterion) {
    let w = common::standard_7wp_waypoints();
    // trajkit's embedded default Panda path (8 waypoints).
    let default: Vec<f64> = include_str!("../../trajkit-cli/src/default_waypoints.csv")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("panda"))
        .flat_map(|l| l.split(',').map(|v| v.trim().parse::<f64>().unwrap()))
        .collect();
    let panda = Limits::preset("panda").unwrap();
    let slow = slow_panda();
    let coarse = TotgOptions {
        arc_step: 5e-3,
        ..Default::default()
    };
    let mut g = c.benchmark_group("totg_solve");
    g.sample_size(30);
    for (name, lim, opts) in [
        ("panda_7wp_dev0.1", &panda, TotgOptions::default()),
        ("panda_7wp_dev0.1_10x_slower", &slow, TotgOptions::default()),
        ("panda_7wp_dev0.1_arc_step_5e-3", &panda, coarse),
        ("default_path_dev0.1", &panda, TotgOptions::default()),
    ] {
        let w = if name.starts_with("default") {
            &default
        } else {
            &w
        };
        let t = plan_totg(w, 7, lim, &opts).unwrap().duration();
        eprintln!("{name}: duration {t:.6} s");
        g.bench_function(name, |b| {
            b.iter(|| black_box(plan_totg(w, 7, lim, &opts).unwrap().duration()))
        });
    }
    g.finish();
    let n = w.len() / 7;
    let ss: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    let spline = trajkit::spline::CubicSpline::natural(&ss, &w, 7).unwrap();
    let mut g = c.benchmark_group("ni_solve");
    g.sample_size(10);
    g.bench_function("spline_7wp_1000_knots", |b| {
        b.iter(|| {
            let p = Toppra::with_limits(&spline, &panda)
                .unwrap()
                .gridpoints(Gridpoints::Uniform(1000));
            black_box(ni::solve_profile(&p).unwrap().profile.duration())
        })
    });
    g.finish();
}

criterion_group!(benches, bench);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
}
