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
    #[error("{field} = {} {reason}", show(*value))]
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
    /// A limit the operation needs was given by no source. An absent limit is never read as
    /// "unlimited": the caller supplies it, or states infinity explicitly.
    #[error(
        "{} has no {field} limit (none was given; supply one, or state it as unlimited explicitly)",
        joint_label(*joint, name)
    )]
    MissingLimit {
        /// 0-based joint index (messages print it 1-based).
        joint: usize,
        /// Joint name; may be empty.
        name: String,
        /// The missing field: `"velocity"`, `"acceleration"`, `"jerk"` or `"position range"`.
        field: &'static str,
    },
    /// Data (waypoint or table columns) and limits both name their joints, and some data joint
    /// has no limits of that name.
    #[error(
        "no limits for {data} joint(s) {}: {data} joints [{}], limit joints [{}]",
        missing.join(", "),
        names.join(", "),
        limit_names.join(", ")
    )]
    JointNames {
        /// What names the joints: `"waypoint"`, `"table"`, `"filled"`.
        data: &'static str,
        /// The data joints without limits.
        missing: Vec<String>,
        /// Every data joint name, in order.
        names: Vec<String>,
        /// Every joint name of the limits, in order.
        limit_names: Vec<String>,
    },
    /// A count the caller controls (waypoints, gridpoints, samples, basis functions, ...)
    /// would need more memory or work than trajkit allows; checked before allocating.
    #[error("{what} = {} is above the limit of {} ({reason})", show(*value), show(*limit))]
    TooLarge {
        /// What was counted, e.g. `"sample count (duration × rate)"`.
        what: String,
        /// The count asked for.
        value: f64,
        /// The largest count allowed.
        limit: f64,
        /// Why the limit is there, e.g. `"each sample of 7 joints takes 232 bytes; budget 1 GiB"`.
        reason: String,
    },
    /// A trajectory leaves a joint's position range.
    #[error(
        "{} reaches {value} at t = {time} s, outside its position range [{lo}, {hi}] by {}",
        joint_label(*joint, name),
        excess(*value, *lo, *hi)
    )]
    OutOfRange {
        /// 0-based joint index.
        joint: usize,
        /// Joint name; may be empty.
        name: String,
        /// When (seconds; the path parameter where no time exists yet).
        time: f64,
        /// The position reached.
        value: f64,
        /// Lower end of the range.
        lo: f64,
        /// Upper end of the range.
        hi: f64,
    },
    /// A waypoint lies outside its joint's position range: no motion through it is allowed.
    #[error(
        "waypoint {waypoint} {} = {value} is outside the position range [{lo}, {hi}]",
        joint_label(*joint, name)
    )]
    WaypointOutOfRange {
        /// 0-based waypoint index (in the input, before duplicates are removed).
        waypoint: usize,
        /// 0-based joint index.
        joint: usize,
        /// Joint name; may be empty.
        name: String,
        /// The waypoint's position.
        value: f64,
        /// Lower end of the range.
        lo: f64,
        /// Upper end of the range.
        hi: f64,
    },
    /// The chosen method cannot hold a limit it was given (a finite jerk limit for a method
    /// whose jerk is unbounded, say); the reason says why and what to do.
    #[error("{} {field} limit {value} cannot be held: {reason}", joint_label(*joint, name))]
    CannotHold {
        /// 0-based joint index.
        joint: usize,
        /// Joint name; may be empty.
        name: String,
        /// `"velocity"`, `"acceleration"`, `"jerk"`, `"effort"`.
        field: &'static str,
        /// The limit.
        value: f64,
        /// Why, and the way out.
        reason: String,
    },
    /// A trajectory exceeds a velocity, acceleration or jerk limit.
    #[error(
        "{} {field} {value} at t = {time} s is {ratio} × its limit",
        joint_label(*joint, name)
    )]
    LimitExceeded {
        /// 0-based joint index.
        joint: usize,
        /// Joint name; may be empty.
        name: String,
        /// `"velocity"`, `"acceleration"` or `"jerk"`.
        field: &'static str,
        /// The value reached.
        value: f64,
        /// Its ratio to the limit (directional limits respected).
        ratio: f64,
        /// When, in seconds.
        time: f64,
    },
    /// Online generation failed (see [`crate::otg::OtgError`]: the DOF, field and value).
    #[error("otg: {0}")]
    Otg(#[from] crate::otg::OtgError),
}

