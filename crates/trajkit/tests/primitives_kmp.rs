//! KMP: reference from GMM/GMR, ProMP and aligned samples; mean/covariance; via points.

use trajkit::primitives::{
    Demo, GmmConfig, Kmp, KmpConfig, KmpReference, KmpVia, ProMp, ProMpConfig,
};
use trajkit::rng::SplitMix64;
use trajkit::{Order, Trajectory};

fn demos(m: usize, n: usize, dof: usize, seed: u64) -> (Vec<f64>, Vec<Vec<f64>>) {
    let mut rng = SplitMix64::new(seed);
    let t: Vec<f64> = (0..n).map(|k| 2.0 * k as f64 / (n - 1) as f64).collect();
    let qs = (0..m)
        .map(|_| {
            let amp: Vec<f64> = (0..dof).map(|_| rng.uniform(0.8, 1.2)).collect();
            let mut q = Vec::with_capacity(n * dof);
            for &tk in &t {
                for j in 0..dof {
                    q.push(amp[j] * (1.5 * tk + 0.4 * j as f64).sin() + 0.01 * rng.normal());
                }
            }
            q
        })
        .collect();
    (t, qs)
}

#[test]
fn gmr_reference_kmp_follows_demos_and_reports_variance() {
    let (t, qs) = demos(5, 100, 3, 1);
    let ds: Vec<Demo> = qs.iter().map(|q| Demo { t: &t, q }).collect();
    let r = KmpReference::from_demos(&ds, 3, &GmmConfig::default(), 50).unwrap();
    let kmp = Kmp::fit(&r, &KmpConfig::default()).unwrap();
    assert_eq!(kmp.jitter(), 0.0);
    let mut y = [0.0; 3];
    let mut worst: f64 = 0.0;
    for k in 0..100 {
        kmp.eval(t[k], Order::Position, &mut y);
        for j in 0..3 {
            let m: f64 = qs.iter().map(|q| q[k * 3 + j]).sum::<f64>() / 5.0;
            worst = worst.max((y[j] - m).abs());
        }
    }
    assert!(worst < 0.05, "{worst}");
    let mut c = [0.0; 9];
    kmp.covariance(1.0, Order::Position, &mut c);
    for j in 0..3 {
        assert!(c[j * 4] > 0.0);
        for i in 0..3 {
            assert_eq!(c[i * 3 + j], c[j * 3 + i]);
        }
    }
}

#[test]
fn via_point_with_small_variance_is_passed() {
    // Ten demonstrations (Σ_n full rank over 7 joints), GMR reference of 50 points.
    let (t, qs) = demos(10, 100, 7, 2);
    let ds: Vec<Demo> = qs.iter().map(|q| Demo { t: &t, q }).collect();
    let gmm = GmmConfig {
        max_iter: 40,
        ..Default::default()
    };
    let r = KmpReference::from_demos(&ds, 7, &gmm, 50).unwrap();
    let kmp = Kmp::fit(&r, &KmpConfig::default()).unwrap();
    // Targets 0.1 away from the mean on every joint.
    let mut target = [0.0; 7];
    kmp.eval(0.755, Order::Position, &mut target);
    target.iter_mut().for_each(|v| *v += 0.1);
    let mut cov = vec![0.0; 49];
    for j in 0..7 {
        cov[j * 8] = 1e-6;
    }
    // One via point between reference points (inserted) and an end point (replaced).
    let mut end = [0.0; 7];
    kmp.eval(2.0, Order::Position, &mut end);
    end.iter_mut().for_each(|v| *v -= 0.1);
    let v = kmp
        .with_via_points(&[
            KmpVia {
                t: 0.755,
                mean: target.to_vec(),
                cov: cov.clone(),
            },
            KmpVia {
                t: 2.0,
                mean: end.to_vec(),
                cov,
            },
        ])
        .unwrap();
    assert_eq!(v.reference().t.len(), 51);
    let mut y = [0.0; 7];
    v.eval(0.755, Order::Position, &mut y);
    let e = (0..7).map(|j| (y[j] - target[j]).abs()).fold(0.0, f64::max);
    v.eval(2.0, Order::Position, &mut y);
    let e2 = (0..7).map(|j| (y[j] - end[j]).abs()).fold(0.0, f64::max);
    eprintln!("via errors {e:.2e} {e2:.2e}");
    assert!(e < 1e-3 && e2 < 1e-3, "{e} {e2}");
    // The covariance shrinks at the via point.
    let (mut c0, mut c1) = ([0.0; 49], [0.0; 49]);
    kmp.covariance(0.755, Order::Position, &mut c0);
    v.covariance(0.755, Order::Position, &mut c1);
    assert!(c1[0] < c0[0]);
}

