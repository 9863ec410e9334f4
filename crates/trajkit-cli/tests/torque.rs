//! End-to-end tests of `trajkit plan --torque-limits`.

use std::path::{Path, PathBuf};
use std::process::Output;
mod common;
use common::trajkit;

/// A two-link arm in the vertical x-z plane, with effort limits that bind.
const ARM: &str = include_str!("../../trajkit/tests/fixtures/two_link_arm.urdf");

/// Named like the URDF's joints (the columns take the limits of their name).
const WAYPOINTS: &str = "shoulder,elbow\n0,0\n1.2,-1.0\n0.3,1.0\n-0.5,0.2\n";

/// A fresh directory holding the arm's URDF and the waypoints.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("trajkit-torque-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("arm.urdf"), ARM).unwrap();
    std::fs::write(d.join("w.csv"), WAYPOINTS).unwrap();
    d
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).to_string()
}

/// The duration from the summary's "method: ..., duration: X s" line.
fn duration(summary: &str) -> f64 {
    let rest = summary.split("duration: ").nth(1).expect("a duration");
    rest.split(' ').next().unwrap().parse().unwrap()
}

#[test]
fn plan_with_torque_limits_holds_the_efforts() {
    let d = scratch("ok");
    let base = [
        "plan",
        "--waypoints",
        "w.csv",
        "--limits",
        "arm.urdf",
        "--max-acceleration",
        "40",
        "--max-jerk",
        "2000",
    ];
    let free = trajkit(&[&base[..], &["--out", "free.csv"]].concat(), &d);
    assert_eq!(free.status.code(), Some(0), "{}", text(&free.stderr));
    let free_out = text(&free.stdout);
    assert!(!free_out.contains("torque:"), "{free_out}");
    // Jerk bounded, then torque: the dynamics default to the --limits URDF.
    let o = trajkit(&[&base[..], &["--torque-limits"]].concat(), &d);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    assert!(out.contains("torque: worst ratio"), "{out}");
    assert!(out.contains("within effort limits"), "{out}");
    assert!(
        out.contains("worst: ") && out.contains("within limits"),
        "{out}"
    );
    let ratio: f64 = out
        .split("torque: worst ratio ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(ratio <= 1.0 + 1e-6 && ratio > 0.9, "{ratio}");
    assert!(duration(&out) > duration(&free_out), "{out}\n{free_out}");
    assert!(sampled_torque_ratio(&d.join("trajectory.csv")) <= 1.0 + 1e-6);
    // Raw TOPP-RA with an explicit --dynamics.
    let o = trajkit(
        &[
            "plan",
            "--waypoints",
            "w.csv",
            "--limits",
            "arm.urdf",
            "--torque-limits",
            "--dynamics",
            "arm.urdf",
            "--no-jerk-limit",
            "--max-acceleration",
            "40",
            "--out",
            "raw.csv",
        ],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    assert!(out.contains("within effort limits"), "{out}");
    assert!(!out.contains("slowed down"), "{out}");
}

/// Worst |τ| / effort recomputed from the written table's q, q̇, q̈ columns.
fn sampled_torque_ratio(csv: &Path) -> f64 {
    use trajkit::topp::InverseDynamics;
    let chain = trajkit::dynamics::SerialChain::from_urdf_str(ARM, "arm.urdf").unwrap();
    let effort = [24.0, 6.0];
    let table = std::fs::read_to_string(csv).unwrap();
    let mut lines = table.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,q_shoulder,q_elbow,qd_shoulder,qd_elbow,qdd_shoulder,qdd_elbow,qddd_shoulder,qddd_elbow"
    );
    let mut worst: f64 = 0.0;
    let mut tau = [0.0; 2];
    for line in lines {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        chain.torque(&v[1..3], &v[3..5], &v[5..7], &mut tau);
        for j in 0..2 {
            worst = worst.max(tau[j].abs() / effort[j]);
        }
    }
    worst
}

fn one_line_error(o: &Output) -> String {
    assert_eq!(o.status.code(), Some(2), "{}", text(&o.stdout));
    let err = text(&o.stderr);
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    err
}

#[test]
fn torque_limits_bad_input_is_one_line_and_writes_nothing() {
    let d = scratch("bad");
    let entries = || {
        let mut v: Vec<String> = std::fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
            .collect();
        v.sort();
        v
    };
    // A preset has no dynamics model.
    let o = trajkit(&["plan", "--torque-limits", "--limits", "panda"], &d);
    let err = one_line_error(&o);
    assert!(err.contains("--dynamics"), "{err}");
    // Efforts missing from the limits.
    std::fs::write(d.join("noeff.urdf"), ARM.replace(" effort=\"24\"", "")).unwrap();
    let o = trajkit(
        &[
            "plan",
            "--waypoints",
            "w.csv",
            "--limits",
            "noeff.urdf",
            "--max-acceleration",
            "40",
            "--max-jerk",
            "2000",
            "--torque-limits",
        ],
        &d,
    );
    let err = one_line_error(&o);
    assert!(
        err.contains("joint 1 (shoulder) has no effort limit"),
        "{err}"
    );
    // A broken dynamics file names file, line, field and value.
    std::fs::write(
        d.join("bad.urdf"),
        ARM.replace("value=\"1.5\"", "value=\"heavy\""),
    )
    .unwrap();
    let o = trajkit(
        &[
            "plan",
            "--waypoints",
            "w.csv",
            "--limits",
            "arm.urdf",
            "--torque-limits",
            "--dynamics",
            "bad.urdf",
            "--max-acceleration",
            "40",
            "--max-jerk",
            "2000",
        ],
        &d,
    );
    let err = one_line_error(&o);
    assert!(
        err.contains("bad.urdf:8") && err.contains("<mass value>") && err.contains("'heavy'"),
        "{err}"
    );
    // --dynamics alone, and with the polynomial method.
    let o = trajkit(&["plan", "--dynamics", "arm.urdf"], &d);
    assert!(one_line_error(&o).contains("only with --torque-limits"));
    let o = trajkit(
        &[
            "plan",
            "--waypoints",
            "w.csv",
            "--limits",
            "arm.urdf",
            "--torque-limits",
            "--max-acceleration",
            "40",
            "--max-jerk",
            "2000",
            "--method",
            "poly",
        ],
        &d,
    );
    assert!(one_line_error(&o).contains("--method toppra"));
    assert_eq!(
        entries(),
        vec!["arm.urdf", "bad.urdf", "noeff.urdf", "w.csv"]
    );
}
