//! Lesson 2: Catmull-Rom splines through draggable points, in the three parameterizations
//! (uniform, centripetal, chordal).

use super::to_rows;
use crate::studio::caps;
use crate::studio::error::{ApiError, ApiResult};
use serde::{Deserialize, Serialize};
use trajkit::spline::{CatmullRom, CatmullRomKind};
use trajkit::Path;

/// A Catmull-Rom parameterization (knot spacing ‖P_{i+1} − P_i‖^α).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// α = 0.
    Uniform,
    /// α = ½.
    Centripetal,
    /// α = 1.
    Chordal,
}

impl From<Kind> for CatmullRomKind {
    fn from(k: Kind) -> Self {
        match k {
            Kind::Uniform => CatmullRomKind::Uniform,
            Kind::Centripetal => CatmullRomKind::Centripetal,
            Kind::Chordal => CatmullRomKind::Chordal,
        }
    }
}

/// `POST /api/catmull-rom`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Request {
    /// The points (2 to 64, each of 1 to 3 coordinates).
    pub points: Vec<Vec<f64>>,
    /// Which variants (default: all three).
    #[serde(default = "all_kinds")]
    pub kinds: Vec<Kind>,
    /// Samples per segment, 1..=200 (default 32).
    #[serde(default = "default_per_segment")]
    pub samples_per_segment: usize,
}

fn all_kinds() -> Vec<Kind> {
    vec![Kind::Uniform, Kind::Centripetal, Kind::Chordal]
}

fn default_per_segment() -> usize {
    32
}

/// The answer: one curve per requested variant.
#[derive(Debug, Serialize)]
pub struct Response {
    /// The curves, in the order asked.
    pub curves: Vec<Curve>,
}

/// One sampled Catmull-Rom curve.
#[derive(Debug, Serialize)]
pub struct Curve {
    /// The variant.
    pub kind: Kind,
    /// Its exponent α.
    pub alpha: f64,
    /// Knot parameters t_i of the points.
    pub parameters: Vec<f64>,
    /// Parameter of each sample.
    pub s: Vec<f64>,
    /// The sampled curve, one row per sample.
    pub points: Vec<Vec<f64>>,
}

/// Answers the request.
pub fn handle(req: Request) -> ApiResult<Response> {
    let (flat, dim) = caps::rows("points", &req.points, 2, caps::MAX_CURVE_POINTS, 3)?;
    caps::count("kinds (count)", req.kinds.len(), 1, 3)?;
    let per = caps::count("samples_per_segment", req.samples_per_segment, 1, 200)?;
    let mut curves = Vec::with_capacity(req.kinds.len());
    for kind in &req.kinds {
        let cr = CatmullRom::new(&flat, dim, (*kind).into()).map_err(|e| {
            let mut err = ApiError::from_lib("points", e);
            err.message = format!("{} ({kind:?} Catmull-Rom)", err.message).to_string();
            err
        })?;
        let knots = cr.parameters().to_vec();
        let mut s = Vec::with_capacity((knots.len() - 1) * per + 1);
        for w in knots.windows(2) {
            for k in 0..per {
                s.push(w[0] + (w[1] - w[0]) * k as f64 / per as f64);
            }
        }
        s.push(knots[knots.len() - 1]);
        let mut out = vec![0.0; s.len() * dim];
        for (k, &sk) in s.iter().enumerate() {
            cr.eval(sk, 0, &mut out[k * dim..(k + 1) * dim]);
        }
        curves.push(Curve {
            kind: *kind,
            alpha: CatmullRomKind::from(*kind).alpha(),
            parameters: knots,
            s,
            points: to_rows(&out, dim),
        });
    }
    Ok(Response { curves })
}
