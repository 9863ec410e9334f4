//! Time rescaling: a path composed with a timing law, and uniform time scaling.
//!
//! The formal rescaling ξ(t) = σ(s(t)) keeps the geometry of a path σ and chooses only the
//! timing s(t). [`Retimed`] composes any [`Path`] with any [`TimeLaw`] and evaluates the chain
//! rule exactly:
//!
//! ```text
//!   ξ̇ = σ′ṡ,   ξ̈ = σ″ṡ² + σ′s̈,   ξ⃛ = σ‴ṡ³ + 3σ″ṡs̈ + σ′s⃛
//! ```
//!
//! Timing laws: the TOPP-RA [`crate::topp::PhaseProfile`], a constant-speed [`LinearLaw`], a
//! rest-to-rest minimum-jerk [`QuinticLaw`], or user code.
//!
//! [`Scaled`] slows a whole trajectory down (or speeds it up) by a factor k: ξ_k(t) = ξ(t/k),
//! so velocity scales by 1/k, acceleration by 1/k², jerk by 1/k³; [`min_time_scale`] finds the
//! smallest k that meets given limits.
//!
//! # Precision contract
//! [`Retimed`] adds no approximation: its values are the chain rule applied to the path's and
//! the law's own values (rounding only). [`min_time_scale`] is exact at the sampled instants
//! (the limits hold there with equality for the binding joint) and, like any sampled check,
//! does not see between samples. Evaluation allocates nothing; paths with more than
//! [`MAX_DOF`] joints are refused at construction (a fixed-size scratch buffer).
//!
//! ```
//! use trajkit::topp::{Retimed, QuinticLaw, LinearPath};
//! use trajkit::{Order, Trajectory};
//!
//! let path = LinearPath::new(&[0.0, 0.0, 1.0, 2.0], 2)?; // a straight line, s = arc length
//! let law = QuinticLaw::new(0.0, 5f64.sqrt(), 2.0)?;      // rest to rest in 2 s
//! let traj = Retimed::new(&path, law)?;
//! let mut q = [0.0; 2];
//! traj.eval(1.0, Order::Position, &mut q);
//! assert!((q[0] - 0.5).abs() < 1e-15 && (q[1] - 1.0).abs() < 1e-15);
//! # Ok::<(), trajkit::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::traj::clamp_time;
use crate::{Limits, Order, Path, Trajectory};

/// Largest path dimension [`Retimed`] accepts.
pub const MAX_DOF: usize = 64;

/// A timing law s(t) on `[0, duration]`.
pub trait TimeLaw {
    /// Duration in seconds.
    fn duration(&self) -> f64;
    /// `[s, ṡ, s̈, s⃛]` at `t`, with `t` clamped to `[0, duration]`. Must not allocate.
    fn eval(&self, t: f64) -> [f64; 4];

    /// [`TimeLaw::eval`] at every time of `times` into `out` (at least as long): each entry
    /// what `eval` returns. The default calls `eval` per time; a law whose pieces can be
    /// found from the previous time's overrides it (same arithmetic, bitwise equal). Fastest
    /// on non-decreasing times, correct on any. Must not allocate.
    fn eval_many(&self, times: &[f64], out: &mut [[f64; 4]]) {
        for (&t, o) in times.iter().zip(out.iter_mut()) {
            *o = self.eval(t);
        }
    }
}

impl<L: TimeLaw + ?Sized> TimeLaw for &L {
    fn duration(&self) -> f64 {
        (**self).duration()
    }
    fn eval(&self, t: f64) -> [f64; 4] {
        (**self).eval(t)
    }
    fn eval_many(&self, times: &[f64], out: &mut [[f64; 4]]) {
        (**self).eval_many(times, out)
    }
}

/// A path timed by a law: ξ(t) = σ(s(t)), a [`Trajectory`].
#[derive(Debug, Clone)]
pub struct Retimed<P: Path, L: TimeLaw> {
    path: P,
    law: L,
}

