//! The input of the generator: current state, target state, limits and options.
//!
//! Field names follow Ruckig's `InputParameter`, so that a problem written for Ruckig reads the
//! same here. [`InputParameter`] has a compile-time number of degrees of freedom (arrays, no
//! allocation); [`DynInputParameter`] has a run-time number (vectors, e.g. for the CLI). An
//! infinite limit means unlimited: `max_jerk = ∞` gives second-order (trapezoidal) profiles,
//! `max_acceleration = ∞` first-order (velocity-limited) ones. Minima default to the negated
//! maxima. A zero limit is accepted as in Ruckig: a third-order degree of freedom with a zero
//! jerk or acceleration limit (or a second-order one with zero velocity limits) cannot change
//! its acceleration and coasts ([`super::zero`]).
//!
//! The input types are `#[non_exhaustive]` (build them with `new` and set the fields, so
//! that fields can be added). Ruckig Pro's fields are supported: position limits
//! (`min_position`/`max_position`) and the calculation budget
//! (`options.interrupt_calculation_duration`) are fields of the input; intermediate waypoints
//! with per-section limits and minimum durations are a [`super::Waypoints`] next to it
//! ([`super::plan_waypoints`], which also honours the budget; [`super::Waypoints::validate`]
//! is `validate_input` for them). The JSON reader ([`super::json`]) reads all of them.

pub use super::problem::ControlInterface;
use super::problem::Dof1;
use super::result::OtgError;

/// How the degrees of freedom are coordinated in time.
///
/// `Time`, `TimeIfNecessary`, `Phase` and `None` are Ruckig's modes, with Ruckig's meaning.
/// `StraightLine` is trajkit's own: the fastest motion along the straight line in joint
/// space. Side by side, for boundary states that are collinear (start and target velocity and
/// acceleration parallel to the displacement):
///
/// | mode | duration | path in joint space |
/// |---|---|---|
/// | `Time` | the time-synchronized optimum | any |
/// | `Phase` | the time-synchronized optimum (the same as `Time`) | straight when scaling the limiting DOF's profile onto the others keeps every limit; otherwise `Time`'s motion |
/// | `StraightLine` | the fastest straight-line motion (may be longer than `Time`'s) | always straight |
///
/// For boundary states that are not collinear all three give `Time`'s motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Synchronization {
    /// All degrees of freedom finish at the same time (the default).
    #[default]
    Time,
    /// Only degrees of freedom with a non-zero target velocity or acceleration are synchronized
    /// (with the slowest of all); the others finish as fast as they can.
    TimeIfNecessary,
    /// Ruckig's phase synchronization: the time-synchronized duration, and a straight line in
    /// joint space (every phase-synchronized DOF's profile a scaled copy of the limiting DOF's)
    /// when the boundary states are collinear and the scaled profiles keep every limit;
    /// otherwise the time-synchronized motion.
    Phase,
    /// trajkit's fastest straight-line motion (when the boundary states are collinear): one
    /// path-coordinate problem under every joint's limits. Never shorter than `Time`, and
    /// longer when a straight line costs time. Only as the global mode (not per DOF).
    StraightLine,
    /// Every degree of freedom finishes as fast as it can.
    None,
}

/// Whether the duration must be a multiple of the control period.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DurationDiscretization {
    /// Any duration.
    #[default]
    Continuous,
    /// A multiple of the generator's `delta_time`.
    Discrete,
}

/// The options shared by both input types (the global ones; per-DOF overrides are fields of
/// the input).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct OtgOptions {
    /// Time coordination.
    pub synchronization: Synchronization,
    /// Position or velocity target.
    pub control_interface: ControlInterface,
    /// Continuous or discrete duration.
    pub duration_discretization: DurationDiscretization,
    /// The trajectory lasts at least this long (seconds), if given.
    pub minimum_duration: Option<f64>,
    /// A calculation budget in microseconds (Ruckig Pro's `interrupt_calculation_duration`):
    /// the calculation returns the best valid result it has found when the budget runs out,
    /// or [`super::OtgError::Interrupted`] when it has none yet. See the module
    /// documentation of [`crate::otg`] for what is iterative.
    pub interrupt_calculation_duration: Option<f64>,
}

