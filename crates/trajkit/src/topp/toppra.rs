//! TOPP-RA: time-optimal path parameterization by reachability analysis.
//!
//! With state x = ṡ² and control u = s̈, the path velocity evolves between gridpoints as
//! x_{i+1} = x_i + 2Δ_i·u_i (constant s̈ on each interval). Each constraint gives half-planes in
//! (u, x) at every gridpoint ([`crate::topp::Constraint`]). The solver
//! 1. evaluates the path and all constraints at every gridpoint (on paths that are
//!    polynomials of degree ≤ 5 between breakpoints, the path once per piece: σ, σ′, σ″ at the
//!    gridpoints inside a piece come from its Taylor expansion at the piece's midpoint, exact
//!    up to rounding; on pieces of degree 4 or 5 the six derivatives moved to a gridpoint are
//!    kept for the interval starting there while they fit in 16 MB, and beyond that moved
//!    again from the piece's midpoint, or taken from the gridpoint values, when the
//!    between-gridpoint rows and checks ask for them, bitwise the same: see `topp::between`).
//!    A grid that keeps the points of the previous grid of the same solve (the rounds of the
//!    default grid halve or cut its intervals) takes their rows, bounds and Taylor data from
//!    it instead of evaluating them again: the same numbers (while that grid has at most
//!    4096 points, so that holding both grids' data stays within the memory kept between
//!    solves);
//! 2. **backward pass**: from the end set K_N = {ṡ_end²}, computes the controllable sets
//!    K_i = [min, max] of the x from which some admissible u reaches K_{i+1} — two exact
//!    two-variable linear programs per stage (`topp/lp.rs`);
//! 3. **forward pass**: from x_0 = ṡ_start², takes the largest admissible u that stays in
//!    K_{i+1} (a one-variable program: the smallest upper bound);
//! 4. with [`ToppraOptions::refine`] (the default) the limits hold between gridpoints too
//!    (module `topp::between`): on paths that are polynomials of degree ≤ 5 between
//!    breakpoints (trajkit's splines and polylines) each stage also carries the interior
//!    Bernstein coefficients of the joint velocity and acceleration along the interval (rows
//!    linear in (u, x_i)), so the one solve holds them everywhere, and an exact check (closed-
//!    form extrema) covers intervals at breakpoints and collocation; other paths and
//!    constraints are checked at sample points and the grid cut where they are exceeded.
//!
//! Gridpoints ([`Gridpoints`]): by default chosen from a duration tolerance of 1e-4 relative
//! ([`Gridpoints::Auto`]: equal intervals per path piece, halved, then refined where the
//! duration is sensitive; see [`crate::topp::Gridpoints`] and `toppra/auto.rs`), or a uniform
//! count, a chord tolerance, or a given list.
//!
//! Discretization ([`Discretization`]): *interpolation* (default) enforces the constraints of
//! interval i at both s_i and s_{i+1} with the same u_i (x_{i+1} = x_i + 2Δu_i), so the limits
//! hold at every gridpoint for the acceleration actually used on both sides; *collocation*
//! enforces them at s_i only (cheaper, but the acceleration at s_{i+1} within interval i is not
//! checked).
//!
//! Nothing caps ṡ: the only bounds are the constraints. A stretch of path on which no constraint
//! bounds the velocity is reported as an error.
//!
//! # Precision contract
//! - The profile is the exact greedy solution of the discretized problem up to the LP tolerance
//!   (1e-10 relative, to the larger of the next controllable set's top and the problem's scale
//!   of ṡ², the median velocity bound at the gridpoints; so limits of any size, 1e-9 included,
//!   get the same relative precision): at every gridpoint, every constraint holds for the
//!   interval's u on both sides within 1e-9 relative.
//! - Between gridpoints, with [`ToppraOptions::refine`] on (the default):
//!   - on paths that are polynomials of degree ≤ 5 between breakpoints
//!     ([`crate::Path::piecewise_degree`]) with gridpoints at the breakpoints (every grid but
//!     a [`Gridpoints::Given`] one), joint velocity and joint acceleration limits hold on the
//!     whole continuous trajectory within 1e-8 relative, up to rounding: by construction
//!     (Bernstein rows) on intervals between ordinary gridpoints, and by the exact check
//!     ([`crate::topp::Constraint::excess_on_cubic`], tolerance 1e-8, failing intervals get
//!     the rows at their worst point and are solved again) at breakpoints and with
//!     collocation. The tests sample seeded random paths at 10 kHz (50 kHz in the long suite)
//!     with finite differences.
//!   - any other path or constraint (torque, end-effector speed, user constraints) is checked
//!     at each interval's midpoint, its quarters and points approaching both ends
//!     geometrically (down to 4⁻⁷ of its length), and the interval cut into equal parts (as many
//!     as the measured excess calls for, the excess shrinking as Δ²) where a constraint is
//!     exceeded by more than 3e-7 relative, up to [`MAX_REFINE_ROUNDS`] times (and while the
//!     grid stays below [`MAX_REFINED_INTERVALS`] intervals); the tests check 1e-6 relative on
//!     1 ms samples. An interval found within the limits in one round and unchanged in the next
//!     (same ends, ṡ² at both ends within 1e-9 relative) is not checked again.
//! - With `refine` off the excess between gridpoints is O(Δ²) (it shrinks fourfold when N
//!   doubles), except across a kink of the velocity limit curve (where the binding joint
//!   changes), where it is O(Δ).
//! - The duration is the sum of 2Δ_i/(ṡ_i + ṡ_{i+1}). With the limits held everywhere it is never
//!   below the continuous optimum T*, and it converges to it at about first order in the
//!   spacing; the default grid ([`Gridpoints::Auto`], 1e-4) is graded until its first-order
//!   error estimate is within 1e-4, tested against 5·10⁴ and 2·10⁵ uniform intervals
//!   (measured 6.0e-6 to 7.4e-5 above).
//!
//! Repeated solves on one thread reuse the buffers of the previous one (up to 64 MB), so a
//! solve neither grows them step by step nor asks the system for fresh pages.
//!
//! Files: this one holds the options, the problem builder and the passes; `toppra/auto.rs`
//! the rounds of the default grid; `toppra/stage.rs`
//! the stage's half-planes, the greedy step and the record of checked steps; `toppra/explain.rs`
//! the infeasibility diagnostics.

