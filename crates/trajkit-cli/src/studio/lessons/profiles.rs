//! Lesson 4: the trapezoidal (second-order) and 7-phase S-curve (jerk-limited) profiles of a
//! rest-to-rest move of distance D under v_max, a_max and j_max, computed by trajkit's online
//! generator (`otg`): durations, phases and the four derivatives.

use super::{series, uniform_times, Series};
use crate::studio::caps;
use crate::studio::error::{ApiError, ApiResult};
use axum::http::StatusCode;
use serde::{Deserialize, Serialize};
use trajkit::otg::{calculate_dyn, DynInputParameter};

/// `POST /api/profiles`. Defaults are the specification's: D = 1, v_max = 0.6, a_max = 1,
/// j_max = 4 (trapezoid 2.2667 s, S-curve 2.5167 s).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Request {
    /// Distance D (default 1).
    #[serde(default = "one")]
    pub distance: f64,
    /// v_max (default 0.6).
    #[serde(default = "v_default")]
    pub v_max: f64,
    /// a_max (default 1).
    #[serde(default = "one")]
    pub a_max: f64,
    /// j_max (default 4); only the S-curve uses it.
    #[serde(default = "j_default")]
    pub j_max: f64,
    /// Samples per profile, 2..=5000 (default 201).
    #[serde(default = "super::default_samples")]
    pub samples: usize,
}

fn one() -> f64 {
    1.0
}
fn v_default() -> f64 {
    0.6
}
fn j_default() -> f64 {
    4.0
}

/// The answer.
#[derive(Debug, Serialize)]
pub struct Response {
    /// Velocity and acceleration limited (infinite jerk: acceleration jumps).
    pub trapezoid: Profile,
    /// Velocity, acceleration and jerk limited (7 phases when every limit is reached).
    pub s_curve: Profile,
}

/// One profile.
#[derive(Debug, Serialize)]
pub struct Profile {
    /// Duration, seconds.
    pub duration: f64,
    /// The constant-jerk segments (phases of zero length left out).
    pub phases: Vec<Phase>,
    /// The sampled motion (one joint).
    pub samples: Series,
}

/// A segment of constant jerk.
#[derive(Debug, Serialize)]
pub struct Phase {
    /// Start time.
    pub t: f64,
    /// Duration.
    pub duration: f64,
    /// Position, velocity and acceleration at its start.
    pub start: [f64; 3],
    /// Position, velocity and acceleration at its end (the trapezoid's acceleration then jumps
    /// to the next phase's start).
    pub end: [f64; 3],
    /// Its jerk (0 for every segment of the trapezoid: its acceleration jumps between them).
    pub jerk: f64,
}

fn profile(distance: f64, v: f64, a: f64, j: f64, samples: usize) -> ApiResult<Profile> {
    let mut input = DynInputParameter::new(1);
    input.target_position = vec![distance];
    input.max_velocity = vec![v];
    input.max_acceleration = vec![a];
    input.max_jerk = vec![j];
    let tr = calculate_dyn(&input, 0.001)
        .map_err(|e| ApiError::plain(StatusCode::UNPROCESSABLE_ENTITY, format!("otg: {e}")))?;
    let p = &tr.dofs()[0].profile;
    let phases = (0..p.segments())
        .filter_map(|k| {
            let (t, d, s, jerk) = p.segment(k)?;
            // The state reached at the end of this constant-jerk segment (before any jump of
            // acceleration into the next one, which is the trapezoid's jerk impulse).
            let end = [
                s.p + d * (s.v + d * (s.a / 2.0 + d * jerk / 6.0)),
                s.v + d * (s.a + d * jerk / 2.0),
                s.a + d * jerk,
            ];
            (d > 0.0).then_some(Phase {
                t,
                duration: d,
                start: [s.p, s.v, s.a],
                end,
                jerk,
            })
        })
        .collect();
    Ok(Profile {
        duration: tr.duration(),
        phases,
        samples: series(&tr, uniform_times(tr.duration(), samples))?,
    })
}

/// Answers the request.
pub fn handle(req: Request) -> ApiResult<Response> {
    let d = caps::finite("distance", req.distance)?;
    let v = caps::positive("v_max", req.v_max)?;
    let a = caps::positive("a_max", req.a_max)?;
    let j = caps::positive("j_max", req.j_max)?;
    let n = caps::count("samples", req.samples, 2, caps::MAX_PLOT_SAMPLES)?;
    Ok(Response {
        trapezoid: profile(d, v, a, f64::INFINITY, n)?,
        s_curve: profile(d, v, a, j, n)?,
    })
}
