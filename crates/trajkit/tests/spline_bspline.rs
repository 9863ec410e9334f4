//! B-spline properties on seeded random cases: partition of unity, non-negativity, local
//! support, convex hull, derivatives against finite differences, representation changes that
//! keep the curve (knot insertion, degree elevation, clamping), batch evaluation, the design
//! matrix, minimum-jerk/minimum-snap optimality and bad input.

use trajkit::rng::SplitMix64;
use trajkit::spline::{BSpline, EndDerivative, QuinticHermiteSpline};
use trajkit::{Error, Path};

/// A random B-spline of degree `k`: clamped or not, with repeated interior knots sometimes.
fn random_bspline(r: &mut SplitMix64, k: usize, dim: usize, clamped: bool) -> BSpline {
    let n = k + 1 + r.below(8) as usize;
    let mut t: Vec<f64> = if clamped {
        let mut inner: Vec<f64> = (0..n - k - 1).map(|_| r.uniform(0.0, 3.0)).collect();
        if k >= 2 && inner.len() >= 2 && r.below(3) == 0 {
            inner[1] = inner[0]; // a double knot
        }
        inner.sort_by(f64::total_cmp);
        let mut t = vec![0.0; k + 1];
        t.extend(inner);
        t.extend(std::iter::repeat_n(3.0, k + 1));
        t
    } else {
        (0..n + k + 1).map(|_| r.uniform(-1.0, 4.0)).collect()
    };
    t.sort_by(f64::total_cmp);
    let c: Vec<f64> = (0..n * dim).map(|_| r.uniform(-2.0, 2.0)).collect();
    BSpline::new(&t, &c, dim, k).unwrap()
}

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    let scale = a.iter().chain(b).fold(1.0f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol * scale)
}

#[test]
fn partition_of_unity_nonnegativity_local_support_and_convex_hull() {
    let mut r = SplitMix64::new(1);
    for case in 0..200 {
        let k = case % 8;
        let b = random_bspline(&mut r, k, 3, case % 3 != 0);
        let (a, e) = b.domain();
        let mut w = vec![0.0; k + 1];
        let mut p = [0.0; 3];
        for _ in 0..20 {
            let s = r.uniform(a, e);
            let f = b.basis(s, 0, &mut w);
            let sum: f64 = w.iter().sum();
            assert!((sum - 1.0).abs() < 1e-14, "k={k} sum={sum}");
            assert!(w.iter().all(|&v| v >= -1e-15), "k={k} negative basis {w:?}");
            // Convex hull: the point is inside the bounding box of its k + 1 control points.
            b.eval(s, 0, &mut p);
            let c = b.control_points();
            for d in 0..3 {
                let lo = (f..=f + k)
                    .map(|j| c[j * 3 + d])
                    .fold(f64::INFINITY, f64::min);
                let hi = (f..=f + k)
                    .map(|j| c[j * 3 + d])
                    .fold(f64::NEG_INFINITY, f64::max);
                assert!(
                    p[d] >= lo - 1e-12 && p[d] <= hi + 1e-12,
                    "k={k} convex hull"
                );
            }
            // Local support: moving a control point outside f..=f+k changes nothing at s.
            let n = b.num_control_points();
            if let Some(j) = (0..n).find(|&j| j < f || j > f + k) {
                let mut c2 = c.to_vec();
                c2[j * 3] += 10.0;
                let b2 = BSpline::new(b.knots(), &c2, 3, k).unwrap();
                let mut q = [0.0; 3];
                b2.eval(s, 0, &mut q);
                assert_eq!(p, q, "k={k} local support");
            }
        }
    }
}

#[test]
fn derivatives_agree_with_finite_differences_and_the_hodograph() {
    let mut r = SplitMix64::new(2);
    for case in 0..120 {
        let k = 1 + case % 7;
        let b = random_bspline(&mut r, k, 2, case % 2 == 0);
        let (a, e) = b.domain();
        let knots = b.knots().to_vec();
        let mut lo = [0.0; 2];
        let mut hi = [0.0; 2];
        let mut mid = [0.0; 2];
        for _ in 0..10 {
            let s = r.uniform(a, e);
            // Stay away from knots, where derivatives of order k may jump.
            let h = 1e-6 * (e - a);
            if knots.iter().any(|&t| (t - s).abs() < 10.0 * h) {
                continue;
            }
            for m in 1..=k + 1 {
                b.eval(s - h, m - 1, &mut lo);
                b.eval(s + h, m - 1, &mut hi);
                b.eval(s, m, &mut mid);
                let scale = [lo, hi, mid]
                    .iter()
                    .flatten()
                    .fold(1.0f64, |x, v| x.max(v.abs()));
                for d in 0..2 {
                    let fd = (hi[d] - lo[d]) / (2.0 * h);
                    assert!(
                        (fd - mid[d]).abs() < 2e-5 * scale,
                        "k={k} m={m}: fd {fd} vs {}",
                        mid[d]
                    );
                }
                let hod = b.derivative(m);
                let mut via = [0.0; 2];
                hod.eval(s, 0, &mut via);
                assert!(close(&via, &mid, 1e-11), "k={k} m={m} hodograph");
            }
        }
    }
}

