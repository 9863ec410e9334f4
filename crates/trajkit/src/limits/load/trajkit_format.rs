//! trajkit's own limits format (JSON or YAML), see the [parent module](super).

use super::value::*;
use crate::error::Result;
use crate::limits::{presets, Given, JointLimits, Limits, PartialLimits};
use serde::de::{DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::fmt;

// ---------------------------------------------------------------------------------------------
// trajkit format.

/// One entry of `joints`: only the fields that were written.
#[derive(Debug, Clone, Default)]
struct FileJoint {
    index: usize,
    name: Option<String>,
    position_min: Option<f64>,
    position_max: Option<f64>,
    velocity: Option<f64>,
    acceleration: Option<f64>,
    jerk: Option<f64>,
    min_velocity: Option<Option<f64>>,
    min_acceleration: Option<Option<f64>>,
    effort: Option<Option<f64>>,
}

impl FileJoint {
    fn apply(&self, jl: &mut JointLimits, g: &mut Given) {
        if let Some(n) = &self.name {
            jl.name = n.clone();
        }
        if let Some(x) = self.position_min {
            jl.position_min = x;
            g.position_min = true;
        }
        if let Some(x) = self.position_max {
            jl.position_max = x;
            g.position_max = true;
        }
        if let Some(x) = self.velocity {
            jl.velocity = x;
            g.velocity = true;
        }
        if let Some(x) = self.acceleration {
            jl.acceleration = x;
            g.acceleration = true;
        }
        if let Some(x) = self.jerk {
            jl.jerk = x;
            g.jerk = true;
        }
        if let Some(x) = self.min_velocity {
            jl.min_velocity = x;
        }
        if let Some(x) = self.min_acceleration {
            jl.min_acceleration = x;
        }
        if let Some(x) = self.effort {
            jl.effort = x;
        }
    }
}

const JOINT_FIELDS: &str = "name, position, position_min, position_max, velocity, \
                            acceleration, jerk, min_velocity, min_acceleration, effort";

struct JointSeed {
    index: usize,
}

impl<'de> DeserializeSeed<'de> for JointSeed {
    type Value = FileJoint;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<FileJoint, D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for JointSeed {
    type Value = FileJoint;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "joints[{}] to be a mapping of limits", self.index)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> std::result::Result<FileJoint, A::Error> {
        let i = self.index;
        let mut j = FileJoint {
            index: i,
            ..Default::default()
        };
        let mut seen: Vec<String> = Vec::new();
        let mut range_given = false;
        while let Some(key) = m.next_key::<String>()? {
            let field = format!("joints[{i}].{key}");
            if seen.contains(&key) {
                m.next_value::<IgnoredAny>()?;
                return Err(located(&field, "is given twice"));
            }
            seen.push(key.clone());
            let kind = match key.as_str() {
                "name" => Kind::Text,
                "position" => Kind::Range,
                "position_min" => Kind::Bound { upper: false },
                "position_max" => Kind::Bound { upper: true },
                "velocity" | "acceleration" | "jerk" => Kind::Max,
                "min_velocity" | "min_acceleration" => Kind::Min,
                "effort" => Kind::Effort,
                _ => {
                    m.next_value_seed(FieldSeed {
                        field: &field,
                        kind: Kind::Unknown(JOINT_FIELDS),
                    })?;
                    continue;
                }
            };
            let v = m.next_value_seed(FieldSeed {
                field: &field,
                kind,
            })?;
            match (key.as_str(), v) {
                ("name", Val::Text(s)) => j.name = Some(s),
                ("position", Val::Range(lo, hi)) => {
                    range_given = true;
                    j.position_min = Some(lo);
                    j.position_max = Some(hi);
                }
                ("position_min", Val::Num(x)) => j.position_min = Some(x),
                ("position_max", Val::Num(x)) => j.position_max = Some(x),
                ("velocity", Val::Num(x)) => j.velocity = Some(x),
                ("acceleration", Val::Num(x)) => j.acceleration = Some(x),
                ("jerk", Val::Num(x)) => j.jerk = Some(x),
                ("min_velocity", Val::Opt(x)) => j.min_velocity = Some(x),
                ("min_acceleration", Val::Opt(x)) => j.min_acceleration = Some(x),
                ("effort", Val::Opt(x)) => j.effort = Some(x),
                _ => return Err(located(&field, "has a value of the wrong kind")),
            }
        }
        if range_given
            && (seen
                .iter()
                .any(|k| k == "position_min" || k == "position_max"))
        {
            return Err(located(
                &format!("joints[{i}].position"),
                "is given together with position_min/position_max; use one or the other",
            ));
        }
        if let (Some(lo), Some(hi)) = (j.position_min, j.position_max) {
            if hi <= lo {
                return Err(located(
                    &format!("joints[{i}].position_max"),
                    format!("{hi} is not above position_min {lo}"),
                ));
            }
        }
        Ok(j)
    }
}

struct JointsSeed;

impl<'de> DeserializeSeed<'de> for JointsSeed {
    type Value = Vec<FileJoint>;
    fn deserialize<D: Deserializer<'de>>(
        self,
        d: D,
    ) -> std::result::Result<Vec<FileJoint>, D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for JointsSeed {
    type Value = Vec<FileJoint>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("`joints` to be a list")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut s: A) -> std::result::Result<Self::Value, A::Error> {
        let mut v = Vec::new();
        while let Some(j) = s.next_element_seed(JointSeed { index: v.len() })? {
            v.push(j);
        }
        Ok(v)
    }
}

