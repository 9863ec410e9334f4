//! One degree of freedom's motion: a short list of constant-jerk segments.
//!
//! A [`Profile`] starts at a state (p, v, a) and runs through at most [`MAX_SEGMENTS`]
//! segments. Each segment has a duration, a constant jerk, and its own starting velocity and
//! acceleration: third-order profiles keep them continuous, second-order profiles let the
//! acceleration jump between segments (infinite jerk) and first-order profiles let the velocity
//! jump. Position is always continuous. After the last segment the profile continues with the
//! final velocity and acceleration held as they are (constant acceleration), which is how an
//! online generator extrapolates; [`Profile::state_at`] with `t > duration` follows that rule.
//!
//! Precision: the state at time t is evaluated by Horner-form polynomials from the segment
//! start, whose state was obtained by integrating the previous segments in f64. The round-off
//! accumulated over ten segments is a few ulp of the largest |p|, |v|·T, |a|·T², |j|·T³.

/// Largest number of segments in a profile: up to 6 brake segments and 7 main segments, plus
/// one spare. (A motion through a position limit, two legs of up to 7 segments, fits when it
/// needs no brake; the size is kept small because every profile is copied on the hot path.)
pub const MAX_SEGMENTS: usize = 14;

/// A kinematic state of one degree of freedom.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct State1 {
    /// Position.
    pub p: f64,
    /// Velocity.
    pub v: f64,
    /// Acceleration.
    pub a: f64,
}

/// Integrates a constant-jerk segment from (p, v, a) for `t` seconds.
#[inline]
pub(crate) fn integrate(p: f64, v: f64, a: f64, j: f64, t: f64) -> (f64, f64, f64) {
    (
        p + t * (v + t * (a / 2.0 + t * j / 6.0)),
        v + t * (a + t * j / 2.0),
        a + t * j,
    )
}

/// The motion of one degree of freedom: constant-jerk segments from a start state.
///
/// Entries past the last segment are unspecified (a profile reused as a buffer keeps old
/// values there); equality compares the segments and the final state only.
#[derive(Debug, Clone, Copy)]
pub struct Profile {
    n: usize,
    brake: usize,
    /// Segment start times; `t[n]` is the duration.
    t: [f64; MAX_SEGMENTS + 1],
    /// State at each segment start; index `n` is the final state.
    p: [f64; MAX_SEGMENTS + 1],
    v: [f64; MAX_SEGMENTS + 1],
    a: [f64; MAX_SEGMENTS + 1],
    j: [f64; MAX_SEGMENTS],
    /// Segment durations (kept exactly; differences of start times lose precision).
    d: [f64; MAX_SEGMENTS],
}

impl PartialEq for Profile {
    fn eq(&self, o: &Profile) -> bool {
        let (n, m) = (self.n, self.n + 1);
        n == o.n
            && self.brake == o.brake
            && self.t[..m] == o.t[..m]
            && self.p[..m] == o.p[..m]
            && self.v[..m] == o.v[..m]
            && self.a[..m] == o.a[..m]
            && self.j[..n] == o.j[..n]
            && self.d[..n] == o.d[..n]
    }
}

impl Default for Profile {
    fn default() -> Self {
        Profile::at_rest(0.0)
    }
}

impl Profile {
    /// A profile of zero duration standing at `p`.
    pub(crate) fn at_rest(p: f64) -> Profile {
        Profile::new(State1 { p, v: 0.0, a: 0.0 })
    }

    /// An empty profile (duration 0) that starts, and stays, in `s`.
    pub(crate) fn new(s: State1) -> Profile {
        let mut pr = Profile {
            n: 0,
            brake: 0,
            t: [0.0; MAX_SEGMENTS + 1],
            p: [0.0; MAX_SEGMENTS + 1],
            v: [0.0; MAX_SEGMENTS + 1],
            a: [0.0; MAX_SEGMENTS + 1],
            j: [0.0; MAX_SEGMENTS],
            d: [0.0; MAX_SEGMENTS],
        };
        pr.p[0] = s.p;
        pr.v[0] = s.v;
        pr.a[0] = s.a;
        pr
    }

