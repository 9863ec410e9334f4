//! A C² interpolating spline that stays inside per-component bounds, proven exactly.
//!
//! An interpolating cubic spline (natural, not-a-knot, clamped) through points that all lie
//! inside a box can leave the box between them: a joint that turns around near its limit
//! swings past the waypoint, and a long piece between short ones wiggles. [`BoundedSpline`]
//! takes such a C² spline and bounds `lo[d] ≤ σ_d(s) ≤ hi[d]` and returns a spline that
//!
//! - passes through every point of the base spline at every break (same breaks),
//! - is C² (value, first and second derivative continuous at every break),
//! - stays inside the bounds on its whole interval, **verified exactly**: the extrema of each
//!   piece of each component are the roots of its derivative, found by root isolation
//!   ([`crate::poly::roots::roots_in`]), not by sampling,
//! - equals the base spline wherever the base already stays inside: only the pieces next to a
//!   break whose data had to change are different, and only in the offending component.
//!
//! # Method
//! Each component is handled on its own (the breaks are shared, so components do not
//! interact). Every piece is described by its end data: value p, slope v and second
//! derivative a at both breaks; the quintic Hermite polynomial with that data is unique, and
//! for the base spline's own data it *is* the base piece. Two pieces sharing a break share
//! its (p, v, a), so any choice of (v, a) per break gives a C² spline through the points.
//!
//! 1. Each piece's exact range is computed (Bernstein coefficients first: a polynomial lies
//!    within the range of its Bernstein coefficients, which settles most pieces with no root
//!    finding; the derivative's roots otherwise).
//! 2. For every piece that leaves the bounds (beyond rounding, 1e-12 relative), the data at
//!    both of its breaks is changed, one step at a time:
//!    - **shape** (first step): at a break where the component turns around (or is flat),
//!      the slope becomes 0 and the second derivative takes the sign of a maximum (≤ 0) or
//!      minimum (≥ 0); elsewhere a slope pointing against the motion becomes 0;
//!    - **shrink** (next steps): slope and second derivative are halved, up to
//!      [`MAX_HALVINGS`] times;
//!    - **rest** (last step): both become 0.
//! 3. The pieces next to a changed break are computed again, and so on until no piece leaves
//!    the bounds.
//!
//! **Guarantee.** A piece whose two breaks are both at rest (v = a = 0) is
//! p₀ + (p₁ − p₀)(10τ³ − 15τ⁴ + 6τ⁵), τ ∈ [0, 1], which is monotone between its two points:
//! inside the bounds whenever the points are. Every round moves at least one break of every
//! offending piece one step closer to rest, and a break has at most `MAX_HALVINGS + 2` steps,
//! so the loop ends after at most `(breaks) · (MAX_HALVINGS + 2)` rounds with every piece
//! inside. A final exact pass over every piece confirms it (an error otherwise, which the
//! argument above rules out up to rounding).
//!
//! A break where *every* component ends at rest has zero path speed σ′ = 0: a path parameter
//! that must race through it. [`BoundedSpline::slow_breaks`] lists such interior breaks (and
//! nearly such) so that a planner can stop there instead (see [`crate::topp::messy`]).
//!
//! # Precision contract
//! Values at the breaks are the base spline's own values (the stored constant coefficients);
//! continuity of σ′ and σ″ at changed breaks holds to rounding of the Hermite coefficients
//! (1e-12 relative in the tests); the bounds hold within 1e-12 · max(1, |lo|, |hi|).

use crate::error::{Error, Result};
use crate::poly::roots::{horner, roots_in, MAX_DEGREE};
use crate::spline::ppoly::{quintic_coeffs, PiecewisePolynomial};

/// How many times a break's slope and second derivative are halved before they are set to 0.
pub const MAX_HALVINGS: u8 = 8;

/// What [`BoundedSpline::new`] changed in one component.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundRepair {
    /// The component (0-based).
    pub component: usize,
    /// The base spline's value farthest outside the bounds.
    pub value: f64,
    /// Where it was (the parameter s).
    pub at: f64,
    /// How far outside the bounds it was.
    pub excursion: f64,
    /// How many breaks got a new slope and second derivative.
    pub breaks_changed: usize,
}

