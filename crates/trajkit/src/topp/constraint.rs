//! Constraints on the path velocity and acceleration, in TOPP-RA's general linear form.
//!
//! Along a path σ(s) timed by s(t), the joint velocity is q̇ = σ′ṡ and the joint acceleration
//! q̈ = σ′s̈ + σ″ṡ². With the state x = ṡ² and the control u = s̈, every constraint trajkit
//! handles has, at each path point s, the form
//!
//! ```text
//!     a(s)·u + b(s)·x + c(s) = v,   F(s)·v ≤ g(s),        x_min(s) ≤ x ≤ x_max(s)
//! ```
//!
//! A [`Constraint`] writes that form at one path point into [`ConstraintRows`], which turns it
//! into half-planes in the (u, x) plane for the solver. Built-ins:
//! - [`JointVelocity`]: |q̇| within per-joint directional limits (bounds on x alone);
//! - [`JointAcceleration`]: q̈ within per-joint directional limits;
//! - [`JointTorque`]: τ = ID(q, q̇, q̈) (+ Coulomb friction) within torque limits, through an
//!   [`InverseDynamics`] model the user implements;
//! - [`EndEffectorSpeed`]: ‖J(q)·q̇‖ ≤ v_max through a user [`Jacobian`].
//!
//! User code can implement [`Constraint`] for anything else of this form.
//!
//! Between gridpoints TOPP-RA keeps s̈ = u constant, so x = ṡ² is linear in s. Where the path
//! is a polynomial of degree ≤ 3 ([`CubicPiece`]), the joint acceleration σ′u + σ″x is then a
//! quadratic in s and the squared joint velocity σ′²x has its extrema where that acceleration
//! is zero: [`JointVelocity`] and [`JointAcceleration`] find their worst value on a whole
//! interval in closed form ([`Constraint::excess_on_cubic`]). On pieces of degree 4 or 5 (the
//! range-repaired splines of [`crate::spline::BoundedSpline`]) the acceleration is a quartic
//! and σ′²x has degree 9: the same two constraints bound them from Bernstein coefficients
//! (degree 4 and 9 in θ = (s − s0)/Δ, linear in (u, x0)) and from the roots of a quartic or
//! cubic isolated by [`crate::roots::roots_in`] ([`Constraint::handles_quintic`]).
//!
//! # Precision contract
//! Rows are written exactly as the formulas above (no linearisation or padding); a limit of
//! `±∞` writes no row. [`Constraint::excess_on_cubic`] of the built-ins is the exact maximum
//! over the closed interval up to rounding (the candidates are the two ends and the real roots
//! of one quadratic per joint, in the stable form; on quintic pieces the roots of one quartic
//! or cubic per joint, bracketed to 4 ulp). Zero limits are allowed here (they make the problem infeasible when the
//! joint must move, which the solver reports with the path position and this constraint's
//! name).

use crate::error::{Error, Result};
pub use crate::inverse_dynamics::InverseDynamics;
use crate::limits::Limits;
use crate::Order;

mod dynamics;
mod quintic;
mod worst;

use worst::{enclosed_excess, worst_over};

pub use dynamics::{EndEffectorSpeed, Jacobian, JointTorque};

/// 1/6 and 1/24: the Taylor factors of the quintic pieces' rows, multiplied rather than
/// divided (the rows of every interval of a quintic path need them).
const INV6: f64 = 1.0 / 6.0;
const INV24: f64 = 1.0 / 24.0;

/// The path's derivatives at one path point, handed to every constraint.
#[derive(Debug, Clone, Copy)]
pub struct PathPoint<'a> {
    /// The path parameter s.
    pub s: f64,
    /// σ(s).
    pub q: &'a [f64],
    /// σ′(s).
    pub dq: &'a [f64],
    /// σ″(s).
    pub ddq: &'a [f64],
}

/// One interval `[s0, s1]` between gridpoints on which the path is a polynomial of degree at
/// most 5, given by its Taylor coefficients at `s0` (the limits from inside the interval): with
/// t = s − s0, σ(s) = d0 + d1·t + d2·t²/2 + d3·t³/6 + d4·t⁴/24 + d5·t⁵/120. On a cubic piece
/// (`d4` and `d5` all zero, [`CubicPiece::is_cubic`]) σ′(s) = d1 + d2·t + d3·t²/2 and
/// σ″(s) = d2 + d3·t. Each slice has one entry per joint; `d0` holds zeros when no constraint
/// of the problem reads the position. The solver hands pieces of degree 4 or 5 only to
/// constraints that say they handle them ([`Constraint::handles_quintic`]).
#[derive(Debug, Clone, Copy)]
pub struct CubicPiece<'a> {
    /// Start of the interval.
    pub s0: f64,
    /// End of the interval.
    pub s1: f64,
    /// σ(s0).
    pub d0: &'a [f64],
    /// σ′(s0).
    pub d1: &'a [f64],
    /// σ″(s0).
    pub d2: &'a [f64],
    /// σ‴(s0) (constant on the interval when the piece is cubic).
    pub d3: &'a [f64],
    /// σ⁗(s0): zeros on a cubic piece.
    pub d4: &'a [f64],
    /// σ⁽⁵⁾ (constant on the interval): zeros on a cubic or quartic piece.
    pub d5: &'a [f64],
}