    /// Empties the profile in place (duration 0, starting and staying in `s`), without
    /// clearing the storage past the start.
    #[inline]
    pub(crate) fn reset(&mut self, s: State1) {
        self.n = 0;
        self.brake = 0;
        self.t[0] = 0.0;
        self.p[0] = s.p;
        self.v[0] = s.v;
        self.a[0] = s.a;
    }

    /// Appends a segment of `duration` seconds with constant `jerk`, continuing from the current
    /// end state. Returns false (and changes nothing) when the profile is full or the duration
    /// is negative or not finite. Zero durations are skipped.
    pub(crate) fn push(&mut self, duration: f64, jerk: f64) -> bool {
        let (v, a) = (self.v[self.n], self.a[self.n]);
        self.push_with(duration, v, a, jerk)
    }

    /// Appends a segment that starts with velocity `v` and acceleration `a` (a jump when they
    /// differ from the current end state: second- and first-order profiles) and constant
    /// `jerk`.
    pub(crate) fn push_with(&mut self, duration: f64, v: f64, a: f64, jerk: f64) -> bool {
        // (A range check compiles to two comparisons; NaN, negative and infinite durations
        // fail it.)
        if !(0.0..=f64::MAX).contains(&duration) || self.n >= MAX_SEGMENTS {
            return false;
        }
        if duration == 0.0 {
            return true;
        }
        let k = self.n;
        self.v[k] = v;
        self.a[k] = a;
        self.j[k] = jerk;
        self.d[k] = duration;
        let (p1, v1, a1) = integrate(self.p[k], v, a, jerk, duration);
        self.t[k + 1] = self.t[k] + duration;
        self.p[k + 1] = p1;
        self.v[k + 1] = v1;
        self.a[k + 1] = a1;
        self.n += 1;
        true
    }

    /// Appends the segments `(duration, jerk)` in order, each continuing from the end state,
    /// exactly as that many calls of [`Profile::push`] would (the same integration, bit for
    /// bit), with the running state kept in registers. Stops and returns false at the first
    /// segment `push` would refuse (negative or non-finite duration, profile full); zero
    /// durations are skipped.
    #[inline]
    pub(crate) fn push_run(&mut self, segs: &[(f64, f64)]) -> bool {
        let mut k = self.n;
        let (mut t, mut p, mut v, mut a) = (self.t[k], self.p[k], self.v[k], self.a[k]);
        let mut ok = true;
        for &(duration, jerk) in segs {
            if !(0.0..=f64::MAX).contains(&duration) || k >= MAX_SEGMENTS {
                ok = false;
                break;
            }
            if duration == 0.0 {
                continue;
            }
            self.v[k] = v;
            self.a[k] = a;
            self.j[k] = jerk;
            self.d[k] = duration;
            (p, v, a) = integrate(p, v, a, jerk, duration);
            t += duration;
            k += 1;
            self.t[k] = t;
            self.p[k] = p;
        }
        self.v[k] = v;
        self.a[k] = a;
        self.n = k;
        ok
    }

    /// Sets the velocity and acceleration held after the end (for profiles whose last
    /// segment jumps to a final value, e.g. first-order profiles stop with v = 0).
    pub(crate) fn set_final(&mut self, v: f64, a: f64) {
        self.v[self.n] = v;
        self.a[self.n] = a;
    }

