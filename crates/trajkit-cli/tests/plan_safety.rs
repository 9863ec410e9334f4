//! The main job on any robot: `trajkit plan` never hands out a trajectory that breaks a limit
//! it was given (position range included), agrees with `trajkit check`, pairs joints by name,
//! refuses missing limits, never loses a file, bounds sizes and reads input strictly.

use std::path::{Path, PathBuf};
use std::process::Output;
mod common;
use common::{entries, scratch, trajkit};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).to_string()
}

/// Exit status 2 with exactly one line on stderr; returns it.
fn one_line_2(o: &Output, what: &str) -> String {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{what}: {e}{}", stdout(o));
    assert_eq!(e.trim_end().lines().count(), 1, "{what}: not one line: {e}");
    e
}

/// The repository's UR5e example (URDF, MoveIt joint_limits.yaml, named waypoints).
fn ur5e_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/robots/ur5e")
}

fn copy_ur5e(d: &Path) {
    for f in ["ur5e.urdf", "joint_limits.yaml", "path.csv"] {
        std::fs::copy(ur5e_dir().join(f), d.join(f)).unwrap();
    }
}

/// The 7-waypoint standard Panda problem as a CSV without a header.
fn std7_csv() -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../trajkit/tests/fixtures/topp/toppra_panda.json");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
    let prob = v["problems"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "standard_7wp_natural_N1000")
        .unwrap()
        .clone();
    let mut s = String::new();
    for row in prob["waypoints"].as_array().unwrap() {
        let r: Vec<String> = row
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap().to_string())
            .collect();
        s.push_str(&r.join(","));
        s.push('\n');
    }
    s
}