impl CubicPiece<'_> {
    /// Whether the piece is a polynomial of degree ≤ 3 (`d4` and `d5` all zero).
    #[inline]
    pub fn is_cubic(&self) -> bool {
        self.d4.iter().chain(self.d5).all(|&v| v == 0.0)
    }

    /// Joint j's σ′ and σ″ at s.
    #[inline]
    pub fn derivatives(&self, j: usize, s: f64) -> (f64, f64) {
        let t = s - self.s0;
        let (d3, d4, d5) = (self.d3[j], self.d4[j], self.d5[j]);
        (
            self.d1[j] + t * (self.d2[j] + t * (0.5 * d3 + t * (d4 / 6.0 + t * d5 / 24.0))),
            self.d2[j] + t * (d3 + t * (0.5 * d4 + t * d5 / 6.0)),
        )
    }

    /// Joint j's acceleration σ′u + σ″x along the interval, with x = x0 + 2u(s − s0), as the
    /// quartic `[c0, …, c4]` in t = s − s0 (lowest order first): with σ′ = Σ p_k t^k and
    /// σ″ = Σ q_k t^k, c_k = u·p_k + x0·q_k + 2u·q_{k−1}.
    pub fn acceleration_quartic(&self, j: usize, u: f64, x0: f64) -> [f64; 5] {
        let (a, b) = self.acceleration_rows(j);
        std::array::from_fn(|k| a[k] * u + b[k] * x0)
    }

    /// The acceleration quartic's coefficients (in t) as rows in (u, x0): c_k = α_k·u + β_k·x0.
    #[inline]
    fn acceleration_rows(&self, j: usize) -> ([f64; 5], [f64; 5]) {
        let p = [
            self.d1[j],
            self.d2[j],
            0.5 * self.d3[j],
            self.d4[j] * INV6,
            self.d5[j] * INV24,
        ];
        let q = [
            self.d2[j],
            self.d3[j],
            0.5 * self.d4[j],
            self.d5[j] * INV6,
            0.0,
        ];
        let alpha = std::array::from_fn(|k| p[k] + if k > 0 { 2.0 * q[k - 1] } else { 0.0 });
        (alpha, q)
    }

    /// Joint j's σ′ as a quartic in θ = (s − s0)/(s1 − s0) ∈ [0, 1], in Bernstein form
    /// `[b0, …, b4]` (σ′ = Σ C(4,k)·b_k·θ^k(1 − θ)^(4−k); it lies between the least and the
    /// largest of them).
    #[inline]
    pub fn first_bernstein4(&self, j: usize) -> [f64; 5] {
        let h = self.s1 - self.s0;
        let p = [
            self.d1[j],
            self.d2[j] * h,
            0.5 * self.d3[j] * h * h,
            self.d4[j] * INV6 * h * h * h,
            self.d5[j] * INV24 * h * h * h * h,
        ];
        quintic::power_to_bernstein4(p)
    }

    /// Joint j's acceleration σ′u + σ″x along the interval, with x = x0 + 2u(s − s0), as the
    /// quadratic `[c0, c1, c2]` in t = s − s0 (value c0 + c1·t + c2·t²).
    #[inline]
    pub fn acceleration_quadratic(&self, j: usize, u: f64, x0: f64) -> [f64; 3] {
        let (d1, d2, d3) = (self.d1[j], self.d2[j], self.d3[j]);
        [u * d1 + d2 * x0, 3.0 * u * d2 + d3 * x0, 2.5 * u * d3]
    }

    /// Joint j's σ′ as a quadratic in θ = (s − s0)/(s1 − s0) ∈ [0, 1], in Bernstein form
    /// `[b0, b1, b2]` (σ′ = b0(1 − θ)² + 2b1θ(1 − θ) + b2θ²; it lies between the least and the
    /// largest of them).
    #[inline]
    pub fn first_bernstein(&self, j: usize) -> [f64; 3] {
        let h = self.s1 - self.s0;
        let (d1, d2, d3) = (self.d1[j], self.d2[j], self.d3[j]);
        [d1, d1 + 0.5 * h * d2, d1 + h * (d2 + 0.5 * h * d3)]
    }

    /// Writes σ, σ′, σ″ at s into the three buffers (one entry per joint).
    pub fn eval_into(&self, s: f64, q: &mut [f64], dq: &mut [f64], ddq: &mut [f64]) {
        let t = s - self.s0;
        for j in 0..self.d1.len() {
            let (d0, d1, d2, d3) = (self.d0[j], self.d1[j], self.d2[j], self.d3[j]);
            let (d4, d5) = (self.d4[j], self.d5[j]);
            q[j] =
                d0 + t * (d1 + t * (0.5 * d2 + t * (d3 / 6.0 + t * (d4 / 24.0 + t * d5 / 120.0))));
            (dq[j], ddq[j]) = self.derivatives(j, s);
        }
    }
}