impl<P: Path, L: TimeLaw> Retimed<P, L> {
    /// Composes `path` with `law`. The law's s values should lie in the path's interval (the
    /// path clamps them otherwise).
    pub fn new(path: P, law: L) -> Result<Self> {
        if path.dim() > MAX_DOF || path.dim() == 0 {
            return Err(Error::DimensionMismatch {
                what: format!("path dimension (1..={MAX_DOF})"),
                expected: MAX_DOF,
                found: path.dim(),
            });
        }
        Ok(Retimed { path, law })
    }

    /// The path.
    pub fn path(&self) -> &P {
        &self.path
    }

    /// The timing law.
    pub fn law(&self) -> &L {
        &self.law
    }

    /// The path and the law, moved out.
    pub fn into_parts(self) -> (P, L) {
        (self.path, self.law)
    }
}

impl<P: Path, L: TimeLaw> Trajectory for Retimed<P, L> {
    fn dof(&self) -> usize {
        self.path.dim()
    }
    fn duration(&self) -> f64 {
        self.law.duration()
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        let n = self.path.dim();
        let [s, sd, sdd, sddd] = self.law.eval(t);
        let out = &mut out[..n];
        let mut tmp = [0.0; MAX_DOF];
        let tmp = &mut tmp[..n];
        match order {
            Order::Position => self.path.eval(s, 0, out),
            Order::Velocity => {
                self.path.eval(s, 1, out);
                out.iter_mut().for_each(|v| *v *= sd);
            }
            Order::Acceleration => {
                self.path.eval(s, 1, out);
                self.path.eval(s, 2, tmp);
                let x = sd * sd;
                for j in 0..n {
                    out[j] = out[j] * sdd + tmp[j] * x;
                }
            }
            Order::Jerk => {
                self.path.eval(s, 3, out);
                let c3 = sd * sd * sd;
                out.iter_mut().for_each(|v| *v *= c3);
                let c2 = 3.0 * sd * sdd;
                if c2 != 0.0 {
                    self.path.eval(s, 2, tmp);
                    for j in 0..n {
                        out[j] += c2 * tmp[j];
                    }
                }
                if sddd != 0.0 {
                    self.path.eval(s, 1, tmp);
                    for j in 0..n {
                        out[j] += sddd * tmp[j];
                    }
                }
            }
        }
    }

    /// One law evaluation per time and one path sweep for orders 0..=3
    /// ([`Path::eval_many_orders`]), in blocks of 64 times; the chain rule as in `eval`, term
    /// by term.
    fn eval_rows(&self, times: &[f64], out: [&mut [f64]; 4]) {
        self.rows::<false>(times, 1.0, out);
    }

    /// `eval_rows` at `times[i] / factor` with the factors applied as the chain rule writes
    /// each row (the same products as the default's pass after it, bitwise equal).
    fn eval_rows_scaled(&self, times: &[f64], factor: f64, out: [&mut [f64]; 4]) {
        self.rows::<true>(times, factor, out);
    }
}

