//! Reading waypoints and sampled trajectories, writing sampled trajectories: CSV and JSON.
//!
//! # Waypoints
//! - CSV: one row per waypoint, one column per joint. An optional first row of joint names
//!   (any non-numeric field makes it a header). Blank lines and lines starting with `#` are
//!   skipped.
//! - JSON: either an array of rows `[[q1, q2, ...], ...]` or an object
//!   `{"joint_names": [...], "waypoints": [[...], ...]}`; any other key is an error that
//!   suggests the closest known one.
//!
//! A CSV header or `joint_names` *names* the joints ([`Waypoints::has_names`]): limits are
//! then matched to the columns by name ([`crate::limits::match_names`]). Without them the
//! joints are `q1..qn` and matched by position.
//!
//! # Sample tables
//! - CSV: header `t,q1..qn,qd1..qdn,qdd1..qddn,qddd1..qdddn` (derivative groups optional when
//!   reading). A table whose joints have names writes them instead of the indices:
//!   `t,q_<name>..,qd_<name>..,qdd_<name>..,qddd_<name>..` (`q_panda_joint1`), in joint
//!   order; reading pairs derivative columns with position columns by name. Names with a
//!   comma, semicolon, tab, quote or line break cannot be CSV headers: such a table is written
//!   with indices. A foreign table whose header has a `t` (or `time`) column but no `q<k>` or
//!   `q_<name>` columns is read as times plus positions, one column per joint.
//! - JSON: `{"joint_names": [...], "t": [...], "q": [[...]...], "qd": ..., "qdd": ..., "qddd": ...}`
//!   (`qd`, `qdd`, `qddd` optional when reading).
//!
//! Every error names the source, the line (CSV; JSON where the parser knows it) and the field.
//! Non-finite numbers (`nan`, `inf`) are refused. Files above [`MAX_FILE_BYTES`] are refused
//! before they are read ([`Error::TooLarge`]).

use crate::error::{Error, Location, Result};
use crate::sample::SampleTable;
use crate::traj::Order;
use std::fmt::Write as _;

/// Largest input file read ([`read_text`]): a quarter of [`crate::size::MEMORY_BUDGET`], since
/// the parsed numbers can take several times the text's size.
pub const MAX_FILE_BYTES: u64 = (crate::size::MEMORY_BUDGET / 4) as u64;

/// Waypoints: `len() × dof` positions, row-major, with optional joint names.
#[derive(Debug, Clone, PartialEq)]
pub struct Waypoints {
    dof: usize,
    points: Vec<f64>,
    names: Vec<String>,
    named: bool,
}

fn parse_err(
    source: &str,
    line: usize,
    field: impl Into<String>,
    message: impl Into<String>,
) -> Error {
    Error::Parse {
        location: Location {
            source: source.to_string(),
            line,
            field: field.into(),
        },
        message: message.into(),
    }
}

fn parse_number(s: &str, source: &str, line: usize, field: &str) -> Result<f64> {
    let t = s.trim();
    let v: f64 = t
        .parse()
        .map_err(|_| parse_err(source, line, field, format!("'{t}' is not a number")))?;
    if !v.is_finite() {
        return Err(parse_err(
            source,
            line,
            field,
            format!("{v} is not a finite number"),
        ));
    }
    Ok(v)
}

/// Splits a CSV line on commas (or semicolons/tabs when the line has no comma).
fn split_fields(line: &str) -> Vec<&str> {
    let sep = if line.contains(',') {
        ','
    } else if line.contains(';') {
        ';'
    } else if line.contains('\t') {
        '\t'
    } else {
        ','
    };
    line.split(sep).map(|f| f.trim()).collect()
}

