//! NURBS curves: rational B-splines with weights, rational derivatives of any order, exact
//! circles and arcs.

use crate::error::{Error, Result};
use crate::spline::basis::{basis_ders, find_span, K1};
use crate::spline::bspline::BSpline;
use crate::spline::validate;

/// Highest derivative order a NURBS evaluates; higher orders write NaN.
pub const NURBS_MAX_ORDER: usize = 31;

/// A non-uniform rational B-spline `C(s) = Σ N_{i,k}(s) w_i P_i / Σ N_{i,k}(s) w_i` with
/// positive weights, on the base interval `[t_k, t_n]` (clamped outside it, like every curve in
/// [`crate::spline`]).
///
/// Derivatives come from `A = Σ N_i w_i P_i` and `W = Σ N_i w_i` by the quotient recurrence
/// `C⁽ʲ⁾ = (A⁽ʲ⁾ − Σ_{i=1..j} C(j,i) W⁽ⁱ⁾ C⁽ʲ⁻ⁱ⁾) / W`, per component on stack buffers (no
/// allocation), up to order [`NURBS_MAX_ORDER`].
///
/// ```
/// use trajkit::{spline::Nurbs, Path};
/// let c = Nurbs::circle([0.0, 0.0], 1.0)?;
/// let mut p = [0.0; 2];
/// c.eval(0.3, 0, &mut p);
/// assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-15);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    k: usize,
    dim: usize,
    t: Vec<f64>,
    /// Weighted control points w_i P_i, row-major n × dim.
    wp: Vec<f64>,
    w: Vec<f64>,
}

impl Nurbs {
    /// From knots, control points `P_i` (row-major `n × dim`) and weights `w_i > 0`.
    pub fn new(
        knots: &[f64],
        points: &[f64],
        weights: &[f64],
        dim: usize,
        degree: usize,
    ) -> Result<Self> {
        // The knot/point checks are those of a B-spline on the same data.
        BSpline::new(knots, points, dim, degree)?;
        let n = points.len() / dim;
        validate::len("NURBS weight count", weights, n)?;
        for (i, &w) in weights.iter().enumerate() {
            if !(w.is_finite() && w > 0.0) {
                return Err(Error::InvalidValue {
                    field: format!("weights[{i}]"),
                    value: w,
                    reason: "is not a positive finite number",
                });
            }
        }
        let wp = (0..n * dim).map(|j| points[j] * weights[j / dim]).collect();
        Ok(Nurbs {
            k: degree,
            dim,
            t: knots.to_vec(),
            wp,
            w: weights.to_vec(),
        })
    }

    /// A B-spline as a NURBS with unit weights.
    pub fn from_bspline(b: &BSpline) -> Nurbs {
        let n = b.num_control_points();
        Nurbs {
            k: b.degree(),
            dim: b.dim(),
            t: b.knots().to_vec(),
            wp: b.control_points().to_vec(),
            w: vec![1.0; n],
        }
    }

    /// The full circle in the plane as the classic 9-point quadratic NURBS on `[0, 1]`, starting
    /// at `center + (radius, 0)` and running counter-clockwise (each quarter on a quarter of the
    /// parameter interval, not at constant speed).
    pub fn circle(center: [f64; 2], radius: f64) -> Result<Self> {
        Self::arc(center, radius, 0.0, 2.0 * std::f64::consts::PI)
    }