/// The real roots of c0 + c1·t + c2·t² inside the open interval (lo, hi), stable form; at most
/// two (none when the polynomial is identically zero).
fn quadratic_roots_in(c: [f64; 3], lo: f64, hi: f64) -> ([f64; 2], usize) {
    let [c0, c1, c2] = c;
    let mut out = [0.0; 2];
    let mut n = 0;
    let mut push = |t: f64| {
        if t > lo && t < hi {
            out[n] = t;
            n += 1;
        }
    };
    let scale = c0
        .abs()
        .max(c1.abs() * (hi - lo))
        .max(c2.abs() * (hi - lo) * (hi - lo));
    if c2.abs() * (hi - lo) * (hi - lo) <= 1e-14 * scale {
        if c1 != 0.0 {
            push(-c0 / c1);
        }
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc >= 0.0 {
            let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
            if q != 0.0 {
                push(q / c2);
                push(c0 / q);
            } else {
                push(0.0);
            }
        }
    }
    (out, n)
}

/// Collects one constraint's rows at one path point: half-planes `α·u + β·x ≤ γ` and bounds on
/// x = ṡ². Written by [`Constraint::write`], read by the solver.
#[derive(Debug, Default, Clone)]
pub struct ConstraintRows {
    /// Half-planes (α, β, γ): α·u + β·x ≤ γ.
    pub(crate) rows: Vec<[f64; 3]>,
    /// Where this point's rows start in `rows` (the solver lets every point append to one
    /// buffer).
    pub(crate) start: usize,
    /// Lower bound on x.
    pub(crate) x_min: f64,
    /// Upper bound on x.
    pub(crate) x_max: f64,
    /// A row that can never hold (0·u + 0·x ≤ γ < 0) or a NaN was written.
    pub(crate) broken: Option<&'static str>,
}

impl ConstraintRows {
    /// Empty rows, x unbounded.
    pub fn new() -> Self {
        ConstraintRows {
            rows: Vec::new(),
            start: 0,
            x_min: 0.0,
            x_max: f64::INFINITY,
            broken: None,
        }
    }

    pub(crate) fn clear(&mut self) {
        self.rows.clear();
        self.clear_bounds();
    }

    /// Starts a new point: resets the bounds on x and the broken flag, keeping earlier points'
    /// rows in the buffer.
    pub(crate) fn clear_bounds(&mut self) {
        self.start = self.rows.len();
        self.x_min = 0.0;
        self.x_max = f64::INFINITY;
        self.broken = None;
    }

    /// The half-planes written so far, `(α, β, γ)` meaning `α·u + β·x ≤ γ`.
    pub fn half_planes(&self) -> &[[f64; 3]] {
        &self.rows[self.start..]
    }

    /// The bounds on x = ṡ² written so far (`[0, ∞)` when none).
    pub fn x_bounds(&self) -> (f64, f64) {
        (self.x_min, self.x_max)
    }

    /// Adds `α·u + β·x ≤ γ`.
    #[inline]
    pub fn half_plane(&mut self, alpha: f64, beta: f64, gamma: f64) {
        if alpha.is_nan() || beta.is_nan() || gamma.is_nan() {
            self.broken = Some("produced a NaN coefficient");
            return;
        }
        if gamma == f64::INFINITY {
            return;
        }
        if alpha == 0.0 && beta == 0.0 {
            if gamma < 0.0 {
                self.broken = Some("cannot hold at any velocity");
            }
            return;
        }
        self.rows.push([alpha, beta, gamma]);
    }

    /// Adds `lo ≤ a·u + b·x + c ≤ hi` (either side may be infinite).
    #[inline]
    pub fn interval(&mut self, a: f64, b: f64, c: f64, lo: f64, hi: f64) {
        if hi < f64::INFINITY {
            self.half_plane(a, b, hi - c);
        }
        if lo > f64::NEG_INFINITY {
            self.half_plane(-a, -b, c - lo);
        }
    }

    /// Adds `lo[j] ≤ a[j]·u + b[j]·x ≤ hi[j]` for every j: the same rows as
    /// [`ConstraintRows::interval`] with `c = 0`, in one pass (joint accelerations write
    /// this at every gridpoint).
    pub fn intervals(&mut self, a: &[f64], b: &[f64], lo: &[f64], hi: &[f64]) {
        let n = a.len().min(b.len()).min(lo.len()).min(hi.len());
        self.rows.reserve(2 * n);
        for j in 0..n {
            let (aj, bj, l, h) = (a[j], b[j], lo[j], hi[j]);
            if aj.is_nan() || bj.is_nan() || l.is_nan() || h.is_nan() {
                self.broken = Some("produced a NaN coefficient");
                return;
            }
            if aj == 0.0 && bj == 0.0 {
                if h < 0.0 || l > 0.0 {
                    self.broken = Some("cannot hold at any velocity");
                }
                continue;
            }
            if h < f64::INFINITY && l > f64::NEG_INFINITY {
                // Both sides (the usual case): one append.
                self.rows.extend_from_slice(&[[aj, bj, h], [-aj, -bj, -l]]);
                continue;
            }
            if h < f64::INFINITY {
                self.rows.push([aj, bj, h]);
            }
            if l > f64::NEG_INFINITY {
                self.rows.push([-aj, -bj, -l]);
            }
        }
    }

