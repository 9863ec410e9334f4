//! Rest to rest in closed form (third order, position interface): the common case of step 1,
//! and the shape step 2 reuses for synchronized rest-to-rest motions.

use super::super::problem::{ControlInterface, Dof1, ProfileOrder};
use super::super::profile::{Profile, State1};
use super::verify::verify;

/// Rest to rest (third order, position interface, v₀ = a₀ = v_f = a_f = 0) in closed form,
/// written straight into `pr`: the time-optimal profile changes velocity as fast as possible
/// from rest to a peak velocity v_p in the direction of the displacement D and straight back,
/// cruising at the velocity limit V in between when the two changes alone do not cover D.
///
/// A change between rest and v under jerk J and acceleration limit A ramps for r = √(v/J)
/// (no plateau, when J·v ≤ A²) or for r = A/J with a plateau h = v/A − A/J, and covers
/// v·(2r + h)/2 (its velocity is point-symmetric about its midpoint). With v = V the cruise
/// lasts D/V − (t₁ + t₂)/2; when that is negative, v_p < V covers D exactly:
/// D = 2J·r³ without plateaus (r = ∛(D/(2J))), or D = v_p·(v_p/A + A/J) with them, a
/// quadratic in v_p. The limits are those of the direction (V = v_max or −v_min, the first
/// change accelerating with a_max or −a_min and the second braking with the other).
///
/// The profile is built by integrating its segments and verified like every candidate. Its
/// duration is the only candidate (nothing else is valid and faster, and towards rest the
/// candidates serve only the minimum). Returns `None`, leaving `pr` to the general
/// enumeration, when the problem is not rest to rest, the displacement is zero or not finite,
/// the acceleration limits are asymmetric and no cruise fits, or verification fails.
pub(super) fn rest_to_rest(dof: &Dof1, pr: &mut Profile) -> Option<()> {
    if dof.v0 != 0.0
        || dof.a0 != 0.0
        || dof.vf != 0.0
        || dof.af != 0.0
        || dof.interface != ControlInterface::Position
        || dof.order() != ProfileOrder::Third
    {
        return None;
    }
    let dist = dof.pf - dof.p0;
    if dist == 0.0 || !dist.is_finite() {
        return None;
    }
    let (s, d, v, a_up, a_down) = if dist > 0.0 {
        (1.0, dist, dof.vmax, dof.amax, -dof.amin)
    } else {
        (-1.0, -dist, -dof.vmin, -dof.amin, dof.amax)
    };
    let j = dof.jmax;
    let shape = if v.is_finite() {
        let (r1, h1) = rest_change(v, a_up, j);
        let (r2, h2) = rest_change(v, a_down, j);
        let cruise = d / v - (2.0 * (r1 + r2) + h1 + h2) / 2.0;
        if cruise >= 0.0 {
            RestShape {
                r1,
                h1,
                r2,
                h2,
                vp: v,
                cruise,
            }
        } else {
            peak(d, j, a_up, a_down)?
        }
    } else {
        peak(d, j, a_up, a_down)?
    };
    if !shape.write(pr, dof.p0, s, j) || !verify(dof, pr) {
        return None;
    }
    Some(())
}

/// The no-cruise case of [`rest_to_rest`] for symmetric acceleration limits; `None` for
/// asymmetric ones.
fn peak(d: f64, j: f64, a_up: f64, a_down: f64) -> Option<RestShape> {
    if a_up != a_down {
        return None;
    }
    let a = a_up;
    let ramp_max = a / j;
    let r = (d / (2.0 * j)).cbrt();
    let (r, h, vp) = if r <= ramp_max {
        (r, 0.0, j * r * r)
    } else {
        // v_p²/A + v_p·A/J − D = 0, positive root, as v_p/A.
        let k = ramp_max;
        let vpa = 0.5 * (-k + (k * k + 4.0 * d / a).sqrt());
        (k, (vpa - k).max(0.0), a * vpa)
    };
    Some(RestShape {
        r1: r,
        h1: h,
        r2: r,
        h2: h,
        vp,
        cruise: 0.0,
    })
}

/// Ramp and plateau durations of the fastest change between rest and velocity `v` > 0 under
/// jerk limit `j` and acceleration limit `a`: (√(v/j), 0) when j·v ≤ a², otherwise
/// (a/j, v/a − a/j). (The same values as [`fastest`] between (0, 0) and (v, 0).)
#[inline]
fn rest_change(v: f64, a: f64, j: f64) -> (f64, f64) {
    let alpha = (j * v).sqrt();
    if alpha <= a {
        (alpha / j, 0.0)
    } else {
        (a / j, (v / a - a / j).max(0.0))
    }
}

