//! `trajkit.spline`: scipy's interpolator names and call conventions on trajkit's curves.
//!
//! Every class derives from `Curve`, which holds a `trajkit::Path` and evaluates it over
//! arrays with the GIL released (`curve(x, nu=0)`, shape `x.shape + (dim,)`, or `x.shape` when
//! `y` was 1-D, as in scipy). The constructors map one to one onto the library's named
//! constructors; the only translation is of scipy's argument conventions (`bc_type`, `k`,
//! `method`). Outside the curve's interval the parameter is clamped (trajkit's one
//! out-of-range policy); scipy extrapolates instead. A curve pickles by its constructor
//! arguments.

use std::sync::Arc;

use numpy::PyUntypedArrayMethods;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use trajkit::spline::{
    AkimaSpline, BSpline, Bezier, CatmullRom, CatmullRomKind, CubicHermiteSpline, CubicSpline,
    EndDerivative, Nurbs, PchipSpline, Quat, SO3Spline,
};
use trajkit::{Path, PathAsTrajectory};

use crate::convert::{
    array, bad, eval_times, eval_times_many, obj, order, table, values, vector, Floats, IntoPy,
    Table,
};
use crate::traj::PyTrajectory;

/// A shared, thread-safe path.
pub type SharedPath = Arc<dyn Path + Send + Sync>;

/// A [`SharedPath`] as a `Path` (plain delegation), so that generic library code such as
/// `Toppra<P>` can own one.
#[derive(Clone)]
pub struct PathRef(pub SharedPath);

impl Path for PathRef {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn interval(&self) -> (f64, f64) {
        self.0.interval()
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        self.0.eval(s, order, out)
    }
    fn eval_derivatives(&self, s: f64, first: &mut [f64], second: &mut [f64]) {
        self.0.eval_derivatives(s, first, second)
    }
    fn eval_many(&self, s: &[f64], order: usize, out: &mut [f64]) {
        self.0.eval_many(s, order, out)
    }
    fn piecewise_degree(&self) -> Option<usize> {
        self.0.piecewise_degree()
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.0.breakpoints()
    }
}

/// The base class of every curve: a vector-valued path σ(s) over `[s_start, s_end]`.
#[pyclass(module = "trajkit.spline", name = "Curve", subclass, frozen)]
pub struct Curve {
    /// The library's curve.
    pub path: SharedPath,
    /// Whether values were given 1-D (results then drop their last axis).
    squeeze: bool,
    /// Constructor arguments, for pickling.
    args: Py<PyTuple>,
}

impl Curve {
    pub fn make(path: SharedPath, squeeze: bool, args: Bound<'_, PyTuple>) -> Self {
        Curve {
            path,
            squeeze,
            args: args.unbind(),
        }
    }
}

#[pymethods]
impl Curve {
    /// The `nu`-th derivative at `x` (scalar or array of any shape).
    #[pyo3(signature = (x, nu = 0))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        x: Floats<'py>,
        nu: i64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let k = order(nu, 20)?;
        let p = self.path.as_ref();
        eval_times_many(py, &x, p.dim(), self.squeeze, |s, out| {
            p.eval_many(s, k, out)
        })
    }

    /// The breakpoints (pieces' joints, both ends included), scipy's `x`.
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let b = self.path.breakpoints();
        let n = b.len();
        array(py, b, &[n])
    }

    /// The parameter interval `(start, end)`.
    #[getter]
    fn interval(&self) -> (f64, f64) {
        self.path.interval()
    }

    /// Number of components.
    #[getter]
    fn dim(&self) -> usize {
        self.path.dim()
    }

    /// The curve played as a trajectory: time runs over the parameter from its start.
    fn as_trajectory(&self) -> PyTrajectory {
        PyTrajectory::new(Arc::new(PathAsTrajectory(PathRef(self.path.clone()))))
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        Ok((slf.get_type().into_any(), slf.get().args.bind(py).clone()))
    }

    fn __repr__(slf: &Bound<'_, Self>) -> PyResult<String> {
        let c = slf.get();
        let (a, b) = c.path.interval();
        Ok(format!(
            "{}(dim={}, interval=({a}, {b}))",
            slf.get_type().qualname()?,
            c.path.dim()
        ))
    }
}

