//! Limits as their sources give them: which fields were given, and which are absent.
//!
//! A URDF has no acceleration or jerk limits; a MoveIt `joint_limits.yaml` leaves out what its
//! `has_…` flags turn off; a trajkit limits file lists what it lists; command-line overrides
//! name one field at a time. An absent limit is **not** "unlimited": [`PartialLimits`] keeps
//! the values (absent ones hold the "no limit" value of [`JointLimits`], ±∞) together with a
//! [`Given`] record per joint, combines sources ([`PartialLimits::fill_from`],
//! [`PartialLimits::with_override`], [`PartialLimits::with_position_range`],
//! [`PartialLimits::scaled`], [`crate::limits::load::apply_moveit_joint_limits`]) and is turned
//! into complete [`Limits`] by [`PartialLimits::complete`], which refuses every limit the
//! caller needs that no source gave ([`Error::MissingLimit`], naming the joint and the field).
//! An explicit infinity (`null` or `.inf` in a file, `inf` on the command line) is given: it
//! states "unlimited" on purpose.
//!
//! Joints are matched between sources and data by name where both sides name them
//! ([`match_names`]).

use super::{JointLimits, Limits};
use crate::error::{Error, Result};
use crate::traj::Order;

/// Which limits of one joint some source gave (an explicit infinity counts as given).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Given {
    /// The lower end of the position range.
    pub position_min: bool,
    /// The upper end of the position range.
    pub position_max: bool,
    /// The maximum velocity (and its directional minimum, when any).
    pub velocity: bool,
    /// The maximum acceleration (and its directional minimum, when any).
    pub acceleration: bool,
    /// The maximum jerk.
    pub jerk: bool,
}

impl Given {
    /// Every field given.
    pub const ALL: Given = Given {
        position_min: true,
        position_max: true,
        velocity: true,
        acceleration: true,
        jerk: true,
    };

    /// Nothing given.
    pub const NONE: Given = Given {
        position_min: false,
        position_max: false,
        velocity: false,
        acceleration: false,
        jerk: false,
    };
}

/// The limits an operation needs: each `true` field must be given for every joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Needs {
    /// The position range (both ends).
    pub position: bool,
    /// The maximum velocity.
    pub velocity: bool,
    /// The maximum acceleration.
    pub acceleration: bool,
    /// The maximum jerk.
    pub jerk: bool,
}

impl Needs {
    /// Every limit.
    pub const ALL: Needs = Needs {
        position: true,
        velocity: true,
        acceleration: true,
        jerk: true,
    };

    /// No limit (absent ones become unlimited: for reports that say what they did not check).
    pub const NONE: Needs = Needs {
        position: false,
        velocity: false,
        acceleration: false,
        jerk: false,
    };
}

/// How [`PartialLimits::fill_from`] pairs joints with the source it fills from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FillBy {
    /// A joint takes the limits of the source's joint of the same name.
    #[default]
    Name,
    /// Joint j takes the limits of the source's joint j (the source may have more joints).
    Index,
}

/// Per-joint limits with a record of what was given (see the module documentation).
///
/// ```
/// # #[cfg(feature = "urdf")] {
/// use trajkit::limits::{load, FillBy, Needs, PartialLimits};
/// let urdf = r#"<robot name="r">
///   <joint name="shoulder_pan_joint" type="revolute">
///     <limit lower="-6.28" upper="6.28" velocity="3.14" effort="150"/></joint>
/// </robot>"#;
/// let l = load::from_urdf_str(urdf, "r.urdf")?;
/// // A URDF has no acceleration limit: refused, naming the joint and the field.
/// let e = l.complete(Needs::ALL).unwrap_err().to_string();
/// assert!(e.starts_with("joint 1 (shoulder_pan_joint) has no acceleration limit"));
/// // Filled from the UR5e preset by joint name, it is complete.
/// let ur5e = PartialLimits::from(trajkit::Limits::preset("ur5e")?);
/// let full = l.fill_from(&ur5e, FillBy::Name)?.complete(Needs::ALL)?;
/// assert_eq!(full.joint(0).acceleration, 10.0);
/// # }
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PartialLimits {
    joints: Vec<JointLimits>,
    given: Vec<Given>,
}