    /// Replaces the end velocity and acceleration by the exact values a closed-form step was
    /// aiming at (removing round-off of order 1e-16 that a long following segment would
    /// otherwise integrate). Only for corrections far below the precision contract.
    ///
    /// When the last segment started from a velocity far larger than `v` (a state that began
    /// far outside the limits), the round-off of integrating it is of the size of that start
    /// velocity, which can exceed the limit tolerance where the segment lands on a limit. The
    /// segment is then split: its final piece starts from a state integrated backwards from the
    /// exact end, so the landing is evaluated at the scale of `v` (the split leaves a
    /// discontinuity of that round-off, far below the contract, where the velocity is inside).
    pub(crate) fn snap(&mut self, v: f64, a: f64) {
        if self.n == 0 {
            return;
        }
        let k = self.n - 1;
        let (vs, d, j) = (self.v[k], self.d[k], self.j[k]);
        if k >= self.brake && vs.abs() > 256.0 * v.abs() && j != 0.0 && self.n < MAX_SEGMENTS {
            let tau = if a != 0.0 {
                v.abs() / a.abs()
            } else {
                (2.0 * v.abs() / j.abs()).sqrt()
            };
            let tau = tau.min(0.5 * d);
            if tau > 0.0 {
                let te = self.t[k + 1];
                let pe = self.p[k + 1];
                let (pb, vb, ab) = integrate(pe, v, a, j, -tau);
                self.d[k] = d - tau;
                self.t[k + 1] = te - tau;
                self.p[k + 1] = pb;
                self.v[k + 1] = vb;
                self.a[k + 1] = ab;
                self.j[k + 1] = j;
                self.d[k + 1] = tau;
                self.t[k + 2] = te;
                self.p[k + 2] = pe;
                self.n += 1;
            }
        }
        self.v[self.n] = v;
        self.a[self.n] = a;
    }

    /// Appends a cruise of `tau` seconds at `v` after the velocity change pushed so far (its
    /// end snapped to (v, 0) first, see [`Profile::snap`]). With no segment yet and the start
    /// at zero acceleration (the change was empty: `v` is the start velocity up to the
    /// round-off of the root that gave it), the cruise continues from the start velocity
    /// itself, so that the profile begins exactly at its start state.
    pub(crate) fn push_cruise(&mut self, tau: f64, v: f64) -> bool {
        if self.n == 0 && self.a[0] == 0.0 {
            let v0 = self.v[0];
            return self.push_with(tau, v0, 0.0, 0.0);
        }
        self.snap(v, 0.0);
        self.push_with(tau, v, 0.0, 0.0)
    }

    /// Marks the segments pushed so far as the brake pre-profile.
    pub(crate) fn mark_brake(&mut self) {
        self.brake = self.n;
    }

    /// Number of segments.
    pub fn segments(&self) -> usize {
        self.n
    }

    /// Duration of the brake pre-profile (0 when the start state was inside the limits).
    pub fn brake_duration(&self) -> f64 {
        self.t[self.brake]
    }

    /// Duration in seconds.
    pub fn duration(&self) -> f64 {
        self.t[self.n]
    }

    /// The start state.
    pub fn start(&self) -> State1 {
        State1 {
            p: self.p[0],
            v: self.v[0],
            a: self.a[0],
        }
    }

    /// The state at the end of the last segment.
    pub fn end(&self) -> State1 {
        State1 {
            p: self.p[self.n],
            v: self.v[self.n],
            a: self.a[self.n],
        }
    }

    /// The brake pre-profile alone (its end state is where the main profile starts).
    pub(crate) fn brake_part(&self) -> Profile {
        let mut q = *self;
        q.n = self.brake;
        q
    }

    /// Segment `k`: (start time, duration, start state, jerk).
    pub fn segment(&self, k: usize) -> Option<(f64, f64, State1, f64)> {
        (k < self.n).then(|| {
            (
                self.t[k],
                self.d[k],
                State1 {
                    p: self.p[k],
                    v: self.v[k],
                    a: self.a[k],
                },
                self.j[k],
            )
        })
    }

