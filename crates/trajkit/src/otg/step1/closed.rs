//! The families of the time-optimal jerk-limited motion in closed form: the cruise at the
//! velocity limit, and a₀ ↗ α₁ ↘ α₂ ↗ a_f with or without plateaus, each from the roots of its
//! position polynomial ([`super::super::families`]).

use super::super::families_gen::{s1_acc0, s1_acc01, s1_acc1, s1_none};
use super::super::problem::{Dof1, ProfileOrder};
use super::super::profile::{integrate, State1};
use super::super::velocity_change::push_change;
use super::scan::scan_piece;
use super::verify::{velocity_window, TOL_POSITION};
use super::Collector;
use crate::num::clamp_in;
use crate::roots::MAX_POLY;

/// A sequence of up to 7 constant-jerk segments.
#[derive(Clone, Copy)]
pub(super) struct Seq {
    n: usize,
    d: [f64; 7],
    j: [f64; 7],
}

impl Seq {
    pub(super) fn new() -> Seq {
        Seq {
            n: 0,
            d: [0.0; 7],
            j: [0.0; 7],
        }
    }
    #[inline]
    pub(super) fn add(&mut self, d: f64, j: f64) {
        self.d[self.n] = d.max(0.0);
        self.j[self.n] = j;
        self.n += 1;
    }
    /// Offers the sequence, started from `q`'s start state (mirrored back when `mirror`), to
    /// the collector unless it cannot matter; returns whether it was offered and valid.
    pub(super) fn offer(&self, q: &Dof1, mirror: bool, col: &mut Collector<'_>) -> bool {
        if !col.wants(self.d[..self.n].iter().sum()) {
            return false;
        }
        let pr = col.scratch(State1 {
            p: q.p0,
            v: q.v0,
            a: q.a0,
        });
        for k in 0..self.n {
            pr.push(self.d[k], self.j[k]);
        }
        if mirror {
            pr.mirror();
        }
        col.submit()
    }
    #[inline]
    pub(super) fn displacement(&self, v0: f64, a0: f64) -> f64 {
        let (mut p, mut v, mut a) = (0.0, v0, a0);
        for k in 0..self.n {
            (p, v, a) = super::super::profile::integrate(p, v, a, self.j[k], self.d[k]);
        }
        p
    }
}

/// The cruise family (vel) in the positive direction of the (possibly mirrored) problem `q`:
/// fastest change to (v_max, 0), cruise, fastest change to the target. When it offered a
/// valid profile, returns the cruise's share of its duration.
pub(super) fn vel_family(q: &Dof1, mirror: bool, col: &mut Collector<'_>) -> Option<f64> {
    let j = q.jmax;
    let (a0, v0, af, vf) = (q.a0, q.v0, q.af, q.vf);
    let amax = q.amax;
    let a2 = -q.amin;
    let d = q.pf - q.p0;
    // vel: cruise at v_max.
    if q.vmax.is_finite() {
        let c1 = super::super::velocity_change::fastest3(v0, a0, q.vmax, 0.0, j, amax, -a2);
        let c2 = super::super::velocity_change::fastest3(q.vmax, 0.0, vf, af, j, amax, -a2);
        if let (Some(c1), Some(c2)) = (c1, c2) {
            let tau = (d - c1.dist - c2.dist) / q.vmax;
            if tau >= 0.0 {
                let pr = col.scratch(State1 {
                    p: q.p0,
                    v: v0,
                    a: a0,
                });
                push_change(pr, ProfileOrder::Third, &c1, v0);
                pr.push_cruise(tau, q.vmax);
                push_change(pr, ProfileOrder::Third, &c2, q.vmax);
                if mirror {
                    pr.mirror();
                }
                let share = tau / pr.duration();
                return col.submit().then_some(share);
            }
        }
    }
    None
}

