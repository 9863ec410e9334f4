//! Straight-line pieces, timed exactly: the 1-D jerk-limited rest-to-rest optimum.
//!
//! A rest-to-rest piece whose path is the straight segment from q₀ to q₁ (all its waypoints
//! collinear and in order: a natural or not-a-knot spline through such points, parameterized
//! by chord length, *is* that segment) reduces to the one-dimensional third-order problem in
//! the distance s ∈ [0, L] along it, L = |q₁ − q₀|, direction u = (q₁ − q₀)/L. Joint j moves as
//! q̇ⱼ = uⱼṡ, q̈ⱼ = uⱼs̈, q⃛ⱼ = uⱼs⃛, so its limits project onto the line as
//! `ṡ ≤ min_j v⁺ⱼ/uⱼ` (v⁺ the limit in the direction the joint moves: the upper one where
//! uⱼ > 0, the lower one's magnitude where uⱼ < 0), the same for s̈ in both directions, and
//! `|s⃛| ≤ min_j Jⱼ/|uⱼ|`. trajkit's online generator ([`crate::otg::time_optimal`]) solves
//! that problem exactly (rest to rest, no time grid), and [`LineMotion`] plays
//! ξ(t) = q₀ + (q₁ − q₀)·s(t)/L: the time-optimal jerk-limited motion along the segment.
//!
//! # When it applies
//! [`line_motion`] accepts a path only when it can prove that the path is the segment: the
//! path must be a piecewise polynomial of degree d ≤ 6 ([`crate::Path::piecewise_degree`]),
//! and at d + 1 evenly spaced parameters of every polynomial piece σ(s) must be within
//! [`LINE_TOLERANCE`] (joint units) of q₀ + (q₁ − q₀)·(s − s₀)/(s₁ − s₀). The difference of
//! two polynomials of degree d is bounded on the piece by its values at those points times
//! the Lebesgue constant of d + 1 equispaced nodes (at most 4.55 for d ≤ 6), so the path and
//! the played segment are within 5·[`LINE_TOLERANCE`] everywhere. Interior waypoints are
//! passed within that distance.
//!
//! # Precision contract
//! The generator keeps ṡ, s̈ within the projected limits to 1e-12 relative; the limits given
//! to it are lowered by [`LIMIT_MARGIN`] relative, so each joint's velocity, acceleration and
//! jerk stay within its limits at every instant up to rounding, not only at samples (the
//! profile is piecewise cubic in time with constant jerk on each segment; the limits are
//! checked at its segment boundaries and velocity extrema by the generator). The profile's
//! final position s_f may differ from L by rounding (the generator's contract: 1e-8); the
//! played motion is q₀ + (q₁ − q₀)·s(t/k)/s_f, which ends exactly at q₁, with the time
//! stretched by k = max(1, L/s_f) so that the rescaling never raises a derivative. Positions
//! stay between q₀ and q₁ (clamped per joint, against rounding), so inside any box that holds
//! both.

use crate::otg::{self, Dof1};
use crate::{Limits, Order, Path, Trajectory};

/// Largest distance (joint units, per joint) between a path and the straight segment through
/// its ends at the checked parameters for [`line_motion`] to treat the path as that segment.
pub const LINE_TOLERANCE: f64 = 1e-9;

/// Relative amount by which the projected limits given to the generator are lowered (room for
/// the generator's own 1e-12 rounding contract).
pub const LIMIT_MARGIN: f64 = 1e-10;

/// A rest-to-rest motion along a straight segment, timed by the 1-D jerk-limited optimum.
#[derive(Debug, Clone)]
pub struct LineMotion {
    q0: Vec<f64>,
    q1: Vec<f64>,
    /// Per joint, the smaller and larger of q₀ⱼ and q₁ⱼ.
    lo: Vec<f64>,
    hi: Vec<f64>,
    profile: otg::Profile,
    /// The profile's final position.
    s_f: f64,
    /// Time stretch (≥ 1).
    k: f64,
    /// The path's parameter interval (for the phase plane).
    s_range: (f64, f64),
}

impl LineMotion {
    /// The path parameter and its rate at time `t` (for the phase plane).
    pub fn path_state(&self, t: f64) -> (f64, f64) {
        let (p, v, _, _) = self
            .profile
            .state_at((t / self.k).clamp(0.0, self.profile.duration()));
        let (a, b) = self.s_range;
        let lambda = (p / self.s_f).clamp(0.0, 1.0);
        (a + (b - a) * lambda, (b - a) * v / self.s_f / self.k)
    }
}