    /// Position, velocity, acceleration and jerk at time `t`. Before 0 the start state is
    /// reported (jerk 0); after the end the final state is extrapolated with constant
    /// acceleration (jerk 0). NaN gives NaN.
    pub fn state_at(&self, t: f64) -> (f64, f64, f64, f64) {
        if t.is_nan() {
            return (f64::NAN, f64::NAN, f64::NAN, f64::NAN);
        }
        if t <= 0.0 || self.n == 0 {
            if t <= 0.0 {
                return (self.p[0], self.v[0], self.a[0], 0.0);
            }
            let (p, v, a) = integrate(self.p[0], self.v[0], self.a[0], 0.0, t);
            return (p, v, a, 0.0);
        }
        if t >= self.t[self.n] {
            let n = self.n;
            let (p, v, a) = integrate(self.p[n], self.v[n], self.a[n], 0.0, t - self.t[n]);
            return (p, v, a, 0.0);
        }
        let mut k = 0;
        while k + 1 < self.n && self.t[k + 1] <= t {
            k += 1;
        }
        let dt = t - self.t[k];
        let (p, v, a) = integrate(self.p[k], self.v[k], self.a[k], self.j[k], dt);
        (p, v, a, self.j[k])
    }

    /// Mirrors the profile (p, v, a, j → −p, −v, −a, −j).
    pub(crate) fn mirror(&mut self) {
        for k in 0..=self.n {
            self.p[k] = -self.p[k];
            self.v[k] = -self.v[k];
            self.a[k] = -self.a[k];
        }
        for k in 0..self.n {
            self.j[k] = -self.j[k];
        }
    }

    /// Appends all segments of `other` (which must start where `self` ends).
    pub(crate) fn append(&mut self, other: &Profile) -> bool {
        for k in 0..other.n {
            let d = other.d[k];
            if !self.push_with(d, other.v[k], other.a[k], other.j[k]) {
                return false;
            }
        }
        self.v[self.n] = other.v[other.n];
        self.a[self.n] = other.a[other.n];
        true
    }

    /// Scales the profile as p ↦ p0 + s·(p − p0) with the same times (phase synchronization).
    pub(crate) fn scaled_from(&self, s: f64, p0: f64) -> Profile {
        let mut q = *self;
        for k in 0..=self.n {
            q.p[k] = p0 + s * (self.p[k] - self.p[0]);
            q.v[k] = s * self.v[k];
            q.a[k] = s * self.a[k];
        }
        for k in 0..self.n {
            q.j[k] = s * self.j[k];
        }
        q
    }

    /// The profile with every segment's input (jerk; for `order` 2 the acceleration, for
    /// `order` 1 the velocity) multiplied by `s`, integrated from `start` (Ruckig's phase
    /// synchronization: another DOF follows the same timing from its own state).
    pub(crate) fn scaled_onto(&self, s: f64, start: State1, order: u8) -> Profile {
        let mut q = Profile::new(start);
        for k in 0..self.n {
            let e = q.end();
            let v = if order == 1 { s * self.v[k] } else { e.v };
            let a = match order {
                3 => e.a,
                2 => s * self.a[k],
                _ => 0.0,
            };
            q.push_with(self.d[k], v, a, s * self.j[k]);
            if k + 1 == self.brake {
                q.mark_brake();
            }
        }
        if order < 3 {
            q.set_final(s * self.v[self.n], s * self.a[self.n]);
        }
        q
    }

    /// Smallest and largest position over `[0, duration]` with the times at which they occur:
    /// `(min, t_min, max, t_max)`. Checks segment ends and interior velocity zeros.
    pub fn position_extrema(&self) -> (f64, f64, f64, f64) {
        let mut lo = (self.p[0], 0.0);
        let mut hi = (self.p[0], 0.0);
        let mut see = |p: f64, t: f64| {
            if p < lo.0 {
                lo = (p, t);
            }
            if p > hi.0 {
                hi = (p, t);
            }
        };
        for k in 0..self.n {
            let d = self.d[k];
            let mut roots = [0.0; 2];
            let m = quad_roots(self.j[k] / 2.0, self.a[k], self.v[k], 0.0, d, &mut roots);
            for &r in &roots[..m] {
                let (p, _, _) = integrate(self.p[k], self.v[k], self.a[k], self.j[k], r);
                see(p, self.t[k] + r);
            }
            see(self.p[k + 1], self.t[k + 1]);
        }
        (lo.0, lo.1, hi.0, hi.1)
    }