/// Reads `(x, y)` interpolation data; `axis` must be 0.
fn data<'a>(x: &'a Floats<'_>, y: &'a Floats<'_>, axis: i64) -> PyResult<(Vec<f64>, Table<'a>)> {
    if axis != 0 {
        return Err(bad(format!(
            "axis = {axis}: only axis=0 (one row per data site) is supported"
        )));
    }
    let xs = vector(x, "x", None)?;
    let t = table(y, "y")?;
    if t.rows != xs.len() {
        return Err(bad(format!(
            "y: expected {} rows (one per x), found {}",
            xs.len(),
            t.rows
        )));
    }
    Ok((xs, t))
}

fn no_extrapolation(extrapolate: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
    if let Some(e) = extrapolate {
        if e.is_truthy()? && !e.is_none() {
            let s: String = e.str()?.extract()?;
            if s != "False" {
                return Err(bad(format!(
                    "extrapolate = {s}: trajkit clamps outside the interval (extrapolate=False); extrapolation is not offered"
                )));
            }
        }
    }
    Ok(())
}

/// One end of scipy's `bc_type` tuple form: `(order, value)`.
fn end_condition(obj: &Bound<'_, PyAny>, dim: usize) -> PyResult<(usize, Vec<f64>)> {
    let (k, v): (usize, Bound<'_, PyAny>) = obj
        .extract()
        .map_err(|_| bad("bc_type: each end must be (derivative order, value)"))?;
    let vals = crate::convert::floats(&v, "bc_type value", None)?;
    let vals = if vals.len() == 1 && dim > 1 {
        vec![vals[0]; dim]
    } else {
        vals
    };
    if vals.len() != dim {
        return Err(bad(format!(
            "bc_type: expected {dim} values at an end, found {}",
            vals.len()
        )));
    }
    Ok((k, vals))
}

/// scipy's `CubicSpline(x, y, axis=0, bc_type='not-a-knot', extrapolate=None)`:
/// `'not-a-knot'`, `'natural'`, `'clamped'` (zero slope), `'periodic'`, or
/// `((1, d0), (1, d1))` (given slopes) / `((2, 0), (2, 0))` (natural).
#[pyclass(module = "trajkit.spline", name = "CubicSpline", extends = Curve, frozen)]
pub struct PyCubicSpline;

#[pymethods]
impl PyCubicSpline {
    #[new]
    #[pyo3(signature = (x, y, axis = 0, bc_type = None, extrapolate = None))]
    fn new<'py>(
        py: Python<'py>,
        x: Floats<'py>,
        y: Floats<'py>,
        axis: i64,
        bc_type: Option<Bound<'py, PyAny>>,
        extrapolate: Option<Bound<'py, PyAny>>,
    ) -> PyResult<PyClassInitializer<Self>> {
        no_extrapolation(extrapolate.as_ref())?;
        let (xs, t) = data(&x, &y, axis)?;
        let (y_, dim) = (&t.data[..], t.dim);
        let spline = match &bc_type {
            None => CubicSpline::not_a_knot(&xs, y_, dim),
            Some(b) => {
                if let Ok(name) = b.extract::<String>() {
                    match name.as_str() {
                        "not-a-knot" => CubicSpline::not_a_knot(&xs, y_, dim),
                        "natural" => CubicSpline::natural(&xs, y_, dim),
                        "clamped" => {
                            let z = vec![0.0; dim];
                            CubicSpline::clamped(&xs, y_, dim, &z, &z)
                        }
                        "periodic" => CubicSpline::periodic(&xs, y_, dim),
                        other => {
                            return Err(bad(format!(
                            "bc_type = '{other}' is not one of 'not-a-knot', 'natural', 'clamped', 'periodic'"
                        )))
                        }
                    }
                } else {
                    let (a, e): (Bound<'_, PyAny>, Bound<'_, PyAny>) = b.extract().map_err(|_| {
                        bad("bc_type: a name or a pair ((order, value), (order, value))")
                    })?;
                    let (ka, va) = end_condition(&a, dim)?;
                    let (ke, ve) = end_condition(&e, dim)?;
                    match (ka, ke) {
                        (1, 1) => CubicSpline::clamped(&xs, y_, dim, &va, &ve),
                        (2, 2) if va.iter().chain(&ve).all(|v| *v == 0.0) => {
                            CubicSpline::natural(&xs, y_, dim)
                        }
                        _ => {
                            return Err(bad(
                            "bc_type: trajkit's cubic spline takes first derivatives at both ends ((1, d0), (1, d1)) or zero second derivatives ((2, 0), (2, 0))",
                        ))
                        }
                    }
                }
            }
        }
        .py()?;
        let args = PyTuple::new(
            py,
            [
                obj(&x),
                obj(&y),
                axis.into_pyobject(py)?.into_any(),
                bc_type.unwrap_or_else(|| py.None().into_bound(py)),
            ],
        )?;
        Ok(
            PyClassInitializer::from(Curve::make(Arc::new(spline), t.was_1d, args))
                .add_subclass(PyCubicSpline),
        )
    }
}

