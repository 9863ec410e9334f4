//! Planner output as it comes: duplicate waypoints, reversals, corners.
//!
//! [`plan_waypoints`] takes joint-space waypoints straight from a motion planner and returns a
//! time-optimal trajectory through them:
//! 1. consecutive waypoints closer than a tolerance are merged ([`dedup_waypoints`]);
//! 2. the waypoints are split into pieces at *stops* ([`stop_indices`]): exact reversals (the
//!    path turns back on itself, a cusp where the robot must stop) for splines, and every
//!    corner for piecewise-linear paths (a polyline's velocity jumps at a corner);
//! 3. each piece becomes a path ([`PathKind`]: a C² cubic spline parameterized by chord length,
//!    or a polyline) that stays inside the joints' position ranges (see below) and is timed
//!    from rest to rest by TOPP-RA or, with [`PlanOptions::solver`], by numerical integration
//!    ([`crate::topp::ni`]);
//! 4. the pieces are played one after the other ([`Sequence`]).
//!
//! # Position ranges
//! Waypoints outside a joint's range are refused ([`Error::WaypointOutOfRange`]). Between
//! waypoints inside it, a polyline stays inside (a box is convex), but a cubic spline can
//! swing out: a joint that turns around near its limit overshoots the waypoint. Every spline
//! piece therefore goes through [`BoundedSpline`]: its exact per-joint extrema are computed
//! (roots of the derivative) and, where a joint leaves its range, that joint's slope and
//! curvature at the neighbouring waypoints are reduced (quintic Hermite pieces, still C²,
//! still through every waypoint) until it provably stays inside; the other joints keep the
//! spline as it was ([`PiecePath::Bounded`]; [`PiecePath::Cubic`] when nothing had to change).
//! If the reduction leaves the path with (almost) no speed at a waypoint — every joint
//! brought to rest there — the robot stops at that waypoint instead: the piece is split there
//! like at a reversal, and each part is built again.
//!
//! With [`PlanOptions::torque`] set, every piece is also limited in joint torque
//! ([`JointTorque::from_limits`]: `±effort` of `limits`) through the given inverse-dynamics
//! model, e.g. a [`crate::dynamics::SerialChain`] read from a URDF.
//!
//! Nearly collinear waypoints need nothing special. A joint with a zero limit that must move
//! is an [`Error::Infeasible`] naming the joint, and an infeasible problem names the path piece,
//! the position s and the constraint.
//!
//! # Precision contract
//! Each piece carries the precision contract of [`crate::topp::Toppra`]; at piece boundaries
//! the robot is at rest (velocity exactly zero) and the position is the shared waypoint.

use super::constraint::{InverseDynamics, JointTorque};
use super::paths::{check_waypoints, seg_len, LinearPath};
use super::{Parametrized, Toppra, ToppraOptions};
use crate::error::{Error, Result};
use crate::spline::{BoundedSpline, CubicSpline};
use crate::traj::{clamp_time, find_piece};
use crate::{Limits, Order, Path, Trajectory};
use std::sync::Arc;

/// Removes consecutive waypoints within `tol` (Euclidean distance) of the previous kept one.
/// Returns the kept waypoints (row-major) and their indices in the input.
pub fn dedup_waypoints(waypoints: &[f64], dim: usize, tol: f64) -> Result<(Vec<f64>, Vec<usize>)> {
    let count = check_waypoints(waypoints, dim).or_else(|e| match e {
        Error::TooFewWaypoints { .. } if waypoints.len() == dim => Ok(1),
        e => Err(e),
    })?;
    if !(tol >= 0.0 && tol.is_finite()) {
        return Err(Error::InvalidValue {
            field: "duplicate waypoint tolerance".into(),
            value: tol,
            reason: "is not a finite number >= 0",
        });
    }
    let mut out = waypoints[..dim].to_vec();
    let mut kept = vec![0];
    for i in 1..count {
        let last = &out[out.len() - dim..];
        let w = &waypoints[i * dim..(i + 1) * dim];
        let d: f64 = last
            .iter()
            .zip(w)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt();
        if d > tol {
            out.extend_from_slice(w);
            kept.push(i);
        }
    }
    Ok((out, kept))
}

