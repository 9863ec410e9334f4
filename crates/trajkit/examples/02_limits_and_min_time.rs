//! 02 — The shortest polynomial move within a robot's limits, all joints arriving together,
//! verified by the limit checker.
//!
//! Run: `cargo run -p trajkit --example 02_limits_and_min_time`

use trajkit::check::{check_trajectory, Tolerance};
use trajkit::poly::{min_duration_rest_to_rest, Degree, PolyMove};
use trajkit::{Limits, Trajectory};

fn main() -> Result<(), trajkit::Error> {
    let panda = Limits::preset("panda")?;
    let q0 = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];
    let q1 = [1.2, 0.3, -0.5, -1.2, 0.6, 2.2, -0.4];
    for d in [Degree::Quintic, Degree::Septic] {
        let t = min_duration_rest_to_rest(d, &q0, &q1, &panda)?;
        let mv = PolyMove::rest_to_rest(d, &q0, &q1, t)?;
        let report = check_trajectory(&mv, &panda, 1000.0)?;
        println!(
            "{:8} T = {:.4} s, exact worst ratio {:.6}, sampled check worst {:.6}, passes: {}",
            d.name(),
            mv.duration(),
            mv.worst_limit_ratio(&panda)?,
            report.worst(),
            report.passes(&Tolerance::default())
        );
    }
    Ok(())
}
