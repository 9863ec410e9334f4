//! Loading limits from files: trajkit's own JSON/YAML format, MoveIt `joint_limits.yaml`, and
//! URDF `<limit>` tags.
//!
//! Every loader returns validated [`PartialLimits`]: the values, and which of them the file
//! gave. A limit the file does not give is *absent*, not unlimited; complete the limits with
//! other sources ([`PartialLimits::fill_from`], overrides) and then
//! [`PartialLimits::complete`], which refuses absent limits an operation needs. A bad file
//! gives an [`Error::Parse`] whose location names the file, the line when the format tells it,
//! and the field (for example `joints[2].velocity`), and whose message quotes the offending
//! value. Unknown fields are errors that suggest the closest known field, so a misspelt key
//! never goes unnoticed.
//!
//! # trajkit limits format (JSON or YAML)
//! ```yaml
//! preset: panda            # optional: start from a robot preset
//! joints:
//!   - name: panda_joint1   # optional
//!     position: [-2.8973, 2.8973]   # optional; or position_min / position_max
//!     velocity: 2.175      # optional
//!     acceleration: 15
//!     jerk: 7500
//!     min_velocity: -1.0   # optional: most negative velocity, must be negative
//!     min_acceleration: -10
//!     effort: 87           # optional
//! ```
//! Without `preset`, the listed joints are the robot, and a limit a joint does not list is
//! absent. With `preset`, the listed fields override the preset's: a joint entry with a
//! `name` updates the preset joint of that name, one without a name updates the joint at the
//! same index; absent fields keep the preset's value. In both cases `null` means unlimited
//! (for `velocity`, `acceleration`, `jerk`) or unbounded (for the ends of `position`), stated
//! on purpose, "the negated maximum" (for `min_velocity`, `min_acceleration`) and unknown (for
//! `effort`). YAML's `.inf` is accepted as unlimited too; NaN and strings are refused.
//!
//! # MoveIt `joint_limits.yaml`
//! The `joint_limits` mapping (joint name → `has_velocity_limits`, `max_velocity`,
//! `has_acceleration_limits`, `max_acceleration`, `has_jerk_limits`, `max_jerk`,
//! `has_position_limits`, `min_position`, `max_position`, `has_effort_limits`, `max_effort`)
//! is read as MoveIt reads it: a value applies only when its `has_…` flag is `true`, and then it
//! must be present and valid; a limit whose flag is `false` or missing is absent (MoveIt
//! itself substitutes defaults there, trajkit asks). The keys `has_deceleration_limits`, `max_deceleration`,
//! `angle_wraparound`, `has_soft_limits`, `k_position`, `k_velocity`, `soft_lower_limit` and
//! `soft_upper_limit` are accepted and ignored (trajkit's model has no deceleration or soft
//! limits). The top-level `default_velocity_scaling_factor` and
//! `default_acceleration_scaling_factor` are checked to be numbers and **ignored**: they are
//! MoveIt's default request scaling, not robot limits; scale limits explicitly with
//! [`crate::Limits::scaled`] instead. A MoveIt maximum replaces the base joint's limit in both
//! directions (any direction-dependent minimum is dropped).
//!
//! # URDF
//! Every `<joint>` child of `<robot>` of type `revolute`, `prismatic` or `continuous`, in
//! document order, except joints with a `<mimic>` element (they follow another joint and are
//! not commanded). Its `<limit>` gives the position range (`lower`, `upper`; none for
//! `continuous`, whose range is unbounded by definition; an absent attribute leaves that end
//! absent), `velocity` (absent when the attribute is) and `effort` (absent or `0`, which URDF
//! exporters write for "unknown": no effort limit). URDF has no acceleration or jerk limits:
//! they are absent; complete them with [`PartialLimits::fill_from`] from a preset or another
//! file, or with explicit values.
//!
//! ```
//! use trajkit::limits::load;
//! let text = r#"{"preset": "panda", "joints": [{"name": "panda_joint2", "velocity": 1.0}]}"#;
//! let limits = load::from_json_str(text, "limits.json")?;
//! assert_eq!(limits.joint(1).velocity, 1.0);
//! assert_eq!(limits.joint(0).velocity, 2.175);
//! let limits = limits.complete(trajkit::limits::Needs::ALL)?; // the preset gives everything
//! # Ok::<(), trajkit::Error>(())
//! ```

#[cfg(feature = "yaml")]
mod moveit;
#[cfg(feature = "serde")]
mod trajkit_format;
#[cfg(feature = "urdf")]
mod urdf;
#[cfg(feature = "serde")]
mod value;