mod auto;
mod explain;
mod stage;

use super::constraint::{Constraint, ConstraintRows, PathPoint};
use super::grid::Gridpoints;
use super::lp::{self, BOX};
use super::parametrized::{Parametrized, PhaseProfile};
use super::rescale::Retimed;
use crate::error::{Error, Result};
use crate::num::clamp_in;
use crate::{Limits, Path};
pub(crate) use stage::{largest_step, CleanSteps, Stage};

/// How constraints are enforced on an interval.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Discretization {
    /// At both ends of each interval with the interval's u (default; safe).
    #[default]
    Interpolation,
    /// At the start of each interval only.
    Collocation,
}

/// Largest number of refinement rounds of [`ToppraOptions::refine`].
pub const MAX_REFINE_ROUNDS: usize = 8;

/// Refinement stops before the grid would exceed this many intervals.
pub const MAX_REFINED_INTERVALS: usize = 1 << 22;

/// Relative excess between gridpoints that triggers refinement.
pub(crate) const REFINE_TOL: f64 = 3e-7;

/// Where each interval is checked (fractions of its length): the midpoint and points
/// approaching both ends geometrically (4⁻¹ … 4⁻⁷ from each end). A constraint active at a
/// gridpoint can be exceeded just inside the interval, in a bump whose peak lies at some
/// distance d from the end; the nearest point between d/4 and d sees at least 7/16 of its height.
pub(crate) const REFINE_POINTS: [f64; 15] = [
    1.0 / 16384.0,
    1.0 / 4096.0,
    1.0 / 1024.0,
    1.0 / 256.0,
    1.0 / 64.0,
    1.0 / 16.0,
    0.25,
    0.5,
    0.75,
    1.0 - 1.0 / 16.0,
    1.0 - 1.0 / 64.0,
    1.0 - 1.0 / 256.0,
    1.0 - 1.0 / 1024.0,
    1.0 - 1.0 / 4096.0,
    1.0 - 1.0 / 16384.0,
];

/// Solver options. `ToppraOptions::default()`: the grid chosen from a 1e-4 duration tolerance
/// ([`Gridpoints::Auto`]), interpolation, rest to rest, limits guaranteed between gridpoints
/// (`refine` on).
#[derive(Debug, Clone, PartialEq)]
pub struct ToppraOptions {
    /// Gridpoints.
    pub gridpoints: Gridpoints,
    /// Discretization scheme.
    pub discretization: Discretization,
    /// Path velocity ṡ at the start (≥ 0).
    pub start_velocity: f64,
    /// Path velocity ṡ at the end (≥ 0).
    pub end_velocity: f64,
    /// Check between gridpoints and refine the grid where a constraint is exceeded.
    pub refine: bool,
}

impl Default for ToppraOptions {
    fn default() -> Self {
        ToppraOptions {
            gridpoints: Gridpoints::Auto { tolerance: 1e-4 },
            discretization: Discretization::Interpolation,
            start_velocity: 0.0,
            end_velocity: 0.0,
            refine: true,
        }
    }
}

/// A TOPP-RA problem: a path, constraints and options.
///
/// ```
/// use trajkit::topp::{LinearPath, Toppra};
/// use trajkit::{Limits, Order, Trajectory};
///
/// let path = LinearPath::new(&[0.0, 0.0, 1.0, 0.5], 2)?;
/// let limits = Limits::uniform(2, 1.0, 2.0, f64::INFINITY)?;
/// let traj = Toppra::with_limits(&path, &limits)?.solve()?;
/// // Straight line, 1D in effect: bang-coast-bang, duration known in closed form.
/// let d = 1.0f64; // joint 1 travel, the binding joint
/// let t = d / 1.0 + 1.0 / 2.0;
/// assert!((traj.duration() - t).abs() < 1e-3);
/// # Ok::<(), trajkit::Error>(())
/// ```
pub struct Toppra<'c, P: Path> {
    path: P,
    constraints: Vec<Box<dyn Constraint + 'c>>,
    options: ToppraOptions,
}

impl<'c, P: Path> Toppra<'c, P> {
    /// A problem on `path` with no constraints yet and default options.
    pub fn new(path: P) -> Self {
        Toppra {
            path,
            constraints: Vec::new(),
            options: ToppraOptions::default(),
        }
    }

    /// A problem on `path` with the velocity and acceleration limits of `limits`.
    pub fn with_limits(path: P, limits: &Limits) -> Result<Self> {
        limits.expect_dof(path.dim(), "the path")?;
        Self::new(path)
            .constraint(super::JointVelocity::from_limits(limits))?
            .constraint(super::JointAcceleration::from_limits(limits))
    }

    /// Adds a constraint (its joint count must equal the path's dimension).
    pub fn constraint(mut self, c: impl Constraint + 'c) -> Result<Self> {
        if c.dof() != self.path.dim() {
            return Err(Error::DimensionMismatch {
                what: format!("{} joint count", c.name()),
                expected: self.path.dim(),
                found: c.dof(),
            });
        }
        self.constraints.push(Box::new(c));
        Ok(self)
    }

    /// Replaces the options.
    pub fn options(mut self, options: ToppraOptions) -> Self {
        self.options = options;
        self
    }