/// scipy's `PchipInterpolator(x, y, axis=0, extrapolate=None)`: monotone, no overshoot.
#[pyclass(module = "trajkit.spline", name = "PchipInterpolator", extends = Curve, frozen)]
pub struct PyPchip;

#[pymethods]
impl PyPchip {
    #[new]
    #[pyo3(signature = (x, y, axis = 0, extrapolate = None))]
    fn new<'py>(
        py: Python<'py>,
        x: Floats<'py>,
        y: Floats<'py>,
        axis: i64,
        extrapolate: Option<Bound<'py, PyAny>>,
    ) -> PyResult<PyClassInitializer<Self>> {
        no_extrapolation(extrapolate.as_ref())?;
        let (xs, t) = data(&x, &y, axis)?;
        let s = PchipSpline::new(&xs, &t.data, t.dim).py()?;
        let args = PyTuple::new(py, [obj(&x), obj(&y)])?;
        Ok(
            PyClassInitializer::from(Curve::make(Arc::new(s), t.was_1d, args))
                .add_subclass(PyPchip),
        )
    }
}

/// scipy's `Akima1DInterpolator(x, y, axis=0, *, method='akima')`; `method='makima'` is the
/// modified form.
#[pyclass(module = "trajkit.spline", name = "Akima1DInterpolator", extends = Curve, frozen)]
pub struct PyAkima;

#[pymethods]
impl PyAkima {
    #[new]
    #[pyo3(signature = (x, y, axis = 0, method = "akima", extrapolate = None))]
    fn new<'py>(
        py: Python<'py>,
        x: Floats<'py>,
        y: Floats<'py>,
        axis: i64,
        method: &str,
        extrapolate: Option<Bound<'py, PyAny>>,
    ) -> PyResult<PyClassInitializer<Self>> {
        no_extrapolation(extrapolate.as_ref())?;
        let (xs, t) = data(&x, &y, axis)?;
        let s = match method {
            "akima" => AkimaSpline::original(&xs, &t.data, t.dim),
            "makima" => AkimaSpline::modified(&xs, &t.data, t.dim),
            other => {
                return Err(bad(format!(
                    "method = '{other}' is not 'akima' or 'makima'"
                )))
            }
        }
        .py()?;
        let args = PyTuple::new(
            py,
            [
                obj(&x),
                obj(&y),
                0i64.into_pyobject(py)?.into_any(),
                method.into_pyobject(py)?.into_any(),
            ],
        )?;
        Ok(
            PyClassInitializer::from(Curve::make(Arc::new(s), t.was_1d, args))
                .add_subclass(PyAkima),
        )
    }
}

/// scipy's `CubicHermiteSpline(x, y, dydx)`: given slopes at every point.
#[pyclass(module = "trajkit.spline", name = "CubicHermiteSpline", extends = Curve, frozen)]
pub struct PyHermite;

