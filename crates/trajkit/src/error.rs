//! The one error type of the library.
//!
//! Every fallible constructor and loader in trajkit returns [`Result<T>`]. Each variant carries
//! the offending value and names the field it came from, so that a message such as
//! `limits: joint 3 (panda_joint3) velocity = -1 is not a positive number` can be shown to a user
//! as it is. Variants are `#[non_exhaustive]`: match with a wildcard arm.

use std::fmt;

/// Shorthand for `std::result::Result<T, trajkit::Error>`.
pub type Result<T> = std::result::Result<T, Error>;

/// Where a bad value was found in a file: the file, a 1-based line (0 when unknown) and a field.
#[derive(Debug, Clone, PartialEq)]
pub struct Location {
    /// File name or description of the source (`"<embedded>"`, `"<stdin>"`).
    pub source: String,
    /// 1-based line number; 0 when the format has no meaningful line (e.g. a value deep in JSON).
    pub line: usize,
    /// Field or column name, e.g. `"q3"` or `"joints[2].velocity"`.
    pub field: String,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.source)?;
        if self.line > 0 {
            write!(f, ":{}", self.line)?;
        }
        if !self.field.is_empty() {
            write!(f, " field '{}'", self.field)?;
        }
        Ok(())
    }
}

/// Everything that can go wrong in trajkit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A number is not acceptable for the named field (NaN, infinite, zero, negative, ...).
    #[error("{field} = {value} {reason}")]
    InvalidValue {
        /// The field, e.g. `"joint 2 velocity limit"`.
        field: String,
        /// The value that was given.
        value: f64,
        /// Why it is refused, e.g. `"is not a positive number"`.
        reason: &'static str,
    },
    /// Two sizes that must agree do not.
    #[error("{what}: expected {expected}, found {found}")]
    DimensionMismatch {
        /// What was being compared, e.g. `"waypoint 4 joint count"`.
        what: String,
        /// The size required.
        expected: usize,
        /// The size given.
        found: usize,
    },
    /// Fewer waypoints than the operation needs.
    #[error("{needed} waypoints needed, found {found}")]
    TooFewWaypoints {
        /// The minimum number of waypoints.
        needed: usize,
        /// How many were given (after removing duplicates where that applies).
        found: usize,
    },
    /// Two consecutive waypoints are identical (a zero-length segment).
    #[error("waypoint {index} repeats waypoint {} (zero-length segment)", index - 1)]
    DuplicateWaypoint {
        /// Index of the second of the two identical waypoints.
        index: usize,
    },
    /// A robot preset name that trajkit does not know.
    #[error("unknown robot preset '{name}' (known: {known})")]
    UnknownPreset {
        /// The name given.
        name: String,
        /// Comma-separated list of known names.
        known: &'static str,
    },
    /// A file could not be parsed, or a value in it is invalid.
    #[error("{location}: {message}")]
    Parse {
        /// Where in the file.
        location: Location,
        /// What is wrong there.
        message: String,
    },
    /// A file could not be read or written.
    #[error("{path}: {message}")]
    Io {
        /// The path.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The problem has no solution within the limits (e.g. a joint must move but its limit is
    /// zero); the message says where and why.
    #[error("infeasible: {0}")]
    Infeasible(String),
    /// Online generation failed (see [`crate::otg::OtgError`]: the DOF, field and value).
    #[error("otg: {0}")]
    Otg(#[from] crate::otg::OtgError),
}

/// Checks that `value` is finite; `field` names it in the error.
pub(crate) fn finite(field: impl FnOnce() -> String, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::InvalidValue {
            field: field(),
            value,
            reason: "is not a finite number",
        })
    }
}

/// Checks that `value` is strictly positive and finite.
pub(crate) fn positive(field: impl FnOnce() -> String, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::InvalidValue {
            field: field(),
            value,
            reason: "is not a positive finite number",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_field_and_value() {
        let e = positive(|| "joint 2 velocity limit".into(), -1.5).unwrap_err();
        assert_eq!(
            e.to_string(),
            "joint 2 velocity limit = -1.5 is not a positive finite number"
        );
        let e = Error::Parse {
            location: Location {
                source: "w.csv".into(),
                line: 4,
                field: "q3".into(),
            },
            message: "'abc' is not a number".into(),
        };
        assert_eq!(e.to_string(), "w.csv:4 field 'q3': 'abc' is not a number");
        assert_eq!(
            Error::DuplicateWaypoint { index: 3 }.to_string(),
            "waypoint 3 repeats waypoint 2 (zero-length segment)"
        );
        assert!(finite(|| "t".into(), f64::NAN).is_err());
        assert_eq!(finite(|| "t".into(), 2.0).unwrap(), 2.0);
    }
}