/// The input with a compile-time number of degrees of freedom.
///
/// ```
/// use trajkit::otg::{InputParameter, Otg};
/// let mut input = InputParameter::<1>::new();
/// input.target_position = [1.0];
/// input.max_velocity = [0.6];
/// input.max_acceleration = [1.0];
/// input.max_jerk = [4.0];
/// let otg = Otg::<1>::new(0.001);
/// let traj = otg.calculate(&input).unwrap();
/// assert!((traj.duration() - 2.516_666_666_666_667).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct InputParameter<const DOF: usize> {
    /// Current position.
    pub current_position: [f64; DOF],
    /// Current velocity.
    pub current_velocity: [f64; DOF],
    /// Current acceleration.
    pub current_acceleration: [f64; DOF],
    /// Target position.
    pub target_position: [f64; DOF],
    /// Target velocity.
    pub target_velocity: [f64; DOF],
    /// Target acceleration.
    pub target_acceleration: [f64; DOF],
    /// Velocity limit (> 0; ∞ = unlimited).
    pub max_velocity: [f64; DOF],
    /// Acceleration limit (> 0; ∞ = first-order profiles).
    pub max_acceleration: [f64; DOF],
    /// Jerk limit (> 0; ∞ = second-order profiles).
    pub max_jerk: [f64; DOF],
    /// Direction-dependent minimum velocity (< 0); `None` = −max_velocity.
    pub min_velocity: Option<[f64; DOF]>,
    /// Direction-dependent minimum acceleration (< 0); `None` = −max_acceleration.
    pub min_acceleration: Option<[f64; DOF]>,
    /// Largest position along the whole motion (Ruckig Pro's `max_position`; ∞ = none).
    pub max_position: [f64; DOF],
    /// Smallest position along the whole motion (Ruckig Pro's `min_position`; −∞ = none).
    pub min_position: [f64; DOF],
    /// Degrees of freedom to plan; a disabled one keeps its current acceleration.
    pub enabled: [bool; DOF],
    /// Per-DOF synchronization, overriding `options.synchronization` (Ruckig's
    /// `per_dof_synchronization`; `StraightLine` is not accepted per DOF).
    pub per_dof_synchronization: Option<[Synchronization; DOF]>,
    /// Per-DOF control interface, overriding `options.control_interface` (Ruckig's
    /// `per_dof_control_interface`).
    pub per_dof_control_interface: Option<[ControlInterface; DOF]>,
    /// Options.
    pub options: OtgOptions,
}

impl<const DOF: usize> Default for InputParameter<DOF> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const DOF: usize> InputParameter<DOF> {
    /// All states zero, all limits infinite (set at least the limits before use), all degrees
    /// of freedom enabled, default options.
    pub fn new() -> Self {
        InputParameter {
            current_position: [0.0; DOF],
            current_velocity: [0.0; DOF],
            current_acceleration: [0.0; DOF],
            target_position: [0.0; DOF],
            target_velocity: [0.0; DOF],
            target_acceleration: [0.0; DOF],
            max_velocity: [f64::INFINITY; DOF],
            max_acceleration: [f64::INFINITY; DOF],
            max_jerk: [f64::INFINITY; DOF],
            min_velocity: None,
            min_acceleration: None,
            max_position: [f64::INFINITY; DOF],
            min_position: [f64::NEG_INFINITY; DOF],
            enabled: [true; DOF],
            per_dof_synchronization: None,
            per_dof_control_interface: None,
            options: OtgOptions::default(),
        }
    }

    pub(crate) fn view(&self) -> InputView<'_> {
        InputView {
            cp: &self.current_position,
            cv: &self.current_velocity,
            ca: &self.current_acceleration,
            tp: &self.target_position,
            tv: &self.target_velocity,
            ta: &self.target_acceleration,
            vmax: &self.max_velocity,
            amax: &self.max_acceleration,
            jmax: &self.max_jerk,
            vmin: self.min_velocity.as_ref().map(|v| &v[..]),
            amin: self.min_acceleration.as_ref().map(|v| &v[..]),
            pmax: &self.max_position,
            pmin: &self.min_position,
            enabled: &self.enabled,
            sync: self.per_dof_synchronization.as_ref().map(|v| &v[..]),
            iface: self.per_dof_control_interface.as_ref().map(|v| &v[..]),
            options: self.options,
            same_lengths: true,
        }
    }
}