impl<P: Path, L: TimeLaw> Retimed<P, L> {
    /// The rows of [`Trajectory::eval_rows`] (`SCALED` false) or of
    /// [`Trajectory::eval_rows_scaled`] with factor `k` (`SCALED` true): the law at `t` (or
    /// `t / k`), the path's orders 0..=3 at its s values, the chain rule (then times
    /// `k.powi(-1..=-3)`) row by row.
    fn rows<const SCALED: bool>(&self, times: &[f64], k: f64, mut out: [&mut [f64]; 4]) {
        use crate::traj::{row_block, scale_factors, ROW_BLOCK};
        let n = self.path.dim();
        let mut law = [[0.0; 4]; ROW_BLOCK];
        let mut s = [0.0; ROW_BLOCK];
        let mut at = [0.0; ROW_BLOCK];
        let c = if SCALED { scale_factors(k) } else { [1.0; 3] };
        for (b, chunk) in times.chunks(ROW_BLOCK).enumerate() {
            let m = chunk.len();
            let from = b * ROW_BLOCK;
            let chunk = if SCALED {
                for (x, &t) in at.iter_mut().zip(chunk) {
                    *x = t / k;
                }
                &at[..m]
            } else {
                chunk
            };
            self.law.eval_many(chunk, &mut law[..m]);
            for (si, l) in s.iter_mut().zip(&law[..m]) {
                *si = l[0];
            }
            let [q, v, a, jk] = row_block(&mut out, n, from, from + m);
            self.path
                .eval_many_orders(&s[..m], [&mut *q, &mut *v, &mut *a, &mut *jk]);
            for (i, &[_, sd, sdd, sddd]) in law[..m].iter().enumerate() {
                let r = i * n..(i + 1) * n;
                let (d1, d2, d3) = (&mut v[r.clone()], &mut a[r.clone()], &mut jk[r]);
                let law = [sd, sdd, sddd];
                match (3.0 * sd * sdd != 0.0, sddd != 0.0) {
                    (true, true) => chain_rule::<true, true, SCALED>(d1, d2, d3, law, c),
                    (true, false) => chain_rule::<true, false, SCALED>(d1, d2, d3, law, c),
                    (false, true) => chain_rule::<false, true, SCALED>(d1, d2, d3, law, c),
                    (false, false) => chain_rule::<false, false, SCALED>(d1, d2, d3, law, c),
                }
            }
        }
    }
}

/// The chain rule of [`Retimed::eval`] on one row, in place: σ′, σ″, σ‴ in `d1`, `d2`, `d3`
/// become ξ̇, ξ̈, ξ⃛ for the law's `[ṡ, s̈, s⃛]`. The terms `3ṡs̈·σ″` (`C2`) and `s⃛·σ′` (`S3`)
/// are added only where their factor is not zero, as `eval` does; the choice is made once per
/// row, so the joint loop has no branch. With `SCALED` each result is then multiplied by its
/// factor of `scale` (velocity, acceleration, jerk), as [`Scaled`] multiplies its rows.
#[inline(always)]
fn chain_rule<const C2: bool, const S3: bool, const SCALED: bool>(
    d1: &mut [f64],
    d2: &mut [f64],
    d3: &mut [f64],
    [sd, sdd, sddd]: [f64; 3],
    scale: [f64; 3],
) {
    let (c3, c2, x) = (sd * sd * sd, 3.0 * sd * sdd, sd * sd);
    for ((v, a), jk) in d1.iter_mut().zip(d2.iter_mut()).zip(d3.iter_mut()) {
        let mut jerk = *jk * c3;
        if C2 {
            jerk += c2 * *a;
        }
        if S3 {
            jerk += sddd * *v;
        }
        let acc = *v * sdd + *a * x;
        let vel = *v * sd;
        if SCALED {
            (*v, *a, *jk) = (vel * scale[0], acc * scale[1], jerk * scale[2]);
        } else {
            (*v, *a, *jk) = (vel, acc, jerk);
        }
    }
}

/// Constant path speed: s(t) = s0 + (s1 − s0)·t/T.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearLaw {
    s0: f64,
    s1: f64,
    duration: f64,
}

impl LinearLaw {
    /// From `s0` to `s1` in `duration` seconds (> 0).
    pub fn new(s0: f64, s1: f64, duration: f64) -> Result<Self> {
        crate::error::finite(|| "law start s".into(), s0)?;
        crate::error::finite(|| "law end s".into(), s1)?;
        crate::error::positive(|| "law duration".into(), duration)?;
        Ok(LinearLaw { s0, s1, duration })
    }
}

impl TimeLaw for LinearLaw {
    fn duration(&self) -> f64 {
        self.duration
    }
    fn eval(&self, t: f64) -> [f64; 4] {
        let t = clamp_time(t, self.duration);
        let v = (self.s1 - self.s0) / self.duration;
        [self.s0 + v * t, v, 0.0, 0.0]
    }
}

/// Rest-to-rest minimum-jerk law: s(t) = s0 + (s1 − s0)·(10τ³ − 15τ⁴ + 6τ⁵), τ = t/T.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuinticLaw {
    s0: f64,
    s1: f64,
    duration: f64,
}

