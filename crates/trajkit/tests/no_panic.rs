//! No panic on any input: seeded property tests that throw extreme but finite values (limits
//! from 1e-300 to 1e300, states one ulp beyond their limits, zero-length and 1e-15 motions,
//! duplicate adjacent waypoints) and non-finite ones (NaN, ±∞, negative limits) at the public
//! entry points: the online generator with every option (fixed and dynamic DOF, intermediate
//! waypoints), `plan`, TOPP-RA on small paths, and spline construction and evaluation.
//!
//! The only property asserted is that every call returns, `Ok` or a typed error: proptest
//! turns a panic into a failure and shrinks it to a minimal case. Results are judged by the
//! per-module property tests (`otg_proptest`, `topp_proptest`, `spline_proptest`). Fixed
//! cases below pin what panicked or aborted before: step 1's clamp of a level to a window
//! whose ends round-off had crossed (a start acceleration one ulp past its limit) and TOTG
//! with an absurd arc step (an allocation abort); and polynomials spanning nearly the whole
//! finite range (where derivative coefficients overflow; no panic found).

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use trajkit::io::Waypoints as PlanWaypoints;
use trajkit::otg::{
    calculate_dyn, plan_waypoints, ControlInterface, DurationDiscretization, DynInputParameter,
    InputParameter, Otg, Synchronization, Waypoints,
};
use trajkit::poly::{min_duration_rest_to_rest, Degree};
use trajkit::spline::{AkimaSpline, CubicSpline, PchipSpline};
use trajkit::topp::{BlendedPath, Gridpoints, LinearPath, Toppra, ToppraOptions, Totg};
use trajkit::{plan, Limits, Order, Path, PlanOptions, Trajectory};

/// A magnitude over the whole finite range, ordinary values most often.
fn magnitude() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => 0.1f64..10.0,
        1 => Just(1e-300),
        1 => Just(1e-150),
        1 => Just(1e-15),
        1 => Just(1e15),
        1 => Just(1e150),
        1 => Just(1e300),
        1 => (-300.0f64..300.0).prop_map(|e| 10f64.powf(e)),
    ]
}

/// A limit: a magnitude, or zero, negative, NaN or infinite.
fn limit() -> impl Strategy<Value = f64> {
    prop_oneof![
        60 => magnitude(),
        1 => Just(0.0),
        1 => Just(-1.0),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
    ]
}

/// A state value relative to its limit `l`, by kind: at rest, inside, exactly at ±l, one
/// ulp beyond ±l, far beyond, or non-finite.
fn relative(kind: u8, l: f64) -> f64 {
    match kind {
        0..=63 => 0.0,
        64..=127 => 0.5 * l,
        128..=159 => l,
        160..=191 => -l,
        192..=215 => beyond(l),
        216..=239 => -beyond(l),
        240..=251 => 3.0 * l,
        252 | 253 => f64::NAN,
        _ => f64::INFINITY,
    }
}

/// One ulp further from zero than `l` (for l ≥ 0).
fn beyond(l: f64) -> f64 {
    f64::from_bits(l.to_bits() + 1)
}

/// A displacement: none, 1e-15, one position ulp, or a signed magnitude.
fn displacement() -> impl Strategy<Value = f64> {
    prop_oneof![
        2 => Just(0.0),
        1 => Just(1e-15),
        1 => Just(-1e-15),
        1 => Just(f64::MIN_POSITIVE),
        4 => magnitude(),
        4 => magnitude().prop_map(|m| -m),
    ]
}

/// One DOF: (p0, v0, a0, p1, v1, a1, vmax, amax, jmax).
fn dof() -> impl Strategy<Value = [f64; 9]> {
    (
        (limit(), limit(), limit()),
        any::<[u8; 4]>(),
        prop_oneof![3 => Just(0.0), 1 => magnitude(), 1 => magnitude().prop_map(|m| -m)],
        displacement(),
    )
        .prop_map(|((vm, am, jm), [fv0, fa0, fv1, fa1], p0, d)| {
            let r = relative;
            // Mostly a target at rest in acceleration (others are often unreachable).
            // The target mostly inside its limits and at rest in acceleration (others are
            // refused or unreachable; the start is what may lie beyond).
            let v1 = r(if fv1 < 240 { fv1 % 192 } else { fv1 }, vm);
            let a1 = if fa1 < 224 { 0.0 } else { r(fa1, am) };
            [p0, r(fv0, vm), r(fa0, am), p0 + d, v1, a1, vm, am, jm]
        })
}

/// Every option of the generator: (synchronization, control interface, discretization,
/// minimum duration, per-DOF overrides, min limits).
type Options = (usize, bool, bool, Option<f64>, bool, bool);

fn options() -> impl Strategy<Value = Options> {
    (
        0usize..5,
        any::<bool>(),
        any::<bool>(),
        prop_oneof![6 => Just(None), 3 => magnitude().prop_map(Some), 1 => Just(Some(f64::NAN))],
        any::<bool>(),
        any::<bool>(),
    )
}

