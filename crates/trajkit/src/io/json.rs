//! JSON: waypoints and sample tables (see the [parent module](super) for the format).
//!
//! Both readers walk a `serde_json::Value` instead of deriving `Deserialize` for the file's
//! shape: the messages name the field and quote the value (`waypoints[2][1]: "a" is not a
//! number`), check a row's length before its values, and suggest the closest known key for an
//! unknown one; a derive (even with `serde_path_to_error` for the path) gives serde's own
//! messages (`invalid type: string "a", expected f64`) in its own order. Errors found in the
//! tree carry no line (0): the tree keeps none; syntax errors carry serde_json's line.

use super::{parse_err, Waypoints, PREFIX};
use crate::error::Result;
use crate::sample::SampleTable;
use crate::traj::Order;

impl Waypoints {
    /// Parses JSON text (see the module docs).
    pub fn from_json(text: &str, source: &str) -> Result<Self> {
        let v: serde_json::Value = serde_json::from_str(text)
            .map_err(|e| parse_err(source, e.line(), "", e.to_string()))?;
        let (rows, names) = match &v {
            serde_json::Value::Array(_) => (&v, Vec::new()),
            serde_json::Value::Object(m) => {
                reject_unknown_keys(m, &["joint_names", "waypoints"], source)?;
                let rows = m
                    .get("waypoints")
                    .ok_or_else(|| parse_err(source, 0, "waypoints", "missing"))?;
                let names = match m.get("joint_names") {
                    None | Some(serde_json::Value::Null) => Vec::new(),
                    Some(serde_json::Value::Array(a)) => a
                        .iter()
                        .enumerate()
                        .map(|(i, x)| {
                            x.as_str().map(str::to_string).ok_or_else(|| {
                                parse_err(source, 0, format!("joint_names[{i}]"), "is not a string")
                            })
                        })
                        .collect::<Result<Vec<_>>>()?,
                    Some(_) => return Err(parse_err(source, 0, "joint_names", "is not an array")),
                };
                (rows, names)
            }
            _ => {
                return Err(parse_err(
                    source,
                    0,
                    "",
                    "expected an array of waypoints or an object with 'waypoints'",
                ))
            }
        };
        let rows = rows
            .as_array()
            .ok_or_else(|| parse_err(source, 0, "waypoints", "is not an array"))?;
        let mut dof = names.len();
        let mut points = Vec::new();
        for (i, row) in rows.iter().enumerate() {
            let row = row.as_array().ok_or_else(|| {
                parse_err(source, 0, format!("waypoints[{i}]"), "is not an array")
            })?;
            if i == 0 && dof == 0 {
                dof = row.len();
            }
            if row.len() != dof {
                return Err(parse_err(
                    source,
                    0,
                    format!("waypoints[{i}]"),
                    format!("{} values, expected {dof}", row.len()),
                ));
            }
            for (j, x) in row.iter().enumerate() {
                let v = x.as_f64().ok_or_else(|| {
                    parse_err(
                        source,
                        0,
                        format!("waypoints[{i}][{j}]"),
                        format!("{x} is not a number"),
                    )
                })?;
                points.push(v);
            }
        }
        if points.is_empty() {
            return Err(parse_err(source, 0, "waypoints", "no waypoints"));
        }
        Waypoints::new(points, dof, names)
    }
}

/// An error for the first key of `m` that is not in `known`, suggesting the closest known one.
fn reject_unknown_keys(
    m: &serde_json::Map<String, serde_json::Value>,
    known: &[&str],
    source: &str,
) -> Result<()> {
    let Some(k) = m.keys().find(|k| !known.contains(&k.as_str())) else {
        return Ok(());
    };
    let hint = match crate::error::closest_name(k, known) {
        Some(c) => format!("did you mean '{c}'? "),
        None => String::new(),
    };
    Err(parse_err(
        source,
        0,
        k.as_str(),
        format!("unknown field ({hint}known: {})", known.join(", ")),
    ))
}

/// Writes a sample table as JSON (see the module docs).
pub fn table_to_json(table: &SampleTable) -> String {
    let mut m = serde_json::Map::new();
    m.insert("dof".into(), table.dof().into());
    m.insert("joint_names".into(), table.names().to_vec().into());
    m.insert("t".into(), table.times().to_vec().into());
    for o in Order::ALL {
        if table.has(o) {
            let rows: Vec<serde_json::Value> = (0..table.len())
                .map(|i| table.row(o, i).expect("present").to_vec().into())
                .collect();
            m.insert(PREFIX[o.index()].into(), rows.into());
        }
    }
    serde_json::Value::Object(m).to_string()
}

/// Reads a sample table from JSON (see the module docs).
pub fn table_from_json(text: &str, source: &str) -> Result<SampleTable> {
    let v: serde_json::Value =
        serde_json::from_str(text).map_err(|e| parse_err(source, e.line(), "", e.to_string()))?;
    let obj = v
        .as_object()
        .ok_or_else(|| parse_err(source, 0, "", "expected an object with 't' and 'q'"))?;
    let nums = |key: &str, x: &serde_json::Value| -> Result<Vec<f64>> {
        x.as_array()
            .ok_or_else(|| parse_err(source, 0, key, "is not an array"))?
            .iter()
            .enumerate()
            .map(|(i, e)| {
                e.as_f64().ok_or_else(|| {
                    parse_err(
                        source,
                        0,
                        format!("{key}[{i}]"),
                        format!("{e} is not a number"),
                    )
                })
            })
            .collect()
    };
    let t = nums(
        "t",
        obj.get("t")
            .ok_or_else(|| parse_err(source, 0, "t", "missing"))?,
    )?;
    let mut dof = 0;
    let mut data: [Option<Vec<f64>>; 4] = Default::default();
    for (k, key) in PREFIX.iter().enumerate() {
        let Some(rows) = obj.get(*key) else { continue };
        if rows.is_null() {
            continue;
        }
        let rows = rows
            .as_array()
            .ok_or_else(|| parse_err(source, 0, *key, "is not an array"))?;
        if rows.len() != t.len() {
            return Err(parse_err(
                source,
                0,
                *key,
                format!("{} rows, expected {} (one per time)", rows.len(), t.len()),
            ));
        }
        let mut flat = Vec::new();
        for (i, r) in rows.iter().enumerate() {
            let r = nums(&format!("{key}[{i}]"), r)?;
            if dof == 0 {
                dof = r.len();
            }
            if r.len() != dof {
                return Err(parse_err(
                    source,
                    0,
                    format!("{key}[{i}]"),
                    format!("{} values, expected {dof}", r.len()),
                ));
            }
            flat.extend(r);
        }
        data[k] = Some(flat);
    }
    if data[0].is_none() {
        return Err(parse_err(source, 0, "q", "missing"));
    }
    let table =
        SampleTable::new(dof, t, data).map_err(|e| parse_err(source, 0, "", e.to_string()))?;
    if let Some(serde_json::Value::Array(n)) = obj.get("joint_names") {
        let names: Vec<String> = n
            .iter()
            .map(|x| x.as_str().unwrap_or("").to_string())
            .collect();
        if names.len() == dof {
            return table.with_names(names);
        }
    }
    Ok(table)
}
