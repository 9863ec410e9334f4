//! The inverse-dynamics model behind torque limits, below both [`crate::topp`] (which
//! constrains torques through it) and [`crate::dynamics`] (which implements it for a serial
//! chain read from a URDF).

/// A robot's inverse dynamics τ = ID(q, q̇, q̈) = M(q)q̈ + C(q, q̇)q̇ + g(q), implemented by the
/// user (from a rigid-body library or a hand-derived model) or by
/// [`SerialChain`](crate::dynamics::SerialChain) from a URDF.
///
/// TOPP-RA uses that ID is affine in q̈ and quadratic in q̇ (no friction terms here: see
/// [`JointTorque::with_coulomb_friction`](crate::topp::JointTorque::with_coulomb_friction)).
///
/// ```
/// use trajkit::InverseDynamics;
///
/// /// A point mass `m` on a massless arm of length `l` turning about a vertical axis.
/// struct Turntable { m: f64, l: f64 }
///
/// impl InverseDynamics for Turntable {
///     fn dof(&self) -> usize { 1 }
///     fn torque(&self, _q: &[f64], _qd: &[f64], qdd: &[f64], tau: &mut [f64]) {
///         tau[0] = self.m * self.l * self.l * qdd[0];
///     }
/// }
///
/// let mut tau = [0.0];
/// Turntable { m: 2.0, l: 0.5 }.torque(&[0.0], &[0.0], &[3.0], &mut tau);
/// assert_eq!(tau[0], 1.5);
/// ```
pub trait InverseDynamics {
    /// Number of joints.
    fn dof(&self) -> usize;
    /// Writes the joint torques for `q`, `qd`, `qdd` into `tau` (all of length `dof()`).
    fn torque(&self, q: &[f64], qd: &[f64], qdd: &[f64], tau: &mut [f64]);
}
