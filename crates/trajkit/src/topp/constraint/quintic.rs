//! Joint velocity and acceleration on path pieces of degree 4 or 5 (the range-repaired
//! splines of [`crate::spline::BoundedSpline`]), for [`super::Constraint::excess_on_cubic`] and
//! [`super::Constraint::hold_on_cubic`] when [`super::Constraint::handles_quintic`]: σ′_j is a
//! quartic, the acceleration σ′_j·u + σ″_j·x a quartic and σ′_j²·x of degree 9 in
//! θ = (s − s0)/Δ. Their Bernstein coefficients, linear in (u, x0), enclose them (the
//! sufficient rows and the cheap check); where they reach a limit, the extremes are at the ends
//! and at the real roots of the acceleration (velocity) or of its derivative (acceleration),
//! isolated by [`crate::roots::roots_in`] (bracketed to 4 ulp).

use super::worst::{enclosed_excess, worst_over};
use super::{ConstraintRows, CubicPiece, JointAcceleration, JointVelocity};

/// Bernstein coefficients of a quartic on [0, 1] from its power coefficients (lowest first):
/// b_i = Σ_{k ≤ i} C(i, k)/C(4, k)·p_k.
#[inline]
pub(super) fn power_to_bernstein4(p: [f64; 5]) -> [f64; 5] {
    [
        p[0],
        p[0] + 0.25 * p[1],
        p[0] + 0.5 * p[1] + p[2] * super::INV6,
        p[0] + 0.75 * p[1] + 0.5 * p[2] + 0.25 * p[3],
        p[0] + p[1] + p[2] + p[3] + p[4],
    ]
}

/// Bernstein coefficients (degree 8) of the square of a quartic given by its own:
/// w_k = Σ_{i+l=k} C(4, i)·C(4, l)·c_i·c_l / C(8, k).
#[inline]
pub(super) fn square_bernstein4(c: [f64; 5]) -> [f64; 9] {
    const C4: [f64; 5] = [1.0, 4.0, 6.0, 4.0, 1.0];
    const C8: [f64; 9] = [1.0, 8.0, 28.0, 56.0, 70.0, 56.0, 28.0, 8.0, 1.0];
    let mut w = [0.0; 9];
    for i in 0..5 {
        for l in 0..5 {
            w[i + l] += C4[i] * C4[l] * c[i] * c[l];
        }
    }
    for (wk, ck) in w.iter_mut().zip(C8) {
        *wk /= ck;
    }
    w
}

/// [`velocity_bound`] for a quartic σ′_j given by its Bernstein coefficients.
#[inline]
pub(super) fn velocity_bound4(c: &[f64; 5], lo: f64, hi: f64) -> f64 {
    if c.iter().all(|&v| v >= 0.0) {
        hi
    } else if c.iter().all(|&v| v <= 0.0) {
        -lo
    } else {
        hi.min(-lo)
    }
}

/// The real roots in [0, h] of the polynomial `c` (in t, lowest order first) followed by the
/// two ends: the candidates for the extremes of its antiderivative-like companions.
pub(super) fn candidates_in(
    c: &[f64],
    h: f64,
    out: &mut [f64; crate::roots::MAX_DEGREE + 2],
) -> usize {
    let mut roots = [0.0; crate::roots::MAX_DEGREE];
    let n = crate::roots::roots_in(c, 0.0, h, &mut roots);
    out[0] = 0.0;
    out[1] = h;
    out[2..2 + n].copy_from_slice(&roots[..n]);
    2 + n
}

impl JointVelocity {
    /// [`super::Constraint::excess_on_cubic`] on a piece of degree 4 or 5: σ′_j is a quartic, σ′_j²·x
    /// has degree 9 with Bernstein coefficients b_k = ((9 − k)·w_k·x0 + k·w_{k−1}·x1)/9 (w
    /// those of σ′_j², degree 8); where they exceed the limit, the extremes are at the ends
    /// and at the real roots of the joint acceleration (a quartic, isolated exactly).
    pub(super) fn excess_quintic(&self, piece: &CubicPiece<'_>, u: f64, x0: f64) -> (f64, f64) {
        let h = piece.s1 - piece.s0;
        let x1 = x0 + 2.0 * u * h;
        let mut worst = (0.0f64, piece.s0);
        let mut ts = [0.0; crate::roots::MAX_DEGREE + 2];
        for j in 0..self.hi.len() {
            let c = piece.first_bernstein4(j);
            let limit = velocity_bound4(&c, self.lo[j], self.hi[j]);
            let l2 = limit * limit;
            let w = square_bernstein4(c);
            let mut bmax = 0.0f64;
            for k in 0..10 {
                let kf = k as f64;
                let wk = if k < 9 { w[k] } else { 0.0 };
                let wk1 = if k > 0 { w[k - 1] } else { 0.0 };
                bmax = bmax.max(((9.0 - kf) * wk * x0 + kf * wk1 * x1) / 9.0);
            }
            if bmax <= l2 {
                worst.0 = worst.0.max(bmax / l2);
                continue;
            }
            let n = candidates_in(&piece.acceleration_quartic(j, u, x0), h, &mut ts);
            worst_over(
                piece,
                u,
                x0,
                &ts[..n],
                &mut worst,
                (j, self.squared_ratio(j)),
            );
        }
        (worst.0.sqrt() - 1.0, worst.1)
    }

