//! `trajkit.topp`: time-optimal path parameterization with toppra-like building blocks.
//!
//! A path is any `trajkit.spline` curve (toppra's `SplineInterpolator(ss, way_pts)` is a
//! not-a-knot `CubicSpline`) or a `LinearPath`; constraints are `JointVelocityConstraint` and
//! `JointAccelerationConstraint` (toppra's names and `(dof, 2)` limit arrays); `TOPPRA` and
//! `NumericalIntegration` take the same constraint list and path and return a
//! `trajkit.Trajectory` from `compute_trajectory(sd_start, sd_end)`; `TOTG` times waypoints
//! with circular blends. Each solve is one library call (`Toppra::solve`, `ni::solve`,
//! `Totg::solve`, `plan_totg`, `messy::plan_waypoints`) run with the GIL released.

use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyTuple;
use trajkit::limits::Needs;
use trajkit::topp::messy::{plan_waypoints as plan_pieces, PathKind, PieceSolver, PlanOptions};
use trajkit::topp::{
    ni, plan_totg, Discretization, Gridpoints, JointAcceleration, JointVelocity, LinearPath,
    Toppra, ToppraOptions, TotgOptions,
};

use crate::convert::{bad, obj, table, values, vector, Floats, IntoPy};
use crate::limits::complete_of;
use crate::spline::{Curve, PathRef};
use crate::traj::{with_recipe, PyTrajectory, SharedTrajectory};

/// A polyline through `waypoints` (`(n, dof)`), parameterized by cumulative chord length.
#[pyclass(module = "trajkit.topp", name = "LinearPath", extends = Curve, frozen)]
pub struct PyLinearPath;

#[pymethods]
impl PyLinearPath {
    #[new]
    fn new<'py>(py: Python<'py>, waypoints: Floats<'py>) -> PyResult<PyClassInitializer<Self>> {
        let t = table(&waypoints, "waypoints")?;
        let p = LinearPath::new(&t.data, t.dim).py()?;
        let args = PyTuple::new(py, [obj(&waypoints)])?;
        Ok(
            PyClassInitializer::from(Curve::make(Arc::new(p), false, args))
                .add_subclass(PyLinearPath),
        )
    }
}

/// Which joint-limit constraint.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Velocity,
    Acceleration,
}

/// Lower and upper limits per joint from toppra's `(dof, 2)` array or a symmetric `(dof,)`.
fn ranges(a: &Floats<'_>, name: &str) -> PyResult<(Vec<f64>, Vec<f64>)> {
    let t = table(a, name)?;
    if t.was_1d {
        let hi = t.data.to_vec();
        return Ok((hi.iter().map(|v| -v).collect(), hi));
    }
    if t.dim != 2 {
        return Err(bad(format!(
            "{name}: expected shape (dof, 2) (lower, upper) or (dof,), found ({}, {})",
            t.rows, t.dim
        )));
    }
    Ok((
        t.data.chunks_exact(2).map(|r| r[0]).collect(),
        t.data.chunks_exact(2).map(|r| r[1]).collect(),
    ))
}

/// A joint velocity or acceleration constraint (validated by the library on creation).
#[pyclass(module = "trajkit.topp", name = "_JointConstraint", subclass, frozen)]
pub struct JointConstraint {
    kind: Kind,
    lo: Vec<f64>,
    hi: Vec<f64>,
    args: Py<PyTuple>,
}

#[pymethods]
impl JointConstraint {
    /// Number of joints.
    #[getter]
    fn dof(&self) -> usize {
        self.lo.len()
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        Ok((
            slf.get_type().into_any(),
            slf.get().args.bind(slf.py()).clone(),
        ))
    }
}

fn joint_constraint<'py>(
    py: Python<'py>,
    kind: Kind,
    lim: Floats<'py>,
    name: &str,
) -> PyResult<JointConstraint> {
    let (lo, hi) = ranges(&lim, name)?;
    match kind {
        Kind::Velocity => JointVelocity::new(&lo, &hi).map(|_| ()),
        Kind::Acceleration => JointAcceleration::new(&lo, &hi).map(|_| ()),
    }
    .py()?;
    Ok(JointConstraint {
        kind,
        lo,
        hi,
        args: PyTuple::new(py, [obj(&lim)])?.unbind(),
    })
}

