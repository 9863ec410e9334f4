//! Spline benchmarks. Run: `cargo bench -p trajkit --bench spline`; the peer timings come from
//! `tools/bench_spline_peer.py`, which runs this and scipy on the same data in one go.
//!
//! - `bspline_eval/cubic_100cp_7d_1e6_sorted`: a clamped uniform cubic B-spline with 100
//!   control points `c[i][d] = sin(0.37 i + 1.3 d)` in 7 dimensions, evaluated at 10⁶ equally
//!   spaced sorted parameters over its domain [0, 1].
//! - `cubic_spline_build/not_a_knot/N`: natural-cubic construction through N waypoints
//!   (7-D), N = 1 000 and 10 000, to show linear time.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use trajkit::spline::{BSpline, CubicSpline};

fn peer_data() -> (BSpline, Vec<f64>) {
    let (n, dim) = (100, 7);
    let t = BSpline::clamped_uniform_knots(n, 3, 0.0, 1.0);
    let mut c = vec![0.0; n * dim];
    for i in 0..n {
        for d in 0..dim {
            c[i * dim + d] = (0.37 * i as f64 + 1.3 * d as f64).sin();
        }
    }
    let b = BSpline::new(&t, &c, dim, 3).unwrap();
    let m = 1_000_000;
    let s: Vec<f64> = (0..m).map(|i| i as f64 / (m - 1) as f64).collect();
    (b, s)
}

fn bspline_eval(cr: &mut Criterion) {
    let (b, s) = peer_data();
    let mut out = vec![0.0; s.len() * 7];
    let mut g = cr.benchmark_group("bspline_eval");
    g.sample_size(20);
    g.throughput(Throughput::Elements(s.len() as u64));
    g.bench_function("cubic_100cp_7d_1e6_sorted", |bch| {
        bch.iter(|| {
            b.eval_many(black_box(&s), 0, &mut out);
            black_box(&out);
        })
    });
    // The same work timed in this thread's CPU time (Linux /proc, 10 ms ticks summed over
    // many iterations), which a loaded shared machine distorts less than wall time.
    g.bench_function("cubic_100cp_7d_1e6_sorted_cputime", |bch| {
        bch.iter_custom(|iters| {
            let c0 = thread_cpu_seconds();
            let w0 = std::time::Instant::now();
            for _ in 0..iters {
                b.eval_many(black_box(&s), 0, &mut out);
                black_box(&out);
            }
            match (c0, thread_cpu_seconds()) {
                (Some(a), Some(z)) => std::time::Duration::from_secs_f64(z - a),
                _ => w0.elapsed(),
            }
        })
    });
    g.finish();
}

/// User + system CPU time of the calling thread, from /proc (None where unavailable).
fn thread_cpu_seconds() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/stat").ok()?;
    let fields: Vec<&str> = text.rsplit(')').next()?.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

fn cubic_build(cr: &mut Criterion) {
    let mut g = cr.benchmark_group("cubic_spline_build");
    g.sample_size(20);
    for &n in &[1_000usize, 10_000] {
        let dim = 7;
        let x: Vec<f64> = (0..n)
            .map(|i| i as f64 + 0.3 * ((i * 7919) % 13) as f64 / 13.0)
            .collect();
        let y: Vec<f64> = (0..n * dim).map(|k| (0.01 * k as f64).sin()).collect();
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::new("not_a_knot", n), &n, |bch, _| {
            bch.iter(|| {
                black_box(CubicSpline::not_a_knot(black_box(&x), black_box(&y), dim).unwrap())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bspline_eval, cubic_build);
criterion_main!(benches);
