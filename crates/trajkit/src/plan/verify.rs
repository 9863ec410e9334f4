//! The last step of [`super::plan`]: the samples that will be written are checked exactly as
//! `trajkit check` checks them, and nothing that fails is returned. Sampling and checking run
//! in one pass, block by block ([`crate::check::sample_and_check`]): the same table and the
//! same report as sampling first and checking the table after.

use crate::check::{sample_and_check, LimitReport, Tolerance};
use crate::error::{Error, Result};
use crate::sample::SampleTable;
use crate::topp::Scaled;
use crate::{Limits, Trajectory};

/// How many times the final check may slow the trajectory down before giving up.
const MAX_GUARD_ROUNDS: usize = 4;

/// The trajectory's samples at `rate` (named), their check against `limits`, and the uniform
/// slow-down the check needed (1 when none). A velocity, acceleration or jerk excess beyond
/// the check's tolerance (sampled values between a planner's own checks: rounding-level) is
/// removed by slowing down uniformly by the factor the ratios call for (k = max(r_v, √r_a,
/// ∛r_j) over pointwise and finite-difference ratios) and sampling again; a position excess
/// cannot be removed by timing and is an [`Error::OutOfRange`]; an excess left after
/// [`MAX_GUARD_ROUNDS`] rounds is an [`Error::LimitExceeded`].
pub(crate) fn verified_samples(
    mut traj: Box<dyn Trajectory + Send + Sync>,
    limits: &Limits,
    names: &[String],
    rate: f64,
) -> Result<(
    Box<dyn Trajectory + Send + Sync>,
    SampleTable,
    LimitReport,
    f64,
)> {
    let tol = Tolerance::default();
    let mut scale = 1.0;
    for round in 0..=MAX_GUARD_ROUNDS {
        // The table and its CSV or JSON text (about 24 characters a value): written whole.
        crate::sample::check_sample_memory(
            traj.duration(),
            rate,
            traj.dof(),
            32.0,
            " with its text",
        )?;
        let (table, report) = sample_and_check(&*traj, rate, names.to_vec(), limits)?;
        if report.passes(&tol) {
            return Ok((traj, table, report, scale));
        }
        for jr in &report.joints {
            if jr.position.excursion > tol.position {
                let jl = limits.joint(jr.joint);
                let value = if jr.position.max > jl.position_max {
                    jr.position.max
                } else {
                    jr.position.min
                };
                return Err(Error::OutOfRange {
                    joint: jr.joint,
                    name: jr.name.clone(),
                    time: jr.position.time,
                    value,
                    lo: jl.position_min,
                    hi: jl.position_max,
                });
            }
        }
        let (k, worst) = needed_scale(&report);
        if round == MAX_GUARD_ROUNDS || !k.is_finite() {
            let (joint, field, peak) = worst;
            return Err(Error::LimitExceeded {
                joint,
                name: report.joints[joint].name.clone(),
                field,
                value: peak.value,
                ratio: peak.ratio,
                time: peak.time,
            });
        }
        scale *= k;
        traj = Box::new(Scaled::new(traj, k)?);
    }
    unreachable!("the loop returns")
}

/// The slow-down factor the report's worst ratios call for (slightly above), and the worst
/// peak (joint, field, peak).
fn needed_scale(report: &LimitReport) -> (f64, (usize, &'static str, crate::check::Peak)) {
    let mut k: f64 = 1.0;
    let mut worst = None;
    let mut worst_ratio = f64::NEG_INFINITY;
    for jr in &report.joints {
        for (order, d) in jr.derivatives.iter().enumerate() {
            for peak in [d.pointwise, d.finite_difference].into_iter().flatten() {
                let r = if peak.ratio.is_nan() {
                    f64::INFINITY
                } else {
                    peak.ratio
                };
                k = k.max(r.powf(1.0 / (order + 1) as f64));
                if r > worst_ratio {
                    worst_ratio = r;
                    worst = Some((jr.joint, d.order.name(), peak));
                }
            }
        }
    }
    (
        k * (1.0 + 1e-7),
        worst.expect("a failing report has a derivative peak"),
    )
}
