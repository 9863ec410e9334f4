//! DMP: reproduction accuracy, goal/start/τ changes, both scalings, g = y₀, integration
//! convergence, derivative consistency, bad input.

use trajkit::primitives::{Dmp, DmpConfig, ForcingScaling, GoalChange, RolloutOptions};
use trajkit::rng::SplitMix64;
use trajkit::{Error, Order, Trajectory};

/// A smooth 7-joint demonstration, `n` samples over `dur` seconds.
fn demo7(n: usize, dur: f64) -> (Vec<f64>, Vec<f64>) {
    let t: Vec<f64> = (0..n).map(|k| dur * k as f64 / (n - 1) as f64).collect();
    let mut q = Vec::with_capacity(n * 7);
    for &tk in &t {
        let s = tk / dur;
        let mj = 10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5);
        for j in 0..7 {
            let jf = j as f64;
            let amp = [0.8, -0.5, 1.2, 0.3, -1.0, 0.6, 0.05][j];
            let bump = 0.2 * (std::f64::consts::PI * s).sin().powi(2) * (3.0 * s + jf).sin();
            q.push(0.1 * jf - 0.3 + amp * mj + bump);
        }
    }
    (t, q)
}

fn rms_rel(traj: &impl Trajectory, t: &[f64], q: &[f64], dof: usize) -> Vec<f64> {
    let mut y = vec![0.0; dof];
    let mut se = vec![0.0; dof];
    let mut lo = vec![f64::INFINITY; dof];
    let mut hi = vec![f64::NEG_INFINITY; dof];
    for (k, &tk) in t.iter().enumerate() {
        traj.eval(tk - t[0], Order::Position, &mut y);
        for j in 0..dof {
            let d = y[j] - q[k * dof + j];
            se[j] += d * d;
            lo[j] = lo[j].min(q[k * dof + j]);
            hi[j] = hi[j].max(q[k * dof + j]);
        }
    }
    (0..dof)
        .map(|j| (se[j] / t.len() as f64).sqrt() / (hi[j] - lo[j]))
        .collect()
}

#[test]
fn reproduces_smooth_7dof_demo_within_1e4_of_range() {
    let (t, q) = demo7(1001, 1.0);
    for scaling in [ForcingScaling::Hoffmann2009, ForcingScaling::Ijspeert2013] {
        let cfg = DmpConfig {
            scaling,
            ..Default::default()
        };
        let dmp = Dmp::fit(&t, &q, 7, &cfg).unwrap();
        let roll = dmp.rollout(&RolloutOptions::default()).unwrap();
        let e = rms_rel(&roll, &t, &q, 7);
        let worst = e.iter().cloned().fold(0.0, f64::max);
        eprintln!("{scaling:?}: worst relative RMS {worst:.3e}");
        assert!(worst <= 1e-4, "{scaling:?}: {e:?}");
    }
}

#[test]
fn seed_constants_are_the_defaults() {
    let c = DmpConfig::default();
    assert_eq!((c.alpha_z, c.beta_z), (25.0, 6.25));
    assert_eq!(c.scaling, ForcingScaling::Hoffmann2009);
    assert_eq!(
        ForcingScaling::from_name("ijspeert").unwrap(),
        ForcingScaling::Ijspeert2013
    );
    assert_eq!(
        ForcingScaling::from_name("Hoffmann").unwrap(),
        ForcingScaling::Hoffmann2009
    );
    assert!(ForcingScaling::from_name("pydmps").is_err());
}

#[test]
fn integration_converges() {
    // Both integrators: refining the default 500 steps per τ 16-fold changes the rollout by
    // < 1e-9 (positions; the joint ranges exceed 0.5).
    let (t, q) = demo7(501, 2.0);
    let dmp = Dmp::fit(&t, &q, 7, &DmpConfig::default()).unwrap();
    for coupling in [
        None,
        Some(&no_coupling as &dyn trajkit::primitives::CouplingTerm),
    ] {
        let a = dmp
            .rollout(&RolloutOptions {
                coupling,
                ..Default::default()
            })
            .unwrap();
        let b = dmp
            .rollout(&RolloutOptions {
                steps_per_tau: Some(8000),
                coupling,
                ..Default::default()
            })
            .unwrap();
        let e = max_diff(&a, &b, 2.0, 200);
        assert!(e[0] < 1e-9, "coupling {}: {e:?}", coupling.is_some());
    }
}

