//! End-to-end tests of `trajkit dmp`, `trajkit promp` and `trajkit kmp`.

use std::path::Path;
use std::process::Output;
mod common;
use common::{scratch, trajkit};

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Writes `n` two-joint demonstrations d0.csv.. (201 samples over 1 s).
fn write_demos(d: &Path, n: usize) {
    for m in 0..n {
        let mut s = String::from("t,q1,q2\n");
        for k in 0..=200 {
            let t = k as f64 / 200.0;
            let mj = 10.0 * t.powi(3) - 15.0 * t.powi(4) + 6.0 * t.powi(5);
            let q1 = (0.8 + 0.1 * m as f64) * mj;
            let q2 = 0.3 * (std::f64::consts::PI * t).sin().powi(2) + 0.05 * m as f64 * t;
            s.push_str(&format!("{t},{q1},{q2}\n"));
        }
        std::fs::write(d.join(format!("d{m}.csv")), s).unwrap();
    }
}

fn last_row(path: &Path) -> Vec<f64> {
    let s = std::fs::read_to_string(path).unwrap();
    s.lines()
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect()
}

#[test]
fn dmp_reproduces_and_generalizes() {
    let d = scratch("dmp");
    write_demos(&d, 1);
    let o = trajkit(&["dmp", "--demo", "d0.csv", "--plot", "dmp.svg"], &d);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("reproduction RMS error"));
    assert!(d.join("trajectory.csv").exists() && d.join("dmp.svg").exists());
    let o = trajkit(
        &[
            "dmp",
            "--demo",
            "d0.csv",
            "--goal",
            "1.5,-0.2",
            "--duration",
            "3",
            "-o",
            "g.csv",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", text(&o));
    let r = last_row(&d.join("g.csv"));
    assert!((r[0] - 3.0).abs() < 1e-12);
    assert!(
        (r[1] - 1.5).abs() < 1e-3 && (r[2] + 0.2).abs() < 1e-3,
        "{r:?}"
    );
    let o = trajkit(
        &[
            "dmp",
            "--demo",
            "d0.csv",
            "--scaling",
            "ijspeert",
            "-o",
            "i.json",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", text(&o));
}

#[test]
fn dmp_within_limits() {
    let d = scratch("dmp-within");
    write_demos(&d, 1);
    std::fs::write(
        d.join("lim.yaml"),
        "joints:\n  - position: [-1.5, 1.5]\n    velocity: 2\n    acceleration: 10\n    jerk: 100\n  - position: [-1, 1]\n    velocity: 2\n    acceleration: 10\n    jerk: 100\n",
    )
    .unwrap();
    let o = trajkit(
        &[
            "dmp", "--demo", "d0.csv", "--within", "lim.yaml", "--goal", "1.49,0.2", "-o", "w.csv",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("kept strictly inside"));
    let s = std::fs::read_to_string(d.join("w.csv")).unwrap();
    for l in s.lines().skip(1) {
        let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
        assert!(v[1] < 1.5 && v[1] > -1.5 && v[2].abs() < 1.0, "{l}");
    }
    let o = trajkit(
        &[
            "dmp", "--demo", "d0.csv", "--within", "lim.yaml", "--goal", "2,0",
        ],
        &d,
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
}

#[test]
fn promp_via_point_and_band() {
    let d = scratch("promp");
    write_demos(&d, 3);
    let o = trajkit(
        &[
            "promp",
            "--demo",
            "d0.csv",
            "--demo",
            "d1.csv",
            "--demo",
            "d2.csv",
            "--via",
            "0.5:0.4,0.3",
            "--band",
            "band.csv",
            "--plot",
            "p.svg",
            "--rate",
            "100",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("via point 1 at t = 0.5"));
    let band = std::fs::read_to_string(d.join("band.csv")).unwrap();
    assert!(band.starts_with("t,q1,q1_lo,q1_hi,q2,q2_lo,q2_hi\n"));
    let row: Vec<f64> = band
        .lines()
        .find(|l| l.starts_with("0.5,"))
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(
        (row[1] - 0.4).abs() < 1e-9 && (row[4] - 0.3).abs() < 1e-9,
        "{row:?}"
    );
    assert!(d.join("p.svg").exists());
}

#[test]
fn kmp_via_point() {
    let d = scratch("kmp");
    write_demos(&d, 3);
    let o = trajkit(
        &[
            "kmp",
            "--demo",
            "d0.csv",
            "--demo",
            "d1.csv",
            "--demo",
            "d2.csv",
            "--via",
            "0.5:0.4,0.3",
            "--band",
            "kb.csv",
            "--rate",
            "100",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", text(&o));
    let row: Vec<f64> = std::fs::read_to_string(d.join("trajectory.csv"))
        .unwrap()
        .lines()
        .find(|l| l.starts_with("0.5,"))
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(
        (row[1] - 0.4).abs() < 1e-3 && (row[2] - 0.3).abs() < 1e-3,
        "{row:?}"
    );
}

#[test]
fn bad_input_is_one_line_exit_2_and_leaves_no_file() {
    let d = scratch("bad");
    write_demos(&d, 2);
    std::fs::write(d.join("nan.csv"), "t,q1,q2\n0,0,0\n0.5,NaN,1\n1,1,1\n").unwrap();
    for args in [
        vec!["dmp", "--demo", "missing.csv"],
        vec!["dmp", "--demo", "d0.csv", "--goal", "1"],
        vec!["dmp", "--demo", "d0.csv", "--tau", "-1"],
        vec!["dmp", "--demo", "nan.csv"],
        vec!["promp", "--demo", "d0.csv"],
        vec![
            "promp", "--demo", "d0.csv", "--demo", "d1.csv", "--via", "0.5:1",
        ],
        vec![
            "promp", "--demo", "d0.csv", "--demo", "d1.csv", "--via", "x:1,2",
        ],
        vec!["kmp", "--demo", "d0.csv", "--via-variance", "0"],
    ] {
        let o = trajkit(&args, &d);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(!d.join("trajectory.csv").exists(), "{args:?}");
    }
}
