//! A calculated trajectory checked against its own input: how far each DOF ends from its
//! target state, and how much of its velocity and acceleration limits it uses.
//!
//! The check reads the profiles exactly (segment boundaries and interior velocity extrema
//! after the brake pre-profile, which is allowed to start beyond the limits), so it is cheap
//! and allocates nothing. Front ends report it next to the result (`trajkit otg`'s
//! `final_error` and `worst_limit_ratio`).

use super::input::{ControlInterface, DynInputParameter};
use super::trajectory::DynTrajectory;

/// What [`check`] found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolutionCheck {
    /// Largest |end − target| over the enabled DOFs: position (position interface only),
    /// velocity, acceleration (third-order DOFs only).
    pub final_error: [f64; 3],
    /// Largest share of a velocity (position interface) or acceleration limit used after the
    /// brake pre-profile; 1.0 is exactly at a limit.
    pub worst_limit_ratio: f64,
    /// Largest distance beyond a position limit (`min_position`/`max_position`) over the
    /// enabled position-interface DOFs, from the profiles' exact position extrema; 0.0 when
    /// every motion stays inside.
    pub position_excess: f64,
}

/// Checks `trajectory` against the `input` it was calculated for (see the module docs).
pub fn check(input: &DynInputParameter, trajectory: &DynTrajectory) -> SolutionCheck {
    let mut e = [0.0f64; 3];
    let mut worst = 0.0f64;
    let mut excess = 0.0f64;
    for (i, d) in trajectory.dofs().iter().enumerate() {
        if !input.enabled[i] {
            continue;
        }
        let p = &d.profile;
        let end = p.end();
        let position = input.options.control_interface == ControlInterface::Position;
        if position {
            e[0] = e[0].max((end.p - input.target_position[i]).abs());
        }
        e[1] = e[1].max((end.v - input.target_velocity[i]).abs());
        if input.max_jerk[i].is_finite() {
            e[2] = e[2].max((end.a - input.target_acceleration[i]).abs());
        }
        let vmax = input.max_velocity[i];
        let vmin = input.min_velocity.as_ref().map_or(-vmax, |m| m[i]);
        let amax = input.max_acceleration[i];
        let amin = input.min_acceleration.as_ref().map_or(-amax, |m| m[i]);
        if position {
            if let Some((lo, _, hi, _)) = trajectory.position_extrema(i) {
                excess = excess
                    .max(hi - input.max_position[i])
                    .max(input.min_position[i] - lo);
            }
        }
        let ratio = |x: f64, hi: f64, lo: f64| if x >= 0.0 { x / hi } else { x / lo };
        let tb = p.brake_duration();
        for k in 0..p.segments() {
            let Some((t0, dur, s, j)) = p.segment(k) else {
                break;
            };
            if t0 + dur <= tb {
                continue;
            }
            let mut vs = [s.v, s.v + dur * (s.a + dur * j / 2.0), s.v];
            if j != 0.0 && -s.a / j > 0.0 && -s.a / j < dur {
                let r = -s.a / j;
                vs[2] = s.v + r * (s.a + r * j / 2.0);
            }
            if position {
                for v in vs {
                    worst = worst.max(ratio(v, vmax, vmin));
                }
            }
            if amax.is_finite() {
                for a in [s.a, s.a + dur * j] {
                    worst = worst.max(ratio(a, amax, amin));
                }
            }
        }
    }
    SolutionCheck {
        final_error: e,
        worst_limit_ratio: worst,
        position_excess: excess,
    }
}