    /// A circular arc in the plane from angle `start` to `end` (radians, counter-clockwise when
    /// `end > start`, `0 < |end − start| <= 2π`) as a quadratic NURBS on `[0, 1]`, with one
    /// rational segment per (at most) quarter turn.
    pub fn arc(center: [f64; 2], radius: f64, start: f64, end: f64) -> Result<Self> {
        crate::error::positive(|| "arc radius".into(), radius)?;
        crate::error::finite(|| "arc start angle".into(), start)?;
        crate::error::finite(|| "arc end angle".into(), end)?;
        let sweep = end - start;
        let tau = 2.0 * std::f64::consts::PI;
        if sweep == 0.0 || sweep.abs() > tau * (1.0 + 1e-15) {
            return Err(Error::InvalidValue {
                field: "arc sweep (end − start)".into(),
                value: sweep,
                reason: "must be non-zero and at most 2π in magnitude",
            });
        }
        let segs = ((sweep.abs() / (0.5 * std::f64::consts::PI)) - 1e-12)
            .ceil()
            .max(1.0) as usize;
        let d = sweep / segs as f64;
        let wm = (0.5 * d).cos();
        let mut pts = Vec::with_capacity((2 * segs + 1) * 2);
        let mut wts = Vec::with_capacity(2 * segs + 1);
        let on = |a: f64| {
            // Exact values on the axes keep the classic circle's control points exact.
            let (s, c) = a.sin_cos();
            let snap = |v: f64| if v.abs() < 1e-15 { 0.0 } else { v };
            [center[0] + radius * snap(c), center[1] + radius * snap(s)]
        };
        let p0 = on(start);
        pts.extend_from_slice(&p0);
        wts.push(1.0);
        for i in 0..segs {
            let a0 = start + d * i as f64;
            let a1 = if i + 1 == segs { end } else { a0 + d };
            let mid = 0.5 * (a0 + a1);
            let r = radius / (0.5 * (a1 - a0)).cos();
            let (s, c) = mid.sin_cos();
            let snap = |v: f64| {
                if (v.abs() - 1.0).abs() < 1e-15 {
                    v.signum()
                } else if v.abs() < 1e-15 {
                    0.0
                } else {
                    v
                }
            };
            pts.extend_from_slice(&[center[0] + r * snap(c), center[1] + r * snap(s)]);
            wts.push(wm);
            pts.extend_from_slice(&on(a1));
            wts.push(1.0);
        }
        let mut t = vec![0.0; 3];
        for i in 1..segs {
            let u = i as f64 / segs as f64;
            t.push(u);
            t.push(u);
        }
        t.extend_from_slice(&[1.0; 3]);
        Self::new(&t, &pts, &wts, 2, 2)
    }

    /// Degree.
    pub fn degree(&self) -> usize {
        self.k
    }

    /// Knots.
    pub fn knots(&self) -> &[f64] {
        &self.t
    }

    /// Weights.
    pub fn weights(&self) -> &[f64] {
        &self.w
    }

    /// Control points `P_i` (unweighted), row-major `n × dim`.
    pub fn control_points(&self) -> Vec<f64> {
        (0..self.wp.len())
            .map(|j| self.wp[j] / self.w[j / self.dim])
            .collect()
    }

    /// The base interval.
    pub fn domain(&self) -> (f64, f64) {
        (self.t[self.k], self.t[self.w.len()])
    }

    /// Writes the `order`-th derivative at `s` (clamped) into `out[..dim]`.
    pub fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        let dim = self.dim;
        let out = &mut out[..dim];
        if s.is_nan() || order > NURBS_MAX_ORDER {
            out.fill(f64::NAN);
            return;
        }
        let (a, b) = self.domain();
        let s = s.clamp(a, b);
        let k = self.k;
        let l = find_span(&self.t, k, s);
        let top = order.min(k);
        let mut nd = [[0.0; K1]; K1];
        for j in 0..=top {
            basis_ders(&self.t, k, l, s, j, &mut nd[j]);
        }
        const M: usize = NURBS_MAX_ORDER + 1;
        let mut wd = [0.0; M];
        for j in 0..=top {
            wd[j] = (0..=k).map(|r| nd[j][r] * self.w[l - k + r]).sum();
        }
        // Pascal's triangle row by row as j grows.
        let mut cd = [0.0; M];
        for (dd, o) in out.iter_mut().enumerate() {
            let mut binom = [0.0; M];
            binom[0] = 1.0;
            for j in 0..=order {
                if j > 0 {
                    for i in (1..=j).rev() {
                        binom[i] += binom[i - 1];
                    }
                }
                let aj = if j <= top {
                    (0..=k)
                        .map(|r| nd[j][r] * self.wp[(l - k + r) * dim + dd])
                        .sum()
                } else {
                    0.0
                };
                let mut v = aj;
                for i in 1..=j.min(top) {
                    v -= binom[i] * wd[i] * cd[j - i];
                }
                cd[j] = v / wd[0];
            }
            *o = cd[order];
        }
    }
}

impl crate::Path for Nurbs {
    fn dim(&self) -> usize {
        self.dim
    }
    fn interval(&self) -> (f64, f64) {
        self.domain()
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        Nurbs::eval(self, s, order, out)
    }
    fn breakpoints(&self) -> Vec<f64> {
        let (a, b) = self.domain();
        let mut v = vec![a];
        for &x in &self.t {
            if x > *v.last().unwrap() && x <= b {
                v.push(x);
            }
        }
        v
    }
}

