//! The phase plane (s, ṡ) of a path-parameterized plan as JSON: `trajkit::plan` computes it
//! ([`trajkit::plan::PhasePlane`]: per rest-to-rest piece the maximum velocity curve, the
//! phase-plane solver's profile and the profile played after the jerk stage); this only
//! translates it (`null` where the maximum velocity curve is unbounded).

use serde::Serialize;

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
    pub mvc: Vec<Option<f64>>,
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

impl From<&trajkit::plan::PhasePlane> for PhasePlane {
    fn from(p: &trajkit::plan::PhasePlane) -> Self {
        PhasePlane {
            pieces: p
                .pieces
                .iter()
                .map(|q| PhasePiece {
                    start_time: q.start_time,
                    s: q.s.clone(),
                    mvc: q.mvc.iter().map(|&v| v.is_finite().then_some(v)).collect(),
                    solver: q.solver.clone(),
                    played: q.played.as_ref().map(|(s, sd)| Played {
                        s: s.clone(),
                        sd: sd.clone(),
                    }),
                })
                .collect(),
        }
    }
}
