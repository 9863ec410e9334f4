//! The filtered law between its kinks, for [`super::bound`]: the unfiltered TOPP-RA law by
//! interval index and the cubic the moving average is on each segment.
//!
//! # Precision contract
//! The cubic's coefficients are the closed-form moving-average derivatives from the two
//! interval states (exact up to rounding); [`Cubic::time_at`] finds the crossing time of a
//! path breakpoint to about 1e-15 of the segment's time (safeguarded Newton). The sweep
//! re-anchors the propagated s on the exact moving average every 256 segments
//! ([`super::bound`]).

use super::FilteredProfile;

/// The state of the filtered law on one segment, as a polynomial in τ = t − a.
#[derive(Debug, Clone, Copy)]
pub(super) struct Cubic {
    /// s, ṡ, s̈ at τ = 0 and the constant s⃛.
    pub(super) c: [f64; 4],
}

impl Cubic {
    #[inline]
    pub(super) fn s(&self, t: f64) -> f64 {
        let c = &self.c;
        c[0] + t * (c[1] + t * (0.5 * c[2] + t * c[3] / 6.0))
    }
    #[inline]
    pub(super) fn sd(&self, t: f64) -> f64 {
        let c = &self.c;
        c[1] + t * (c[2] + 0.5 * t * c[3])
    }
    #[inline]
    pub(super) fn sdd(&self, t: f64) -> f64 {
        self.c[2] + t * self.c[3]
    }
    /// The τ in `[lo, hi]` where s(τ) = target (s is non-decreasing on the segment):
    /// bisection-safeguarded Newton.
    pub(super) fn time_at(&self, target: f64, mut lo: f64, mut hi: f64) -> f64 {
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

/// The unfiltered law by interval index (−1: before the start, n: after the end), for the
/// sweep.
pub(super) struct RawLaw<'a> {
    pub(super) p: &'a crate::topp::parametrized::PhaseProfile,
    pub(super) n: usize,
    pub(super) w: f64,
}

impl<'a> RawLaw<'a> {
    pub(super) fn new(law: &'a FilteredProfile) -> Self {
        let p = law.profile();
        RawLaw {
            p,
            n: p.accelerations().len(),
            w: law.window(),
        }
    }

    /// (s, ṡ, s̈) in interval `i` at time `t`.
    pub(super) fn state(&self, i: isize, t: f64) -> [f64; 3] {
        let gs = self.p.gridpoints();
        if i < 0 {
            [gs[0], 0.0, 0.0]
        } else if i as usize >= self.n {
            [gs[self.n], 0.0, 0.0]
        } else {
            let i = i as usize;
            let tau = t - self.p.times()[i];
            let u = self.p.accelerations()[i];
            [
                gs[i] + tau * (self.p.velocities()[i] + 0.5 * u * tau),
                self.p.velocities()[i] + u * tau,
                u,
            ]
        }
    }

    /// s̈ in interval `i`.
    pub(super) fn acc(&self, i: isize) -> f64 {
        if i < 0 || i as usize >= self.n {
            0.0
        } else {
            self.p.accelerations()[i as usize]
        }
    }

    /// End of interval `i` (the next kink of t).
    pub(super) fn next_i(&self, i: isize) -> f64 {
        if (i as usize) < self.n {
            self.p.times()[i as usize + 1]
        } else {
            f64::INFINITY
        }
    }

    /// End of interval `k` shifted by the window (the next kink of t − w).
    pub(super) fn next_k(&self, k: isize) -> f64 {
        if k < self.n as isize {
            self.p.times()[(k + 1) as usize] + self.w
        } else {
            f64::INFINITY
        }
    }

    /// The filtered law from time `a` (t in interval `i`, t − w in interval `k`) with
    /// s(a) = `s_at_a`.
    pub(super) fn cubic(&self, i: isize, k: isize, a: f64, s_at_a: f64) -> Cubic {
        let now = self.state(i, a);
        let before = self.state(k, a - self.w);
        let w = self.w;
        Cubic {
            c: [
                s_at_a,
                ((now[0] - before[0]) / w).max(0.0),
                (now[1] - before[1]) / w,
                (self.acc(i) - self.acc(k)) / w,
            ],
        }
    }
}
