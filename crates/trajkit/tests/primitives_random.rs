//! Seeded random suites with invariants on every case. The default run checks a few cases;
//! `cargo test --release -- --ignored` runs the long versions.

use trajkit::primitives::{
    Demo, Dmp, DmpConfig, ForcingScaling, ProMp, ProMpConfig, RolloutOptions, ViaPoint,
};
use trajkit::rng::SplitMix64;
use trajkit::{Order, Trajectory};

/// A random smooth demonstration: per joint a minimum-jerk move plus two random sine bumps.
fn random_demo(rng: &mut SplitMix64, dof: usize, n: usize, dur: f64) -> (Vec<f64>, Vec<f64>) {
    let t: Vec<f64> = (0..n).map(|k| dur * k as f64 / (n - 1) as f64).collect();
    let p: Vec<[f64; 6]> = (0..dof)
        .map(|_| {
            [
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.5, 1.5),
                rng.uniform(-0.3, 0.3),
                rng.uniform(1.0, 4.0),
                rng.uniform(-0.2, 0.2),
                rng.uniform(0.0, 6.0),
            ]
        })
        .collect();
    let mut q = Vec::with_capacity(n * dof);
    for &tk in &t {
        let s = tk / dur;
        let mj = 10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5);
        let env = (std::f64::consts::PI * s).sin().powi(2);
        for c in &p {
            q.push(
                c[0] + c[1] * mj + env * (c[2] * (c[3] * s).sin() + c[4] * (c[3] * s + c[5]).cos()),
            );
        }
    }
    (t, q)
}

fn dmp_suite(cases: usize, seed: u64) {
    let mut rng = SplitMix64::new(seed);
    for case in 0..cases {
        let dof = 1 + rng.below(7) as usize;
        let dur = rng.uniform(0.5, 5.0);
        let n = 1000;
        let (t, q) = random_demo(&mut rng, dof, n, dur);
        let scaling = if rng.below(2) == 0 {
            ForcingScaling::Hoffmann2009
        } else {
            ForcingScaling::Ijspeert2013
        };
        let cfg = DmpConfig {
            scaling,
            ..Default::default()
        };
        let dmp = Dmp::fit(&t, &q, dof, &cfg).unwrap();
        let roll = dmp.rollout(&RolloutOptions::default()).unwrap();
        let mut y = vec![0.0; dof];
        for j in 0..dof {
            let (mut se, mut lo, mut hi) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
            for (k, &tk) in t.iter().enumerate() {
                roll.eval(tk, Order::Position, &mut y);
                se += (y[j] - q[k * dof + j]).powi(2);
                lo = lo.min(q[k * dof + j]);
                hi = hi.max(q[k * dof + j]);
            }
            let rel = (se / n as f64).sqrt() / (hi - lo);
            assert!(
                rel <= 1e-4,
                "case {case} ({scaling:?}, dof {dof}, T {dur:.2}): joint {j} {rel:.2e}"
            );
        }
        // A new goal is reached after a few τ.
        let goal: Vec<f64> = (0..dof).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let roll = dmp
            .rollout(&RolloutOptions {
                goal: Some(goal.clone()),
                duration: Some(4.0 * dur),
                ..Default::default()
            })
            .unwrap();
        roll.eval(4.0 * dur, Order::Position, &mut y);
        for j in 0..dof {
            let scale = 1.0 + (goal[j] - dmp.start()[j]).abs();
            assert!(
                (y[j] - goal[j]).abs() < 1e-3 * scale,
                "case {case}: goal joint {j}"
            );
        }
    }
}

fn promp_suite(cases: usize, seed: u64) {
    let mut rng = SplitMix64::new(seed);
    for case in 0..cases {
        let dof = 1 + rng.below(7) as usize;
        let m = 3 + rng.below(10) as usize;
        let dur = rng.uniform(0.5, 3.0);
        let demos: Vec<(Vec<f64>, Vec<f64>)> = (0..m)
            .map(|_| random_demo(&mut rng, dof, 100, dur))
            .collect();
        let ds: Vec<Demo> = demos.iter().map(|(t, q)| Demo { t, q }).collect();
        let p = ProMp::fit(&ds, dof, &ProMpConfig::default()).unwrap();
        let nv = 1 + rng.below(3) as usize;
        let mut times: Vec<f64> = (0..nv)
            .map(|i| p.duration() * (i as f64 + rng.uniform(0.2, 0.8)) / nv as f64)
            .collect();
        times.sort_by(f64::total_cmp);
        let via: Vec<ViaPoint> = times
            .iter()
            .map(|&tv| {
                let mut mean = vec![0.0; dof];
                p.eval(tv, Order::Position, &mut mean);
                let v: Vec<f64> = mean.iter().map(|x| x + rng.uniform(-0.3, 0.3)).collect();
                ViaPoint::position(tv, &v, 0.0)
            })
            .collect();
        let c = p.condition(&via).unwrap();
        let mut y = vec![0.0; dof];
        let mut var = vec![0.0; dof];
        for v in &via {
            c.eval(v.t, Order::Position, &mut y);
            c.variance(v.t, Order::Position, &mut var);
            for j in 0..dof {
                assert!(
                    (y[j] - v.value[j]).abs() < 1e-6,
                    "case {case}: via {} joint {j}: {}",
                    v.t,
                    (y[j] - v.value[j]).abs()
                );
                assert!(var[j] < 1e-8, "case {case}: variance {}", var[j]);
            }
        }
        // Conditioning never increases the variance anywhere.
        let (mut v0, mut v1) = (vec![0.0; dof], vec![0.0; dof]);
        for k in 0..=20 {
            let s = p.duration() * k as f64 / 20.0;
            p.variance(s, Order::Position, &mut v0);
            c.variance(s, Order::Position, &mut v1);
            for j in 0..dof {
                assert!(v1[j] <= v0[j] * (1.0 + 1e-9) + 1e-15, "case {case}");
            }
        }
    }
}

#[test]
fn dmp_random_suite_small() {
    dmp_suite(6, 100);
}

#[test]
#[ignore]
fn dmp_random_suite_long() {
    dmp_suite(300, 101);
}

#[test]
fn promp_random_suite_small() {
    promp_suite(10, 200);
}

#[test]
#[ignore]
fn promp_random_suite_long() {
    promp_suite(500, 201);
}
