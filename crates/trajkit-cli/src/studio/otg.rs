//! `POST /api/otg`: one online-generation problem in the JSON that `trajkit otg` reads, answered
//! with the JSON that `trajkit otg` writes (`result`, `duration`, `independent_min_durations`,
//! `final_error`, `worst_limit_ratio`, `samples`).
//!
//! [`otg_request`] is the one function the handler calls; it reads the problem into the
//! library's `DynInputParameter`, calls `otg::calculate_dyn`, and writes the answer. The input
//! follows `trajkit otg` (Ruckig's field names; only `current_position` and `target_position`
//! required; a missing or `null` limit is unlimited; `dt` default 1 ms) except that unknown
//! fields are refused here. When the library reads and writes this JSON itself, the body of
//! [`otg_request`] becomes those two calls. A test runs both this endpoint and `trajkit otg` on
//! the same problems and compares the answers.

use super::caps;
use super::error::{ApiError, ApiResult};
use axum::http::StatusCode;
use serde::Deserialize;
use serde_json::{json, Value};
use trajkit::otg::{
    calculate_dyn, ControlInterface, DurationDiscretization, DynInputParameter, DynTrajectory,
    Synchronization,
};

/// The problem, with Ruckig's field names.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Problem {
    /// Required; its length is the number of degrees of freedom.
    pub current_position: Vec<Option<f64>>,
    /// Default 0.
    pub current_velocity: Option<Vec<Option<f64>>>,
    /// Default 0.
    pub current_acceleration: Option<Vec<Option<f64>>>,
    /// Required.
    pub target_position: Vec<Option<f64>>,
    /// Default 0.
    pub target_velocity: Option<Vec<Option<f64>>>,
    /// Default 0.
    pub target_acceleration: Option<Vec<Option<f64>>>,
    /// Missing or null: unlimited.
    pub max_velocity: Option<Vec<Option<f64>>>,
    /// Missing or null: unlimited (first-order profiles).
    pub max_acceleration: Option<Vec<Option<f64>>>,
    /// Missing or null: unlimited (trapezoidal profiles).
    pub max_jerk: Option<Vec<Option<f64>>>,
    /// Direction-dependent minimum velocity (null entries: −max).
    pub min_velocity: Option<Vec<Option<f64>>>,
    /// Direction-dependent minimum acceleration (null entries: −max).
    pub min_acceleration: Option<Vec<Option<f64>>>,
    /// Degrees of freedom to plan (default all).
    pub enabled: Option<Vec<bool>>,
    /// Minimum duration, seconds.
    pub minimum_duration: Option<f64>,
    /// `time` (default), `time_if_necessary`, `phase`, `none`.
    pub synchronization: Option<String>,
    /// `position` (default), `velocity`.
    pub control_interface: Option<String>,
    /// `continuous` (default), `discrete`.
    pub duration_discretization: Option<String>,
    /// Sample period, seconds (default 0.001).
    pub dt: Option<f64>,
}

/// A list field: its length must be the DOF count; null entries (and a missing list) give
/// `default`.
fn list(field: &str, v: &Option<Vec<Option<f64>>>, n: usize, default: f64) -> ApiResult<Vec<f64>> {
    match v {
        None => Ok(vec![default; n]),
        Some(a) if a.len() != n => Err(ApiError::bad(
            &format!("{field} (length)"),
            json!(a.len()),
            format!("differs from current_position's {n}"),
        )),
        Some(a) => Ok(a.iter().map(|x| x.unwrap_or(default)).collect()),
    }
}

/// A direction-dependent minimum: null entries are the negated maximum.
fn minimum(field: &str, v: &Option<Vec<Option<f64>>>, max: &[f64]) -> ApiResult<Option<Vec<f64>>> {
    let Some(a) = v else { return Ok(None) };
    let m = list(field, &Some(a.clone()), max.len(), f64::NAN)?;
    Ok(Some(
        m.iter()
            .zip(max)
            .map(|(&x, &hi)| if x.is_nan() { -hi } else { x })
            .collect(),
    ))
}

fn word<T>(field: &str, v: &Option<String>, options: &[(&str, T)]) -> ApiResult<T>
where
    T: Copy,
{
    let w = v.as_deref().unwrap_or(options[0].0);
    options
        .iter()
        .find(|(name, _)| *name == w)
        .map(|(_, t)| *t)
        .ok_or_else(|| {
            let names: Vec<&str> = options.iter().map(|o| o.0).collect();
            ApiError::bad(
                field,
                json!(w),
                format!("is not one of {}", names.join(", ")),
            )
        })
}

