//! End-to-end tests of `trajkit otg`.

mod common;
use common::{entries, scratch, trajkit_stdin};

const SEED: &str = r#"{"current_position":[0],"target_position":[1],"max_velocity":[0.6],"max_acceleration":[1],"max_jerk":[4]}"#;

#[test]
fn seed_example_json_csv_and_plot() {
    let d = scratch("seed");
    let o = trajkit_stdin(&["otg", "-"], &d, Some(SEED));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let t = v["duration"].as_f64().unwrap();
    assert!((t - (1.0 / 0.6 + 0.6 + 0.25)).abs() < 1e-12, "{t}");
    assert!(v["final_error"]["position"].as_f64().unwrap() < 1e-8);
    assert!(v["worst_limit_ratio"].as_f64().unwrap() <= 1.0 + 1e-12);
    // Trapezoid: an "inf" jerk limit is unlimited; CSV by extension, and a plot.
    std::fs::write(d.join("p.json"), SEED.replace("[4]", r#"["inf"]"#)).unwrap();
    let o = trajkit_stdin(
        &["otg", "p.json", "--out", "s.csv", "--plot", "p.svg"],
        &d,
        None,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("duration 2.266666667"));
    let csv = std::fs::read_to_string(d.join("s.csv")).unwrap();
    assert!(csv.starts_with("t,q1,qd1,qdd1,qddd1"));
    assert!(std::fs::read_to_string(d.join("p.svg"))
        .unwrap()
        .starts_with("<svg"));
}

#[test]
fn batch_one_line_per_problem() {
    let d = scratch("batch");
    let lines = [
        SEED.to_string(),
        r#"{"current_position":[0,1],"current_velocity":[0.5,0],"target_position":[1,-1],"target_velocity":[0.2,0],"max_velocity":[1,1],"max_acceleration":[2,2],"max_jerk":[5,5],"synchronization":"phase"}"#.to_string(),
        "not json".to_string(),
        r#"{"current_position":[0],"target_position":[1],"max_velocity":[-1],"max_acceleration":[1],"max_jerk":[1]}"#.to_string(),
    ];
    std::fs::write(d.join("b.jsonl"), lines.join("\n")).unwrap();
    let o = trajkit_stdin(&["otg", "--batch", "b.jsonl", "--out", "r.jsonl"], &d, None);
    // Two lines failed: exit 1, and the count on standard error (the results are written).
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("2 of 4 problems failed"));
    let text = std::fs::read_to_string(d.join("r.jsonl")).unwrap();
    let rows: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(rows.len(), 4);
    assert_eq!(rows[0]["result"], "working");
    assert!((rows[0]["duration"].as_f64().unwrap() - 2.5166666666666667).abs() < 1e-12);
    assert!(rows[0].get("samples").is_none());
    assert_eq!(rows[1]["result"], "working");
    assert!(rows[1]["final_error"]["position"].as_f64().unwrap() < 1e-8);
    assert_eq!(rows[2]["result"], "invalid_input");
    assert_eq!(rows[3]["result"], "invalid_input");
    assert!(rows[3]["message"]
        .as_str()
        .unwrap()
        .contains("max_velocity[0] = -1"));
    assert_eq!(rows[3]["dof"], 0);
    // With --profiles, every DOF's segments; all lines solved: exit 0.
    std::fs::write(d.join("c.jsonl"), lines[..2].join("\n")).unwrap();
    let o = trajkit_stdin(
        &["otg", "--batch", "c.jsonl", "--profiles", "--out", "c.out"],
        &d,
        None,
    );
    assert_eq!(o.status.code(), Some(0));
    let text = std::fs::read_to_string(d.join("c.out")).unwrap();
    let row: serde_json::Value = serde_json::from_str(text.lines().nth(1).unwrap()).unwrap();
    let prof = &row["profiles"][1];
    let total: f64 = prof["segments"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s[0].as_f64().unwrap())
        .sum();
    assert!((total - row["duration"].as_f64().unwrap()).abs() < 1e-12);
    assert!((prof["end"][0].as_f64().unwrap() + 1.0).abs() < 1e-12);
}

#[test]
fn position_limits_and_budget() {
    let d = scratch("position");
    let lines = [
        r#"{"current_position":[0],"target_position":[1],"max_velocity":[0.6],"max_acceleration":[1],"max_jerk":[4],"max_position":[1],"min_position":["-inf"],"interrupt_calculation_duration":100000}"#,
        r#"{"current_position":[0],"current_velocity":[0.9],"target_position":[0],"max_velocity":[1],"max_acceleration":[2],"max_jerk":[10],"max_position":[0.05]}"#,
    ];
    std::fs::write(d.join("b.jsonl"), lines.join("\n")).unwrap();
    let o = trajkit_stdin(&["otg", "--batch", "b.jsonl", "--out", "r.jsonl"], &d, None);
    assert_eq!(o.status.code(), Some(1));
    let text = std::fs::read_to_string(d.join("r.jsonl")).unwrap();
    let rows: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(rows[0]["result"], "working");
    assert!((rows[0]["duration"].as_f64().unwrap() - 2.5166666666666667).abs() < 1e-12);
    assert!(rows[0]["position_excess"].as_f64().unwrap() <= 0.0);
    assert_eq!(rows[1]["result"], "position_limits");
    assert_eq!(rows[1]["dof"], 0);
}

#[test]
fn strict_fields() {
    let d = scratch("strict");
    for (problem, needle) in [
        (
            r#"{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerk":[1],"max_jerks":[1]}"#,
            "'max_jerks': is not a known field (did you mean 'max_jerk'?)",
        ),
        (
            r#"{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerk":[1],"intermediate_positions":[[0.5]],"per_section_min_velocity":[[-1],[-1]]}"#,
            "does not support yet",
        ),
        (
            r#"{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerk":[1],"per_dof_synchronization":["straight_line"]}"#,
            "per_dof_synchronization[0]",
        ),
    ] {
        let o = trajkit_stdin(&["otg", "-"], &d, Some(problem));
        assert_eq!(o.status.code(), Some(2), "{problem}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(needle), "{problem}: {err}");
    }
    // Every Ruckig field trajkit does not support is refused by name, never ignored.
    for field in trajkit::otg::json::NOT_SUPPORTED_YET {
        let problem = format!(
            r#"{{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerk":[1],"intermediate_positions":[[0.5]],"{field}":[[0],[0]]}}"#
        );
        let o = trajkit_stdin(&["otg", "-"], &d, Some(problem.as_str()));
        assert_eq!(o.status.code(), Some(2), "{problem}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(&format!("'{field}'")) && err.contains("does not support yet"),
            "{field}: {err}"
        );
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
}

#[test]
fn bad_input_exits_2_with_one_line_and_no_file() {
    let d = scratch("bad");
    for (i, (problem, needle)) in [
        (
            r#"{"current_position":[0],"target_position":[1,2]}"#,
            "target_position",
        ),
        (
            r#"{"current_position":[0],"target_position":[1],"synchronization":"fast"}"#,
            "synchronization",
        ),
        (
            r#"{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerk":["x"]}"#,
            "max_jerk[0]",
        ),
        (r#"{"target_position":[1]}"#, "current_position"),
        (
            r#"{"current_position":[0],"target_position":[1]}"#,
            "'max_velocity': is required",
        ),
        (
            r#"{"current_position":[0],"target_position":[1],"max_velocity":["inf"],"max_acceleration":["inf"],"max_jerk":["inf"]}"#,
            "max_velocity[0] = inf",
        ),
        (
            r#"{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerk":[1],"dt":0}"#,
            "dt",
        ),
        ("[1, 2", "line 1"),
    ]
    .into_iter()
    .enumerate()
    {
        let f = format!("p{i}.json");
        std::fs::write(d.join(&f), problem).unwrap();
        let o = trajkit_stdin(&["otg", &f, "--out", "s.csv", "--plot", "p.svg"], &d, None);
        assert_eq!(o.status.code(), Some(2), "{problem}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{problem}: {err}");
        let left: Vec<String> = entries(&d)
            .into_iter()
            .filter(|e| !e.ends_with(".json"))
            .collect();
        assert!(left.is_empty(), "{left:?}");
    }
    let o = trajkit_stdin(
        &["otg", "--batch", "missing.jsonl", "--out", "r.jsonl"],
        &d,
        None,
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(!d.join("r.jsonl").exists());
}

#[test]
fn too_many_samples_is_bad_input() {
    let d = scratch("many");
    let p = r#"{"current_position":[0],"target_position":[10000],"max_velocity":[0.01],"max_acceleration":[1],"max_jerk":[1]}"#;
    let o = trajkit_stdin(&["otg", "-", "--out", "s.csv"], &d, Some(p));
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("'dt'"));
    assert!(entries(&d).is_empty());
    // The same problem in a batch: a result line with the duration, no samples.
    std::fs::write(d.join("b.jsonl"), p).unwrap();
    let o = trajkit_stdin(&["otg", "--batch", "b.jsonl"], &d, None);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // D/v + 2·sqrt(v/j): the acceleration limit is not reached.
    assert!(
        (v["duration"].as_f64().unwrap() - (1e6 + 0.2)).abs() < 1e-6,
        "{v}"
    );
}
