//! Curved test paths of the jerk-limited stages, shared by their test suites: seeded random
//! Panda splines, a path with 1e-3 rad segments, the IPOPT reference cases, Panda limits with
//! scaled jerk.
#![allow(dead_code)]

use serde_json::Value;
use trajkit::rng::SplitMix64;
use trajkit::spline::CubicSpline;
use trajkit::{Limits, Order};

/// The Panda's limits with every jerk limit multiplied by `scale`.
pub fn panda_with_jerk_scale(scale: f64) -> Limits {
    let panda = Limits::preset("panda").unwrap();
    let js: Vec<f64> = panda.joints().iter().map(|j| j.jerk * scale).collect();
    panda.with_override(Order::Jerk, &js).unwrap()
}

/// A natural cubic spline through 7-DOF waypoints (row-major), chord-length parameter.
pub fn chord_spline(w: &[f64]) -> CubicSpline {
    let count = w.len() / 7;
    let mut s = vec![0.0; count];
    for i in 1..count {
        let d: f64 = (0..7)
            .map(|j| (w[i * 7 + j] - w[(i - 1) * 7 + j]).powi(2))
            .sum::<f64>()
            .sqrt();
        s[i] = s[i - 1] + d;
    }
    CubicSpline::natural(&s, w, 7).unwrap()
}

/// `count` seeded random Panda waypoints (0.1 inside the position ranges).
pub fn random_waypoints(seed: u64, count: usize) -> Vec<f64> {
    let mut rng = SplitMix64::new(seed);
    let panda = Limits::preset("panda").unwrap();
    let mut w = Vec::with_capacity(count * 7);
    for _ in 0..count {
        for j in panda.joints() {
            w.push(rng.uniform(j.position_min + 0.1, j.position_max - 0.1));
        }
    }
    w
}

/// A natural cubic spline (chord length) through `count` seeded random Panda waypoints.
pub fn random_path(seed: u64, count: usize) -> CubicSpline {
    chord_spline(&random_waypoints(seed, count))
}

/// Waypoints of the 1e-3 rad segment case: two seeded random Panda waypoints with four
/// waypoints 1e-3 rad apart (along a random direction) halfway between them.
pub fn short_segment_waypoints() -> Vec<f64> {
    let mut rng = SplitMix64::new(33);
    let panda = Limits::preset("panda").unwrap();
    let random = |rng: &mut SplitMix64| -> Vec<f64> {
        panda
            .joints()
            .iter()
            .map(|j| rng.uniform(j.position_min + 0.3, j.position_max - 0.3))
            .collect()
    };
    let (a, b) = (random(&mut rng), random(&mut rng));
    let mut w = a.clone();
    let dir: Vec<f64> = (0..7).map(|_| rng.uniform(-1.0, 1.0)).collect();
    let norm = dir.iter().map(|d| d * d).sum::<f64>().sqrt();
    let mid: Vec<f64> = (0..7).map(|j| 0.5 * (a[j] + b[j])).collect();
    for k in 0..4 {
        w.extend((0..7).map(|j| mid[j] + 1e-3 * k as f64 * dir[j] / norm));
    }
    w.extend(&b);
    w
}

/// The path of [`short_segment_waypoints`].
pub fn short_segment_path() -> CubicSpline {
    chord_spline(&short_segment_waypoints())
}

/// The cases of `tests/fixtures/jerk/curved_ipopt.json` (`tools/jerk_reference_ipopt.py`):
/// name, jerk scale, waypoints, IPOPT duration.
pub fn ipopt_cases() -> Vec<(String, f64, Vec<f64>, f64)> {
    let p = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/jerk/curved_ipopt.json"
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
    v["cases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let w: Vec<f64> = c["waypoints"]
                .as_array()
                .unwrap()
                .iter()
                .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
                .collect();
            (
                c["name"].as_str().unwrap().to_string(),
                c["jerk_scale"].as_f64().unwrap(),
                w,
                c["duration"].as_f64().unwrap(),
            )
        })
        .collect()
}
