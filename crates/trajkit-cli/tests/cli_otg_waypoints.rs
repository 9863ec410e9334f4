//! End-to-end tests of `trajkit otg` with intermediate waypoints.

mod common;
use common::{scratch, trajkit_stdin};

const WP: &str = r#"{"current_position":[0,0],"target_position":[2,1],"intermediate_positions":[[1,0.2],[1.5,0.8]],"max_velocity":[1,1],"max_acceleration":[2,2],"max_jerk":[10,10],"per_section_minimum_duration":[0,0,0.5],"dt":0.01}"#;

#[test]
fn waypoints_one_problem_and_batch() {
    let d = scratch("waypoints");
    let o = trajkit_stdin(&["otg", "-"], &d, Some(WP));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let t = v["duration"].as_f64().unwrap();
    let stop = v["stop_at_every_waypoint_duration"].as_f64().unwrap();
    assert!(t > 0.0 && t < stop, "{t} vs {stop}");
    assert!(v["waypoint_error"].as_f64().unwrap() <= 1e-8);
    assert!(v["worst_limit_ratio"].as_f64().unwrap() <= 1.0 + 1e-12);
    let secs = v["section_durations"].as_array().unwrap();
    assert_eq!(secs.len(), 3);
    assert!(secs[2].as_f64().unwrap() >= 0.5);
    // Batch: the waypoint problem, and one whose per-section field has the wrong length.
    let bad = WP.replace("[0,0,0.5]", "[0,0.5]");
    std::fs::write(d.join("b.jsonl"), format!("{WP}\n{bad}\n")).unwrap();
    let o = trajkit_stdin(&["otg", "--batch", "b.jsonl", "--profiles"], &d, None);
    assert_eq!(o.status.code(), Some(1));
    let rows: Vec<serde_json::Value> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(rows[0]["result"], "working");
    assert_eq!(rows[0]["duration"].as_f64(), Some(t));
    assert_eq!(rows[0]["profiles"].as_array().unwrap().len(), 3);
    assert_eq!(rows[1]["result"], "invalid_input");
    assert!(rows[1]["message"]
        .as_str()
        .unwrap()
        .contains("per_section_minimum_duration = 2"));
    // A refused option is one clear line and exit 2.
    let o = trajkit_stdin(
        &["otg", "-"],
        &d,
        Some(&WP.replace("\"dt\"", "\"synchronization\":\"none\",\"dt\"")),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("synchronization"));
}
