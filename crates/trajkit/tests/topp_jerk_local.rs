//! The local jerk stage (`topp::jerk_local`): never longer than the filter, limits along the
//! continuous trajectory (50 kHz samples, finite differences), overhead over raw TOPP-RA on
//! seeded curved 7-DOF paths and the 1e-3 rad segment case, against the IPOPT reference
//! (`tests/fixtures/jerk/curved_ipopt.json`).
//!
//! The table for BENCHMARKS.md is `#[ignore]`d:
//! `cargo test --release -p trajkit --test topp_jerk_local -- --ignored --nocapture`.

mod jerk_common;
mod topp_common;

use jerk_common::{
    chord_spline, ipopt_cases, panda_with_jerk_scale, random_path, short_segment_path,
};
use topp_common::{finite_difference_error, worst_ratio_with_range};
use trajkit::topp::jerk::{limit_jerk, JerkOptions};
use trajkit::topp::jerk_local::{limit_jerk_local, LocalOptions, LocalReport};
use trajkit::topp::Toppra;
use trajkit::{Limits, Order, Path, Trajectory};

/// Raw TOPP-RA (default options), the filter and the local stage on `path`.
fn run<P: Path + Clone>(path: &P, limits: &Limits) -> (f64, f64, LocalReport, [f64; 2]) {
    let raw = Toppra::with_limits(path.clone(), limits)
        .unwrap()
        .solve()
        .unwrap();
    let t0 = std::time::Instant::now();
    let filt = limit_jerk(
        path.clone(),
        raw.law().clone(),
        limits,
        &JerkOptions::default(),
    )
    .unwrap();
    let filter_ms = t0.elapsed().as_secs_f64() * 1e3;
    let t0 = std::time::Instant::now();
    let (traj, report) = limit_jerk_local(
        path.clone(),
        raw.law().clone(),
        limits,
        &LocalOptions::default(),
    )
    .unwrap();
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    assert!(traj.duration() <= filt.duration(), "longer than the filter");
    assert_eq!(traj.duration(), report.duration);
    // (Position ranges: these natural splines may leave them; `plan` repairs the path first.)
    let (w, _) = worst_ratio_with_range(&traj, limits, 50_000.0);
    assert!(w.iter().all(|&r| r <= 1.0 + 1e-9), "{w:?}");
    let fd = finite_difference_error(&traj, 400);
    assert!(fd[0] < 1e-6, "{fd:?}");
    let dv = difference_error(&traj, Order::Velocity, 1e-6, 400);
    assert!(dv < 1e-5, "velocity against acceleration: {dv}");
    assert!(difference_error(&traj, Order::Acceleration, 1e-7, 400) < 1e-3);
    (raw.duration(), filt.duration(), report, [filter_ms, ms])
}

/// Central differences (step h) of `order` (velocity or acceleration) against the evaluated
/// next order (relative to 1 + its size) at `count` times, skipping the instants within 2h of
/// a jerk jump larger than the tolerance: the filtered law's jerk jumps at its kinks, a few
/// milliseconds apart (less on short segments), and a jump Δj within h of an instant moves
/// the velocity's difference by up to Δj·h/4 and the acceleration's by up to Δj/2; a jump
/// below the tolerance moves them by at most that much.
fn difference_error(traj: &dyn Trajectory, order: Order, h: f64, count: usize) -> f64 {
    let next = match order {
        Order::Velocity => Order::Acceleration,
        _ => Order::Jerk,
    };
    let n = traj.dof();
    let (mut a, mut b, mut c, mut j0, mut j1) = (
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
    );
    let mut err = 0.0f64;
    let mut checked = 0;
    for k in 1..count {
        let t = traj.duration() * (k as f64 + 0.381_966) / (count as f64 + 1.0);
        traj.eval(t - 2.0 * h, Order::Jerk, &mut j0);
        traj.eval(t + 2.0 * h, Order::Jerk, &mut j1);
        if j0
            .iter()
            .zip(&j1)
            .any(|(x, y)| (x - y).abs() > 1e-3 * (1.0 + x.abs()))
        {
            continue;
        }
        checked += 1;
        traj.eval(t + h, order, &mut a);
        traj.eval(t - h, order, &mut b);
        traj.eval(t, next, &mut c);
        for q in 0..n {
            let num = (a[q] - b[q]) / (2.0 * h);
            err = err.max((num - c[q]).abs() / (1.0 + c[q].abs()));
        }
    }
    assert!(
        checked > count / 4,
        "only {checked} of {count} instants away from kinks"
    );
    err
}

#[test]
fn curved_paths_hold_the_limits_and_beat_the_filter_at_one_percent_jerk() {
    let limits = panda_with_jerk_scale(0.01);
    for seed in [7, 8] {
        let (raw, filt, rep, _) = run(&random_path(seed, 4), &limits);
        // Overhead over raw TOPP-RA at most 0.6× the filter's on the seeded set of
        // BENCHMARKS.md (asserted by `report_curved_paths`: 0.33-0.56×); these two shorter
        // paths measure 0.605× (seed 7) and 0.35× (seed 8).
        assert!(
            rep.duration - raw <= 0.62 * (filt - raw),
            "seed {seed}: raw {raw} filter {filt} local {}",
            rep.duration
        );
    }
}

