//! `trajkit.poly`: polynomial moves (cubic, quintic = minimum jerk, septic) between states and
//! through waypoints, each function one call of `trajkit::poly`.

use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyTuple;
use trajkit::poly::{
    min_duration_rest_to_rest, peak_coefficients as peaks, Degree, EndState, PolyMove, ViaTiming,
    ViaTrajectory, ViaVelocities,
};

use crate::convert::{bad, obj, table, vector, Floats, IntoPy};
use crate::limits::complete_of;
use crate::traj::{with_recipe, PyTrajectory};

fn degree(name: &str) -> PyResult<Degree> {
    Degree::parse(name).py()
}

fn opt(a: &Option<Floats<'_>>, name: &str, n: usize) -> PyResult<Vec<f64>> {
    match a {
        None => Ok(vec![]),
        Some(a) => vector(a, name, Some(n)),
    }
}

/// The rest-to-rest move from `q0` to `q1` over `duration` seconds; `degree` is `'cubic'`,
/// `'quintic'` (minimum jerk, default) or `'septic'`.
#[pyfunction]
#[pyo3(signature = (q0, q1, duration, degree = "quintic"))]
fn rest_to_rest<'py>(
    py: Python<'py>,
    q0: Floats<'py>,
    q1: Floats<'py>,
    duration: f64,
    degree: &str,
) -> PyResult<Bound<'py, PyTrajectory>> {
    let a = vector(&q0, "q0", None)?;
    let b = vector(&q1, "q1", Some(a.len()))?;
    let m = PolyMove::rest_to_rest(self::degree(degree)?, &a, &b, duration).py()?;
    let args = (obj(&q0), obj(&q1), duration, degree).into_pyobject(py)?;
    with_recipe(py, Arc::new(m), "trajkit.poly", "rest_to_rest", args)
}

/// The move between two states over `duration`: positions `q0`, `q1` and optional
/// velocities, accelerations, jerks (zero when absent; as many as the degree can meet).
#[pyfunction]
#[pyo3(signature = (q0, q1, duration, degree = "quintic", qd0 = None, qd1 = None, qdd0 = None, qdd1 = None, qddd0 = None, qddd1 = None))]
fn between<'py>(
    py: Python<'py>,
    q0: Floats<'py>,
    q1: Floats<'py>,
    duration: f64,
    degree: &str,
    qd0: Option<Floats<'py>>,
    qd1: Option<Floats<'py>>,
    qdd0: Option<Floats<'py>>,
    qdd1: Option<Floats<'py>>,
    qddd0: Option<Floats<'py>>,
    qddd1: Option<Floats<'py>>,
) -> PyResult<Bound<'py, PyTrajectory>> {
    let a = vector(&q0, "q0", None)?;
    let n = a.len();
    let start = EndState {
        q: a,
        qd: opt(&qd0, "qd0", n)?,
        qdd: opt(&qdd0, "qdd0", n)?,
        qddd: opt(&qddd0, "qddd0", n)?,
    };
    let end = EndState {
        q: vector(&q1, "q1", Some(n))?,
        qd: opt(&qd1, "qd1", n)?,
        qdd: opt(&qdd1, "qdd1", n)?,
        qddd: opt(&qddd1, "qddd1", n)?,
    };
    let m = PolyMove::between(self::degree(degree)?, &start, &end, duration).py()?;
    let o = |a: &Option<Floats<'py>>| a.as_ref().map(obj);
    let args = (
        obj(&q0),
        obj(&q1),
        duration,
        degree,
        o(&qd0),
        o(&qd1),
        o(&qdd0),
        o(&qdd1),
        o(&qddd0),
        o(&qddd1),
    )
        .into_pyobject(py)?;
    with_recipe(py, Arc::new(m), "trajkit.poly", "between", args)
}

/// The shortest duration of the rest-to-rest move from `q0` to `q1` within `limits`.
#[pyfunction]
#[pyo3(signature = (q0, q1, limits, degree = "quintic"))]
fn min_duration(
    q0: Floats<'_>,
    q1: Floats<'_>,
    limits: &Bound<'_, PyAny>,
    degree: &str,
) -> PyResult<f64> {
    let a = vector(&q0, "q0", None)?;
    let b = vector(&q1, "q1", None)?;
    let d = self::degree(degree)?;
    let l = complete_of(limits, timing_needs(d))?;
    min_duration_rest_to_rest(d, &a, &b, &l).py()
}

/// The limits that timing a polynomial move reads: velocity, acceleration, and jerk unless
/// the move is cubic (whose jerk the limits do not bound); a missing one is an error.
fn timing_needs(d: Degree) -> trajkit::limits::Needs {
    trajkit::limits::Needs {
        position: false,
        velocity: true,
        acceleration: true,
        jerk: d != Degree::Cubic,
    }
}

/// Peak |velocity|·T/D, |acceleration|·T²/D, |jerk|·T³/D of the unit rest-to-rest profile.
#[pyfunction]
#[pyo3(signature = (degree = "quintic"))]
fn peak_coefficients(degree: &str) -> PyResult<(f64, f64, f64)> {
    let p = peaks(self::degree(degree)?);
    Ok((p[0], p[1], p[2]))
}

/// A piecewise polynomial through `waypoints` (`(n, dof)`), at rest at both ends: segment
/// durations given (`durations`, one per segment) or the shortest within `limits`; interior
/// velocities `'heuristic'` (default), `'zero'` or an array `(n - 2, dof)`.
#[pyfunction]
#[pyo3(signature = (waypoints, limits = None, durations = None, degree = "quintic", velocities = None))]
fn via<'py>(
    py: Python<'py>,
    waypoints: Floats<'py>,
    limits: Option<Bound<'py, PyAny>>,
    durations: Option<Floats<'py>>,
    degree: &str,
    velocities: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyTrajectory>> {
    let w = table(&waypoints, "waypoints")?;
    let vel = match &velocities {
        None => ViaVelocities::Heuristic,
        Some(v) => match v.extract::<String>() {
            Ok(s) if s == "heuristic" => ViaVelocities::Heuristic,
            Ok(s) if s == "zero" => ViaVelocities::Zero,
            Ok(s) => {
                return Err(bad(format!(
                    "velocities = '{s}' is not 'heuristic', 'zero' or an array"
                )))
            }
            Err(_) => ViaVelocities::Given(crate::convert::floats(v, "velocities", None)?),
        },
    };
    let d = self::degree(degree)?;
    let lim = limits
        .as_ref()
        .map(|l| complete_of(l, timing_needs(d)))
        .transpose()?;
    let timing = match (&lim, &durations) {
        (Some(l), None) => ViaTiming::Limits(l),
        (None, Some(d)) => ViaTiming::Durations(vector(d, "durations", None)?),
        _ => return Err(bad("give exactly one of limits= and durations=")),
    };
    let t = ViaTrajectory::new(&w.data, w.dim, d, vel, timing).py()?;
    let args = PyTuple::new(
        py,
        [
            Some(obj(&waypoints)),
            limits,
            durations.as_ref().map(obj),
            Some(degree.into_pyobject(py)?.into_any()),
            velocities,
        ],
    )?;
    with_recipe(py, Arc::new(t), "trajkit.poly", "via", args)
}

/// Registers the polynomial functions.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(rest_to_rest, m)?)?;
    m.add_function(wrap_pyfunction!(between, m)?)?;
    m.add_function(wrap_pyfunction!(min_duration, m)?)?;
    m.add_function(wrap_pyfunction!(peak_coefficients, m)?)?;
    m.add_function(wrap_pyfunction!(via, m)?)?;
    Ok(())
}
