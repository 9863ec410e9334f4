//! Orientation interpolation: unit quaternions, slerp, and a C² interpolating spline on SO(3)
//! (a cumulative cubic B-spline) with angular velocity and acceleration.
//!
//! Conventions: a quaternion is `w + xi + yj + zk`, Hamilton product, active rotation
//! `v ↦ q v q*`. A rotation vector φ has angle `‖φ‖` about axis `φ/‖φ‖`;
//! `exp(φ) = (cos(‖φ‖/2), sin(‖φ‖/2) φ/‖φ‖)` and [`Quat::log`] is its inverse with angle in
//! `[0, π]`. Angular velocities and accelerations are in the world frame, in rad/s and rad/s².

use crate::error::{Error, Result};
use crate::spline::banded::Banded;
use crate::spline::basis::{basis_ders, find_span, K1};
use crate::spline::validate;
use std::ops::Mul;

/// A unit quaternion `w + xi + yj + zk` (a rotation): Hamilton product (`a * b` applies `b`
/// first), active rotation `v ↦ q v q*`. [`Quat::exp`] maps a rotation vector φ (angle `‖φ‖`
/// about `φ/‖φ‖`) to its rotation and [`Quat::log`] back (angle in `[0, π]`); angular
/// velocities are world-frame. The orientation DMP ([`crate::primitives::QuaternionDmp`])
/// uses the same type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quat {
    /// Scalar part.
    pub w: f64,
    /// i component.
    pub x: f64,
    /// j component.
    pub y: f64,
    /// k component.
    pub z: f64,
}

/// Hamilton product `a ⊗ b` (apply `b` first, then `a`).
impl Mul for Quat {
    type Output = Quat;
    fn mul(self, o: Quat) -> Quat {
        Quat {
            w: self.w * o.w - self.x * o.x - self.y * o.y - self.z * o.z,
            x: self.w * o.x + self.x * o.w + self.y * o.z - self.z * o.y,
            y: self.w * o.y - self.x * o.z + self.y * o.w + self.z * o.x,
            z: self.w * o.z + self.x * o.y - self.y * o.x + self.z * o.w,
        }
    }
}

