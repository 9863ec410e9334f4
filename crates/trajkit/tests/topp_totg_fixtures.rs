//! trajkit's TOTG against the original TOTG (tesseract-robotics 0.5.1, the MoveIt-derived port
//! of Kunz & Stilman's code) on the seeded Panda suite of `tools/totg_fixtures.py`.
//!
//! The binding gives the original's time stamps at the waypoints only, so its limit compliance
//! cannot be sampled. What decides instead: on the same path (the same blend geometry), no
//! trajectory within the limits is faster than the time-optimal one, and trajkit's duration
//! is within 0.01% above that optimum (`topp_totg.rs` checks it against TOPP-RA). So an
//! original more than 0.1% faster than trajkit must exceed the limits somewhere; everywhere
//! else the durations are compared and reported (agreement within 0.1%, or the original slower:
//! trajkit within the limits and faster). On single straight segments both are the closed
//! form and must agree within 1e-6. Where the original fails, trajkit must succeed. trajkit is
//! checked within the limits (1e-6, pointwise and by finite differences of 1 ms samples) on
//! every problem. Measured (notes/totg.md): of 22 problems the original solves, it agrees on 3,
//! is faster than the optimum on 17 (0.1% to 7%: it exceeds the limits there), slower on 2.

mod topp_common;

use serde_json::Value;
use topp_common::{floats, worst_for};
use trajkit::topp::{plan_totg, TotgOptions};
use trajkit::{Limits, Trajectory};

fn problems() -> Vec<Value> {
    let p = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/totg/totg_panda.json"
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
    v["problems"].as_array().unwrap().clone()
}

#[test]
fn trajkit_matches_or_beats_the_original_totg() {
    let lim = Limits::preset("panda").unwrap();
    let (mut agree, mut faster, mut failed, mut slower) = (0, 0, 0, 0);
    for p in problems() {
        let name = p["name"].as_str().unwrap();
        let w: Vec<f64> = p["waypoints"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(floats)
            .collect();
        let o = TotgOptions {
            max_deviation: p["max_deviation"].as_f64().unwrap(),
            ..Default::default()
        };
        let traj = plan_totg(&w, 7, &lim, &o).unwrap_or_else(|e| panic!("{name}: {e}"));
        let r = worst_for(&traj, &lim);
        for v in [r.velocity, r.acceleration, r.fd_velocity, r.fd_acceleration] {
            assert!(v <= 1.0 + 1e-6, "{name}: ratio {v}");
        }
        let orig = &p["original"];
        let t = traj.duration();
        match (orig["status"].as_str().unwrap(), orig["duration"].as_f64()) {
            ("ok", Some(to)) => {
                let ratio = to / t;
                let reported = orig["waypoint_acceleration_ratio"].as_f64().unwrap_or(0.0);
                eprintln!("{name:20} original {to:.6} trajkit {t:.6} ratio {ratio:.5} (original's waypoint acceleration ratio {reported:.4})");
                if name.starts_with("line") {
                    // One straight segment: both are the closed-form trapezoid/triangle.
                    assert!((ratio - 1.0).abs() < 1e-6, "{name}: {to} vs {t}");
                }
                if ratio < 1.0 - 1e-3 {
                    // Faster than the time-optimal duration allows: the original exceeds the
                    // limits on this problem.
                    faster += 1;
                } else if ratio <= 1.0 + 1e-3 {
                    agree += 1;
                } else {
                    slower += 1;
                }
            }
            (status, _) => {
                eprintln!("{name:20} original {status}, trajkit {t:.6}");
                failed += 1;
            }
        }
    }
    eprintln!("agree within 0.1%: {agree}; original faster than the optimum (exceeds limits): {faster}; original slower: {slower}; original failed: {failed}");
    // The original fails on the uneven problem and the exact reversal; trajkit succeeded there.
    assert!(agree >= 3 && failed >= 2, "{agree} {failed}");
}
