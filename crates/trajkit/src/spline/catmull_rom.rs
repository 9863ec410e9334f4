//! Catmull-Rom splines in the Barry–Goldman form with parameter exponent α: uniform (α = 0),
//! centripetal (α = ½) and chordal (α = 1).

use crate::error::{Error, Result};
use crate::spline::ppoly::PiecewisePolynomial;
use crate::spline::validate;

/// Which Catmull-Rom: the knot spacing is `‖P_{i+1} − P_i‖^α`.
///
/// Catmull-Rom exists in incompatible variants; trajkit's is the Barry–Goldman pyramid with
/// this spacing (not the tension form, not finite differences over given times).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CatmullRomKind {
    /// α = 0: knots one apart. May form cusps and self-intersections on uneven spacing.
    Uniform,
    /// α = ½: no cusps or self-intersections within a segment (Yuksel et al. 2011).
    Centripetal,
    /// α = 1: knot spacing is the chord length.
    Chordal,
}

impl CatmullRomKind {
    /// The exponent α.
    pub fn alpha(self) -> f64 {
        match self {
            CatmullRomKind::Uniform => 0.0,
            CatmullRomKind::Centripetal => 0.5,
            CatmullRomKind::Chordal => 1.0,
        }
    }
}

/// An interpolating, C¹ Catmull-Rom spline through points `P_0 … P_{n−1}` (row-major
/// `n × dim`), parameterized by its knots `t_0 = 0`, `t_{i+1} = t_i + ‖P_{i+1} − P_i‖^α`.
///
/// Each segment is the Barry–Goldman cubic through `P_{i−1} … P_{i+2}`; written in Hermite form
/// its tangent at `P_i` is
/// `(P_i − P_{i−1})/(t_i − t_{i−1}) − (P_{i+1} − P_{i−1})/(t_{i+1} − t_{i−1}) + (P_{i+1} − P_i)/(t_{i+1} − t_i)`,
/// shared by both segments at `P_i`. At the ends the missing neighbour is the reflection
/// `2P_0 − P_1` (and `2P_{n−1} − P_{n−2}`), which makes the end tangent the end chord's slope.
///
/// ```
/// use trajkit::{spline::{CatmullRom, CatmullRomKind}, Path};
/// let p = [0.0, 0.0, 1.0, 1.0, 2.0, 0.0, 3.0, 1.0];
/// let cr = CatmullRom::new(&p, 2, CatmullRomKind::Centripetal)?;
/// let t = cr.parameters().to_vec();
/// let mut q = [0.0; 2];
/// cr.eval(t[2], 0, &mut q);
/// assert!((q[0] - 2.0).abs() < 1e-15 && q[1].abs() < 1e-15);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CatmullRom {
    kind: CatmullRomKind,
    pp: PiecewisePolynomial,
}

impl CatmullRom {
    /// Through `points` (at least 2, row-major `n × dim`) with the given variant. For
    /// centripetal and chordal, two equal consecutive points are an error (a zero knot step);
    /// uniform accepts them.
    pub fn new(points: &[f64], dim: usize, kind: CatmullRomKind) -> Result<Self> {
        validate::dim(dim)?;
        let n = points.len() / dim;
        if points.len() != n * dim {
            return Err(Error::DimensionMismatch {
                what: format!("point entries (a multiple of dim = {dim})"),
                expected: n * dim,
                found: points.len(),
            });
        }
        if n < 2 {
            return Err(Error::TooFewWaypoints {
                needed: 2,
                found: n,
            });
        }
        validate::finite("points", points, dim)?;
        let alpha = kind.alpha();
        let mut t = vec![0.0; n];
        for i in 1..n {
            let d2: f64 = (0..dim)
                .map(|d| (points[i * dim + d] - points[(i - 1) * dim + d]).powi(2))
                .sum();
            let step = if alpha == 0.0 {
                1.0
            } else {
                d2.sqrt().powf(alpha)
            };
            if step <= 0.0 {
                return Err(Error::DuplicateWaypoint { index: i });
            }
            t[i] = t[i - 1] + step;
        }
        let p = |i: usize, d: usize| points[i * dim + d];
        let mut m = vec![0.0; n * dim];
        for d in 0..dim {
            m[d] = (p(1, d) - p(0, d)) / (t[1] - t[0]);
            m[(n - 1) * dim + d] = (p(n - 1, d) - p(n - 2, d)) / (t[n - 1] - t[n - 2]);
            for i in 1..n - 1 {
                m[i * dim + d] = (p(i, d) - p(i - 1, d)) / (t[i] - t[i - 1])
                    - (p(i + 1, d) - p(i - 1, d)) / (t[i + 1] - t[i - 1])
                    + (p(i + 1, d) - p(i, d)) / (t[i + 1] - t[i]);
            }
        }
        Ok(CatmullRom {
            kind,
            pp: PiecewisePolynomial::cubic_hermite_unchecked(&t, points, &m, dim),
        })
    }

    /// Uniform Catmull-Rom (α = 0).
    pub fn uniform(points: &[f64], dim: usize) -> Result<Self> {
        Self::new(points, dim, CatmullRomKind::Uniform)
    }

    /// Centripetal Catmull-Rom (α = ½).
    pub fn centripetal(points: &[f64], dim: usize) -> Result<Self> {
        Self::new(points, dim, CatmullRomKind::Centripetal)
    }

    /// Chordal Catmull-Rom (α = 1).
    pub fn chordal(points: &[f64], dim: usize) -> Result<Self> {
        Self::new(points, dim, CatmullRomKind::Chordal)
    }

    /// The variant.
    pub fn kind(&self) -> CatmullRomKind {
        self.kind
    }

    /// The knots `t_i` at which the curve passes through `P_i`.
    pub fn parameters(&self) -> &[f64] {
        self.pp.breaks()
    }
}

crate::spline::ppoly_backed!(CatmullRom);
