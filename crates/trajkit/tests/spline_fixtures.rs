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
    eprintln!("{label}: worst relative error {worst:.2e}");
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

fn bspline_of(c: &Value) -> BSpline {
    BSpline::new(
        &arr(&c["t"]),
        &arr(&c["c"]),
        dim(c),
        c["k"].as_u64().unwrap() as usize,
    )
    .unwrap()
}

/// Compares knots and control points of `b` with those of case `c` (relative to their scale).
fn same_representation(label: &str, b: &BSpline, c: &Value, tol: f64) {
    let (t, cc) = (arr(&c["t"]), arr(&c["c"]));
    assert_eq!(b.knots().len(), t.len(), "{label}: knot count");
    for (a, w) in b.knots().iter().zip(&t) {
        assert!(
            (a - w).abs() <= tol * w.abs().max(1.0),
            "{label}: knot {a} vs {w}"
        );
    }
    let scale = cc.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let n = b.control_points().len();
    assert!(cc.len() >= n, "{label}: control point count");
    for (a, w) in b.control_points().iter().zip(&cc[..n]) {
        assert!(
            (a - w).abs() <= tol * scale,
            "{label}: control point {a} vs {w}"
        );
    }
}

#[test]
fn bspline_derivatives_insert_knot_and_design_matrix_match_scipy() {
    let f = load("bspline.json");
    for c in f["cases"].as_array().unwrap() {
        let b = bspline_of(c);
        let label = format!("k={} n={}", b.degree(), b.num_control_points());
        compare(&label, &b, c, 1e-12);
        for ins in c["insert_knot"].as_array().unwrap() {
            let bi = b.insert_knot(ins["x"].as_f64().unwrap(), 1).unwrap();
            same_representation(&format!("{label} insert"), &bi, ins, 1e-12);
            compare(&format!("{label} after insertion"), &bi, c, 1e-12);
        }
        let s = arr(&c["s"]);
        let dm = b.design_matrix(&s, 0).to_dense();
        let want = arr(&c["design_matrix"]);
        assert_eq!(dm.len(), want.len());
        for (a, w) in dm.iter().zip(&want) {
            assert!((a - w).abs() <= 1e-12, "{label}: design matrix {a} vs {w}");
        }
    }
}

#[test]
fn bspline_interpolation_matches_make_interp_spline() {
    let f = load("interp.json");
    for c in f["cases"].as_array().unwrap() {
        let (x, y, d) = (arr(&c["x"]), arr(&c["y"]), dim(c));
        let k = c["k"].as_u64().unwrap() as usize;
        let bc = c["bc"].as_str().unwrap();
        let b = match bc {
            "default" => BSpline::interpolate(&x, &y, d, k).unwrap(),
            "natural" | "clamped" => {
                let z = vec![0.0; d];
                let order = if bc == "natural" { 2 } else { 1 };
                let e = [EndDerivative { order, value: &z }];
                BSpline::interpolate_with_ends(&x, &y, d, k, &e, &e).unwrap()
            }
            _ => {
                let st: Vec<Vec<f64>> = c["d_start"].as_array().unwrap().iter().map(arr).collect();
                let en: Vec<Vec<f64>> = c["d_end"].as_array().unwrap().iter().map(arr).collect();
                let e = |v: &[Vec<f64>]| -> Vec<(usize, Vec<f64>)> {
                    v.iter()
                        .enumerate()
                        .map(|(i, x)| (i + 1, x.clone()))
                        .collect()
                };
                let (es, ee) = (e(&st), e(&en));
                let es: Vec<EndDerivative> = es
                    .iter()
                    .map(|(o, v)| EndDerivative {
                        order: *o,
                        value: v,
                    })
                    .collect();
                let ee: Vec<EndDerivative> = ee
                    .iter()
                    .map(|(o, v)| EndDerivative {
                        order: *o,
                        value: v,
                    })
                    .collect();
                match k {
                    5 => BSpline::minimum_jerk(
                        &x,
                        &y,
                        d,
                        es[0].value,
                        es[1].value,
                        ee[0].value,
                        ee[1].value,
                    )
                    .unwrap(),
                    7 => BSpline::minimum_snap(
                        &x,
                        &y,
                        d,
                        [es[0].value, es[1].value, es[2].value],
                        [ee[0].value, ee[1].value, ee[2].value],
                    )
                    .unwrap(),
                    _ => BSpline::interpolate_with_ends(&x, &y, d, k, &es, &ee).unwrap(),
                }
            }
        };
        let label = format!("interp k={k} n={} bc={bc}", x.len());
        same_representation(&label, &b, c, 1e-11);
        compare(&label, &b, c, 1e-12);
    }
}

#[test]
fn bspline_least_squares_matches_make_lsq_spline() {
    let f = load("lsq.json");
    for c in f["cases"].as_array().unwrap() {
        let (x, y, d) = (arr(&c["x"]), arr(&c["y"]), dim(c));
        let k = c["k"].as_u64().unwrap() as usize;
        let b = BSpline::least_squares(&x, &y, d, &arr(&c["t"]), k, None).unwrap();
        let label = format!("lsq k={k}");
        same_representation(&label, &b, c, 1e-12);
        compare(&label, &b, c, 1e-12);
    }
}

#[test]
fn degree_elevation_matches_geomdl_on_a_bezier_segment() {
    let f = load("nurbs.json");
    let c = &f["cases"]["elevate"];
    let b = BSpline::new(&arr(&c["knots"]), &arr(&c["points"]), dim(c), 3).unwrap();
    let e = b
        .elevate_degree(c["times"].as_u64().unwrap() as usize)
        .unwrap();
    assert_eq!(e.degree(), c["elevated_degree"].as_u64().unwrap() as usize);
    assert_eq!(e.knots(), &arr(&c["elevated_knots"])[..]);
    for (a, w) in e.control_points().iter().zip(&arr(&c["elevated_points"])) {
        assert!((a - w).abs() < 1e-12, "{a} vs {w}");
    }
}

#[test]
fn nurbs_matches_geomdl_and_the_circle_is_exact() {
    let f = load("nurbs.json");
    for name in ["circle", "rational3d"] {
        let c = &f["cases"][name];
        let nb = Nurbs::new(
            &arr(&c["knots"]),
            &arr(&c["points"]),
            &arr(&c["weights"]),
            dim(c),
            c["degree"].as_u64().unwrap() as usize,
        )
        .unwrap();
        compare(name, &nb, c, 1e-12);
        if name == "circle" {
            let mine = Nurbs::circle([0.0, 0.0], 1.0).unwrap();
            assert_eq!(mine.knots(), nb.knots());
            compare("Nurbs::circle", &mine, c, 1e-12);
        }
    }
    // The 9-point unit circle has radius 1 within 1e-14 at 10 000 points.
    let circ = Nurbs::circle([0.0, 0.0], 1.0).unwrap();
    let mut p = [0.0; 2];
    let mut worst = 0.0f64;
    for i in 0..10_000 {
        circ.eval(i as f64 / 9_999.0, 0, &mut p);
        worst = worst.max((p[0].hypot(p[1]) - 1.0).abs());
    }
    assert!(worst <= 1e-14, "radius error {worst:e}");
}
