//! The 3-D algebra of the dynamics model: vectors, rotation matrices, rigid frames and
//! rigid-body inertia, on stack arrays.

pub(super) type Vec3 = [f64; 3];
/// Row-major 3 × 3 matrix.
pub(super) type Mat3 = [[f64; 3]; 3];

pub(super) const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
pub(super) const ZERO3: Vec3 = [0.0; 3];

pub(super) fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub(super) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(super) fn scale(a: Vec3, k: f64) -> Vec3 {
    [a[0] * k, a[1] * k, a[2] * k]
}
pub(super) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(super) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
/// m · v.
pub(super) fn mul(m: &Mat3, v: Vec3) -> Vec3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}
/// mᵀ · v.
pub(super) fn mul_t(m: &Mat3, v: Vec3) -> Vec3 {
    [
        m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2],
        m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
        m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2],
    ]
}
pub(super) fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut out = [[0.0; 3]; 3];
    for (r, row) in out.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
        }
    }
    out
}
pub(super) fn transpose(a: &Mat3) -> Mat3 {
    let mut out = [[0.0; 3]; 3];
    for (r, row) in out.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = a[c][r];
        }
    }
    out
}

/// URDF roll-pitch-yaw: R = Rz(yaw)·Ry(pitch)·Rx(roll).
pub(super) fn rpy_matrix(rpy: Vec3) -> Mat3 {
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
pub(super) fn axis_rotation(u: Vec3, angle: f64) -> Mat3 {
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
pub(super) struct Frame {
    pub(super) rot: Mat3,
    pub(super) pos: Vec3,
}

impl Frame {
    pub(super) const IDENTITY: Frame = Frame {
        rot: IDENTITY,
        pos: ZERO3,
    };
    /// `self` followed by `child` (child given in `self`'s frame).
    pub(super) fn then(&self, child: &Frame) -> Frame {
        Frame {
            rot: mat_mul(&self.rot, &child.rot),
            pos: add(self.pos, mul(&self.rot, child.pos)),
        }
    }
}

/// Mass, centre of mass and inertia about the centre of mass, in one frame.
#[derive(Debug, Clone, Copy)]
pub(super) struct Inertial {
    pub(super) mass: f64,
    pub(super) com: Vec3,
    pub(super) inertia: Mat3,
}

impl Inertial {
    pub(super) const ZERO: Inertial = Inertial {
        mass: 0.0,
        com: ZERO3,
        inertia: [[0.0; 3]; 3],
    };

    /// `self` expressed in the parent frame of `f` (self given in `f`'s frame).
    pub(super) fn transformed(&self, f: &Frame) -> Inertial {
        Inertial {
            mass: self.mass,
            com: add(f.pos, mul(&f.rot, self.com)),
            inertia: mat_mul(&mat_mul(&f.rot, &self.inertia), &transpose(&f.rot)),
        }
    }

    /// The rigid union of two bodies given in the same frame.
    pub(super) fn merged(&self, other: &Inertial) -> Inertial {
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
