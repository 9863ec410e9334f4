//! Real-time paths allocate nothing: trajectory evaluation is run under a counting global
//! allocator and must not allocate once constructed.
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

use trajkit::poly::{Degree, PolyMove, ViaTiming, ViaTrajectory, ViaVelocities};
use trajkit::{Limits, Order, Trajectory};

fn exercise(tr: &dyn Trajectory) -> f64 {
    let mut out = [0.0; 16];
    let mut s = 0.0;
    let n = 2000;
    for i in 0..=n {
        // Includes times before 0 and after the end (clamping) and NaN.
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
fn evaluation_allocates_nothing() {
    let limits = Limits::preset("panda").unwrap();
    let q0 = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];
    let q1 = [1.2, 0.3, -0.5, -1.2, 0.6, 2.2, -0.4];
    let mv = PolyMove::rest_to_rest(Degree::Septic, &q0, &q1, 2.0).unwrap();
    let mut wps = q0.to_vec();
    wps.extend_from_slice(&q1);
    wps.extend_from_slice(&q0);
    let via = ViaTrajectory::new(
        &wps,
        7,
        Degree::Quintic,
        ViaVelocities::Heuristic,
        ViaTiming::Limits(&limits),
    )
    .unwrap();
    let path_traj = trajkit::PathAsTrajectory(LinePath);
    let cases: [(&str, &dyn Trajectory); 3] = [
        ("PolyMove", &mv),
        ("ViaTrajectory", &via),
        ("PathAsTrajectory", &path_traj),
    ];
    for (name, tr) in cases {
        let mut sink = 0.0;
        let n = allocations(|| sink = exercise(tr));
        assert!(sink.is_finite() || sink.is_nan());
        assert_eq!(n, 0, "{name} allocated {n} times during evaluation");
    }
    // The counter works: a Vec allocates.
    assert!(allocations(|| drop(std::hint::black_box(vec![1u8; 10]))) >= 1);
}

/// A straight line in 2-D as a path, to cover the adapter.
struct LinePath;
impl trajkit::Path for LinePath {
    fn dim(&self) -> usize {
        2
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        let s = s.clamp(0.0, 1.0);
        match order {
            0 => out[..2].copy_from_slice(&[s, 2.0 * s]),
            1 => out[..2].copy_from_slice(&[1.0, 2.0]),
            _ => out[..2].fill(0.0),
        }
    }
}
