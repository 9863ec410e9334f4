//! Catmull-Rom and Bézier curves against independent constructions (Barry–Goldman pyramid,
//! Bernstein sums, the equivalent clamped B-spline), and their derivatives against finite
//! differences.

use trajkit::rng::SplitMix64;
use trajkit::spline::*;
use trajkit::{Error, Path};

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    let scale = a.iter().chain(b).fold(1.0f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol * scale)
}

/// The Barry–Goldman pyramid for the segment P1..P2 at parameter t (t1 <= t <= t2).
fn barry_goldman(p: [&[f64]; 4], tk: [f64; 4], t: f64, out: &mut [f64]) {
    let lerp =
        |a: f64, b: f64, ta: f64, tb: f64| (tb - t) / (tb - ta) * a + (t - ta) / (tb - ta) * b;
    for d in 0..out.len() {
        let a1 = lerp(p[0][d], p[1][d], tk[0], tk[1]);
        let a2 = lerp(p[1][d], p[2][d], tk[1], tk[2]);
        let a3 = lerp(p[2][d], p[3][d], tk[2], tk[3]);
        let b1 = lerp(a1, a2, tk[0], tk[2]);
        let b2 = lerp(a2, a3, tk[1], tk[3]);
        out[d] = lerp(b1, b2, tk[1], tk[2]);
    }
}

#[test]
fn catmull_rom_matches_the_barry_goldman_pyramid() {
    let mut r = SplitMix64::new(21);
    for case in 0..30 {
        let n = 2 + case % 7;
        let dim = 1 + case % 3;
        let pts: Vec<f64> = (0..n * dim).map(|_| r.uniform(-2.0, 2.0)).collect();
        for kind in [
            CatmullRomKind::Uniform,
            CatmullRomKind::Centripetal,
            CatmullRomKind::Chordal,
        ] {
            let cr = CatmullRom::new(&pts, dim, kind).unwrap();
            assert_eq!(cr.kind(), kind);
            let t = cr.parameters().to_vec();
            // Phantom end points by reflection, with their knots.
            let mut ext = Vec::new();
            ext.extend((0..dim).map(|d| 2.0 * pts[d] - pts[dim + d]));
            ext.extend_from_slice(&pts);
            ext.extend((0..dim).map(|d| 2.0 * pts[(n - 1) * dim + d] - pts[(n - 2) * dim + d]));
            let mut tk = vec![t[0] - (t[1] - t[0])];
            tk.extend_from_slice(&t);
            tk.push(t[n - 1] + (t[n - 1] - t[n - 2]));
            let pt = |i: usize| &ext[i * dim..(i + 1) * dim];
            let mut a = vec![0.0; dim];
            let mut b = vec![0.0; dim];
            for seg in 0..n - 1 {
                for f in [0.0, 0.2, 0.5, 0.9, 1.0] {
                    let s = t[seg] + f * (t[seg + 1] - t[seg]);
                    cr.eval(s, 0, &mut a);
                    barry_goldman(
                        [pt(seg), pt(seg + 1), pt(seg + 2), pt(seg + 3)],
                        [tk[seg], tk[seg + 1], tk[seg + 2], tk[seg + 3]],
                        s,
                        &mut b,
                    );
                    assert!(
                        close(&a, &b, 1e-12),
                        "{kind:?} seg {seg} f {f}: {a:?} vs {b:?}"
                    );
                }
            }
            if kind == CatmullRomKind::Uniform && n >= 3 {
                // The classic tangent (P_{i+1} − P_{i−1}) / 2.
                cr.eval(t[1], 1, &mut a);
                for d in 0..dim {
                    assert!((a[d] - 0.5 * (pts[2 * dim + d] - pts[d])).abs() < 1e-14);
                }
            }
        }
    }
}

