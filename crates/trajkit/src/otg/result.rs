//! The status of an update and the error of a calculation: plain `Copy` enums, no allocation.
//!
//! [`OtgResult`] is what [`super::Otg::update`] reports when it succeeds (`Working` or
//! `Finished`, as Ruckig's `Result`); every failure is an [`OtgError`], which names the degree
//! of freedom (`Some(i)`, or `None` for fields that are not per DOF), the field and the value.
//! An `OtgError` converts into [`crate::Error`] (`Error::Otg`), so `?` works in functions that
//! return trajkit's error. Neither type allocates: building, copying and returning one is safe
//! on a real-time path.

use std::fmt;

/// Which input field an [`OtgError::InvalidInput`] refers to.
pub type FieldName = &'static str;

/// Outcome of a successful [`super::Otg::update`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OtgResult {
    /// The trajectory is being followed; the target is not reached yet.
    Working,
    /// The target state has been reached (the time after this update is past the duration).
    Finished,
}

impl OtgResult {
    /// A short machine-readable name: `working`, `finished`.
    pub fn name(&self) -> &'static str {
        match self {
            OtgResult::Working => "working",
            OtgResult::Finished => "finished",
        }
    }
}

impl fmt::Display for OtgResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a calculation failed.
///
/// `Display` gives one line such as `invalid input: max_velocity[2] = -1 is not a number ≥ 0
/// (or infinity)`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum OtgError {
    /// An input value is not acceptable.
    InvalidInput {
        /// The degree of freedom (0-based); `None` for fields that are not per DOF.
        dof: Option<usize>,
        /// The field (Ruckig's input field name).
        field: FieldName,
        /// The value given (a length for vectors of the wrong size).
        value: f64,
        /// Why it is refused.
        reason: &'static str,
    },
    /// Step 1 found no valid time-optimal profile for a degree of freedom (a solver gap).
    CalculationFailed {
        /// The degree of freedom.
        dof: usize,
    },
    /// A degree of freedom with a zero limit cannot reach its target (it can only coast at its
    /// current acceleration), or cannot do so at the duration the others need.
    ZeroLimits {
        /// The degree of freedom.
        dof: usize,
    },
    /// A degree of freedom with position limits cannot reach its target without leaving them
    /// (Ruckig Pro's `ErrorPositionalLimits`): its brake, or every motion to its target, or
    /// its continuation after an early end, would cross `min_position` or `max_position`.
    PositionLimits {
        /// The degree of freedom.
        dof: usize,
    },
    /// The calculation budget (`interrupt_calculation_duration`) ran out before a valid
    /// result was found.
    Interrupted {
        /// The budget, in microseconds.
        budget_us: f64,
    },
    /// A motion through intermediate waypoints ([`super::plan_waypoints`]): a waypoint or
    /// per-section field is not acceptable, or a section cannot be planned.
    Waypoints {
        /// The waypoint (`intermediate_positions`) or section (per-section fields, a section
        /// that cannot be planned) the error is about, 0-based.
        index: usize,
        /// The degree of freedom, if the error is about one.
        dof: Option<usize>,
        /// The field (Ruckig's input field name).
        field: FieldName,
        /// The value given (a length for lists of the wrong size).
        value: f64,
        /// Why it is refused.
        reason: &'static str,
    },
    /// No common duration could be found for the synchronized degrees of freedom.
    SynchronizationFailed {
        /// The degree of freedom that could not be re-planned last (`None` when none was
        /// tried).
        dof: Option<usize>,
        /// The last duration tried, in seconds.
        duration: f64,
    },
}

impl OtgError {
    /// A short machine-readable name: `invalid_input`, `calculation_failed`, `zero_limits`,
    /// `position_limits`, `interrupted`, `waypoints`, `synchronization_failed`.
    pub fn name(&self) -> &'static str {
        match self {
            OtgError::InvalidInput { .. } => "invalid_input",
            OtgError::CalculationFailed { .. } => "calculation_failed",
            OtgError::ZeroLimits { .. } => "zero_limits",
            OtgError::PositionLimits { .. } => "position_limits",
            OtgError::Interrupted { .. } => "interrupted",
            OtgError::Waypoints { .. } => "waypoints",
            OtgError::SynchronizationFailed { .. } => "synchronization_failed",
        }
    }

    /// The degree of freedom the error is about, if any.
    pub fn dof(&self) -> Option<usize> {
        match *self {
            OtgError::InvalidInput { dof, .. }
            | OtgError::SynchronizationFailed { dof, .. }
            | OtgError::Waypoints { dof, .. } => dof,
            OtgError::CalculationFailed { dof }
            | OtgError::ZeroLimits { dof }
            | OtgError::PositionLimits { dof } => Some(dof),
            OtgError::Interrupted { .. } => None,
        }
    }
}

impl fmt::Display for OtgError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            OtgError::InvalidInput {
                dof,
                field,
                value,
                reason,
            } => match dof {
                None => write!(f, "invalid input: {field} = {value} {reason}"),
                Some(i) => write!(f, "invalid input: {field}[{i}] = {value} {reason}"),
            },
            OtgError::CalculationFailed { dof } => {
                write!(
                    f,
                    "calculation failed: no valid time-optimal profile for DOF {dof}"
                )
            }
            OtgError::ZeroLimits { dof } => write!(
                f,
                "zero limits: DOF {dof} has a zero limit and cannot reach its target at the \
                 duration the motion needs"
            ),
            OtgError::PositionLimits { dof } => write!(
                f,
                "position limits: DOF {dof} cannot reach its target without leaving \
                 [min_position, max_position]"
            ),
            OtgError::Interrupted { budget_us } => write!(
                f,
                "interrupted: no valid trajectory within the calculation budget of {budget_us} µs"
            ),
            OtgError::Waypoints {
                index,
                dof,
                field,
                value,
                reason,
            } => {
                write!(f, "invalid waypoint input: {field}[{index}]")?;
                if let Some(i) = dof {
                    write!(f, "[{i}]")?;
                }
                write!(f, " = {value} {reason}")
            }
            OtgError::SynchronizationFailed { dof, duration } => match dof {
                Some(i) => write!(
                    f,
                    "synchronization failed: DOF {i} has no profile of duration {duration} s"
                ),
                None => write!(
                    f,
                    "synchronization failed: no common duration found (last tried {duration} s)"
                ),
            },
        }
    }
}

impl std::error::Error for OtgError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_dof_field_and_value() {
        let e = OtgError::InvalidInput {
            dof: Some(2),
            field: "max_velocity",
            value: -1.0,
            reason: "is negative",
        };
        assert_eq!(
            e.to_string(),
            "invalid input: max_velocity[2] = -1 is negative"
        );
        assert_eq!(e.dof(), Some(2));
        let e = OtgError::InvalidInput {
            dof: None,
            field: "minimum_duration",
            value: f64::NAN,
            reason: "is not a number",
        };
        assert_eq!(
            e.to_string(),
            "invalid input: minimum_duration = NaN is not a number"
        );
        assert_eq!(e.dof(), None);
        let t: crate::Error = OtgError::CalculationFailed { dof: 1 }.into();
        assert_eq!(
            t.to_string(),
            "otg: calculation failed: no valid time-optimal profile for DOF 1"
        );
    }
}