#[test]
fn insertion_elevation_and_clamping_keep_the_curve() {
    let mut r = SplitMix64::new(3);
    for case in 0..80 {
        let k = case % 6;
        let b = random_bspline(&mut r, k, 2, case % 2 == 0);
        let (a, e) = b.domain();
        let ins = b
            .insert_knot(r.uniform(a, e), 1 + r.below(k.min(2) as u64) as usize)
            .unwrap();
        let cl = b.to_clamped();
        // Degree 0 is discontinuous everywhere: elevating it is refused.
        let el = if k == 0 {
            b.clone()
        } else {
            b.elevate_degree(1 + r.below(2) as usize).unwrap()
        };
        assert_eq!(cl.domain(), (a, e));
        let mut p = [0.0; 2];
        let mut q = [0.0; 2];
        for i in 0..=50 {
            let s = a + (e - a) * i as f64 / 50.0;
            b.eval(s, 0, &mut p);
            for (name, other) in [("insert", &ins), ("clamp", &cl), ("elevate", &el)] {
                other.eval(s, 0, &mut q);
                assert!(close(&p, &q, 1e-11), "k={k} {name} at {s}: {p:?} vs {q:?}");
            }
        }
    }
}

#[test]
fn batch_evaluation_and_design_matrix_agree_with_pointwise_evaluation() {
    let mut r = SplitMix64::new(4);
    for case in 0..60 {
        let k = case % 8;
        let dim = if case % 5 == 0 { 17 } else { 1 + case % 4 }; // 17: the wide-path code
        let b = random_bspline(&mut r, k, dim, case % 2 == 0);
        let (a, e) = b.domain();
        let mut s: Vec<f64> = (0..200).map(|_| r.uniform(a - 0.5, e + 0.5)).collect();
        if case % 3 != 0 {
            s.sort_by(f64::total_cmp);
        }
        s.push(a);
        s.push(e);
        for order in 0..4 {
            let mut many = vec![0.0; s.len() * dim];
            b.eval_many(&s, order, &mut many);
            let dm = b.design_matrix(&s, order);
            let mut via = vec![0.0; s.len() * dim];
            dm.apply(b.control_points(), dim, &mut via);
            let mut one = vec![0.0; dim];
            for (i, &si) in s.iter().enumerate() {
                b.eval(si, order, &mut one);
                assert!(
                    close(&one, &many[i * dim..(i + 1) * dim], 1e-13),
                    "k={k} dim={dim} order={order} s={si} domain={:?}: {one:?} vs {:?}",
                    b.domain(),
                    &many[i * dim..(i + 1) * dim]
                );
                assert!(
                    close(&one, &via[i * dim..(i + 1) * dim], 1e-13),
                    "k={k} design"
                );
            }
        }
    }
}

#[test]
fn evaluation_never_panics_and_clamps() {
    let mut r = SplitMix64::new(5);
    let b = random_bspline(&mut r, 3, 2, false);
    let (a, e) = b.domain();
    let mut p = [0.0; 2];
    let mut q = [0.0; 2];
    for order in [0, 1, 2, 3, 4, 50] {
        b.eval(f64::NEG_INFINITY, order, &mut p);
        b.eval(a, order, &mut q);
        assert_eq!(p, q);
        b.eval(1e300, order, &mut p);
        b.eval(e, order, &mut q);
        assert_eq!(p, q);
        b.eval(f64::NAN, order, &mut p);
        assert!(p.iter().all(|v| v.is_nan()));
    }
    let mut many = [0.0; 6];
    b.eval_many(&[f64::NAN, -1e9, 1e9], 0, &mut many);
    assert!(many[0].is_nan() && many[2].is_finite() && many[4].is_finite());
}