impl From<Limits> for PartialLimits {
    /// Complete limits: every field given.
    fn from(l: Limits) -> Self {
        let n = l.dof();
        PartialLimits {
            joints: l.joints().to_vec(),
            given: vec![Given::ALL; n],
        }
    }
}

impl PartialLimits {
    /// Validates the given values (as [`Limits::new`] does; absent fields must hold the "no
    /// limit" value) and wraps them. `given` has one entry per joint.
    pub fn new(joints: Vec<JointLimits>, given: Vec<Given>) -> Result<Self> {
        if given.len() != joints.len() {
            return Err(Error::DimensionMismatch {
                what: "given-limit records".into(),
                expected: joints.len(),
                found: given.len(),
            });
        }
        Limits::new(joints.clone())?;
        Ok(PartialLimits { joints, given })
    }

    /// `dof` unnamed joints with nothing given (the start for command-line overrides alone).
    pub fn unnamed(dof: usize) -> Result<Self> {
        PartialLimits::new(vec![JointLimits::default(); dof], vec![Given::NONE; dof])
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// Values of joint `j` (absent fields hold ±∞). Panics if `j >= dof()`.
    pub fn joint(&self, j: usize) -> &JointLimits {
        &self.joints[j]
    }

    /// Values of every joint (absent fields hold ±∞).
    pub fn joints(&self) -> &[JointLimits] {
        &self.joints
    }

    /// What was given, per joint.
    pub fn given(&self) -> &[Given] {
        &self.given
    }

    /// Joint names (possibly empty).
    pub fn names(&self) -> Vec<String> {
        self.joints.iter().map(|j| j.name.clone()).collect()
    }

    /// Absent fields that `needs` asks for, as (joint, field name), in joint order.
    pub fn missing(&self, needs: Needs) -> Vec<(usize, &'static str)> {
        let mut out = Vec::new();
        for (j, g) in self.given.iter().enumerate() {
            if needs.velocity && !g.velocity {
                out.push((j, "velocity"));
            }
            if needs.acceleration && !g.acceleration {
                out.push((j, "acceleration"));
            }
            if needs.jerk && !g.jerk {
                out.push((j, "jerk"));
            }
            if needs.position && !(g.position_min && g.position_max) {
                out.push((j, "position range"));
            }
        }
        out
    }

    /// Complete limits: every field that `needs` asks for must have been given
    /// ([`Error::MissingLimit`] names the first joint and field that was not); absent fields
    /// that are not needed become unlimited.
    pub fn complete(&self, needs: Needs) -> Result<Limits> {
        if let Some(&(joint, field)) = self.missing(needs).first() {
            return Err(Error::MissingLimit {
                joint,
                name: self.joints[joint].name.clone(),
                field,
            });
        }
        Limits::new(self.joints.clone())
    }

    /// Replaces the limits of derivative `order` (velocity, acceleration or jerk) with the
    /// given values (one for every joint, or one per joint; `inf` states "unlimited") and marks
    /// them given. A velocity or acceleration override drops that order's directional minimum.
    pub fn with_override(mut self, order: Order, values: &[f64]) -> Result<Self> {
        let l = Limits::new(self.joints.clone())?.with_override(order, values)?;
        self.joints = l.joints().to_vec();
        for g in &mut self.given {
            match order {
                Order::Velocity => g.velocity = true,
                Order::Acceleration => g.acceleration = true,
                Order::Jerk => g.jerk = true,
                Order::Position => {}
            }
        }
        Ok(self)
    }

    /// Replaces every joint's position range with `ranges` (one `(lo, hi)` for every joint, or
    /// one per joint; infinite ends state "unbounded") and marks them given.
    pub fn with_position_range(mut self, ranges: &[(f64, f64)]) -> Result<Self> {
        let ranges = super::per_joint(ranges, self.dof(), "position ranges")?;
        for ((jl, g), &(lo, hi)) in self.joints.iter_mut().zip(&mut self.given).zip(&ranges) {
            jl.position_min = lo;
            jl.position_max = hi;
            g.position_min = true;
            g.position_max = true;
        }
        Limits::new(self.joints.clone())?;
        Ok(self)
    }

    /// Every given velocity, acceleration and jerk limit multiplied by its scale (see
    /// [`Limits::scaled`]); absent ones stay absent.
    pub fn scaled(&self, velocity: f64, acceleration: f64, jerk: f64) -> Result<Self> {
        let l = Limits::new(self.joints.clone())?.scaled(velocity, acceleration, jerk)?;
        Ok(PartialLimits {
            joints: l.joints().to_vec(),
            given: self.given.clone(),
        })
    }

    /// Fills absent acceleration and jerk limits (with the acceleration's directional minimum)
    /// from `from`, joint by joint as `by` says. Joints without a counterpart keep theirs
    /// absent (and [`PartialLimits::complete`] will name them). Velocities and position ranges
    /// are never filled: they belong to the robot the limits describe.
    ///
    /// Errors: [`Error::JointNames`] when `by` is [`FillBy::Name`] and no joint name of `self`
    /// is in `from` (with names on both sides); [`Error::DimensionMismatch`] when `by` is
    /// [`FillBy::Index`] and `from` has fewer joints.
    pub fn fill_from(&self, from: &PartialLimits, by: FillBy) -> Result<Self> {
        let source: Vec<Option<usize>> = match by {
            FillBy::Index => {
                if from.dof() < self.dof() {
                    return Err(Error::DimensionMismatch {
                        what: "joints of the limits filled from (by index)".into(),
                        expected: self.dof(),
                        found: from.dof(),
                    });
                }
                (0..self.dof()).map(Some).collect()
            }
            FillBy::Name => {
                let idx: Vec<Option<usize>> = self
                    .joints
                    .iter()
                    .map(|j| {
                        (!j.name.is_empty())
                            .then(|| from.joints.iter().position(|f| f.name == j.name))
                            .flatten()
                    })
                    .collect();
                if idx.iter().all(Option::is_none) {
                    let names = self.names();
                    return Err(Error::JointNames {
                        data: "filled",
                        missing: names.clone(),
                        names,
                        limit_names: from.names(),
                    });
                }
                idx
            }
        };
        let mut out = self.clone();
        for (j, src) in source.into_iter().enumerate() {
            let Some(s) = src else { continue };
            let (f, fg) = (&from.joints[s], from.given[s]);
            let (t, tg) = (&mut out.joints[j], &mut out.given[j]);
            if !tg.acceleration && fg.acceleration {
                t.acceleration = f.acceleration;
                t.min_acceleration = f.min_acceleration;
                tg.acceleration = true;
            }
            if !tg.jerk && fg.jerk {
                t.jerk = f.jerk;
                tg.jerk = true;
            }
        }
        Limits::new(out.joints.clone())?;
        Ok(out)
    }

    /// The joints at `indices` (into these limits), in that order.
    pub fn select(&self, indices: &[usize]) -> Result<Self> {
        let mut joints = Vec::with_capacity(indices.len());
        let mut given = Vec::with_capacity(indices.len());
        for &i in indices {
            if i >= self.dof() {
                return Err(Error::DimensionMismatch {
                    what: "joint index into the limits".into(),
                    expected: self.dof(),
                    found: i,
                });
            }
            joints.push(self.joints[i].clone());
            given.push(self.given[i]);
        }
        PartialLimits::new(joints, given)
    }

    /// These limits for data (`what`: `"waypoint"`, `"table"`) whose joints are `names`
    /// (`None`: the data names none), matched as [`match_names`] says. Returns the limits in
    /// the data's joint order and the names of the limits' joints left out.
    pub fn for_joints(
        &self,
        what: &'static str,
        names: Option<&[String]>,
    ) -> Result<(Self, Vec<String>)> {
        match match_names(what, names, &self.names())? {
            None => Ok((self.clone(), Vec::new())),
            Some(idx) => Ok((self.select(&idx)?, left_out(&self.names(), &idx))),
        }
    }
}

impl Limits {
    /// The joints at `indices` (into these limits), in that order.
    pub fn select(&self, indices: &[usize]) -> Result<Limits> {
        PartialLimits::from(self.clone())
            .select(indices)?
            .complete(Needs::NONE)
    }

