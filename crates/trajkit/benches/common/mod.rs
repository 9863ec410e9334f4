//! Inputs shared by the TOPP benchmarks (each uses some of them).
#![allow(dead_code)]

use trajkit::io::Waypoints;
use trajkit::rng::SplitMix64;
use trajkit::Limits;

/// `n` seeded random Panda configurations (uniform, 0.1 rad inside each joint's range): the
/// waypoints of the `random_W` benchmarks.
pub fn random_panda_waypoints(n: usize) -> Waypoints {
    let lim = Limits::preset("panda").unwrap();
    let mut rng = SplitMix64::new(4242);
    let mut wp = Vec::with_capacity(n * 7);
    for _ in 0..n {
        for j in lim.joints() {
            wp.push(rng.uniform(j.position_min + 0.1, j.position_max - 0.1));
        }
    }
    Waypoints::new(wp, 7, vec![]).unwrap()
}

/// The `standard_7wp_natural_N1000` TOPP-RA fixture problem (waypoints, limits, toppra's
/// answer) as JSON.
pub fn standard_7wp_problem() -> serde_json::Value {
    let p = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/topp/toppra_panda.json"
    );
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
    v["problems"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "standard_7wp_natural_N1000")
        .unwrap()
        .clone()
}

/// The waypoints (row-major, 7 × 7) of the `standard_7wp_natural_N1000` TOPP-RA fixture
/// problem: 7 random Panda configurations.
pub fn standard_7wp_waypoints() -> Vec<f64> {
    let prob = standard_7wp_problem();
    prob["waypoints"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
        .collect()
}