/// The cross product `a × b`.
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a + b`.
pub(crate) fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `s · a`.
pub(crate) fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

impl Quat {
    /// The identity rotation.
    pub const IDENTITY: Quat = Quat {
        w: 1.0,
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };

    /// The normalized quaternion `(w, x, y, z)`; a zero or non-finite input is an error.
    pub fn new(w: f64, x: f64, y: f64, z: f64) -> Result<Quat> {
        let n = (w * w + x * x + y * y + z * z).sqrt();
        if !(n.is_finite() && n > 0.0) {
            return Err(Error::InvalidValue {
                field: "quaternion norm".into(),
                value: n,
                reason: "is zero or not finite (not a rotation)",
            });
        }
        Ok(Quat {
            w: w / n,
            x: x / n,
            y: y / n,
            z: z / n,
        })
    }

    /// Rotation by `angle` (radians) about `axis` (any non-zero length).
    pub fn from_axis_angle(axis: [f64; 3], angle: f64) -> Result<Quat> {
        let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        if !(n.is_finite() && n > 0.0 && angle.is_finite()) {
            return Err(Error::InvalidValue {
                field: "rotation axis length".into(),
                value: n,
                reason: "is zero or not finite, or the angle is not finite",
            });
        }
        Ok(Quat::exp(scale(axis, angle / n)))
    }

    /// `exp(φ)` of a rotation vector.
    pub fn exp(phi: [f64; 3]) -> Quat {
        let th = (phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2]).sqrt();
        let (w, k) = if th < 1e-6 {
            // Taylor series, exact to rounding for such small angles.
            let t2 = th * th;
            (
                1.0 - t2 / 8.0 + t2 * t2 / 384.0,
                0.5 - t2 / 48.0 + t2 * t2 / 3840.0,
            )
        } else {
            ((0.5 * th).cos(), (0.5 * th).sin() / th)
        };
        Quat {
            w,
            x: k * phi[0],
            y: k * phi[1],
            z: k * phi[2],
        }
    }

    /// The rotation vector of this rotation, angle in `[0, π]`.
    pub fn log(self) -> [f64; 3] {
        let q = if self.w < 0.0 { self.neg() } else { self };
        let s = (q.x * q.x + q.y * q.y + q.z * q.z).sqrt();
        let k = if s < 1e-8 {
            // θ / s with θ = 2 atan2(s, w) ≈ 2 s / w (1 − s²/(3w²)).
            2.0 / q.w * (1.0 - s * s / (3.0 * q.w * q.w))
        } else {
            2.0 * s.atan2(q.w) / s
        };
        [k * q.x, k * q.y, k * q.z]
    }

    /// The same rotation with every component negated (the other hemisphere).
    pub(crate) fn neg(self) -> Quat {
        Quat {
            w: -self.w,
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }

    /// The inverse rotation (conjugate).
    pub fn conj(self) -> Quat {
        Quat {
            w: self.w,
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }

    /// Rotates a vector.
    pub fn rotate(self, v: [f64; 3]) -> [f64; 3] {
        let u = [self.x, self.y, self.z];
        let t = scale(cross(u, v), 2.0);
        add(add(v, scale(t, self.w)), cross(u, t))
    }

    /// The rotation angle between two orientations, in `[0, π]`.
    pub fn angle_to(self, o: Quat) -> f64 {
        let l = self.conj().mul(o).log();
        (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt()
    }

    /// Components as `[w, x, y, z]`.
    pub fn to_array(self) -> [f64; 4] {
        [self.w, self.x, self.y, self.z]
    }

    /// Spherical linear interpolation along the shorter arc: `self` at `t = 0`, `o` at
    /// `t = 1`, constant angular velocity `slerp_velocity(o)` in between. `t` is clamped to
    /// `[0, 1]`.
    pub fn slerp(self, o: Quat, t: f64) -> Quat {
        let t = if t.is_nan() { t } else { t.clamp(0.0, 1.0) };
        let phi = self.conj().mul(o).log();
        self.mul(Quat::exp(scale(phi, t)))
    }

    /// The world-frame angular velocity of `slerp(self, o, t)` per unit `t`.
    pub fn slerp_velocity(self, o: Quat) -> [f64; 3] {
        self.rotate(self.conj().mul(o).log())
    }

    /// The time derivative `q̇ = ½ (0, ω) ⊗ q` of this orientation `q` turning with the
    /// world-frame angular velocity `omega` (rad/s), as `[w, x, y, z]` (not a rotation itself).
    pub fn derivative(self, omega: [f64; 3]) -> [f64; 4] {
        (Quat::pure(omega) * self).to_array().map(|v| 0.5 * v)
    }

    /// The second time derivative `q̈ = ½ ((0, ω̇) ⊗ q + (0, ω) ⊗ q̇)` of this orientation `q`
    /// turning with the world-frame angular velocity `omega` (rad/s) and angular acceleration
    /// `omega_dot` (rad/s²), as `[w, x, y, z]`.
    pub fn second_derivative(self, omega: [f64; 3], omega_dot: [f64; 3]) -> [f64; 4] {
        let d = self.derivative(omega);
        let qd = Quat {
            w: d[0],
            x: d[1],
            y: d[2],
            z: d[3],
        };
        let a = (Quat::pure(omega_dot) * self).to_array();
        let b = (Quat::pure(omega) * qd).to_array();
        std::array::from_fn(|c| 0.5 * (a[c] + b[c]))
    }

    /// The pure quaternion `(0, v)` (a vector, not a rotation), for products.
    fn pure(v: [f64; 3]) -> Quat {
        Quat {
            w: 0.0,
            x: v[0],
            y: v[1],
            z: v[2],
        }
    }
}

/// A C² orientation trajectory: a cumulative cubic B-spline on SO(3),
/// `R(t) = C_{l−3} ∏_{j=1..3} exp(B̃_j(t) Ω_j)`, `Ω_j = log(C_{l−4+j}⁻¹ C_{l−3+j})`, with the
/// cumulative cubic basis `B̃_j = Σ_{r≥j} N_{l−3+r}` on the knots (the keyframe times, extended
/// by three mirrored steps at each end).
///
/// [`SO3Spline::interpolate`] finds control rotations `C_{−1} … C_n` so that the spline passes
/// through keyframes at increasing times; the rotation beyond each end is the reflection of its
/// neighbour (`C_{−1} = C_0 (C_0⁻¹ C_1)⁻¹`), which for evenly spaced times gives zero angular
/// acceleration at both ends: about a fixed axis the angle is then the natural cubic spline of
/// the keyframe angles. Angular velocity and acceleration are analytic (body-frame recursions,
/// returned in the world frame) and continuous everywhere. Times outside the interval are
/// clamped.
///
/// ```
/// use trajkit::spline::{Quat, SO3Spline};
/// let k = [
///     Quat::IDENTITY,
///     Quat::from_axis_angle([0.0, 0.0, 1.0], 1.0)?,
///     Quat::from_axis_angle([1.0, 1.0, 0.0], 0.5)?,
/// ];
/// let sp = SO3Spline::interpolate(&[0.0, 0.4, 1.5], &k)?;
/// assert!(sp.eval(0.4).angle_to(k[1]) < 1e-12);
/// let w = sp.angular_velocity(0.7);
/// assert!(w.iter().all(|v| v.is_finite()));
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SO3Spline {
    /// Knots: n + 6 for n + 2 control rotations; the interval is [t[3], t[n + 2]].
    t: Vec<f64>,
    /// Control rotations C_{−1} … C_n.
    c: Vec<Quat>,
}