/// Interior waypoint indices where the path must stop: where the turning angle between the
/// incoming and outgoing segments exceeds `max_turn` radians (π − 1e-9 for "exact reversals
/// only", 0 for "every corner"). Waypoints must have no consecutive duplicates.
pub fn stop_indices(waypoints: &[f64], dim: usize, max_turn: f64) -> Vec<usize> {
    let count = waypoints.len() / dim.max(1);
    let mut out = Vec::new();
    for i in 1..count.saturating_sub(1) {
        let (l0, l1) = (seg_len(waypoints, dim, i - 1), seg_len(waypoints, dim, i));
        if l0 == 0.0 || l1 == 0.0 {
            continue;
        }
        let mut dot = 0.0;
        for j in 0..dim {
            let a = waypoints[i * dim + j] - waypoints[(i - 1) * dim + j];
            let b = waypoints[(i + 1) * dim + j] - waypoints[i * dim + j];
            dot += a * b;
        }
        let turn = (dot / (l0 * l1)).clamp(-1.0, 1.0).acos();
        if turn > max_turn {
            out.push(i);
        }
    }
    out
}

/// The geometric path through each piece of waypoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PathKind {
    /// Natural cubic spline (zero curvature at the ends), C², parameterized by chord length.
    #[default]
    NaturalCubic,
    /// Not-a-knot cubic spline, C², parameterized by chord length.
    NotAKnotCubic,
    /// Cubic spline with zero end slopes (the path itself starts and ends at rest), C².
    ClampedCubic,
    /// Straight segments (stops at every corner).
    Linear,
}

impl PathKind {
    /// Parses `natural`, `not-a-knot`, `clamped`, `linear`.
    pub fn parse(name: &str) -> Result<Self> {
        match name {
            "natural" | "cubic" => Ok(PathKind::NaturalCubic),
            "not-a-knot" => Ok(PathKind::NotAKnotCubic),
            "clamped" => Ok(PathKind::ClampedCubic),
            "linear" => Ok(PathKind::Linear),
            _ => Err(Error::Parse {
                location: crate::error::Location {
                    source: "path kind".into(),
                    line: 0,
                    field: String::new(),
                },
                message: format!(
                    "'{name}' is not a path kind (natural, not-a-knot, clamped, linear)"
                ),
            }),
        }
    }
}

/// One piece's path: a spline or a polyline.
#[derive(Debug, Clone)]
pub enum PiecePath {
    /// A cubic spline through the piece's waypoints (it stays inside the position ranges as
    /// it is).
    Cubic(CubicSpline),
    /// The cubic spline repaired to stay inside the position ranges (see the module
    /// documentation); [`BoundedSpline::repairs`] says which joints changed.
    Bounded(BoundedSpline),
    /// A polyline.
    Linear(LinearPath),
}

