//! `POST /api/otg`: one online-generation problem in the JSON that `trajkit otg` reads, answered
//! with the JSON that `trajkit otg` writes (`result`, `duration`, `independent_min_durations`,
//! `final_error`, `worst_limit_ratio`, `samples`): the library's reader
//! (`trajkit::otg::json::parse_problem`, strict: unknown fields and missing limits are refused),
//! `otg::calculate_dyn` (or `otg::plan_waypoints` with `intermediate_positions`), and the library's
//! answer (`trajkit::otg::json::answer`, `answer_waypoints`). The only
//! addition is the cap on the number of samples.

use super::caps;
use super::error::{ApiError, ApiResult};
use axum::http::StatusCode;
use serde_json::{json, Value};
use trajkit::otg::json::{answer, answer_waypoints, parse_problem};
use trajkit::otg::{calculate_dyn, plan_waypoints};

/// Answers `POST /api/otg` from the request body.
pub fn otg_request(body: &[u8]) -> ApiResult<Value> {
    let text = std::str::from_utf8(body)
        .map_err(|e| ApiError::plain(StatusCode::BAD_REQUEST, format!("body: {e}")))?;
    let problem = parse_problem(text, "request", 0).map_err(|e| {
        let field = match &e {
            trajkit::Error::Parse { location, .. } => location.field.clone(),
            _ => String::new(),
        };
        ApiError::from_lib(&field, e)
    })?;
    let (input, dt) = (&problem.input, problem.delta_time);
    let status = |e: trajkit::otg::OtgError| {
        let status = if e.name() == "invalid_input" {
            StatusCode::BAD_REQUEST
        } else {
            StatusCode::UNPROCESSABLE_ENTITY
        };
        ApiError::plain(status, format!("otg: {e}"))
    };
    let cap = caps::MAX_SAMPLE_ROWS.min(caps::MAX_SAMPLE_VALUES / (4 * input.dof()));
    let too_many = |duration: f64| {
        let rows = duration / dt;
        (rows > cap as f64).then(|| {
            ApiError::bad(
                "dt",
                json!(dt),
                format!(
                    "gives {rows:.0} samples for a {duration:.6} s trajectory (cap {cap}): use a larger dt"
                ),
            )
        })
    };
    if let Some(w) = &problem.waypoints {
        let tr = plan_waypoints(input, w, dt).map_err(status)?;
        if let Some(e) = too_many(tr.duration()) {
            return Err(e);
        }
        return answer_waypoints(&problem, w, &tr).map_err(|e| ApiError::from_lib("dt", e));
    }
    let tr = calculate_dyn(input, dt).map_err(status)?;
    if let Some(e) = too_many(tr.duration()) {
        return Err(e);
    }
    answer(&problem, &tr).map_err(|e| ApiError::from_lib("dt", e))
}
