//! CSV: waypoints and sample tables (see the [parent module](super) for the format).

use super::{parse_err, Waypoints, PREFIX};
use crate::error::Result;
use crate::sample::SampleTable;
use crate::traj::Order;
use std::fmt::Write as _;

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
}

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
