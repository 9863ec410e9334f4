//! The time-scale factor of a filtered law, bounded on the whole continuous trajectory.
//!
//! The moving average s_w of a TOPP-RA law s* (constant s̈* between gridpoint times T_i) is a
//! cubic polynomial in t between consecutive *kinks*: the times T_i, the times T_i + w, and the
//! times where s_w crosses a breakpoint of the path. On such a segment
//! `s⃛_w = (s̈*(t) − s̈*(t − w))/w` is constant, and where the path is a polynomial of degree
//! d ≤ 6 (every trajkit spline and polyline) each joint's q̇, q̈ and q⃛ is a polynomial in t.
//! [`scale_bound`] sweeps the segments in time order (the gridpoint indices of t and t − w are
//! known, so no value is taken from the wrong side of a kink) and bounds each of them:
//!
//! - the path is evaluated once per segment, at the middle of its s-range, for σ′..σ⁽ᵈ⁾; the
//!   derivatives at the segment's ends and middle follow from the Taylor expansion of the
//!   polynomial piece (exact, and one-sided at path breakpoints by construction);
//! - each of f = q̇ⱼ, q̈ⱼ, q⃛ⱼ is interpolated by the quadratic p through its values at the
//!   ends and the middle, and `|f − p| ≤ M₃·h³/(72√3)` on a segment of length h, where
//!   M₃ ≥ |f‴| is bounded by Faà di Bruno's formula with absolute values: q⁽ⁿ⁾ =
//!   Σₖ σ⁽ᵏ⁾(s)·Bₙ,ₖ(ṡ, s̈, s⃛, 0, …) (complete Bell polynomials; s⁽⁴⁾ = 0 on a segment), with
//!   |σ⁽ᵏ⁾| bounded on the segment's s-range from the Taylor coefficients and |ṡ|, |s̈|, |s⃛|
//!   bounded exactly (a quadratic, a line and a constant in t);
//! - so `max f ≤ max p + M₃h³/(72√3)` and `min f ≥ min p − M₃h³/(72√3)`, with the extremum of
//!   the quadratic in closed form. The segments are a few milliseconds long, so the margin
//!   is about 1e-9 of the limits where the limits bind.
//!
//! The factor is `k = max(r_v, √r_a, ∛r_j)` over these bounds (r: the fraction of the
//! directional limit used): played k times slower, the trajectory holds every velocity,
//! acceleration and jerk limit at every instant, up to rounding.
//!
//! Paths that are not piecewise polynomials of degree ≤ 6 ([`crate::Path::piecewise_degree`])
//! are evaluated directly at [`SAMPLED_POINTS`] points per segment instead, and the result is
//! marked as sampled ([`ScaleBound::certified`] false): no bound between those points.
//!
//! The sweep allocates its buffers once; its cost is linear in the number of TOPP-RA
//! gridpoints (each gives at most two kinks).

use super::FilteredProfile;
use crate::topp::rescale::TimeLaw;
use crate::{Limits, Order, Path};

/// Points per segment on paths that are not piecewise polynomials (no bound between them).
pub const SAMPLED_POINTS: usize = 9;

/// Highest path degree the certified bound handles (s⁽ⁿ⁾ and σ⁽ⁿ⁾ up to n = 6 appear).
const MAX_DEGREE: usize = 6;

/// What [`scale_bound`] found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScaleBound {
    /// The smallest uniform slow-down that meets every limit: `max(r_v, √r_a, ∛r_j)` over the
    /// bounds of every segment (an upper bound of the exact factor when `certified`).
    pub factor: f64,
    /// The same over the evaluated points only (a lower bound of the exact factor).
    pub sampled: f64,
    /// True when the path is a piecewise polynomial of degree ≤ 6, so that `factor` bounds
    /// the trajectory between the evaluated points too.
    pub certified: bool,
    /// Segments (pieces between kinks) examined.
    pub segments: usize,
    /// Where the factor is reached: time (of the unscaled law), joint, order.
    pub at: (f64, usize, Order),
}