/// Knots for keyframe times: the times, with three steps mirrored beyond each end.
fn extended_knots(times: &[f64]) -> Vec<f64> {
    let n = times.len();
    let (h0, h1) = (times[1] - times[0], times[n - 1] - times[n - 2]);
    let mut t = vec![times[0] - 3.0 * h0, times[0] - 2.0 * h0, times[0] - h0];
    t.extend_from_slice(times);
    t.extend_from_slice(&[
        times[n - 1] + h1,
        times[n - 1] + 2.0 * h1,
        times[n - 1] + 3.0 * h1,
    ]);
    t
}

fn normalized(q: &[Quat]) -> Result<Vec<Quat>> {
    q.iter().map(|q| Quat::new(q.w, q.x, q.y, q.z)).collect()
}

/// The quasi-Newton matrix of [`SO3Spline::interpolate`], factored: the (linear, Euclidean)
/// collocation system of the cubic B-spline on knots `t` at the keyframe times, with the
/// reflected end rotations folded in; exact in one step about a fixed axis.
fn collocation_matrix(t: &[f64], times: &[f64]) -> Result<Banded> {
    let n = times.len();
    let mut a = Banded::zeros(n, 2, 2);
    for (i, &ti) in times.iter().enumerate() {
        let l = find_span(t, 3, ti);
        let mut nb = [0.0; K1];
        basis_ders(t, 3, l, ti, 0, &mut nb);
        let mut row = vec![0.0; n];
        for r in 0..4 {
            let j = l - 3 + r; // index into c = [C_{−1}, C_0, …, C_n]
            let w = nb[r];
            if j == 0 {
                row[0] += 2.0 * w;
                row[1] -= w;
            } else if j == n + 1 {
                row[n - 1] += 2.0 * w;
                row[n - 2] -= w;
            } else {
                row[j - 1] += w;
            }
        }
        for (col, &v) in row.iter().enumerate() {
            if v != 0.0 {
                a.set(i, col, v);
            }
        }
    }
    a.factor()
        .map_err(|_| Error::Infeasible("SO(3) spline: singular collocation system".into()))?;
    Ok(a)
}

/// World-frame keyframe residuals of `sp` into `delta` (3 per keyframe); returns the largest
/// angle. Left perturbations of all control rotations move the curve (to first order) by the
/// same combination of them.
fn keyframe_residual(sp: &SO3Spline, times: &[f64], keys: &[Quat], delta: &mut [f64]) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..keys.len() {
        let d = keys[i].mul(sp.eval(times[i]).conj()).log();
        worst = worst.max((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt());
        delta[i * 3..i * 3 + 3].copy_from_slice(&d);
    }
    worst
}

