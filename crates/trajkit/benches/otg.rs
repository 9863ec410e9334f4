//! Online trajectory generation, side by side with rsruckig (Ruckig's Rust port) on the same
//! problems in the same run: 1, 3 and 7 DOF with Franka Panda limits (the first N joints),
//! general states (non-zero current and target velocity and acceleration) and rest-to-rest.
//!
//! Both libraries write into a trajectory reused across calls (trajkit's `calculate_into`,
//! rsruckig's `calculate(&input, &mut trajectory)`): the same calling pattern.
//!
//! Criterion reports the mean time per `calculate`; after it, a per-call timing pass over the
//! same problem sets prints mean and p99 (`OTG_P99=0` skips it).
//!
//! `OTG_DUMP=<dir>` writes the six problem sets as text (for timing another implementation on
//! the same problems) and exits.
//!
//! `OTG_MINREP=1` runs only a min-of-repetitions pass instead (each repetition times all
//! problems of one library, the libraries alternate, the minimum per library is kept: robust to
//! load spikes on a shared machine). `OTG_PROFILE=<dof><g|r>` (e.g. `7g`; `R7g` for rsruckig)
//! runs one library alone on one problem set for `OTG_SECS` seconds (default 5), for a
//! profiler.
//!
//! `otg/waypoints_7dof_5` times `plan_waypoints` (7 DOF, 5 waypoints; `otg_waypoints/`);
//! `OTG_WAYP=1` prints its medians instead.
//!
//! Run: `cargo bench -p trajkit --bench otg`.

mod otg_waypoints;

use criterion::{criterion_group, Criterion};
use std::hint::black_box;
use std::time::Instant;
use trajkit::otg::{FixedTrajectory, InputParameter, Otg};
use trajkit::rng::SplitMix64;
use trajkit::Limits;

const PROBLEMS: usize = 512;

fn problems<const N: usize>(general: bool, seed: u64) -> Vec<InputParameter<N>> {
    let lim = Limits::preset("panda").unwrap();
    let mut r = SplitMix64::new(seed);
    (0..PROBLEMS)
        .map(|_| {
            let mut p = InputParameter::<N>::new();
            for i in 0..N {
                let j = lim.joint(i);
                p.max_velocity[i] = j.velocity;
                p.max_acceleration[i] = j.acceleration;
                p.max_jerk[i] = j.jerk;
                p.current_position[i] = r.uniform(-2.0, 2.0);
                p.target_position[i] = r.uniform(-2.0, 2.0);
                if general {
                    // Inside the limits, with v ± a|a|/(2j) inside too.
                    loop {
                        let (v0, a0) = (
                            r.uniform(-0.8, 0.8) * j.velocity,
                            r.uniform(-0.8, 0.8) * j.acceleration,
                        );
                        let (vf, af) = (
                            r.uniform(-0.8, 0.8) * j.velocity,
                            r.uniform(-0.8, 0.8) * j.acceleration,
                        );
                        let ok = |v: f64, a: f64| (v.abs() + a * a / (2.0 * j.jerk)) <= j.velocity;
                        if ok(v0, a0) && ok(vf, af) {
                            p.current_velocity[i] = v0;
                            p.current_acceleration[i] = a0;
                            p.target_velocity[i] = vf;
                            p.target_acceleration[i] = af;
                            break;
                        }
                    }
                }
            }
            p
        })
        .collect()
}

fn to_ruckig<const N: usize>(p: &InputParameter<N>) -> rsruckig::prelude::InputParameter<N> {
    let mut q = rsruckig::prelude::InputParameter::<N>::new(None);
    for i in 0..N {
        q.current_position[i] = p.current_position[i];
        q.current_velocity[i] = p.current_velocity[i];
        q.current_acceleration[i] = p.current_acceleration[i];
        q.target_position[i] = p.target_position[i];
        q.target_velocity[i] = p.target_velocity[i];
        q.target_acceleration[i] = p.target_acceleration[i];
        q.max_velocity[i] = p.max_velocity[i];
        q.max_acceleration[i] = p.max_acceleration[i];
        q.max_jerk[i] = p.max_jerk[i];
    }
    q
}

