//! The fallback families of step 1, for degenerate cases the closed forms miss: the same
//! families solved by bracketing their residual, the peak family over the whole velocity
//! range, and (second order) the cruise family.

use super::super::bracket::{first_at_root, Grid};
use super::super::problem::Dof1;
use super::super::profile::State1;
use super::super::velocity_change::{fastest, kink, via_velocity, VelChange};
use super::closed::{square_window, Seq};
use super::verify::velocity_cap;
use super::Collector;

/// Peak family: fastest change to (v_c, 0), then fastest change to the target; residual in
/// position, free parameter v_c.
pub(super) fn peak_family(dof: &Dof1, col: &mut Collector<'_>) {
    let order = dof.order();
    let d = dof.pf - dof.p0;
    let vcap = velocity_cap(
        dof,
        State1 {
            p: dof.p0,
            v: dof.v0,
            a: dof.a0,
        },
    );
    let vcap_neg = velocity_cap(
        &dof.mirrored(),
        State1 {
            p: -dof.p0,
            v: -dof.v0,
            a: -dof.a0,
        },
    );
    let (lo, hi) = (-vcap_neg, vcap);
    let parts = |vc: f64| -> Option<(VelChange, VelChange)> {
        let c1 = fastest(order, dof.v0, dof.a0, vc, 0.0, dof.jmax, dof.amax, dof.amin)?;
        let c2 = fastest(order, vc, 0.0, dof.vf, dof.af, dof.jmax, dof.amax, dof.amin)?;
        Some((c1, c2))
    };
    let f = |vc: f64| parts(vc).map(|(c1, c2)| c1.dist + c2.dist - d);
    let cuts = [
        lo,
        hi,
        0.0,
        kink(order, dof.v0, dof.a0, dof.jmax, 1.0),
        kink(order, dof.vf, dof.af, dof.jmax, -1.0),
    ];
    // Every root's profile is offered (none ends the search).
    first_at_root(cuts, Grid::Coarse, f, |vc| -> Option<()> {
        let (c1, c2) = parts(vc)?;
        col.offer(&via_velocity(dof, order, &c1, vc, None, &c2));
        None
    });
}

/// Cruise family: fastest change to (v_max, 0), cruise, fastest change to the target (both
/// signs of the cruise velocity).
pub(super) fn cruise_family(dof: &Dof1, col: &mut Collector<'_>) {
    let order = dof.order();
    let d = dof.pf - dof.p0;
    for vc in [dof.vmax, dof.vmin] {
        if !vc.is_finite() || vc == 0.0 {
            continue;
        }
        let Some(c1) = fastest(order, dof.v0, dof.a0, vc, 0.0, dof.jmax, dof.amax, dof.amin) else {
            continue;
        };
        let Some(c2) = fastest(order, vc, 0.0, dof.vf, dof.af, dof.jmax, dof.amax, dof.amin) else {
            continue;
        };
        let tau = (d - c1.dist - c2.dist) / vc;
        if tau.is_nan() || tau < 0.0 {
            continue;
        }
        col.offer(&via_velocity(dof, order, &c1, vc, Some(tau), &c2));
    }
}

/// The third-order families in the positive direction of the (possibly mirrored) problem `q`,
/// by bracketing (the fallback of [`super::closed::closed_families`]): none and acc0 with
/// either sign of the second level, acc1, acc0_acc1.
pub(super) fn third_families(q: &Dof1, mirror: bool, col: &mut Collector<'_>) {
    let (j, a0, amax) = (q.jmax, q.a0, q.amax);
    let a2 = -q.amin;
    let vlim = if q.vmax.is_finite() {
        q.vmax
    } else {
        velocity_cap(
            q,
            State1 {
                p: q.p0,
                v: q.v0,
                a: a0,
            },
        )
    };
    let tol = 1e-12 * (amax + a2);
    if a0 > amax + tol {
        return;
    }
    let b = Bracketed {
        q,
        mirror,
        a2,
        dv: q.vf - q.v0,
        tol,
        tau_hi: (vlim - q.v0 - (amax * amax - a0 * a0) / (2.0 * j)) / amax,
    };
    for sign in [1.0, -1.0] {
        b.none(sign, col);
        if b.tau_hi >= 0.0 {
            b.acc0(sign, col);
        }
    }
    b.acc1(col);
    if b.tau_hi >= 0.0 {
        b.acc0_acc1(col);
    }
}

/// What [`third_families`] shares between its families.
struct Bracketed<'q> {
    q: &'q Dof1,
    mirror: bool,
    /// −a_min.
    a2: f64,
    /// v_f − v₀.
    dv: f64,
    /// Tolerance of the acceleration levels.
    tol: f64,
    /// The longest plateau at a_max before the velocity bound.
    tau_hi: f64,
}

