//! B-splines of any degree (up to [`MAX_DEGREE`]) on clamped or unclamped, uniform or
//! non-uniform knots: evaluation, derivatives, knot insertion, degree elevation,
//! interpolation (including minimum-jerk and minimum-snap), least squares and the design
//! matrix.
//!
//! This file holds the type, evaluation and the shape-preserving edits (hodograph, knot
//! insertion, clamping, degree elevation); `bspline/fit.rs` holds the fitting constructors
//! (interpolation, minimum-jerk/snap, least squares) and the collocation solve.

mod fit;

use crate::error::{Error, Result};
pub use crate::spline::basis::MAX_DEGREE;
use crate::spline::basis::{self, basis_ders, basis_funs, find_span, find_span_from, K1};
use crate::spline::validate;
use fit::{collocate, Row};

/// A vector-valued B-spline `σ(s) = Σ_i c_i N_{i,k}(s)` of degree `k` with knots
/// `t_0 <= … <= t_{n+k}` and `n` control points `c_i` (row-major `n × dim`).
///
/// The curve is defined on its base interval `[t_k, t_n]` (for clamped knots, the first and last
/// knot); parameters outside it are clamped (see the [module policy](crate::spline)).
/// Evaluation at a knot uses the span to its right (the last span at `t_n`), so derivatives
/// there are right-hand ones. Evaluation allocates nothing: the basis functions live in
/// fixed-size stack buffers.
///
/// ```
/// use trajkit::{spline::BSpline, Path};
/// // A clamped quadratic in the plane through 4 control points.
/// let t = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
/// let c = [0.0, 0.0, 1.0, 2.0, 3.0, 2.0, 4.0, 0.0];
/// let b = BSpline::new(&t, &c, 2, 2)?;
/// let mut p = [0.0; 2];
/// b.eval(1.0, 0, &mut p); // clamped: ends at the last control point
/// assert_eq!(p, [4.0, 0.0]);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BSpline {
    k: usize,
    dim: usize,
    t: Vec<f64>,
    c: Vec<f64>,
}

/// The linear map from control points to values (or derivatives) at given parameters:
/// row `r` has `k + 1` non-zero entries starting at column `first(r)`. Optimizers use it to
/// write constraints and costs on a curve that are linear in its control points.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignMatrix {
    rows: usize,
    cols: usize,
    width: usize,
    first: Vec<usize>,
    values: Vec<f64>,
}

impl DesignMatrix {
    /// Number of rows (parameters).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of columns (control points).
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Row `r`: the first non-zero column and the `k + 1` entries from there.
    pub fn row(&self, r: usize) -> (usize, &[f64]) {
        (
            self.first[r],
            &self.values[r * self.width..(r + 1) * self.width],
        )
    }

    /// The matrix as a dense row-major `rows × cols` array.
    pub fn to_dense(&self) -> Vec<f64> {
        let mut m = vec![0.0; self.rows * self.cols];
        for r in 0..self.rows {
            let (f, v) = self.row(r);
            m[r * self.cols + f..r * self.cols + f + self.width].copy_from_slice(v);
        }
        m
    }

    /// `out = M · c` for control points `c` (row-major `cols × dim`); `out` is `rows × dim`.
    pub fn apply(&self, c: &[f64], dim: usize, out: &mut [f64]) {
        for r in 0..self.rows {
            let (f, v) = self.row(r);
            let o = &mut out[r * dim..(r + 1) * dim];
            o.fill(0.0);
            for (j, &w) in v.iter().enumerate() {
                for d in 0..dim {
                    o[d] += w * c[(f + j) * dim + d];
                }
            }
        }
    }
}

/// End-derivative conditions for [`BSpline::interpolate_with_ends`]: derivative `order` takes
/// the value `value` (`dim` entries).
#[derive(Debug, Clone, Copy)]
pub struct EndDerivative<'a> {
    /// Derivative order, 1..=degree.
    pub order: usize,
    /// The derivative's value, one entry per component.
    pub value: &'a [f64],
}

