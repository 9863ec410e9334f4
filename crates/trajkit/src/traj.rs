//! The trajectory model shared by every family in trajkit.
//!
//! A [`Trajectory`] is a vector-valued function of time ξ(t) over `[0, duration]` with one
//! component per joint (degree of freedom). It evaluates its position or any time derivative at
//! `t` into a buffer the caller owns: evaluation never allocates, so it can run inside a control
//! loop. Polynomials, splines used as trajectories, online-generated profiles, time-optimal
//! parameterizations and movement-primitive rollouts all implement it, so every one of them can
//! be sampled ([`crate::sample`]), limit-checked ([`crate::check`]) and plotted
//! ([`crate::plot`]) the same way.
//!
//! # Time outside `[0, duration]`
//! One policy holds for every implementation in trajkit: **time is clamped**. For `t < 0` the
//! trajectory reports its state at `t = 0`, for `t > duration` its state at `t = duration`
//! (position *and* derivatives, as evaluated at the end point). A NaN time gives NaN outputs.
//! Nothing panics for any `t`.
//!
//! # Example
//! ```
//! use trajkit::{poly::PolyMove, Trajectory, Order};
//!
//! // Quintic (minimum-jerk) rest-to-rest move of two joints in 2 s.
//! let mv = PolyMove::rest_to_rest(trajkit::poly::Degree::Quintic, &[0.0, 1.0], &[1.0, -1.0], 2.0)?;
//! let mut q = [0.0; 2];
//! mv.eval(1.0, Order::Position, &mut q); // half-way in time is half-way in position
//! assert!((q[0] - 0.5).abs() < 1e-15 && q[1].abs() < 1e-15);
//! # Ok::<(), trajkit::Error>(())
//! ```

/// Which derivative of position to evaluate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Order {
    /// q(t).
    Position = 0,
    /// q̇(t).
    Velocity = 1,
    /// q̈(t).
    Acceleration = 2,
    /// q⃛(t).
    Jerk = 3,
}

impl Order {
    /// All four orders, position first.
    pub const ALL: [Order; 4] = [
        Order::Position,
        Order::Velocity,
        Order::Acceleration,
        Order::Jerk,
    ];

    /// The derivative order as a number (position = 0).
    pub fn index(self) -> usize {
        self as usize
    }

    /// Human name: `"position"`, `"velocity"`, `"acceleration"`, `"jerk"`.
    pub fn name(self) -> &'static str {
        ["position", "velocity", "acceleration", "jerk"][self as usize]
    }

    /// The order from a number 0..=3.
    pub fn from_index(i: usize) -> Option<Order> {
        Order::ALL.get(i).copied()
    }
}

/// A time-parameterized trajectory ξ(t), t ∈ [0, duration], with `dof()` components.
///
/// Implementations must not allocate in [`Trajectory::eval`] and must follow the clamping
/// policy of the module documentation. `out` must have at least `dof()` entries; only the first
/// `dof()` are written. A shorter buffer is a programming error and panics; use
/// [`Trajectory::try_eval`] to get an error instead.
pub trait Trajectory {
    /// Number of joints (degrees of freedom).
    fn dof(&self) -> usize;

    /// Duration T in seconds; the trajectory is defined on `[0, T]`.
    fn duration(&self) -> f64;

    /// Writes the `order`-th time derivative at time `t` (clamped to `[0, T]`) into `out`.
    fn eval(&self, t: f64, order: Order, out: &mut [f64]);

    /// Like [`Trajectory::eval`], but returns an error instead of panicking when `out` is too
    /// short.
    fn try_eval(&self, t: f64, order: Order, out: &mut [f64]) -> crate::Result<()> {
        if out.len() < self.dof() {
            return Err(crate::Error::DimensionMismatch {
                what: "output buffer length".into(),
                expected: self.dof(),
                found: out.len(),
            });
        }
        self.eval(t, order, out);
        Ok(())
    }

    /// Writes position, velocity, acceleration and jerk at `t` into `state`.
    fn eval_state(&self, t: f64, state: &mut State<'_>) {
        self.eval(t, Order::Position, state.q);
        self.eval(t, Order::Velocity, state.qd);
        self.eval(t, Order::Acceleration, state.qdd);
        self.eval(t, Order::Jerk, state.qddd);
    }

    /// Writes position, velocity, acceleration and jerk at every time of `times` into
    /// `out[0]..out[3]` (row-major, `times.len() × dof()` values each): row i of `out[k]` is
    /// what [`Trajectory::eval`] writes for order k at `times[i]`.
    ///
    /// What sampling calls ([`crate::sample::sample_at`]). The default calls `eval` per time
    /// and order; a trajectory that can share work between the four orders and between
    /// consecutive times (one timing-law evaluation per time, each piece searched from the
    /// previous one) overrides it with the same arithmetic, so that the rows stay bitwise
    /// equal to `eval`'s. Fastest on non-decreasing times, correct on any. Allocates nothing;
    /// a buffer shorter than `times.len() × dof()` is a programming error and panics.
    fn eval_rows(&self, times: &[f64], out: [&mut [f64]; 4]) {
        let dof = self.dof();
        for (order, col) in Order::ALL.into_iter().zip(out) {
            for (&t, row) in times.iter().zip(col.chunks_exact_mut(dof.max(1))) {
                self.eval(t, order, row);
            }
        }
    }