/// Per-joint limit reciprocals: ratio = value·hi for value ≥ 0, value·lo below (0 when
/// unlimited).
struct Inverse {
    hi: [Vec<f64>; 3],
    lo: [Vec<f64>; 3],
    /// max(hi, −lo): the ratio of a magnitude against the smaller directional limit.
    sym: [Vec<f64>; 3],
}

impl Inverse {
    fn new(limits: &Limits) -> Self {
        let inv = |x: f64| if x.is_finite() { 1.0 / x } else { 0.0 };
        let mut hi: [Vec<f64>; 3] = Default::default();
        let mut lo: [Vec<f64>; 3] = Default::default();
        for (o, order) in [Order::Velocity, Order::Acceleration, Order::Jerk]
            .into_iter()
            .enumerate()
        {
            for j in limits.joints() {
                let (l, h) = j.range(order);
                hi[o].push(inv(h));
                lo[o].push(inv(l));
            }
        }
        let sym =
            [0, 1, 2].map(|o: usize| hi[o].iter().zip(&lo[o]).map(|(h, l)| h.max(-l)).collect());
        Inverse { hi, lo, sym }
    }

    /// The fraction of the limit used by values in `[lo, hi]`.
    #[inline]
    fn ratio(&self, o: usize, j: usize, lo: f64, hi: f64) -> f64 {
        (hi * self.hi[o][j]).max(lo * self.lo[o][j])
    }
}

/// The state of the filtered law on one segment, as a polynomial in τ = t − a.
#[derive(Debug, Clone, Copy)]
struct Cubic {
    /// s, ṡ, s̈ at τ = 0 and the constant s⃛.
    c: [f64; 4],
}

impl Cubic {
    #[inline]
    fn s(&self, t: f64) -> f64 {
        let c = &self.c;
        c[0] + t * (c[1] + t * (0.5 * c[2] + t * c[3] / 6.0))
    }
    #[inline]
    fn sd(&self, t: f64) -> f64 {
        let c = &self.c;
        c[1] + t * (c[2] + 0.5 * t * c[3])
    }
    #[inline]
    fn sdd(&self, t: f64) -> f64 {
        self.c[2] + t * self.c[3]
    }
    /// The τ in `[lo, hi]` where s(τ) = target (s is non-decreasing on the segment):
    /// bisection-safeguarded Newton.
    fn time_at(&self, target: f64, mut lo: f64, mut hi: f64) -> f64 {
        let mut t = 0.5 * (lo + hi);
        for _ in 0..100 {
            let f = self.s(t) - target;
            if f < 0.0 {
                lo = t;
            } else {
                hi = t;
            }
            let d = self.sd(t);
            let next = if d > 0.0 { t - f / d } else { f64::NAN };
            let next = if next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
            if (next - t).abs() <= 1e-15 * hi.abs().max(1e-300) || hi - lo <= 0.0 {
                return next;
            }
            t = next;
        }
        t
    }
}

/// The sweep's scratch buffers and running maxima.
struct Sweep<'a, P: Path> {
    path: &'a P,
    inv: Inverse,
    dim: usize,
    degree: Option<usize>,
    breaks: Vec<f64>,
    /// Per path piece: its middle s, then σ⁽ᵐ⁾ there for m = 0..=degree (index
    /// (piece·(degree + 1) + m)·dim + j).
    ref_s: Vec<f64>,
    ref_der: Vec<f64>,
    /// The path piece of the current segment.
    piece: usize,
    /// Largest certified ratio per order (velocity, acceleration, jerk), where it occurs.
    bound: [f64; 3],
    at: [(f64, usize); 3],
    /// Largest factor max(r_v, √r_a, ∛r_j) at evaluated points (a lower bound of the result),
    /// and its powers 1, 2, 3: a joint and order whose bound stays below are skipped.
    k_low: f64,
    threshold: [f64; 3],
    segments: usize,
}