#[cfg(feature = "yaml")]
pub use moveit::{apply_moveit_joint_limits, moveit_joint_limits_from_str};
#[cfg(feature = "serde")]
pub use trajkit_format::from_json_str;
#[cfg(feature = "yaml")]
pub use trajkit_format::from_yaml_str;
#[cfg(feature = "urdf")]
pub use urdf::{from_urdf, from_urdf_str};

use super::{presets, PartialLimits};
use crate::error::{Error, Location, Result};
use std::path::Path;

// ---------------------------------------------------------------------------------------------
// Dispatch.

/// True when YAML text is a mapping with a top-level `joint_limits` key (MoveIt's format).
#[cfg(feature = "yaml")]
fn is_moveit_yaml(text: &str, source: &str) -> Result<bool> {
    let v: serde_yaml_ng::Value =
        serde_yaml_ng::from_str(text).map_err(|e| value::yaml_error(source, e))?;
    Ok(v.as_mapping()
        .is_some_and(|m| m.contains_key(serde_yaml_ng::Value::from("joint_limits"))))
}

/// Loads a limits file, choosing the format by extension: `.json` (trajkit format), `.yaml` /
/// `.yml` (MoveIt `joint_limits.yaml` when it has a top-level `joint_limits` key, else trajkit
/// format), `.urdf` / `.xml` (URDF).
///
/// Errors: [`Error::Io`] naming the path when it cannot be read; [`Error::Parse`] for an
/// unknown extension or bad content.
pub fn from_file(path: &Path) -> Result<PartialLimits> {
    let source = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    if !matches!(ext.as_str(), "json" | "yaml" | "yml" | "urdf" | "xml") {
        return Err(file_error(
            &source,
            "",
            format!(
                "cannot tell the limits format from the extension '{ext}' \
                 (expected .json, .yaml, .yml, .urdf or .xml)"
            ),
        ));
    }
    #[cfg_attr(not(any(feature = "serde", feature = "urdf")), allow(unused_variables))]
    let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
        path: source.clone(),
        message: e.to_string(),
    })?;
    match ext.as_str() {
        #[cfg(feature = "serde")]
        "json" => from_json_str(&text, &source),
        #[cfg(feature = "yaml")]
        "yaml" | "yml" => {
            if is_moveit_yaml(&text, &source)? {
                moveit_joint_limits_from_str(&text, &source, None)
            } else {
                from_yaml_str(&text, &source)
            }
        }
        #[cfg(feature = "urdf")]
        "urdf" | "xml" => from_urdf_str(&text, &source),
        other => Err(file_error(
            &source,
            "",
            format!(
                "reading .{other} limits files needs trajkit's `{}` feature, which this build \
                 leaves out",
                match other {
                    "json" => "serde",
                    "yaml" | "yml" => "yaml",
                    _ => "urdf",
                }
            ),
        )),
    }
}

/// Limits from a command-line style specification: a robot preset name (see
/// [`presets::NAMES`]) or the path of a limits file (see [`from_file`]).
///
/// A specification that is neither a preset nor an existing file gives
/// [`Error::UnknownPreset`] when it looks like a name (no extension, no path separator) and
/// [`Error::Io`] otherwise.
pub fn from_spec(spec: &str) -> Result<PartialLimits> {
    if let Ok(l) = presets::by_name(spec) {
        return Ok(l.into());
    }
    let path = Path::new(spec);
    let looks_like_name = !spec.contains(['/', '\\', '.']);
    if looks_like_name && !path.exists() {
        return presets::by_name(spec).map(Into::into);
    }
    from_file(path).map_err(|e| match e {
        Error::Io { path, message } => Error::Io {
            path,
            message: format!(
                "{message} (and it is not a robot preset: {})",
                presets::NAMES
            ),
        },
        other => other,
    })
}

/// Wraps an error found after parsing (no line known) so that it names the file.
#[cfg_attr(not(any(feature = "serde", feature = "urdf")), allow(dead_code))]
pub(super) fn in_file(source: &str, e: Error) -> Error {
    match e {
        Error::Parse { .. } | Error::Io { .. } => e,
        other => Error::Parse {
            location: Location {
                source: source.to_string(),
                line: 0,
                field: String::new(),
            },
            message: other.to_string(),
        },
    }
}

pub(super) fn file_error(source: &str, field: &str, message: impl Into<String>) -> Error {
    Error::Parse {
        location: Location {
            source: source.to_string(),
            line: 0,
            field: field.to_string(),
        },
        message: message.into(),
    }
}

#[cfg(all(test, feature = "yaml", feature = "urdf"))]
mod tests;
