//! The calculation budget of a motion through waypoints (`interrupt_calculation_duration`,
//! µs, Ruckig Pro's field): one wall-clock deadline for the whole planning, started before
//! validation.
//!
//! The planner is an anytime algorithm (`plan.rs`): stopping at every waypoint is solved
//! first and kept, then the search improves on it. With a budget every section solve is timed
//! and gets a deadline of its own (so the synchronization's own search and bisection stop in
//! time): all that is left for the reference; for a rating or a section of the final build,
//! what is left less a tail of 5 % of the budget and the measured estimate of what must follow
//! (see the module docs of `otg::waypoints`). The search stops when what is left would not pay
//! for its next step and the build, and a build that does not finish in time falls back to
//! the reference. Only a reference that does not fit is [`OtgError::Interrupted`].

use crate::otg::result::OtgError;
use std::time::{Duration, Instant};

/// A deadline and the budget it came from.
#[derive(Debug, Clone, Copy)]
pub(super) struct Clock {
    start: Instant,
    deadline: Instant,
    us: f64,
}

impl Clock {
    /// A budget of `us` microseconds from now (non-positive or non-finite values are refused
    /// later by validation; they give a deadline of now).
    pub(super) fn start(us: f64) -> Clock {
        let start = Instant::now();
        let secs = (us * 1e-6).clamp(0.0, 1e9);
        let deadline = start
            .checked_add(Duration::try_from_secs_f64(secs).unwrap_or_default())
            .unwrap_or(start);
        Clock {
            start,
            deadline,
            us,
        }
    }

    /// The budget in microseconds.
    pub(super) fn budget_us(&self) -> f64 {
        self.us
    }

    /// Microseconds since the start.
    pub(super) fn elapsed_us(&self) -> f64 {
        self.start.elapsed().as_secs_f64() * 1e6
    }

    /// The budget's own error: [`OtgError::Interrupted`] naming the whole budget (not what
    /// was left of it for one section).
    pub(super) fn interrupted(&self) -> OtgError {
        OtgError::Interrupted { budget_us: self.us }
    }

    /// Microseconds left; [`OtgError::Interrupted`] when none are.
    pub(super) fn left_us(&self) -> Result<f64, OtgError> {
        let now = Instant::now();
        if now >= self.deadline {
            return Err(OtgError::Interrupted { budget_us: self.us });
        }
        Ok((self.deadline - now).as_secs_f64() * 1e6)
    }
}
