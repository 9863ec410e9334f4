//! End-to-end tests of `trajkit plan --method totg` and `--method ni`.

use std::process::Output;
mod common;
use common::{entries, scratch, trajkit};

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// The duration printed in the summary line `method: ..., duration: X s, ...`.
fn duration(summary: &str) -> f64 {
    let line = summary
        .lines()
        .find(|l| l.starts_with("method:"))
        .expect("summary line");
    let after = line.split("duration: ").nth(1).unwrap();
    after.split(' ').next().unwrap().parse().unwrap()
}

#[test]
fn totg_and_ni_plans_pass_the_checker() {
    let d = scratch("totg-ok");
    // TOTG cannot bound jerk: with the Panda's jerk limits it refuses, saying how to go on.
    let o = trajkit(&["plan", "--method", "totg", "--out", "totg.csv"], &d);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let err = text(&o);
    assert!(
        err.contains("jerk limit 7500 cannot be held") && err.contains("--no-jerk-limit"),
        "{err}"
    );
    assert!(entries(&d).is_empty());
    let o = trajkit(
        &[
            "plan",
            "--method",
            "totg",
            "--no-jerk-limit",
            "--max-deviation",
            "0.1",
            "--out",
            "totg.csv",
        ],
        &d,
    );
    let out = text(&o);
    assert!(o.status.success(), "{out}");
    assert!(out.contains("within limits"), "{out}");
    assert!(out.contains("only C¹"), "{out}");
    // Velocity and acceleration checked by the independent checker (the blended path's
    // curvature jumps, so jerk is not limited and not checked).
    let o = trajkit(
        &[
            "check",
            "totg.csv",
            "--limits",
            "panda",
            "--max-jerk",
            "inf",
        ],
        &d,
    );
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    // A smaller deviation cuts corners less: slower (at 0.1 most blends of the default path are
    // already bounded by half their segments).
    let o = trajkit(
        &[
            "plan",
            "--method",
            "totg",
            "--no-jerk-limit",
            "--max-deviation",
            "0.02",
            "--out",
            "tight.csv",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", text(&o));
    let (wide, tight) = (duration(&out), duration(&text(&o)));
    assert!(wide < tight, "{wide} vs {tight}");
    // NI on the spline path, jerk bounded like toppra: every Panda limit holds.
    let o = trajkit(&["plan", "--method", "ni", "--out", "ni.csv"], &d);
    let ni = text(&o);
    assert!(o.status.success(), "{ni}");
    assert!(ni.contains("jerk: bounded (NI"), "{ni}");
    let o = trajkit(&["check", "ni.csv", "--limits", "panda"], &d);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    // Raw NI and raw TOPP-RA on the same path agree within 0.1%.
    let o = trajkit(
        &[
            "plan",
            "--method",
            "ni",
            "--no-jerk-limit",
            "--gridpoints",
            "4000",
            "--out",
            "ni-raw.csv",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", text(&o));
    let t_ni = duration(&text(&o));
    let o = trajkit(
        &[
            "plan",
            "--no-jerk-limit",
            "--gridpoints",
            "4000",
            "--out",
            "ra-raw.csv",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", text(&o));
    let t_ra = duration(&text(&o));
    assert!((t_ni / t_ra - 1.0).abs() < 1e-3, "NI {t_ni} TOPP-RA {t_ra}");
}

#[test]
fn bad_max_deviation_exits_2_with_one_line_and_no_output() {
    let d = scratch("totg-bad");
    for (value, needle) in [
        ("NaN", "max deviation = NaN"),
        ("-1", "max deviation = -1"),
        ("0", "max deviation = 0"),
        ("inf", "max deviation = inf"),
    ] {
        let arg = format!("--max-deviation={value}");
        for args in [
            vec!["plan", "--method", "totg", arg.as_str()],
            vec!["plan", "--method", "totg", "--max-deviation", value],
        ] {
            let mut full = args.clone();
            full.extend(["--out", "out.csv", "--plot", "out.svg"]);
            let o = trajkit(&full, &d);
            let err = String::from_utf8_lossy(&o.stderr).to_string();
            assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
            assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
            assert!(err.contains(needle), "{args:?}: {err}");
            assert!(o.stdout.is_empty());
            assert!(entries(&d).is_empty(), "{args:?} left {:?}", entries(&d));
        }
    }
    // Only meaningful with totg.
    let o = trajkit(&["plan", "--max-deviation", "0.1", "--out", "o.csv"], &d);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--method totg"));
    assert!(entries(&d).is_empty());
}
