//! The JSON problem format of `trajkit otg` from Python: reading is the library's reader
//! (`trajkit::otg::json::parse_problem`, the one the command line calls, so the accepted
//! fields and the error messages are the same); writing produces text that reader reads back
//! as an equal input (every field explicit, numbers in shortest round-trip form, infinite
//! limits as `"inf"` / `"-inf"`; a value JSON cannot hold, such as NaN or an infinite state,
//! is an error naming the field).

use pyo3::prelude::*;
use serde_json::{Map, Value};
use trajkit::otg::json::parse_problem;
use trajkit::otg::{
    ControlInterface as CI, DurationDiscretization as DD, DynInputParameter,
    Synchronization as Sync_,
};

use super::PyInput;
use crate::convert::{bad, err};

/// Parses `text` with the command line's reader: the input (with its waypoints) and `dt`.
pub fn parse(text: &str, source: &str) -> PyResult<(PyInput, f64)> {
    let p = parse_problem(text, source, 0).map_err(err)?;
    let input = PyInput {
        inner: p.input,
        wp: p.waypoints.unwrap_or_default(),
    };
    Ok((input, p.delta_time))
}

/// Reads one problem in the JSON format of `trajkit otg` (Ruckig's field names, `dt`,
/// `intermediate_positions` and the per-section fields): `(InputParameter, delta_time)`,
/// `delta_time` being the file's `dt` (0.001 when absent). Raises `TrajkitError` with the
/// command line's message (`source`, the field and the value) on any mistake.
#[pyfunction]
#[pyo3(signature = (text, source = "<json>"))]
pub fn read_problem(text: &str, source: &str) -> PyResult<(PyInput, f64)> {
    parse(text, source)
}

/// The strings the reader accepts for `+inf` and `-inf` in a field (None: not accepted).
type Inf = (Option<&'static str>, Option<&'static str>);

/// One number; `inf` as in [`Inf`].
fn num(field: &str, x: f64, inf: Inf) -> PyResult<Value> {
    if x.is_finite() {
        return Ok(Value::from(x));
    }
    match inf {
        (Some(pos), _) if x == f64::INFINITY => Ok(Value::from(pos)),
        (_, Some(neg)) if x == f64::NEG_INFINITY => Ok(Value::from(neg)),
        _ => Err(bad(format!(
            "{field} = {x} cannot be written in the JSON problem format"
        ))),
    }
}

fn nums(field: &str, v: &[f64], inf: Inf) -> PyResult<Value> {
    v.iter()
        .enumerate()
        .map(|(i, &x)| num(&format!("{field}[{i}]"), x, inf))
        .collect::<PyResult<Vec<_>>>()
        .map(Value::Array)
}

fn rows(field: &str, r: &[Vec<f64>], inf: Inf) -> PyResult<Value> {
    r.iter()
        .enumerate()
        .map(|(k, row)| nums(&format!("{field}[{k}]"), row, inf))
        .collect::<PyResult<Vec<_>>>()
        .map(Value::Array)
}

fn sync_word(s: Sync_) -> &'static str {
    match s {
        Sync_::Time => "time",
        Sync_::TimeIfNecessary => "time_if_necessary",
        Sync_::Phase => "phase",
        Sync_::None => "none",
        Sync_::StraightLine => "straight_line",
    }
}

fn iface_word(c: CI) -> &'static str {
    match c {
        CI::Velocity => "velocity",
        _ => "position",
    }
}

const FINITE: Inf = (None, None);
const UP: Inf = (Some("inf"), None);
const DOWN: Inf = (None, Some("-inf"));