impl Waypoints {
    /// From row-major points; checks the shape (at least one waypoint) and finiteness.
    pub fn new(points: Vec<f64>, dof: usize, names: Vec<String>) -> Result<Self> {
        if dof == 0 || points.is_empty() || points.len() % dof != 0 {
            return Err(Error::DimensionMismatch {
                what: "waypoint values (a non-zero multiple of the joint count)".into(),
                expected: dof.max(1),
                found: points.len(),
            });
        }
        if let Some(i) = points.iter().position(|v| !v.is_finite()) {
            return Err(Error::InvalidValue {
                field: format!("waypoint {} joint {}", i / dof, i % dof + 1),
                value: points[i],
                reason: "is not a finite number",
            });
        }
        let named = !names.is_empty();
        let names = if names.is_empty() {
            (1..=dof).map(|j| format!("q{j}")).collect()
        } else if names.len() != dof {
            return Err(Error::DimensionMismatch {
                what: "joint name count".into(),
                expected: dof,
                found: names.len(),
            });
        } else {
            names
        };
        if named {
            for (j, n) in names.iter().enumerate() {
                if n.is_empty() || names[..j].contains(n) {
                    return Err(Error::InvalidValue {
                        field: format!("joint name '{n}' (column {})", j + 1),
                        value: j as f64 + 1.0,
                        reason: "is empty or names an earlier column too",
                    });
                }
            }
        }
        Ok(Waypoints {
            dof,
            points,
            names,
            named,
        })
    }

    /// True when the input named its joints (a CSV header, JSON `joint_names`).
    pub fn has_names(&self) -> bool {
        self.named
    }

    /// The joint names when the input gave them, for [`crate::limits::match_names`].
    pub fn given_names(&self) -> Option<&[String]> {
        self.named.then_some(&self.names[..])
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }
    /// Number of waypoints.
    pub fn len(&self) -> usize {
        self.points.len() / self.dof
    }
    /// True when there are no waypoints (never, for a constructed value).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
    /// Row-major positions.
    pub fn points(&self) -> &[f64] {
        &self.points
    }
    /// Waypoint `i`.
    pub fn point(&self, i: usize) -> &[f64] {
        &self.points[i * self.dof..(i + 1) * self.dof]
    }
    /// Joint names (`q1..qn` when the input had none).
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Removes waypoints equal to their predecessor (within `tol` in every joint); returns how
    /// many were removed.
    pub fn dedup(&mut self, tol: f64) -> usize {
        let dof = self.dof;
        let mut kept: Vec<f64> = Vec::with_capacity(self.points.len());
        let mut removed = 0;
        for row in self.points.chunks(dof) {
            let dup = kept.len() >= dof
                && kept[kept.len() - dof..]
                    .iter()
                    .zip(row)
                    .all(|(a, b)| (a - b).abs() <= tol);
            if dup {
                removed += 1;
            } else {
                kept.extend_from_slice(row);
            }
        }
        self.points = kept;
        removed
    }

    /// Parses CSV text (see the module docs). `source` names the input in errors.
    pub fn from_csv(text: &str, source: &str) -> Result<Self> {
        let mut names: Vec<String> = Vec::new();
        let mut points = Vec::new();
        let mut dof = 0;
        let mut first = true;
        for (ln, raw) in text.lines().enumerate() {
            let line = raw.trim();
            let lineno = ln + 1;
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let fields = split_fields(line);
            if first {
                first = false;
                dof = fields.len();
                if fields.iter().any(|f| f.parse::<f64>().is_err()) {
                    names = fields.iter().map(|s| s.to_string()).collect();
                    continue;
                }
            }
            if fields.len() != dof {
                return Err(parse_err(
                    source,
                    lineno,
                    "",
                    format!("{} columns, expected {dof}", fields.len()),
                ));
            }
            for (j, f) in fields.iter().enumerate() {
                let name = names
                    .get(j)
                    .cloned()
                    .unwrap_or_else(|| format!("q{}", j + 1));
                points.push(parse_number(f, source, lineno, &name)?);
            }
        }
        if points.is_empty() {
            return Err(parse_err(source, 0, "", "no waypoints"));
        }
        Waypoints::new(points, dof, names)
    }

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

