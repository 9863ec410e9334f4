//! Interpolating cubic splines (C²) with natural, clamped, not-a-knot and periodic end
//! conditions.
//!
//! The spline is found from its slopes at the breaks: one tridiagonal system (cyclic for
//! periodic), solved by banded LU with partial pivoting for all components at once, so
//! construction is O(n · dim). Values agree with scipy's `CubicSpline` with the same `bc_type`
//! within 1e-12 relative (fixtures in `tests/fixtures/spline/`).

use crate::error::{Error, Result};
use crate::spline::banded::Banded;
use crate::spline::ppoly::PiecewisePolynomial;
use crate::spline::validate;

/// A C² cubic spline through points `y` (row-major `n × dim`) at increasing parameters `x`.
///
/// The constructors name the end condition. Evaluation of any derivative order goes through
/// [`crate::Path::eval`] (orders above 3 are zero); the parameter is clamped to
/// `[x[0], x[n−1]]`.
///
/// ```
/// use trajkit::{spline::CubicSpline, Path};
/// // Two joints through three waypoints at s = 0, 1, 2.
/// let sp = CubicSpline::natural(&[0.0, 1.0, 2.0], &[0.0, 0.0, 1.0, 2.0, 0.0, 0.0], 2)?;
/// let mut q = [0.0; 2];
/// sp.eval(1.0, 0, &mut q);
/// assert_eq!(q, [1.0, 2.0]);
/// sp.eval(0.0, 2, &mut q); // natural: zero second derivative at the ends
/// assert!(q[0].abs() < 1e-15 && q[1].abs() < 1e-15);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CubicSpline {
    pp: PiecewisePolynomial,
}

/// One end condition of the slope system.
#[derive(Clone, Copy)]
enum End<'a> {
    Natural,
    Clamped(&'a [f64]),
    NotAKnot,
}

impl CubicSpline {
    /// Natural end conditions: zero second derivative at both ends. At least 2 points.
    pub fn natural(x: &[f64], y: &[f64], dim: usize) -> Result<Self> {
        check(x, y, dim, 2)?;
        Self::solve(x, y, dim, End::Natural, End::Natural)
    }

    /// Clamped end conditions: first derivative `d_start` (length `dim`) at `x[0]` and `d_end`
    /// at `x[n−1]`. At least 2 points.
    pub fn clamped(
        x: &[f64],
        y: &[f64],
        dim: usize,
        d_start: &[f64],
        d_end: &[f64],
    ) -> Result<Self> {
        check(x, y, dim, 2)?;
        validate::values("d_start", d_start, 1, dim)?;
        validate::values("d_end", d_end, 1, dim)?;
        Self::solve(x, y, dim, End::Clamped(d_start), End::Clamped(d_end))
    }

    /// Not-a-knot end conditions: the third derivative is continuous at `x[1]` and `x[n−2]`
    /// (the first two and the last two pieces are one cubic each). With 2 points the spline is
    /// the straight line, with 3 the parabola through them, as in scipy. At least 2 points.
    pub fn not_a_knot(x: &[f64], y: &[f64], dim: usize) -> Result<Self> {
        check(x, y, dim, 2)?;
        let n = x.len();
        if n == 2 {
            let m: Vec<f64> = (0..dim)
                .map(|d| (y[dim + d] - y[d]) / (x[1] - x[0]))
                .collect();
            let mm: Vec<f64> = m.iter().chain(m.iter()).copied().collect();
            return Ok(CubicSpline {
                pp: PiecewisePolynomial::cubic_hermite_unchecked(x, y, &mm, dim),
            });
        }
        if n == 3 {
            // The parabola through the three points, written with its slopes.
            let (h0, h1) = (x[1] - x[0], x[2] - x[1]);
            let mut m = vec![0.0; 3 * dim];
            for d in 0..dim {
                let s0 = (y[dim + d] - y[d]) / h0;
                let s1 = (y[2 * dim + d] - y[dim + d]) / h1;
                let a = (s1 - s0) / (h0 + h1);
                m[d] = s0 - a * h0;
                m[dim + d] = s0 + a * h0;
                m[2 * dim + d] = s1 + a * h1;
            }
            return Ok(CubicSpline {
                pp: PiecewisePolynomial::cubic_hermite_unchecked(x, y, &m, dim),
            });
        }
        Self::solve(x, y, dim, End::NotAKnot, End::NotAKnot)
    }