    /// Adds `F·(a·u + b·x + c) ≤ g` for a general polytope: `a`, `b`, `c` have `m` entries,
    /// `f` is row-major `k × m`, `g` has `k` entries.
    pub fn polytope(&mut self, a: &[f64], b: &[f64], c: &[f64], f: &[f64], g: &[f64]) {
        let m = a.len();
        if b.len() != m || c.len() != m || f.len() != g.len() * m {
            self.broken = Some("wrote a polytope with inconsistent sizes");
            return;
        }
        for (r, &gr) in g.iter().enumerate() {
            let fr = &f[r * m..(r + 1) * m];
            let (mut fa, mut fb, mut fc) = (0.0, 0.0, 0.0);
            for j in 0..m {
                fa += fr[j] * a[j];
                fb += fr[j] * b[j];
                fc += fr[j] * c[j];
            }
            self.half_plane(fa, fb, gr - fc);
        }
    }

    /// An error naming the constraint and the path position when a written row can never
    /// hold or was NaN.
    pub(crate) fn check(&self, constraint: &dyn Constraint, s: f64) -> Result<()> {
        match self.broken {
            Some(why) => Err(Error::Infeasible(format!(
                "constraint '{}' at s = {s}: {why}",
                constraint.name()
            ))),
            None => Ok(()),
        }
    }

    /// The largest relative excess of these rows at path acceleration `u` and x = ṡ² = `xs`:
    /// for the velocity bound √(x/x_max) − 1, for each half-plane (α·u + β·x − γ) divided by
    /// the largest of |γ|, |α·u|, |β·x|. Negative or zero when every row holds.
    pub(crate) fn relative_excess(&self, u: f64, xs: f64) -> f64 {
        // ṡ ≤ √x_max: the relative excess of a velocity is that of √x.
        let mut e = if self.x_max > 0.0 {
            (xs / self.x_max).sqrt() - 1.0
        } else if xs > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        for &[a, b, g] in self.half_planes() {
            let scale = g.abs().max((a * u).abs()).max((b * xs).abs());
            if scale > 0.0 {
                e = e.max((a * u + b * xs - g) / scale);
            }
        }
        e
    }

    /// Requires `x ≤ value` (x = ṡ²).
    pub fn x_at_most(&mut self, value: f64) {
        if value.is_nan() {
            self.broken = Some("produced a NaN velocity bound");
        } else if value < self.x_max {
            self.x_max = value;
        }
    }

    /// Requires `x ≥ value` (x = ṡ²).
    pub fn x_at_least(&mut self, value: f64) {
        if value.is_nan() {
            self.broken = Some("produced a NaN velocity bound");
        } else if value > self.x_min {
            self.x_min = value;
        }
    }
}

/// A constraint of the general form of the module documentation.
///
/// Implementations are evaluated once per gridpoint when a problem is solved (not in a control
/// loop) and may allocate.
pub trait Constraint {
    /// A short human name used in error messages, e.g. `"joint acceleration"`.
    fn name(&self) -> String;

    /// The number of joints the constraint expects (the path's dimension).
    fn dof(&self) -> usize;

