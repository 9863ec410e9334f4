//! One joint's polynomial over `[0, T]`, stored in normalized time τ = t/T.

use crate::error::{Error, Result};
use crate::roots::{horner, max_abs_in, MAX_DEGREE};

/// Factorial-ratio i!/(i−k)! for i ≥ k.
#[inline]
fn falling(i: usize, k: usize) -> f64 {
    ((i - k + 1)..=i).fold(1.0, |p, x| p * x as f64)
}

/// A scalar polynomial q(t) = Σ cᵢ (t/T)ⁱ on `[0, T]`, degree ≤ 7.
///
/// Storing coefficients in normalized time keeps them of the order of the motion itself, so
/// evaluation stays accurate for long and short durations alike. The k-th time derivative is
/// `T⁻ᵏ · dᵏ/dτᵏ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Polynomial {
    /// Coefficients in τ = t/T, used on the first half.
    c: [f64; 8],
    /// Coefficients in u = 1 − τ of the same polynomial, used on the second half, so that the
    /// end conditions are met as exactly as the start conditions (no cancellation at τ = 1).
    r: [f64; 8],
    len: usize,
    duration: f64,
    /// Evaluation tables for orders 0..=3: `fwd[k]` are the τ-coefficients of the k-th time
    /// derivative (factorial factors and T⁻ᵏ folded in), `rev[k]` the same in u = 1 − τ with the
    /// sign (−1)ᵏ folded in. Evaluation is then one Horner pass.
    fwd: [[f64; 8]; 4],
    rev: [[f64; 8]; 4],
}

impl Polynomial {
    /// From normalized coefficients `c` (lowest order first, at most 8) and a duration.
    pub fn from_normalized(c: &[f64], duration: f64) -> Result<Self> {
        if c.is_empty() || c.len() > 8 {
            return Err(Error::DimensionMismatch {
                what: "polynomial coefficient count (1..=8)".into(),
                expected: 8,
                found: c.len(),
            });
        }
        for (i, &v) in c.iter().enumerate() {
            crate::error::finite(|| format!("polynomial coefficient c{i}"), v)?;
        }
        crate::error::positive(|| "polynomial duration".into(), duration)?;
        let mut a = [0.0; 8];
        a[..c.len()].copy_from_slice(c);
        // Taylor shift to u = 1 − τ: r_k = (−1)^k Σ_{i≥k} C(i,k) c_i.
        let mut r = [0.0; 8];
        for k in 0..c.len() {
            let s: f64 = (k..c.len())
                .map(|i| a[i] * falling(i, k) / falling(k, k))
                .sum();
            r[k] = if k % 2 == 0 { s } else { -s };
        }
        Ok(Polynomial::assemble(a, r, c.len(), duration))
    }

    /// The polynomial of odd degree 2m−1 that meets m conditions at each end: `start` and `end`
    /// are `[q, q̇, q̈, q⃛][..m]` at t = 0 and t = T, with m = 2 (cubic), 3 (quintic) or
    /// 4 (septic).
    ///
    /// The m lowest coefficients follow from the start conditions directly; the m highest solve
    /// an m×m linear system (Gaussian elimination with partial pivoting).
    pub fn from_boundary(start: &[f64], end: &[f64], duration: f64) -> Result<Self> {
        let m = start.len();
        if !(2..=4).contains(&m) || end.len() != m {
            return Err(Error::DimensionMismatch {
                what: "boundary conditions per end (2, 3 or 4: cubic, quintic, septic)".into(),
                expected: m.clamp(2, 4),
                found: if (2..=4).contains(&m) { end.len() } else { m },
            });
        }
        crate::error::positive(|| "polynomial duration".into(), duration)?;
        const NAMES: [&str; 4] = ["position", "velocity", "acceleration", "jerk"];
        for k in 0..m {
            crate::error::finite(|| format!("start {}", NAMES[k]), start[k])?;
            crate::error::finite(|| format!("end {}", NAMES[k]), end[k])?;
        }
        let n = 2 * m;
        let c = solve_forward(start, end, duration);
        // The same problem seen from the end, in u = 1 − τ: derivatives change sign with order.
        let flip = |v: &[f64]| -> [f64; 4] {
            let mut o = [0.0; 4];
            for k in 0..m {
                o[k] = if k % 2 == 0 { v[k] } else { -v[k] };
            }
            o
        };
        let r = solve_forward(&flip(end)[..m], &flip(start)[..m], duration);
        if c[..n].iter().chain(&r[..n]).any(|v| !v.is_finite()) {
            return Err(Error::InvalidValue {
                field: "polynomial duration".into(),
                value: duration,
                reason: "gives non-finite coefficients for these boundary conditions",
            });
        }
        Ok(Polynomial::assemble(c, r, n, duration))
    }

