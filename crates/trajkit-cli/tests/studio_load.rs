//! Load test of `trajkit studio` on loopback: a bounded mix of valid and invalid requests from
//! dozens of concurrent clients. Every valid request must be answered correctly (checked
//! against analytic values or the CLI), every invalid one refused with the expected status and
//! field, and the server must still be up at the end. Prints latency percentiles per kind.
//!
//! Ignored by default (it wants an optimized build):
//!
//! ```sh
//! cargo test --release -p trajkit-cli --test studio_load -- --ignored --nocapture
//! ```
//!
//! `STUDIO_LOAD_REQUESTS` (default 4000) and `STUDIO_LOAD_CLIENTS` (default 32) change the size.

mod studio_common;

use serde_json::{json, Value};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use studio_common::{default_waypoints_csv, request, Studio};

/// Checks an answer (status, body); `Err` says what is wrong.
type Check = Box<dyn Fn(u16, &[u8]) -> Result<(), String> + Send + Sync>;

/// One answered request: its kind, latency and verdict.
type Outcome = (usize, Duration, Result<(), String>);

/// One kind of request: a name, how to send it, what the answer must be.
struct Kind {
    name: &'static str,
    valid: bool,
    path: &'static str,
    content_type: Option<&'static str>,
    body: Vec<u8>,
    /// Checks the answer.
    check: Check,
}

fn json_body(v: Value) -> Vec<u8> {
    v.to_string().into_bytes()
}

