//! 07 — Online generation in a control loop: 7 Panda joints, a new target half-way.
//!
//! `update` is called every 1 ms; it re-plans only when the input changes (here once at the
//! start and once when the target moves) and reports how long that took.
//!
//! Run: `cargo run --release -p trajkit --example 07_otg_update_loop`

use trajkit::otg::{InputParameter, Otg, OtgResult, OutputParameter};
use trajkit::Limits;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let panda = Limits::preset("panda")?;
    let mut input = InputParameter::<7>::new();
    for i in 0..7 {
        let j = panda.joint(i);
        input.max_velocity[i] = j.velocity;
        input.max_acceleration[i] = j.acceleration;
        input.max_jerk[i] = j.jerk;
    }
    input.current_position = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];
    input.target_position = [1.2, 0.3, -0.5, -1.2, 0.6, 2.2, -0.4];
    input.target_velocity[0] = 0.2; // pass the target moving

    let mut otg = Otg::<7>::new(0.001);
    let mut out = OutputParameter::<7>::default();
    let mut cycle = 0;
    loop {
        let r = otg.update(&input, &mut out)?;
        if out.new_calculation {
            println!(
                "cycle {cycle}: new trajectory, duration {:.4} s, computed in {:.1} µs",
                out.duration, out.calculation_duration_us
            );
        }
        match r {
            OtgResult::Working => {}
            OtgResult::Finished => break,
        }
        out.pass_to_input(&mut input);
        cycle += 1;
        if cycle == 300 {
            // A new target arrives mid-motion: re-plan from the current (moving) state.
            input.target_position = [0.5, 0.0, 0.3, -1.5, 0.0, 1.8, 0.2];
            input.target_velocity[0] = 0.0;
        }
    }
    println!(
        "finished after {cycle} cycles at q = [{}]",
        out.new_position
            .iter()
            .map(|q| format!("{q:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}
