//! Rigid-body inverse dynamics of a serial chain read from a URDF.
//!
//! [`SerialChain`] reads the kinematic chain and the inertial parameters of a robot from a URDF
//! and computes joint torques τ = M(q)q̈ + C(q, q̇)q̇ + g(q) by the recursive Newton–Euler
//! algorithm. It implements [`InverseDynamics`], so it plugs into
//! [`JointTorque`](crate::topp::JointTorque) for torque-limited TOPP-RA.
//!
//! # What is read
//! - The chain: starting at the root link (the one link that is no joint's child), each link
//!   may have at most one child joint; a link with two is refused as "not a serial chain".
//!   Joints of type `revolute`, `continuous` and `prismatic` are the model's joints; `fixed`
//!   joints merge their child link rigidly into the body before them (links fixed to the root
//!   before the first movable joint are part of the fixed base and carry no torque).
//! - Per joint: `<origin xyz rpy>` (default zero), `<axis xyz>` (default `1 0 0`, normalized).
//! - Per link: `<inertial>` with `<origin xyz rpy>`, `<mass value>` and
//!   `<inertia ixx ixy ixz iyy iyz izz>` about the centre of mass in the inertial frame. A link
//!   without `<inertial>` is massless.
//! - Gravity is (0, 0, −9.81) m/s² in the root link's frame unless set with
//!   [`SerialChain::with_gravity`].
//!
//! The joint order is the order of the movable joints along the chain, which must equal their
//! order in the file, because that is the order [`crate::limits::load::from_urdf_str`] gives the
//! joints' limits. Mimic, floating and planar joints are refused, as are more than
//! [`MAX_JOINTS`] joints.
//!
//! Bad input gives [`Error::Parse`] naming the file, the line, the field and the value.
//!
//! # Precision contract
//! The Newton–Euler recursion is exact in exact arithmetic: the only error is floating-point
//! rounding, a few ulps per joint of the largest torque term (well below 1e-12 relative for
//! chains of realistic size). The result is as exact as the URDF's inertial parameters; they
//! are used as given (no physical-consistency check of the inertia tensor beyond finiteness and
//! a mass ≥ 0). [`InverseDynamics::torque`] does not allocate.

use crate::error::{Error, Location, Result};
use crate::limits::load::line_of;
use crate::topp::InverseDynamics;

/// The largest number of movable joints a [`SerialChain`] holds.
pub const MAX_JOINTS: usize = 32;

type Vec3 = [f64; 3];
/// Row-major 3 × 3 matrix.
type Mat3 = [[f64; 3]; 3];

const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
const ZERO3: Vec3 = [0.0; 3];

fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: Vec3, k: f64) -> Vec3 {
    [a[0] * k, a[1] * k, a[2] * k]
}
fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
/// m · v.
fn mul(m: &Mat3, v: Vec3) -> Vec3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}
/// mᵀ · v.
fn mul_t(m: &Mat3, v: Vec3) -> Vec3 {
    [
        m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2],
        m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
        m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2],
    ]
}
fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut out = [[0.0; 3]; 3];
    for (r, row) in out.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
        }
    }
    out
}
fn transpose(a: &Mat3) -> Mat3 {
    let mut out = [[0.0; 3]; 3];
    for (r, row) in out.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = a[c][r];
        }
    }
    out
}

