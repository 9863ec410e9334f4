//! Motions through intermediate waypoints (`otg::plan_waypoints`): seeded 7-DOF random sets
//! with Franka Panda limits, each case checked by an independent dense-sampling checker
//! (only `Trajectory::eval`: limits at 2 kHz and at every section boundary, position and
//! velocity consistent with finite differences, every waypoint passed), never longer than
//! stopping at every waypoint, and at most 0.8× that along bent joint-space paths (no joint
//! reverses at a waypoint). Also per-section limits and minimum durations, bad input, and
//! the JSON reader; and (ignored, long) the bent paths next to `trajkit::plan`'s jerk-limited
//! path parameterization through the same points.

use trajkit::otg::{plan_waypoints, DynInputParameter, OtgError, WaypointTrajectory, Waypoints};
use trajkit::rng::SplitMix64;
use trajkit::{Limits, Order, Trajectory};

const N: usize = 7;

fn panda_input() -> DynInputParameter {
    let lim = Limits::preset("panda").unwrap();
    let mut p = DynInputParameter::new(N);
    for i in 0..N {
        let j = lim.joint(i);
        p.max_velocity[i] = j.velocity;
        p.max_acceleration[i] = j.acceleration;
        p.max_jerk[i] = j.jerk;
    }
    p
}

/// A bent path: every joint moves in one direction (random per joint) by a random amount in
/// each section, so the direction in joint space turns at every waypoint but no joint
/// reverses. Start and target at rest.
fn bent_case(r: &mut SplitMix64) -> (DynInputParameter, Waypoints) {
    let mut p = panda_input();
    let m = 1 + (r.next_u64() % 10) as usize;
    let sign: Vec<f64> = (0..N)
        .map(|_| if r.next_u64() % 2 == 0 { 1.0 } else { -1.0 })
        .collect();
    let mut x: Vec<f64> = (0..N).map(|_| r.uniform(-1.0, 1.0)).collect();
    p.current_position.clone_from(&x);
    let mut wps = Vec::new();
    for k in 0..=m {
        for i in 0..N {
            x[i] += sign[i] * r.uniform(0.05, 0.6);
        }
        if k < m {
            wps.push(x.clone());
        }
    }
    p.target_position = x;
    (p, Waypoints::new(wps))
}

/// A general case: random waypoints (joints may reverse), random start and target states
/// inside the limits.
fn general_case(r: &mut SplitMix64) -> (DynInputParameter, Waypoints) {
    let mut p = panda_input();
    let m = 1 + (r.next_u64() % 6) as usize;
    for i in 0..N {
        p.current_position[i] = r.uniform(-2.0, 2.0);
        p.target_position[i] = r.uniform(-2.0, 2.0);
        p.current_velocity[i] = r.uniform(-0.5, 0.5) * p.max_velocity[i];
        p.target_velocity[i] = r.uniform(-0.5, 0.5) * p.max_velocity[i];
        p.current_acceleration[i] = r.uniform(-0.3, 0.3) * p.max_acceleration[i];
    }
    let wps = (0..m)
        .map(|_| (0..N).map(|_| r.uniform(-2.0, 2.0)).collect())
        .collect();
    (p, Waypoints::new(wps))
}

/// Section `s`'s limit of DOF `i` from a per-section field or the global one.
fn lim(per: &Option<Vec<Vec<f64>>>, global: &[f64], s: usize, i: usize) -> f64 {
    per.as_ref().map_or(global[i], |v| v[s][i])
}