impl SO3Spline {
    /// The interpolating spline through `keys` at increasing finite `times` (at least 2 of
    /// each, as many times as keys). The control rotations are found by a damped quasi-Newton
    /// iteration (the B-spline collocation system, solved once by banded LU) that stops at
    /// 1e-14 rad. Like a Euclidean interpolating spline, the control polygon swings wider than
    /// the keyframes where they turn sharply; a cumulative spline needs consecutive control
    /// rotations less than π apart, so keyframes that are far apart *and* turn sharply (e.g.
    /// 1.4 rad steps that reverse direction) are refused with [`Error::Infeasible`]. Steps of up
    /// to about 1 rad are safe.
    pub fn interpolate(times: &[f64], keys: &[Quat]) -> Result<SO3Spline> {
        validate::increasing("keyframe times", times, 2)?;
        if keys.len() != times.len() {
            return Err(Error::DimensionMismatch {
                what: "keyframe count (one per time)".into(),
                expected: times.len(),
                found: keys.len(),
            });
        }
        let n = keys.len();
        let keys = normalized(keys)?;
        let t = extended_knots(times);
        let mut c = Vec::with_capacity(n + 2);
        c.push(keys[0]);
        c.extend_from_slice(&keys);
        c.push(keys[n - 1]);
        let mut sp = SO3Spline { t, c };
        let a = collocation_matrix(&sp.t, times)?;
        if sp.newton(&a, times, &keys) {
            return Ok(sp);
        }
        sp.reflect_ends();
        let worst = (0..n)
            .map(|i| sp.eval(times[i]).angle_to(keys[i]))
            .fold(0.0, f64::max);
        if worst <= 1e-12 {
            return Ok(sp);
        }
        let widest =
            sp.c.windows(2)
                .map(|w| w[0].angle_to(w[1]))
                .fold(0.0, f64::max);
        Err(Error::Infeasible(format!(
            "SO(3) spline: no control rotations found (keyframe error {worst:e} rad; widest control step {widest:.3} rad): the keyframes turn too sharply for a cumulative spline, whose control rotations must stay less than π apart"
        )))
    }

    /// [`SO3Spline::interpolate`] with keyframes `dt > 0` apart from `t0`.
    pub fn interpolate_uniform(t0: f64, dt: f64, keys: &[Quat]) -> Result<SO3Spline> {
        crate::error::finite(|| "SO(3) spline start time".into(), t0)?;
        crate::error::positive(|| "SO(3) spline time step".into(), dt)?;
        let times: Vec<f64> = (0..keys.len()).map(|i| t0 + dt * i as f64).collect();
        Self::interpolate(&times, keys)
    }

    /// A spline from its control rotations `C_{−1} … C_n` (at least 4) on uniform knots `dt`
    /// apart: it approximates them (B-spline) and spans `[t0, t0 + (len − 3)·dt]`.
    pub fn from_control_rotations(t0: f64, dt: f64, controls: &[Quat]) -> Result<SO3Spline> {
        crate::error::finite(|| "SO(3) spline start time".into(), t0)?;
        crate::error::positive(|| "SO(3) spline time step".into(), dt)?;
        if controls.len() < 4 {
            return Err(Error::TooFewWaypoints {
                needed: 4,
                found: controls.len(),
            });
        }
        let c = normalized(controls)?;
        let t = (0..c.len() + 4)
            .map(|i| t0 + dt * (i as f64 - 3.0))
            .collect();
        Ok(SO3Spline { t, c })
    }

    /// The time interval.
    pub fn interval(&self) -> (f64, f64) {
        (self.t[3], self.t[self.c.len()])
    }

    /// The control rotations `C_{−1} … C_n`.
    pub fn control_rotations(&self) -> &[Quat] {
        &self.c
    }