    /// These limits for data (`what`: `"waypoint"`, `"table"`) whose joints are `names`
    /// (`None`: the data names none), matched as [`match_names`] says. Returns the limits in
    /// the data's joint order and the names of the limits' joints left out.
    pub fn for_joints(
        &self,
        what: &'static str,
        names: Option<&[String]>,
    ) -> Result<(Limits, Vec<String>)> {
        let (p, out) = PartialLimits::from(self.clone()).for_joints(what, names)?;
        Ok((p.complete(Needs::NONE)?, out))
    }
}

/// Names of `all` whose index is not in `taken`.
fn left_out(all: &[String], taken: &[usize]) -> Vec<String> {
    all.iter()
        .enumerate()
        .filter(|(i, _)| !taken.contains(i))
        .map(|(_, n)| n.clone())
        .collect()
}

/// How data joints (waypoint or table columns) pair with limit joints.
///
/// When the data names its joints (`Some`) and every limit joint has a distinct non-empty
/// name, each data joint takes the limits of the same name, in any order: returns the index
/// into `limit_names` of each data joint; limit joints no data joint names are left out. A data
/// joint with no limits of its name is [`Error::JointNames`] listing both sets (`what` names
/// the data: `"waypoint"`, `"table"`). Otherwise
/// (either side unnamed) the pairing is by position: `Ok(None)`, and the caller checks that
/// the counts agree.
///
/// ```
/// use trajkit::limits::match_names;
/// let limits = ["a".to_string(), "b".into(), "c".into()];
/// let data = ["c".to_string(), "a".into()];
/// assert_eq!(match_names("waypoint", Some(&data), &limits)?, Some(vec![2, 0]));
/// assert_eq!(match_names("waypoint", None, &limits)?, None);
/// assert!(match_names("waypoint", Some(&["x".to_string()]), &limits).is_err());
/// # Ok::<(), trajkit::Error>(())
/// ```
pub fn match_names(
    what: &'static str,
    data: Option<&[String]>,
    limit_names: &[String],
) -> Result<Option<Vec<usize>>> {
    let Some(data) = data else {
        return Ok(None);
    };
    let limits_named = !limit_names.is_empty()
        && limit_names.iter().all(|n| !n.is_empty())
        && limit_names
            .iter()
            .enumerate()
            .all(|(i, n)| !limit_names[..i].contains(n));
    if !limits_named {
        return Ok(None);
    }
    for (i, n) in data.iter().enumerate() {
        if data[..i].contains(n) {
            return Err(Error::InvalidValue {
                field: format!("joint name '{n}' (column {})", i + 1),
                value: i as f64 + 1.0,
                reason: "is given to two columns",
            });
        }
    }
    let idx: Vec<Option<usize>> = data
        .iter()
        .map(|n| limit_names.iter().position(|l| l == n))
        .collect();
    let missing: Vec<String> = data
        .iter()
        .zip(&idx)
        .filter(|(_, i)| i.is_none())
        .map(|(n, _)| n.clone())
        .collect();
    if !missing.is_empty() {
        return Err(Error::JointNames {
            data: what,
            missing,
            names: data.to_vec(),
            limit_names: limit_names.to_vec(),
        });
    }
    Ok(Some(idx.into_iter().flatten().collect()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn missing_limits_are_named_and_explicit_infinity_is_given() {
        let p = PartialLimits::unnamed(2).unwrap();
        let e = p.complete(Needs::ALL).unwrap_err();
        assert_eq!(
            e,
            Error::MissingLimit {
                joint: 0,
                name: String::new(),
                field: "velocity"
            }
        );
        let p = p
            .with_override(Order::Velocity, &[1.0])
            .unwrap()
            .with_override(Order::Acceleration, &[2.0, 3.0])
            .unwrap()
            .with_override(Order::Jerk, &[f64::INFINITY])
            .unwrap();
        assert_eq!(
            p.missing(Needs::ALL),
            vec![(0, "position range"), (1, "position range")]
        );
        let l = p
            .clone()
            .with_position_range(&[(f64::NEG_INFINITY, f64::INFINITY)])
            .unwrap()
            .complete(Needs::ALL)
            .unwrap();
        assert_eq!(l.joint(1).acceleration, 3.0);
        assert!(l.joint(0).jerk.is_infinite());
        // Not needed: absent fields become unlimited.
        let l = p
            .complete(Needs {
                position: false,
                ..Needs::ALL
            })
            .unwrap();
        assert!(l.joint(0).position_max.is_infinite());
        assert!(PartialLimits::unnamed(2)
            .unwrap()
            .with_position_range(&[(1.0, 0.0)])
            .is_err());
    }

    #[test]
    fn fill_by_name_and_by_index() {
        let mut urdf = PartialLimits::from(Limits::preset("ur5e").unwrap());
        for g in &mut urdf.given {
            g.acceleration = false;
            g.jerk = false;
        }
        let panda = PartialLimits::from(Limits::preset("panda").unwrap());
        // By name: no UR joint is a Panda joint.
        let e = urdf.fill_from(&panda, FillBy::Name).unwrap_err();
        assert!(matches!(e, Error::JointNames { .. }), "{e}");
        // By index, on request: the Panda's first six joints.
        let full = urdf
            .fill_from(&panda, FillBy::Index)
            .unwrap()
            .complete(Needs::ALL)
            .unwrap();
        assert_eq!(full.joint(1).acceleration, 7.5);
        assert_eq!(full.joint(5).jerk, 10000.0);
        let ur = PartialLimits::from(Limits::preset("ur5e").unwrap());
        let full = urdf.fill_from(&ur, FillBy::Name).unwrap();
        assert!(full.missing(Needs::ALL).is_empty());
        // Given values are never overwritten.
        let mut one = PartialLimits::from(Limits::preset("panda").unwrap());
        one.given[2].jerk = false;
        one.joints[2].jerk = f64::INFINITY;
        let filled = one.fill_from(&panda, FillBy::Name).unwrap();
        assert_eq!(filled.joint(2).jerk, 5000.0);
        assert_eq!(filled.joint(0).acceleration, 15.0);
        assert!(PartialLimits::unnamed(8)
            .unwrap()
            .fill_from(&panda, FillBy::Index)
            .is_err());
    }

    #[test]
    fn names_pair_data_with_limits() {
        let lim = names(&["a", "b", "c"]);
        assert_eq!(
            match_names("waypoint", Some(&names(&["b", "c", "a"])), &lim).unwrap(),
            Some(vec![1, 2, 0])
        );
        let e = match_names("waypoint", Some(&names(&["a", "x", "y"])), &lim).unwrap_err();
        assert_eq!(
            e.to_string(),
            "no limits for waypoint joint(s) x, y: waypoint joints [a, x, y], limit joints [a, b, c]"
        );
        assert!(match_names("waypoint", Some(&names(&["a", "a"])), &lim).is_err());
        // Unnamed limits: by position.
        assert_eq!(
            match_names("table", Some(&names(&["a", "b"])), &names(&["", ""])).unwrap(),
            None
        );
        let panda = Limits::preset("panda").unwrap();
        let (l, out) = panda
            .for_joints("waypoint", Some(&names(&["panda_joint7", "panda_joint1"])))
            .unwrap();
        assert_eq!(l.joint(0).name, "panda_joint7");
        assert_eq!(l.joint(1).velocity, 2.175);
        assert_eq!(out.len(), 5);
    }
}