/// URDF roll-pitch-yaw: R = Rz(yaw)·Ry(pitch)·Rx(roll).
fn rpy_matrix(rpy: Vec3) -> Mat3 {
    let (sr, cr) = rpy[0].sin_cos();
    let (sp, cp) = rpy[1].sin_cos();
    let (sy, cy) = rpy[2].sin_cos();
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

/// Rotation by `angle` about the unit vector `u` (Rodrigues).
fn axis_rotation(u: Vec3, angle: f64) -> Mat3 {
    let (s, c) = angle.sin_cos();
    let v = 1.0 - c;
    [
        [
            c + u[0] * u[0] * v,
            u[0] * u[1] * v - u[2] * s,
            u[0] * u[2] * v + u[1] * s,
        ],
        [
            u[1] * u[0] * v + u[2] * s,
            c + u[1] * u[1] * v,
            u[1] * u[2] * v - u[0] * s,
        ],
        [
            u[2] * u[0] * v - u[1] * s,
            u[2] * u[1] * v + u[0] * s,
            c + u[2] * u[2] * v,
        ],
    ]
}

/// A rigid transform: a frame's orientation and origin in its parent frame.
#[derive(Debug, Clone, Copy)]
struct Frame {
    rot: Mat3,
    pos: Vec3,
}

impl Frame {
    const IDENTITY: Frame = Frame {
        rot: IDENTITY,
        pos: ZERO3,
    };
    /// `self` followed by `child` (child given in `self`'s frame).
    fn then(&self, child: &Frame) -> Frame {
        Frame {
            rot: mat_mul(&self.rot, &child.rot),
            pos: add(self.pos, mul(&self.rot, child.pos)),
        }
    }
}

/// Mass, centre of mass and inertia about the centre of mass, in one frame.
#[derive(Debug, Clone, Copy)]
struct Inertial {
    mass: f64,
    com: Vec3,
    inertia: Mat3,
}

impl Inertial {
    const ZERO: Inertial = Inertial {
        mass: 0.0,
        com: ZERO3,
        inertia: [[0.0; 3]; 3],
    };

    /// `self` expressed in the parent frame of `f` (self given in `f`'s frame).
    fn transformed(&self, f: &Frame) -> Inertial {
        Inertial {
            mass: self.mass,
            com: add(f.pos, mul(&f.rot, self.com)),
            inertia: mat_mul(&mat_mul(&f.rot, &self.inertia), &transpose(&f.rot)),
        }
    }

    /// The rigid union of two bodies given in the same frame.
    fn merged(&self, other: &Inertial) -> Inertial {
        let mass = self.mass + other.mass;
        if mass == 0.0 {
            let mut inertia = self.inertia;
            for (r, row) in inertia.iter_mut().enumerate() {
                for (c, x) in row.iter_mut().enumerate() {
                    *x += other.inertia[r][c];
                }
            }
            return Inertial {
                mass,
                com: ZERO3,
                inertia,
            };
        }
        let com = scale(
            add(scale(self.com, self.mass), scale(other.com, other.mass)),
            1.0 / mass,
        );
        let mut inertia = [[0.0; 3]; 3];
        for b in [self, other] {
            let d = sub(b.com, com);
            let dd = dot(d, d);
            for (r, row) in inertia.iter_mut().enumerate() {
                for (c, x) in row.iter_mut().enumerate() {
                    let delta = if r == c { dd } else { 0.0 };
                    *x += b.inertia[r][c] + b.mass * (delta - d[r] * d[c]);
                }
            }
        }
        Inertial { mass, com, inertia }
    }
}

/// One movable joint and the rigid body it moves.
#[derive(Debug, Clone)]
struct Body {
    name: String,
    prismatic: bool,
    /// The joint frame (at q = 0) in the previous body's frame (the root link's for the first).
    origin: Frame,
    /// Unit joint axis in the joint frame.
    axis: Vec3,
    /// The body's inertia in its own frame (the joint frame moved by q).
    inertial: Inertial,
}

/// A serial chain of rigid bodies read from a URDF, with its inverse dynamics. See the module
/// documentation.
///
/// ```
/// use trajkit::dynamics::SerialChain;
/// use trajkit::topp::InverseDynamics;
/// let urdf = r#"<robot name="pendulum">
///   <link name="base"/>
///   <link name="arm"><inertial><origin xyz="0.5 0 0"/><mass value="2"/>
///     <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
///   <joint name="hinge" type="continuous"><parent link="base"/><child link="arm"/>
///     <axis xyz="0 1 0"/></joint>
/// </robot>"#;
/// let chain = SerialChain::from_urdf_str(urdf, "pendulum.urdf")?;
/// let mut tau = [0.0];
/// chain.torque(&[0.0], &[0.0], &[0.0], &mut tau);
/// // Holding the arm horizontal: gravity pulls it towards −z, i.e. positive about y.
/// assert!((tau[0] + 2.0 * 9.81 * 0.5).abs() < 1e-12);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct SerialChain {
    bodies: Vec<Body>,
    gravity: Vec3,
}

/// Reads attributes of one URDF document, with errors located in it.
struct Reader<'a, 'input> {
    doc: &'a roxmltree::Document<'input>,
    source: &'a str,
}

impl<'a, 'input> Reader<'a, 'input> {
    fn error_at(&self, pos: usize, field: String, message: String) -> Error {
        Error::Parse {
            location: Location {
                source: self.source.to_string(),
                line: line_of(self.doc, pos),
                field,
            },
            message,
        }
    }

    fn node_error(&self, node: roxmltree::Node<'_, '_>, field: String, message: String) -> Error {
        self.error_at(node.range().start, field, message)
    }

    /// A whitespace-separated list of `N` finite numbers; `None` when the attribute is absent.
    fn numbers<const N: usize>(
        &self,
        node: roxmltree::Node<'_, '_>,
        attr: &str,
        field: impl Fn() -> String,
    ) -> Result<Option<[f64; N]>> {
        let Some(a) = node.attribute_node(attr) else {
            return Ok(None);
        };
        let raw = a.value();
        let pos = a.range_value().start;
        let mut out = [0.0; N];
        let mut count = 0;
        for word in raw.split_whitespace() {
            let quoted = if raw.trim() == word {
                format!("'{word}'")
            } else {
                format!("'{word}' in '{raw}'")
            };
            let x: f64 = word
                .parse()
                .map_err(|_| self.error_at(pos, field(), format!("{quoted} is not a number")))?;
            if !x.is_finite() {
                return Err(self.error_at(
                    pos,
                    field(),
                    format!("{quoted} is not a finite number"),
                ));
            }
            if count < N {
                out[count] = x;
            }
            count += 1;
        }
        if count != N {
            return Err(self.error_at(
                pos,
                field(),
                format!("'{raw}' has {count} numbers, expected {N}"),
            ));
        }
        Ok(Some(out))
    }

    /// A required single finite number.
    fn number(&self, node: roxmltree::Node<'_, '_>, attr: &str, field: String) -> Result<f64> {
        match self.numbers::<1>(node, attr, || field.clone())? {
            Some([x]) => Ok(x),
            None => Err(self.node_error(
                node,
                field.clone(),
                format!("the attribute '{attr}' is missing"),
            )),
        }
    }

