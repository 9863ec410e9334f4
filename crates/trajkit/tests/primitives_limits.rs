//! Movement primitives refuse sizes and inputs outside their meaningful domain with typed
//! errors, before allocating: basis counts, reference points, rollout lengths, goals far from
//! the demonstration, via points outside the movement.

use trajkit::primitives::{
    Demo, Dmp, DmpConfig, GmmConfig, Kmp, KmpConfig, KmpReference, KmpVia, ProMp, ProMpConfig,
    RolloutOptions, ViaPoint,
};
use trajkit::Error;

/// A 2-joint demonstration over 2 s at `rate` Hz.
fn demo_at(shift: f64, rate: f64) -> (Vec<f64>, Vec<f64>) {
    let n = (2.0 * rate) as usize;
    let t: Vec<f64> = (0..=n).map(|k| k as f64 / rate).collect();
    let q: Vec<f64> = t
        .iter()
        .flat_map(|&s| {
            let x = s / 2.0;
            let m = 10.0 * x.powi(3) - 15.0 * x.powi(4) + 6.0 * x.powi(5);
            [m + shift, 0.5 * (1.0 - m) - shift]
        })
        .collect();
    (t, q)
}

/// A 2-joint demonstration over 2 s at 100 Hz.
fn demo(shift: f64) -> (Vec<f64>, Vec<f64>) {
    demo_at(shift, 100.0)
}

fn too_large(e: &Error) -> bool {
    matches!(e, Error::TooLarge { .. })
}

#[test]
fn dmp_basis_rollout_and_goal_domain() {
    let (t, q) = demo(0.0);
    let cfg = DmpConfig {
        n_basis: 1_000_000,
        ..Default::default()
    };
    let e = Dmp::fit(&t, &q, 2, &cfg).unwrap_err();
    assert!(too_large(&e), "{e}");
    assert!(
        e.to_string()
            .starts_with("basis function count = 1000000 is above the limit of 2000"),
        "{e}"
    );
    let dmp = Dmp::fit(&t, &q, 2, &DmpConfig::default()).unwrap();
    // A goal 1e300 away writes 1e307-sized values: refused, naming the joint.
    let far = RolloutOptions {
        goal: Some(vec![1e300, 0.0]),
        ..Default::default()
    };
    let e = dmp.rollout(&far).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidValue { field, value, .. } if field == "goal of joint 1" && *value == 1e300),
        "{e}"
    );
    // Within 1e6 × the demonstration's extent (1 here): accepted.
    let near = RolloutOptions {
        goal: Some(vec![1e5, 0.0]),
        ..Default::default()
    };
    assert!(dmp.rollout(&near).is_ok());
    let start = RolloutOptions {
        start: Some(vec![0.0, -2e6]),
        ..Default::default()
    };
    assert!(dmp.rollout(&start).is_err());
    // A rollout of a year at 500 steps per τ.
    let long = RolloutOptions {
        duration: Some(3.15e7),
        ..Default::default()
    };
    let e = dmp.rollout(&long).unwrap_err();
    assert!(too_large(&e), "{e}");
}

#[test]
fn promp_via_points_inside_the_movement() {
    let (t1, q1) = demo(0.0);
    let (t2, q2) = demo(0.05);
    let demos = [Demo { t: &t1, q: &q1 }, Demo { t: &t2, q: &q2 }];
    let p = ProMp::fit(&demos, 2, &ProMpConfig::default()).unwrap();
    let e = p
        .condition(&[ViaPoint::position(99.0, &[0.3, 0.2], 0.0)])
        .unwrap_err();
    assert!(
        matches!(&e, Error::InvalidValue { value, .. } if *value == 99.0),
        "{e}"
    );
    assert!(e.to_string().contains("the movement lasts 2 s"), "{e}");
    assert!(p
        .condition(&[ViaPoint::position(-0.1, &[0.3, 0.2], 0.0)])
        .is_err());
    assert!(p
        .condition(&[ViaPoint::position(1.0, &[0.3, 0.2], 0.0)])
        .is_ok());
    let big = ProMpConfig {
        n_basis: 3000,
        ..Default::default()
    };
    assert!(too_large(&ProMp::fit(&demos, 2, &big).unwrap_err()));
}

#[test]
fn kmp_points_and_via_points() {
    let (t1, q1) = demo_at(0.0, 10.0);
    let (t2, q2) = demo_at(0.05, 10.0);
    let demos = [Demo { t: &t1, q: &q1 }, Demo { t: &t2, q: &q2 }];
    let gmm = GmmConfig {
        components: 3,
        max_iter: 30,
        ..Default::default()
    };
    let e = KmpReference::from_demos(&demos, 2, &gmm, 100_000).unwrap_err();
    assert!(too_large(&e), "{e}");
    assert!(
        e.to_string()
            .contains("KMP unknowns (reference points × joints) = 200000"),
        "{e}"
    );
    let r = KmpReference::from_demos(&demos, 2, &gmm, 20).unwrap();
    let kmp = Kmp::fit(&r, &KmpConfig::default()).unwrap();
    let via = |t: f64| KmpVia {
        t,
        mean: vec![0.3, 0.2],
        cov: vec![1e-6, 0.0, 0.0, 1e-6],
    };
    let e = kmp.with_via_points(&[via(99.0)]).unwrap_err();
    assert!(
        matches!(&e, Error::InvalidValue { value, .. } if *value == 99.0),
        "{e}"
    );
    assert!(kmp.with_via_points(&[via(1.0)]).is_ok());
}
