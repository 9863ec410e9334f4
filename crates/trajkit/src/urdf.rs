//! URDF: a robot description read once into a [`Robot`], for every part of trajkit that needs
//! one.
//!
//! [`Robot::parse`] reads the XML (roxmltree) and keeps the elements trajkit uses, with their
//! lines: the `<link>`s (name, `<inertial>` with `<origin>`, `<mass>`, `<inertia>`) and the
//! `<joint>`s (name, type, `<parent>`, `<child>`, `<origin>`, `<axis>`, `<limit>`, `<mimic>`),
//! in document order. Numbers are read when asked for, so that each user reads only what it
//! needs and reports the first problem in its own order:
//! [`crate::limits::load::from_urdf`] reads the joints' `<limit>` tags,
//! [`crate::dynamics::SerialChain::from_urdf`] the chain and the inertial parameters. Parse a
//! file once and hand the same [`Robot`] to both.
//!
//! Every error is an [`Error::Parse`] naming the file, the line (of the attribute's value for
//! a bad number, else of the element), the field (`joint 'elbow' <limit velocity>`,
//! `link 'l2' <inertia izz>`) and the value.
//!
//! ```
//! use trajkit::urdf::{JointType, Robot};
//! let robot = Robot::parse(
//!     r#"<robot name="r"><link name="a"/><link name="b"/>
//!        <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
//!          <axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="2" effort="10"/>
//!        </joint></robot>"#,
//!     "r.urdf",
//! )?;
//! let j = &robot.joints()[0];
//! assert_eq!((j.name()?, j.joint_type()?), ("j", JointType::Revolute));
//! assert_eq!(j.axis()?, Some([0.0, 0.0, 1.0]));
//! let limits = trajkit::limits::load::from_urdf(&robot)?;
//! assert_eq!(limits.joint(0).velocity, 2.0);
//! # Ok::<(), trajkit::Error>(())
//! ```

use crate::error::{Error, Location, Result};
use std::sync::Arc;

/// An attribute as written: its text and the line of its value.
#[derive(Debug, Clone, PartialEq)]
struct Attr {
    name: String,
    text: String,
    line: usize,
}

/// One element: its line and its attributes.
#[derive(Debug, Clone, PartialEq)]
struct Tag {
    line: usize,
    attrs: Vec<Attr>,
}

impl Tag {
    fn read(doc: &roxmltree::Document<'_>, node: roxmltree::Node<'_, '_>) -> Tag {
        Tag {
            line: line_of(doc, node.range().start),
            attrs: node
                .attributes()
                .map(|a| Attr {
                    name: a.name().to_string(),
                    text: a.value().to_string(),
                    line: line_of(doc, a.range_value().start),
                })
                .collect(),
        }
    }

    fn attr(&self, name: &str) -> Option<&Attr> {
        self.attrs.iter().find(|a| a.name == name)
    }

    fn text(&self, name: &str) -> Option<&str> {
        self.attr(name).map(|a| a.text.as_str())
    }
}

fn line_of(doc: &roxmltree::Document<'_>, pos: usize) -> usize {
    doc.text_pos_at(pos).row as usize
}

/// The first child element of `node` named `tag`.
fn child<'a, 'input>(
    node: roxmltree::Node<'a, 'input>,
    tag: &str,
) -> Option<roxmltree::Node<'a, 'input>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == tag)
}

/// Where errors point: the file's name, shared by every element of one robot.
#[derive(Debug, Clone, PartialEq)]
struct Src(Arc<str>);

impl Src {
    fn error(&self, line: usize, field: impl Into<String>, message: impl Into<String>) -> Error {
        Error::Parse {
            location: Location {
                source: self.0.to_string(),
                line,
                field: field.into(),
            },
            message: message.into(),
        }
    }