    /// The rows of this trajectory played `factor` times slower (what
    /// [`crate::topp::Scaled`] samples): [`Trajectory::eval_rows`] at the times
    /// `times[i] / factor`, with velocity, acceleration and jerk then multiplied by
    /// `factor.powi(-1)`, `factor.powi(-2)` and `factor.powi(-3)`.
    ///
    /// The default does exactly that, a block of times at a time. A trajectory whose row pass
    /// can apply the factors as it writes its rows (one pass over the output instead of two)
    /// overrides it with the same operations, bitwise equal. Allocates nothing; a buffer
    /// shorter than `times.len() × dof()` is a programming error and panics.
    fn eval_rows_scaled(&self, times: &[f64], factor: f64, mut out: [&mut [f64]; 4]) {
        let (k, dof) = (factor, self.dof());
        let mut buf = [0.0; ROW_BLOCK];
        for (b, chunk) in times.chunks(ROW_BLOCK).enumerate() {
            for (x, &t) in buf.iter_mut().zip(chunk) {
                *x = t / k;
            }
            let from = b * ROW_BLOCK;
            let block = row_block(&mut out, dof, from, from + chunk.len());
            self.eval_rows(&buf[..chunk.len()], block);
        }
        for (c, col) in scale_factors(k).into_iter().zip(out.into_iter().skip(1)) {
            col[..times.len() * dof].iter_mut().for_each(|v| *v *= c);
        }
    }
}

/// The factors of a trajectory played `k` times slower for velocity, acceleration and jerk:
/// `k.powi(-1)`, `k.powi(-2)`, `k.powi(-3)` ([`Trajectory::eval_rows_scaled`]).
#[inline]
pub(crate) fn scale_factors(k: f64) -> [f64; 3] {
    [Order::Velocity, Order::Acceleration, Order::Jerk].map(|o| k.powi(-(o.index() as i32)))
}

/// Times per block in the [`Trajectory::eval_rows`] overrides that transform time (scaling,
/// piece offsets) into a stack buffer.
pub(crate) const ROW_BLOCK: usize = 64;

/// The rows `from..to` (of `dof` values each) of the four matrices of
/// [`Trajectory::eval_rows`].
#[inline]
pub(crate) fn row_block<'a>(
    out: &'a mut [&mut [f64]; 4],
    dof: usize,
    from: usize,
    to: usize,
) -> [&'a mut [f64]; 4] {
    let [a, b, c, d] = out;
    let r = from * dof..to * dof;
    [
        &mut a[r.clone()],
        &mut b[r.clone()],
        &mut c[r.clone()],
        &mut d[r],
    ]
}

/// Caller-owned buffers for a full kinematic state (position through jerk).
#[derive(Debug)]
pub struct State<'a> {
    /// Position, one entry per joint.
    pub q: &'a mut [f64],
    /// Velocity.
    pub qd: &'a mut [f64],
    /// Acceleration.
    pub qdd: &'a mut [f64],
    /// Jerk.
    pub qddd: &'a mut [f64],
}

impl<T: Trajectory + ?Sized> Trajectory for &T {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn duration(&self) -> f64 {
        (**self).duration()
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        (**self).eval(t, order, out)
    }
    fn eval_rows(&self, times: &[f64], out: [&mut [f64]; 4]) {
        (**self).eval_rows(times, out)
    }
    fn eval_rows_scaled(&self, times: &[f64], factor: f64, out: [&mut [f64]; 4]) {
        (**self).eval_rows_scaled(times, factor, out)
    }
}

impl<T: Trajectory + ?Sized> Trajectory for Box<T> {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn duration(&self) -> f64 {
        (**self).duration()
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        (**self).eval(t, order, out)
    }
    fn eval_rows(&self, times: &[f64], out: [&mut [f64]; 4]) {
        (**self).eval_rows(times, out)
    }
    fn eval_rows_scaled(&self, times: &[f64], factor: f64, out: [&mut [f64]; 4]) {
        (**self).eval_rows_scaled(times, factor, out)
    }
}

/// Clamps `t` to `[0, duration]` per the module's policy (NaN stays NaN).
#[inline]
pub fn clamp_time(t: f64, duration: f64) -> f64 {
    if t < 0.0 {
        0.0
    } else if t > duration {
        duration
    } else {
        t
    }
}

/// Finds the piece of a piecewise function that holds `t`.
///
/// `breaks` are the increasing piece boundaries `b_0 < b_1 < ... < b_n` (n pieces). Returns the
/// index `i` in `0..n` with `b_i <= t < b_{i+1}`, the last piece for `t >= b_n` and the first for
/// `t < b_0` (and for NaN). Binary search; no allocation.
#[inline]
pub fn find_piece(breaks: &[f64], t: f64) -> usize {
    let n = breaks.len().saturating_sub(1);
    if n <= 1 || t.is_nan() {
        return 0;
    }
    // partition_point: number of interior breaks <= t.
    let k = breaks[1..n].partition_point(|&b| b <= t);
    k.min(n - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn piece_search() {
        let b = [0.0, 1.0, 2.5, 4.0];
        assert_eq!(find_piece(&b, -1.0), 0);
        assert_eq!(find_piece(&b, 0.0), 0);
        assert_eq!(find_piece(&b, 0.999), 0);
        assert_eq!(find_piece(&b, 1.0), 1);
        assert_eq!(find_piece(&b, 2.5), 2);
        assert_eq!(find_piece(&b, 4.0), 2);
        assert_eq!(find_piece(&b, 9.0), 2);
        assert_eq!(find_piece(&b, f64::NAN), 0);
        assert_eq!(find_piece(&[0.0, 1.0], 0.5), 0);
    }

    #[test]
    fn clamping() {
        assert_eq!(clamp_time(-1.0, 2.0), 0.0);
        assert_eq!(clamp_time(3.0, 2.0), 2.0);
        assert_eq!(clamp_time(1.5, 2.0), 1.5);
        assert!(clamp_time(f64::NAN, 2.0).is_nan());
        assert_eq!(Order::from_index(2), Some(Order::Acceleration));
        assert_eq!(Order::Jerk.name(), "jerk");
    }
}