    /// `<origin xyz rpy>` of `node` (identity when absent).
    fn origin(&self, node: roxmltree::Node<'_, '_>, owner: &str) -> Result<Frame> {
        let Some(o) = child(node, "origin") else {
            return Ok(Frame::IDENTITY);
        };
        let xyz = self
            .numbers::<3>(o, "xyz", || format!("{owner} <origin xyz>"))?
            .unwrap_or(ZERO3);
        let rpy = self
            .numbers::<3>(o, "rpy", || format!("{owner} <origin rpy>"))?
            .unwrap_or(ZERO3);
        Ok(Frame {
            rot: rpy_matrix(rpy),
            pos: xyz,
        })
    }

    /// A link's `<inertial>` in the link frame (zero when absent).
    fn inertial(&self, link: roxmltree::Node<'_, '_>, name: &str) -> Result<Inertial> {
        let Some(node) = child(link, "inertial") else {
            return Ok(Inertial::ZERO);
        };
        let owner = format!("link '{name}'");
        let frame = self.origin(node, &owner)?;
        let Some(m) = child(node, "mass") else {
            return Err(self.node_error(
                node,
                format!("{owner} <mass>"),
                "the <inertial> element has no <mass>".into(),
            ));
        };
        let mass = self.number(m, "value", format!("{owner} <mass value>"))?;
        if mass < 0.0 {
            return Err(self.node_error(
                m,
                format!("{owner} <mass value>"),
                format!("{mass} is negative"),
            ));
        }
        let Some(i) = child(node, "inertia") else {
            return Err(self.node_error(
                node,
                format!("{owner} <inertia>"),
                "the <inertial> element has no <inertia>".into(),
            ));
        };
        let mut v = [0.0; 6];
        for (k, attr) in ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]
            .iter()
            .enumerate()
        {
            v[k] = self.number(i, attr, format!("{owner} <inertia {attr}>"))?;
        }
        let [ixx, ixy, ixz, iyy, iyz, izz] = v;
        let local = Inertial {
            mass,
            com: ZERO3,
            inertia: [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]],
        };
        Ok(local.transformed(&frame))
    }
}

fn child<'a, 'input>(
    node: roxmltree::Node<'a, 'input>,
    tag: &str,
) -> Option<roxmltree::Node<'a, 'input>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == tag)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Fixed,
    Revolute,
    Prismatic,
}

struct RawJoint<'a, 'input> {
    node: roxmltree::Node<'a, 'input>,
    name: &'a str,
    kind: Kind,
    parent: &'a str,
    child: &'a str,
}

