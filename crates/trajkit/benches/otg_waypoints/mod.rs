//! Motions through intermediate waypoints (`otg::plan_waypoints`): 7 DOF with Franka Panda
//! limits, 5 waypoints along bent joint-space paths (every joint moves one way, by a random
//! amount per section), start and target at rest. No open peer plans waypoints locally, so
//! there is no side-by-side column; `OTG_WAYP=1` prints the median time per plan and the
//! median duration relative to stopping at every waypoint instead of running criterion.

use criterion::Criterion;
use std::hint::black_box;
use std::time::Instant;
use trajkit::otg::{plan_waypoints, DynInputParameter, Waypoints};
use trajkit::rng::SplitMix64;
use trajkit::Limits;

const CASES: usize = 64;

fn cases(waypoints: usize) -> Vec<(DynInputParameter, Waypoints)> {
    let lim = Limits::preset("panda").unwrap();
    let mut r = SplitMix64::new(0x3a7e + waypoints as u64);
    (0..CASES)
        .map(|_| {
            let mut p = DynInputParameter::new(7);
            let mut x = vec![0.0; 7];
            let mut sign = [1.0; 7];
            for i in 0..7 {
                let j = lim.joint(i);
                p.max_velocity[i] = j.velocity;
                p.max_acceleration[i] = j.acceleration;
                p.max_jerk[i] = j.jerk;
                x[i] = r.uniform(-1.0, 1.0);
                sign[i] = if r.next_u64() % 2 == 0 { 1.0 } else { -1.0 };
            }
            p.current_position.clone_from(&x);
            let mut wps = Vec::new();
            for k in 0..=waypoints {
                for i in 0..7 {
                    x[i] += sign[i] * r.uniform(0.05, 0.6);
                }
                if k < waypoints {
                    wps.push(x.clone());
                }
            }
            p.target_position = x;
            (p, Waypoints::new(wps))
        })
        .collect()
}

/// The criterion group `otg/waypoints_7dof_5`.
pub fn group(c: &mut Criterion) {
    let set = cases(5);
    let mut g = c.benchmark_group("otg/waypoints_7dof_5");
    g.bench_function("trajkit", |b| {
        let mut k = 0;
        b.iter(|| {
            k = (k + 1) % CASES;
            let (p, w) = &set[k];
            black_box(plan_waypoints(black_box(p), w, 0.001).map(|t| t.duration()))
        })
    });
    g.finish();
}

/// Median time per plan (µs) and median duration / stop-at-every, for 1, 5 and 10 waypoints.
pub fn medians() {
    println!("| waypoints | median µs per plan | median duration / stop at every |");
    for m in [1, 5, 10] {
        let set = cases(m);
        let mut times = Vec::new();
        let mut ratios = Vec::new();
        for _round in 0..5 {
            for (p, w) in &set {
                let t0 = Instant::now();
                let tr = plan_waypoints(p, w, 0.001).unwrap();
                times.push(t0.elapsed().as_secs_f64() * 1e6);
                ratios.push(tr.duration() / tr.stop_at_every_waypoint_duration());
            }
        }
        times.sort_by(f64::total_cmp);
        ratios.sort_by(f64::total_cmp);
        println!(
            "| {m:>9} | {:>18.1} | {:>31.3} |",
            times[times.len() / 2],
            ratios[ratios.len() / 2]
        );
    }
}