    /// Sets the gridpoints.
    pub fn gridpoints(mut self, g: Gridpoints) -> Self {
        self.options.gridpoints = g;
        self
    }

    /// Sets the path velocities ṡ at start and end.
    pub fn boundary_velocities(mut self, start: f64, end: f64) -> Self {
        self.options.start_velocity = start;
        self.options.end_velocity = end;
        self
    }

    /// The path.
    pub fn path(&self) -> &P {
        &self.path
    }

    /// The options.
    pub fn options_ref(&self) -> &ToppraOptions {
        &self.options
    }

    /// The constraints, in the order they were added.
    pub fn constraints_ref(&self) -> &[Box<dyn Constraint + 'c>] {
        &self.constraints
    }

    /// Gives the path back.
    pub fn into_path(self) -> P {
        self.path
    }

    /// Solves and returns the timing only.
    pub fn solve_profile(&self) -> Result<PhaseProfile> {
        let o = &self.options;
        let (a, b) = self.path.interval();
        crate::error::finite(|| "path interval start".into(), a)?;
        crate::error::finite(|| "path interval end".into(), b)?;
        if b.partial_cmp(&a) != Some(std::cmp::Ordering::Greater) {
            return Err(Error::InvalidValue {
                field: "path interval end".into(),
                value: b,
                reason: "is not above the interval start",
            });
        }
        for (name, v) in [
            ("start path velocity", o.start_velocity),
            ("end path velocity", o.end_velocity),
        ] {
            if !(v >= 0.0 && v.is_finite()) {
                return Err(Error::InvalidValue {
                    field: name.into(),
                    value: v,
                    reason: "is not a finite number >= 0",
                });
            }
        }
        if let Gridpoints::Auto { tolerance } = o.gridpoints {
            return self.solve_auto(tolerance);
        }
        let mut grid = o.gridpoints.points(&self.path)?;
        let mut ws = Workspace::take_spare();
        let x = self.solve_on(&mut ws, &mut grid);
        ws.keep_spare();
        profile_from(grid, x?)
    }

    /// Solves on `grid` (changed where the check between gridpoints cuts intervals); returns
    /// x_i = ṡ_i² at the final gridpoints.
    fn solve_on(&self, ws: &mut Workspace, grid: &mut Vec<f64>) -> Result<Vec<f64>> {
        let refine = self.options.refine;
        ws.reset_between();
        ws.evaluate(&self.path, &self.constraints, grid)?;
        if refine {
            ws.prepare(&self.path, &self.constraints, grid);
        }
        let mut x = Vec::new();
        ws.solve(self, grid, &mut x, None)?;
        if !refine {
            return Ok(x);
        }
        for _ in 0..MAX_REFINE_ROUNDS {
            let c = ws.check_between(
                &self.path,
                &self.constraints,
                grid,
                &x,
                self.options.discretization,
            );
            match c {
                super::between::Check::Clean => return Ok(x),
                super::between::Check::Tightened(lo, hi) => {
                    ws.solve(self, grid, &mut x, Some((lo, hi)))?
                }
                super::between::Check::Split(next) => {
                    *grid = next;
                    ws.evaluate(&self.path, &self.constraints, grid)?;
                    ws.prepare(&self.path, &self.constraints, grid);
                    ws.solve(self, grid, &mut x, None)?;
                }
            }
        }
        Ok(x)
    }

    /// [`Gridpoints::Auto`]: equal intervals per path piece, [`super::grid::AUTO_START`]
    /// first, then every interval halved, then graded rounds that cut the intervals by their
    /// estimated share of the duration error, until the estimates sum to at most
    /// `tolerance`·T (see [`super::grid`] and `toppra/auto.rs`).
    fn solve_auto(&self, tolerance: f64) -> Result<PhaseProfile> {
        crate::error::positive(|| "gridpoint tolerance".into(), tolerance)?;
        let mut ws = Workspace::take_spare();
        let result = self.auto_loop(&mut ws, tolerance);
        ws.keep_spare();
        result
    }

    /// Solves and returns the timed trajectory ξ(t) = σ(s(t)).
    pub fn solve(self) -> Result<Parametrized<P>> {
        let profile = self.solve_profile()?;
        Retimed::new(self.path, profile)
    }
}

/// The profile on `grid` with ṡ² = `x` (negative rounding clamped to 0); both vectors become
/// the profile's.
fn profile_from(grid: Vec<f64>, mut x: Vec<f64>) -> Result<PhaseProfile> {
    for v in &mut x {
        *v = v.max(0.0).sqrt();
    }
    PhaseProfile::from_vecs(grid, x)
}

/// Constraint data at every gridpoint and scratch space.
#[derive(Default)]
pub(super) struct Workspace {
    /// The constraints' data at the gridpoints.
    pub(super) pts: PointData,
    nc: usize,
    /// The problem's scale of x = ṡ² (see [`Workspace::x_scale`]): the LP tolerances are
    /// relative to it, so that a problem whose limits are all multiplied by c > 0 is solved
    /// with the same relative precision (ṡ² scales by c, or c² for velocity limits).
    scale: f64,
    /// Scratch space of [`x_scale`].
    scale_keys: Vec<u64>,
    /// Controllable sets.
    klo: Vec<f64>,
    khi: Vec<f64>,
    pub(super) cr: ConstraintRows,
    /// Intervals found within the limits by the last refinement check.
    pub(super) clean: CleanSteps,
    /// Rows of interior points of the intervals, in (u, x_i) (see the `between` module):
    /// interval i's are `mid[mid_off[i]..mid_off[i + 1]]` (`mid_off` empty: none).
    pub(super) mid: Vec<[f64; 3]>,
    pub(super) mid_off: Vec<usize>,
    /// Rows found by a check round, added to `mid` at its end.
    pub(super) mid_add: Vec<(usize, [f64; 3])>,
    /// The path's Taylor data per interval, for exact checks (see the `between` module).
    pub(super) pieces: super::between::Pieces,
    /// Taylor data of one path piece, for the values at gridpoints.
    anchor: super::between::PieceAnchor,
    /// Per constraint, during a check: whether it is checked at sample points.
    pub(super) sample: Vec<bool>,
    /// Per constraint: whether its sufficient rows were prepared on the exact pieces.
    pub(super) proved: Vec<bool>,
    pub(super) q: Vec<f64>,
    pub(super) dq: Vec<f64>,
    pub(super) ddq: Vec<f64>,
    /// Whether `pts` belong to the current solve; the data of the grid before them and
    /// whether those do (see [`REUSE_POINTS`]).
    this_solve: bool,
    prev: PointData,
    prev_valid: bool,
}

