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

/// The attribute names trajkit reads; attributes of other names are not kept.
const NAMES: [&str; 16] = [
    "name", "type", "link", "xyz", "rpy", "value", "ixx", "ixy", "ixz", "iyy", "iyz", "izz",
    "lower", "upper", "velocity", "effort",
];

/// The index of `name` in [`NAMES`].
fn name_id(name: &str) -> Option<u8> {
    NAMES.iter().position(|n| *n == name).map(|i| i as u8)
}

/// An attribute as written: its name (index in [`NAMES`]), its text (a range of
/// [`Doc::values`]) and the line of its value.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Attr {
    name: u8,
    start: usize,
    end: usize,
    line: usize,
}

/// One element: its line and its attributes (a range of [`Doc::attrs`]).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Tag {
    line: usize,
    first: usize,
    last: usize,
}

/// What one parse keeps, shared by every element of the robot: the file's name for errors,
/// the kept attributes' texts one after the other, and the attributes.
///
/// Reading a UR5e-sized file stays close to the cost of roxmltree's parse: no allocation per
/// element or attribute (a `String` per attribute doubled the reading time), and numbers are
/// parsed only when a getter asks for them.
#[derive(Debug, PartialEq)]
struct Doc {
    source: Box<str>,
    values: String,
    attrs: Vec<Attr>,
}

/// Collects the tags of one document.
struct Reader {
    lines: Lines,
    values: String,
    attrs: Vec<Attr>,
}

impl Reader {
    fn tag(&mut self, node: roxmltree::Node<'_, '_>) -> Tag {
        let first = self.attrs.len();
        for a in node.attributes() {
            let Some(name) = name_id(a.name()) else {
                continue;
            };
            let start = self.values.len();
            self.values.push_str(a.value());
            self.attrs.push(Attr {
                name,
                start,
                end: self.values.len(),
                line: self.lines.line_of(a.range_value().start),
            });
        }
        Tag {
            line: self.lines.line_of(node.range().start),
            first,
            last: self.attrs.len(),
        }
    }

    fn child(&mut self, node: roxmltree::Node<'_, '_>, tag: &str) -> Option<Tag> {
        child(node, tag).map(|n| self.tag(n))
    }
}

/// Line numbers of byte positions in the text, from the positions of its line breaks (found
/// once: roxmltree's own `text_pos_at` counts from the start at every call).
struct Lines(Vec<usize>);

impl Lines {
    fn new(text: &str) -> Lines {
        Lines(
            text.bytes()
                .enumerate()
                .filter(|&(_, b)| b == b'\n')
                .map(|(i, _)| i)
                .collect(),
        )
    }

    /// The 1-based line of byte position `pos`: one more than the line breaks before it.
    fn line_of(&self, pos: usize) -> usize {
        1 + self.0.partition_point(|&nl| nl < pos)
    }
}

/// The first child element of `node` named `tag`.
fn child<'a, 'input>(
    node: roxmltree::Node<'a, 'input>,
    tag: &str,
) -> Option<roxmltree::Node<'a, 'input>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == tag)
}

/// Where errors point and what the tags refer to, shared by every element of one robot.
#[derive(Debug, Clone, PartialEq)]
struct Src(Arc<Doc>);

/// An error about the whole document (no field), before its tags are kept.
fn src_error(source: &str, line: usize, message: String) -> Error {
    Error::Parse {
        location: Location {
            source: source.to_string(),
            line,
            field: String::new(),
        },
        message,
    }
}

impl Src {
    fn error(&self, line: usize, field: impl Into<String>, message: impl Into<String>) -> Error {
        Error::Parse {
            location: Location {
                source: self.0.source.to_string(),
                line,
                field: field.into(),
            },
            message: message.into(),
        }
    }

    fn attr(&self, tag: &Tag, name: &str) -> Option<&Attr> {
        let id = name_id(name)?;
        self.0.attrs[tag.first..tag.last]
            .iter()
            .find(|a| a.name == id)
    }

    fn text_of(&self, a: &Attr) -> &str {
        &self.0.values[a.start..a.end]
    }

    fn text(&self, tag: &Tag, name: &str) -> Option<&str> {
        self.attr(tag, name).map(|a| self.text_of(a))
    }

    /// The `name` attribute of this `<element>`; errors name the element when it is missing.
    fn name(&self, tag: &Tag, element: &str) -> Result<&str> {
        self.text(tag, "name").ok_or_else(|| {
            self.error(
                tag.line,
                format!("<{element} name>"),
                format!("the {element} has no name attribute"),
            )
        })
    }