/// A C² spline through the points of a base spline, inside per-component bounds (see the
/// module documentation).
///
/// ```
/// use trajkit::spline::{BoundedSpline, CubicSpline};
/// use trajkit::Path;
/// // One component turning around at 0.95 with an upper bound of 1: the natural spline
/// // overshoots to about 1.034, the bounded one stays below 1.
/// let x = [0.0, 1.0, 3.0];
/// let y = [0.0, 0.95, 0.0];
/// let base = CubicSpline::natural(&x, &y, 1)?;
/// let bounded = BoundedSpline::new(base.as_ppoly(), &[-1.0], &[1.0])?;
/// assert_eq!(bounded.repairs().len(), 1);
/// let (lo, hi) = bounded.range(0);
/// assert!(hi <= 1.0 && lo >= -1.0);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BoundedSpline {
    pp: PiecewisePolynomial,
    repairs: Vec<BoundRepair>,
}

crate::spline::ppoly_backed!(BoundedSpline);

/// A piece of one component in the normalized variable τ = (s − b_i)/h ∈ [0, 1]: coefficients
/// of τ⁰..τ⁵.
type Normalized = [f64; 6];

/// Per-break data of one component: slope and second derivative, and the repair step reached.
#[derive(Debug, Clone, Copy)]
struct BreakData {
    v: f64,
    a: f64,
    /// 0 untouched, 1 shaped, 2..=MAX_HALVINGS+1 halved, MAX_HALVINGS+2 at rest.
    level: u8,
}

const AT_REST: u8 = MAX_HALVINGS + 2;

impl BoundedSpline {
    /// Bounds the C² piecewise polynomial `base` (degree ≤ 5, e.g. a [`super::CubicSpline`]'s
    /// [`as_ppoly`](super::CubicSpline::as_ppoly)) to `lo[d] ≤ σ_d ≤ hi[d]` (one bound per
    /// component; infinite bounds are allowed and leave the component as it is).
    ///
    /// Errors: [`Error::DimensionMismatch`] for bounds of the wrong length or a degree above
    /// 5; [`Error::InvalidValue`] for NaN or inverted bounds; [`Error::OutOfRange`] (with the
    /// break's parameter as `time`) when a point of the base spline at a break lies outside
    /// its bounds — no spline through it can stay inside.
    pub fn new(base: &PiecewisePolynomial, lo: &[f64], hi: &[f64]) -> Result<Self> {
        let dim = base.dim();
        for (what, b) in [("lower bounds", lo), ("upper bounds", hi)] {
            if b.len() != dim {
                return Err(Error::DimensionMismatch {
                    what: format!("{what} of a bounded spline"),
                    expected: dim,
                    found: b.len(),
                });
            }
        }
        if base.degree() > 5 {
            return Err(Error::DimensionMismatch {
                what: "degree of a bounded spline's base (at most 5)".into(),
                expected: 5,
                found: base.degree(),
            });
        }
        for d in 0..dim {
            if lo[d].is_nan() || hi[d].is_nan() || lo[d] >= hi[d] {
                return Err(Error::InvalidValue {
                    field: format!("bounds of component {d} (upper)"),
                    value: hi[d],
                    reason: "is not above the lower bound",
                });
            }
        }
        let n = base.num_pieces();
        let breaks = base.breaks().to_vec();
        let k = base.degree() + 1;
        // Base pieces, normalized, per component: norm[i * dim + d].
        let mut norm: Vec<Normalized> = Vec::with_capacity(n * dim);
        for i in 0..n {
            let h = breaks[i + 1] - breaks[i];
            let c = base.piece(i);
            for d in 0..dim {
                let mut e = [0.0; 6];
                let mut hp = 1.0;
                for m in 0..k {
                    e[m] = c[d * k + m] * hp;
                    hp *= h;
                }
                norm.push(e);
            }
        }
        let mut out = norm.clone();
        let mut repairs = Vec::new();
        for d in 0..dim {
            if lo[d] == f64::NEG_INFINITY && hi[d] == f64::INFINITY {
                continue;
            }
            let comp = Component::new(&breaks, &norm, dim, d, lo[d], hi[d]);
            comp.check_points()?;
            if let Some(repair) = comp.repair(&mut out)? {
                repairs.push(repair);
            }
        }
        let pp = if repairs.is_empty() {
            base.clone()
        } else {
            let mut coeffs = Vec::with_capacity(n * dim * 6);
            for i in 0..n {
                let h = breaks[i + 1] - breaks[i];
                for d in 0..dim {
                    let e = &out[i * dim + d];
                    let mut hp = 1.0;
                    for m in 0..6 {
                        coeffs.push(e[m] / hp);
                        hp *= h;
                    }
                }
            }
            PiecewisePolynomial::new(breaks, dim, 5, coeffs)?
        };
        Ok(BoundedSpline { pp, repairs })
    }

