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

mod csv;
#[cfg(feature = "serde")]
mod json;
#[cfg(test)]
mod tests;

pub use csv::{table_from_csv, table_to_csv};
#[cfg(feature = "serde")]
pub use json::{table_from_json, table_to_json};

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

pub(crate) fn parse_err(
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

    /// Reads a file, choosing the format by extension (`.json` → JSON, anything else → CSV).
    pub fn from_file(path: &std::path::Path) -> Result<Self> {
        let text = read_text(path)?;
        let src = path.display().to_string();
        if !is_json(path) {
            return Waypoints::from_csv(&text, &src);
        }
        #[cfg(feature = "serde")]
        return Waypoints::from_json(&text, &src);
        #[cfg(not(feature = "serde"))]
        return Err(no_json(&src));
    }
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

/// Column prefixes (CSV) and keys (JSON) of positions, velocities, accelerations and jerks.
const PREFIX: [&str; 4] = ["q", "qd", "qdd", "qddd"];

/// Reads a sample table from a file, by extension (`.json` → JSON, else CSV).
pub fn table_from_file(path: &std::path::Path) -> Result<SampleTable> {
    let text = read_text(path)?;
    let src = path.display().to_string();
    if !is_json(path) {
        return table_from_csv(&text, &src);
    }
    #[cfg(feature = "serde")]
    return table_from_json(&text, &src);
    #[cfg(not(feature = "serde"))]
    return Err(no_json(&src));
}

/// The error for a JSON file in a build without the `serde` feature.
#[cfg(not(feature = "serde"))]
fn no_json(source: &str) -> Error {
    parse_err(
        source,
        0,
        "",
        "reading JSON needs trajkit's `serde` feature, which this build leaves out",
    )
}
