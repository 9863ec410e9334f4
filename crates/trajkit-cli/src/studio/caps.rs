//! The work a single request may ask for, and the checks that enforce it.
//!
//! Every count a request controls is checked against its cap before anything is allocated or
//! computed, and refused with a 400 naming the field, the value and the cap. The caps keep one
//! request within about a second of CPU and a few MB of response on a laptop; they are part of
//! the documented API (README, "Studio").

use super::error::{number, ApiError, ApiResult};
use serde_json::json;

/// Largest request body, bytes (413 beyond).
pub const MAX_BODY_BYTES: usize = 2 << 20;
/// Largest number of waypoints in a plan request.
pub const MAX_WAYPOINTS: usize = 1000;
/// Largest number of joints (plan, OTG, primitives).
pub const MAX_JOINTS: usize = 32;
/// Largest TOPP-RA/NI gridpoint interval count per rest-to-rest piece.
pub const MAX_GRIDPOINTS: usize = 20_000;
/// Largest number of sample rows in a response.
pub const MAX_SAMPLE_ROWS: usize = 100_000;
/// Largest number of sampled values (rows × joints × 4 orders) in a response.
pub const MAX_SAMPLE_VALUES: usize = 4_000_000;
/// Largest number of samples a lesson plot asks for (polynomials, splines, profiles,
/// primitives).
pub const MAX_PLOT_SAMPLES: usize = 5_000;
/// Largest number of spline points (Catmull-Rom points, B-spline control points).
pub const MAX_CURVE_POINTS: usize = 64;
/// Largest B-spline degree in the editor.
pub const MAX_DEGREE: usize = 10;
/// Largest number of samples in one demonstration (DMP, ProMP).
pub const MAX_DEMO_SAMPLES: usize = 5_000;
/// Largest number of demonstrations (ProMP).
pub const MAX_DEMOS: usize = 50;
/// Largest number of basis functions per joint (DMP, ProMP).
pub const MAX_BASIS: usize = 200;
/// Largest number of via points (ProMP).
pub const MAX_VIA_POINTS: usize = 20;
/// Largest magnitude accepted for a position, distance or time in the lessons.
pub const MAX_MAGNITUDE: f64 = 1e6;

/// `count` within `lo..=hi`, else 400 naming `field`.
pub fn count(field: &str, count: usize, lo: usize, hi: usize) -> ApiResult<usize> {
    if count < lo {
        return Err(ApiError::bad(field, json!(count), format!("is below {lo}")));
    }
    if count > hi {
        return Err(ApiError::bad(
            field,
            json!(count),
            format!("exceeds the cap of {hi}"),
        ));
    }
    Ok(count)
}

/// A finite number with |v| ≤ [`MAX_MAGNITUDE`].
pub fn finite(field: &str, v: f64) -> ApiResult<f64> {
    if !v.is_finite() {
        return Err(ApiError::bad(field, number(v), "is not a finite number"));
    }
    if v.abs() > MAX_MAGNITUDE {
        return Err(ApiError::bad(
            field,
            number(v),
            format!("is beyond ±{MAX_MAGNITUDE:e}"),
        ));
    }
    Ok(v)
}

/// A finite number > 0 (and ≤ [`MAX_MAGNITUDE`]).
pub fn positive(field: &str, v: f64) -> ApiResult<f64> {
    finite(field, v)?;
    if v <= 0.0 {
        return Err(ApiError::bad(field, number(v), "is not a positive number"));
    }
    Ok(v)
}

/// Rows of equal length `dim` (1 ≤ dim ≤ `max_dim`), at most `max_rows`, at least `min_rows`,
/// every entry finite: flattened row-major. `field` names the array (`points`), entries are
/// named `points[i][j]`.
pub fn rows(
    field: &str,
    rows: &[Vec<f64>],
    min_rows: usize,
    max_rows: usize,
    max_dim: usize,
) -> ApiResult<(Vec<f64>, usize)> {
    count(
        &format!("{field} (row count)"),
        rows.len(),
        min_rows,
        max_rows,
    )?;
    let dim = rows.first().map_or(0, Vec::len);
    count(&format!("{field}[0] (length)"), dim, 1, max_dim)?;
    let mut flat = Vec::with_capacity(rows.len() * dim);
    for (i, r) in rows.iter().enumerate() {
        if r.len() != dim {
            return Err(ApiError::bad(
                &format!("{field}[{i}] (length)"),
                json!(r.len()),
                format!("differs from the first row's {dim}"),
            ));
        }
        for (j, &v) in r.iter().enumerate() {
            flat.push(finite(&format!("{field}[{i}][{j}]"), v)?);
        }
    }
    Ok((flat, dim))
}