/// The library input and the sample period.
fn input(p: &Problem) -> ApiResult<(DynInputParameter, f64)> {
    let n = caps::count(
        "current_position (length)",
        p.current_position.len(),
        1,
        caps::MAX_JOINTS,
    )?;
    let some = |v: &Vec<Option<f64>>| Some(v.clone());
    let mut i = DynInputParameter::new(n);
    i.current_position = list("current_position", &some(&p.current_position), n, 0.0)?;
    i.current_velocity = list("current_velocity", &p.current_velocity, n, 0.0)?;
    i.current_acceleration = list("current_acceleration", &p.current_acceleration, n, 0.0)?;
    i.target_position = list("target_position", &some(&p.target_position), n, 0.0)?;
    i.target_velocity = list("target_velocity", &p.target_velocity, n, 0.0)?;
    i.target_acceleration = list("target_acceleration", &p.target_acceleration, n, 0.0)?;
    i.max_velocity = list("max_velocity", &p.max_velocity, n, f64::INFINITY)?;
    i.max_acceleration = list("max_acceleration", &p.max_acceleration, n, f64::INFINITY)?;
    i.max_jerk = list("max_jerk", &p.max_jerk, n, f64::INFINITY)?;
    i.min_velocity = minimum("min_velocity", &p.min_velocity, &i.max_velocity)?;
    i.min_acceleration = minimum("min_acceleration", &p.min_acceleration, &i.max_acceleration)?;
    if let Some(e) = &p.enabled {
        if e.len() != n {
            return Err(ApiError::bad(
                "enabled (length)",
                json!(e.len()),
                format!("differs from current_position's {n}"),
            ));
        }
        i.enabled = e.clone();
    }
    i.options.minimum_duration = p.minimum_duration;
    i.options.synchronization = word(
        "synchronization",
        &p.synchronization,
        &[
            ("time", Synchronization::Time),
            ("time_if_necessary", Synchronization::TimeIfNecessary),
            ("phase", Synchronization::Phase),
            ("none", Synchronization::None),
        ],
    )?;
    i.options.control_interface = word(
        "control_interface",
        &p.control_interface,
        &[
            ("position", ControlInterface::Position),
            ("velocity", ControlInterface::Velocity),
        ],
    )?;
    i.options.duration_discretization = word(
        "duration_discretization",
        &p.duration_discretization,
        &[
            ("continuous", DurationDiscretization::Continuous),
            ("discrete", DurationDiscretization::Discrete),
        ],
    )?;
    let dt = p.dt.unwrap_or(0.001);
    if !(dt.is_finite() && dt > 0.0) {
        return Err(ApiError::bad("dt", json!(dt), "is not a positive number"));
    }
    Ok((i, dt))
}

/// The distance of the final state from the target (position for the position interface,
/// acceleration only where jerk is limited) and the largest ratio of velocity (position
/// interface) and acceleration to their limits after the brake pre-profile, over segment
/// boundaries and interior velocity extrema: the self-check that `trajkit otg` writes.
fn self_check(i: &DynInputParameter, tr: &DynTrajectory) -> ([f64; 3], f64) {
    let position = i.options.control_interface == ControlInterface::Position;
    let mut err = [0.0_f64; 3];
    let mut worst = 0.0_f64;
    let use_of = |x: f64, lo: f64, hi: f64| if x < 0.0 { x / lo } else { x / hi };
    for (k, dof) in tr.dofs().iter().enumerate().filter(|(k, _)| i.enabled[*k]) {
        let p = &dof.profile;
        let end = p.end();
        let targets = [
            (position, end.p - i.target_position[k]),
            (true, end.v - i.target_velocity[k]),
            (i.max_jerk[k].is_finite(), end.a - i.target_acceleration[k]),
        ];
        for (e, (on, d)) in err.iter_mut().zip(targets) {
            if on {
                *e = e.max(d.abs());
            }
        }
        let vhi = i.max_velocity[k];
        let vlo = i.min_velocity.as_ref().map_or(-vhi, |m| m[k]);
        let ahi = i.max_acceleration[k];
        let alo = i.min_acceleration.as_ref().map_or(-ahi, |m| m[k]);
        let brake_end = p.brake_duration();
        for (t0, d, s, j) in (0..p.segments()).filter_map(|m| p.segment(m)) {
            if t0 + d <= brake_end {
                continue;
            }
            let v_at = |t: f64| s.v + t * (s.a + 0.5 * j * t);
            if position {
                let mut vs = vec![s.v, v_at(d)];
                let turn = if j != 0.0 { -s.a / j } else { -1.0 };
                if turn > 0.0 && turn < d {
                    vs.push(v_at(turn));
                }
                for v in vs {
                    worst = worst.max(use_of(v, vlo, vhi));
                }
            }
            if ahi.is_finite() {
                for a in [s.a, s.a + d * j] {
                    worst = worst.max(use_of(a, alo, ahi));
                }
            }
        }
    }
    (err, worst)
}

/// Answers `POST /api/otg` from the request body.
pub fn otg_request(body: &[u8]) -> ApiResult<Value> {
    let problem: Problem = super::error::parse_json(body)?;
    let (input, dt) = input(&problem)?;
    let tr = calculate_dyn(&input, dt).map_err(|e| {
        let status = if e.name() == "invalid_input" {
            StatusCode::BAD_REQUEST
        } else {
            StatusCode::UNPROCESSABLE_ENTITY
        };
        ApiError::plain(status, format!("otg: {e}"))
    })?;
    let rows = tr.duration() / dt;
    let cap = caps::MAX_SAMPLE_ROWS.min(caps::MAX_SAMPLE_VALUES / (4 * input.dof()));
    if rows > cap as f64 {
        return Err(ApiError::bad(
            "dt",
            json!(dt),
            format!(
                "gives {rows:.0} samples for a {:.6} s trajectory (cap {cap}): use a larger dt",
                tr.duration()
            ),
        ));
    }
    let table = trajkit::sample::sample(&tr, 1.0 / dt).map_err(|e| ApiError::from_lib("dt", e))?;
    let samples: Value = serde_json::from_str(&trajkit::io::table_to_json(&table))
        .map_err(|e| ApiError::plain(StatusCode::INTERNAL_SERVER_ERROR, e.to_string()))?;
    let mut mins = vec![0.0; tr.dof()];
    tr.independent_min_durations(&mut mins);
    let (e, worst) = self_check(&input, &tr);
    Ok(json!({
        "result": "working",
        "duration": tr.duration(),
        "independent_min_durations": mins,
        "final_error": {"position": e[0], "velocity": e[1], "acceleration": e[2]},
        "worst_limit_ratio": worst,
        "samples": samples,
    }))
}
