//! One recipe from a front end's limit settings to the limits of some data, see [`LimitsSpec`].

use super::{FillBy, PartialLimits};
use crate::error::Error;
use crate::traj::Order;
use std::fmt;

/// A text file given by content: its name (used in error messages) and its text.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct TextFile {
    /// Name of the file, e.g. `joint_limits.yaml`; errors cite it.
    pub name: String,
    /// The file's content.
    pub text: String,
}

/// Everything a front end (the command line, the studio, the Python package) may say about
/// limits, as plain data; [`LimitsSpec::resolve`] turns it into the limits of some data in one
/// fixed order of steps:
///
/// 1. the **source**: [`source`](Self::source), or, when `None`, limits for `dof` unnamed
///    joints in which nothing is given (the overrides below then give them);
/// 2. MoveIt **overrides** by joint name ([`joint_limits`](Self::joint_limits), a MoveIt
///    `joint_limits.yaml`; feature `yaml`);
/// 3. absent accelerations and jerks **filled** from [`fill_from`](Self::fill_from), paired
///    as [`fill_by`](Self::fill_by) says;
/// 4. **pairing** with the data's joints by name ([`PartialLimits::for_joints`]) and a check
///    that the joint counts agree;
/// 5. per-order **overrides** ([`max_velocity`](Self::max_velocity),
///    [`max_acceleration`](Self::max_acceleration), [`max_jerk`](Self::max_jerk): one value
///    for every joint or one per data joint) and [`position_range`](Self::position_range);
/// 6. the **scales** (applied only when one differs from 1).
///
/// A failure says which step failed ([`SpecError::step`]), so that a front end words it with
/// its own names for the settings (`--fill-from`, `limits.fill_from`). What a method needs and
/// no step gave is refused later, by [`PartialLimits::complete`].
///
/// ```
/// use trajkit::limits::{LimitsSpec, Needs};
/// let spec = LimitsSpec {
///     source: Some(trajkit::Limits::preset("panda")?.into()),
///     max_velocity: Some(vec![1.0]),
///     jerk_scale: 0.5,
///     ..LimitsSpec::default()
/// };
/// let r = spec.resolve("waypoint", None, 7)?;
/// let limits = r.limits.complete(Needs::ALL)?;
/// assert_eq!(limits.joint(3).velocity, 1.0);
/// assert_eq!(limits.joint(0).jerk, 3750.0);
/// # Ok::<(), trajkit::limits::SpecError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct LimitsSpec {
    /// The limits to start from (a preset, a loaded file); `None`: no source, every limit
    /// comes from the overrides.
    pub source: Option<PartialLimits>,
    /// A MoveIt `joint_limits.yaml` whose joints override the source's by name.
    #[cfg(feature = "yaml")]
    pub joint_limits: Option<TextFile>,
    /// Limits to fill absent accelerations and jerks from (e.g. a preset for a URDF).
    pub fill_from: Option<PartialLimits>,
    /// How [`fill_from`](Self::fill_from) pairs joints.
    pub fill_by: FillBy,
    /// Maximum velocities: one for every joint, or one per data joint (`inf`: unlimited).
    pub max_velocity: Option<Vec<f64>>,
    /// Maximum accelerations, as [`max_velocity`](Self::max_velocity).
    pub max_acceleration: Option<Vec<f64>>,
    /// Maximum jerks, as [`max_velocity`](Self::max_velocity).
    pub max_jerk: Option<Vec<f64>>,
    /// Position ranges `(lo, hi)`: one for every joint or one per data joint (infinite ends:
    /// unbounded).
    pub position_range: Option<Vec<(f64, f64)>>,
    /// Factor on every velocity limit (1: unchanged).
    pub velocity_scale: f64,
    /// Factor on every acceleration limit (1: unchanged).
    pub acceleration_scale: f64,
    /// Factor on every jerk limit (1: unchanged).
    pub jerk_scale: f64,
}