    /// What was changed, one entry per changed component; empty when the base spline already
    /// stayed inside the bounds (the spline is then the base itself).
    pub fn repairs(&self) -> &[BoundRepair] {
        &self.repairs
    }

    /// The exact smallest and largest value of component `d` over the whole interval.
    /// Panics if `d >= dim`.
    pub fn range(&self, d: usize) -> (f64, f64) {
        exact_range_of(&self.pp, d)
    }

    /// Interior breaks (indices) where the repair left the path slow: the Euclidean norm of
    /// σ′ there is below `min_speed` (the repair can bring every component's slope to 0 at
    /// one break, where a time parameterization would have to race through). Empty when
    /// nothing was repaired.
    pub fn slow_breaks(&self, min_speed: f64) -> Vec<usize> {
        if self.repairs.is_empty() {
            return Vec::new();
        }
        let n = self.pp.num_pieces();
        let k = self.pp.degree() + 1;
        let dim = self.pp.dim();
        (1..n)
            .filter(|&i| {
                let c = self.pp.piece(i);
                let speed2: f64 = (0..dim).map(|d| c[d * k + 1] * c[d * k + 1]).sum();
                speed2.sqrt() < min_speed
            })
            .collect()
    }
}

/// The exact range of component `d` of any piecewise polynomial of degree ≤ [`MAX_DEGREE`].
pub(crate) fn exact_range_of(pp: &PiecewisePolynomial, d: usize) -> (f64, f64) {
    let k = pp.degree() + 1;
    let mut r = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..pp.num_pieces() {
        let h = pp.breaks()[i + 1] - pp.breaks()[i];
        let c = &pp.piece(i)[d * k..(d + 1) * k];
        let mut e = [0.0; MAX_DEGREE + 1];
        let mut hp = 1.0;
        for m in 0..k.min(MAX_DEGREE + 1) {
            e[m] = c[m] * hp;
            hp *= h;
        }
        let (lo, _, hi, _) = poly_range(&e[..k.min(MAX_DEGREE + 1)]);
        r.0 = r.0.min(lo);
        r.1 = r.1.max(hi);
    }
    r
}

/// Exact range of a polynomial (coefficients of τ⁰.. on [0, 1]): (min, argmin, max, argmax).
fn poly_range(e: &[f64]) -> (f64, f64, f64, f64) {
    let mut best = (e[0], 0.0, e[0], 0.0);
    let mut consider = |t: f64| {
        let v = horner(e, t);
        if v < best.0 {
            best.0 = v;
            best.1 = t;
        }
        if v > best.2 {
            best.2 = v;
            best.3 = t;
        }
    };
    consider(1.0);
    let len = e.len();
    if len > 2 {
        let mut dc = [0.0; MAX_DEGREE + 1];
        for m in 0..len - 1 {
            dc[m] = e[m + 1] * (m + 1) as f64;
        }
        let mut roots = [0.0; MAX_DEGREE];
        let nr = roots_in(&dc[..len - 1], 0.0, 1.0, &mut roots);
        for &t in &roots[..nr] {
            consider(t);
        }
    }
    best
}