impl Nurbs {
    /// The rational basis functions `R_i(s) = N_{i,k}(s) w_i / Σ_j N_{j,k}(s) w_j` that are
    /// non-zero at `s` (clamped to the base interval), written to `values[..=k]`; returns the
    /// index of the first of them, so `C(s) = Σ_r values[r] · P_{first + r}`. They are
    /// non-negative and sum to 1 (partition of unity, to rounding), and with equal weights
    /// they are the B-spline basis. `values` must hold at least `k + 1` entries. NaN `s`
    /// writes NaN and returns 0. No allocation.
    ///
    /// ```
    /// use trajkit::spline::Nurbs;
    /// let c = Nurbs::circle([0.0, 0.0], 1.0)?;
    /// let mut r = [0.0; 3];
    /// let first = c.rational_basis(0.3, &mut r);
    /// assert!((r.iter().sum::<f64>() - 1.0).abs() < 1e-15);
    /// assert!(first + 3 <= c.weights().len());
    /// # Ok::<(), trajkit::Error>(())
    /// ```
    pub fn rational_basis(&self, s: f64, values: &mut [f64]) -> usize {
        let k = self.k;
        let values = &mut values[..=k];
        if s.is_nan() {
            values.fill(f64::NAN);
            return 0;
        }
        let (a, b) = self.domain();
        let s = s.clamp(a, b);
        let l = find_span(&self.t, k, s);
        let mut n = [0.0; K1];
        basis_ders(&self.t, k, l, s, 0, &mut n);
        let mut total = 0.0;
        for r in 0..=k {
            values[r] = n[r] * self.w[l - k + r];
            total += values[r];
        }
        for v in values.iter_mut() {
            *v /= total;
        }
        l - k
    }
}

#[cfg(test)]
mod rational_basis_tests {
    use super::*;

    #[test]
    fn partition_of_unity_and_curve_reconstruction() {
        // 7 control points in the plane, degree 3, one weight raised to 5.
        let pts = [
            0.0, 0.0, 1.0, 2.0, 2.0, -1.0, 3.0, 1.5, 4.0, 0.0, 5.0, 2.0, 6.0, 0.5,
        ];
        let w = [1.0, 1.0, 1.0, 5.0, 1.0, 1.0, 1.0];
        let t = BSpline::clamped_uniform_knots(7, 3, 0.0, 1.0);
        let c = Nurbs::new(&t, &pts, &w, 2, 3).unwrap();
        let mut r = [0.0; 4];
        let mut p = [0.0; 2];
        for i in 0..=200 {
            let s = i as f64 / 200.0;
            let first = c.rational_basis(s, &mut r);
            assert!(r.iter().all(|&v| v >= 0.0));
            assert!((r.iter().sum::<f64>() - 1.0).abs() < 1e-14, "s = {s}");
            let mut q = [0.0; 2];
            for (m, rv) in r.iter().enumerate() {
                q[0] += rv * pts[2 * (first + m)];
                q[1] += rv * pts[2 * (first + m) + 1];
            }
            c.eval(s, 0, &mut p);
            assert!((q[0] - p[0]).abs() < 1e-13 && (q[1] - p[1]).abs() < 1e-13);
        }
        // Out of range is clamped, NaN propagates.
        let first = c.rational_basis(2.0, &mut r);
        assert_eq!(first + 4, 7);
        assert!((r[3] - 1.0).abs() < 1e-15);
        c.rational_basis(f64::NAN, &mut r);
        assert!(r.iter().all(|v| v.is_nan()));
    }

    #[test]
    fn equal_weights_give_the_bspline_basis() {
        let pts = [0.0, 1.0, 3.0, 2.0, 5.0, 4.0];
        let t = BSpline::clamped_uniform_knots(6, 2, 0.0, 1.0);
        let b = BSpline::new(&t, &pts, 1, 2).unwrap();
        let c = Nurbs::new(&t, &pts, &[2.5; 6], 1, 2).unwrap();
        let (mut rb, mut rn) = ([0.0; 3], [0.0; 3]);
        for i in 0..=50 {
            let s = i as f64 / 50.0;
            let fb = b.basis(s, 0, &mut rb);
            let fn_ = c.rational_basis(s, &mut rn);
            assert_eq!(fb, fn_);
            for m in 0..3 {
                assert!((rb[m] - rn[m]).abs() < 1e-15);
            }
        }
    }
}