/// The input with a run-time number of degrees of freedom; same fields as
/// [`InputParameter`]. Vectors shorter or longer than `current_position` are invalid input.
#[derive(Debug, PartialEq, Default)]
#[non_exhaustive]
pub struct DynInputParameter {
    /// Current position; its length is the number of degrees of freedom.
    pub current_position: Vec<f64>,
    /// Current velocity.
    pub current_velocity: Vec<f64>,
    /// Current acceleration.
    pub current_acceleration: Vec<f64>,
    /// Target position.
    pub target_position: Vec<f64>,
    /// Target velocity.
    pub target_velocity: Vec<f64>,
    /// Target acceleration.
    pub target_acceleration: Vec<f64>,
    /// Velocity limit.
    pub max_velocity: Vec<f64>,
    /// Acceleration limit.
    pub max_acceleration: Vec<f64>,
    /// Jerk limit.
    pub max_jerk: Vec<f64>,
    /// Direction-dependent minimum velocity.
    pub min_velocity: Option<Vec<f64>>,
    /// Direction-dependent minimum acceleration.
    pub min_acceleration: Option<Vec<f64>>,
    /// Largest position (see [`InputParameter::max_position`]).
    pub max_position: Vec<f64>,
    /// Smallest position (see [`InputParameter::min_position`]).
    pub min_position: Vec<f64>,
    /// Degrees of freedom to plan.
    pub enabled: Vec<bool>,
    /// Per-DOF synchronization (see [`InputParameter::per_dof_synchronization`]).
    pub per_dof_synchronization: Option<Vec<Synchronization>>,
    /// Per-DOF control interface (see [`InputParameter::per_dof_control_interface`]).
    pub per_dof_control_interface: Option<Vec<ControlInterface>>,
    /// Options.
    pub options: OtgOptions,
}

impl Clone for DynInputParameter {
    fn clone(&self) -> Self {
        DynInputParameter {
            current_position: self.current_position.clone(),
            current_velocity: self.current_velocity.clone(),
            current_acceleration: self.current_acceleration.clone(),
            target_position: self.target_position.clone(),
            target_velocity: self.target_velocity.clone(),
            target_acceleration: self.target_acceleration.clone(),
            max_velocity: self.max_velocity.clone(),
            max_acceleration: self.max_acceleration.clone(),
            max_jerk: self.max_jerk.clone(),
            min_velocity: self.min_velocity.clone(),
            min_acceleration: self.min_acceleration.clone(),
            max_position: self.max_position.clone(),
            min_position: self.min_position.clone(),
            enabled: self.enabled.clone(),
            per_dof_synchronization: self.per_dof_synchronization.clone(),
            per_dof_control_interface: self.per_dof_control_interface.clone(),
            options: self.options,
        }
    }

    /// Field by field, reusing the vectors' storage: no allocation when `self` already has
    /// as many degrees of freedom (what [`super::DynOtg::update`] relies on).
    fn clone_from(&mut self, source: &Self) {
        self.current_position.clone_from(&source.current_position);
        self.current_velocity.clone_from(&source.current_velocity);
        self.current_acceleration
            .clone_from(&source.current_acceleration);
        self.target_position.clone_from(&source.target_position);
        self.target_velocity.clone_from(&source.target_velocity);
        self.target_acceleration
            .clone_from(&source.target_acceleration);
        self.max_velocity.clone_from(&source.max_velocity);
        self.max_acceleration.clone_from(&source.max_acceleration);
        self.max_jerk.clone_from(&source.max_jerk);
        self.min_velocity.clone_from(&source.min_velocity);
        self.min_acceleration.clone_from(&source.min_acceleration);
        self.max_position.clone_from(&source.max_position);
        self.min_position.clone_from(&source.min_position);
        self.enabled.clone_from(&source.enabled);
        self.per_dof_synchronization
            .clone_from(&source.per_dof_synchronization);
        self.per_dof_control_interface
            .clone_from(&source.per_dof_control_interface);
        self.options = source.options;
    }
}

/// The same problem with a run-time number of degrees of freedom: every field copied
/// (the arrays become vectors of length `DOF`). Allocates; for setting up a [`super::DynOtg`],
/// not for its update loop.
impl<const DOF: usize> From<&InputParameter<DOF>> for DynInputParameter {
    fn from(p: &InputParameter<DOF>) -> Self {
        DynInputParameter {
            current_position: p.current_position.to_vec(),
            current_velocity: p.current_velocity.to_vec(),
            current_acceleration: p.current_acceleration.to_vec(),
            target_position: p.target_position.to_vec(),
            target_velocity: p.target_velocity.to_vec(),
            target_acceleration: p.target_acceleration.to_vec(),
            max_velocity: p.max_velocity.to_vec(),
            max_acceleration: p.max_acceleration.to_vec(),
            max_jerk: p.max_jerk.to_vec(),
            min_velocity: p.min_velocity.map(|v| v.to_vec()),
            min_acceleration: p.min_acceleration.map(|v| v.to_vec()),
            max_position: p.max_position.to_vec(),
            min_position: p.min_position.to_vec(),
            enabled: p.enabled.to_vec(),
            per_dof_synchronization: p.per_dof_synchronization.map(|v| v.to_vec()),
            per_dof_control_interface: p.per_dof_control_interface.map(|v| v.to_vec()),
            options: p.options,
        }
    }
}