impl QuinticLaw {
    /// From `s0` to `s1` in `duration` seconds (> 0), at rest at both ends.
    pub fn new(s0: f64, s1: f64, duration: f64) -> Result<Self> {
        crate::error::finite(|| "law start s".into(), s0)?;
        crate::error::finite(|| "law end s".into(), s1)?;
        crate::error::positive(|| "law duration".into(), duration)?;
        Ok(QuinticLaw { s0, s1, duration })
    }
}

impl TimeLaw for QuinticLaw {
    fn duration(&self) -> f64 {
        self.duration
    }
    fn eval(&self, t: f64) -> [f64; 4] {
        let t = clamp_time(t, self.duration);
        let big_t = self.duration;
        let d = self.s1 - self.s0;
        let x = t / big_t;
        let (x2, x3) = (x * x, x * x * x);
        [
            self.s0 + d * x3 * (10.0 - 15.0 * x + 6.0 * x2),
            d / big_t * 30.0 * x2 * (1.0 - 2.0 * x + x2),
            d / (big_t * big_t) * 60.0 * x * (1.0 - 3.0 * x + 2.0 * x2),
            d / (big_t * big_t * big_t) * 60.0 * (1.0 - 6.0 * x + 6.0 * x2),
        ]
    }
}

/// A trajectory played `factor` times slower: ξ_k(t) = ξ(t/k), duration k·T.
///
/// ```
/// use trajkit::topp::{LinearPath, QuinticLaw, Retimed, Scaled};
/// use trajkit::{Limits, Order, Trajectory};
///
/// let path = LinearPath::new(&[0.0, 1.0], 1)?;
/// let fast = Retimed::new(&path, QuinticLaw::new(0.0, 1.0, 0.5)?)?; // too fast for the limits
/// let limits = Limits::uniform(1, 1.0, 4.0, 50.0)?;
/// let slow = Scaled::to_limits(&fast, &limits, 1000.0)?;          // smallest factor that fits
/// assert!(slow.factor() > 1.0);
/// let mut v = [0.0];
/// slow.eval(slow.duration() / 2.0, Order::Velocity, &mut v);      // peak velocity
/// assert!(v[0] <= 1.0 + 1e-12);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Scaled<T: Trajectory> {
    inner: T,
    factor: f64,
}

impl<T: Trajectory> Scaled<T> {
    /// `factor > 1` slows down, `factor < 1` speeds up.
    pub fn new(inner: T, factor: f64) -> Result<Self> {
        crate::error::positive(|| "time scale factor".into(), factor)?;
        Ok(Scaled { inner, factor })
    }

    /// Scaled by the smallest factor that meets `limits` at samples taken at `rate_hz` (see
    /// [`min_time_scale`]); a trajectory that does not move is returned unscaled.
    pub fn to_limits(inner: T, limits: &Limits, rate_hz: f64) -> Result<Self> {
        let k = min_time_scale(&inner, limits, rate_hz)?;
        Self::new(inner, if k > 0.0 { k } else { 1.0 })
    }

    /// The factor k.
    pub fn factor(&self) -> f64 {
        self.factor
    }

    /// The unscaled trajectory.
    pub fn inner(&self) -> &T {
        &self.inner
    }
}

impl<T: Trajectory> Trajectory for Scaled<T> {
    fn dof(&self) -> usize {
        self.inner.dof()
    }
    fn duration(&self) -> f64 {
        self.inner.duration() * self.factor
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        let k = self.factor;
        self.inner.eval(t / k, order, out);
        let c = k.powi(-(order.index() as i32));
        if order != Order::Position {
            out[..self.inner.dof()].iter_mut().for_each(|v| *v *= c);
        }
    }

    /// The inner trajectory's [`Trajectory::eval_rows_scaled`]: its rows at `t/k`, scaled
    /// as in `eval`.
    fn eval_rows(&self, times: &[f64], out: [&mut [f64]; 4]) {
        self.inner.eval_rows_scaled(times, self.factor, out);
    }
}

