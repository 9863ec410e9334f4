//! Fitting constructors of [`BSpline`]: interpolation with scipy's default knots or with
//! end-derivative conditions (minimum-jerk, minimum-snap), and weighted least squares by
//! banded Givens QR. The square collocation solve (banded LU) is shared with degree
//! elevation.

use super::{check_knots, singular, too_high, BSpline, EndDerivative, MAX_DEGREE};
use crate::error::{Error, Result};
use crate::spline::banded::Banded;
use crate::spline::basis::{basis_ders, basis_funs, find_span, K1};
use crate::spline::validate;

impl BSpline {
    /// Interpolation through `y` (row-major `n × dim`) at increasing `x` with scipy's default
    /// knots (`make_interp_spline` with no boundary conditions): for odd degree the not-a-knot
    /// knots (the data sites without the `(k−1)/2` next to each end), for even degree the
    /// midpoints without the `k/2` next to each end; degree 1 is the broken line. Needs at
    /// least `degree + 1` points.
    pub fn interpolate(x: &[f64], y: &[f64], dim: usize, degree: usize) -> Result<BSpline> {
        validate::interpolation_data(x, y, dim, 2)?;
        let k = degree;
        if k > MAX_DEGREE {
            return Err(too_high(k));
        }
        let n = x.len();
        if n < k + 1 {
            return Err(Error::TooFewWaypoints {
                needed: k + 1,
                found: n,
            });
        }
        let (x0, xn) = (x[0], x[n - 1]);
        let mut t = vec![x0; k + 1];
        if k == 0 {
            t = x.to_vec();
            t.push(xn);
            return Ok(BSpline {
                k,
                dim,
                t,
                c: y.to_vec(),
            });
        }
        if k == 1 {
            t = vec![x0];
            t.extend_from_slice(x);
            t.push(xn);
            return Ok(BSpline {
                k,
                dim,
                t,
                c: y.to_vec(),
            });
        }
        if k % 2 == 1 {
            let k2 = k.div_ceil(2);
            t.extend_from_slice(&x[k2..n - k2]);
        } else {
            let k2 = k / 2;
            let mids: Vec<f64> = (0..n - 1).map(|i| (x[i + 1] + x[i]) / 2.0).collect();
            t.extend_from_slice(&mids[k2..n - 1 - k2]);
        }
        t.extend(std::iter::repeat_n(xn, k + 1));
        let rows: Vec<Row> = x.iter().map(|&s| Row::at(s, 0)).collect();
        let c = collocate(&t, k, &rows, y, dim).map_err(|_| singular("x"))?;
        Ok(BSpline { k, dim, t, c })
    }