#[pymethods]
impl PyHermite {
    #[new]
    #[pyo3(signature = (x, y, dydx, axis = 0, extrapolate = None))]
    fn new<'py>(
        py: Python<'py>,
        x: Floats<'py>,
        y: Floats<'py>,
        dydx: Floats<'py>,
        axis: i64,
        extrapolate: Option<Bound<'py, PyAny>>,
    ) -> PyResult<PyClassInitializer<Self>> {
        no_extrapolation(extrapolate.as_ref())?;
        let (xs, t) = data(&x, &y, axis)?;
        let d = values(&dydx);
        let s = CubicHermiteSpline::new(&xs, &t.data, &d, t.dim).py()?;
        let args = PyTuple::new(py, [obj(&x), obj(&y), obj(&dydx)])?;
        Ok(
            PyClassInitializer::from(Curve::make(Arc::new(s), t.was_1d, args))
                .add_subclass(PyHermite),
        )
    }
}

/// scipy's `BSpline(t, c, k)`: knots `t`, coefficients `c` (`(n,)` or `(n, dim)`), degree `k`.
#[pyclass(module = "trajkit.spline", name = "BSpline", extends = Curve, frozen)]
pub struct PyBSpline {
    k: usize,
}

fn bspline_object<'py>(py: Python<'py>, b: BSpline, squeeze: bool) -> PyResult<Bound<'py, PyAny>> {
    let t = b.knots().to_vec();
    let n = b.num_control_points();
    let dim = b.dim();
    let c = b.control_points().to_vec();
    let k = b.degree();
    let tl = t.len();
    let c_arr = if squeeze {
        array(py, c, &[n])?
    } else {
        array(py, c, &[n, dim])?
    };
    let args = PyTuple::new(
        py,
        [array(py, t, &[tl])?, c_arr, k.into_pyobject(py)?.into_any()],
    )?;
    let init = PyClassInitializer::from(Curve::make(Arc::new(b), squeeze, args))
        .add_subclass(PyBSpline { k });
    Ok(Bound::new(py, init)?.into_any())
}

#[pymethods]
impl PyBSpline {
    #[new]
    #[pyo3(signature = (t, c, k, extrapolate = None, axis = 0))]
    fn new<'py>(
        py: Python<'py>,
        t: Floats<'py>,
        c: Floats<'py>,
        k: usize,
        extrapolate: Option<Bound<'py, PyAny>>,
        axis: i64,
    ) -> PyResult<PyClassInitializer<Self>> {
        no_extrapolation(extrapolate.as_ref())?;
        if axis != 0 {
            return Err(bad(format!("axis = {axis}: only axis=0 is supported")));
        }
        let knots = vector(&t, "t", None)?;
        let ct = table(&c, "c")?;
        let b = BSpline::new(&knots, &ct.data, ct.dim, k).py()?;
        let args = PyTuple::new(py, [obj(&t), obj(&c), k.into_pyobject(py)?.into_any()])?;
        Ok(
            PyClassInitializer::from(Curve::make(Arc::new(b), ct.was_1d, args))
                .add_subclass(PyBSpline { k }),
        )
    }

    /// The degree.
    #[getter]
    fn k(&self) -> usize {
        self.k
    }
}