impl Path for PiecePath {
    fn dim(&self) -> usize {
        match self {
            PiecePath::Cubic(p) => p.dim(),
            PiecePath::Bounded(p) => p.dim(),
            PiecePath::Linear(p) => p.dim(),
        }
    }
    fn interval(&self) -> (f64, f64) {
        match self {
            PiecePath::Cubic(p) => p.interval(),
            PiecePath::Bounded(p) => p.interval(),
            PiecePath::Linear(p) => p.interval(),
        }
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        match self {
            PiecePath::Cubic(p) => p.eval(s, order, out),
            PiecePath::Bounded(p) => p.eval(s, order, out),
            PiecePath::Linear(p) => p.eval(s, order, out),
        }
    }
    fn eval_derivatives(&self, s: f64, first: &mut [f64], second: &mut [f64]) {
        match self {
            PiecePath::Cubic(p) => p.eval_derivatives(s, first, second),
            PiecePath::Bounded(p) => p.eval_derivatives(s, first, second),
            PiecePath::Linear(p) => p.eval_derivatives(s, first, second),
        }
    }
    fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
        match self {
            PiecePath::Cubic(p) => p.eval_many(s, order, out),
            PiecePath::Bounded(p) => p.eval_many(s, order, out),
            PiecePath::Linear(p) => p.eval_many(s, order, out),
        }
    }
    fn eval_many_orders(&self, s: &[f64], out: [&mut [f64]; 4]) {
        match self {
            PiecePath::Cubic(p) => p.eval_many_orders(s, out),
            PiecePath::Bounded(p) => p.eval_many_orders(s, out),
            PiecePath::Linear(p) => p.eval_many_orders(s, out),
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        match self {
            PiecePath::Cubic(p) => p.breakpoints(),
            PiecePath::Bounded(p) => p.breakpoints(),
            PiecePath::Linear(p) => p.breakpoints(),
        }
    }
    fn piecewise_degree(&self) -> Option<usize> {
        match self {
            PiecePath::Cubic(p) => p.piecewise_degree(),
            PiecePath::Bounded(p) => p.piecewise_degree(),
            PiecePath::Linear(p) => p.piecewise_degree(),
        }
    }
}

/// Trajectories played one after the other (each starts where the previous ended).
#[derive(Debug, Clone)]
pub struct Sequence<T: Trajectory> {
    pieces: Vec<T>,
    starts: Vec<f64>,
}

impl<T: Trajectory> Sequence<T> {
    /// At least one piece; all with the same joint count.
    pub fn new(pieces: Vec<T>) -> Result<Self> {
        if pieces.is_empty() {
            return Err(Error::DimensionMismatch {
                what: "trajectory piece count".into(),
                expected: 1,
                found: 0,
            });
        }
        let mut starts = vec![0.0];
        for (k, p) in pieces.iter().enumerate() {
            if p.dof() != pieces[0].dof() {
                return Err(Error::DimensionMismatch {
                    what: format!("trajectory piece {k} joint count"),
                    expected: pieces[0].dof(),
                    found: p.dof(),
                });
            }
            starts.push(starts[k] + p.duration());
        }
        Ok(Sequence { pieces, starts })
    }

    /// The pieces.
    pub fn pieces(&self) -> &[T] {
        &self.pieces
    }

    /// Start time of each piece, then the total duration.
    pub fn boundaries(&self) -> &[f64] {
        &self.starts
    }

    /// The pieces, moved out.
    pub fn into_pieces(self) -> Vec<T> {
        self.pieces
    }
}

impl<T: Trajectory> Trajectory for Sequence<T> {
    fn dof(&self) -> usize {
        self.pieces[0].dof()
    }
    fn duration(&self) -> f64 {
        self.starts[self.starts.len() - 1]
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        let t = clamp_time(t, self.duration());
        let k = find_piece(&self.starts, t);
        self.pieces[k].eval(t - self.starts[k], order, out)
    }

    /// Runs of times in one piece go to that piece's `eval_rows` (in blocks of
    /// 64), shifted as in `eval`.
    fn eval_rows(&self, times: &[f64], mut out: [&mut [f64]; 4]) {
        use crate::traj::{row_block, ROW_BLOCK};
        let (big_t, dof) = (self.duration(), self.dof());
        let mut buf = [0.0; ROW_BLOCK];
        let mut i = 0;
        while i < times.len() {
            let k = find_piece(&self.starts, clamp_time(times[i], big_t));
            let mut m = 0;
            while m < ROW_BLOCK && i + m < times.len() {
                let t = clamp_time(times[i + m], big_t);
                if find_piece(&self.starts, t) != k {
                    break;
                }
                buf[m] = t - self.starts[k];
                m += 1;
            }
            self.pieces[k].eval_rows(&buf[..m], row_block(&mut out, dof, i, i + m));
            i += m;
        }
    }
}