impl Trajectory for LineMotion {
    fn dof(&self) -> usize {
        self.q0.len()
    }

    fn duration(&self) -> f64 {
        self.profile.duration() * self.k
    }

    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        let tau = (t / self.k).clamp(0.0, self.profile.duration());
        let (p, v, a, j) = self.profile.state_at(tau);
        let lambda = (p / self.s_f).clamp(0.0, 1.0);
        let scale = match order {
            Order::Position => 0.0,
            Order::Velocity => v / self.s_f / self.k,
            Order::Acceleration => a / self.s_f / (self.k * self.k),
            Order::Jerk => j / self.s_f / (self.k * self.k * self.k),
        };
        for (i, o) in out.iter_mut().enumerate().take(self.q0.len()) {
            let d = self.q1[i] - self.q0[i];
            *o = match order {
                Order::Position => {
                    // From the nearer end, so that both ends are exact.
                    let q = if lambda <= 0.5 {
                        self.q0[i] + d * lambda
                    } else {
                        self.q1[i] - d * (1.0 - lambda)
                    };
                    q.clamp(self.lo[i], self.hi[i])
                }
                _ => d * scale,
            };
        }
    }
}

/// The exact jerk-limited motion along `path` when it is a straight segment (see the module
/// documentation), `None` when it is not (or is not provably so), or when the generator finds
/// no profile (the caller then uses another jerk stage).
pub fn line_motion<P: Path>(path: &P, limits: &Limits) -> Option<LineMotion> {
    let n = path.dim();
    if limits.dof() != n {
        return None;
    }
    let (s0, s1) = path.interval();
    let mut q0 = vec![0.0; n];
    let mut q1 = vec![0.0; n];
    path.eval(s0, 0, &mut q0);
    path.eval(s1, 0, &mut q1);
    let length = q0
        .iter()
        .zip(&q1)
        .map(|(a, b)| (b - a) * (b - a))
        .sum::<f64>()
        .sqrt();
    if !(length > 0.0 && length.is_finite() && s1 > s0) {
        return None;
    }
    if !is_segment(path, &q0, &q1) {
        return None;
    }
    let (vmax, vmin, amax, amin, jmax) = projected_limits(limits, &q0, &q1, length)?;
    let m = 1.0 - LIMIT_MARGIN;
    let dof = Dof1 {
        vmax: vmax * m,
        vmin: vmin * m,
        amax: amax * m,
        amin: amin * m,
        jmax: jmax * m,
        ..Dof1::rest_to_rest(0.0, length, 1.0, 1.0, 1.0)
    };
    let profile = otg::time_optimal(&dof)?;
    let s_f = profile.end().p;
    if !(s_f > 0.0 && s_f.is_finite() && profile.duration().is_finite()) {
        return None;
    }
    // The generator's own contract: the end within 1e-8 of the target.
    if (s_f - length).abs() > 1e-8 * length.max(1.0) {
        return None;
    }
    let k = (length / s_f).max(1.0);
    let lo = q0.iter().zip(&q1).map(|(a, b)| a.min(*b)).collect();
    let hi = q0.iter().zip(&q1).map(|(a, b)| a.max(*b)).collect();
    Some(LineMotion {
        q0,
        q1,
        lo,
        hi,
        profile,
        s_f,
        k,
        s_range: (s0, s1),
    })
}

/// True when `path` is provably within [`LINE_TOLERANCE`]·(Lebesgue constant) of the segment
/// from `q0` to `q1`, linearly in its parameter.
fn is_segment<P: Path>(path: &P, q0: &[f64], q1: &[f64]) -> bool {
    let Some(d) = path.piecewise_degree().filter(|&d| (1..=6).contains(&d)) else {
        return false;
    };
    let (s0, s1) = path.interval();
    let breaks = path.breakpoints();
    let mut q = vec![0.0; q0.len()];
    for pair in breaks.windows(2) {
        for m in 0..=d {
            let s = pair[0] + (pair[1] - pair[0]) * m as f64 / d as f64;
            path.eval(s, 0, &mut q);
            let lambda = (s - s0) / (s1 - s0);
            let off = q.iter().zip(q0.iter().zip(q1)).any(|(&x, (&a, &b))| {
                let gap = (x - (a + (b - a) * lambda)).abs();
                gap.is_nan() || gap > LINE_TOLERANCE
            });
            if off {
                return false;
            }
        }
    }
    true
}