    fn assemble(c: [f64; 8], r: [f64; 8], len: usize, duration: f64) -> Polynomial {
        let mut fwd = [[0.0; 8]; 4];
        let mut rev = [[0.0; 8]; 4];
        for k in 0..4.min(len) {
            let scale = duration.powi(-(k as i32));
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            for i in k..len {
                fwd[k][i - k] = c[i] * falling(i, k) * scale;
                rev[k][i - k] = sign * r[i] * falling(i, k) * scale;
            }
        }
        Polynomial {
            c,
            r,
            len,
            duration,
            fwd,
            rev,
        }
    }

    /// The evaluation table of order `k` (< 4) for the first (`first_half`) or second half:
    /// `len() - k` coefficients of a polynomial in τ (first half) or u = 1 − τ (second half).
    pub(crate) fn table(&self, k: usize, first_half: bool) -> &[f64] {
        let n = self.len.saturating_sub(k);
        if first_half {
            &self.fwd[k][..n]
        } else {
            &self.rev[k][..n]
        }
    }

    /// Degree (number of coefficients − 1).
    pub fn degree(&self) -> usize {
        self.len - 1
    }

    /// Duration T.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Normalized coefficients cᵢ (lowest first).
    pub fn normalized_coefficients(&self) -> &[f64] {
        &self.c[..self.len]
    }

    /// Coefficients of the k-th τ-derivative (lowest first) into `out`; returns their count.
    fn deriv_coeffs(&self, k: usize, out: &mut [f64; 8]) -> usize {
        if k >= self.len {
            return 0;
        }
        let n = self.len - k;
        for j in 0..n {
            out[j] = self.c[j + k] * falling(j + k, k);
        }
        n
    }

    /// The k-th time derivative at `t` (clamped to `[0, T]`; NaN gives NaN).
    #[inline]
    pub fn eval(&self, t: f64, k: usize) -> f64 {
        let tc = crate::traj::clamp_time(t, self.duration);
        if k >= self.len {
            return if tc.is_nan() { f64::NAN } else { 0.0 };
        }
        let tau = tc / self.duration;
        let first_half = tau <= 0.5;
        // u = 1 − τ, computed from T − t so that u is exactly 0 at the end.
        let x = if first_half {
            tau
        } else {
            (self.duration - tc) / self.duration
        };
        let n = self.len - k;
        if k < 4 {
            let tab = if first_half {
                &self.fwd[k]
            } else {
                &self.rev[k]
            };
            let mut acc = 0.0;
            for i in (0..n).rev() {
                acc = acc * x + tab[i];
            }
            return acc;
        }
        let (coef, sign) = if first_half {
            (&self.c, 1.0)
        } else {
            (&self.r, if k % 2 == 0 { 1.0 } else { -1.0 })
        };
        let mut acc = 0.0;
        for i in (k..self.len).rev() {
            acc = acc * x + coef[i] * falling(i, k);
        }
        sign * acc * self.duration.powi(-(k as i32))
    }

    /// All four of q, q̇, q̈, q⃛ at `t` in one pass.
    #[inline]
    pub fn eval_all(&self, t: f64) -> [f64; 4] {
        [
            self.eval(t, 0),
            self.eval(t, 1),
            self.eval(t, 2),
            self.eval(t, 3),
        ]
    }

    /// The largest |k-th time derivative| over `[0, T]` and the time where it occurs, found
    /// from the real roots of the (k+1)-th derivative (exact up to root bracketing, ~1e-15).
    pub fn peak_abs(&self, k: usize) -> (f64, f64) {
        let mut d = [0.0; 8];
        let n = self.deriv_coeffs(k, &mut d);
        if n == 0 {
            return (0.0, 0.0);
        }
        debug_assert!(n <= MAX_DEGREE + 1);
        let (v, tau) = max_abs_in(&d[..n], 0.0, 1.0);
        (v * self.duration.powi(-(k as i32)), tau * self.duration)
    }

    /// The smallest and largest value of q over `[0, T]`.
    pub fn position_range(&self) -> (f64, f64) {
        let mut d = [0.0; 8];
        let n = self.deriv_coeffs(1, &mut d);
        let c = self.normalized_coefficients();
        let mut lo = horner(c, 0.0).min(horner(c, 1.0));
        let mut hi = horner(c, 0.0).max(horner(c, 1.0));
        let mut r = [0.0; MAX_DEGREE];
        let m = crate::roots::roots_in(&d[..n], 0.0, 1.0, &mut r);
        for &x in &r[..m] {
            let v = horner(c, x);
            lo = lo.min(v);
            hi = hi.max(v);
        }
        (lo, hi)
    }
}