#[test]
fn catmull_rom_bad_input() {
    assert!(matches!(
        CatmullRom::centripetal(&[0.0, 0.0, 1.0, 1.0, 1.0, 1.0], 2),
        Err(Error::DuplicateWaypoint { index: 2 })
    ));
    assert!(CatmullRom::uniform(&[0.0, 0.0, 1.0, 1.0, 1.0, 1.0], 2).is_ok());
    assert!(matches!(
        CatmullRom::chordal(&[0.0, 1.0], 2),
        Err(Error::TooFewWaypoints { .. })
    ));
    assert!(matches!(
        CatmullRom::chordal(&[0.0, 1.0, 2.0], 2),
        Err(Error::DimensionMismatch { .. })
    ));
    assert!(matches!(
        CatmullRom::chordal(&[0.0, f64::NAN], 1),
        Err(Error::InvalidValue { .. })
    ));
}

fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |a, i| a * (n - i) as f64 / (i + 1) as f64)
}

#[test]
fn bezier_matches_bernstein_sums_and_the_clamped_bspline() {
    let mut r = SplitMix64::new(22);
    for k in 0..=9 {
        let dim = 2;
        let c: Vec<f64> = (0..(k + 1) * dim).map(|_| r.uniform(-2.0, 2.0)).collect();
        let bz = Bezier::new(&c, dim).unwrap();
        assert_eq!(bz.degree(), k);
        let mut knots = vec![0.0; k + 1];
        knots.extend(vec![1.0; k + 1]);
        let bs = BSpline::new(&knots, &c, dim, k).unwrap();
        let mut a = [0.0; 2];
        let mut b = [0.0; 2];
        for i in 0..=20 {
            let s = i as f64 / 20.0;
            bz.eval(s, 0, &mut a);
            let mut sum = [0.0; 2];
            for j in 0..=k {
                let w = binom(k, j) * s.powi(j as i32) * (1.0 - s).powi((k - j) as i32);
                for d in 0..dim {
                    sum[d] += w * c[j * dim + d];
                }
            }
            assert!(close(&a, &sum, 1e-13), "k={k} Bernstein");
            for order in 0..=k + 1 {
                bz.eval(s, order, &mut a);
                bs.eval(s, order, &mut b);
                assert!(close(&a, &b, 1e-11), "k={k} order {order}: {a:?} vs {b:?}");
            }
            // Hodograph curve = first derivative.
            bz.hodograph().eval(s, 0, &mut b);
            bz.eval(s, 1, &mut a);
            assert!(close(&a, &b, 1e-13));
        }
    }
}

#[test]
fn bezier_split_and_elevation_keep_the_curve() {
    let mut r = SplitMix64::new(23);
    for k in 1..=8 {
        let c: Vec<f64> = (0..(k + 1) * 3).map(|_| r.uniform(-2.0, 2.0)).collect();
        let bz = Bezier::new(&c, 3).unwrap();
        let at = r.uniform(0.1, 0.9);
        let (l, rt) = bz.split(at).unwrap();
        let el = bz.elevate().unwrap();
        assert_eq!(el.degree(), k + 1);
        let mut a = [0.0; 3];
        let mut b = [0.0; 3];
        for i in 0..=20 {
            let s = i as f64 / 20.0;
            bz.eval(s * at, 0, &mut a);
            l.eval(s, 0, &mut b);
            assert!(close(&a, &b, 1e-13), "left half");
            bz.eval(at + s * (1.0 - at), 0, &mut a);
            rt.eval(s, 0, &mut b);
            assert!(close(&a, &b, 1e-13), "right half");
            bz.eval(s, 0, &mut a);
            el.eval(s, 0, &mut b);
            assert!(close(&a, &b, 1e-13), "elevation");
        }
        // Finite differences of the first three derivatives.
        let h = 1e-6;
        for s in [0.3, 0.6] {
            for m in 1..=3 {
                let (mut p, mut q, mut mid) = ([0.0; 3], [0.0; 3], [0.0; 3]);
                bz.eval(s + h, m - 1, &mut p);
                bz.eval(s - h, m - 1, &mut q);
                bz.eval(s, m, &mut mid);
                let fd: Vec<f64> = (0..3).map(|d| (p[d] - q[d]) / (2.0 * h)).collect();
                assert!(close(&fd, &mid, 1e-6), "k={k} m={m}");
            }
        }
    }
    let bz = Bezier::new(&[0.0, 1.0], 1).unwrap();
    assert!(bz.split(0.0).is_err() && bz.split(f64::NAN).is_err());
    assert!(matches!(
        Bezier::new(&[], 1),
        Err(Error::TooFewWaypoints { .. })
    ));
    assert!(Bezier::new(&[0.0; 22], 1).is_err());
    let mut o = [0.0];
    bz.eval(f64::NAN, 0, &mut o);
    assert!(o[0].is_nan());
    bz.eval(7.0, 0, &mut o);
    assert_eq!(o[0], 1.0);
}