/// Complete Bell polynomials B_{n,k}(x1, x2, x3, 0, 0, 0) for n = 4, 5, 6 and k = 2..=6 (x4 and
/// above vanish: s is a cubic in t on a segment).
fn bell(n: usize, x1: f64, x2: f64, x3: f64) -> [f64; 7] {
    let (x1s, x2s) = (x1 * x1, x2 * x2);
    match n {
        4 => [
            0.0,
            0.0,
            4.0 * x1 * x3 + 3.0 * x2s,
            6.0 * x1s * x2,
            x1s * x1s,
            0.0,
            0.0,
        ],
        5 => [
            0.0,
            0.0,
            10.0 * x2 * x3,
            10.0 * x1s * x3 + 15.0 * x1 * x2s,
            10.0 * x1s * x1 * x2,
            x1s * x1s * x1,
            0.0,
        ],
        _ => [
            0.0,
            0.0,
            10.0 * x3 * x3,
            60.0 * x1 * x2 * x3 + 15.0 * x2s * x2,
            20.0 * x1s * x1 * x3 + 45.0 * x1s * x2s,
            15.0 * x1s * x1s * x2,
            x1s * x1s * x1s,
        ],
    }
}

/// Range of the quadratic through (0, f0), (½, fm), (1, f1) on [0, 1].
#[inline]
fn quadratic_range(f0: f64, fm: f64, f1: f64) -> (f64, f64) {
    let c = 2.0 * (f0 + f1) - 4.0 * fm;
    let b = f1 - f0 - c;
    let (mut lo, mut hi) = (f0.min(f1).min(fm), f0.max(f1).max(fm));
    if c != 0.0 {
        let x = -b / (2.0 * c);
        if x > 0.0 && x < 1.0 {
            let v = f0 + x * (b + c * x);
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    (lo, hi)
}

impl<P: Path> Sweep<'_, P> {
    /// Bounds one segment `[t0, t1]` (τ relative to the cubic's origin) that lies within one
    /// piece of the path; `time` is the law's time at τ = 0.
    fn segment(&mut self, cub: &Cubic, t0: f64, t1: f64, time: f64) {
        self.segments += 1;
        match self.degree {
            Some(1) => self.poly_segment::<1>(cub, t0, t1, time),
            Some(2) => self.poly_segment::<2>(cub, t0, t1, time),
            Some(3) => self.poly_segment::<3>(cub, t0, t1, time),
            Some(4) => self.poly_segment::<4>(cub, t0, t1, time),
            Some(5) => self.poly_segment::<5>(cub, t0, t1, time),
            Some(_) => self.poly_segment::<6>(cub, t0, t1, time),
            None => self.sampled_segment(cub, t0, t1, time),
        }
    }

    /// A value of order `o` found at a point: raises the lower bound of the factor.
    #[inline]
    fn sampled(&mut self, o: usize, r: f64) {
        if r > self.threshold[o] {
            let k = match o {
                0 => r,
                1 => r.sqrt(),
                _ => r.cbrt(),
            };
            if k > self.k_low {
                self.k_low = k;
                self.threshold = [k, k * k, k * k * k];
            }
        }
    }

    /// [`Sweep::segment`] on a path of degree ≤ `D`.
    fn poly_segment<const D: usize>(&mut self, cub: &Cubic, t0: f64, t1: f64, time: f64) {
        let dim = self.dim;
        let tm = 0.5 * (t0 + t1);
        let (s0, sm, s1) = (cub.s(t0), cub.s(tm), cub.s(t1));
        let sddd = cub.c[3];
        // Taylor weights dⁱ/i! of: the middle's offset from the piece's reference point, the
        // three points' offsets from the middle, and the largest of those.
        let piece = self.piece;
        let offsets = [
            sm - self.ref_s[piece],
            s0 - sm,
            0.0,
            s1 - sm,
            (s0 - sm).abs().max((s1 - sm).abs()),
        ];
        let mut wts = [[0.0f64; MAX_DEGREE + 1]; 5];
        for (wt, &d) in wts.iter_mut().zip(&offsets) {
            wt[0] = 1.0;
            for i in 1..=D {
                wt[i] = wt[i - 1] * d / i as f64;
            }
        }
        let times = [t0, tm, t1];
        let sd = times.map(|t| cub.sd(t));
        let sdd = times.map(|t| cub.sdd(t));
        // |ṡ|, |s̈| on the segment (s̈ linear, ṡ quadratic with its vertex at s̈ = 0).
        let x2 = sdd[0].abs().max(sdd[2].abs());
        let mut x1 = sd[0].abs().max(sd[2].abs());
        if sddd != 0.0 {
            let tv = -cub.c[2] / sddd;
            if tv > t0 && tv < t1 {
                x1 = x1.max(cub.sd(tv).abs());
            }
        }
        let x3 = sddd.abs();
        let mut bells: Option<[[f64; 7]; 3]> = None;
        let h = t1 - t0;
        let rem = h * h * h / (72.0 * 3f64.sqrt());
        let base = piece * (D + 1) * dim;
        for j in 0..dim {
            // σ⁽ᵐ⁾ at the middle, from the piece's reference point (exact for a polynomial).
            let mut rd = [0.0f64; MAX_DEGREE + 1];
            for m in 1..=D {
                rd[m] = self.ref_der[base + m * dim + j];
            }
            let mut md = [0.0f64; MAX_DEGREE + 1];
            let mut sb = [0.0f64; MAX_DEGREE + 1];
            for m in 1..=D {
                for mm in m..=D {
                    md[m] += rd[mm] * wts[0][mm - m];
                }
            }
            // |σ⁽ᵏ⁾| on the segment.
            for k in 1..=D {
                for m in k..=D {
                    sb[k] += md[m].abs() * wts[4][m - k];
                }
            }
            // Interval bounds of |q̇|, |q̈|, |q⃛|: skip the joint when none can matter.
            let cheap = [
                sb[1] * x1 * self.inv.sym[0][j],
                (sb[2] * x1 * x1 + sb[1] * x2) * self.inv.sym[1][j],
                (sb[3] * x1 * x1 * x1 + 3.0 * sb[2] * x1 * x2 + sb[1] * x3) * self.inv.sym[2][j],
            ];
            if cheap[0] <= self.threshold[0]
                && cheap[1] <= self.threshold[1]
                && cheap[2] <= self.threshold[2]
            {
                continue;
            }
            let value = |p: usize| -> [f64; 3] {
                let wt = &wts[p + 1];
                let mut d = [0.0f64; 3];
                for k in 0..3 {
                    for m in (k + 1)..=D {
                        d[k] += md[m] * wt[m - k - 1];
                    }
                }
                let (v, a) = (sd[p], sdd[p]);
                [
                    d[0] * v,
                    d[1] * v * v + d[0] * a,
                    d[2] * v * v * v + 3.0 * d[1] * v * a + d[0] * sddd,
                ]
            };
            let f = [value(0), value(1), value(2)];
            let bells = bells.get_or_insert_with(|| {
                [
                    bell(4, x1, x2, x3),
                    bell(5, x1, x2, x3),
                    bell(6, x1, x2, x3),
                ]
            });
            for o in 0..3 {
                if cheap[o] <= self.threshold[o] {
                    continue;
                }
                let (mut lo, mut hi) = quadratic_range(f[0][o], f[1][o], f[2][o]);
                let r = self.inv.ratio(o, j, lo, hi);
                self.sampled(o, r);
                let b = &bells[o];
                let mut m3 = 0.0;
                for k in 2..=D.min(o + 4) {
                    m3 += sb[k] * b[k];
                }
                let e = m3 * rem;
                lo -= e;
                hi += e;
                let r = self.inv.ratio(o, j, lo, hi);
                if r > self.bound[o] {
                    self.bound[o] = r;
                    self.at[o] = (time + tm, j);
                }
            }
        }
    }

    /// [`Sweep::segment`] on a path that is not a piecewise polynomial: direct evaluation at
    /// [`SAMPLED_POINTS`] points, no bound between them.
    fn sampled_segment(&mut self, cub: &Cubic, t0: f64, t1: f64, time: f64) {
        let dim = self.dim;
        let sddd = cub.c[3];
        let mut buf = [0.0; 3 * crate::topp::rescale::MAX_DOF];
        for p in 0..SAMPLED_POINTS {
            let t = t0 + (t1 - t0) * p as f64 / (SAMPLED_POINTS - 1) as f64;
            let (s, sd, sdd) = (cub.s(t), cub.sd(t), cub.sdd(t));
            for m in 1..=3 {
                self.path.eval(s, m, &mut buf[(m - 1) * dim..m * dim]);
            }
            for j in 0..dim {
                let (d1, d2, d3) = (buf[j], buf[dim + j], buf[2 * dim + j]);
                let v = [
                    d1 * sd,
                    d2 * sd * sd + d1 * sdd,
                    d3 * sd * sd * sd + 3.0 * d2 * sd * sdd + d1 * sddd,
                ];
                for o in 0..3 {
                    let r = self.inv.ratio(o, j, v[o], v[o]);
                    self.sampled(o, r);
                    if r > self.bound[o] {
                        self.bound[o] = r;
                        self.at[o] = (time + t, j);
                    }
                }
            }
        }
    }
}

/// The time-scale factor of `law` on `path` under `limits` (see the module documentation).
/// `path` and `limits` must have the law's dimension (checked by the caller).
pub fn scale_bound<P: Path>(path: &P, law: &FilteredProfile, limits: &Limits) -> ScaleBound {
    let dim = path.dim();
    let degree = path.piecewise_degree().filter(|&d| d <= MAX_DEGREE);
    let breaks = path.breakpoints();
    let (mut ref_s, mut ref_der) = (Vec::new(), Vec::new());
    if let Some(d) = degree {
        let pieces = breaks.len().saturating_sub(1);
        ref_s.reserve(pieces);
        ref_der.resize(pieces * (d + 1) * dim, 0.0);
        for (p, pair) in breaks.windows(2).enumerate() {
            let mid = 0.5 * (pair[0] + pair[1]);
            ref_s.push(mid);
            for m in 1..=d {
                let at = (p * (d + 1) + m) * dim;
                path.eval(mid, m, &mut ref_der[at..at + dim]);
            }
        }
    }
    let mut sw = Sweep {
        path,
        inv: Inverse::new(limits),
        dim,
        degree,
        breaks,
        ref_s,
        ref_der,
        piece: 0,
        bound: [0.0; 3],
        at: [(0.0, 0); 3],
        k_low: 0.0,
        threshold: [0.0; 3],
        segments: 0,
    };
    let p = law.profile();
    let w = law.window();
    let (gs, gsd, gu, gt) = (p.gridpoints(), p.velocities(), p.accelerations(), p.times());
    let n = gu.len();
    // Raw state (s, ṡ, s̈) in interval i (−1: before the start, n: after the end) at time t.
    let raw = |i: isize, t: f64| -> [f64; 3] {
        if i < 0 {
            [gs[0], 0.0, 0.0]
        } else if i as usize >= n {
            [gs[n], 0.0, 0.0]
        } else {
            let i = i as usize;
            let tau = t - gt[i];
            let u = gu[i];
            [gs[i] + tau * (gsd[i] + 0.5 * u * tau), gsd[i] + u * tau, u]
        }
    };
    let acc = |i: isize| -> f64 {
        if i < 0 || i as usize >= n {
            0.0
        } else {
            gu[i as usize]
        }
    };
    let next_i = |i: isize| -> f64 {
        if (i as usize) < n {
            gt[i as usize + 1]
        } else {
            f64::INFINITY
        }
    };
    let next_k = |k: isize| -> f64 {
        if k < n as isize {
            gt[(k + 1) as usize] + w
        } else {
            f64::INFINITY
        }
    };
    let end = gt[n] + w;
    let (mut i, mut k) = (0isize, -1isize);
    let mut a = 0.0;
    let mut s_at_a = gs[0];
    // First path breakpoint above the current s.
    let mut bp = sw.breaks.partition_point(|&b| b <= s_at_a);
    let mut count = 0usize;
    loop {
        let b = next_i(i).min(next_k(k)).min(end);
        if b > a {
            let now = raw(i, a);
            let before = raw(k, a - w);
            if count % 256 == 0 && a > 0.0 {
                // Re-anchor the propagated s on the exact moving average.
                s_at_a = law.eval(a)[0];
            }
            count += 1;
            let cub = Cubic {
                c: [
                    s_at_a,
                    ((now[0] - before[0]) / w).max(0.0),
                    (now[1] - before[1]) / w,
                    (acc(i) - acc(k)) / w,
                ],
            };
            let h = b - a;
            let s_end = cub.s(h).clamp(gs[0], gs[n]);
            let mut t_prev = 0.0;
            let last_piece = sw.breaks.len().saturating_sub(2);
            while bp < sw.breaks.len() && sw.breaks[bp] < s_end {
                let tc = cub.time_at(sw.breaks[bp], t_prev, h);
                if tc > t_prev {
                    sw.piece = bp.saturating_sub(1).min(last_piece);
                    sw.segment(&cub, t_prev, tc, a);
                    t_prev = tc;
                }
                bp += 1;
            }
            sw.piece = bp.saturating_sub(1).min(last_piece);
            sw.segment(&cub, t_prev, h, a);
            s_at_a = s_end;
        }
        if b >= end {
            break;
        }
        if next_i(i) <= b {
            i += 1;
        }
        if next_k(k) <= b {
            k += 1;
        }
        a = b;
    }
    let roots = |r: [f64; 3]| r[0].max(r[1].sqrt()).max(r[2].cbrt());
    let certified = roots(sw.bound);
    let factor = certified.max(sw.k_low);
    let which = if factor == sw.bound[0] {
        0
    } else if factor == sw.bound[1].sqrt() {
        1
    } else {
        2
    };
    let (t_at, j_at) = sw.at[which];
    ScaleBound {
        factor,
        sampled: sw.k_low,
        certified: degree.is_some(),
        segments: sw.segments,
        at: (
            t_at,
            j_at,
            [Order::Velocity, Order::Acceleration, Order::Jerk][which],
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CubicSpline;
    use crate::topp::jerk::filter_window;
    use crate::topp::rescale::{min_time_scale, Retimed};
    use crate::topp::Toppra;

    /// The analytic factor bounds dense sampling from above, and closely.
    #[test]
    fn factor_bounds_dense_sampling_tightly() {
        let s = [0.0, 0.4, 0.9, 1.3, 2.0];
        let w = [
            0.0, 0.0, 0.0, //
            0.3, -0.2, 0.1, //
            0.5, 0.1, 0.4, //
            0.2, 0.5, 0.6, //
            0.6, 0.3, 1.0,
        ];
        let path = CubicSpline::natural(&s, &w, 3).unwrap();
        for jerk in [50.0, 2000.0] {
            let limits = Limits::uniform(3, 1.0, 3.0, jerk).unwrap();
            let raw = Toppra::with_limits(path.clone(), &limits)
                .unwrap()
                .solve()
                .unwrap();
            let win = filter_window(raw.law(), &path, &limits, 0.5)
                .unwrap()
                .unwrap();
            let law = FilteredProfile::new(raw.law().clone(), win).unwrap();
            let b = scale_bound(&path, &law, &limits);
            assert!(b.certified && b.segments > 10, "{b:?}");
            let traj = Retimed::new(&path, law).unwrap();
            let dense = min_time_scale(&traj, &limits, 200_000.0).unwrap();
            assert!(
                b.factor >= dense * (1.0 - 1e-12),
                "bound {} below sampled {dense}",
                b.factor
            );
            assert!(
                b.factor <= dense * (1.0 + 1e-5),
                "bound {} loose against {dense}",
                b.factor
            );
            assert!(b.sampled <= b.factor);
        }
    }
}
