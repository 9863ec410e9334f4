//! Property tests with shrinking for TOPP-RA inputs: random paths (polylines and natural
//! cubic splines, duplicate and collinear waypoints included), limits (zero and tiny ones,
//! non-finite and negative values), grids (empty, single point, uniform, automatic) and
//! boundary path velocities. Whatever the input, the solver must not panic: it returns a
//! typed error, or a trajectory that holds its velocity and acceleration limits when sampled
//! densely, starts and ends at the path's ends, and (on a polyline) stays inside the
//! waypoints' bounding box. A failure is shrunk by proptest to a minimal case.

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use trajkit::spline::CubicSpline;
use trajkit::topp::{Gridpoints, LinearPath, Toppra, ToppraOptions};
use trajkit::{Error, Limits, Order, Path, Trajectory};

/// A limit value: mostly ordinary, sometimes degenerate (zero, small, huge) or invalid
/// (negative, NaN, infinite). Small spans 1e-9 to 1e-4 (log-uniform): see also
/// [`tiny_velocity_limits_hold`].
fn limit() -> impl Strategy<Value = f64> {
    prop_oneof![
        24 => 0.2f64..5.0,
        1 => Just(0.0),
        1 => (-9.0f64..-4.0).prop_map(|e| 10f64.powf(e)),
        1 => Just(1e9),
        1 => Just(-1.0),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
    ]
}

/// A boundary path velocity ṡ: mostly rest, sometimes moving, sometimes invalid.
fn boundary_velocity() -> impl Strategy<Value = f64> {
    prop_oneof![
        12 => Just(0.0),
        6 => 0.0f64..0.5,
        1 => Just(50.0),
        1 => Just(-0.1),
        1 => Just(f64::NAN),
    ]
}

/// Gridpoints: automatic, or a uniform count (0 and 1 included).
fn grid() -> impl Strategy<Value = Gridpoints> {
    prop_oneof![
        1 => Just(Gridpoints::Auto { tolerance: 1e-3 }),
        3 => (0usize..60).prop_map(Gridpoints::Uniform),
    ]
}

