//! Piecewise polynomials: breaks and per-piece coefficients in the local variable.
//!
//! Evaluation over many parameters ([`PiecewisePolynomial::eval_many`], also `Path::eval_many`
//! of every spline built on it) finds each parameter's piece from the previous one and writes
//! into a caller buffer without allocating; its values are bitwise those of one-point `eval`
//! (same operations, same order), which the tests check for every degree, dimension and
//! parameter order. [`PiecewisePolynomial::eval_many_orders`] (orders 0..=3 in one sweep, what
//! sampling a retimed path needs) writes bitwise what `eval_many` writes for each order.

use crate::error::{Error, Result};
use crate::spline::validate;

/// A vector-valued piecewise polynomial of one degree on increasing breaks
/// `b_0 < b_1 < … < b_n` (n pieces).
///
/// On piece `i` (`b_i <= s < b_{i+1}`, the last piece closed) component `d` is
/// `p(s) = Σ_j c[i][d][j] · (s − b_i)^j`, `j = 0..=degree`. Coefficients are stored flat,
/// `coeffs[(i·dim + d)·(degree + 1) + j]`. Every interpolating spline of this module that is
/// polynomial between its breaks is one of these.
///
/// Parameters outside `[b_0, b_n]` are clamped (see the [module policy](crate::spline)).
///
/// ```
/// use trajkit::spline::PiecewisePolynomial;
/// use trajkit::Path;
/// // Two pieces of one component: s² on [0, 1], then 1 + 2(s − 1) on [1, 2].
/// let pp = PiecewisePolynomial::new(vec![0.0, 1.0, 2.0], 1, 2, vec![0.0, 0.0, 1.0, 1.0, 2.0, 0.0])?;
/// let mut v = [0.0];
/// pp.eval(1.5, 0, &mut v);
/// assert_eq!(v[0], 2.0);
/// pp.eval(0.5, 1, &mut v);
/// assert_eq!(v[0], 1.0);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewisePolynomial {
    breaks: Vec<f64>,
    dim: usize,
    degree: usize,
    coeffs: Vec<f64>,
}

/// Coefficients (ascending powers of the local variable) of the quintic on `[0, h]` with
/// values `p0, p1`, slopes `v0, v1` and second derivatives `a0, a1` at its ends.
pub(crate) fn quintic_coeffs(
    h: f64,
    p0: f64,
    p1: f64,
    v0: f64,
    v1: f64,
    a0: f64,
    a1: f64,
) -> [f64; 6] {
    // Remaining conditions on c3 h³, c4 h⁴, c5 h⁵ after c0..c2 fix p0, v0, a0.
    let e0 = p1 - p0 - v0 * h - 0.5 * a0 * h * h;
    let e1 = (v1 - v0 - a0 * h) * h;
    let e2 = (a1 - a0) * h * h;
    let c3 = 10.0 * e0 - 4.0 * e1 + 0.5 * e2;
    let c4 = -15.0 * e0 + 7.0 * e1 - e2;
    let c5 = 6.0 * e0 - 3.0 * e1 + 0.5 * e2;
    let h3 = h * h * h;
    [p0, v0, 0.5 * a0, c3 / h3, c4 / (h3 * h), c5 / (h3 * h * h)]
}

/// j! / (j − m)!, as f64.
#[inline]
fn falling(j: usize, m: usize) -> f64 {
    let mut f = 1.0;
    for k in (j - m + 1)..=j {
        f *= k as f64;
    }
    f
}

/// The derivative factors `j!/(j − order)!` of the `K` coefficients (0 below `order`; all 1,
/// unused, for order 0).
fn factors<const K: usize>(order: usize) -> [f64; K] {
    let mut f = [1.0; K];
    if order > 0 {
        for (j, fj) in f.iter_mut().enumerate() {
            *fj = if j >= order { falling(j, order) } else { 0.0 };
        }
    }
    f
}

/// Order `order`'s Horner pass at `h` over a derivative block of
/// `PiecewisePolynomial::eval_many_block` (`block[j][d]`: coefficient `j` of component `d`
/// times `j!/(j − order)!`), all components at once.
#[inline(always)]
fn horner_block<const K: usize, const MD: usize>(
    block: &[[f64; MD]; K],
    order: usize,
    h: f64,
) -> [f64; MD] {
    let mut acc = [0.0; MD];
    let rows = if order == 0 {
        acc = block[K - 1];
        &block[..K - 1]
    } else {
        &block[order..]
    };
    for row in rows.iter().rev() {
        for d in 0..MD {
            acc[d] = acc[d] * h + row[d];
        }
    }
    acc
}