/// The independent checker: samples the trajectory through `Trajectory::eval` only. Returns
/// the largest waypoint position error.
fn check_dense(inp: &DynInputParameter, wp: &Waypoints, tr: &WaypointTrajectory) -> f64 {
    let t_end = tr.duration();
    let starts = tr.section_start_times().to_vec();
    let mut times: Vec<f64> = (0..=(t_end * 2000.0).ceil() as usize)
        .map(|k| (k as f64 / 2000.0).min(t_end))
        .collect();
    for &s in &starts {
        times.extend([s, (s - 1e-9).max(0.0), (s + 1e-9).min(t_end)]);
    }
    let (mut p, mut v, mut a, mut j) = ([0.0; N], [0.0; N], [0.0; N], [0.0; N]);
    let (mut pm, mut pp) = ([0.0; N], [0.0; N]);
    for &t in &times {
        let s = starts.partition_point(|&x| x <= t).saturating_sub(1);
        // At a boundary both sections' limits apply to the shared state; use the larger
        // excess allowance only for jerk, which jumps there.
        tr.eval(t, Order::Position, &mut p);
        tr.eval(t, Order::Velocity, &mut v);
        tr.eval(t, Order::Acceleration, &mut a);
        tr.eval(t, Order::Jerk, &mut j);
        for i in 0..N {
            let vmax = lim(&wp.per_section_max_velocity, &inp.max_velocity, s, i);
            let amax = lim(
                &wp.per_section_max_acceleration,
                &inp.max_acceleration,
                s,
                i,
            );
            let jmax = lim(&wp.per_section_max_jerk, &inp.max_jerk, s, i);
            let jmax_prev = if s > 0 {
                lim(&wp.per_section_max_jerk, &inp.max_jerk, s - 1, i)
            } else {
                jmax
            };
            // The first section may start outside the limits (then it brakes first).
            let first = s == 0;
            let (vl, al) = if first {
                (
                    vmax.max(inp.current_velocity[i].abs()),
                    amax.max(inp.current_acceleration[i].abs()),
                )
            } else {
                (vmax, amax)
            };
            assert!(v[i].abs() <= vl * (1.0 + 1e-9), "v[{i}]={} t={t}", v[i]);
            assert!(a[i].abs() <= al * (1.0 + 1e-9), "a[{i}]={} t={t}", a[i]);
            assert!(
                j[i].abs() <= jmax.max(jmax_prev) * (1.0 + 1e-12),
                "j[{i}]={}",
                j[i]
            );
        }
        // Velocity is the derivative of position (central difference, error ≤ j h²/6).
        let h = 1e-5;
        if t > h && t + h < t_end {
            tr.eval(t - h, Order::Position, &mut pm);
            tr.eval(t + h, Order::Position, &mut pp);
            for i in 0..N {
                let fd = (pp[i] - pm[i]) / (2.0 * h);
                let jmax = inp.max_jerk[i];
                assert!(
                    (fd - v[i]).abs() <= jmax * h * h + 1e-9,
                    "fd {fd} v {}",
                    v[i]
                );
            }
        }
    }
    // Every waypoint is passed at the start of its following section; the target at the end.
    let mut worst = 0.0f64;
    for (k, w) in wp.intermediate_positions.iter().enumerate() {
        tr.eval(starts[k + 1], Order::Position, &mut p);
        for i in 0..N {
            worst = worst.max((p[i] - w[i]).abs());
        }
    }
    tr.eval(t_end, Order::Position, &mut p);
    tr.eval(t_end, Order::Velocity, &mut v);
    for i in 0..N {
        worst = worst.max((p[i] - inp.target_position[i]).abs());
        assert!((v[i] - inp.target_velocity[i]).abs() <= 1e-9);
    }
    assert!(worst <= 1e-8, "waypoint error {worst}");
    worst
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

#[test]
fn bent_paths_pass_every_waypoint_within_limits_and_save_a_fifth() {
    let mut r = SplitMix64::new(0x5eed_0016);
    let mut ratios = Vec::new();
    for _ in 0..60 {
        let (inp, wp) = bent_case(&mut r);
        let tr = plan_waypoints(&inp, &wp, 0.001).unwrap();
        check_dense(&inp, &wp, &tr);
        let c = trajkit::otg::check_waypoints(&inp, &wp, &tr).unwrap();
        assert!(c.waypoint_error <= 1e-8 && c.solution.worst_limit_ratio <= 1.0 + 1e-12);
        let ratio = tr.duration() / tr.stop_at_every_waypoint_duration();
        assert!(
            ratio <= 0.8,
            "ratio {ratio} with {} waypoints",
            wp.sections() - 1
        );
        ratios.push(ratio);
    }
    let med = median(ratios.clone());
    let worst = ratios.iter().cloned().fold(0.0, f64::max);
    eprintln!("bent paths: duration / stop-at-every median {med:.3}, worst {worst:.3}");
}

#[test]
fn general_sets_pass_every_waypoint_and_never_exceed_stopping() {
    let mut r = SplitMix64::new(0x5eed_0017);
    for _ in 0..40 {
        let (inp, wp) = general_case(&mut r);
        let tr = plan_waypoints(&inp, &wp, 0.001).unwrap();
        check_dense(&inp, &wp, &tr);
        assert!(tr.duration() <= tr.stop_at_every_waypoint_duration());
    }
}

#[test]
fn per_section_limits_and_minimum_durations_hold() {
    let mut r = SplitMix64::new(0x5eed_0018);
    for _ in 0..20 {
        let (inp, mut wp) = bent_case(&mut r);
        let s = wp.sections();
        let scale = |r: &mut SplitMix64, g: &[f64]| -> Vec<Vec<f64>> {
            (0..s)
                .map(|_| g.iter().map(|x| x * r.uniform(0.3, 1.0)).collect())
                .collect()
        };
        wp.per_section_max_velocity = Some(scale(&mut r, &inp.max_velocity));
        wp.per_section_max_acceleration = Some(scale(&mut r, &inp.max_acceleration));
        wp.per_section_max_jerk = Some(scale(&mut r, &inp.max_jerk));
        let mins: Vec<f64> = (0..s).map(|_| r.uniform(0.0, 1.5)).collect();
        wp.per_section_minimum_duration = Some(mins.clone());
        let tr = plan_waypoints(&inp, &wp, 0.001).unwrap();
        check_dense(&inp, &wp, &tr);
        for (sec, m) in tr.sections().iter().zip(&mins) {
            assert!(sec.duration() >= m - 1e-12, "{} < {m}", sec.duration());
        }
        assert!(tr.duration() <= tr.stop_at_every_waypoint_duration());
    }
}

#[test]
fn no_waypoints_is_the_plain_generator() {
    let mut r = SplitMix64::new(7);
    let (inp, _) = general_case(&mut r);
    let tr = plan_waypoints(&inp, &Waypoints::new(vec![]), 0.001).unwrap();
    let plain = trajkit::otg::calculate_dyn(&inp, 0.001).unwrap();
    assert_eq!(tr.duration(), plain.duration());
    assert!(same_motion(&tr.sections()[0], &plain));
}

/// Equal durations and profiles (the cached minimum durations may be NaN, never equal).
fn same_motion(a: &trajkit::otg::DynTrajectory, b: &trajkit::otg::DynTrajectory) -> bool {
    a.duration() == b.duration()
        && a.dofs()
            .iter()
            .zip(b.dofs())
            .all(|(x, y)| x.profile == y.profile)
}

/// The error of planning, which `Waypoints::validate` (Ruckig's `validate_input`) must give
/// the same, message included.
fn err(inp: &DynInputParameter, wp: &Waypoints) -> OtgError {
    let e = plan_waypoints(inp, wp, 0.001).unwrap_err();
    for (cur, tgt) in [(false, false), (true, true)] {
        let v = wp.validate(inp, 0.001, cur, tgt).unwrap_err();
        // Debug strings: NaN values compare unequal.
        assert_eq!(format!("{v:?} {v}"), format!("{e:?} {e}"));
    }
    e
}

#[test]
fn validate_input_checks_the_states_against_the_first_and_last_section() {
    let mut r = SplitMix64::new(13);
    let (mut inp, mut wp) = bent_case(&mut r);
    assert_eq!(wp.validate(&inp, 0.001, true, true), Ok(()));
    // A current velocity above the global limit but within the first section's.
    inp.current_velocity[2] = 1.5 * inp.max_velocity[2];
    let mut rows = vec![inp.max_velocity.clone(); wp.sections()];
    rows[0][2] *= 2.0;
    wp.per_section_max_velocity = Some(rows.clone());
    assert_eq!(wp.validate(&inp, 0.001, true, true), Ok(()));
    rows[0][2] = inp.max_velocity[2];
    wp.per_section_max_velocity = Some(rows.clone());
    assert!(matches!(
        wp.validate(&inp, 0.001, true, true),
        Err(OtgError::InvalidInput {
            field: "current_velocity",
            dof: Some(2),
            ..
        })
    ));
    assert_eq!(wp.validate(&inp, 0.001, false, true), Ok(()));
    // The target state against the last section's limits.
    inp.current_velocity[2] = 0.0;
    inp.target_velocity[5] = 0.9 * inp.max_velocity[5];
    assert_eq!(wp.validate(&inp, 0.001, true, true), Ok(()));
    rows.last_mut().unwrap()[5] = 0.5 * inp.max_velocity[5];
    wp.per_section_max_velocity = Some(rows);
    // A target velocity outside its limits is refused whatever the flags, as planning does.
    let e = plan_waypoints(&inp, &wp, 0.001).unwrap_err();
    assert!(matches!(
        e,
        OtgError::InvalidInput {
            field: "target_velocity",
            dof: Some(5),
            ..
        }
    ));
    assert_eq!(wp.validate(&inp, 0.001, false, true), Err(e));
    assert_eq!(wp.validate(&inp, 0.001, false, false), Err(e));
}

#[test]
fn bad_input_is_a_typed_error_naming_field_index_and_value() {
    let mut r = SplitMix64::new(9);
    let (inp, wp) = bent_case(&mut r);
    let field_of = |e: OtgError| match e {
        OtgError::Waypoints {
            index, dof, field, ..
        } => (field, index, dof),
        OtgError::InvalidInput { dof, field, .. } => (field, usize::MAX, dof),
        other => panic!("{other}"),
    };
    let mut w = wp.clone();
    w.intermediate_positions[0].pop();
    assert_eq!(field_of(err(&inp, &w)), ("intermediate_positions", 0, None));
    let mut w = wp.clone();
    w.intermediate_positions[0] = vec![];
    assert_eq!(field_of(err(&inp, &w)), ("intermediate_positions", 0, None));
    let mut w = wp.clone();
    w.intermediate_positions[0][3] = f64::NAN;
    assert_eq!(
        field_of(err(&inp, &w)),
        ("intermediate_positions", 0, Some(3))
    );
    let mut w = wp.clone();
    w.intermediate_positions
        .insert(0, inp.current_position.clone());
    let e = err(&inp, &w);
    assert!(e.to_string().contains("duplicate"), "{e}");
    let mut w = wp.clone();
    w.intermediate_positions.push(inp.target_position.clone());
    assert!(err(&inp, &w).to_string().contains("equals target_position"));
    let mut w = wp.clone();
    w.per_section_max_velocity = Some(vec![inp.max_velocity.clone()]);
    assert_eq!(field_of(err(&inp, &w)).0, "per_section_max_velocity");
    let mut w = wp.clone();
    let mut rows = vec![inp.max_jerk.clone(); wp.sections()];
    rows[0][2] = -1.0;
    w.per_section_max_jerk = Some(rows);
    assert_eq!(
        field_of(err(&inp, &w)),
        ("per_section_max_jerk", 0, Some(2))
    );
    let mut w = wp.clone();
    let mut d = vec![0.0; wp.sections()];
    d[wp.sections() - 1] = f64::NAN;
    w.per_section_minimum_duration = Some(d);
    assert_eq!(
        field_of(err(&inp, &w)),
        ("per_section_minimum_duration", wp.sections() - 1, None)
    );
    // Unsupported options are refused, not ignored.
    let mut i2 = inp.clone();
    i2.options.synchronization = trajkit::otg::Synchronization::None;
    assert_eq!(field_of(err(&i2, &wp)).0, "synchronization");
    let mut i2 = inp.clone();
    i2.enabled[4] = false;
    assert_eq!(field_of(err(&i2, &wp)), ("enabled", usize::MAX, Some(4)));
    let mut i2 = inp.clone();
    i2.options.minimum_duration = Some(1.0);
    assert_eq!(field_of(err(&i2, &wp)).0, "minimum_duration");
    // Waypoints outside the position limits.
    let mut i2 = inp.clone();
    i2.max_position = vec![10.0; N];
    i2.max_position[1] = wp.intermediate_positions[0][1] - 1e-3;
    i2.current_position[1] = i2.current_position[1].min(i2.max_position[1]);
    i2.target_position[1] = i2.target_position[1].min(i2.max_position[1]);
    assert_eq!(
        field_of(err(&i2, &wp)),
        ("intermediate_positions", 0, Some(1))
    );
    // The input's own fields are checked by the generator's validation.
    let mut i2 = inp.clone();
    i2.max_acceleration[6] = f64::NAN;
    assert_eq!(
        field_of(err(&i2, &wp)),
        ("max_acceleration", usize::MAX, Some(6))
    );
}

#[cfg(feature = "serde")]
#[test]
fn json_problems_with_waypoints_plan_as_the_library() {
    use trajkit::otg::json::{answer_waypoints, parse_problem};
    let mut r = SplitMix64::new(11);
    let (inp, wp) = bent_case(&mut r);
    let text = serde_json::json!({
        "current_position": inp.current_position,
        "target_position": inp.target_position,
        "max_velocity": inp.max_velocity,
        "max_acceleration": inp.max_acceleration,
        "max_jerk": inp.max_jerk,
        "intermediate_positions": wp.intermediate_positions,
        "per_section_minimum_duration": vec![0.25; wp.sections()],
        "dt": 0.01,
    })
    .to_string();
    let p = parse_problem(&text, "wp.json", 0).unwrap();
    let w = p.waypoints.clone().unwrap();
    assert_eq!(w.intermediate_positions, wp.intermediate_positions);
    assert_eq!(p.input, inp);
    let tr = plan_waypoints(&p.input, &w, p.delta_time).unwrap();
    let mut lib = wp.clone();
    lib.per_section_minimum_duration = Some(vec![0.25; wp.sections()]);
    let direct = plan_waypoints(&inp, &lib, 0.01).unwrap();
    assert_eq!(tr.duration(), direct.duration());
    for (a, b) in tr.sections().iter().zip(direct.sections()) {
        assert!(same_motion(a, b));
    }
    let a = answer_waypoints(&p, &w, &tr).unwrap();
    assert_eq!(a["duration"].as_f64(), Some(tr.duration()));
    assert!(a["waypoint_error"].as_f64().unwrap() <= 1e-8);
    assert!(a["worst_limit_ratio"].as_f64().unwrap() <= 1.0 + 1e-12);
    assert_eq!(
        a["section_durations"].as_array().unwrap().len(),
        wp.sections()
    );
}

/// The waypoint motion next to the default jerk-limited path parameterization
/// (`trajkit::plan`: TOPP-RA along a natural cubic spline through the same points, then the
/// jerk stage) on the seeded bent 7-DOF paths of the test above (same seed, same cases, same
/// Panda velocity/acceleration/jerk limits, no position ranges). Prints the per-case ratio
/// (waypoint motion / plan) and their distribution; long (60 plans), so ignored by default:
/// `cargo test --release -p trajkit --test otg_waypoints -- --ignored --nocapture`.
#[test]
#[ignore]
fn bent_paths_next_to_the_path_parameterization() {
    let lim = Limits::preset("panda").unwrap();
    let joints = (0..N)
        .map(|i| {
            let mut j = lim.joint(i).clone();
            (j.position_min, j.position_max) = (f64::NEG_INFINITY, f64::INFINITY);
            j
        })
        .collect();
    let lim = Limits::new(joints).unwrap();
    let mut r = SplitMix64::new(0x5eed_0016);
    let (mut vs_plan, mut vs_stop) = (Vec::new(), Vec::new());
    for case in 0..60 {
        let (inp, wp) = bent_case(&mut r);
        let tr = plan_waypoints(&inp, &wp, 0.001).unwrap();
        let mut pts = inp.current_position.clone();
        for w in &wp.intermediate_positions {
            pts.extend_from_slice(w);
        }
        pts.extend_from_slice(&inp.target_position);
        let path = trajkit::io::Waypoints::new(pts, N, Vec::new()).unwrap();
        let plan = trajkit::plan(&path, &lim, &trajkit::PlanOptions::default()).unwrap();
        let (tw, tp) = (tr.duration(), plan.trajectory.duration());
        let stop = tr.stop_at_every_waypoint_duration();
        eprintln!(
            "case {case:2} ({} waypoints): waypoints {tw:.4} s, plan {tp:.4} s, ratio {:.3}; \
             stop-at-every {stop:.4} s (plan/stop {:.3})",
            wp.sections() - 1,
            tw / tp,
            tp / stop
        );
        vs_plan.push(tw / tp);
        vs_stop.push(tp / stop);
    }
    let q = |x: &[f64], f: f64| {
        let mut y = x.to_vec();
        y.sort_by(f64::total_cmp);
        y[((y.len() - 1) as f64 * f).round() as usize]
    };
    eprintln!(
        "waypoints / plan: min {:.3}, quartiles {:.3} {:.3} {:.3}, max {:.3}",
        q(&vs_plan, 0.0),
        q(&vs_plan, 0.25),
        q(&vs_plan, 0.5),
        q(&vs_plan, 0.75),
        q(&vs_plan, 1.0)
    );
    eprintln!(
        "plan / stop-at-every: median {:.3}, max {:.3}",
        q(&vs_stop, 0.5),
        q(&vs_stop, 1.0)
    );
    // Both are valid motions through the same points; the measured distribution is the
    // result (BENCHMARKS.md). Sanity only: neither is absurdly off the other.
    assert!(vs_plan.iter().all(|&x| x > 0.2 && x < 5.0));
}