/// Waypoints (row-major, `dof` columns): 2 to 5 points with coordinates in [−2, 2], where a
/// point may repeat the previous one.
fn waypoints() -> impl Strategy<Value = (usize, Vec<f64>)> {
    (1usize..=3, 2usize..=5).prop_flat_map(|(dof, n)| {
        (
            Just(dof),
            prop::collection::vec((prop::collection::vec(-2.0f64..2.0, dof), any::<bool>()), n),
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

/// Velocity/acceleration use of `traj` against `limits` over at least 2000 samples (both
/// ends included): the largest |v|/v_max and |a|/a_max over joints and samples.
fn worst_use<T: Trajectory>(traj: &T, limits: &Limits) -> (f64, f64) {
    let dof = limits.dof();
    let (mut v, mut a) = (vec![0.0; dof], vec![0.0; dof]);
    let (mut wv, mut wa) = (0.0f64, 0.0f64);
    let n = 2000;
    for k in 0..=n {
        let t = traj.duration() * k as f64 / n as f64;
        traj.eval(t, Order::Velocity, &mut v);
        traj.eval(t, Order::Acceleration, &mut a);
        for (j, jl) in limits.joints().iter().enumerate() {
            wv = wv.max(use_of(v[j], jl.velocity));
            wa = wa.max(use_of(a[j], jl.acceleration));
        }
    }
    (wv, wa)
}

/// |value| / limit, 0 for a zero value (a zero limit may hold a joint that does not move).
fn use_of(value: f64, limit: f64) -> f64 {
    if value == 0.0 {
        0.0
    } else {
        value.abs() / limit
    }
}

/// The properties every solved case holds (see the file's documentation).
fn check_solution<P: Path + Clone>(
    path: &P,
    limits: &Limits,
    options: ToppraOptions,
    bounding_box: Option<(&[f64], usize)>,
) -> Result<(), TestCaseError> {
    let problem = match Toppra::with_limits(path.clone(), limits) {
        Ok(p) => p,
        Err(e) => return typed(e),
    };
    let traj = match problem.options(options).solve() {
        Ok(t) => t,
        Err(e) => return typed(e),
    };
    let dof = limits.dof();
    prop_assert!(traj.duration().is_finite() && traj.duration() >= 0.0);
    let (wv, wa) = worst_use(&traj, limits);
    prop_assert!(wv <= 1.0 + 1e-6, "velocity at {wv} of its limit");
    prop_assert!(wa <= 1.0 + 1e-6, "acceleration at {wa} of its limit");
    let (s0, s1) = path.interval();
    let (mut q, mut p) = (vec![0.0; dof], vec![0.0; dof]);
    for (t, s) in [(0.0, s0), (traj.duration(), s1)] {
        traj.eval(t, Order::Position, &mut q);
        path.eval(s, 0, &mut p);
        for j in 0..dof {
            prop_assert!(
                (q[j] - p[j]).abs() <= 1e-9 * (1.0 + p[j].abs()),
                "end {t}: {q:?} vs {p:?}"
            );
        }
    }
    if let Some((w, dim)) = bounding_box {
        let n = 500;
        for k in 0..=n {
            traj.eval(
                traj.duration() * k as f64 / n as f64,
                Order::Position,
                &mut q,
            );
            for j in 0..dim {
                let col = w.iter().skip(j).step_by(dim);
                let lo = col.clone().fold(f64::INFINITY, |m, &v| m.min(v));
                let hi = col.fold(f64::NEG_INFINITY, |m, &v| m.max(v));
                prop_assert!(
                    q[j] >= lo - 1e-9 && q[j] <= hi + 1e-9,
                    "joint {j}: {} outside [{lo}, {hi}]",
                    q[j]
                );
            }
        }
    }
    Ok(())
}

/// An error is fine when it is a typed one that says something: its message is not empty.
fn typed(e: Error) -> Result<(), TestCaseError> {
    prop_assert!(!e.to_string().is_empty());
    Ok(())
}

fn limits_of(dof: usize, v: f64, a: f64) -> Option<Limits> {
    Limits::uniform(dof, v, a, f64::INFINITY).ok()
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 96,
        // Reproducible runs, no failure files: a failure prints its shrunk case.
        rng_seed: RngSeed::Fixed(0x746f_7070),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Polylines: duplicates and reversals included.
    #[test]
    fn toppra_on_polylines_errs_or_holds_its_limits(
        (dof, w) in waypoints(),
        v in limit(),
        a in limit(),
        grid in grid(),
        v0 in boundary_velocity(),
        v1 in boundary_velocity(),
    ) {
        if v.is_nan() || v < 0.0 || a.is_nan() || a < 0.0 {
            // Invalid limits are refused by Limits itself, before any solver.
            prop_assert!(limits_of(dof, v, a).is_none());
            return Ok(());
        }
        let Some(limits) = limits_of(dof, v, a) else { return Ok(()) };
        let path = match LinearPath::new(&w, dof) {
            Ok(p) => p,
            Err(e) => return typed(e),
        };
        let options = ToppraOptions {
            gridpoints: grid,
            start_velocity: v0,
            end_velocity: v1,
            ..ToppraOptions::default()
        };
        check_solution(&path, &limits, options, Some((&w, dof)))?;
    }

    /// Natural cubic splines through the waypoints, parameterized uniformly.
    #[test]
    fn toppra_on_splines_errs_or_holds_its_limits(
        (dof, w) in waypoints(),
        v in limit(),
        a in limit(),
        grid in grid(),
        v0 in boundary_velocity(),
        v1 in boundary_velocity(),
    ) {
        let Some(limits) = limits_of(dof, v, a) else { return Ok(()) };
        let n = w.len() / dof;
        let x: Vec<f64> = (0..n).map(|k| k as f64).collect();
        let path = match CubicSpline::natural(&x, &w, dof) {
            Ok(p) => p,
            Err(e) => return typed(e),
        };
        let options = ToppraOptions {
            gridpoints: grid,
            start_velocity: v0,
            end_velocity: v1,
            ..ToppraOptions::default()
        };
        check_solution(&path, &limits, options, None)?;
    }
}

/// The smallest case the property test found (shrunk) when its limits went below 1e-4: a
/// natural spline through three points with a velocity limit of 1e-6 or less came out up to
/// 1.9× above its velocity limit while the solver's tolerances were absolute in x = ṡ² (as
/// large as x itself under such limits). They are relative to the problem's scale of x now.
#[test]
fn tiny_velocity_limits_hold() {
    let x = [0.0, 1.0, 2.0];
    let w = [0.0, 1.8964997692526548, -0.7762982103459327];
    let path = CubicSpline::natural(&x, &w, 1).unwrap();
    let speeds = [1.0, 1e-2, 1e-4, 1e-5, 1e-6, 1e-7, 1e-9];
    // Tiny velocity limits alone, then with tiny acceleration limits too.
    let cases = speeds
        .iter()
        .map(|&v| (v, 0.2))
        .chain(speeds.iter().map(|&v| (v, 0.2 * v)));
    for (v, a) in cases {
        let limits = Limits::uniform(1, v, a, f64::INFINITY).unwrap();
        for n in [5, 50] {
            let options = ToppraOptions {
                gridpoints: Gridpoints::Uniform(n),
                ..ToppraOptions::default()
            };
            let traj = Toppra::with_limits(path.clone(), &limits)
                .and_then(|p| p.options(options).solve())
                .unwrap();
            let (wv, wa) = worst_use(&traj, &limits);
            assert!(
                wv <= 1.0 + 1e-6 && wa <= 1.0 + 1e-6,
                "v = {v:e}, a = {a:e}, {n} gridpoints: use {wv}, {wa}"
            );
        }
    }
}
