//! URDF `<limit>` tags, see the [parent module](super).

use super::value::{file_error, in_file};
use crate::error::{Error, Location, Result};
use crate::limits::{Given, JointLimits, PartialLimits};

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
pub fn from_urdf_str(text: &str, source: &str) -> Result<PartialLimits> {
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
    let mut given: Vec<Given> = Vec::new();
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
        // A continuous joint has no range by definition: unbounded, stated by the file.
        let mut g = Given {
            position_min: continuous,
            position_max: continuous,
            ..Given::NONE
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
                    g.velocity = true;
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
                        g.position_min = true;
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
                        g.position_max = true;
                    }
                }
            }
        }
        joints.push(jl);
        given.push(g);
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
    PartialLimits::new(joints, given).map_err(|e| in_file(source, e))
}