/// Copies the first `o.len()` components of `acc` into `o` (a copy of fixed size when all
/// `MD` are used: no call per point).
#[inline(always)]
fn write_row<const MD: usize>(o: &mut [f64], acc: &[f64; MD]) {
    if o.len() == MD {
        o[..MD].copy_from_slice(acc);
    } else {
        o.copy_from_slice(&acc[..o.len()]);
    }
}

impl PiecewisePolynomial {
    /// A piecewise polynomial from breaks (at least 2, finite, strictly increasing) and
    /// coefficients laid out as in the type documentation
    /// (`(breaks.len() − 1) · dim · (degree + 1)` finite values).
    pub fn new(breaks: Vec<f64>, dim: usize, degree: usize, coeffs: Vec<f64>) -> Result<Self> {
        validate::dim(dim)?;
        validate::increasing("breaks", &breaks, 2)?;
        let n = breaks.len() - 1;
        let k = degree + 1;
        if coeffs.len() != n * dim * k {
            return Err(Error::DimensionMismatch {
                what: format!(
                    "coefficient count (pieces × dim × (degree + 1) = {n} × {dim} × {k})"
                ),
                expected: n * dim * k,
                found: coeffs.len(),
            });
        }
        validate::finite("coeffs", &coeffs, k)?;
        Ok(PiecewisePolynomial {
            breaks,
            dim,
            degree,
            coeffs,
        })
    }

    /// Internal constructor for already validated data.
    pub(crate) fn from_parts(
        breaks: Vec<f64>,
        dim: usize,
        degree: usize,
        coeffs: Vec<f64>,
    ) -> Self {
        debug_assert_eq!(coeffs.len(), (breaks.len() - 1) * dim * (degree + 1));
        PiecewisePolynomial {
            breaks,
            dim,
            degree,
            coeffs,
        }
    }

    /// The broken line through `y` (row-major `n × dim`) at the breaks `x` (Drake's
    /// `FirstOrderHold`): degree 1, continuous, its derivative jumps at the breaks.
    pub fn linear(x: &[f64], y: &[f64], dim: usize) -> Result<Self> {
        validate::interpolation_data(x, y, dim, 2)?;
        let n = x.len() - 1;
        let mut c = vec![0.0; n * dim * 2];
        for i in 0..n {
            let h = x[i + 1] - x[i];
            for d in 0..dim {
                let o = (i * dim + d) * 2;
                c[o] = y[i * dim + d];
                c[o + 1] = (y[(i + 1) * dim + d] - y[i * dim + d]) / h;
            }
        }
        Ok(Self::from_parts(x.to_vec(), dim, 1, c))
    }

    /// The piecewise cubic that takes values `y` (row-major `n × dim`) and first derivatives
    /// `dydx` (same shape) at the breaks `x` (Drake's `CubicHermite`): C¹.
    pub fn cubic_hermite(x: &[f64], y: &[f64], dydx: &[f64], dim: usize) -> Result<Self> {
        validate::dim(dim)?;
        validate::increasing("x", x, 2)?;
        validate::values("y", y, x.len(), dim)?;
        validate::values("dydx", dydx, x.len(), dim)?;
        Ok(Self::cubic_hermite_unchecked(x, y, dydx, dim))
    }

    pub(crate) fn cubic_hermite_unchecked(x: &[f64], y: &[f64], m: &[f64], dim: usize) -> Self {
        let n = x.len() - 1;
        let mut c = vec![0.0; n * dim * 4];
        for i in 0..n {
            let h = x[i + 1] - x[i];
            for d in 0..dim {
                let y0 = y[i * dim + d];
                let y1 = y[(i + 1) * dim + d];
                let m0 = m[i * dim + d];
                let m1 = m[(i + 1) * dim + d];
                let slope = (y1 - y0) / h;
                let t = (m0 + m1 - 2.0 * slope) / h;
                let o = (i * dim + d) * 4;
                c[o] = y0;
                c[o + 1] = m0;
                c[o + 2] = (slope - m0) / h - t;
                c[o + 3] = t / h;
            }
        }
        Self::from_parts(x.to_vec(), dim, 3, c)
    }

