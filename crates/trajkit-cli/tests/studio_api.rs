//! Tests of `trajkit studio`'s HTTP API against the running binary: every endpoint with valid
//! input (values checked against analytic results, the CLI or the library's own guarantees),
//! invalid input (4xx naming the field), caps, the worker pool and the embedded page.

mod studio_common;

use serde_json::{json, Value};
use std::time::{Duration, Instant};
use studio_common::{default_waypoints_csv, get, post, refused, request, Studio};

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
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