const SYNC: [Synchronization; 5] = [
    Synchronization::Time,
    Synchronization::TimeIfNecessary,
    Synchronization::Phase,
    Synchronization::StraightLine,
    Synchronization::None,
];

fn input(d: &[[f64; 9]; 2], o: Options) -> InputParameter<2> {
    let mut inp = InputParameter::<2>::new();
    for (i, [p0, v0, a0, p1, v1, a1, vm, am, jm]) in d.iter().copied().enumerate() {
        inp.current_position[i] = p0;
        inp.current_velocity[i] = v0;
        inp.current_acceleration[i] = a0;
        inp.target_position[i] = p1;
        inp.target_velocity[i] = v1;
        inp.target_acceleration[i] = a1;
        inp.max_velocity[i] = vm;
        inp.max_acceleration[i] = am;
        inp.max_jerk[i] = jm;
    }
    let (sync, velocity, discrete, min_duration, per_dof, min_limits) = o;
    inp.options.synchronization = SYNC[sync];
    if velocity {
        inp.options.control_interface = ControlInterface::Velocity;
    }
    if discrete {
        inp.options.duration_discretization = DurationDiscretization::Discrete;
    }
    inp.options.minimum_duration = min_duration;
    if per_dof {
        let other = [Synchronization::Time, Synchronization::None][sync % 2];
        inp.per_dof_synchronization = Some([other, SYNC[sync % 3]]);
        inp.per_dof_control_interface =
            Some([ControlInterface::Position, ControlInterface::Velocity]);
    }
    if min_limits {
        inp.min_velocity = Some([-0.5 * d[0][6], -2.0 * d[1][6]]);
        inp.min_acceleration = Some([-d[0][7], -0.25 * d[1][7]]);
    }
    inp
}

/// Samples a trajectory at its ends and middle (evaluation must not panic either).
fn sample<T: Trajectory>(t: &T, dof: usize) {
    let mut out = vec![0.0; dof];
    let d = t.duration();
    for time in [0.0, 0.5 * d, d, d + 1.0, f64::NAN] {
        for order in [
            Order::Position,
            Order::Velocity,
            Order::Acceleration,
            Order::Jerk,
        ] {
            t.eval(time, order, &mut out);
        }
    }
}

/// Points (row-major, `dof` columns) with duplicate adjacent rows and extreme scales.
fn points() -> impl Strategy<Value = (usize, Vec<f64>)> {
    (1usize..=2, 2usize..=4).prop_flat_map(|(dof, n)| {
        (
            Just(dof),
            prop::collection::vec(
                (prop::collection::vec(displacement(), dof), any::<bool>()),
                n,
            ),
        )
            .prop_map(|(dof, rows)| {
                let mut w: Vec<f64> = Vec::new();
                for (k, (row, repeat)) in rows.into_iter().enumerate() {
                    if repeat && k > 0 {
                        let prev = w[(k - 1) * dof..k * dof].to_vec();
                        w.extend(prev);
                    } else {
                        w.extend(row);
                    }
                }
                (dof, w)
            })
    })
}

/// Strictly increasing abscissae with extreme spacings (and sometimes a duplicate).
fn abscissae(n: usize, spacing: f64, duplicate: bool) -> Vec<f64> {
    let mut x: Vec<f64> = (0..n).map(|k| k as f64 * spacing).collect();
    if duplicate && n > 2 {
        x[2] = x[1];
    }
    x
}