    /// One number (`None` when the attribute is absent); surrounding white space is allowed.
    /// Messages quote the attribute as written.
    fn number(&self, tag: &Tag, attr: &str, field: impl FnOnce() -> String) -> Result<Option<f64>> {
        let Some(a) = tag.attr(attr) else {
            return Ok(None);
        };
        match a.text.trim().parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(Some(x)),
            Ok(_) => Err(self.error(
                a.line,
                field(),
                format!("'{}' is not a finite number", a.text),
            )),
            Err(_) => Err(self.error(a.line, field(), format!("'{}' is not a number", a.text))),
        }
    }

    /// A white-space separated list of `N` finite numbers; `None` when the attribute is
    /// absent. Messages quote the offending word (and the list when it has more than one).
    fn numbers<const N: usize>(
        &self,
        tag: &Tag,
        attr: &str,
        field: impl Fn() -> String,
    ) -> Result<Option<[f64; N]>> {
        let Some(a) = tag.attr(attr) else {
            return Ok(None);
        };
        let raw = a.text.as_str();
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
                .map_err(|_| self.error(a.line, field(), format!("{quoted} is not a number")))?;
            if !x.is_finite() {
                return Err(self.error(
                    a.line,
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
            return Err(self.error(
                a.line,
                field(),
                format!("'{raw}' has {count} numbers, expected {N}"),
            ));
        }
        Ok(Some(out))
    }

    /// A required single number (written as a list of one).
    fn required(&self, tag: &Tag, attr: &str, field: String) -> Result<f64> {
        match self.numbers::<1>(tag, attr, || field.clone())? {
            Some([x]) => Ok(x),
            None => Err(self.error(
                tag.line,
                field,
                format!("the attribute '{attr}' is missing"),
            )),
        }
    }

    /// `<origin xyz rpy>` (zero where absent) as written in `tag`.
    fn pose(&self, origin: Option<&Tag>, owner: &str) -> Result<Pose> {
        let Some(o) = origin else {
            return Ok(Pose::default());
        };
        Ok(Pose {
            xyz: self
                .numbers::<3>(o, "xyz", || format!("{owner} <origin xyz>"))?
                .unwrap_or_default(),
            rpy: self
                .numbers::<3>(o, "rpy", || format!("{owner} <origin rpy>"))?
                .unwrap_or_default(),
        })
    }
}

/// A frame's placement as URDF writes it: translation `xyz` (m) and roll-pitch-yaw `rpy`
/// (rad, R = Rz(yaw)·Ry(pitch)·Rx(roll)).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Pose {
    /// Translation.
    pub xyz: [f64; 3],
    /// Roll, pitch, yaw.
    pub rpy: [f64; 3],
}

/// The type of a URDF joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointType {
    /// Rotation about the axis, within a position range.
    Revolute,
    /// Rotation about the axis without a range.
    Continuous,
    /// Translation along the axis.
    Prismatic,
    /// No motion: the child link is rigidly attached.
    Fixed,
    /// Six degrees of freedom.
    Floating,
    /// Motion in a plane.
    Planar,
}

impl JointType {
    /// True for the joints a controller commands one value of: revolute, continuous,
    /// prismatic.
    pub fn is_movable(self) -> bool {
        matches!(
            self,
            JointType::Revolute | JointType::Continuous | JointType::Prismatic
        )
    }
}

/// A `<joint>` element with the children trajkit reads.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    src: Src,
    tag: Tag,
    parent: Option<Tag>,
    child: Option<Tag>,
    origin: Option<Tag>,
    axis: Option<Tag>,
    limit: Option<Tag>,
    mimic: bool,
}

impl Joint {
    /// The line of the `<joint>` element.
    pub fn line(&self) -> usize {
        self.tag.line
    }

    /// The joint's name. Errors: the attribute is missing.
    pub fn name(&self) -> Result<&str> {
        self.tag.text("name").ok_or_else(|| {
            self.src.error(
                self.tag.line,
                "<joint name>",
                "the joint has no name attribute",
            )
        })
    }

    /// `joint 'name'` for fields in messages.
    fn owner(&self) -> String {
        format!("joint '{}'", self.tag.text("name").unwrap_or(""))
    }

    /// The joint's type. Errors: a missing or unknown `type`, quoted.
    pub fn joint_type(&self) -> Result<JointType> {
        Ok(match self.tag.text("type").unwrap_or("") {
            "revolute" => JointType::Revolute,
            "continuous" => JointType::Continuous,
            "prismatic" => JointType::Prismatic,
            "fixed" => JointType::Fixed,
            "floating" => JointType::Floating,
            "planar" => JointType::Planar,
            other => {
                return Err(self.error(
                    format!("{} type", self.owner()),
                    format!(
                        "'{other}' is not a URDF joint type (revolute, continuous, prismatic, \
                         fixed, floating, planar)"
                    ),
                ))
            }
        })
    }

    /// True when the joint has a `<mimic>` element (it follows another joint).
    pub fn is_mimic(&self) -> bool {
        self.mimic
    }