/// The constraints' data at every gridpoint of one grid.
#[derive(Default)]
pub(super) struct PointData {
    /// The grid (kept only while it may be reused, see [`REUSE_POINTS`]).
    grid: Vec<f64>,
    /// Raw half-planes of all gridpoints and constraints, concatenated.
    rows: Vec<[f64; 3]>,
    /// `off[i * (nc + 1) + k]`: start of constraint k's rows at gridpoint i.
    off: Vec<usize>,
    /// Bounds on x per gridpoint, and the constraint that set the upper one.
    xlo: Vec<f64>,
    xhi: Vec<f64>,
    xhi_by: Vec<usize>,
    /// Whether every row at the gridpoint holds at rest (right-hand side ≥ 0).
    rests: Vec<bool>,
    /// σ, σ′, σ″ at every gridpoint (`3·dim` numbers each; σ zero when no constraint reads it).
    pub(super) at_points: Vec<f64>,
}

/// A grid takes the data of the points it shares with the previous grid of the same solve
/// while that grid has at most this many points. Then both grids' data are held (the previous
/// one in `Workspace::prev`); beyond it the second copy would take the workspace kept between
/// solves over [`SPARE_BYTES`] (and every solve would ask for fresh pages), for a gain of a
/// few per cent.
const REUSE_POINTS: usize = 4096;

impl PointData {
    /// Bytes held (roughly).
    fn bytes(&self) -> usize {
        let f = std::mem::size_of::<f64>();
        3 * f * self.rows.capacity()
            + f * (self.grid.capacity()
                + self.off.capacity()
                + self.xlo.capacity()
                + self.xhi.capacity()
                + self.xhi_by.capacity()
                + self.at_points.capacity())
            + self.rests.capacity()
    }
}

/// Largest workspace (bytes, roughly) kept for the next solve on the same thread.
const SPARE_BYTES: usize = 64 << 20;

thread_local! {
    /// The workspace of the last solve on this thread: its buffers (several MB on fine grids)
    /// serve the next solve, which then neither asks the system for fresh pages nor grows them
    /// step by step.
    static SPARE: std::cell::RefCell<Option<Workspace>> = const { std::cell::RefCell::new(None) };
}

impl Workspace {
    /// The spare workspace of this thread (a new one if there is none).
    fn take_spare() -> Workspace {
        let mut ws: Workspace = SPARE
            .try_with(|s| s.borrow_mut().take())
            .ok()
            .flatten()
            .unwrap_or_default();
        // Another problem: its gridpoints' data are not this one's.
        ws.this_solve = false;
        ws.prev_valid = false;
        ws
    }

    /// Keeps this workspace for the next solve on this thread, unless it is very large.
    fn keep_spare(self) {
        let bytes = self.pts.bytes()
            + std::mem::size_of::<[f64; 3]>() * self.mid.capacity()
            + self.prev.bytes()
            + self.pieces.bytes();
        if bytes <= SPARE_BYTES {
            let _ = SPARE.try_with(|s| *s.borrow_mut() = Some(self));
        }
    }
}

/// Whether two controllable-set bounds are the same up to rounding.
fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-13 * a.abs().max(b.abs())
}

/// Stand-in for "no finite bound": velocities beyond this are reported as unbounded.
const X_BIG: f64 = 1e30;

/// The scale of x = ṡ² for the LP tolerances: the median of the positive, finite velocity
/// bounds at the gridpoints (1 when there is none). The median ignores the few huge bounds
/// where the path nearly stops (ṡ unbounded) and the zeros where it must rest; an absolute
/// tolerance instead would be as large as ṡ² itself under tiny limits (ṡ² ~ 1e-12 for a
/// velocity limit of 1e-6) and let the solution exceed them.
///
/// `keys` is scratch space (kept between rounds). The bounds taken are positive and finite,
/// whose bit patterns order as their values do: the selection compares integers.
fn x_scale(xhi: &[f64], keys: &mut Vec<u64>) -> f64 {
    keys.clear();
    keys.extend(
        xhi.iter()
            .filter(|&&v| v > 0.0 && v < X_BIG)
            .map(|v| v.to_bits()),
    );
    if keys.is_empty() {
        return 1.0;
    }
    let mid = keys.len() / 2;
    let (_, m, _) = keys.select_nth_unstable(mid);
    f64::from_bits(*m)
}