impl Default for LimitsSpec {
    /// No source, no overrides, fill by name, scales 1.
    fn default() -> Self {
        LimitsSpec {
            source: None,
            #[cfg(feature = "yaml")]
            joint_limits: None,
            fill_from: None,
            fill_by: FillBy::Name,
            max_velocity: None,
            max_acceleration: None,
            max_jerk: None,
            position_range: None,
            velocity_scale: 1.0,
            acceleration_scale: 1.0,
            jerk_scale: 1.0,
        }
    }
}

/// The step of [`LimitsSpec::resolve`] that failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpecStep {
    /// Making the limits of unnamed joints when there is no source.
    Source,
    /// Applying the MoveIt `joint_limits.yaml`.
    JointLimits,
    /// Filling from [`LimitsSpec::fill_from`].
    FillFrom,
    /// Pairing the limits' joints with the data's by name.
    Pairing,
    /// The limits (after pairing) have another number of joints than the data.
    JointCount,
    /// A per-order override (velocity, acceleration or jerk).
    Override(Order),
    /// The position ranges.
    PositionRange,
    /// The scales.
    Scales,
}

/// A failure of [`LimitsSpec::resolve`]: the step and the library's error.
#[derive(Debug, Clone, PartialEq)]
pub struct SpecError {
    /// Which step failed.
    pub step: SpecStep,
    /// Why.
    pub error: Error,
}

impl fmt::Display for SpecError {
    /// The error alone: the step is for the front end to name in its own words.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.error.fmt(f)
    }
}

impl std::error::Error for SpecError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

impl From<SpecError> for Error {
    fn from(e: SpecError) -> Self {
        e.error
    }
}

impl From<Error> for SpecError {
    /// An error outside [`LimitsSpec::resolve`]'s steps (e.g. loading a source) counts as the
    /// source's.
    fn from(error: Error) -> Self {
        SpecError {
            step: SpecStep::Source,
            error,
        }
    }
}

/// What [`LimitsSpec::resolve`] gives for some data.
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedLimits {
    /// The limits, one per data joint in the data's order, with what was given.
    pub limits: PartialLimits,
    /// Joints of the source that no data joint names.
    pub unused: Vec<String>,
}

impl LimitsSpec {
    /// True when some per-order override or position range is set (they can give limits
    /// without a source).
    pub fn has_overrides(&self) -> bool {
        self.max_velocity.is_some()
            || self.max_acceleration.is_some()
            || self.max_jerk.is_some()
            || self.position_range.is_some()
    }

    /// The limits for data (`what`: `"waypoint"`, `"table"`) of `dof` joints named `names`
    /// (`None`: unnamed, paired by position), through the steps of the type documentation.
    pub fn resolve(
        &self,
        what: &'static str,
        names: Option<&[String]>,
        dof: usize,
    ) -> std::result::Result<ResolvedLimits, SpecError> {
        let at = |step: SpecStep| move |error: Error| SpecError { step, error };
        let mut l = match &self.source {
            Some(l) => l.clone(),
            None => PartialLimits::unnamed(dof).map_err(at(SpecStep::Source))?,
        };
        #[cfg(feature = "yaml")]
        if let Some(f) = &self.joint_limits {
            l = super::load::apply_moveit_joint_limits(&l, &f.text, &f.name)
                .map_err(at(SpecStep::JointLimits))?;
        }
        if let Some(from) = &self.fill_from {
            l = l
                .fill_from(from, self.fill_by)
                .map_err(at(SpecStep::FillFrom))?;
        }
        let (mut l, unused) = l.for_joints(what, names).map_err(at(SpecStep::Pairing))?;
        if l.dof() != dof {
            return Err(SpecError {
                step: SpecStep::JointCount,
                error: joint_count_error(what, dof, l.dof()),
            });
        }
        for (order, v) in [
            (Order::Velocity, &self.max_velocity),
            (Order::Acceleration, &self.max_acceleration),
            (Order::Jerk, &self.max_jerk),
        ] {
            if let Some(v) = v {
                l = l
                    .with_override(order, v)
                    .map_err(at(SpecStep::Override(order)))?;
            }
        }
        if let Some(r) = &self.position_range {
            l = l
                .with_position_range(r)
                .map_err(at(SpecStep::PositionRange))?;
        }
        let scales = (
            self.velocity_scale,
            self.acceleration_scale,
            self.jerk_scale,
        );
        if scales != (1.0, 1.0, 1.0) {
            l = l
                .scaled(scales.0, scales.1, scales.2)
                .map_err(at(SpecStep::Scales))?;
        }
        Ok(ResolvedLimits { limits: l, unused })
    }
}