fn too_high(k: usize) -> Error {
    Error::InvalidValue {
        field: "B-spline degree".into(),
        value: k as f64,
        reason: "exceeds trajkit's maximum degree (20)",
    }
}

fn check_knots(t: &[f64], k: usize, n: usize) -> Result<()> {
    if k > MAX_DEGREE {
        return Err(too_high(k));
    }
    if n < k + 1 {
        return Err(Error::TooFewWaypoints {
            needed: k + 1,
            found: n,
        });
    }
    if t.len() != n + k + 1 {
        return Err(Error::DimensionMismatch {
            what: format!("knot count (control points + degree + 1 = {n} + {k} + 1)"),
            expected: n + k + 1,
            found: t.len(),
        });
    }
    validate::nondecreasing("knots", t)?;
    if t[k] >= t[n] {
        return Err(Error::InvalidValue {
            field: format!("knots[{n}]"),
            value: t[n],
            reason: "does not exceed knots[degree]: the base interval is empty",
        });
    }
    // No interior knot of multiplicity above k + 1 (the basis would lose a function).
    let mut run = 1;
    for i in 1..t.len() {
        run = if t[i] == t[i - 1] { run + 1 } else { 1 };
        if run > k + 1 && i > k && i < n {
            return Err(Error::InvalidValue {
                field: format!("knots[{i}]"),
                value: t[i],
                reason: "has multiplicity above degree + 1",
            });
        }
    }
    Ok(())
}

fn singular(what: &str) -> Error {
    Error::InvalidValue {
        field: what.into(),
        value: f64::NAN,
        reason: "give a singular system (the parameters violate the Schoenberg-Whitney condition for these knots)",
    }
}

impl BSpline {
    /// A B-spline of `degree` from knots (non-decreasing, finite, `n + degree + 1` of them, a
    /// non-empty base interval) and `n >= degree + 1` control points (row-major `n × dim`).
    pub fn new(knots: &[f64], control_points: &[f64], dim: usize, degree: usize) -> Result<Self> {
        validate::dim(dim)?;
        if control_points.len() % dim != 0 {
            return Err(Error::DimensionMismatch {
                what: format!("control point entries (a multiple of dim = {dim})"),
                expected: control_points.len() / dim * dim,
                found: control_points.len(),
            });
        }
        let n = control_points.len() / dim;
        check_knots(knots, degree, n)?;
        validate::finite("control_points", control_points, dim)?;
        Ok(BSpline {
            k: degree,
            dim,
            t: knots.to_vec(),
            c: control_points.to_vec(),
        })
    }

    /// The clamped uniform knot vector for `n` control points of `degree` on `[a, b]`:
    /// `degree + 1` copies of each end and equally spaced interior knots.
    pub fn clamped_uniform_knots(n: usize, degree: usize, a: f64, b: f64) -> Vec<f64> {
        let mut t = vec![a; degree + 1];
        let inner = n.saturating_sub(degree + 1);
        for i in 1..=inner {
            t.push(a + (b - a) * i as f64 / (inner + 1) as f64);
        }
        t.extend(std::iter::repeat_n(b, degree + 1));
        t
    }

    /// Degree `k`.
    pub fn degree(&self) -> usize {
        self.k
    }

    /// Number of components.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The knots.
    pub fn knots(&self) -> &[f64] {
        &self.t
    }

    /// The control points, row-major `n × dim`.
    pub fn control_points(&self) -> &[f64] {
        &self.c
    }

    /// Number of control points `n`.
    pub fn num_control_points(&self) -> usize {
        self.c.len() / self.dim
    }

