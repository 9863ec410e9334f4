//! The counting global allocator shared by the `*no_alloc` test binaries: real-time paths
//! (trajectory evaluation, the online generator's update) must not allocate, and these tests
//! prove it by counting every allocation made on the test's thread.
//!
//! `unsafe` appears here for one reason only: `GlobalAlloc` is an unsafe trait. The library
//! itself forbids unsafe code.
#![allow(unsafe_code)]
#![allow(dead_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use trajkit::{Order, Trajectory};

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
pub fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCS.with(|c| c.get());
    f();
    ALLOCS.with(|c| c.get()) - before
}

/// Evaluates every order of `tr` at `n + 1` times spanning `[-0.1, T + 0.1]` (clamping
/// included) and once at NaN; returns a checksum so the work is not optimized away.
pub fn exercise(tr: &dyn Trajectory, n: usize) -> f64 {
    let mut out = [0.0; 16];
    let mut s = 0.0;
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