/// scipy's `make_interp_spline(x, y, k=3, bc_type=None)`: the interpolating B-spline of degree
/// `k` with scipy's default knots, or with end derivatives `bc_type=([(order, value), ...],
/// [(order, value), ...])` (knots at the data sites). Returns a `BSpline`.
#[pyfunction]
#[pyo3(signature = (x, y, k = 3, t = None, bc_type = None, axis = 0, check_finite = true))]
fn make_interp_spline<'py>(
    py: Python<'py>,
    x: Floats<'py>,
    y: Floats<'py>,
    k: usize,
    t: Option<Bound<'py, PyAny>>,
    bc_type: Option<Bound<'py, PyAny>>,
    axis: i64,
    check_finite: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let _ = check_finite; // trajkit always checks.
    if t.as_ref().is_some_and(|t| !t.is_none()) {
        return Err(bad(
            "t: given knots are not supported; trajkit chooses scipy's default knots",
        ));
    }
    let (xs, tb) = data(&x, &y, axis)?;
    let dim = tb.dim;
    let b = match bc_type.filter(|b| !b.is_none()) {
        None => BSpline::interpolate(&xs, &tb.data, dim, k),
        Some(b) => {
            let (s, e): (Bound<'_, PyAny>, Bound<'_, PyAny>) = b
                .extract()
                .map_err(|_| bad("bc_type: a pair (start conditions, end conditions)"))?;
            let read = |side: &Bound<'_, PyAny>| -> PyResult<Vec<(usize, Vec<f64>)>> {
                if side.is_none() {
                    return Ok(vec![]);
                }
                let items: Vec<Bound<'_, PyAny>> = side.extract()?;
                items.iter().map(|i| end_condition(i, dim)).collect()
            };
            let (sv, ev) = (read(&s)?, read(&e)?);
            let se: Vec<EndDerivative<'_>> = sv
                .iter()
                .map(|(order, value)| EndDerivative {
                    order: *order,
                    value,
                })
                .collect();
            let ee: Vec<EndDerivative<'_>> = ev
                .iter()
                .map(|(order, value)| EndDerivative {
                    order: *order,
                    value,
                })
                .collect();
            BSpline::interpolate_with_ends(&xs, &tb.data, dim, k, &se, &ee)
        }
    }
    .py()?;
    bspline_object(py, b, tb.was_1d)
}

fn zeros_or(a: Option<Floats<'_>>, name: &str, dim: usize) -> PyResult<Vec<f64>> {
    match a {
        None => Ok(vec![0.0; dim]),
        Some(a) => vector(&a, name, Some(dim)),
    }
}

/// The minimum-jerk interpolating spline (quintic B-spline with end velocity and acceleration,
/// zero by default) through `y` at `x`. Returns a `BSpline`.
#[pyfunction]
#[pyo3(signature = (x, y, v_start = None, a_start = None, v_end = None, a_end = None))]
fn minimum_jerk<'py>(
    py: Python<'py>,
    x: Floats<'py>,
    y: Floats<'py>,
    v_start: Option<Floats<'py>>,
    a_start: Option<Floats<'py>>,
    v_end: Option<Floats<'py>>,
    a_end: Option<Floats<'py>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (xs, t) = data(&x, &y, 0)?;
    let d = t.dim;
    let (vs, as_, ve, ae) = (
        zeros_or(v_start, "v_start", d)?,
        zeros_or(a_start, "a_start", d)?,
        zeros_or(v_end, "v_end", d)?,
        zeros_or(a_end, "a_end", d)?,
    );
    let b = BSpline::minimum_jerk(&xs, &t.data, d, &vs, &as_, &ve, &ae).py()?;
    bspline_object(py, b, t.was_1d)
}

/// The minimum-snap interpolating spline (septic B-spline with end velocity, acceleration and
/// jerk, zero by default) through `y` at `x`. Returns a `BSpline`.
#[pyfunction]
#[pyo3(signature = (x, y, start = None, end = None))]
fn minimum_snap<'py>(
    py: Python<'py>,
    x: Floats<'py>,
    y: Floats<'py>,
    start: Option<Floats<'py>>,
    end: Option<Floats<'py>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (xs, t) = data(&x, &y, 0)?;
    let d = t.dim;
    let read = |a: Option<Floats<'_>>, name: &str| -> PyResult<Vec<f64>> {
        match a {
            None => Ok(vec![0.0; 3 * d]),
            Some(a) => {
                if a.shape() != [3, d] && !(d == 1 && a.shape() == [3]) {
                    return Err(bad(format!(
                        "{name}: expected shape (3, {d}) (velocity, acceleration, jerk), found {:?}",
                        a.shape()
                    )));
                }
                Ok(values(&a).into_owned())
            }
        }
    };
    let (s, e) = (read(start, "start")?, read(end, "end")?);
    let b = BSpline::minimum_snap(
        &xs,
        &t.data,
        d,
        [&s[..d], &s[d..2 * d], &s[2 * d..]],
        [&e[..d], &e[d..2 * d], &e[2 * d..]],
    )
    .py()?;
    bspline_object(py, b, t.was_1d)
}