/// Limits on s along the segment (unit speed): (ṡ_max, ṡ_min, s̈_max, s̈_min, |s⃛|_max), or
/// `None` when some joint's limit is not a number.
fn projected_limits(
    limits: &Limits,
    q0: &[f64],
    q1: &[f64],
    length: f64,
) -> Option<(f64, f64, f64, f64, f64)> {
    let (mut vmax, mut vmin, mut amax, mut amin, mut jmax) = (
        f64::INFINITY,
        f64::INFINITY,
        f64::INFINITY,
        f64::INFINITY,
        f64::INFINITY,
    );
    for (j, jl) in limits.joints().iter().enumerate() {
        let u = (q1[j] - q0[j]) / length;
        if u == 0.0 {
            continue;
        }
        let (vl, vh) = jl.range(Order::Velocity);
        let (al, ah) = jl.range(Order::Acceleration);
        let (_, jh) = jl.range(Order::Jerk);
        if [vl, vh, al, ah, jh].iter().any(|x| x.is_nan()) {
            return None;
        }
        // Forward along the line the joint moves with sign(u); backward against it.
        let (fv, bv, fa, ba) = if u > 0.0 {
            (vh / u, -vl / u, ah / u, -al / u)
        } else {
            (-vl / -u, vh / -u, -al / -u, ah / -u)
        };
        vmax = vmax.min(fv);
        vmin = vmin.min(bv);
        amax = amax.min(fa);
        amin = amin.min(ba);
        jmax = jmax.min(jh / u.abs());
    }
    if !(vmax > 0.0 && vmin > 0.0 && amax > 0.0 && amin > 0.0 && jmax > 0.0) {
        return None;
    }
    Some((vmax, -vmin, amax, -amin, jmax))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topp::LinearPath;

    #[test]
    fn one_joint_line_is_the_known_optimum() {
        // 1 rad with v = 1, a = 2, j = 10: the jerk-limited optimum is 1.7 s.
        let path = LinearPath::new(&[0.0, 1.0], 1).unwrap();
        let limits = Limits::uniform(1, 1.0, 2.0, 10.0).unwrap();
        let m = line_motion(&path, &limits).unwrap();
        assert!((m.duration() - 1.7).abs() < 1e-8, "{}", m.duration());
        let mut q = [0.0];
        m.eval(m.duration(), Order::Position, &mut q);
        assert_eq!(q, [1.0]);
        m.eval(0.0, Order::Position, &mut q);
        assert_eq!(q, [0.0]);
    }

    #[test]
    fn bent_paths_are_not_lines() {
        let path = LinearPath::new(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0], 2).unwrap();
        let limits = Limits::uniform(2, 1.0, 2.0, 10.0).unwrap();
        assert!(line_motion(&path, &limits).is_none());
        // Collinear but not evenly parameterized (a kink in speed is fine, a detour is not):
        // 0 → 1 → 0.5 reverses and is refused.
        let back = LinearPath::new(&[0.0, 1.0, 0.5], 1).unwrap();
        assert!(line_motion(&back, &Limits::uniform(1, 1.0, 2.0, 10.0).unwrap()).is_none());
    }

    #[test]
    fn directional_limits_project_on_the_line() {
        // Joint 1 moves backwards twice as far as joint 0 moves forwards; joint 1's lower
        // velocity limit is the binding one.
        let mut joints = Limits::uniform(2, 1.0, 2.0, 10.0)
            .unwrap()
            .joints()
            .to_vec();
        joints[1].min_velocity = Some(-0.5);
        let limits = Limits::new(joints).unwrap();
        let path = LinearPath::new(&[0.0, 0.0, 1.0, -2.0], 2).unwrap();
        let m = line_motion(&path, &limits).unwrap();
        let mut peak = [0.0f64; 2];
        let mut v = [0.0; 2];
        for i in 0..=2000 {
            m.eval(m.duration() * i as f64 / 2000.0, Order::Velocity, &mut v);
            peak[0] = peak[0].max(v[0].abs());
            peak[1] = peak[1].max(-v[1]);
        }
        assert!(peak[1] <= 0.5 && peak[1] > 0.499, "{peak:?}");
    }
}