#[test]
fn standard_problem_stays_in_range_and_agrees_with_check() {
    let d = scratch("std7");
    std::fs::write(d.join("std7.csv"), std7_csv()).unwrap();
    // Raw TOPP-RA (fast in a debug build); the same path as the default run, whose jerk stage
    // only retimes it (the ignored test below runs the default command itself).
    let o = trajkit(
        &[
            "plan",
            "--waypoints",
            "std7.csv",
            "--limits",
            "panda",
            "--no-jerk-limit",
            "--out",
            "s.csv",
        ],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("reshaped for joint 6 (panda_joint6)"), "{out}");
    assert!(out.contains("within limits"), "{out}");
    let o = trajkit(
        &["check", "s.csv", "--limits", "panda", "--max-jerk", "inf"],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    // Every Panda limit, jerk included: the polynomial method.
    let o = trajkit(
        &[
            "plan",
            "--waypoints",
            "std7.csv",
            "--limits",
            "panda",
            "--method",
            "poly",
            "--out",
            "p.csv",
        ],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = trajkit(&["check", "p.csv", "--limits", "panda"], &d);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

#[test]
#[ignore = "slow in a debug build (the jerk filter on a 10 s path): cargo test --release -- --ignored"]
fn standard_problem_default_command() {
    let d = scratch("std7-default");
    std::fs::write(d.join("std7.csv"), std7_csv()).unwrap();
    let o = trajkit(
        &["plan", "--waypoints", "std7.csv", "--limits", "panda"],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("within limits"));
    let o = trajkit(&["check", "trajectory.csv", "--limits", "panda"], &d);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

#[test]
fn a_failed_run_leaves_every_file_byte_identical() {
    let d = scratch("files");
    let keep = b"t,q1\n0,0.123456789\n".to_vec();
    std::fs::write(d.join("keep.csv"), &keep).unwrap();
    std::fs::create_dir(d.join("a_dir")).unwrap();
    let before = entries(&d);
    // The second output cannot be written (no such directory): the first is not either.
    for plot in ["/nonexistent/p.svg", "a_dir"] {
        let o = trajkit(&["plan", "--out", "keep.csv", "--plot", plot], &d);
        let e = one_line_2(&o, plot);
        assert!(e.contains(plot), "{e}");
        assert_eq!(std::fs::read(d.join("keep.csv")).unwrap(), keep, "{plot}");
        assert_eq!(entries(&d), before, "{plot}: files created or left behind");
    }
    // A new output next to a failing one is not created either.
    let o = trajkit(&["plan", "--out", "new.csv", "--plot", "a_dir"], &d);
    one_line_2(&o, "new.csv");
    assert_eq!(entries(&d), before);
    // The same file for two outputs.
    let o = trajkit(&["plan", "--out", "x.svg", "--plot", "x.svg"], &d);
    assert!(one_line_2(&o, "twice").contains("two outputs"));
    // A successful run replaces the file and leaves nothing else behind.
    let o = trajkit(&["plan", "--out", "keep.csv", "--plot", "p.svg"], &d);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_ne!(std::fs::read(d.join("keep.csv")).unwrap(), keep);
    assert_eq!(entries(&d), vec!["a_dir", "keep.csv", "p.svg"]);
}

#[test]
fn joint_names_are_the_key() {
    let d = scratch("names");
    let panda = trajkit::Limits::preset("panda").unwrap();
    let names: Vec<&str> = panda.joints().iter().map(|j| j.name.as_str()).collect();
    let rows = [
        [0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0],
        [0.4, 0.2, -0.2, -1.2, 0.1, 1.8, 0.3],
    ];
    // Joints 2 and 4 swapped, with their names.
    let order = [0, 3, 2, 1, 4, 5, 6];
    let mut csv = order.map(|j| names[j]).join(",");
    csv.push('\n');
    for r in rows {
        csv.push_str(&order.map(|j| r[j].to_string()).join(","));
        csv.push('\n');
    }
    std::fs::write(d.join("swapped.csv"), &csv).unwrap();
    let o = trajkit(
        &[
            "plan",
            "--waypoints",
            "swapped.csv",
            "--limits",
            "panda",
            "--method",
            "poly",
        ],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = std::fs::read_to_string(d.join("trajectory.csv")).unwrap();
    assert!(
        text.starts_with("t,q_panda_joint1,q_panda_joint4,q_panda_joint3,q_panda_joint2,"),
        "{}",
        &text[..120]
    );
    // `check` pairs the columns by name too.
    let o = trajkit(&["check", "trajectory.csv", "--limits", "panda"], &d);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    // Unknown names: exit 2, both sets listed.
    std::fs::write(d.join("abc.csv"), "a,b,c\n0,0,0\n0.1,0.1,0.1\n").unwrap();
    let o = trajkit(&["plan", "--waypoints", "abc.csv", "--limits", "panda"], &d);
    let e = one_line_2(&o, "abc");
    assert!(
        e.contains("no limits for waypoint joint(s) a, b, c")
            && e.contains("waypoint joints [a, b, c]")
            && e.contains("panda_joint7]"),
        "{e}"
    );
    // A subset of the joints, in any order: the other limits are not used, and said so.
    std::fs::write(
        d.join("two.csv"),
        "panda_joint7,panda_joint1\n0,0\n0.5,0.3\n",
    )
    .unwrap();
    let o = trajkit(
        &[
            "plan",
            "--waypoints",
            "two.csv",
            "--limits",
            "panda",
            "--method",
            "poly",
            "--out",
            "two_out.csv",
        ],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("limits of panda_joint2, panda_joint3"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn a_missing_limit_is_never_unlimited() {
    let d = scratch("missing");
    copy_ur5e(&d);
    let plan = |extra: &[&str]| {
        let mut a = vec!["plan", "--waypoints", "path.csv", "--out", "u.csv"];
        a.extend_from_slice(extra);
        trajkit(&a, &d)
    };
    // The user's own waypoints never get the Panda's limits by default.
    let e = one_line_2(&plan(&[]), "no limits");
    assert!(
        e.contains("no limits given") && e.contains("--limits"),
        "{e}"
    );
    // A URDF has no acceleration limit.
    let e = one_line_2(&plan(&["--limits", "ur5e.urdf"]), "urdf");
    assert!(
        e.contains("joint 1 (shoulder_pan_joint) has no acceleration limit")
            && e.contains("--max-acceleration"),
        "{e}"
    );
    // Filled from another robot by name: nothing matches, and the way out is named.
    let e = one_line_2(
        &plan(&["--limits", "ur5e.urdf", "--fill-from", "panda"]),
        "fill panda",
    );
    assert!(e.contains("--fill-by index"), "{e}");
    // By index, when asked: the Panda's first six joints' acceleration and jerk.
    let o = plan(&[
        "--limits",
        "ur5e.urdf",
        "--fill-from",
        "panda",
        "--fill-by",
        "index",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // MoveIt's joint_limits.yaml gives acceleration; jerk is still missing for toppra.
    let e = one_line_2(
        &plan(&[
            "--limits",
            "ur5e.urdf",
            "--joint-limits",
            "joint_limits.yaml",
        ]),
        "moveit",
    );
    assert!(
        e.contains("has no jerk limit") && e.contains("--max-jerk"),
        "{e}"
    );
    // ... but not for TOTG, which does not bound jerk.
    let o = plan(&[
        "--limits",
        "ur5e.urdf",
        "--joint-limits",
        "joint_limits.yaml",
        "--method",
        "totg",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // Completed by name from the UR5e preset: the whole job, then check with the same flags.
    let flags = [
        "--limits",
        "ur5e.urdf",
        "--joint-limits",
        "joint_limits.yaml",
        "--fill-from",
        "ur5e",
    ];
    let o = plan(&flags);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let mut check = vec!["check", "u.csv"];
    check.extend_from_slice(&flags);
    let o = trajkit(&check, &d);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    // The elbow range of joint_limits.yaml (±3) holds although the URDF allows ±π.
    let text = std::fs::read_to_string(d.join("u.csv")).unwrap();
    let elbow = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(3).unwrap().parse::<f64>().unwrap())
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(elbow <= 3.0, "{elbow}");
}

#[test]
fn overrides_alone_work_for_any_joint_count() {
    let d = scratch("overrides");
    std::fs::write(d.join("one.csv"), "0\n0.8\n0.2\n").unwrap();
    let base = [
        "plan",
        "--waypoints",
        "one.csv",
        "--max-velocity",
        "1",
        "--max-acceleration",
        "2",
        "--max-jerk",
        "50",
    ];
    // The position range is a limit like the others.
    let e = one_line_2(&trajkit(&base, &d), "range");
    assert!(
        e.contains("joint 1 has no position range") && e.contains("--position-range"),
        "{e}"
    );
    let o = trajkit(
        &[
            &base[..],
            &["--position-range", "-1:1", "--out", "one_out.csv"],
        ]
        .concat(),
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // `check` with a velocity limit alone checks the velocity and says what it did not check.
    let o = trajkit(&["check", "one_out.csv", "--max-velocity", "0.6"], &d);
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(1), "{out}{}", stderr(&o));
    assert!(out.contains("not checked (no limit given): position range of every joint; acceleration of every joint; jerk of every joint"), "{out}");
    let o = trajkit(&["check", "one_out.csv", "--max-velocity", "1"], &d);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    // No limits at all: exit 2 asking for them.
    assert!(
        one_line_2(&trajkit(&["check", "one_out.csv"], &d), "check").contains("no limits given")
    );
    // `trajkit poly --help`'s example for one joint.
    let o = trajkit(
        &[
            "poly",
            "--from",
            "0",
            "--to",
            "1",
            "--max-velocity",
            "1",
            "--max-acceleration",
            "2",
            "--max-jerk",
            "20",
        ],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let help = stdout(&trajkit(&["poly", "--help"], &d));
    assert!(
        help.contains(
            "trajkit poly --from 0 --to 1 --max-velocity 1 --max-acceleration 2 --max-jerk 20"
        ),
        "{help}"
    );
}

#[test]
fn sizes_are_bounded_not_fatal() {
    let d = scratch("sizes");
    for (file, shift) in [("demo.csv", 0.0), ("demo2.csv", 0.01)] {
        let mut demo = String::from("t,q1\n");
        for k in 0..=100 {
            let x = k as f64 / 100.0;
            demo.push_str(&format!("{x},{}\n", x * x * (3.0 - 2.0 * x) + shift));
        }
        std::fs::write(d.join(file), &demo).unwrap();
    }
    let e = one_line_2(
        &trajkit(&["dmp", "--demo", "demo.csv", "--basis", "1000000"], &d),
        "dmp basis",
    );
    assert!(
        e.contains("basis function count = 1000000 is above the limit of 2000"),
        "{e}"
    );
    let e = one_line_2(
        &trajkit(
            &[
                "kmp",
                "--demo",
                "demo.csv",
                "--demo",
                "demo2.csv",
                "--points",
                "100000",
            ],
            &d,
        ),
        "kmp points",
    );
    assert!(
        e.contains("KMP unknowns") && e.contains("limit of 8192"),
        "{e}"
    );
    let mut big = String::new();
    for k in 0..=10_000 {
        big.push_str(if k % 2 == 0 { "0\n" } else { "0.1\n" });
    }
    std::fs::write(d.join("big.csv"), big).unwrap();
    let e = one_line_2(
        &trajkit(
            &[
                "plan",
                "--waypoints",
                "big.csv",
                "--max-velocity",
                "1",
                "--max-acceleration",
                "1",
                "--max-jerk",
                "10",
                "--position-range",
                "-1:1",
            ],
            &d,
        ),
        "waypoints",
    );
    assert!(
        e.contains("waypoint count = 10001 is above the limit of 10000"),
        "{e}"
    );
    let e = one_line_2(&trajkit(&["plan", "--rate", "1e12"], &d), "rate");
    assert!(e.contains("sample count (duration × rate)"), "{e}");
    let e = one_line_2(&trajkit(&["plan", "--gridpoints", "60000000"], &d), "grid");
    assert!(
        e.contains("gridpoints = 60000000 is above the limit"),
        "{e}"
    );
    assert_eq!(entries(&d), vec!["big.csv", "demo.csv", "demo2.csv"]);
}

#[test]
fn input_is_read_strictly() {
    let d = scratch("strict");
    std::fs::write(d.join("w.json"), r#"{"waypionts": [[0, 1], [0.5, 1.2]]}"#).unwrap();
    let e = one_line_2(
        &trajkit(&["plan", "--waypoints", "w.json", "--limits", "panda"], &d),
        "json",
    );
    assert!(
        e.contains("'waypionts': unknown field (did you mean 'waypoints'?"),
        "{e}"
    );
    std::fs::write(
        d.join("l.yaml"),
        "joints:\n  - name: a\n    velocty: 1\n    acceleration: 2\n",
    )
    .unwrap();
    std::fs::write(d.join("w.csv"), "a\n0\n0.5\n").unwrap();
    let e = one_line_2(
        &trajkit(&["plan", "--waypoints", "w.csv", "--limits", "l.yaml"], &d),
        "yaml",
    );
    assert!(
        e.contains("l.yaml:3 field 'joints[0].velocty': unknown field (did you mean 'velocity'?"),
        "{e}"
    );
    // Primitive inputs outside their domain.
    let mut demo = String::from("t,q1,q2\n");
    for k in 0..=40 {
        let x = k as f64 / 20.0;
        demo.push_str(&format!("{x},{},{}\n", 0.1 * x, 0.2 - 0.05 * x));
    }
    std::fs::write(d.join("d1.csv"), &demo).unwrap();
    std::fs::write(d.join("d2.csv"), demo.replace(",0.2", ",0.25")).unwrap();
    let e = one_line_2(
        &trajkit(&["dmp", "--demo", "d1.csv", "--goal", "1e300,0"], &d),
        "dmp goal",
    );
    assert!(e.contains("goal of joint 1 = 1e300"), "{e}");
    let e = one_line_2(
        &trajkit(
            &[
                "promp",
                "--demo",
                "d1.csv",
                "--demo",
                "d2.csv",
                "--via",
                "99:0.1,0.1",
            ],
            &d,
        ),
        "promp via",
    );
    assert!(e.contains("via point 1 time") && e.contains("= 99"), "{e}");
}

/// Seeded random waypoints on the three presets, every method: `plan` succeeds and `check`
/// with the same limits agrees (exit 0).
#[test]
fn seeded_plans_pass_check_on_three_robots() {
    use trajkit::rng::SplitMix64;
    let d = scratch("seeded");
    for (k, preset) in ["panda", "ur5e", "iiwa14"].iter().enumerate() {
        let l = trajkit::Limits::preset(preset).unwrap();
        let mut rng = SplitMix64::new(77 + k as u64);
        let mut csv = String::new();
        let mut p: Vec<f64> = l
            .joints()
            .iter()
            .map(|j| {
                // Near an end of the range, where paths overshoot.
                if rng.next_f64() < 0.5 {
                    j.position_max - 0.01
                } else {
                    rng.uniform(j.position_min + 0.3, j.position_max - 0.3)
                }
            })
            .collect();
        for _ in 0..4 {
            csv.push_str(
                &p.iter()
                    .map(|x| x.to_string())
                    .collect::<Vec<_>>()
                    .join(","),
            );
            csv.push('\n');
            for (j, q) in p.iter_mut().enumerate() {
                let jl = l.joint(j);
                *q = (*q + rng.uniform(-0.3, 0.3)).clamp(jl.position_min, jl.position_max);
            }
        }
        let file = format!("{preset}.csv");
        std::fs::write(d.join(&file), csv).unwrap();
        for method in [
            &["--method", "toppra"][..],
            &["--method", "ni", "--no-jerk-limit"],
            &["--method", "totg", "--no-jerk-limit"],
            &["--method", "poly"],
        ] {
            let out = format!("{preset}-{}.csv", method[1]);
            let mut args = vec![
                "plan",
                "--waypoints",
                &file,
                "--limits",
                preset,
                "--out",
                &out,
            ];
            args.extend_from_slice(method);
            let o = trajkit(&args, &d);
            assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
            let mut check = vec!["check", out.as_str(), "--limits", preset];
            if method.contains(&"--no-jerk-limit") {
                check.extend(["--max-jerk", "inf"]);
            }
            let o = trajkit(&check, &d);
            assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stdout(&o));
        }
    }
}
