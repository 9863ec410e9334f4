//! TOPP-RA output, retimed paths, scaled trajectories and rest-to-rest sequences evaluate
//! without allocating (counting global allocator, as in no_alloc.rs).
//!
//! This test binary needs `unsafe` for one reason only: `GlobalAlloc` is an unsafe trait. The
//! library itself forbids unsafe code.
#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made on this thread while running `f`.
fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCS.with(|c| c.get());
    f();
    ALLOCS.with(|c| c.get()) - before
}

use trajkit::spline::CubicSpline;
use trajkit::topp::messy::{plan_waypoints, PlanOptions};
use trajkit::topp::{Gridpoints, Options, QuinticLaw, Retimed, Scaled, Toppra};
use trajkit::{Limits, Order, Trajectory};

fn exercise(tr: &dyn Trajectory) -> f64 {
    let mut out = [0.0; 16];
    let mut s = 0.0;
    let n = 2000;
    for i in 0..=n {
        let t = -0.1 + (tr.duration() + 0.2) * i as f64 / n as f64;
        for o in Order::ALL {
            tr.eval(t, o, &mut out);
            s += out[0];
        }
    }
    tr.eval(f64::NAN, Order::Jerk, &mut out);
    s
}

#[test]
fn topp_outputs_evaluate_without_allocating() {
    let lim = Limits::preset("panda").unwrap();
    let wp: Vec<f64> = (0..5)
        .flat_map(|i| {
            (0..7).map(move |j| 0.3 * ((i * 7 + j) as f64).sin() - if j == 3 { 1.5 } else { 0.0 })
        })
        .collect();
    let ss: Vec<f64> = (0..5).map(|i| i as f64 / 4.0).collect();
    let path = CubicSpline::natural(&ss, &wp, 7).unwrap();
    let opts = Options {
        gridpoints: Gridpoints::Uniform(100),
        refine: false,
        ..Options::default()
    };
    let traj = Toppra::with_limits(&path, &lim)
        .unwrap()
        .options(opts.clone())
        .solve()
        .unwrap();
    let retimed = Retimed::new(&path, QuinticLaw::new(0.0, 1.0, 3.0).unwrap()).unwrap();
    let scaled = Scaled::new(&traj, 1.7).unwrap();
    let seq = plan_waypoints(
        &wp,
        7,
        &lim,
        &PlanOptions {
            toppra: opts,
            ..PlanOptions::default()
        },
    )
    .unwrap();
    for tr in [&traj as &dyn Trajectory, &retimed, &scaled, &seq] {
        let mut s = 0.0;
        let n = allocations(|| s = exercise(tr));
        assert!(s.is_finite());
        assert_eq!(n, 0, "evaluation allocated {n} times");
    }
}
