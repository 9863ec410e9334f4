//! Convex polygons in the (x, u) = (ṡ², s̈) plane: the controllable sets of the backward pass.
//!
//! A polygon is its vertex list in counter-clockwise order; a segment (two vertices) and a
//! point (one) are valid degenerate polygons, an empty list is the empty set. The only
//! operations the solver needs are clipping by a half-plane (Sutherland–Hodgman, exact for
//! convex polygons), the range of a parameter along a line that stays inside, and
//! simplification. Simplification only ever removes vertices, so the result is a subset of the
//! input: every set the solver keeps is an inner approximation of the exact one, which keeps
//! the forward pass feasible (a state inside a kept set can always be steered onwards).
//!
//! Tolerances are relative to the polygon's extent in each coordinate: a vertex counts as
//! inside a half-plane `a·q ≤ c` when `a·q − c ≤ 1e-12·(|a₀|·X + |a₁|·U + |c|)` with X, U the
//! largest |x|, |u| of the polygon.

/// A point (x, u).
pub(crate) type Pt = [f64; 2];

/// Relative tolerance of the inside test.
const REL: f64 = 1e-12;

/// Largest vertex count kept by [`Polygon::simplify`].
pub(crate) const MAX_VERTICES: usize = 24;

/// A convex polygon (counter-clockwise vertices); see the module documentation.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Polygon {
    pub(crate) v: Vec<Pt>,
}

impl Polygon {
    /// The axis-aligned box `[x0, x1] × [u0, u1]`.
    pub(crate) fn rect(x0: f64, x1: f64, u0: f64, u1: f64) -> Self {
        Polygon {
            v: vec![[x0, u0], [x1, u0], [x1, u1], [x0, u1]],
        }
    }

    /// Whether the set is empty.
    pub(crate) fn is_empty(&self) -> bool {
        self.v.is_empty()
    }

    /// The largest |x| and |u| over the vertices (at least the smallest positive normal).
    pub(crate) fn extent(&self) -> (f64, f64) {
        let mut ex = f64::MIN_POSITIVE;
        let mut eu = f64::MIN_POSITIVE;
        for p in &self.v {
            ex = ex.max(p[0].abs());
            eu = eu.max(p[1].abs());
        }
        (ex, eu)
    }

    /// The tolerance of the half-plane `a·q ≤ c` on this polygon.
    #[inline]
    pub(crate) fn tol(&self, a: [f64; 2], c: f64) -> f64 {
        let (ex, eu) = self.extent();
        REL * (a[0].abs() * ex + a[1].abs() * eu + c.abs())
    }

    /// Whether the half-plane `a·q ≤ c` cuts this polygon (some vertex is outside).
    #[inline]
    pub(crate) fn cut_by(&self, a: [f64; 2], c: f64, tol: f64) -> bool {
        self.v.iter().any(|p| a[0] * p[0] + a[1] * p[1] - c > tol)
    }

    /// Intersects with the half-plane `a·q ≤ c`, using `scratch` for the output (swapped in).
    pub(crate) fn clip(&mut self, a: [f64; 2], c: f64, scratch: &mut Vec<Pt>) {
        if self.v.is_empty() || !(a[0].is_finite() && a[1].is_finite()) || c.is_nan() {
            if c.is_nan() || a[0].is_nan() || a[1].is_nan() {
                self.v.clear();
            }
            return;
        }
        if a[0] == 0.0 && a[1] == 0.0 {
            if c < 0.0 {
                self.v.clear();
            }
            return;
        }
        let tol = self.tol(a, c);
        if !self.cut_by(a, c, tol) {
            return;
        }
        scratch.clear();
        let n = self.v.len();
        let f = |p: &Pt| a[0] * p[0] + a[1] * p[1] - c;
        if n == 1 {
            return self.v.clear();
        }
        for k in 0..n {
            let p = self.v[k];
            let q = self.v[(k + 1) % n];
            let (fp, fq) = (f(&p), f(&q));
            let (ip, iq) = (fp <= tol, fq <= tol);
            if ip {
                scratch.push(p);
            }
            if ip != iq && (fp - fq).abs() > 0.0 {
                // The crossing of the boundary line, computed from the inside end for accuracy.
                let t = fp / (fp - fq);
                let t = t.clamp(0.0, 1.0);
                scratch.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
            }
            if n == 2 {
                // A segment has one edge; the loop would visit it twice.
                if iq {
                    scratch.push(q);
                }
                break;
            }
        }
        std::mem::swap(&mut self.v, scratch);
        self.dedup();
    }

