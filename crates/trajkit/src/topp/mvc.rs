//! The maximum velocity curve (MVC) of a time-parameterization problem: at each path point, the
//! largest path velocity ṡ at which some path acceleration s̈ satisfies every constraint.
//!
//! It is what the phase-plane picture of TOPP-RA, TOTG and numerical integration draws above
//! the solved profile (s, ṡ(s)): a time-optimal profile touches it and never crosses it. With
//! x = ṡ² and u = s̈, each constraint writes half-planes `α·u + β·x ≤ γ` and bounds on x at the
//! point ([`crate::topp::Constraint`]). Eliminating u exactly (Fourier–Motzkin): a row with
//! α > 0 bounds u from above by `(γ − β x)/α`, one with α < 0 from below; some u exists iff
//! every lower bound is at most every upper bound, and each such pair (r, r′) is one linear
//! inequality in x, `(|α_r|·β_{r′} + α_{r′}·β_r)·x ≤ |α_r|·γ_{r′} + α_{r′}·γ_r`
//! (written without divisions). Rows with α = 0 bound x directly. The admissible x form an
//! interval; its upper end is x_mvc and the MVC is √x_mvc.
//!
//! # Precision contract
//! No discretization: each value is exact up to floating-point rounding of the constraints'
//! own rows (a few ulp of the binding pair's coefficients). `+∞` where no constraint bounds
//! the velocity. Cost O(m²) per point for m half-planes (2 per joint for accelerations).

use super::constraint::{ConstraintRows, PathPoint};
use super::toppra::Toppra;
use crate::error::{Error, Result};
use crate::Path;

/// The maximum path velocity ṡ_max(s) of `problem` at each of the path parameters `s` (each
/// clamped by the path like any evaluation): `+∞` where the constraints do not bound the
/// velocity. The problem's gridpoints and boundary velocities are not used.
///
/// Errors: [`Error::InvalidValue`] naming the point for a non-finite `s` or path value;
/// [`Error::Infeasible`] naming the point and constraint where no velocity at all (not even
/// rest) satisfies the constraints.
///
/// ```
/// use trajkit::topp::{max_velocity_curve, LinearPath, Toppra};
/// use trajkit::Limits;
/// // A straight line: σ′ is constant and σ″ = 0, so only the velocity limits bound ṡ:
/// // ṡ ≤ min_j v_j / |σ′_j|, with σ′ = Δq / L for the arc-length parameter.
/// let path = LinearPath::new(&[0.0, 0.0, 3.0, 4.0], 2)?;     // length 5
/// let limits = Limits::uniform(2, 1.0, 2.0, 10.0)?;
/// let problem = Toppra::with_limits(path, &limits)?;
/// let mvc = max_velocity_curve(&problem, &[0.0, 2.5, 5.0])?;
/// assert!(mvc.iter().all(|&v| (v - 1.0 / 0.8).abs() < 1e-12));
/// # Ok::<(), trajkit::Error>(())
/// ```
pub fn max_velocity_curve<P: Path>(problem: &Toppra<'_, P>, s: &[f64]) -> Result<Vec<f64>> {
    let path = problem.path();
    let n = path.dim();
    let (mut q, mut dq, mut ddq) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut rows = ConstraintRows::new();
    let mut out = Vec::with_capacity(s.len());
    for (i, &si) in s.iter().enumerate() {
        crate::error::finite(|| format!("MVC path parameter {i}"), si)?;
        path.eval(si, 0, &mut q);
        path.eval_derivatives(si, &mut dq, &mut ddq);
        super::toppra::check_path_values(si, &q, &dq, &ddq)?;
        let point = PathPoint {
            s: si,
            q: &q,
            dq: &dq,
            ddq: &ddq,
        };
        rows.clear();
        let mut x_hi = f64::INFINITY;
        let mut x_lo = 0.0_f64;
        for c in problem.constraints_ref() {
            rows.clear_bounds();
            c.write(&point, &mut rows);
            if let Some(why) = rows.broken {
                return Err(Error::Infeasible(format!(
                    "at s = {si}: '{}' {why}",
                    c.name()
                )));
            }
            let (lo, hi) = rows.x_bounds();
            x_lo = x_lo.max(lo);
            x_hi = x_hi.min(hi);
        }
        rows.start = 0;
        let (lo, hi) = admissible_x(rows.half_planes(), x_lo, x_hi);
        // Empty (or NaN): no velocity at all is admissible here.
        if lo
            .partial_cmp(&hi)
            .is_none_or(|o| o == std::cmp::Ordering::Greater)
        {
            let names: Vec<String> = problem.constraints_ref().iter().map(|c| c.name()).collect();
            return Err(Error::Infeasible(format!(
                "at s = {si}: no path velocity satisfies {} (not even rest)",
                names.join(", ")
            )));
        }
        out.push(hi.sqrt());
    }
    Ok(out)
}