impl DynInputParameter {
    /// `dof` degrees of freedom, all zero, limits infinite, all enabled.
    pub fn new(dof: usize) -> Self {
        let z = vec![0.0; dof];
        let inf = vec![f64::INFINITY; dof];
        DynInputParameter {
            current_position: z.clone(),
            current_velocity: z.clone(),
            current_acceleration: z.clone(),
            target_position: z.clone(),
            target_velocity: z.clone(),
            target_acceleration: z,
            max_velocity: inf.clone(),
            max_acceleration: inf.clone(),
            max_jerk: inf,
            min_velocity: None,
            min_acceleration: None,
            max_position: vec![f64::INFINITY; dof],
            min_position: vec![f64::NEG_INFINITY; dof],
            enabled: vec![true; dof],
            per_dof_synchronization: None,
            per_dof_control_interface: None,
            options: OtgOptions::default(),
        }
    }

    /// Number of degrees of freedom.
    pub fn dof(&self) -> usize {
        self.current_position.len()
    }

    /// Ruckig's `validate_input`: the checks a calculation makes before planning (lengths,
    /// options, finite states, signs of the limits, for every DOF), and optionally that the
    /// current (`current_within_limits`) and target (`target_within_limits`) velocity and
    /// acceleration of every enabled DOF lie within `[min, max]` of their limits (a
    /// calculation accepts a current state outside them and brakes first). The first
    /// violation is the error, with the field, the DOF and the value. For a motion through
    /// intermediate waypoints use [`super::Waypoints::validate`], which also checks the
    /// waypoints and per-section fields.
    ///
    /// ```
    /// use trajkit::otg::{DynInputParameter, OtgError};
    /// let mut input = DynInputParameter::new(2);
    /// input.max_velocity = vec![1.0, 1.0];
    /// input.max_acceleration = vec![2.0, 2.0];
    /// input.max_jerk = vec![10.0, 10.0];
    /// input.current_velocity = vec![0.0, 1.5];
    /// assert!(input.validate(0.001, false, true).is_ok());
    /// assert!(matches!(
    ///     input.validate(0.001, true, true),
    ///     Err(OtgError::InvalidInput { dof: Some(1), field: "current_velocity", .. })
    /// ));
    /// ```
    pub fn validate(
        &self,
        delta_time: f64,
        current_within_limits: bool,
        target_within_limits: bool,
    ) -> Result<(), OtgError> {
        let view = self.view();
        view.check_shape(delta_time)?;
        for i in 0..self.dof() {
            let d = view.dof_problem(i)?;
            if !self.enabled[i] {
                continue;
            }
            let states = [
                (
                    current_within_limits,
                    "current_velocity",
                    d.v0,
                    "current_acceleration",
                    d.a0,
                ),
                (
                    target_within_limits,
                    "target_velocity",
                    d.vf,
                    "target_acceleration",
                    d.af,
                ),
            ];
            for (on, fv, v, fa, a) in states {
                if !on {
                    continue;
                }
                if v > d.vmax || v < d.vmin {
                    return Err(bad(i, fv, v, "is outside [min_velocity, max_velocity]"));
                }
                if a > d.amax || a < d.amin {
                    return Err(bad(
                        i,
                        fa,
                        a,
                        "is outside [min_acceleration, max_acceleration]",
                    ));
                }
            }
        }
        Ok(())
    }

    pub(crate) fn view(&self) -> InputView<'_> {
        InputView {
            cp: &self.current_position,
            cv: &self.current_velocity,
            ca: &self.current_acceleration,
            tp: &self.target_position,
            tv: &self.target_velocity,
            ta: &self.target_acceleration,
            vmax: &self.max_velocity,
            amax: &self.max_acceleration,
            jmax: &self.max_jerk,
            vmin: self.min_velocity.as_deref(),
            amin: self.min_acceleration.as_deref(),
            pmax: &self.max_position,
            pmin: &self.min_position,
            enabled: &self.enabled,
            sync: self.per_dof_synchronization.as_deref(),
            iface: self.per_dof_control_interface.as_deref(),
            options: self.options,
            same_lengths: false,
        }
    }
}

