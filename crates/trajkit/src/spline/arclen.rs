//! Arc length of any [`Path`], its inverse, and arc-length reparameterization.

use crate::error::{Error, Result};
use crate::spline::ppoly::{quintic_coeffs, PiecewisePolynomial};
use crate::Path;

/// 8-point Gauss–Legendre nodes on [−1, 1] (positive half) and weights.
pub(crate) const GX: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
pub(crate) const GW: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// Components up to which evaluation uses stack scratch; wider paths allocate per call.
const STACK_DIM: usize = 64;

/// Runs `f` with three scratch vectors of length `dim`: on the stack up to [`STACK_DIM`]
/// components, on the heap above.
fn with_scratch<R>(dim: usize, f: impl FnOnce(&mut [f64], &mut [f64], &mut [f64]) -> R) -> R {
    if dim <= STACK_DIM {
        let mut a = [0.0; STACK_DIM];
        let mut b = [0.0; STACK_DIM];
        let mut c = [0.0; STACK_DIM];
        f(&mut a[..dim], &mut b[..dim], &mut c[..dim])
    } else {
        let mut v = vec![0.0; 3 * dim];
        let (a, rest) = v.split_at_mut(dim);
        let (b, c) = rest.split_at_mut(dim);
        f(a, b, c)
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// An accepted subinterval `[u0, u1]` of the path parameter: its length `h`, and du/ds and
/// d²u/ds² at both ends from inside.
#[derive(Debug, Clone, Copy)]
struct Accepted {
    h: f64,
    u0: f64,
    u1: f64,
    v0: f64,
    v1: f64,
    a0: f64,
    a1: f64,
}

/// The speed ‖σ′(u)‖ (`d` is scratch of length `dim`).
fn speed<P: Path>(path: &P, u: f64, d: &mut [f64]) -> f64 {
    path.eval(u, 1, d);
    norm(d)
}

/// 8-point Gauss–Legendre length of `[a, b]`.
fn gl<P: Path>(path: &P, a: f64, b: f64, d: &mut [f64]) -> f64 {
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    let mut s = 0.0;
    for i in 0..4 {
        s += GW[i] * (speed(path, c - h * GX[i], d) + speed(path, c + h * GX[i], d));
    }
    s * h
}

/// du/ds and d²u/ds² of the inverse u(s) at u, from the side the evaluation lands on; a zero
/// or non-finite speed is a typed error.
fn inverse_derivs<P: Path>(path: &P, u: f64, d1: &mut [f64], d2: &mut [f64]) -> Result<(f64, f64)> {
    path.eval(u, 1, d1);
    path.eval(u, 2, d2);
    let g = norm(d1);
    if !(g > 0.0 && g.is_finite()) {
        return Err(Error::InvalidValue {
            field: format!("path speed |σ′| at parameter {u}"),
            value: g,
            reason:
                "is zero or not finite: arc length parameterization needs a path that does not stop",
        });
    }
    let gu = dot(d1, d2) / g;
    Ok((1.0 / g, -gu / (g * g * g)))
}

/// Bisects the smooth piece `[a, b]` of the path until Gauss–Legendre agrees with the two
/// halves within the subinterval's share of `tol` and the quintic model of u(s) hits the
/// quarter points within `tol / 5` (or depth 60); appends the accepted subintervals in
/// increasing order.
#[allow(clippy::too_many_arguments)]
fn subdivide_piece<P: Path>(
    path: &P,
    a: f64,
    b: f64,
    tol: f64,
    span: f64,
    d1: &mut [f64],
    d2: &mut [f64],
    out: &mut Vec<Accepted>,
) -> Result<()> {
    // Left-limit derivatives at b: evaluate just inside the piece.
    let b_in = b - (b - a) * 1e-12;
    let mut stack = vec![(a, b, 0usize)];
    while let Some((x0, x1, depth)) = stack.pop() {
        let whole = gl(path, x0, x1, d1);
        let xm = 0.5 * (x0 + x1);
        let left = gl(path, x0, xm, d1);
        let right = gl(path, xm, x1, d1);
        let share = tol * (x1 - x0) / span;
        let mut ok = (whole - left - right).abs() <= 0.1 * share || depth >= 60;
        let (v0, a0) = inverse_derivs(path, x0, d1, d2)?;
        let xe = if x1 == b { b_in } else { x1 };
        let (v1, a1) = inverse_derivs(path, xe, d1, d2)?;
        let h = left + right;
        if ok && depth < 60 {
            // Does the quintic model of u(s) hit the quarter points? (Not the midpoint
            // alone: on a symmetric piece the model is exact there whatever its error
            // elsewhere.)
            let c = quintic_coeffs(h, x0, x1, v0, v1, a0, a1);
            let model =
                |sm: f64| ((((c[5] * sm + c[4]) * sm + c[3]) * sm + c[2]) * sm + c[1]) * sm + c[0];
            let (xq, x3) = (x0 + 0.25 * (x1 - x0), x0 + 0.75 * (x1 - x0));
            let (lq, l3) = (gl(path, x0, xq, d1), left + gl(path, xm, x3, d1));
            let eq = (model(lq) - xq).abs() * speed(path, xq, d1);
            let e3 = (model(l3) - x3).abs() * speed(path, x3, d1);
            ok = eq.max(e3) <= 0.2 * tol;
        }
        if ok {
            out.push(Accepted {
                h,
                u0: x0,
                u1: x1,
                v0,
                v1,
                a0,
                a1,
            });
        } else {
            // Right half first so the left one is processed next (increasing order).
            stack.push((xm, x1, depth + 1));
            stack.push((x0, xm, depth + 1));
        }
    }
    Ok(())
}

/// The subdivision nodes, the length up to each, and u(s) as a piecewise quintic Hermite on
/// those lengths, from the accepted subintervals in order (`ub` closes the last one).
fn inverse_model(seg_data: &[Accepted], ub: f64) -> (Vec<f64>, Vec<f64>, PiecewisePolynomial) {
    let mut total = 0.0;
    let mut u: Vec<f64> = Vec::with_capacity(seg_data.len() + 1);
    let mut len: Vec<f64> = Vec::with_capacity(seg_data.len() + 1);
    for sd in seg_data {
        u.push(sd.u0);
        len.push(total);
        total += sd.h;
    }
    u.push(ub);
    len.push(total);
    let mut coeffs = Vec::with_capacity(seg_data.len() * 6);
    let mut breaks = len.clone();
    // Guard against zero-length subintervals from round-off (cannot happen with positive
    // speed, but keep the breaks strictly increasing).
    for i in 1..breaks.len() {
        if breaks[i] <= breaks[i - 1] {
            breaks[i] = breaks[i - 1] * (1.0 + f64::EPSILON) + f64::MIN_POSITIVE;
        }
    }
    for sd in seg_data {
        coeffs.extend_from_slice(&quintic_coeffs(
            sd.h, sd.u0, sd.u1, sd.v0, sd.v1, sd.a0, sd.a1,
        ));
    }
    let inv = PiecewisePolynomial::from_parts(breaks, 1, 5, coeffs);
    (u, len, inv)
}

/// Arc length of a path `σ(u)` and its arc-length reparameterization `x(s) = σ(u(s))`,
/// `s ∈ [0, L]`, to an absolute tolerance chosen at construction.
///
/// Construction subdivides every smooth piece of the path (between its
/// [`Path::breakpoints`]) until 8-point Gauss–Legendre on each subinterval agrees with the two
/// halves within its share of the tolerance, and until a quintic Hermite model of `u(s)` on the
/// subinterval reproduces its quarter points within a fifth of the tolerance. Then:
/// - [`ArcLength::length`] and [`ArcLength::length_at`] are within `tol` of the true length;
/// - [`ArcLength::param_at`] solves `length_at(u) = s` by safeguarded Newton to `tol`;
/// - as a [`Path`], `x(s)` has unit speed (σ′/‖σ′‖ exactly) and its position is within `tol` of
///   the curve point at arc length `s`. Orders 0..=3 are evaluated by the chain rule from σ′, σ″,
///   σ‴; higher orders are zero. Paths with more than 64 components allocate scratch per call.
///
/// The path must not stop: a zero speed ‖σ′‖ at a subdivision node is a typed error.
///
/// ```
/// use trajkit::{spline::{ArcLength, Nurbs}, Path};
/// let circle = Nurbs::circle([0.0, 0.0], 2.0)?;
/// let al = ArcLength::new(&circle, 1e-10)?;
/// assert!((al.length() - 4.0 * std::f64::consts::PI).abs() < 1e-10);
/// let mut v = [0.0; 2];
/// al.eval(1.0, 1, &mut v); // unit speed
/// assert!((v[0].hypot(v[1]) - 1.0).abs() < 1e-12);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct ArcLength<P: Path> {
    path: P,
    tol: f64,
    /// Subdivision nodes in the path parameter and the length up to each.
    u: Vec<f64>,
    len: Vec<f64>,
    /// u(s), piecewise quintic Hermite on breaks `len`.
    inv: PiecewisePolynomial,
}

impl<P: Path> ArcLength<P> {
    /// Measures `path` to absolute tolerance `tol > 0`.
    pub fn new(path: P, tol: f64) -> Result<Self> {
        crate::error::positive(|| "arc length tolerance".into(), tol)?;
        let dim = path.dim();
        let (ua, ub) = path.interval();
        let span = ub - ua;
        let mut d1 = vec![0.0; dim];
        let mut d2 = vec![0.0; dim];
        let br = path.breakpoints();
        let mut seg_data: Vec<Accepted> = Vec::new();
        for w in br.windows(2) {
            let (a, b) = (w[0], w[1]);
            if b <= a {
                continue;
            }
            subdivide_piece(&path, a, b, tol, span, &mut d1, &mut d2, &mut seg_data)?;
        }
        let (u, len, inv) = inverse_model(&seg_data, ub);
        Ok(ArcLength {
            path,
            tol,
            u,
            len,
            inv,
        })
    }

    /// The total arc length L.
    pub fn length(&self) -> f64 {
        *self.len.last().unwrap()
    }

    /// The tolerance the table was built for.
    pub fn tolerance(&self) -> f64 {
        self.tol
    }

    /// The underlying path.
    pub fn path(&self) -> &P {
        &self.path
    }

    /// Arc length from the start of the path to parameter `u` (clamped to the interval).
    pub fn length_at(&self, u: f64) -> f64 {
        let (a, b) = self.path.interval();
        let u = u.clamp(a, b);
        let j = crate::traj::find_piece(&self.u, u);
        with_scratch(self.path.dim(), |d, _, _| {
            self.len[j] + self.gl(self.u[j], u, d)
        })
    }

    fn gl(&self, a: f64, b: f64, d: &mut [f64]) -> f64 {
        if b <= a {
            return 0.0;
        }
        let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
        let mut s = 0.0;
        for i in 0..4 {
            self.path.eval(c - h * GX[i], 1, d);
            let g0 = norm(d);
            self.path.eval(c + h * GX[i], 1, d);
            s += GW[i] * (g0 + norm(d));
        }
        s * h
    }

    /// The path parameter at arc length `s` (clamped to `[0, L]`), to the tolerance: safeguarded
    /// Newton on the exact length function, started from the Hermite model.
    pub fn param_at(&self, s: f64) -> f64 {
        if s.is_nan() {
            return f64::NAN;
        }
        let s = s.clamp(0.0, self.length());
        let j = crate::traj::find_piece(&self.len, s);
        let (mut lo, mut hi) = (self.u[j], self.u[j + 1]);
        let mut g = [0.0];
        self.inv.eval(s, 0, &mut g);
        let mut u = g[0].clamp(lo, hi);
        with_scratch(self.path.dim(), |d, _, _| {
            for _ in 0..60 {
                let f = self.len[j] + self.gl(self.u[j], u, d) - s;
                if f.abs() <= 0.01 * self.tol {
                    break;
                }
                if f > 0.0 {
                    hi = u;
                } else {
                    lo = u;
                }
                self.path.eval(u, 1, d);
                let sp = norm(d);
                let mut next = u - f / sp;
                if !(next > lo && next < hi) {
                    next = 0.5 * (lo + hi);
                }
                if (next - u).abs() <= f64::EPSILON * u.abs().max(1.0) {
                    u = next;
                    break;
                }
                u = next;
            }
            u
        })
    }

    /// u(s) from the Hermite model (within the tolerance), without Newton polishing.
    fn u_of(&self, s: f64) -> f64 {
        let mut g = [0.0];
        self.inv.eval(s, 0, &mut g);
        g[0]
    }
}

impl<P: Path> Path for ArcLength<P> {
    fn dim(&self) -> usize {
        self.path.dim()
    }

    fn interval(&self) -> (f64, f64) {
        (0.0, self.length())
    }

    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        let dim = self.path.dim();
        if s.is_nan() {
            out[..dim].fill(f64::NAN);
            return;
        }
        let (a, b) = self.path.interval();
        let u = self.u_of(s.clamp(0.0, self.length())).clamp(a, b);
        match order {
            0 => self.path.eval(u, 0, out),
            1 => {
                self.path.eval(u, 1, out);
                let g = norm(&out[..dim]);
                for v in out[..dim].iter_mut() {
                    *v /= g;
                }
            }
            2 | 3 => with_scratch(dim, |d1, d2, d3| {
                self.path.eval(u, 1, d1);
                self.path.eval(u, 2, d2);
                let g = norm(d1);
                let gu = dot(d1, d2) / g;
                let up = 1.0 / g;
                let upp = -gu / (g * g * g);
                if order == 2 {
                    for i in 0..dim {
                        out[i] = d2[i] * up * up + d1[i] * upp;
                    }
                } else {
                    self.path.eval(u, 3, d3);
                    let guu = (dot(d2, d2) + dot(d1, d3)) / g - gu * gu / g;
                    let uppp = -guu / g.powi(4) + 3.0 * gu * gu / g.powi(5);
                    for i in 0..dim {
                        out[i] = d3[i] * up * up * up + 3.0 * d2[i] * up * upp + d1[i] * uppp;
                    }
                }
            }),
            _ => out[..dim].fill(0.0),
        }
    }

    fn breakpoints(&self) -> Vec<f64> {
        let pb = self.path.breakpoints();
        let mut v: Vec<f64> = pb.iter().map(|&u| self.length_at(u)).collect();
        v.dedup();
        v
    }
}