/// toppra's `JointVelocityConstraint(vlim)`: `vlim` of shape `(dof, 2)` (lower, upper) or
/// `(dof,)` (symmetric).
#[pyclass(module = "trajkit.topp", name = "JointVelocityConstraint", extends = JointConstraint, frozen)]
pub struct PyVel;

#[pymethods]
impl PyVel {
    #[new]
    fn new<'py>(py: Python<'py>, vlim: Floats<'py>) -> PyResult<PyClassInitializer<Self>> {
        Ok(
            PyClassInitializer::from(joint_constraint(py, Kind::Velocity, vlim, "vlim")?)
                .add_subclass(PyVel),
        )
    }
}

/// toppra's `JointAccelerationConstraint(alim)`: `alim` of shape `(dof, 2)` or `(dof,)`.
#[pyclass(module = "trajkit.topp", name = "JointAccelerationConstraint", extends = JointConstraint, frozen)]
pub struct PyAcc;

#[pymethods]
impl PyAcc {
    #[new]
    fn new<'py>(py: Python<'py>, alim: Floats<'py>) -> PyResult<PyClassInitializer<Self>> {
        Ok(
            PyClassInitializer::from(joint_constraint(py, Kind::Acceleration, alim, "alim")?)
                .add_subclass(PyAcc),
        )
    }
}

/// The solver problem as plain data (Send), built into a `Toppra` inside the solve.
struct Problem {
    path: PathRef,
    constraints: Vec<(Kind, Vec<f64>, Vec<f64>)>,
    options: ToppraOptions,
}

impl Problem {
    fn build(&self) -> trajkit::Result<Toppra<'static, PathRef>> {
        let mut p = Toppra::new(self.path.clone()).options(self.options.clone());
        for (k, lo, hi) in &self.constraints {
            p = match k {
                Kind::Velocity => p.constraint(JointVelocity::new(lo, hi)?)?,
                Kind::Acceleration => p.constraint(JointAcceleration::new(lo, hi)?)?,
            };
        }
        Ok(p)
    }
}

fn gridpoints(g: Option<&Bound<'_, PyAny>>) -> PyResult<Gridpoints> {
    match g {
        None => Ok(ToppraOptions::default().gridpoints),
        Some(g) if g.is_none() => Ok(ToppraOptions::default().gridpoints),
        Some(g) => {
            if let Ok(n) = g.extract::<usize>() {
                return Ok(Gridpoints::Uniform(n));
            }
            let a: Floats<'_> = g
                .extract()
                .map_err(|_| bad("gridpoints: an interval count or an array of path positions"))?;
            Ok(Gridpoints::Given(values(&a).into_owned()))
        }
    }
}

/// Shared state of `TOPPRA` and `NumericalIntegration`.
#[pyclass(module = "trajkit.topp", name = "_Parameterizer", subclass, frozen)]
pub struct Parameterizer {
    problem: Arc<Problem>,
    ni: bool,
    args: Py<PyTuple>,
}

fn parameterizer<'py>(
    py: Python<'py>,
    constraint_list: Vec<Bound<'py, JointConstraint>>,
    path: Bound<'py, Curve>,
    gridpoints_: Option<Bound<'py, PyAny>>,
    discretization: &str,
    refine: bool,
    ni: bool,
) -> PyResult<Parameterizer> {
    let options = ToppraOptions {
        gridpoints: gridpoints(gridpoints_.as_ref())?,
        discretization: match discretization {
            "interpolation" => Discretization::Interpolation,
            "collocation" => Discretization::Collocation,
            other => {
                return Err(bad(format!(
                    "discretization = '{other}' is not 'interpolation' or 'collocation'"
                )))
            }
        },
        refine,
        ..ToppraOptions::default()
    };
    let constraints = constraint_list
        .iter()
        .map(|c| {
            let c = c.get();
            (c.kind, c.lo.clone(), c.hi.clone())
        })
        .collect();
    let problem = Problem {
        path: PathRef(path.get().path.clone()),
        constraints,
        options,
    };
    problem.build().py()?;
    let args = (constraint_list, path, gridpoints_, discretization, refine).into_pyobject(py)?;
    Ok(Parameterizer {
        problem: Arc::new(problem),
        ni,
        args: args.unbind(),
    })
}

