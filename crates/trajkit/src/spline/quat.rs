//! Orientation interpolation: unit quaternions, slerp, and a C² interpolating spline on SO(3)
//! (a cumulative cubic B-spline) with angular velocity and acceleration.
//!
//! Conventions: a quaternion is `w + xi + yj + zk`, Hamilton product, active rotation
//! `v ↦ q v q*`. A rotation vector φ has angle `‖φ‖` about axis `φ/‖φ‖`;
//! `exp(φ) = (cos(‖φ‖/2), sin(‖φ‖/2) φ/‖φ‖)` and [`Quat::log`] is its inverse with angle in
//! `[0, π]`. Angular velocities and accelerations are in the world frame, in rad/s and rad/s².

use crate::error::{Error, Result};
use std::ops::Mul;

/// A unit quaternion (rotation).
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

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
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

    fn neg(self) -> Quat {
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
}

/// A C² orientation trajectory: a cumulative cubic B-spline on SO(3) with uniform knots,
/// `R(t) = C_{i−1} ∏_{j=1..3} exp(B̃_j(u) Ω_j)`, `Ω_j = log(C_{i+j−2}⁻¹ C_{i+j−1})`,
/// `u = (t − t_i)/Δt`, with cumulative cubic basis `B̃_j`.
///
/// [`SO3Spline::interpolate`] finds the control rotations so that the spline passes through
/// keyframes at `t_0 + iΔt` (zero angular acceleration at both ends, the SO(3) analogue of the
/// natural cubic spline: about a fixed axis the angle *is* the natural cubic spline of the
/// keyframe angles). Angular velocity and acceleration are analytic (body-frame recursions,
/// returned in the world frame); they are continuous everywhere. Times outside the interval are
/// clamped.
///
/// ```
/// use trajkit::spline::{Quat, SO3Spline};
/// let k = [
///     Quat::IDENTITY,
///     Quat::from_axis_angle([0.0, 0.0, 1.0], 1.0)?,
///     Quat::from_axis_angle([1.0, 1.0, 0.0], 0.5)?,
/// ];
/// let sp = SO3Spline::interpolate(0.0, 0.5, &k)?;
/// assert!(sp.eval(0.5).angle_to(k[1]) < 1e-12);
/// let w = sp.angular_velocity(0.7);
/// assert!(w.iter().all(|v| v.is_finite()));
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SO3Spline {
    t0: f64,
    dt: f64,
    /// Control rotations C_{−1} … C_n (n + 2 of them for n keyframes).
    c: Vec<Quat>,
}

impl SO3Spline {
    /// The interpolating spline through `keys` (at least 2) at times `t0 + i·dt`, `dt > 0`.
    /// Consecutive keyframes should be less than π apart; the control rotations are found by a
    /// fixed-point iteration that stops at 1e-14 rad, and an error is returned if it does not
    /// converge.
    pub fn interpolate(t0: f64, dt: f64, keys: &[Quat]) -> Result<SO3Spline> {
        crate::error::finite(|| "SO(3) spline start time".into(), t0)?;
        crate::error::positive(|| "SO(3) spline knot spacing".into(), dt)?;
        let n = keys.len();
        if n < 2 {
            return Err(Error::TooFewWaypoints {
                needed: 2,
                found: n,
            });
        }
        let keys: Vec<Quat> = keys
            .iter()
            .map(|q| Quat::new(q.w, q.x, q.y, q.z))
            .collect::<Result<_>>()?;
        let mut c = Vec::with_capacity(n + 2);
        c.push(keys[0]);
        c.extend_from_slice(&keys);
        c.push(keys[n - 1]);
        let mut sp = SO3Spline { t0, dt, c };
        for _ in 0..500 {
            sp.reflect_ends();
            let mut worst = 0.0f64;
            for i in 0..n {
                let r = sp.at_knot(i);
                let d = r.conj().mul(keys[i]).log();
                let m = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                worst = worst.max(m);
                // Jacobi step; the diagonal weight of the collocation is 4/6.
                sp.c[i + 1] = sp.c[i + 1].mul(Quat::exp(scale(d, 1.5)));
            }
            if worst <= 1e-14 {
                sp.reflect_ends();
                return Ok(sp);
            }
            if !worst.is_finite() {
                break;
            }
        }
        sp.reflect_ends();
        let worst = (0..n)
            .map(|i| sp.at_knot(i).angle_to(keys[i]))
            .fold(0.0, f64::max);
        if worst <= 1e-12 {
            return Ok(sp);
        }
        Err(Error::Infeasible(format!(
            "SO(3) spline: control rotations did not converge (keyframe error {worst:e} rad); keyframes more than π apart?"
        )))
    }