    /// Periodic end conditions: value, first and second derivatives agree at both ends. The
    /// first row of `y` must equal the last (within 1e-15 absolute + relative, as in scipy).
    /// At least 2 points (2 points give the constant).
    pub fn periodic(x: &[f64], y: &[f64], dim: usize) -> Result<Self> {
        check(x, y, dim, 2)?;
        let n = x.len();
        for d in 0..dim {
            let (a, b) = (y[d], y[(n - 1) * dim + d]);
            if (a - b).abs() > 1e-15 + 1e-15 * b.abs() {
                return Err(Error::InvalidValue {
                    field: format!("y[{}][{d}] (periodic spline: last point)", n - 1),
                    value: b,
                    reason: "differs from the first point",
                });
            }
        }
        let big_n = n - 1; // unknown slopes m_0..m_{N-1}; m_N = m_0
        let h: Vec<f64> = (0..big_n).map(|i| x[i + 1] - x[i]).collect();
        let mut delta = vec![0.0; big_n * dim];
        for i in 0..big_n {
            for d in 0..dim {
                delta[i * dim + d] = (y[(i + 1) * dim + d] - y[i * dim + d]) / h[i];
            }
        }
        let mut m = vec![0.0; n * dim];
        // Two points give the constant: slopes zero.
        if big_n > 1 {
            periodic_slopes(&h, &delta, dim, &mut m)?;
            for d in 0..dim {
                m[big_n * dim + d] = m[d];
            }
        }
        Ok(CubicSpline {
            pp: PiecewisePolynomial::cubic_hermite_unchecked(x, y, &m, dim),
        })
    }

    fn solve(x: &[f64], y: &[f64], dim: usize, start: End<'_>, end: End<'_>) -> Result<Self> {
        let n = x.len();
        let h: Vec<f64> = (0..n - 1).map(|i| x[i + 1] - x[i]).collect();
        let mut delta = vec![0.0; (n - 1) * dim];
        for i in 0..n - 1 {
            for d in 0..dim {
                delta[i * dim + d] = (y[(i + 1) * dim + d] - y[i * dim + d]) / h[i];
            }
        }
        let mut a = Banded::zeros(n, 1, 1);
        let mut b = vec![0.0; n * dim];
        for i in 1..n - 1 {
            a.set(i, i - 1, h[i]);
            a.set(i, i, 2.0 * (h[i - 1] + h[i]));
            a.set(i, i + 1, h[i - 1]);
            for d in 0..dim {
                b[i * dim + d] =
                    3.0 * (h[i] * delta[(i - 1) * dim + d] + h[i - 1] * delta[i * dim + d]);
            }
        }
        match start {
            End::Natural => {
                a.set(0, 0, 2.0);
                a.set(0, 1, 1.0);
                for d in 0..dim {
                    b[d] = 3.0 * delta[d];
                }
            }
            End::Clamped(v) => {
                a.set(0, 0, 1.0);
                b[..dim].copy_from_slice(v);
            }
            End::NotAKnot => {
                let s = x[2] - x[0];
                a.set(0, 0, h[1]);
                a.set(0, 1, s);
                for d in 0..dim {
                    b[d] = ((h[0] + 2.0 * s) * h[1] * delta[d] + h[0] * h[0] * delta[dim + d]) / s;
                }
            }
        }
        let l = n - 1;
        match end {
            End::Natural => {
                a.set(l, l, 2.0);
                a.set(l, l - 1, 1.0);
                for d in 0..dim {
                    b[l * dim + d] = 3.0 * delta[(l - 1) * dim + d];
                }
            }
            End::Clamped(v) => {
                a.set(l, l, 1.0);
                b[l * dim..].copy_from_slice(v);
            }
            End::NotAKnot => {
                let s = x[l] - x[l - 2];
                let (hl, hp) = (h[l - 1], h[l - 2]);
                a.set(l, l, hp);
                a.set(l, l - 1, s);
                for d in 0..dim {
                    b[l * dim + d] = (hl * hl * delta[(l - 2) * dim + d]
                        + (2.0 * s + hl) * hp * delta[(l - 1) * dim + d])
                        / s;
                }
            }
        }
        a.factor().map_err(|_| singular())?;
        a.solve(&mut b, dim);
        Ok(CubicSpline {
            pp: PiecewisePolynomial::cubic_hermite_unchecked(x, y, &b, dim),
        })
    }
}

