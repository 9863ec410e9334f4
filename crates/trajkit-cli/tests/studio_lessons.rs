//! Tests of `trajkit studio`'s lesson endpoints against the running binary: every lesson with
//! valid input (values checked against analytic results and the library) and invalid input
//! (4xx naming the field).

mod studio_common;

use serde_json::{json, Value};
use studio_common::{post, refused, Studio};

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[test]
fn polynomials_peaks_boundaries_and_limits() {
    let s = Studio::start(&[]);
    let r = post(
        s.addr,
        "/api/polynomials",
        &json!({"limits": {"velocity": 2.175, "acceleration": 15, "jerk": 7500}}),
    );
    assert_eq!(r.status, 200);
    let j = r.json();
    let expected = [
        ("cubic", [1.5, 6.0, 12.0], [true, false, false]),
        ("quintic", [1.875, 5.7735, 60.0], [true, true, false]),
        ("septic", [2.1875, 7.5132, 52.5], [true, true, true]),
    ];
    for (p, (name, peaks, zero)) in j["profiles"].as_array().unwrap().iter().zip(expected) {
        assert_eq!(p["degree"], name);
        for k in 0..3 {
            let c = f(&p["peak_coefficients"][k]);
            assert!((c - peaks[k]).abs() < 5e-5, "{name} {k}: {c}");
            // Δq = 1, T = 1: the move's peaks are the coefficients.
            assert!((f(&p["peaks"][k]) - c).abs() < 1e-9 * c);
            assert_eq!(p["zero_at_ends"][k], zero[k], "{name} {k}");
        }
        // Panda joint 1 (q̇max 2.175): only the septic's 2.1875 exceeds it.
        let exceeds = p["exceeds"].as_array().unwrap();
        assert_eq!(exceeds.len(), usize::from(name == "septic"), "{name}");
        // The shortest duration within the limits puts the peak velocity exactly on the limit.
        let tmin = f(&p["min_duration"]);
        assert!((peaks[0] / tmin - 2.175).abs() < 1e-3 || name == "cubic" && tmin > 0.0);
        let q = &p["samples"]["q"][0];
        assert_eq!(f(&q[0]), 0.0);
        assert!((f(&q[200]) - 1.0).abs() < 1e-12);
    }
    // Scaling: Δq = 5 in T = 0.5 s needs q̇ = 5/0.5·1.5 = 15 with the cubic.
    let j = post(
        s.addr,
        "/api/polynomials",
        &json!({"delta_q": 5, "duration": 0.5}),
    )
    .json();
    assert!((f(&j["profiles"][0]["peaks"][0]) - 15.0).abs() < 1e-9);
    refused(
        &post(s.addr, "/api/polynomials", &json!({"duration": 0})),
        400,
        "duration",
        "duration = 0",
    );
    refused(
        &post(s.addr, "/api/polynomials", &json!({"samples": 1000000})),
        400,
        "samples",
        "exceeds the cap of 5000",
    );
    refused(
        &post(
            s.addr,
            "/api/polynomials",
            &json!({"limits": {"velocity": -1, "acceleration": 1, "jerk": 1}}),
        ),
        400,
        "limits.velocity",
        "-1",
    );
    refused(
        &post(
            s.addr,
            "/api/polynomials",
            &json!({"limits": {"velocity": 1, "acceleration": 1}}),
        ),
        400,
        "limits",
        "missing field `jerk`",
    );
}

