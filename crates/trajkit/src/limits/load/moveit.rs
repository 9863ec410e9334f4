//! MoveIt `joint_limits.yaml`, see the [parent module](super).

use super::value::*;
use crate::error::{Error, Result};
use crate::limits::{Given, JointLimits, PartialLimits};
use serde::de::{DeserializeSeed, Deserializer, IgnoredAny, MapAccess, Visitor};
use std::fmt;

// ---------------------------------------------------------------------------------------------
// MoveIt joint_limits.yaml.

/// The limits a MoveIt entry sets (`None`: its `has_…` flag is absent or false).
#[derive(Debug, Clone, Default)]
struct MoveItJoint {
    name: String,
    position: Option<(f64, f64)>,
    velocity: Option<f64>,
    acceleration: Option<f64>,
    jerk: Option<f64>,
    effort: Option<f64>,
}

impl MoveItJoint {
    fn apply(&self, jl: &mut JointLimits, g: &mut Given) {
        if let Some((lo, hi)) = self.position {
            jl.position_min = lo;
            jl.position_max = hi;
            g.position_min = true;
            g.position_max = true;
        }
        if let Some(v) = self.velocity {
            jl.velocity = v;
            jl.min_velocity = None;
            g.velocity = true;
        }
        if let Some(a) = self.acceleration {
            jl.acceleration = a;
            jl.min_acceleration = None;
            g.acceleration = true;
        }
        if let Some(j) = self.jerk {
            jl.jerk = j;
            g.jerk = true;
        }
        if let Some(e) = self.effort {
            jl.effort = Some(e);
        }
    }
}

const MOVEIT_FIELDS: &str = "has_velocity_limits, max_velocity, has_acceleration_limits, \
     max_acceleration, has_jerk_limits, max_jerk, has_position_limits, min_position, \
     max_position, has_effort_limits, max_effort";

const MOVEIT_IGNORED: [&str; 8] = [
    "has_deceleration_limits",
    "max_deceleration",
    "angle_wraparound",
    "has_soft_limits",
    "k_position",
    "k_velocity",
    "soft_lower_limit",
    "soft_upper_limit",
];

struct MoveItJointSeed<'a> {
    name: &'a str,
}

impl<'de> DeserializeSeed<'de> for MoveItJointSeed<'_> {
    type Value = MoveItJoint;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<MoveItJoint, D::Error> {
        d.deserialize_map(self)
    }
}

// Hand-written rather than derived: a derived `Deserialize` (with `serde_path_to_error` for the
// path) does not give the same errors. Its unknown-field message has no closest-name
// suggestion (`deny_unknown_fields`) or silently accepts the key (without it), where MoveIt's
// own extra keys must be accepted and any other refused; its duplicate-field message is
// serde's, not "is given twice"; and each value must be checked while the format still points
// at it (see `FieldSeed`), so that the error carries the value's line — a derived field type
// would need a hand-written `Deserialize` of its own for that. The reading (`read`, per key)
// and the checks across keys (`into_joint`) are separate functions.
impl<'de> Visitor<'de> for MoveItJointSeed<'_> {
    type Value = MoveItJoint;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "joint_limits.{} to be a mapping", self.name)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> std::result::Result<MoveItJoint, A::Error> {
        let mut entries = MoveItEntries::default();
        while let Some(key) = m.next_key::<String>()? {
            entries.read(self.name, key, &mut m)?;
        }
        entries.into_joint(self.name)
    }
}

/// The flags and numbers of one MoveIt entry, as read (each key at most once).
#[derive(Default)]
struct MoveItEntries {
    flags: Vec<(String, bool)>,
    nums: Vec<(String, f64)>,
}

