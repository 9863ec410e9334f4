//! `trajkit::plan` speed, jerk stage included: 7-DOF Panda (velocity, acceleration and jerk
//! limits of the preset).
//!
//! - `plan_default/std7`: [`plan`] with `PlanOptions::default()` (TOPP-RA on the auto grid with
//!   its between-gridpoint guarantee, the default jerk stage, 1 kHz samples and their check)
//!   on the 7 waypoints of the `standard_7wp_natural_N1000` fixture problem;
//! - `plan_default/random_W`: the same through W seeded random Panda waypoints (W = 10, 100);
//! - `plan_default/line`: a 2-waypoint straight line (the exact 1-D optimum);
//! - `plan_raw/std7_n1000`: what `trajkit.plan(wp, limits, jerk_limit=False, gridpoints=1000)`
//!   runs from Python on the standard problem (`tools/bench_python.py`'s plan row): the
//!   fixture's velocity and acceleration limits, unbounded positions and jerk, no jerk stage,
//!   TOPP-RA on 1000 uniform intervals, 1 kHz samples and their check;
//! - `jerk_scale/analytic` and `jerk_scale/sampled_20khz`: the filter's time-scale factor
//!   on the standard problem's TOPP-RA result, by the per-segment bound
//!   ([`trajkit::topp::jerk::scale_bound`]) and by sampling the filtered trajectory at 20 kHz
//!   (what the filter did before the bound);
//! - `toppra_default/std7`: the TOPP-RA stage alone (the paths and the auto-grid solve);
//! - `toppra_default/random_W`: the same through W seeded random Panda waypoints (W = 10, 100,
//!   1000): the cost per waypoint should stay flat.
//!
//! Run: `cargo bench -p trajkit --bench plan`.

mod common;

use criterion::{criterion_group, BenchmarkId, Criterion};
use std::hint::black_box;
use trajkit::io::Waypoints;
use trajkit::plan::{plan, JerkStage, PlanOptions};
use trajkit::topp::jerk::{filter_window, scale_bound, FilteredProfile};
use trajkit::topp::messy;
use trajkit::topp::{min_time_scale, Gridpoints, Retimed};
use trajkit::{Limits, Trajectory};

/// The Panda preset with the `standard_7wp_natural_N1000` fixture's velocity and acceleration
/// limits, positions and jerk unbounded: the limits of `tools/bench_python.py`'s plan row.
fn fixture_limits() -> Limits {
    let prob = common::standard_7wp_problem();
    let row = |k: &str| -> Vec<f64> {
        let a = prob[k].as_array().unwrap();
        a.iter().map(|x| x.as_f64().unwrap()).collect()
    };
    let (vmax, amax) = (row("vmax"), row("amax"));
    let mut joints = Limits::preset("panda").unwrap().joints().to_vec();
    for (j, jl) in joints.iter_mut().enumerate() {
        jl.velocity = vmax[j];
        jl.acceleration = amax[j];
        jl.min_velocity = None;
        jl.min_acceleration = None;
        jl.jerk = f64::INFINITY;
        jl.position_min = f64::NEG_INFINITY;
        jl.position_max = f64::INFINITY;
    }
    Limits::new(joints).unwrap()
}

fn bench(c: &mut Criterion) {
    let limits = Limits::preset("panda").unwrap();
    let std7 = Waypoints::new(common::standard_7wp_waypoints(), 7, vec![]).unwrap();
    let raw_limits = fixture_limits();
    let raw_options = PlanOptions {
        gridpoints: Gridpoints::Uniform(1000),
        jerk: JerkStage::Off,
        ..PlanOptions::default()
    };
    let mut g = c.benchmark_group("plan_raw");
    g.bench_function("std7_n1000", |b| {
        b.iter(|| black_box(plan(&std7, &raw_limits, &raw_options).unwrap().duration()))
    });
    g.finish();
    let q0 = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];
    let line: Vec<f64> = q0
        .iter()
        .copied()
        .chain(q0.iter().map(|q| q + 0.5))
        .collect();
    let line = Waypoints::new(line, 7, vec![]).unwrap();
    let mut g = c.benchmark_group("plan_default");
    let mut cases = vec![("std7".to_string(), std7.clone()), ("line".into(), line)];
    for n in [10usize, 100] {
        cases.push((format!("random_{n}"), common::random_panda_waypoints(n)));
    }
    for (name, w) in &cases {
        g.bench_with_input(BenchmarkId::from_parameter(name), w, |b, w| {
            b.iter(|| {
                black_box(
                    plan(w, &limits, &PlanOptions::default())
                        .unwrap()
                        .duration(),
                )
            })
        });
    }
    g.finish();

    let mo = messy::PlanOptions::default();
    let mut g = c.benchmark_group("toppra_default");
    let mut cases = vec![("std7".to_string(), std7.clone())];
    for n in [10usize, 100, 1000] {
        cases.push((format!("random_{n}"), common::random_panda_waypoints(n)));
    }
    for (name, w) in &cases {
        if name == "random_1000" {
            g.sample_size(10);
        }
        g.bench_with_input(BenchmarkId::from_parameter(name), w, |b, w| {
            b.iter(|| {
                let paths = messy::piece_paths(w.points(), 7, &limits, &mo).unwrap();
                let raw = messy::time_pieces(paths, &limits, &mo, &mut |_, _| {}).unwrap();
                black_box(raw.duration())
            })
        });
    }
    g.finish();

    let paths = messy::piece_paths(std7.points(), 7, &limits, &mo).unwrap();
    let raw = messy::time_pieces(paths, &limits, &mo, &mut |_, _| {}).unwrap();
    let piece = &raw.pieces()[0];
    let w = filter_window(piece.law(), piece.path(), &limits, 0.5)
        .unwrap()
        .unwrap();
    let law = FilteredProfile::new(piece.law().clone(), w).unwrap();
    let mut g = c.benchmark_group("jerk_scale");
    g.bench_function("analytic", |b| {
        b.iter(|| black_box(scale_bound(piece.path(), &law, &limits).factor))
    });
    let traj = Retimed::new(piece.path(), law.clone()).unwrap();
    g.bench_function("sampled_20khz", |b| {
        b.iter(|| black_box(min_time_scale(&traj, &limits, 20_000.0).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, bench);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
}
