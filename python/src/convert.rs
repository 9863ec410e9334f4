//! The one conversion module: errors, arrays in, arrays out, and evaluation over arrays of
//! times with the GIL released.
//!
//! - Errors: every `trajkit::Error` (and the online generator's error) becomes
//!   `trajkit.TrajkitError`, a `ValueError`, carrying the Rust error's message unchanged.
//! - Arrays in: anything numpy can turn into float64 ([`Floats`]). A C-contiguous float64
//!   array is read in place (no copy); anything else is converted once.
//! - Arrays out: evaluation over arrays writes into a numpy-allocated array with the GIL
//!   released; other results are computed into a `Vec<f64>` and handed to numpy without a
//!   copy (`PyArray::from_vec`), then reshaped.
//! - Evaluation over many times ([`eval_times_many`], [`eval_times`]) releases the GIL and
//!   splits large arrays across all cores (`std::thread::scope`), each thread calling the
//!   library's allocation-free many-point evaluation (`Path::eval_many`: each point's piece
//!   found from the previous one) or `eval` into its slice of the output.

use std::borrow::Cow;

use numpy::{
    AllowTypeChange, PyArray, PyArrayDyn, PyArrayLikeDyn, PyArrayMethods, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

pyo3::create_exception!(
    trajkit,
    TrajkitError,
    PyValueError,
    "Bad input or an infeasible problem; the message is trajkit's (it names the field and the value)."
);

/// Any array-like that numpy converts to float64.
pub type Floats<'py> = PyArrayLikeDyn<'py, f64, AllowTypeChange>;

/// The library's error as `trajkit.TrajkitError` with the same message.
pub fn err(e: trajkit::Error) -> PyErr {
    TrajkitError::new_err(e.to_string())
}

/// A message of the binding's own (wrong shape of an argument, unknown option name) as
/// `trajkit.TrajkitError`.
pub fn bad(message: impl Into<String>) -> PyErr {
    TrajkitError::new_err(message.into())
}

/// `Result<T, trajkit::Error>` to `PyResult<T>`.
pub trait IntoPy<T> {
    /// Converts the error with [`err`].
    fn py(self) -> PyResult<T>;
}

impl<T> IntoPy<T> for trajkit::Result<T> {
    fn py(self) -> PyResult<T> {
        self.map_err(err)
    }
}

/// The array as a Python object (what a pickling recipe stores).
pub fn obj<'py>(a: &Floats<'py>) -> Bound<'py, PyAny> {
    a.as_any().clone()
}

/// The values of an array in C order: borrowed when the array is C-contiguous, else copied.
pub fn values<'a>(a: &'a Floats<'_>) -> Cow<'a, [f64]> {
    // `as_slice` also accepts Fortran order, whose memory order is not C order.
    if a.is_c_contiguous() {
        if let Ok(s) = a.as_slice() {
            return Cow::Borrowed(s);
        }
    }
    Cow::Owned(a.as_array().iter().copied().collect())
}

/// A table of `rows × dim` values (row-major) from a 1-D array (`dim = 1`, `was_1d`) or a 2-D
/// array. `name` names the argument in the error.
pub struct Table<'a> {
    /// Row-major values.
    pub data: Cow<'a, [f64]>,
    /// Number of rows.
    pub rows: usize,
    /// Number of columns.
    pub dim: usize,
    /// Whether the input was 1-D (results then drop their last axis, as scipy's do).
    pub was_1d: bool,
}

/// Reads a 1-D or 2-D array as a [`Table`].
pub fn table<'a>(a: &'a Floats<'_>, name: &str) -> PyResult<Table<'a>> {
    let shape = a.shape().to_vec();
    match shape.len() {
        1 => Ok(Table {
            data: values(a),
            rows: shape[0],
            dim: 1,
            was_1d: true,
        }),
        2 => Ok(Table {
            data: values(a),
            rows: shape[0],
            dim: shape[1],
            was_1d: false,
        }),
        n => Err(bad(format!(
            "{name}: expected a 1-D or 2-D array, found {n} dimensions (shape {shape:?})"
        ))),
    }
}

/// Reads a 1-D array (a 0-d array counts as one value when `len == Some(1)`); with `len`, its
/// length must be that.
pub fn vector(a: &Floats<'_>, name: &str, len: Option<usize>) -> PyResult<Vec<f64>> {
    if a.ndim() > 1 {
        return Err(bad(format!(
            "{name}: expected a 1-D array, found shape {:?}",
            a.shape()
        )));
    }
    let v = values(a).into_owned();
    if let Some(n) = len {
        if v.len() != n {
            return Err(bad(format!(
                "{name}: expected {n} values, found {}",
                v.len()
            )));
        }
    }
    Ok(v)
}