/// The families a₀ ↗ α₁ ↘ α₂ ↗ a_f (with or without plateaus at a_max and a_min) in the
/// positive direction of the (possibly mirrored) problem `q`, each from the roots of its
/// position polynomial (see [`super::super::families`]).
pub(super) fn closed_families(q: &Dof1, mirror: bool, col: &mut Collector<'_>) {
    let (amax, amin, j) = (q.amax, q.amin, q.jmax);
    let tol = 1e-12 * (amax - amin);
    if q.a0 > amax + tol || !(amax.is_finite() && amin.is_finite()) {
        return;
    }
    // Every family here ramps the acceleration up, down, up (a₀ ↗ α₁ ↘ α₂ ↗ a_f): the
    // velocity never falls below the start's dip or the target's approach from below.
    let v_low =
        (q.v0 - q.a0.min(0.0).powi(2) / (2.0 * j)).min(q.vf - q.af.max(0.0).powi(2) / (2.0 * j));
    if col.cannot_cover(q.pf - q.p0, v_low, q.vmax.max(q.v0)) {
        return;
    }
    let dscale = (amax - amin) / j;
    let f = Closed {
        q,
        mirror,
        dv: q.vf - q.v0,
        d: q.pf - q.p0,
        tol,
        dscale,
        // Where a plateau family passes a velocity peak (the acceleration turning from
        // positive to negative), the peak must not exceed v_max (or the start's velocity,
        // when the brake left it above): a necessary condition that narrows the parameter
        // windows, with a margin far above round-off (verification accepts 0.5e-12
        // relative). The peak velocity is a function of the parameter in closed form.
        vtop: q.vmax.max(q.v0) + 1e-9 * (q.vmax.abs().min(1e300) + q.v0.abs() + q.vf.abs()),
    };
    let mut roots = [0.0; MAX_POLY];
    f.none(col, &mut roots);
    f.acc0(col, &mut roots);
    if q.af >= amin - tol {
        f.acc1(col, &mut roots);
        f.acc0_acc1(col, &mut roots);
    }
    f.none_ends(col);
    f.none_by_ramp(col);
}

/// How near (relative) a boundary level must be to a bound, to zero or to the other, or K to
/// zero, for [`Closed::none_by_ramp`] to run: where the none polynomial is ill-conditioned.
const NEAR: f64 = 1e-3;

/// What [`closed_families`] shares between its four families.
struct Closed<'q> {
    q: &'q Dof1,
    mirror: bool,
    /// v_f − v₀.
    dv: f64,
    /// p_f − p₀.
    d: f64,
    /// Tolerance of the acceleration levels.
    tol: f64,
    /// (a_max − a_min)/j, the scale of the durations.
    dscale: f64,
    /// The largest velocity a plateau family's peak may have.
    vtop: f64,
}