/// Normalized coefficients (in τ) of the degree 2m−1 polynomial meeting `start` at τ = 0 and
/// `end` at τ = 1 (both `[q, q̇, q̈, q⃛][..m]` in time units over duration `duration`).
fn solve_forward(start: &[f64], end: &[f64], duration: f64) -> [f64; 8] {
    let m = start.len();
    let mut c = [0.0; 8];
    // Normalized derivative at τ: d^k/dτ^k = T^k d^k/dt^k.
    let mut tk = 1.0;
    let mut fact = 1.0;
    let mut rhs_end = [0.0; 4];
    for k in 0..m {
        if k > 0 {
            fact *= k as f64;
        }
        c[k] = start[k] * tk / fact;
        rhs_end[k] = end[k] * tk;
        tk *= duration;
    }
    // Conditions at τ = 1: Σ_i c_i i!/(i-k)! = rhs_end[k]; the known low coefficients move
    // to the right-hand side, the unknowns c_m..c_{n-1} follow from the exact inverse.
    let mut rhs = [0.0; 4];
    for k in 0..m {
        let known: f64 = (k..m).map(|i| c[i] * falling(i, k)).sum();
        rhs[k] = rhs_end[k] - known;
    }
    let inv = &end_inverses()[m - 2];
    for r in 0..m {
        c[m + r] = (0..m).map(|k| inv[r][k] * rhs[k]).sum();
    }
    c
}

/// The exact inverses for m = 2, 3, 4, computed once.
fn end_inverses() -> &'static [[[f64; 4]; 4]; 3] {
    static INV: std::sync::OnceLock<[[[f64; 4]; 4]; 3]> = std::sync::OnceLock::new();
    INV.get_or_init(|| {
        [
            end_matrix_inverse(2),
            end_matrix_inverse(3),
            end_matrix_inverse(4),
        ]
    })
}