    /// Reads a file, choosing the format by extension (`.json` → JSON, anything else → CSV).
    pub fn from_file(path: &std::path::Path) -> Result<Self> {
        let text = read_text(path)?;
        let src = path.display().to_string();
        if is_json(path) {
            Waypoints::from_json(&text, &src)
        } else {
            Waypoints::from_csv(&text, &src)
        }
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

/// Reads a whole file as UTF-8 text; errors name the path. A regular file above
/// [`MAX_FILE_BYTES`] is refused before it is read ([`Error::TooLarge`]).
pub fn read_text(path: &std::path::Path) -> Result<String> {
    let io = |e: std::io::Error| Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if meta.is_file() && meta.len() > MAX_FILE_BYTES {
        return Err(Error::TooLarge {
            what: format!("{} size (bytes)", path.display()),
            value: meta.len() as f64,
            limit: MAX_FILE_BYTES as f64,
            reason: format!(
                "input files are read whole; {} at most",
                crate::size::human_bytes(MAX_FILE_BYTES as f64)
            ),
        });
    }
    std::fs::read_to_string(path).map_err(io)
}

/// True when the path's extension is `.json` (case-insensitive).
pub fn is_json(path: &std::path::Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

const PREFIX: [&str; 4] = ["q", "qd", "qdd", "qddd"];
const JSON_KEYS: [&str; 4] = ["q", "qd", "qdd", "qddd"];

/// The table's joint names when they can be CSV headers: every name non-empty, distinct, and
/// free of separators, quotes and line breaks.
fn csv_names(table: &SampleTable) -> Option<&[String]> {
    let names = table.names();
    let ok = names.iter().enumerate().all(|(j, n)| {
        !n.is_empty()
            && n.trim() == n
            && !n.contains([',', ';', '\t', '"', '\n', '\r'])
            && !names[..j].contains(n)
    });
    ok.then_some(names)
}

/// Writes a sample table as CSV (header `t,q1..,qd1..,qdd1..,qddd1..`, or with the joint names
/// `t,q_<name>..,qd_<name>..` when the table has names that fit a CSV header; only the
/// derivative groups the table has). Numbers use Rust's shortest round-trip representation.
pub fn table_to_csv(table: &SampleTable) -> String {
    let dof = table.dof();
    let names = csv_names(table);
    let orders: Vec<Order> = Order::ALL
        .iter()
        .copied()
        .filter(|o| table.has(*o))
        .collect();
    let mut s = String::with_capacity(table.len() * (1 + dof * orders.len()) * 12);
    s.push('t');
    for o in &orders {
        for j in 1..=dof {
            match names {
                Some(n) => {
                    let _ = write!(s, ",{}_{}", PREFIX[o.index()], n[j - 1]);
                }
                None => {
                    let _ = write!(s, ",{}{j}", PREFIX[o.index()]);
                }
            }
        }
    }
    s.push('\n');
    for i in 0..table.len() {
        let _ = write!(s, "{}", table.times()[i]);
        for o in &orders {
            for v in table.row(*o, i).expect("present") {
                let _ = write!(s, ",{v}");
            }
        }
        s.push('\n');
    }
    s
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
            m.insert(JSON_KEYS[o.index()].into(), rows.into());
        }
    }
    serde_json::Value::Object(m).to_string()
}

/// Reads a sample table from CSV (see the module docs).
pub fn table_from_csv(text: &str, source: &str) -> Result<SampleTable> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let (hl, header) = lines
        .next()
        .ok_or_else(|| parse_err(source, 0, "", "empty file: no header"))?;
    let raw_cols: Vec<String> = split_fields(header).iter().map(|s| s.to_string()).collect();
    let cols: Vec<String> = raw_cols.iter().map(|s| s.to_ascii_lowercase()).collect();
    let tcol = cols
        .iter()
        .position(|c| c == "t" || c == "time" || c == "time_from_start")
        .ok_or_else(|| parse_err(source, hl + 1, "t", "header has no 't' (time) column"))?;
    let (map, dof, names) = classify_columns(&raw_cols, &cols, tcol, source, hl + 1)?;
    let mut present = [false; 4];
    let mut counts = [0usize; 4];
    for (k, _) in map.iter().flatten() {
        present[*k] = true;
        counts[*k] += 1;
    }
    for k in 0..4 {
        if present[k] && counts[k] != dof {
            return Err(parse_err(
                source,
                hl + 1,
                PREFIX[k],
                format!("{} {} columns, expected {dof}", counts[k], PREFIX[k]),
            ));
        }
    }
    let mut t = Vec::new();
    let mut data: [Vec<f64>; 4] = Default::default();
    for (ln, line) in lines {
        let fields = split_fields(line);
        if fields.len() != cols.len() {
            return Err(parse_err(
                source,
                ln + 1,
                "",
                format!("{} columns, expected {}", fields.len(), cols.len()),
            ));
        }
        let row = t.len();
        for k in 0..4 {
            if present[k] {
                data[k].resize((row + 1) * dof, 0.0);
            }
        }
        for (i, f) in fields.iter().enumerate() {
            let v = parse_number(f, source, ln + 1, &cols[i])?;
            if i == tcol {
                t.push(v);
            } else if let Some((k, j)) = map[i] {
                data[k][row * dof + j - 1] = v;
            }
        }
    }
    if t.is_empty() {
        return Err(parse_err(source, 0, "", "no samples"));
    }
    let [d0, d1, d2, d3] = data;
    let opt = |k: usize, d: Vec<f64>| if present[k] { Some(d) } else { None };
    let table = SampleTable::new(dof, t, [opt(0, d0), opt(1, d1), opt(2, d2), opt(3, d3)])
        .map_err(|e| parse_err(source, 0, "", e.to_string()))?;
    match names {
        Some(n) => table.with_names(n),
        None => Ok(table),
    }
}