    /// Interpolation through `y` at `x` with derivative conditions at the ends, on the knots
    /// `x` with each end repeated `degree + 1` times (scipy's `make_interp_spline` with
    /// `bc_type=(start, end)`). `start.len() + end.len()` must be `degree − 1`.
    pub fn interpolate_with_ends(
        x: &[f64],
        y: &[f64],
        dim: usize,
        degree: usize,
        start: &[EndDerivative<'_>],
        end: &[EndDerivative<'_>],
    ) -> Result<BSpline> {
        validate::interpolation_data(x, y, dim, 2)?;
        let k = degree;
        if !(2..=MAX_DEGREE).contains(&k) {
            return Err(Error::InvalidValue {
                field: "degree of interpolation with end derivatives".into(),
                value: k as f64,
                reason: "must be between 2 and 20",
            });
        }
        if start.len() + end.len() != k - 1 {
            return Err(Error::DimensionMismatch {
                what: format!("end-derivative conditions (degree − 1 for degree {k})"),
                expected: k - 1,
                found: start.len() + end.len(),
            });
        }
        for (side, conds) in [("start", start), ("end", end)] {
            for (i, e) in conds.iter().enumerate() {
                if e.order == 0 || e.order > k {
                    return Err(Error::InvalidValue {
                        field: format!("{side} condition {i} derivative order"),
                        value: e.order as f64,
                        reason: "must be between 1 and the degree",
                    });
                }
                validate::values(&format!("{side} condition {i} value"), e.value, 1, dim)?;
            }
        }
        let n = x.len();
        let (x0, xn) = (x[0], x[n - 1]);
        let mut t = vec![x0; k];
        t.extend_from_slice(x);
        t.extend(std::iter::repeat_n(xn, k));
        let mut rows = Vec::with_capacity(n + k - 1);
        let mut rhs = Vec::with_capacity((n + k - 1) * dim);
        for e in start {
            rows.push(Row::at(x0, e.order));
            rhs.extend_from_slice(e.value);
        }
        for (i, &s) in x.iter().enumerate() {
            rows.push(Row::at(s, 0));
            rhs.extend_from_slice(&y[i * dim..(i + 1) * dim]);
        }
        for e in end {
            rows.push(Row::at(xn, e.order));
            rhs.extend_from_slice(e.value);
        }
        let c = collocate(&t, k, &rows, &rhs, dim).map_err(|_| singular("x"))?;
        Ok(BSpline { k, dim, t, c })
    }

    /// The multi-segment **minimum-jerk** trajectory through `y` at times `x`: the quintic
    /// (C⁴) interpolating spline with velocity and acceleration given at both ends. Among all
    /// curves through the waypoints with those end conditions it minimizes ∫‖σ‴‖². Needs at
    /// least 2 waypoints; each end vector has `dim` entries.
    ///
    /// ```
    /// use trajkit::{spline::BSpline, Path};
    /// let x = [0.0, 1.0, 2.5, 3.0];
    /// let y = [0.0, 1.0, -1.0, 0.5];
    /// let z = [0.0];
    /// let mj = BSpline::minimum_jerk(&x, &y, 1, &z, &z, &z, &z)?;
    /// let mut v = [0.0];
    /// mj.eval(2.5, 0, &mut v);
    /// assert!((v[0] + 1.0).abs() < 1e-12);
    /// mj.eval(3.0, 1, &mut v); // rest at the end
    /// assert!(v[0].abs() < 1e-12);
    /// # Ok::<(), trajkit::Error>(())
    /// ```
    pub fn minimum_jerk(
        x: &[f64],
        y: &[f64],
        dim: usize,
        v_start: &[f64],
        a_start: &[f64],
        v_end: &[f64],
        a_end: &[f64],
    ) -> Result<BSpline> {
        let e = |order, value| EndDerivative { order, value };
        Self::interpolate_with_ends(
            x,
            y,
            dim,
            5,
            &[e(1, v_start), e(2, a_start)],
            &[e(1, v_end), e(2, a_end)],
        )
    }

    /// The multi-segment **minimum-snap** trajectory through `y` at times `x`: the degree-7
    /// (C⁶) interpolating spline with velocity, acceleration and jerk given at both ends; it
    /// minimizes ∫‖σ⁗‖² among curves through the waypoints with those end conditions.
    pub fn minimum_snap(
        x: &[f64],
        y: &[f64],
        dim: usize,
        start: [&[f64]; 3],
        end: [&[f64]; 3],
    ) -> Result<BSpline> {
        let e = |order, value| EndDerivative { order, value };
        Self::interpolate_with_ends(
            x,
            y,
            dim,
            7,
            &[e(1, start[0]), e(2, start[1]), e(3, start[2])],
            &[e(1, end[0]), e(2, end[1]), e(3, end[2])],
        )
    }

    /// Weighted least-squares approximation of `y` (row-major `m × dim`) at non-decreasing
    /// `x` by a B-spline of `degree` on the given knots (scipy's `make_lsq_spline`): minimizes
    /// `Σ w_j² ‖σ(x_j) − y_j‖²` (`w` all ones when `None`). Banded QR by Givens rotations, so the
    /// normal equations' squared condition number is avoided. The data must satisfy the
    /// Schoenberg–Whitney condition for the knots, otherwise a typed error.
    pub fn least_squares(
        x: &[f64],
        y: &[f64],
        dim: usize,
        knots: &[f64],
        degree: usize,
        w: Option<&[f64]>,
    ) -> Result<BSpline> {
        let data = LsqData {
            x,
            y,
            dim,
            knots,
            k: degree,
            w,
        };
        let n = data.check()?;
        let (mut r, mut z) = data.givens_band(n);
        back_substitute(&mut r, &mut z, degree + 1, n, dim)?;
        Ok(BSpline {
            k: degree,
            dim,
            t: knots.to_vec(),
            c: z,
        })
    }
}

/// One collocation condition: the `order`-th derivative at `s`.
#[derive(Clone, Copy)]
pub(super) struct Row {
    s: f64,
    order: usize,
}

impl Row {
    pub(super) fn at(s: f64, order: usize) -> Row {
        Row { s, order }
    }
}

/// Solves the square collocation system `Σ_j c_j N_j^(order_r)(s_r) = rhs_r` (one row per
/// condition, in order) by banded LU; the bandwidth is measured from the rows.
pub(super) fn collocate(
    t: &[f64],
    k: usize,
    rows: &[Row],
    rhs: &[f64],
    dim: usize,
) -> std::result::Result<Vec<f64>, crate::spline::banded::Singular> {
    let n = t.len() - k - 1;
    debug_assert_eq!(rows.len(), n);
    let mut firsts = Vec::with_capacity(n);
    let mut vals = vec![0.0; n * (k + 1)];
    let (mut kl, mut ku) = (0usize, 0usize);
    for (i, r) in rows.iter().enumerate() {
        let l = find_span(t, k, r.s);
        basis_ders(t, k, l, r.s, r.order, &mut vals[i * (k + 1)..]);
        let f = l - k;
        firsts.push(f);
        kl = kl.max(i.saturating_sub(f));
        ku = ku.max((f + k).saturating_sub(i));
    }
    let mut a = Banded::zeros(n, kl, ku);
    for i in 0..n {
        for j in 0..=k {
            a.set(i, firsts[i] + j, vals[i * (k + 1) + j]);
        }
    }
    a.factor()?;
    let mut c = rhs.to_vec();
    a.solve(&mut c, dim);
    Ok(c)
}

/// The data of [`BSpline::least_squares`]: `m` parameters `x`, values `y` (`m × dim`), the
/// knots, the degree `k` and the optional weights.
#[derive(Clone, Copy)]
struct LsqData<'a> {
    x: &'a [f64],
    y: &'a [f64],
    dim: usize,
    knots: &'a [f64],
    k: usize,
    w: Option<&'a [f64]>,
}

impl LsqData<'_> {
    /// Validates the data; returns the number of control points.
    fn check(&self) -> Result<usize> {
        let LsqData {
            x,
            y,
            dim,
            knots,
            k,
            w,
        } = *self;
        validate::dim(dim)?;
        if knots.len() < k + 2 {
            return Err(Error::TooFewWaypoints {
                needed: k + 2,
                found: knots.len(),
            });
        }
        let n = knots.len() - k - 1;
        check_knots(knots, k, n)?;
        validate::nondecreasing("x", x)?;
        validate::values("y", y, x.len(), dim)?;
        if let Some(w) = w {
            validate::values("w", w, x.len(), 1)?;
        }
        let (a, b) = (knots[k], knots[n]);
        if let Some(i) = x.iter().position(|&v| v < a || v > b) {
            return Err(Error::InvalidValue {
                field: format!("x[{i}]"),
                value: x[i],
                reason: "is outside the knots' base interval",
            });
        }
        if x.len() < n {
            return Err(Error::TooFewWaypoints {
                needed: n,
                found: x.len(),
            });
        }
        Ok(n)
    }