/// Range of the Bernstein coefficients of a quintic in τ (a polynomial lies within it).
fn bernstein_hull(e: &Normalized) -> (f64, f64) {
    // b_k = Σ_{m ≤ k} C(k, m) / C(5, m) · e_m.
    const BINOM: [[f64; 6]; 6] = [
        [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 2.0, 1.0, 0.0, 0.0, 0.0],
        [1.0, 3.0, 3.0, 1.0, 0.0, 0.0],
        [1.0, 4.0, 6.0, 4.0, 1.0, 0.0],
        [1.0, 5.0, 10.0, 10.0, 5.0, 1.0],
    ];
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for k in 0..6 {
        let mut b = 0.0;
        for m in 0..=k {
            b += BINOM[k][m] / BINOM[5][m] * e[m];
        }
        lo = lo.min(b);
        hi = hi.max(b);
    }
    (lo, hi)
}

/// The normalized quintic with end data (p, v, a) at τ = 0 and 1 on a piece of width `h`.
fn hermite(h: f64, p0: f64, p1: f64, d0: BreakData, d1: BreakData) -> Normalized {
    let c = quintic_coeffs(h, p0, p1, d0.v, d1.v, d0.a, d1.a);
    let mut e = [0.0; 6];
    let mut hp = 1.0;
    for m in 0..6 {
        e[m] = c[m] * hp;
        hp *= h;
    }
    // The constant term is the point itself, exactly.
    e[0] = p0;
    e
}

/// One component's repair state.
struct Component<'a> {
    breaks: &'a [f64],
    base: &'a [Normalized],
    dim: usize,
    d: usize,
    lo: f64,
    hi: f64,
    tol: f64,
    /// Point values at the breaks.
    p: Vec<f64>,
}

impl<'a> Component<'a> {
    fn new(
        breaks: &'a [f64],
        base: &'a [Normalized],
        dim: usize,
        d: usize,
        lo: f64,
        hi: f64,
    ) -> Self {
        let n = breaks.len() - 1;
        let mut p: Vec<f64> = (0..n).map(|i| base[i * dim + d][0]).collect();
        p.push(base[(n - 1) * dim + d].iter().sum());
        let scale = [1.0, lo.abs(), hi.abs()]
            .into_iter()
            .filter(|x| x.is_finite())
            .fold(0.0, f64::max);
        Component {
            breaks,
            base,
            dim,
            d,
            lo,
            hi,
            tol: 1e-12 * scale,
            p,
        }
    }

    /// Every point at a break must be inside the bounds.
    fn check_points(&self) -> Result<()> {
        for (i, &v) in self.p.iter().enumerate() {
            if v < self.lo - self.tol || v > self.hi + self.tol {
                return Err(Error::OutOfRange {
                    joint: self.d,
                    name: String::new(),
                    time: self.breaks[i],
                    value: v,
                    lo: self.lo,
                    hi: self.hi,
                });
            }
        }
        Ok(())
    }

    /// Distance outside the bounds of a normalized piece, and where (τ) and the value there;
    /// `None` when inside.
    fn excursion(&self, e: &Normalized) -> Option<(f64, f64, f64)> {
        let (blo, bhi) = bernstein_hull(e);
        if blo >= self.lo - self.tol && bhi <= self.hi + self.tol {
            return None;
        }
        let (mn, tmn, mx, tmx) = poly_range(e);
        let below = self.lo - mn;
        let above = mx - self.hi;
        if below <= self.tol && above <= self.tol {
            None
        } else if below >= above {
            Some((below, tmn, mn))
        } else {
            Some((above, tmx, mx))
        }
    }

    /// Base data (v, a) at every break, read from the pieces (C² base: both sides agree).
    fn base_data(&self) -> Vec<BreakData> {
        let n = self.breaks.len() - 1;
        let mut data = Vec::with_capacity(n + 1);
        for i in 0..n {
            let h = self.breaks[i + 1] - self.breaks[i];
            let e = &self.base[i * self.dim + self.d];
            data.push(BreakData {
                v: e[1] / h,
                a: 2.0 * e[2] / (h * h),
                level: 0,
            });
        }
        let h = self.breaks[n] - self.breaks[n - 1];
        let e = &self.base[(n - 1) * self.dim + self.d];
        let v: f64 = (1..6).map(|m| m as f64 * e[m]).sum::<f64>() / h;
        let a: f64 = (2..6).map(|m| (m * (m - 1)) as f64 * e[m]).sum::<f64>() / (h * h);
        data.push(BreakData { v, a, level: 0 });
        data
    }

