//! Arc length, its inverse and arc-length reparameterization against exact geometry.

use trajkit::spline::*;
use trajkit::{Error, Path};

#[test]
fn circle_length_inverse_and_unit_speed() {
    let r = 2.0;
    let c = Nurbs::circle([0.5, -1.0], r).unwrap();
    for tol in [1e-6, 1e-9, 1e-12] {
        let al = ArcLength::new(&c, tol).unwrap();
        let l = al.length();
        assert!(
            (l - 2.0 * std::f64::consts::PI * r).abs() <= tol,
            "tol {tol}: L = {l}"
        );
        let mut p = [0.0; 2];
        let mut v = [0.0; 2];
        let mut a = [0.0; 2];
        let mut j = [0.0; 2];
        for i in 0..=200 {
            let s = l * i as f64 / 200.0;
            // Position at arc length s is at angle s / r.
            al.eval(s, 0, &mut p);
            let want = [0.5 + r * (s / r).cos(), -1.0 + r * (s / r).sin()];
            assert!(
                (p[0] - want[0]).hypot(p[1] - want[1]) <= tol,
                "tol {tol} s {s}: {p:?} vs {want:?}"
            );
            // Inverse to tolerance.
            let u = al.param_at(s);
            assert!((al.length_at(u) - s).abs() <= tol, "param_at");
            // Unit speed, curvature 1/r, jerk of magnitude 1/r² along −tangent.
            al.eval(s, 1, &mut v);
            assert!((v[0].hypot(v[1]) - 1.0).abs() < 1e-13);
            al.eval(s, 2, &mut a);
            assert!((a[0].hypot(a[1]) - 1.0 / r).abs() < 1e-9, "curvature");
            assert!((a[0] * v[0] + a[1] * v[1]).abs() < 1e-9);
            al.eval(s, 3, &mut j);
            assert!(
                (j[0] + v[0] / (r * r)).abs() < 1e-8 && (j[1] + v[1] / (r * r)).abs() < 1e-8,
                "jerk {j:?}"
            );
        }
    }
}

#[test]
fn polyline_and_cubic_lengths() {
    // A degree-1 B-spline is a polyline: corners are breakpoints.
    let pts = [0.0, 0.0, 3.0, 4.0, 3.0, 0.0, 6.0, 4.0];
    let b = BSpline::interpolate(&[0.0, 1.0, 2.0, 3.0], &pts, 2, 1).unwrap();
    let al = ArcLength::new(&b, 1e-12).unwrap();
    assert!((al.length() - 14.0).abs() < 1e-12);
    assert!((al.param_at(5.0) - 1.0).abs() < 1e-12);
    assert!((al.param_at(7.0) - 1.5).abs() < 1e-12);
    let mut p = [0.0; 2];
    al.eval(11.5, 0, &mut p);
    assert!(
        (p[0] - 4.5).abs() < 1e-12 && (p[1] - 2.0).abs() < 1e-12,
        "{p:?}"
    );
    assert_eq!(al.breakpoints().len(), 4);
    // A cubic Bézier against a fine composite Simpson reference.
    let bz = Bezier::new(&[0.0, 0.0, 1.0, 2.0, 3.0, -1.0, 4.0, 1.0], 2).unwrap();
    let n = 200_000;
    let mut d = [0.0; 2];
    let mut sum = 0.0;
    for i in 0..=n {
        let s = i as f64 / n as f64;
        bz.eval(s, 1, &mut d);
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        sum += w * d[0].hypot(d[1]);
    }
    let reference = sum / (3.0 * n as f64);
    let al = ArcLength::new(&bz, 1e-11).unwrap();
    assert!(
        (al.length() - reference).abs() < 1e-10,
        "{} vs {reference}",
        al.length()
    );
}

#[test]
fn reparameterized_derivatives_agree_with_finite_differences() {
    let x = [0.0, 1.0, 2.0, 3.5];
    let y = [0.0, 0.0, 0.0, 1.0, 1.0, 0.5, 2.0, 1.0, 1.5, 3.0, 0.0, 2.0];
    let sp = CubicSpline::natural(&x, &y, 3).unwrap();
    let al = ArcLength::new(&sp, 1e-12).unwrap();
    let l = al.length();
    let h = 1e-5;
    let (mut lo, mut hi, mut mid) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for i in 1..20 {
        let s = l * i as f64 / 20.0;
        for m in 1..=3 {
            al.eval(s - h, m - 1, &mut lo);
            al.eval(s + h, m - 1, &mut hi);
            al.eval(s, m, &mut mid);
            for d in 0..3 {
                let fd = (hi[d] - lo[d]) / (2.0 * h);
                assert!(
                    (fd - mid[d]).abs() < 1e-5 * (1.0 + mid[d].abs()),
                    "order {m} at {s}: {fd} vs {}",
                    mid[d]
                );
            }
        }
    }
}

#[test]
fn stopping_paths_and_bad_tolerances_are_refused() {
    let stop = Bezier::new(&[0.0, 0.0, 0.0, 0.0, 1.0, 1.0], 2).unwrap(); // zero speed at s = 0
    assert!(matches!(
        ArcLength::new(&stop, 1e-9),
        Err(Error::InvalidValue { .. })
    ));
    let ok = Bezier::new(&[0.0, 0.0, 1.0, 1.0], 2).unwrap();
    for tol in [0.0, -1.0, f64::NAN] {
        assert!(ArcLength::new(&ok, tol).is_err());
    }
    let al = ArcLength::new(&ok, 1e-9).unwrap();
    let mut p = [0.0; 2];
    al.eval(f64::NAN, 0, &mut p);
    assert!(p[0].is_nan());
    al.eval(100.0, 0, &mut p);
    assert_eq!(p, [1.0, 1.0]);
    assert!(al.param_at(f64::NAN).is_nan());
}