    /// True when the joint has a `<limit>` element.
    pub fn has_limit(&self) -> bool {
        self.limit.is_some()
    }

    fn link<'a>(&'a self, tag: &str, el: &'a Option<Tag>) -> Result<&'a str> {
        el.as_ref().and_then(|t| t.text("link")).ok_or_else(|| {
            self.error(
                format!("{} <{tag} link>", self.owner()),
                format!("the joint has no <{tag} link=...>"),
            )
        })
    }

    /// The name of the parent link (`<parent link>`). Errors: it is missing.
    pub fn parent(&self) -> Result<&str> {
        self.link("parent", &self.parent)
    }

    /// The name of the child link (`<child link>`). Errors: it is missing.
    pub fn child(&self) -> Result<&str> {
        self.link("child", &self.child)
    }

    /// The joint frame in the parent link's frame (`<origin>`; zero when absent). Errors: a
    /// value that is not three finite numbers.
    pub fn origin(&self) -> Result<Pose> {
        self.src.pose(self.origin.as_ref(), &self.owner())
    }

    /// The axis as written (`<axis xyz>`, not normalized); `None` when absent (URDF's
    /// default is `1 0 0`). Errors: a value that is not three finite numbers.
    pub fn axis(&self) -> Result<Option<[f64; 3]>> {
        match &self.axis {
            None => Ok(None),
            Some(a) => self
                .src
                .numbers::<3>(a, "xyz", || format!("{} <axis xyz>", self.owner())),
        }
    }

    /// One attribute of `<limit>` (`lower`, `upper`, `velocity`, `effort`) with the line of
    /// its value; `None` when `<limit>` or the attribute is absent.
    pub(crate) fn limit_value(&self, attr: &str) -> Result<Option<(f64, usize)>> {
        let Some(l) = &self.limit else {
            return Ok(None);
        };
        let line = l.attr(attr).map_or(0, |a| a.line);
        let field = || format!("{} <limit {attr}>", self.owner());
        Ok(self.src.number(l, attr, field)?.map(|x| (x, line)))
    }

    /// An error at the joint's element.
    pub(crate) fn error(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        self.src.error(self.tag.line, field, message)
    }

    /// An error at the joint's `<axis>` element (at the joint when there is none).
    pub(crate) fn axis_error(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        let line = self.axis.as_ref().map_or(self.tag.line, |a| a.line);
        self.src.error(line, field, message)
    }

    /// An error on line `line` (of one of the joint's attributes).
    pub(crate) fn error_at(
        &self,
        line: usize,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> Error {
        self.src.error(line, field, message)
    }
}

/// A link's inertial parameters as written (`<inertial>`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertial {
    /// The centre-of-mass frame in the link frame.
    pub origin: Pose,
    /// Mass (kg, ≥ 0).
    pub mass: f64,
    /// `ixx, ixy, ixz, iyy, iyz, izz` about the centre of mass, in the `origin` frame.
    pub inertia: [f64; 6],
}

/// An `<inertial>` element with its children.
#[derive(Debug, Clone, PartialEq)]
struct InertialTags {
    tag: Tag,
    origin: Option<Tag>,
    mass: Option<Tag>,
    inertia: Option<Tag>,
}

/// A `<link>` element.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    src: Src,
    tag: Tag,
    inertial: Option<InertialTags>,
}

impl Link {
    /// The line of the `<link>` element.
    pub fn line(&self) -> usize {
        self.tag.line
    }

    /// The link's name. Errors: the attribute is missing.
    pub fn name(&self) -> Result<&str> {
        self.tag.text("name").ok_or_else(|| {
            self.src.error(
                self.tag.line,
                "<link name>",
                "the link has no name attribute",
            )
        })
    }