type RuckigOtg<const N: usize> =
    rsruckig::prelude::Ruckig<N, rsruckig::prelude::IgnoreErrorHandler>;

/// One problem set for both libraries: the problems in each library's input type, and for
/// each a generator and a trajectory reused across calls (the same calling pattern).
struct Pair<const N: usize> {
    ours: Vec<InputParameter<N>>,
    theirs: Vec<rsruckig::prelude::InputParameter<N>>,
    otg: Otg<N>,
    ot: FixedTrajectory<N>,
    rk: RuckigOtg<N>,
    tr: rsruckig::prelude::Trajectory<N>,
}

impl<const N: usize> Pair<N> {
    fn new(general: bool) -> Self {
        let ours = problems::<N>(general, 7 + N as u64 + general as u64);
        let theirs = ours.iter().map(to_ruckig).collect();
        Pair {
            ours,
            theirs,
            otg: Otg::new(0.001),
            ot: FixedTrajectory::default(),
            rk: RuckigOtg::new(None, 0.001),
            tr: rsruckig::prelude::Trajectory::new(None),
        }
    }

    /// trajkit on problem `k`.
    #[inline(always)]
    fn ours(&mut self, k: usize) {
        let _ = self
            .otg
            .calculate_into(black_box(&self.ours[k]), &mut self.ot);
        black_box(self.ot.duration());
    }

    /// rsruckig on problem `k`.
    #[inline(always)]
    fn theirs(&mut self, k: usize) {
        let _ = self.rk.calculate(black_box(&self.theirs[k]), &mut self.tr);
        black_box(self.tr.get_duration());
    }
}

fn group<const N: usize>(c: &mut Criterion, general: bool) {
    let name = format!("otg/{}dof_{}", N, if general { "general" } else { "rest" });
    let mut pair = Pair::<N>::new(general);
    let mut g = c.benchmark_group(&name);
    g.bench_function("trajkit", |b| {
        let mut k = 0;
        b.iter(|| {
            k = (k + 1) % PROBLEMS;
            pair.ours(k)
        })
    });
    g.bench_function("rsruckig", |b| {
        let mut k = 0;
        b.iter(|| {
            k = (k + 1) % PROBLEMS;
            pair.theirs(k)
        })
    });
    g.finish();
}

fn bench(c: &mut Criterion) {
    group::<1>(c, true);
    group::<1>(c, false);
    group::<3>(c, true);
    group::<3>(c, false);
    group::<7>(c, true);
    group::<7>(c, false);
    otg_waypoints::group(c);
}

/// Mean and p99 of single calls in nanoseconds.
fn stats(mut ns: Vec<f64>) -> (f64, f64) {
    let mean = ns.iter().sum::<f64>() / ns.len() as f64;
    ns.sort_by(f64::total_cmp);
    (mean, ns[(ns.len() as f64 * 0.99) as usize])
}

fn p99<const N: usize>(general: bool) {
    let mut pair = Pair::<N>::new(general);
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for _round in 0..40 {
        for k in 0..PROBLEMS {
            let t0 = Instant::now();
            pair.ours(k);
            a.push(t0.elapsed().as_nanos() as f64);
            let t0 = Instant::now();
            pair.theirs(k);
            b.push(t0.elapsed().as_nanos() as f64);
        }
    }
    let (ma, pa) = stats(a);
    let (mb, pb) = stats(b);
    println!(
        "| {N} DOF {:<7} | {:>8.2} | {:>8.2} | {:>8.2} | {:>8.2} | {:>5.2} |",
        if general { "general" } else { "rest" },
        ma / 1e3,
        pa / 1e3,
        mb / 1e3,
        pb / 1e3,
        ma / mb
    );
}

/// Minimum over repetitions of the mean time per call (ns) of both libraries, alternating.
fn minrep<const N: usize>(general: bool, reps: usize) {
    let mut pair = Pair::<N>::new(general);
    let (mut a, mut b) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..reps {
        let t0 = Instant::now();
        for k in 0..PROBLEMS {
            pair.ours(k);
        }
        a = a.min(t0.elapsed().as_nanos() as f64 / PROBLEMS as f64);
        let t0 = Instant::now();
        for k in 0..PROBLEMS {
            pair.theirs(k);
        }
        b = b.min(t0.elapsed().as_nanos() as f64 / PROBLEMS as f64);
    }
    println!(
        "| {N} DOF {:<7} | {:>8.3} | {:>8.3} | {:>5.2} |",
        if general { "general" } else { "rest" },
        a / 1e3,
        b / 1e3,
        a / b
    );
}

