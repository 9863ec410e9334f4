//! `trajkit::plan`, the main job: every output keeps every limit it was given (position range
//! included) and passes the checker; names pair columns with limits; impossible requests are
//! typed errors.

use trajkit::check::{check_samples, Tolerance};
use trajkit::io::{table_from_csv, table_to_csv, Waypoints};
use trajkit::plan::{plan, JerkStage, Method, PlanOptions, ViaVelocity};
use trajkit::poly::Degree;
use trajkit::rng::SplitMix64;
use trajkit::topp::messy::PathKind;
use trajkit::topp::Gridpoints;
use trajkit::{Error, Limits, Order};

mod topp_common;

/// The 7-waypoint standard problem (`toppra_panda.json`, `standard_7wp_natural_N1000`).
fn std7() -> Waypoints {
    let rows = topp_common::fixture_waypoints("standard_7wp_natural_N1000");
    Waypoints::new(rows, 7, vec![]).unwrap()
}

fn unlimited_jerk(l: &Limits) -> Limits {
    l.clone()
        .with_override(Order::Jerk, &[f64::INFINITY])
        .unwrap()
}

/// The plan's samples, written as trajkit writes them and read back, checked against `limits`
/// by the checker itself: the verdict `trajkit check` would give.
fn check_written(p: &trajkit::Plan, limits: &Limits) -> trajkit::check::LimitReport {
    let text = table_to_csv(&p.samples);
    let table = table_from_csv(&text, "plan.csv").unwrap();
    check_samples(&table, limits).unwrap()
}

#[test]
fn standard_problem_stays_inside_joint_6_range() {
    // The natural spline leaves joint 6's range [-0.0175, 3.7525] by 0.12 rad between
    // waypoints 2 and 3; the planned path must not.
    let panda = Limits::preset("panda").unwrap();
    let w = std7();
    let raw = PlanOptions {
        jerk: JerkStage::Off,
        ..PlanOptions::default()
    };
    let free = unlimited_jerk(&panda);
    for method in [Method::Toppra, Method::Ni] {
        let p = plan(
            &w,
            &free,
            &PlanOptions {
                method,
                ..raw.clone()
            },
        )
        .unwrap();
        let r = &p.range_repairs;
        assert_eq!(r.len(), 1, "{method:?}: {r:?}");
        assert_eq!(r[0].joint, 5);
        assert!((r[0].excursion - 0.1199).abs() < 1e-3, "{r:?}");
        assert_eq!(r[0].between, (2, 3));
        let report = check_written(&p, &free);
        assert!(
            report.passes(&Tolerance::default()),
            "{method:?}: {:?}",
            report.violations(&Tolerance::default())
        );
        assert!(report.joints[5].position.max <= 3.7525);
    }
    // Polynomial segments: with every Panda limit, jerk included.
    let p = plan(
        &w,
        &panda,
        &PlanOptions {
            method: Method::Poly,
            ..PlanOptions::default()
        },
    )
    .unwrap();
    assert!(check_written(&p, &panda).passes(&Tolerance::default()));
}

