//! URDF `<limit>` tags, see the [parent module](super); the file is read by [`crate::urdf`].

use super::in_file;
use crate::error::Result;
use crate::limits::{Given, JointLimits, PartialLimits};
use crate::urdf::{Joint, JointType, Robot};

/// Reads the limits of the movable joints of a URDF (see the module documentation).
pub fn from_urdf_str(text: &str, source: &str) -> Result<PartialLimits> {
    from_urdf(&Robot::parse(text, source)?)
}

/// The limits of the movable joints of a robot read by [`Robot::parse`] (see the module
/// documentation), for a caller that also reads its dynamics from the same file.
pub fn from_urdf(robot: &Robot) -> Result<PartialLimits> {
    let mut joints: Vec<JointLimits> = Vec::new();
    let mut given: Vec<Given> = Vec::new();
    for joint in robot.joints() {
        let name = joint.name()?;
        let kind = joint.joint_type()?;
        if !kind.is_movable() || joint.is_mimic() {
            continue;
        }
        if joints.iter().any(|j| j.name == name) {
            return Err(joint.error(
                format!("joint '{name}'"),
                "a joint of this name appears earlier in the file",
            ));
        }
        let (jl, g) = joint_limits(joint, name, kind)?;
        joints.push(jl);
        given.push(g);
    }
    if joints.is_empty() {
        let hint = if robot.mentions_xacro() {
            " (it looks like an unexpanded xacro file: run xacro on it first)"
        } else {
            ""
        };
        return Err(robot.file_error(
            "",
            format!(
                "the URDF has no movable joint (revolute, prismatic or continuous, not mimic){hint}"
            ),
        ));
    }
    PartialLimits::new(joints, given).map_err(|e| in_file(robot.source(), e))
}

/// The limits one movable joint's `<limit>` gives, and which of them it gives.
fn joint_limits(joint: &Joint, name: &str, kind: JointType) -> Result<(JointLimits, Given)> {
    let continuous = kind == JointType::Continuous;
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
    if !joint.has_limit() {
        if continuous {
            return Ok((jl, g));
        }
        let kind = if kind == JointType::Revolute {
            "revolute"
        } else {
            "prismatic"
        };
        return Err(joint.error(
            format!("joint '{name}' <limit>"),
            format!("a {kind} joint needs a <limit> element"),
        ));
    }
    let bad = |line: usize, attr: &str, message: String| {
        joint.error_at(line, format!("joint '{name}' <limit {attr}>"), message)
    };
    if let Some((v, line)) = joint.limit_value("velocity")? {
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
    if let Some((e, line)) = joint.limit_value("effort")? {
        if e < 0.0 {
            return Err(bad(line, "effort", format!("{e} is negative")));
        }
        jl.effort = (e > 0.0).then_some(e);
    }
    if !continuous {
        if let Some((lo, _)) = joint.limit_value("lower")? {
            jl.position_min = lo;
            g.position_min = true;
        }
        if let Some((hi, line)) = joint.limit_value("upper")? {
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
    Ok((jl, g))
}