    /// The piece `i` as it stands: the base piece when neither break changed.
    fn piece(&self, i: usize, data: &[BreakData]) -> Normalized {
        if data[i].level == 0 && data[i + 1].level == 0 {
            self.base[i * self.dim + self.d]
        } else {
            let h = self.breaks[i + 1] - self.breaks[i];
            hermite(h, self.p[i], self.p[i + 1], data[i], data[i + 1])
        }
    }

    /// One repair step at break `k` (see the module documentation).
    fn step(&self, k: usize, data: &mut [BreakData]) {
        let n = self.p.len() - 1;
        let b = &mut data[k];
        if b.level == 0 {
            b.level = 1;
            let dl = (k > 0).then(|| self.p[k] - self.p[k - 1]);
            let dr = (k < n).then(|| self.p[k + 1] - self.p[k]);
            let (v0, a0) = (b.v, b.a);
            match (dl, dr) {
                (Some(l), Some(r)) if l * r <= 0.0 => {
                    b.v = 0.0;
                    let is_max = l > 0.0 || r < 0.0;
                    let is_min = l < 0.0 || r > 0.0;
                    b.a = match (is_max, is_min) {
                        (true, false) => b.a.min(0.0),
                        (false, true) => b.a.max(0.0),
                        _ => 0.0,
                    };
                }
                (l, r) => {
                    let dir = l.or(r).unwrap_or(0.0);
                    if b.v * dir <= 0.0 {
                        b.v = 0.0;
                    }
                }
            }
            if b.v != v0 || b.a != a0 {
                return;
            }
        }
        if b.level <= MAX_HALVINGS {
            b.level += 1;
            b.v *= 0.5;
            b.a *= 0.5;
        } else {
            b.level = AT_REST;
            b.v = 0.0;
            b.a = 0.0;
        }
    }

