//! The phase plane (s, ṡ) of a path-parameterized plan: per rest-to-rest piece, the maximum
//! velocity curve (`trajkit::topp::mvc`), the phase-plane solver's profile, and the profile
//! actually played after the jerk stage.

use super::error::{ApiError, ApiResult};
use serde::Serialize;
use trajkit::topp::jerk::JerkLimited;
use trajkit::topp::messy::Sequence;
use trajkit::topp::mvc::max_velocity_curve;
use trajkit::topp::{Parametrized, TimeLaw, Toppra};
use trajkit::{Limits, Path};

/// Largest number of points per curve and piece sent to the page.
const POINTS: usize = 400;

/// The phase plane of every piece.
#[derive(Debug, Serialize)]
pub struct PhasePlane {
    /// One entry per rest-to-rest piece (the robot stops between pieces).
    pub pieces: Vec<PhasePiece>,
}

/// One piece's curves; s is the piece's own path parameter (arc length of the path for
/// trajkit's splines and blends), ṡ in its units per second.
#[derive(Debug, Serialize)]
pub struct PhasePiece {
    /// Start time of the piece in the trajectory, seconds.
    pub start_time: f64,
    /// Path parameters of `mvc` and `solver` (a subset of the solver's gridpoints).
    pub s: Vec<f64>,
    /// The maximum velocity curve ṡ_max(s) (`null` where unbounded).
    pub mvc: Vec<f64>,
    /// The solver's ṡ at `s` (TOPP-RA, NI or TOTG).
    pub solver: Vec<f64>,
    /// The played profile after the jerk stage, when there is one: (s, ṡ) pairs.
    pub played: Option<Played>,
}

/// The profile after the jerk stage, sampled in time.
#[derive(Debug, Serialize)]
pub struct Played {
    /// Path parameter.
    pub s: Vec<f64>,
    /// Path velocity.
    pub sd: Vec<f64>,
}

/// The phase plane of `raw` (and of its jerk-bounded version `played`).
pub fn phase_plane<P: Path + Clone>(
    raw: &Sequence<Parametrized<P>>,
    played: Option<&Sequence<JerkLimited<P>>>,
    limits: &Limits,
) -> ApiResult<PhasePlane> {
    let lib = |e| ApiError::from_lib("phase_plane", e);
    let mut pieces = Vec::with_capacity(raw.pieces().len());
    let starts = match played {
        Some(p) => p.boundaries(),
        None => raw.boundaries(),
    };
    for (k, piece) in raw.pieces().iter().enumerate() {
        let law = piece.law();
        let grid = law.gridpoints();
        let step = grid.len().div_ceil(POINTS).max(1);
        let mut idx: Vec<usize> = (0..grid.len()).step_by(step).collect();
        if idx.last() != Some(&(grid.len() - 1)) {
            idx.push(grid.len() - 1);
        }
        let s: Vec<f64> = idx.iter().map(|&i| grid[i]).collect();
        let solver = idx.iter().map(|&i| law.velocities()[i]).collect();
        let problem = Toppra::with_limits(piece.path().clone(), limits).map_err(lib)?;
        let mvc = max_velocity_curve(&problem, &s).map_err(lib)?;
        let played = played.map(|seq| {
            let p = &seq.pieces()[k];
            let (inner, factor) = (p.inner().law(), p.factor());
            let d = inner.duration();
            let (mut ss, mut sd) = (Vec::with_capacity(POINTS), Vec::with_capacity(POINTS));
            for m in 0..POINTS {
                let v = inner.eval(d * m as f64 / (POINTS - 1) as f64);
                ss.push(v[0]);
                sd.push(v[1] / factor);
            }
            Played { s: ss, sd }
        });
        pieces.push(PhasePiece {
            start_time: starts[k],
            s,
            mvc,
            solver,
            played,
        });
    }
    Ok(PhasePlane { pieces })
}