    /// The piecewise quintic that takes values `y`, first derivatives `dydx` and second
    /// derivatives `d2ydx2` (each row-major `n × dim`) at the breaks `x`: C².
    pub fn quintic_hermite(
        x: &[f64],
        y: &[f64],
        dydx: &[f64],
        d2ydx2: &[f64],
        dim: usize,
    ) -> Result<Self> {
        validate::dim(dim)?;
        validate::increasing("x", x, 2)?;
        validate::values("y", y, x.len(), dim)?;
        validate::values("dydx", dydx, x.len(), dim)?;
        validate::values("d2ydx2", d2ydx2, x.len(), dim)?;
        let n = x.len() - 1;
        let mut c = vec![0.0; n * dim * 6];
        for i in 0..n {
            let h = x[i + 1] - x[i];
            for d in 0..dim {
                let (p0, p1) = (y[i * dim + d], y[(i + 1) * dim + d]);
                let (v0, v1) = (dydx[i * dim + d], dydx[(i + 1) * dim + d]);
                let (a0, a1) = (d2ydx2[i * dim + d], d2ydx2[(i + 1) * dim + d]);
                let o = (i * dim + d) * 6;
                c[o..o + 6].copy_from_slice(&quintic_coeffs(h, p0, p1, v0, v1, a0, a1));
            }
        }
        Ok(Self::from_parts(x.to_vec(), dim, 5, c))
    }

    /// The breaks `b_0 < … < b_n`.
    pub fn breaks(&self) -> &[f64] {
        &self.breaks
    }

    /// Number of components.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Polynomial degree of every piece.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Number of pieces (`breaks().len() − 1`).
    pub fn num_pieces(&self) -> usize {
        self.breaks.len() - 1
    }

    /// All coefficients, laid out as in the type documentation.
    pub fn coeffs(&self) -> &[f64] {
        &self.coeffs
    }

    /// The coefficients of piece `i` (`dim × (degree + 1)`, row-major, ascending powers of
    /// `s − b_i`). Panics if `i >= num_pieces()`.
    pub fn piece(&self, i: usize) -> &[f64] {
        let k = (self.degree + 1) * self.dim;
        &self.coeffs[i * k..(i + 1) * k]
    }

    /// The piece that holds `s` (clamped): `b_i <= s < b_{i+1}`, the last piece for `s >= b_n`.
    #[inline]
    pub fn piece_index(&self, s: f64) -> usize {
        crate::traj::find_piece(&self.breaks, s)
    }

    /// Like [`PiecewisePolynomial::piece_index`], starting the search at piece `hint`: O(1) when
    /// `s` is in that piece or the next one (sorted sweeps), binary search otherwise.
    #[inline]
    pub fn piece_index_from(&self, s: f64, hint: usize) -> usize {
        let n = self.breaks.len() - 1;
        if hint < n && s >= self.breaks[hint] {
            if hint + 1 == n || s < self.breaks[hint + 1] {
                return hint;
            }
            if hint + 2 == n || (hint + 2 < n && s < self.breaks[hint + 2]) {
                return hint + 1;
            }
        }
        self.piece_index(s)
    }

