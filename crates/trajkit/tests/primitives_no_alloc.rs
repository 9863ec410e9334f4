//! Evaluating a movement primitive's trajectory (DMP rollout, ProMP mean and samples, KMP
//! mean) and a KMP covariance query allocate nothing, under a counting global allocator.

use trajkit::primitives::{
    Demo, Dmp, DmpConfig, Kmp, KmpConfig, KmpReference, ProMp, ProMpConfig, RolloutOptions,
};
use trajkit::rng::SplitMix64;
use trajkit::Trajectory;

mod alloc_counter;
use alloc_counter::{allocations, exercise};

#[test]
fn primitive_trajectories_evaluate_without_allocating() {
    let t: Vec<f64> = (0..200).map(|k| k as f64 / 199.0).collect();
    let demos: Vec<Vec<f64>> = (0..4)
        .map(|m| {
            t.iter()
                .flat_map(|&s| [(1.0 + 0.1 * m as f64) * s * s, (3.0 * s + m as f64).sin()])
                .collect()
        })
        .collect();
    let dmp = Dmp::fit(&t, &demos[0], 2, &DmpConfig::default()).unwrap();
    let roll = dmp.rollout(&RolloutOptions::default()).unwrap();
    let ds: Vec<Demo> = demos.iter().map(|q| Demo { t: &t, q }).collect();
    let promp = ProMp::fit(&ds, 2, &ProMpConfig::default()).unwrap();
    let sample = promp.sample(&mut SplitMix64::new(1)).unwrap();
    let tk: Vec<f64> = t.iter().step_by(10).cloned().collect();
    let sub: Vec<Vec<f64>> = demos
        .iter()
        .map(|q| q.chunks(2).step_by(10).flatten().cloned().collect())
        .collect();
    let subs: Vec<&[f64]> = sub.iter().map(|q| q.as_slice()).collect();
    let r = KmpReference::from_aligned_samples(&tk, &subs, 2, 1e-4).unwrap();
    let kmp = Kmp::fit(&r, &KmpConfig::default()).unwrap();
    // KMP covariance queries (positions and velocities) too.
    let mut cov = [0.0; 4];
    let n = allocations(|| {
        for k in 0..=50 {
            kmp.covariance(k as f64 / 50.0, trajkit::Order::Position, &mut cov);
            kmp.covariance(k as f64 / 50.0, trajkit::Order::Velocity, &mut cov);
            std::hint::black_box(cov[0]);
        }
    });
    assert_eq!(n, 0);
    for tr in [&roll as &dyn Trajectory, &promp, &sample, &kmp] {
        let n = allocations(|| {
            std::hint::black_box(exercise(tr, 500));
        });
        assert_eq!(n, 0);
    }
}
