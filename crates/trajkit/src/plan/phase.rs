//! The phase plane (s, ṡ) of a path-parameterized plan, for pictures: per rest-to-rest piece,
//! the maximum velocity curve ([`crate::topp::max_velocity_curve`]), the phase-plane
//! solver's profile at (a subset of) its gridpoints, and the profile actually played after the
//! jerk stage.
//!
//! Asked for with [`super::PlanOptions::phase_plane`]; methods that do not parameterize a path
//! (`poly`) have none. Start times and played path velocities are those of the final
//! trajectory (after torque and check slow-downs); the solver's profile is the method's own
//! result, before any of them.

use crate::error::Result;
use crate::topp::jerk::JerkLimited;
use crate::topp::max_velocity_curve;
use crate::topp::messy::Sequence;
use crate::topp::{Parametrized, TimeLaw, Toppra};
use crate::{Limits, Path};

/// Largest number of points per curve and piece.
pub const PHASE_POINTS: usize = 400;

/// The phase plane of every rest-to-rest piece of a plan.
#[derive(Debug, Clone, PartialEq)]
pub struct PhasePlane {
    /// One entry per rest-to-rest piece (the robot stops between pieces).
    pub pieces: Vec<PhasePiece>,
}

/// One piece's curves. `s` is the piece's own path parameter (arc length of the path for
/// trajkit's splines and blends), ṡ is in its units per second.
#[derive(Debug, Clone, PartialEq)]
pub struct PhasePiece {
    /// Start time of the piece in the final trajectory, seconds.
    pub start_time: f64,
    /// Path parameters of `mvc` and `solver` (at most [`PHASE_POINTS`] of the solver's
    /// gridpoints, the last one included).
    pub s: Vec<f64>,
    /// The maximum velocity curve ṡ_max(s); `f64::INFINITY` where nothing bounds it.
    pub mvc: Vec<f64>,
    /// The method's own ṡ at `s` (TOPP-RA, NI or TOTG), before the jerk stage.
    pub solver: Vec<f64>,
    /// The profile played after the jerk stage, sampled evenly in time: `(s, ṡ)`; `None` when
    /// no jerk stage changed the solver's profile.
    pub played: Option<(Vec<f64>, Vec<f64>)>,
}

/// The solver's profiles and maximum velocity curves of `raw`.
pub(crate) fn of_raw<P: Path + Clone>(
    raw: &Sequence<Parametrized<P>>,
    limits: &Limits,
) -> Result<PhasePlane> {
    let mut pieces = Vec::with_capacity(raw.pieces().len());
    for (k, piece) in raw.pieces().iter().enumerate() {
        let law = piece.law();
        let grid = law.gridpoints();
        let step = grid.len().div_ceil(PHASE_POINTS).max(1);
        let mut idx: Vec<usize> = (0..grid.len()).step_by(step).collect();
        if idx.last() != Some(&(grid.len() - 1)) {
            idx.push(grid.len() - 1);
        }
        let s: Vec<f64> = idx.iter().map(|&i| grid[i]).collect();
        let solver = idx.iter().map(|&i| law.velocities()[i]).collect();
        let problem = Toppra::with_limits(piece.path().clone(), limits)?;
        let mvc = max_velocity_curve(&problem, &s)?;
        pieces.push(PhasePiece {
            start_time: raw.boundaries()[k],
            s,
            mvc,
            solver,
            played: None,
        });
    }
    Ok(PhasePlane { pieces })
}

/// Adds the jerk-bounded profiles of `played` (piece by piece the same pieces).
pub(crate) fn add_played<P: Path + Clone>(
    plane: &mut PhasePlane,
    played: &Sequence<JerkLimited<P>>,
) {
    for (k, piece) in plane.pieces.iter_mut().enumerate() {
        let p = &played.pieces()[k];
        let (inner, factor) = (p.inner().law(), p.factor());
        let d = inner.duration();
        let (mut s, mut sd) = (
            Vec::with_capacity(PHASE_POINTS),
            Vec::with_capacity(PHASE_POINTS),
        );
        for m in 0..PHASE_POINTS {
            let v = inner.eval(d * m as f64 / (PHASE_POINTS - 1) as f64);
            s.push(v[0]);
            sd.push(v[1] / factor);
        }
        piece.start_time = played.boundaries()[k];
        piece.played = Some((s, sd));
    }
}

/// Applies a uniform slow-down by `k` of the whole trajectory (torque, final check).
pub(crate) fn slow_down(plane: &mut PhasePlane, k: f64) {
    if k == 1.0 {
        return;
    }
    for piece in &mut plane.pieces {
        piece.start_time *= k;
        match &mut piece.played {
            Some((_, sd)) => sd.iter_mut().for_each(|v| *v /= k),
            None => {
                // The solver's profile is the method's own; the played one is it, slowed.
                let sd = piece.solver.iter().map(|v| v / k).collect();
                piece.played = Some((piece.s.clone(), sd));
            }
        }
    }
}
