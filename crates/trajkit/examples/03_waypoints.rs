//! 03 — Through several waypoints: piecewise quintic segments timed to the limits, stopping at
//! every waypoint versus the continuous-velocity heuristic; sampled to CSV and plotted.
//!
//! Run: `cargo run -p trajkit --example 03_waypoints` (writes waypoints.csv and waypoints.svg
//! to the system temp directory).

use trajkit::poly::{Degree, ViaTiming, ViaTrajectory, ViaVelocities};
use trajkit::{Limits, Trajectory};

fn main() -> Result<(), trajkit::Error> {
    let limits = Limits::preset("ur5e")?;
    // 4 waypoints × 6 joints, row-major.
    let wps = [
        0.0, -1.57, 1.57, -1.57, -1.57, 0.0, //
        0.5, -1.20, 1.20, -1.40, -1.57, 0.3, //
        1.0, -1.00, 0.80, -1.20, -1.40, 0.6, //
        1.2, -1.30, 1.10, -1.50, -1.57, 0.2,
    ];
    for vel in [ViaVelocities::Zero, ViaVelocities::Heuristic] {
        let tr = ViaTrajectory::new(
            &wps,
            6,
            Degree::Quintic,
            vel.clone(),
            ViaTiming::Limits(&limits),
        )?;
        println!(
            "{vel:?}: duration {:.4} s, worst ratio {:.6}",
            tr.duration(),
            tr.worst_limit_ratio(&limits)?
        );
    }
    let tr = ViaTrajectory::new(
        &wps,
        6,
        Degree::Quintic,
        ViaVelocities::Heuristic,
        ViaTiming::Limits(&limits),
    )?;
    let table = trajkit::sample::sample(&tr, 500.0)?;
    let dir = std::env::temp_dir();
    let csv = dir.join("waypoints.csv");
    let svg = dir.join("waypoints.svg");
    std::fs::write(&csv, trajkit::io::table_to_csv(&table)).map_err(|e| trajkit::Error::Io {
        path: csv.display().to_string(),
        message: e.to_string(),
    })?;
    let plot = trajkit::plot::svg(&table, Some(&limits), &Default::default())?;
    std::fs::write(&svg, plot).map_err(|e| trajkit::Error::Io {
        path: svg.display().to_string(),
        message: e.to_string(),
    })?;
    println!(
        "wrote {} ({} samples) and {}",
        csv.display(),
        table.len(),
        svg.display()
    );
    Ok(())
}