/// The whole trajkit-format file.
#[derive(Debug, Default)]
struct LimitsFile {
    preset: Option<(String, Limits)>,
    joints: Option<Vec<FileJoint>>,
}

struct LimitsFileSeed;

impl<'de> DeserializeSeed<'de> for LimitsFileSeed {
    type Value = LimitsFile;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<LimitsFile, D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for LimitsFileSeed {
    type Value = LimitsFile;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a limits mapping with `joints` and/or `preset`")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> std::result::Result<LimitsFile, A::Error> {
        let mut file = LimitsFile::default();
        while let Some(key) = m.next_key::<String>()? {
            match key.as_str() {
                "preset" => {
                    let name = match m.next_value_seed(FieldSeed {
                        field: "preset",
                        kind: Kind::Preset,
                    })? {
                        Val::Text(s) => s,
                        _ => String::new(),
                    };
                    match presets::by_name(&name) {
                        Ok(l) => file.preset = Some((name, l)),
                        Err(e) => return Err(located("preset", e)),
                    }
                }
                "joints" => file.joints = Some(m.next_value_seed(JointsSeed)?),
                _ => {
                    m.next_value_seed(FieldSeed {
                        field: &key,
                        kind: Kind::Unknown("preset, joints"),
                    })?;
                }
            }
        }
        Ok(file)
    }
}

fn build_from_file(file: LimitsFile, source: &str) -> Result<PartialLimits> {
    let entries = file.joints.unwrap_or_default();
    let (joints, given) = match file.preset {
        None => {
            if entries.is_empty() {
                return Err(file_error(
                    source,
                    "joints",
                    "no joints given (list them under `joints`, or name a `preset`)",
                ));
            }
            entries
                .iter()
                .map(|e| {
                    let mut jl = JointLimits::default();
                    let mut g = Given::NONE;
                    e.apply(&mut jl, &mut g);
                    (jl, g)
                })
                .unzip()
        }
        Some((preset_name, base)) => {
            let mut joints = base.joints().to_vec();
            let mut given = vec![Given::ALL; joints.len()];
            let mut taken = vec![None::<usize>; joints.len()];
            for e in &entries {
                let target = match &e.name {
                    Some(n) => joints.iter().position(|jl| &jl.name == n).ok_or_else(|| {
                        let known: Vec<&str> = joints.iter().map(|j| j.name.as_str()).collect();
                        file_error(
                            source,
                            &format!("joints[{}].name", e.index),
                            format!(
                                "'{n}' is not a joint of preset {preset_name} (joints: {})",
                                known.join(", ")
                            ),
                        )
                    })?,
                    None if e.index < joints.len() => e.index,
                    None => {
                        return Err(file_error(
                            source,
                            &format!("joints[{}]", e.index),
                            format!(
                                "preset {preset_name} has only {} joints; name the joint or \
                                 remove the entry",
                                joints.len()
                            ),
                        ))
                    }
                };
                if let Some(prev) = taken[target] {
                    return Err(file_error(
                        source,
                        &format!("joints[{}]", e.index),
                        format!(
                            "changes joint {} ({}) already changed by joints[{prev}]",
                            target + 1,
                            joints[target].name
                        ),
                    ));
                }
                taken[target] = Some(e.index);
                e.apply(&mut joints[target], &mut given[target]);
            }
            (joints, given)
        }
    };
    PartialLimits::new(joints, given).map_err(|e| in_file(source, e))
}

/// Reads limits in trajkit's format from JSON text; `source` names the file in errors.
pub fn from_json_str(text: &str, source: &str) -> Result<PartialLimits> {
    let mut de = serde_json::Deserializer::from_str(text);
    let file = LimitsFileSeed
        .deserialize(&mut de)
        .and_then(|f| de.end().map(|()| f))
        .map_err(|e| json_error(source, e))?;
    build_from_file(file, source)
}

/// Reads limits in trajkit's format from YAML text; `source` names the file in errors.
pub fn from_yaml_str(text: &str, source: &str) -> Result<PartialLimits> {
    let de = serde_yaml_ng::Deserializer::from_str(text);
    let file = LimitsFileSeed
        .deserialize(de)
        .map_err(|e| yaml_error(source, e))?;
    build_from_file(file, source)
}