/// ∫ ‖σ^(m)‖² over [a, b] by 8-point Gauss–Legendre on each piece between breakpoints.
fn energy(p: &dyn Path, m: usize) -> f64 {
    const X: [f64; 4] = [
        0.1834346424956498,
        0.525_532_409_916_329,
        0.7966664774136267,
        0.9602898564975363,
    ];
    const W: [f64; 4] = [
        0.362_683_783_378_362,
        0.3137066458778873,
        0.2223810344533745,
        0.1012285362903763,
    ];
    let br = p.breakpoints();
    let mut v = vec![0.0; p.dim()];
    let mut sum = 0.0;
    for w in br.windows(2) {
        let (c, h) = (0.5 * (w[0] + w[1]), 0.5 * (w[1] - w[0]));
        for i in 0..4 {
            for sgn in [-1.0, 1.0] {
                // Evaluate inside the piece (the right-hand piece is used at a break).
                p.eval(c + sgn * h * X[i], m, &mut v);
                sum += W[i] * h * v.iter().map(|x| x * x).sum::<f64>();
            }
        }
    }
    sum
}

#[test]
fn minimum_jerk_and_minimum_snap_are_optimal_and_smooth() {
    let mut r = SplitMix64::new(6);
    for case in 0..10 {
        let n = 2 + case % 6;
        let dim = 2;
        let mut x = vec![0.0];
        for _ in 1..n {
            let l = *x.last().unwrap();
            x.push(l + r.uniform(0.3, 1.5));
        }
        let y: Vec<f64> = (0..n * dim).map(|_| r.uniform(-1.0, 1.0)).collect();
        let ends: Vec<Vec<f64>> = (0..6)
            .map(|_| (0..dim).map(|_| r.uniform(-1.0, 1.0)).collect())
            .collect();
        let mj =
            BSpline::minimum_jerk(&x, &y, dim, &ends[0], &ends[1], &ends[2], &ends[3]).unwrap();
        let ms = BSpline::minimum_snap(
            &x,
            &y,
            dim,
            [&ends[0], &ends[1], &ends[4]],
            [&ends[2], &ends[3], &ends[5]],
        )
        .unwrap();
        let mut v = vec![0.0; dim];
        let mut w = vec![0.0; dim];
        // Interpolation, end conditions, continuity of derivatives up to degree − 1.
        for (sp, deg) in [(&mj, 5usize), (&ms, 7)] {
            for i in 0..n {
                sp.eval(x[i], 0, &mut v);
                assert!(close(&v, &y[i * dim..(i + 1) * dim], 1e-12));
            }
            sp.eval(x[0], 1, &mut v);
            assert!(close(&v, &ends[0], 1e-11));
            sp.eval(x[n - 1], 2, &mut v);
            assert!(close(&v, &ends[3], 1e-10));
            for i in 1..n - 1 {
                for m in 0..deg {
                    sp.eval(x[i] - 1e-13, m, &mut v);
                    sp.eval(x[i], m, &mut w);
                    assert!(close(&v, &w, 1e-7), "deg {deg} C{m} at break {i}");
                }
            }
        }
        ms.eval(x[n - 1], 3, &mut v);
        assert!(close(&v, &ends[5], 1e-9));
        // Optimality: the quintic Hermite through the same points with the minimum-jerk
        // spline's own interior velocities/accelerations is the same curve; perturbing them
        // only increases ∫‖jerk‖².
        let mut vel = vec![0.0; n * dim];
        let mut acc = vec![0.0; n * dim];
        for i in 0..n {
            mj.eval(x[i], 1, &mut vel[i * dim..(i + 1) * dim]);
            mj.eval(x[i], 2, &mut acc[i * dim..(i + 1) * dim]);
        }
        let base = QuinticHermiteSpline::new(&x, &y, &vel, &acc, dim).unwrap();
        let j0 = energy(&mj, 3);
        assert!((energy(&base, 3) - j0).abs() <= 1e-10 * j0.max(1.0));
        if n > 2 {
            for _ in 0..5 {
                let (mut v2, mut a2) = (vel.clone(), acc.clone());
                let i = 1 + r.below((n - 2) as u64) as usize;
                v2[i * dim] += r.uniform(-1e-3, 1e-3);
                a2[i * dim + 1] += r.uniform(-1e-3, 1e-3);
                let other = QuinticHermiteSpline::new(&x, &y, &v2, &a2, dim).unwrap();
                assert!(energy(&other, 3) > j0, "min-jerk is not minimal");
            }
        }
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let t = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
    let c = [0.0; 8];
    // Non-monotone knots, NaN knots, wrong counts, too few control points, empty domain.
    assert!(matches!(
        BSpline::new(&[0.0, 0.0, 0.0, 0.7, 0.5, 1.0, 1.0], &c, 2, 2),
        Err(Error::InvalidValue { .. })
    ));
    assert!(matches!(
        BSpline::new(&[0.0, 0.0, 0.0, f64::NAN, 1.0, 1.0, 1.0], &c, 2, 2),
        Err(Error::InvalidValue { .. })
    ));
    assert!(matches!(
        BSpline::new(&t[..6], &c, 2, 2),
        Err(Error::DimensionMismatch { .. })
    ));
    assert!(matches!(
        BSpline::new(&t, &c[..7], 2, 2),
        Err(Error::DimensionMismatch { .. })
    ));
    assert!(matches!(
        BSpline::new(&[0.0, 0.0, 1.0, 1.0], &[0.0, 0.0], 1, 2),
        Err(Error::TooFewWaypoints {
            needed: 3,
            found: 2
        })
    ));
    assert!(matches!(
        BSpline::new(&[0.0; 7], &c, 2, 2),
        Err(Error::InvalidValue { .. })
    ));
    let mut cn = c;
    cn[3] = f64::INFINITY;
    assert!(matches!(
        BSpline::new(&t, &cn, 2, 2),
        Err(Error::InvalidValue { .. })
    ));
    assert!(BSpline::new(&[0.0; 50], &[0.0; 25], 1, 24).is_err());
    // Interpolation: duplicates, too few points, bad end conditions.
    let x = [0.0, 1.0, 1.0, 2.0];
    assert!(matches!(
        BSpline::interpolate(&x, &[0.0; 4], 1, 3),
        Err(Error::DuplicateWaypoint { index: 2 })
    ));
    assert!(matches!(
        BSpline::interpolate(&[0.0, 1.0, 2.0], &[0.0; 3], 1, 3),
        Err(Error::TooFewWaypoints {
            needed: 4,
            found: 3
        })
    ));
    let z = [0.0];
    let e = [EndDerivative {
        order: 1,
        value: &z,
    }];
    assert!(matches!(
        BSpline::interpolate_with_ends(&[0.0, 1.0, 2.0], &[0.0; 3], 1, 5, &e, &e),
        Err(Error::DimensionMismatch { .. })
    ));
    assert!(matches!(
        BSpline::minimum_jerk(&[0.0, 1.0], &[0.0; 4], 2, &z, &z, &z, &z),
        Err(Error::DimensionMismatch { .. })
    ));
    // Elevating a discontinuous curve.
    let disc = BSpline::new(&[0.0, 0.0, 0.5, 0.5, 1.0, 1.0], &[0.0, 1.0, 2.0, 3.0], 1, 1).unwrap();
    assert!(matches!(
        disc.elevate_degree(1),
        Err(Error::InvalidValue { .. })
    ));
    // Least squares with data that leave a basis function without support.
    let kn = [0.0, 0.0, 0.0, 0.0, 0.5, 0.6, 1.0, 1.0, 1.0, 1.0];
    let xs: Vec<f64> = (0..20).map(|i| 0.015 * i as f64).collect(); // nothing past 0.3
    assert!(BSpline::least_squares(&xs, &[1.0; 20], 1, &kn, 3, None).is_err());
    assert!(matches!(
        BSpline::least_squares(&[2.0], &[1.0], 1, &kn, 3, None),
        Err(Error::InvalidValue { .. })
    ));
}

/// The long seeded suite (run with `cargo test --release -- --ignored`): interpolation of every
/// degree 1..=9 through random data reproduces the data, and minimum-jerk/snap hit their end
/// conditions, on 20 000 cases.
#[test]
#[ignore]
fn long_random_interpolation_suite() {
    let mut r = SplitMix64::new(77);
    for case in 0..20_000 {
        let k = 1 + case % 9;
        let n = k + 1 + r.below(30) as usize;
        let dim = 1 + r.below(4) as usize;
        let mut x = vec![r.uniform(-5.0, 5.0)];
        for _ in 1..n {
            let l = *x.last().unwrap();
            x.push(l + r.uniform(0.01, 3.0));
        }
        let y: Vec<f64> = (0..n * dim).map(|_| r.uniform(-10.0, 10.0)).collect();
        let b = BSpline::interpolate(&x, &y, dim, k).unwrap();
        let mut p = vec![0.0; dim];
        for i in 0..n {
            b.eval(x[i], 0, &mut p);
            assert!(
                close(&p, &y[i * dim..(i + 1) * dim], 1e-8),
                "case {case} k={k} n={n}"
            );
        }
        let z = vec![0.0; dim];
        let mj = BSpline::minimum_jerk(&x, &y, dim, &z, &z, &z, &z).unwrap();
        mj.eval(x[n - 1], 1, &mut p);
        assert!(
            p.iter().all(|v| v.abs() < 1e-6),
            "case {case} minimum jerk end velocity {p:?}"
        );
    }
}
