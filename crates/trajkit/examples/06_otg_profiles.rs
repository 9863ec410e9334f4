//! 06 — Online generation, one joint: the seed's trapezoid vs S-curve, then a move from a
//! state beyond the limits.
//!
//! Run: `cargo run -p trajkit --example 06_otg_profiles`

use trajkit::otg::{InputParameter, Otg, OtgError};
use trajkit::{Order, Trajectory};

fn main() -> Result<(), OtgError> {
    let otg = Otg::<1>::new(0.001);
    // D = 1, v_max = 0.6, a_max = 1, j_max = 4 (the seed's acceptance numbers).
    let mut input = InputParameter::<1>::new();
    input.target_position = [1.0];
    input.max_velocity = [0.6];
    input.max_acceleration = [1.0];
    input.max_jerk = [4.0];
    let s_curve = otg.calculate(&input)?;
    input.max_jerk = [f64::INFINITY]; // no jerk limit: second order, trapezoidal velocity
    let trapezoid = otg.calculate(&input)?;
    input.max_acceleration = [f64::INFINITY]; // no acceleration limit: first order
    let first = otg.calculate(&input)?;
    println!("first order  T = {:.4} s (D/v)", first.duration());
    println!("trapezoid    T = {:.4} s (D/v + v/a)", trapezoid.duration());
    println!(
        "S-curve      T = {:.4} s (D/v + v/a + a/j)",
        s_curve.duration()
    );

    // The S-curve's seven phases: jerk +j, 0, −j, 0 (cruise), −j, 0, +j.
    let prof = &s_curve.dofs()[0].profile;
    for k in 0..prof.segments() {
        let (t0, d, s, j) = prof.segment(k).expect("segment index in range");
        println!(
            "  phase {k}: t = {t0:.4} s for {d:.4} s, jerk {j:+}, v = {:.4}, a = {:.4}",
            s.v, s.a
        );
    }

    // A joint moving faster than its limit (v = 1.2 > 0.6) and accelerating: the brake
    // pre-profile brings it back inside the limits first.
    let mut input = InputParameter::<1>::new();
    input.current_velocity = [1.2];
    input.current_acceleration = [0.5];
    input.target_position = [0.5];
    input.max_velocity = [0.6];
    input.max_acceleration = [1.0];
    input.max_jerk = [4.0];
    let tr = otg.calculate(&input)?;
    let prof = &tr.dofs()[0].profile;
    println!(
        "from beyond the limits: T = {:.4} s, of which brake {:.4} s",
        tr.duration(),
        prof.brake_duration()
    );
    let (lo, t_lo, hi, t_hi) = tr.position_extrema(0).expect("DOF 0 exists");
    println!("  position range [{lo:.4} at {t_lo:.3} s, {hi:.4} at {t_hi:.3} s]");
    let mut v = [0.0];
    tr.eval(tr.duration(), Order::Velocity, &mut v);
    println!("  final velocity {:.2e}", v[0]);
    Ok(())
}