#[test]
fn catmull_rom_interpolates_in_three_variants() {
    let s = Studio::start(&[]);
    let pts = json!([[1, 1], [2.6, 4.6], [4.4, 4.2], [6.2, 1.4], [8.8, 3.6]]);
    let j = post(
        s.addr,
        "/api/catmull-rom",
        &json!({"points": pts, "samples_per_segment": 10}),
    )
    .json();
    let curves = j["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 3);
    for (c, alpha) in curves.iter().zip([0.0, 0.5, 1.0]) {
        assert_eq!(f(&c["alpha"]), alpha);
        let curve = c["points"].as_array().unwrap();
        assert_eq!(curve.len(), 4 * 10 + 1);
        // Interpolating: the curve passes through every point, at its knot parameter.
        for i in 0..5 {
            for d in 0..2 {
                let got = f(&curve[i * 10][d]);
                assert!((got - f(&pts[i][d])).abs() < 1e-12, "{} {i}", c["kind"]);
            }
            assert_eq!(f(&c["s"][i * 10]), f(&c["parameters"][i]));
        }
    }
    // Uniform knots are 0, 1, 2, ...
    assert_eq!(curves[0]["parameters"], json!([0.0, 1.0, 2.0, 3.0, 4.0]));
    refused(
        &post(s.addr, "/api/catmull-rom", &json!({"points": [[0, 0]]})),
        400,
        "points (row count)",
        "below 2",
    );
    refused(
        &post(
            s.addr,
            "/api/catmull-rom",
            &json!({"points": [[0, 0], [1, 1], [1, 1]], "kinds": ["centripetal"]}),
        ),
        400,
        "points",
        "Centripetal",
    );
    refused(
        &post(
            s.addr,
            "/api/catmull-rom",
            &json!({"points": [[0, 0], [1, 1]], "kinds": ["bogus"]}),
        ),
        400,
        "kinds[0]",
        "unknown variant `bogus`",
    );
    let many: Vec<[f64; 2]> = (0..65).map(|i| [i as f64, 0.0]).collect();
    refused(
        &post(s.addr, "/api/catmull-rom", &json!({ "points": many })),
        400,
        "points (row count)",
        "cap of 64",
    );
    refused(
        &post(
            s.addr,
            "/api/catmull-rom",
            &json!({"points": [[0, 0], [1]]}),
        ),
        400,
        "points[1] (length)",
        "differs",
    );
}

#[test]
fn bspline_local_control_weights_and_partition_of_unity() {
    let s = Studio::start(&[]);
    let mut pts = vec![
        [0.8, 1.0],
        [1.8, 4.8],
        [3.4, 5.2],
        [4.6, 1.4],
        [6.2, 1.2],
        [7.6, 4.8],
        [9.2, 3.2],
    ];
    let ask = |pts: &Vec<[f64; 2]>, extra: Value| {
        let mut body =
            json!({"control_points": pts, "degree": 3, "compare_degree": 2, "samples": 101});
        for (k, v) in extra.as_object().unwrap() {
            body[k] = v.clone();
        }
        let r = post(s.addr, "/api/bspline", &body);
        assert_eq!(r.status, 200, "{:?}", r.error());
        r.json()
    };
    let a = ask(&pts, json!({}));
    assert_eq!(
        a["knots"],
        json!([0.0, 0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0])
    );
    // Clamped: the curve starts and ends at the end control points.
    assert_eq!(a["curve"][0], json!(pts[0]));
    assert_eq!(a["curve"][100], json!(pts[6]));
    // Partition of unity.
    for v in a["basis"]["sum"].as_array().unwrap() {
        assert!((f(v) - 1.0).abs() < 1e-14);
    }
    assert_eq!(a["support"][0], json!([0.0, 0.25]));
    assert_eq!(a["support"][3], json!([0.0, 1.0]));
    assert_eq!(a["comparison"]["degree"], 2);
    // Local control: moving P0 changes the curve on u < 0.25 only (samples 0..25 of 101).
    pts[0] = [2.0, 0.2];
    let b = ask(&pts, json!({}));
    let (ca, cb) = (
        a["curve"].as_array().unwrap(),
        b["curve"].as_array().unwrap(),
    );
    assert!((0..25).any(|m| ca[m] != cb[m]));
    assert_eq!(&ca[25..], &cb[25..]);
    // NURBS: weight 5 on P3 pulls the curve towards it.
    let closest = |c: &Value| {
        c.as_array()
            .unwrap()
            .iter()
            .map(|p| (f(&p[0]) - 4.6).hypot(f(&p[1]) - 1.4))
            .fold(f64::INFINITY, f64::min)
    };
    let w1 = ask(&pts, json!({"weights": [1, 1, 1, 1, 1, 1, 1]}));
    let w5 = ask(&pts, json!({"weights": [1, 1, 1, 5, 1, 1, 1]}));
    // Equal weights: the B-spline (to rounding).
    for (p, q) in w1["curve"]
        .as_array()
        .unwrap()
        .iter()
        .zip(b["curve"].as_array().unwrap())
    {
        assert!((f(&p[0]) - f(&q[0])).abs() < 1e-12 && (f(&p[1]) - f(&q[1])).abs() < 1e-12);
    }
    assert!(closest(&w5["curve"]) < 0.5 * closest(&w1["curve"]));
    assert_eq!(w5["rational"], true);
    for v in w5["basis"]["sum"].as_array().unwrap() {
        assert!((f(v) - 1.0).abs() < 1e-14);
    }
    refused(
        &post(
            s.addr,
            "/api/bspline",
            &json!({"control_points": pts, "degree": 7}),
        ),
        400,
        "degree",
        "needs at least 8 control points",
    );
    refused(
        &post(
            s.addr,
            "/api/bspline",
            &json!({"control_points": pts, "degree": 11}),
        ),
        400,
        "degree",
        "cap of 10",
    );
    refused(
        &post(
            s.addr,
            "/api/bspline",
            &json!({"control_points": pts, "weights": [1, 1, -2, 1, 1, 1, 1]}),
        ),
        400,
        "weights[2]",
        "-2",
    );
    refused(
        &post(
            s.addr,
            "/api/bspline",
            &json!({"control_points": pts, "weights": [1, 1]}),
        ),
        400,
        "weights (count)",
        "7 control points",
    );
}

#[test]
fn profiles_match_the_specification() {
    let s = Studio::start(&[]);
    let j = post(s.addr, "/api/profiles", &json!({})).json();
    let trap = f(&j["trapezoid"]["duration"]);
    let scurve = f(&j["s_curve"]["duration"]);
    // D/v + v/a, and + a/j for the S-curve (every limit reached).
    assert!((trap - (1.0 / 0.6 + 0.6)).abs() < 1e-9, "{trap}");
    assert!((scurve - (1.0 / 0.6 + 0.6 + 0.25)).abs() < 1e-9, "{scurve}");
    assert_eq!(format!("{trap:.3} {scurve:.3}"), "2.267 2.517");
    assert_eq!(j["trapezoid"]["phases"].as_array().unwrap().len(), 3);
    assert_eq!(j["s_curve"]["phases"].as_array().unwrap().len(), 7);
    // The trapezoid's acceleration jumps between phases (its jerk is impulses).
    let ph = &j["trapezoid"]["phases"];
    assert_eq!(f(&ph[0]["end"][2]), 1.0);
    assert_eq!(f(&ph[1]["start"][2]), 0.0);
    let last = j["s_curve"]["samples"]["q"][0].as_array().unwrap();
    assert!((f(last.last().unwrap()) - 1.0).abs() < 1e-8);
    for (field, body) in [
        ("v_max", json!({"v_max": 0})),
        ("a_max", json!({"a_max": -1})),
        ("j_max", json!({"j_max": 1e300})),
        ("distance", json!({"distance": 1e7})),
    ] {
        refused(&post(s.addr, "/api/profiles", &body), 400, field, field);
    }
}

#[test]
fn primitives_dmp_goal_and_promp_via_point() {
    let s = Studio::start(&[]);
    let t: Vec<f64> = (0..=50).map(|k| k as f64 / 50.0).collect();
    let q: Vec<[f64; 2]> = t
        .iter()
        .map(|&s| [s * s * (3.0 - 2.0 * s), (3.0 * s).sin()])
        .collect();
    let demo = json!({"t": t, "q": q});
    let j = post(
        s.addr,
        "/api/dmp",
        &json!({"demo": demo, "goal": [2.0, 0.5]}),
    )
    .json();
    let end = j["rollout"]["q"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .clone();
    // The phase reaches 0.01 at t = τ: the rollout is within a few % of the new goal's offset.
    assert!(
        (f(&end[0]) - 2.0).abs() < 0.05 && (f(&end[1]) - 0.5).abs() < 0.05,
        "{end}"
    );
    let rep = j["reproduction"]["q"].as_array().unwrap();
    for (k, row) in rep.iter().enumerate().step_by(20) {
        let tk = f(&j["reproduction"]["t"][k]);
        let want = [tk * tk * (3.0 - 2.0 * tk), (3.0 * tk).sin()];
        assert!((f(&row[0]) - want[0]).abs() < 0.02 && (f(&row[1]) - want[1]).abs() < 0.02);
    }
    refused(
        &post(
            s.addr,
            "/api/dmp",
            &json!({"demo": {"t": [0, 1], "q": [[0], [1]]}}),
        ),
        400,
        "demo.t (count)",
        "below 3",
    );
    refused(
        &post(s.addr, "/api/dmp", &json!({"demo": demo, "goal": [1]})),
        400,
        "goal (length)",
        "2 joints",
    );
    refused(
        &post(
            s.addr,
            "/api/dmp",
            &json!({"demo": {"t": [0, 1, 1], "q": [[0], [1], [2]]}}),
        ),
        400,
        "demo",
        "does not increase",
    );
    // ProMP: three demonstrations, conditioned exactly through a via point.
    let demos: Vec<Value> = [0.9, 1.0, 1.1]
        .iter()
        .map(|a| json!({"t": t, "q": t.iter().map(|&s| [a * (3.0 * s).sin()]).collect::<Vec<_>>()}))
        .collect();
    let j = post(
        s.addr,
        "/api/promp",
        &json!({"demos": demos, "via": [{"t": 0.5, "q": [1.5], "variance": 0}], "samples": 101}),
    )
    .json();
    assert!((f(&j["posterior"]["mean"][0][50]) - 1.5).abs() < 1e-6);
    assert!(f(&j["posterior"]["std"][0][50]) < 1e-3);
    assert!(f(&j["prior"]["std"][0][50]) > 0.01);
    let band = |b: &Value, k: usize| f(&b["upper"][0][k]) - f(&b["lower"][0][k]);
    assert!((band(&j["prior"], 30) - 4.0 * f(&j["prior"]["std"][0][30])).abs() < 1e-12);
    refused(
        &post(s.addr, "/api/promp", &json!({"demos": [demos[0]]})),
        400,
        "demos (count)",
        "below 2",
    );
    refused(
        &post(
            s.addr,
            "/api/promp",
            &json!({"demos": demos, "via": [{"t": 5, "q": [1]}]}),
        ),
        400,
        "via[0].t",
        "outside",
    );
}
