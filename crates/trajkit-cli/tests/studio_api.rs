//! Tests of `trajkit studio`'s HTTP API against the running binary: every endpoint with valid
//! input (values checked against analytic results, the CLI or the library's own guarantees),
//! invalid input (4xx naming the field), caps, the worker pool and the embedded page.

mod studio_common;

use serde_json::{json, Value};
use std::time::{Duration, Instant};
use studio_common::{default_waypoints_csv, get, post, request, Studio};

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// Asserts a 4xx refusal naming `field` (a prefix of the field reported) and mentioning
/// `needle` in its message.
fn refused(r: &studio_common::Response, status: u16, field: &str, needle: &str) {
    assert_eq!(
        r.status,
        status,
        "{}",
        String::from_utf8_lossy(&r.body[..r.body.len().min(400)])
    );
    let (message, got) = r.error();
    let got = got.unwrap_or_default();
    assert!(
        got.starts_with(field),
        "field {got:?}, wanted {field:?} ({message})"
    );
    assert!(message.contains(needle), "{message:?} lacks {needle:?}");
}

#[test]
fn page_and_assets_are_embedded() {
    let s = Studio::start(&[]);
    let r = get(s.addr, "/");
    assert_eq!(r.status, 200);
    assert!(r.header("content-type").unwrap().starts_with("text/html"));
    let csp = r.header("content-security-policy").unwrap();
    assert!(csp.contains("default-src 'self'"), "{csp}");
    let html = String::from_utf8_lossy(&r.body);
    assert!(html.contains("/assets/js/main.js") && !html.contains("http"));
    for lesson in [
        "polynomials",
        "catmull_rom",
        "bspline",
        "profiles",
        "plan",
        "primitives",
    ] {
        let r = get(s.addr, &format!("/assets/lessons/{lesson}.js"));
        assert_eq!(r.status, 200, "{lesson}");
        assert!(r
            .header("content-type")
            .unwrap()
            .starts_with("text/javascript"));
        // Offline: no lesson loads anything from another host.
        let js = String::from_utf8_lossy(&r.body);
        assert!(
            !js.contains("http://") && !js.contains("https://"),
            "{lesson}"
        );
    }
    assert_eq!(get(s.addr, "/assets/nope.js").status, 404);
    assert_eq!(get(s.addr, "/assets/../Cargo.toml").status, 404);
    let index = get(s.addr, "/api").json();
    assert_eq!(index["endpoints"].as_array().unwrap().len(), 10);
    assert_eq!(get(s.addr, "/api/health").json()["status"], "ok");
}