    /// Writes the constraint at path point `p` into `out`.
    fn write(&self, p: &PathPoint<'_>, out: &mut ConstraintRows);

    /// Whether [`Constraint::write`] reads `p.q` (the path position). The solver skips
    /// evaluating σ(s) when no constraint does; `p.q` then holds unspecified values. Default
    /// `true`.
    fn uses_position(&self) -> bool {
        true
    }

    /// When the solver finds that the path cannot move at `p`, a sentence naming the cause
    /// (e.g. a joint that must move but has a zero limit), if this constraint knows one.
    fn diagnose(&self, p: &PathPoint<'_>) -> Option<String> {
        let _ = p;
        None
    }

    /// The worst value of the constraint over a whole interval on which the path is a
    /// polynomial of degree ≤ 3 (≤ 5 when [`Constraint::handles_quintic`]), timed with
    /// constant path acceleration `u` and
    /// x = ṡ² = `x0` + 2u(s − s0): `Some((e, s))` with the largest relative excess e (as the
    /// value relative to the limit, e.g. |q̇|/v_max − 1) and a point s where it occurs. When the constraint holds everywhere the value may instead be any upper bound
    /// ≤ 0 of the worst excess (a cheap enclosure suffices). It must be rigorous (not sampled):
    /// the solver relies on it to guarantee the constraint between gridpoints. `None` (the
    /// default) when the constraint cannot say; the solver then checks it at sample points.
    fn excess_on_cubic(&self, piece: &CubicPiece<'_>, u: f64, x0: f64) -> Option<(f64, f64)> {
        let _ = (piece, u, x0);
        None
    }

    /// Half-planes `α·u + β·x0 ≤ γ` in the interval's (u, x0), with x0 = ṡ² at `piece.s0`
    /// and x = x0 + 2u(s − s0) along the piece, that together with the constraint's own rows
    /// at both ends of the interval *imply* it on the whole piece: a sufficient condition, such
    /// as the interior Bernstein coefficients of the polynomial the constraint becomes (the end
    /// coefficients are the end rows). Rows that cannot bind while ṡ² stays within `x_max` at
    /// both ends (`[at s0, at s1]`, the velocity bounds there) may be left out. Returns `false`
    /// (the default) when the constraint cannot; it must then also return `None` from
    /// [`Constraint::excess_on_cubic`].
    fn hold_on_cubic(
        &self,
        piece: &CubicPiece<'_>,
        x_max: [f64; 2],
        out: &mut ConstraintRows,
    ) -> bool {
        let _ = (piece, x_max, out);
        false
    }

    /// Whether [`Constraint::excess_on_cubic`] and [`Constraint::hold_on_cubic`] handle pieces
    /// of degree 4 and 5 (`d4`, `d5` of [`CubicPiece`] nonzero). Default `false`: the solver
    /// then hands such a constraint cubic pieces only and checks it at sample points elsewhere.
    fn handles_quintic(&self) -> bool {
        false
    }
}

impl<C: Constraint + ?Sized> Constraint for Box<C> {
    fn name(&self) -> String {
        (**self).name()
    }
    fn dof(&self) -> usize {
        (**self).dof()
    }
    fn write(&self, p: &PathPoint<'_>, out: &mut ConstraintRows) {
        (**self).write(p, out)
    }
    fn uses_position(&self) -> bool {
        (**self).uses_position()
    }
    fn diagnose(&self, p: &PathPoint<'_>) -> Option<String> {
        (**self).diagnose(p)
    }
    fn excess_on_cubic(&self, piece: &CubicPiece<'_>, u: f64, x0: f64) -> Option<(f64, f64)> {
        (**self).excess_on_cubic(piece, u, x0)
    }
    fn hold_on_cubic(
        &self,
        piece: &CubicPiece<'_>,
        x_max: [f64; 2],
        out: &mut ConstraintRows,
    ) -> bool {
        (**self).hold_on_cubic(piece, x_max, out)
    }
    fn handles_quintic(&self) -> bool {
        (**self).handles_quintic()
    }
}

/// Validates directional limit pairs: `lo ≤ 0 ≤ hi`, no NaN. Zero is allowed.
fn check_ranges(what: &str, lo: &[f64], hi: &[f64]) -> Result<()> {
    if lo.len() != hi.len() {
        return Err(Error::DimensionMismatch {
            what: format!("{what} lower limits"),
            expected: hi.len(),
            found: lo.len(),
        });
    }
    if hi.is_empty() {
        return Err(Error::DimensionMismatch {
            what: format!("{what} limits joint count"),
            expected: 1,
            found: 0,
        });
    }
    for j in 0..hi.len() {
        if hi[j].is_nan() || hi[j] < 0.0 {
            return Err(Error::InvalidValue {
                field: format!("joint {} {what} upper limit", j + 1),
                value: hi[j],
                reason: "is not a number >= 0",
            });
        }
        if lo[j].is_nan() || lo[j] > 0.0 {
            return Err(Error::InvalidValue {
                field: format!("joint {} {what} lower limit", j + 1),
                value: lo[j],
                reason: "is not a number <= 0",
            });
        }
    }
    Ok(())
}

/// Names the joints that move at `p` (σ′ ≠ 0) but have a zero limit in a direction they need.
fn zero_limit_joints(what: &str, lo: &[f64], hi: &[f64], p: &PathPoint<'_>) -> Option<String> {
    let bad: Vec<String> = (0..hi.len())
        .filter(|&j| p.dq[j] != 0.0 && (hi[j] == 0.0 || lo[j] == 0.0))
        .map(|j| {
            format!(
                "joint {} must move (dq/ds = {:.6}) but its {what} limit is [{}, {}]",
                j + 1,
                p.dq[j],
                lo[j],
                hi[j]
            )
        })
        .collect();
    if bad.is_empty() {
        None
    } else {
        Some(bad.join("; "))
    }
}

fn ranges_from(limits: &Limits, order: Order) -> (Vec<f64>, Vec<f64>) {
    limits.joints().iter().map(|j| j.range(order)).unzip()
}

/// The velocity limit that applies on a piece where σ′_j has Bernstein coefficients `c`: the
/// upper one when σ′_j ≥ 0 there, the lower one's magnitude when σ′_j ≤ 0, the smaller
/// magnitude when the sign may change.
fn velocity_bound(c: [f64; 3], lo: f64, hi: f64) -> f64 {
    if c.iter().all(|&v| v >= 0.0) {
        hi
    } else if c.iter().all(|&v| v <= 0.0) {
        -lo
    } else {
        hi.min(-lo)
    }
}

/// The Bernstein coefficients (degree 5 in θ) of σ′_j²·x with x = x0 + (x1 − x0)·θ, from the
/// Bernstein coefficients `c` of σ′_j: b_k = ((5 − k)·w_k·x0 + k·w_{k−1}·x1)/5 with w those of
/// σ′_j² (degree 4). Also the (α, β) of each as a row in (u, x0): x1 = x0 + 2uΔ.
fn velocity_bernstein(c: [f64; 3], x0: f64, x1: f64) -> [f64; 6] {
    let w = square_bernstein(c);
    let mut b = [0.0; 6];
    for (k, bk) in b.iter_mut().enumerate() {
        let wk = if k < 5 { w[k] } else { 0.0 };
        let wk1 = if k > 0 { w[k - 1] } else { 0.0 };
        let kf = k as f64;
        *bk = ((5.0 - kf) * wk * x0 + kf * wk1 * x1) / 5.0;
    }
    b
}

/// Bernstein coefficients (degree 4) of the square of a quadratic given by its own.
fn square_bernstein([c0, c1, c2]: [f64; 3]) -> [f64; 5] {
    [
        c0 * c0,
        c0 * c1,
        (c0 * c2 + 2.0 * c1 * c1) / 3.0,
        c1 * c2,
        c2 * c2,
    ]
}

/// Joint velocity limits `lo_j ≤ σ′_j(s)·ṡ ≤ hi_j`: an upper bound on x = ṡ² at each point.
///
/// ```
/// use trajkit::topp::{JointVelocity, Constraint};
/// let c = JointVelocity::new(&[-1.0, -2.0], &[1.0, 2.0])?;
/// assert_eq!(c.dof(), 2);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct JointVelocity {
    lo: Vec<f64>,
    hi: Vec<f64>,
}

