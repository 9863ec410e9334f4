//! Polynomial evaluation: a 7-joint quintic move and a 7-joint, 8-waypoint piecewise quintic,
//! evaluated (position, velocity, acceleration, jerk) at 100 000 sorted times.
//!
//! Peer: `tools/bench_poly_peer.py` evaluates the same coefficients with NumPy.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use trajkit::poly::{Degree, PolyMove, ViaTiming, ViaTrajectory, ViaVelocities};
use trajkit::{Limits, Order, Trajectory};

const N: usize = 100_000;

fn bench(c: &mut Criterion) {
    let q0 = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];
    let q1 = [1.2, 0.3, -0.5, -1.2, 0.6, 2.2, -0.4];
    let mv = PolyMove::rest_to_rest(Degree::Quintic, &q0, &q1, 2.0).unwrap();
    let limits = Limits::preset("panda").unwrap();
    let wps = trajkit_default_waypoints();
    let via = ViaTrajectory::new(
        &wps,
        7,
        Degree::Quintic,
        ViaVelocities::Heuristic,
        ViaTiming::Limits(&limits),
    )
    .unwrap();

    let mut g = c.benchmark_group("poly_eval");
    g.throughput(Throughput::Elements(N as u64));
    for (name, tr) in [
        ("quintic_move_7dof", &mv as &dyn Trajectory),
        ("via_quintic_7dof_8wp", &via),
    ] {
        let times: Vec<f64> = (0..N)
            .map(|i| tr.duration() * i as f64 / (N - 1) as f64)
            .collect();
        g.bench_function(format!("{name}/position"), |b| {
            let mut out = [0.0; 7];
            b.iter(|| {
                let mut s = 0.0;
                for &t in &times {
                    tr.eval(t, Order::Position, &mut out);
                    s += out[0];
                }
                black_box(s)
            })
        });
        g.bench_function(format!("{name}/pos_vel_acc_jerk"), |b| {
            let mut out = [0.0; 7];
            b.iter(|| {
                let mut s = 0.0;
                for &t in &times {
                    for o in Order::ALL {
                        tr.eval(t, o, &mut out);
                        s += out[6];
                    }
                }
                black_box(s)
            })
        });
    }
    g.finish();
}

fn trajkit_default_waypoints() -> Vec<f64> {
    vec![
        0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, //
        0.21, -0.52, 0.13, -2.10, 0.05, 1.69, 0.92, //
        0.55, -0.31, 0.28, -1.87, 0.18, 1.83, 1.12, //
        0.83, -0.18, 0.22, -1.64, 0.41, 1.62, 1.35, //
        1.02, 0.05, 0.05, -1.49, 0.63, 1.48, 1.21, //
        1.18, 0.27, -0.16, -1.31, 0.58, 1.71, 0.94, //
        1.41, 0.42, -0.34, -1.18, 0.39, 1.95, 0.66, //
        1.57, 0.35, -0.41, -1.42, 0.22, 2.10, 0.52,
    ]
}

criterion_group!(benches, bench);
criterion_main!(benches);
