//! End-to-end tests of the `trajkit` binary: the main job, the seed's table, and bad input.

use std::process::Output;
mod common;
use common::{entries, scratch, trajkit};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).to_string()
}

#[test]
fn plan_default_passes_check_against_panda() {
    let d = scratch("plan-default");
    let o = trajkit(&["plan", "--plot", "t.svg"], &d);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("within limits"), "{out}");
    assert!(d.join("trajectory.csv").exists() && d.join("t.svg").exists());
    let text = std::fs::read_to_string(d.join("trajectory.csv")).unwrap();
    // The columns carry the joint names.
    assert!(
        text.starts_with("t,q_panda_joint1,q_panda_joint2,"),
        "{}",
        &text[..80]
    );
    // The default method: TOPP-RA, then jerk bounded; every Panda limit holds, jerk included.
    assert!(out.contains("jerk: bounded (TOPP-RA"), "{out}");
    let o = trajkit(&["check", "trajectory.csv", "--limits", "panda"], &d);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    // Raw TOPP-RA on request: velocity and acceleration hold, jerk is not limited (and said so).
    let o = trajkit(&["plan", "--no-jerk-limit", "--out", "raw.csv"], &d);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("jerk: not bounded"), "{}", stdout(&o));
    let o = trajkit(
        &["check", "raw.csv", "--limits", "panda", "--max-jerk", "inf"],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert!(stdout(&o).contains("PASS"));
    // Polynomials: jerk limited too, JSON output and a different degree.
    let o = trajkit(
        &[
            "plan",
            "--method",
            "poly",
            "--degree",
            "septic",
            "--via-velocity",
            "zero",
            "--out",
            "t.json",
            "--rate",
            "250",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("t.json")).unwrap()).unwrap();
    assert_eq!(v["dof"], 7);
    let o = trajkit(&["check", "t.json", "--json", "--limits", "panda"], &d);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let r: serde_json::Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    assert_eq!(r["passes"], true);
}

#[test]
fn poly_table_prints_the_seed_coefficients() {
    let d = scratch("poly-table");
    let o = trajkit(&["poly", "--table"], &d);
    assert!(o.status.success());
    let t = stdout(&o);
    for row in [
        ["cubic", "1.5000", "6.0000", "12.0000"],
        ["quintic", "1.8750", "5.7735", "60.0000"],
        ["septic", "2.1875", "7.5132", "52.5000"],
    ] {
        let line = t
            .lines()
            .find(|l| l.starts_with(row[0]))
            .expect("row present");
        let fields: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(&fields[..], &row[..], "{line}");
    }
}

