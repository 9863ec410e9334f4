//! Per-joint kinematic limits, robot presets, and loaders for limits files and URDF.
//!
//! [`Limits`] holds one [`JointLimits`] per joint: a position range, maximum velocity,
//! acceleration and jerk, and optional direction-dependent minima (the most negative velocity
//! or acceleration allowed; by default the negated maximum). In `Limits` every field is
//! meant: `f64::INFINITY` is "unlimited", stated on purpose. Construction through
//! [`Limits::new`] validates every number: NaN, zero or negative maxima, positive minima and
//! empty or inverted position ranges are refused with an error that names the joint, the
//! field and the value.
//!
//! Sources of limits: [`presets`] (manufacturer data, complete), [`load`] (trajkit JSON/YAML
//! limits files, MoveIt `joint_limits.yaml`, URDF `<limit>` tags). A file may leave limits
//! out, so the loaders return [`PartialLimits`], which records what was given; an absent
//! limit is never read as "unlimited": [`PartialLimits::complete`] refuses it where it is
//! needed ([`crate::Error::MissingLimit`]). Data and limits are paired by joint name where
//! both name their joints ([`match_names`], [`Limits::for_joints`]). [`LimitsSpec`] is the one
//! recipe every front end (command line, studio, Python) follows from its settings (source,
//! MoveIt overrides, completion, per-joint overrides, position ranges, scales) to the limits
//! of its data.

pub mod load;
mod partial;
pub mod presets;
mod spec;

pub use partial::{match_names, FillBy, Given, Needs, PartialLimits};
pub use spec::{LimitsSpec, ResolvedLimits, SpecError, SpecStep, TextFile};

use crate::error::{Error, Result};

/// Limits of one joint. Units are the joint's (rad or m) per second, per second², per second³.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointLimits {
    /// Joint name (from a URDF or a preset); may be empty.
    #[cfg_attr(feature = "serde", serde(default))]
    pub name: String,
    /// Lowest position; `-inf` when unbounded.
    #[cfg_attr(feature = "serde", serde(default = "neg_inf"))]
    pub position_min: f64,
    /// Highest position; `+inf` when unbounded.
    #[cfg_attr(feature = "serde", serde(default = "pos_inf"))]
    pub position_max: f64,
    /// Largest velocity (> 0); `inf` when unlimited.
    #[cfg_attr(feature = "serde", serde(default = "pos_inf"))]
    pub velocity: f64,
    /// Largest acceleration (> 0); `inf` when unlimited.
    #[cfg_attr(feature = "serde", serde(default = "pos_inf"))]
    pub acceleration: f64,
    /// Largest jerk (> 0); `inf` when unlimited.
    #[cfg_attr(feature = "serde", serde(default = "pos_inf"))]
    pub jerk: f64,
    /// Most negative velocity allowed (< 0); `None` means `-velocity`.
    #[cfg_attr(feature = "serde", serde(default))]
    pub min_velocity: Option<f64>,
    /// Most negative acceleration allowed (< 0); `None` means `-acceleration`.
    #[cfg_attr(feature = "serde", serde(default))]
    pub min_acceleration: Option<f64>,
    /// Largest joint torque or force (> 0), when known (URDF `effort`); informational here,
    /// used by torque-constrained time parameterization.
    #[cfg_attr(feature = "serde", serde(default))]
    pub effort: Option<f64>,
}

#[cfg(feature = "serde")]
fn neg_inf() -> f64 {
    f64::NEG_INFINITY
}
#[cfg(feature = "serde")]
fn pos_inf() -> f64 {
    f64::INFINITY
}

impl Default for JointLimits {
    fn default() -> Self {
        JointLimits {
            name: String::new(),
            position_min: f64::NEG_INFINITY,
            position_max: f64::INFINITY,
            velocity: f64::INFINITY,
            acceleration: f64::INFINITY,
            jerk: f64::INFINITY,
            min_velocity: None,
            min_acceleration: None,
            effort: None,
        }
    }
}

