//! Checks of a waypoint problem before planning: the input's own fields (the generator's
//! checks), the options that waypoints do not support, and every waypoint and per-section
//! field (sizes, finite values, signs, duplicates, position limits). The first violation is
//! the error, naming the field, the waypoint or section, the DOF and the value.

use super::Waypoints;
use crate::otg::input::{ControlInterface, DynInputParameter, Synchronization};
use crate::otg::result::OtgError;

/// More waypoints than this is refused as an absurd size.
pub(crate) const MAX_WAYPOINTS: usize = 100_000;

fn wp(
    index: usize,
    dof: Option<usize>,
    field: &'static str,
    value: f64,
    reason: &'static str,
) -> OtgError {
    OtgError::Waypoints {
        index,
        dof,
        field,
        value,
        reason,
    }
}

fn unsupported(field: &'static str, value: f64, reason: &'static str) -> OtgError {
    OtgError::InvalidInput {
        dof: None,
        field,
        value,
        reason,
    }
}

/// Validates `input` and `waypoints` (see the module docs).
pub(crate) fn validate(
    input: &DynInputParameter,
    waypoints: &Waypoints,
    delta_time: f64,
) -> Result<(), OtgError> {
    input.validate(delta_time, false, false)?;
    options(input)?;
    let n = input.dof();
    let m = waypoints.intermediate_positions.len();
    if m > MAX_WAYPOINTS {
        return Err(unsupported(
            "intermediate_positions",
            m as f64,
            "waypoints are more than 100000",
        ));
    }
    positions(input, waypoints)?;
    let sections = m + 1;
    let limits = [
        (
            "per_section_max_velocity",
            &waypoints.per_section_max_velocity,
        ),
        (
            "per_section_max_acceleration",
            &waypoints.per_section_max_acceleration,
        ),
        ("per_section_max_jerk", &waypoints.per_section_max_jerk),
    ];
    for (field, values) in limits {
        let Some(values) = values else { continue };
        sized(field, values.len(), sections)?;
        for (s, row) in values.iter().enumerate() {
            if row.len() != n {
                return Err(wp(
                    s,
                    None,
                    field,
                    row.len() as f64,
                    "has not one value per DOF",
                ));
            }
            for (i, &x) in row.iter().enumerate() {
                if x.is_nan() || x <= 0.0 {
                    return Err(wp(
                        s,
                        Some(i),
                        field,
                        x,
                        "is not a number > 0 (or infinity)",
                    ));
                }
            }
        }
    }
    if let Some(d) = &waypoints.per_section_minimum_duration {
        let field = "per_section_minimum_duration";
        sized(field, d.len(), sections)?;
        for (s, &x) in d.iter().enumerate() {
            if !(x.is_finite() && x >= 0.0) {
                return Err(wp(s, None, field, x, "is not a finite number ≥ 0"));
            }
        }
    }
    Ok(())
}

fn sized(field: &'static str, len: usize, sections: usize) -> Result<(), OtgError> {
    if len == sections {
        return Ok(());
    }
    Err(unsupported(
        field,
        len as f64,
        "is not a list with one entry per section (waypoints + 1)",
    ))
}

/// The options a motion through waypoints does not support.
fn options(input: &DynInputParameter) -> Result<(), OtgError> {
    let o = &input.options;
    if !matches!(
        o.synchronization,
        Synchronization::Time | Synchronization::Phase
    ) {
        return Err(unsupported(
            "synchronization",
            f64::NAN,
            "must be time or phase with intermediate_positions (every DOF reaches each waypoint at once)",
        ));
    }
    if o.control_interface != ControlInterface::Position {
        return Err(unsupported(
            "control_interface",
            f64::NAN,
            "must be position with intermediate_positions",
        ));
    }
    if input.per_dof_synchronization.is_some() {
        return Err(unsupported(
            "per_dof_synchronization",
            f64::NAN,
            "is not supported with intermediate_positions",
        ));
    }
    if input.per_dof_control_interface.is_some() {
        return Err(unsupported(
            "per_dof_control_interface",
            f64::NAN,
            "is not supported with intermediate_positions",
        ));
    }
    if let Some(i) = input.enabled.iter().position(|e| !e) {
        return Err(OtgError::InvalidInput {
            dof: Some(i),
            field: "enabled",
            value: 0.0,
            reason: "is false: every DOF must be enabled with intermediate_positions",
        });
    }
    if let Some(d) = o.minimum_duration {
        return Err(unsupported(
            "minimum_duration",
            d,
            "is not supported with intermediate_positions (use per_section_minimum_duration)",
        ));
    }
    Ok(())
}

/// Sizes, finite values, duplicates and position limits of the waypoints.
fn positions(input: &DynInputParameter, waypoints: &Waypoints) -> Result<(), OtgError> {
    let n = input.dof();
    let field = "intermediate_positions";
    let mut previous: &[f64] = &input.current_position;
    for (k, p) in waypoints.intermediate_positions.iter().enumerate() {
        if p.len() != n {
            return Err(wp(
                k,
                None,
                field,
                p.len() as f64,
                "has not one value per DOF",
            ));
        }
        for (i, &x) in p.iter().enumerate() {
            if !x.is_finite() {
                return Err(wp(k, Some(i), field, x, "is not a finite number"));
            }
            if x > input.max_position[i] || x < input.min_position[i] {
                return Err(wp(
                    k,
                    Some(i),
                    field,
                    x,
                    "is outside [min_position, max_position]",
                ));
            }
        }
        if p[..] == previous[..] {
            let reason = if k == 0 {
                "equals current_position (a duplicate waypoint)"
            } else {
                "equals the previous waypoint (a duplicate waypoint)"
            };
            return Err(wp(k, None, field, p[0], reason));
        }
        previous = p;
    }
    if let Some(k) = waypoints.intermediate_positions.len().checked_sub(1) {
        if previous[..] == input.target_position[..] {
            return Err(wp(
                k,
                None,
                field,
                previous[0],
                "equals target_position (a duplicate waypoint)",
            ));
        }
    }
    Ok(())
}
