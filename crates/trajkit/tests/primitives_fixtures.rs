//! Peer fixtures from movement_primitives / scipy (tools/primitives_fixtures.py).

use serde_json::Value;
use trajkit::primitives::{
    Demo, Dmp, DmpConfig, GaussianBasis, ProMp, ProMpConfig, RolloutOptions, ViaPoint,
};
use trajkit::{Order, Trajectory};

fn load(name: &str) -> Value {
    let p = format!(
        "{}/tests/fixtures/primitives/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

fn vecf(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn dmp_basis_matches_movement_primitives() {
    let f = load("dmp_basis.json");
    let b = GaussianBasis::dmp(50, f["alpha_x"].as_f64().unwrap(), 0.8).unwrap();
    for (a, e) in b.centers().iter().zip(vecf(&f["centers"])) {
        assert!((a - e).abs() <= 1e-14 * e.abs().max(1.0));
    }
    for (a, e) in b.widths().iter().zip(vecf(&f["widths"])) {
        assert!((a - e).abs() <= 1e-10 * e.abs(), "{a} vs {e}");
    }
}

#[test]
fn dmp_rollout_matches_exact_ode_solution() {
    let f = load("dmp_rollout.json");
    let dof = f["dof"].as_u64().unwrap() as usize;
    let cfg = DmpConfig {
        n_basis: f["n_basis"].as_u64().unwrap() as usize,
        ..Default::default()
    };
    let dmp = Dmp::from_weights(
        &cfg,
        f["tau"].as_f64().unwrap(),
        &vecf(&f["start"]),
        &vecf(&f["goal"]),
        &vecf(&f["weights"]),
    )
    .unwrap();
    let roll = dmp.rollout(&RolloutOptions::default()).unwrap();
    let t = vecf(&f["t"]);
    let q = vecf(&f["q"]);
    let exact = vecf(&f["exact"]);
    let mut y = vec![0.0; dof];
    let mut se = vec![0.0; dof];
    for (k, &tk) in t.iter().enumerate() {
        roll.eval(tk, Order::Position, &mut y);
        for j in 0..dof {
            se[j] += (y[j] - exact[k * dof + j]).powi(2);
        }
    }
    let mp_rk4 = vecf(&f["mp_rk4_rel_rms_vs_exact"]);
    for j in 0..dof {
        let (lo, hi) = (0..t.len()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), k| {
            (l.min(q[k * dof + j]), h.max(q[k * dof + j]))
        });
        let rel = (se[j] / t.len() as f64).sqrt() / (hi - lo);
        eprintln!(
            "joint {j}: trajkit {rel:.2e}, movement_primitives rk4 {:.2e} (relative RMS vs exact)",
            mp_rk4[j]
        );
        assert!(rel < 1e-8, "joint {j}: {rel}");
        assert!(rel * 1e4 < mp_rk4[j]);
    }
}

#[test]
fn dmp_fit_reproduces_better_than_movement_primitives() {
    let f = load("dmp_rollout.json");
    let dof = f["dof"].as_u64().unwrap() as usize;
    let t = vecf(&f["t"]);
    let q = vecf(&f["q"]);
    let cfg = DmpConfig {
        n_basis: f["n_basis"].as_u64().unwrap() as usize,
        ..Default::default()
    };
    let dmp = Dmp::fit(&t, &q, dof, &cfg).unwrap();
    let roll = dmp.rollout(&RolloutOptions::default()).unwrap();
    let mp = vecf(&f["mp_rk4_rel_rms_vs_demo"]);
    let mut y = vec![0.0; dof];
    for j in 0..dof {
        let mut se = 0.0;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (k, &tk) in t.iter().enumerate() {
            roll.eval(tk, Order::Position, &mut y);
            se += (y[j] - q[k * dof + j]).powi(2);
            lo = lo.min(q[k * dof + j]);
            hi = hi.max(q[k * dof + j]);
        }
        let rel = (se / t.len() as f64).sqrt() / (hi - lo);
        eprintln!(
            "joint {j}: trajkit {rel:.2e}, movement_primitives {:.2e}",
            mp[j]
        );
        assert!(rel < mp[j] / 5.0, "joint {j}: {rel} vs {}", mp[j]);
    }
}

#[test]
fn promp_weights_and_conditioning_match_movement_primitives() {
    let f = load("promp.json");
    let dof = f["dof"].as_u64().unwrap() as usize;
    let cfg = ProMpConfig {
        n_basis: f["n_basis"].as_u64().unwrap() as usize,
        ridge: f["ridge"].as_f64().unwrap(),
        prior_variance: f["prior_variance"].as_f64().unwrap(),
        ..Default::default()
    };
    let t = vecf(&f["t"]);
    let qs: Vec<Vec<f64>> = f["demos"].as_array().unwrap().iter().map(vecf).collect();
    let demos: Vec<Demo> = qs.iter().map(|q| Demo { t: &t, q }).collect();
    for (d, w) in demos.iter().zip(f["weights"].as_array().unwrap()) {
        let ours = ProMp::demo_weights(d, dof, &cfg).unwrap();
        for (a, e) in ours.iter().zip(vecf(w)) {
            assert!((a - e).abs() < 1e-7 * (1.0 + e.abs()), "{a} vs {e}");
        }
    }
    let p = ProMp::fit(&demos, dof, &cfg).unwrap();
    let mean = vecf(&f["mean"]);
    let mut y = vec![0.0; dof];
    for (k, &tk) in t.iter().enumerate() {
        p.eval(tk, Order::Position, &mut y);
        for j in 0..dof {
            assert!((y[j] - mean[k * dof + j]).abs() < 1e-9);
        }
    }
    let c = p
        .condition(&[ViaPoint {
            t: f["via_t"].as_f64().unwrap(),
            order: Order::Position,
            value: vecf(&f["via_value"]),
            cov: vecf(&f["via_cov"]),
        }])
        .unwrap();
    // movement_primitives returns (n_steps, n_dims) after reshaping a joint-major vector.
    let cm = vecf(&f["cond_mean"]);
    let cv = vecf(&f["cond_var"]);
    let n = t.len();
    let mut v = vec![0.0; dof];
    for (k, &tk) in t.iter().enumerate() {
        c.eval(tk, Order::Position, &mut y);
        c.variance(tk, Order::Position, &mut v);
        for j in 0..dof {
            assert!((y[j] - cm[k * dof + j]).abs() < 1e-8, "mean t={tk} j={j}");
            // var_trajectory reshapes the joint-major diagonal as (n_dims, n_steps).T
            let e = cv[k * dof + j];
            let _ = n;
            assert!(
                (v[j] - e).abs() < 1e-8 * (1.0 + e),
                "var t={tk} j={j}: {} vs {e}",
                v[j]
            );
        }
    }
    assert!(f["mp_mutates_time_array"].as_bool().unwrap());
}