impl SerialChain {
    /// Reads a serial chain from URDF text; `source` names it in errors (a file name).
    ///
    /// Errors: [`Error::Parse`] with file, line, field and value for malformed XML, missing or
    /// non-finite numbers, a missing `<mass>`, unknown or unsupported joint types, a branching
    /// tree, no movable joint, more than [`MAX_JOINTS`] joints, or a chain order that differs
    /// from the file order of the movable joints.
    pub fn from_urdf_str(text: &str, source: &str) -> Result<Self> {
        let doc = roxmltree::Document::parse(text).map_err(|e| Error::Parse {
            location: Location {
                source: source.to_string(),
                line: e.pos().row as usize,
                field: String::new(),
            },
            message: format!("not well-formed XML: {e}"),
        })?;
        let rd = Reader { doc: &doc, source };
        let root = doc.root_element();
        if root.tag_name().name() != "robot" {
            return Err(rd.node_error(
                root,
                String::new(),
                format!(
                    "the root element is <{}>, a URDF's is <robot>",
                    root.tag_name().name()
                ),
            ));
        }
        let elements = |tag: &'static str| {
            root.children()
                .filter(move |n| n.is_element() && n.tag_name().name() == tag)
        };
        let mut links: Vec<(&str, roxmltree::Node<'_, '_>)> = Vec::new();
        for node in elements("link") {
            let Some(name) = node.attribute("name") else {
                return Err(rd.node_error(
                    node,
                    "<link name>".into(),
                    "the link has no name attribute".into(),
                ));
            };
            if links.iter().any(|(n, _)| *n == name) {
                return Err(rd.node_error(
                    node,
                    format!("link '{name}'"),
                    "a link of this name appears earlier in the file".into(),
                ));
            }
            links.push((name, node));
        }
        let mut joints: Vec<RawJoint<'_, '_>> = Vec::new();
        let mut file_order: Vec<&str> = Vec::new();
        for node in elements("joint") {
            let Some(name) = node.attribute("name") else {
                return Err(rd.node_error(
                    node,
                    "<joint name>".into(),
                    "the joint has no name attribute".into(),
                ));
            };
            let kind = match node.attribute("type").unwrap_or("") {
                "revolute" | "continuous" => Kind::Revolute,
                "prismatic" => Kind::Prismatic,
                "fixed" => Kind::Fixed,
                other @ ("floating" | "planar") => {
                    return Err(rd.node_error(
                        node,
                        format!("joint '{name}' type"),
                        format!(
                            "'{other}' joints are not supported by the dynamics model \
                             (revolute, continuous, prismatic, fixed)"
                        ),
                    ))
                }
                other => {
                    return Err(rd.node_error(
                        node,
                        format!("joint '{name}' type"),
                        format!(
                            "'{other}' is not a URDF joint type (revolute, continuous, \
                             prismatic, fixed, floating, planar)"
                        ),
                    ))
                }
            };
            if kind != Kind::Fixed && child(node, "mimic").is_some() {
                return Err(rd.node_error(
                    node,
                    format!("joint '{name}' <mimic>"),
                    "mimic joints are not supported by the dynamics model".into(),
                ));
            }
            let link_of = |tag: &str| -> Result<&str> {
                child(node, tag)
                    .and_then(|c| c.attribute("link"))
                    .ok_or_else(|| {
                        rd.node_error(
                            node,
                            format!("joint '{name}' <{tag} link>"),
                            format!("the joint has no <{tag} link=...>"),
                        )
                    })
            };
            let (parent, child_link) = (link_of("parent")?, link_of("child")?);
            for l in [parent, child_link] {
                if !links.iter().any(|(n, _)| *n == l) {
                    return Err(rd.node_error(
                        node,
                        format!("joint '{name}'"),
                        format!("the link '{l}' is not defined in the file"),
                    ));
                }
            }
            if let Some(other) = joints.iter().find(|j| j.child == child_link) {
                return Err(rd.node_error(
                    node,
                    format!("joint '{name}' <child link>"),
                    format!(
                        "the link '{child_link}' is already the child of joint '{}'",
                        other.name
                    ),
                ));
            }
            if kind != Kind::Fixed {
                file_order.push(name);
            }
            joints.push(RawJoint {
                node,
                name,
                kind,
                parent,
                child: child_link,
            });
        }
        if file_order.is_empty() {
            return Err(rd.node_error(
                root,
                String::new(),
                "the URDF has no movable joint (revolute, continuous or prismatic)".into(),
            ));
        }
        let roots: Vec<&str> = links
            .iter()
            .map(|(n, _)| *n)
            .filter(|n| !joints.iter().any(|j| j.child == *n))
            .collect();
        let root_link = match roots.as_slice() {
            [one] => *one,
            [] => {
                return Err(rd.node_error(
                    root,
                    String::new(),
                    "every link is some joint's child: the joints form a cycle".into(),
                ))
            }
            [a, b, ..] => {
                let node = links.iter().find(|(n, _)| n == b).map(|(_, n)| *n);
                return Err(rd.node_error(
                    node.unwrap_or(root),
                    format!("link '{b}'"),
                    format!("links '{a}' and '{b}' both have no parent joint: not a serial chain"),
                ));
            }
        };
        let link_node = |name: &str| {
            links
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, node)| *node)
                .unwrap_or(root)
        };
        // Walk the chain from the root.
        let mut bodies: Vec<Body> = Vec::new();
        let mut current = root_link;
        // The current link's frame in the last body's frame (the root's before the first).
        let mut acc = Frame::IDENTITY;
        for _ in 0..=joints.len() {
            let kids: Vec<&RawJoint<'_, '_>> =
                joints.iter().filter(|j| j.parent == current).collect();
            let j = match kids.as_slice() {
                [] => break,
                [j] => *j,
                [a, b, ..] => {
                    return Err(rd.node_error(
                        link_node(current),
                        format!("link '{current}'"),
                        format!(
                            "the link has more than one child joint ('{}', '{}'): not a serial \
                             chain",
                            a.name, b.name
                        ),
                    ))
                }
            };
            let owner = format!("joint '{}'", j.name);
            let frame = acc.then(&rd.origin(j.node, &owner)?);
            let child_inertial = rd.inertial(link_node(j.child), j.child)?;
            if j.kind == Kind::Fixed {
                acc = frame;
                if let Some(b) = bodies.last_mut() {
                    b.inertial = b.inertial.merged(&child_inertial.transformed(&acc));
                }
            } else {
                if bodies.len() == MAX_JOINTS {
                    return Err(rd.node_error(
                        j.node,
                        owner,
                        format!(
                            "the chain has more than {MAX_JOINTS} movable joints, the most the \
                             dynamics model supports"
                        ),
                    ));
                }
                let axis = match child(j.node, "axis") {
                    None => [1.0, 0.0, 0.0],
                    Some(a) => rd
                        .numbers::<3>(a, "xyz", || format!("{owner} <axis xyz>"))?
                        .unwrap_or([1.0, 0.0, 0.0]),
                };
                let norm = dot(axis, axis).sqrt();
                if norm == 0.0 {
                    let a = child(j.node, "axis").unwrap_or(j.node);
                    return Err(rd.node_error(
                        a,
                        format!("{owner} <axis xyz>"),
                        "'0 0 0' is not a direction".into(),
                    ));
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
            return Err(rd.node_error(root, String::new(), message));
        }
        Ok(SerialChain {
            bodies,
            gravity: [0.0, 0.0, -9.81],
        })
    }

    /// Reads a serial chain from a URDF file.
    ///
    /// Errors: [`Error::Io`] naming the path when it cannot be read; otherwise as
    /// [`SerialChain::from_urdf_str`].
    pub fn from_urdf_file(path: &std::path::Path) -> Result<Self> {
        let source = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
            path: source.clone(),
            message: e.to_string(),
        })?;
        Self::from_urdf_str(&text, &source)
    }

    /// The same chain with gravity `g` (m/s², in the root link's frame).
    ///
    /// Errors: [`Error::InvalidValue`] for a non-finite component.
    pub fn with_gravity(mut self, g: [f64; 3]) -> Result<Self> {
        for (k, &x) in g.iter().enumerate() {
            crate::error::finite(|| format!("gravity component {}", ["x", "y", "z"][k]), x)?;
        }
        self.gravity = g;
        Ok(self)
    }

    /// Gravity in the root link's frame.
    pub fn gravity(&self) -> [f64; 3] {
        self.gravity
    }

    /// The movable joints' names, in joint order.
    pub fn joint_names(&self) -> Vec<&str> {
        self.bodies.iter().map(|b| b.name.as_str()).collect()
    }

    /// The total mass of the moving bodies (links fixed to the root excluded).
    pub fn moving_mass(&self) -> f64 {
        self.bodies.iter().map(|b| b.inertial.mass).sum()
    }
}