#[pymethods]
impl Parameterizer {
    /// Solves and returns the time-optimal trajectory ξ(t) = σ(s(t)); `sd_start`, `sd_end`
    /// are the path velocities ṡ at the ends (toppra's names).
    #[pyo3(signature = (sd_start = 0.0, sd_end = 0.0))]
    fn compute_trajectory<'py>(
        slf: &Bound<'py, Self>,
        sd_start: f64,
        sd_end: f64,
    ) -> PyResult<Bound<'py, PyTrajectory>> {
        let py = slf.py();
        let me = slf.get();
        let problem = me.problem.clone();
        let ni_ = me.ni;
        let traj = py
            .detach(move || -> trajkit::Result<SharedTrajectory> {
                let p = problem.build()?.boundary_velocities(sd_start, sd_end);
                Ok(if ni_ {
                    Arc::new(ni::solve(p)?)
                } else {
                    Arc::new(p.solve()?)
                })
            })
            .py()?;
        let rebuild = py.import("trajkit.topp")?.getattr("_solve")?;
        let args = (slf.clone(), sd_start, sd_end).into_pyobject(py)?;
        let t = Bound::new(py, PyTrajectory::new(traj))?;
        t.call_method1("_set_recipe", (rebuild, args))?;
        Ok(t)
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        Ok((
            slf.get_type().into_any(),
            slf.get().args.bind(slf.py()).clone(),
        ))
    }
}

/// toppra's `TOPPRA(constraint_list, path, gridpoints=None)`: TOPP-RA (reachability analysis)
/// on `gridpoints` (an interval count, an array of path positions, or None for 1000
/// intervals), refined where a limit is exceeded between gridpoints unless `refine=False`.
#[pyclass(module = "trajkit.topp", name = "TOPPRA", extends = Parameterizer, frozen)]
pub struct PyToppra;

#[pymethods]
impl PyToppra {
    #[new]
    #[pyo3(signature = (constraint_list, path, gridpoints = None, discretization = "interpolation", refine = true))]
    fn new<'py>(
        py: Python<'py>,
        constraint_list: Vec<Bound<'py, JointConstraint>>,
        path: Bound<'py, Curve>,
        gridpoints: Option<Bound<'py, PyAny>>,
        discretization: &str,
        refine: bool,
    ) -> PyResult<PyClassInitializer<Self>> {
        let p = parameterizer(
            py,
            constraint_list,
            path,
            gridpoints,
            discretization,
            refine,
            false,
        )?;
        Ok(PyClassInitializer::from(p).add_subclass(PyToppra))
    }
}

/// Phase-plane numerical integration (Bobrow / TOPP-NI) on the same problem as `TOPPRA`;
/// `gridpoints` are its initial knots.
#[pyclass(module = "trajkit.topp", name = "NumericalIntegration", extends = Parameterizer, frozen)]
pub struct PyNi;

#[pymethods]
impl PyNi {
    #[new]
    #[pyo3(signature = (constraint_list, path, gridpoints = None, discretization = "interpolation", refine = true))]
    fn new<'py>(
        py: Python<'py>,
        constraint_list: Vec<Bound<'py, JointConstraint>>,
        path: Bound<'py, Curve>,
        gridpoints: Option<Bound<'py, PyAny>>,
        discretization: &str,
        refine: bool,
    ) -> PyResult<PyClassInitializer<Self>> {
        let p = parameterizer(
            py,
            constraint_list,
            path,
            gridpoints,
            discretization,
            refine,
            true,
        )?;
        Ok(PyClassInitializer::from(p).add_subclass(PyNi))
    }
}