/// A coupling term that adds nothing: it routes a rollout through the general RK4 path.
fn no_coupling(_: f64, _: &[f64], _: &[f64], _: &mut [f64]) {}

/// Largest absolute difference of position, velocity and acceleration over `samples + 1`
/// times in `[0, dur]`.
fn max_diff(a: &impl Trajectory, b: &impl Trajectory, dur: f64, samples: usize) -> [f64; 3] {
    let dof = a.dof();
    let (mut ya, mut yb) = (vec![0.0; dof], vec![0.0; dof]);
    let mut e = [0.0f64; 3];
    for k in 0..=samples {
        let tk = dur * k as f64 / samples as f64;
        for (o, eo) in e.iter_mut().enumerate() {
            let order = Order::from_index(o).unwrap();
            a.eval(tk, order, &mut ya);
            b.eval(tk, order, &mut yb);
            for j in 0..dof {
                *eo = eo.max((ya[j] - yb[j]).abs());
            }
        }
    }
    e
}

#[test]
fn exponential_integrator_equals_the_converged_rk4_rollout() {
    // The default rollout (uncoupled: exact propagation, quintic forcing interpolant) against
    // RK4 at 16× the default steps, for both scalings, a new goal and start, a slower τ, a
    // longer duration and a goal change.
    let (t, q) = demo7(1001, 1.0);
    let range = 0.5; // smallest joint range of demo7 is larger
    for scaling in [ForcingScaling::Hoffmann2009, ForcingScaling::Ijspeert2013] {
        let dmp = Dmp::fit(
            &t,
            &q,
            7,
            &DmpConfig {
                scaling,
                ..Default::default()
            },
        )
        .unwrap();
        let variants = [
            RolloutOptions::default(),
            RolloutOptions {
                goal: Some(dmp.goal().iter().map(|g| g + 0.3).collect()),
                start: Some(dmp.start().iter().map(|g| g - 0.2).collect()),
                tau: Some(1.7),
                duration: Some(2.5),
                ..Default::default()
            },
            RolloutOptions {
                goal_changes: vec![GoalChange {
                    t: 0.4,
                    goal: dmp.goal().iter().map(|g| g - 0.5).collect(),
                }],
                duration: Some(1.5),
                ..Default::default()
            },
        ];
        for (i, opts) in variants.into_iter().enumerate() {
            let fast = dmp.rollout(&opts).unwrap();
            let reference = dmp
                .rollout(&RolloutOptions {
                    steps_per_tau: Some(8000),
                    coupling: Some(&no_coupling),
                    ..opts.clone()
                })
                .unwrap();
            // With a goal change the acceleration jumps at a grid time and the dense output
            // of either integrator is only as good as its step next to it: compare there at
            // the coarse grid's times (τ/500 apart).
            let samples = if i == 2 { 750 } else { 3000 };
            let e = max_diff(&fast, &reference, fast.duration(), samples);
            eprintln!(
                "{scaling:?} variant {i}: pos {:.1e} vel {:.1e} acc {:.1e}",
                e[0], e[1], e[2]
            );
            assert!(e[0] < 1e-9 * range, "{scaling:?} {i}: {e:?}");
            assert!(e[1] < 1e-8, "{scaling:?} {i}: {e:?}");
            assert!(e[2] < 1e-5, "{scaling:?} {i}: {e:?}");
        }
    }
}