/// The interval of x ≥ 0 for which some u satisfies every half-plane `α·u + β·x ≤ γ`, within
/// `[x_lo, x_hi]`; empty (lo > hi, or NaN) when there is none.
fn admissible_x(rows: &[[f64; 3]], x_lo: f64, x_hi: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (x_lo, x_hi);
    // a·x ≤ b as a bound on x.
    let mut bound = |a: f64, b: f64| {
        if a > 0.0 {
            hi = hi.min(b / a);
        } else if a < 0.0 {
            lo = lo.max(b / a);
        } else if b < 0.0 {
            lo = f64::INFINITY;
        }
    };
    for &[alpha, beta, gamma] in rows {
        if alpha == 0.0 {
            bound(beta, gamma);
        }
    }
    for &[al, bl, gl] in rows.iter().filter(|r| r[0] < 0.0) {
        for &[au, bu, gu] in rows.iter().filter(|r| r[0] > 0.0) {
            // lower (γl − βl x)/αl ≤ upper (γu − βu x)/αu, multiplied by |αl|·αu > 0.
            let a = -al;
            bound(au * bl + a * bu, a * gu + au * gl);
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CubicSpline;
    use crate::topp::{Gridpoints, JointAcceleration};
    use crate::Limits;

    /// A circle of radius r in two joints, parameterized by angle.
    struct Circle(f64);

    impl Path for Circle {
        fn dim(&self) -> usize {
            2
        }
        fn interval(&self) -> (f64, f64) {
            (0.0, 6.0)
        }
        fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
            let (sn, cs) = s.sin_cos();
            let r = self.0;
            let v = match order % 4 {
                0 => [r * cs, r * sn],
                1 => [-r * sn, r * cs],
                2 => [-r * cs, -r * sn],
                _ => [r * sn, -r * cs],
            };
            out[..2].copy_from_slice(&v);
        }
    }

    #[test]
    fn circle_acceleration_limit_curve_is_analytic() {
        // Joint acceleration |q̈_j| ≤ a only, q̈ = σ′u + σ″x. At s = 0: joint 1 gives r·x ≤ a (σ′₁ = 0), joint 2 is free through u: x = a/r.
        // At s = π/4: |u + x|, |u − x| ≤ a/(r c) with c = √2/2 → x = a/(r c) at u = 0.
        let (r, a) = (0.5, 2.0);
        let problem = Toppra::new(Circle(r))
            .constraint(JointAcceleration::new(&[-a, -a], &[a, a]).unwrap())
            .unwrap();
        let pi4 = std::f64::consts::FRAC_PI_4;
        let m = max_velocity_curve(&problem, &[0.0, pi4, 2.0 * pi4]).unwrap();
        assert!((m[0] - (a / r).sqrt()).abs() < 1e-12, "{m:?}");
        let c = std::f64::consts::FRAC_1_SQRT_2;
        assert!((m[1] - (a / (r * c)).sqrt()).abs() < 1e-12, "{m:?}");
        assert!((m[2] - (a / r).sqrt()).abs() < 1e-12, "{m:?}");
    }

    #[test]
    fn unbounded_velocity_is_infinite_and_bad_input_is_named() {
        // Only accelerations on a straight line (σ″ = 0): ṡ is unbounded.
        let path = crate::topp::LinearPath::new(&[0.0, 1.0], 1).unwrap();
        let p = Toppra::new(path)
            .constraint(JointAcceleration::new(&[-1.0], &[1.0]).unwrap())
            .unwrap();
        let m = max_velocity_curve(&p, &[0.0, 0.5]).unwrap();
        assert!(m.iter().all(|v| v.is_infinite()));
        let e = max_velocity_curve(&p, &[f64::NAN]).unwrap_err().to_string();
        assert!(e.contains("MVC path parameter 0"), "{e}");
    }

    #[test]
    fn toppra_profile_stays_below_and_touches_the_mvc() {
        let limits = Limits::preset("panda").unwrap();
        let w = [
            0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0, //
            0.5, 0.3, -0.2, -1.2, 0.1, 1.8, 0.4, //
            1.0, -0.2, 0.1, -2.0, 0.3, 1.2, 0.8,
        ];
        let path = CubicSpline::natural(&[0.0, 0.5, 1.0], &w, 7).unwrap();
        let problem = Toppra::with_limits(path, &limits)
            .unwrap()
            .gridpoints(Gridpoints::Uniform(400));
        let profile = problem.solve_profile().unwrap();
        let s = profile.gridpoints();
        let mvc = max_velocity_curve(&problem, s).unwrap();
        let mut touches = 0;
        for (i, (&v, &m)) in profile.velocities().iter().zip(&mvc).enumerate() {
            assert!(
                v <= m * (1.0 + 1e-6),
                "gridpoint {i}: ṡ = {v} above the MVC {m}"
            );
            if v >= m * (1.0 - 1e-6) {
                touches += 1;
            }
        }
        // A time-optimal profile rides the MVC somewhere between its start and stop.
        assert!(touches > 0);
    }
}