    /// Removes consecutive vertices that coincide (relative 1e-13 of the extent).
    fn dedup(&mut self) {
        if self.v.len() < 2 {
            return;
        }
        let (ex, eu) = self.extent();
        let close =
            |p: &Pt, q: &Pt| (p[0] - q[0]).abs() <= 1e-13 * ex && (p[1] - q[1]).abs() <= 1e-13 * eu;
        let mut out = 0;
        for k in 0..self.v.len() {
            if out == 0 || !close(&self.v[k], &self.v[out - 1]) {
                self.v[out] = self.v[k];
                out += 1;
            }
        }
        self.v.truncate(out);
        while self.v.len() > 1 && close(&self.v[0], &self.v[self.v.len() - 1]) {
            self.v.pop();
        }
    }

    /// Removes vertices where the boundary is straight to relative 1e-12, then, while there
    /// are more than [`MAX_VERTICES`], the vertex whose removal loses the least area. The
    /// result is a subset of the input.
    pub(crate) fn simplify(&mut self) {
        if self.v.len() <= 3 {
            return;
        }
        let (ex, eu) = self.extent();
        let area_scale = ex * eu;
        // Area of the triangle (prev, k, next), normalized.
        let tri = |v: &[Pt], k: usize| {
            let n = v.len();
            let p = v[(k + n - 1) % n];
            let q = v[k];
            let r = v[(k + 1) % n];
            0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])).abs()
        };
        let mut k = 0;
        while k < self.v.len() && self.v.len() > 3 {
            if tri(&self.v, k) <= 1e-12 * area_scale {
                self.v.remove(k);
            } else {
                k += 1;
            }
        }
        while self.v.len() > MAX_VERTICES {
            let best = (0..self.v.len())
                .min_by(|&a, &b| tri(&self.v, a).total_cmp(&tri(&self.v, b)))
                .unwrap_or(0);
            self.v.remove(best);
        }
    }

    /// The interval of t for which `p + t·d` lies in the polygon (with the polygon's
    /// tolerance), or `None` when the line misses it.
    #[cfg(test)]
    pub(crate) fn line_range(&self, p: Pt, d: Pt) -> Option<(f64, f64)> {
        self.line_range_tol(p, d, 1e-9)
    }

    /// The t in the polygon along `p + t·d`, preferring points inside by 1e-10 relative (so
    /// that rounding of the next step cannot leave the set), then with the usual tolerance,
    /// and when the line misses the polygon, the t nearest to it (the smallest largest
    /// violation of an edge), as a one-point interval.
    pub(crate) fn line_range_robust(&self, p: Pt, d: Pt) -> Option<(f64, f64)> {
        if self.v.len() >= 3 {
            for rel in [-1e-10, -1e-13, 0.0] {
                if let Some(r) = self.line_range_tol(p, d, rel) {
                    return Some(r);
                }
            }
        }
        if let Some(r) = self.line_range_tol(p, d, 1e-9) {
            return Some(r);
        }
        self.nearest(p, d).map(|t| (t, t))
    }

    /// The t minimizing the largest normalized violation of the polygon's edges along
    /// `p + t·d` (a convex piecewise-linear function: checked at all crossings of two edges).
    fn nearest(&self, p: Pt, d: Pt) -> Option<f64> {
        let rows = super::solve::edges(self);
        let (ex, eu) = self.extent();
        let lines: Vec<(f64, f64)> = rows
            .iter()
            .map(|(m, c)| {
                let nrm = m[0].abs() * ex + m[1].abs() * eu;
                let nrm = if nrm > 0.0 { nrm } else { 1.0 };
                (
                    (m[0] * d[0] + m[1] * d[1]) / nrm,
                    (m[0] * p[0] + m[1] * p[1] - c) / nrm,
                )
            })
            .collect();
        let f = |t: f64| {
            lines
                .iter()
                .fold(f64::NEG_INFINITY, |m, l| m.max(l.0 * t + l.1))
        };
        let mut best: Option<(f64, f64)> = None;
        for (a, la) in lines.iter().enumerate() {
            for lb in &lines[a + 1..] {
                let den = la.0 - lb.0;
                if den != 0.0 {
                    let t = (lb.1 - la.1) / den;
                    let val = f(t);
                    if t.is_finite() && best.is_none_or(|b| val < b.1) {
                        best = Some((t, val));
                    }
                }
            }
        }
        best.map(|b| b.0)
    }

    /// [`Polygon::line_range`] with the edges moved out by `rel` (relative to the extent;
    /// negative moves them in).
    fn line_range_tol(&self, p: Pt, d: Pt, rel: f64) -> Option<(f64, f64)> {
        let n = self.v.len();
        match n {
            0 => None,
            1 => {
                // A point: the line must pass through it.
                let q = self.v[0];
                let t = if d[0].abs() * 1.0 >= d[1].abs() {
                    (q[0] - p[0]) / d[0]
                } else {
                    (q[1] - p[1]) / d[1]
                };
                let (ex, eu) = self.extent();
                let ok = (p[0] + t * d[0] - q[0]).abs() <= 1e-9 * ex
                    && (p[1] + t * d[1] - q[1]).abs() <= 1e-9 * eu;
                ok.then_some((t, t))
            }
            _ => {
                let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
                let (ex, eu) = self.extent();
                let edges = if n == 2 { 1 } else { n };
                for k in 0..edges {
                    let a = self.v[k];
                    let b = self.v[(k + 1) % n];
                    // Outward normal of the edge a→b of a counter-clockwise polygon.
                    let nrm = [b[1] - a[1], a[0] - b[0]];
                    let c = nrm[0] * a[0] + nrm[1] * a[1];
                    let tol = rel * (nrm[0].abs() * ex + nrm[1].abs() * eu);
                    let rows: &[(Pt, f64)] = if n == 2 {
                        // A segment: both sides of its line, and its two ends.
                        &[
                            (nrm, c + tol),
                            ([-nrm[0], -nrm[1]], -c + tol),
                            (
                                [b[0] - a[0], b[1] - a[1]],
                                (b[0] - a[0]) * b[0] + (b[1] - a[1]) * b[1],
                            ),
                            (
                                [a[0] - b[0], a[1] - b[1]],
                                (a[0] - b[0]) * a[0] + (a[1] - b[1]) * a[1],
                            ),
                        ]
                    } else {
                        &[(nrm, c + tol)]
                    };
                    for &(m, cc) in rows {
                        let den = m[0] * d[0] + m[1] * d[1];
                        let num = cc - (m[0] * p[0] + m[1] * p[1]);
                        if den > 0.0 {
                            hi = hi.min(num / den);
                        } else if den < 0.0 {
                            lo = lo.max(num / den);
                        } else if num < 0.0 {
                            return None;
                        }
                    }
                }
                (lo <= hi).then_some((lo, hi))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clip_square_by_diagonal() {
        let mut p = Polygon::rect(0.0, 1.0, 0.0, 1.0);
        let mut s = Vec::new();
        p.clip([1.0, 1.0], 1.0, &mut s);
        assert_eq!(p.v.len(), 3);
        // Line through the centre, direction (1, 1): inside for t in [-0.5, 0] (x + u ≤ 1
        // and the square).
        let (lo, hi) = p.line_range([0.5, 0.5], [1.0, 1.0]).unwrap();
        assert!((lo + 0.5).abs() < 1e-9 && hi.abs() < 1e-9, "{lo} {hi}");
        p.clip([-1.0, -1.0], -2.0, &mut s);
        assert!(p.is_empty());
    }

    #[test]
    fn segments_and_simplify_are_subsets() {
        let mut seg = Polygon {
            v: vec![[0.0, 0.0], [2.0, -1.0]],
        };
        let mut s = Vec::new();
        seg.clip([1.0, 0.0], 1.0, &mut s);
        assert_eq!(seg.v, vec![[0.0, 0.0], [1.0, -0.5]]);
        let (lo, hi) = seg.line_range([0.0, 1.0], [0.0, -1.0]).unwrap();
        assert!((lo - 1.0).abs() < 1e-8 && (hi - 1.0).abs() < 1e-8);
        // A 40-gon (circle) simplified to MAX_VERTICES vertices stays inside the circle.
        let mut c = Polygon {
            v: (0..40)
                .map(|k| {
                    let a = k as f64 * std::f64::consts::TAU / 40.0;
                    [a.cos(), a.sin()]
                })
                .collect(),
        };
        c.simplify();
        assert_eq!(c.v.len(), MAX_VERTICES);
        assert!(c
            .v
            .iter()
            .all(|p| (p[0] * p[0] + p[1] * p[1] - 1.0).abs() < 1e-12));
    }
}
