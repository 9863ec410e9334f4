//! Interpolating piecewise-polynomial splines on seeded random data: interpolation,
//! continuity, derivatives against finite differences, and the shape-preservation promises of
//! PCHIP and modified Akima (no overshoot between waypoints).

use trajkit::rng::SplitMix64;
use trajkit::spline::*;
use trajkit::Path;

fn data(r: &mut SplitMix64, n: usize, dim: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = vec![r.uniform(-1.0, 1.0)];
    for _ in 1..n {
        let l = *x.last().unwrap();
        x.push(l + r.uniform(0.05, 2.0));
    }
    let y = (0..n * dim).map(|_| r.uniform(-3.0, 3.0)).collect();
    (x, y)
}

/// Every interpolating curve of this module on the data, with its smoothness (C^m).
fn curves(
    r: &mut SplitMix64,
    x: &[f64],
    y: &[f64],
    dim: usize,
) -> Vec<(String, Box<dyn Path>, usize)> {
    let n = x.len();
    let mut yp = y.to_vec();
    yp[(n - 1) * dim..].copy_from_slice(&y[..dim]);
    let v: Vec<f64> = (0..n * dim).map(|_| r.uniform(-2.0, 2.0)).collect();
    let a: Vec<f64> = (0..n * dim).map(|_| r.uniform(-2.0, 2.0)).collect();
    let mut out: Vec<(String, Box<dyn Path>, usize)> = vec![
        (
            "natural".into(),
            Box::new(CubicSpline::natural(x, y, dim).unwrap()),
            2,
        ),
        (
            "clamped".into(),
            Box::new(CubicSpline::clamped(x, y, dim, &v[..dim], &a[..dim]).unwrap()),
            2,
        ),
        (
            "not-a-knot".into(),
            Box::new(CubicSpline::not_a_knot(x, y, dim).unwrap()),
            2,
        ),
        (
            "periodic".into(),
            Box::new(CubicSpline::periodic(x, &yp, dim).unwrap()),
            2,
        ),
        (
            "hermite3".into(),
            Box::new(CubicHermiteSpline::new(x, y, &v, dim).unwrap()),
            1,
        ),
        (
            "hermite5".into(),
            Box::new(QuinticHermiteSpline::new(x, y, &v, &a, dim).unwrap()),
            2,
        ),
        (
            "pchip".into(),
            Box::new(PchipSpline::new(x, y, dim).unwrap()),
            1,
        ),
        (
            "akima".into(),
            Box::new(AkimaSpline::original(x, y, dim).unwrap()),
            1,
        ),
        (
            "makima".into(),
            Box::new(AkimaSpline::modified(x, y, dim).unwrap()),
            1,
        ),
    ];
    if n >= 4 {
        out.push((
            "bspline3".into(),
            Box::new(BSpline::interpolate(x, y, dim, 3).unwrap()),
            2,
        ));
    }
    out
}

#[test]
fn interpolation_continuity_and_finite_differences() {
    let mut r = SplitMix64::new(11);
    for case in 0..40 {
        let n = 2 + case % 9;
        let dim = 1 + case % 3;
        let (x, y) = data(&mut r, n, dim);
        for (name, c, smooth) in curves(&mut r, &x, &y, dim) {
            let mut p = vec![0.0; dim];
            let mut q = vec![0.0; dim];
            for i in 0..n {
                c.eval(x[i], 0, &mut p);
                let want = if name == "periodic" && i == n - 1 {
                    &y[..dim]
                } else {
                    &y[i * dim..(i + 1) * dim]
                };
                for d in 0..dim {
                    assert!(
                        (p[d] - want[d]).abs() < 1e-12 * (1.0 + want[d].abs()),
                        "{name} interpolation"
                    );
                }
            }
            // Continuity at interior breaks up to the promised order.
            for &b in &c.breakpoints()[1..c.breakpoints().len() - 1] {
                // Left limit from just below the break, corrected by the next derivative.
                let h = 1e-9;
                let mut slope = vec![0.0; dim];
                for m in 0..=smooth {
                    c.eval(b - h, m, &mut p);
                    c.eval(b - h, m + 1, &mut slope);
                    c.eval(b, m, &mut q);
                    let scale = p.iter().chain(&q).fold(1.0f64, |s, v| s.max(v.abs()));
                    for d in 0..dim {
                        let left = p[d] + h * slope[d];
                        assert!(
                            (left - q[d]).abs() < 1e-6 * scale + 1e-4 * h * slope[d].abs(),
                            "{name} C{m} at {b}: {left} vs {}",
                            q[d]
                        );
                    }
                }
            }
            // Finite differences away from the breaks, orders 1..=3.
            let br = c.breakpoints();
            for w in br.windows(2) {
                let (a, e) = (w[0], w[1]);
                let h = 1e-5 * (e - a);
                for frac in [0.25, 0.5, 0.8] {
                    let s = a + frac * (e - a);
                    for m in 1..=3 {
                        c.eval(s + h, m - 1, &mut p);
                        c.eval(s - h, m - 1, &mut q);
                        let mut mid = vec![0.0; dim];
                        c.eval(s, m, &mut mid);
                        let scale = p
                            .iter()
                            .chain(&q)
                            .chain(&mid)
                            .fold(1.0f64, |s, v| s.max(v.abs()));
                        for d in 0..dim {
                            let fd = (p[d] - q[d]) / (2.0 * h);
                            assert!(
                                (fd - mid[d]).abs() < 1e-5 * scale,
                                "{name} order {m}: fd {fd} vs {}",
                                mid[d]
                            );
                        }
                    }
                }
            }
        }
    }
}

