//! ProMP: fit, conditioning on via points, velocities in real units, sampling, bad input.

use trajkit::primitives::{Demo, ProMp, ProMpConfig, ViaPoint};
use trajkit::rng::SplitMix64;
use trajkit::{Order, Trajectory};

/// `m` noisy variations of a smooth 7-joint movement, 100 samples, durations around `dur`.
fn demos(m: usize, dur: f64, seed: u64) -> Vec<(Vec<f64>, Vec<f64>)> {
    let mut rng = SplitMix64::new(seed);
    (0..m)
        .map(|_| {
            let d = dur * rng.uniform(0.9, 1.1);
            let amp: Vec<f64> = (0..7).map(|_| rng.uniform(0.7, 1.3)).collect();
            let off: Vec<f64> = (0..7).map(|_| rng.uniform(-0.1, 0.1)).collect();
            let t: Vec<f64> = (0..100).map(|k| d * k as f64 / 99.0).collect();
            let mut q = Vec::with_capacity(700);
            for &tk in &t {
                let s = tk / d;
                for j in 0..7 {
                    q.push(off[j] + amp[j] * (2.0 * s + 0.3 * j as f64).sin() * s);
                }
            }
            (t, q)
        })
        .collect()
}

fn as_demos(v: &[(Vec<f64>, Vec<f64>)]) -> Vec<Demo<'_>> {
    v.iter().map(|(t, q)| Demo { t, q }).collect()
}

#[test]
fn mean_of_identical_demos_reproduces_them() {
    let d = demos(1, 1.0, 1);
    let two = vec![d[0].clone(), d[0].clone()];
    let p = ProMp::fit(&as_demos(&two), 7, &ProMpConfig::default()).unwrap();
    let mut y = [0.0; 7];
    let (t, q) = &d[0];
    let mut worst: f64 = 0.0;
    for k in 0..100 {
        p.eval(t[k], Order::Position, &mut y);
        for j in 0..7 {
            worst = worst.max((y[j] - q[k * 7 + j]).abs());
        }
    }
    // The basis approximation error of 20 functions for this movement, and the mean weights are
    // exactly the single demonstration's regression weights.
    assert!(worst < 1e-2, "{worst}");
    let w = ProMp::demo_weights(&Demo { t, q }, 7, &ProMpConfig::default()).unwrap();
    for (a, b) in w.iter().zip(p.weight_mean()) {
        assert!((a - b).abs() < 1e-12 * (1.0 + a.abs()));
    }
}

#[test]
fn zero_noise_conditioning_passes_exactly() {
    let d = demos(10, 2.0, 2);
    let p = ProMp::fit(&as_demos(&d), 7, &ProMpConfig::default()).unwrap();
    let target = [0.3, -0.2, 0.5, 0.1, 0.0, 0.4, -0.3];
    let c = p
        .condition(&[ViaPoint::position(0.7, &target, 0.0)])
        .unwrap();
    let mut y = [0.0; 7];
    c.eval(0.7, Order::Position, &mut y);
    for j in 0..7 {
        assert!((y[j] - target[j]).abs() < 1e-9, "j={j}: {}", y[j]);
    }
    let mut var = [0.0; 7];
    c.variance(0.7, Order::Position, &mut var);
    assert!(var.iter().all(|v| *v < 1e-9), "{var:?}");
    // Unconditioned ProMP unchanged.
    let mut y0 = [0.0; 7];
    p.eval(0.7, Order::Position, &mut y0);
    assert!((y0[0] - target[0]).abs() > 1e-3);
}

