//! Inputs shared by the TOPP benchmarks.

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