/// The error of [`SpecStep::JointCount`], worded as [`super::Limits::expect_dof`] words it.
fn joint_count_error(what: &str, dof: usize, found: usize) -> Error {
    Error::DimensionMismatch {
        what: format!("limits joint count for the {what}s"),
        expected: dof,
        found,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::{Limits, Needs};

    fn panda() -> PartialLimits {
        Limits::preset("panda").unwrap().into()
    }

    #[test]
    fn steps_apply_in_order() {
        let spec = LimitsSpec {
            source: Some(panda()),
            max_velocity: Some(vec![1.0]),
            position_range: Some(vec![(-1.0, 1.0)]),
            velocity_scale: 0.5,
            ..LimitsSpec::default()
        };
        let r = spec.resolve("waypoint", None, 7).unwrap();
        let l = r.limits.complete(Needs::ALL).unwrap();
        // The override comes before the scale.
        assert_eq!(l.joint(6).velocity, 0.5);
        assert_eq!(
            (l.joint(2).position_min, l.joint(2).position_max),
            (-1.0, 1.0)
        );
        assert!(r.unused.is_empty());
    }

    #[test]
    fn named_data_selects_and_reports_unused() {
        let spec = LimitsSpec {
            source: Some(panda()),
            ..LimitsSpec::default()
        };
        let names = ["panda_joint3".to_string(), "panda_joint1".to_string()];
        let r = spec.resolve("waypoint", Some(&names), 2).unwrap();
        assert_eq!(r.limits.names(), names);
        assert_eq!(r.unused.len(), 5);
    }

    #[test]
    fn failures_name_their_step() {
        let spec = LimitsSpec {
            source: Some(panda()),
            ..LimitsSpec::default()
        };
        let e = spec.resolve("table", None, 3).unwrap_err();
        assert_eq!(e.step, SpecStep::JointCount);
        assert_eq!(
            e.to_string(),
            "limits joint count for the tables: expected 3, found 7"
        );
        let spec = LimitsSpec {
            max_jerk: Some(vec![1.0, 2.0]),
            ..spec
        };
        let e = spec.resolve("waypoint", None, 7).unwrap_err();
        assert_eq!(e.step, SpecStep::Override(Order::Jerk));
        let spec = LimitsSpec {
            fill_from: Some(PartialLimits::unnamed(2).unwrap()),
            fill_by: FillBy::Index,
            ..LimitsSpec::default()
        };
        let e = spec.resolve("waypoint", None, 3).unwrap_err();
        assert_eq!(e.step, SpecStep::FillFrom);
        let spec = LimitsSpec {
            velocity_scale: -1.0,
            ..LimitsSpec::default()
        };
        assert_eq!(
            spec.resolve("waypoint", None, 3).unwrap_err().step,
            SpecStep::Scales
        );
    }

    #[test]
    fn no_source_gives_nothing_but_the_overrides() {
        let spec = LimitsSpec {
            max_velocity: Some(vec![2.0]),
            ..LimitsSpec::default()
        };
        assert!(spec.has_overrides());
        let l = spec.resolve("waypoint", None, 2).unwrap().limits;
        assert_eq!(l.joint(1).velocity, 2.0);
        assert!(l.complete(Needs::ALL).is_err());
    }
}
