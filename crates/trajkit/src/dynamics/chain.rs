//! A [`SerialChain`] from a [`Robot`]: the chain from the root link, fixed joints merged into
//! the body before them. See the [module documentation](super) for what is read and refused.

use super::spatial::{dot, rpy_matrix, scale, Frame, Inertial, ZERO3};
use super::{Body, SerialChain, MAX_JOINTS};
use crate::error::Result;
use crate::urdf::{Joint, JointType, Link, Pose, Robot};

/// What the chain needs of a joint type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Fixed,
    Revolute,
    Prismatic,
}

/// A joint of the chain with its links' names.
struct ChainJoint<'a> {
    joint: &'a Joint,
    name: &'a str,
    kind: Kind,
    parent: &'a str,
    child: &'a str,
}

/// The links by name (names checked, no duplicates), in document order.
type Links<'a> = Vec<(&'a str, &'a Link)>;

/// Reads the chain (see the module documentation for the errors).
pub(super) fn from_robot(robot: &Robot) -> Result<SerialChain> {
    let links = named_links(robot)?;
    let (joints, file_order) = chain_joints(robot, &links)?;
    if file_order.is_empty() {
        return Err(robot.error(
            "",
            "the URDF has no movable joint (revolute, continuous or prismatic)",
        ));
    }
    let root_link = root_link(robot, &links, &joints)?;
    let bodies = walk(robot, &links, &joints, root_link)?;
    let chain: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
    if chain != file_order {
        let missing = file_order.iter().find(|n| !chain.contains(n));
        let message = match missing {
            Some(m) => format!(
                "the movable joint '{m}' is not on the chain from the root link \
                 '{root_link}': not a serial chain"
            ),
            None => format!(
                "the joints' order along the chain ({}) differs from their order in the file \
                 ({}), which is the order of the limits: reorder the <joint> elements",
                chain.join(", "),
                file_order.join(", ")
            ),
        };
        return Err(robot.error("", message));
    }
    Ok(SerialChain {
        bodies,
        gravity: [0.0, 0.0, -9.81],
    })
}

fn named_links(robot: &Robot) -> Result<Links<'_>> {
    let mut links: Links<'_> = Vec::new();
    for link in robot.links() {
        let name = link.name()?;
        if links.iter().any(|(n, _)| *n == name) {
            return Err(link.error(
                format!("link '{name}'"),
                "a link of this name appears earlier in the file",
            ));
        }
        links.push((name, link));
    }
    Ok(links)
}

/// Every joint with its links (checked to exist, each link the child of one joint at most),
/// and the movable joints' names in file order.
fn chain_joints<'a>(
    robot: &'a Robot,
    links: &Links<'a>,
) -> Result<(Vec<ChainJoint<'a>>, Vec<&'a str>)> {
    let mut joints: Vec<ChainJoint<'a>> = Vec::new();
    let mut file_order: Vec<&str> = Vec::new();
    for joint in robot.joints() {
        let name = joint.name()?;
        let kind = match joint.joint_type()? {
            JointType::Revolute | JointType::Continuous => Kind::Revolute,
            JointType::Prismatic => Kind::Prismatic,
            JointType::Fixed => Kind::Fixed,
            other @ (JointType::Floating | JointType::Planar) => {
                let other = if other == JointType::Floating {
                    "floating"
                } else {
                    "planar"
                };
                return Err(joint.error(
                    format!("joint '{name}' type"),
                    format!(
                        "'{other}' joints are not supported by the dynamics model \
                         (revolute, continuous, prismatic, fixed)"
                    ),
                ));
            }
        };
        if kind != Kind::Fixed && joint.is_mimic() {
            return Err(joint.error(
                format!("joint '{name}' <mimic>"),
                "mimic joints are not supported by the dynamics model",
            ));
        }
        let (parent, child) = (joint.parent()?, joint.child()?);
        for l in [parent, child] {
            if !links.iter().any(|(n, _)| *n == l) {
                return Err(joint.error(
                    format!("joint '{name}'"),
                    format!("the link '{l}' is not defined in the file"),
                ));
            }
        }
        if let Some(other) = joints.iter().find(|j| j.child == child) {
            return Err(joint.error(
                format!("joint '{name}' <child link>"),
                format!(
                    "the link '{child}' is already the child of joint '{}'",
                    other.name
                ),
            ));
        }
        if kind != Kind::Fixed {
            file_order.push(name);
        }
        joints.push(ChainJoint {
            joint,
            name,
            kind,
            parent,
            child,
        });
    }
    Ok((joints, file_order))
}

