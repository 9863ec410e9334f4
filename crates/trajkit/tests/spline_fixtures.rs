//! trajkit::spline against reference values from scipy.interpolate and geomdl
//! (tests/fixtures/spline/, written by tools/spline_fixtures.py).
//!
//! Agreement is relative: |got − want| ≤ 1e-12 · max(1, max |want|), the maximum taken over the
//! case's values of that derivative order.

use serde_json::Value;
use trajkit::spline::*;
use trajkit::Path;

fn load(name: &str) -> Value {
    let p = format!(
        "{}/tests/fixtures/spline/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap()
}

fn arr(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn dim(c: &Value) -> usize {
    c["dim"].as_u64().unwrap() as usize
}

/// Compares `path` with the case's `values` at its `s`, orders 0..values.len(); returns the
/// worst relative error.
fn compare(label: &str, path: &dyn Path, c: &Value, tol: f64) -> f64 {
    let s = arr(&c["s"]);
    let dim = path.dim();
    let mut out = vec![0.0; dim];
    let mut worst = 0.0f64;
    for (k, vals) in c["values"].as_array().unwrap().iter().enumerate() {
        let want = arr(vals);
        let scale = want.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for (i, &si) in s.iter().enumerate() {
            path.eval(si, k, &mut out);
            for d in 0..dim {
                let e = (out[d] - want[i * dim + d]).abs() / scale;
                worst = worst.max(e);
                assert!(
                    e <= tol,
                    "{label}: order {k} at s = {si} dim {d}: got {} want {} (rel {e:e})",
                    out[d],
                    want[i * dim + d]
                );
            }
        }
    }
    worst
}

#[test]
fn cubic_spline_matches_scipy_cubicspline() {
    let f = load("cubic.json");
    let mut worst = 0.0f64;
    for c in f["cases"].as_array().unwrap() {
        let (x, y, d) = (arr(&c["x"]), arr(&c["y"]), dim(c));
        let bc = c["bc"].as_str().unwrap();
        let sp = match bc {
            "natural" => CubicSpline::natural(&x, &y, d),
            "clamped" => CubicSpline::clamped(&x, &y, d, &arr(&c["d_start"]), &arr(&c["d_end"])),
            "not-a-knot" => CubicSpline::not_a_knot(&x, &y, d),
            "periodic" => CubicSpline::periodic(&x, &y, d),
            _ => unreachable!(),
        }
        .unwrap();
        worst = worst.max(compare(&format!("{bc} n={}", x.len()), &sp, c, 1e-12));
    }
    eprintln!("CubicSpline worst relative error {worst:e}");
}

#[test]
fn hermite_splines_match_scipy() {
    let f = load("hermite.json");
    for c in f["cases"].as_array().unwrap() {
        let (x, y, d) = (arr(&c["x"]), arr(&c["y"]), dim(c));
        let dy = arr(&c["dydx"]);
        match c["kind"].as_str().unwrap() {
            "cubic" => {
                let sp = CubicHermiteSpline::new(&x, &y, &dy, d).unwrap();
                compare("cubic hermite", &sp, c, 1e-12);
            }
            _ => {
                let sp = QuinticHermiteSpline::new(&x, &y, &dy, &arr(&c["d2ydx2"]), d).unwrap();
                compare("quintic hermite", &sp, c, 1e-12);
            }
        }
    }
}

#[test]
fn pchip_and_akima_match_scipy() {
    let f = load("shape_preserving.json");
    for c in f["cases"].as_array().unwrap() {
        let (x, y, d) = (arr(&c["x"]), arr(&c["y"]), dim(c));
        let kind = c["kind"].as_str().unwrap();
        let sp: Box<dyn Path> = match kind {
            "pchip" => Box::new(PchipSpline::new(&x, &y, d).unwrap()),
            "akima" => Box::new(AkimaSpline::original(&x, &y, d).unwrap()),
            _ => Box::new(AkimaSpline::modified(&x, &y, d).unwrap()),
        };
        compare(&format!("{kind} n={}", x.len()), &sp, c, 1e-12);
    }
}
