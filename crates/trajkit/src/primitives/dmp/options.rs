//! What a rollout can change: new start, goal, τ, goal changes and filter, coupling terms
//! (obstacle avoidance or any closure) and phase stopping.

use crate::error::{Error, Result};

/// A goal change during execution: from time `t` on, the goal target is `goal`.
#[derive(Debug, Clone, PartialEq)]
pub struct GoalChange {
    /// Time (seconds from the start of the rollout).
    pub t: f64,
    /// New goal, one entry per joint.
    pub goal: Vec<f64>,
}

/// A coupling term of the transformation system: given time `t` (s), position `y` and velocity
/// `ẏ` (per second), it adds its acceleration-level contribution `C` (same units as `τ² ÿ`) to
/// `out`. Closures `Fn(f64, &[f64], &[f64], &mut [f64])` implement it, and so does
/// [`ObstacleAvoidance`].
pub trait CouplingTerm {
    /// Adds `C(t, y, ẏ)` to `out`.
    fn add(&self, t: f64, y: &[f64], yd: &[f64], out: &mut [f64]);
}

impl<F: Fn(f64, &[f64], &[f64], &mut [f64])> CouplingTerm for F {
    fn add(&self, t: f64, y: &[f64], yd: &[f64], out: &mut [f64]) {
        self(t, y, yd, out)
    }
}

/// A borrowed coupling term, as stored in [`RolloutOptions`].
pub type Coupling<'a> = &'a dyn CouplingTerm;

/// Obstacle avoidance for 2- or 3-dimensional DMPs (Hoffmann et al. 2009): for each point
/// obstacle `o`, with `r = o − y` and `φ` the angle between `r` and `ẏ`,
/// `C = γ · R ẏ · φ · exp(−β φ)` where `R` turns `ẏ` by 90° away from the obstacle, in the
/// plane of `r` and `ẏ`. Defaults `γ = 1000`, `β = 20/π`. Adds nothing when `ẏ = 0` or `y`
/// is on the obstacle.
#[derive(Debug, Clone, PartialEq)]
pub struct ObstacleAvoidance {
    dim: usize,
    obstacles: Vec<f64>,
    /// Gain γ.
    pub gamma: f64,
    /// Angular decay β.
    pub beta: f64,
}

impl ObstacleAvoidance {
    /// Point obstacles, row-major `count × dim` with `dim` 2 or 3.
    pub fn new(obstacles: &[f64], dim: usize) -> Result<Self> {
        if !(dim == 2 || dim == 3) {
            return Err(Error::DimensionMismatch {
                what: "obstacle avoidance dimension (2 or 3)".into(),
                expected: 3,
                found: dim,
            });
        }
        if obstacles.len() % dim != 0 {
            return Err(Error::DimensionMismatch {
                what: format!("obstacle coordinates (a multiple of {dim})"),
                expected: (obstacles.len() / dim + 1) * dim,
                found: obstacles.len(),
            });
        }
        for (i, &v) in obstacles.iter().enumerate() {
            crate::error::finite(|| format!("obstacle {} coordinate {}", i / dim, i % dim), v)?;
        }
        Ok(ObstacleAvoidance {
            dim,
            obstacles: obstacles.to_vec(),
            gamma: 1000.0,
            beta: 20.0 / std::f64::consts::PI,
        })
    }
}

