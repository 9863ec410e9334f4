//! 09 — TOTG: straight segments between waypoints, corners blended by circular arcs within a
//! maximum deviation, timed in the phase plane with exact limits; what `--max-deviation` does,
//! the switching points met, and the same blended path timed by TOPP-RA for comparison.
//!
//! Run: `cargo run -p trajkit --example 09_totg`

use trajkit::check::{check_trajectory, Tolerance};
use trajkit::topp::ni::SwitchKind;
use trajkit::topp::{plan_totg, BlendedPath, Gridpoints, Toppra, Totg, TotgOptions};
use trajkit::{Limits, Order, Path, Trajectory};

fn main() -> Result<(), trajkit::Error> {
    let panda = Limits::preset("panda")?;
    // Five Panda waypoints (row-major, 7 joints), a path as a planner returns it.
    let w: [f64; 35] = [
        0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, //
        0.55, -0.31, 0.28, -1.87, 0.18, 1.83, 1.12, //
        1.02, 0.05, 0.05, -1.49, 0.63, 1.48, 1.21, //
        1.18, 0.27, -0.16, -1.31, 0.58, 1.71, 0.94, //
        1.57, 0.35, -0.41, -1.42, 0.22, 2.10, 0.52,
    ];
    // The velocity and acceleration limits only (TOTG's blended path is C¹: its curvature
    // jumps where arcs meet segments, so jerk is not limited).
    let checked = panda.clone().with_override(Order::Jerk, &[f64::INFINITY])?;

    // 1. --max-deviation: how far a blend may pass from its waypoint. Larger blends have
    //    larger radii, so the robot keeps more speed through the corner (the centripetal
    //    acceleration σ″ṡ² = ṡ²/r is what the arc costs); each blend is also limited to half
    //    of its adjacent segments, so beyond some deviation nothing changes.
    println!("max deviation → blend radii (rad), duration");
    for dev in [0.001, 0.01, 0.05, 0.1, 0.3] {
        let path = BlendedPath::new(&w, 7, dev)?;
        let radii: Vec<String> = path.arc_radii().iter().map(|r| format!("{r:.3}")).collect();
        let traj = plan_totg(
            &w,
            7,
            &panda,
            &TotgOptions {
                max_deviation: dev,
                ..Default::default()
            },
        )?;
        let report = check_trajectory(&traj, &checked, 1000.0)?;
        println!(
            "  {dev:>5}: radii [{}], duration {:.6} s, worst limit ratio {:.6} ({})",
            radii.join(", "),
            traj.duration(),
            report.worst(),
            if report.passes(&Tolerance::default()) {
                "within limits"
            } else {
                "EXCEEDED"
            }
        );
    }

    // 2. The phase plane at deviation 0.1: where the optimal ṡ(s) touches the limit curves.
    let path = BlendedPath::new(&w, 7, 0.1)?;
    let sol = Totg::new(path.clone(), &panda)?.solve_detailed()?;
    println!(
        "\nswitching points (path length {:.4}, {} knots):",
        path.interval().1,
        sol.profile.gridpoints().len()
    );
    for p in &sol.switching_points {
        let kind = match p.kind {
            SwitchKind::Discontinuity => "discontinuity (segment/arc junction)",
            SwitchKind::VelocityLimit => "velocity limit curve",
            SwitchKind::Tangent => "acceleration limit curve (tangent)",
            SwitchKind::Singular => "acceleration limit curve (singular)",
        };
        println!("  s = {:.4}, ṡ = {:.4}: {kind}", p.s, p.sd);
    }

    // 3. The same blended path timed by TOPP-RA: the durations converge to TOTG's as the grid
    //    is refined (TOTG is within 0.01% of the optimum).
    let totg = sol.profile.duration();
    println!("\nTOTG: {totg:.6} s");
    for n in [1000, 10000, 100000] {
        let t = Toppra::with_limits(&path, &panda)?
            .gridpoints(Gridpoints::Uniform(n))
            .solve_profile()?
            .duration();
        println!(
            "TOPP-RA, N = {n:>6}: {t:.6} s ({:+.4}% vs TOTG)",
            100.0 * (t / totg - 1.0)
        );
    }
    Ok(())
}
