//! Geometric paths σ(s): the input of time parameterization.
//!
//! A [`Path`] is a vector-valued curve in joint space over a parameter interval
//! `[s_start, s_end]`, with no notion of time. Time-optimal parameterization (TOPP-RA, TOTG,
//! numerical integration) chooses s(t) and produces the trajectory ξ(t) = σ(s(t)) with
//! ξ̇ = σ′ṡ, ξ̈ = σ″ṡ² + σ′s̈ (and ξ⃛ = σ‴ṡ³ + 3σ″ṡs̈ + σ′s⃛).
//!
//! Splines implement `Path`; so can user code. As for trajectories, evaluation writes into a
//! caller buffer and never allocates; `s` outside the interval is clamped to it.

/// A geometric path σ(s) in joint space.
pub trait Path {
    /// Number of joints (dimension of σ).
    fn dim(&self) -> usize;

    /// The parameter interval `(s_start, s_end)`, `s_start < s_end`.
    fn interval(&self) -> (f64, f64);

    /// Writes the `order`-th derivative dᵏσ/dsᵏ at `s` (clamped to the interval) into `out`.
    /// Orders 0..=3 must be supported (σ‴ may be zero where the path is only C²); higher orders
    /// may be zero.
    fn eval(&self, s: f64, order: usize, out: &mut [f64]);

    /// Writes σ′(s) into `first` and σ″(s) into `second`: what time parameterization needs at
    /// every gridpoint. The default calls [`Path::eval`] twice; a path that can share work
    /// between the two (one piece search, one pass over the coefficients) should override it.
    /// Both must equal what `eval` writes for orders 1 and 2.
    fn eval_derivatives(&self, s: f64, first: &mut [f64], second: &mut [f64]) {
        self.eval(s, 1, first);
        self.eval(s, 2, second);
    }

    /// Writes the `order`-th derivative at every parameter of `s` into `out` (row-major,
    /// `s.len() × dim()`), each row what [`Path::eval`] writes (to rounding: an override may
    /// evaluate differently, as B-splines do). The default calls `eval` per point; piecewise
    /// curves override it to find each point's piece from the previous one (fast on sorted
    /// parameters, correct on any). No allocation.
    fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
        let dim = self.dim();
        for (&si, o) in s.iter().zip(out.chunks_exact_mut(dim.max(1))) {
            self.eval(si, order, o);
        }
    }

    /// Writes orders 0 to 3 at every parameter of `s` into `out[0..4]` (each row-major,
    /// `s.len() × dim()`), each what [`Path::eval_many`] writes for that order. The default
    /// makes the four `eval_many` calls; a path that can share the piece search and the
    /// coefficient setup between the orders should override it (bitwise equal values). No
    /// allocation.
    fn eval_many_orders(&self, s: &[f64], out: [&mut [f64]; 4]) {
        for (order, o) in out.into_iter().enumerate() {
            self.eval_many(s, order, o);
        }
    }

    /// Parameters where σ or a low derivative is not smooth (segment joints of a spline,
    /// corners of a piecewise-linear path), increasing, including both ends. Time
    /// parameterization puts gridpoints there. The default is just the two ends; a path that
    /// knows its joints should override this.
    fn breakpoints(&self) -> Vec<f64> {
        let (a, b) = self.interval();
        vec![a, b]
    }

    /// `Some(d)` when σ is a polynomial of degree at most `d` between consecutive
    /// [`Path::breakpoints`] (splines, polylines), `None` (the default) when it is not or the
    /// path does not say. For `d ≤ 3` the path's σ′, σ″ and σ‴ at one point of a piece
    /// determine σ on the whole piece, which lets time parameterization bound its constraints
    /// between gridpoints exactly instead of probing them.
    fn piecewise_degree(&self) -> Option<usize> {
        None
    }
}

impl<P: Path + ?Sized> Path for &P {
    fn dim(&self) -> usize {
        (**self).dim()
    }
    fn interval(&self) -> (f64, f64) {
        (**self).interval()
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        (**self).eval(s, order, out)
    }
    fn eval_derivatives(&self, s: f64, first: &mut [f64], second: &mut [f64]) {
        (**self).eval_derivatives(s, first, second)
    }
    fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
        (**self).eval_many(s, order, out)
    }
    fn eval_many_orders(&self, s: &[f64], out: [&mut [f64]; 4]) {
        (**self).eval_many_orders(s, out)
    }
    fn breakpoints(&self) -> Vec<f64> {
        (**self).breakpoints()
    }
    fn piecewise_degree(&self) -> Option<usize> {
        (**self).piecewise_degree()
    }
}

impl<P: Path + ?Sized> Path for Box<P> {
    fn dim(&self) -> usize {
        (**self).dim()
    }
    fn interval(&self) -> (f64, f64) {
        (**self).interval()
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        (**self).eval(s, order, out)
    }
    fn eval_derivatives(&self, s: f64, first: &mut [f64], second: &mut [f64]) {
        (**self).eval_derivatives(s, first, second)
    }
    fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
        (**self).eval_many(s, order, out)
    }
    fn eval_many_orders(&self, s: &[f64], out: [&mut [f64]; 4]) {
        (**self).eval_many_orders(s, out)
    }
    fn breakpoints(&self) -> Vec<f64> {
        (**self).breakpoints()
    }
    fn piecewise_degree(&self) -> Option<usize> {
        (**self).piecewise_degree()
    }
}

/// A path used directly as a trajectory: time t runs over the parameter, `s = s_start + t`,
/// so the duration is `s_end - s_start` and time derivatives equal parameter derivatives.
///
/// Useful when a spline was fitted through waypoints at given times.
#[derive(Debug, Clone)]
pub struct PathAsTrajectory<P: Path>(pub P);

impl<P: Path> crate::Trajectory for PathAsTrajectory<P> {
    fn dof(&self) -> usize {
        self.0.dim()
    }
    fn duration(&self) -> f64 {
        let (a, b) = self.0.interval();
        b - a
    }
    fn eval(&self, t: f64, order: crate::Order, out: &mut [f64]) {
        let (a, b) = self.0.interval();
        let t = crate::traj::clamp_time(t, b - a);
        self.0.eval(a + t, order.index(), out)
    }
}