#[test]
fn goal_start_and_tau_changes() {
    let (t, q) = demo7(1001, 1.0);
    let dmp = Dmp::fit(&t, &q, 7, &DmpConfig::default()).unwrap();
    let goal: Vec<f64> = dmp.goal().iter().map(|g| g + 0.3).collect();
    let start: Vec<f64> = dmp.start().iter().map(|g| g - 0.2).collect();
    let roll = dmp
        .rollout(&RolloutOptions {
            goal: Some(goal.clone()),
            start: Some(start.clone()),
            tau: Some(2.0),
            duration: Some(6.0),
            ..Default::default()
        })
        .unwrap();
    assert!((roll.duration() - 6.0).abs() < 1e-12);
    let mut y = [0.0; 7];
    roll.eval(0.0, Order::Position, &mut y);
    for j in 0..7 {
        assert_eq!(y[j], start[j]);
    }
    // Converges to the new goal.
    roll.eval(6.0, Order::Position, &mut y);
    for j in 0..7 {
        assert!(
            (y[j] - goal[j]).abs() < 1e-3,
            "j={j}: {} vs {}",
            y[j],
            goal[j]
        );
    }
    // τ = 2: the same shape at half speed (same goal/start): y(2t) of the slow rollout equals
    // y(t) of the original, and velocities are per second (half as large).
    let fast = dmp.rollout(&RolloutOptions::default()).unwrap();
    let slow = dmp
        .rollout(&RolloutOptions {
            tau: Some(2.0),
            start_velocity: Some(dmp.start_velocity().iter().map(|v| v / 2.0).collect()),
            ..Default::default()
        })
        .unwrap();
    let (mut a, mut b) = ([0.0; 7], [0.0; 7]);
    for k in 0..=10 {
        let tk = k as f64 / 10.0;
        fast.eval(tk, Order::Position, &mut a);
        slow.eval(2.0 * tk, Order::Position, &mut b);
        for j in 0..7 {
            assert!((a[j] - b[j]).abs() < 1e-9);
        }
        fast.eval(tk, Order::Velocity, &mut a);
        slow.eval(2.0 * tk, Order::Velocity, &mut b);
        for j in 0..7 {
            assert!((a[j] - 2.0 * b[j]).abs() < 1e-8);
        }
    }
}

#[test]
fn goal_change_during_execution_with_and_without_filter() {
    let (t, q) = demo7(1001, 1.0);
    let dmp = Dmp::fit(&t, &q, 7, &DmpConfig::default()).unwrap();
    let new_goal: Vec<f64> = dmp.goal().iter().map(|g| g - 0.5).collect();
    for filter in [None, Some(12.5)] {
        let roll = dmp
            .rollout(&RolloutOptions {
                goal_changes: vec![GoalChange {
                    t: 0.4,
                    goal: new_goal.clone(),
                }],
                goal_filter: filter,
                duration: Some(3.0),
                ..Default::default()
            })
            .unwrap();
        let base = dmp.rollout(&RolloutOptions::default()).unwrap();
        let (mut a, mut b) = ([0.0; 7], [0.0; 7]);
        // Identical before the change (the filtered rollout integrates by RK4, the base one by
        // the exponential integrator: equal within the integration contract).
        roll.eval(0.39, Order::Position, &mut a);
        base.eval(0.39, Order::Position, &mut b);
        if filter.is_none() {
            assert_eq!(a, b);
        } else {
            for j in 0..7 {
                assert!((a[j] - b[j]).abs() < 1e-9, "j={j}");
            }
        }
        roll.eval(3.0, Order::Position, &mut a);
        for j in 0..7 {
            assert!((a[j] - new_goal[j]).abs() < 2e-3, "{filter:?} j={j}");
        }
        // Acceleration stays finite and the filtered version has no jump at the change.
        let (mut a0, mut a1) = ([0.0; 7], [0.0; 7]);
        roll.eval(0.4 - 1e-6, Order::Acceleration, &mut a0);
        roll.eval(0.4 + 1e-3, Order::Acceleration, &mut a1);
        let jump = (0..7).map(|j| (a1[j] - a0[j]).abs()).fold(0.0, f64::max);
        if filter.is_some() {
            assert!(jump < 1.0, "filtered jump {jump}");
        }
    }
}