    /// One number (`None` when the attribute is absent); surrounding white space is allowed.
    /// Messages quote the attribute as written.
    fn number(&self, tag: &Tag, attr: &str, field: impl FnOnce() -> String) -> Result<Option<f64>> {
        let Some(a) = self.attr(tag, attr) else {
            return Ok(None);
        };
        let text = self.text_of(a);
        match text.trim().parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(Some(x)),
            Ok(_) => Err(self.error(a.line, field(), format!("'{text}' is not a finite number"))),
            Err(_) => Err(self.error(a.line, field(), format!("'{text}' is not a number"))),
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
        let Some(a) = self.attr(tag, attr) else {
            return Ok(None);
        };
        let raw = self.text_of(a);
        let mut out = [0.0; N];
        let mut count = 0;
        for word in raw.split_whitespace() {
            let quoted = || {
                if raw.trim() == word {
                    format!("'{word}'")
                } else {
                    format!("'{word}' in '{raw}'")
                }
            };
            let x: f64 = word.parse().map_err(|_| {
                self.error(a.line, field(), format!("{} is not a number", quoted()))
            })?;
            if !x.is_finite() {
                return Err(self.error(
                    a.line,
                    field(),
                    format!("{} is not a finite number", quoted()),
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
    fn required(&self, tag: &Tag, attr: &str, field: impl Fn() -> String) -> Result<f64> {
        match self.numbers::<1>(tag, attr, &field)? {
            Some([x]) => Ok(x),
            None => Err(self.error(
                tag.line,
                field(),
                format!("the attribute '{attr}' is missing"),
            )),
        }
    }

    /// `<origin xyz rpy>` (zero where absent) as written in `tag`; `owner` names the element
    /// in messages.
    fn pose(&self, origin: Option<&Tag>, owner: impl Fn() -> String) -> Result<Pose> {
        let Some(o) = origin else {
            return Ok(Pose::default());
        };
        Ok(Pose {
            xyz: self
                .numbers::<3>(o, "xyz", || format!("{} <origin xyz>", owner()))?
                .unwrap_or_default(),
            rpy: self
                .numbers::<3>(o, "rpy", || format!("{} <origin rpy>", owner()))?
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
        self.src.name(&self.tag, "joint")
    }

    /// `joint 'name'` for fields in messages.
    fn owner(&self) -> String {
        format!("joint '{}'", self.src.text(&self.tag, "name").unwrap_or(""))
    }

    /// The joint's type. Errors: a missing or unknown `type`, quoted.
    pub fn joint_type(&self) -> Result<JointType> {
        Ok(match self.src.text(&self.tag, "type").unwrap_or("") {
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
        el.as_ref()
            .and_then(|t| self.src.text(t, "link"))
            .ok_or_else(|| {
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
        self.src.pose(self.origin.as_ref(), || self.owner())
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
        let line = self.src.attr(l, attr).map_or(0, |a| a.line);
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

/// The tags of one joint: its own, those of `<parent>`, `<child>`, `<origin>`, `<axis>`,
/// `<limit>` when present, and whether it has a `<mimic>`.
type JointTags = (Tag, [Option<Tag>; 5], bool);

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
        self.src.name(&self.tag, "link")
    }

    /// The inertial parameters; `None` for a link without `<inertial>` (massless). Errors: a
    /// missing `<mass>` or `<inertia>`, a missing or non-finite value, a negative mass.
    pub fn inertial(&self) -> Result<Option<Inertial>> {
        let Some(i) = &self.inertial else {
            return Ok(None);
        };
        let owner = || format!("link '{}'", self.src.text(&self.tag, "name").unwrap_or(""));
        let origin = self.src.pose(i.origin.as_ref(), owner)?;
        let Some(m) = &i.mass else {
            return Err(self.src.error(
                i.tag.line,
                format!("{} <mass>", owner()),
                "the <inertial> element has no <mass>",
            ));
        };
        let mass = self
            .src
            .required(m, "value", || format!("{} <mass value>", owner()))?;
        if mass < 0.0 {
            return Err(self.src.error(
                m.line,
                format!("{} <mass value>", owner()),
                format!("{mass} is negative"),
            ));
        }
        let Some(t) = &i.inertia else {
            return Err(self.src.error(
                i.tag.line,
                format!("{} <inertia>", owner()),
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
                .required(t, attr, || format!("{} <inertia {attr}>", owner()))?;
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
        let doc = roxmltree::Document::parse(text).map_err(|e| {
            src_error(
                source,
                e.pos().row as usize,
                format!("not well-formed XML: {e}"),
            )
        })?;
        let mut reader = Reader {
            lines: Lines::new(text),
            values: String::with_capacity(text.len() / 4),
            attrs: Vec::new(),
        };
        let root = doc.root_element();
        let root_tag = reader.tag(root);
        if root.tag_name().name() != "robot" {
            return Err(src_error(
                source,
                root_tag.line,
                format!(
                    "the root element is <{}>, a URDF's is <robot>",
                    root.tag_name().name()
                ),
            ));
        }
        let elements = |name: &'static str| {
            root.children()
                .filter(move |n| n.is_element() && n.tag_name().name() == name)
        };
        let links: Vec<_> = elements("link")
            .map(|node| {
                let tag = reader.tag(node);
                let inertial = child(node, "inertial").map(|i| InertialTags {
                    tag: reader.tag(i),
                    origin: reader.child(i, "origin"),
                    mass: reader.child(i, "mass"),
                    inertia: reader.child(i, "inertia"),
                });
                (tag, inertial)
            })
            .collect();
        let joints: Vec<_> = elements("joint")
            .map(|node| {
                let tag = reader.tag(node);
                let children = ["parent", "child", "origin", "axis", "limit"]
                    .map(|name| reader.child(node, name));
                (tag, children, child(node, "mimic").is_some())
            })
            .collect();
        let src = Src(Arc::new(Doc {
            source: source.into(),
            values: reader.values,
            attrs: reader.attrs,
        }));
        Ok(Robot::assemble(
            src,
            root_tag,
            links,
            joints,
            text.contains("xacro"),
        ))
    }

    /// The robot from its tags, each link and joint sharing the document `src`.
    fn assemble(
        src: Src,
        root: Tag,
        links: Vec<(Tag, Option<InertialTags>)>,
        joints: Vec<JointTags>,
        mentions_xacro: bool,
    ) -> Robot {
        let links = links
            .into_iter()
            .map(|(tag, inertial)| Link {
                src: src.clone(),
                tag,
                inertial,
            })
            .collect();
        let joints = joints
            .into_iter()
            .map(|(tag, [parent, child, origin, axis, limit], mimic)| Joint {
                src: src.clone(),
                tag,
                parent,
                child,
                origin,
                axis,
                limit,
                mimic,
            })
            .collect();
        Robot {
            src,
            root,
            links,
            joints,
            mentions_xacro,
        }
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
        &self.src.0.source
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