    /// A spline from its control rotations `C_{−1} … C_n` (at least 4) directly: it
    /// approximates them (B-spline), spanning `[t0, t0 + (len − 3)·dt]`.
    pub fn from_control_rotations(t0: f64, dt: f64, controls: &[Quat]) -> Result<SO3Spline> {
        crate::error::finite(|| "SO(3) spline start time".into(), t0)?;
        crate::error::positive(|| "SO(3) spline knot spacing".into(), dt)?;
        if controls.len() < 4 {
            return Err(Error::TooFewWaypoints {
                needed: 4,
                found: controls.len(),
            });
        }
        let c = controls
            .iter()
            .map(|q| Quat::new(q.w, q.x, q.y, q.z))
            .collect::<Result<_>>()?;
        Ok(SO3Spline { t0, dt, c })
    }

    /// The time interval `[t0, t_end]`.
    pub fn interval(&self) -> (f64, f64) {
        (self.t0, self.t0 + (self.c.len() - 3) as f64 * self.dt)
    }

    /// The control rotations `C_{−1} … C_n`.
    pub fn control_rotations(&self) -> &[Quat] {
        &self.c
    }

    /// Natural ends: C_{−1} = C_0 (C_0⁻¹ C_1)⁻¹, likewise at the other end.
    fn reflect_ends(&mut self) {
        let m = self.c.len();
        let a = self.c[1].conj().mul(self.c[2]).log();
        self.c[0] = self.c[1].mul(Quat::exp(scale(a, -1.0)));
        let b = self.c[m - 2].conj().mul(self.c[m - 3]).log();
        self.c[m - 1] = self.c[m - 2].mul(Quat::exp(scale(b, -1.0)));
    }

    fn at_knot(&self, i: usize) -> Quat {
        let segs = self.c.len() - 3;
        if i < segs {
            self.segment(i, 0.0).0
        } else {
            self.segment(segs - 1, 1.0).0
        }
    }

    /// Rotation, body angular velocity and body angular acceleration per unit u on segment
    /// `i` at `u ∈ [0, 1]`.
    fn segment(&self, i: usize, u: f64) -> (Quat, [f64; 3], [f64; 3]) {
        let b = [
            (5.0 + 3.0 * u - 3.0 * u * u + u * u * u) / 6.0,
            (1.0 + 3.0 * u + 3.0 * u * u - 2.0 * u * u * u) / 6.0,
            u * u * u / 6.0,
        ];
        let db = [
            (3.0 - 6.0 * u + 3.0 * u * u) / 6.0,
            (3.0 + 6.0 * u - 6.0 * u * u) / 6.0,
            0.5 * u * u,
        ];
        let ddb = [u - 1.0, 1.0 - 2.0 * u, u];
        let mut r = self.c[i];
        let mut w = [0.0; 3];
        let mut al = [0.0; 3];
        for j in 0..3 {
            let om = self.c[i + j].conj().mul(self.c[i + j + 1]).log();
            let a = Quat::exp(scale(om, b[j]));
            r = r.mul(a);
            let inv = a.conj();
            let dw = scale(om, db[j]);
            w = add(inv.rotate(w), dw);
            al = add(add(inv.rotate(al), scale(om, ddb[j])), cross(w, dw));
        }
        (r, w, al)
    }

    fn locate(&self, t: f64) -> (usize, f64) {
        let segs = self.c.len() - 3;
        let (a, e) = self.interval();
        let t = if t < a {
            a
        } else if t > e {
            e
        } else {
            t
        };
        let x = (t - self.t0) / self.dt;
        let i = (x.floor().max(0.0) as usize).min(segs - 1);
        (i, x - i as f64)
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
            return (
                Quat {
                    w: nan,
                    x: nan,
                    y: nan,
                    z: nan,
                },
                [nan; 3],
                [nan; 3],
            );
        }
        let (i, u) = self.locate(t);
        let (r, w, a) = self.segment(i, u);
        let k = 1.0 / self.dt;
        (r, r.rotate(scale(w, k)), r.rotate(scale(a, k * k)))
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