#[test]
fn goal_equal_to_start_stays_bounded() {
    // A loop demonstration: returns to where it started.
    let n = 1001;
    let t: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
    let q: Vec<f64> = t
        .iter()
        .map(|&s| 0.5 * (std::f64::consts::PI * s).sin().powi(2))
        .collect();
    for scaling in [ForcingScaling::Hoffmann2009, ForcingScaling::Ijspeert2013] {
        let cfg = DmpConfig {
            scaling,
            ..Default::default()
        };
        let dmp = Dmp::fit(&t, &q, 1, &cfg).unwrap();
        let wmax = dmp.weights().iter().fold(0.0f64, |m, w| m.max(w.abs()));
        assert!(wmax < 1e4, "{scaling:?}: weights {wmax}");
        let roll = dmp.rollout(&RolloutOptions::default()).unwrap();
        let e = rms_rel(&roll, &t, &q, 1);
        assert!(e[0] < 1e-4, "{scaling:?} {e:?}");
        // And with start = goal moved elsewhere, still bounded.
        let roll = dmp
            .rollout(&RolloutOptions {
                start: Some(vec![2.0]),
                goal: Some(vec![2.0]),
                ..Default::default()
            })
            .unwrap();
        let mut y = [0.0];
        for k in 0..=100 {
            roll.eval(k as f64 / 100.0, Order::Position, &mut y);
            assert!((y[0] - 2.0).abs() < 1.0, "{scaling:?}");
        }
    }
}

#[test]
fn derivatives_are_consistent() {
    let (t, q) = demo7(301, 1.5);
    let dmp = Dmp::fit(&t, &q, 7, &DmpConfig::default()).unwrap();
    let roll = dmp.rollout(&RolloutOptions::default()).unwrap();
    let mut rng = SplitMix64::new(3);
    let e = 1e-6;
    let (mut lo, mut hi, mut d) = ([0.0; 7], [0.0; 7], [0.0; 7]);
    for _ in 0..200 {
        let tk = rng.uniform(0.01, 1.49);
        for k in 0..3 {
            let o = Order::from_index(k).unwrap();
            roll.eval(tk - e, o, &mut lo);
            roll.eval(tk + e, o, &mut hi);
            roll.eval(tk, Order::from_index(k + 1).unwrap(), &mut d);
            for j in 0..7 {
                let fd = (hi[j] - lo[j]) / (2.0 * e);
                let tol = 1e-5 * (1.0 + d[j].abs()) * 10f64.powi(2 * k as i32);
                assert!(
                    (fd - d[j]).abs() < tol,
                    "t={tk} order={k} j={j}: {fd} vs {}",
                    d[j]
                );
            }
        }
    }
    // Clamped time policy.
    roll.eval(-1.0, Order::Position, &mut lo);
    roll.eval(0.0, Order::Position, &mut hi);
    assert_eq!(lo, hi);
    roll.eval(f64::NAN, Order::Position, &mut lo);
    assert!(lo.iter().all(|v| v.is_nan()));
}

#[test]
fn user_coupling_hook_is_applied() {
    let (t, q) = demo7(201, 1.0);
    let dmp = Dmp::fit(&t, &q, 7, &DmpConfig::default()).unwrap();
    // A constant push on joint 1 shifts its equilibrium by C / (α_z β_z) at the end.
    let push = |_t: f64, _y: &[f64], _v: &[f64], out: &mut [f64]| out[0] += 15.625;
    let roll = dmp
        .rollout(&RolloutOptions {
            coupling: Some(&push),
            duration: Some(4.0),
            ..Default::default()
        })
        .unwrap();
    let mut y = [0.0; 7];
    roll.eval(4.0, Order::Position, &mut y);
    assert!((y[0] - (dmp.goal()[0] + 0.1)).abs() < 1e-3, "{}", y[0]);
    assert!((y[1] - dmp.goal()[1]).abs() < 1e-3);
}