    /// Repairs the component into `out` (normalized pieces, `out[i * dim + d]`); `None` when
    /// the base stays inside.
    fn repair(&self, out: &mut [Normalized]) -> Result<Option<BoundRepair>> {
        let n = self.breaks.len() - 1;
        let mut data = self.base_data();
        // The base's worst excursion, for the report.
        let mut worst: Option<(f64, f64, f64)> = None;
        let mut bad: Vec<bool> = vec![false; n];
        for i in 0..n {
            if let Some((x, t, v)) = self.excursion(&self.base[i * self.dim + self.d]) {
                bad[i] = true;
                let s = self.breaks[i] + t * (self.breaks[i + 1] - self.breaks[i]);
                if worst.is_none_or(|w| x > w.0) {
                    worst = Some((x, s, v));
                }
            }
        }
        let Some((excursion, at, value)) = worst else {
            return Ok(None);
        };
        let max_rounds = (n + 1) * (AT_REST as usize + 1) + 1;
        for _ in 0..max_rounds {
            let offending: Vec<usize> = (0..n).filter(|&i| bad[i]).collect();
            if offending.is_empty() {
                break;
            }
            let mut stepped = vec![false; n + 1];
            for &i in &offending {
                for k in [i, i + 1] {
                    if !stepped[k] && data[k].level < AT_REST {
                        self.step(k, &mut data);
                        stepped[k] = true;
                    }
                }
            }
            for i in 0..n {
                if stepped[i] || stepped[i + 1] {
                    bad[i] = self.excursion(&self.piece(i, &data)).is_some();
                }
            }
        }
        // Final exact pass over every piece of this component.
        for i in 0..n {
            let e = self.piece(i, &data);
            if let Some((_, t, v)) = self.excursion(&e) {
                return Err(Error::OutOfRange {
                    joint: self.d,
                    name: String::new(),
                    time: self.breaks[i] + t * (self.breaks[i + 1] - self.breaks[i]),
                    value: v,
                    lo: self.lo,
                    hi: self.hi,
                });
            }
            out[i * self.dim + self.d] = e;
        }
        let breaks_changed = data.iter().filter(|b| b.level > 0).count();
        Ok(Some(BoundRepair {
            component: self.d,
            value,
            at,
            excursion,
            breaks_changed,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use crate::spline::CubicSpline;
    use crate::Path;

    fn chord(y: &[f64], dim: usize) -> Vec<f64> {
        let n = y.len() / dim;
        let mut s = vec![0.0; n];
        for i in 1..n {
            let d: f64 = (0..dim)
                .map(|j| (y[i * dim + j] - y[(i - 1) * dim + j]).powi(2))
                .sum();
            s[i] = s[i - 1] + d.sqrt();
        }
        s
    }

    /// Every property of the module's contract, checked on one case.
    fn check_contract(base: &PiecewisePolynomial, b: &BoundedSpline, lo: &[f64], hi: &[f64]) {
        let dim = base.dim();
        let x = base.breaks();
        let (mut p, mut q) = (vec![0.0; dim], vec![0.0; dim]);
        for (i, &xi) in x.iter().enumerate() {
            base.eval(xi, 0, &mut p);
            b.eval(xi, 0, &mut q);
            for d in 0..dim {
                assert!(
                    (p[d] - q[d]).abs() <= 1e-12 * (1.0 + p[d].abs()),
                    "point {i}"
                );
            }
        }
        // C²: one-sided derivatives agree at interior breaks.
        let pp = b.as_ppoly();
        let k = pp.degree() + 1;
        for i in 1..pp.num_pieces() {
            let h = x[i] - x[i - 1];
            let left = &pp.piece(i - 1);
            let right = &pp.piece(i);
            for d in 0..dim {
                let c = &left[d * k..(d + 1) * k];
                let v: f64 = (1..k).map(|m| m as f64 * c[m] * h.powi(m as i32 - 1)).sum();
                let a: f64 = (2..k)
                    .map(|m| (m * (m - 1)) as f64 * c[m] * h.powi(m as i32 - 2))
                    .sum();
                let (vr, ar) = (right[d * k + 1], 2.0 * right[d * k + 2]);
                assert!((v - vr).abs() <= 1e-9 * (1.0 + vr.abs()), "σ′ at break {i}");
                assert!((a - ar).abs() <= 1e-7 * (1.0 + ar.abs()), "σ″ at break {i}");
            }
        }
        for d in 0..dim {
            let tol = 1e-12 * (1.0f64).max(lo[d].abs()).max(hi[d].abs());
            let (mn, mx) = b.range(d);
            assert!(
                mn >= lo[d] - tol && mx <= hi[d] + tol,
                "component {d}: [{mn}, {mx}]"
            );
            // The exact range really bounds the spline: dense samples never exceed it.
            let (s0, s1) = b.interval();
            for k in 0..=400 {
                let s = s0 + (s1 - s0) * k as f64 / 400.0;
                b.eval(s, 0, &mut q);
                assert!(q[d] >= mn - 1e-12 && q[d] <= mx + 1e-12);
            }
            // Components that never left the bounds are the base itself.
            if !b.repairs().iter().any(|r| r.component == d) {
                for k in 0..=200 {
                    let s = s0 + (s1 - s0) * k as f64 / 200.0;
                    base.eval(s, 0, &mut p);
                    b.eval(s, 0, &mut q);
                    assert!((p[d] - q[d]).abs() <= 1e-12 * (1.0 + p[d].abs()));
                }
            }
        }
    }

    #[test]
    fn turning_near_the_bound_peaks_at_the_waypoint() {
        let x = [0.0, 1.0, 3.0];
        let y = [0.0, 0.95, 0.0];
        let base = CubicSpline::natural(&x, &y, 1).unwrap();
        // The exact maximum of the natural spline (1.0342290 on a 1e-4 grid).
        let top = exact_range_of(base.as_ppoly(), 0).1;
        assert!((top - 1.034229).abs() < 1e-6, "{top}");
        let b = BoundedSpline::new(base.as_ppoly(), &[-1.0], &[1.0]).unwrap();
        let r = &b.repairs()[0];
        assert_eq!(r.component, 0);
        assert!(r.excursion > 0.0 && (r.value - 1.0 - r.excursion).abs() < 1e-12);
        check_contract(base.as_ppoly(), &b, &[-1.0], &[1.0]);
        // Inside bounds that are wide enough, nothing changes.
        let b = BoundedSpline::new(base.as_ppoly(), &[-2.0], &[2.0]).unwrap();
        assert!(b.repairs().is_empty());
        assert_eq!(b.as_ppoly(), base.as_ppoly());
    }

    #[test]
    fn points_on_the_bounds_and_flat_stretches() {
        // Touches the upper bound twice in a row, then the lower one.
        let y = [0.0, 1.0, 1.0, -1.0, 0.5, -1.0, -1.0, 0.0];
        let x: Vec<f64> = (0..y.len())
            .map(|i| i as f64 * 0.7 + (i % 3) as f64 * 0.1)
            .collect();
        for base in [
            CubicSpline::natural(&x, &y, 1).unwrap(),
            CubicSpline::not_a_knot(&x, &y, 1).unwrap(),
            CubicSpline::clamped(&x, &y, 1, &[3.0], &[-3.0]).unwrap(),
        ] {
            let b = BoundedSpline::new(base.as_ppoly(), &[-1.0], &[1.0]).unwrap();
            assert!(!b.repairs().is_empty());
            check_contract(base.as_ppoly(), &b, &[-1.0], &[1.0]);
        }
    }

    #[test]
    fn seeded_random_waypoints_stay_inside() {
        let mut rng = SplitMix64::new(13);
        let lo = [
            -2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973,
        ];
        let hi = [2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973];
        let mut repaired = 0;
        for case in 0..120 {
            let n = 3 + case % 12;
            let mut y = Vec::with_capacity(n * 7);
            for _ in 0..n {
                for d in 0..7 {
                    // Some points right on a bound.
                    let u = rng.next_f64();
                    let v = if u < 0.05 {
                        lo[d]
                    } else if u > 0.95 {
                        hi[d]
                    } else {
                        lo[d] + (hi[d] - lo[d]) * rng.next_f64()
                    };
                    y.push(v);
                }
            }
            let x = chord(&y, 7);
            let base = match case % 3 {
                0 => CubicSpline::natural(&x, &y, 7),
                1 => CubicSpline::not_a_knot(&x, &y, 7),
                _ => CubicSpline::clamped(&x, &y, 7, &[0.0; 7], &[0.0; 7]),
            }
            .unwrap();
            let b = BoundedSpline::new(base.as_ppoly(), &lo, &hi).unwrap();
            repaired += usize::from(!b.repairs().is_empty());
            check_contract(base.as_ppoly(), &b, &lo, &hi);
        }
        // The suite exercises the repair (most random paths overshoot somewhere).
        assert!(repaired > 60, "{repaired}");
    }

    #[test]
    fn bad_input() {
        let base = CubicSpline::natural(&[0.0, 1.0], &[0.0, 2.0], 1).unwrap();
        let e = BoundedSpline::new(base.as_ppoly(), &[-1.0], &[1.0]).unwrap_err();
        assert!(
            matches!(e, Error::OutOfRange { value, .. } if value == 2.0),
            "{e}"
        );
        assert!(BoundedSpline::new(base.as_ppoly(), &[1.0], &[1.0]).is_err());
        assert!(BoundedSpline::new(base.as_ppoly(), &[f64::NAN], &[1.0]).is_err());
        assert!(BoundedSpline::new(base.as_ppoly(), &[0.0, 0.0], &[1.0, 1.0]).is_err());
        // Unbounded components are left alone.
        let b =
            BoundedSpline::new(base.as_ppoly(), &[f64::NEG_INFINITY], &[f64::INFINITY]).unwrap();
        assert!(b.repairs().is_empty());
    }
}
