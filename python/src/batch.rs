//! `trajkit.batch`: many independent problems in one call, across all cores, GIL released.
//!
//! Inputs are converted to plain Rust data while the GIL is held, then the problems are
//! solved on `threads` scoped threads (default: every core) that take the next problem from a
//! shared counter; each item is one library call. Results come back in input order; a
//! problem that fails gives a `trajkit.TrajkitError` instance in its place instead of
//! aborting the batch.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyList;
use trajkit::topp::messy::plan_waypoints as plan_pieces;
use trajkit::topp::{plan_totg, TotgOptions};

use crate::convert::{bad, table, Floats, TrajkitError};
use crate::limits::complete_of;
use crate::otg::{otg_err, solve, PyInput, PyOtgTrajectory};
use crate::topp::{piece_options, PIECES_NEEDS, TOTG_NEEDS};
use crate::traj::{PyTrajectory, SharedTrajectory};

/// Applies `f` to `0..n` on `threads` threads (work taken from a shared counter); results in
/// index order.
fn par_map<R: Send>(n: usize, threads: usize, f: impl Fn(usize) -> R + Sync) -> Vec<R> {
    let threads = threads.clamp(1, n.max(1));
    let next = AtomicUsize::new(0);
    let mut parts: Vec<Vec<(usize, R)>> = Vec::with_capacity(threads);
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                s.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        if i >= n {
                            break done;
                        }
                        done.push((i, f(i)));
                    }
                })
            })
            .collect();
        for h in handles {
            parts.push(h.join().expect("a batch worker panicked"));
        }
    });
    let mut all: Vec<(usize, R)> = parts.into_iter().flatten().collect();
    all.sort_unstable_by_key(|(i, _)| *i);
    all.into_iter().map(|(_, r)| r).collect()
}

fn threads_of(threads: Option<usize>) -> PyResult<usize> {
    match threads {
        Some(0) => Err(bad("threads = 0: at least one thread is needed")),
        Some(t) => Ok(t),
        None => Ok(std::thread::available_parallelism().map_or(1, |n| n.get())),
    }
}

/// Results to a list: each `Ok` through `make`, each error a `TrajkitError` instance (made by
/// `error`: the otg errors carry `result`, `kind` and `dof` as `Ruckig.calculate` raises them).
fn to_list<'py, T, E>(
    py: Python<'py>,
    results: Vec<Result<T, E>>,
    error: impl Fn(E) -> PyErr,
    make: impl Fn(T) -> PyResult<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyList>> {
    let items = results
        .into_iter()
        .map(|r| match r {
            Ok(v) => make(v),
            Err(e) => Ok(error(e).into_value(py).into_bound(py).into_any()),
        })
        .collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, items)
}

/// A library error as a `TrajkitError` with its message.
fn message(e: impl std::fmt::Display) -> PyErr {
    TrajkitError::new_err(e.to_string())
}

/// Calculates every `trajkit.otg.InputParameter` of `inputs` (through its intermediate
/// waypoints when it has any) with control period `delta_time`: a list of
/// `trajkit.otg.Trajectory` (or `TrajkitError` for a failed input), in input order.
#[pyfunction]
#[pyo3(signature = (inputs, delta_time = 0.001, threads = None))]
fn otg<'py>(
    py: Python<'py>,
    inputs: Vec<PyRef<'py, PyInput>>,
    delta_time: f64,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyList>> {
    let data: Vec<PyInput> = inputs.iter().map(|i| (**i).clone()).collect();
    let th = threads_of(threads)?;
    let results = py.detach(|| {
        par_map(data.len(), th, |i| {
            solve(&data[i].inner, data[i].waypoints(), delta_time)
        })
    });
    let paired: Vec<_> = results
        .into_iter()
        .zip(data)
        .map(|(r, input)| r.map(|t| (input, t)))
        .collect();
    to_list(py, paired, otg_err, |(input, t)| {
        Ok(Bound::new(py, PyOtgTrajectory::calculated(input, delta_time, t))?.into_any())
    })
}

/// Reads waypoint sets (each `(n, dof)`) as owned row-major data.
fn waypoint_sets(sets: &[Floats<'_>]) -> PyResult<Vec<(Vec<f64>, usize)>> {
    sets.iter()
        .enumerate()
        .map(|(i, w)| {
            let t = table(w, &format!("waypoint_sets[{i}]"))?;
            Ok((t.data.into_owned(), t.dim))
        })
        .collect()
}

/// `trajkit.topp.plan_waypoints` on every waypoint set (each `(n, dof)`), in parallel: a list
/// of `trajkit.Trajectory` (or `TrajkitError`), in input order.
#[pyfunction]
#[pyo3(signature = (waypoint_sets, limits, path = "natural", solver = "toppra", gridpoints = 1000, threads = None))]
fn plan_waypoints<'py>(
    py: Python<'py>,
    waypoint_sets: Vec<Floats<'py>>,
    limits: Bound<'py, PyAny>,
    path: &str,
    solver: &str,
    gridpoints: usize,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyList>> {
    let sets = self::waypoint_sets(&waypoint_sets)?;
    let l = complete_of(&limits, PIECES_NEEDS)?;
    let opts = piece_options(path, solver, gridpoints)?;
    let th = threads_of(threads)?;
    let results = py.detach(|| {
        par_map(sets.len(), th, |i| {
            let (w, d) = &sets[i];
            plan_pieces(w, *d, &l, &opts).map(|t| Arc::new(t) as SharedTrajectory)
        })
    });
    to_list(py, results, message, |t| {
        Ok(Bound::new(py, PyTrajectory::new(t))?.into_any())
    })
}

/// `trajkit.topp.totg` on every waypoint set, in parallel.
#[pyfunction]
#[pyo3(signature = (waypoint_sets, limits, max_deviation = 0.1, threads = None))]
fn totg<'py>(
    py: Python<'py>,
    waypoint_sets: Vec<Floats<'py>>,
    limits: Bound<'py, PyAny>,
    max_deviation: f64,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyList>> {
    let sets = self::waypoint_sets(&waypoint_sets)?;
    let l = complete_of(&limits, TOTG_NEEDS)?;
    let opts = TotgOptions {
        max_deviation,
        ..TotgOptions::default()
    };
    let th = threads_of(threads)?;
    let results = py.detach(|| {
        par_map(sets.len(), th, |i| {
            let (w, d) = &sets[i];
            plan_totg(w, *d, &l, &opts).map(|t| Arc::new(t) as SharedTrajectory)
        })
    });
    to_list(py, results, message, |t| {
        Ok(Bound::new(py, PyTrajectory::new(t))?.into_any())
    })
}

/// Registers the batch functions.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(otg, m)?)?;
    m.add_function(wrap_pyfunction!(plan_waypoints, m)?)?;
    m.add_function(wrap_pyfunction!(totg, m)?)?;
    Ok(())
}