impl Workspace {
    fn evaluate<P: Path>(
        &mut self,
        path: &P,
        cons: &[Box<dyn Constraint + '_>],
        grid: &[f64],
    ) -> Result<()> {
        let n = path.dim();
        let nc = cons.len();
        // The current data become the previous grid's when this solve wrote them for a grid
        // small enough (see `REUSE_POINTS`); otherwise they are overwritten. (With three rounds
        // the first and the last write the same buffers, those of the last solve's last round.)
        let reuse = self.this_solve && self.nc == nc;
        self.prev_valid = reuse;
        if reuse {
            std::mem::swap(&mut self.pts, &mut self.prev);
        }
        self.this_solve = false;
        self.nc = nc;
        self.q.resize(n, 0.0);
        self.dq.resize(n, 0.0);
        self.ddq.resize(n, 0.0);
        self.pts.off.clear();
        self.pts.xlo.clear();
        self.pts.xhi.clear();
        self.pts.xhi_by.clear();
        self.pts.rests.clear();
        self.pts.rests.reserve(grid.len());
        self.pts.off.reserve((nc + 1) * grid.len());
        self.pts.xlo.reserve(grid.len());
        self.pts.xhi.reserve(grid.len());
        self.pts.xhi_by.reserve(grid.len());
        // The constraints append straight to the workspace's rows (no copy per gridpoint):
        // lend them to the collector for the pass and take them back afterwards.
        let own = std::mem::replace(&mut self.cr.rows, std::mem::take(&mut self.pts.rows));
        self.cr.rows.clear();
        let result = self.evaluate_rows(path, cons, grid);
        self.pts.rows = std::mem::replace(&mut self.cr.rows, own);
        self.scale = x_scale(&self.pts.xhi, &mut self.scale_keys);
        // Kept for the next grid of this solve when small enough to be reused.
        self.pts.grid.clear();
        if grid.len() <= REUSE_POINTS {
            self.pts.grid.extend_from_slice(grid);
            self.this_solve = result.is_ok();
        }
        result
    }

    /// Takes gridpoint `p` of the previous grid (the same s) as the next gridpoint when its
    /// data are there: its rows, bounds and values, the numbers an evaluation would write.
    /// Returns false (nothing taken) otherwise.
    fn copy_point(&mut self, p: usize, dim: usize, keep: bool) -> bool {
        let nc = self.nc;
        let prev = &self.prev;
        let base = p * (nc + 1);
        let (Some(off), Some(&rests)) = (prev.off.get(base..=base + nc), prev.rests.get(p)) else {
            return false;
        };
        let (lo, hi, by) = (prev.xlo[p], prev.xhi[p], prev.xhi_by[p]);
        let points = if keep {
            &[][..]
        } else {
            match prev.at_points.get(3 * dim * p..3 * dim * (p + 1)) {
                Some(v) => v,
                None => return false,
            }
        };
        if !self.pieces.copy_gridpoint(p, dim) {
            return false;
        }
        let rows = &mut self.cr.rows;
        for k in 0..nc {
            self.pts.off.push(rows.len());
            rows.extend_from_slice(&prev.rows[off[k]..off[k + 1]]);
        }
        self.pts.off.push(rows.len());
        self.pts.rests.push(rests);
        self.pts.xlo.push(lo);
        self.pts.xhi.push(hi);
        self.pts.xhi_by.push(by);
        self.pts.at_points.extend_from_slice(points);
        true
    }

    fn evaluate_rows<P: Path>(
        &mut self,
        path: &P,
        cons: &[Box<dyn Constraint + '_>],
        grid: &[f64],
    ) -> Result<()> {
        let need_q = cons.iter().any(|c| c.uses_position());
        let dim = path.dim();
        self.q.iter_mut().for_each(|v| *v = 0.0);
        self.pts.at_points.clear();
        let breaks = anchor_breaks(path);
        let mut anchor = std::mem::take(&mut self.anchor);
        anchor.reset(dim);
        // Paths of degree 4 or 5: the intervals' Taylor data come from the pieces' anchors.
        let reuse = self.prev_valid;
        let anchored = !breaks.is_empty();
        let keep = (self.pieces).start_gridpoints(path, need_q, anchored, grid.len(), reuse);
        if !keep {
            self.pts.at_points.reserve(3 * dim * grid.len());
        }
        let mut b = 0;
        // Points of the previous grid of this solve keep their data (see `copy_point`).
        let mut old_p = 0;
        for &s in grid {
            while b < breaks.len() && breaks[b] <= s {
                b += 1;
            }
            if reuse {
                let old = &self.prev.grid;
                while old_p < old.len() && old[old_p] < s {
                    old_p += 1;
                }
                if old_p < old.len() && old[old_p] == s && self.copy_point(old_p, dim, keep) {
                    self.reserve_rows(grid.len());
                    continue;
                }
            }
            let inside = b >= 1 && b < breaks.len() && breaks[b - 1] < s;
            let out = [&mut self.q[..], &mut self.dq[..], &mut self.ddq[..]];
            let at = (inside, b);
            let (anchored, full) =
                (self.pieces).eval_gridpoint(&mut anchor, path, &breaks, at, s, out);
            if !anchored {
                if need_q {
                    path.eval(s, 0, &mut self.q);
                }
                path.eval_derivatives(s, &mut self.dq, &mut self.ddq);
            }
            let p = match full {
                // Finite full Taylor data (σ in them only when read): no other check, no copy.
                Some(d) => point_in(s, d, if need_q { &d[..dim] } else { &self.q }),
                None => {
                    check_path_values(s, &self.q, &self.dq, &self.ddq)?;
                    PathPoint {
                        s,
                        q: &self.q,
                        dq: &self.dq,
                        ddq: &self.ddq,
                    }
                }
            };
            if !keep {
                // Read by the cubic pieces' data only (see `between::Pieces`).
                self.pts.at_points.extend_from_slice(p.q);
                self.pts.at_points.extend_from_slice(p.dq);
                self.pts.at_points.extend_from_slice(p.ddq);
            }
            let (mut lo, mut hi, mut by) = (0.0f64, f64::INFINITY, usize::MAX);
            let first = self.cr.rows.len();
            for (k, c) in cons.iter().enumerate() {
                self.pts.off.push(self.cr.rows.len());
                self.cr.clear_bounds();
                c.write(&p, &mut self.cr);
                self.cr.check(&**c, s)?;
                lo = lo.max(self.cr.x_min);
                if self.cr.x_max < hi {
                    hi = self.cr.x_max;
                    by = k;
                }
            }
            self.pts
                .rests
                .push(self.cr.rows[first..].iter().all(|r| r[2] >= 0.0));
            self.pts.off.push(self.cr.rows.len());
            self.reserve_rows(grid.len());
            if lo > hi * (1.0 + 1e-12) {
                return Err(contradiction(s, lo, hi, &cons[by].name()));
            }
            self.pts.xlo.push(lo);
            self.pts.xhi.push(hi.max(lo));
            self.pts.xhi_by.push(by);
        }
        self.anchor = anchor;
        Ok(())
    }

    /// Reserves the rows of a grid of `points` gridpoints once the first gridpoint is written
    /// (every gridpoint usually has as many rows as the first).
    fn reserve_rows(&mut self, points: usize) {
        if self.pts.off.len() == self.nc + 1 {
            let per_point = self.cr.rows.len();
            self.cr.rows.reserve(per_point * points);
        }
    }

    /// [`Workspace::prepare_between`] with the velocity bounds at the gridpoints.
    fn prepare<P: Path>(&mut self, path: &P, cons: &[Box<dyn Constraint + '_>], grid: &[f64]) {
        let xhi = std::mem::take(&mut self.pts.xhi);
        let at_points = std::mem::take(&mut self.pts.at_points);
        self.prepare_between(path, cons, grid, &xhi, &at_points);
        self.pts.xhi = xhi;
        self.pts.at_points = at_points;
    }

    /// Rows of constraint k at gridpoint i.
    fn rows_of(&self, i: usize, k: usize) -> &[[f64; 3]] {
        let base = i * (self.nc + 1);
        &self.pts.rows[self.pts.off[base + k]..self.pts.off[base + k + 1]]
    }

    /// All rows at gridpoint i.
    fn rows_at(&self, i: usize) -> &[[f64; 3]] {
        let base = i * (self.nc + 1);
        &self.pts.rows[self.pts.off[base]..self.pts.off[base + self.nc]]
    }

    /// Rows of interior points of interval i, in (u, x_i).
    pub(super) fn mid_rows(&self, i: usize) -> &[[f64; 3]] {
        match self.mid_off.get(i + 1) {
            Some(&end) => &self.mid[self.mid_off[i]..end],
            None => &[],
        }
    }

    /// The half-planes of stage i in (u, x), restricted to constraint `only` when given.
    fn stage(
        &self,
        i: usize,
        delta: f64,
        disc: Discretization,
        only: Option<usize>,
        khi: f64,
        klo: f64,
    ) -> Stage<'_> {
        let (here, next) = match only {
            Some(k) => (self.rows_of(i, k), self.rows_of(i + 1, k)),
            None => (self.rows_at(i), self.rows_at(i + 1)),
        };
        Stage {
            here,
            next: if disc == Discretization::Interpolation {
                next
            } else {
                &[]
            },
            mid: match only {
                Some(_) => &[],
                None => self.mid_rows(i),
            },
            two_delta: 2.0 * delta,
            khi,
            klo,
        }
    }

    /// Backward and forward passes on `grid`, into `x` (x_i = ṡ_i²). With `changed` =
    /// `Some((lo, hi))`, only the interior rows of intervals lo..=hi changed since `x` was
    /// solved: the backward pass starts at hi and stops below lo where the controllable sets
    /// come out as before, and the forward pass runs from the first point that can differ until
    /// it meets the previous solution again beyond hi.
    fn solve<P: Path>(
        &mut self,
        prob: &Toppra<'_, P>,
        grid: &[f64],
        x: &mut Vec<f64>,
        changed: Option<(usize, usize)>,
    ) -> Result<()> {
        let n = grid.len() - 1;
        let first_k = match changed {
            Some((lo, hi)) if x.len() == n + 1 && self.khi.len() == n + 1 => {
                // x_m can change where K_m did (step m − 1) and beyond interval lo's rows.
                let first_k = self.backward(prob, grid, hi + 1, lo)?;
                first_k.saturating_sub(1).min(lo)
            }
            _ => {
                self.start_backward(prob, grid)?;
                self.backward(prob, grid, n, 0)?;
                x.clear();
                x.resize(n + 1, 0.0);
                0
            }
        };
        let o = &prob.options;
        let x_start = o.start_velocity * o.start_velocity;
        if x_start > self.khi[0] * (1.0 + 1e-9) + 1e-300 || x_start < self.klo[0] * (1.0 - 1e-9) {
            return Err(Error::Infeasible(format!(
                "the start path velocity ṡ = {} is not controllable: from s = {} the path velocity must be in [{}, {}] to meet the constraints and the end velocity",
                o.start_velocity,
                grid[0],
                self.klo[0].sqrt(),
                self.khi[0].sqrt()
            )));
        }
        let settled_after = changed.map_or(n, |(_, hi)| hi);
        self.forward(prob, grid, x, first_k, settled_after)
    }

    /// The end of the backward pass: K_N = {ṡ_end²}.
    fn start_backward<P: Path>(&mut self, prob: &Toppra<'_, P>, grid: &[f64]) -> Result<()> {
        let o = &prob.options;
        let n = grid.len() - 1;
        let x_end = o.end_velocity * o.end_velocity;
        self.klo.clear();
        self.klo.resize(n + 1, 0.0);
        self.khi.clear();
        self.khi.resize(n + 1, 0.0);
        if x_end > self.pts.xhi[n] * (1.0 + 1e-9) || x_end < self.pts.xlo[n] * (1.0 - 1e-9) {
            return Err(Error::Infeasible(format!(
                "the end path velocity ṡ = {} is outside what '{}' allows at s = {} (ṡ ≤ {})",
                o.end_velocity,
                self.name_of(prob, self.pts.xhi_by[n]),
                grid[n],
                self.pts.xhi[n].sqrt()
            )));
        }
        self.klo[n] = x_end;
        self.khi[n] = x_end;
        Ok(())
    }

    /// Controllable sets K_i for i < `top` (K_top must be known). Below `settle`, stops at
    /// the first set that comes out as it was. Returns the lowest index recomputed.
    fn backward<P: Path>(
        &mut self,
        prob: &Toppra<'_, P>,
        grid: &[f64],
        top: usize,
        settle: usize,
    ) -> Result<usize> {
        let disc = prob.options.discretization;
        let incremental = settle > 0;
        let mut hint_max = [BOX, BOX];
        let mut hint_min = [BOX, BOX];
        for i in (0..top).rev() {
            let delta = grid[i + 1] - grid[i];
            let (klo, khi) = (self.klo[i + 1], self.khi[i + 1]);
            let tol = 1e-10 * (self.scale + khi);
            let stage = &self.stage(i, delta, disc, None, khi, klo);
            let xhi = self.pts.xhi[i].min(X_BIG);
            let xlo = self.pts.xlo[i];
            let lo = [(klo - xhi) / (2.0 * delta), xlo];
            let hi = [(khi - xlo) / (2.0 * delta), xhi];
            let best = lp::maximize([0.0, 1.0], stage, lo, hi, hint_max, tol);
            // The lowest controllable velocity is often zero (rest is admissible with u = 0):
            // skip the second program then.
            let rest_ok = xlo == 0.0
                && klo <= 0.0
                && self.pts.rests[i]
                && (disc == Discretization::Collocation || self.pts.rests[i + 1])
                && self.mid_rows(i).iter().all(|r| r[2] >= 0.0);
            let worst = if rest_ok {
                best.map(|_| lp::LpSolution {
                    v: [0.0, 0.0],
                    active: hint_min,
                })
            } else {
                best.and_then(|_| lp::maximize([0.0, -1.0], stage, lo, hi, hint_min, tol))
            };
            let (best, worst) = match (best, worst) {
                (Some(b), Some(w)) => (b, w),
                _ => return Err(self.explain_stage(prob, grid, i)),
            };
            if best.v[1] >= X_BIG * 0.5 {
                return Err(Error::Infeasible(format!(
                    "no constraint bounds the path velocity near s = {} (the path does not move there, or nothing limits it)",
                    grid[i]
                )));
            }
            hint_max = best.active;
            hint_min = worst.active;
            let new_hi =
                clamp_in(best.v[1], xlo, xhi).ok_or_else(|| self.explain_stage(prob, grid, i))?;
            let new_lo = worst.v[1].clamp(xlo, new_hi);
            if incremental && i < settle && same(new_hi, self.khi[i]) && same(new_lo, self.klo[i]) {
                return Ok(i + 1);
            }
            self.khi[i] = new_hi;
            self.klo[i] = new_lo;
        }
        Ok(0)
    }

    /// Forward pass from x_`from` (recomputing x_0 when `from` is 0); stops early, beyond
    /// `settled_after`, where x meets its previous value.
    fn forward<P: Path>(
        &mut self,
        prob: &Toppra<'_, P>,
        grid: &[f64],
        x: &mut [f64],
        from: usize,
        settled_after: usize,
    ) -> Result<()> {
        let o = &prob.options;
        let n = grid.len() - 1;
        let disc = o.discretization;
        if from == 0 {
            let x_start = o.start_velocity * o.start_velocity;
            x[0] = x_start.clamp(self.klo[0], self.khi[0]);
        }
        for i in from..n {
            let delta = grid[i + 1] - grid[i];
            let xi = x[i];
            let next_rows: &[[f64; 3]] = if disc == Discretization::Interpolation {
                self.rows_at(i + 1)
            } else {
                &[]
            };
            let u = largest_step(
                self.rows_at(i),
                next_rows,
                2.0 * delta,
                xi,
                (self.khi[i + 1] - xi) / (2.0 * delta),
            );
            let u = largest_step(self.mid_rows(i), &[], 0.0, xi, u);
            let next = (xi + 2.0 * delta * u).clamp(self.klo[i + 1], self.khi[i + 1]);
            if next <= 0.0 && xi <= 0.0 {
                return Err(self.explain_stall(prob, grid, i));
            }
            let settled = i >= settled_after && next == x[i + 1];
            x[i + 1] = next;
            if settled {
                break;
            }
        }
        Ok(())
    }
}

/// The path point at `s` with σ = `q` and σ′, σ″ from the Taylor data `d` (`6·dim` numbers,
/// block k the k-th derivative).
fn point_in<'a>(s: f64, d: &'a [f64], q: &'a [f64]) -> PathPoint<'a> {
    let dim = q.len();
    PathPoint {
        s,
        q,
        dq: &d[dim..2 * dim],
        ddq: &d[2 * dim..3 * dim],
    }
}

pub(crate) fn check_path_values(s: f64, q: &[f64], dq: &[f64], ddq: &[f64]) -> Result<()> {
    // x·0 is 0 for finite x and NaN otherwise: one branch-free pass in the common case, on
    // four running sums.
    let probe = |v: &[f64]| {
        let mut acc = [0.0; 4];
        for chunk in v.chunks(4) {
            for (a, &x) in acc.iter_mut().zip(chunk) {
                *a += x * 0.0;
            }
        }
        acc[0] + acc[1] + acc[2] + acc[3]
    };
    if probe(q) + probe(dq) + probe(ddq) == 0.0 {
        return Ok(());
    }
    for (name, v) in [
        ("position", q),
        ("first derivative", dq),
        ("second derivative", ddq),
    ] {
        if let Some(j) = v.iter().position(|x| !x.is_finite()) {
            return Err(Error::InvalidValue {
                field: format!("path {name} of joint {} at s = {s}", j + 1),
                value: v[j],
                reason: "is not a finite number",
            });
        }
    }
    Ok(())
}

/// The breakpoints whose pieces [`Workspace::evaluate_rows`] expands from Taylor data: on paths
/// of degree ≤ 5 between breakpoints, points inside a piece take σ, σ′, σ″ from the piece's
/// Taylor data (one path evaluation per piece). Empty (evaluate the path at every gridpoint)
/// for other paths, and for breakpoints out of order (a path breaking its contract).
fn anchor_breaks<P: Path>(path: &P) -> Vec<f64> {
    if path.piecewise_degree().is_none_or(|d| d > 5) {
        return Vec::new();
    }
    let breaks = path.breakpoints();
    if breaks.windows(2).all(|w| w[0] <= w[1]) {
        breaks
    } else {
        Vec::new()
    }
}

/// The error of a gridpoint whose lower velocity bound exceeds the upper one set by `by`.
fn contradiction(s: f64, lo: f64, hi: f64, by: &str) -> Error {
    Error::Infeasible(format!(
        "at s = {s}: the velocity bounds contradict each other (ṡ² ≥ {lo} but ṡ² ≤ {hi} by '{by}')"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// The median found on the bounds' bit patterns is the one of their values (`total_cmp`
    /// selection), with zeros, huge, infinite, NaN and subnormal bounds among them.
    #[test]
    fn x_scale_is_the_median_of_the_finite_positive_bounds() {
        let mut rng = SplitMix64::new(17);
        let mut keys = Vec::new();
        for n in 0..60 {
            let xhi: Vec<f64> = (0..n)
                .map(|_| match (rng.uniform(0.0, 8.0)) as u32 {
                    0 => 0.0,
                    1 => f64::INFINITY,
                    2 => f64::NAN,
                    3 => 2e30,
                    4 => 1e-310 * rng.uniform(0.0, 1.0),
                    _ => 10f64.powf(rng.uniform(-12.0, 12.0)),
                })
                .collect();
            let mut finite: Vec<f64> = xhi
                .iter()
                .copied()
                .filter(|&v| v > 0.0 && v < X_BIG)
                .collect();
            finite.sort_by(f64::total_cmp);
            let want = finite.get(finite.len() / 2).copied().unwrap_or(1.0);
            assert_eq!(
                x_scale(&xhi, &mut keys).to_bits(),
                want.to_bits(),
                "{xhi:?}"
            );
        }
    }
    use crate::spline::{BoundedSpline, CubicSpline};
    use crate::topp::grid::subdivide;

    /// The gridpoint data and interval rows of `fine` after evaluating `coarse` first (its
    /// points reused where `fine` keeps them) and on a fresh workspace.
    fn reused_and_fresh<P: Path>(path: &P, limits: &Limits, coarse: &[f64], fine: &[f64]) {
        let prob = Toppra::with_limits(path, limits).unwrap();
        let cons = prob.constraints_ref();
        let mut reused = Workspace::default();
        reused.evaluate(path, cons, coarse).unwrap();
        reused.prepare(path, cons, coarse);
        reused.evaluate(path, cons, fine).unwrap();
        assert!(reused.prev_valid && reused.prev.grid == coarse);
        reused.prepare(path, cons, fine);
        let mut fresh = Workspace::default();
        fresh.evaluate(path, cons, fine).unwrap();
        fresh.prepare(path, cons, fine);
        assert_eq!(reused.pts.rows, fresh.pts.rows);
        assert_eq!(reused.pts.off, fresh.pts.off);
        assert_eq!(reused.pts.xlo, fresh.pts.xlo);
        assert_eq!(reused.pts.xhi, fresh.pts.xhi);
        assert_eq!(reused.pts.xhi_by, fresh.pts.xhi_by);
        assert_eq!(reused.pts.rests, fresh.pts.rests);
        assert_eq!(reused.pts.at_points, fresh.pts.at_points);
        assert_eq!(reused.pieces.grid_piece, fresh.pieces.grid_piece);
        // The interval rows read the Taylor data kept at the gridpoints.
        assert_eq!(reused.mid, fresh.mid);
        assert_eq!(reused.mid_off, fresh.mid_off);
        assert_eq!(reused.scale, fresh.scale);
    }

    /// A grid that keeps the points of the previous one takes their data from it: the same
    /// numbers as evaluating them again, on cubic and on range-repaired (quintic) splines.
    #[test]
    fn reused_gridpoints_equal_evaluated_ones() {
        let lim = Limits::preset("panda").unwrap();
        let lo: Vec<f64> = lim.joints().iter().map(|j| j.position_min).collect();
        let hi: Vec<f64> = lim.joints().iter().map(|j| j.position_max).collect();
        let mut rng = SplitMix64::new(77);
        let mut quintic = 0;
        for case in 0..12 {
            let n = 4 + case % 4;
            let wp: Vec<f64> = (0..n)
                .flat_map(|_| lim.joints().to_vec())
                .map(|j| rng.uniform(j.position_min + 0.05, j.position_max - 0.05))
                .collect();
            let ss: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
            let natural = CubicSpline::natural(&ss, &wp, 7).unwrap();
            let coarse = Gridpoints::Uniform(30 + case).points(&natural).unwrap();
            let parts: Vec<usize> = (0..coarse.len() - 1)
                .map(|i| 1 + (i * 7 + case) % 4)
                .collect();
            let fine = subdivide(&coarse, &parts);
            reused_and_fresh(&natural, &lim, &coarse, &fine);
            let bounded = BoundedSpline::new(natural.as_ppoly(), &lo, &hi).unwrap();
            if bounded.piecewise_degree() == Some(5) {
                quintic += 1;
                reused_and_fresh(&bounded, &lim, &coarse, &fine);
            }
        }
        assert!(quintic > 0);
    }
}
