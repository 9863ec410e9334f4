//! The status of a calculation or an update: a plain enum, no allocation.

use std::fmt;

/// Which input field a [`OtgResult::InvalidInput`] refers to.
pub type FieldName = &'static str;

/// Outcome of [`super::Otg::calculate`] and [`super::Otg::update`].
///
/// Errors carry the degree of freedom and the value involved; `Display` turns them into a
/// one-line message such as `invalid input: max_velocity[2] = -1 is not a positive number`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum OtgResult {
    /// The trajectory is being followed; the target is not reached yet.
    Working,
    /// The target state has been reached (the time after this update is past the duration).
    Finished,
    /// An input value is not acceptable.
    InvalidInput {
        /// The degree of freedom (0-based); `usize::MAX` for fields that are not per DOF.
        dof: usize,
        /// The field (Ruckig's input field name).
        field: FieldName,
        /// The value given.
        value: f64,
        /// Why it is refused.
        reason: &'static str,
    },
    /// Step 1 found no valid time-optimal profile for a degree of freedom (a solver gap).
    CalculationFailed {
        /// The degree of freedom.
        dof: usize,
    },
    /// No common duration could be found for the synchronized degrees of freedom.
    SynchronizationFailed {
        /// The degree of freedom that could not be re-planned last.
        dof: usize,
        /// The last duration tried, in seconds.
        duration: f64,
    },
}

impl OtgResult {
    /// True for `Working` and `Finished`.
    pub fn is_ok(&self) -> bool {
        matches!(self, OtgResult::Working | OtgResult::Finished)
    }

    /// A short machine-readable name: `working`, `finished`, `invalid_input`,
    /// `calculation_failed`, `synchronization_failed`.
    pub fn name(&self) -> &'static str {
        match self {
            OtgResult::Working => "working",
            OtgResult::Finished => "finished",
            OtgResult::InvalidInput { .. } => "invalid_input",
            OtgResult::CalculationFailed { .. } => "calculation_failed",
            OtgResult::SynchronizationFailed { .. } => "synchronization_failed",
        }
    }
}

impl fmt::Display for OtgResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            OtgResult::Working => write!(f, "working"),
            OtgResult::Finished => write!(f, "finished"),
            OtgResult::InvalidInput {
                dof,
                field,
                value,
                reason,
            } => {
                if dof == usize::MAX {
                    write!(f, "invalid input: {field} = {value} {reason}")
                } else {
                    write!(f, "invalid input: {field}[{dof}] = {value} {reason}")
                }
            }
            OtgResult::CalculationFailed { dof } => {
                write!(
                    f,
                    "calculation failed: no valid time-optimal profile for DOF {dof}"
                )
            }
            OtgResult::SynchronizationFailed { dof, duration } => write!(
                f,
                "synchronization failed: DOF {dof} has no profile of duration {duration} s"
            ),
        }
    }
}

impl std::error::Error for OtgResult {}