impl Closed<'_> {
    #[inline]
    fn emit(&self, seq: &Seq, col: &mut Collector<'_>) -> bool {
        seq.offer(self.q, self.mirror, col)
    }

    /// Durations may come out negative at round-off level on a family's edge.
    #[inline]
    fn okd(&self, x: f64) -> bool {
        x >= -1e-12 * self.dscale.max(1e-300)
    }

    /// The plateau families' plateau duration is convex in their parameter, so its largest
    /// value over the parameter window is at one of the window's ends. When it is clearly
    /// negative at both (beyond the tolerance of `okd`, with a margin far above round-off),
    /// no root can give a valid profile and the family is skipped: neither its coefficients
    /// nor its polynomial are computed.
    #[inline]
    fn hopeless(&self, t: f64, size: f64) -> bool {
        t < -1e-12 * self.dscale.max(1e-300) - 1e-9 * size
    }

    /// none: s = α₁, α₂ = w when K < 0 (|α₁| < |α₂|); otherwise [`Self::none_by_second`].
    /// The parameter is the level of smaller magnitude: the other one, ±√(s² ∓ K), then moves
    /// less than it, whereas the larger level as parameter amplifies its rounding error by the
    /// ratio of the levels (1e4 on the `step1_property` reproducer: one rounding unit of α₁
    /// missed the target by 1.7e-8 and the fastest profile was dropped). Each root is offered
    /// with the other level both from the generated W(s) and from the velocity equation with
    /// the exact K (the two differ by up to 2e-11 when |v_f − v₀| ≪ |v₀|; verification keeps
    /// what reaches the target, the collector the shorter), and [`Self::end_roots`] adds roots
    /// next to the window ends that the polynomial lost. (Coefficients only when a window is
    /// not empty.)
    #[inline]
    fn none(&self, col: &mut Collector<'_>, roots: &mut [f64; MAX_POLY]) {
        let q = self.q;
        let (j, a0, af, amin, tol) = (q.jmax, q.a0, q.af, q.amin, self.tol);
        let k = j * self.dv + (a0 * a0 - af * af) / 2.0;
        if k.abs() <= 1e-12 * (j * self.dv.abs() + a0 * a0 + af * af) && af >= a0 {
            // K = 0: the branch α₂ = α₁ is the single ramp a₀ ↗ a_f for every α₁, so P
            // vanishes identically along it and has no isolated root there. The ramp is a
            // candidate of its own.
            let mut s = Seq::new();
            s.add((af - a0) / j, j);
            self.emit(&s, col);
        }
        if k >= 0.0 {
            return self.none_by_second(col, roots, k);
        }
        let mut none = None;
        // α₂² = α₁² − K with α₂ ∈ [a_min, a_f]:
        // α₁² ∈ [K (+a_f² when a_f < 0), K + max(a_f², a_min²)].
        let l = k + if af < 0.0 { af * af } else { 0.0 };
        let af_pos = if af >= 0.0 { af * af } else { 0.0 };
        let u = k + af_pos.max(amin * amin);
        for (lo, hi) in square_window(l.max(0.0), u, a0.min(q.amax), q.amax, true, tol) {
            let r = none.get_or_insert_with(|| s1_none(a0, af, q.v0, q.vf, self.d, j));
            let n = r.roots_with_ends(lo, hi, roots);
            // α₂ from the velocity equation (K exact; the sign from W's branch) besides the
            // generated W(s), whose coefficients cancel j·v₀ against j·v_f: see `end_roots`.
            let w = |x: f64| (x * x - k).max(0.0).sqrt().copysign(r.w_at(x));
            let n = self.end_roots(lo, hi, n, roots, |x| self.none_miss(x, w(x)));
            for &x in &roots[..n] {
                let (wa, we) = (r.w_at(x), w(x));
                for al2 in [wa, we].into_iter().take(if wa == we { 1 } else { 2 }) {
                    for (x, al2) in self.polish_none(x, al2, k) {
                        let (x, al2) = snap_level(x, al2, k, af, amin, tol);
                        if al2 > x + tol || al2 > af + tol || al2 < amin - tol {
                            continue;
                        }
                        self.emit_none(x, al2, col);
                    }
                }
            }
        }
    }

    /// The none family's profiles with a level on a bound of its window, in closed form from
    /// the velocity equation α₁² − α₂² = K: α₁ = a₀ or α₂ = a_f (a ramp of length zero: two
    /// ramps a₀ ↘ α₂ ↗ a_f or a₀ ↗ α₁ ↘ a_f), α₁ = a_max or α₂ = a_min (a plateau of length
    /// zero), each with both signs of the other level. The polynomials' roots there are
    /// double or lie on the window's end, where round-off can lose them; these candidates
    /// cost a square root each, and a verification when faster than the fastest so far (only
    /// then are they offered: a rescue of the fastest profile, not more candidate durations).
    /// The other level is ill-conditioned where it is small (α₂² = a₀² − K cancels): a
    /// candidate that fails verification where the other level's square is below [`NEAR`]
    /// of the bound's (three digits or more lost) is offered again polished
    /// ([`Self::polish_none`]), when the polished levels stay on their windows (to the
    /// levels' tolerance): on a `step1_property` problem with α₁ = a₀ and
    /// α₂ = 5.9e-6, the closed form missed the target by 1.2e-7 (a 50.65 s ramp at 62 m/s),
    /// the exact root's α₁ lies 1e-16 below a₀ (just outside the polynomial's window), and a
    /// profile five times longer won.
    fn none_ends(&self, col: &mut Collector<'_>) {
        let q = self.q;
        let (j, a0, af, amax, amin, tol) = (q.jmax, q.a0, q.af, q.amax, q.amin, self.tol);
        let k = j * self.dv + (a0 * a0 - af * af) / 2.0;
        let best = col.best().map_or(f64::INFINITY, |b| b.duration());
        for (first, c) in [(true, a0), (false, af), (true, amax), (false, amin)] {
            let w = if first { c * c - k } else { c * c + k };
            if w.is_nan() || w < 0.0 {
                continue;
            }
            let r = w.sqrt();
            for other in [r, -r] {
                let (a1, a2) = if first { (c, other) } else { (other, c) };
                if a1 < a0 - tol
                    || a1 > amax + tol
                    || a2 < amin - tol
                    || a2 > af + tol
                    || a2 > a1 + tol
                    || (2.0 * (a1 - a2) + af - a0) / j >= best
                {
                    continue;
                }
                if let (Some(c1), Some(c2)) = (clamp_in(a1, a0, amax), clamp_in(a2, amin, af)) {
                    if self.emit_none(c1, c2.min(c1), col) {
                        continue;
                    }
                }
                // The closed form missed: where it is ill-conditioned, its polished levels.
                if w < NEAR * c * c {
                    self.none_end_polished(a1, a2, k, col);
                }
            }
        }
    }

    /// [`Self::none_ends`]' candidate (α₁, α₂) polished ([`Self::polish_none`]), offered when
    /// its levels differ and stay on their windows (to the levels' tolerance). Out of line:
    /// it runs only where the closed form is ill-conditioned and missed.
    #[cold]
    fn none_end_polished(&self, a1: f64, a2: f64, k: f64, col: &mut Collector<'_>) {
        let q = self.q;
        let (a0, af, amax, amin, tol) = (q.a0, q.af, q.amax, q.amin, self.tol);
        let Some((p1, p2)) = self.polish_none(a1, a2, k).next() else {
            return;
        };
        if (p1, p2) == (a1, a2)
            || p1 < a0 - tol
            || p1 > amax + tol
            || p2 < amin - tol
            || p2 > af + tol
        {
            return;
        }
        if let (Some(p1), Some(p2)) = (clamp_in(p1, a0, amax), clamp_in(p2, amin, af)) {
            self.emit_none(p1, p2.min(p1), col);
        }
    }

    /// none solved in the middle ramp's duration t = (α₁ − α₂)/j by bracketing the
    /// integrated position residual: with α₁ + α₂ = K/(j t) from the velocity equation both
    /// levels are single-valued in t (no branch of a square root), and the duration
    /// 2t + (a_f − a₀)/j grows with t. The t where a level meets one of its bounds (roots of
    /// quadratics in j·t) cut (0, (a_max − a_min)/j] into pieces; on every piece where the
    /// levels lie within their bounds (to the levels' tolerance) the residual is sampled
    /// ([`scan_piece`]: sign changes and tangent roots); the levels are clamped to the
    /// bounds they pass by round-off. Only t below the fastest profile so far's counterpart
    /// is scanned (a rescue of the fastest profile: the candidate durations that bound
    /// blocked intervals still come from the polynomials), and only where the polynomial is
    /// ill-conditioned: a boundary level within [`NEAR`] of the acceleration range from a
    /// bound, zero or the other boundary level, or |K| within [`NEAR`] of its terms (levels
    /// of nearly equal magnitude). On the seeded property test (`otg_step1_shapes`, 3·10⁵
    /// cases) running it everywhere finds nothing more; its cost is about 30 evaluations of
    /// the residual per piece scanned, plus ~10 per root.
    fn none_by_ramp(&self, col: &mut Collector<'_>) {
        let q = self.q;
        let (j, a0, af, amax, amin, tol) = (q.jmax, q.a0, q.af, q.amax, q.amin, self.tol);
        let k = j * self.dv + (a0 * a0 - af * af) / 2.0;
        let span = amax - amin;
        let near = |x: f64| x.abs() <= NEAR * span;
        if !(k.abs() <= NEAR * (a0 * a0 + af * af + (j * self.dv).abs())
            || near(amax - a0)
            || near(a0 - amin)
            || near(amax - af)
            || near(af - amin)
            || near(a0)
            || near(af)
            || near(a0 - af))
        {
            return;
        }
        let levels = |t: f64| {
            let s = k / (j * t);
            ((j * t + s) / 2.0, (s - j * t) / 2.0)
        };
        let valid = |(a1, a2): (f64, f64)| {
            a1 >= a0 - tol && a1 <= amax + tol && a2 >= amin - tol && a2 <= af + tol
        };
        // t below (T_best − (a_f − a₀)/j)/2.
        let t_cap = col.best().map_or(f64::INFINITY, |b| {
            (b.duration() - (af - a0) / j) / 2.0 * (1.0 + 1e-9)
        });
        let t_hi = ((amax - amin) / j).min(t_cap);
        if !(t_hi > 0.0 && t_hi.is_finite()) {
            return;
        }
        // α₁ = c ⇔ (jt)² − 2c·jt + K = 0; α₂ = c ⇔ (jt)² + 2c·jt − K = 0.
        let mut cuts = [0.0; 10];
        let mut n = 0;
        for (c, sg) in [(a0, 1.0), (amax, 1.0), (amin, -1.0), (af, -1.0)] {
            let disc = c * c - sg * k;
            if disc < 0.0 {
                continue;
            }
            for r in [sg * c + disc.sqrt(), sg * c - disc.sqrt()] {
                let t = r / j;
                if t > 0.0 && t < t_hi {
                    cuts[n] = t;
                    n += 1;
                }
            }
        }
        cuts[n] = t_hi;
        n += 1;
        let cuts = &mut cuts[..n];
        cuts.sort_unstable_by(f64::total_cmp);
        let mut lo = 0.0;
        for &hi in cuts.iter() {
            let mid = if lo > 0.0 { (lo * hi).sqrt() } else { 0.5 * hi };
            if hi > lo && valid(levels(mid)) {
                scan_piece(
                    lo,
                    hi,
                    |t| {
                        let (a1, a2) = levels(t);
                        self.none_miss(a1, a2)
                    },
                    |t| {
                        let (a1, a2) = levels(t);
                        if let (Some(a1), Some(a2)) =
                            (clamp_in(a1, a0, amax), clamp_in(a2, amin, af))
                        {
                            self.emit_none(a1, a2, col);
                        }
                    },
                );
            }
            lo = hi;
        }
    }

    /// Offers a₀ ↗ α₁ ↘ α₂ ↗ a_f; returns whether it was valid (and wanted).
    #[inline]
    fn emit_none(&self, al1: f64, al2: f64, col: &mut Collector<'_>) -> bool {
        let (a0, af, j) = (self.q.a0, self.q.af, self.q.jmax);
        let mut s = Seq::new();
        s.add((al1 - a0) / j, j);
        s.add((al1 - al2) / j, -j);
        s.add((af - al2) / j, j);
        self.emit(&s, col)
    }

    /// none for K ≥ 0 (|α₂| ≤ |α₁|), parameterized by the second level: the time-reversed,
    /// mirrored problem ((−p_f, v_f, −a_f) to (−p₀, v₀, −a₀), same displacement) has the same
    /// family with first level s = −α₂ and second level −α₁, so its polynomial is the same
    /// generated one with the boundary states swapped.
    fn none_by_second(&self, col: &mut Collector<'_>, roots: &mut [f64; MAX_POLY], k: f64) {
        let q = self.q;
        let (j, a0, af, amax, amin, tol) = (q.jmax, q.a0, q.af, q.amax, q.amin, self.tol);
        let mut none = None;
        // α₁² = K + α₂² with α₁ ∈ [a₀, a_max]:
        // α₂² ∈ [a₀² − K when a₀ > 0 (else 0), max(a₀², a_max²) − K].
        let l = if a0 > 0.0 { a0 * a0 - k } else { 0.0 };
        let u = (a0 * a0).max(amax * amax) - k;
        // The ends a_min and a_f are common roots (a plateau's or the last ramp's length zero):
        // the window includes them with the levels' tolerance.
        for (lo, hi) in square_window(l.max(0.0), u, amin - tol, af + tol, true, tol) {
            let r = none.get_or_insert_with(|| s1_none(-af, -a0, q.vf, q.v0, self.d, j));
            let n = r.roots_with_ends(-hi, -lo, roots);
            // α₁ from the velocity equation (K exact) besides W(s), as in `none`.
            let w = |s: f64| (k + s * s).sqrt().copysign(-r.w_at(s));
            let n = self.end_roots(-hi, -lo, n, roots, |s| self.none_miss(w(s), -s));
            for &s in &roots[..n] {
                let (wa, we) = (-r.w_at(s), w(s));
                for x in [wa, we].into_iter().take(if wa == we { 1 } else { 2 }) {
                    for (x, al2) in self.polish_none(x, -s, k) {
                        if x < a0 - tol || x > amax + tol || al2 > x + tol {
                            continue;
                        }
                        self.emit_none(x, al2, col);
                    }
                }
            }
        }
    }

    /// Adds to the `n` polynomial roots in `roots` those of the accurate residual `g` next to
    /// an end of `[lo, hi]` that the polynomial misses. Its coefficients cancel j·v₀ against
    /// j·v_f, so when |v_f − v₀| ≪ |v₀| a root within a few 1e-11 of an end, where a ramp is
    /// that short, can vanish from P (it stayed of one sign while the residual `g`, with the
    /// other level from the exact K, changed sign 2.7e-11 inside the window). A sign change of
    /// `g` between an end and 1e-4 of the window inward, with no polynomial root there, is
    /// bisected to a root. Every root still passes verification by integration.
    fn end_roots(
        &self,
        lo: f64,
        hi: f64,
        mut n: usize,
        roots: &mut [f64; MAX_POLY],
        g: impl Fn(f64) -> f64,
    ) -> usize {
        let h = 1e-4 * (hi - lo);
        for (e, inner) in [(lo, lo + h), (hi, hi - h)] {
            let (a, b) = (e.min(inner), e.max(inner));
            if n == MAX_POLY
                || h.is_nan()
                || h <= 0.0
                || roots[..n].iter().any(|&x| x >= a && x <= b)
            {
                continue;
            }
            let (mut x0, mut x1, mut g0) = (a, b, g(a));
            let sign = g0 * g(b);
            if sign.is_nan() || sign >= 0.0 {
                continue;
            }
            for _ in 0..64 {
                let m = 0.5 * (x0 + x1);
                if m <= x0 || m >= x1 {
                    break;
                }
                let gm = g(m);
                if (gm < 0.0) == (g0 < 0.0) {
                    (x0, g0) = (m, gm);
                } else {
                    x1 = m;
                }
            }
            roots[n] = 0.5 * (x0 + x1);
            n += 1;
        }
        n
    }

    /// The displacement of a₀ ↗ α₁ ↘ α₂ ↗ a_f minus the target's (durations unclamped).
    #[inline]
    fn none_miss(&self, al1: f64, al2: f64) -> f64 {
        let q = self.q;
        let j = q.jmax;
        let (p, v, a) = integrate(0.0, q.v0, q.a0, j, (al1 - q.a0) / j);
        let (p, v, a) = integrate(p, v, a, -j, (al1 - al2) / j);
        integrate(p, v, a, j, (q.af - al2) / j).0 - self.d
    }

    /// Polishes a root of the none family whose position misses the target by more than
    /// round-off (1e-4 of the position tolerance). Near α₂ = 0 the parameter α₁ is
    /// ill-conditioned (α₂ = ±√(α₁² − K) moves by α₁/α₂ times as much, so one rounding unit
    /// of α₁ can move the end by more than 1e-8 on a long motion), and with levels of nearly
    /// equal magnitude the polynomial's coefficients cancel: a root missing by 1.8e-10, within
    /// the tolerance, was 2.2e-9 of the duration longer than the exact one (tiny jerk, both
    /// levels next to a_min). The middle ramp's duration t = (α₁ − α₂)/j is well conditioned:
    /// with α₁ + α₂ = K/(j t) from the velocity equation, a few Newton steps on the position
    /// residual in t (central-difference derivative) keep the best of the levels seen. A
    /// root that missed by more than a quarter of the tolerance is replaced by the polished
    /// levels (Newton down to 1e-2 of that quarter); one that missed by less (Newton down to
    /// round-off, stopped when a step no longer reduces the residual) is returned after
    /// them: next to a near-double root
    /// the polished levels can be the longer profile of the two (5 of 2.5·10⁵ cases of the
    /// long `otg_step1_shapes` run), and verification and the collector keep the shorter
    /// valid one.
    fn polish_none(&self, x: f64, al2: f64, k: f64) -> impl Iterator<Item = (f64, f64)> {
        let j = self.q.jmax;
        let coarse = 0.25 * TOL_POSITION.min(1e-5 * self.d.abs());
        let miss = self.none_miss(x, al2).abs();
        let mut best = (x, al2, miss);
        if miss.is_nan() || miss <= 4e-4 * coarse {
            return [(x, al2), (x, al2)].into_iter().take(1);
        }
        // Above a quarter of the tolerance the polished root replaces the root.
        let (keep, tol) = (
            miss <= coarse,
            if miss <= coarse { 4e-4 } else { 1.0 } * coarse,
        );
        let levels = |t: f64| {
            let s = k / (j * t);
            ((j * t + s) / 2.0, (s - j * t) / 2.0)
        };
        let mut t = (x - al2) / j;
        for i in 0..4 {
            if !(t > 0.0 && t.is_finite()) {
                break;
            }
            let (a1, a2) = levels(t);
            let f = self.none_miss(a1, a2);
            if f.abs() < best.2 {
                best = (a1, a2, f.abs());
            } else if i > 0 && keep {
                break;
            }
            if best.2 <= 0.01 * tol {
                break;
            }
            let h = 1e-6 * t;
            let (p1, p2) = levels(t + h);
            let (m1, m2) = levels(t - h);
            let df = (self.none_miss(p1, p2) - self.none_miss(m1, m2)) / (2.0 * h);
            if df == 0.0 || !df.is_finite() {
                break;
            }
            t -= f / df;
        }
        let n = if keep && (best.0, best.1) != (x, al2) {
            2
        } else {
            1
        };
        [(best.0, best.1), (x, al2)].into_iter().take(n)
    }

    /// Polishes a plateau family's root `x` whose integrated position residual `r` is above
    /// round-off (1e-4 of the position tolerance): a root as imprecise as a near-double
    /// root's passes verification with a duration up to a few 1e-9 off. At most three
    /// Newton steps (central-difference derivative); the parameter with the smallest
    /// residual seen is kept, so polishing never makes a root worse; `x` stays in `[lo, hi]`.
    fn polish(&self, x: f64, (lo, hi): (f64, f64), r: impl Fn(f64) -> f64) -> f64 {
        let tol = 1e-4 * TOL_POSITION.min(1e-5 * self.d.abs());
        let mut best = (x, r(x).abs());
        if best.1.is_nan() || best.1 <= tol {
            return x;
        }
        let h = 1e-7 * (self.q.amax - self.q.amin);
        let mut y = x;
        for _ in 0..3 {
            let df = (r(y + h) - r(y - h)) / (2.0 * h);
            let fy = r(y);
            if df == 0.0 || !df.is_finite() {
                break;
            }
            // Ordered: the caller's `clamp_in` on this window succeeded.
            y = (y - fy / df).clamp(lo, hi);
            let fy = r(y).abs();
            if fy.is_nan() || fy >= best.1 {
                break;
            }
            best = (y, fy);
            if fy <= tol {
                break;
            }
        }
        best.0
    }

    /// acc0: s = α₂, plateau τ₁ at a_max. For α₂ < 0 the peak is v_f + (2α₂² − a_f²)/(2j).
    #[inline]
    fn acc0(&self, col: &mut Collector<'_>, roots: &mut [f64; MAX_POLY]) {
        let q = self.q;
        let (j, a0, af, amax, amin, tol) = (q.jmax, q.a0, q.af, q.amax, q.amin, self.tol);
        let c0 = amax * amax + (af * af - a0 * a0) / 2.0 - j * self.dv;
        let peak_lo = -(af * af / 2.0 + j * (self.vtop - q.vf)).max(0.0).sqrt();
        let (xlo, xhi) = ((amin - tol).max(peak_lo - tol), amax.min(af) + tol);
        let t1_at = |x: f64| (x * x - c0) / (j * amax);
        let t1_size = |x: f64| (x * x + c0.abs()) / (j * amax);
        let n = if xlo > xhi
            || (self.hopeless(t1_at(xlo), t1_size(xlo)) && self.hopeless(t1_at(xhi), t1_size(xhi)))
        {
            0
        } else {
            s1_acc0(a0, af, q.v0, q.vf, self.d, j, amax).roots_with_ends_above(
                xlo,
                xhi,
                self.end_floor(),
                roots,
            )
        };
        let seq = |x: f64| {
            let mut s = Seq::new();
            s.add((amax - a0) / j, j);
            s.add(t1_at(x), 0.0);
            s.add((amax - x) / j, -j);
            s.add((af - x) / j, j);
            s
        };
        // A root just past a bound of α₂ (the window's tolerance) on the bound, where its
        // ramp's length and the velocity equation agree.
        self.emit_plateau_roots(&roots[..n], (amin, amax.min(af)), seq, t1_at, col);
    }

    /// acc1: s = α₁, plateau τ₂ at a_min. For α₁ > 0 the peak is v₀ + (2α₁² − a₀²)/(2j).
    #[inline]
    fn acc1(&self, col: &mut Collector<'_>, roots: &mut [f64; MAX_POLY]) {
        let q = self.q;
        let (j, a0, af, amax, amin, tol) = (q.jmax, q.a0, q.af, q.amax, q.amin, self.tol);
        let dv = self.dv;
        let t2_of = |x: f64| {
            ((2.0 * x * x - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j) - dv) / -amin
        };
        let t2_size = |x: f64| {
            ((2.0 * x * x + a0 * a0 + 2.0 * amin * amin + af * af) / (2.0 * j) + dv.abs()) / -amin
        };
        let peak_hi = (j * (self.vtop - q.v0) + a0 * a0 / 2.0).max(0.0).sqrt();
        let (xlo, xhi) = (a0.min(amax) - tol, amax.min(peak_hi) + tol);
        let n = if xlo > xhi
            || (self.hopeless(t2_of(xlo), t2_size(xlo)) && self.hopeless(t2_of(xhi), t2_size(xhi)))
        {
            0
        } else {
            s1_acc1(a0, af, q.v0, q.vf, self.d, j, amin).roots_with_ends_above(
                xlo,
                xhi,
                self.end_floor(),
                roots,
            )
        };
        let seq = |x: f64| {
            let mut s = Seq::new();
            s.add((x - a0) / j, j);
            s.add((x - amin) / j, -j);
            s.add(t2_of(x), 0.0);
            s.add((af - amin) / j, j);
            s
        };
        // A root just past a bound of α₁ on the bound (as in `acc0`).
        self.emit_plateau_roots(&roots[..n], (a0.min(amax), amax), seq, t2_of, col);
    }

    /// Offers the plateau families' (`acc0`, `acc1`) profiles `seq(x)` at the roots `x`:
    /// each put on the window `w` of its level when just past it, polished by Newton steps on
    /// the integrated residual ([`Closed::polish`]), and kept when the plateau's duration
    /// `plateau(x)` is valid.
    fn emit_plateau_roots(
        &self,
        roots: &[f64],
        w: (f64, f64),
        seq: impl Fn(f64) -> Seq,
        plateau: impl Fn(f64) -> f64,
        col: &mut Collector<'_>,
    ) {
        let (v0, a0) = (self.q.v0, self.q.a0);
        for &x in roots {
            let Some(x) = clamp_in(x, w.0, w.1) else {
                continue;
            };
            let x = self.polish(x, w, |x| seq(x).displacement(v0, a0) - self.d);
            if self.okd(plateau(x)) {
                self.emit(&seq(x), col);
            }
        }
    }

    /// The rounding of the displacement p_f − p₀ (16 rounding units of the positions), plus
    /// 1e-4 of the position tolerance (the polish's target, [`Closed::polish`]): added to
    /// the end test of the plateau families' polynomials, whose P is the position residual
    /// itself (`roots_with_ends_above`). Their coefficients do not carry that rounding, so a
    /// root it moved just past the window was lost with its family: α₂ 4.9e-13 past a_f (a
    /// last ramp of −6e-15 s) on a `step1_property` problem starting 2.8e-13 below a_max at
    /// p₀ = −84, P 2.1e-12 of its terms at the window's end, where the profile misses the
    /// target by 4e-17; a profile 122 times longer won.
    #[inline]
    fn end_floor(&self) -> f64 {
        let q = self.q;
        16.0 * f64::EPSILON * q.p0.abs().max(q.pf.abs())
            + 1e-4 * TOL_POSITION.min(1e-5 * self.d.abs())
    }

    /// acc0_acc1: s = τ₁ (τ₂ grows with τ₁: its largest value is at the window's end). The
    /// peak is v₀ + (2a_max² − a₀²)/(2j) + a_max·τ₁.
    #[inline]
    fn acc0_acc1(&self, col: &mut Collector<'_>, roots: &mut [f64; MAX_POLY]) {
        let q = self.q;
        let (j, a0, af, amax, amin) = (q.jmax, q.a0, q.af, q.amax, q.amin);
        let dv = self.dv;
        let (vlo, vhi) = velocity_window(q);
        let t1_peak = (self.vtop - q.v0 - (2.0 * amax * amax - a0 * a0) / (2.0 * j)) / amax;
        let t1_hi = (((vhi - vlo).abs() + dv.abs()) / amax).min(t1_peak);
        let k01 = (2.0 * amax * amax - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j);
        let t2_at = |x: f64| (k01 + amax * x - dv) / -amin;
        let size = (k01.abs() + amax * t1_hi + dv.abs()) / -amin;
        let n = if t1_hi < 0.0 || self.hopeless(t2_at(t1_hi), size) {
            0
        } else {
            s1_acc01(a0, af, q.v0, q.vf, self.d, j, amax, amin).roots_with_ends(0.0, t1_hi, roots)
        };
        for &x in &roots[..n] {
            let t2 = ((2.0 * amax * amax - a0 * a0 - 2.0 * amin * amin + af * af) / (2.0 * j)
                + amax * x
                - dv)
                / -amin;
            if !self.okd(t2) {
                continue;
            }
            let mut s = Seq::new();
            s.add((amax - a0) / j, j);
            s.add(x, 0.0);
            s.add((amax - amin) / j, -j);
            s.add(t2, 0.0);
            s.add((af - amin) / j, j);
            self.emit(&s, col);
        }
    }
}