impl CouplingTerm for ObstacleAvoidance {
    fn add(&self, _t: f64, y: &[f64], yd: &[f64], out: &mut [f64]) {
        let d = self.dim;
        let v = [yd[0], yd[1], if d == 3 { yd[2] } else { 0.0 }];
        let vn = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if vn == 0.0 {
            return;
        }
        for o in self.obstacles.chunks_exact(d) {
            let r = [
                o[0] - y[0],
                o[1] - y[1],
                if d == 3 { o[2] - y[2] } else { 0.0 },
            ];
            let rn = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
            if rn == 0.0 {
                continue;
            }
            let cos = ((r[0] * v[0] + r[1] * v[1] + r[2] * v[2]) / (rn * vn)).clamp(-1.0, 1.0);
            let phi = cos.acos();
            // Unit vector in the plane of r and v, perpendicular to v, pointing away from r.
            let mut p = [0.0; 3];
            let along = (r[0] * v[0] + r[1] * v[1] + r[2] * v[2]) / (vn * vn);
            for k in 0..3 {
                p[k] = -(r[k] - along * v[k]);
            }
            let pn = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            if pn == 0.0 {
                // Heading straight at (or away from) the obstacle: turn in a fixed direction.
                p = if v[0].abs() < 0.9 * vn {
                    [0.0, -v[2], v[1]]
                } else {
                    [-v[1], v[0], 0.0]
                };
                let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                if n == 0.0 {
                    continue;
                }
                p.iter_mut().for_each(|x| *x /= n);
            } else {
                p.iter_mut().for_each(|x| *x /= pn);
            }
            let mag = self.gamma * vn * phi * (-self.beta * phi).exp();
            for k in 0..d {
                out[k] += mag * p[k];
            }
        }
    }
}

/// Options of [`Dmp::rollout`](super::Dmp::rollout). Every field defaults to "as demonstrated".
#[derive(Clone, Default)]
pub struct RolloutOptions<'a> {
    /// New start position y₀ (default: the demonstration's).
    pub start: Option<Vec<f64>>,
    /// Start velocity, per second (default: the demonstration's initial velocity).
    pub start_velocity: Option<Vec<f64>>,
    /// New goal g (default: the demonstration's end).
    pub goal: Option<Vec<f64>>,
    /// New temporal scale τ in seconds (default: the demonstration's duration).
    pub tau: Option<f64>,
    /// Rollout duration in seconds (default: τ).
    pub duration: Option<f64>,
    /// Integration steps per τ (default 500).
    pub steps_per_tau: Option<usize>,
    /// Goal changes during execution, applied at the first integration step at or after `t`.
    pub goal_changes: Vec<GoalChange>,
    /// Goal filter gain α_g: the goal follows its target by `τ ġ = α_g (g_target − g)`. `None`
    /// switches the goal instantly.
    pub goal_filter: Option<f64>,
    /// Extra acceleration-level coupling term (obstacles, user feedback, ...).
    pub coupling: Option<Coupling<'a>>,
    /// Phase stopping: the phase slows down while the actual position lags the DMP's.
    pub phase_stop: Option<PhaseStop<'a>>,
}

/// The measured position for [`PhaseStop`]: `(t, y, ỹ_out)`.
pub type ActualPosition<'a> = &'a dyn Fn(f64, &[f64], &mut [f64]);

/// Phase stopping (Ijspeert et al. 2013): `τ ẋ = −α_x x / (1 + α_px ‖ỹ − y‖²)`, with `ỹ` the
/// actual (measured) position, so the movement waits while the robot cannot follow.
#[derive(Clone, Copy)]
pub struct PhaseStop<'a> {
    /// Gain α_px (1/position²).
    pub gain: f64,
    /// Writes the actual position `ỹ` at time `t` given the DMP's position `y`:
    /// `(t, y, ỹ_out)`.
    pub actual: ActualPosition<'a>,
}

impl std::fmt::Debug for PhaseStop<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PhaseStop")
            .field("gain", &self.gain)
            .finish()
    }
}

impl std::fmt::Debug for RolloutOptions<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RolloutOptions")
            .field("start", &self.start)
            .field("start_velocity", &self.start_velocity)
            .field("goal", &self.goal)
            .field("tau", &self.tau)
            .field("duration", &self.duration)
            .field("steps_per_tau", &self.steps_per_tau)
            .field("goal_changes", &self.goal_changes)
            .field("goal_filter", &self.goal_filter)
            .field("coupling", &self.coupling.is_some())
            .field("phase_stop", &self.phase_stop)
            .finish()
    }
}