    /// The inertial parameters; `None` for a link without `<inertial>` (massless). Errors: a
    /// missing `<mass>` or `<inertia>`, a missing or non-finite value, a negative mass.
    pub fn inertial(&self) -> Result<Option<Inertial>> {
        let Some(i) = &self.inertial else {
            return Ok(None);
        };
        let owner = format!("link '{}'", self.tag.text("name").unwrap_or(""));
        let origin = self.src.pose(i.origin.as_ref(), &owner)?;
        let Some(m) = &i.mass else {
            return Err(self.src.error(
                i.tag.line,
                format!("{owner} <mass>"),
                "the <inertial> element has no <mass>",
            ));
        };
        let mass = self
            .src
            .required(m, "value", format!("{owner} <mass value>"))?;
        if mass < 0.0 {
            return Err(self.src.error(
                m.line,
                format!("{owner} <mass value>"),
                format!("{mass} is negative"),
            ));
        }
        let Some(t) = &i.inertia else {
            return Err(self.src.error(
                i.tag.line,
                format!("{owner} <inertia>"),
                "the <inertial> element has no <inertia>",
            ));
        };
        let mut inertia = [0.0; 6];
        for (v, attr) in inertia
            .iter_mut()
            .zip(["ixx", "ixy", "ixz", "iyy", "iyz", "izz"])
        {
            *v = self
                .src
                .required(t, attr, format!("{owner} <inertia {attr}>"))?;
        }
        Ok(Some(Inertial {
            origin,
            mass,
            inertia,
        }))
    }

    /// An error at the link's element.
    pub(crate) fn error(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        self.src.error(self.tag.line, field, message)
    }
}

/// A robot description: the `<link>` and `<joint>` children of `<robot>`, in document order.
#[derive(Debug, Clone, PartialEq)]
pub struct Robot {
    src: Src,
    root: Tag,
    links: Vec<Link>,
    joints: Vec<Joint>,
    mentions_xacro: bool,
}

impl Robot {
    /// Reads URDF text; `source` names it in errors (a file name).
    ///
    /// Errors: [`Error::Parse`] with the line for text that is not well-formed XML, or whose
    /// root element is not `<robot>`. Everything else is checked by the getters, when read.
    pub fn parse(text: &str, source: &str) -> Result<Robot> {
        let src = Src(Arc::from(source));
        let doc = roxmltree::Document::parse(text).map_err(|e| {
            src.error(
                e.pos().row as usize,
                "",
                format!("not well-formed XML: {e}"),
            )
        })?;
        let root = doc.root_element();
        let root_tag = Tag::read(&doc, root);
        if root.tag_name().name() != "robot" {
            return Err(src.error(
                root_tag.line,
                "",
                format!(
                    "the root element is <{}>, a URDF's is <robot>",
                    root.tag_name().name()
                ),
            ));
        }
        let tag_of = |n: Option<roxmltree::Node<'_, '_>>| n.map(|n| Tag::read(&doc, n));
        let elements = |name: &'static str| {
            root.children()
                .filter(move |n| n.is_element() && n.tag_name().name() == name)
        };
        let links = elements("link")
            .map(|node| Link {
                src: src.clone(),
                tag: Tag::read(&doc, node),
                inertial: child(node, "inertial").map(|i| InertialTags {
                    tag: Tag::read(&doc, i),
                    origin: tag_of(child(i, "origin")),
                    mass: tag_of(child(i, "mass")),
                    inertia: tag_of(child(i, "inertia")),
                }),
            })
            .collect();
        let joints = elements("joint")
            .map(|node| Joint {
                src: src.clone(),
                tag: Tag::read(&doc, node),
                parent: tag_of(child(node, "parent")),
                child: tag_of(child(node, "child")),
                origin: tag_of(child(node, "origin")),
                axis: tag_of(child(node, "axis")),
                limit: tag_of(child(node, "limit")),
                mimic: child(node, "mimic").is_some(),
            })
            .collect();
        Ok(Robot {
            src,
            root: root_tag,
            links,
            joints,
            mentions_xacro: text.contains("xacro"),
        })
    }

    /// Reads a URDF file.
    ///
    /// Errors: [`Error::Io`] naming the path when it cannot be read (or is larger than
    /// [`crate::io::MAX_FILE_BYTES`]); otherwise as [`Robot::parse`].
    pub fn from_file(path: &std::path::Path) -> Result<Robot> {
        let text = crate::io::read_text(path)?;
        Robot::parse(&text, &path.display().to_string())
    }

    /// The name that errors give as the file.
    pub fn source(&self) -> &str {
        &self.src.0
    }

    /// The `<link>` elements, in document order.
    pub fn links(&self) -> &[Link] {
        &self.links
    }

    /// The `<joint>` elements, in document order.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// True when the text mentions xacro (an unexpanded xacro file, likely).
    pub(crate) fn mentions_xacro(&self) -> bool {
        self.mentions_xacro
    }

    /// An error at the `<robot>` element.
    pub(crate) fn error(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        self.src.error(self.root.line, field, message)
    }

    /// An error about the whole file (no line).
    pub(crate) fn file_error(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        self.src.error(0, field, message)
    }
}