/// `joint 3 (elbow)`, or `joint 3` when unnamed (`joint` is 0-based).
pub fn joint_label(joint: usize, name: &str) -> String {
    if name.is_empty() {
        format!("joint {}", joint + 1)
    } else {
        format!("joint {} ({name})", joint + 1)
    }
}

/// A number for messages: Rust's shortest form, in exponent notation when it would run to
/// more than 16 digits (`1e300`, not three hundred zeros).
fn show(v: f64) -> String {
    let a = v.abs();
    if v.is_finite() && a != 0.0 && !(1e-5..1e16).contains(&a) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// How far `value` lies outside `[lo, hi]` (0 inside).
fn excess(value: f64, lo: f64, hi: f64) -> f64 {
    (lo - value).max(value - hi).max(0.0)
}

/// The known name closest to `given` (edit distance, case-insensitive), when it is close
/// enough to be a likely misspelling: at most 2 edits, or a third of the longer name. Used to
/// suggest a field in "unknown field" errors.
///
/// ```
/// use trajkit::error::closest_name;
/// assert_eq!(closest_name("max_velocityy", &["max_velocity", "max_jerk"]), Some("max_velocity"));
/// assert_eq!(closest_name("waypionts", &["waypoints", "joint_names"]), Some("waypoints"));
/// assert_eq!(closest_name("colour", &["waypoints", "joint_names"]), None);
/// ```
pub fn closest_name<'a>(given: &str, known: &[&'a str]) -> Option<&'a str> {
    let g: Vec<char> = given.to_lowercase().chars().collect();
    let mut best: Option<(usize, &'a str)> = None;
    for &k in known {
        let kc: Vec<char> = k.to_lowercase().chars().collect();
        // Levenshtein distance, one row at a time.
        let mut row: Vec<usize> = (0..=kc.len()).collect();
        for (i, &a) in g.iter().enumerate() {
            let mut prev = row[0];
            row[0] = i + 1;
            for (j, &b) in kc.iter().enumerate() {
                let cur = row[j + 1];
                row[j + 1] = (prev + usize::from(a != b)).min(row[j] + 1).min(cur + 1);
                prev = cur;
            }
        }
        let d = row[kc.len()];
        let allowed = 2.max(g.len().max(kc.len()) / 3);
        if d <= allowed && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, k));
        }
    }
    best.map(|(_, k)| k)
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
        let e = Error::InvalidValue {
            field: "goal".into(),
            value: 1e300,
            reason: "is far",
        };
        assert_eq!(e.to_string(), "goal = 1e300 is far");
        let e = Error::MissingLimit {
            joint: 2,
            name: "elbow".into(),
            field: "acceleration",
        };
        assert!(e
            .to_string()
            .starts_with("joint 3 (elbow) has no acceleration limit"));
        let e = Error::OutOfRange {
            joint: 5,
            name: String::new(),
            time: 3.0,
            value: 3.875,
            lo: -0.0175,
            hi: 3.75,
        };
        assert_eq!(
            e.to_string(),
            "joint 6 reaches 3.875 at t = 3 s, outside its position range [-0.0175, 3.75] by 0.125"
        );
        let e = Error::JointNames {
            data: "waypoint",
            missing: vec!["c".into()],
            names: vec!["a".into(), "c".into()],
            limit_names: vec!["a".into(), "b".into()],
        };
        assert_eq!(
            e.to_string(),
            "no limits for waypoint joint(s) c: waypoint joints [a, c], limit joints [a, b]"
        );
        assert_eq!(finite(|| "t".into(), 2.0).unwrap(), 2.0);
    }
}