#[test]
fn two_via_points_from_ten_demos_both_met() {
    let d = demos(10, 2.0, 3);
    let p = ProMp::fit(&as_demos(&d), 7, &ProMpConfig::default()).unwrap();
    let a = [0.5, -0.4, 0.6, 0.2, -0.1, 0.3, 0.0];
    let b = [-0.2, 0.3, 0.1, 0.8, 0.5, -0.6, 0.2];
    let c = p
        .condition(&[
            ViaPoint::position(0.5, &a, 0.0),
            ViaPoint::position(1.4, &b, 0.0),
        ])
        .unwrap();
    let mut y = [0.0; 7];
    c.eval(0.5, Order::Position, &mut y);
    let ea = (0..7).map(|j| (y[j] - a[j]).abs()).fold(0.0, f64::max);
    c.eval(1.4, Order::Position, &mut y);
    let eb = (0..7).map(|j| (y[j] - b[j]).abs()).fold(0.0, f64::max);
    eprintln!(
        "two via points: errors {ea:.2e} {eb:.2e}, jitter {}",
        c.last_jitter()
    );
    assert!(ea < 1e-3 && eb < 1e-3, "{ea} {eb}");
    // Without the prior, Σ_w has rank ≤ 9 < 14 constraints: the points cannot both be met.
    let cfg = ProMpConfig {
        prior_variance: 0.0,
        ..Default::default()
    };
    let p0 = ProMp::fit(&as_demos(&d), 7, &cfg).unwrap();
    let c0 = p0
        .condition(&[
            ViaPoint::position(0.5, &a, 0.0),
            ViaPoint::position(1.4, &b, 0.0),
        ])
        .unwrap();
    assert!(c0.last_jitter() > 0.0);
    c0.eval(0.5, Order::Position, &mut y);
    let ea0 = (0..7).map(|j| (y[j] - a[j]).abs()).fold(0.0, f64::max);
    assert!(ea0 > 1e-3, "{ea0}");
}

#[test]
fn velocity_via_point_and_coupling() {
    let d = demos(10, 1.0, 4);
    let p = ProMp::fit(&as_demos(&d), 7, &ProMpConfig::default()).unwrap();
    let v = vec![1.0; 7];
    let c = p
        .condition(&[ViaPoint {
            t: 0.5,
            order: Order::Velocity,
            value: v.clone(),
            cov: vec![],
        }])
        .unwrap();
    let mut y = [0.0; 7];
    c.eval(0.5, Order::Velocity, &mut y);
    for j in 0..7 {
        assert!((y[j] - 1.0).abs() < 1e-9);
    }
    // Coupling: conditioning joint 1 alone (huge variance on the others) moves joint 2 too,
    // because the demonstrations correlate them.
    let mut cov = vec![0.0; 49];
    for j in 1..7 {
        cov[j * 7 + j] = 1e6;
    }
    let mut mean = [0.0; 7];
    p.eval(0.5, Order::Position, &mut mean);
    let mut target = mean;
    target[0] += 0.2;
    let c = p
        .condition(&[ViaPoint {
            t: 0.5,
            order: Order::Position,
            value: target.to_vec(),
            cov,
        }])
        .unwrap();
    c.eval(0.5, Order::Position, &mut y);
    assert!((y[0] - target[0]).abs() < 1e-6);
    assert!(
        (y[1] - mean[1]).abs() > 1e-4,
        "no coupling: {} vs {}",
        y[1],
        mean[1]
    );
}