#[test]
fn poly_move_to_stdout_and_min_duration() {
    let d = scratch("poly-move");
    let o = trajkit(
        &[
            "poly",
            "--from",
            "0",
            "--to",
            "1",
            "--duration",
            "1",
            "--rate",
            "4",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let lines: Vec<String> = stdout(&o).lines().map(str::to_string).collect();
    assert_eq!(lines.len(), 6); // header + 5 samples
    assert!(lines[3].starts_with("0.5,0.5,1.875,"), "{}", lines[3]);
    let o = trajkit(
        &[
            "poly",
            "--from",
            "0,0,0,-1.5,0,1.5,0",
            "--to",
            "1,0.5,0,-1,0,2,0.5",
            "--limits",
            "panda",
            "--out",
            "m.csv",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = trajkit(&["check", "m.csv", "--limits", "panda"], &d);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

/// `trajkit poly` arguments of a move far beyond the Panda's velocity limit (2 rad in 0.2 s
/// with a cubic), written to `out`.
fn too_fast_cubic(out: &str) -> [&str; 9] {
    [
        "poly",
        "--from",
        "0,0,0,-1.5,0,1.5,0",
        "--to",
        "2,0,0,-1.5,0,1.5,0",
        "--duration",
        "0.2",
        "--out",
        out,
    ]
}

#[test]
fn check_fails_on_a_violating_trajectory() {
    let d = scratch("check-fail");
    let o = trajkit(&too_fast_cubic("fast.csv"), &d);
    assert!(o.status.success());
    let o = trajkit(&["check", "fast.csv", "--limits", "panda"], &d);
    assert_eq!(o.status.code(), Some(1));
    assert!(stdout(&o).contains("FAIL: joint 1"), "{}", stdout(&o));
}

/// Every bad input: exit status 2, exactly one line on stderr that names the problem, and no
/// output file left behind.
#[test]
fn bad_inputs_exit_2_with_one_line_and_no_output() {
    let d = scratch("bad");
    let write = |name: &str, text: &str| std::fs::write(d.join(name), text).unwrap();
    write("cols.csv", "0,0,0,0,0,1,0\n0.1,0.1,0.1,-1,0.1,1\n");
    write("nan.csv", "0,0,0,-1,0,1,0\n0.1,nan,0.1,-1,0.1,1,0\n");
    write("inf.csv", "0,0,0,-1,0,1,0\n0.1,0.1,inf,-1,0.1,1,0\n");
    write("one.csv", "0,0,0,-1,0,1,0\n");
    write("dups.csv", "0,0,0,-1,0,1,0\n0,0,0,-1,0,1,0\n");
    write("three.csv", "0,0,0\n1,1,1\n");
    write("ok.csv", "0,0,0,-1,0,1,0\n0.5,0.1,0.1,-1,0.1,1.2,0\n");
    write("range.csv", "0,0,0,-1,0,1,0\n3.5,0.1,0.1,-1,0.1,1.2,0\n");
    write(
        "neg.yaml",
        "joints:\n  - velocity: -1\n    acceleration: 1\n    jerk: 1\n",
    );
    write("bad.json", "[[0,1],[2,");
    let cases: &[(&[&str], &[&str])] = &[
        (
            &["plan", "--waypoints", "cols.csv"],
            &["cols.csv:2", "6 columns, expected 7"],
        ),
        (
            &["plan", "--waypoints", "nan.csv"],
            &["nan.csv:2", "q2", "NaN"],
        ),
        (
            &["plan", "--waypoints", "inf.csv"],
            &["inf.csv:2", "q3", "inf"],
        ),
        (
            &["plan", "--waypoints", "one.csv"],
            &["one.csv", "2 waypoints needed, found 1"],
        ),
        (
            &["plan", "--waypoints", "dups.csv"],
            &["dups.csv", "found 1"],
        ),
        (
            &["plan", "--waypoints", "three.csv", "--limits", "panda"],
            &["three.csv", "the limits have 7 joints, the waypoints 3"],
        ),
        (
            &["plan", "--waypoints", "range.csv", "--limits", "panda"],
            &["range.csv", "waypoint 1 joint 1", "3.5", "position range"],
        ),
        (&["plan", "--waypoints", "missing.csv"], &["missing.csv"]),
        (&["plan", "--waypoints", "bad.json"], &["bad.json:1"]),
        (
            &["plan", "--waypoints", "ok.csv", "--max-velocity", "0"],
            &["velocity", "= 0"],
        ),
        (
            &["plan", "--waypoints", "ok.csv", "--max-acceleration", "-3"],
            &["acceleration", "-3"],
        ),
        (
            &["plan", "--waypoints", "ok.csv", "--limits", "pr2"],
            &["unknown robot preset 'pr2'"],
        ),
        (
            &["plan", "--waypoints", "ok.csv", "--limits", "neg.yaml"],
            &["neg.yaml", "velocity", "-1"],
        ),
        (&["plan", "--rate", "0"], &["sample rate", "= 0"]),
        (&["plan", "--bogus"], &["--bogus"]),
        (&["check", "missing.csv"], &["missing.csv"]),
        (&["check", "cols.csv"], &["cols.csv", "'t'"]),
        (
            &["poly", "--from", "0", "--to", "nan", "--duration", "1"],
            &["--to", "NaN"],
        ),
        (
            &["poly", "--from", "0", "--to", "1", "--duration", "-1"],
            &["duration", "-1"],
        ),
    ];
    for (args, needles) in cases {
        let before = entries(&d);
        let mut full: Vec<&str> = args.to_vec();
        full.extend(
            ["--out", "out.csv", "--plot", "out.svg"]
                .iter()
                .filter(|_| args[0] != "check"),
        );
        let o = trajkit(&full, &d);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
        for n in *needles {
            assert!(err.contains(n), "{args:?}: '{n}' not in: {err}");
        }
        assert!(stdout(&o).is_empty(), "{args:?}");
        assert_eq!(entries(&d), before, "{args:?} left files behind");
    }
}

/// Writing to a device (here /dev/null) must not replace it with a regular file.
#[cfg(unix)]
#[test]
fn output_to_a_device_writes_in_place() {
    use std::os::unix::fs::FileTypeExt;
    let d = scratch("devnull");
    let o = trajkit(
        &[
            "poly",
            "--from",
            "0",
            "--to",
            "1",
            "--duration",
            "1",
            "--out",
            "/dev/null",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let meta = std::fs::metadata("/dev/null").unwrap();
    assert!(
        meta.file_type().is_char_device(),
        "/dev/null is no longer a device"
    );
}

#[test]
fn help_has_examples_everywhere() {
    let d = scratch("help");
    for sub in [
        vec!["--help"],
        vec!["plan", "--help"],
        vec!["poly", "--help"],
        vec!["check", "--help"],
    ] {
        let o = trajkit(&sub, &d);
        assert!(o.status.success());
        assert!(stdout(&o).contains("Examples:"), "{sub:?}");
    }
}

#[test]
fn urdf_limits_with_fill_from_preset() {
    let d = scratch("urdf");
    let mut urdf = String::from("<robot name=\"two\">\n");
    for (i, (lo, hi)) in [(-2.0, 2.0), (-1.5, 1.5)].iter().enumerate() {
        urdf.push_str(&format!(
            "  <joint name=\"j{i}\" type=\"revolute\"><limit lower=\"{lo}\" upper=\"{hi}\" velocity=\"1.5\" effort=\"10\"/></joint>\n"
        ));
    }
    urdf.push_str("</robot>\n");
    std::fs::write(d.join("two.urdf"), urdf).unwrap();
    std::fs::write(d.join("w.csv"), "j0,j1\n0,0\n1,-1\n0.5,0.5\n").unwrap();
    // URDF has no acceleration/jerk: fill them from a 2-joint override.
    let o = trajkit(
        &[
            "plan",
            "--method",
            "poly",
            "--waypoints",
            "w.csv",
            "--limits",
            "two.urdf",
            "--max-acceleration",
            "5",
            "--max-jerk",
            "100",
            "--out",
            "t.csv",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = trajkit(
        &[
            "check",
            "t.csv",
            "--limits",
            "two.urdf",
            "--max-acceleration",
            "5",
            "--max-jerk",
            "100",
        ],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

#[test]
fn plan_toppra_paths_gridpoints_and_messy_waypoints() {
    let d = scratch("plan-toppra");
    // A repeated waypoint and an exact reversal: the robot stops at the reversal.
    std::fs::write(
        d.join("w.csv"),
        "a,b\n0,0\n0.5,0.2\n0.5,0.2\n1.0,0.4\n0.5,0.2\n0.3,0.9\n",
    )
    .unwrap();
    std::fs::write(
        d.join("two.json"),
        r#"{"joints":[{"name":"a","position":[-2,2],"velocity":1,"acceleration":2,"jerk":100},{"name":"b","position":[-2,2],"velocity":1,"acceleration":2,"jerk":100}]}"#,
    )
    .unwrap();
    for extra in [
        vec![],
        vec!["--path", "linear"],
        vec!["--path", "not-a-knot", "--gridpoints", "auto"],
        vec!["--path", "clamped", "--gridpoints", "200"],
    ] {
        let mut args = vec![
            "plan",
            "--waypoints",
            "w.csv",
            "--limits",
            "two.json",
            "--out",
            "t.csv",
        ];
        args.extend(extra.iter().copied());
        let o = trajkit(&args, &d);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        let out = stdout(&o);
        assert!(
            out.contains("within limits") && out.contains("removed 1 duplicate"),
            "{out}"
        );
        let o = trajkit(
            &[
                "check",
                "t.csv",
                "--limits",
                "two.json",
                "--max-jerk",
                "inf",
            ],
            &d,
        );
        assert_eq!(o.status.code(), Some(0), "{extra:?}: {}", stdout(&o));
    }
    // Bad --gridpoints and --path values: exit 2, one line.
    for (args, want) in [
        (
            vec!["plan", "--gridpoints", "0"],
            "'0' is not a positive interval count",
        ),
        (vec!["plan", "--path", "bezier"], "bezier"),
    ] {
        let o = trajkit(&args, &d);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains(want), "{}", stderr(&o));
    }
}

#[test]
fn check_reads_standard_input() {
    use common::trajkit_stdin;
    let d = scratch("check-stdin");
    // `plan --out -` writes the CSV table to standard output; `check` reads it back.
    let o = trajkit(&["plan", "--out", "-"], &d);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(entries(&d).is_empty(), "{:?}", entries(&d));
    let csv = stdout(&o);
    let o = trajkit_stdin(&["check", "--limits", "panda"], &d, Some(&csv));
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert!(stdout(&o).contains("PASS"), "{}", stdout(&o));
    // JSON is recognized by its first character; '-' names standard input explicitly.
    let o = trajkit(&["plan", "--out", "t.json"], &d);
    assert!(o.status.success(), "{}", stderr(&o));
    let json = std::fs::read_to_string(d.join("t.json")).unwrap();
    let o = trajkit_stdin(
        &["check", "-", "--json", "--limits", "panda"],
        &d,
        Some(&json),
    );
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let v: serde_json::Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    assert_eq!(v["passes"], true);
    // A violation read from standard input still exits 1.
    let o = trajkit(&too_fast_cubic("-"), &d);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = trajkit_stdin(&["check", "--limits", "panda"], &d, Some(&stdout(&o)));
    assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
    // Empty or malformed standard input: exit 2, one line naming <stdin>.
    for bad in ["", "t,q1\n0,x\n", "{\"t\": [0, 1]"] {
        let o = trajkit_stdin(&["check"], &d, Some(bad));
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.trim().lines().count(), 1, "{e}");
        assert!(e.contains("<stdin>"), "{e}");
    }
}

#[test]
fn a_reader_that_goes_away_ends_the_run_quietly() {
    // `trajkit plan -o - | head -1`: the table (~700 kB) overflows the pipe's buffer after the
    // reader has gone, so the write meets a closed pipe: status 0, no panic, no error line.
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    let args = ["plan", "--limits", "panda", "-o", "-"];
    let mut child = Command::new(env!("CARGO_BIN_EXE_trajkit"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert!(!first.is_empty(), "{args:?}");
    // The reader is dropped here: the rest of the output meets a closed pipe.
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert!(!err.contains("Broken pipe"), "{args:?}: {err}");
}