/// Largest excursion of `c` outside [min, max] of the two waypoints of each piece.
fn overshoot(c: &dyn Path, x: &[f64], y: &[f64], dim: usize) -> f64 {
    let mut worst = 0.0f64;
    let mut p = vec![0.0; dim];
    for i in 0..x.len() - 1 {
        for k in 0..=100 {
            let s = x[i] + (x[i + 1] - x[i]) * k as f64 / 100.0;
            c.eval(s, 0, &mut p);
            for d in 0..dim {
                let (a, b) = (y[i * dim + d], y[(i + 1) * dim + d]);
                worst = worst.max(p[d] - a.max(b)).max(a.min(b) - p[d]);
            }
        }
    }
    worst
}

#[test]
fn pchip_never_overshoots_and_keeps_monotone_data_monotone() {
    let mut r = SplitMix64::new(12);
    for case in 0..100 {
        let n = 2 + case % 12;
        let (x, mut y) = data(&mut r, n, 2);
        let p = PchipSpline::new(&x, &y, 2).unwrap();
        assert!(overshoot(&p, &x, &y, 2) <= 1e-12, "pchip overshoot");
        // Monotone (with flats) in component 0.
        let mut acc = 0.0;
        for i in 0..n {
            if r.below(4) != 0 {
                acc += r.uniform(0.0, 1.0);
            }
            y[i * 2] = acc;
        }
        let p = PchipSpline::new(&x, &y, 2).unwrap();
        let mut v = [0.0; 2];
        for k in 0..=500 {
            let s = x[0] + (x[n - 1] - x[0]) * k as f64 / 500.0;
            p.eval(s, 1, &mut v);
            assert!(v[0] >= -1e-12, "pchip not monotone: slope {}", v[0]);
        }
    }
}

#[test]
fn modified_akima_stays_flat_around_steps() {
    let x: Vec<f64> = (0..10).map(|i| i as f64).collect();
    let y = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0];
    let mk = AkimaSpline::modified(&x, &y, 1).unwrap();
    assert!(overshoot(&mk, &x, &y, 1) <= 1e-15);
    let pc = PchipSpline::new(&x, &y, 1).unwrap();
    assert!(overshoot(&pc, &x, &y, 1) <= 1e-15);
    // The natural cubic spline does overshoot here: the reason shape-preserving splines exist.
    let nat = CubicSpline::natural(&x, &y, 1).unwrap();
    assert!(overshoot(&nat, &x, &y, 1) > 0.01);
}

#[test]
fn splines_serve_as_paths_for_time_parameterization() {
    // σ, σ′, σ″, σ‴ are available through the Path trait; PathAsTrajectory runs it in time.
    use trajkit::{Order, PathAsTrajectory, Trajectory};
    let x = [0.0, 0.5, 1.5, 2.0];
    let y = [0.0, 1.0, 0.5, 2.0, -1.0, 0.0, 0.0, 1.0];
    let sp = CubicSpline::natural(&x, &y, 2).unwrap();
    assert_eq!(sp.breakpoints(), x.to_vec());
    assert_eq!(sp.interval(), (0.0, 2.0));
    let tr = PathAsTrajectory(&sp);
    assert_eq!(tr.duration(), 2.0);
    let mut a = [0.0; 2];
    let mut b = [0.0; 2];
    tr.eval(0.7, Order::Jerk, &mut a);
    sp.eval(0.7, 3, &mut b);
    assert_eq!(a, b);
}