/// The current and target states of `i` by field name.
pub fn states(i: &DynInputParameter) -> [(&'static str, &Vec<f64>); 6] {
    [
        ("current_position", &i.current_position),
        ("current_velocity", &i.current_velocity),
        ("current_acceleration", &i.current_acceleration),
        ("target_position", &i.target_position),
        ("target_velocity", &i.target_velocity),
        ("target_acceleration", &i.target_acceleration),
    ]
}

/// The states, limits and options of `i` into `m`.
fn input_fields(i: &DynInputParameter, m: &mut Map<String, Value>) -> PyResult<()> {
    for (k, v) in states(i) {
        m.insert(k.into(), nums(k, v, FINITE)?);
    }
    for (k, v) in [
        ("max_velocity", &i.max_velocity),
        ("max_acceleration", &i.max_acceleration),
        ("max_jerk", &i.max_jerk),
    ] {
        m.insert(k.into(), nums(k, v, UP)?);
    }
    for (k, v) in [
        ("min_velocity", &i.min_velocity),
        ("min_acceleration", &i.min_acceleration),
    ] {
        if let Some(v) = v {
            m.insert(k.into(), nums(k, v, DOWN)?);
        }
    }
    m.insert(
        "max_position".into(),
        nums("max_position", &i.max_position, UP)?,
    );
    m.insert(
        "min_position".into(),
        nums("min_position", &i.min_position, DOWN)?,
    );
    m.insert("enabled".into(), Value::from(i.enabled.clone()));
    let o = &i.options;
    m.insert(
        "synchronization".into(),
        sync_word(o.synchronization).into(),
    );
    m.insert(
        "control_interface".into(),
        iface_word(o.control_interface).into(),
    );
    let disc = match o.duration_discretization {
        DD::Discrete => "discrete",
        _ => "continuous",
    };
    m.insert("duration_discretization".into(), disc.into());
    if let Some(s) = &i.per_dof_synchronization {
        let w: Vec<_> = s.iter().map(|&s| sync_word(s)).collect();
        m.insert("per_dof_synchronization".into(), Value::from(w));
    }
    if let Some(c) = &i.per_dof_control_interface {
        let w: Vec<_> = c.iter().map(|&c| iface_word(c)).collect();
        m.insert("per_dof_control_interface".into(), Value::from(w));
    }
    if let Some(d) = o.minimum_duration {
        m.insert(
            "minimum_duration".into(),
            num("minimum_duration", d, FINITE)?,
        );
    }
    if let Some(b) = o.interrupt_calculation_duration {
        let k = "interrupt_calculation_duration";
        m.insert(k.into(), num(k, b, FINITE)?);
    }
    Ok(())
}

/// `input` as JSON text (see the module documentation).
pub fn write(input: &PyInput, delta_time: Option<f64>, indent: Option<usize>) -> PyResult<String> {
    let mut m = Map::new();
    input_fields(&input.inner, &mut m)?;
    if let Some(w) = input.waypoints() {
        let k = "intermediate_positions";
        m.insert(k.into(), rows(k, &w.intermediate_positions, FINITE)?);
        for (k, v) in [
            ("per_section_max_velocity", &w.per_section_max_velocity),
            (
                "per_section_max_acceleration",
                &w.per_section_max_acceleration,
            ),
            ("per_section_max_jerk", &w.per_section_max_jerk),
        ] {
            if let Some(v) = v {
                m.insert(k.into(), rows(k, v, UP)?);
            }
        }
        if let Some(d) = &w.per_section_minimum_duration {
            let k = "per_section_minimum_duration";
            m.insert(k.into(), nums(k, d, FINITE)?);
        }
    }
    if let Some(dt) = delta_time {
        m.insert("dt".into(), num("delta_time", dt, FINITE)?);
    }
    let v = Value::Object(m);
    let text = match indent {
        None => serde_json::to_string(&v),
        Some(n) => {
            let pad = " ".repeat(n);
            let fmt = serde_json::ser::PrettyFormatter::with_indent(pad.as_bytes());
            let mut buf = Vec::new();
            let mut ser = serde_json::Serializer::with_formatter(&mut buf, fmt);
            serde::Serialize::serialize(&v, &mut ser)
                .map(|_| String::from_utf8_lossy(&buf).into_owned())
        }
    };
    text.map_err(|e| bad(format!("the problem cannot be written as JSON: {e}")))
}
