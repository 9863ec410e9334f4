//! The shape of a middle interval: how s̈ varies between two gridpoints.
//!
//! On middle interval i (δ = s − s_i ∈ [0, Δ]) the planner's unknowns are the state
//! (x_i, u_i) = (ṡ², s̈) at s_i and one number v_i per interval. s̈ is linear not in s but in a
//! *reference time* θ(δ), whose rate θ′ = dθ/ds is linear in δ:
//!
//! ```text
//!   θ′(δ) = p + q·δ,         φ(δ) = θ(δ) − θ(0) = p·δ + q·δ²/2,
//!   u(δ)  = u_i + v_i·φ(δ),  x(δ) = x_i + 2u_i·δ + 2v_i·ψ(δ),  ψ(δ) = p·δ²/2 + q·δ³/6,
//! ```
//!
//! (x′ = 2u holds exactly). The path jerk is s⃛ = ṡ·du/ds = v_i·θ′(δ)·√x(δ). The interval's
//! (p, q) interpolate 1/√x̄ of a reference solution x̄ (the previous round's, `Shape::new`), so
//! θ is the reference's own time up to second order and **v_i is the path jerk in time**,
//! nearly constant over the interval once x is close to x̄. This is what removes the
//! first-order loss of s̈ linear in s (p = 1, q = 0), where the path jerk v·√x varies with ṡ
//! inside an interval, so that a jerk ramp must run below the limit at the interval's slow
//! end: here a constant path jerk in time is represented to second order in the grid step.
//!
//! Everything the planner needs stays linear in (x_i, u_i, v_i): x(δ), u(δ) and the joint jerk
//! ṡ·(σ‴x + 3σ″u + σ′·v·θ′) apart from the factor ṡ (handled by the tangent of J/√x, see
//! [`super::discretize`]).

/// The reference-time rate θ′(δ) = p + q·δ of one middle interval (p, p + qΔ > 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Shape {
    pub(crate) p: f64,
    pub(crate) q: f64,
}

/// The coefficients of x(δ), u(δ) and θ′(δ) at one point δ of an interval:
/// x(δ) = x_i + e1·u_i + e2·v, u(δ) = u_i + f·v.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct At {
    pub(crate) delta: f64,
    pub(crate) e1: f64,
    pub(crate) e2: f64,
    pub(crate) f: f64,
    pub(crate) th: f64,
}

impl At {
    /// The interval's start (δ = 0): x and u are the state.
    pub(crate) fn start(th: f64) -> Self {
        At {
            delta: 0.0,
            e1: 0.0,
            e2: 0.0,
            f: 0.0,
            th,
        }
    }
}

impl Default for Shape {
    fn default() -> Self {
        Shape { p: 1.0, q: 0.0 }
    }
}

impl Shape {
    /// The shape of an interval of length `len` from the reference's x̄ at both ends: θ′
    /// interpolates 1/√x̄ linearly. A reference that is not positive at an end takes the other
    /// end's value (or θ′ = 1 when neither is).
    pub(crate) fn new(x0: f64, x1: f64, len: f64) -> Self {
        let ok = |x: f64| x > 0.0 && x.is_finite();
        let (r0, r1) = match (ok(x0), ok(x1)) {
            (true, true) => (1.0 / x0.sqrt(), 1.0 / x1.sqrt()),
            (true, false) => (1.0 / x0.sqrt(), 1.0 / x0.sqrt()),
            (false, true) => (1.0 / x1.sqrt(), 1.0 / x1.sqrt()),
            (false, false) => (1.0, 1.0),
        };
        Shape {
            p: r0,
            q: (r1 - r0) / len,
        }
    }

    /// θ′(δ).
    #[inline]
    pub(crate) fn rate(&self, d: f64) -> f64 {
        self.p + self.q * d
    }

    /// φ(δ) = ∫₀^δ θ′.
    #[inline]
    pub(crate) fn phi(&self, d: f64) -> f64 {
        d * (self.p + 0.5 * self.q * d)
    }

    /// 2ψ(δ) = 2∫₀^δ φ.
    #[inline]
    pub(crate) fn psi2(&self, d: f64) -> f64 {
        d * d * (self.p + self.q * d / 3.0)
    }

    /// The coefficients at δ.
    #[inline]
    pub(crate) fn at(&self, d: f64) -> At {
        At {
            delta: d,
            e1: 2.0 * d,
            e2: self.psi2(d),
            f: self.phi(d),
            th: self.rate(d),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn x_derivative_is_twice_u_and_jerk_is_v_theta_rate_sd() {
        let sh = Shape::new(0.3, 1.7, 0.2);
        let (x0, u0, v) = (0.3, 2.0, 7.0);
        let x = |d: f64| {
            let a = sh.at(d);
            x0 + a.e1 * u0 + a.e2 * v
        };
        let u = |d: f64| u0 + sh.at(d).f * v;
        let h = 1e-6;
        for k in 1..10 {
            let d = 0.02 * k as f64;
            let dx = (x(d + h) - x(d - h)) / (2.0 * h);
            assert!((dx - 2.0 * u(d)).abs() < 1e-7, "{dx} {}", 2.0 * u(d));
            let du = (u(d + h) - u(d - h)) / (2.0 * h);
            assert!((du - v * sh.rate(d)).abs() < 1e-6);
        }
        // θ′ interpolates 1/√x̄ at both ends.
        assert!((sh.rate(0.0) - 1.0 / 0.3f64.sqrt()).abs() < 1e-14);
        assert!((sh.rate(0.2) - 1.0 / 1.7f64.sqrt()).abs() < 1e-14);
    }
}