/// A Catmull-Rom spline through `points` (`(n, dim)`), `kind` `'uniform'`, `'centripetal'`
/// (default) or `'chordal'`, parameterized by its knots (`.x`).
#[pyclass(module = "trajkit.spline", name = "CatmullRom", extends = Curve, frozen)]
pub struct PyCatmullRom;

#[pymethods]
impl PyCatmullRom {
    #[new]
    #[pyo3(signature = (points, kind = "centripetal"))]
    fn new<'py>(
        py: Python<'py>,
        points: Floats<'py>,
        kind: &str,
    ) -> PyResult<PyClassInitializer<Self>> {
        let k = match kind {
            "uniform" => CatmullRomKind::Uniform,
            "centripetal" => CatmullRomKind::Centripetal,
            "chordal" => CatmullRomKind::Chordal,
            other => {
                return Err(bad(format!(
                    "kind = '{other}' is not 'uniform', 'centripetal' or 'chordal'"
                )))
            }
        };
        let t = table(&points, "points")?;
        let c = CatmullRom::new(&t.data, t.dim, k).py()?;
        let args = PyTuple::new(py, [obj(&points), kind.into_pyobject(py)?.into_any()])?;
        Ok(
            PyClassInitializer::from(Curve::make(Arc::new(c), t.was_1d, args))
                .add_subclass(PyCatmullRom),
        )
    }
}

/// A Bézier curve on `[0, 1]` from its control points (`(n, dim)`).
#[pyclass(module = "trajkit.spline", name = "Bezier", extends = Curve, frozen)]
pub struct PyBezier;

#[pymethods]
impl PyBezier {
    #[new]
    fn new<'py>(
        py: Python<'py>,
        control_points: Floats<'py>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let t = table(&control_points, "control_points")?;
        let b = Bezier::new(&t.data, t.dim).py()?;
        let args = PyTuple::new(py, [obj(&control_points)])?;
        Ok(
            PyClassInitializer::from(Curve::make(Arc::new(b), t.was_1d, args))
                .add_subclass(PyBezier),
        )
    }
}

/// A NURBS curve: knots `t`, control points `c` (`(n, dim)`), positive `weights`, degree `k`.
#[pyclass(module = "trajkit.spline", name = "NURBS", extends = Curve, frozen)]
pub struct PyNurbs;

#[pymethods]
impl PyNurbs {
    #[new]
    fn new<'py>(
        py: Python<'py>,
        t: Floats<'py>,
        c: Floats<'py>,
        weights: Floats<'py>,
        k: usize,
    ) -> PyResult<PyClassInitializer<Self>> {
        let knots = vector(&t, "t", None)?;
        let ct = table(&c, "c")?;
        let w = vector(&weights, "weights", None)?;
        let n = Nurbs::new(&knots, &ct.data, &w, ct.dim, k).py()?;
        let args = PyTuple::new(
            py,
            [
                obj(&t),
                obj(&c),
                obj(&weights),
                k.into_pyobject(py)?.into_any(),
            ],
        )?;
        Ok(
            PyClassInitializer::from(Curve::make(Arc::new(n), ct.was_1d, args))
                .add_subclass(PyNurbs),
        )
    }

    /// The exact circle of `radius` around `center` (2-D), parameter in `[0, 1]`.
    #[staticmethod]
    fn circle<'py>(
        py: Python<'py>,
        center: (f64, f64),
        radius: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        nurbs_object(py, Nurbs::circle([center.0, center.1], radius).py()?)
    }

    /// The exact arc of `radius` around `center` from angle `start` to `end` (radians).
    #[staticmethod]
    fn arc<'py>(
        py: Python<'py>,
        center: (f64, f64),
        radius: f64,
        start: f64,
        end: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        nurbs_object(
            py,
            Nurbs::arc([center.0, center.1], radius, start, end).py()?,
        )
    }
}