impl JointLimits {
    /// Symmetric limits with an unbounded position range.
    pub fn symmetric(velocity: f64, acceleration: f64, jerk: f64) -> Self {
        JointLimits {
            velocity,
            acceleration,
            jerk,
            ..Default::default()
        }
    }

    /// The allowed interval `[lo, hi]` for derivative `order` (1 = velocity, 2 = acceleration,
    /// 3 = jerk; 0 = position range).
    pub fn range(&self, order: crate::Order) -> (f64, f64) {
        use crate::Order::*;
        match order {
            Position => (self.position_min, self.position_max),
            Velocity => (self.min_velocity.unwrap_or(-self.velocity), self.velocity),
            Acceleration => (
                self.min_acceleration.unwrap_or(-self.acceleration),
                self.acceleration,
            ),
            Jerk => (-self.jerk, self.jerk),
        }
    }

    /// How much of the limit a value uses: `value / max` for `value >= 0`, `value / min` for
    /// negative values (so 1.0 means exactly at the limit). 0 for an unlimited derivative.
    /// Only for orders 1..=3.
    pub fn ratio(&self, order: crate::Order, value: f64) -> f64 {
        let (lo, hi) = self.range(order);
        ratio_in(lo, hi, value)
    }

    /// The smaller magnitude of the two directional limits of `order` (1..=3): the symmetric
    /// limit that is safe in both directions.
    pub fn symmetric_limit(&self, order: crate::Order) -> f64 {
        let (lo, hi) = self.range(order);
        hi.min(-lo)
    }

    fn validate(&self, j: usize) -> Result<()> {
        let label = |what: &str| {
            if self.name.is_empty() {
                format!("joint {} {}", j + 1, what)
            } else {
                format!("joint {} ({}) {}", j + 1, self.name, what)
            }
        };
        let max_ok = |v: f64| v > 0.0 && !v.is_nan(); // +inf allowed (unlimited)
        for (what, v) in [
            ("velocity limit", self.velocity),
            ("acceleration limit", self.acceleration),
            ("jerk limit", self.jerk),
        ] {
            if !max_ok(v) {
                return Err(Error::InvalidValue {
                    field: label(what),
                    value: v,
                    reason: "is not a positive number",
                });
            }
        }
        for (what, v) in [
            ("minimum velocity", self.min_velocity),
            ("minimum acceleration", self.min_acceleration),
        ] {
            if let Some(v) = v {
                if v.is_nan() || v >= 0.0 {
                    return Err(Error::InvalidValue {
                        field: label(what),
                        value: v,
                        reason: "is not a negative number",
                    });
                }
            }
        }
        if let Some(e) = self.effort {
            if !max_ok(e) {
                return Err(Error::InvalidValue {
                    field: label("effort limit"),
                    value: e,
                    reason: "is not a positive number",
                });
            }
        }
        if self.position_min.is_nan() || self.position_min == f64::INFINITY {
            return Err(Error::InvalidValue {
                field: label("lower position limit"),
                value: self.position_min,
                reason: "is not a number below +inf",
            });
        }
        if self.position_max.is_nan() || self.position_max == f64::NEG_INFINITY {
            return Err(Error::InvalidValue {
                field: label("upper position limit"),
                value: self.position_max,
                reason: "is not a number above -inf",
            });
        }
        if self.position_max <= self.position_min {
            return Err(Error::InvalidValue {
                field: label("upper position limit"),
                value: self.position_max,
                reason: "is not above the lower position limit",
            });
        }
        Ok(())
    }
}

/// One value for every joint (`values` of length 1) or one per joint, as a vector of `dof`
/// values; `what` names them in the error.
pub(crate) fn per_joint<T: Copy>(values: &[T], dof: usize, what: &str) -> Result<Vec<T>> {
    match values.len() {
        1 => Ok(vec![values[0]; dof]),
        n if n == dof => Ok(values.to_vec()),
        n => Err(Error::DimensionMismatch {
            what: what.to_string(),
            expected: dof,
            found: n,
        }),
    }
}