/// Borrowed view of either input type.
pub(crate) struct InputView<'a> {
    pub cp: &'a [f64],
    pub cv: &'a [f64],
    pub ca: &'a [f64],
    pub tp: &'a [f64],
    pub tv: &'a [f64],
    pub ta: &'a [f64],
    pub vmax: &'a [f64],
    pub amax: &'a [f64],
    pub jmax: &'a [f64],
    pub vmin: Option<&'a [f64]>,
    pub amin: Option<&'a [f64]>,
    pub pmax: &'a [f64],
    pub pmin: &'a [f64],
    pub enabled: &'a [bool],
    pub sync: Option<&'a [Synchronization]>,
    pub iface: Option<&'a [ControlInterface]>,
    pub options: OtgOptions,
    /// Whether all vectors have the same length by construction (arrays of one compile-time
    /// size): then [`InputView::check_shape`] need not compare them.
    pub same_lengths: bool,
}

const NOT_FINITE: &str = "is not a finite number";
const NOT_POSITIVE: &str = "is not a number ≥ 0 (or infinity)";
const NOT_NEGATIVE: &str = "is not a number ≤ 0 (or -infinity)";
const WRONG_LEN: &str = "is the length of this vector, which differs from the number of DOFs";

fn bad(dof: usize, field: &'static str, value: f64, reason: &'static str) -> OtgError {
    OtgError::InvalidInput {
        dof: Some(dof),
        field,
        value,
        reason,
    }
}

fn bad_global(field: &'static str, value: f64, reason: &'static str) -> OtgError {
    OtgError::InvalidInput {
        dof: None,
        field,
        value,
        reason,
    }
}