fn check_otg(d: &[[f64; 9]; 2], o: Options) {
    let inp = input(d, o);
    for dt in [0.001, 1e-300] {
        if let Ok(t) = Otg::<2>::new(dt).calculate(&inp) {
            sample(&t, 2);
        }
    }
    let dynamic = DynInputParameter::from(&inp);
    if let Ok(t) = calculate_dyn(&dynamic, 0.001) {
        sample(&t, 2);
    }
    // The same problem through one intermediate waypoint: the start repeated, then the
    // target (duplicate adjacent positions) or the midpoint.
    for mid in [inp.current_position.to_vec(), inp.target_position.to_vec()] {
        if let Ok(t) = plan_waypoints(&dynamic, &Waypoints::new(vec![mid]), 0.001) {
            sample(&t, 2);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 3000,
        // Reproducible runs, no failure files: a failure prints its shrunk case.
        rng_seed: RngSeed::Fixed(0x6e6f_7061),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// The online generator, fixed and dynamic DOF, with and without waypoints.
    #[test]
    fn otg_never_panics(a in dof(), b in dof(), o in options()) {
        check_otg(&[a, b], o);
    }

    /// Spline construction and evaluation: extreme spacings, duplicate abscissae, extreme
    /// and non-finite ordinates.
    #[test]
    fn splines_never_panic(
        (dof, y) in points(),
        spacing in prop_oneof![3 => magnitude(), 1 => Just(f64::NAN), 1 => Just(0.0)],
        duplicate in any::<bool>(),
        poison in prop_oneof![4 => Just(None), 1 => Just(Some(f64::NAN)), 1 => Just(Some(f64::INFINITY))],
    ) {
        let n = y.len() / dof;
        let mut y = y;
        if let Some(p) = poison {
            y[0] = p;
        }
        let x = abscissae(n, spacing, duplicate);
        let mut out = vec![0.0; dof];
        let mut eval = |p: &dyn Path| {
            let (a, b) = p.interval();
            for s in [a, 0.5 * (a + b), b, b + 1.0, f64::NAN] {
                for k in 0..3 {
                    p.eval(s, k, &mut out);
                }
            }
        };
        if let Ok(p) = CubicSpline::natural(&x, &y, dof) { eval(&p) }
        if let Ok(p) = CubicSpline::not_a_knot(&x, &y, dof) { eval(&p) }
        if let Ok(p) = CubicSpline::periodic(&x, &y, dof) { eval(&p) }
        if let Ok(p) = PchipSpline::new(&x, &y, dof) { eval(&p) }
        if let Ok(p) = AkimaSpline::original(&x, &y, dof) { eval(&p) }
        if let Ok(p) = AkimaSpline::modified(&x, &y, dof) { eval(&p) }
        if let Ok(p) = LinearPath::new(&y, dof) { eval(&p) }
        // Point-to-point polynomials between the first two points, limits from the spacing.
        if let Ok(limits) = Limits::uniform(dof, spacing, spacing, spacing) {
            for degree in [Degree::Cubic, Degree::Quintic, Degree::Septic] {
                let _ = min_duration_rest_to_rest(degree, &y[..dof], &y[dof..2 * dof], &limits);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 64,
        rng_seed: RngSeed::Fixed(0x6e6f_7062),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// TOPP-RA on small polylines and `plan` on the same waypoints: extreme limits and
    /// scales, duplicate adjacent waypoints.
    #[test]
    fn toppra_and_plan_never_panic(
        (dof, w) in points(),
        v in limit(),
        a in limit(),
        j in limit(),
        n in prop_oneof![Just(0usize), Just(1), Just(2), Just(16)],
    ) {
        if let (Ok(limits), Ok(path)) = (Limits::uniform(dof, v, a, f64::INFINITY), LinearPath::new(&w, dof)) {
            let options = ToppraOptions { gridpoints: Gridpoints::Uniform(n), ..ToppraOptions::default() };
            if let Ok(t) = Toppra::with_limits(path, &limits).and_then(|p| p.options(options).solve()) {
                sample(&t, dof);
            }
        }
        let names = (0..dof).map(|k| format!("j{k}")).collect();
        if let (Ok(limits), Ok(wp)) = (Limits::uniform(dof, v, a, j), PlanWaypoints::new(w, dof, names)) {
            if let Ok(p) = plan(&wp, &limits, &PlanOptions::default()) {
                sample(&p.trajectory, dof);
            }
        }
    }
}

/// A start acceleration one ulp past its limit: step 1 clamped a level to [a₀, a_max], an
/// empty window (`f64::clamp` panicked); now `num::clamp_in` drops that candidate.
#[test]
fn start_acceleration_one_ulp_past_its_limit() {
    for amax in [0.1, 1.0, 7.3, 1e3] {
        for (v0, d) in [(0.0, 1.0), (0.3, -0.2), (-0.7, 1e-15), (0.9, 0.0)] {
            for sign in [1.0, -1.0] {
                let mut inp = InputParameter::<1>::new();
                inp.current_velocity = [sign * v0];
                inp.current_acceleration = [sign * beyond(amax)];
                inp.target_position = [d];
                inp.target_acceleration = [sign * 0.5 * amax];
                inp.max_velocity = [1.0];
                inp.max_acceleration = [amax];
                inp.max_jerk = [2.0];
                for sync in SYNC {
                    inp.options.synchronization = sync;
                    if let Ok(t) = Otg::<1>::new(0.001).calculate(&inp) {
                        sample(&t, 1);
                    }
                }
            }
        }
    }
}

/// TOTG with an arc step of 1e-300 rad asked for ~10³⁰⁰ knots on each arc (an allocation
/// abort); now a typed error names the count.
#[test]
fn totg_with_a_tiny_arc_step_is_an_error() {
    let path = BlendedPath::new(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0], 2, 0.1).unwrap();
    let limits = Limits::uniform(2, 1.0, 1.0, f64::INFINITY).unwrap();
    let Err(e) = Totg::new(path, &limits)
        .unwrap()
        .arc_step(1e-300)
        .unwrap()
        .solve()
    else {
        panic!("an arc step of 1e-300 was accepted");
    };
    assert!(e.to_string().contains("knots on one arc"), "{e}");
}

/// Point-to-point polynomials across nearly the whole finite range: the derivatives'
/// coefficients overflow (a limit check on them must fail, not panic).
#[test]
fn polynomials_across_the_finite_range() {
    let limits = Limits::uniform(1, 1.0, 1.0, 1.0).unwrap();
    for degree in [Degree::Cubic, Degree::Quintic, Degree::Septic] {
        for (q0, q1) in [(-1.7e308, 1.7e308), (0.0, 1e307), (-1e306, 1e306)] {
            let _ = min_duration_rest_to_rest(degree, &[q0], &[q1], &limits);
        }
    }
}
