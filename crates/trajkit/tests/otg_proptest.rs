//! Property tests with shrinking for the online generator's inputs: random 3-DOF states and
//! limits (ordinary, tiny and huge), and the same with one field made invalid (a NaN or
//! infinite state, a NaN or negative limit). Whatever the input, `calculate` must not
//! panic: it returns a typed error for invalid input, and for valid input a trajectory that
//! ends at the target and, sampled densely through the shared `Trajectory` model (not the
//! profile data the generator verified itself), holds its velocity, acceleration and jerk
//! limits. A failure is shrunk by proptest to a minimal case.

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use trajkit::otg::{InputParameter, Otg, OtgError};
use trajkit::{Order, Trajectory};

/// A limit: mostly ordinary, sometimes tiny or huge (log-uniform over 1e-3..1e3).
fn limit() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => 0.2f64..8.0,
        1 => (-3.0f64..3.0).prop_map(|e| 10f64.powf(e)),
    ]
}

/// One DOF's valid problem: (p0, v0, a0, p1, v1, vmax, amax, jmax), the start state inside
/// the limits with its braking velocity v0 ± a0²/(2j) inside too (no brake pre-profile, whose
/// repair is exempt from the limits), the target velocity inside, target acceleration 0.
fn dof() -> impl Strategy<Value = [f64; 8]> {
    (
        limit(),
        limit(),
        limit(),
        -3.0f64..3.0,
        -3.0f64..3.0,
        -1.0f64..1.0,
        -1.0f64..1.0,
        -0.9f64..0.9,
    )
        .prop_map(|(vmax, amax, jmax, p0, p1, fv, fa, fv1)| {
            let v0 = fv * vmax;
            let mut a0 = fa * amax;
            let reach = a0 * a0 / (2.0 * jmax);
            if (v0.abs() + reach) > vmax {
                a0 = 0.0;
            }
            [p0, v0, a0, p1, fv1 * vmax, vmax, amax, jmax]
        })
}

fn input(d: &[[f64; 8]; 3]) -> InputParameter<3> {
    let mut inp = InputParameter::<3>::new();
    for (i, [p0, v0, a0, p1, v1, vmax, amax, jmax]) in d.iter().copied().enumerate() {
        inp.current_position[i] = p0;
        inp.current_velocity[i] = v0;
        inp.current_acceleration[i] = a0;
        inp.target_position[i] = p1;
        inp.target_velocity[i] = v1;
        inp.max_velocity[i] = vmax;
        inp.max_acceleration[i] = amax;
        inp.max_jerk[i] = jmax;
    }
    inp
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 128,
        // Reproducible runs, no failure files: a failure prints its shrunk case.
        rng_seed: RngSeed::Fixed(0x6f74_6770),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Valid input: a trajectory that arrives and holds every limit at 4001 samples.
    #[test]
    fn valid_input_arrives_within_its_limits(d in prop::array::uniform3(dof())) {
        let inp = input(&d);
        let tr = Otg::<3>::new(0.001).calculate(&inp);
        prop_assert!(tr.is_ok(), "{:?}", tr.err());
        let tr = tr.unwrap();
        let t_end = tr.duration();
        prop_assert!(t_end.is_finite() && t_end >= 0.0, "{t_end}");
        let mut y = [0.0; 3];
        for (order, target) in [
            (Order::Position, inp.target_position),
            (Order::Velocity, inp.target_velocity),
        ] {
            tr.eval(t_end, order, &mut y);
            for i in 0..3 {
                let scale = 1.0 + target[i].abs();
                prop_assert!((y[i] - target[i]).abs() <= 1e-8 * scale,
                    "{order:?} {i}: {} vs {}", y[i], target[i]);
            }
        }
        let n = 4000;
        for k in 0..=n {
            let t = t_end * k as f64 / n as f64;
            for (order, lim) in [
                (Order::Velocity, inp.max_velocity),
                (Order::Acceleration, inp.max_acceleration),
                (Order::Jerk, inp.max_jerk),
            ] {
                tr.eval(t, order, &mut y);
                for i in 0..3 {
                    prop_assert!(y[i].abs() <= lim[i] * (1.0 + 1e-9) + 1e-12,
                        "{order:?} {i} at t = {t}: {} vs limit {}", y[i], lim[i]);
                }
            }
        }
    }

    /// One field made invalid: a typed `InvalidInput` naming a field, never a panic.
    #[test]
    fn invalid_input_is_a_typed_error(
        d in prop::array::uniform3(dof()),
        dof_index in 0usize..3,
        field in 0usize..6,
        bad in prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(-1.0), Just(0.0)],
    ) {
        let mut inp = input(&d);
        let i = dof_index;
        match field {
            0 => inp.current_position[i] = if bad.is_finite() { f64::NAN } else { bad },
            1 => inp.current_velocity[i] = if bad.is_finite() { f64::NAN } else { bad },
            2 => inp.target_position[i] = if bad.is_finite() { f64::INFINITY } else { bad },
            // A limit that is NaN or negative (an infinite one states "unlimited" explicitly).
            3 => inp.max_velocity[i] = if bad.is_nan() || bad < 0.0 { bad } else { -2.0 },
            4 => inp.max_acceleration[i] = if bad.is_nan() || bad < 0.0 { bad } else { -0.5 },
            _ => inp.max_jerk[i] = if bad.is_nan() || bad < 0.0 { bad } else { f64::NAN },
        }
        match Otg::<3>::new(0.001).calculate(&inp) {
            Err(OtgError::InvalidInput { field, .. }) => prop_assert!(!field.is_empty()),
            other => prop_assert!(false, "field {field} = {bad}: {other:?}"),
        }
    }
}
