//! Movement primitives: DMP fit + rollout (7 joints, 1000 samples, 50 basis functions), ProMP
//! fit (10 demonstrations × 7 joints × 100 samples), KMP fit (7 joints, 200 reference points)
//! and a KMP mean + covariance query.
//!
//! Peer: `tools/bench_primitives_peer.py` times movement_primitives and a NumPy KMP on the same
//! inputs (the demonstrations are the closed-form functions below, repeated in the script).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use trajkit::primitives::{
    Demo, Dmp, DmpConfig, Kmp, KmpConfig, KmpReference, ProMp, ProMpConfig, RolloutOptions,
};
use trajkit::{Order, Trajectory};

/// Joint `j` of demonstration `m` at normalized time `s`.
fn q(m: usize, j: usize, s: f64) -> f64 {
    let mj = 10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5);
    let amp = 0.5 + 0.1 * j as f64 + 0.02 * m as f64;
    0.1 * j as f64 - 0.3
        + amp * mj
        + 0.2
            * (std::f64::consts::PI * s).sin().powi(2)
            * (3.0 * s + j as f64 + 0.1 * m as f64).sin()
}

fn demo(m: usize, n: usize, dur: f64) -> (Vec<f64>, Vec<f64>) {
    let t: Vec<f64> = (0..n).map(|k| dur * k as f64 / (n - 1) as f64).collect();
    let mut y = Vec::with_capacity(n * 7);
    for &tk in &t {
        for j in 0..7 {
            y.push(q(m, j, tk / dur));
        }
    }
    (t, y)
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("primitives");
    g.sample_size(30);

    let (t, y) = demo(0, 1000, 1.0);
    let cfg = DmpConfig::default();
    g.bench_function("dmp_fit_rollout_7dof_1000", |b| {
        b.iter(|| {
            let dmp = Dmp::fit(black_box(&t), black_box(&y), 7, &cfg).unwrap();
            // Default integration: 500 RK4 steps per τ (error 4.5e-10 of the range here).
            black_box(dmp.rollout(&RolloutOptions::default()).unwrap())
        })
    });
    g.bench_function("dmp_fit_7dof_1000", |b| {
        b.iter(|| black_box(Dmp::fit(black_box(&t), black_box(&y), 7, &cfg).unwrap()))
    });
    let dmp = Dmp::fit(&t, &y, 7, &cfg).unwrap();
    g.bench_function("dmp_rollout_7dof_500_steps", |b| {
        b.iter(|| black_box(dmp.rollout(&RolloutOptions::default()).unwrap()))
    });
    g.bench_function("dmp_fit_rollout_7dof_1000_steps", |b| {
        let opts = RolloutOptions {
            steps_per_tau: Some(1000),
            ..Default::default()
        };
        b.iter(|| {
            let dmp = Dmp::fit(black_box(&t), black_box(&y), 7, &cfg).unwrap();
            black_box(dmp.rollout(&opts).unwrap())
        })
    });

    let demos: Vec<(Vec<f64>, Vec<f64>)> = (0..10).map(|m| demo(m, 100, 1.0)).collect();
    let ds: Vec<Demo> = demos.iter().map(|(t, q)| Demo { t, q }).collect();
    let pcfg = ProMpConfig::default();
    g.bench_function("promp_fit_10x7x100", |b| {
        b.iter(|| black_box(ProMp::fit(black_box(&ds), 7, &pcfg).unwrap()))
    });

    // KMP reference: sample mean and covariance of 10 demonstrations at 200 times.
    let kd: Vec<(Vec<f64>, Vec<f64>)> = (0..10).map(|m| demo(m, 200, 2.0)).collect();
    let refs: Vec<&[f64]> = kd.iter().map(|(_, q)| q.as_slice()).collect();
    let reference = KmpReference::from_aligned_samples(&kd[0].0, &refs, 7, 1e-6).unwrap();
    let kcfg = KmpConfig::default();
    g.sample_size(10);
    g.bench_function("kmp_fit_7dof_200", |b| {
        b.iter(|| black_box(Kmp::fit(black_box(&reference), &kcfg).unwrap()))
    });
    let kmp = Kmp::fit(&reference, &kcfg).unwrap();
    g.sample_size(50);
    g.bench_function("kmp_query_mean_cov_7dof_200", |b| {
        let (mut m, mut cov) = ([0.0; 7], [0.0; 49]);
        b.iter(|| {
            kmp.eval(black_box(0.77), Order::Position, &mut m);
            kmp.covariance(black_box(0.77), Order::Position, &mut cov);
            black_box((m[0], cov[0]))
        })
    });
    g.bench_function("kmp_query_mean_7dof_200", |b| {
        let mut m = [0.0; 7];
        b.iter(|| {
            kmp.eval(black_box(0.77), Order::Position, &mut m);
            black_box(m[0])
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