#[test]
fn protocol_errors_are_json_and_name_the_problem() {
    let s = Studio::start(&[]);
    refused(&get(s.addr, "/api/nothing"), 404, "path", "/api/nothing");
    let r = get(s.addr, "/api/plan");
    assert_eq!(r.status, 405);
    assert!(r.error().0.contains("GET is not allowed on /api/plan"));
    // Not JSON.
    let r = request(s.addr, "POST", "/api/profiles", &[], b"{}").unwrap();
    assert_eq!(r.status, 415);
    // Too large: 2 MiB + 1.
    let big = vec![b' '; (2 << 20) + 1];
    let r = request(
        s.addr,
        "POST",
        "/api/profiles",
        &[("Content-Type", "application/json")],
        &big,
    )
    .unwrap();
    assert_eq!(r.status, 413);
    assert!(r.error().0.contains("2097152"), "{:?}", r.error());
    // Malformed JSON, wrong types, unknown fields: 400 with the JSON path.
    let r = request(
        s.addr,
        "POST",
        "/api/profiles",
        &[("Content-Type", "application/json")],
        b"{\"v_max\": 0.6,",
    )
    .unwrap();
    assert_eq!(r.status, 400);
    refused(
        &post(s.addr, "/api/profiles", &json!({"v_max": "fast"})),
        400,
        "v_max",
        "invalid type: string \"fast\"",
    );
    refused(
        &post(s.addr, "/api/profiles", &json!({"vmax": 1})),
        400,
        "vmax",
        "unknown field `vmax`",
    );
    refused(
        &post(
            s.addr,
            "/api/plan",
            &json!({"limits": {"preset": "panda", "velocty_scale": 2}}),
        ),
        400,
        "limits.velocty_scale",
        "unknown field",
    );
    // DNS rebinding: a foreign Host header is refused.
    let r = request(
        s.addr,
        "GET",
        "/api/health",
        &[("Host", "evil.example:80")],
        b"",
    )
    .unwrap();
    refused(&r, 403, "", "evil.example:80");
    let r = request(s.addr, "GET", "/api/health", &[("Host", "localhost")], b"").unwrap();
    assert_eq!(r.status, 403);
    let port = s.addr.port().to_string();
    let local = format!("localhost:{port}");
    let r = request(s.addr, "GET", "/api/health", &[("Host", &local)], b"").unwrap();
    assert_eq!(r.status, 200);
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

fn default_plan(extra: Value) -> Value {
    let mut body = json!({
        "waypoints_file": {"name": "default.csv", "text": default_waypoints_csv()},
        "limits": {"preset": "panda"},
    });
    for (k, v) in extra.as_object().unwrap() {
        body[k] = v.clone();
    }
    body
}

/// The duration `trajkit plan` prints for `args` (6 decimals).
fn cli_duration(args: &[&str]) -> f64 {
    let d = std::env::temp_dir().join(format!("trajkit-studio-api-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_trajkit"))
        .args(["plan", "--out", "-"])
        .args(args)
        .current_dir(&d)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stderr);
    let line = text
        .lines()
        .find(|l| l.contains("duration:"))
        .unwrap_or_else(|| panic!("{text}"));
    line.split("duration: ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn plan_matches_the_cli_and_checks_its_output() {
    let s = Studio::start(&[]);
    for (method, args) in [
        ("toppra", vec![]),
        ("totg", vec!["--method", "totg", "--no-jerk-limit"]),
        ("poly", vec!["--method", "poly"]),
    ] {
        let r = post(
            s.addr,
            "/api/plan",
            &default_plan(json!({ "method": method })),
        );
        assert_eq!(r.status, 200, "{method}: {:?}", r.error());
        let j = r.json();
        let d = f(&j["duration"]);
        assert!((d - cli_duration(&args)).abs() < 1e-6, "{method}: {d}");
        assert!(f(&j["check"]["worst"]) <= 1.0 + 1e-6, "{method}");
        assert_eq!(j["joint_names"][0], "panda_joint1");
        assert_eq!(j["samples"]["q"].as_array().unwrap().len(), 7);
        assert_eq!(j["limits"][0]["velocity"], json!([-2.175, 2.175]));
        match method {
            "poly" => assert!(j["phase_plane"].is_null()),
            _ => {
                for p in j["phase_plane"]["pieces"].as_array().unwrap() {
                    let (mvc, solver) = (
                        p["mvc"].as_array().unwrap(),
                        p["solver"].as_array().unwrap(),
                    );
                    for (m, v) in mvc.iter().zip(solver) {
                        // The profile never rises above the maximum velocity curve.
                        assert!(m.is_null() || f(v) <= f(m) * (1.0 + 1e-6), "{method}");
                    }
                    assert_eq!(p["played"].is_null(), method == "totg");
                }
            }
        }
    }
    // The table as the CLI writes it.
    let r = post(
        s.addr,
        "/api/plan?format=csv",
        &default_plan(json!({"rate": 1000})),
    );
    assert_eq!(r.status, 200);
    assert_eq!(r.header("content-type"), Some("text/csv"));
    assert!(r
        .header("content-disposition")
        .unwrap()
        .contains("trajectory.csv"));
    let text = String::from_utf8_lossy(&r.body);
    assert!(
        text.starts_with("t,q_panda_joint1,q_panda_joint2,"),
        "{}",
        &text[..80]
    );
    // A header, then samples at every millisecond up to the duration and at the end.
    let d = f(&post(s.addr, "/api/plan", &default_plan(json!({}))).json()["duration"]);
    assert_eq!(
        text.lines().count(),
        1 + (d * 1000.0 + 1e-9).floor() as usize + 2
    );
    let r = post(
        s.addr,
        "/api/plan?format=json",
        &default_plan(json!({"rate": 10})),
    );
    assert_eq!(r.json()["dof"], 7);
    refused(
        &post(s.addr, "/api/plan?format=xml", &default_plan(json!({}))),
        400,
        "format",
        "unknown variant",
    );
}

#[test]
fn plan_limits_from_files_and_missing_limits() {
    let s = Studio::start(&[]);
    let urdf = r#"<robot name="two"><link name="a"/><link name="b"/><link name="c"/>
      <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
        <limit lower="-2" upper="2" velocity="1.5" effort="10"/></joint>
      <joint name="j2" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 1 0"/>
        <limit lower="-2" upper="2" velocity="1.0" effort="10"/></joint></robot>"#;
    let wp = json!([[0, 0], [0.5, 0.3], [1.0, -0.2]]);
    // URDF has no acceleration limits: refused, naming what is missing and how to supply it.
    let r = post(
        s.addr,
        "/api/plan",
        &json!({"waypoints": wp, "limits": {"file": {"name": "two.urdf", "text": urdf}}}),
    );
    refused(&r, 400, "limits (joint 1 j1 acceleration)", "fill_from");
    // Completed by explicit values: plans.
    let body = json!({"waypoints": wp, "limits": {"file": {"name": "two.urdf", "text": urdf},
        "max_acceleration": [3, 2], "max_jerk": [30, 20]}});
    let r = post(s.addr, "/api/plan", &body);
    assert_eq!(r.status, 200, "{:?}", r.error());
    // Unnamed waypoint columns take the names of the limits' joints.
    assert_eq!(r.json()["joint_names"], json!(["j1", "j2"]));
    assert_eq!(r.json()["limits"][1]["velocity"], json!([-1.0, 1.0]));
    // Without jerk limits, the jerk stage refuses; raw TOPP-RA does not need them.
    let mut raw = json!({"waypoints": wp, "limits": {"file": {"name": "two.urdf", "text": urdf},
        "max_acceleration": [3, 2]}});
    refused(
        &post(s.addr, "/api/plan", &raw),
        400,
        "limits (joint 1 j1 jerk)",
        "jerk_limit false",
    );
    raw["jerk_limit"] = json!(false);
    let r = post(s.addr, "/api/plan", &raw);
    assert_eq!(r.status, 200, "{:?}", r.error());
    assert!(r.json()["notes"][0]
        .as_str()
        .unwrap()
        .contains("not bounded"));
    // MoveIt joint_limits.yaml, recognized by its top-level key.
    let moveit = "joint_limits:\n  a:\n    has_velocity_limits: true\n    max_velocity: 1.0\n    has_acceleration_limits: true\n    max_acceleration: 2.0\n    has_jerk_limits: true\n    max_jerk: 20\n";
    // A MoveIt file alone has no position ranges: refused, then given explicitly.
    let r = post(
        s.addr,
        "/api/plan",
        &json!({"waypoints": [[0], [1]], "limits": {"file": {"name": "joint_limits.yaml", "text": moveit}}}),
    );
    refused(&r, 400, "limits (joint 1 a position range)", "position");
    let r = post(
        s.addr,
        "/api/plan",
        &json!({"waypoints": [[0], [1]], "limits": {"file": {"name": "joint_limits.yaml", "text": moveit},
            "position_range": [[-2, 2]]}}),
    );
    assert_eq!(r.status, 200, "{:?}", r.error());
    // trajkit JSON limits.
    let lj = r#"{"joints": [{"position": [-2, 2], "velocity": 1, "acceleration": 2, "jerk": 10}]}"#;
    let r = post(
        s.addr,
        "/api/plan",
        &json!({"waypoints": [[0], [1]], "limits": {"file": {"name": "l.json", "text": lj}}, "method": "poly"}),
    );
    assert_eq!(r.status, 200, "{:?}", r.error());
    // Errors in files name the file and the field.
    let r = post(
        s.addr,
        "/api/plan",
        &json!({"waypoints": [[0], [1]], "limits": {"file": {"name": "l.json", "text": r#"{"joints": [{"velocity": -1}]}"#}}}),
    );
    refused(&r, 400, "limits.file", "l.json");
    refused(
        &post(
            s.addr,
            "/api/plan",
            &json!({"waypoints": [[0], [1]], "limits": {"file": {"name": "l.txt", "text": "x"}}}),
        ),
        400,
        "limits.file.name",
        "l.txt",
    );
    refused(
        &post(
            s.addr,
            "/api/plan",
            &json!({"waypoints": [[0], [1]], "limits": {"preset": "r2d2"}}),
        ),
        400,
        "limits.preset",
        "r2d2",
    );
    refused(
        &post(
            s.addr,
            "/api/plan",
            &json!({"waypoints": [[0], [1]], "limits": {}}),
        ),
        400,
        "limits",
        "exactly one of",
    );
}

#[test]
fn plan_refuses_bad_waypoints_and_caps() {
    let s = Studio::start(&[]);
    let panda = json!({"preset": "panda"});
    let zero = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];
    refused(
        &post(
            s.addr,
            "/api/plan",
            &json!({"waypoints": [zero, zero], "limits": panda}),
        ),
        400,
        "waypoints",
        "2 waypoints needed, found 1",
    );
    let mut far = zero;
    far[0] = 3.5;
    refused(
        &post(
            s.addr,
            "/api/plan",
            &json!({"waypoints": [zero, far], "limits": panda}),
        ),
        400,
        "waypoints",
        "outside the position range",
    );
    refused(
        &post(
            s.addr,
            "/api/plan",
            &json!({"waypoints": [[0, 1], [1, 1]], "limits": panda}),
        ),
        400,
        "limits",
        "expected 2, found 7",
    );
    let many: Vec<[f64; 7]> = (0..1001)
        .map(|k| {
            let mut w = zero;
            w[0] = k as f64 * 1e-3;
            w
        })
        .collect();
    refused(
        &post(
            s.addr,
            "/api/plan",
            &json!({"waypoints": many, "limits": panda}),
        ),
        400,
        "waypoints (row count)",
        "cap of 1000",
    );
    refused(
        &post(
            s.addr,
            "/api/plan",
            &default_plan(json!({"gridpoints": 20001})),
        ),
        400,
        "gridpoints",
        "cap of 20000",
    );
    refused(
        &post(s.addr, "/api/plan", &default_plan(json!({"gridpoints": 0}))),
        400,
        "gridpoints",
        "below 1",
    );
    refused(
        &post(
            s.addr,
            "/api/plan",
            &default_plan(json!({"gridpoints": "fine"})),
        ),
        400,
        "gridpoints",
        "auto",
    );
    refused(
        &post(s.addr, "/api/plan", &default_plan(json!({"rate": 20000}))),
        400,
        "rate",
        "10000 Hz",
    );
    // 10 kHz on a trajectory slowed down 20× (~27 s) is more samples than the cap.
    refused(
        &post(
            s.addr,
            "/api/plan",
            &default_plan(
                json!({"rate": 10000, "limits": {"preset": "panda", "velocity_scale": 0.05, "acceleration_scale": 0.05}}),
            ),
        ),
        400,
        "rate",
        "cap",
    );
    refused(
        &post(
            s.addr,
            "/api/plan",
            &default_plan(json!({"max_deviation": 0.1})),
        ),
        400,
        "max_deviation",
        "only with method totg",
    );
    refused(
        &post(
            s.addr,
            "/api/plan",
            &default_plan(json!({"method": "magic"})),
        ),
        400,
        "method",
        "unknown variant `magic`",
    );
    let bad_csv = default_plan(json!({"waypoints_file": {"name": "w.csv", "text": "1,2\n3,x\n"}}));
    refused(
        &post(s.addr, "/api/plan", &bad_csv),
        400,
        "waypoints_file",
        "w.csv:2",
    );
}

#[test]
fn otg_answers_exactly_what_the_cli_writes() {
    let s = Studio::start(&[]);
    let problems = [
        json!({"current_position": [0], "target_position": [1], "max_velocity": [0.6], "max_acceleration": [1], "max_jerk": [4], "dt": 0.01}),
        json!({"current_position": [0, 1, -0.5], "current_velocity": [0.3, 0, 0.1], "target_position": [1, -0.5, 0.2],
               "target_velocity": [0.2, 0, 0], "max_velocity": [1, 1, 2], "max_acceleration": [2, 2, "inf"],
               "max_jerk": [10, "inf", 5], "synchronization": "phase", "dt": 0.02}),
        json!({"current_position": [0.5], "current_velocity": [3], "target_position": [0], "max_velocity": [1],
               "max_acceleration": [2], "max_jerk": [20], "min_velocity": [-0.5], "minimum_duration": 3, "dt": 0.05}),
    ];
    let d = std::env::temp_dir();
    for p in &problems {
        let r = post(s.addr, "/api/otg", p);
        assert_eq!(r.status, 200, "{:?}", r.error());
        let o = studio_common_cli_otg(p, &d);
        assert_eq!(r.json(), o, "{p}");
    }
    refused(
        &post(
            s.addr,
            "/api/otg",
            &json!({"current_position": [0], "target_position": [1], "max_velocityy": [1]}),
        ),
        400,
        "max_velocityy",
        "did you mean 'max_velocity'",
    );
    refused(
        &post(
            s.addr,
            "/api/otg",
            &json!({"current_position": [0], "target_position": [1, 2]}),
        ),
        400,
        "target_position",
        "has 2 values, current_position has 1",
    );
    refused(
        &post(
            s.addr,
            "/api/otg",
            &json!({"current_position": [0], "target_position": [1], "synchronization": "sometimes"}),
        ),
        400,
        "synchronization",
        "is not one of",
    );
    let r = post(
        s.addr,
        "/api/otg",
        &json!({"current_position": [0], "target_position": [1], "max_velocity": [-1],
                "max_acceleration": [1], "max_jerk": [1]}),
    );
    assert_eq!(r.status, 400);
    assert!(r.error().0.contains("max_velocity"), "{:?}", r.error());
    // A missing limit is refused, never read as unlimited.
    refused(
        &post(
            s.addr,
            "/api/otg",
            &json!({"current_position": [0], "target_position": [1], "max_velocity": [1]}),
        ),
        400,
        "max_acceleration",
        "is required",
    );
    refused(
        &post(
            s.addr,
            "/api/otg",
            &json!({"current_position": [0], "target_position": [1000], "max_velocity": [1], "max_acceleration": [1], "max_jerk": [1], "dt": 0.0001}),
        ),
        400,
        "dt",
        "cap",
    );
}

/// `trajkit otg -` on `problem`, its JSON output.
fn studio_common_cli_otg(problem: &Value, dir: &std::path::Path) -> Value {
    use std::io::Write;
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_trajkit"))
        .args(["otg", "-"])
        .current_dir(dir)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(problem.to_string().as_bytes())
        .unwrap();
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
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

#[test]
fn a_slow_request_does_not_block_the_others_and_a_full_pool_answers_503() {
    // One worker per class; a request waits at most 0.2 s for one.
    let s = Studio::start(&["--workers", "1", "--queue-timeout", "0.2"]);
    let addr = s.addr;
    // A 300-waypoint Panda path on the automatic grid: seconds in a debug build.
    let rows: Vec<Vec<f64>> = (0..300)
        .map(|i| {
            let q0 = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];
            (0..7)
                .map(|k| q0[k] + 0.3 * (0.1 * i as f64 + k as f64).sin())
                .collect()
        })
        .collect();
    let slow_body = json!({"waypoints": rows, "limits": {"preset": "panda"}});
    let slow = std::thread::spawn(move || {
        let t = Instant::now();
        let r = post(addr, "/api/plan", &slow_body);
        (r.status, t.elapsed())
    });
    std::thread::sleep(Duration::from_millis(100));
    // The executor is free: static files and health answer at once.
    let t = Instant::now();
    assert_eq!(get(s.addr, "/api/health").status, 200);
    assert_eq!(get(s.addr, "/").status, 200);
    let quick = t.elapsed();
    // The lessons have their own workers: answered while the plan runs.
    let t = Instant::now();
    assert_eq!(post(s.addr, "/api/profiles", &json!({})).status, 200);
    let lesson = t.elapsed();
    // The only planning worker is busy: another plan waits 0.2 s, then 503 (a bad plan
    // request is refused at once, without waiting).
    let busy = post(s.addr, "/api/plan", &default_plan(json!({})));
    let t = Instant::now();
    let bad = post(s.addr, "/api/plan", &default_plan(json!({"gridpoints": 0})));
    let refusal = t.elapsed();
    let (status, took) = slow.join().unwrap();
    assert_eq!(status, 200);
    assert!(quick < took / 4, "{quick:?} vs {took:?}");
    assert!(lesson < took / 2, "{lesson:?} vs {took:?}");
    refused(&busy, 503, "", "busy");
    refused(&bad, 400, "gridpoints", "below 1");
    assert!(refusal < Duration::from_millis(150), "{refusal:?}");
    // Afterwards the server is fine.
    assert_eq!(post(s.addr, "/api/profiles", &json!({})).status, 200);
}

/// Every leaf of `v` (by JSON pointer), arrays' first two entries only.
fn leaves(v: &Value, at: String, out: &mut Vec<String>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                leaves(x, format!("{at}/{k}"), out);
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate().take(2) {
                leaves(x, format!("{at}/{i}"), out);
            }
        }
        _ => out.push(at),
    }
}

#[test]
fn no_input_makes_the_server_fail() {
    // Each leaf of a valid request of every endpoint replaced by each of a set of hostile
    // values: the answer is a success or a refusal (4xx) with an error naming it, never a
    // server error, and the server stays up.
    let mut s = Studio::start(&[]);
    let t: Vec<f64> = (0..=10).map(|k| k as f64 / 10.0).collect();
    let demo = json!({"t": t, "q": t.iter().map(|&x| [x, x * x]).collect::<Vec<_>>()});
    let requests = [
        (
            "/api/polynomials",
            json!({"delta_q": 1, "duration": 1, "samples": 11,
            "limits": {"velocity": 2, "acceleration": 10, "jerk": 100}}),
        ),
        (
            "/api/catmull-rom",
            json!({"points": [[0, 0], [1, 2], [3, 1]], "kinds": ["chordal"], "samples_per_segment": 4}),
        ),
        (
            "/api/bspline",
            json!({"control_points": [[0, 0], [1, 2], [3, 1], [4, 0]], "degree": 2,
            "weights": [1, 2, 1, 1], "compare_degree": 1, "samples": 11}),
        ),
        (
            "/api/profiles",
            json!({"distance": 1, "v_max": 0.6, "a_max": 1, "j_max": 4, "samples": 11}),
        ),
        (
            "/api/otg",
            json!({"current_position": [0, 1], "target_position": [1, 0], "max_velocity": [1, 1],
            "max_acceleration": [2, 2], "max_jerk": [10, 10], "min_velocity": [-1, -1], "enabled": [true, true],
            "minimum_duration": 1, "synchronization": "time", "dt": 0.1}),
        ),
        (
            "/api/dmp",
            json!({"demo": demo, "goal": [2, 1], "start": [0, 0], "duration": 1, "n_basis": 10, "samples": 11}),
        ),
        (
            "/api/promp",
            json!({"demos": [demo, demo], "via": [{"t": 0.5, "q": [0.5, 0.3], "variance": 0.01}],
            "n_basis": 5, "samples": 11}),
        ),
        (
            "/api/plan",
            json!({"waypoints": [[0, 0], [0.5, 0.2], [1, -0.3]], "joint_names": ["a", "b"],
            "limits": {"preset": "panda", "max_velocity": [1], "max_acceleration": [2], "max_jerk": [50],
                "velocity_scale": 1, "acceleration_scale": 1, "jerk_scale": 1},
            "method": "toppra", "path": "natural", "gridpoints": 50, "jerk_limit": true, "rate": 20, "phase_plane": true}),
        ),
    ];
    let hostile = [
        json!(0),
        json!(-1),
        json!(1e308),
        json!(-1e308),
        json!(18446744073709551615u64),
        json!(0.5),
        json!("x"),
        json!(null),
        json!([]),
        json!({}),
        json!(true),
    ];
    let mut count = 0;
    for (path, body) in &requests {
        let mut at = Vec::new();
        leaves(body, String::new(), &mut at);
        for pointer in &at {
            for h in &hostile {
                let mut b = body.clone();
                *b.pointer_mut(pointer).unwrap() = h.clone();
                let r = post(s.addr, path, &b);
                count += 1;
                assert!(
                    r.status == 200 || (400..500).contains(&r.status),
                    "{path} {pointer} = {h}: {} {}",
                    r.status,
                    String::from_utf8_lossy(&r.body)
                );
                if r.status != 200 {
                    assert!(!r.error().0.is_empty());
                }
            }
        }
    }
    assert!(count > 500, "{count}");
    assert!(s.alive());
    assert_eq!(get(s.addr, "/api/health").status, 200);
}
