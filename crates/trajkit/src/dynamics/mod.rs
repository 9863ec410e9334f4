//! Rigid-body inverse dynamics of a serial chain read from a URDF.
//!
//! [`SerialChain`] takes the kinematic chain and the inertial parameters of a robot from a URDF
//! (read by [`crate::urdf`]) and computes joint torques τ = M(q)q̈ + C(q, q̇)q̇ + g(q) by the recursive Newton–Euler
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
//! order in the file, because that is the order [`crate::limits::load::from_urdf`] gives the
//! joints' limits (one [`Robot`] serves both). Mimic, floating and planar joints are refused, as are more than
//! [`MAX_JOINTS`] joints.
//!
//! Bad input gives [`Error::Parse`] naming the file, the line, the field and the value.
//!
//! Files: `chain.rs` builds the bodies from the [`Robot`] (the walk from the root link, fixed
//! joints merged), `spatial.rs` holds the 3-D algebra (rotations, frames, rigid-body inertia),
//! `rnea.rs` the recursion.
//!
//! # Precision contract
//! The Newton–Euler recursion is exact in exact arithmetic: the only error is floating-point
//! rounding, a few ulps per joint of the largest torque term (well below 1e-12 relative for
//! chains of realistic size). The result is as exact as the URDF's inertial parameters; they
//! are used as given (no physical-consistency check of the inertia tensor beyond finiteness and
//! a mass ≥ 0). [`InverseDynamics::torque`] does not allocate.

mod chain;
mod rnea;
mod spatial;
#[cfg(test)]
mod tests;

use crate::error::Result;
pub use crate::inverse_dynamics::InverseDynamics;
use crate::urdf::Robot;
use spatial::{Frame, Inertial, Vec3};

/// The largest number of movable joints a [`SerialChain`] holds.
pub const MAX_JOINTS: usize = 32;

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
/// use trajkit::dynamics::InverseDynamics;
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

impl SerialChain {
    /// Reads a serial chain from URDF text; `source` names it in errors (a file name).
    ///
    /// Errors: [`Error::Parse`](crate::Error::Parse) with file, line, field and value for
    /// malformed XML, missing or non-finite numbers, a missing `<mass>`, unknown or unsupported
    /// joint types, a branching tree, no movable joint, more than [`MAX_JOINTS`] joints, or a
    /// chain order that differs from the file order of the movable joints.
    pub fn from_urdf_str(text: &str, source: &str) -> Result<Self> {
        Self::from_urdf(&Robot::parse(text, source)?)
    }

    /// Reads a serial chain from a URDF file.
    ///
    /// Errors: [`Error::Io`](crate::Error::Io) naming the path when it cannot be read;
    /// otherwise as [`SerialChain::from_urdf_str`].
    pub fn from_urdf_file(path: &std::path::Path) -> Result<Self> {
        Self::from_urdf(&Robot::from_file(path)?)
    }

    /// The serial chain of a robot read by [`Robot::parse`] (errors as
    /// [`SerialChain::from_urdf_str`]).
    pub fn from_urdf(robot: &Robot) -> Result<Self> {
        chain::from_robot(robot)
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