#[test]
fn names_pair_columns_with_limits() {
    let panda = Limits::preset("panda").unwrap();
    let names: Vec<String> = panda.joints().iter().map(|j| j.name.clone()).collect();
    let rows = [
        [0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0],
        [0.4, 0.2, -0.2, -1.2, 0.1, 1.8, 0.3],
        [0.8, -0.1, 0.1, -1.8, 0.3, 1.2, 0.6],
    ];
    let opts = PlanOptions {
        method: Method::Poly,
        ..PlanOptions::default()
    };
    let make = |order: &[usize]| {
        let header: Vec<String> = order.iter().map(|&j| names[j].clone()).collect();
        let pts: Vec<f64> = rows
            .iter()
            .flat_map(|r| order.iter().map(move |&j| r[j]))
            .collect();
        Waypoints::new(pts, 7, header).unwrap()
    };
    let straight = plan(&make(&[0, 1, 2, 3, 4, 5, 6]), &panda, &opts).unwrap();
    // Joints 2 and 4 swapped, with their names: the same motion, columns swapped.
    let swapped = plan(&make(&[0, 3, 2, 1, 4, 5, 6]), &panda, &opts).unwrap();
    assert_eq!(straight.duration(), swapped.duration());
    assert_eq!(swapped.names[1], "panda_joint4");
    assert_eq!(swapped.limits.joint(1).acceleration, 12.5);
    let (a, b) = (&straight.samples, &swapped.samples);
    for i in (0..a.len()).step_by(97) {
        assert_eq!(
            a.value(Order::Position, i, 1),
            b.value(Order::Position, i, 3)
        );
    }
    // The same swap without names applies joint 2's limits to joint 4's column: a different
    // (wrong-robot) plan, which the names prevent.
    let unnamed = Waypoints::new(make(&[0, 3, 2, 1, 4, 5, 6]).points().to_vec(), 7, vec![]);
    let e = plan(&unnamed.unwrap(), &panda, &opts).unwrap_err();
    assert!(
        matches!(e, Error::WaypointOutOfRange { joint: 3, .. }),
        "{e}"
    );
    // Unknown names: both sets listed.
    let abc = Waypoints::new(
        vec![0.0, 0.0, 0.0, 0.1, 0.1, 0.1],
        3,
        vec!["a".into(), "b".into(), "c".into()],
    )
    .unwrap();
    let e = plan(&abc, &panda, &opts).unwrap_err();
    match &e {
        Error::JointNames {
            missing,
            limit_names,
            ..
        } => {
            assert_eq!(missing, &["a", "b", "c"]);
            assert_eq!(limit_names.len(), 7);
        }
        other => panic!("{other}"),
    }
    // Extra limit joints are left out, with a note.
    let two = Waypoints::new(
        vec![0.0, 0.0, 0.5, 0.3],
        2,
        vec!["panda_joint7".into(), "panda_joint1".into()],
    )
    .unwrap();
    let p = plan(&two, &panda, &opts).unwrap();
    assert_eq!(p.limits.dof(), 2);
    assert!(
        p.notes
            .iter()
            .any(|n| n.contains("panda_joint2") && n.contains("not used")),
        "{:?}",
        p.notes
    );
    assert_eq!(p.samples.names(), ["panda_joint7", "panda_joint1"]);
}

#[test]
fn methods_that_cannot_bound_jerk_refuse_a_jerk_limit() {
    let panda = Limits::preset("panda").unwrap();
    let w = Waypoints::new(
        vec![
            0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0, 0.3, 0.2, -0.2, -1.2, 0.1, 1.8, 0.3,
        ],
        7,
        vec![],
    )
    .unwrap();
    for opts in [
        PlanOptions {
            method: Method::Totg,
            ..PlanOptions::default()
        },
        PlanOptions {
            jerk: JerkStage::Off,
            ..PlanOptions::default()
        },
        PlanOptions {
            method: Method::Poly,
            degree: Degree::Cubic,
            ..PlanOptions::default()
        },
    ] {
        let e = plan(&w, &panda, &opts).unwrap_err();
        assert!(
            matches!(e, Error::CannotHold { joint: 0, field: "jerk", value, .. } if value == 7500.0),
            "{opts:?}: {e}"
        );
        // Stated unlimited, they plan, and the result passes the checker with those limits.
        let free = unlimited_jerk(&panda);
        let p = plan(&w, &free, &opts).unwrap();
        assert!(check_written(&p, &free).passes(&Tolerance::default()));
    }
}

#[test]
fn sizes_are_refused_before_allocating() {
    let panda = Limits::preset("panda").unwrap();
    let one = Limits::uniform(1, 1.0, 1.0, 1.0).unwrap();
    let many: Vec<f64> = (0..=trajkit::plan::MAX_WAYPOINTS)
        .map(|i| (i % 2) as f64 * 0.1)
        .collect();
    let w = Waypoints::new(many, 1, vec![]).unwrap();
    let e = plan(&w, &one, &PlanOptions::default()).unwrap_err();
    assert!(
        matches!(e, Error::TooLarge { limit, .. } if limit == trajkit::plan::MAX_WAYPOINTS as f64),
        "{e}"
    );
    let w = Waypoints::new(vec![0.0, 0.5], 1, vec![]).unwrap();
    let huge_grid = PlanOptions {
        gridpoints: Gridpoints::Uniform(1 << 26),
        ..PlanOptions::default()
    };
    let e = plan(&w, &one, &huge_grid).unwrap_err();
    assert!(matches!(e, Error::TooLarge { .. }), "{e}");
    let fast = PlanOptions {
        sample_rate: 1e12,
        jerk: JerkStage::Off,
        ..PlanOptions::default()
    };
    let e = plan(&w, &unlimited_jerk(&one), &fast).unwrap_err();
    assert!(
        e.to_string().starts_with("sample count (duration × rate)"),
        "{e}"
    );
    let _ = panda;
}

