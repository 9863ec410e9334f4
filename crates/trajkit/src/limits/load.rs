//! Loading limits from files: trajkit's own JSON/YAML format, MoveIt `joint_limits.yaml`, and
//! URDF `<limit>` tags.
//!
//! Every loader returns validated [`Limits`]. A bad file gives an [`Error::Parse`] whose
//! location names the file, the line when the format tells it, and the field (for example
//! `joints[2].velocity`), and whose message quotes the offending value. Unknown fields are
//! errors, so a misspelt key never goes unnoticed.
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
//! Without `preset`, the listed joints are the robot, and an absent limit is unlimited. With
//! `preset`, the listed fields override the preset's: a joint entry with a `name` updates the
//! preset joint of that name, one without a name updates the joint at the same index; absent
//! fields keep the preset's value. In both cases `null` means unlimited (for `velocity`,
//! `acceleration`, `jerk`), unbounded (for the ends of `position`), "the negated maximum" (for
//! `min_velocity`, `min_acceleration`) and unknown (for `effort`). YAML's `.inf` is accepted
//! as unlimited too; NaN and strings are refused.
//!
//! # MoveIt `joint_limits.yaml`
//! The `joint_limits` mapping (joint name → `has_velocity_limits`, `max_velocity`,
//! `has_acceleration_limits`, `max_acceleration`, `has_jerk_limits`, `max_jerk`,
//! `has_position_limits`, `min_position`, `max_position`, `has_effort_limits`, `max_effort`)
//! is read as MoveIt reads it: a value applies only when its `has_…` flag is `true`, and then it
//! must be present and valid. The keys `has_deceleration_limits`, `max_deceleration`,
//! `angle_wraparound`, `has_soft_limits`, `k_position`, `k_velocity`, `soft_lower_limit` and
//! `soft_upper_limit` are accepted and ignored (trajkit's model has no deceleration or soft
//! limits). The top-level `default_velocity_scaling_factor` and
//! `default_acceleration_scaling_factor` are checked to be numbers and **ignored**: they are
//! MoveIt's default request scaling, not robot limits; scale limits explicitly with
//! [`Limits::scaled`] instead. A MoveIt maximum replaces the base joint's limit in both
//! directions (any direction-dependent minimum is dropped).
//!
//! # URDF
//! Every `<joint>` child of `<robot>` of type `revolute`, `prismatic` or `continuous`, in
//! document order, except joints with a `<mimic>` element (they follow another joint and are
//! not commanded). Its `<limit>` gives the position range (`lower`, `upper`; none for
//! `continuous`, an absent attribute leaves that side unbounded), `velocity` (absent:
//! unlimited) and `effort` (absent or `0`, which URDF exporters write for "unknown": no effort
//! limit). URDF has no acceleration or jerk limits: they are unlimited; complete them with
//! [`fill_missing`] from a preset or another file.
//!
//! ```
//! use trajkit::limits::load;
//! let text = r#"{"preset": "panda", "joints": [{"name": "panda_joint2", "velocity": 1.0}]}"#;
//! let limits = load::from_json_str(text, "limits.json")?;
//! assert_eq!(limits.joint(1).velocity, 1.0);
//! assert_eq!(limits.joint(0).velocity, 2.175);
//! # Ok::<(), trajkit::Error>(())
//! ```

use super::{presets, JointLimits, Limits};
use crate::error::{Error, Location, Result};
use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::fmt;
use std::path::Path;

// ---------------------------------------------------------------------------------------------
// Errors raised while deserializing.
//
// A visitor that finds a bad value raises a serde error whose text carries the field between
// two markers; the format's own error then adds the line. `parse_error` takes both apart again.

const MARK: char = '\u{1e}';
const SEP: char = '\u{1f}';

fn located<E: de::Error>(field: &str, message: impl fmt::Display) -> E {
    E::custom(format!("{MARK}{field}{SEP}{message}{MARK}"))
}

/// Builds an [`Error::Parse`] from the text of a serde error and the line the format reported.
fn parse_error(source: &str, line: usize, text: &str) -> Error {
    let (field, message) = if let Some((_, rest)) = text.split_once(MARK) {
        let inner = rest.split_once(MARK).map_or(rest, |(a, _)| a);
        match inner.split_once(SEP) {
            Some((f, m)) => (f.to_string(), m.to_string()),
            None => (String::new(), inner.to_string()),
        }
    } else {
        let text = strip_position(text);
        let text = text.as_str();
        // serde_yaml_ng prefixes a path such as `joints[1].velocity: ` to its own messages.
        match text.split_once(": ") {
            Some((p, m))
                if !p.is_empty()
                    && p.chars()
                        .all(|c| c.is_ascii_alphanumeric() || "_.[]".contains(c)) =>
            {
                (p.to_string(), m.to_string())
            }
            _ => (String::new(), text.to_string()),
        }
    };
    Error::Parse {
        location: Location {
            source: source.to_string(),
            line,
            field,
        },
        message,
    }
}

/// Removes ` at line N column M` (reported separately as the line) from a message.
fn strip_position(text: &str) -> String {
    const AT: &str = " at line ";
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find(AT) {
        out.push_str(&rest[..i]);
        let tail = &rest[i + AT.len()..];
        let digits = |s: &str| s.bytes().take_while(u8::is_ascii_digit).count();
        let n = digits(tail);
        let skip = if n > 0 && tail[n..].starts_with(" column ") {
            let m = digits(&tail[n + " column ".len()..]);
            (m > 0).then_some(n + " column ".len() + m)
        } else {
            None
        };
        match skip {
            Some(k) => rest = &tail[k..],
            None => {
                out.push_str(AT);
                rest = tail;
            }
        }
    }
    out.push_str(rest);
    out
}

fn json_error(source: &str, e: serde_json::Error) -> Error {
    parse_error(source, e.line(), &e.to_string())
}

fn yaml_error(source: &str, e: serde_yaml_ng::Error) -> Error {
    let line = e.location().map_or(0, |l| l.line());
    parse_error(source, line, &e.to_string())
}

