//! Values as written in a limits file: checked inside the format's deserializer so that an
//! error carries the value's line, and turned into [`Error::Parse`] naming file, line and field.

pub(super) use super::{file_error, in_file};
use crate::error::{Error, Location};
use crate::limits::presets;
use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::fmt;

// ---------------------------------------------------------------------------------------------
// Errors raised while deserializing.
//
// A visitor that finds a bad value raises a serde error whose text carries the field between
// two markers; the format's own error then adds the line. `parse_error` takes both apart again.

const MARK: char = '\u{1e}';
const SEP: char = '\u{1f}';

pub(super) fn located<E: de::Error>(field: &str, message: impl fmt::Display) -> E {
    E::custom(format!("{MARK}{field}{SEP}{message}{MARK}"))
}

/// Builds an [`Error::Parse`] from the text of a serde error and the line the format reported.
pub(super) fn parse_error(source: &str, line: usize, text: &str) -> Error {
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
pub(super) fn strip_position(text: &str) -> String {
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

pub(super) fn json_error(source: &str, e: serde_json::Error) -> Error {
    parse_error(source, e.line(), &e.to_string())
}

#[cfg(feature = "yaml")]
pub(super) fn yaml_error(source: &str, e: serde_yaml_ng::Error) -> Error {
    let line = e.location().map_or(0, |l| l.line());
    parse_error(source, line, &e.to_string())
}

// ---------------------------------------------------------------------------------------------
// A scalar (or small list) as written in the file, kept for validation and quoting.

/// A value as written, for checks and quoting.
///
/// Its `Deserialize` is hand-written: a derived `#[serde(untagged)]` enum would first buffer
/// each value (a mapping's whole contents too) and then try the variants one by one, where
/// this visitor takes the value as the format hands it.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Raw {
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
pub(super) enum Kind {
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
pub(super) enum Val {
    Num(f64),
    Opt(Option<f64>),
    Bool(bool),
    Text(String),
    Range(f64, f64),
}

pub(super) fn number(raw: &Raw) -> std::result::Result<Option<f64>, String> {
    match raw {
        Raw::Null => Ok(None),
        Raw::Num(x) if x.is_nan() => Err(format!("{x} is not a number")),
        Raw::Num(x) => Ok(Some(*x)),
        other => Err(format!("{other} is not a number")),
    }
}

pub(super) fn check(kind: Kind, raw: &Raw) -> std::result::Result<Val, String> {
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
///
/// A visitor rather than derived field types: the check must run while the format still
/// points at the value, and the messages quote the value as written (`'fast' is not a
/// number`, `[1, 0]: the upper end is not above the lower end`) where serde's derived
/// messages say `invalid type: string "fast", expected f64` and know nothing of the limit's
/// meaning (positive maximum, negative minimum, unbounded `null`). `serde_path_to_error`
/// would give the path, but the path is already the field named here.
pub(super) struct FieldSeed<'a> {
    pub(super) field: &'a str,
    pub(super) kind: Kind,
}

impl FieldSeed<'_> {
    fn finish<E: de::Error>(self, raw: Raw) -> std::result::Result<Val, E> {
        if let Kind::Unknown(expected) = self.kind {
            return Err(located(self.field, unknown_field(self.field, expected)));
        }
        check(self.kind, &raw).map_err(|m| located(self.field, m))
    }
}

/// "unknown field (did you mean 'velocity'? known: ...)" for the last segment of `field`.
pub(super) fn unknown_field(field: &str, expected: &str) -> String {
    let key = field.rsplit('.').next().unwrap_or(field);
    let known: Vec<&str> = expected.split(", ").collect();
    match crate::error::closest_name(key, &known) {
        Some(k) => format!("unknown field (did you mean '{k}'? known: {expected})"),
        None => format!("unknown field (known: {expected})"),
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