/// Validated limits for every joint of a robot.
///
/// ```
/// use trajkit::Limits;
/// let panda = Limits::preset("panda")?;
/// assert_eq!(panda.dof(), 7);
/// assert_eq!(panda.joint(0).velocity, 2.175);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Limits {
    joints: Vec<JointLimits>,
}

impl Limits {
    /// Validates and wraps per-joint limits. At least one joint is required.
    pub fn new(joints: Vec<JointLimits>) -> Result<Self> {
        if joints.is_empty() {
            return Err(Error::DimensionMismatch {
                what: "limits joint count".into(),
                expected: 1,
                found: 0,
            });
        }
        for (j, jl) in joints.iter().enumerate() {
            jl.validate(j)?;
        }
        Ok(Limits { joints })
    }

    /// The same symmetric velocity/acceleration/jerk limits on `dof` joints, unbounded positions.
    pub fn uniform(dof: usize, velocity: f64, acceleration: f64, jerk: f64) -> Result<Self> {
        Limits::new(vec![
            JointLimits::symmetric(velocity, acceleration, jerk);
            dof
        ])
    }

    /// A robot preset by name (see [`presets::NAMES`]).
    pub fn preset(name: &str) -> Result<Self> {
        presets::by_name(name)
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// Limits of joint `j` (0-based). Panics if `j >= dof()`.
    pub fn joint(&self, j: usize) -> &JointLimits {
        &self.joints[j]
    }

    /// All joints.
    pub fn joints(&self) -> &[JointLimits] {
        &self.joints
    }

    /// Returns an error unless there are exactly `dof` joints; `what` names the other side.
    pub fn expect_dof(&self, dof: usize, what: &str) -> Result<()> {
        if self.dof() == dof {
            Ok(())
        } else {
            Err(Error::DimensionMismatch {
                what: format!("limits joint count for {what}"),
                expected: dof,
                found: self.dof(),
            })
        }
    }

    /// Refuses a waypoint (rows of row-major `points`, one value per joint) outside its joint's
    /// position range: [`Error::WaypointOutOfRange`] naming the waypoint (`index[i]` when given,
    /// the row otherwise), the joint, the value and the range.
    pub fn check_waypoints(&self, points: &[f64], index: Option<&[usize]>) -> Result<()> {
        for (i, row) in points.chunks(self.dof()).enumerate() {
            for (j, &q) in row.iter().enumerate() {
                let jl = &self.joints[j];
                if q < jl.position_min || q > jl.position_max {
                    return Err(Error::WaypointOutOfRange {
                        waypoint: index.map_or(i, |k| k[i]),
                        joint: j,
                        name: jl.name.clone(),
                        value: q,
                        lo: jl.position_min,
                        hi: jl.position_max,
                    });
                }
            }
        }
        Ok(())
    }

    /// Replaces the limits of derivative `order` (1..=3) on every joint with the given values
    /// (one per joint, or one for all), then re-validates.
    pub fn with_override(mut self, order: crate::Order, values: &[f64]) -> Result<Self> {
        let values = per_joint(
            values,
            self.dof(),
            &format!("{} limit values", order.name()),
        )?;
        for (jl, &v) in self.joints.iter_mut().zip(&values) {
            match order {
                crate::Order::Velocity => {
                    jl.velocity = v;
                    jl.min_velocity = None;
                }
                crate::Order::Acceleration => {
                    jl.acceleration = v;
                    jl.min_acceleration = None;
                }
                crate::Order::Jerk => jl.jerk = v,
                crate::Order::Position => {
                    return Err(Error::InvalidValue {
                        field: "limit override order".into(),
                        value: 0.0,
                        reason: "must be velocity, acceleration or jerk",
                    })
                }
            }
        }
        Limits::new(self.joints)
    }

    /// Every joint's limits multiplied: velocity by `velocity_scale`, acceleration (and its
    /// minimum) by `acceleration_scale`, jerk by `jerk_scale`. Scales must be positive and finite
    /// (below 1 slows the robot down).
    pub fn scaled(
        &self,
        velocity_scale: f64,
        acceleration_scale: f64,
        jerk_scale: f64,
    ) -> Result<Self> {
        crate::error::positive(|| "velocity scale".into(), velocity_scale)?;
        crate::error::positive(|| "acceleration scale".into(), acceleration_scale)?;
        crate::error::positive(|| "jerk scale".into(), jerk_scale)?;
        let joints = self
            .joints
            .iter()
            .map(|j| JointLimits {
                velocity: j.velocity * velocity_scale,
                min_velocity: j.min_velocity.map(|v| v * velocity_scale),
                acceleration: j.acceleration * acceleration_scale,
                min_acceleration: j.min_acceleration.map(|v| v * acceleration_scale),
                jerk: j.jerk * jerk_scale,
                ..j.clone()
            })
            .collect();
        Limits::new(joints)
    }
}

/// [`JointLimits::ratio`] for the limits `(lo, hi)` of one order, read once.
#[inline]
pub(crate) fn ratio_in(lo: f64, hi: f64, value: f64) -> f64 {
    if value >= 0.0 {
        if hi.is_infinite() {
            0.0
        } else {
            value / hi
        }
    } else if lo.is_infinite() {
        0.0
    } else {
        value / lo
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Order;

    #[test]
    fn validation_names_joint_field_value() {
        let mut j = JointLimits::symmetric(1.0, 2.0, 3.0);
        j.acceleration = -2.0;
        let e = Limits::new(vec![JointLimits::symmetric(1.0, 1.0, 1.0), j]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "joint 2 acceleration limit = -2 is not a positive number"
        );
        let mut j = JointLimits::symmetric(1.0, 2.0, 3.0);
        j.velocity = f64::NAN;
        assert!(Limits::new(vec![j]).is_err());
        let mut j = JointLimits::symmetric(1.0, 2.0, 0.0);
        j.name = "elbow".into();
        let e = Limits::new(vec![j]).unwrap_err().to_string();
        assert!(
            e.contains("elbow") && e.contains("jerk") && e.contains("= 0"),
            "{e}"
        );
        let mut j = JointLimits::symmetric(1.0, 2.0, 3.0);
        j.position_min = 1.0;
        j.position_max = 1.0;
        assert!(Limits::new(vec![j]).is_err());
        let mut j = JointLimits::symmetric(1.0, 2.0, 3.0);
        j.min_velocity = Some(0.5);
        assert!(Limits::new(vec![j]).is_err());
        assert!(Limits::new(vec![]).is_err());
        // Unlimited (infinite) maxima are allowed.
        assert!(Limits::uniform(3, f64::INFINITY, 1.0, f64::INFINITY).is_ok());
    }

    #[test]
    fn ratios_use_directional_limits() {
        let mut j = JointLimits::symmetric(2.0, 10.0, 100.0);
        j.min_velocity = Some(-1.0);
        assert_eq!(j.ratio(Order::Velocity, 1.0), 0.5);
        assert_eq!(j.ratio(Order::Velocity, -1.0), 1.0);
        assert_eq!(j.ratio(Order::Acceleration, -5.0), 0.5);
        assert_eq!(j.symmetric_limit(Order::Velocity), 1.0);
        let free = JointLimits::default();
        assert_eq!(free.ratio(Order::Jerk, 1e9), 0.0);
    }

    #[test]
    fn overrides_and_scaling() {
        let l = Limits::uniform(2, 1.0, 2.0, 3.0).unwrap();
        let l2 = l.clone().with_override(Order::Jerk, &[10.0, 20.0]).unwrap();
        assert_eq!(l2.joint(1).jerk, 20.0);
        assert!(l
            .clone()
            .with_override(Order::Jerk, &[1.0, 2.0, 3.0])
            .is_err());
        assert!(l.clone().with_override(Order::Velocity, &[-1.0]).is_err());
        let s = l.scaled(0.5, 0.25, 1.0).unwrap();
        assert_eq!(s.joint(0).velocity, 0.5);
        assert_eq!(s.joint(0).acceleration, 0.5);
        assert!(l.scaled(0.0, 1.0, 1.0).is_err());
    }
}
