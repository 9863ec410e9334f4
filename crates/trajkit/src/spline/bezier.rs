//! Bézier curves: de Casteljau evaluation, hodographs, subdivision, degree elevation.

use crate::error::{Error, Result};
use crate::spline::basis::{K1, MAX_DEGREE};
use crate::spline::validate;

/// A Bézier curve of degree `k` on `[0, 1]` with `k + 1` control points (row-major
/// `(k+1) × dim`). Evaluation is de Casteljau's algorithm on stack buffers (no allocation);
/// the `m`-th derivative is de Casteljau on the `m`-th forward differences, scaled by
/// `k!/(k−m)!` (the hodograph). Degrees up to [`MAX_DEGREE`].
///
/// ```
/// use trajkit::{spline::Bezier, Path};
/// let b = Bezier::new(&[0.0, 0.0, 1.0, 2.0, 2.0, 0.0], 2)?; // quadratic in the plane
/// let mut p = [0.0; 2];
/// b.eval(0.5, 0, &mut p);
/// assert_eq!(p, [1.0, 1.0]);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Bezier {
    dim: usize,
    c: Vec<f64>,
}

impl Bezier {
    /// From `k + 1 >= 1` control points (`k <= MAX_DEGREE`).
    pub fn new(control_points: &[f64], dim: usize) -> Result<Self> {
        validate::dim(dim)?;
        let n = control_points.len() / dim;
        if control_points.len() != n * dim {
            return Err(Error::DimensionMismatch {
                what: format!("control point entries (a multiple of dim = {dim})"),
                expected: n * dim,
                found: control_points.len(),
            });
        }
        if n == 0 {
            return Err(Error::TooFewWaypoints {
                needed: 1,
                found: 0,
            });
        }
        if n > MAX_DEGREE + 1 {
            return Err(Error::InvalidValue {
                field: "Bézier degree".into(),
                value: (n - 1) as f64,
                reason: "exceeds trajkit's maximum degree (20)",
            });
        }
        validate::finite("control_points", control_points, dim)?;
        Ok(Bezier {
            dim,
            c: control_points.to_vec(),
        })
    }

    /// Degree `k`.
    pub fn degree(&self) -> usize {
        self.c.len() / self.dim - 1
    }

    /// Control points, row-major `(k+1) × dim`.
    pub fn control_points(&self) -> &[f64] {
        &self.c
    }

    /// Writes the `order`-th derivative at `s` (clamped to `[0, 1]`) into `out[..dim]`.
    pub fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        let dim = self.dim;
        let out = &mut out[..dim];
        if s.is_nan() {
            out.fill(f64::NAN);
            return;
        }
        let s = s.clamp(0.0, 1.0);
        let k = self.degree();
        if order > k {
            out.fill(0.0);
            return;
        }
        let mut scale = 1.0;
        for j in 0..order {
            scale *= (k - j) as f64;
        }
        let m = k - order; // degree of the hodograph
        let mut b = [0.0; K1];
        for (d, o) in out.iter_mut().enumerate() {
            for i in 0..=k {
                b[i] = self.c[i * dim + d];
            }
            // Forward differences, `order` times.
            for r in 0..order {
                for i in 0..k - r {
                    b[i] = b[i + 1] - b[i];
                }
            }
            // de Casteljau on b[0..=m].
            for r in 1..=m {
                for i in 0..=m - r {
                    b[i] = (1.0 - s) * b[i] + s * b[i + 1];
                }
            }
            *o = scale * b[0];
        }
    }

    /// The hodograph (first derivative) as a Bézier curve of degree `k − 1`; the derivative of a
    /// degree-0 curve is the zero point.
    pub fn hodograph(&self) -> Bezier {
        let k = self.degree();
        let dim = self.dim;
        if k == 0 {
            return Bezier {
                dim,
                c: vec![0.0; dim],
            };
        }
        let mut c = vec![0.0; k * dim];
        for i in 0..k {
            for d in 0..dim {
                c[i * dim + d] = k as f64 * (self.c[(i + 1) * dim + d] - self.c[i * dim + d]);
            }
        }
        Bezier { dim, c }
    }

    /// Splits at `s` in (0, 1) into the curves on `[0, s]` and `[s, 1]`, each reparameterized
    /// to `[0, 1]` (de Casteljau's triangle edges).
    pub fn split(&self, s: f64) -> Result<(Bezier, Bezier)> {
        if !(s > 0.0 && s < 1.0) {
            return Err(Error::InvalidValue {
                field: "split parameter".into(),
                value: s,
                reason: "is not strictly between 0 and 1",
            });
        }
        let k = self.degree();
        let dim = self.dim;
        let mut left = vec![0.0; (k + 1) * dim];
        let mut right = vec![0.0; (k + 1) * dim];
        let mut b = self.c.clone();
        for r in 0..=k {
            for d in 0..dim {
                left[r * dim + d] = b[d];
                right[(k - r) * dim + d] = b[(k - r) * dim + d];
            }
            for i in 0..k - r {
                for d in 0..dim {
                    b[i * dim + d] = (1.0 - s) * b[i * dim + d] + s * b[(i + 1) * dim + d];
                }
            }
        }
        Ok((Bezier { dim, c: left }, Bezier { dim, c: right }))
    }

    /// The same curve with degree `k + 1`.
    pub fn elevate(&self) -> Result<Bezier> {
        let k = self.degree();
        let dim = self.dim;
        if k + 1 > MAX_DEGREE {
            return Err(Error::InvalidValue {
                field: "elevated Bézier degree".into(),
                value: (k + 1) as f64,
                reason: "exceeds trajkit's maximum degree (20)",
            });
        }
        let mut c = vec![0.0; (k + 2) * dim];
        for i in 0..=k + 1 {
            let a = i as f64 / (k + 1) as f64;
            for d in 0..dim {
                let prev = if i > 0 {
                    self.c[(i - 1) * dim + d]
                } else {
                    0.0
                };
                let cur = if i <= k { self.c[i * dim + d] } else { 0.0 };
                c[i * dim + d] = a * prev + (1.0 - a) * cur;
            }
        }
        Ok(Bezier { dim, c })
    }
}

impl crate::Path for Bezier {
    fn dim(&self) -> usize {
        self.dim
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        Bezier::eval(self, s, order, out)
    }
}