    /// Damped quasi-Newton on the interior control rotations (at most 100 steps, each halved
    /// until the largest keyframe error decreases, down to 1e-4); true once that error is at
    /// most 1e-14 rad (the ends are then reflected), false when it stalls or is not finite.
    fn newton(&mut self, a: &Banded, times: &[f64], keys: &[Quat]) -> bool {
        let n = keys.len();
        let mut delta = vec![0.0; n * 3];
        let mut trial = vec![0.0; n * 3];
        self.reflect_ends();
        let mut worst = keyframe_residual(self, times, keys, &mut delta);
        for _ in 0..100 {
            if worst <= 1e-14 {
                return true;
            }
            if !worst.is_finite() {
                break;
            }
            a.solve(&mut delta, 3);
            // Backtracking: halve the step until the largest keyframe error decreases.
            let base = self.c.clone();
            let mut step = 1.0;
            loop {
                for i in 0..n {
                    let d = scale([delta[i * 3], delta[i * 3 + 1], delta[i * 3 + 2]], step);
                    self.c[i + 1] = Quat::exp(d).mul(base[i + 1]);
                }
                self.reflect_ends();
                let w = keyframe_residual(self, times, keys, &mut trial);
                if w < worst || step < 1e-4 {
                    worst = w;
                    std::mem::swap(&mut delta, &mut trial);
                    break;
                }
                step *= 0.5;
            }
        }
        false
    }

    /// C_{−1} = C_0 (C_0⁻¹ C_1)⁻¹, likewise at the other end.
    fn reflect_ends(&mut self) {
        let m = self.c.len();
        let a = self.c[1].conj().mul(self.c[2]).log();
        self.c[0] = self.c[1].mul(Quat::exp(scale(a, -1.0)));
        let b = self.c[m - 2].conj().mul(self.c[m - 3]).log();
        self.c[m - 1] = self.c[m - 2].mul(Quat::exp(scale(b, -1.0)));
    }

    /// The orientation at time `t` (clamped). A NaN time gives a NaN quaternion.
    pub fn eval(&self, t: f64) -> Quat {
        self.eval_all(t).0
    }

    /// Orientation, world angular velocity (rad/s) and world angular acceleration (rad/s²) at
    /// `t` (clamped).
    pub fn eval_all(&self, t: f64) -> (Quat, [f64; 3], [f64; 3]) {
        if t.is_nan() {
            let nan = f64::NAN;
            let q = Quat {
                w: nan,
                x: nan,
                y: nan,
                z: nan,
            };
            return (q, [nan; 3], [nan; 3]);
        }
        let (a, e) = self.interval();
        let t = if t < a {
            a
        } else if t > e {
            e
        } else {
            t
        };
        let l = find_span(&self.t, 3, t);
        let mut nd = [[0.0; K1]; 3];
        for (m, row) in nd.iter_mut().enumerate() {
            basis_ders(&self.t, 3, l, t, m, &mut row[..]);
        }
        // Cumulative basis B̃_j = Σ_{r ≥ j} N_r and its derivatives, j = 1..3.
        let cum = |m: usize, j: usize| (j..4).map(|r| nd[m][r]).sum::<f64>();
        let mut r = self.c[l - 3];
        let mut w = [0.0; 3];
        let mut al = [0.0; 3];
        for j in 1..4 {
            let om = self.c[l + j - 4].conj().mul(self.c[l + j - 3]).log();
            let aj = Quat::exp(scale(om, cum(0, j)));
            r = r.mul(aj);
            let inv = aj.conj();
            let dw = scale(om, cum(1, j));
            w = add(inv.rotate(w), dw);
            al = add(add(inv.rotate(al), scale(om, cum(2, j))), cross(w, dw));
        }
        (r, r.rotate(w), r.rotate(al))
    }

    /// World angular velocity at `t` (rad/s).
    pub fn angular_velocity(&self, t: f64) -> [f64; 3] {
        self.eval_all(t).1
    }

    /// World angular acceleration at `t` (rad/s²).
    pub fn angular_acceleration(&self, t: f64) -> [f64; 3] {
        self.eval_all(t).2
    }
}
