//! Joint velocity and acceleration on path pieces of degree 4 or 5 (the range-repaired
//! splines of [`crate::spline::BoundedSpline`]), for [`super::Constraint::excess_on_cubic`] and
//! [`super::Constraint::hold_on_cubic`] when [`super::Constraint::handles_quintic`]: σ′_j is a
//! quartic, the acceleration σ′_j·u + σ″_j·x a quartic and σ′_j²·x of degree 9 in
//! θ = (s − s0)/Δ. Their Bernstein coefficients, linear in (u, x0), enclose them (the
//! sufficient rows and the cheap check); where they reach a limit, the extremes are at the ends
//! and at the real roots of the acceleration (velocity) or of its derivative (acceleration),
//! isolated by [`crate::roots::roots_in`] (bracketed to 4 ulp). Cost of the sufficient rows:
//! a joint whose sum of absolute power coefficients (a bound on every Bernstein coefficient)
//! stays below its limit by 1e-12 relative is left out before its Bernstein coefficients are
//! computed; the margin is far above the rounding of either test, so the rows are those of
//! the exact test alone.

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
        let x_top = x_max[0].max(x_max[1]);
        for j in 0..self.hi.len() {
            if self.slow_enough(piece, j, h, x_top) {
                continue;
            }
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

impl JointVelocity {
    /// Whether joint j's velocity provably stays within its limits on the interval for
    /// x ≤ `x_top`, so that [`JointVelocity::hold_quintic`]'s first test (|σ′_j| ≤ the largest
    /// |Bernstein coefficient| m, m²·x ≤ limit²) would leave it out: the power coefficients of
    /// σ′_j in θ are (σ′, σ″Δ, σ‴Δ²/2, σ⁗Δ³/6, σ⁽⁵⁾Δ⁴/24) at s0 and each Bernstein coefficient
    /// of degree 4 combines them with weights in [0, 1], so m ≤ M = Σ|coefficients|; the test
    /// M²·x_top ≤ min(hi, −lo)²·(1 − 1e-12) leaves a margin far above the rounding of either
    /// computation, so it never skips a joint the exact test keeps (the rows are the same,
    /// without the Bernstein coefficients of the joints far from their limit). False (the
    /// exact test decides) on infinite or NaN inputs.
    #[inline]
    fn slow_enough(&self, piece: &CubicPiece<'_>, j: usize, h: f64, x_top: f64) -> bool {
        let limit = self.hi[j].min(-self.lo[j]);
        if !(limit.is_finite() && x_top.is_finite() && x_top > 0.0) {
            return false;
        }
        let (d1, d2, d3) = (piece.d1[j].abs(), piece.d2[j].abs(), piece.d3[j].abs());
        let (d4, d5) = (piece.d4[j].abs(), piece.d5[j].abs());
        let m = d1 + h * (d2 + h * (0.5 * d3 + h * (d4 * super::INV6 + h * (d5 * super::INV24))));
        m * m * x_top <= limit * limit * (1.0 - 1e-12)
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
    /// cubic piece. A joint whose coefficients provably all stay within its limits
    /// ([`JointAcceleration::far_from_limits`]) is skipped before they are computed.
    pub(super) fn hold_quintic(
        &self,
        piece: &CubicPiece<'_>,
        u_max: f64,
        x0_max: f64,
        out: &mut ConstraintRows,
    ) {
        let h = piece.s1 - piece.s0;
        for j in 0..self.hi.len() {
            if self.far_from_limits(piece, j, h, u_max, x0_max) {
                continue;
            }
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

    /// Whether every interior Bernstein coefficient b_k = α_k·u + β_k·x0 (k = 1..3) of joint
    /// j's acceleration provably stays within its limits for |u| ≤ `u_max`, 0 ≤ x0 ≤ `x0_max`,
    /// so that [`JointAcceleration::hold_quintic`]'s own test would leave out each of them:
    /// the power coefficients of the acceleration quartic in θ are α = (σ′, 3σ″Δ, 2.5σ‴Δ²,
    /// 7/6·σ⁗Δ³, 3/8·σ⁽⁵⁾Δ⁴)·u and β = (σ″, σ‴Δ, σ⁗Δ²/2, σ⁽⁵⁾Δ³/6, 0)·x0 at s0, and a Bernstein
    /// coefficient of degree 4 is a combination of them with weights in [0, 1], so
    /// |α_k| ≤ A = Σ|α_m| and |β_k| ≤ B = Σ|β_m|. The test A·U + B·X ≤ min(hi, −lo)·(1 − 1e-12)
    /// leaves a margin far above the rounding of either computation (a few ulp), so it never
    /// skips a joint the exact test would keep: the rows are the same, only cheaper. False
    /// (the exact test decides) on infinite or NaN inputs and zero limits.
    #[inline]
    fn far_from_limits(
        &self,
        piece: &CubicPiece<'_>,
        j: usize,
        h: f64,
        u_max: f64,
        x0_max: f64,
    ) -> bool {
        let limit = self.hi[j].min(-self.lo[j]);
        if !(limit.is_finite() && u_max.is_finite() && x0_max.is_finite()) {
            return false;
        }
        let (d1, d2, d3) = (piece.d1[j].abs(), piece.d2[j].abs(), piece.d3[j].abs());
        let (d4, d5) = (piece.d4[j].abs(), piece.d5[j].abs());
        let a = d1 + h * (3.0 * d2 + h * (2.5 * d3 + h * (7.0 / 6.0 * d4 + h * (0.375 * d5))));
        let b = d2 + h * (d3 + h * (0.5 * d4 + h * (d5 * super::INV6)));
        a * u_max + b * x0_max <= limit * (1.0 - 1e-12)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// Random Taylor data of one joint (magnitudes over many decades) on an interval of length
    /// `h`, as a piece of one joint.
    fn random_data(rng: &mut SplitMix64) -> ([f64; 6], f64) {
        let mut d = [0.0; 6];
        for v in d.iter_mut().skip(1) {
            *v = rng.uniform(-1.0, 1.0) * 10f64.powf(rng.uniform(-3.0, 3.0));
        }
        if rng.below(4) == 0 {
            // σ′ constant: the screens' bounds are then attained.
            d[2..].fill(0.0);
        }
        (d, 10f64.powf(rng.uniform(-4.0, 0.0)))
    }

    fn piece_of(d: &[f64; 6], h: f64) -> CubicPiece<'_> {
        CubicPiece {
            s0: 1.0,
            s1: 1.0 + h,
            d0: &d[0..1],
            d1: &d[1..2],
            d2: &d[2..3],
            d3: &d[3..4],
            d4: &d[4..5],
            d5: &d[5..6],
        }
    }

    /// The screens that skip a joint before its Bernstein coefficients are computed never skip
    /// one that the exact tests keep, also with limits placed right at the screens' bounds.
    #[test]
    fn joint_screens_skip_only_what_the_exact_tests_skip() {
        let mut rng = SplitMix64::new(14);
        let (mut skipped_a, mut skipped_v) = (0, 0);
        for _ in 0..20_000 {
            let (d, h) = random_data(&mut rng);
            let piece = piece_of(&d, h);
            let h = piece.s1 - piece.s0;
            let (u_max, x0_max) = (rng.uniform(0.0, 10.0), rng.uniform(0.0, 10.0));
            // Limits at the screen's bound, a hair above or below it.
            let nudge = 1.0 + rng.uniform(-3e-12, 3e-12);
            // The bound A·U + B·X of the screen.
            let (d1, d2, d3) = (d[1].abs(), d[2].abs(), d[3].abs());
            let (d4, d5) = (d[4].abs(), d[5].abs());
            let a = d1 + h * (3.0 * d2 + h * (2.5 * d3 + h * (7.0 / 6.0 * d4 + h * 0.375 * d5)));
            let b = d2 + h * (d3 + h * (0.5 * d4 + h * d5 / 6.0));
            let level = a * u_max + b * x0_max;
            let hi = level * nudge;
            let lo = -hi * if rng.below(2) == 0 { 1.0 } else { 1.5 };
            let acc = JointAcceleration::new(&[lo], &[hi]).unwrap();
            if acc.far_from_limits(&piece, 0, h, u_max, x0_max) {
                skipped_a += 1;
                let (ra, rb) = JointAcceleration::bernstein_rows(&piece, 0);
                for k in 1..4 {
                    let reach_hi = ra[k].abs() * u_max + rb[k].max(0.0) * x0_max;
                    let reach_lo = -(ra[k].abs() * u_max) + rb[k].min(0.0) * x0_max;
                    assert!(reach_hi <= hi && reach_lo >= lo, "{d:?} {h} {k}");
                }
            }
            let x_top = rng.uniform(0.0, 10.0);
            let m = d1 + h * (d2 + h * (0.5 * d3 + h * (d4 / 6.0 + h * d5 / 24.0)));
            let vlim = m * x_top.sqrt() * nudge;
            let vel = JointVelocity::new(&[-vlim * 2.0], &[vlim]).unwrap();
            if vel.slow_enough(&piece, 0, h, x_top) {
                skipped_v += 1;
                let c = piece.first_bernstein4(0);
                let limit = velocity_bound4(&c, vel.lo[0], vel.hi[0]);
                let m = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(m * m * x_top <= limit * limit, "{d:?} {h}");
            }
        }
        // Both outcomes occur.
        assert!(skipped_a > 1000 && skipped_a < 19_000, "{skipped_a}");
        assert!(skipped_v > 1000 && skipped_v < 19_000, "{skipped_v}");
    }
}