crate::spline::ppoly_backed!(CubicSpline);

use crate::spline::validate::interpolation_data as check;

fn singular() -> Error {
    Error::Infeasible("cubic spline: the slope system is singular".into())
}

/// The slopes m_0..m_{N−1} of the periodic cubic spline (N = `h.len()` ≥ 2 intervals, `delta`
/// their divided differences, row-major with `dim` columns) into the first N rows of `m`.
///
/// Row i: h_i m_{i-1} + 2(h_{i-1} + h_i) m_i + h_{i-1} m_{i+1} = 3 (h_i δ_{i-1} + h_{i-1} δ_i),
/// indices cyclic.
fn periodic_slopes(h: &[f64], delta: &[f64], dim: usize, m: &mut [f64]) -> Result<()> {
    let big_n = h.len();
    let prev = |i: usize| if i == 0 { big_n - 1 } else { i - 1 };
    let mut rhs = vec![0.0; big_n * dim];
    for i in 0..big_n {
        let p = prev(i);
        for d in 0..dim {
            rhs[i * dim + d] = 3.0 * (h[i] * delta[p * dim + d] + h[p] * delta[i * dim + d]);
        }
    }
    let diag = |i: usize| 2.0 * (h[prev(i)] + h[i]);
    if big_n == 2 {
        // Both neighbours of each unknown are the other one.
        let (a00, a01) = (diag(0), h[1] + h[0]);
        let (a10, a11) = (h[1] + h[0], diag(1));
        let det = a00 * a11 - a01 * a10;
        for d in 0..dim {
            let (r0, r1) = (rhs[d], rhs[dim + d]);
            m[d] = (r0 * a11 - a01 * r1) / det;
            m[dim + d] = (a00 * r1 - a10 * r0) / det;
        }
        Ok(())
    } else {
        cyclic_solve(h, &rhs, dim, m)
    }
}

