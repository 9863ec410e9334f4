//! End-to-end tests of `trajkit spline`.

mod common;
use common::{scratch, trajkit};

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).to_string()
}

#[test]
fn every_curve_fits_and_samples() {
    let d = scratch("all");
    std::fs::write(d.join("p.csv"), "x,y\n0,0\n1,2\n0.5,1\n2,0\n3,1\n0,0\n").unwrap();
    for curve in [
        "linear",
        "natural",
        "clamped",
        "not-a-knot",
        "periodic",
        "pchip",
        "akima",
        "makima",
        "catmull-rom-uniform",
        "catmull-rom-centripetal",
        "catmull-rom-chordal",
        "bspline",
        "minimum-jerk",
        "minimum-snap",
    ] {
        let o = trajkit(
            &[
                "spline", "--points", "p.csv", "--curve", curve, "--rate", "10",
            ],
            &d,
        );
        assert!(o.status.success(), "{curve}: {}", text(&o.stderr));
        let out = text(&o.stdout);
        let mut lines = out.lines();
        let header = lines.next().unwrap();
        assert!(
            header.starts_with("t,") && header.split(',').count() == 9,
            "{header}"
        );
        // The first row is the first point.
        let first: Vec<f64> = lines
            .next()
            .unwrap()
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        assert!(
            first[1].abs() < 1e-12 && first[2].abs() < 1e-12,
            "{curve}: {first:?}"
        );
    }
}

#[test]
fn minimum_jerk_through_timed_points_with_plot_and_json() {
    let d = scratch("mj");
    std::fs::write(d.join("p.csv"), "0,0\n1,2\n0.5,1\n2,0\n").unwrap();
    let o = trajkit(
        &[
            "spline",
            "--points",
            "p.csv",
            "--curve",
            "minimum-jerk",
            "--times",
            "0,0.5,2,3",
            "--rate",
            "100",
            "--out",
            "s.json",
            "--plot",
            "s.svg",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("s.json")).unwrap()).unwrap();
    let q = v["q"].as_array().unwrap();
    assert_eq!(q.len(), 301);
    // Passes through the point at t = 2 (row 200) and ends at rest.
    assert!((q[200][0].as_f64().unwrap() - 0.5).abs() < 1e-12);
    let qd = v["qd"].as_array().unwrap();
    assert!(qd[300][1].as_f64().unwrap().abs() < 1e-12);
    assert!(std::fs::read_to_string(d.join("s.svg"))
        .unwrap()
        .starts_with("<svg"));
}

#[test]
fn bad_input_exits_2_with_one_line() {
    let d = scratch("bad");
    std::fs::write(d.join("p.csv"), "0,0\n1,2\n0.5,1\n").unwrap();
    std::fs::write(d.join("dup.csv"), "0,0\n1,2\n1,2\n").unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &["spline", "--points", "p.csv", "--curve", "periodic"],
            "differs from the first point",
        ),
        (
            &["spline", "--points", "p.csv", "--times", "0,1"],
            "--times has 2 values",
        ),
        (
            &["spline", "--points", "p.csv", "--times", "0,2,1"],
            "does not increase",
        ),
        (
            &[
                "spline", "--points", "p.csv", "--curve", "bspline", "--degree", "5",
            ],
            "waypoints needed",
        ),
        (
            &[
                "spline",
                "--points",
                "dup.csv",
                "--curve",
                "catmull-rom-chordal",
            ],
            "repeats",
        ),
        (
            &[
                "spline",
                "--points",
                "p.csv",
                "--curve",
                "catmull-rom-uniform",
                "--duration",
                "2",
            ],
            "do not apply",
        ),
        (
            &["spline", "--points", "p.csv", "--start-velocity", "1,2,3"],
            "3 values",
        ),
        (&["spline", "--points", "missing.csv"], "missing.csv"),
    ];
    for (args, want) in cases {
        let o = trajkit(args, &d);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let e = text(&o.stderr);
        assert_eq!(e.trim_end().lines().count(), 1, "{args:?}: {e}");
        assert!(e.contains(want), "{args:?}: {e}");
    }
}
