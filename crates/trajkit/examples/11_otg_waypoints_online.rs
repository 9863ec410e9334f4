//! 11 — Online generation through waypoints (Ruckig Pro's example 04): 3 DOF, four
//! intermediate waypoints, a calculation budget of 500 µs, `update` every 10 ms until the
//! target is reached.
//!
//! `WaypointOtg::update` plans when the input changes (here once, at the start), follows the
//! motion, reports each passed waypoint (`did_section_change`) and, when the budget cut the
//! planning short, refines the motion in the following cycles (a new motion is taken only when
//! it arrives at least one control period sooner). `pass_to_input` feeds the state back and
//! removes each passed waypoint from the input.
//!
//! Run: `cargo run --release -p trajkit --example 11_otg_waypoints_online`

use trajkit::otg::{
    DynInputParameter, OtgError, OtgResult, WaypointOtg, WaypointOutput, Waypoints,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut otg = WaypointOtg::new(0.01); // control period [s]
    let mut input = DynInputParameter::new(3);
    let mut out = WaypointOutput::new(3);

    input.current_position = vec![0.2, 0.0, -0.3];
    input.current_velocity = vec![0.0, 0.2, 0.0];
    input.current_acceleration = vec![0.0, 0.6, 0.0];
    let mut waypoints = Waypoints::new(vec![
        vec![1.4, -1.6, 1.0],
        vec![-0.6, -0.5, 0.4],
        vec![-0.4, -0.35, 0.0],
        vec![0.8, 1.8, -0.1],
    ]);
    input.target_position = vec![0.5, 1.0, 0.0];
    input.target_velocity = vec![0.2, 0.0, 0.3];
    input.target_acceleration = vec![0.0, 0.1, -0.1];
    input.max_velocity = vec![1.0, 2.0, 1.0];
    input.max_acceleration = vec![3.0, 2.0, 2.0];
    input.max_jerk = vec![6.0, 10.0, 20.0];
    input.options.interrupt_calculation_duration = Some(500.0); // [µs]

    println!("t | position");
    let mut cycles = 0;
    loop {
        cycles += 1;
        let result = match otg.update(&input, &waypoints, &mut out) {
            Ok(r) => r,
            // The budget is wall-clock time: on a busy machine even stopping at every waypoint
            // can miss it before any motion exists. Hold still and try again next cycle.
            Err(OtgError::Interrupted { .. }) if otg.trajectory().is_none() && cycles < 100 => {
                println!("No motion within the budget yet; holding.");
                continue;
            }
            Err(e) => return Err(e.into()),
        };
        let o = &out.output;
        if o.new_calculation {
            println!("Updated the trajectory:");
            println!("  Reached target position in {:.4} [s].", o.duration);
            println!("  Calculation in {:.1} [µs].", o.calculation_duration_us);
            println!(
                "  Interrupted by the budget: {}",
                o.was_calculation_interrupted
            );
        }
        if out.did_section_change {
            println!("  passed section {}", out.new_section);
        }
        let p: Vec<String> = o.new_position.iter().map(|x| format!("{x:.4}")).collect();
        println!("{:.2} | {}", o.time, p.join(" "));
        out.pass_to_input(&mut input, &mut waypoints);
        if result == OtgResult::Finished {
            break;
        }
    }
    // `time` restarts with every new calculation; the cycles count the whole motion.
    println!(
        "Reached the target after {cycles} cycles ({:.2} s); last trajectory {:.4} s.",
        cycles as f64 * otg.delta_time,
        out.output.duration
    );
    Ok(())
}