    /// Writes the `order`-th derivative at `s` (clamped to the interval) into `out[..dim]`.
    /// Orders above the degree give zeros; a NaN `s` gives NaN.
    #[inline]
    pub fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        let s = self.clamp(s);
        let i = self.piece_index(s);
        self.eval_piece(i, s, order, out);
    }

    /// Writes the `order`-th derivative at every parameter of `s` into `out` (row-major,
    /// `s.len() × dim`): for each point exactly what [`PiecewisePolynomial::eval`] writes
    /// (the same operations in the same order, so bitwise equal), without allocating.
    ///
    /// Each point's piece is searched from the previous point's piece
    /// ([`PiecewisePolynomial::piece_index_from`]): O(1) per point for increasing (or nearly
    /// increasing) parameters, a binary search otherwise, so any order of `s` is correct and
    /// sorted sweeps are fastest. Degrees 1, 3, 5 and 7 run with the piece width fixed at
    /// compile time. Panics only if `out` holds fewer than `s.len() × dim` values.
    ///
    /// ```
    /// use trajkit::spline::CubicSpline;
    /// use trajkit::Path;
    /// let sp = CubicSpline::natural(&[0.0, 1.0, 3.0], &[0.0, 1.0, 0.0, 2.0, 1.0, -1.0], 2)?;
    /// let s = [2.5, -1.0, 0.3, 0.7, 3.0];
    /// let mut many = [0.0; 10];
    /// sp.as_ppoly().eval_many(&s, 1, &mut many);
    /// let mut one = [0.0; 2];
    /// for (i, &si) in s.iter().enumerate() {
    ///     sp.eval(si, 1, &mut one);
    ///     assert_eq!(&many[2 * i..2 * i + 2], &one);
    /// }
    /// # Ok::<(), trajkit::Error>(())
    /// ```
    pub fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
        let out = &mut out[..s.len() * self.dim];
        match self.degree {
            1 => self.eval_many_fixed::<2>(s, order, out),
            3 => self.eval_many_fixed::<4>(s, order, out),
            5 => self.eval_many_fixed::<6>(s, order, out),
            7 => self.eval_many_fixed::<8>(s, order, out),
            _ => self.eval_many_general(s, order, out),
        }
    }

    /// [`PiecewisePolynomial::eval_many`] for any degree and dimension: `eval_piece` per
    /// point, each piece searched from the previous one.
    fn eval_many_general(&self, s: &[f64], order: usize, out: &mut [f64]) {
        let mut hint = 0;
        for (&si, o) in s.iter().zip(out.chunks_exact_mut(self.dim)) {
            let x = self.clamp(si);
            let i = if x.is_nan() {
                0
            } else {
                self.piece_index_from(x, hint)
            };
            hint = i;
            self.eval_piece(i, x, order, o);
        }
    }

    /// [`PiecewisePolynomial::eval_many`] with `K = degree + 1` fixed (the loops over a piece's
    /// coefficients unroll). Up to 16 components, each piece's coefficients (times the
    /// derivative factors) are transposed once per piece into a stack block, power-major, so
    /// that every point is one Horner pass over all components at once (the loop over
    /// components vectorizes). The arithmetic per component is `eval_piece`'s.
    fn eval_many_fixed<const K: usize>(&self, s: &[f64], order: usize, out: &mut [f64]) {
        let dim = self.dim;
        if order >= K {
            for (&x, o) in s.iter().zip(out.chunks_exact_mut(dim)) {
                o.fill(if x.is_nan() { f64::NAN } else { 0.0 });
            }
            return;
        }
        match dim {
            1 => self.eval_many_block::<K, 1>(s, order, out),
            2 => self.eval_many_block::<K, 2>(s, order, out),
            3 => self.eval_many_block::<K, 3>(s, order, out),
            4 => self.eval_many_block::<K, 4>(s, order, out),
            5 => self.eval_many_block::<K, 5>(s, order, out),
            6 => self.eval_many_block::<K, 6>(s, order, out),
            7 => self.eval_many_block::<K, 7>(s, order, out),
            8 => self.eval_many_block::<K, 8>(s, order, out),
            9..=16 => self.eval_many_block::<K, 16>(s, order, out),
            _ => self.eval_many_general(s, order, out),
        }
    }

    /// The block form of [`PiecewisePolynomial::eval_many_fixed`] for at most `MD` components
    /// (exactly `MD` for up to 8, so that the row copy has a fixed size):
    /// `block[j][d]` holds piece `i`'s `c[d][j] · j!/(j − order)!` (the factor 1 for order 0).
    fn eval_many_block<const K: usize, const MD: usize>(
        &self,
        s: &[f64],
        order: usize,
        out: &mut [f64],
    ) {
        let f = factors::<K>(order);
        let mut block = [[0.0; MD]; K];
        let mut piece = usize::MAX;
        let mut left = 0.0;
        for (&si, o) in s.iter().zip(out.chunks_exact_mut(self.dim)) {
            if si.is_nan() {
                o.fill(f64::NAN);
                continue;
            }
            let x = self.clamp(si);
            if self.sweep_to(x, &mut piece, &mut left) {
                self.fill_block(piece, order, &f, &mut block);
            }
            write_row(o, &horner_block(&block, order, x - left));
        }
    }

    /// Moves a sweep's `piece` (`usize::MAX` before the first point) to the piece holding `x`
    /// (clamped, not NaN), `left` to its left break; true when the piece changed.
    #[inline(always)]
    fn sweep_to(&self, x: f64, piece: &mut usize, left: &mut f64) -> bool {
        let i = self.piece_index_from(x, if *piece == usize::MAX { 0 } else { *piece });
        if i == *piece {
            return false;
        }
        *piece = i;
        *left = self.breaks[i];
        true
    }

    /// Piece `i`'s derivative block for `order` (see [`PiecewisePolynomial::eval_many_block`];
    /// `f` from [`factors`]), power-major.
    #[inline(always)]
    fn fill_block<const K: usize, const MD: usize>(
        &self,
        i: usize,
        order: usize,
        f: &[f64; K],
        block: &mut [[f64; MD]; K],
    ) {
        let dim = self.dim;
        let c = &self.coeffs[i * dim * K..(i + 1) * dim * K];
        for (d, cd) in c.chunks_exact(K).enumerate() {
            for j in 0..K {
                block[j][d] = if order == 0 { cd[j] } else { cd[j] * f[j] };
            }
        }
    }

    /// Writes orders 0 to 3 (position, first, second and third derivative) at every parameter
    /// of `s` into `out[0..4]` (each row-major, `s.len() × dim`): bitwise what
    /// [`PiecewisePolynomial::eval_many`] writes for each order, with one clamp and one piece
    /// search per point and the piece's four coefficient blocks made once per piece.
    /// Degrees 1, 3, 5 and 7 with up to 16 components take this fused pass; other shapes make
    /// the four `eval_many` calls. Panics only if an `out` slice is too short.
    pub fn eval_many_orders(&self, s: &[f64], out: [&mut [f64]; 4]) {
        let n = s.len() * self.dim;
        let out = out.map(|o| &mut o[..n]);
        match (self.degree, self.dim) {
            (1, 1..=16) => self.eval_orders_fixed::<2>(s, out),
            (3, 1..=16) => self.eval_orders_fixed::<4>(s, out),
            (5, 1..=16) => self.eval_orders_fixed::<6>(s, out),
            (7, 1..=16) => self.eval_orders_fixed::<8>(s, out),
            _ => {
                for (order, o) in out.into_iter().enumerate() {
                    self.eval_many(s, order, o);
                }
            }
        }
    }

    /// [`PiecewisePolynomial::eval_many_orders`] with `K = degree + 1` fixed, by component
    /// count (exactly `MD` up to 8, at most 16 otherwise).
    fn eval_orders_fixed<const K: usize>(&self, s: &[f64], out: [&mut [f64]; 4]) {
        match self.dim {
            1 => self.eval_orders_block::<K, 1>(s, out),
            2 => self.eval_orders_block::<K, 2>(s, out),
            3 => self.eval_orders_block::<K, 3>(s, out),
            4 => self.eval_orders_block::<K, 4>(s, out),
            5 => self.eval_orders_block::<K, 5>(s, out),
            6 => self.eval_orders_block::<K, 6>(s, out),
            7 => self.eval_orders_block::<K, 7>(s, out),
            8 => self.eval_orders_block::<K, 8>(s, out),
            _ => self.eval_orders_block::<K, 16>(s, out),
        }
    }

    /// The fused form of [`PiecewisePolynomial::eval_many_block`]: `blocks[m]` is that
    /// function's block for order `m`, and each order's Horner pass is its pass (same
    /// operations, same order); orders at or above `K` are zeros, as `eval_many_fixed` writes.
    fn eval_orders_block<const K: usize, const MD: usize>(&self, s: &[f64], out: [&mut [f64]; 4]) {
        let dim = self.dim;
        let f = [0, 1, 2, 3].map(factors::<K>);
        let mut blocks = [[[0.0; MD]; K]; 4];
        let mut piece = usize::MAX;
        let mut left = 0.0;
        let [o0, o1, o2, o3] = out;
        let rows = o0
            .chunks_exact_mut(dim)
            .zip(o1.chunks_exact_mut(dim))
            .zip(o2.chunks_exact_mut(dim))
            .zip(o3.chunks_exact_mut(dim));
        for (&si, (((r0, r1), r2), r3)) in s.iter().zip(rows) {
            let rows = [r0, r1, r2, r3];
            if si.is_nan() {
                rows.into_iter().for_each(|r| r.fill(f64::NAN));
                continue;
            }
            let x = self.clamp(si);
            if self.sweep_to(x, &mut piece, &mut left) {
                for (m, (fm, block)) in f.iter().zip(&mut blocks).enumerate().take(K) {
                    self.fill_block(piece, m, fm, block);
                }
            }
            let h = x - left;
            for (m, o) in rows.into_iter().enumerate() {
                if m >= K {
                    o.fill(0.0);
                    continue;
                }
                write_row(o, &horner_block(&blocks[m], m, h));
            }
        }
    }

    /// Writes the first derivative at `s` (clamped) into `first[..dim]` and the second into
    /// `second[..dim]`, with one piece search and one pass over each component's coefficients;
    /// the values are those of [`PiecewisePolynomial::eval`] with orders 1 and 2.
    pub fn eval_derivatives(&self, s: f64, first: &mut [f64], second: &mut [f64]) {
        let dim = self.dim;
        let (first, second) = (&mut first[..dim], &mut second[..dim]);
        let k = self.degree + 1;
        if s.is_nan() || !(3..=16).contains(&k) {
            self.eval(s, 1, first);
            self.eval(s, 2, second);
            return;
        }
        let s = self.clamp(s);
        let i = self.piece_index(s);
        let h = s - self.breaks[i];
        let base = i * dim * k;
        let block = &self.coeffs[base..base + dim * k];
        // The factors j and j·(j − 1), as `eval_piece` uses them.
        let mut f1 = [0.0; 16];
        let mut f2 = [0.0; 16];
        for j in 1..k {
            f1[j] = j as f64;
            f2[j] = (j * (j - 1)) as f64;
        }
        for ((d1, d2), c) in first
            .iter_mut()
            .zip(second.iter_mut())
            .zip(block.chunks_exact(k))
        {
            let (mut a1, mut a2) = (0.0, 0.0);
            for j in (2..k).rev() {
                a1 = a1 * h + c[j] * f1[j];
                a2 = a2 * h + c[j] * f2[j];
            }
            *d1 = a1 * h + c[1];
            *d2 = a2;
        }
    }

    /// Clamps `s` to the interval (NaN stays NaN).
    #[inline]
    pub(crate) fn clamp(&self, s: f64) -> f64 {
        let a = self.breaks[0];
        let b = self.breaks[self.breaks.len() - 1];
        if s < a {
            a
        } else if s > b {
            b
        } else {
            s
        }
    }

    /// Evaluates piece `i`'s polynomial at `s` (no clamping).
    #[inline]
    pub(crate) fn eval_piece(&self, i: usize, s: f64, order: usize, out: &mut [f64]) {
        let dim = self.dim;
        let out = &mut out[..dim];
        if s.is_nan() {
            out.fill(f64::NAN);
            return;
        }
        let k = self.degree + 1;
        if order > self.degree {
            out.fill(0.0);
            return;
        }
        let h = s - self.breaks[i];
        let base = i * dim * k;
        let block = &self.coeffs[base..base + dim * k];
        if order == 0 {
            for (o, c) in out.iter_mut().zip(block.chunks_exact(k)) {
                let mut acc = c[k - 1];
                for j in (0..k - 1).rev() {
                    acc = acc * h + c[j];
                }
                *o = acc;
            }
        } else if k <= 16 {
            // The factors j!/(j−order)! are the same for every component: once per call.
            let mut f = [0.0; 16];
            for j in order..k {
                f[j] = falling(j, order);
            }
            for (o, c) in out.iter_mut().zip(block.chunks_exact(k)) {
                let mut acc = 0.0;
                for j in (order..k).rev() {
                    acc = acc * h + c[j] * f[j];
                }
                *o = acc;
            }
        } else {
            for (o, c) in out.iter_mut().zip(block.chunks_exact(k)) {
                let mut acc = 0.0;
                for j in (order..k).rev() {
                    acc = acc * h + c[j] * falling(j, order);
                }
                *o = acc;
            }
        }
    }

    /// The `order`-th derivative as a piecewise polynomial of degree `degree − order` (degree 0
    /// with zero coefficients when `order > degree`).
    pub fn derivative(&self, order: usize) -> PiecewisePolynomial {
        let n = self.num_pieces();
        let k = self.degree + 1;
        if order > self.degree {
            return Self::from_parts(self.breaks.clone(), self.dim, 0, vec![0.0; n * self.dim]);
        }
        let nk = k - order;
        let mut c = Vec::with_capacity(n * self.dim * nk);
        for blk in self.coeffs.chunks_exact(k) {
            for j in order..k {
                c.push(blk[j] * falling(j, order));
            }
        }
        Self::from_parts(self.breaks.clone(), self.dim, self.degree - order, c)
    }

    /// The antiderivative that is zero at `b_0`, continuous across breaks (degree + 1).
    pub fn antiderivative(&self) -> PiecewisePolynomial {
        let n = self.num_pieces();
        let k = self.degree + 1;
        let dim = self.dim;
        let mut c = vec![0.0; n * dim * (k + 1)];
        let mut acc = vec![0.0; dim];
        for i in 0..n {
            let h = self.breaks[i + 1] - self.breaks[i];
            for d in 0..dim {
                let src = &self.coeffs[(i * dim + d) * k..(i * dim + d + 1) * k];
                let dst = &mut c[(i * dim + d) * (k + 1)..(i * dim + d + 1) * (k + 1)];
                dst[0] = acc[d];
                for j in 0..k {
                    dst[j + 1] = src[j] / (j + 1) as f64;
                }
                let mut v = dst[k];
                for j in (0..k).rev() {
                    v = v * h + dst[j];
                }
                acc[d] = v;
            }
        }
        Self::from_parts(self.breaks.clone(), dim, self.degree + 1, c)
    }
}