fn parse(body: &[u8]) -> Result<Value, String> {
    serde_json::from_slice(body).map_err(|e| format!("not JSON: {e}"))
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

/// An answer that must be 200 and pass `ok`.
fn valid(
    name: &'static str,
    path: &'static str,
    body: Value,
    ok: impl Fn(&Value) -> Result<(), String> + Send + Sync + 'static,
) -> Kind {
    Kind {
        name,
        valid: true,
        path,
        content_type: Some("application/json"),
        body: json_body(body),
        check: Box::new(move |status, b| {
            if status != 200 {
                return Err(format!("status {status}: {}", String::from_utf8_lossy(b)));
            }
            ok(&parse(b)?)
        }),
    }
}

/// A request that must be refused with `status`, naming `field` (a prefix) when given.
fn invalid(
    name: &'static str,
    path: &'static str,
    content_type: Option<&'static str>,
    body: Vec<u8>,
    status: u16,
    field: Option<&'static str>,
) -> Kind {
    Kind {
        name,
        valid: false,
        path,
        content_type,
        body,
        check: Box::new(move |got, b| {
            if got != status {
                return Err(format!("status {got}, wanted {status}"));
            }
            let e = parse(b)?;
            let message = e["error"]["message"].as_str().unwrap_or("");
            if message.is_empty() {
                return Err("no error message".into());
            }
            match field {
                Some(f) if !e["error"]["field"].as_str().unwrap_or("").starts_with(f) => {
                    Err(format!("field {:?}, wanted {f}", e["error"]["field"]))
                }
                _ => Ok(()),
            }
        }),
    }
}

fn close(a: f64, b: f64, tol: f64) -> Result<(), String> {
    if (a - b).abs() <= tol {
        Ok(())
    } else {
        Err(format!("{a} is not {b} (± {tol})"))
    }
}

/// The duration `trajkit plan` prints for the default path, and its wall time per run.
fn cli_plan() -> (f64, Vec<Duration>) {
    let mut times = Vec::new();
    let mut duration = f64::NAN;
    for _ in 0..15 {
        let t = Instant::now();
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_trajkit"))
            .args(["plan", "--out", "-"])
            .output()
            .expect("trajkit plan runs");
        times.push(t.elapsed());
        let text = String::from_utf8_lossy(&o.stderr);
        let line = text
            .lines()
            .find(|l| l.contains("duration:"))
            .expect("summary");
        duration = line
            .split("duration: ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .and_then(|d| d.parse().ok())
            .expect("a duration");
    }
    (duration, times)
}

fn catalog(plan_duration: f64) -> Vec<Kind> {
    let waypoints = default_waypoints_csv();
    let plan_body = json!({
        "waypoints_file": {"name": "default.csv", "text": waypoints},
        "limits": {"preset": "panda"},
    });
    let t: Vec<f64> = (0..=50).map(|k| k as f64 / 50.0).collect();
    let demos: Vec<Value> = [0.9, 1.0, 1.1]
        .iter()
        .map(|a| json!({"t": t, "q": t.iter().map(|&s| [a * (3.0 * s).sin()]).collect::<Vec<_>>()}))
        .collect();
    let demo = json!({"t": t, "q": t.iter().map(|&s| [s, (3.0 * s).sin()]).collect::<Vec<_>>()});
    vec![
        valid("profiles", "/api/profiles", json!({}), |j| {
            close(num(&j["trapezoid"]["duration"]), 1.0 / 0.6 + 0.6, 1e-9)?;
            close(num(&j["s_curve"]["duration"]), 1.0 / 0.6 + 0.85, 1e-9)
        }),
        valid(
            "polynomials",
            "/api/polynomials",
            json!({"samples": 101}),
            |j| {
                for (k, c) in [1.5, 1.875, 2.1875].iter().enumerate() {
                    close(num(&j["profiles"][k]["peak_coefficients"][0]), *c, 1e-12)?;
                }
                Ok(())
            },
        ),
        valid(
            "catmull-rom",
            "/api/catmull-rom",
            json!({"points": [[0, 0], [1, 2], [3, 1], [4, 3]], "samples_per_segment": 20}),
            |j| {
                for c in j["curves"].as_array().ok_or("no curves")? {
                    close(num(&c["points"][20][0]), 1.0, 1e-12)?;
                    close(num(&c["points"][40][1]), 1.0, 1e-12)?;
                }
                Ok(())
            },
        ),
        valid(
            "bspline",
            "/api/bspline",
            json!({"control_points": [[0, 0], [1, 3], [3, 3], [4, 0], [6, 1]], "degree": 3,
                   "weights": [1, 1, 5, 1, 1], "compare_degree": 2}),
            |j| {
                for s in j["basis"]["sum"].as_array().ok_or("no basis")? {
                    close(num(s), 1.0, 1e-13)?;
                }
                close(num(&j["curve"][200][0]), 6.0, 1e-12)
            },
        ),
        valid(
            "otg",
            "/api/otg",
            json!({"current_position": [0], "target_position": [1], "max_velocity": [0.6],
                   "max_acceleration": [1], "max_jerk": [4], "dt": 0.01}),
            |j| close(num(&j["duration"]), 1.0 / 0.6 + 0.85, 1e-9),
        ),
        valid(
            "promp",
            "/api/promp",
            json!({"demos": demos, "via": [{"t": 0.5, "q": [1.2], "variance": 0}], "samples": 51}),
            |j| close(num(&j["posterior"]["mean"][0][25]), 1.2, 1e-6),
        ),
        valid(
            "dmp",
            "/api/dmp",
            json!({"demo": demo, "goal": [2.0, 0.0], "samples": 101}),
            |j| {
                let end = &j["rollout"]["q"][100];
                close(num(&end[0]), 2.0, 0.05)?;
                close(num(&end[1]), 0.0, 0.05)
            },
        ),
        valid("plan", "/api/plan", plan_body.clone(), move |j| {
            close(num(&j["duration"]), plan_duration, 1e-6)?;
            if num(&j["check"]["worst"]) > 1.0 + 1e-6 {
                return Err(format!("worst ratio {}", j["check"]["worst"]));
            }
            Ok(())
        }),
        invalid(
            "bad value",
            "/api/profiles",
            Some("application/json"),
            json_body(json!({"v_max": -1})),
            400,
            Some("v_max"),
        ),
        invalid(
            "unknown field",
            "/api/bspline",
            Some("application/json"),
            json_body(json!({"control_points": [[0, 0], [1, 1]], "degre": 1})),
            400,
            Some("degre"),
        ),
        invalid(
            "malformed JSON",
            "/api/polynomials",
            Some("application/json"),
            b"{\"delta_q\": 1,".to_vec(),
            400,
            None,
        ),
        invalid(
            "not JSON",
            "/api/otg",
            Some("text/plain"),
            b"current_position=0".to_vec(),
            415,
            None,
        ),
        invalid(
            "cap",
            "/api/plan",
            Some("application/json"),
            json_body(
                json!({"waypoints": [[0], [1]], "limits": {"preset": "panda"}, "gridpoints": 1000000}),
            ),
            400,
            Some("gridpoints"),
        ),
        invalid(
            "bad limits",
            "/api/plan",
            Some("application/json"),
            json_body(
                json!({"waypoints_file": {"name": "w.csv", "text": waypoints}, "limits": {"preset": "r2d2"}}),
            ),
            400,
            Some("limits.preset"),
        ),
        invalid(
            "too large",
            "/api/catmull-rom",
            Some("application/json"),
            vec![b' '; (2 << 20) + 10],
            413,
            None,
        ),
        invalid(
            "no endpoint",
            "/api/teleport",
            Some("application/json"),
            b"{}".to_vec(),
            404,
            Some("path"),
        ),
    ]
}

/// The p-th percentile (0..=100) of sorted durations, in ms.
fn pct(sorted: &[Duration], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let i = ((p / 100.0) * (sorted.len() - 1) as f64).round() as usize;
    sorted[i].as_secs_f64() * 1e3
}

#[test]
#[ignore = "load test: run with --release -- --ignored (README, Studio)"]
fn thousands_of_mixed_requests_from_dozens_of_clients() {
    let total: usize = std::env::var("STUDIO_LOAD_REQUESTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(4000);
    let clients: usize = std::env::var("STUDIO_LOAD_CLIENTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(32);
    let (plan_duration, cli_times) = cli_plan();
    let kinds = Arc::new(catalog(plan_duration));
    let mut studio = Studio::start(&[]);
    let addr = studio.addr;
    // Unloaded latency first: one client, one request at a time, a plan and a lesson.
    let mut alone: Vec<(&str, Vec<Duration>)> = Vec::new();
    for k in ["plan", "profiles"] {
        let kind = kinds.iter().find(|c| c.name == k).expect("kind");
        let mut d = Vec::new();
        for _ in 0..15 {
            let t = Instant::now();
            let r = request(
                addr,
                "POST",
                kind.path,
                &[("Content-Type", "application/json")],
                &kind.body,
            )
            .expect("answered");
            d.push(t.elapsed());
            (kind.check)(r.status, &r.body).expect("a correct answer");
        }
        d.sort();
        alone.push((k, d));
    }
    let next = Arc::new(AtomicUsize::new(0));
    let results: Arc<Mutex<Vec<Outcome>>> = Arc::new(Mutex::new(Vec::with_capacity(total)));
    let deadline = Instant::now() + Duration::from_secs(600);
    let start = Instant::now();
    let threads: Vec<_> = (0..clients)
        .map(|_| {
            let (kinds, next, results) = (kinds.clone(), next.clone(), results.clone());
            std::thread::spawn(move || loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= total || Instant::now() > deadline {
                    break;
                }
                // A fixed interleaving: every kind in turn (half of them valid).
                let k = i % kinds.len();
                let kind = &kinds[k];
                let headers: Vec<(&str, &str)> = kind
                    .content_type
                    .map(|c| vec![("Content-Type", c)])
                    .unwrap_or_default();
                let t = Instant::now();
                let r = request(addr, "POST", kind.path, &headers, &kind.body);
                let took = t.elapsed();
                let verdict = match r {
                    Ok(r) => (kind.check)(r.status, &r.body),
                    Err(e) => Err(format!("transport: {e}")),
                };
                results.lock().unwrap().push((k, took, verdict));
            })
        })
        .collect();
    for t in threads {
        t.join().expect("client thread");
    }
    let wall = start.elapsed();
    let results = Arc::try_unwrap(results).unwrap().into_inner().unwrap();
    assert_eq!(results.len(), total, "the run hit its 600 s deadline");
    // The server is still up and answering.
    assert!(studio.alive(), "the server died");
    let health = request(addr, "GET", "/api/health", &[], b"").expect("health");
    assert_eq!(health.status, 200);

    let mut failures = Vec::new();
    let mut all = Vec::new();
    let (mut valid_n, mut invalid_n) = (0, 0);
    println!("\n| request | kind | count | p50 ms | p90 ms | p99 ms | max ms |");
    println!("|---|---|---:|---:|---:|---:|---:|");
    for (k, kind) in kinds.iter().enumerate() {
        let mut d: Vec<Duration> = results.iter().filter(|r| r.0 == k).map(|r| r.1).collect();
        d.sort();
        for (_, _, v) in results.iter().filter(|r| r.0 == k) {
            if let Err(e) = v {
                failures.push(format!("{}: {e}", kind.name));
            }
        }
        if kind.valid {
            valid_n += d.len();
        } else {
            invalid_n += d.len();
        }
        println!(
            "| {} | {} | {} | {:.2} | {:.2} | {:.2} | {:.2} |",
            kind.name,
            if kind.valid { "valid" } else { "refused" },
            d.len(),
            pct(&d, 50.0),
            pct(&d, 90.0),
            pct(&d, 99.0),
            pct(&d, 100.0)
        );
        all.extend(d);
    }
    all.sort();
    println!(
        "| all | {valid_n} valid + {invalid_n} invalid | {} | {:.2} | {:.2} | {:.2} | {:.2} |",
        all.len(),
        pct(&all, 50.0),
        pct(&all, 90.0),
        pct(&all, 99.0),
        pct(&all, 100.0)
    );
    let mut cli = cli_times;
    cli.sort();
    for (k, d) in &alone {
        println!(
            "alone (one client, sequential): {k} median {:.2} ms over {} requests",
            pct(d, 50.0),
            d.len()
        );
    }
    println!(
        "\n{total} requests from {clients} clients in {:.2} s ({:.0} requests/s); `trajkit plan` as a process in the same run: median {:.2} ms over {} runs",
        wall.as_secs_f64(),
        total as f64 / wall.as_secs_f64(),
        pct(&cli, 50.0),
        cli.len()
    );
    assert!(
        failures.is_empty(),
        "{} of {total} requests failed, first: {:?}",
        failures.len(),
        &failures[..failures.len().min(5)]
    );
}