#[test]
fn nurbs_arcs_are_exact_and_derivatives_agree_with_finite_differences() {
    for (a0, a1) in [
        (0.0, 1.0),
        (0.3, 2.5),
        (-1.0, 3.0),
        (2.0, -1.5),
        (0.0, std::f64::consts::TAU),
    ] {
        let arc = Nurbs::arc([1.0, -2.0], 2.5, a0, a1).unwrap();
        let mut p = [0.0; 2];
        for i in 0..=1000 {
            arc.eval(i as f64 / 1000.0, 0, &mut p);
            let r = (p[0] - 1.0).hypot(p[1] + 2.0);
            assert!((r - 2.5).abs() < 1e-14, "radius {r}");
        }
        arc.eval(0.0, 0, &mut p);
        assert!(
            (p[0] - (1.0 + 2.5 * a0.cos())).abs() < 1e-14
                && (p[1] - (-2.0 + 2.5 * a0.sin())).abs() < 1e-14
        );
        arc.eval(1.0, 0, &mut p);
        assert!(
            (p[0] - (1.0 + 2.5 * a1.cos())).abs() < 1e-13
                && (p[1] - (-2.0 + 2.5 * a1.sin())).abs() < 1e-13
        );
        // Rational derivatives (also above the degree) against finite differences.
        let h = 1e-6;
        for s in [0.1, 0.37, 0.61, 0.9] {
            if arc.knots().iter().any(|&k| (k - s).abs() < 1e-3) {
                continue;
            }
            for m in 1..=5 {
                let (mut lo, mut hi, mut mid) = ([0.0; 2], [0.0; 2], [0.0; 2]);
                arc.eval(s - h, m - 1, &mut lo);
                arc.eval(s + h, m - 1, &mut hi);
                arc.eval(s, m, &mut mid);
                let fd = [(hi[0] - lo[0]) / (2.0 * h), (hi[1] - lo[1]) / (2.0 * h)];
                assert!(close(&fd, &mid, 1e-5), "order {m}: {fd:?} vs {mid:?}");
            }
        }
    }
    let mut o = [0.0; 2];
    let c = Nurbs::circle([0.0, 0.0], 1.0).unwrap();
    c.eval(0.5, NURBS_MAX_ORDER + 1, &mut o);
    assert!(o[0].is_nan());
}