/// A shared inverse-dynamics model, for torque limits in [`PlanOptions::torque`]. Clones share
/// the model; two are equal when they share it.
#[derive(Clone)]
pub struct TorqueModel(pub Arc<dyn InverseDynamics + Send + Sync>);

impl TorqueModel {
    /// Wraps a model.
    pub fn new(dynamics: impl InverseDynamics + Send + Sync + 'static) -> Self {
        TorqueModel(Arc::new(dynamics))
    }
}

impl std::fmt::Debug for TorqueModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "TorqueModel {{ dof: {} }}", self.0.dof())
    }
}

impl PartialEq for TorqueModel {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl InverseDynamics for TorqueModel {
    fn dof(&self) -> usize {
        self.0.dof()
    }
    fn torque(&self, q: &[f64], qd: &[f64], qdd: &[f64], tau: &mut [f64]) {
        self.0.torque(q, qd, qdd, tau)
    }
}

/// Settings of [`plan_waypoints`].
#[derive(Debug, Clone, PartialEq)]
pub struct PlanOptions {
    /// Path through each piece.
    pub kind: PathKind,
    /// Waypoints closer than this (Euclidean, joint units) to the previous one are dropped.
    pub duplicate_tolerance: f64,
    /// Turning angle (radians) above which a spline path stops at a waypoint; the default
    /// π − 1e-6 stops only at (numerically) exact reversals. Linear paths stop at every corner
    /// sharper than 1e-9 rad.
    pub reversal_angle: f64,
    /// TOPP-RA options for each piece (boundary velocities are forced to zero).
    pub toppra: ToppraOptions,
    /// Joint torque limits: when set, each piece is also held within `±effort` of the limits
    /// (every joint needs an `effort`) for this inverse-dynamics model. Default `None`.
    pub torque: Option<TorqueModel>,
    /// How each piece is solved (the problem is the same). Default [`PieceSolver::Toppra`].
    pub solver: PieceSolver,
}

/// The method that times each piece in [`plan_waypoints`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PieceSolver {
    /// TOPP-RA ([`Toppra::solve`]).
    #[default]
    Toppra,
    /// Numerical integration in the phase plane ([`crate::topp::ni::solve`]); the gridpoints
    /// are its initial knots.
    Ni,
}

impl Default for PlanOptions {
    fn default() -> Self {
        PlanOptions {
            kind: PathKind::NaturalCubic,
            duplicate_tolerance: 1e-9,
            reversal_angle: std::f64::consts::PI - 1e-6,
            toppra: ToppraOptions::default(),
            torque: None,
            solver: PieceSolver::Toppra,
        }
    }
}

/// A time-optimal trajectory through messy waypoints (row-major `count × dim`) under the
/// velocity and acceleration limits of `limits` (and the torque limits when
/// [`PlanOptions::torque`] is set). See the module documentation.
///
/// Errors besides the solver's: [`Error::InvalidValue`] when torque limits are asked for and a
/// joint has no effort limit; [`Error::DimensionMismatch`] when the model's joint count differs.
///
/// ```
/// use trajkit::topp::messy::{plan_waypoints, PlanOptions};
/// use trajkit::{Limits, Trajectory};
/// let limits = Limits::uniform(2, 1.0, 2.0, f64::INFINITY)?;
/// // A repeated waypoint and an exact reversal: two rest-to-rest pieces.
/// let w = [0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0];
/// let traj = plan_waypoints(&w, 2, &limits, &PlanOptions::default())?;
/// assert_eq!(traj.pieces().len(), 2);
/// # Ok::<(), trajkit::Error>(())
/// ```
pub fn plan_waypoints(
    waypoints: &[f64],
    dim: usize,
    limits: &Limits,
    options: &PlanOptions,
) -> Result<Sequence<Parametrized<PiecePath>>> {
    let paths = piece_paths(waypoints, dim, limits, options)?;
    time_pieces(paths, limits, options, &mut |_, _| {})
}