    /// Smallest and largest velocity over the profile, checking segment ends, interior
    /// acceleration zeros and both sides of velocity jumps.
    pub fn velocity_range(&self) -> (f64, f64) {
        let mut lo = self.v[0];
        let mut hi = self.v[0];
        for k in 0..self.n {
            let d = self.d[k];
            let (_, v_end, _) = integrate(self.p[k], self.v[k], self.a[k], self.j[k], d);
            for v in [self.v[k], v_end] {
                lo = lo.min(v);
                hi = hi.max(v);
            }
            if self.j[k] != 0.0 {
                let r = -self.a[k] / self.j[k];
                if r > 0.0 && r < d {
                    let (_, v, _) = integrate(self.p[k], self.v[k], self.a[k], self.j[k], r);
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            }
        }
        (lo, hi)
    }

    /// Smallest and largest acceleration over the profile (segment ends).
    pub fn acceleration_range(&self) -> (f64, f64) {
        let mut lo = self.a[0];
        let mut hi = self.a[0];
        for k in 0..self.n {
            let d = self.d[k];
            for a in [self.a[k], self.a[k] + self.j[k] * d] {
                lo = lo.min(a);
                hi = hi.max(a);
            }
        }
        (lo, hi)
    }

    /// First time in `[0, duration]` at which the position equals `p`, if any.
    pub fn first_time_at_position(&self, p: f64) -> Option<f64> {
        if self.p[0] == p {
            return Some(0.0);
        }
        for k in 0..self.n {
            let d = self.d[k];
            let mut roots = [0.0; 3];
            let m = cubic_roots_in(
                [self.p[k] - p, self.v[k], self.a[k] / 2.0, self.j[k] / 6.0],
                0.0,
                d,
                &mut roots,
            );
            if m > 0 {
                return Some(self.t[k] + roots[0]);
            }
        }
        None
    }

    /// First time in `[after, duration]` at which the position equals `p`, if any (Ruckig's
    /// `time_after`); for `after ≤ 0` it is [`Profile::first_time_at_position`]. Segments that
    /// end before `after` are skipped and the first one searched from `after` on.
    pub fn first_time_at_position_after(&self, p: f64, after: f64) -> Option<f64> {
        if after.is_nan() || after <= 0.0 {
            return self.first_time_at_position(p);
        }
        for k in 0..self.n {
            let d = self.d[k];
            if self.t[k] + d < after {
                continue;
            }
            let lo = (after - self.t[k]).max(0.0);
            let mut roots = [0.0; 3];
            let m = cubic_roots_in(
                [self.p[k] - p, self.v[k], self.a[k] / 2.0, self.j[k] / 6.0],
                lo,
                d,
                &mut roots,
            );
            if m > 0 {
                return Some(self.t[k] + roots[0]);
            }
        }
        None
    }
}

/// Real roots of `a x² + b x + c` in the open interval `(lo, hi)`; returns how many.
fn quad_roots(a: f64, b: f64, c: f64, lo: f64, hi: f64, out: &mut [f64; 2]) -> usize {
    let mut m = 0;
    let mut put = |r: f64, out: &mut [f64; 2]| {
        if r > lo && r < hi && m < 2 {
            out[m] = r;
            m += 1;
        }
    };
    if a == 0.0 {
        if b != 0.0 {
            put(-c / b, out);
        }
        return m;
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return 0;
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q != 0.0 {
        put(q / a, out);
        put(c / q, out);
    } else {
        put(0.0, out);
    }
    m
}

/// Real roots of the cubic `c0 + c1 x + c2 x² + c3 x³` in `[lo, hi]`, increasing.
fn cubic_roots_in(c: [f64; 4], lo: f64, hi: f64, out: &mut [f64; 3]) -> usize {
    let mut buf = [0.0; crate::roots::MAX_DEGREE];
    let m = crate::roots::roots_in(&c, lo, hi, &mut buf).min(3);
    out[..m].copy_from_slice(&buf[..m]);
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `first_time_at_position_after`: at or after `after`, at the position, and the first
    /// such time (no sign change of `p(t) − target` between `after` and it on a fine grid).
    #[test]
    fn first_time_at_position_after_is_the_first_from_after() {
        // Up through 0.1 and back down through it: two crossings.
        let mut pr = Profile::new(State1 {
            p: 0.0,
            v: 1.0,
            a: 0.0,
        });
        assert!(pr.push(0.5, -4.0));
        assert!(pr.push(0.5, 0.0));
        assert!(pr.push(1.0, 4.0));
        let target = 0.1;
        let end = 2.0;
        assert_eq!(
            pr.first_time_at_position_after(target, 0.0),
            pr.first_time_at_position(target)
        );
        let mut crossings = 0;
        for i in 0..=400 {
            let after = end * i as f64 / 400.0;
            match pr.first_time_at_position_after(target, after) {
                Some(t) => {
                    assert!(t >= after && t <= end, "after {after}: {t}");
                    assert!((pr.state_at(t).0 - target).abs() < 1e-12);
                    let s0 = pr.state_at(after).0 - target;
                    for k in 0..200 {
                        let u = after + (t - after) * k as f64 / 200.0;
                        let su = pr.state_at(u).0 - target;
                        assert!(su == 0.0 || su.signum() == s0.signum() || (u - t).abs() < 1e-9);
                    }
                }
                None => {
                    // No crossing left: the rest stays on one side.
                    let s0 = pr.state_at(after).0 - target;
                    for k in 0..=200 {
                        let u = after + (end - after) * k as f64 / 200.0;
                        assert!((pr.state_at(u).0 - target).signum() == s0.signum());
                    }
                    crossings += 1;
                }
            }
        }
        assert!(crossings > 0, "the last crossing is followed by no other");
        assert_eq!(pr.first_time_at_position_after(target, 5.0), None);
    }

    #[test]
    fn integrate_matches_finite_differences() {
        let mut pr = Profile::new(State1 {
            p: 0.5,
            v: -0.2,
            a: 0.3,
        });
        assert!(pr.push(0.4, 2.0));
        assert!(pr.push(0.3, 0.0));
        assert!(pr.push(0.5, -1.5));
        let h = 1e-6;
        for i in 1..60 {
            let t = i as f64 * 0.02;
            let (p0, v0, a0, _) = pr.state_at(t - h);
            let (p1, v1, a1, _) = pr.state_at(t + h);
            let (_, v, a, j) = pr.state_at(t);
            assert!(((p1 - p0) / (2.0 * h) - v).abs() < 1e-8);
            if (t - 0.4).abs() > 2.0 * h && (t - 0.7).abs() > 2.0 * h {
                assert!(((v1 - v0) / (2.0 * h) - a).abs() < 1e-8);
                assert!(((a1 - a0) / (2.0 * h) - j).abs() < 1e-6);
            }
        }
        assert!((pr.duration() - 1.2).abs() < 1e-15);
    }

    #[test]
    fn extrema_and_first_time() {
        // v = 1 - t for 2 s: position peaks at t = 1 with 0.5.
        let mut pr = Profile::new(State1 {
            p: 0.0,
            v: 1.0,
            a: -1.0,
        });
        pr.push(2.0, 0.0);
        let (lo, tlo, hi, thi) = pr.position_extrema();
        assert!((hi - 0.5).abs() < 1e-15 && (thi - 1.0).abs() < 1e-15);
        assert_eq!((lo, tlo), (0.0, 0.0));
        let t = pr.first_time_at_position(0.375).unwrap();
        assert!((t - 0.5).abs() < 1e-12);
        assert!(pr.first_time_at_position(0.6).is_none());
        let (vlo, vhi) = pr.velocity_range();
        assert_eq!((vlo, vhi), (-1.0, 1.0));
    }
}