/// A motion from rest to rest in one direction: ramp r₁, plateau h₁, ramp r₁ up to the peak
/// velocity v_p, a cruise there, then r₂, h₂, r₂ back to rest (steps 1 and 2).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RestShape {
    /// Ramp duration of the change up to the peak velocity.
    pub r1: f64,
    /// Acceleration plateau of the change up (0 without one).
    pub h1: f64,
    /// Ramp duration of the change back to rest.
    pub r2: f64,
    /// Acceleration plateau of the change back to rest (0 without one).
    pub h2: f64,
    /// Peak (cruise) velocity, > 0.
    pub vp: f64,
    /// Cruise duration at the peak velocity (0 without a cruise).
    pub cruise: f64,
}

impl RestShape {
    /// Writes the shape into `pr` (emptied first), from rest at `p0` in direction `s` (±1)
    /// with jerk limit `j`, integrating its segments; false when a duration is refused (then
    /// `pr` is unspecified).
    pub(crate) fn write(&self, pr: &mut Profile, p0: f64, s: f64, j: f64) -> bool {
        let js = s * j;
        pr.reset(State1 {
            p: p0,
            v: 0.0,
            a: 0.0,
        });
        if !pr.push_run(&[(self.r1, js), (self.h1, 0.0), (self.r1, -js)]) {
            return false;
        }
        // The exact peak velocity (removing the integration's round-off before the cruise).
        pr.snap(s * self.vp, 0.0);
        pr.push_run(&[
            (self.cruise, 0.0),
            (self.r2, -js),
            (self.h2, 0.0),
            (self.r2, js),
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::super::closed::{closed_families, vel_family};
    use super::super::Collector;
    use super::*;

    #[test]
    fn rest_to_rest_closed_form_matches_the_enumeration() {
        // The closed form against the families it replaces (cruise and the closed families,
        // both directions), on seeded random limits and distances, direction-dependent
        // limits included.
        let mut r = crate::rng::SplitMix64::new(17);
        let (mut cruise, mut peak, mut plateau, mut fell_back) = (0, 0, 0, 0);
        for k in 0..6000 {
            let vmax = r.uniform(0.05, 3.0);
            let amax = r.uniform(0.2, 20.0);
            let jmax = 10f64.powf(r.uniform(-1.0, 4.5));
            let dist = r.uniform(-2.0, 2.0) * 10f64.powf(r.uniform(-4.0, 1.0));
            let mut d = Dof1::rest_to_rest(0.3, 0.3 + dist, vmax, amax, jmax);
            if k % 2 == 1 {
                d.vmin = -r.uniform(0.05, 3.0);
            }
            if k % 4 >= 2 {
                d.amin = -r.uniform(0.2, 20.0);
            }
            let mut pr = Profile::default();
            let fast = rest_to_rest(&d, &mut pr);
            let (mut out, mut own) = (Profile::default(), None);
            let mut col = Collector::new(&d, &mut out, &mut own, false);
            let mut cruised = false;
            for mirror in [false, true] {
                let q = if mirror { d.mirrored() } else { d };
                cruised |= vel_family(&q, mirror, &mut col).is_some();
                closed_families(&q, mirror, &mut col);
            }
            let t_enum = col
                .best()
                .expect("the enumeration finds a profile")
                .duration();
            let Some(()) = fast else {
                // Only asymmetric acceleration limits without a cruise are left to the
                // enumeration.
                assert!(d.amax != -d.amin && !cruised, "{d:?}");
                fell_back += 1;
                continue;
            };
            assert!(verify(&d, &pr));
            let t = pr.duration();
            assert!(
                (t - t_enum).abs() <= 1e-12 * t_enum,
                "{d:?}: {t} vs {t_enum}"
            );
            let (lo, hi) = pr.velocity_range();
            let v_peak = if dist > 0.0 { hi } else { -lo };
            let v_lim = if dist > 0.0 { d.vmax } else { -d.vmin };
            if cruised {
                cruise += 1;
                assert!((v_peak - v_lim).abs() <= 1e-12 * v_lim);
            } else {
                peak += 1;
                assert!(v_peak < v_lim);
                let (alo, ahi) = pr.acceleration_range();
                if ahi.max(-alo) >= d.amax * (1.0 - 1e-12) {
                    plateau += 1;
                }
            }
        }
        // Every case was exercised.
        assert!(cruise > 500 && peak > 500 && plateau > 100 && fell_back > 100);
        assert!(peak > plateau);
    }
}
