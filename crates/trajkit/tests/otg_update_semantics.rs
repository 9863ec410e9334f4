//! The three update loops (`Otg`, `DynOtg`, `WaypointOtg`) follow Ruckig's `update`: the
//! result is `Finished` only once the new time is past the duration (the cycle landing exactly
//! on it writes the target state and is still `Working`), and `calculation_duration_us` is
//! the wall-clock time of the whole update, calculating or not (the Ruckig 0.19.4 wheel: a
//! 1-DOF motion of 5 s at dt = 0.25 s is `Working` at cycle 20, time 5.0, and `Finished` at
//! cycle 21; its following cycles report about 0.2–1.2 µs).

use std::time::Instant;
use trajkit::otg::{
    DynInputParameter, DynOtg, DynOutputParameter, InputParameter, Otg, OtgResult, OutputParameter,
    WaypointOtg, WaypointOutput, Waypoints,
};

/// A 1-DOF motion over 1 at limits (1, 1, 1), stretched to 5 s by its minimum duration.
fn five_seconds() -> InputParameter<1> {
    let mut inp = InputParameter::<1>::new();
    inp.target_position = [1.0];
    inp.max_velocity = [1.0];
    inp.max_acceleration = [1.0];
    inp.max_jerk = [1.0];
    inp.options.minimum_duration = Some(5.0);
    inp
}

fn dyn_five_seconds() -> DynInputParameter {
    let mut inp = DynInputParameter::new(1);
    inp.target_position = vec![1.0];
    inp.max_velocity = vec![1.0];
    inp.max_acceleration = vec![1.0];
    inp.max_jerk = vec![1.0];
    inp.options.minimum_duration = Some(5.0);
    inp
}

/// Asserts the wall-clock report of one update: positive and within the time measured around
/// the call.
fn assert_timed(us: f64, outer: Instant) {
    let outer_us = outer.elapsed().as_secs_f64() * 1e6;
    assert!(
        us > 0.0 && us <= outer_us,
        "{us} µs reported, {outer_us} µs around the call"
    );
}

/// An output's time, position, `calculation_duration_us` and duration.
type Row = (f64, f64, f64, f64);

/// The [`Row`] of an output of either generator.
macro_rules! row {
    ($o:expr) => {
        (
            $o.time,
            $o.new_position[0],
            $o.calculation_duration_us,
            $o.duration,
        )
    };
}

/// Runs a loop's cycles (`cycle` updates, feeds the state back and returns the result and
/// the output's [`Row`]) until `Finished`, checking each cycle's wall-clock report and the
/// duration; returns each cycle's result, time and position.
fn run(mut cycle: impl FnMut() -> (OtgResult, Row)) -> Vec<(OtgResult, f64, f64)> {
    let mut results = Vec::new();
    for _ in 0..25 {
        let outer = Instant::now();
        let (r, (t, p, us, d)) = cycle();
        assert_timed(us, outer);
        assert_eq!(d, 5.0);
        results.push((r, t, p));
        if r == OtgResult::Finished {
            break;
        }
    }
    results
}

#[test]
fn otg_and_dyn_otg_finish_after_the_cycle_that_lands_on_the_duration() {
    for dt in [0.25, 0.3] {
        let (mut otg, mut inp) = (Otg::<1>::new(dt), five_seconds());
        let mut out = OutputParameter::<1>::default();
        let fixed = run(|| {
            let r = otg.update(&inp, &mut out).unwrap();
            out.pass_to_input(&mut inp);
            (r, row!(out))
        });
        check_cycles(&fixed, dt);
        let (mut otg, mut inp) = (DynOtg::new(1, dt), dyn_five_seconds());
        let mut out = DynOutputParameter::new(1);
        let dynamic = run(|| {
            let r = otg.update(&inp, &mut out).unwrap();
            out.pass_to_input(&mut inp);
            (r, row!(out))
        });
        assert_eq!(fixed, dynamic);
    }
}

/// 5 s at dt = 0.25 (sums exact): cycles 1–20 `Working`, cycle 20 at time 5.0 on the target,
/// cycle 21 `Finished`. At dt = 0.3: cycle 16 (4.8 s) `Working`, cycle 17 (5.1 s) `Finished`.
fn check_cycles(results: &[(OtgResult, f64, f64)], dt: f64) {
    let n = (5.0 / dt).floor() as usize + 1;
    assert_eq!(results.len(), n, "dt {dt}: {results:?}");
    for (k, &(r, t, _)) in results.iter().enumerate() {
        let want = if k + 1 == n {
            OtgResult::Finished
        } else {
            OtgResult::Working
        };
        assert_eq!(r, want, "dt {dt}, cycle {} at {t}", k + 1);
    }
    if dt == 0.25 {
        let (_, t, p) = results[n - 2];
        assert_eq!(t, 5.0);
        assert!((p - 1.0).abs() <= 1e-8, "{p}");
    }
}

#[test]
fn waypoint_otg_finishes_after_the_cycle_that_lands_on_the_duration() {
    let mut inp = DynInputParameter::new(2);
    inp.current_position = vec![0.0, 0.0];
    inp.target_position = vec![1.0, -0.5];
    inp.max_velocity = vec![1.0, 1.0];
    inp.max_acceleration = vec![1.0, 2.0];
    inp.max_jerk = vec![1.0, 5.0];
    let wp = Waypoints::new(vec![vec![0.6, 0.3]]);
    let mut first = WaypointOtg::new(0.001);
    let mut out = WaypointOutput::new(2);
    first.update(&inp, &wp, &mut out).unwrap();
    let d = out.output.duration;
    // Half the duration: two cycles land exactly on it (D/2 + D/2 = D in floating point).
    for (dt, landing) in [(d / 2.0, true), (d / 2.0 * (1.0 + 1e-9), false)] {
        let mut otg = WaypointOtg::new(dt);
        let (mut i, mut w) = (inp.clone(), wp.clone());
        let mut results = Vec::new();
        for _ in 0..5 {
            let outer = Instant::now();
            let r = otg.update(&i, &w, &mut out).unwrap();
            assert_timed(out.output.calculation_duration_us, outer);
            assert_eq!(out.output.duration, d);
            results.push((r, out.output.time, out.output.new_position[0]));
            out.pass_to_input(&mut i, &mut w);
            if r == OtgResult::Finished {
                break;
            }
        }
        let want: &[OtgResult] = if landing {
            assert_eq!(results[1].1, d);
            assert!((results[1].2 - 1.0).abs() <= 1e-8, "{results:?}");
            &[OtgResult::Working, OtgResult::Working, OtgResult::Finished]
        } else {
            &[OtgResult::Working, OtgResult::Finished]
        };
        let got: Vec<_> = results.iter().map(|x| x.0).collect();
        assert_eq!(got, want, "dt {dt}: {results:?}");
    }
}