#[test]
fn nurbs_with_unit_weights_is_its_bspline_and_bad_weights_are_refused() {
    let mut r = SplitMix64::new(24);
    let t = [0.0, 0.0, 0.0, 0.0, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0];
    let c: Vec<f64> = (0..18).map(|_| r.uniform(-1.0, 1.0)).collect();
    let b = BSpline::new(&t, &c, 3, 3).unwrap();
    let n = Nurbs::from_bspline(&b);
    let n2 = Nurbs::new(&t, &c, &[2.0; 6], 3, 3).unwrap(); // equal weights cancel
    let (mut p, mut q, mut z) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for i in 0..=20 {
        for m in 0..4 {
            let s = i as f64 / 20.0;
            b.eval(s, m, &mut p);
            n.eval(s, m, &mut q);
            n2.eval(s, m, &mut z);
            assert!(close(&p, &q, 1e-13) && close(&p, &z, 1e-12));
        }
    }
    assert_eq!(n2.control_points().len(), 18);
    for bad in [0.0, -1.0, f64::NAN] {
        let mut w = [1.0; 6];
        w[2] = bad;
        assert!(matches!(
            Nurbs::new(&t, &c, &w, 3, 3),
            Err(Error::InvalidValue { .. })
        ));
    }
    assert!(matches!(
        Nurbs::new(&t, &c, &[1.0; 5], 3, 3),
        Err(Error::DimensionMismatch { .. })
    ));
    assert!(Nurbs::arc([0.0, 0.0], -1.0, 0.0, 1.0).is_err());
    assert!(Nurbs::arc([0.0, 0.0], 1.0, 0.0, 0.0).is_err());
    assert!(Nurbs::arc([0.0, 0.0], 1.0, 0.0, 7.0).is_err());
}

#[test]
fn catmull_rom_and_broken_line_derivatives_agree_with_finite_differences() {
    let mut r = SplitMix64::new(25);
    let pts: Vec<f64> = (0..7 * 3).map(|_| r.uniform(-2.0, 2.0)).collect();
    let x: Vec<f64> = (0..7)
        .map(|i| i as f64 * 0.7 + (i * i) as f64 * 0.05)
        .collect();
    let curves: Vec<Box<dyn Path>> = vec![
        Box::new(CatmullRom::uniform(&pts, 3).unwrap()),
        Box::new(CatmullRom::centripetal(&pts, 3).unwrap()),
        Box::new(CatmullRom::chordal(&pts, 3).unwrap()),
        Box::new(PiecewisePolynomial::linear(&x, &pts, 3).unwrap()),
    ];
    for (ci, c) in curves.iter().enumerate() {
        let br = c.breakpoints();
        for w in br.windows(2) {
            let h = 1e-6 * (w[1] - w[0]);
            for f in [0.3, 0.7] {
                let s = w[0] + f * (w[1] - w[0]);
                for m in 1..=4 {
                    let (mut lo, mut hi, mut mid) = ([0.0; 3], [0.0; 3], [0.0; 3]);
                    c.eval(s - h, m - 1, &mut lo);
                    c.eval(s + h, m - 1, &mut hi);
                    c.eval(s, m, &mut mid);
                    let fd: Vec<f64> = (0..3).map(|d| (hi[d] - lo[d]) / (2.0 * h)).collect();
                    assert!(
                        close(&fd, &mid, 1e-6),
                        "curve {ci} order {m}: {fd:?} vs {mid:?}"
                    );
                }
            }
        }
        // C¹ (Catmull-Rom) / C⁰ (broken line) at the interior breaks.
        for &b in &br[1..br.len() - 1] {
            let smooth = if ci < 3 { 1 } else { 0 };
            for m in 0..=smooth {
                let (mut a, mut e, mut slope) = ([0.0; 3], [0.0; 3], [0.0; 3]);
                let h = 1e-9;
                c.eval(b - h, m, &mut a);
                c.eval(b - h, m + 1, &mut slope);
                c.eval(b, m, &mut e);
                let left: Vec<f64> = (0..3).map(|d| a[d] + h * slope[d]).collect();
                assert!(close(&left, &e, 1e-7), "curve {ci} C{m} at {b}");
            }
        }
    }
    let lin = PiecewisePolynomial::linear(&x, &pts, 3).unwrap();
    let mut p = [0.0; 3];
    lin.eval(0.5 * (x[2] + x[3]), 0, &mut p);
    for d in 0..3 {
        assert!((p[d] - 0.5 * (pts[6 + d] + pts[9 + d])).abs() < 1e-15);
    }
    assert!(PiecewisePolynomial::linear(&[0.0, 0.0], &[1.0, 2.0], 1).is_err());
}