    /// [`super::Constraint::hold_on_cubic`] on a piece of degree 4 or 5: the interior Bernstein
    /// coefficients b_1..b_8 of σ′_j²·x (degree 9, see [`JointVelocity::excess_quintic`]),
    /// linear in (u, x0) with x1 = x0 + 2uΔ.
    pub(super) fn hold_quintic(
        &self,
        piece: &CubicPiece<'_>,
        x_max: [f64; 2],
        out: &mut ConstraintRows,
    ) {
        let h = piece.s1 - piece.s0;
        for j in 0..self.hi.len() {
            let c = piece.first_bernstein4(j);
            let limit = velocity_bound4(&c, self.lo[j], self.hi[j]);
            if limit.is_infinite() {
                continue;
            }
            let l2 = limit * limit;
            let m = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if m * m * x_max[0].max(x_max[1]) <= l2 {
                continue;
            }
            let w = square_bernstein4(c);
            let reach = |k: usize| {
                let kf = k as f64;
                ((9.0 - kf) * w[k]).max(0.0) * x_max[0] + (kf * w[k - 1]).max(0.0) * x_max[1]
            };
            if (1..9).all(|k| reach(k) <= 9.0 * l2) {
                continue;
            }
            for k in 1..9 {
                let kf = k as f64;
                let alpha = kf * w[k - 1] * 2.0 * h / 9.0;
                let beta = ((9.0 - kf) * w[k] + kf * w[k - 1]) / 9.0;
                out.half_plane(alpha, beta, l2);
            }
        }
    }
}

impl JointAcceleration {
    /// The joint acceleration's Bernstein coefficients (degree 4 in θ = (s − s0)/Δ) as rows in
    /// (u, x0): b_k = α_k·u + β_k·x0.
    #[inline]
    pub(super) fn bernstein_rows(piece: &CubicPiece<'_>, j: usize) -> ([f64; 5], [f64; 5]) {
        let h = piece.s1 - piece.s0;
        let (mut a, mut b) = piece.acceleration_rows(j);
        let mut hp = 1.0;
        for k in 0..5 {
            a[k] *= hp;
            b[k] *= hp;
            hp *= h;
        }
        (power_to_bernstein4(a), power_to_bernstein4(b))
    }

    /// [`super::Constraint::excess_on_cubic`] on a piece of degree 4 or 5: the acceleration is a
    /// quartic in s; its extremes are at the ends and at the real roots of its derivative (a
    /// cubic, isolated exactly). Joints whose Bernstein hull is within the limits are not
    /// solved for.
    pub(super) fn excess_quintic(&self, piece: &CubicPiece<'_>, u: f64, x0: f64) -> (f64, f64) {
        let h = piece.s1 - piece.s0;
        let mut worst = (f64::NEG_INFINITY, piece.s0);
        let mut ts = [0.0; crate::roots::MAX_DEGREE + 2];
        for j in 0..self.hi.len() {
            let (ra, rb) = Self::bernstein_rows(piece, j);
            let (mut amin, mut amax) = (f64::INFINITY, f64::NEG_INFINITY);
            for k in 0..5 {
                let b = ra[k] * u + rb[k] * x0;
                amin = amin.min(b);
                amax = amax.max(b);
            }
            if amax <= self.hi[j] && amin >= self.lo[j] {
                worst.0 = worst
                    .0
                    .max(enclosed_excess(amin, amax, self.lo[j], self.hi[j]));
                continue;
            }
            let c = piece.acceleration_quartic(j, u, x0);
            let dc = [c[1], 2.0 * c[2], 3.0 * c[3], 4.0 * c[4]];
            let n = candidates_in(&dc, h, &mut ts);
            worst_over(
                piece,
                u,
                x0,
                &ts[..n],
                &mut worst,
                (j, self.excess_at(j, u)),
            );
        }
        worst
    }

    /// [`super::Constraint::hold_on_cubic`] on a piece of degree 4 or 5: the interior Bernstein
    /// coefficients b_1..b_3 of the acceleration quartic, linear in (u, x0), pruned as on a
    /// cubic piece.
    pub(super) fn hold_quintic(
        &self,
        piece: &CubicPiece<'_>,
        u_max: f64,
        x0_max: f64,
        out: &mut ConstraintRows,
    ) {
        for j in 0..self.hi.len() {
            let (ra, rb) = Self::bernstein_rows(piece, j);
            for k in 1..4 {
                let (a, b) = (ra[k], rb[k]);
                let reach_hi = a.abs() * u_max + b.max(0.0) * x0_max;
                let reach_lo = -(a.abs() * u_max) + b.min(0.0) * x0_max;
                if reach_hi <= self.hi[j] && reach_lo >= self.lo[j] {
                    continue;
                }
                out.interval(a, b, 0.0, self.lo[j], self.hi[j]);
            }
        }
    }
}