impl MoveItEntries {
    /// Reads the value of `key` of joint `name`, checking it where it is written.
    fn read<'de, A: MapAccess<'de>>(
        &mut self,
        name: &str,
        key: String,
        m: &mut A,
    ) -> std::result::Result<(), A::Error> {
        let field = format!("joint_limits.{name}.{key}");
        if self.flags.iter().any(|(k, _)| *k == key) || self.nums.iter().any(|(k, _)| *k == key) {
            m.next_value::<IgnoredAny>()?;
            return Err(located(&field, "is given twice"));
        }
        match key.as_str() {
            "has_velocity_limits"
            | "has_acceleration_limits"
            | "has_jerk_limits"
            | "has_position_limits"
            | "has_effort_limits" => {
                if let Val::Bool(b) = m.next_value_seed(FieldSeed {
                    field: &field,
                    kind: Kind::Bool,
                })? {
                    self.flags.push((key, b));
                }
            }
            "max_velocity" | "max_acceleration" | "max_jerk" | "min_position" | "max_position"
            | "max_effort" => {
                if let Val::Num(x) = m.next_value_seed(FieldSeed {
                    field: &field,
                    kind: Kind::Number,
                })? {
                    self.nums.push((key, x));
                }
            }
            k if MOVEIT_IGNORED.contains(&k) => {
                m.next_value::<IgnoredAny>()?;
            }
            _ => {
                m.next_value_seed(FieldSeed {
                    field: &field,
                    kind: Kind::Unknown(MOVEIT_FIELDS),
                })?;
            }
        }
        Ok(())
    }

    /// The limits of joint `name` whose `has_…` flag is true, each checked.
    fn into_joint<E: serde::de::Error>(self, name: &str) -> std::result::Result<MoveItJoint, E> {
        let flag = |k: &str| self.flags.iter().any(|(f, b)| f == k && *b);
        let num = |k: &str| -> std::result::Result<f64, E> {
            self.nums
                .iter()
                .find(|(f, _)| f == k)
                .map(|(_, x)| *x)
                .ok_or_else(|| {
                    located(
                        &format!("joint_limits.{name}.{k}"),
                        "is missing (its has_… flag is true)",
                    )
                })
        };
        let positive = |k: &str| -> std::result::Result<f64, E> {
            let x = num(k)?;
            if x > 0.0 && x.is_finite() {
                Ok(x)
            } else {
                Err(located(
                    &format!("joint_limits.{name}.{k}"),
                    format!("{x} is not a positive finite number"),
                ))
            }
        };
        let mut j = MoveItJoint {
            name: name.to_string(),
            ..Default::default()
        };
        if flag("has_velocity_limits") {
            j.velocity = Some(positive("max_velocity")?);
        }
        if flag("has_acceleration_limits") {
            j.acceleration = Some(positive("max_acceleration")?);
        }
        if flag("has_jerk_limits") {
            j.jerk = Some(positive("max_jerk")?);
        }
        if flag("has_effort_limits") {
            j.effort = Some(positive("max_effort")?);
        }
        if flag("has_position_limits") {
            let lo = num("min_position")?;
            let hi = num("max_position")?;
            if !(lo.is_finite() && hi.is_finite() && hi > lo) {
                return Err(located(
                    &format!("joint_limits.{name}.max_position"),
                    format!("{hi} is not a finite number above min_position {lo}"),
                ));
            }
            j.position = Some((lo, hi));
        }
        Ok(j)
    }
}

struct MoveItJointsSeed;