#[test]
fn caller_data_is_not_mutated_and_bad_input_is_typed() {
    let (t, q) = demo7(101, 1.0);
    let (t2, q2) = (t.clone(), q.clone());
    let _ = Dmp::fit(&t, &q, 7, &DmpConfig::default()).unwrap();
    assert_eq!((t.clone(), q.clone()), (t2, q2));
    let mut bad = q.clone();
    bad[17] = f64::NAN;
    let e = Dmp::fit(&t, &bad, 7, &DmpConfig::default()).unwrap_err();
    assert!(e.to_string().contains("joint 4"), "{e}");
    assert!(matches!(
        Dmp::fit(&t, &q[..50], 7, &DmpConfig::default()),
        Err(Error::DimensionMismatch { .. })
    ));
    let mut tb = t.clone();
    tb[5] = tb[4];
    assert!(Dmp::fit(&tb, &q, 7, &DmpConfig::default()).is_err());
    assert!(Dmp::fit(&t[..2], &q[..14], 7, &DmpConfig::default()).is_err());
    let cfg = DmpConfig {
        alpha_z: -1.0,
        ..Default::default()
    };
    assert!(Dmp::fit(&t, &q, 7, &cfg).is_err());
    let dmp = Dmp::fit(&t, &q, 7, &DmpConfig::default()).unwrap();
    for opts in [
        RolloutOptions {
            tau: Some(0.0),
            ..Default::default()
        },
        RolloutOptions {
            goal: Some(vec![0.0; 3]),
            ..Default::default()
        },
        RolloutOptions {
            duration: Some(f64::INFINITY),
            ..Default::default()
        },
        RolloutOptions {
            goal_filter: Some(f64::NAN),
            ..Default::default()
        },
    ] {
        assert!(dmp.rollout(&opts).is_err(), "{opts:?}");
    }
}

