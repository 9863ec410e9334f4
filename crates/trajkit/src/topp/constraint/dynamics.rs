//! Constraints that read the robot's model through user code: joint torque through an
//! [`InverseDynamics`] model ([`JointTorque`]) and end-effector speed through a [`Jacobian`]
//! ([`EndEffectorSpeed`]).
//!
//! # Precision contract
//! Rows are written exactly as the formulas in the item docs, from the user model's values at
//! the path point (no linearisation or padding). They have no exact bound between gridpoints
//! ([`super::Constraint::excess_on_cubic`] is `None`): the solver checks them at sample points.

use super::{check_ranges, Constraint, ConstraintRows, InverseDynamics, PathPoint};
use crate::error::{Error, Result};
use crate::limits::Limits;

/// Joint torque limits `τ_min ≤ ID(q, q̇, q̈) + f_c·sign(q̇) ≤ τ_max`.
///
/// With q̇ = σ′ṡ and q̈ = σ′u + σ″x the torque is `a·u + b·x + c` with
/// `c = ID(σ, 0, 0)`, `a = ID(σ, 0, σ′) − c` and `b = ID(σ, σ′, σ″) − c`. Coulomb friction
/// `f_c·sign(σ′_j)` (ṡ ≥ 0) is added to `c` when given.
pub struct JointTorque<D: InverseDynamics> {
    dynamics: D,
    lo: Vec<f64>,
    hi: Vec<f64>,
    coulomb: Vec<f64>,
}

impl<D: InverseDynamics> JointTorque<D> {
    /// Torque limits per joint: `lo[j] ≤ 0 ≤ hi[j]`.
    pub fn new(dynamics: D, lo: &[f64], hi: &[f64]) -> Result<Self> {
        check_ranges("torque", lo, hi)?;
        if dynamics.dof() != hi.len() {
            return Err(Error::DimensionMismatch {
                what: "inverse dynamics joint count".into(),
                expected: hi.len(),
                found: dynamics.dof(),
            });
        }
        Ok(JointTorque {
            dynamics,
            coulomb: vec![0.0; hi.len()],
            lo: lo.to_vec(),
            hi: hi.to_vec(),
        })
    }

    /// Symmetric torque limits `±effort` from the `effort` entries of `limits`.
    pub fn from_limits(dynamics: D, limits: &Limits) -> Result<Self> {
        let mut hi = Vec::with_capacity(limits.dof());
        for (j, jl) in limits.joints().iter().enumerate() {
            match jl.effort {
                Some(e) => hi.push(e),
                None => {
                    return Err(Error::InvalidValue {
                        field: format!("joint {} effort limit", j + 1),
                        value: f64::NAN,
                        reason: "is missing (needed for torque limits)",
                    })
                }
            }
        }
        let lo: Vec<f64> = hi.iter().map(|h| -h).collect();
        Self::new(dynamics, &lo, &hi)
    }

    /// Adds Coulomb friction `f_c[j]·sign(q̇_j)` (each `f_c[j] ≥ 0`).
    pub fn with_coulomb_friction(mut self, fc: &[f64]) -> Result<Self> {
        if fc.len() != self.hi.len() {
            return Err(Error::DimensionMismatch {
                what: "Coulomb friction coefficients".into(),
                expected: self.hi.len(),
                found: fc.len(),
            });
        }
        for (j, &f) in fc.iter().enumerate() {
            if !(f >= 0.0 && f.is_finite()) {
                return Err(Error::InvalidValue {
                    field: format!("joint {} Coulomb friction", j + 1),
                    value: f,
                    reason: "is not a finite number >= 0",
                });
            }
        }
        self.coulomb = fc.to_vec();
        Ok(self)
    }
}

impl<D: InverseDynamics> Constraint for JointTorque<D> {
    fn name(&self) -> String {
        "joint torque".into()
    }
    fn dof(&self) -> usize {
        self.hi.len()
    }
    fn write(&self, p: &PathPoint<'_>, out: &mut ConstraintRows) {
        let n = self.hi.len();
        let zero = vec![0.0; n];
        let mut c = vec![0.0; n];
        let mut a = vec![0.0; n];
        let mut b = vec![0.0; n];
        self.dynamics.torque(p.q, &zero, &zero, &mut c);
        self.dynamics.torque(p.q, &zero, p.dq, &mut a);
        self.dynamics.torque(p.q, p.dq, p.ddq, &mut b);
        for j in 0..n {
            let friction = self.coulomb[j] * p.dq[j].signum() * (p.dq[j] != 0.0) as u8 as f64;
            out.interval(
                a[j] - c[j],
                b[j] - c[j],
                c[j] + friction,
                self.lo[j],
                self.hi[j],
            );
        }
    }
}

/// A user-supplied kinematic Jacobian: the linear velocity of a point (the end effector) is
/// `J(q)·q̇`, with `J` row-major `rows() × dof()`.
pub trait Jacobian {
    /// Number of joints.
    fn dof(&self) -> usize;
    /// Number of rows (3 for a linear velocity in space, 2 in a plane).
    fn rows(&self) -> usize;
    /// Writes J(q) row-major into `out` (`rows() · dof()` entries).
    fn jacobian(&self, q: &[f64], out: &mut [f64]);
}

/// End-effector speed limit `‖J(q)·σ′·ṡ‖ ≤ v_max`: a bound on x = ṡ².
pub struct EndEffectorSpeed<J: Jacobian> {
    jacobian: J,
    v_max: f64,
}

impl<J: Jacobian> EndEffectorSpeed<J> {
    /// Limits the speed of the point whose Jacobian is `jacobian` to `v_max` (> 0).
    pub fn new(jacobian: J, v_max: f64) -> Result<Self> {
        crate::error::positive(|| "end-effector speed limit".into(), v_max)?;
        Ok(EndEffectorSpeed { jacobian, v_max })
    }
}

impl<J: Jacobian> Constraint for EndEffectorSpeed<J> {
    fn name(&self) -> String {
        "end-effector speed".into()
    }
    fn dof(&self) -> usize {
        self.jacobian.dof()
    }
    fn write(&self, p: &PathPoint<'_>, out: &mut ConstraintRows) {
        let (r, n) = (self.jacobian.rows(), self.jacobian.dof());
        let mut jm = vec![0.0; r * n];
        self.jacobian.jacobian(p.q, &mut jm);
        let mut sq = 0.0;
        for i in 0..r {
            let v: f64 = (0..n).map(|j| jm[i * n + j] * p.dq[j]).sum();
            sq += v * v;
        }
        if sq > 0.0 {
            out.x_at_most(self.v_max * self.v_max / sq);
        }
    }
}