/// Runs one library alone (trajkit, or rsruckig when `peer`) on one problem set for about
/// `secs` seconds (for a profiler).
fn profile_loop<const N: usize>(general: bool, peer: bool, secs: f64) {
    let mut pair = Pair::<N>::new(general);
    let t0 = Instant::now();
    while t0.elapsed().as_secs_f64() < secs {
        for k in 0..PROBLEMS {
            if peer {
                pair.theirs(k);
            } else {
                pair.ours(k);
            }
        }
    }
}

/// Writes the problem set (one problem per line: current p, v, a, target p, v, a, max v, a,
/// j, each N numbers) to `dir/otg_<N><g|r>.txt`, so that another implementation (Ruckig's
/// C++, built outside this repository) can be timed on exactly the same problems.
fn dump<const N: usize>(dir: &str, general: bool) {
    let pair = Pair::<N>::new(general);
    let mut text = String::new();
    for p in &pair.ours {
        let fields = [
            &p.current_position,
            &p.current_velocity,
            &p.current_acceleration,
            &p.target_position,
            &p.target_velocity,
            &p.target_acceleration,
            &p.max_velocity,
            &p.max_acceleration,
            &p.max_jerk,
        ];
        let line: Vec<String> = fields
            .iter()
            .flat_map(|f| f.iter().map(|x| format!("{x:?}")))
            .collect();
        text.push_str(&line.join(" "));
        text.push('\n');
    }
    let name = format!("{dir}/otg_{N}{}.txt", if general { 'g' } else { 'r' });
    std::fs::write(&name, text).expect("cannot write the problem set");
}

criterion_group!(benches, bench);

fn main() {
    if let Ok(case) = std::env::var("OTG_PROFILE") {
        let secs = std::env::var("OTG_SECS")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(5.0);
        let peer = case.starts_with('R');
        match case.trim_start_matches('R') {
            "1g" => profile_loop::<1>(true, peer, secs),
            "1r" => profile_loop::<1>(false, peer, secs),
            "3g" => profile_loop::<3>(true, peer, secs),
            "3r" => profile_loop::<3>(false, peer, secs),
            "7g" => profile_loop::<7>(true, peer, secs),
            _ => profile_loop::<7>(false, peer, secs),
        }
        return;
    }
    if std::env::var("OTG_WAYP").is_ok() {
        otg_waypoints::medians();
        return;
    }
    if let Ok(dir) = std::env::var("OTG_DUMP") {
        for general in [true, false] {
            dump::<1>(&dir, general);
            dump::<3>(&dir, general);
            dump::<7>(&dir, general);
        }
        return;
    }
    if let Ok(reps) = std::env::var("OTG_MINREP") {
        let reps = reps.parse::<usize>().unwrap_or(1).max(30);
        println!(
            "min over {reps} repetitions of the mean per calculate, µs ({PROBLEMS} problems):"
        );
        println!("| problem         | trajkit | rsruckig | ratio |");
        minrep::<1>(true, reps);
        minrep::<1>(false, reps);
        minrep::<3>(true, reps);
        minrep::<3>(false, reps);
        minrep::<7>(true, reps);
        minrep::<7>(false, reps);
        return;
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
    if std::env::var("OTG_P99").as_deref() != Ok("0") && !std::env::args().any(|a| a == "--test") {
        println!("\nper-call timing, µs ({PROBLEMS} problems × 40 rounds, interleaved):");
        println!("| problem         | trajkit mean | trajkit p99 | rsruckig mean | rsruckig p99 | ratio (mean) |");
        p99::<1>(true);
        p99::<1>(false);
        p99::<3>(true);
        p99::<3>(false);
        p99::<7>(true);
        p99::<7>(false);
    }
}