impl JointVelocity {
    /// Limits per joint: `lo[j] ≤ 0 ≤ hi[j]` (infinite = unlimited; zero allowed).
    pub fn new(lo: &[f64], hi: &[f64]) -> Result<Self> {
        check_ranges("velocity", lo, hi)?;
        Ok(JointVelocity {
            lo: lo.to_vec(),
            hi: hi.to_vec(),
        })
    }

    /// The velocity limits of `limits` (directional minima included).
    pub fn from_limits(limits: &Limits) -> Self {
        let (lo, hi) = ranges_from(limits, Order::Velocity);
        JointVelocity { lo, hi }
    }

    /// Joint j's squared ratio v²/limit² from (σ′_j, σ″_j, x): the value
    /// [`worst_over`] maximises.
    fn squared_ratio(&self, j: usize) -> impl Fn(f64, f64, f64) -> f64 + '_ {
        move |d1, _, x| {
            let limit = if d1 > 0.0 { self.hi[j] } else { self.lo[j] };
            if d1 == 0.0 || x == 0.0 {
                0.0
            } else {
                d1 * d1 * x / (limit * limit)
            }
        }
    }
}

impl Constraint for JointVelocity {
    fn name(&self) -> String {
        "joint velocity".into()
    }
    fn dof(&self) -> usize {
        self.hi.len()
    }
    fn write(&self, p: &PathPoint<'_>, out: &mut ConstraintRows) {
        let mut sd_max = f64::INFINITY;
        for j in 0..self.hi.len() {
            let d = p.dq[j];
            let bound = if d > 0.0 {
                self.hi[j] / d
            } else if d < 0.0 {
                self.lo[j] / d
            } else {
                f64::INFINITY
            };
            sd_max = sd_max.min(bound);
        }
        out.x_at_most(sd_max * sd_max);
    }
    fn uses_position(&self) -> bool {
        false
    }
    fn diagnose(&self, p: &PathPoint<'_>) -> Option<String> {
        zero_limit_joints("velocity", &self.lo, &self.hi, p)
    }
    /// |σ′_j|·√x is extreme at the ends and where its derivative, the joint acceleration
    /// σ′_j·u + σ″_j·x (a quadratic in s), is zero. Joints whose Bernstein bound is within
    /// the limit are not solved for.
    fn excess_on_cubic(&self, piece: &CubicPiece<'_>, u: f64, x0: f64) -> Option<(f64, f64)> {
        if !piece.is_cubic() {
            return Some(self.excess_quintic(piece, u, x0));
        }
        let h = piece.s1 - piece.s0;
        let x1 = x0 + 2.0 * u * h;
        // The worst squared ratio v²/limit² and where.
        let mut worst = (0.0f64, piece.s0);
        for j in 0..self.hi.len() {
            let c = piece.first_bernstein(j);
            let limit = velocity_bound(c, self.lo[j], self.hi[j]);
            let l2 = limit * limit;
            let b = velocity_bernstein(c, x0, x1);
            let bmax = b.iter().cloned().fold(0.0, f64::max);
            if bmax <= l2 {
                worst.0 = worst.0.max(bmax / l2);
                continue;
            }
            let (roots, nr) = quadratic_roots_in(piece.acceleration_quadratic(j, u, x0), 0.0, h);
            let candidates = [0.0, h, roots[0], roots[1]];
            let f = (j, self.squared_ratio(j));
            worst_over(piece, u, x0, &candidates[..2 + nr], &mut worst, f);
        }
        Some((worst.0.sqrt() - 1.0, worst.1))
    }
    /// σ′_j²·x is a polynomial of degree 5 in θ = (s − s0)/Δ, the product of σ′_j² (degree 4)
    /// and x = x0 + 2uΔθ; its Bernstein coefficients b_0..b_5 are linear in (u, x0) and bound
    /// it. b_0 and b_5 are the velocity bounds at the ends; b_1..b_4 are written, for the
    /// joints whose coefficients can reach the limit within `x_max`.
    fn hold_on_cubic(
        &self,
        piece: &CubicPiece<'_>,
        x_max: [f64; 2],
        out: &mut ConstraintRows,
    ) -> bool {
        if !piece.is_cubic() {
            self.hold_quintic(piece, x_max, out);
            return true;
        }
        let h = piece.s1 - piece.s0;
        for j in 0..self.hi.len() {
            let c = piece.first_bernstein(j);
            let limit = velocity_bound(c, self.lo[j], self.hi[j]);
            if limit.is_infinite() {
                continue;
            }
            // Quick: |σ′| ≤ max |c_k| and x ≤ the larger bound.
            let m = c[0].abs().max(c[1].abs()).max(c[2].abs());
            if m * m * x_max[0].max(x_max[1]) <= limit * limit {
                continue;
            }
            // b_k is linear in (x0, x1) ∈ [0, x_max[0]] × [0, x_max[1]]: its largest value
            // takes each term at the end of its range where it is largest.
            let w = square_bernstein(c);
            let reach = |k: usize| {
                let kf = k as f64;
                ((5.0 - kf) * w[k]).max(0.0) * x_max[0] + (kf * w[k - 1]).max(0.0) * x_max[1]
            };
            if (1..5).all(|k| reach(k) <= 5.0 * limit * limit) {
                continue;
            }
            // b_k = ((5 − k)·w_k·x0 + k·w_{k−1}·(x0 + 2uh)) / 5.
            for k in 1..5 {
                let kf = k as f64;
                let alpha = kf * w[k - 1] * 2.0 * h / 5.0;
                let beta = ((5.0 - kf) * w[k] + kf * w[k - 1]) / 5.0;
                out.half_plane(alpha, beta, limit * limit);
            }
        }
        true
    }
    fn handles_quintic(&self) -> bool {
        true
    }
}

