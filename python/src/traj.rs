//! `trajkit.Trajectory`: any trajkit trajectory (polynomial moves, TOPP results, primitive
//! rollouts, splines through timed points) behind one Python class.
//!
//! Evaluation maps to `trajkit::Trajectory::eval` (time clamped to `[0, duration]`, the
//! library's policy) over arrays of times with the GIL released; `sample` maps to
//! `trajkit::sample::sample`. A trajectory pickles by its recipe: the Python call that made it
//! and its arguments (set by the function that returned it), so unpickling recomputes the same
//! trajectory (every trajkit computation is deterministic).

use std::sync::{Arc, OnceLock};

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use trajkit::{Order, Trajectory};

use crate::convert::{array, eval_times, order, Floats, IntoPy};

/// A shared, thread-safe trajectory.
pub type SharedTrajectory = Arc<dyn Trajectory + Send + Sync>;

/// A trajectory ξ(t) over `[0, duration]` with `dof` components.
#[pyclass(module = "trajkit", name = "Trajectory", frozen, subclass)]
pub struct PyTrajectory {
    /// The library's trajectory.
    pub inner: SharedTrajectory,
    /// `(callable, args)` that rebuilds it, for pickling.
    recipe: OnceLock<(Py<PyAny>, Py<PyTuple>)>,
}

impl PyTrajectory {
    /// Wraps a library trajectory.
    pub fn new(inner: SharedTrajectory) -> Self {
        PyTrajectory {
            inner,
            recipe: OnceLock::new(),
        }
    }
}

/// Evaluates `traj` at `t` (scalar or array) for derivative `nu`.
pub fn eval_traj<'py>(
    py: Python<'py>,
    traj: &(dyn Trajectory + Send + Sync),
    t: &Floats<'py>,
    nu: i64,
) -> PyResult<Bound<'py, PyAny>> {
    let o = Order::from_index(order(nu, 3)?).expect("order checked");
    eval_times(py, t, traj.dof(), false, |ti, out| traj.eval(ti, o, out))
}

#[pymethods]
impl PyTrajectory {
    /// Duration in seconds.
    #[getter]
    fn duration(&self) -> f64 {
        self.inner.duration()
    }

    /// Number of degrees of freedom (joints).
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }

    /// The `order`-th time derivative (0 position … 3 jerk) at `t`, a scalar or an array of
    /// any shape; the result has shape `t.shape + (dof,)`. Time is clamped to `[0, duration]`.
    #[pyo3(signature = (t, order = 0))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        t: Floats<'py>,
        order: i64,
    ) -> PyResult<Bound<'py, PyAny>> {
        eval_traj(py, self.inner.as_ref(), &t, order)
    }

    /// Position at `t` (toppra's name).
    fn eval<'py>(&self, py: Python<'py>, t: Floats<'py>) -> PyResult<Bound<'py, PyAny>> {
        eval_traj(py, self.inner.as_ref(), &t, 0)
    }

    /// Velocity at `t` (toppra's name).
    fn evald<'py>(&self, py: Python<'py>, t: Floats<'py>) -> PyResult<Bound<'py, PyAny>> {
        eval_traj(py, self.inner.as_ref(), &t, 1)
    }

    /// Acceleration at `t` (toppra's name).
    fn evaldd<'py>(&self, py: Python<'py>, t: Floats<'py>) -> PyResult<Bound<'py, PyAny>> {
        eval_traj(py, self.inner.as_ref(), &t, 2)
    }

    /// Samples at `rate` Hz, both ends included: `(t, q, qd, qdd, qddd)`, `t` of shape `(n,)`
    /// and the others `(n, dof)`.
    fn sample<'py>(&self, py: Python<'py>, rate: f64) -> PyResult<Bound<'py, PyTuple>> {
        let inner = self.inner.clone();
        let table = py
            .detach(|| trajkit::sample::sample(inner.as_ref(), rate))
            .py()?;
        table_tuple(py, &table)
    }

    /// Sets how this trajectory is rebuilt when unpickled (`callable(*args)`); used by the
    /// functions that return trajectories.
    fn _set_recipe(&self, callable: Py<PyAny>, args: Py<PyTuple>) {
        let _ = self.recipe.set((callable, args));
    }

    fn __reduce__(&self, py: Python<'_>) -> PyResult<(Py<PyAny>, Py<PyTuple>)> {
        match self.recipe.get() {
            Some((c, a)) => Ok((c.clone_ref(py), a.clone_ref(py))),
            None => Err(PyTypeError::new_err(
                "this trajectory has no recipe to rebuild it from and cannot be pickled",
            )),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "trajkit.Trajectory(dof={}, duration={})",
            self.inner.dof(),
            self.inner.duration()
        )
    }
}

/// A sample table as `(t, q, qd, qdd, qddd)`: `t` of shape `(n,)`, the others `(n, dof)`.
pub fn table_tuple<'py>(
    py: Python<'py>,
    table: &trajkit::sample::SampleTable,
) -> PyResult<Bound<'py, PyTuple>> {
    let n = table.len();
    let dof = table.dof();
    let mut items = vec![array(py, table.times().to_vec(), &[n])?];
    for o in Order::ALL {
        let m = table.matrix(o).map(|m| m.to_vec()).unwrap_or_default();
        items.push(array(py, m, &[n, dof])?);
    }
    PyTuple::new(py, items)
}

/// A trajectory object whose pickling recipe is `module.func(*args)`.
pub fn with_recipe<'py>(
    py: Python<'py>,
    inner: SharedTrajectory,
    module: &str,
    func: &str,
    args: Bound<'py, PyTuple>,
) -> PyResult<Bound<'py, PyTrajectory>> {
    let t = PyTrajectory::new(inner);
    let f = py.import(module)?.getattr(func)?;
    let _ = t.recipe.set((f.unbind(), args.unbind()));
    Bound::new(py, t)
}