fn nurbs_object<'py>(py: Python<'py>, n: Nurbs) -> PyResult<Bound<'py, PyAny>> {
    let t = n.knots().to_vec();
    let w = n.weights().to_vec();
    let c = n.control_points();
    let dim = n.dim();
    let (tl, wl) = (t.len(), w.len());
    let args = PyTuple::new(
        py,
        [
            array(py, t, &[tl])?,
            array(py, c, &[wl, dim])?,
            array(py, w, &[wl])?,
            n.degree().into_pyobject(py)?.into_any(),
        ],
    )?;
    let init =
        PyClassInitializer::from(Curve::make(Arc::new(n), false, args)).add_subclass(PyNurbs);
    Ok(Bound::new(py, init)?.into_any())
}

/// Quaternions `(n, 4)` in `(w, x, y, z)` order to the library's type.
fn quats(a: &Floats<'_>, name: &str) -> PyResult<Vec<Quat>> {
    let t = table(a, name)?;
    if t.dim != 4 || t.was_1d {
        return Err(bad(format!(
            "{name}: expected shape (n, 4) (w, x, y, z), found {:?}",
            a.shape()
        )));
    }
    t.data
        .chunks_exact(4)
        .map(|q| Quat::new(q[0], q[1], q[2], q[3]))
        .collect::<trajkit::Result<Vec<_>>>()
        .py()
}

/// A C² orientation spline through unit quaternions `keys` (`(n, 4)`, `(w, x, y, z)`) at
/// increasing `times`.
#[pyclass(module = "trajkit.spline", name = "SO3Spline", frozen)]
pub struct PySO3 {
    spline: SO3Spline,
    args: Py<PyTuple>,
}

#[pymethods]
impl PySO3 {
    #[new]
    fn new<'py>(py: Python<'py>, times: Floats<'py>, keys: Floats<'py>) -> PyResult<Self> {
        let ts = vector(&times, "times", None)?;
        let ks = quats(&keys, "keys")?;
        let spline = SO3Spline::interpolate(&ts, &ks).py()?;
        let args = PyTuple::new(py, [obj(&times), obj(&keys)])?.unbind();
        Ok(PySO3 { spline, args })
    }

    /// The orientation at `t` as unit quaternions, shape `t.shape + (4,)`.
    fn __call__<'py>(&self, py: Python<'py>, t: Floats<'py>) -> PyResult<Bound<'py, PyAny>> {
        let s = &self.spline;
        eval_times(py, &t, 4, false, |ti, out| {
            out.copy_from_slice(&s.eval(ti).to_array())
        })
    }

    /// Angular velocity (rad/s, world frame) at `t`, shape `t.shape + (3,)`.
    fn angular_velocity<'py>(
        &self,
        py: Python<'py>,
        t: Floats<'py>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let s = &self.spline;
        eval_times(py, &t, 3, false, |ti, out| {
            out.copy_from_slice(&s.angular_velocity(ti))
        })
    }

    /// Angular acceleration (rad/s²) at `t`, shape `t.shape + (3,)`.
    fn angular_acceleration<'py>(
        &self,
        py: Python<'py>,
        t: Floats<'py>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let s = &self.spline;
        eval_times(py, &t, 3, false, |ti, out| {
            out.copy_from_slice(&s.angular_acceleration(ti))
        })
    }

    /// The time interval `(start, end)`.
    #[getter]
    fn interval(&self) -> (f64, f64) {
        self.spline.interval()
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        Ok((slf.get_type().into_any(), slf.get().args.bind(py).clone()))
    }
}

/// Registers the spline classes and functions.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Curve>()?;
    m.add_class::<PyCubicSpline>()?;
    m.add_class::<PyPchip>()?;
    m.add_class::<PyAkima>()?;
    m.add_class::<PyHermite>()?;
    m.add_class::<PyBSpline>()?;
    m.add_class::<PyCatmullRom>()?;
    m.add_class::<PyBezier>()?;
    m.add_class::<PyNurbs>()?;
    m.add_class::<PySO3>()?;
    m.add_function(wrap_pyfunction!(make_interp_spline, m)?)?;
    m.add_function(wrap_pyfunction!(minimum_jerk, m)?)?;
    m.add_function(wrap_pyfunction!(minimum_snap, m)?)?;
    Ok(())
}