#[test]
fn derivative_kernels_match_finite_differences() {
    let (t, qs) = demos(4, 60, 2, 3);
    let refs: Vec<&[f64]> = qs.iter().map(|q| q.as_slice()).collect();
    let r = KmpReference::from_aligned_samples(&t, &refs, 2, 1e-4).unwrap();
    let kmp = Kmp::fit(&r, &KmpConfig::default()).unwrap();
    let e = 1e-6;
    let (mut a, mut b, mut d) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    for k in 1..20 {
        let s = 2.0 * k as f64 / 20.0;
        for o in 0..3 {
            kmp.eval(s - e, Order::from_index(o).unwrap(), &mut a);
            kmp.eval(s + e, Order::from_index(o).unwrap(), &mut b);
            kmp.eval(s, Order::from_index(o + 1).unwrap(), &mut d);
            for j in 0..2 {
                let fd = (b[j] - a[j]) / (2.0 * e);
                assert!((fd - d[j]).abs() < 1e-5 * (1.0 + d[j].abs()) * 10f64.powi(2 * o as i32));
            }
        }
    }
    // Velocity covariance is positive.
    let mut c = [0.0; 4];
    kmp.covariance(1.0, Order::Velocity, &mut c);
    assert!(c[0] > 0.0 && c[3] > 0.0);
}

#[test]
fn promp_reference() {
    let (t, qs) = demos(6, 80, 2, 4);
    let ds: Vec<Demo> = qs.iter().map(|q| Demo { t: &t, q }).collect();
    let p = ProMp::fit(&ds, 2, &ProMpConfig::default()).unwrap();
    let r = KmpReference::from_promp(&p, 40).unwrap();
    let kmp = Kmp::fit(&r, &KmpConfig::default()).unwrap();
    let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
    for k in 0..=10 {
        let s = 0.2 * k as f64;
        kmp.eval(s, Order::Position, &mut a);
        p.eval(s, Order::Position, &mut b);
        for j in 0..2 {
            assert!((a[j] - b[j]).abs() < 0.05, "s={s}: {} vs {}", a[j], b[j]);
        }
    }
}

#[test]
fn bad_input_is_typed() {
    let r = KmpReference {
        dof: 1,
        t: vec![0.0, 1.0],
        mean: vec![0.0, 1.0],
        cov: vec![1.0],
    };
    assert!(Kmp::fit(&r, &KmpConfig::default()).is_err());
    let r = KmpReference {
        dof: 1,
        t: vec![0.0, 0.0],
        mean: vec![0.0, 1.0],
        cov: vec![1.0, 1.0],
    };
    assert!(Kmp::fit(&r, &KmpConfig::default()).is_err());
    let r = KmpReference {
        dof: 1,
        t: vec![0.0, 1.0],
        mean: vec![0.0, 1.0],
        cov: vec![1.0, 1.0],
    };
    let cfg = KmpConfig {
        lambda: 0.0,
        ..Default::default()
    };
    assert!(Kmp::fit(&r, &cfg).is_err());
    let k = Kmp::fit(&r, &KmpConfig::default()).unwrap();
    assert!(k
        .with_via_points(&[KmpVia {
            t: 0.5,
            mean: vec![1.0, 2.0],
            cov: vec![1.0]
        }])
        .is_err());
    assert!(k
        .with_via_points(&[KmpVia {
            t: f64::NAN,
            mean: vec![1.0],
            cov: vec![1.0]
        }])
        .is_err());
}