#[test]
fn short_segments_stay_within_two_percent_of_raw_toppra() {
    // The filter takes +101 % here; the local slow-down +1.95 %.
    let limits = panda_with_jerk_scale(1.0);
    let (raw, filt, rep, _) = run(&short_segment_path(), &limits);
    assert!(
        rep.duration <= 1.02 * raw,
        "raw {raw} filter {filt} local {}",
        rep.duration
    );
}

/// BENCHMARKS.md: per-path figures against the IPOPT reference and the 1e-3 rad segment case.
#[test]
#[ignore]
fn report_curved_paths() {
    println!("| path | jerk ×Panda | IPOPT (s) | raw TOPP-RA (s) | filter (s) | local (s) | local over raw | filter over raw | overhead ratio | local / IPOPT | round | filter ms | local ms |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut cases: Vec<(String, f64, trajkit::spline::CubicSpline, Option<f64>)> = ipopt_cases()
        .into_iter()
        .map(|(n, s, w, d)| (n, s, chord_spline(&w), Some(d)))
        .collect();
    for seed in 0..6u64 {
        for scale in [0.01, 1.0] {
            cases.push((
                format!("random7_{seed}"),
                scale,
                random_path(100 + seed, 7),
                None,
            ));
        }
    }
    cases.push((
        "short_segments_1e-3".into(),
        1.0,
        short_segment_path(),
        None,
    ));
    cases.push((
        "short_segments_1e-3".into(),
        0.01,
        short_segment_path(),
        None,
    ));
    for (name, scale, path, reference) in cases {
        let limits = panda_with_jerk_scale(scale);
        let (raw, filt, rep, ms) = run(&path, &limits);
        // The targets: at 1 % of the Panda's jerk at most 0.6× the filter's overhead on the
        // seeded random paths; at its own limits at most 2 % over raw TOPP-RA.
        if scale < 1.0 && !name.starts_with("short") {
            assert!(rep.duration - raw <= 0.6 * (filt - raw), "{name}");
        }
        if scale == 1.0 {
            assert!(rep.duration <= 1.02 * raw, "{name}");
        }
        let reference_s = reference.map_or("—".to_string(), |r| format!("{r:.5}"));
        let vs = reference.map_or("—".to_string(), |r| format!("{:.4}", rep.duration / r));
        println!(
            "| {name} | {scale} | {reference_s} | {raw:.5} | {filt:.5} | {:.5} | {:+.3} % | {:+.3} % | {:.3} | {vs} | {} | {:.1} | {:.1} |",
            rep.duration,
            100.0 * (rep.duration / raw - 1.0),
            100.0 * (filt / raw - 1.0),
            (rep.duration - raw) / (filt - raw),
            rep.round.map_or("filter".to_string(), |r| r.to_string()),
            ms[0],
            ms[1],
        );
    }
}

/// Median of `runs` timings (ms) of the filter and of the local stage, alternating, on one
/// rest-to-rest TOPP-RA result.
fn median_costs<P: Path + Clone>(
    path: &P,
    law: &trajkit::topp::PhaseProfile,
    limits: &Limits,
    runs: usize,
) -> [f64; 2] {
    let mut ms = [Vec::new(), Vec::new()];
    for _ in 0..runs {
        let t0 = std::time::Instant::now();
        let f = limit_jerk(path.clone(), law.clone(), limits, &JerkOptions::default()).unwrap();
        ms[0].push(t0.elapsed().as_secs_f64() * 1e3);
        let t0 = std::time::Instant::now();
        let l = limit_jerk_local(path.clone(), law.clone(), limits, &LocalOptions::default());
        ms[1].push(t0.elapsed().as_secs_f64() * 1e3);
        assert!(l.unwrap().0.duration() <= f.duration());
    }
    ms.map(|mut v| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    })
}

/// BENCHMARKS.md: the stage's cost next to the filter's (medians of 7 alternating runs) on
/// the standard problem's piece (as `plan` builds it) and the seeded paths.
#[test]
#[ignore]
fn report_costs() {
    println!("| path | jerk ×Panda | filter ms | local ms | ratio |");
    println!("|---|---|---|---|---|");
    let w = topp_common::fixture_waypoints("standard_7wp_natural_N1000");
    let mo = trajkit::topp::messy::PlanOptions::default();
    let panda = Limits::preset("panda").unwrap();
    let paths = trajkit::topp::messy::piece_paths(&w, 7, &panda, &mo).unwrap();
    for scale in [1.0, 0.01] {
        let limits = panda_with_jerk_scale(scale);
        let raw =
            trajkit::topp::messy::time_pieces(paths.clone(), &limits, &mo, &mut |_, _| {}).unwrap();
        let piece = &raw.pieces()[0];
        let [f, l] = median_costs(piece.path(), piece.law(), &limits, 7);
        println!("| std7 | {scale} | {f:.2} | {l:.2} | {:.1} |", l / f);
    }
    let limits = panda_with_jerk_scale(0.01);
    let mut cases: Vec<(String, trajkit::spline::CubicSpline)> = ipopt_cases()
        .into_iter()
        .filter(|c| c.1 == 0.01)
        .map(|(n, _, w, _)| (n, chord_spline(&w)))
        .collect();
    for seed in 0..6u64 {
        cases.push((format!("random7_{seed}"), random_path(100 + seed, 7)));
    }
    for (name, path) in cases {
        let raw = Toppra::with_limits(path.clone(), &limits)
            .unwrap()
            .solve()
            .unwrap();
        let [f, l] = median_costs(&path, raw.law(), &limits, 7);
        println!("| {name} | 0.01 | {f:.2} | {l:.2} | {:.1} |", l / f);
    }
}
