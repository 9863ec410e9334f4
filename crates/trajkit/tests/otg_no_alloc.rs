//! The online generator allocates nothing with a compile-time number of degrees of freedom:
//! `calculate`, `calculate_into`, `update` and trajectory queries run under a counting global
//! allocator; nor does the run-time-sized `DynOtg` once its storage is sized.

mod alloc_counter;
use alloc_counter::allocations;

use trajkit::otg::{
    calculate_dyn, DynInputParameter, DynOtg, DynOutputParameter, DynTrajectory, FixedTrajectory,
    InputParameter, Otg, OtgError, OtgResult, OutputParameter, Synchronization,
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

#[test]
fn the_run_time_sized_generator_allocates_nothing_once_sized_and_matches_the_fixed_one() {
    let mut r = SplitMix64::new(11);
    let mut fixed = Vec::new();
    for k in 0..48 {
        let mut p = panda();
        for i in 0..7 {
            p.current_position[i] = r.uniform(-2.0, 2.0);
            p.target_position[i] = r.uniform(-2.0, 2.0);
            if k % 2 == 1 {
                p.current_velocity[i] = r.uniform(-1.0, 1.0);
                p.target_velocity[i] = r.uniform(-0.5, 0.5);
                p.current_acceleration[i] = r.uniform(-2.0, 2.0);
            }
        }
        if k % 8 == 3 {
            p.options.synchronization = Synchronization::Phase;
        }
        fixed.push(p);
    }
    let dyns: Vec<DynInputParameter> = fixed.iter().map(DynInputParameter::from).collect();
    // Reference: the compile-time-sized generator (durations and update states).
    let mut otg7 = Otg::<7>::new(0.001);
    let mut out7 = OutputParameter::<7>::default();
    let mut want = Vec::new();
    for p in &fixed {
        let d = otg7.calculate(p).unwrap().duration();
        let mut inp = *p;
        let mut states = Vec::new();
        for _ in 0..30 {
            let res = otg7.update(&inp, &mut out7).unwrap();
            states.push((res, out7.new_position, out7.new_jerk));
            out7.pass_to_input(&mut inp);
        }
        want.push((d, states));
    }
    let mut otg = DynOtg::new(7, 0.001);
    let mut traj = DynTrajectory::new(7);
    let mut out = DynOutputParameter::new(7);
    let mut inp = dyns[0].clone();
    let mut got_d = vec![0.0; dyns.len()];
    let mut got_states = vec![[(OtgResult::Working, [0.0; 7], [0.0; 7]); 30]; dyns.len()];
    let n = allocations(|| {
        for (k, p) in dyns.iter().enumerate() {
            otg.calculate_into(p, &mut traj).unwrap();
            got_d[k] = traj.duration();
            inp.clone_from(p);
            for s in got_states[k].iter_mut() {
                let res = otg.update(&inp, &mut out).unwrap();
                s.0 = res;
                s.1.copy_from_slice(&out.new_position);
                s.2.copy_from_slice(&out.new_jerk);
                out.pass_to_input(&mut inp);
            }
            assert!(!traj.was_interrupted() && !out.was_calculation_interrupted);
        }
    });
    assert_eq!(n, 0, "allocations in DynOtg::calculate_into / update");
    for k in 0..dyns.len() {
        assert_eq!(got_d[k], want[k].0, "problem {k}");
        assert_eq!(got_states[k].to_vec(), want[k].1, "problem {k}");
        assert_eq!(
            calculate_dyn(&dyns[k], 0.001).unwrap().duration(),
            want[k].0
        );
    }
    // A re-plan happens exactly when the input changes: fed back, the output does not cause one.
    let mut inp = dyns[1].clone();
    otg.reset();
    otg.update(&inp, &mut out).unwrap();
    assert!(out.new_calculation);
    out.pass_to_input(&mut inp);
    otg.update(&inp, &mut out).unwrap();
    assert!(!out.new_calculation);
    inp.target_position[2] += 0.1;
    otg.update(&inp, &mut out).unwrap();
    assert!(out.new_calculation);
    // Bad input is an error, and the next update calculates again.
    inp.max_jerk[4] = f64::NAN;
    assert!(matches!(
        otg.update(&inp, &mut out),
        Err(OtgError::InvalidInput {
            dof: Some(4),
            field: "max_jerk",
            ..
        })
    ));
}