/// Snaps the none family's second level α₂ to the bound a_f (or a_min) it passes by a little,
/// with α₁ = ±√(K + α₂²) from the velocity equation. Near α₂ = 0, α₂ = ±√(α₁² − K) carries
/// α₁/α₂ times α₁'s rounding error (and K's cancellation), far more than the levels' tolerance
/// `tol`: a root whose last ramp should be a few 1e-11 long came out a few 1e-11 negative and
/// was dropped. "A little" is 1e-4 of the levels' scale: the snapped candidate still has to
/// pass verification by integration, so a wider net costs a verification, never a limit.
fn snap_level(x: f64, al2: f64, k: f64, af: f64, amin: f64, tol: f64) -> (f64, f64) {
    let net = tol + 1e-4 * (x.abs() + al2.abs());
    let to = if al2 > af + tol && al2 <= af + net && af <= x {
        af
    } else if al2 < amin - tol && al2 >= amin - net {
        amin
    } else {
        return (x, al2);
    };
    let w = k + to * to;
    if w < 0.0 {
        return (x, al2);
    }
    (w.sqrt().copysign(x), to)
}

/// The parts of `[lo, hi]` where x² ∈ [l, u]: up to two intervals (the negative one only
/// when `neg_ok`). Bounds are widened by `tol` so that edge roots survive round-off.
pub(super) fn square_window(
    l: f64,
    u: f64,
    lo: f64,
    hi: f64,
    neg_ok: bool,
    tol: f64,
) -> impl Iterator<Item = (f64, f64)> {
    let mut out = [(1.0, 0.0); 2];
    if l <= u && u >= 0.0 {
        let (r0, r1) = (l.max(0.0).sqrt(), u.sqrt());
        let (a, b) = ((r0 - tol).max(lo), (r1 + tol).min(hi));
        if a <= b {
            out[0] = (a, b);
        }
        if neg_ok {
            let (a, b) = ((-r1 - tol).max(lo), (-r0 + tol).min(hi));
            if a <= b {
                out[1] = (a, b);
            }
        }
    }
    out.into_iter().filter(|(a, b)| a <= b)
}