impl Bracketed<'_> {
    /// Brackets the position residual of the family `seq` (a profile for each parameter, or
    /// `None` outside its domain) on `[lo, hi]` and offers the profiles at its roots.
    fn solve(&self, seq: &impl Fn(f64) -> Option<Seq>, lo: f64, hi: f64, col: &mut Collector<'_>) {
        let q = self.q;
        let d = q.pf - q.p0;
        let f = |x: f64| seq(x).map(|s| s.displacement(q.v0, q.a0) - d);
        // One piece, [lo, hi]; every root's profile is offered.
        first_at_root([lo, hi], Grid::Coarse, f, |x| -> Option<()> {
            seq(x)?.offer(q, self.mirror, col);
            None
        });
    }

    /// none: parameter α₁, α₂ of sign `sign`.
    fn none(&self, sign: f64, col: &mut Collector<'_>) {
        let q = self.q;
        let (j, a0, af, a2, tol, dv) = (q.jmax, q.a0, q.af, self.a2, self.tol, self.dv);
        let none = |x: f64| -> Option<Seq> {
            let rad = x * x + (af * af - a0 * a0) / 2.0 - j * dv;
            if rad < -tol * tol {
                return None;
            }
            let al2 = sign * rad.max(0.0).sqrt();
            if al2 > x + tol || al2 > af + tol || al2 < -a2 - tol {
                return None;
            }
            let mut s = Seq::new();
            s.add((x - a0) / j, j);
            s.add((x - al2) / j, -j);
            s.add((af - al2) / j, j);
            Some(s)
        };
        // Valid domain: x² ∈ [l, u] (and the sign conditions), computed in closed form so
        // that narrow windows are not missed by sampling.
        let k = (af * af - a0 * a0) / 2.0 - j * dv;
        let (l, u, neg_ok) = if sign > 0.0 {
            if af < -tol || k > tol * tol {
                (1.0, 0.0, false)
            } else {
                ((-k).max(0.0), af.max(0.0) * af.max(0.0) - k, false)
            }
        } else {
            let l = (-k).max(0.0).max(if af < 0.0 { af * af - k } else { 0.0 });
            (l, a2 * a2 - k, k >= -tol * tol)
        };
        for (lo, hi) in square_window(l, u, a0.min(q.amax), q.amax, neg_ok, tol) {
            self.solve(&none, lo, hi, col);
        }
    }

    /// acc0: parameter τ₁, α₂ of sign `sign`.
    fn acc0(&self, sign: f64, col: &mut Collector<'_>) {
        let q = self.q;
        let (j, a0, af, amax, a2, tol, dv) =
            (q.jmax, q.a0, q.af, q.amax, self.a2, self.tol, self.dv);
        let acc0 = |t1: f64| -> Option<Seq> {
            let rad = amax * amax + (af * af - a0 * a0) / 2.0 + j * amax * t1 - j * dv;
            if rad < -tol * tol {
                return None;
            }
            let al2 = sign * rad.max(0.0).sqrt();
            if al2 > amax + tol || al2 > af + tol || al2 < -a2 - tol {
                return None;
            }
            let mut s = Seq::new();
            s.add((amax - a0) / j, j);
            s.add(t1, 0.0);
            s.add((amax - al2) / j, -j);
            s.add((af - al2) / j, j);
            Some(s)
        };
        // rad = c0 + j·amax·τ1 must lie in [l, u].
        let c0 = amax * amax + (af * af - a0 * a0) / 2.0 - j * dv;
        let (l, u) = if sign > 0.0 {
            (0.0, if af < 0.0 { -1.0 } else { amax.min(af).powi(2) })
        } else {
            (if af < 0.0 { af * af } else { 0.0 }, a2 * a2)
        };
        let lo = ((l - c0) / (j * amax)).max(0.0);
        let hi = ((u - c0) / (j * amax)).min(self.tau_hi);
        if lo <= hi {
            self.solve(&acc0, lo, hi, col);
        }
    }

    /// acc1: parameter α₁.
    fn acc1(&self, col: &mut Collector<'_>) {
        let q = self.q;
        let (j, a0, af, a2, tol, dv) = (q.jmax, q.a0, q.af, self.a2, self.tol, self.dv);
        let acc1 = |x: f64| -> Option<Seq> {
            let t2 = ((2.0 * x * x - a0 * a0 - 2.0 * a2 * a2 + af * af) / (2.0 * j) - dv) / a2;
            if t2 < 0.0 || af < -a2 - tol {
                return None;
            }
            let mut s = Seq::new();
            s.add((x - a0) / j, j);
            s.add((x + a2) / j, -j);
            s.add(t2, 0.0);
            s.add((af + a2) / j, j);
            Some(s)
        };
        // τ2 ≥ 0 ⇔ x² ≥ l.
        let l = (2.0 * j * dv + a0 * a0 + 2.0 * a2 * a2 - af * af) / 2.0;
        for (lo, hi) in square_window(l.max(0.0), f64::INFINITY, a0.min(q.amax), q.amax, true, tol)
        {
            self.solve(&acc1, lo, hi, col);
        }
    }

    /// acc0_acc1: parameter τ₁.
    fn acc0_acc1(&self, col: &mut Collector<'_>) {
        let q = self.q;
        let (j, a0, af, amax, a2, dv) = (q.jmax, q.a0, q.af, q.amax, self.a2, self.dv);
        let acc01 = |t1: f64| -> Option<Seq> {
            let t2 = ((2.0 * amax * amax - a0 * a0 - 2.0 * a2 * a2 + af * af) / (2.0 * j)
                + amax * t1
                - dv)
                / a2;
            if t2 < 0.0 {
                return None;
            }
            let mut s = Seq::new();
            s.add((amax - a0) / j, j);
            s.add(t1, 0.0);
            s.add((amax + a2) / j, -j);
            s.add(t2, 0.0);
            s.add((af + a2) / j, j);
            Some(s)
        };
        let lo = ((dv - (2.0 * amax * amax - a0 * a0 - 2.0 * a2 * a2 + af * af) / (2.0 * j))
            / amax)
            .max(0.0);
        if lo <= self.tau_hi {
            self.solve(&acc01, lo, self.tau_hi, col);
        }
    }
}