/// Wraps an error found after parsing (no line known) so that it names the file.
fn in_file(source: &str, e: Error) -> Error {
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

fn file_error(source: &str, field: &str, message: impl Into<String>) -> Error {
    Error::Parse {
        location: Location {
            source: source.to_string(),
            line: 0,
            field: field.to_string(),
        },
        message: message.into(),
    }
}

// ---------------------------------------------------------------------------------------------
// A scalar (or small list) as written in the file, kept for validation and quoting.

#[derive(Debug, Clone, PartialEq)]
enum Raw {
    Null,
    Bool(bool),
    Num(f64),
    Str(String),
    Seq(Vec<Raw>),
    Map,
}

impl fmt::Display for Raw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Raw::Null => f.write_str("null"),
            Raw::Bool(b) => write!(f, "{b}"),
            Raw::Num(x) => write!(f, "{x}"),
            Raw::Str(s) => write!(f, "'{s}'"),
            Raw::Seq(v) => {
                f.write_str("[")?;
                for (i, x) in v.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{x}")?;
                }
                f.write_str("]")
            }
            Raw::Map => f.write_str("a mapping"),
        }
    }
}

impl<'de> de::Deserialize<'de> for Raw {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Raw;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a value")
            }
            fn visit_bool<E: de::Error>(self, v: bool) -> std::result::Result<Raw, E> {
                Ok(Raw::Bool(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> std::result::Result<Raw, E> {
                Ok(Raw::Num(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> std::result::Result<Raw, E> {
                Ok(Raw::Num(v as f64))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> std::result::Result<Raw, E> {
                Ok(Raw::Num(v))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> std::result::Result<Raw, E> {
                Ok(Raw::Str(v.to_string()))
            }
            fn visit_unit<E: de::Error>(self) -> std::result::Result<Raw, E> {
                Ok(Raw::Null)
            }
            fn visit_none<E: de::Error>(self) -> std::result::Result<Raw, E> {
                Ok(Raw::Null)
            }
            fn visit_some<D: Deserializer<'de>>(self, d: D) -> std::result::Result<Raw, D::Error> {
                Raw::deserialize(d)
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut s: A) -> std::result::Result<Raw, A::Error> {
                let mut v = Vec::new();
                while let Some(x) = s.next_element::<Raw>()? {
                    v.push(x);
                }
                Ok(Raw::Seq(v))
            }
            fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> std::result::Result<Raw, A::Error> {
                while m.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
                Ok(Raw::Map)
            }
        }
        d.deserialize_any(V)
    }
}

/// What a field accepts.
#[derive(Debug, Clone, Copy)]
enum Kind {
    /// A maximum: positive number or `+inf`; `null` is unlimited (`+inf`).
    Max,
    /// A directional minimum: negative number; `null` is "none".
    Min,
    /// An effort limit: positive finite; `null` is "none".
    Effort,
    /// One end of a position range: any non-NaN number; `null` is unbounded.
    Bound { upper: bool },
    /// Any number (NaN refused); `null` refused.
    Number,
    /// A boolean.
    Bool,
    /// A string.
    Text,
    /// A two-element position range.
    Range,
    /// A robot preset name.
    Preset,
    /// A key that is not allowed here; the text lists the allowed keys.
    Unknown(&'static str),
}

/// A checked field value.
#[derive(Debug, Clone, PartialEq)]
enum Val {
    Num(f64),
    Opt(Option<f64>),
    Bool(bool),
    Text(String),
    Range(f64, f64),
}

fn number(raw: &Raw) -> std::result::Result<Option<f64>, String> {
    match raw {
        Raw::Null => Ok(None),
        Raw::Num(x) if x.is_nan() => Err(format!("{x} is not a number")),
        Raw::Num(x) => Ok(Some(*x)),
        other => Err(format!("{other} is not a number")),
    }
}

fn check(kind: Kind, raw: &Raw) -> std::result::Result<Val, String> {
    match kind {
        Kind::Max => match number(raw)? {
            None => Ok(Val::Num(f64::INFINITY)),
            Some(x) if x > 0.0 => Ok(Val::Num(x)),
            Some(x) => Err(format!("{x} is not a positive number")),
        },
        Kind::Min => match number(raw)? {
            None => Ok(Val::Opt(None)),
            Some(x) if x < 0.0 => Ok(Val::Opt(Some(x))),
            Some(x) => Err(format!("{x} is not a negative number")),
        },
        Kind::Effort => match number(raw)? {
            None => Ok(Val::Opt(None)),
            Some(x) if x > 0.0 && x.is_finite() => Ok(Val::Opt(Some(x))),
            Some(x) => Err(format!("{x} is not a positive finite number")),
        },
        Kind::Bound { upper } => match number(raw)? {
            None => Ok(Val::Num(if upper {
                f64::INFINITY
            } else {
                f64::NEG_INFINITY
            })),
            Some(x) if (upper && x == f64::NEG_INFINITY) || (!upper && x == f64::INFINITY) => {
                Err(format!("{x} leaves no room for the position"))
            }
            Some(x) => Ok(Val::Num(x)),
        },
        Kind::Number => match number(raw)? {
            Some(x) => Ok(Val::Num(x)),
            None => Err("null is not a number".into()),
        },
        Kind::Bool => match raw {
            Raw::Bool(b) => Ok(Val::Bool(*b)),
            other => Err(format!("{other} is not true or false")),
        },
        Kind::Text => match raw {
            Raw::Str(s) => Ok(Val::Text(s.clone())),
            other => Err(format!("{other} is not a string")),
        },
        Kind::Range => match raw {
            Raw::Seq(v) if v.len() == 2 => {
                let lo = match check(Kind::Bound { upper: false }, &v[0]) {
                    Ok(Val::Num(x)) => x,
                    Ok(_) => f64::NEG_INFINITY,
                    Err(m) => return Err(format!("lower end {m}")),
                };
                let hi = match check(Kind::Bound { upper: true }, &v[1]) {
                    Ok(Val::Num(x)) => x,
                    Ok(_) => f64::INFINITY,
                    Err(m) => return Err(format!("upper end {m}")),
                };
                if hi <= lo {
                    return Err(format!("{raw}: the upper end is not above the lower end"));
                }
                Ok(Val::Range(lo, hi))
            }
            other => Err(format!("{other} is not a list [lower, upper]")),
        },
        Kind::Preset => match raw {
            Raw::Str(s) => presets::by_name(s)
                .map(|_| Val::Text(s.clone()))
                .map_err(|e| e.to_string()),
            other => Err(format!("{other} is not a preset name")),
        },
        Kind::Unknown(expected) => Err(format!("unknown field (expected one of: {expected})")),
    }
}

/// Deserializes one field value and checks it inside the format's deserializer, so that an
/// error carries the line of the value.
struct FieldSeed<'a> {
    field: &'a str,
    kind: Kind,
}

impl FieldSeed<'_> {
    fn finish<E: de::Error>(self, raw: Raw) -> std::result::Result<Val, E> {
        check(self.kind, &raw).map_err(|m| located(self.field, m))
    }
}

impl<'de> DeserializeSeed<'de> for FieldSeed<'_> {
    type Value = Val;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> std::result::Result<Val, D::Error> {
        d.deserialize_any(self)
    }
}

// The check runs inside the visitor: formats attach the value's own position to errors raised
// there (after the visitor returns, some report the enclosing mapping's position instead).
impl<'de> Visitor<'de> for FieldSeed<'_> {
    type Value = Val;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a value for {}", self.field)
    }
    fn visit_bool<E: de::Error>(self, v: bool) -> std::result::Result<Val, E> {
        self.finish(Raw::Bool(v))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> std::result::Result<Val, E> {
        self.finish(Raw::Num(v as f64))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> std::result::Result<Val, E> {
        self.finish(Raw::Num(v as f64))
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> std::result::Result<Val, E> {
        self.finish(Raw::Num(v))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> std::result::Result<Val, E> {
        self.finish(Raw::Str(v.to_string()))
    }
    fn visit_unit<E: de::Error>(self) -> std::result::Result<Val, E> {
        self.finish(Raw::Null)
    }
    fn visit_none<E: de::Error>(self) -> std::result::Result<Val, E> {
        self.finish(Raw::Null)
    }
    fn visit_some<D: Deserializer<'de>>(self, d: D) -> std::result::Result<Val, D::Error> {
        d.deserialize_any(self)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut s: A) -> std::result::Result<Val, A::Error> {
        let mut v = Vec::new();
        while let Some(x) = s.next_element::<Raw>()? {
            v.push(x);
        }
        self.finish(Raw::Seq(v))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> std::result::Result<Val, A::Error> {
        while m.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
        self.finish(Raw::Map)
    }
}

use serde::Deserialize as _;

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
    fn apply(&self, jl: &mut JointLimits) {
        if let Some(n) = &self.name {
            jl.name = n.clone();
        }
        if let Some(x) = self.position_min {
            jl.position_min = x;
        }
        if let Some(x) = self.position_max {
            jl.position_max = x;
        }
        if let Some(x) = self.velocity {
            jl.velocity = x;
        }
        if let Some(x) = self.acceleration {
            jl.acceleration = x;
        }
        if let Some(x) = self.jerk {
            jl.jerk = x;
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

fn build_from_file(file: LimitsFile, source: &str) -> Result<Limits> {
    let entries = file.joints.unwrap_or_default();
    let joints = match file.preset {
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
                    e.apply(&mut jl);
                    jl
                })
                .collect()
        }
        Some((preset_name, base)) => {
            let mut joints = base.joints().to_vec();
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
                e.apply(&mut joints[target]);
            }
            joints
        }
    };
    Limits::new(joints).map_err(|e| in_file(source, e))
}

/// Reads limits in trajkit's format from JSON text; `source` names the file in errors.
pub fn from_json_str(text: &str, source: &str) -> Result<Limits> {
    let mut de = serde_json::Deserializer::from_str(text);
    let file = LimitsFileSeed
        .deserialize(&mut de)
        .and_then(|f| de.end().map(|()| f))
        .map_err(|e| json_error(source, e))?;
    build_from_file(file, source)
}

/// Reads limits in trajkit's format from YAML text; `source` names the file in errors.
pub fn from_yaml_str(text: &str, source: &str) -> Result<Limits> {
    let de = serde_yaml_ng::Deserializer::from_str(text);
    let file = LimitsFileSeed
        .deserialize(de)
        .map_err(|e| yaml_error(source, e))?;
    build_from_file(file, source)
}

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
    fn apply(&self, jl: &mut JointLimits) {
        if let Some((lo, hi)) = self.position {
            jl.position_min = lo;
            jl.position_max = hi;
        }
        if let Some(v) = self.velocity {
            jl.velocity = v;
            jl.min_velocity = None;
        }
        if let Some(a) = self.acceleration {
            jl.acceleration = a;
            jl.min_acceleration = None;
        }
        if let Some(j) = self.jerk {
            jl.jerk = j;
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

impl<'de> Visitor<'de> for MoveItJointSeed<'_> {
    type Value = MoveItJoint;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "joint_limits.{} to be a mapping", self.name)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> std::result::Result<MoveItJoint, A::Error> {
        let name = self.name;
        let mut flags: Vec<(String, bool)> = Vec::new();
        let mut nums: Vec<(String, f64)> = Vec::new();
        while let Some(key) = m.next_key::<String>()? {
            let field = format!("joint_limits.{name}.{key}");
            if flags.iter().any(|(k, _)| *k == key) || nums.iter().any(|(k, _)| *k == key) {
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
                        flags.push((key, b));
                    }
                }
                "max_velocity" | "max_acceleration" | "max_jerk" | "min_position"
                | "max_position" | "max_effort" => {
                    if let Val::Num(x) = m.next_value_seed(FieldSeed {
                        field: &field,
                        kind: Kind::Number,
                    })? {
                        nums.push((key, x));
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
        }
        let flag = |k: &str| flags.iter().any(|(f, b)| f == k && *b);
        let num = |k: &str| -> std::result::Result<f64, A::Error> {
            nums.iter()
                .find(|(f, _)| f == k)
                .map(|(_, x)| *x)
                .ok_or_else(|| {
                    located(
                        &format!("joint_limits.{name}.{k}"),
                        "is missing (its has_… flag is true)",
                    )
                })
        };
        let positive = |k: &str| -> std::result::Result<f64, A::Error> {
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
/// name) gets the limits whose `has_…` flag is true; other limits keep `base`'s values. Joints
/// of the file that `base` does not have are ignored, but a file in which no joint matches is
/// an error. See the module documentation for the keys read.
pub fn apply_moveit_joint_limits(base: &Limits, text: &str, source: &str) -> Result<Limits> {
    let file = parse_moveit(text, source)?;
    let mut joints = base.joints().to_vec();
    let mut matched = 0;
    for mj in &file {
        if let Some(jl) = joints.iter_mut().find(|jl| jl.name == mj.name) {
            mj.apply(jl);
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
    Limits::new(joints).map_err(|e| in_file(source, e))
}

/// Builds limits from a MoveIt `joint_limits.yaml` alone. Joints come in `joint_order` when
/// given (every name must be in the file; other joints of the file are left out), else in the
/// file's order. A limit whose `has_…` flag is false or absent is unlimited.
pub fn moveit_joint_limits_from_str(
    text: &str,
    source: &str,
    joint_order: Option<&[&str]>,
) -> Result<Limits> {
    let file = parse_moveit(text, source)?;
    let make = |mj: &MoveItJoint| {
        let mut jl = JointLimits {
            name: mj.name.clone(),
            ..Default::default()
        };
        mj.apply(&mut jl);
        jl
    };
    let joints: Vec<JointLimits> = match joint_order {
        None => file.iter().map(make).collect(),
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
            v
        }
    };
    Limits::new(joints).map_err(|e| in_file(source, e))
}

// ---------------------------------------------------------------------------------------------
// URDF.

pub(crate) fn line_of(doc: &roxmltree::Document<'_>, pos: usize) -> usize {
    doc.text_pos_at(pos).row as usize
}

/// Reads a numeric attribute of `<limit>`; `None` when absent.
fn urdf_attr(
    doc: &roxmltree::Document<'_>,
    node: roxmltree::Node<'_, '_>,
    attr: &str,
    joint: &str,
    source: &str,
) -> Result<Option<(f64, usize)>> {
    let Some(a) = node.attribute_node(attr) else {
        return Ok(None);
    };
    let line = line_of(doc, a.range_value().start);
    let raw = a.value();
    let err = |message: String| Error::Parse {
        location: Location {
            source: source.to_string(),
            line,
            field: format!("joint '{joint}' <limit {attr}>"),
        },
        message,
    };
    match raw.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(Some((x, line))),
        Ok(_) => Err(err(format!("'{raw}' is not a finite number"))),
        Err(_) => Err(err(format!("'{raw}' is not a number"))),
    }
}

/// Reads the limits of the movable joints of a URDF (see the module documentation).
pub fn from_urdf_str(text: &str, source: &str) -> Result<Limits> {
    let doc = roxmltree::Document::parse(text).map_err(|e| Error::Parse {
        location: Location {
            source: source.to_string(),
            line: e.pos().row as usize,
            field: String::new(),
        },
        message: format!("not well-formed XML: {e}"),
    })?;
    let root = doc.root_element();
    let at = |node: roxmltree::Node<'_, '_>, field: String, message: String| Error::Parse {
        location: Location {
            source: source.to_string(),
            line: line_of(&doc, node.range().start),
            field,
        },
        message,
    };
    if root.tag_name().name() != "robot" {
        return Err(at(
            root,
            String::new(),
            format!(
                "the root element is <{}>, a URDF's is <robot>",
                root.tag_name().name()
            ),
        ));
    }
    let mut joints: Vec<JointLimits> = Vec::new();
    for node in root
        .children()
        .filter(|n| n.is_element() && n.tag_name().name() == "joint")
    {
        let Some(name) = node.attribute("name") else {
            return Err(at(
                node,
                "<joint name>".into(),
                "the joint has no name attribute".into(),
            ));
        };
        let kind = node.attribute("type").unwrap_or("");
        let continuous = match kind {
            "revolute" | "prismatic" => false,
            "continuous" => true,
            "fixed" | "floating" | "planar" => continue,
            other => {
                return Err(at(
                    node,
                    format!("joint '{name}' type"),
                    format!(
                        "'{other}' is not a URDF joint type (revolute, continuous, prismatic, \
                         fixed, floating, planar)"
                    ),
                ))
            }
        };
        let element = |tag: &str| {
            node.children()
                .find(|c| c.is_element() && c.tag_name().name() == tag)
        };
        if element("mimic").is_some() {
            continue;
        }
        if joints.iter().any(|j| j.name == name) {
            return Err(at(
                node,
                format!("joint '{name}'"),
                "a joint of this name appears earlier in the file".into(),
            ));
        }
        let mut jl = JointLimits {
            name: name.to_string(),
            ..Default::default()
        };
        match element("limit") {
            None if !continuous => {
                return Err(at(
                    node,
                    format!("joint '{name}' <limit>"),
                    format!("a {kind} joint needs a <limit> element"),
                ))
            }
            None => {}
            Some(limit) => {
                let field = |attr: &str| format!("joint '{name}' <limit {attr}>");
                let bad = |line: usize, attr: &str, message: String| Error::Parse {
                    location: Location {
                        source: source.to_string(),
                        line,
                        field: field(attr),
                    },
                    message,
                };
                if let Some((v, line)) = urdf_attr(&doc, limit, "velocity", name, source)? {
                    if v <= 0.0 {
                        return Err(bad(
                            line,
                            "velocity",
                            format!("{v} is not a positive number"),
                        ));
                    }
                    jl.velocity = v;
                }
                if let Some((e, line)) = urdf_attr(&doc, limit, "effort", name, source)? {
                    if e < 0.0 {
                        return Err(bad(line, "effort", format!("{e} is negative")));
                    }
                    jl.effort = (e > 0.0).then_some(e);
                }
                if !continuous {
                    let lower = urdf_attr(&doc, limit, "lower", name, source)?;
                    let upper = urdf_attr(&doc, limit, "upper", name, source)?;
                    if let Some((lo, _)) = lower {
                        jl.position_min = lo;
                    }
                    if let Some((hi, line)) = upper {
                        if hi <= jl.position_min {
                            return Err(bad(
                                line,
                                "upper",
                                format!("{hi} is not above lower = {}", jl.position_min),
                            ));
                        }
                        jl.position_max = hi;
                    }
                }
            }
        }
        joints.push(jl);
    }
    if joints.is_empty() {
        let hint = if text.contains("xacro") {
            " (it looks like an unexpanded xacro file: run xacro on it first)"
        } else {
            ""
        };
        return Err(file_error(
            source,
            "",
            format!(
                "the URDF has no movable joint (revolute, prismatic or continuous, not mimic){hint}"
            ),
        ));
    }
    Limits::new(joints).map_err(|e| in_file(source, e))
}

// ---------------------------------------------------------------------------------------------
// Combining and dispatch.

/// Completes `limits` from `from`, joint by joint (same index): an unlimited (infinite)
/// acceleration takes `from`'s acceleration and its directional minimum, an unlimited jerk
/// takes `from`'s jerk. Other fields are kept. Used to complete URDF limits from a preset.
///
/// Errors: [`Error::DimensionMismatch`] when the joint counts differ.
pub fn fill_missing(limits: &Limits, from: &Limits) -> Result<Limits> {
    from.expect_dof(limits.dof(), "completing missing limits")?;
    let joints = limits
        .joints()
        .iter()
        .zip(from.joints())
        .map(|(a, b)| {
            let mut j = a.clone();
            if j.acceleration.is_infinite() {
                j.acceleration = b.acceleration;
                j.min_acceleration = b.min_acceleration;
            }
            if j.jerk.is_infinite() {
                j.jerk = b.jerk;
            }
            j
        })
        .collect();
    Limits::new(joints)
}

/// True when YAML text is a mapping with a top-level `joint_limits` key (MoveIt's format).
fn is_moveit_yaml(text: &str, source: &str) -> Result<bool> {
    let v: serde_yaml_ng::Value =
        serde_yaml_ng::from_str(text).map_err(|e| yaml_error(source, e))?;
    Ok(v.as_mapping()
        .is_some_and(|m| m.contains_key(serde_yaml_ng::Value::from("joint_limits"))))
}

/// Loads a limits file, choosing the format by extension: `.json` (trajkit format), `.yaml` /
/// `.yml` (MoveIt `joint_limits.yaml` when it has a top-level `joint_limits` key, else trajkit
/// format), `.urdf` / `.xml` (URDF).
///
/// Errors: [`Error::Io`] naming the path when it cannot be read; [`Error::Parse`] for an
/// unknown extension or bad content.
pub fn from_file(path: &Path) -> Result<Limits> {
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
    let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
        path: source.clone(),
        message: e.to_string(),
    })?;
    match ext.as_str() {
        "json" => from_json_str(&text, &source),
        "yaml" | "yml" => {
            if is_moveit_yaml(&text, &source)? {
                moveit_joint_limits_from_str(&text, &source, None)
            } else {
                from_yaml_str(&text, &source)
            }
        }
        _ => from_urdf_str(&text, &source),
    }
}

/// Limits from a command-line style specification: a robot preset name (see
/// [`presets::NAMES`]) or the path of a limits file (see [`from_file`]).
///
/// A specification that is neither a preset nor an existing file gives
/// [`Error::UnknownPreset`] when it looks like a name (no extension, no path separator) and
/// [`Error::Io`] otherwise.
pub fn from_spec(spec: &str) -> Result<Limits> {
    if let Ok(l) = presets::by_name(spec) {
        return Ok(l);
    }
    let path = Path::new(spec);
    let looks_like_name = !spec.contains(['/', '\\', '.']);
    if looks_like_name && !path.exists() {
        return presets::by_name(spec);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_err(e: Error) -> (String, usize, String, String) {
        let shown = e.to_string();
        match e {
            Error::Parse { location, message } => {
                (location.source, location.line, location.field, message)
            }
            other => panic!("expected a parse error, got {other:?} ({shown})"),
        }
    }

    const YAML: &str = "\
# Panda-like limits
joints:
  - name: a1
    position: [-2.8973, 2.8973]
    velocity: 2.175
    acceleration: 15
    jerk: 7500
    min_velocity: -1.0
    effort: 87
  - name: a2
    position_min: -1.7628
    position_max: 1.7628
    velocity: 2.175
    acceleration: 7.5
    jerk: 3750
  - name: a3
    velocity: null
    acceleration: .inf
";

    #[test]
    fn yaml_round_trip() {
        let l = from_yaml_str(YAML, "robot.yaml").unwrap();
        assert_eq!(l.dof(), 3);
        let j = l.joint(0);
        assert_eq!(j.name, "a1");
        assert_eq!((j.position_min, j.position_max), (-2.8973, 2.8973));
        assert_eq!((j.velocity, j.acceleration, j.jerk), (2.175, 15.0, 7500.0));
        assert_eq!(j.min_velocity, Some(-1.0));
        assert_eq!(j.min_acceleration, None);
        assert_eq!(j.effort, Some(87.0));
        assert_eq!(l.joint(1).position_max, 1.7628);
        let j = l.joint(2);
        assert!(j.velocity.is_infinite() && j.acceleration.is_infinite() && j.jerk.is_infinite());
        assert!(j.position_min.is_infinite());
    }

    #[test]
    fn json_round_trip_and_preset_override() {
        let json = serde_json::json!({
            "joints": [
                {"name": "x", "position": [-1, 1], "velocity": 1, "acceleration": 2, "jerk": 3},
                {"velocity": 4, "min_acceleration": -0.5, "acceleration": 1}
            ]
        })
        .to_string();
        let l = from_json_str(&json, "l.json").unwrap();
        assert_eq!(l.dof(), 2);
        assert_eq!(l.joint(0).jerk, 3.0);
        assert_eq!(l.joint(1).min_acceleration, Some(-0.5));
        assert_eq!(l.joint(1).name, "");

        let text = r#"{"preset": "panda", "joints": [
            {"name": "panda_joint3", "velocity": 1.5, "min_velocity": -1.0},
            {"jerk": null}
        ]}"#;
        let l = from_json_str(text, "p.json").unwrap();
        let panda = presets::panda();
        assert_eq!(l.dof(), 7);
        assert_eq!(l.joint(2).velocity, 1.5);
        assert_eq!(l.joint(2).min_velocity, Some(-1.0));
        assert_eq!(l.joint(2).acceleration, panda.joint(2).acceleration);
        assert!(l.joint(1).jerk.is_infinite()); // by index, null = unlimited
        assert_eq!(l.joint(1).velocity, panda.joint(1).velocity);
        assert_eq!(l.joint(0).velocity, panda.joint(0).velocity);
        // Only a preset.
        assert_eq!(
            from_yaml_str("preset: ur5e\n", "u.yaml").unwrap(),
            presets::ur5e()
        );
    }

    #[test]
    fn errors_name_file_line_field_value() {
        let bad = YAML.replace(
            "velocity: 2.175\n    acceleration: 7.5",
            "velocity: -3\n    acceleration: 7.5",
        );
        let (src, line, field, msg) = parse_err(from_yaml_str(&bad, "robot.yaml").unwrap_err());
        assert_eq!(
            (src.as_str(), line, field.as_str()),
            ("robot.yaml", 13, "joints[1].velocity")
        );
        assert!(
            msg.contains("-3") && msg.contains("not a positive"),
            "{msg}"
        );

        let e = from_yaml_str(&bad, "robot.yaml").unwrap_err().to_string();
        assert!(
            e.starts_with("robot.yaml:13 field 'joints[1].velocity': -3"),
            "{e}"
        );

        // NaN-like strings and YAML NaN.
        let bad = YAML.replace("jerk: 3750", "jerk: \"NaN\"");
        let (_, line, field, msg) = parse_err(from_yaml_str(&bad, "r.yaml").unwrap_err());
        assert_eq!((line, field.as_str()), (15, "joints[1].jerk"));
        assert!(msg.contains("'NaN' is not a number"), "{msg}");
        let bad = YAML.replace("jerk: 3750", "jerk: .nan");
        let (_, _, field, msg) = parse_err(from_yaml_str(&bad, "r.yaml").unwrap_err());
        assert_eq!(field, "joints[1].jerk");
        assert!(msg.contains("NaN is not a number"), "{msg}");

        // Unknown field (a typo) with its line.
        let bad = YAML.replace("    jerk: 7500", "    jerck: 7500");
        let (_, line, field, msg) = parse_err(from_yaml_str(&bad, "r.yaml").unwrap_err());
        assert_eq!((line, field.as_str()), (7, "joints[0].jerck"));
        assert!(msg.contains("unknown field"), "{msg}");
        let e = from_json_str(r#"{"joints": [], "jionts": 1}"#, "j.json").unwrap_err();
        let (_, line, field, msg) = parse_err(e);
        assert_eq!((line, field.as_str()), (1, "jionts"));
        assert!(msg.contains("unknown field"));

        // Zero and positive-minimum limits.
        let e = from_json_str(
            "{\"joints\": [\n {\"velocity\": 1},\n {\"acceleration\": 0}\n]}",
            "z.json",
        )
        .unwrap_err();
        let (_, line, field, msg) = parse_err(e);
        assert_eq!((line, field.as_str()), (3, "joints[1].acceleration"));
        assert!(msg.starts_with("0 is not a positive number"), "{msg}");
        let e = from_json_str(r#"{"joints": [{"min_velocity": 0.5}]}"#, "z.json").unwrap_err();
        assert!(
            e.to_string().contains("0.5 is not a negative number"),
            "{e}"
        );
        // Wrong type and inverted range.
        let e = from_json_str(r#"{"joints": [{"position": [1, -1]}]}"#, "z.json").unwrap_err();
        assert!(e.to_string().contains("joints[0].position"), "{e}");
        let e = from_json_str(r#"{"joints": [{"velocity": true}]}"#, "z.json").unwrap_err();
        assert!(e.to_string().contains("true is not a number"), "{e}");
        // Syntax errors carry the line.
        let (_, line, _, _) =
            parse_err(from_json_str("{\n\"joints\": [\n}", "s.json").unwrap_err());
        assert_eq!(line, 3);
        let (_, line, _, _) =
            parse_err(from_yaml_str("joints:\n  - velocity: [1\n", "s.yaml").unwrap_err());
        assert!(line >= 2, "{line}");
        assert_eq!(
            strip_position("bad node at line 2 column 1, while parsing at line x"),
            "bad node, while parsing at line x"
        );
        // Empty and trailing content.
        assert!(from_json_str("{}", "e.json")
            .unwrap_err()
            .to_string()
            .contains("no joints"));
        assert!(from_json_str(r#"{"preset": "ur5e"} x"#, "e.json").is_err());
        assert!(from_yaml_str("", "e.yaml").is_err());
        assert!(from_yaml_str("- 1\n- 2\n", "e.yaml").is_err());
    }

    #[test]
    fn preset_errors() {
        let e = from_yaml_str("preset: pandaa\n", "p.yaml").unwrap_err();
        let (src, line, field, msg) = parse_err(e);
        assert_eq!(
            (src.as_str(), line, field.as_str()),
            ("p.yaml", 1, "preset")
        );
        assert!(msg.contains("unknown robot preset 'pandaa'"), "{msg}");
        let e = from_yaml_str(
            "preset: panda\njoints:\n  - name: elbow\n    velocity: 1\n",
            "p.yaml",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("joints[0].name") && e.contains("'elbow' is not a joint of preset panda"),
            "{e}"
        );
        let many = format!("preset: ur5e\njoints:\n{}", "  - velocity: 1\n".repeat(7));
        assert!(from_yaml_str(&many, "p.yaml")
            .unwrap_err()
            .to_string()
            .contains("joints[6]"));
        // Override that breaks validation after merging is reported with the file.
        let e = from_yaml_str("preset: panda\njoints:\n  - position_max: -3\n", "p.yaml")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.yaml") && e.contains("panda_joint1"), "{e}");
        assert!(matches!(
            from_spec("no_such_robot"),
            Err(Error::UnknownPreset { .. })
        ));
        assert_eq!(from_spec("PANDA").unwrap(), presets::panda());
        let e = from_spec("/nonexistent/limits.yaml").unwrap_err();
        assert!(matches!(e, Error::Io { .. }));
        assert!(e.to_string().contains("/nonexistent/limits.yaml"));
    }

    const MOVEIT: &str = "\
default_velocity_scaling_factor: 0.1
default_acceleration_scaling_factor: 0.1
joint_limits:
  panda_joint1:
    has_velocity_limits: true
    max_velocity: 2.0
    has_acceleration_limits: true
    max_acceleration: 3.75
    has_jerk_limits: false
    max_jerk: 0
  panda_joint2:
    has_velocity_limits: false
    max_velocity: 0
    has_acceleration_limits: true
    max_acceleration: 1.875
    has_position_limits: true
    min_position: -1.5
    max_position: 1.5
    has_effort_limits: true
    max_effort: 80
    has_deceleration_limits: false
    max_deceleration: 0
  panda_finger_joint1:
    has_velocity_limits: true
    max_velocity: 0.2
";

    #[test]
    fn moveit_apply_and_standalone() {
        let panda = presets::panda();
        let l = apply_moveit_joint_limits(&panda, MOVEIT, "joint_limits.yaml").unwrap();
        assert_eq!(l.dof(), 7);
        assert_eq!(l.joint(0).velocity, 2.0);
        assert_eq!(l.joint(0).acceleration, 3.75);
        assert_eq!(l.joint(0).jerk, panda.joint(0).jerk); // has_jerk_limits: false
        assert_eq!(l.joint(1).velocity, panda.joint(1).velocity);
        assert_eq!(
            (l.joint(1).position_min, l.joint(1).position_max),
            (-1.5, 1.5)
        );
        assert_eq!(l.joint(1).effort, Some(80.0));
        assert_eq!(l.joint(2), panda.joint(2));

        let s = moveit_joint_limits_from_str(MOVEIT, "jl.yaml", None).unwrap();
        assert_eq!(s.dof(), 3);
        assert_eq!(s.joint(2).name, "panda_finger_joint1");
        assert!(s.joint(0).jerk.is_infinite() && s.joint(1).velocity.is_infinite());
        let order = ["panda_joint2", "panda_joint1"];
        let s = moveit_joint_limits_from_str(MOVEIT, "jl.yaml", Some(&order)).unwrap();
        assert_eq!(s.joint(0).name, "panda_joint2");
        let e = moveit_joint_limits_from_str(MOVEIT, "jl.yaml", Some(&["elbow"])).unwrap_err();
        assert!(e.to_string().contains("jl.yaml") && e.to_string().contains("'elbow'"));

        // No joint in common.
        let ur = presets::ur5e();
        let e = apply_moveit_joint_limits(&ur, MOVEIT, "jl.yaml")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("jl.yaml") && e.contains("no joint"), "{e}");
    }

    #[test]
    fn moveit_errors() {
        let bad = MOVEIT.replace("max_velocity: 2.0", "max_velocity: -2.0");
        let e = moveit_joint_limits_from_str(&bad, "jl.yaml", None).unwrap_err();
        let (_, line, field, msg) = parse_err(e);
        assert_eq!(field, "joint_limits.panda_joint1.max_velocity");
        assert!((4..=6).contains(&line), "{line}");
        assert!(msg.contains("-2"), "{msg}");
        let bad = MOVEIT.replace("max_acceleration: 3.75", "max_acceleration: fast");
        let (_, line, field, msg) =
            parse_err(moveit_joint_limits_from_str(&bad, "jl.yaml", None).unwrap_err());
        assert_eq!(
            (line, field.as_str()),
            (8, "joint_limits.panda_joint1.max_acceleration")
        );
        assert!(msg.contains("'fast' is not a number"), "{msg}");
        let bad = MOVEIT.replace("has_jerk_limits", "has_jerk_limit");
        let (_, line, field, _) =
            parse_err(moveit_joint_limits_from_str(&bad, "jl.yaml", None).unwrap_err());
        assert_eq!(
            (line, field.as_str()),
            (9, "joint_limits.panda_joint1.has_jerk_limit")
        );
        let bad = MOVEIT.replace("has_jerk_limits: false", "has_jerk_limits: true");
        let e = moveit_joint_limits_from_str(&bad, "jl.yaml", None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("max_jerk") && e.contains("0 is not a positive"),
            "{e}"
        );
        let bad = MOVEIT.replace("    max_velocity: 0.2\n", "");
        let e = moveit_joint_limits_from_str(&bad, "jl.yaml", None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("panda_finger_joint1.max_velocity") && e.contains("missing"),
            "{e}"
        );
        let e = moveit_joint_limits_from_str("joint_limits: {}\n", "jl.yaml", None).unwrap_err();
        assert!(e.to_string().contains("no joints"));
    }

    fn panda_urdf() -> String {
        let p = presets::panda();
        let mut s = String::from(
            "<?xml version=\"1.0\"?>\n<robot name=\"panda\">\n  <link name=\"panda_link0\"/>\n",
        );
        for (i, j) in p.joints().iter().enumerate() {
            s.push_str(&format!(
                "  <joint name=\"{}\" type=\"revolute\">\n    <parent link=\"panda_link{}\"/>\n    <child link=\"panda_link{}\"/>\n    <axis xyz=\"0 0 1\"/>\n    <limit effort=\"{}\" lower=\"{}\" upper=\"{}\" velocity=\"{}\"/>\n  </joint>\n",
                j.name, i, i + 1, j.effort.unwrap(), j.position_min, j.position_max, j.velocity
            ));
        }
        s.push_str(
            "  <joint name=\"panda_joint8\" type=\"fixed\"><parent link=\"panda_link7\"/><child link=\"panda_link8\"/></joint>\n\
             <joint name=\"panda_finger_joint1\" type=\"prismatic\">\n    <limit effort=\"20\" lower=\"0.0\" upper=\"0.04\" velocity=\"0.2\"/>\n  </joint>\n\
             <joint name=\"panda_finger_joint2\" type=\"prismatic\"><limit effort=\"20\" lower=\"0.0\" upper=\"0.04\" velocity=\"0.2\"/><mimic joint=\"panda_finger_joint1\"/></joint>\n\
             <transmission name=\"t1\"><joint name=\"panda_joint1\"/></transmission>\n</robot>\n",
        );
        s
    }

    #[test]
    fn urdf_round_trip_and_fill() {
        let text = panda_urdf();
        let l = from_urdf_str(&text, "panda.urdf").unwrap();
        let p = presets::panda();
        assert_eq!(l.dof(), 8);
        for j in 0..7 {
            assert_eq!(l.joint(j).name, p.joint(j).name);
            assert_eq!(l.joint(j).velocity, p.joint(j).velocity);
            assert_eq!(l.joint(j).position_min, p.joint(j).position_min);
            assert_eq!(l.joint(j).position_max, p.joint(j).position_max);
            assert_eq!(l.joint(j).effort, p.joint(j).effort);
            assert!(l.joint(j).acceleration.is_infinite() && l.joint(j).jerk.is_infinite());
        }
        assert_eq!(l.joint(7).name, "panda_finger_joint1");
        assert_eq!(l.joint(7).position_max, 0.04);

        let arm = Limits::new(l.joints()[..7].to_vec()).unwrap();
        let full = fill_missing(&arm, &p).unwrap();
        assert_eq!(full, p);
        assert!(fill_missing(&l, &p).is_err());

        let c = from_urdf_str(
            "<robot name=\"r\"><joint name=\"wheel\" type=\"continuous\"><limit lower=\"-1\" upper=\"1\" effort=\"0\" velocity=\"3\"/></joint><joint name=\"spin\" type=\"continuous\"/></robot>",
            "c.urdf",
        )
        .unwrap();
        assert_eq!(c.dof(), 2);
        assert!(c.joint(0).position_min.is_infinite() && c.joint(0).effort.is_none());
        assert_eq!(c.joint(0).velocity, 3.0);
        assert!(c.joint(1).velocity.is_infinite());
    }

    #[test]
    fn urdf_errors() {
        let text = panda_urdf();
        // Joint k's (0-based) <limit> is on line 8 + 6 k.
        let bad = text.replacen("velocity=\"2.175\"", "velocity=\"-1\"", 3);
        let (src, line, field, msg) = parse_err(from_urdf_str(&bad, "panda.urdf").unwrap_err());
        assert_eq!((src.as_str(), line), ("panda.urdf", 8));
        assert_eq!(field, "joint 'panda_joint1' <limit velocity>");
        assert!(msg.contains("-1 is not a positive number"), "{msg}");
        let bad = text.replacen("velocity=\"2.175\"", "velocity=\"0\"", 1);
        let e = from_urdf_str(&bad, "panda.urdf").unwrap_err().to_string();
        assert!(
            e.starts_with(
                "panda.urdf:8 field 'joint 'panda_joint1' <limit velocity>': 0 is not a positive"
            ),
            "{e}"
        );
        let bad = text.replacen("upper=\"1.7628\"", "upper=\"NaN\"", 1);
        let (_, line, field, msg) = parse_err(from_urdf_str(&bad, "panda.urdf").unwrap_err());
        assert_eq!(
            (line, field.as_str()),
            (14, "joint 'panda_joint2' <limit upper>")
        );
        assert!(msg.contains("'NaN' is not a finite number"), "{msg}");
        let bad = text.replacen("effort=\"87\"", "effort=\"lots\"", 1);
        let e = from_urdf_str(&bad, "panda.urdf").unwrap_err().to_string();
        assert!(
            e.contains("<limit effort>") && e.contains("'lots' is not a number"),
            "{e}"
        );
        let bad = text.replacen(
            "lower=\"-2.8973\" upper=\"2.8973\"",
            "lower=\"1\" upper=\"0\"",
            1,
        );
        let e = from_urdf_str(&bad, "panda.urdf").unwrap_err().to_string();
        assert!(
            e.contains("<limit upper>") && e.contains("0 is not above lower = 1"),
            "{e}"
        );
        let e = from_urdf_str(
            "<robot name=\"r\"><joint name=\"j\" type=\"revolute\"/></robot>",
            "x.urdf",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("needs a <limit>"), "{e}");
        let e = from_urdf_str(
            "<robot name=\"r\"><joint name=\"j\" type=\"fixed\"/></robot>",
            "x.urdf",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.starts_with("x.urdf") && e.contains("no movable joint"),
            "{e}"
        );
        let (_, line, _, _) =
            parse_err(from_urdf_str("<robot>\n<joint>\n</robot>", "x.urdf").unwrap_err());
        assert_eq!(line, 3);
        assert!(from_urdf_str("<sdf/>", "x.urdf").is_err());
        let e = from_urdf_str(
            "<robot><joint name=\"j\" type=\"hinge\"/></robot>",
            "x.urdf",
        )
        .unwrap_err();
        assert!(e.to_string().contains("'hinge'"));
    }

    #[test]
    fn files_by_extension() {
        let dir = std::env::temp_dir().join(format!("trajkit-load-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let write = |name: &str, text: &str| {
            let p = dir.join(name);
            std::fs::write(&p, text).unwrap();
            p
        };
        let y = write("l.yaml", YAML);
        assert_eq!(from_file(&y).unwrap().dof(), 3);
        let m = write("joint_limits.yml", MOVEIT);
        assert_eq!(from_file(&m).unwrap().dof(), 3);
        let j = write("l.JSON", r#"{"preset": "iiwa14"}"#);
        assert_eq!(from_file(&j).unwrap(), presets::iiwa14());
        let u = write("r.urdf", &panda_urdf());
        assert_eq!(from_spec(u.to_str().unwrap()).unwrap().dof(), 8);
        let t = write("l.txt", "");
        assert!(from_file(&t).unwrap_err().to_string().contains("extension"));
        let missing = dir.join("missing.yaml");
        let e = from_file(&missing).unwrap_err();
        assert!(matches!(&e, Error::Io { path, .. } if path.contains("missing.yaml")));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