/// Joint acceleration limits `lo_j ≤ σ′_j·u + σ″_j·x ≤ hi_j` (direction-dependent minima).
///
/// ```
/// use trajkit::{topp::JointAcceleration, Limits};
/// let c = JointAcceleration::from_limits(&Limits::preset("panda")?);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct JointAcceleration {
    lo: Vec<f64>,
    hi: Vec<f64>,
}

impl JointAcceleration {
    /// Limits per joint: `lo[j] ≤ 0 ≤ hi[j]` (infinite = unlimited; zero allowed).
    pub fn new(lo: &[f64], hi: &[f64]) -> Result<Self> {
        check_ranges("acceleration", lo, hi)?;
        Ok(JointAcceleration {
            lo: lo.to_vec(),
            hi: hi.to_vec(),
        })
    }

    /// The acceleration limits of `limits` (directional minima included).
    pub fn from_limits(limits: &Limits) -> Self {
        let (lo, hi) = ranges_from(limits, Order::Acceleration);
        JointAcceleration { lo, hi }
    }

    /// Joint j's relative excess over its limits from (σ′_j, σ″_j, x) at path acceleration
    /// `u`: the value [`worst_over`] maximises.
    fn excess_at(&self, j: usize, u: f64) -> impl Fn(f64, f64, f64) -> f64 + '_ {
        move |d1, d2, x| {
            let a = d1 * u + d2 * x;
            let terms = (d1 * u).abs().max((d2 * x).abs());
            let mut e = f64::NEG_INFINITY;
            for (limit, sign) in [(self.hi[j], 1.0), (self.lo[j], -1.0)] {
                if limit.is_infinite() {
                    continue;
                }
                // Relative to the limit (its extreme is the acceleration's); a zero limit is
                // measured against the terms.
                let scale = if limit != 0.0 { limit.abs() } else { terms };
                e = e.max(if scale > 0.0 {
                    sign * (a - limit) / scale
                } else {
                    -1.0
                });
            }
            e
        }
    }
}