/// Per column: its (order, 1-based joint) or `None` (time, ignored); the joint count; the
/// joint names when the header names joints (`q_<name>` columns).
type ColumnMap = (Vec<Option<(usize, usize)>>, usize, Option<Vec<String>>);

/// Reads a table header (see the module docs): `q<k>` columns by index, `q_<name>` columns by
/// name (joint order: the order of the `q_` columns), or a foreign header whose non-time
/// columns are all positions.
fn classify_columns(
    raw: &[String],
    cols: &[String],
    tcol: usize,
    source: &str,
    line: usize,
) -> Result<ColumnMap> {
    let by_index = |c: &str| -> Option<(usize, usize)> {
        for (k, p) in PREFIX.iter().enumerate().rev() {
            if let Some(rest) = c.strip_prefix(p) {
                if let Ok(j) = rest.parse::<usize>() {
                    if j >= 1 {
                        return Some((k, j));
                    }
                }
            }
        }
        None
    };
    let by_name = |c: &str| -> Option<(usize, String)> {
        for (k, p) in PREFIX.iter().enumerate().rev() {
            if let Some(rest) = c.strip_prefix(p).and_then(|r| r.strip_prefix('_')) {
                if !rest.is_empty() {
                    return Some((k, rest.to_string()));
                }
            }
        }
        None
    };
    let idx: Vec<Option<(usize, usize)>> = cols
        .iter()
        .enumerate()
        .map(|(i, c)| if i == tcol { None } else { by_index(c) })
        .collect();
    let named: Vec<Option<(usize, String)>> = raw
        .iter()
        .enumerate()
        .map(|(i, c)| if i == tcol { None } else { by_name(c) })
        .collect();
    let has_index_q = idx.iter().any(|m| matches!(m, Some((0, _))));
    let has_named_q = named.iter().any(|m| matches!(m, Some((0, _))));
    match (has_index_q, has_named_q) {
        (true, true) => Err(parse_err(
            source,
            line,
            "",
            "header mixes q<k> and q_<name> position columns",
        )),
        (false, true) => named_columns(raw, &named, tcol, source, line),
        (has_index_q, false) => indexed_columns(idx, has_index_q, cols, tcol, source, line),
    }
}

/// The header's `q_<name>` columns: joints in the order of the position columns, derivative
/// columns paired by name.
fn named_columns(
    raw: &[String],
    named: &[Option<(usize, String)>],
    tcol: usize,
    source: &str,
    line: usize,
) -> Result<ColumnMap> {
    let names: Vec<String> = named
        .iter()
        .filter_map(|m| match m {
            Some((0, n)) => Some(n.clone()),
            _ => None,
        })
        .collect();
    if let Some(j) = (0..names.len()).find(|&j| names[..j].contains(&names[j])) {
        return Err(parse_err(
            source,
            line,
            format!("{}_{}", PREFIX[0], names[j]),
            "names a joint twice",
        ));
    }
    let mut map = vec![None; raw.len()];
    for (i, m) in named.iter().enumerate() {
        let Some((k, n)) = m else { continue };
        let j = names.iter().position(|x| x == n).ok_or_else(|| {
            parse_err(
                source,
                line,
                raw[i].as_str(),
                format!("joint '{n}' has no {}_{n} position column", PREFIX[0]),
            )
        })?;
        map[i] = Some((*k, j + 1));
    }
    if let Some(i) = (0..map.len()).find(|&i| i != tcol && map[i].is_none()) {
        return Err(parse_err(
            source,
            line,
            raw[i].as_str(),
            "is neither a q_/qd_/qdd_/qddd_<name> column nor the time",
        ));
    }
    let dof = names.len();
    Ok((map, dof, Some(names)))
}

