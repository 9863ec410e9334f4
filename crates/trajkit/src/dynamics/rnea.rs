//! The recursive Newton–Euler algorithm: velocities and accelerations outwards from the base,
//! forces and moments inwards from the tip, in stack arrays of [`MAX_JOINTS`] bodies.

use super::spatial::{
    add, axis_rotation, cross, dot, mat_mul, mul, mul_t, scale, Inertial, IDENTITY, ZERO3,
};
use super::{InverseDynamics, SerialChain, MAX_JOINTS};

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
