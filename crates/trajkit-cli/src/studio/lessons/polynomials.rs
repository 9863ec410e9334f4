//! Lesson 1: cubic, quintic and septic rest-to-rest profiles side by side, their peak
//! coefficients, and a move of Δq in T checked against one joint's limits
//! (q̇max = Δq/T·c_v and its acceleration and jerk counterparts).

use super::{series, uniform_times, Series};
use crate::studio::caps;
use crate::studio::error::{ApiError, ApiResult};
use serde::{Deserialize, Serialize};
use trajkit::poly::{min_duration_rest_to_rest, peak_coefficients, Degree, PolyMove};
use trajkit::{JointLimits, Limits, Order, Trajectory};

/// `POST /api/polynomials`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Request {
    /// Displacement Δq (default 1).
    #[serde(default = "one")]
    pub delta_q: f64,
    /// Duration T in seconds (default 1).
    #[serde(default = "one")]
    pub duration: f64,
    /// One joint's limits to compare the peaks with (optional).
    pub limits: Option<JointLimitsIn>,
    /// Samples per profile, 2..=5000 (default 201).
    #[serde(default = "super::default_samples")]
    pub samples: usize,
}

/// One joint's velocity, acceleration and jerk limits (all required, positive).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointLimitsIn {
    /// q̇max.
    pub velocity: f64,
    /// q̈max.
    pub acceleration: f64,
    /// q⃛max.
    pub jerk: f64,
}

/// The answer.
#[derive(Debug, Serialize)]
pub struct Response {
    /// Δq as used.
    pub delta_q: f64,
    /// T as used.
    pub duration: f64,
    /// Cubic, quintic, septic.
    pub profiles: Vec<Profile>,
}

/// One degree's profile.
#[derive(Debug, Serialize)]
pub struct Profile {
    /// `cubic`, `quintic` or `septic`.
    pub degree: &'static str,
    /// Polynomial order (3, 5, 7).
    pub order: usize,
    /// Coefficients of the unit profile f(τ) = Σ a_i τ^i, a_0 first.
    pub coefficients: Vec<f64>,
    /// Peak |q̇|·T, |q̈|·T², |q⃛|·T³ of the unit move (the specification's table).
    pub peak_coefficients: [f64; 3],
    /// Peak |q̇|, |q̈|, |q⃛| of the Δq-in-T move.
    pub peaks: [f64; 3],
    /// q̇, q̈, q⃛ of the move at t = 0 (the end is symmetric).
    pub at_start: [f64; 3],
    /// Whether q̇, q̈, q⃛ are zero at both ends (so continuous with rest before and after).
    pub zero_at_ends: [bool; 3],
    /// Peak / limit for velocity, acceleration, jerk (when limits were given).
    pub limit_ratios: Option<[f64; 3]>,
    /// Names of the limits the move exceeds.
    pub exceeds: Vec<&'static str>,
    /// Shortest duration of this degree within the limits (when limits were given).
    pub min_duration: Option<f64>,
    /// The sampled move.
    pub samples: Series,
}

fn one() -> f64 {
    1.0
}

const ORDERS: [(Order, &str); 3] = [
    (Order::Velocity, "velocity"),
    (Order::Acceleration, "acceleration"),
    (Order::Jerk, "jerk"),
];

/// Answers the request.
pub fn handle(req: Request) -> ApiResult<Response> {
    let dq = caps::finite("delta_q", req.delta_q)?;
    let duration = caps::positive("duration", req.duration)?;
    caps::count("samples", req.samples, 2, caps::MAX_PLOT_SAMPLES)?;
    let limits = match &req.limits {
        None => None,
        Some(l) => {
            let jl = JointLimits::symmetric(
                caps::positive("limits.velocity", l.velocity)?,
                caps::positive("limits.acceleration", l.acceleration)?,
                caps::positive("limits.jerk", l.jerk)?,
            );
            Some(Limits::new(vec![jl]).map_err(|e| ApiError::from_lib("limits", e))?)
        }
    };
    let times = uniform_times(duration, req.samples);
    let mut profiles = Vec::with_capacity(3);
    for degree in Degree::ALL {
        let mv = PolyMove::rest_to_rest(degree, &[0.0], &[dq], duration)
            .map_err(|e| ApiError::from_lib("", e))?;
        let peaks = ORDERS.map(|(o, _)| mv.peaks(o)[0]);
        let (mut start, mut end) = ([0.0; 3], [0.0; 3]);
        let mut v = [0.0];
        for (k, (o, _)) in ORDERS.iter().enumerate() {
            mv.eval(0.0, *o, &mut v);
            start[k] = v[0];
            mv.eval(mv.duration(), *o, &mut v);
            end[k] = v[0];
        }
        // "Zero" relative to the derivative's own peak (rounding of the boundary solve).
        let zero_at_ends: [bool; 3] = std::array::from_fn(|k| {
            let tol = 1e-9 * peaks[k].max(f64::MIN_POSITIVE);
            start[k].abs() <= tol && end[k].abs() <= tol
        });
        let (limit_ratios, exceeds, min_duration) = match &limits {
            None => (None, Vec::new(), None),
            Some(l) => {
                let jl = l.joint(0);
                let ratios = std::array::from_fn(|k| jl.ratio(ORDERS[k].0, peaks[k]));
                let exceeds = (0..3)
                    .filter(|&k| ratios[k] > 1.0 + 1e-12)
                    .map(|k| ORDERS[k].1)
                    .collect();
                let tmin = if dq == 0.0 {
                    Some(0.0)
                } else {
                    Some(
                        min_duration_rest_to_rest(degree, &[0.0], &[dq], l)
                            .map_err(|e| ApiError::from_lib("limits", e))?,
                    )
                };
                (Some(ratios), exceeds, tmin)
            }
        };
        profiles.push(Profile {
            degree: degree.name(),
            order: degree.degree(),
            coefficients: degree.unit_profile().normalized_coefficients().to_vec(),
            peak_coefficients: peak_coefficients(degree),
            peaks,
            at_start: start,
            zero_at_ends,
            limit_ratios,
            exceeds,
            min_duration,
            samples: series(&mv, times.clone())?,
        });
    }
    Ok(Response {
        delta_q: dq,
        duration,
        profiles,
    })
}
