//! Lesson 3: the B-spline / NURBS editor: a clamped uniform B-spline of any degree through
//! draggable control points, the degree-2 curve on the same points, optional weights (NURBS),
//! the basis functions with their sum, and each control point's support.

use super::to_rows;
use crate::studio::caps;
use crate::studio::error::{ApiError, ApiResult};
use serde::{Deserialize, Serialize};
use serde_json::json;
use trajkit::spline::{BSpline, Nurbs};

/// `POST /api/bspline`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Request {
    /// Control points (degree + 1 to 64 of them, 1 to 3 coordinates each).
    pub control_points: Vec<Vec<f64>>,
    /// Degree k, 1..=10 and below the number of control points (default 3).
    #[serde(default = "three")]
    pub degree: usize,
    /// Weights (one per control point, positive): the curve is then a NURBS.
    pub weights: Option<Vec<f64>>,
    /// Also the curve of this degree on the same points (and weights), e.g. 2.
    pub compare_degree: Option<usize>,
    /// Samples over the parameter interval [0, 1], 2..=5000 (default 201).
    #[serde(default = "super::default_samples")]
    pub samples: usize,
    /// Also the basis functions and their sum at the samples (default true).
    #[serde(default = "yes")]
    pub basis: bool,
}

fn three() -> usize {
    3
}

fn yes() -> bool {
    true
}

/// The answer.
#[derive(Debug, Serialize)]
pub struct Response {
    /// Degree k.
    pub degree: usize,
    /// Whether weights were given (NURBS).
    pub rational: bool,
    /// The clamped uniform knot vector on [0, 1].
    pub knots: Vec<f64>,
    /// Parameter of each sample.
    pub u: Vec<f64>,
    /// The curve at each sample, one row per sample.
    pub curve: Vec<Vec<f64>>,
    /// `[u_i, u_{i+k+1}]`: the parameter interval where control point i acts (its basis
    /// function is non-zero), one per control point.
    pub support: Vec<[f64; 2]>,
    /// The comparison curve, when asked.
    pub comparison: Option<Comparison>,
    /// The basis functions at the samples, when asked.
    pub basis: Option<Basis>,
}

/// The curve of another degree on the same control points.
#[derive(Debug, Serialize)]
pub struct Comparison {
    /// Its degree.
    pub degree: usize,
    /// Its knots.
    pub knots: Vec<f64>,
    /// The curve at the same parameters `u`.
    pub curve: Vec<Vec<f64>>,
}

/// Basis functions (rational ones for a NURBS) at the samples.
#[derive(Debug, Serialize)]
pub struct Basis {
    /// `values[i][m]`: basis function i at `u[m]`.
    pub values: Vec<Vec<f64>>,
    /// Σ_i values[i][m]: 1 everywhere (partition of unity), up to rounding.
    pub sum: Vec<f64>,
}

/// A B-spline or NURBS on the request's control points.
enum Curve {
    Plain(BSpline),
    Rational(Nurbs),
}

impl Curve {
    fn new(points: &[f64], dim: usize, degree: usize, weights: Option<&[f64]>) -> ApiResult<Self> {
        let n = points.len() / dim;
        let knots = BSpline::clamped_uniform_knots(n, degree, 0.0, 1.0);
        let lib = |e| ApiError::from_lib("control_points", e);
        Ok(match weights {
            None => Curve::Plain(BSpline::new(&knots, points, dim, degree).map_err(lib)?),
            Some(w) => Curve::Rational(Nurbs::new(&knots, points, w, dim, degree).map_err(lib)?),
        })
    }

    fn knots(&self) -> &[f64] {
        match self {
            Curve::Plain(b) => b.knots(),
            Curve::Rational(r) => r.knots(),
        }
    }

    fn sample(&self, u: &[f64], dim: usize) -> Vec<Vec<f64>> {
        let mut out = vec![0.0; u.len() * dim];
        for (m, &s) in u.iter().enumerate() {
            let o = &mut out[m * dim..(m + 1) * dim];
            match self {
                Curve::Plain(b) => trajkit::Path::eval(b, s, 0, o),
                Curve::Rational(r) => r.eval(s, 0, o),
            }
        }
        to_rows(&out, dim)
    }

    /// Basis functions non-zero at `s` into `values[..=k]`; returns the first index.
    fn basis(&self, s: f64, values: &mut [f64]) -> usize {
        match self {
            Curve::Plain(b) => b.basis(s, 0, values),
            Curve::Rational(r) => r.rational_basis(s, values),
        }
    }
}

fn check_degree(field: &str, degree: usize, n: usize) -> ApiResult<usize> {
    caps::count(field, degree, 1, caps::MAX_DEGREE)?;
    if degree >= n {
        return Err(ApiError::bad(
            field,
            json!(degree),
            format!("needs at least {} control points, {n} given", degree + 1),
        ));
    }
    Ok(degree)
}

/// Answers the request.
pub fn handle(req: Request) -> ApiResult<Response> {
    let (flat, dim) = caps::rows(
        "control_points",
        &req.control_points,
        2,
        caps::MAX_CURVE_POINTS,
        3,
    )?;
    let n = flat.len() / dim;
    let k = check_degree("degree", req.degree, n)?;
    let samples = caps::count("samples", req.samples, 2, caps::MAX_PLOT_SAMPLES)?;
    if let Some(w) = &req.weights {
        if w.len() != n {
            return Err(ApiError::bad(
                "weights (count)",
                json!(w.len()),
                format!("differs from the {n} control points"),
            ));
        }
        for (i, &wi) in w.iter().enumerate() {
            caps::positive(&format!("weights[{i}]"), wi)?;
        }
    }
    let weights = req.weights.as_deref();
    let curve = Curve::new(&flat, dim, k, weights)?;
    let u = super::uniform_times(1.0, samples);
    let knots = curve.knots().to_vec();
    let support = (0..n).map(|i| [knots[i], knots[i + k + 1]]).collect();
    let comparison = match req.compare_degree {
        None => None,
        Some(d) => {
            let d = check_degree("compare_degree", d, n)?;
            let c = Curve::new(&flat, dim, d, weights)?;
            Some(Comparison {
                degree: d,
                knots: c.knots().to_vec(),
                curve: c.sample(&u, dim),
            })
        }
    };
    let basis = req.basis.then(|| {
        let mut values = vec![vec![0.0; samples]; n];
        let mut sum = vec![0.0; samples];
        let mut b = vec![0.0; k + 1];
        for (m, &s) in u.iter().enumerate() {
            let first = curve.basis(s, &mut b);
            for (r, &v) in b.iter().enumerate() {
                values[first + r][m] = v;
                sum[m] += v;
            }
        }
        Basis { values, sum }
    });
    Ok(Response {
        degree: k,
        rational: weights.is_some(),
        curve: curve.sample(&u, dim),
        knots,
        u,
        support,
        comparison,
        basis,
    })
}
