//! The native part of the `trajkit` Python package (`trajkit._trajkit`).
//!
//! A thin layer over the trajkit library: every Python call maps to one library call, errors
//! are converted in one place ([`convert`]), and no algorithm lives here. Each family is a
//! native submodule (`_trajkit.spline`, `_trajkit.otg`, ...) that the Python package
//! (`python/trajkit/`) re-exports as `trajkit.spline`, `trajkit.otg`, ...

mod batch;
mod convert;
mod limits;
mod otg;
mod plan;
mod poly;
mod primitives;
mod spline;
mod topp;
mod traj;

use pyo3::prelude::*;

/// Adds a native submodule `name` filled by `register`.
fn submodule(
    parent: &Bound<'_, PyModule>,
    name: &str,
    register: fn(&Bound<'_, PyModule>) -> PyResult<()>,
) -> PyResult<()> {
    // The full name makes functions pickle by reference (`trajkit.poly.rest_to_rest`).
    let m = PyModule::new(parent.py(), &format!("trajkit.{name}"))?;
    register(&m)?;
    parent.add(name, m)
}

/// The extension module; `trajkit/__init__.py` and the submodules import from it.
#[pymodule]
fn _trajkit(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("TrajkitError", py.get_type::<convert::TrajkitError>())?;
    m.add_class::<traj::PyTrajectory>()?;
    limits::register(m)?;
    plan::register(m)?;
    submodule(m, "spline", spline::register)?;
    submodule(m, "otg", otg::register)?;
    submodule(m, "poly", poly::register)?;
    submodule(m, "topp", topp::register)?;
    submodule(m, "primitives", primitives::register)?;
    submodule(m, "batch", batch::register)?;
    Ok(())
}