/// Waypoints for a preset: a random walk of `n` points with steps up to `step` rad, half the
/// joints pushed near an end of their range (where overshoot matters).
fn walk(rng: &mut SplitMix64, l: &Limits, n: usize, step: f64) -> Vec<f64> {
    let dof = l.dof();
    let mut p: Vec<f64> = (0..dof)
        .map(|j| {
            let jl = l.joint(j);
            let (lo, hi) = (jl.position_min, jl.position_max);
            if rng.next_f64() < 0.5 {
                if rng.next_f64() < 0.5 {
                    lo + 0.02 * (hi - lo) * rng.next_f64()
                } else {
                    hi - 0.02 * (hi - lo) * rng.next_f64()
                }
            } else {
                rng.uniform(lo, hi)
            }
        })
        .collect();
    let mut out = p.clone();
    for _ in 1..n {
        for (j, q) in p.iter_mut().enumerate() {
            let jl = l.joint(j);
            *q = (*q + rng.uniform(-step, step)).clamp(jl.position_min, jl.position_max);
        }
        out.extend_from_slice(&p);
    }
    out
}

/// Every preset × every method and path option on seeded random waypoint sets: each plan
/// returns, and its written samples pass the checker with the limits it was given.
fn seeded_suite(cases: u64, n: usize, step: f64) {
    let option_sets: Vec<(PlanOptions, bool)> = vec![
        (PlanOptions::default(), false),
        (
            PlanOptions {
                method: Method::Ni,
                jerk: JerkStage::Off,
                ..PlanOptions::default()
            },
            true,
        ),
        (
            PlanOptions {
                path: PathKind::NotAKnotCubic,
                jerk: JerkStage::Off,
                gridpoints: Gridpoints::Uniform(200),
                ..PlanOptions::default()
            },
            true,
        ),
        (
            PlanOptions {
                path: PathKind::ClampedCubic,
                jerk: JerkStage::Off,
                gridpoints: Gridpoints::Uniform(200),
                ..PlanOptions::default()
            },
            true,
        ),
        (
            PlanOptions {
                path: PathKind::Linear,
                jerk: JerkStage::Off,
                gridpoints: Gridpoints::Uniform(200),
                ..PlanOptions::default()
            },
            true,
        ),
        (
            PlanOptions {
                method: Method::Totg,
                ..PlanOptions::default()
            },
            true,
        ),
        (
            PlanOptions {
                method: Method::Poly,
                ..PlanOptions::default()
            },
            false,
        ),
        (
            PlanOptions {
                method: Method::Poly,
                degree: Degree::Septic,
                via_velocity: ViaVelocity::Zero,
                ..PlanOptions::default()
            },
            false,
        ),
        (
            PlanOptions {
                method: Method::Poly,
                degree: Degree::Cubic,
                ..PlanOptions::default()
            },
            true,
        ),
    ];
    let mut repaired = 0;
    for preset in ["panda", "ur5e", "iiwa14"] {
        let full = Limits::preset(preset).unwrap();
        for case in 0..cases {
            let mut rng = SplitMix64::new(1000 * case + preset.len() as u64);
            let pts = walk(&mut rng, &full, n, step);
            let w = Waypoints::new(pts, full.dof(), vec![]).unwrap();
            for (k, (opts, free)) in option_sets.iter().enumerate() {
                if opts.jerk == JerkStage::Filter && opts.method == Method::Toppra && case % 2 == 1
                {
                    continue; // the jerk filter is the slow part: every other case
                }
                let limits = if *free {
                    unlimited_jerk(&full)
                } else {
                    full.clone()
                };
                let p = plan(&w, &limits, opts)
                    .unwrap_or_else(|e| panic!("{preset} case {case} options {k}: {e}"));
                repaired += p.range_repairs.len();
                let report = check_written(&p, &limits);
                let tol = Tolerance::default();
                assert!(
                    report.passes(&tol),
                    "{preset} case {case} options {k}: {:?}",
                    report.violations(&tol)
                );
                assert!(p.report.passes(&tol));
            }
        }
    }
    assert!(repaired > 0, "no case needed a range repair");
}

#[test]
fn seeded_random_waypoints_on_three_robots() {
    seeded_suite(2, 4, 0.4);
}

#[test]
#[ignore = "long: 30 seeded waypoint sets per robot, every method (cargo test --release -- --ignored)"]
fn seeded_random_waypoints_on_three_robots_long() {
    seeded_suite(30, 8, 0.8);
}