/// The one link that is no joint's child.
fn root_link<'a>(robot: &Robot, links: &Links<'a>, joints: &[ChainJoint<'a>]) -> Result<&'a str> {
    let roots: Vec<&(&str, &Link)> = links
        .iter()
        .filter(|(n, _)| !joints.iter().any(|j| j.child == *n))
        .collect();
    match roots.as_slice() {
        [one] => Ok(one.0),
        [] => Err(robot.error(
            "",
            "every link is some joint's child: the joints form a cycle",
        )),
        [(a, _), (b, link), ..] => Err(link.error(
            format!("link '{b}'"),
            format!("links '{a}' and '{b}' both have no parent joint: not a serial chain"),
        )),
    }
}

/// The bodies along the chain from `root_link`: one per movable joint, the links after fixed
/// joints merged into the body before them (into the fixed base before the first).
fn walk(
    robot: &Robot,
    links: &Links<'_>,
    joints: &[ChainJoint<'_>],
    root_link: &str,
) -> Result<Vec<Body>> {
    let link = |name: &str| links.iter().find(|(n, _)| *n == name).map(|(_, l)| *l);
    let mut bodies: Vec<Body> = Vec::new();
    let mut current = root_link;
    // The current link's frame in the last body's frame (the root's before the first).
    let mut acc = Frame::IDENTITY;
    for _ in 0..=joints.len() {
        let kids: Vec<&ChainJoint<'_>> = joints.iter().filter(|j| j.parent == current).collect();
        let j = match kids.as_slice() {
            [] => break,
            [j] => *j,
            [a, b, ..] => {
                let field = format!("link '{current}'");
                let message = format!(
                    "the link has more than one child joint ('{}', '{}'): not a serial chain",
                    a.name, b.name
                );
                return Err(match link(current) {
                    Some(l) => l.error(field, message),
                    None => robot.error(field, message),
                });
            }
        };
        let owner = format!("joint '{}'", j.name);
        let frame = acc.then(&frame_of(&j.joint.origin()?));
        let child_inertial = match link(j.child) {
            Some(l) => inertial_of(l)?,
            None => Inertial::ZERO,
        };
        if j.kind == Kind::Fixed {
            acc = frame;
            if let Some(b) = bodies.last_mut() {
                b.inertial = b.inertial.merged(&child_inertial.transformed(&acc));
            }
        } else {
            if bodies.len() == MAX_JOINTS {
                return Err(j.joint.error(
                    owner,
                    format!(
                        "the chain has more than {MAX_JOINTS} movable joints, the most the \
                         dynamics model supports"
                    ),
                ));
            }
            let axis = j.joint.axis()?.unwrap_or([1.0, 0.0, 0.0]);
            let norm = dot(axis, axis).sqrt();
            if norm == 0.0 {
                return Err(j
                    .joint
                    .axis_error(format!("{owner} <axis xyz>"), "'0 0 0' is not a direction"));
            }
            bodies.push(Body {
                name: j.name.to_string(),
                prismatic: j.kind == Kind::Prismatic,
                origin: frame,
                axis: scale(axis, 1.0 / norm),
                inertial: child_inertial,
            });
            acc = Frame::IDENTITY;
        }
        current = j.child;
    }
    Ok(bodies)
}

fn frame_of(p: &Pose) -> Frame {
    Frame {
        rot: rpy_matrix(p.rpy),
        pos: p.xyz,
    }
}

/// A link's inertia in the link frame (zero when it has no `<inertial>`).
fn inertial_of(link: &Link) -> Result<Inertial> {
    let Some(i) = link.inertial()? else {
        return Ok(Inertial::ZERO);
    };
    let [ixx, ixy, ixz, iyy, iyz, izz] = i.inertia;
    let local = Inertial {
        mass: i.mass,
        com: ZERO3,
        inertia: [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]],
    };
    Ok(local.transformed(&frame_of(&i.origin)))
}