    /// Folds the weighted observation rows into an upper-triangular band by Givens rotations:
    /// returns `R` (row `i` holds `R[i][i..=i+k]`, `n × (k + 1)`) and the rotated right-hand side
    /// `z` (`n × dim`).
    fn givens_band(&self, n: usize) -> (Vec<f64>, Vec<f64>) {
        let LsqData {
            x,
            y,
            dim,
            knots,
            k,
            w,
        } = *self;
        let k1 = k + 1;
        let mut r = vec![0.0f64; n * k1];
        let mut z = vec![0.0; n * dim];
        let mut row = [0.0; K1];
        let mut yr = vec![0.0; dim];
        for (j, &s) in x.iter().enumerate() {
            let wj = w.map_or(1.0, |w| w[j]);
            let l = find_span(knots, k, s);
            basis_funs(knots, k, l, s, &mut row);
            for v in row[..k1].iter_mut() {
                *v *= wj;
            }
            for d in 0..dim {
                yr[d] = wj * y[j * dim + d];
            }
            let f = l - k;
            for i in 0..k1 {
                if row[i] == 0.0 {
                    continue;
                }
                let col = f + i;
                let p: f64 = r[col * k1];
                let h = p.hypot(row[i]);
                let (cs, sn) = (p / h, row[i] / h);
                r[col * k1] = h;
                for q in 1..k1 - i {
                    let a = r[col * k1 + q];
                    let b = row[i + q];
                    r[col * k1 + q] = cs * a + sn * b;
                    row[i + q] = -sn * a + cs * b;
                }
                for d in 0..dim {
                    let a = z[col * dim + d];
                    z[col * dim + d] = cs * a + sn * yr[d];
                    yr[d] = -sn * a + cs * yr[d];
                }
            }
        }
        (r, z)
    }
}

/// Solves `R c = z` in place (`c` overwrites `z`) for the band `R` of [`LsqData::givens_band`]; a
/// diagonal entry below 1e-14 of the band's largest entry is a Schoenberg–Whitney failure.
fn back_substitute(r: &mut [f64], z: &mut [f64], k1: usize, n: usize, dim: usize) -> Result<()> {
    let scale = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for i in (0..n).rev() {
        let dgn = r[i * k1];
        if dgn.abs() <= scale * 1e-14 {
            return Err(singular("x"));
        }
        for d in 0..dim {
            let mut v = z[i * dim + d];
            for q in 1..k1.min(n - i) {
                v -= r[i * k1 + q] * z[(i + q) * dim + d];
            }
            z[i * dim + d] = v / dgn;
        }
    }
    Ok(())
}