impl InverseDynamics for SerialChain {
    fn dof(&self) -> usize {
        self.bodies.len()
    }

    /// Recursive Newton–Euler. Slices of a length other than `dof()` give NaN torques (written
    /// into as much of `tau` as exists).
    fn torque(&self, q: &[f64], qd: &[f64], qdd: &[f64], tau: &mut [f64]) {
        let n = self.bodies.len();
        if q.len() != n || qd.len() != n || qdd.len() != n || tau.len() != n || n > MAX_JOINTS {
            tau.fill(f64::NAN);
            return;
        }
        // Per body: orientation in the previous body's frame, origin there, angular velocity,
        // angular acceleration and origin acceleration (gravity included) in the body's frame.
        let mut rot = [IDENTITY; MAX_JOINTS];
        let mut org = [ZERO3; MAX_JOINTS];
        let mut w = [ZERO3; MAX_JOINTS];
        let mut wd = [ZERO3; MAX_JOINTS];
        let mut acc = [ZERO3; MAX_JOINTS];
        let (mut wp, mut wdp, mut ap) = (ZERO3, ZERO3, scale(self.gravity, -1.0));
        for (i, b) in self.bodies.iter().enumerate() {
            let u = b.axis;
            let (r, p) = if b.prismatic {
                (
                    b.origin.rot,
                    add(b.origin.pos, mul(&b.origin.rot, scale(u, q[i]))),
                )
            } else {
                (
                    mat_mul(&b.origin.rot, &axis_rotation(u, q[i])),
                    b.origin.pos,
                )
            };
            let a_origin = add(add(ap, cross(wdp, p)), cross(wp, cross(wp, p)));
            let wi = mul_t(&r, wp);
            let wdi = mul_t(&r, wdp);
            let ai = mul_t(&r, a_origin);
            if b.prismatic {
                w[i] = wi;
                wd[i] = wdi;
                acc[i] = add(add(ai, scale(cross(wi, u), 2.0 * qd[i])), scale(u, qdd[i]));
            } else {
                w[i] = add(wi, scale(u, qd[i]));
                wd[i] = add(add(wdi, scale(u, qdd[i])), scale(cross(wi, u), qd[i]));
                acc[i] = ai;
            }
            rot[i] = r;
            org[i] = p;
            (wp, wdp, ap) = (w[i], wd[i], acc[i]);
        }
        // Force and moment (about the body origin) exerted on body i+1 by body i, in i+1's frame.
        let (mut f_next, mut n_next) = (ZERO3, ZERO3);
        for i in (0..n).rev() {
            let b = &self.bodies[i];
            let Inertial { mass, com, inertia } = b.inertial;
            let a_com = add(
                add(acc[i], cross(wd[i], com)),
                cross(w[i], cross(w[i], com)),
            );
            let force = scale(a_com, mass);
            let moment = add(mul(&inertia, wd[i]), cross(w[i], mul(&inertia, w[i])));
            let (mut f, mut nn) = (force, add(moment, cross(com, force)));
            if i + 1 < n {
                let fc = mul(&rot[i + 1], f_next);
                f = add(f, fc);
                nn = add(add(nn, mul(&rot[i + 1], n_next)), cross(org[i + 1], fc));
            }
            tau[i] = dot(b.axis, if b.prismatic { f } else { nn });
            (f_next, n_next) = (f, nn);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    const G: f64 = 9.81;

    fn link(name: &str, inertial: &str) -> String {
        format!("<link name=\"{name}\">{inertial}</link>")
    }

    fn inertial(xyz: &str, mass: f64, izz: f64) -> String {
        format!(
            "<inertial><origin xyz=\"{xyz}\"/><mass value=\"{mass}\"/>\
             <inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"{izz}\"/></inertial>"
        )
    }

    fn joint(
        name: &str,
        kind: &str,
        parent: &str,
        child: &str,
        origin: &str,
        axis: &str,
    ) -> String {
        format!(
            "<joint name=\"{name}\" type=\"{kind}\"><parent link=\"{parent}\"/>\
             <child link=\"{child}\"/><origin {origin}/><axis xyz=\"{axis}\"/></joint>"
        )
    }

    /// Two-link planar arm in the x-y plane (joint axes z): link lengths l1, centres of mass
    /// at lc1, lc2 along each link, masses m1, m2, inertias i1, i2 about z.
    const ARM: (f64, f64, f64, f64, f64, f64, f64) = (0.7, 0.3, 0.25, 2.0, 1.5, 0.04, 0.02);

    fn arm_urdf() -> String {
        let (l1, lc1, lc2, m1, m2, i1, i2) = ARM;
        format!(
            "<robot name=\"arm\">{}{}{}{}{}</robot>",
            link("base", ""),
            link("l1", &inertial(&format!("{lc1} 0 0"), m1, i1)),
            link("l2", &inertial(&format!("{lc2} 0 0"), m2, i2)),
            joint("j1", "revolute", "base", "l1", "xyz=\"0 0 0\"", "0 0 1"),
            joint(
                "j2",
                "continuous",
                "l1",
                "l2",
                &format!("xyz=\"{l1} 0 0\""),
                "0 0 1"
            ),
        )
    }

    fn tau(chain: &SerialChain, q: &[f64], qd: &[f64], qdd: &[f64]) -> Vec<f64> {
        let mut t = vec![0.0; q.len()];
        chain.torque(q, qd, qdd, &mut t);
        t
    }

    #[test]
    fn two_link_planar_arm_matches_closed_form() {
        let (l1, lc1, lc2, m1, m2, i1, i2) = ARM;
        let chain = SerialChain::from_urdf_str(&arm_urdf(), "arm.urdf")
            .unwrap()
            .with_gravity([0.0, -G, 0.0])
            .unwrap();
        assert_eq!(chain.joint_names(), vec!["j1", "j2"]);
        let mut rng = SplitMix64::new(7);
        for _ in 0..50 {
            let q: Vec<f64> = (0..2).map(|_| rng.uniform(-3.0, 3.0)).collect();
            let qd: Vec<f64> = (0..2).map(|_| rng.uniform(-2.0, 2.0)).collect();
            let qdd: Vec<f64> = (0..2).map(|_| rng.uniform(-5.0, 5.0)).collect();
            let (c1, c2, c12) = (q[0].cos(), q[1].cos(), (q[0] + q[1]).cos());
            let s2 = q[1].sin();
            let m11 = m1 * lc1 * lc1 + i1 + m2 * (l1 * l1 + lc2 * lc2 + 2.0 * l1 * lc2 * c2) + i2;
            let m12 = m2 * (lc2 * lc2 + l1 * lc2 * c2) + i2;
            let m22 = m2 * lc2 * lc2 + i2;
            let h = m2 * l1 * lc2 * s2;
            let g1 = (m1 * lc1 + m2 * l1) * G * c1 + m2 * lc2 * G * c12;
            let g2 = m2 * lc2 * G * c12;
            let want = [
                m11 * qdd[0] + m12 * qdd[1] - h * (2.0 * qd[0] * qd[1] + qd[1] * qd[1]) + g1,
                m12 * qdd[0] + m22 * qdd[1] + h * qd[0] * qd[0] + g2,
            ];
            let got = tau(&chain, &q, &qd, &qdd);
            for j in 0..2 {
                assert!(
                    (got[j] - want[j]).abs() <= 1e-12 * want[j].abs().max(1.0),
                    "joint {j}: {} vs {}",
                    got[j],
                    want[j]
                );
            }
        }
    }

    #[test]
    fn single_pendulum() {
        // Arm along x, hinge about y, default gravity −z (a positive angle lowers the arm):
        // τ = (m l² + Iyy) q̈ − m g l cos q.
        let (m, l, iyy) = (2.0, 0.5, 0.03);
        let urdf = format!(
            "<robot name=\"p\"><link name=\"base\"/><link name=\"arm\"><inertial>\
             <origin xyz=\"{l} 0 0\" rpy=\"0.3 0 0.2\"/><mass value=\"{m}\"/>\
             <inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"{iyy}\" iyz=\"0\" izz=\"0\"/>\
             </inertial></link>{}</robot>",
            joint("hinge", "revolute", "base", "arm", "xyz=\"0 0 1\"", "0 2 0")
        );
        // The inertial frame's rotation must not change Iyy about y only if it is a rotation
        // about y; use rpy = 0 for the closed form and check the rotated one separately.
        let plain = urdf.replace("rpy=\"0.3 0 0.2\"", "");
        let chain = SerialChain::from_urdf_str(&plain, "p.urdf").unwrap();
        assert_eq!(chain.gravity(), [0.0, 0.0, -G]);
        assert_eq!(chain.moving_mass(), m);
        for &(q, qd, qdd) in &[(0.0, 0.0, 0.0), (0.7, 1.3, -2.0), (-2.5, -0.4, 3.0)] {
            let want = (m * l * l + iyy) * qdd - m * G * l * f64::cos(q);
            let got = tau(&chain, &[q], &[qd], &[qdd])[0];
            assert!(
                (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                "{got} vs {want}"
            );
        }
        // Rotated inertial frame: the moment of inertia about y becomes
        // Iyy·(R_y·y)² summed over the rotated axes: only the y row of R matters.
        let rotated = SerialChain::from_urdf_str(&urdf, "p.urdf").unwrap();
        let r = rpy_matrix([0.3, 0.0, 0.2]);
        let iyy_rot = r[1][1] * r[1][1] * iyy;
        let want = m * l * l + iyy_rot;
        let got =
            tau(&rotated, &[0.4], &[0.0], &[1.0])[0] - tau(&rotated, &[0.4], &[0.0], &[0.0])[0];
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }

    /// Three revolute joints about y, fixed joints in between (one with a yaw), masses on the
    /// fixed links too.
    fn three_joint_urdf() -> String {
        let full = |xyz: &str, mass: f64| {
            format!(
                "<inertial><origin xyz=\"{xyz}\" rpy=\"0.1 -0.2 0.3\"/><mass value=\"{mass}\"/>\
                 <inertia ixx=\"0.02\" ixy=\"0.001\" ixz=\"-0.002\" iyy=\"0.03\" iyz=\"0.003\" \
                 izz=\"0.025\"/></inertial>"
            )
        };
        format!(
            "<robot name=\"three\">\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n</robot>",
            link("base", ""),
            link("l1", &full("0.2 0 0", 2.0)),
            link("l1b", &full("0.1 0 0", 1.0)),
            link("l2", &full("0.25 0 0", 1.5)),
            link("l2b", ""),
            link("l3", &full("0 0.2 0", 0.5)),
            joint("j1", "revolute", "base", "l1", "xyz=\"0 0 0.5\"", "0 1 0"),
            joint("f1", "fixed", "l1", "l1b", "xyz=\"0.4 0 0\"", "1 0 0"),
            joint("j2", "revolute", "l1b", "l2", "xyz=\"0.3 0 0\"", "0 1 0"),
            joint(
                "f2",
                "fixed",
                "l2",
                "l2b",
                "xyz=\"0.5 0 0\" rpy=\"0 0 1.5707963267948966\"",
                "1 0 0"
            ),
            joint("j3", "revolute", "l2b", "l3", "xyz=\"0 0 0\"", "1 0 0"),
            // A massless tool flange after the last joint.
            joint("f3", "fixed", "l3", "tool", "xyz=\"0 0 0.1\"", "1 0 0"),
        )
        .replace("</robot>", &format!("{}</robot>", link("tool", "")))
    }

    #[test]
    fn gravity_torques_with_fixed_joints_match_hand_computation() {
        let chain = SerialChain::from_urdf_str(&three_joint_urdf(), "three.urdf").unwrap();
        assert_eq!(chain.joint_names(), vec!["j1", "j2", "j3"]);
        // At q = 0 along x: l1 com 0.2, l1b com 0.5, j2 at 0.7, l2 com 0.95, j3 at 1.2, l3 com
        // at 1.2 − 0.2 = 1.0 (its +y is the world's −x after the yaw). A mass m at horizontal
        // offset dx from a y axis needs τ = −m g dx (a positive angle about y lowers +x).
        let want0 = [
            -G * (2.0 * 0.2 + 1.0 * 0.5 + 1.5 * 0.95 + 0.5 * 1.0),
            -G * (1.5 * 0.25 + 0.5 * 0.3),
            -G * (0.5 * -0.2),
        ];
        let got = tau(&chain, &[0.0; 3], &[0.0; 3], &[0.0; 3]);
        for j in 0..3 {
            assert!(
                (got[j] - want0[j]).abs() < 1e-12,
                "{j}: {} vs {}",
                got[j],
                want0[j]
            );
        }
        // All axes are parallel (world y): with q1 = 0.3 every horizontal offset shrinks by
        // cos 0.3, with q2 = -0.5 as well the offsets beyond joint 2 follow the sum.
        let (a, b) = (0.3_f64, -0.5_f64);
        let x1 = |d: f64| d * a.cos();
        let x2 = |d: f64| d * (a + b).cos();
        let want = [
            -G * (2.0 * x1(0.2)
                + 1.0 * x1(0.5)
                + 1.5 * (x1(0.7) + x2(0.25))
                + 0.5 * (x1(0.7) + x2(0.3))),
            -G * (1.5 * x2(0.25) + 0.5 * x2(0.3)),
            -G * 0.5 * x2(-0.2),
        ];
        let got = tau(&chain, &[a, b, 0.0], &[0.0; 3], &[0.0; 3]);
        for j in 0..3 {
            assert!(
                (got[j] - want[j]).abs() < 1e-12,
                "{j}: {} vs {}",
                got[j],
                want[j]
            );
        }
    }

    #[test]
    fn torque_is_affine_in_acceleration_with_spd_mass_matrix() {
        let mut urdf = three_joint_urdf();
        // Make the last joint prismatic too, to cover that branch.
        urdf = urdf.replace(
            "name=\"j3\" type=\"revolute\"",
            "name=\"j3\" type=\"prismatic\"",
        );
        let chain = SerialChain::from_urdf_str(&urdf, "three.urdf").unwrap();
        let n = 3;
        let mut rng = SplitMix64::new(42);
        for _ in 0..30 {
            let mut v = |k: f64| -> Vec<f64> { (0..n).map(|_| rng.uniform(-k, k)).collect() };
            let (q, qd, qdd1, qdd2) = (v(2.5), v(2.0), v(4.0), v(4.0));
            let zero = vec![0.0; n];
            let bias = tau(&chain, &q, &zero, &zero);
            let mut m = vec![0.0; n * n];
            for c in 0..n {
                let mut e = zero.clone();
                e[c] = 1.0;
                let col = tau(&chain, &q, &zero, &e);
                for r in 0..n {
                    m[r * n + c] = col[r] - bias[r];
                }
            }
            for r in 0..n {
                for c in 0..n {
                    assert!(
                        (m[r * n + c] - m[c * n + r]).abs() < 1e-12,
                        "M not symmetric"
                    );
                }
            }
            crate::linalg::Cholesky::factor(&m, n).expect("M positive definite");
            let sum: Vec<f64> = qdd1.iter().zip(&qdd2).map(|(a, b)| a + b).collect();
            let t12 = tau(&chain, &q, &qd, &sum);
            let t2 = tau(&chain, &q, &qd, &qdd2);
            for r in 0..n {
                let mq: f64 = (0..n).map(|c| m[r * n + c] * qdd1[c]).sum();
                assert!((t12[r] - t2[r] - mq).abs() < 1e-11, "row {r}");
            }
        }
        // Wrong slice lengths give NaN, not a panic.
        let mut t = [0.0; 2];
        chain.torque(&[0.0; 2], &[0.0; 2], &[0.0; 2], &mut t);
        assert!(t.iter().all(|x| x.is_nan()));
    }

    fn parse_err(text: &str) -> (usize, String, String) {
        match SerialChain::from_urdf_str(text, "bad.urdf").unwrap_err() {
            Error::Parse { location, message } => {
                assert_eq!(location.source, "bad.urdf");
                (location.line, location.field, message)
            }
            e => panic!("not a parse error: {e}"),
        }
    }

    #[test]
    fn bad_input_names_file_line_field_value() {
        let arm = arm_urdf().replace("><", ">\n<");
        let line_with =
            |s: &str, needle: &str| s.lines().position(|l| l.contains(needle)).unwrap() + 1;
        // Missing mass.
        let t = arm.replace("<mass value=\"1.5\"/>", "");
        let (line, field, msg) = parse_err(&t);
        assert_eq!(field, "link 'l2' <mass>");
        assert!(msg.contains("no <mass>"), "{msg}");
        assert!(line > 0);
        // Non-finite and non-numeric values.
        let t = arm.replace("izz=\"0.02\"", "izz=\"NaN\"");
        let (line, field, msg) = parse_err(&t);
        assert_eq!(field, "link 'l2' <inertia izz>");
        assert!(msg.contains("'NaN'"), "{msg}");
        assert_eq!(line, line_with(&t, "izz=\"NaN\""));
        let t = arm.replace("xyz=\"0.7 0 0\"", "xyz=\"0.7 zero 0\"");
        let (_, field, msg) = parse_err(&t);
        assert_eq!(field, "joint 'j2' <origin xyz>");
        assert!(msg.contains("'zero'"), "{msg}");
        let t = arm.replace("xyz=\"0.7 0 0\"", "xyz=\"0.7 0\"");
        assert!(parse_err(&t).2.contains("expected 3"));
        let t = arm.replace("<mass value=\"2\"/>", "<mass value=\"-2\"/>");
        assert!(parse_err(&t).2.contains("-2 is negative"));
        // Unknown and unsupported joint types.
        let t = arm.replace("type=\"continuous\"", "type=\"hinge\"");
        let (line, field, msg) = parse_err(&t);
        assert_eq!(field, "joint 'j2' type");
        assert!(msg.contains("'hinge'"), "{msg}");
        assert_eq!(line, line_with(&t, "type=\"hinge\""));
        let t = arm.replace("type=\"continuous\"", "type=\"floating\"");
        assert!(parse_err(&t).2.contains("not supported"));
        // No movable joint.
        let t = arm
            .replace("type=\"continuous\"", "type=\"fixed\"")
            .replace("type=\"revolute\"", "type=\"fixed\"");
        assert!(parse_err(&t).2.contains("no movable joint"));
        // A branching tree names the link.
        let t = arm.replace(
            "</robot>",
            &format!(
                "{}{}</robot>",
                link("l3", ""),
                joint("j3", "revolute", "l1", "l3", "xyz=\"0 0 0\"", "0 0 1")
            ),
        );
        let (_, field, msg) = parse_err(&t);
        assert_eq!(field, "link 'l1'");
        assert!(msg.contains("not a serial chain"), "{msg}");
        // Chain order differing from the file order.
        let j1 =
            joint("j1", "revolute", "base", "l1", "xyz=\"0 0 0\"", "0 0 1").replace("><", ">\n<");
        let t = arm
            .replace(&j1, "")
            .replace("</robot>", &format!("{j1}</robot>"));
        assert!(parse_err(&t)
            .2
            .contains("differs from their order in the file"));
        // Zero axis, undefined link, bad gravity, too many joints.
        let t = arm.replacen("<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 0 0\"/>", 1);
        assert!(parse_err(&t).2.contains("not a direction"));
        let t = arm.replace("<child link=\"l2\"/>", "<child link=\"nowhere\"/>");
        assert!(parse_err(&t).2.contains("'nowhere' is not defined"));
        assert!(SerialChain::from_urdf_str(&arm, "a")
            .unwrap()
            .with_gravity([0.0, f64::INFINITY, 0.0])
            .is_err());
        let mut long = String::from("<robot name=\"long\"><link name=\"l0\"/>");
        for i in 1..=MAX_JOINTS + 1 {
            long += &link(&format!("l{i}"), "");
            long += &joint(
                &format!("j{i}"),
                "revolute",
                &format!("l{}", i - 1),
                &format!("l{i}"),
                "xyz=\"0 0 0\"",
                "0 0 1",
            );
        }
        long += "</robot>";
        assert!(parse_err(&long).2.contains("more than 32"));
        assert!(parse_err("<robot").2.contains("not well-formed"));
        assert!(matches!(
            SerialChain::from_urdf_file(std::path::Path::new("/nonexistent/robot.urdf")),
            Err(Error::Io { .. })
        ));
    }
}