impl Constraint for JointAcceleration {
    fn name(&self) -> String {
        "joint acceleration".into()
    }
    fn dof(&self) -> usize {
        self.hi.len()
    }
    fn write(&self, p: &PathPoint<'_>, out: &mut ConstraintRows) {
        out.intervals(p.dq, p.ddq, &self.lo, &self.hi);
    }
    fn uses_position(&self) -> bool {
        false
    }
    fn diagnose(&self, p: &PathPoint<'_>) -> Option<String> {
        zero_limit_joints("acceleration", &self.lo, &self.hi, p)
    }
    /// The joint acceleration σ′_j·u + σ″_j·x is a quadratic in s: its extremes are at the
    /// ends and at its vertex. Joints whose Bernstein bound is within the limits are not solved
    /// for.
    fn excess_on_cubic(&self, piece: &CubicPiece<'_>, u: f64, x0: f64) -> Option<(f64, f64)> {
        if !piece.is_cubic() {
            return Some(self.excess_quintic(piece, u, x0));
        }
        let h = piece.s1 - piece.s0;
        let mut worst = (f64::NEG_INFINITY, piece.s0);
        for j in 0..self.hi.len() {
            let c = piece.acceleration_quadratic(j, u, x0);
            // Cheap bound first: the Bernstein coefficients (values at both ends and
            // a(0) + a′(0)/2) enclose the quadratic.
            let (a0, a2) = (c[0], c[0] + h * (c[1] + h * c[2]));
            let a1 = a0 + 0.5 * h * c[1];
            let (amin, amax) = (a0.min(a1).min(a2), a0.max(a1).max(a2));
            if amax <= self.hi[j] && amin >= self.lo[j] {
                worst.0 = worst
                    .0
                    .max(enclosed_excess(amin, amax, self.lo[j], self.hi[j]));
                continue;
            }
            let vertex = if c[2] != 0.0 {
                -c[1] / (2.0 * c[2])
            } else {
                0.0
            };
            let candidates = [0.0, h, vertex];
            let n = if vertex > 0.0 && vertex < h { 3 } else { 2 };
            worst_over(
                piece,
                u,
                x0,
                &candidates[..n],
                &mut worst,
                (j, self.excess_at(j, u)),
            );
        }
        Some(worst)
    }
    /// The acceleration σ′_j·u + σ″_j·x is a quadratic in θ = (s − s0)/Δ whose Bernstein
    /// coefficients (its values at both ends, and a(0) + a′(0)/2) are linear in (u, x0) and
    /// bound it; the middle one is written, unless it cannot reach the limits: the rows at s0
    /// bound |u| by U = min over joints k of (max(hi_k, −lo_k) + |σ″_k|·X0)/|σ′_k|, with
    /// x0 ≤ X0 = `x_max[0]`.
    fn hold_on_cubic(
        &self,
        piece: &CubicPiece<'_>,
        x_max: [f64; 2],
        out: &mut ConstraintRows,
    ) -> bool {
        let h = piece.s1 - piece.s0;
        let x0_max = x_max[0];
        let mut u_max = f64::INFINITY;
        for k in 0..self.hi.len() {
            let (d1, d2) = (piece.d1[k].abs(), piece.d2[k].abs());
            if d1 > 0.0 {
                u_max = u_max.min((self.hi[k].max(-self.lo[k]) + d2 * x0_max) / d1);
            }
        }
        if !piece.is_cubic() {
            self.hold_quintic(piece, u_max, x0_max, out);
            return true;
        }
        for j in 0..self.hi.len() {
            let (d1, d2, d3) = (piece.d1[j], piece.d2[j], piece.d3[j]);
            let (a, b) = (d1 + 1.5 * h * d2, d2 + 0.5 * h * d3);
            let reach_hi = a.abs() * u_max + b.max(0.0) * x0_max;
            let reach_lo = -(a.abs() * u_max) + b.min(0.0) * x0_max;
            if reach_hi <= self.hi[j] && reach_lo >= self.lo[j] {
                continue;
            }
            out.interval(a, b, 0.0, self.lo[j], self.hi[j]);
        }
        true
    }
    fn handles_quintic(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bulk_intervals_equal_single_intervals() {
        let a = [1.0, 0.0, -2.0, 0.0, 0.5];
        let b = [0.5, 0.0, 0.0, 3.0, -1.0];
        let lo = [-1.0, -2.0, f64::NEG_INFINITY, -4.0, 0.0];
        let hi = [2.0, 1.0, 3.0, f64::INFINITY, 0.0];
        let mut bulk = ConstraintRows::new();
        bulk.intervals(&a, &b, &lo, &hi);
        let mut one = ConstraintRows::new();
        for j in 0..a.len() {
            one.interval(a[j], b[j], 0.0, lo[j], hi[j]);
        }
        assert_eq!(bulk.half_planes(), one.half_planes());
        assert!(bulk.broken.is_none());
        // A static joint whose range excludes zero cannot hold; a NaN is reported.
        let mut r = ConstraintRows::new();
        r.intervals(&[0.0], &[0.0], &[0.5], &[1.0]);
        assert!(r.broken.is_some());
        let mut r = ConstraintRows::new();
        r.intervals(&[f64::NAN], &[0.0], &[-1.0], &[1.0]);
        assert!(r.broken.is_some());
    }

    #[test]
    fn rows_from_acceleration_and_velocity() {
        let p = PathPoint {
            s: 0.0,
            q: &[0.0, 0.0],
            dq: &[2.0, -1.0],
            ddq: &[0.5, 0.0],
        };
        let mut r = ConstraintRows::new();
        JointVelocity::new(&[-1.0, -3.0], &[4.0, 1.0])
            .unwrap()
            .write(&p, &mut r);
        // joint 1: ṡ ≤ 4/2 = 2; joint 2 moves negatively: ṡ ≤ -3/-1 = 3 → x ≤ 4.
        assert_eq!(r.x_bounds(), (0.0, 4.0));
        let mut r = ConstraintRows::new();
        JointAcceleration::new(&[-1.0, -2.0], &[3.0, f64::INFINITY])
            .unwrap()
            .write(&p, &mut r);
        assert_eq!(
            r.half_planes(),
            &[[2.0, 0.5, 3.0], [-2.0, -0.5, 1.0], [1.0, -0.0, 2.0]]
        );
        assert!(JointVelocity::new(&[0.5], &[1.0]).is_err());
        let e = JointAcceleration::new(&[-1.0], &[f64::NAN]).unwrap_err();
        assert!(e
            .to_string()
            .contains("joint 1 acceleration upper limit = NaN"));
    }

    #[test]
    fn polytope_and_broken_rows() {
        let mut r = ConstraintRows::new();
        // v = (u, x) itself, F = [1 1], g = [2]: u + x ≤ 2.
        r.polytope(&[1.0, 0.0], &[0.0, 1.0], &[0.0, 0.0], &[1.0, 1.0], &[2.0]);
        assert_eq!(r.half_planes(), &[[1.0, 1.0, 2.0]]);
        r.interval(0.0, 0.0, 1.0, -1.0, 0.5);
        assert!(r.broken.is_some());
    }
}
