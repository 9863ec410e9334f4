//! 10 — The main job in one call: waypoints and limits in, a trajectory that keeps every limit
//! out (`trajkit::plan`, what `trajkit plan` runs). The same Panda waypoints planned by each
//! method, with the duration, the worst use of the limits and the notes; then what `plan`
//! refuses instead of returning a motion that breaks a limit.
//!
//! Run: `cargo run -p trajkit --example 10_plan`

use trajkit::check::Tolerance;
use trajkit::io::Waypoints;
use trajkit::plan::Method;
use trajkit::{plan, Limits, Order, PlanOptions, Trajectory};

fn main() -> Result<(), trajkit::Error> {
    let panda = Limits::preset("panda")?;
    // Four waypoints as a motion planner returns them (row-major, 7 joints), the second one
    // repeated: `plan` removes the repeat.
    let points = vec![
        0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, //
        0.55, -0.31, 0.28, -1.87, 0.18, 1.83, 1.12, //
        0.55, -0.31, 0.28, -1.87, 0.18, 1.83, 1.12, //
        1.02, 0.05, 0.05, -1.49, 0.63, 1.48, 1.21, //
        1.57, 0.35, -0.41, -1.42, 0.22, 2.10, 0.52,
    ];
    let waypoints = Waypoints::new(points, 7, Vec::new())?;

    // 1. The default: TOPP-RA on a C² spline kept inside the position ranges, then the jerk
    //    stage, sampled and checked. Every returned plan passed that check.
    let p = plan(&waypoints, &panda, &PlanOptions::default())?;
    println!(
        "toppra: {:.3} s, {} samples, worst use of a limit {:.4}, {} repeat(s) removed",
        p.duration(),
        p.samples.len(),
        p.report.worst(),
        p.repeats_removed
    );
    assert!(p.report.passes(&Tolerance::default()));
    let mut q = [0.0; 7];
    p.trajectory
        .eval(p.trajectory.duration(), Order::Position, &mut q);
    println!("  ends at {q:.3?}");
    for note in &p.notes {
        println!("  note: {note}");
    }

    // 2. The other methods on the same input. TOTG's blended path is only C¹ and cannot bound
    //    jerk: it needs the jerk limits stated as unlimited.
    let no_jerk = panda.clone().with_override(Order::Jerk, &[f64::INFINITY])?;
    for (method, limits) in [
        (Method::Ni, &panda),
        (Method::Poly, &panda),
        (Method::Totg, &no_jerk),
    ] {
        let options = PlanOptions {
            method,
            ..PlanOptions::default()
        };
        let p = plan(&waypoints, limits, &options)?;
        println!(
            "{method:?}: {:.3} s, worst use of a limit {:.4}",
            p.duration(),
            p.report.worst()
        );
    }

    // 3. What `plan` refuses, with a typed error naming the problem.
    let totg = PlanOptions {
        method: Method::Totg,
        ..PlanOptions::default()
    };
    match plan(&waypoints, &panda, &totg) {
        Ok(_) => unreachable!("TOTG cannot bound the Panda's jerk"),
        Err(e) => println!("refused: {e}"),
    }
    let mut far = waypoints.points().to_vec();
    far[7] = 3.5; // joint 1 of the second waypoint beyond the Panda's ±2.9 rad
    let far = Waypoints::new(far, 7, Vec::new())?;
    match plan(&far, &panda, &PlanOptions::default()) {
        Ok(_) => unreachable!("a waypoint outside its range has no in-range path"),
        Err(e) => println!("refused: {e}"),
    }
    Ok(())
}