/// The cyclic tridiagonal system of [`periodic_slopes`] for N ≥ 3 by Sherman–Morrison:
/// A = T + u vᵀ with u = (γ, 0, …, 0, α), v = (1, 0, …, 0, β/γ), α = A[N−1][0] (the m_N = m_0
/// term of row N−1) = h_{N−2}, β = A[0][N−1] (the m_{−1} = m_{N−1} term of row 0) = h_0.
fn cyclic_solve(h: &[f64], rhs: &[f64], dim: usize, m: &mut [f64]) -> Result<()> {
    let nn = h.len();
    let prev = |i: usize| if i == 0 { nn - 1 } else { i - 1 };
    let diag = |i: usize| 2.0 * (h[prev(i)] + h[i]);
    let alpha = h[nn - 2];
    let beta = h[0];
    let gamma = -diag(0);
    let mut t = Banded::zeros(nn, 1, 1);
    for i in 0..nn {
        let mut di = diag(i);
        if i == 0 {
            di -= gamma;
        }
        if i == nn - 1 {
            di -= alpha * beta / gamma;
        }
        t.set(i, i, di);
        if i > 0 {
            t.set(i, i - 1, h[i]);
        }
        if i + 1 < nn {
            t.set(i, i + 1, h[prev(i)]);
        }
    }
    t.factor().map_err(|_| singular())?;
    // Solve for all components and u at once: columns 0..dim are rhs, column dim is u.
    let w = dim + 1;
    let mut b = vec![0.0; nn * w];
    for i in 0..nn {
        b[i * w..i * w + dim].copy_from_slice(&rhs[i * dim..(i + 1) * dim]);
    }
    b[dim] = gamma;
    b[(nn - 1) * w + dim] = alpha;
    t.solve(&mut b, w);
    let vz = b[dim] + beta / gamma * b[(nn - 1) * w + dim];
    for d in 0..dim {
        let vy = b[d] + beta / gamma * b[(nn - 1) * w + d];
        let f = vy / (1.0 + vz);
        for i in 0..nn {
            m[i * dim + d] = b[i * w + d] - f * b[i * w + dim];
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use crate::Path;

    fn data(n: usize, dim: usize, seed: u64) -> (Vec<f64>, Vec<f64>) {
        let mut r = SplitMix64::new(seed);
        let mut x = vec![0.0];
        for _ in 1..n {
            let l = *x.last().unwrap();
            x.push(l + r.uniform(0.1, 2.0));
        }
        let y = (0..n * dim).map(|_| r.uniform(-3.0, 3.0)).collect();
        (x, y)
    }

    fn all(x: &[f64], y: &[f64], dim: usize) -> Vec<(&'static str, CubicSpline)> {
        let n = x.len();
        let mut yp = y.to_vec();
        yp[(n - 1) * dim..].copy_from_slice(&y[..dim]);
        let ds: Vec<f64> = (0..dim).map(|d| d as f64 - 0.5).collect();
        let de: Vec<f64> = (0..dim).map(|d| 1.0 - d as f64).collect();
        vec![
            ("natural", CubicSpline::natural(x, y, dim).unwrap()),
            (
                "clamped",
                CubicSpline::clamped(x, y, dim, &ds, &de).unwrap(),
            ),
            ("not-a-knot", CubicSpline::not_a_knot(x, y, dim).unwrap()),
            ("periodic", CubicSpline::periodic(x, &yp, dim).unwrap()),
        ]
    }

    #[test]
    fn interpolates_and_is_c2_for_every_end_condition() {
        for n in 2..9 {
            let dim = 3;
            let (x, y) = data(n, dim, n as u64);
            for (name, sp) in all(&x, &y, dim) {
                let mut a = vec![0.0; dim];
                let mut b = vec![0.0; dim];
                for i in 0..n {
                    sp.eval(x[i], 0, &mut a);
                    for d in 0..dim {
                        let want = if name == "periodic" && i == n - 1 {
                            y[d]
                        } else {
                            y[i * dim + d]
                        };
                        assert!((a[d] - want).abs() < 1e-12, "{name} n={n} i={i}");
                    }
                }
                for i in 1..n - 1 {
                    for ord in 0..3 {
                        sp.pp.eval_piece(i - 1, x[i], ord, &mut a);
                        sp.pp.eval_piece(i, x[i], ord, &mut b);
                        for d in 0..dim {
                            assert!(
                                (a[d] - b[d]).abs() < 1e-9 * (1.0 + a[d].abs()),
                                "{name} n={n} ord={ord}"
                            );
                        }
                    }
                }
                let (s0, s1) = sp.interval();
                match name {
                    "natural" => {
                        sp.eval(s0, 2, &mut a);
                        sp.eval(s1, 2, &mut b);
                        assert!(a.iter().chain(&b).all(|v| v.abs() < 1e-10), "{n}");
                    }
                    "clamped" => {
                        sp.eval(s0, 1, &mut a);
                        sp.eval(s1, 1, &mut b);
                        for d in 0..dim {
                            assert!((a[d] - (d as f64 - 0.5)).abs() < 1e-12);
                            assert!((b[d] - (1.0 - d as f64)).abs() < 1e-12);
                        }
                    }
                    "periodic" if n > 2 => {
                        for ord in 1..3 {
                            sp.eval(s0, ord, &mut a);
                            sp.eval(s1, ord, &mut b);
                            for d in 0..dim {
                                assert!(
                                    (a[d] - b[d]).abs() < 1e-9 * (1.0 + a[d].abs()),
                                    "periodic n={n} ord={ord}"
                                );
                            }
                        }
                    }
                    "not-a-knot" if n > 3 => {
                        for &i in &[1, n - 2] {
                            sp.pp.eval_piece(i - 1, x[i], 3, &mut a);
                            sp.pp.eval_piece(i, x[i], 3, &mut b);
                            for d in 0..dim {
                                assert!(
                                    (a[d] - b[d]).abs() < 1e-8 * (1.0 + a[d].abs()),
                                    "nak n={n}"
                                );
                            }
                        }
                    }
                    _ => {}
                }
            }
        }
    }

    #[test]
    fn reproduces_cubics_exactly() {
        // Not-a-knot and clamped (with the true end slopes) reproduce any cubic.
        let f = |s: f64| 1.0 - 2.0 * s + 0.5 * s * s - 0.25 * s * s * s;
        let df = |s: f64| -2.0 + s - 0.75 * s * s;
        let x = [0.0, 0.4, 1.5, 2.0, 3.1, 4.0];
        let y: Vec<f64> = x.iter().map(|&s| f(s)).collect();
        let a = CubicSpline::not_a_knot(&x, &y, 1).unwrap();
        let b = CubicSpline::clamped(&x, &y, 1, &[df(0.0)], &[df(4.0)]).unwrap();
        let mut o = [0.0];
        for k in 0..=40 {
            let s = k as f64 * 0.1;
            for sp in [&a, &b] {
                sp.eval(s, 0, &mut o);
                assert!((o[0] - f(s)).abs() < 1e-12);
                sp.eval(s, 1, &mut o);
                assert!((o[0] - df(s)).abs() < 1e-12);
                sp.eval(s, 3, &mut o);
                assert!((o[0] + 1.5).abs() < 1e-11);
                sp.eval(s, 4, &mut o);
                assert_eq!(o[0], 0.0);
            }
        }
    }

    #[test]
    fn out_of_range_is_clamped_and_nan_propagates() {
        let sp = CubicSpline::natural(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0], 1).unwrap();
        let mut a = [0.0];
        let mut b = [0.0];
        for ord in 0..4 {
            sp.eval(-5.0, ord, &mut a);
            sp.eval(0.0, ord, &mut b);
            assert_eq!(a, b);
            sp.eval(7.0, ord, &mut a);
            sp.eval(2.0, ord, &mut b);
            assert_eq!(a, b);
            sp.eval(f64::NAN, ord, &mut a);
            assert!(a[0].is_nan());
        }
    }

    #[test]
    fn bad_input_is_a_typed_error() {
        let x = [0.0, 1.0, 2.0];
        assert!(matches!(
            CubicSpline::natural(&[0.0], &[1.0], 1),
            Err(Error::TooFewWaypoints { .. })
        ));
        assert!(matches!(
            CubicSpline::natural(&[0.0, 1.0, 1.0], &[0.0; 3], 1),
            Err(Error::DuplicateWaypoint { index: 2 })
        ));
        assert!(matches!(
            CubicSpline::natural(&[0.0, 2.0, 1.0], &[0.0; 3], 1),
            Err(Error::InvalidValue { .. })
        ));
        assert!(matches!(
            CubicSpline::natural(&x, &[0.0; 5], 2),
            Err(Error::DimensionMismatch { .. })
        ));
        assert!(matches!(
            CubicSpline::natural(&x, &[0.0, f64::NAN, 1.0], 1),
            Err(Error::InvalidValue { .. })
        ));
        assert!(matches!(
            CubicSpline::natural(&[0.0, f64::NAN, 1.0], &[0.0; 3], 1),
            Err(Error::InvalidValue { .. })
        ));
        assert!(matches!(
            CubicSpline::natural(&x, &[], 0),
            Err(Error::DimensionMismatch { .. })
        ));
        assert!(matches!(
            CubicSpline::clamped(&x, &[0.0; 3], 1, &[0.0, 1.0], &[0.0]),
            Err(Error::DimensionMismatch { .. })
        ));
        assert!(matches!(
            CubicSpline::clamped(&x, &[0.0; 3], 1, &[0.0], &[f64::INFINITY]),
            Err(Error::InvalidValue { .. })
        ));
        let e = CubicSpline::periodic(&x, &[0.0, 1.0, 0.5], 1).unwrap_err();
        assert!(
            e.to_string().contains("differs from the first point"),
            "{e}"
        );
    }

    #[test]
    fn ten_thousand_waypoints_construct_quickly() {
        let (x, y) = data(10_000, 7, 99);
        let t = std::time::Instant::now();
        let sp = CubicSpline::not_a_knot(&x, &y, 7).unwrap();
        let mut yp = y.clone();
        yp[9_999 * 7..].copy_from_slice(&y[..7]);
        let _ = CubicSpline::periodic(&x, &yp, 7).unwrap();
        assert!(t.elapsed().as_secs_f64() < 2.0);
        let mut o = [0.0; 7];
        sp.eval(x[5000], 0, &mut o);
        assert!((o[3] - y[5000 * 7 + 3]).abs() < 1e-12);
    }
}
