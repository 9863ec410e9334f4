//! Torque after the jerk stage: the smallest uniform slow-down that brings the sampled joint
//! torque back within the effort limits.

use crate::error::{Error, Result};
use crate::topp::messy::TorqueModel;
use crate::topp::InverseDynamics;
use crate::topp::Scaled;
use crate::{Limits, Order, Trajectory};

/// Largest uniform time-scale factor tried to bring jerk-bounded output back within torque
/// limits.
pub const MAX_TORQUE_SCALE: f64 = 4.0;

/// Relative torque excess accepted on samples (TOPP-RA's own tolerance between gridpoints).
pub const TORQUE_TOLERANCE: f64 = 1e-6;

/// What the torque check found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorqueReport {
    /// Worst |τ_j| / effort_j over the samples of the final trajectory.
    pub worst: f64,
    /// The joint where it occurs (0-based).
    pub joint: usize,
    /// The uniform slow-down applied after the jerk stage (1 when none was needed).
    pub scale: f64,
}

/// Worst |τ_j| / effort_j over samples at 1 kHz and at `rate` Hz, and the joint where it
/// occurs. A sample count above what a sample table of the trajectory may hold
/// ([`crate::size::check_memory`], 8 + 32·dof bytes a sample) is refused before sampling, so
/// that an absurd duration is an error and not an endless loop.
fn worst_ratio(
    traj: &dyn Trajectory,
    model: &TorqueModel,
    effort: &[f64],
    rate: f64,
) -> Result<(f64, usize)> {
    let n = traj.dof();
    let (mut q, mut qd, mut qdd, mut tau) =
        (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut worst, mut joint) = (0.0_f64, 0);
    let duration = traj.duration();
    for step in [1e-3, 1.0 / rate] {
        if !(step.is_finite() && step > 0.0) {
            continue;
        }
        let count = crate::size::check_memory(
            "torque check sample count (duration / step)",
            (duration / step).ceil(),
            8.0 + 32.0 * n as f64,
            &format!("a sample of {n} joint(s)"),
        )?;
        for k in 0..=count {
            let time = (k as f64 * step).min(duration);
            traj.eval(time, Order::Position, &mut q);
            traj.eval(time, Order::Velocity, &mut qd);
            traj.eval(time, Order::Acceleration, &mut qdd);
            model.torque(&q, &qd, &qdd, &mut tau);
            for j in 0..n {
                let r = tau[j].abs() / effort[j];
                if r > worst || r.is_nan() {
                    worst = if r.is_nan() { f64::INFINITY } else { r };
                    joint = j;
                }
            }
        }
    }
    Ok((worst, joint))
}

/// The smallest uniform time-scale factor k ∈ [1, MAX_TORQUE_SCALE] keeping the sampled torque
/// within the efforts of `limits`, by bisection, and the trajectory slowed by it. Slowing down
/// by k leaves τ = g(q) + (M q̈ + C q̇)/k²: for each path point the torque moves along a segment
/// towards the static torque, so once within the limits it stays within them for every larger
/// k, which makes bisection valid.
pub(crate) fn torque_time_scale(
    traj: Box<dyn Trajectory + Send + Sync>,
    model: &TorqueModel,
    limits: &Limits,
    rate: f64,
) -> Result<(Box<dyn Trajectory + Send + Sync>, TorqueReport)> {
    let mut effort = Vec::with_capacity(limits.dof());
    for (j, jl) in limits.joints().iter().enumerate() {
        match jl.effort {
            Some(e) => effort.push(e),
            None => {
                return Err(Error::MissingLimit {
                    joint: j,
                    name: jl.name.clone(),
                    field: "effort",
                })
            }
        }
    }
    let ok = |r: f64| r <= 1.0 + TORQUE_TOLERANCE;
    let (r1, j1) = worst_ratio(&*traj, model, &effort, rate)?;
    if ok(r1) {
        let report = TorqueReport {
            worst: r1,
            joint: j1,
            scale: 1.0,
        };
        return Ok((traj, report));
    }
    let at = |k: f64| -> Result<(f64, usize)> {
        let s = Scaled::new(&*traj, k)?;
        worst_ratio(&s, model, &effort, rate)
    };
    let (rmax, jmax) = at(MAX_TORQUE_SCALE)?;
    if !ok(rmax) {
        let jl = limits.joint(jmax);
        return Err(Error::CannotHold {
            joint: jmax,
            name: jl.name.clone(),
            field: "effort",
            value: effort[jmax],
            reason: format!(
                "after the jerk stage the torque reaches {r1:.4} × the efforts, and slowing \
                 down {MAX_TORQUE_SCALE}× still leaves {rmax:.4} × here; plan without the jerk \
                 stage or check the efforts"
            ),
        });
    }
    let (mut lo, mut hi, mut best) = (1.0, MAX_TORQUE_SCALE, (rmax, jmax));
    while hi - lo > 1e-4 {
        let mid = 0.5 * (lo + hi);
        let r = at(mid)?;
        if ok(r.0) {
            hi = mid;
            best = r;
        } else {
            lo = mid;
        }
    }
    let report = TorqueReport {
        worst: best.0,
        joint: best.1,
        scale: hi,
    };
    Ok((Box::new(Scaled::new(traj, hi)?), report))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::inverse_dynamics::InverseDynamics;
    use crate::poly::{Degree, PolyMove};
    use std::sync::Arc;

    /// τ = q̈ on one joint.
    struct Inertia;
    impl InverseDynamics for Inertia {
        fn dof(&self) -> usize {
            1
        }
        fn torque(&self, _q: &[f64], _qd: &[f64], qdd: &[f64], tau: &mut [f64]) {
            tau[0] = qdd[0];
        }
    }

    #[test]
    fn an_absurd_duration_is_refused_before_sampling() {
        let model = TorqueModel(Arc::new(Inertia));
        let long = PolyMove::rest_to_rest(Degree::Quintic, &[0.0], &[1.0], 1e12).unwrap();
        match worst_ratio(&long, &model, &[1.0], 100.0) {
            Err(Error::TooLarge { .. }) => {}
            other => panic!("{other:?}"),
        }
        // A second-long move is sampled: its peak acceleration is 10/√3·(1 s)⁻² ≈ 5.77.
        let short = PolyMove::rest_to_rest(Degree::Quintic, &[0.0], &[1.0], 1.0).unwrap();
        let (worst, joint) = worst_ratio(&short, &model, &[1.0], 100.0).unwrap();
        assert_eq!(joint, 0);
        assert!((worst - 10.0 / 3f64.sqrt()).abs() < 1e-3, "{worst}");
    }
}