#[test]
fn obstacle_coupling_steers_around_a_point() {
    use trajkit::primitives::ObstacleAvoidance;
    // Straight 2-D demonstration (0,0) → (1,0).
    let n = 501;
    let t: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
    let q: Vec<f64> = t
        .iter()
        .flat_map(|&s| [10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5), 0.0])
        .collect();
    let dmp = Dmp::fit(&t, &q, 2, &DmpConfig::default()).unwrap();
    let obs = ObstacleAvoidance::new(&[0.5, 0.02], 2).unwrap();
    let free = dmp.rollout(&RolloutOptions::default()).unwrap();
    let avoid = dmp
        .rollout(&RolloutOptions {
            coupling: Some(&obs),
            duration: Some(2.0),
            ..Default::default()
        })
        .unwrap();
    let dist = |r: &dyn Trajectory| {
        let mut y = [0.0; 2];
        (0..=400)
            .map(|k| {
                r.eval(k as f64 / 200.0, Order::Position, &mut y);
                ((y[0] - 0.5).powi(2) + (y[1] - 0.02).powi(2)).sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    };
    let (d0, d1) = (dist(&free), dist(&avoid));
    assert!(d1 > 2.0 * d0, "free {d0}, avoiding {d1}");
    // Passes below the obstacle (away from it) and still reaches the goal.
    let mut y = [0.0; 2];
    avoid.eval(0.5, Order::Position, &mut y);
    assert!(y[1] < 0.0, "{y:?}");
    avoid.eval(2.0, Order::Position, &mut y);
    assert!((y[0] - 1.0).abs() < 1e-2 && y[1].abs() < 1e-2, "{y:?}");
    assert!(ObstacleAvoidance::new(&[0.0; 4], 4).is_err());
    assert!(ObstacleAvoidance::new(&[0.0; 5], 2).is_err());
}

#[test]
fn rhythmic_dmp_repeats_its_period() {
    use trajkit::primitives::RhythmicDmp;
    let tau = std::f64::consts::TAU;
    let f = |s: f64| {
        [
            (tau * s).sin() + 0.3 * (2.0 * tau * s).sin(),
            0.5 * (tau * s).cos(),
        ]
    };
    let n = 1001;
    let period = 1.5;
    let t: Vec<f64> = (0..n).map(|k| period * k as f64 / (n - 1) as f64).collect();
    let q: Vec<f64> = t.iter().flat_map(|&s| f(s / period)).collect();
    let dmp = RhythmicDmp::fit(&t, &q, 2, 50).unwrap();
    let roll = dmp.rollout(3.0 * period, None, None, None).unwrap();
    let mut y = [0.0; 2];
    let mut worst: f64 = 0.0;
    for k in 0..=300 {
        let s = 3.0 * period * k as f64 / 300.0;
        roll.eval(s, Order::Position, &mut y);
        let e = f(s / period);
        worst = worst
            .max((y[0] - e[0]).abs() / 2.6)
            .max((y[1] - e[1]).abs());
    }
    assert!(worst < 1e-3, "{worst}");
    // Twice the amplitude, another anchor, half the period.
    let roll = dmp
        .rollout(period, Some(period / 2.0), Some(&[1.0, -1.0]), Some(2.0))
        .unwrap();
    for k in 0..=50 {
        let s = period * k as f64 / 50.0;
        roll.eval(s, Order::Position, &mut y);
        let e = f(2.0 * s / period);
        assert!((y[0] - (1.0 + 2.0 * e[0])).abs() < 1e-2, "s={s}");
        assert!((y[1] - (-1.0 + 2.0 * e[1])).abs() < 1e-2, "s={s}");
    }
    assert!(dmp.rollout(-1.0, None, None, None).is_err());
    assert!(dmp.rollout(1.0, None, Some(&[0.0]), None).is_err());
}

#[test]
fn phase_stopping_waits_for_a_blocked_robot() {
    use trajkit::primitives::PhaseStop;
    let (t, q) = demo7(501, 1.0);
    let dmp = Dmp::fit(&t, &q, 7, &DmpConfig::default()).unwrap();
    let start = dmp.start().to_vec();
    // The robot is stuck at its start until t = 0.5 s, then (smoothly, by t = 0.6 s) follows.
    let actual = |t: f64, y: &[f64], out: &mut [f64]| {
        let s = ((t - 0.5) / 0.1).clamp(0.0, 1.0);
        let w = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
        for j in 0..y.len() {
            out[j] = start[j] + w * (y[j] - start[j]);
        }
    };
    let ps = PhaseStop {
        gain: 1e4,
        actual: &actual,
    };
    let opts = |spt| RolloutOptions {
        phase_stop: Some(ps),
        duration: Some(4.0),
        steps_per_tau: Some(spt),
        ..Default::default()
    };
    let stopped = dmp.rollout(&opts(500)).unwrap();
    let free = dmp.rollout(&RolloutOptions::default()).unwrap();
    let (mut a, mut b) = ([0.0; 7], [0.0; 7]);
    stopped.eval(0.5, Order::Position, &mut a);
    free.eval(0.5, Order::Position, &mut b);
    let moved = |y: &[f64; 7]| (0..7).map(|j| (y[j] - start[j]).abs()).fold(0.0, f64::max);
    assert!(
        moved(&a) < 0.2 * moved(&b),
        "{} vs {}",
        moved(&a),
        moved(&b)
    );
    stopped.eval(4.0, Order::Position, &mut a);
    for j in 0..7 {
        assert!((a[j] - dmp.goal()[j]).abs() < 1e-3, "j={j}");
    }
    // RK4 with the phase as a state still converges.
    let fine = dmp.rollout(&opts(2000)).unwrap();
    for k in 0..=40 {
        let s = 0.1 * k as f64;
        stopped.eval(s, Order::Position, &mut a);
        fine.eval(s, Order::Position, &mut b);
        for j in 0..7 {
            assert!((a[j] - b[j]).abs() < 1e-7, "t={s}: {}", (a[j] - b[j]).abs());
        }
    }
}

#[test]
fn quaternion_dmp_reproduces_and_reaches_new_goals() {
    use trajkit::primitives::QuaternionDmp;
    use trajkit::spline::Quat;
    // A smooth rotation: rotation vector r(s) = mj(s)·(0.8, −0.5, 1.2) + bump, start at q0.
    let q0 = Quat::exp([0.2, 0.4, -0.6]);
    let rot = |s: f64| {
        let mj = 10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5);
        let b = 0.3 * (std::f64::consts::PI * s).sin().powi(2);
        let r = [0.8 * mj + b, -0.5 * mj, 1.2 * mj - b];
        Quat::exp(r) * q0
    };
    let n = 1001;
    let t: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
    let q: Vec<f64> = t.iter().flat_map(|&s| rot(s).to_array()).collect();
    let dmp = QuaternionDmp::fit(&t, &q).unwrap();
    let roll = dmp.rollout(None, None, None).unwrap();
    // The rotation angle between two orientations: ‖log(a ∗ b̄)‖.
    let angle = |a: Quat, b: Quat| {
        let l = (a * b.conj()).log();
        (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt()
    };
    let mut se = 0.0;
    for &s in &t {
        se += angle(roll.orientation(s), rot(s)).powi(2);
    }
    let rms = (se / n as f64).sqrt();
    assert!(rms < 1e-4, "orientation RMS {rms} rad");
    // Unit norm at the steps; step halving changes little (order-4 integrator).
    let fine = dmp.rollout_steps(None, None, None, 4000).unwrap();
    for k in 0..=20 {
        let s = k as f64 / 20.0;
        let d = angle(roll.orientation(s), fine.orientation(s));
        assert!(d < 1e-10, "s={s}: {d}");
    }
    let mut v = [0.0; 4];
    roll.eval(0.37, Order::Position, &mut v);
    assert!((v.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-12);
    // New goal (and goal = start) stay bounded and converge.
    let g = Quat::exp([0.0, 1.4, 0.0]);
    let r2 = dmp.rollout(None, Some(g), Some(1.5)).unwrap();
    assert!(angle(r2.orientation(1.5), g) < 2e-2);
    let r3 = dmp.rollout(Some(q0), Some(q0), None).unwrap();
    for k in 0..=10 {
        assert!(angle(r3.orientation(k as f64 / 10.0), q0) < 2.5);
    }
    assert!(QuaternionDmp::fit(&t, &vec![0.0; 4 * n]).is_err());
}

#[test]
fn bounded_dmp_stays_inside_joint_limits() {
    use trajkit::primitives::BoundedDmp;
    use trajkit::{JointLimits, Limits};
    let (t, q) = demo7(1001, 1.0);
    let limits = Limits::new(
        (0..7)
            .map(|_| JointLimits {
                position_min: -2.0,
                position_max: 2.0,
                ..JointLimits::default()
            })
            .collect(),
    )
    .unwrap();
    let dmp = BoundedDmp::fit(&t, &q, 7, &DmpConfig::default(), &limits).unwrap();
    let roll = dmp.rollout(&RolloutOptions::default()).unwrap();
    let e = rms_rel(&roll, &t, &q, 7);
    assert!(e.iter().all(|&v| v <= 1e-4), "{e:?}");
    // A goal next to the limit and a strong push outwards: never outside.
    let push =
        |_t: f64, _y: &[f64], _v: &[f64], out: &mut [f64]| out.iter_mut().for_each(|o| *o += 500.0);
    let roll = dmp
        .rollout(&RolloutOptions {
            goal: Some(vec![1.999; 7]),
            coupling: Some(&push),
            duration: Some(3.0),
            ..Default::default()
        })
        .unwrap();
    let mut y = [0.0; 7];
    for k in 0..=3000 {
        roll.eval(k as f64 / 1000.0, Order::Position, &mut y);
        assert!(y.iter().all(|&v| v > -2.0 && v < 2.0), "{y:?}");
    }
    // Chain-rule derivatives agree with finite differences.
    let e = 1e-6;
    let (mut lo, mut hi, mut d) = ([0.0; 7], [0.0; 7], [0.0; 7]);
    for k in 1..30 {
        let s = k as f64 * 0.1;
        for o in 0..3 {
            roll.eval(s - e, Order::from_index(o).unwrap(), &mut lo);
            roll.eval(s + e, Order::from_index(o).unwrap(), &mut hi);
            roll.eval(s, Order::from_index(o + 1).unwrap(), &mut d);
            for j in 0..7 {
                let fd = (hi[j] - lo[j]) / (2.0 * e);
                assert!(
                    (fd - d[j]).abs() < 1e-5 * (1.0 + d[j].abs()) * 10f64.powi(2 * o as i32),
                    "t={s} o={o} j={j}: {fd} vs {}",
                    d[j]
                );
            }
        }
    }
    // Goals on or outside the limits, and demonstrations touching them, are refused.
    assert!(dmp
        .rollout(&RolloutOptions {
            goal: Some(vec![2.5; 7]),
            ..Default::default()
        })
        .is_err());
    let mut bad = q.clone();
    bad[10] = 2.0;
    assert!(BoundedDmp::fit(&t, &bad, 7, &DmpConfig::default(), &limits).is_err());
}