#[test]
fn velocities_are_per_second_and_consistent() {
    let d = demos(10, 2.0, 5);
    let p = ProMp::fit(&as_demos(&d), 7, &ProMpConfig::default()).unwrap();
    let e = 1e-6;
    let (mut a, mut b, mut v) = ([0.0; 7], [0.0; 7], [0.0; 7]);
    for k in 1..20 {
        let t = p.duration() * k as f64 / 20.0;
        for o in 0..3 {
            p.eval(t - e, Order::from_index(o).unwrap(), &mut a);
            p.eval(t + e, Order::from_index(o).unwrap(), &mut b);
            p.eval(t, Order::from_index(o + 1).unwrap(), &mut v);
            for j in 0..7 {
                let fd = (b[j] - a[j]) / (2.0 * e);
                assert!((fd - v[j]).abs() < 1e-5 * (1.0 + v[j].abs()) * 10f64.powi(o as i32 * 2));
            }
        }
    }
    // Twice the duration: half the velocity, a quarter of the velocity variance.
    let slow = p.with_duration(2.0 * p.duration()).unwrap();
    let (mut v1, mut v2) = ([0.0; 7], [0.0; 7]);
    p.eval(0.5, Order::Velocity, &mut v1);
    slow.eval(1.0, Order::Velocity, &mut v2);
    p.variance(0.5, Order::Velocity, &mut a);
    slow.variance(1.0, Order::Velocity, &mut b);
    for j in 0..7 {
        assert!((v1[j] - 2.0 * v2[j]).abs() < 1e-12);
        assert!((a[j] - 4.0 * b[j]).abs() < 1e-9 * a[j].max(1e-12));
    }
    // Covariance is symmetric with the variance on its diagonal.
    let mut cov = [0.0; 49];
    p.covariance(0.3, Order::Position, &mut cov);
    p.variance(0.3, Order::Position, &mut a);
    for i in 0..7 {
        assert!((cov[i * 7 + i] - a[i]).abs() < 1e-15 + 1e-12 * a[i]);
        for j in 0..7 {
            assert_eq!(cov[i * 7 + j], cov[j * 7 + i]);
        }
    }
}

#[test]
fn seeded_sampling_matches_the_distribution() {
    let d = demos(10, 1.0, 6);
    let p = ProMp::fit(&as_demos(&d), 7, &ProMpConfig::default()).unwrap();
    let s1 = p.sample(&mut SplitMix64::new(9)).unwrap();
    let s2 = p.sample(&mut SplitMix64::new(9)).unwrap();
    assert_eq!(s1.weights(), s2.weights());
    let mut rng = SplitMix64::new(10);
    let sampler = p.sampler().unwrap();
    let n = 2000;
    let (mut m, mut m2) = ([0.0; 7], [0.0; 7]);
    let mut y = [0.0; 7];
    for _ in 0..n {
        let s = sampler.sample(&mut rng);
        s.eval(0.6, Order::Position, &mut y);
        for j in 0..7 {
            m[j] += y[j] / n as f64;
            m2[j] += y[j] * y[j] / n as f64;
        }
    }
    let (mut mu, mut var) = ([0.0; 7], [0.0; 7]);
    p.eval(0.6, Order::Position, &mut mu);
    p.variance(0.6, Order::Position, &mut var);
    for j in 0..7 {
        let sv = m2[j] - m[j] * m[j];
        assert!(
            (m[j] - mu[j]).abs() < 5.0 * (var[j] / n as f64).sqrt(),
            "j={j}"
        );
        assert!(
            (sv / var[j] - 1.0).abs() < 0.15,
            "j={j}: {sv} vs {}",
            var[j]
        );
    }
}

#[test]
fn caller_data_untouched_and_bad_input_typed() {
    let d = demos(3, 1.0, 7);
    let copy = d.clone();
    let p = ProMp::fit(&as_demos(&d), 7, &ProMpConfig::default()).unwrap();
    assert_eq!(d, copy);
    assert!(ProMp::fit(&as_demos(&d[..1]), 7, &ProMpConfig::default()).is_err());
    let mut bad = d.clone();
    bad[1].1[20] = f64::INFINITY;
    let e = ProMp::fit(&as_demos(&bad), 7, &ProMpConfig::default()).unwrap_err();
    assert!(e.to_string().contains("demonstration 2"), "{e}");
    assert!(p
        .condition(&[ViaPoint::position(0.5, &[1.0; 3], 0.0)])
        .is_err());
    assert!(p
        .condition(&[ViaPoint::position(f64::NAN, &[1.0; 7], 0.0)])
        .is_err());
    assert!(p
        .condition(&[ViaPoint {
            t: 0.2,
            order: Order::Jerk,
            value: vec![0.0; 7],
            cov: vec![]
        }])
        .is_err());
    assert!(p.with_duration(-1.0).is_err());
}