impl crate::Path for PiecewisePolynomial {
    fn dim(&self) -> usize {
        self.dim
    }
    fn interval(&self) -> (f64, f64) {
        (self.breaks[0], self.breaks[self.breaks.len() - 1])
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        PiecewisePolynomial::eval(self, s, order, out)
    }
    fn eval_derivatives(&self, s: f64, first: &mut [f64], second: &mut [f64]) {
        PiecewisePolynomial::eval_derivatives(self, s, first, second)
    }
    fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
        PiecewisePolynomial::eval_many(self, s, order, out)
    }
    fn eval_many_orders(&self, s: &[f64], out: [&mut [f64]; 4]) {
        PiecewisePolynomial::eval_many_orders(self, s, out)
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.breaks.clone()
    }
    fn piecewise_degree(&self) -> Option<usize> {
        Some(self.degree)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_and_antiderivative_roundtrip() {
        let pp = PiecewisePolynomial::new(
            vec![0.0, 1.0, 3.0],
            2,
            3,
            vec![
                1.0, 2.0, -1.0, 0.5, 0.0, 1.0, 1.0, 1.0, // piece 0
                2.5, 0.5, 0.5, -0.25, 3.0, 6.0, 4.0, 1.0, // piece 1
            ],
        )
        .unwrap();
        let dp = pp.derivative(1);
        let mut a = [0.0; 2];
        let mut b = [0.0; 2];
        for &s in &[0.0, 0.3, 1.0, 1.7, 2.9, 3.0] {
            for ord in 0..5 {
                pp.eval(s, ord + 1, &mut a);
                dp.eval(s, ord, &mut b);
                assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
            }
        }
        let ip = dp.antiderivative();
        let mut v0 = [0.0; 2];
        pp.eval(0.0, 0, &mut v0);
        for &s in &[0.0, 0.5, 1.0, 2.0, 3.0] {
            pp.eval(s, 0, &mut a);
            ip.eval(s, 0, &mut b);
            // Piece 0 is continuous into piece 1 only at d = 0 (2.5 vs 1+2-1+0.5); compare
            // within piece 0 where the antiderivative of the derivative is exact.
            if s <= 1.0 {
                assert!((a[0] - v0[0] - b[0]).abs() < 1e-12, "s={s}");
            }
        }
    }

    #[test]
    fn derivative_pair_equals_single_evaluations() {
        let mut rng = crate::rng::SplitMix64::new(11);
        for degree in 0..=7usize {
            let breaks = vec![-1.0, 0.25, 0.5, 2.0];
            let dim = 3;
            let coeffs: Vec<f64> = (0..3 * dim * (degree + 1))
                .map(|_| rng.uniform(-5.0, 5.0))
                .collect();
            let pp = PiecewisePolynomial::new(breaks, dim, degree, coeffs).unwrap();
            let (mut d1, mut d2, mut e1, mut e2) = ([0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]);
            for s in [-2.0, -1.0, -0.3, 0.25, 0.4, 1.9, 2.0, 3.0, f64::NAN] {
                pp.eval_derivatives(s, &mut d1, &mut d2);
                pp.eval(s, 1, &mut e1);
                pp.eval(s, 2, &mut e2);
                for j in 0..dim {
                    // Bitwise: the same operations in the same order.
                    assert_eq!(d1[j].to_bits(), e1[j].to_bits(), "degree {degree}, s = {s}");
                    assert_eq!(d2[j].to_bits(), e2[j].to_bits(), "degree {degree}, s = {s}");
                }
            }
        }
    }

    #[test]
    fn hints_agree_with_binary_search() {
        let breaks: Vec<f64> = (0..11).map(|i| (i * i) as f64).collect();
        let pp = PiecewisePolynomial::from_parts(breaks, 1, 0, vec![0.0; 10]);
        for h in 0..10 {
            for k in 0..=1000 {
                let s = k as f64 * 0.1 - 0.5;
                assert_eq!(pp.piece_index_from(s, h), pp.piece_index(s), "s={s} h={h}");
            }
        }
    }

    /// `eval_many` writes what `eval` writes, bitwise, for every degree (the fixed-width and the
    /// general loops), order, and order of the parameters (sorted, reversed, random, repeated,
    /// out of range, NaN).
    /// A random piecewise polynomial of 9 pieces, and parameters to evaluate it at: a sorted
    /// sweep past both ends (breaks included), random ones with NaN, ends and infinities, and
    /// the sweep reversed.
    fn random_case(
        rng: &mut crate::rng::SplitMix64,
        degree: usize,
        dim: usize,
    ) -> (PiecewisePolynomial, [Vec<f64>; 3]) {
        let mut breaks = vec![rng.uniform(-2.0, 0.0)];
        for _ in 0..9 {
            let last = *breaks.last().unwrap();
            breaks.push(last + rng.uniform(0.05, 1.5));
        }
        let (a, b) = (breaks[0], breaks[9]);
        let coeffs: Vec<f64> = (0..9 * dim * (degree + 1))
            .map(|_| rng.uniform(-5.0, 5.0))
            .collect();
        let pp = PiecewisePolynomial::new(breaks.clone(), dim, degree, coeffs).unwrap();
        let sorted: Vec<f64> = (0..=400)
            .map(|i| a - 0.3 + (b - a + 0.6) * i as f64 / 400.0)
            .chain(breaks.iter().copied())
            .collect();
        let mut random: Vec<f64> = (0..300).map(|_| rng.uniform(a - 1.0, b + 1.0)).collect();
        random.extend([f64::NAN, a, b, b, a, f64::INFINITY, f64::NEG_INFINITY]);
        let reversed: Vec<f64> = sorted.iter().rev().copied().collect();
        (pp, [sorted, random, reversed])
    }

    #[test]
    fn eval_many_equals_eval_bitwise() {
        let mut rng = crate::rng::SplitMix64::new(29);
        for degree in 0..=8usize {
            for dim in [1usize, 2, 3, 4, 5, 6, 7, 8, 12, 17] {
                let (pp, params) = random_case(&mut rng, degree, dim);
                for s in &params {
                    for order in 0..=degree + 1 {
                        let mut many = vec![7.0; s.len() * dim];
                        pp.eval_many(s, order, &mut many);
                        let mut one = vec![0.0; dim];
                        for (i, &si) in s.iter().enumerate() {
                            pp.eval(si, order, &mut one);
                            for d in 0..dim {
                                assert_eq!(
                                    many[i * dim + d].to_bits(),
                                    one[d].to_bits(),
                                    "degree {degree} dim {dim} order {order} s = {si}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// The fused four-order sweep writes bitwise what `eval_many` writes for each order, on
    /// every degree (fused or not), dimension (fixed, wide, beyond 16) and parameter order,
    /// NaN and out-of-range parameters included.
    #[test]
    fn eval_many_orders_equals_eval_many_bitwise() {
        let mut rng = crate::rng::SplitMix64::new(31);
        for degree in 0..=8usize {
            for dim in [1usize, 2, 3, 5, 7, 8, 9, 16, 17] {
                let (pp, params) = random_case(&mut rng, degree, dim);
                for s in &params {
                    let n = s.len() * dim;
                    let mut fused = [0; 4].map(|_| vec![7.0; n]);
                    let [q, v, acc, j] = &mut fused;
                    pp.eval_many_orders(s, [q, v, acc, j]);
                    for (order, f) in fused.iter().enumerate() {
                        let mut many = vec![-7.0; n];
                        pp.eval_many(s, order, &mut many);
                        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                        assert_eq!(
                            bits(f),
                            bits(&many),
                            "degree {degree} dim {dim} order {order}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn quintic_hermite_hits_its_data() {
        let x = [0.0, 0.7, 2.0];
        let y = [0.0, 1.0, -1.0];
        let v = [0.5, -2.0, 1.0];
        let a = [3.0, 0.0, -4.0];
        let pp = PiecewisePolynomial::quintic_hermite(&x, &y, &v, &a, 1).unwrap();
        let mut o = [0.0];
        for i in 0..3 {
            for (ord, want) in [(0, y[i]), (1, v[i]), (2, a[i])] {
                pp.eval(x[i], ord, &mut o);
                assert!(
                    (o[0] - want).abs() < 1e-12,
                    "i={i} ord={ord} {} {}",
                    o[0],
                    want
                );
                if i == 1 {
                    pp.eval_piece(0, x[1], ord, &mut o);
                    assert!((o[0] - want).abs() < 1e-12);
                }
            }
        }
    }
}
