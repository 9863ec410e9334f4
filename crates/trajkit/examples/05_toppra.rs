//! 05 — Time-optimal path parameterization: TOPP-RA over a cubic spline through Panda
//! waypoints, its exact output, the bounded-jerk version, and both checked against the limits.
//!
//! Run: `cargo run -p trajkit --example 05_toppra`

use trajkit::check::{check_trajectory, Tolerance};
use trajkit::spline::CubicSpline;
use trajkit::topp::jerk::{limit_jerk, JerkOptions};
use trajkit::topp::{Gridpoints, Toppra};
use trajkit::{Limits, Trajectory};

fn main() -> Result<(), trajkit::Error> {
    let panda = Limits::preset("panda")?;
    // Four waypoints (row-major, 7 joints) and a natural cubic spline through them, with the
    // path parameter s spaced by the distance between waypoints.
    let w: [f64; 28] = [
        0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, //
        0.55, -0.31, 0.28, -1.87, 0.18, 1.83, 1.12, //
        1.02, 0.05, 0.05, -1.49, 0.63, 1.48, 1.21, //
        1.57, 0.35, -0.41, -1.42, 0.22, 2.10, 0.52,
    ];
    let mut s = vec![0.0; 4];
    for i in 1..4 {
        let d: f64 = (0..7)
            .map(|j| (w[i * 7 + j] - w[(i - 1) * 7 + j]).powi(2))
            .sum();
        s[i] = s[i - 1] + d.sqrt();
    }
    let path = CubicSpline::natural(&s, &w, 7)?;
    for n in [100, 1000, 10000] {
        let traj = Toppra::with_limits(&path, &panda)?
            .gridpoints(Gridpoints::Uniform(n))
            .solve()?;
        println!("TOPP-RA, N = {n:>5}: duration {:.6} s", traj.duration());
    }
    // The exact output: q̇ = σ′ṡ, q̈ = σ″ṡ² + σ′s̈, never refitted.
    let traj = Toppra::with_limits(path.clone(), &panda)?.solve()?;
    let report = check_trajectory(
        &traj,
        &panda
            .clone()
            .with_override(trajkit::Order::Jerk, &[f64::INFINITY])?,
        1000.0,
    )?;
    println!(
        "velocity/acceleration: worst ratio {:.6}, passes {}",
        report.worst(),
        report.passes(&Tolerance::default())
    );
    // Bounded jerk: filter the timing law, then the smallest time scaling meeting every limit.
    let smooth = limit_jerk(path, traj.law().clone(), &panda, &JerkOptions::default())?;
    let report = check_trajectory(&smooth, &panda, 1000.0)?;
    println!(
        "bounded jerk: duration {:.6} s (+{:.2} %), worst ratio {:.6} with jerk, passes {}",
        smooth.duration(),
        100.0 * (smooth.duration() / traj.duration() - 1.0),
        report.worst(),
        report.passes(&Tolerance::default())
    );
    Ok(())
}