/// Reads a sequence of floats given as a Python object (list, tuple, array) into a `Vec`.
pub fn floats(obj: &Bound<'_, PyAny>, name: &str, len: Option<usize>) -> PyResult<Vec<f64>> {
    let a: Floats<'_> = obj
        .extract()
        .map_err(|e| bad(format!("{name}: not an array of numbers ({e})")))?;
    vector(&a, name, len)
}

/// Hands a vector to numpy without a copy, with the given shape.
pub fn array<'py>(py: Python<'py>, data: Vec<f64>, shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    let flat = PyArray::from_vec(py, data);
    if shape.len() == 1 {
        return Ok(flat.into_any());
    }
    Ok(flat.reshape(shape.to_vec())?.into_any())
}

/// Below this many values, evaluation runs on the calling thread only.
const PARALLEL_MIN: usize = 1 << 15;

/// Calls `f(times, out)` on consecutive chunks of `t` and the matching rows of `out` (`dim`
/// values per time); large arrays are split into one chunk per core, evaluated on scoped
/// threads. `f` is a library many-point evaluation (or a loop over one-point evaluations).
pub fn eval_chunks<F>(t: &[f64], dim: usize, out: &mut [f64], f: &F)
where
    F: Fn(&[f64], &mut [f64]) + Sync,
{
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    if threads <= 1 || t.len() * dim < PARALLEL_MIN || dim == 0 {
        f(t, out);
        return;
    }
    let per = t.len().div_ceil(threads);
    std::thread::scope(|s| {
        for (tc, oc) in t.chunks(per).zip(out.chunks_mut(per * dim)) {
            s.spawn(move || f(tc, oc));
        }
    });
}

/// Evaluates `f` (a many-point evaluation: times in, `dim` values per time out) at every time
/// of `times` (a scalar or an array of any shape) with the GIL released. The result has shape
/// `times.shape + (dim,)`, or `times.shape` when `squeeze` (a curve through 1-D values); a
/// scalar time gives shape `(dim,)` or a float.
pub fn eval_times_many<'py, F>(
    py: Python<'py>,
    times: &Floats<'py>,
    dim: usize,
    squeeze: bool,
    f: F,
) -> PyResult<Bound<'py, PyAny>>
where
    F: Fn(&[f64], &mut [f64]) + Sync + Send,
{
    let shape = times.shape().to_vec();
    let t = values(times);
    let t: &[f64] = &t;
    if shape.is_empty() && squeeze && dim == 1 {
        let mut out = [0.0];
        py.detach(|| f(t, &mut out));
        return Ok(out[0].into_pyobject(py)?.into_any());
    }
    let mut full = shape;
    if !(squeeze && dim == 1) {
        full.push(dim);
    }
    // The output is numpy's own allocation (large arrays get transparent huge pages there,
    // which makes first-touch page faults 512× rarer than with a fresh Rust vector), filled
    // in place with the GIL released.
    let arr = PyArrayDyn::<f64>::zeros(py, full, false);
    {
        let mut rw = arr.readwrite();
        let out = rw
            .as_slice_mut()
            .map_err(|e| bad(format!("output array: {e}")))?;
        py.detach(|| eval_chunks(t, dim, out, &f));
    }
    Ok(arr.into_any())
}

/// [`eval_times_many`] with a one-point evaluation `f(t, out_row)` (the library's `eval`).
pub fn eval_times<'py, F>(
    py: Python<'py>,
    times: &Floats<'py>,
    dim: usize,
    squeeze: bool,
    f: F,
) -> PyResult<Bound<'py, PyAny>>
where
    F: Fn(f64, &mut [f64]) + Sync + Send,
{
    eval_times_many(py, times, dim, squeeze, |ts, out| {
        for (ti, row) in ts.iter().zip(out.chunks_exact_mut(dim.max(1))) {
            f(*ti, row);
        }
    })
}

/// The derivative order of an `order=` argument, 0..=`max`.
pub fn order(order: i64, max: usize) -> PyResult<usize> {
    if order < 0 || order as usize > max {
        return Err(bad(format!(
            "order = {order} is not a derivative order from 0 to {max}"
        )));
    }
    Ok(order as usize)
}