    /// The base interval `[t_k, t_n]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.t[self.k], self.t[self.num_control_points()])
    }

    #[inline]
    fn clamp(&self, s: f64) -> f64 {
        let (a, b) = self.domain();
        if s < a {
            a
        } else if s > b {
            b
        } else {
            s
        }
    }

    /// Writes the `order`-th derivative at `s` (clamped) into `out[..dim]`; `span` is a hint
    /// (any value is valid) and is updated to the span used, so a sweep over increasing `s`
    /// finds each span in O(1).
    #[inline]
    pub fn eval_with_hint(&self, s: f64, order: usize, out: &mut [f64], span: &mut usize) {
        let dim = self.dim;
        let out = &mut out[..dim];
        if s.is_nan() {
            out.fill(f64::NAN);
            return;
        }
        let s = self.clamp(s);
        let k = self.k;
        let l = find_span_from(&self.t, k, s, *span);
        *span = l;
        let mut nb = [0.0; K1];
        if order == 0 {
            basis_funs(&self.t, k, l, s, &mut nb);
        } else {
            basis_ders(&self.t, k, l, s, order, &mut nb);
        }
        let c = &self.c[(l - k) * dim..(l + 1) * dim];
        out.fill(0.0);
        for (w, row) in nb[..=k].iter().zip(c.chunks_exact(dim)) {
            for (o, &v) in out.iter_mut().zip(row) {
                *o += w * v;
            }
        }
    }

    /// Evaluates at many parameters: `out` is `s.len() × dim`, row-major. Any order of `s`
    /// works; increasing `s` is fastest (each span is found from the previous one, and for
    /// values of degree ≤ 5 the span's work is done once per span: with ≤ 16 components its
    /// polynomial is expanded once and each point is a Horner pass, above that the Cox–de Boor
    /// reciprocals are cached). Results agree with [`crate::Path::eval`] to rounding (within
    /// 1e-13 of the largest control-point magnitude on strongly non-uniform knots).
    pub fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
        let dim = self.dim;
        if order == 0 {
            {
                macro_rules! taylor {
                    ($kp1:literal) => {
                        match dim {
                            0..=4 => return self.eval_many_taylor::<$kp1, 4>(s, out),
                            5..=8 => return self.eval_many_taylor::<$kp1, 8>(s, out),
                            9..=16 => return self.eval_many_taylor::<$kp1, 16>(s, out),
                            _ => return self.eval_many_fixed::<$kp1>(s, out),
                        }
                    };
                }
                match self.k {
                    1 => taylor!(2),
                    2 => taylor!(3),
                    3 => taylor!(4),
                    4 => taylor!(5),
                    5 => taylor!(6),
                    _ => {}
                }
            }
            match self.k {
                1 => return self.eval_many_fixed::<2>(s, out),
                2 => return self.eval_many_fixed::<3>(s, out),
                3 => return self.eval_many_fixed::<4>(s, out),
                4 => return self.eval_many_fixed::<5>(s, out),
                5 => return self.eval_many_fixed::<6>(s, out),
                _ => {}
            }
        }
        let mut span = self.k;
        for (si, o) in s.iter().zip(out.chunks_exact_mut(dim)) {
            self.eval_with_hint(*si, order, o, &mut span);
        }
    }

    /// Values (order 0) for a degree fixed at compile time (`KP1 = k + 1`) and at most `MD`
    /// components, through the span's polynomial: when the span changes, its Taylor
    /// coefficients about the left knot are computed once from the de Boor basis derivatives
    /// there (`a_m = Σ_j N_j⁽ᵐ⁾(t_l) c_j / m!`); each point is then one Horner pass over all
    /// components at once (coefficients power-major, component-minor).
    fn eval_many_taylor<const KP1: usize, const MD: usize>(&self, s: &[f64], out: &mut [f64]) {
        let k = KP1 - 1;
        let dim = self.dim;
        let (a, b) = self.domain();
        let t = &self.t[..];
        let last = self.num_control_points() - 1;
        let mut span = usize::MAX;
        let mut coef = [[0.0; MD]; KP1];
        let (mut t0, mut t1) = (0.0, 0.0);
        for (&si, o) in s.iter().zip(out.chunks_exact_mut(dim)) {
            if si.is_nan() {
                o.fill(f64::NAN);
                continue;
            }
            let si = if si < a {
                a
            } else if si > b {
                b
            } else {
                si
            };
            let inside = span != usize::MAX && si >= t0 && (si < t1 || (span == last && si <= t1));
            if !inside {
                let l = find_span_from(t, k, si, if span == usize::MAX { k } else { span });
                span = l;
                t0 = t[l];
                t1 = t[l + 1];
                let c = &self.c[(l - k) * dim..(l + 1) * dim];
                let mut nb = [0.0; K1];
                let mut fact = 1.0;
                for (m, row) in coef.iter_mut().enumerate() {
                    if m > 0 {
                        fact *= m as f64;
                    }
                    basis_ders(t, k, l, t0, m, &mut nb);
                    for (d, v) in row.iter_mut().enumerate().take(dim) {
                        let mut acc = 0.0;
                        for j in 0..KP1 {
                            acc += nb[j] * c[j * dim + d];
                        }
                        *v = acc / fact;
                    }
                }
            }
            let u = si - t0;
            let mut acc = coef[k];
            for m in (0..k).rev() {
                for d in 0..MD {
                    acc[d] = acc[d] * u + coef[m][d];
                }
            }
            o.copy_from_slice(&acc[..dim]);
        }
    }

    /// Values (order 0) for a degree fixed at compile time (`KP1 = k + 1`). The reciprocal
    /// knot differences of the Cox–de Boor recursion depend only on the span, so they are
    /// computed when the span changes and the per-point work has no division.
    fn eval_many_fixed<const KP1: usize>(&self, s: &[f64], out: &mut [f64]) {
        let k = KP1 - 1;
        let dim = self.dim;
        let (a, b) = self.domain();
        let t = &self.t[..];
        let mut span = usize::MAX;
        // inv[j][r] = 1 / (t[l + r + 1] − t[l + 1 − j + r]) for 1 <= j <= k, r < j.
        let mut inv = [[0.0; KP1]; KP1];
        // tl[m] = t[l + 1 − k + m], m = 0..2k.
        let mut tl = [[0.0; KP1]; 2];
        for (&si, o) in s.iter().zip(out.chunks_exact_mut(dim)) {
            if si.is_nan() {
                o.fill(f64::NAN);
                continue;
            }
            let si = if si < a {
                a
            } else if si > b {
                b
            } else {
                si
            };
            let l = if span != usize::MAX && si >= t[span] && si < t[span + 1] {
                span
            } else {
                find_span_from(t, k, si, if span == usize::MAX { k } else { span })
            };
            if l != span {
                span = l;
                for j in 1..=k {
                    for r in 0..j {
                        inv[j][r] = 1.0 / (t[l + r + 1] - t[l + 1 - j + r]);
                    }
                }
                for j in 0..KP1 {
                    tl[0][j] = t[l + 1 - k + j.min(k)]; // t[l+1-j'] for left: index k - j'
                    tl[1][j] = t[(l + j).min(t.len() - 1)]; // t[l + j]
                }
            }
            // Cox–de Boor with precomputed reciprocals.
            let mut nb = [0.0; KP1];
            let mut left = [0.0; KP1];
            let mut right = [0.0; KP1];
            nb[0] = 1.0;
            for j in 1..KP1 {
                left[j] = si - tl[0][k - j];
                right[j] = tl[1][j] - si;
                let mut saved = 0.0;
                for r in 0..j {
                    let temp = nb[r] * inv[j][r];
                    nb[r] = saved + right[r + 1] * temp;
                    saved = left[j - r] * temp;
                }
                nb[j] = saved;
            }
            let c = &self.c[(l - k) * dim..(l + 1) * dim];
            let o = &mut o[..dim];
            for (d, ov) in o.iter_mut().enumerate() {
                let mut acc = 0.0;
                for j in 0..KP1 {
                    acc += nb[j] * c[j * dim + d];
                }
                *ov = acc;
            }
        }
    }

    /// The `order`-th derivatives of the `k + 1` basis functions that are non-zero at `s`
    /// (clamped), written to `values[..=k]`; returns the index of the first of them.
    pub fn basis(&self, s: f64, order: usize, values: &mut [f64]) -> usize {
        let s = self.clamp(s);
        let l = find_span(&self.t, self.k, s);
        basis_ders(&self.t, self.k, l, s, order, values);
        l - self.k
    }

    /// The design matrix of the `order`-th derivative at parameters `s` (each clamped to the
    /// base interval): `M · c` gives the derivative at every `s` for control points `c`.
    pub fn design_matrix(&self, s: &[f64], order: usize) -> DesignMatrix {
        design(&self.t, self.k, s, order)
    }

    /// The hodograph: the `order`-th derivative as a B-spline of degree `k − order` on the knots
    /// without their first and last `order` entries (a constant zero spline when
    /// `order > k`).
    pub fn derivative(&self, order: usize) -> BSpline {
        if order > self.k {
            let (a, b) = self.domain();
            return BSpline {
                k: 0,
                dim: self.dim,
                t: vec![a, b],
                c: vec![0.0; self.dim],
            };
        }
        let mut t = self.t.clone();
        let mut c = self.c.clone();
        let mut k = self.k;
        let dim = self.dim;
        for _ in 0..order {
            let n = c.len() / dim;
            let mut nc = vec![0.0; (n - 1) * dim];
            for i in 0..n - 1 {
                let den = t[i + k + 1] - t[i + 1];
                for d in 0..dim {
                    nc[i * dim + d] = if den > 0.0 {
                        k as f64 * (c[(i + 1) * dim + d] - c[i * dim + d]) / den
                    } else {
                        0.0
                    };
                }
            }
            t = t[1..t.len() - 1].to_vec();
            c = nc;
            k -= 1;
        }
        BSpline { k, dim, t, c }
    }

    /// Inserts the knot `x` (inside the base interval) `times` times (Boehm's algorithm); the
    /// curve is unchanged. Matches scipy's `BSpline.insert_knot`.
    pub fn insert_knot(&self, x: f64, times: usize) -> Result<BSpline> {
        let (a, b) = self.domain();
        if !(x >= a && x <= b) {
            return Err(Error::InvalidValue {
                field: "inserted knot".into(),
                value: x,
                reason: "is outside the base interval",
            });
        }
        let mut out = self.clone();
        for _ in 0..times {
            out = out.insert_once(x)?;
        }
        Ok(out)
    }

    fn insert_once(&self, x: f64) -> Result<BSpline> {
        let (k, dim) = (self.k, self.dim);
        let t = &self.t;
        let n = self.num_control_points();
        let l = find_span(t, k, x);
        let mult = t.iter().filter(|&&v| v == x).count();
        if mult > k && x > t[k] && x < t[n] {
            return Err(Error::InvalidValue {
                field: "inserted knot".into(),
                value: x,
                reason: "already has multiplicity degree + 1",
            });
        }
        let mut nt = Vec::with_capacity(t.len() + 1);
        nt.extend_from_slice(&t[..=l]);
        nt.push(x);
        nt.extend_from_slice(&t[l + 1..]);
        let mut nc = vec![0.0; (n + 1) * dim];
        for i in 0..=n {
            for d in 0..dim {
                nc[i * dim + d] = if i + k <= l {
                    self.c[i * dim + d]
                } else if i > l {
                    self.c[(i - 1) * dim + d]
                } else {
                    let den = t[i + k] - t[i];
                    let al = if den > 0.0 { (x - t[i]) / den } else { 0.0 };
                    (1.0 - al) * self.c[(i - 1) * dim + d] + al * self.c[i * dim + d]
                };
            }
        }
        Ok(BSpline {
            k,
            dim,
            t: nt,
            c: nc,
        })
    }

    /// The same curve on its base interval with clamped knots (each end knot repeated
    /// `k + 1` times), by knot insertion at the ends.
    pub fn to_clamped(&self) -> BSpline {
        let (a, b) = self.domain();
        let k = self.k;
        let mut s = self.clone();
        let ma = s.t.iter().filter(|&&v| v == a).count();
        if ma < k + 1 {
            s = s.insert_knot(a, k + 1 - ma).expect("end of base interval");
        }
        let mb = s.t.iter().filter(|&&v| v == b).count();
        if mb < k + 1 {
            s = s.insert_knot(b, k + 1 - mb).expect("end of base interval");
        }
        // Drop knots and control points outside [a, b].
        let first = s.t.iter().position(|&v| v == a).unwrap();
        let last = s.t.iter().rposition(|&v| v == b).unwrap();
        let t = s.t[first..=last].to_vec();
        let n = t.len() - k - 1;
        let c = s.c[first * s.dim..(first + n) * s.dim].to_vec();
        BSpline {
            k,
            dim: s.dim,
            t,
            c,
        }
    }

    /// The same curve as a B-spline of degree `k + times`: every distinct knot gains `times`
    /// in multiplicity, and the new control points are found by collocation at the Greville
    /// abscissae (exact up to round-off). Unclamped splines are clamped first. A curve that is
    /// discontinuous (an interior knot of multiplicity `k + 1`) is refused with a typed error.
    pub fn elevate_degree(&self, times: usize) -> Result<BSpline> {
        if times == 0 {
            return Ok(self.clone());
        }
        let nk = self.k + times;
        if nk > MAX_DEGREE {
            return Err(too_high(nk));
        }
        let base = self.to_clamped();
        let nb = base.num_control_points();
        let mut run = 1;
        for i in 1..base.t.len() {
            run = if base.t[i] == base.t[i - 1] {
                run + 1
            } else {
                1
            };
            if run > self.k && i > self.k && i < nb {
                return Err(Error::InvalidValue {
                    field: format!("knots[{i}]"),
                    value: base.t[i],
                    reason: "has multiplicity degree + 1 (the curve is discontinuous there): split it before elevating its degree",
                });
            }
        }
        let mut t = Vec::with_capacity(base.t.len() * 2);
        let mut i = 0;
        while i < base.t.len() {
            let v = base.t[i];
            let mut j = i;
            while j < base.t.len() && base.t[j] == v {
                j += 1;
            }
            t.extend(std::iter::repeat_n(v, j - i + times));
            i = j;
        }
        let n = t.len() - nk - 1;
        let g: Vec<f64> = (0..n)
            .map(|i| t[i + 1..=i + nk].iter().sum::<f64>() / nk as f64)
            .collect();
        let mut y = vec![0.0; n * base.dim];
        base.eval_many(&g, 0, &mut y);
        let rows: Vec<Row> = g.iter().map(|&s| Row::at(s, 0)).collect();
        let c = collocate(&t, nk, &rows, &y, base.dim).map_err(|_| singular("elevation"))?;
        Ok(BSpline {
            k: nk,
            dim: base.dim,
            t,
            c,
        })
    }
}

fn design(t: &[f64], k: usize, s: &[f64], order: usize) -> DesignMatrix {
    let n = t.len() - k - 1;
    let (a, b) = (t[k], t[n]);
    let mut first = Vec::with_capacity(s.len());
    let mut values = vec![0.0; s.len() * (k + 1)];
    for (r, &si) in s.iter().enumerate() {
        let si = si.clamp(a, b);
        let l = basis::find_span(t, k, si);
        basis_ders(t, k, l, si, order, &mut values[r * (k + 1)..]);
        first.push(l - k);
    }
    DesignMatrix {
        rows: s.len(),
        cols: n,
        width: k + 1,
        first,
        values,
    }
}

impl crate::Path for BSpline {
    fn dim(&self) -> usize {
        self.dim
    }
    fn interval(&self) -> (f64, f64) {
        self.domain()
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        let mut span = self.k;
        self.eval_with_hint(s, order, out, &mut span)
    }
    fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
        BSpline::eval_many(self, s, order, out)
    }
    fn breakpoints(&self) -> Vec<f64> {
        let (a, b) = self.domain();
        let mut v: Vec<f64> = vec![a];
        for &x in &self.t {
            if x > *v.last().unwrap() && x <= b {
                v.push(x);
            }
        }
        v
    }
}