/// Exact inverse of the m×m end-condition matrix `A[k][i] = (m+i)!/(m+i−k)!` (k, i < m),
/// by Gauss–Jordan elimination over the rationals (i128 numerators and denominators; the
/// entries are small integers, so nothing overflows for m ≤ 4). Rounding happens once, when
/// the exact rational entries become f64.
fn end_matrix_inverse(m: usize) -> [[f64; 4]; 4] {
    fn gcd(a: i128, b: i128) -> i128 {
        if b == 0 {
            a.abs()
        } else {
            gcd(b, a % b)
        }
    }
    #[derive(Clone, Copy)]
    struct Q(i128, i128);
    impl Q {
        fn norm(n: i128, d: i128) -> Q {
            let g = gcd(n, d).max(1);
            let s = if d < 0 { -1 } else { 1 };
            Q(s * n / g, s * d / g)
        }
        fn sub(self, o: Q) -> Q {
            Q::norm(self.0 * o.1 - o.0 * self.1, self.1 * o.1)
        }
        fn mul(self, o: Q) -> Q {
            Q::norm(self.0 * o.0, self.1 * o.1)
        }
        fn div(self, o: Q) -> Q {
            Q::norm(self.0 * o.1, self.1 * o.0)
        }
    }
    let mut a = [[Q(0, 1); 8]; 4];
    for k in 0..m {
        for i in 0..m {
            a[k][i] = Q(falling(m + i, k) as i128, 1);
        }
        a[k][m + k] = Q(1, 1);
    }
    for col in 0..m {
        let piv = (col..m)
            .find(|&r| a[r][col].0 != 0)
            .expect("end matrix is regular");
        a.swap(col, piv);
        let p = a[col][col];
        for c in 0..2 * m {
            a[col][c] = a[col][c].div(p);
        }
        for r in 0..m {
            if r != col && a[r][col].0 != 0 {
                let f = a[r][col];
                for c in 0..2 * m {
                    a[r][c] = a[r][c].sub(f.mul(a[col][c]));
                }
            }
        }
    }
    let mut inv = [[0.0; 4]; 4];
    for r in 0..m {
        for c in 0..m {
            inv[r][c] = a[r][m + c].0 as f64 / a[r][m + c].1 as f64;
        }
    }
    inv
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    #[test]
    fn closed_forms_of_the_seed() {
        // Rest-to-rest 0 -> 1 in T = 1.
        let cubic = Polynomial::from_boundary(&[0.0, 0.0], &[1.0, 0.0], 1.0).unwrap();
        let quintic = Polynomial::from_boundary(&[0.0; 3], &[1.0, 0.0, 0.0], 1.0).unwrap();
        let septic = Polynomial::from_boundary(&[0.0; 4], &[1.0, 0.0, 0.0, 0.0], 1.0).unwrap();
        let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12);
        assert!(close(
            cubic.normalized_coefficients(),
            &[0.0, 0.0, 3.0, -2.0]
        ));
        assert!(close(
            quintic.normalized_coefficients(),
            &[0.0, 0.0, 0.0, 10.0, -15.0, 6.0]
        ));
        assert!(close(
            septic.normalized_coefficients(),
            &[0.0, 0.0, 0.0, 0.0, 35.0, -84.0, 70.0, -20.0]
        ));
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let p =
            Polynomial::from_boundary(&[0.3, -1.0, 2.0, 5.0], &[1.7, 0.5, -1.0, 0.0], 1.3).unwrap();
        let h = 1e-6;
        for i in 1..20 {
            let t = 1.3 * i as f64 / 20.0;
            for k in 0..3 {
                let fd = (p.eval(t + h, k) - p.eval(t - h, k)) / (2.0 * h);
                let exact = p.eval(t, k + 1);
                assert!(
                    (fd - exact).abs() < 1e-6 * (1.0 + exact.abs()),
                    "k={k} t={t} fd={fd} exact={exact}"
                );
            }
        }
    }

    #[test]
    fn seeded_random_boundary_conditions_are_met() {
        let mut g = SplitMix64::new(2024);
        let mut worst: f64 = 0.0;
        for _ in 0..5000 {
            let m = 2 + g.below(3) as usize;
            let duration = 10f64.powf(g.uniform(-2.0, 2.0));
            let start: Vec<f64> = (0..m).map(|_| g.uniform(-3.0, 3.0)).collect();
            let end: Vec<f64> = (0..m).map(|_| g.uniform(-3.0, 3.0)).collect();
            let p = Polynomial::from_boundary(&start, &end, duration).unwrap();
            assert_eq!(p.degree(), 2 * m - 1);
            for k in 0..m {
                // Scale of the k-th derivative over this duration: the conditions themselves
                // and the motion's natural size |Δq|/T^k.
                let scale = start[k].abs().max(end[k].abs()).max(
                    start
                        .iter()
                        .chain(&end)
                        .enumerate()
                        .fold(0.0, |s: f64, (i, v)| {
                            s.max(v.abs() * duration.powi((i % m) as i32 - k as i32))
                        }),
                );
                let e0 = (p.eval(0.0, k) - start[k]).abs() / scale;
                let e1 = (p.eval(duration, k) - end[k]).abs() / scale;
                worst = worst.max(e0).max(e1);
            }
        }
        assert!(worst < 1e-12, "worst relative boundary error {worst:e}");
    }

    #[test]
    fn clamped_time_and_bad_input() {
        let p = Polynomial::from_boundary(&[0.0, 0.0], &[2.0, 0.0], 2.0).unwrap();
        assert_eq!(p.eval(-1.0, 0), 0.0);
        assert_eq!(p.eval(5.0, 0), 2.0);
        assert!(p.eval(f64::NAN, 0).is_nan());
        assert!(p.eval(f64::NAN, 7).is_nan());
        assert_eq!(p.eval(1.0, 4), 0.0);
        assert!(Polynomial::from_boundary(&[0.0], &[1.0], 1.0).is_err());
        assert!(Polynomial::from_boundary(&[0.0, 0.0], &[1.0], 1.0).is_err());
        let e = Polynomial::from_boundary(&[0.0, f64::NAN], &[1.0, 0.0], 1.0).unwrap_err();
        assert!(e.to_string().contains("start velocity"), "{e}");
        let e = Polynomial::from_boundary(&[0.0, 0.0], &[1.0, 0.0], -1.0).unwrap_err();
        assert!(e.to_string().contains("duration = -1"), "{e}");
        assert!(Polynomial::from_normalized(&[], 1.0).is_err());
    }

    #[test]
    fn position_range_finds_overshoot() {
        // Leaves 0 with velocity -3 towards 1: dips below 0 first.
        let p = Polynomial::from_boundary(&[0.0, -3.0], &[1.0, 0.0], 1.0).unwrap();
        let (lo, hi) = p.position_range();
        assert!(lo < -0.1 && (hi - 1.0).abs() < 1e-12, "{lo} {hi}");
    }
}