/// TOTG (Kunz & Stilman): straight segments through `waypoints` (`(n, dof)`) joined by
/// circular blends within `max_deviation`, timed under the velocity and acceleration limits of
/// `limits`; stops at exact reversals. Jerk is not bounded (the path is only C¹).
#[pyfunction]
#[pyo3(signature = (waypoints, limits, max_deviation = 0.1, sd_start = 0.0, sd_end = 0.0))]
fn totg<'py>(
    py: Python<'py>,
    waypoints: Floats<'py>,
    limits: Bound<'py, PyAny>,
    max_deviation: f64,
    sd_start: f64,
    sd_end: f64,
) -> PyResult<Bound<'py, PyTrajectory>> {
    let w = table(&waypoints, "waypoints")?;
    let l = complete_of(&limits, TOTG_NEEDS)?;
    let opts = TotgOptions {
        max_deviation,
        start_velocity: sd_start,
        end_velocity: sd_end,
        ..TotgOptions::default()
    };
    let (data, dim) = (w.data.into_owned(), w.dim);
    let t = py
        .detach(|| plan_totg(&data, dim, &l, &opts).map(|t| Arc::new(t) as SharedTrajectory))
        .py()?;
    let args = (obj(&waypoints), limits, max_deviation, sd_start, sd_end).into_pyobject(py)?;
    with_recipe(py, t, "trajkit.topp", "totg", args)
}

/// What [`totg`] reads from its limits: velocity and acceleration (a missing one is an
/// error; the position range and jerk are not used).
pub const TOTG_NEEDS: Needs = Needs {
    position: false,
    velocity: true,
    acceleration: true,
    jerk: false,
};

/// What [`plan_waypoints`] reads: position range (its paths stay inside), velocity and
/// acceleration (no jerk stage).
pub const PIECES_NEEDS: Needs = Needs {
    position: true,
    velocity: true,
    acceleration: true,
    jerk: false,
};

/// The options of [`plan_waypoints`] from Python arguments.
pub fn piece_options(path: &str, solver: &str, gridpoints_: usize) -> PyResult<PlanOptions> {
    Ok(PlanOptions {
        kind: PathKind::parse(path).py()?,
        solver: match solver {
            "toppra" => PieceSolver::Toppra,
            "ni" => PieceSolver::Ni,
            other => return Err(bad(format!("solver = '{other}' is not 'toppra' or 'ni'"))),
        },
        toppra: ToppraOptions {
            gridpoints: Gridpoints::Uniform(gridpoints_),
            ..ToppraOptions::default()
        },
        ..PlanOptions::default()
    })
}

/// Time-optimal timing of raw planner waypoints (`(n, dof)`) under the velocity and
/// acceleration limits of `limits`: repeated waypoints dropped, a stop at each exact reversal,
/// a spline per piece (`path`: `'natural'`, `'not-a-knot'`, `'clamped'`, `'linear'`), each
/// piece solved by `solver` (`'toppra'` or `'ni'`) on `gridpoints` intervals.
#[pyfunction]
#[pyo3(signature = (waypoints, limits, path = "natural", solver = "toppra", gridpoints = 1000))]
fn plan_waypoints<'py>(
    py: Python<'py>,
    waypoints: Floats<'py>,
    limits: Bound<'py, PyAny>,
    path: &str,
    solver: &str,
    gridpoints: usize,
) -> PyResult<Bound<'py, PyTrajectory>> {
    let w = table(&waypoints, "waypoints")?;
    let l = complete_of(&limits, PIECES_NEEDS)?;
    let opts = piece_options(path, solver, gridpoints)?;
    let (data, dim) = (w.data.into_owned(), w.dim);
    let t = py
        .detach(|| plan_pieces(&data, dim, &l, &opts).map(|t| Arc::new(t) as SharedTrajectory))
        .py()?;
    let args = (obj(&waypoints), limits, path, solver, gridpoints).into_pyobject(py)?;
    with_recipe(py, t, "trajkit.topp", "plan_waypoints", args)
}

/// Registers the time-parameterization classes.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyLinearPath>()?;
    m.add_class::<JointConstraint>()?;
    m.add_class::<PyVel>()?;
    m.add_class::<PyAcc>()?;
    m.add_class::<Parameterizer>()?;
    m.add_class::<PyToppra>()?;
    m.add_class::<PyNi>()?;
    m.add_function(wrap_pyfunction!(totg, m)?)?;
    m.add_function(wrap_pyfunction!(plan_waypoints, m)?)?;
    let _ = vector;
    Ok(())
}
