//! The online generator allocates nothing with a compile-time number of degrees of freedom:
//! `calculate`, `calculate_into`, `update` and trajectory queries run under a counting global
//! allocator.

mod alloc_counter;
use alloc_counter::allocations;

use trajkit::otg::{
    FixedTrajectory, InputParameter, Otg, OtgError, OtgResult, OutputParameter, Synchronization,
};
use trajkit::rng::SplitMix64;
use trajkit::{Order, Trajectory};

fn panda() -> InputParameter<7> {
    let mut inp = InputParameter::<7>::new();
    inp.max_velocity = [2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61];
    inp.max_acceleration = [15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0];
    inp.max_jerk = [7500.0, 3750.0, 5000.0, 6250.0, 7500.0, 10000.0, 10000.0];
    inp
}

#[test]
fn calculate_update_and_queries_allocate_nothing() {
    let mut r = SplitMix64::new(3);
    let mut problems = [panda(); 64];
    for (k, p) in problems.iter_mut().enumerate() {
        for i in 0..7 {
            p.current_position[i] = r.uniform(-2.0, 2.0);
            p.target_position[i] = r.uniform(-2.0, 2.0);
            p.current_velocity[i] = r.uniform(-1.0, 1.0);
            p.target_velocity[i] = r.uniform(-0.5, 0.5);
            p.current_acceleration[i] = r.uniform(-2.0, 2.0);
        }
        p.options.synchronization = [
            Synchronization::Time,
            Synchronization::TimeIfNecessary,
            Synchronization::Phase,
            Synchronization::None,
        ][k % 4];
        // Position limits (step 1 with the position check) and a calculation budget.
        if k % 16 == 1 {
            for i in 0..7 {
                p.max_position[i] = p.current_position[i].max(p.target_position[i]) + 1.0;
                p.min_position[i] = p.current_position[i].min(p.target_position[i]) - 1.0;
            }
        }
        if k % 16 == 2 {
            p.options.interrupt_calculation_duration = Some(1e6);
        }
    }
    // Non-finite input goes through the same path.
    problems[5].target_position[3] = f64::NAN;
    let mut otg = Otg::<7>::new(0.001);
    let mut out = OutputParameter::<7>::default();
    let mut results: [Result<OtgResult, OtgError>; 64] = [Ok(OtgResult::Working); 64];
    let mut reused = FixedTrajectory::<7>::default();
    let mut into_ok = 0;
    let n = allocations(|| {
        for (k, p) in problems.iter().enumerate() {
            let tr = otg.calculate(p);
            if let Ok(tr) = tr {
                let mut q = [0.0; 7];
                tr.eval(tr.duration() * 0.3, Order::Jerk, &mut q);
                let _ = tr.position_extrema(2);
                let _ = tr.first_time_at_position(1, p.target_position[1]);
            }
            if otg.calculate_into(p, &mut reused).is_ok() {
                into_ok += 1;
                let mut q = [0.0; 7];
                reused.eval(reused.duration() * 0.6, Order::Position, &mut q);
            }
            let mut inp = *p;
            for _ in 0..20 {
                results[k] = otg.update(&inp, &mut out);
                if results[k].is_err() {
                    break;
                }
                out.pass_to_input(&mut inp);
            }
        }
    });
    assert_eq!(n, 0, "allocations on the real-time path");
    assert!(matches!(results[5], Err(OtgError::InvalidInput { .. })));
    assert!(results.iter().filter(|r| r.is_ok()).count() >= 60);
    assert!(into_ok >= 60);
}