impl InputView<'_> {
    /// Number of degrees of freedom.
    pub fn dof(&self) -> usize {
        self.cp.len()
    }

    /// The synchronization of degree of freedom `i` (per DOF, else the global one).
    #[inline]
    pub fn sync_of(&self, i: usize) -> Synchronization {
        self.sync.map_or(self.options.synchronization, |s| s[i])
    }

    /// Whether any degree of freedom uses `mode`.
    pub fn any_sync(&self, mode: Synchronization) -> bool {
        match self.sync {
            None => self.options.synchronization == mode,
            Some(s) => s.contains(&mode),
        }
    }

    /// Checks the lengths and the options.
    #[inline]
    pub fn check_shape(&self, delta_time: f64) -> Result<(), OtgError> {
        let n = self.dof();
        // The common case in plain comparisons; a mismatch is named by `length_error`.
        let same = self.same_lengths
            || self.cv.len() == n
                && self.ca.len() == n
                && self.tp.len() == n
                && self.tv.len() == n
                && self.ta.len() == n
                && self.vmax.len() == n
                && self.amax.len() == n
                && self.jmax.len() == n
                && self.enabled.len() == n
                && self.pmax.len() == n
                && self.pmin.len() == n
                && self.vmin.is_none_or(|v| v.len() == n)
                && self.amin.is_none_or(|a| a.len() == n)
                && self.sync.is_none_or(|s| s.len() == n)
                && self.iface.is_none_or(|c| c.len() == n);
        if !same {
            self.length_error()?;
        }
        if let Some(s) = self.sync {
            if let Some(i) = s.iter().position(|&m| m == Synchronization::StraightLine) {
                return Err(bad(
                    i,
                    "per_dof_synchronization",
                    f64::NAN,
                    "is straight_line, which applies to all DOFs only (options.synchronization)",
                ));
            }
        }
        if let Some(m) = self.options.minimum_duration {
            if !(m.is_finite() && m >= 0.0) {
                return Err(bad_global(
                    "minimum_duration",
                    m,
                    "is not a finite number ≥ 0",
                ));
            }
        }
        if let Some(b) = self.options.interrupt_calculation_duration {
            if !(b.is_finite() && b > 0.0) {
                return Err(bad_global(
                    "interrupt_calculation_duration",
                    b,
                    "is not a positive finite number of microseconds",
                ));
            }
        }
        if self.options.duration_discretization == DurationDiscretization::Discrete
            && !(delta_time.is_finite() && delta_time > 0.0)
        {
            return Err(bad_global(
                "delta_time",
                delta_time,
                "is not a positive finite number",
            ));
        }
        Ok(())
    }

    /// The first vector whose length differs from the number of degrees of freedom, as an
    /// error (in field order).
    #[cold]
    fn length_error(&self) -> Result<(), OtgError> {
        let n = self.dof();
        let lens: [(&'static str, usize); 15] = [
            ("current_velocity", self.cv.len()),
            ("current_acceleration", self.ca.len()),
            ("target_position", self.tp.len()),
            ("target_velocity", self.tv.len()),
            ("target_acceleration", self.ta.len()),
            ("max_velocity", self.vmax.len()),
            ("max_acceleration", self.amax.len()),
            ("max_jerk", self.jmax.len()),
            ("enabled", self.enabled.len()),
            ("max_position", self.pmax.len()),
            ("min_position", self.pmin.len()),
            ("min_velocity", self.vmin.map_or(n, |v| v.len())),
            ("min_acceleration", self.amin.map_or(n, |v| v.len())),
            ("per_dof_synchronization", self.sync.map_or(n, |v| v.len())),
            (
                "per_dof_control_interface",
                self.iface.map_or(n, |v| v.len()),
            ),
        ];
        for (f, l) in lens {
            if l != n {
                return Err(bad_global(f, l as f64, WRONG_LEN));
            }
        }
        Ok(())
    }

    /// The validated problem of degree of freedom `i`.
    #[inline(always)]
    pub fn dof_problem(&self, i: usize) -> Result<Dof1, OtgError> {
        let (vmax, amax, jmax) = (self.vmax[i], self.amax[i], self.jmax[i]);
        let vmin = self.vmin.map_or(-vmax, |v| v[i]);
        let amin = self.amin.map_or(-amax, |v| v[i]);
        let (pmin, pmax) = (self.pmin[i], self.pmax[i]);
        // Finite states, positive maxima, negative minima, positions within the position
        // limits: in plain comparisons without branches for the common case; when one fails,
        // `value_error` names the first offender in the order of the fields.
        let m = f64::MAX;
        let (cp, tp) = (self.cp[i], self.tp[i]);
        let plain = (cp.abs() <= m)
            & (self.cv[i].abs() <= m)
            & (self.ca[i].abs() <= m)
            & (tp.abs() <= m)
            & (self.tv[i].abs() <= m)
            & (self.ta[i].abs() <= m)
            & (vmax >= 0.0)
            & (amax >= 0.0)
            & (jmax >= 0.0)
            & (vmin <= 0.0)
            & (amin <= 0.0)
            & (pmin <= cp)
            & (cp <= pmax)
            & (pmin <= tp)
            & (tp <= pmax);
        if !plain {
            self.value_error(i, vmin, amin)?;
        }
        if self.amax[i].is_infinite() != amin.is_infinite() {
            return Err(bad(
                i,
                "min_acceleration",
                amin,
                "must be infinite exactly when max_acceleration is",
            ));
        }
        let d = Dof1 {
            p0: cp,
            v0: self.cv[i],
            a0: self.ca[i],
            pf: tp,
            vf: self.tv[i],
            af: self.ta[i],
            vmax,
            vmin,
            amax,
            amin,
            jmax,
            interface: self.iface.map_or(self.options.control_interface, |c| c[i]),
            pmin,
            pmax,
        };
        check_target(&d, i)?;
        Ok(d)
    }

    /// The first state that is not finite, maximum that is not positive, minimum that is not
    /// negative or position outside the position limits of degree of freedom `i`, as an error.
    #[cold]
    fn value_error(&self, i: usize, vmin: f64, amin: f64) -> Result<(), OtgError> {
        for (f, v) in [
            ("current_position", self.cp[i]),
            ("current_velocity", self.cv[i]),
            ("current_acceleration", self.ca[i]),
            ("target_position", self.tp[i]),
            ("target_velocity", self.tv[i]),
            ("target_acceleration", self.ta[i]),
        ] {
            if !v.is_finite() {
                return Err(bad(i, f, v, NOT_FINITE));
            }
        }
        for (f, v) in [
            ("max_velocity", self.vmax[i]),
            ("max_acceleration", self.amax[i]),
            ("max_jerk", self.jmax[i]),
        ] {
            if v.is_nan() || v < 0.0 {
                return Err(bad(i, f, v, NOT_POSITIVE));
            }
        }
        if vmin.is_nan() || vmin > 0.0 {
            return Err(bad(i, "min_velocity", vmin, NOT_NEGATIVE));
        }
        if amin.is_nan() || amin > 0.0 {
            return Err(bad(i, "min_acceleration", amin, NOT_NEGATIVE));
        }
        self.position_error(i)
    }

    /// The position limits of degree of freedom `i` that are not numbers, cross each other or
    /// do not hold the current or target position, as an error.
    #[cold]
    fn position_error(&self, i: usize) -> Result<(), OtgError> {
        let (pmin, pmax) = (self.pmin[i], self.pmax[i]);
        if pmax.is_nan() {
            return Err(bad(i, "max_position", pmax, "is not a number"));
        }
        if pmin.is_nan() {
            return Err(bad(i, "min_position", pmin, "is not a number"));
        }
        if pmin > pmax {
            return Err(bad(i, "min_position", pmin, "is above max_position"));
        }
        let outside = "is outside the position limits [min_position, max_position]";
        if !(pmin <= self.cp[i] && self.cp[i] <= pmax) {
            return Err(bad(i, "current_position", self.cp[i], outside));
        }
        let velocity = self.iface.map_or(self.options.control_interface, |c| c[i])
            == ControlInterface::Velocity;
        let target_inside = pmin <= self.tp[i] && self.tp[i] <= pmax;
        if !(velocity || target_inside) {
            return Err(bad(i, "target_position", self.tp[i], outside));
        }
        Ok(())
    }
}