/// Times the pieces of [`piece_paths`] as [`plan_waypoints`] does, calling `progress(done,
/// total)` after each piece.
pub fn time_pieces(
    paths: PiecePaths,
    limits: &Limits,
    options: &PlanOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Sequence<Parametrized<PiecePath>>> {
    let kept = paths.kept;
    let total = paths.pieces.len();
    let mut pieces = Vec::with_capacity(total);
    for (p, PiecePlan { from, to, path }) in paths.pieces.into_iter().enumerate() {
        let opts = ToppraOptions {
            start_velocity: 0.0,
            end_velocity: 0.0,
            ..options.toppra.clone()
        };
        let mut problem = Toppra::with_limits(path, limits)?;
        if let Some(model) = &options.torque {
            problem = problem.constraint(JointTorque::from_limits(model.clone(), limits)?)?;
        }
        let problem = problem.options(opts);
        let traj = match options.solver {
            PieceSolver::Toppra => problem.solve(),
            PieceSolver::Ni => super::ni::solve(problem),
        }
        .map_err(|e| in_piece(e, p, kept[from], kept[to]))?;
        pieces.push(traj);
        progress(p + 1, total);
    }
    Sequence::new(pieces)
}

/// Path speed ‖σ′‖ (chord-length units, nominally about 1) below which a waypoint where the
/// range repair slowed every joint becomes a stop.
const MIN_REPAIRED_SPEED: f64 = 1e-3;

/// One rest-to-rest piece of [`piece_paths`].
#[derive(Debug, Clone)]
pub struct PiecePlan {
    /// Its first waypoint (index into [`PiecePaths::waypoints`]).
    pub from: usize,
    /// Its last waypoint.
    pub to: usize,
    /// Its path.
    pub path: PiecePath,
}

/// The waypoints and paths of [`plan_waypoints`] before timing.
#[derive(Debug, Clone)]
pub struct PiecePaths {
    /// The waypoints without consecutive duplicates, row-major.
    pub waypoints: Vec<f64>,
    /// Index in the input of each kept waypoint.
    pub kept: Vec<usize>,
    /// The rest-to-rest pieces, in order.
    pub pieces: Vec<PiecePlan>,
}

/// The rest-to-rest pieces of [`plan_waypoints`] as paths, before timing. Every spline path
/// stays inside the position ranges of `limits` (see the module documentation).
///
/// Errors: [`Error::WaypointOutOfRange`] for a waypoint outside its joint's range (indices of
/// the input); the constructors' errors otherwise.
pub fn piece_paths(
    waypoints: &[f64],
    dim: usize,
    limits: &Limits,
    options: &PlanOptions,
) -> Result<PiecePaths> {
    limits.expect_dof(dim, "the waypoints")?;
    if let Some(model) = &options.torque {
        JointTorque::from_limits(model.clone(), limits)?;
    }
    let (w, kept) = dedup_waypoints(waypoints, dim, options.duplicate_tolerance)?;
    let count = w.len() / dim;
    if count < 2 {
        return Err(Error::TooFewWaypoints {
            needed: 2,
            found: count,
        });
    }
    limits.check_waypoints(&w, Some(&kept))?;
    let max_turn = if options.kind == PathKind::Linear {
        1e-9
    } else {
        options.reversal_angle
    };
    let mut cuts = vec![0];
    cuts.extend(stop_indices(&w, dim, max_turn));
    cuts.push(count - 1);
    let mut paths = Vec::with_capacity(cuts.len() - 1);
    for c in cuts.windows(2) {
        push_piece(&w, dim, c[0], c[1], options.kind, limits, &mut paths)?;
    }
    Ok(PiecePaths {
        waypoints: w,
        kept,
        pieces: paths,
    })
}

/// Builds the path from waypoint `a` to `b` (inclusive) and appends it, split into several
/// pieces where the range repair left the path without speed (see the module documentation).
fn push_piece(
    w: &[f64],
    dim: usize,
    a: usize,
    b: usize,
    kind: PathKind,
    limits: &Limits,
    out: &mut Vec<PiecePlan>,
) -> Result<()> {
    let path = piece_path(&w[a * dim..(b + 1) * dim], dim, kind, limits)?;
    let slow = match &path {
        PiecePath::Bounded(sp) => sp.slow_breaks(MIN_REPAIRED_SPEED),
        _ => Vec::new(),
    };
    if slow.is_empty() {
        out.push(PiecePlan {
            from: a,
            to: b,
            path,
        });
        return Ok(());
    }
    let mut start = a;
    for k in slow.into_iter().map(|k| a + k).chain([b]) {
        push_piece(w, dim, start, k, kind, limits, out)?;
        start = k;
    }
    Ok(())
}

/// Says which piece (0-based `p`, between input waypoints `from` and `to`) an infeasibility
/// belongs to; other errors pass through.
pub(crate) fn in_piece(e: Error, p: usize, from: usize, to: usize) -> Error {
    match e {
        Error::Infeasible(m) => Error::Infeasible(format!(
            "path piece {} (waypoints {from} to {to}): {m}",
            p + 1
        )),
        e => e,
    }
}

fn piece_path(w: &[f64], dim: usize, kind: PathKind, limits: &Limits) -> Result<PiecePath> {
    let count = w.len() / dim;
    if kind == PathKind::Linear {
        return Ok(PiecePath::Linear(LinearPath::new(w, dim)?));
    }
    let mut s = vec![0.0; count];
    for i in 1..count {
        s[i] = s[i - 1] + seg_len(w, dim, i - 1);
    }
    let sp = match kind {
        PathKind::NaturalCubic => CubicSpline::natural(&s, w, dim)?,
        PathKind::NotAKnotCubic => CubicSpline::not_a_knot(&s, w, dim)?,
        PathKind::ClampedCubic => {
            let zero = vec![0.0; dim];
            CubicSpline::clamped(&s, w, dim, &zero, &zero)?
        }
        PathKind::Linear => unreachable!("handled above"),
    };
    let lo: Vec<f64> = limits.joints().iter().map(|j| j.position_min).collect();
    let hi: Vec<f64> = limits.joints().iter().map(|j| j.position_max).collect();
    let bounded = BoundedSpline::new(sp.as_ppoly(), &lo, &hi).map_err(|e| match e {
        Error::OutOfRange {
            joint,
            time,
            value,
            lo,
            hi,
            ..
        } => Error::OutOfRange {
            joint,
            name: limits.joint(joint).name.clone(),
            time,
            value,
            lo,
            hi,
        },
        e => e,
    })?;
    if bounded.repairs().is_empty() {
        Ok(PiecePath::Cubic(sp))
    } else {
        Ok(PiecePath::Bounded(bounded))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dedup_and_stops() {
        let w = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1e-12, 2.0, 0.0, 1.0, 0.0];
        let (d, kept) = dedup_waypoints(&w, 2, 1e-9).unwrap();
        assert_eq!(kept, vec![0, 2, 4, 5]);
        assert_eq!(d.len(), 8);
        // 0 → 1 → 2 → 1 on a line: a reversal at index 2 only.
        assert_eq!(stop_indices(&d, 2, std::f64::consts::PI - 1e-6), vec![2]);
        // A right-angle corner is a stop for a polyline only.
        let c = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0];
        assert_eq!(stop_indices(&c, 2, 1e-9), vec![1]);
        assert!(stop_indices(&c, 2, std::f64::consts::PI - 1e-6).is_empty());
        assert!(dedup_waypoints(&w, 2, -1.0).is_err());
        assert!(PathKind::parse("bogus")
            .unwrap_err()
            .to_string()
            .contains("bogus"));
    }
}
