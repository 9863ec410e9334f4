//! How the default TOPP-RA solve and the default plan scale with path length, and where the
//! time goes.
//!
//! - `toppra`: the solve of `plan.rs`'s `toppra_default/random_W` (the default plan's paths
//!   through W seeded random Panda waypoints, then the auto-grid solve with the
//!   between-gridpoint guarantee), W = 10, 30, 100, 300, 1000;
//! - `plan`: [`trajkit::plan::plan`] with `PlanOptions::default()` (jerk stage, 1 kHz samples
//!   and their check) through the same waypoints, W = 10, 30, 100 (longer motions exceed the
//!   sample table's budget at 1 kHz);
//! - `plan (walk)`: the same through W waypoints of a seeded random walk in the Panda's range
//!   (each joint moves up to ±0.4 rad per waypoint: short segments, where the jerk stage runs
//!   its local slow-down), W = 10, 100, 1000.
//!
//! For each W it prints the median wall time per run and per waypoint over repeated runs on
//! one thread, and — on Linux, from `/proc/self/stat` — the CPU time per run split into user
//! and system time and the page faults per run (the system time is the kernel handing out
//! fresh pages: a thread keeps TOPP-RA's buffers for its next solve up to 64 MB, beyond that
//! they are new memory every time, and so is a plan's sample table once it is too large for
//! the allocator to recycle). The last column is a one-off run: the median of five runs, each
//! in a new process (this binary started again for one run), what a single `trajkit plan`
//! pays.
//!
//! Run: `cargo bench -p trajkit --bench topp_scaling` (about three minutes).

mod common;

use std::hint::black_box;
use std::time::{Duration, Instant};
use trajkit::io::Waypoints;
use trajkit::plan::{plan, PlanOptions};
use trajkit::rng::SplitMix64;
use trajkit::topp::messy;
use trajkit::Limits;

/// W waypoints of a random walk from the middle of the Panda's range: each joint moves by up
/// to ±0.4 rad per waypoint, staying 0.1 rad inside its limits.
fn random_walk(n: usize, limits: &Limits) -> Waypoints {
    let mut rng = SplitMix64::new(2027);
    let joints = limits.joints();
    let mut q: Vec<f64> = joints
        .iter()
        .map(|j| 0.5 * (j.position_min + j.position_max))
        .collect();
    let mut wp = Vec::with_capacity(n * 7);
    for _ in 0..n {
        for (v, j) in q.iter_mut().zip(joints) {
            *v = (*v + rng.uniform(-0.4, 0.4)).clamp(j.position_min + 0.1, j.position_max - 0.1);
        }
        wp.extend_from_slice(&q);
    }
    Waypoints::new(wp, 7, vec![]).unwrap()
}

/// User and system CPU time (clock ticks of 1/100 s, Linux's USER_HZ) and minor page faults
/// of this process, from `/proc/self/stat`; `None` elsewhere.
fn usage() -> Option<[u64; 3]> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which is in parentheses and may hold spaces): state is
    // field 3; minflt is 10, utime 14, stime 15.
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let num = |k: usize| f.get(k - 3)?.parse::<u64>().ok();
    Some([num(14)?, num(15)?, num(10)?])
}

/// Runs `job` repeatedly (at least 5 times and 4 s) and then, five times, in a new process
/// (`args`: what makes this binary run the job once and print its wall time); prints one
/// table row for `w` waypoints.
fn row<T>(label: &str, w: usize, args: [&str; 2], job: &dyn Fn() -> T) {
    black_box(job());
    let mut times = Vec::new();
    let before = usage();
    let start = Instant::now();
    while times.len() < 5 || start.elapsed() < Duration::from_secs(4) {
        let t = Instant::now();
        black_box(job());
        times.push(t.elapsed().as_secs_f64());
    }
    let after = usage();
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let n = times.len() as f64;
    let split = match (before, after) {
        (Some(b), Some(a)) => format!(
            "{:.1} ms | {:.1} ms | {:.0}",
            (a[0] - b[0]) as f64 * 10.0 / n,
            (a[1] - b[1]) as f64 * 10.0 / n,
            (a[2] - b[2]) as f64 / n
        ),
        _ => "— | — | —".into(),
    };
    let exe = std::env::current_exe().unwrap();
    let mut fresh: Vec<f64> = (0..5)
        .map(|_| {
            let out = std::process::Command::new(&exe)
                .args(["--one-off", args[0], args[1]])
                .output()
                .unwrap();
            String::from_utf8_lossy(&out.stdout).trim().parse().unwrap()
        })
        .collect();
    fresh.sort_by(f64::total_cmp);
    println!(
        "| {label} | {w} | {} | {:.3} ms | {:.4} ms | {split} | {:.4} ms |",
        times.len(),
        median * 1e3,
        median * 1e3 / w as f64,
        fresh[2] * 1e3 / w as f64,
    );
}

/// The jobs: (label, job name, waypoint counts).
const JOBS: [(&str, &str, &[usize]); 3] = [
    ("toppra", "toppra", &[10, 30, 100, 300, 1000]),
    ("plan", "plan", &[10, 30, 100]),
    ("plan (walk)", "walk", &[10, 100, 1000]),
];

/// Job `name` on `w` waypoints, as a closure that runs it once and returns the duration.
fn job<'a>(name: &str, w: usize, limits: &'a Limits) -> Box<dyn Fn() -> f64 + 'a> {
    match name {
        "toppra" => {
            let waypoints = common::random_panda_waypoints(w);
            Box::new(move || {
                let options = messy::PlanOptions::default();
                let paths = messy::piece_paths(waypoints.points(), 7, limits, &options).unwrap();
                let raw = messy::time_pieces(paths, limits, &options, &mut |_, _| {}).unwrap();
                trajkit::Trajectory::duration(&raw)
            })
        }
        _ => {
            let waypoints = if name == "plan" {
                common::random_panda_waypoints(w)
            } else {
                random_walk(w, limits)
            };
            Box::new(move || {
                plan(&waypoints, limits, &PlanOptions::default())
                    .unwrap()
                    .duration()
            })
        }
    }
}

fn main() {
    let limits = Limits::preset("panda").unwrap();
    let args: Vec<String> = std::env::args().collect();
    if let Some(k) = args.iter().position(|a| a == "--one-off") {
        // One run in this fresh process: print its wall time (s).
        let w: usize = args[k + 2].parse().unwrap();
        let run = job(&args[k + 1], w, &limits);
        let t = Instant::now();
        black_box(run());
        println!("{}", t.elapsed().as_secs_f64());
        return;
    }
    // `cargo bench` passes `--bench`; a filter argument is not supported.
    println!(
        "| job | waypoints | runs | median wall / run | per waypoint | user / run | system / run | page faults / run | one-off run, per waypoint |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (label, name, counts) in JOBS {
        for &w in counts {
            let run = job(name, w, &limits);
            row(label, w, [name, &w.to_string()], &*run);
        }
    }
}