/// The header's `q<k>` columns, or (without any) a foreign header read as positions.
fn indexed_columns(
    mut map: Vec<Option<(usize, usize)>>,
    has_index_q: bool,
    cols: &[String],
    tcol: usize,
    source: &str,
    line: usize,
) -> Result<ColumnMap> {
    if !has_index_q {
        // Foreign table: every non-time column is a position.
        let mut j = 0;
        for (i, m) in map.iter_mut().enumerate() {
            if i != tcol {
                j += 1;
                *m = Some((0, j));
            }
        }
    }
    let dof = map
        .iter()
        .filter_map(|m| *m)
        .filter(|(k, _)| *k == 0)
        .map(|(_, j)| j)
        .max()
        .unwrap_or(0);
    if dof == 0 {
        return Err(parse_err(
            source,
            line,
            "",
            "header has no position columns",
        ));
    }
    for (k, j) in map.iter().flatten() {
        if *j > dof {
            return Err(parse_err(
                source,
                line,
                &cols[0],
                format!("column {}{} beyond {dof} joints", PREFIX[*k], j),
            ));
        }
    }
    Ok((map, dof, None))
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
    for (k, key) in JSON_KEYS.iter().enumerate() {
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

/// Reads a sample table from a file, by extension (`.json` → JSON, else CSV).
pub fn table_from_file(path: &std::path::Path) -> Result<SampleTable> {
    let text = read_text(path)?;
    let src = path.display().to_string();
    if is_json(path) {
        table_from_json(&text, &src)
    } else {
        table_from_csv(&text, &src)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn waypoints_csv_with_and_without_header() {
        let w = Waypoints::from_csv("a,b\n# comment\n0,1\n\n2,3\n", "w.csv").unwrap();
        assert_eq!(w.dof(), 2);
        assert_eq!(w.len(), 2);
        assert_eq!(w.names(), ["a", "b"]);
        assert_eq!(w.point(1), [2.0, 3.0]);
        let w = Waypoints::from_csv("0;1;2\n3;4;5", "w.csv").unwrap();
        assert_eq!((w.dof(), w.len()), (3, 2));
        assert_eq!(w.names()[2], "q3");
    }

    #[test]
    fn waypoints_csv_errors_name_line_and_field() {
        let e = Waypoints::from_csv("a,b\n0,1\n2,x\n", "w.csv")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "w.csv:3 field 'b': 'x' is not a number");
        let e = Waypoints::from_csv("0,1\n2,nan\n", "w.csv")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "w.csv:2 field 'q2': NaN is not a finite number");
        let e = Waypoints::from_csv("0,1\n2,inf\n", "w.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("inf is not a finite number"), "{e}");
        let e = Waypoints::from_csv("0,1\n2,3,4\n", "w.csv")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "w.csv:2: 3 columns, expected 2");
        assert!(Waypoints::from_csv("", "w.csv").is_err());
        assert!(Waypoints::from_csv("a,b\n", "w.csv").is_err());
    }

    #[test]
    fn waypoints_json_both_shapes() {
        let w = Waypoints::from_json("[[0,1],[2,3.5]]", "w.json").unwrap();
        assert_eq!(w.point(1), [2.0, 3.5]);
        let w = Waypoints::from_json(
            r#"{"joint_names":["x","y"],"waypoints":[[0,1],[2,3]]}"#,
            "w.json",
        )
        .unwrap();
        assert_eq!(w.names(), ["x", "y"]);
        let e = Waypoints::from_json("[[0,1],[2]]", "w.json")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("waypoints[1]") && e.contains("1 values, expected 2"),
            "{e}"
        );
        let e = Waypoints::from_json("[[0,\"a\"]]", "w.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("waypoints[0][1]"), "{e}");
        let e = Waypoints::from_json("[[0,1]\n,", "w.json")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("w.json:2"), "{e}");
    }

    #[test]
    fn names_are_given_or_not_and_json_is_strict() {
        let w = Waypoints::from_csv("a,b\n0,1\n", "w.csv").unwrap();
        assert!(w.has_names());
        assert_eq!(w.given_names().unwrap(), ["a", "b"]);
        let w = Waypoints::from_csv("0,1\n2,3\n", "w.csv").unwrap();
        assert!(!w.has_names() && w.given_names().is_none());
        assert_eq!(w.names(), ["q1", "q2"]);
        let e = Waypoints::from_csv("a,a\n0,1\n", "w.csv").unwrap_err();
        assert!(e.to_string().contains("'a' (column 2)"), "{e}");
        let e = Waypoints::from_json(r#"{"waypionts": [[0, 1]]}"#, "w.json")
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "w.json field 'waypionts': unknown field (did you mean 'waypoints'? known: joint_names, waypoints)"
        );
        let e = Waypoints::from_json(r#"{"waypoints": [[0, 1]], "units": "deg"}"#, "w.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("'units': unknown field (known:"), "{e}");
    }

    /// Two joints, two samples, positions and velocities.
    fn small_table() -> SampleTable {
        SampleTable::new(
            2,
            vec![0.0, 0.5],
            [
                Some(vec![1.0, 2.0, 3.0, 4.0]),
                Some(vec![0.1, 0.2, 0.3, 0.4]),
                None,
                None,
            ],
        )
        .unwrap()
    }

    #[test]
    fn named_tables_round_trip() {
        let t = small_table()
            .with_names(vec!["elbow".into(), "wrist_1".into()])
            .unwrap();
        let csv = table_to_csv(&t);
        assert!(
            csv.starts_with("t,q_elbow,q_wrist_1,qd_elbow,qd_wrist_1\n"),
            "{csv}"
        );
        let back = table_from_csv(&csv, "n.csv").unwrap();
        assert_eq!(back, t);
        // Columns in any order are paired by name.
        let shuffled = "t,qd_wrist_1,q_elbow,qd_elbow,q_wrist_1\n0,0.2,1,0.1,2\n";
        let b = table_from_csv(shuffled, "s.csv").unwrap();
        assert_eq!(b.names(), ["elbow", "wrist_1"]);
        assert_eq!(b.row(Order::Velocity, 0).unwrap(), [0.1, 0.2]);
        for bad in [
            "t,q_a,qd_b\n0,1,2\n",
            "t,q_a,q_a\n0,1,2\n",
            "t,q_a,q2\n0,1,2\n",
            "t,q_a,x\n0,1,2\n",
        ] {
            assert!(table_from_csv(bad, "b.csv").is_err(), "{bad}");
        }
        // A name that cannot be a header: indices instead.
        let t = t.with_names(vec!["a,b".into(), "c".into()]).unwrap();
        assert!(table_to_csv(&t).starts_with("t,q1,q2,"));
    }

    #[test]
    fn dedup_removes_consecutive_repeats() {
        let mut w = Waypoints::new(
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0],
            2,
            vec![],
        )
        .unwrap();
        assert_eq!(w.dedup(0.0), 2);
        assert_eq!(w.len(), 3);
    }

    #[test]
    fn table_round_trips() {
        let t = small_table();
        let csv = table_to_csv(&t);
        assert!(csv.starts_with("t,q1,q2,qd1,qd2\n"));
        assert_eq!(table_from_csv(&csv, "x.csv").unwrap(), t);
        let json = table_to_json(&t);
        let back = table_from_json(&json, "x.json").unwrap();
        assert_eq!(back.times(), t.times());
        assert_eq!(back.row(Order::Velocity, 1), t.row(Order::Velocity, 1));
        // Foreign table: time + positions only, other names.
        let f = table_from_csv("time,j1,j2\n0,0,0\n0.1,0.01,0.02\n", "f.csv").unwrap();
        assert_eq!(f.dof(), 2);
        assert!(!f.has(Order::Velocity));
        let e = table_from_csv("t,q1\n0,0\n0.1,x\n", "f.csv")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "f.csv:3 field 'q1': 'x' is not a number");
        let e = table_from_csv("q1,q2\n0,0\n", "f.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("no 't'"), "{e}");
    }
}