/// The smallest factor k such that `Scaled::new(traj, k)` meets the velocity, acceleration and
/// jerk limits at the instants `k·t_i`, where `t_i` samples `traj` at `rate_hz` (both ends
/// included): `k = max(r_v, √r_a, ∛r_j)` over samples and joints, `r` being the fraction of
/// the limit used (directional limits respected). Below 1 the trajectory may be sped up.
/// Returns 0 for a trajectory that never moves.
pub fn min_time_scale<T: Trajectory + ?Sized>(
    traj: &T,
    limits: &Limits,
    rate_hz: f64,
) -> Result<f64> {
    limits.expect_dof(traj.dof(), "time scaling")?;
    crate::error::positive(|| "sample rate".into(), rate_hz)?;
    let n = traj.dof();
    let big_t = traj.duration();
    let steps = (big_t * rate_hz).floor();
    if steps > 1e9 {
        return Err(Error::InvalidValue {
            field: "sample count (duration × rate)".into(),
            value: steps,
            reason: "is too large (over 1e9)",
        });
    }
    let steps = steps as usize;
    let mut buf = vec![0.0; n];
    let mut k: f64 = 0.0;
    for i in 0..=steps + 1 {
        let t = if i <= steps {
            i as f64 / rate_hz
        } else {
            big_t
        };
        if t > big_t {
            continue;
        }
        for (order, root) in [
            (Order::Velocity, 1.0),
            (Order::Acceleration, 2.0),
            (Order::Jerk, 3.0),
        ] {
            traj.eval(t, order, &mut buf);
            for j in 0..n {
                let r = limits.joint(j).ratio(order, buf[j]);
                let f = if root == 1.0 {
                    r
                } else if root == 2.0 {
                    r.sqrt()
                } else {
                    r.cbrt()
                };
                if f.is_nan() {
                    return Err(Error::InvalidValue {
                        field: format!("joint {} {} at t = {t}", j + 1, order.name()),
                        value: buf[j],
                        reason: "is not a finite number",
                    });
                }
                k = k.max(f);
            }
        }
    }
    Ok(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// σ(s) = (sin s, s², s³): every derivative up to the third is non-trivial.
    struct Curve;
    impl Path for Curve {
        fn dim(&self) -> usize {
            3
        }
        fn interval(&self) -> (f64, f64) {
            (0.0, 2.0)
        }
        fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
            let s = s.clamp(0.0, 2.0);
            let v = match order {
                0 => [s.sin(), s * s, s * s * s],
                1 => [s.cos(), 2.0 * s, 3.0 * s * s],
                2 => [-s.sin(), 2.0, 6.0 * s],
                3 => [-s.cos(), 0.0, 6.0],
                _ => [0.0; 3],
            };
            out[..3].copy_from_slice(&v);
        }
    }

    #[test]
    fn chain_rule_matches_finite_differences() {
        let traj = Retimed::new(Curve, QuinticLaw::new(0.2, 1.9, 1.5).unwrap()).unwrap();
        let h = 1e-5;
        let (mut a, mut b, mut d) = ([0.0; 3], [0.0; 3], [0.0; 3]);
        for &t in &[0.1, 0.4, 0.75, 1.2, 1.45] {
            for k in 1..4 {
                let lower = Order::from_index(k - 1).unwrap();
                traj.eval(t + h, lower, &mut a);
                traj.eval(t - h, lower, &mut b);
                traj.eval(t, Order::from_index(k).unwrap(), &mut d);
                for j in 0..3 {
                    let fd = (a[j] - b[j]) / (2.0 * h);
                    assert!(
                        (fd - d[j]).abs() < 1e-6 * (1.0 + d[j].abs()),
                        "t {t} order {k} joint {j}: {fd} vs {}",
                        d[j]
                    );
                }
            }
        }
    }

    #[test]
    fn uniform_scaling_and_smallest_factor() {
        let traj = Retimed::new(Curve, QuinticLaw::new(0.0, 2.0, 1.0).unwrap()).unwrap();
        let limits = Limits::uniform(3, 10.0, 30.0, 500.0).unwrap();
        let k = min_time_scale(&traj, &limits, 1000.0).unwrap();
        assert!(k > 0.0);
        let slow = Scaled::to_limits(&traj, &limits, 1000.0).unwrap();
        assert!((slow.duration() - k).abs() < 1e-15);
        // At the scaled sample instants the worst ratio is exactly 1.
        let k2 = min_time_scale(&slow, &limits, 1000.0 / k).unwrap();
        assert!((k2 - 1.0).abs() < 1e-12, "{k2}");
        // Derivatives scale by powers of 1/k.
        let s = Scaled::new(&traj, 2.0).unwrap();
        let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
        s.eval(1.0, Order::Jerk, &mut a);
        traj.eval(0.5, Order::Jerk, &mut b);
        assert!((a[2] - b[2] / 8.0).abs() < 1e-12);
        assert!(Scaled::new(&traj, 0.0).is_err());
        assert!(Scaled::new(&traj, f64::NAN).is_err());
    }

    /// Forwards everything but [`Trajectory::eval_rows_scaled`]: the trait's default then
    /// scales after the rows are written.
    struct Plain<T>(T);
    impl<T: Trajectory> Trajectory for Plain<T> {
        fn dof(&self) -> usize {
            self.0.dof()
        }
        fn duration(&self) -> f64 {
            self.0.duration()
        }
        fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
            self.0.eval(t, order, out)
        }
        fn eval_rows(&self, times: &[f64], out: [&mut [f64]; 4]) {
            self.0.eval_rows(times, out)
        }
    }

    #[test]
    fn scaled_rows_fold_the_factors_bitwise() {
        let traj = Retimed::new(Curve, QuinticLaw::new(0.1, 1.8, 1.5).unwrap()).unwrap();
        // More than two blocks of times, past both ends, unsorted at the end.
        let mut times: Vec<f64> = (0..150).map(|i| i as f64 * 0.0173 - 0.1).collect();
        times.extend([0.3, 2.9, 0.0]);
        let rows = times.len() * 3;
        for k in [1.0, 1.37, 0.61, 3.0] {
            let [mut fused, mut plain] = [0, 1].map(|_| [0; 4].map(|_| vec![0.0; rows]));
            let [a, b, c, d] = &mut fused;
            Scaled::new(&traj, k)
                .unwrap()
                .eval_rows(&times, [a, b, c, d]);
            let [a, b, c, d] = &mut plain;
            Scaled::new(Plain(&traj), k)
                .unwrap()
                .eval_rows(&times, [a, b, c, d]);
            let bits = |m: &[Vec<f64>; 4]| {
                m.clone()
                    .map(|c| c.iter().map(|v| v.to_bits()).collect::<Vec<_>>())
            };
            assert_eq!(bits(&fused), bits(&plain), "factor {k}");
            // And each row is what `eval` gives.
            let scaled = Scaled::new(&traj, k).unwrap();
            let mut one = [0.0; 3];
            for (i, &t) in times.iter().enumerate() {
                for (order, col) in Order::ALL.into_iter().zip(&fused) {
                    scaled.eval(t, order, &mut one);
                    let row = &col[i * 3..(i + 1) * 3];
                    assert_eq!(
                        one.map(f64::to_bits),
                        [row[0], row[1], row[2]].map(f64::to_bits),
                        "factor {k}, t {t}, {order:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn clamped_time_and_bad_input() {
        let law = LinearLaw::new(0.0, 2.0, 4.0).unwrap();
        assert_eq!(law.eval(-1.0), [0.0, 0.5, 0.0, 0.0]);
        assert_eq!(law.eval(9.0)[0], 2.0);
        assert!(LinearLaw::new(0.0, 1.0, -1.0).is_err());
        assert!(QuinticLaw::new(f64::NAN, 1.0, 1.0).is_err());
    }
}
