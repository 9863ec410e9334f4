//! Curve evaluation allocates nothing: every curve of trajkit::spline is evaluated (all orders,
//! out-of-range and NaN parameters included) under a counting global allocator.

mod alloc_counter;
use alloc_counter::allocations;

use std::ops::Mul;
use trajkit::spline::*;
use trajkit::Path;

fn exercise(p: &dyn Path) -> f64 {
    let mut out = [0.0; 8];
    let (a, b) = p.interval();
    let mut s = 0.0;
    for i in 0..=500 {
        let u = a - 0.1 + (b - a + 0.2) * i as f64 / 500.0;
        for order in 0..=5 {
            p.eval(u, order, &mut out);
            s += out[0];
        }
    }
    p.eval(f64::NAN, 2, &mut out);
    s
}

#[test]
fn spline_evaluation_does_not_allocate() {
    let x = [0.0, 0.5, 1.5, 2.0, 3.0, 4.5];
    let y: Vec<f64> = (0..12).map(|k| ((k * 7 % 5) as f64 - 2.0) * 0.5).collect();
    let mut yp = y.clone();
    yp[10] = y[0];
    yp[11] = y[1];
    let z = [0.0, 0.0];
    let v = vec![0.3; 12];
    let curves: Vec<Box<dyn Path>> = vec![
        Box::new(CubicSpline::natural(&x, &y, 2).unwrap()),
        Box::new(CubicSpline::periodic(&x, &yp, 2).unwrap()),
        Box::new(CubicHermiteSpline::new(&x, &y, &v, 2).unwrap()),
        Box::new(QuinticHermiteSpline::new(&x, &y, &v, &v, 2).unwrap()),
        Box::new(PchipSpline::new(&x, &y, 2).unwrap()),
        Box::new(AkimaSpline::modified(&x, &y, 2).unwrap()),
        Box::new(CatmullRom::centripetal(&y, 2).unwrap()),
        Box::new(BSpline::interpolate(&x, &y, 2, 3).unwrap()),
        Box::new(BSpline::minimum_jerk(&x, &y, 2, &z, &z, &z, &z).unwrap()),
        Box::new(BSpline::interpolate(&x, &y, 2, 5).unwrap()),
        Box::new(Bezier::new(&y, 2).unwrap()),
        Box::new(Nurbs::circle([0.0, 0.0], 1.0).unwrap()),
    ];
    for (i, c) in curves.iter().enumerate() {
        exercise(c.as_ref()); // warm-up
        assert_eq!(
            allocations(|| {
                exercise(c.as_ref());
            }),
            0,
            "curve {i} allocates"
        );
    }
    // Arc-length reparameterization (2 components: stack scratch) and batch B-spline evaluation.
    let circle = Nurbs::circle([0.0, 0.0], 1.0).unwrap();
    let al = ArcLength::new(&circle, 1e-9).unwrap();
    assert_eq!(
        allocations(|| {
            exercise(&al);
            let _ = al.param_at(1.0) + al.length_at(0.3);
        }),
        0
    );
    let b = BSpline::interpolate(&x, &y, 2, 3).unwrap();
    let s: Vec<f64> = (0..1000).map(|i| i as f64 * 0.0045).collect();
    let mut out = vec![0.0; 2000];
    assert_eq!(allocations(|| b.eval_many(&s, 0, &mut out)), 0);
    assert_eq!(allocations(|| b.eval_many(&s, 2, &mut out)), 0);
    // Batch evaluation of the piecewise-polynomial curves (sorted, reversed, out of range).
    let mut rev = s.clone();
    rev.reverse();
    rev[7] = f64::NAN;
    for c in curves.iter().take(7) {
        for order in 0..=4 {
            assert_eq!(allocations(|| c.eval_many(&s, order, &mut out)), 0);
            assert_eq!(allocations(|| c.eval_many(&rev, order, &mut out)), 0);
        }
    }
    // Orientation spline.
    let keys = [
        Quat::IDENTITY,
        Quat::exp([0.3, 0.1, 0.0]),
        Quat::exp([0.0, 0.5, -0.2]),
    ];
    let so3 = SO3Spline::interpolate_uniform(0.0, 1.0, &keys).unwrap();
    assert_eq!(
        allocations(|| {
            let mut acc = 0.0;
            for i in 0..100 {
                let (q, w, a) = so3.eval_all(i as f64 * 0.021);
                acc += q.w + w[0] + a[0] + q.mul(keys[1]).x + keys[0].slerp(keys[2], 0.3).y;
            }
            assert!(acc.is_finite());
        }),
        0
    );
}