/// The checks that combine a DOF's target with its limits: a target velocity and acceleration
/// that the limits allow to reach, position limits only with the position interface.
#[inline]
fn check_target(d: &Dof1, i: usize) -> Result<(), OtgError> {
    use super::problem::ProfileOrder;
    let order = d.order();
    if d.interface == ControlInterface::Position {
        if order == ProfileOrder::First && (d.vmax.is_infinite() || d.vmin.is_infinite()) {
            return Err(bad(
                i,
                "max_velocity",
                d.vmax,
                "must be finite when the acceleration limit is infinite",
            ));
        }
        if d.vf > d.vmax || d.vf < d.vmin {
            return Err(bad(
                i,
                "target_velocity",
                d.vf,
                "is outside the velocity limits",
            ));
        }
    } else if d.has_position_limits() {
        let (field, value) = if d.pmax < f64::INFINITY {
            ("max_position", d.pmax)
        } else {
            ("min_position", d.pmin)
        };
        return Err(bad(
            i,
            field,
            value,
            "applies to the position interface only (this DOF uses the velocity interface)",
        ));
    }
    if order == ProfileOrder::Third {
        if d.af > d.amax || d.af < d.amin {
            return Err(bad(
                i,
                "target_acceleration",
                d.af,
                "is outside the acceleration limits",
            ));
        }
        // With a_f = 0 this is the target velocity itself, checked above.
        let before = || d.vf - d.af * d.af.abs() / (2.0 * d.jmax);
        if d.interface == ControlInterface::Position
            && d.af != 0.0
            && (before() > d.vmax || before() < d.vmin)
        {
            return Err(bad(
                i,
                "target_acceleration",
                d.af,
                "cannot be reached with the target velocity inside the velocity limits",
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn valid() -> InputParameter<2> {
        let mut p = InputParameter::<2>::new();
        p.max_velocity = [1.0, 2.0];
        p.max_acceleration = [3.0, 4.0];
        p.max_jerk = [5.0, 6.0];
        p.target_velocity = [0.5, -0.5];
        p.target_acceleration = [0.2, -0.3];
        p
    }

    #[test]
    fn the_run_time_sized_input_copies_every_field() {
        let mut p = valid();
        p.current_position = [0.1, 0.2];
        p.current_velocity = [0.3, 0.4];
        p.current_acceleration = [0.5, 0.6];
        p.target_position = [0.7, 0.8];
        p.min_velocity = Some([-0.9, -1.0]);
        p.min_acceleration = Some([-1.1, -1.2]);
        p.max_position = [1.3, 1.4];
        p.min_position = [-1.5, -1.6];
        p.enabled = [true, false];
        p.per_dof_synchronization = Some([Synchronization::None, Synchronization::Phase]);
        p.per_dof_control_interface =
            Some([ControlInterface::Velocity, ControlInterface::Position]);
        p.options.minimum_duration = Some(2.0);
        let d = DynInputParameter::from(&p);
        let mut e = DynInputParameter::new(2);
        e.current_position = vec![0.1, 0.2];
        e.current_velocity = vec![0.3, 0.4];
        e.current_acceleration = vec![0.5, 0.6];
        e.target_position = vec![0.7, 0.8];
        e.target_velocity = vec![0.5, -0.5];
        e.target_acceleration = vec![0.2, -0.3];
        e.max_velocity = vec![1.0, 2.0];
        e.max_acceleration = vec![3.0, 4.0];
        e.max_jerk = vec![5.0, 6.0];
        e.min_velocity = Some(vec![-0.9, -1.0]);
        e.min_acceleration = Some(vec![-1.1, -1.2]);
        e.max_position = vec![1.3, 1.4];
        e.min_position = vec![-1.5, -1.6];
        e.enabled = vec![true, false];
        e.per_dof_synchronization = Some(vec![Synchronization::None, Synchronization::Phase]);
        e.per_dof_control_interface =
            Some(vec![ControlInterface::Velocity, ControlInterface::Position]);
        e.options.minimum_duration = Some(2.0);
        assert_eq!(d, e);
    }

    fn field_of(p: &InputParameter<2>) -> Option<(usize, &'static str)> {
        let v = p.view();
        match v.check_shape(0.001).and_then(|_| {
            for i in 0..2 {
                v.dof_problem(i)?;
            }
            Ok(())
        }) {
            Ok(()) => None,
            Err(OtgError::InvalidInput { dof, field, .. }) => Some((dof.unwrap(), field)),
            Err(e) => panic!("{e}"),
        }
    }

    const FIELDS: [&str; 11] = [
        "current_position",
        "current_velocity",
        "current_acceleration",
        "target_position",
        "target_velocity",
        "target_acceleration",
        "max_velocity",
        "max_acceleration",
        "max_jerk",
        "min_velocity",
        "min_acceleration",
    ];

    /// Makes field `k` (of `FIELDS`) of DOF `i` invalid.
    fn spoil(p: &mut InputParameter<2>, k: usize, i: usize) {
        let not_finite = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY][k % 3];
        let not_signed = [f64::NAN, -1e-300, -1.0][k % 3];
        match k {
            0 => p.current_position[i] = not_finite,
            1 => p.current_velocity[i] = not_finite,
            2 => p.current_acceleration[i] = not_finite,
            3 => p.target_position[i] = not_finite,
            4 => p.target_velocity[i] = not_finite,
            5 => p.target_acceleration[i] = not_finite,
            6 => p.max_velocity[i] = not_signed,
            7 => p.max_acceleration[i] = not_signed,
            8 => p.max_jerk[i] = not_signed,
            9 => p.min_velocity.get_or_insert([-1.0, -2.0])[i] = -not_signed,
            _ => p.min_acceleration.get_or_insert([-3.0, -4.0])[i] = -not_signed,
        }
    }

    #[test]
    fn every_bad_value_is_named_first_in_field_order() {
        assert_eq!(field_of(&valid()), None);
        for (k, &name) in FIELDS.iter().enumerate() {
            for i in 0..2 {
                let mut p = valid();
                spoil(&mut p, k, i);
                assert_eq!(field_of(&p), Some((i, name)));
                // With every later field bad as well, this one is still named.
                for later in k + 1..FIELDS.len() {
                    spoil(&mut p, later, i);
                }
                assert_eq!(field_of(&p), Some((i, name)));
            }
        }
        // The checks that combine limits.
        let mut p = valid();
        p.target_velocity[1] = -2.5;
        assert_eq!(field_of(&p), Some((1, "target_velocity")));
        let mut p = valid();
        p.target_acceleration[0] = 3.5;
        assert_eq!(field_of(&p), Some((0, "target_acceleration")));
        let mut p = valid();
        p.target_velocity[0] = 0.99;
        p.target_acceleration[0] = -2.0;
        assert_eq!(field_of(&p), Some((0, "target_acceleration")));
        p.target_acceleration[0] = 2.0;
        assert_eq!(field_of(&p), None);
        let mut p = valid();
        p.min_acceleration = Some([f64::NEG_INFINITY, -4.0]);
        assert_eq!(field_of(&p), Some((0, "min_acceleration")));
    }

    #[test]
    fn run_time_sizes_are_checked_in_field_order() {
        let mut p = DynInputParameter::new(3);
        assert!(p.view().check_shape(0.001).is_ok());
        p.enabled.pop();
        p.min_acceleration = Some(vec![-1.0; 4]);
        p.max_jerk.push(1.0);
        let field = |p: &DynInputParameter| match p.view().check_shape(0.001) {
            Err(OtgError::InvalidInput { dof, field, .. }) => Some((dof, field)),
            _ => None,
        };
        assert_eq!(field(&p), Some((None, "max_jerk")));
        p.max_jerk.pop();
        assert_eq!(field(&p), Some((None, "enabled")));
        p.enabled.push(true);
        assert_eq!(field(&p), Some((None, "min_acceleration")));
        p.min_acceleration = Some(vec![-1.0; 3]);
        assert_eq!(field(&p), None);
        p.per_dof_synchronization = Some(vec![Synchronization::Phase; 2]);
        assert_eq!(field(&p), Some((None, "per_dof_synchronization")));
        p.per_dof_synchronization = Some(vec![Synchronization::StraightLine; 3]);
        assert_eq!(field(&p), Some((Some(0), "per_dof_synchronization")));
        p.per_dof_synchronization = None;
        p.per_dof_control_interface = Some(vec![ControlInterface::Velocity; 4]);
        assert_eq!(field(&p), Some((None, "per_dof_control_interface")));
    }
}