impl<'de> DeserializeSeed<'de> for MoveItJointsSeed {
    type Value = Vec<MoveItJoint>;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<Self::Value, D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for MoveItJointsSeed {
    type Value = Vec<MoveItJoint>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("`joint_limits` to be a mapping from joint name to limits")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> std::result::Result<Self::Value, A::Error> {
        let mut v: Vec<MoveItJoint> = Vec::new();
        while let Some(name) = m.next_key::<String>()? {
            if v.iter().any(|j| j.name == name) {
                m.next_value::<IgnoredAny>()?;
                return Err(located(&format!("joint_limits.{name}"), "is given twice"));
            }
            let j = m.next_value_seed(MoveItJointSeed { name: &name })?;
            v.push(j);
        }
        Ok(v)
    }
}

struct MoveItFileSeed;

impl<'de> DeserializeSeed<'de> for MoveItFileSeed {
    type Value = Vec<MoveItJoint>;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<Self::Value, D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for MoveItFileSeed {
    type Value = Vec<MoveItJoint>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a MoveIt joint limits mapping with a `joint_limits` key")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> std::result::Result<Self::Value, A::Error> {
        let mut joints = None;
        while let Some(key) = m.next_key::<String>()? {
            match key.as_str() {
                "joint_limits" => joints = Some(m.next_value_seed(MoveItJointsSeed)?),
                "default_velocity_scaling_factor" | "default_acceleration_scaling_factor" => {
                    m.next_value_seed(FieldSeed {
                        field: &key,
                        kind: Kind::Number,
                    })?;
                }
                _ => {
                    m.next_value_seed(FieldSeed {
                        field: &key,
                        kind: Kind::Unknown(
                            "joint_limits, default_velocity_scaling_factor, \
                             default_acceleration_scaling_factor",
                        ),
                    })?;
                }
            }
        }
        joints.ok_or_else(|| located("joint_limits", "is missing"))
    }
}

fn parse_moveit(text: &str, source: &str) -> Result<Vec<MoveItJoint>> {
    let de = serde_yaml_ng::Deserializer::from_str(text);
    let joints = MoveItFileSeed
        .deserialize(de)
        .map_err(|e| yaml_error(source, e))?;
    if joints.is_empty() {
        return Err(file_error(source, "joint_limits", "lists no joints"));
    }
    Ok(joints)
}

/// Applies a MoveIt `joint_limits.yaml` to `base`: each joint of the file that `base` has (by
/// name) gets the limits whose `has_…` flag is true (they become given); other limits keep
/// `base`'s values. Joints of the file that `base` does not have are ignored, but a file in
/// which no joint matches is an error. See the module documentation for the keys read.
pub fn apply_moveit_joint_limits(
    base: &PartialLimits,
    text: &str,
    source: &str,
) -> Result<PartialLimits> {
    let file = parse_moveit(text, source)?;
    let mut joints = base.joints().to_vec();
    let mut given = base.given().to_vec();
    let mut matched = 0;
    for mj in &file {
        if let Some(j) = joints.iter().position(|jl| jl.name == mj.name) {
            mj.apply(&mut joints[j], &mut given[j]);
            matched += 1;
        }
    }
    if matched == 0 {
        let file_names: Vec<&str> = file.iter().map(|j| j.name.as_str()).collect();
        let base_names: Vec<&str> = base.joints().iter().map(|j| j.name.as_str()).collect();
        return Err(file_error(
            source,
            "joint_limits",
            format!(
                "no joint of this file ({}) is a joint of the base limits ({})",
                file_names.join(", "),
                base_names.join(", ")
            ),
        ));
    }
    PartialLimits::new(joints, given).map_err(|e| in_file(source, e))
}

/// Builds limits from a MoveIt `joint_limits.yaml` alone. Joints come in `joint_order` when
/// given (every name must be in the file; other joints of the file are left out), else in the
/// file's order. A limit whose `has_…` flag is false or absent is absent.
pub fn moveit_joint_limits_from_str(
    text: &str,
    source: &str,
    joint_order: Option<&[&str]>,
) -> Result<PartialLimits> {
    let file = parse_moveit(text, source)?;
    let make = |mj: &MoveItJoint| {
        let mut jl = JointLimits {
            name: mj.name.clone(),
            ..Default::default()
        };
        let mut g = Given::NONE;
        mj.apply(&mut jl, &mut g);
        (jl, g)
    };
    let (joints, given): (Vec<JointLimits>, Vec<Given>) = match joint_order {
        None => file.iter().map(make).unzip(),
        Some(order) => {
            if order.is_empty() {
                return Err(Error::DimensionMismatch {
                    what: format!("joint order for {source}"),
                    expected: 1,
                    found: 0,
                });
            }
            let mut v = Vec::with_capacity(order.len());
            for name in order {
                let mj = file.iter().find(|j| j.name == *name).ok_or_else(|| {
                    file_error(source, "joint_limits", format!("has no joint '{name}'"))
                })?;
                v.push(make(mj));
            }
            v.into_iter().unzip()
        }
    };
    PartialLimits::new(joints, given).map_err(|e| in_file(source, e))
}
