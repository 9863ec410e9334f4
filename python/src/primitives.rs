//! `trajkit.primitives`: movement primitives learned from demonstrations (DMP, ProMP, KMP).
//!
//! `DMP.fit` / `DMP.from_weights` → `rollout(...)` (a `trajkit.Trajectory`); `ProMP.fit` →
//! `condition(via)`, mean `promp(t, order)`, `variance`, `covariance`, `sample(seed)`;
//! `KMP.fit` → `with_via_points(via)`, mean `kmp(t, order)`, `covariance`. Each is one call of
//! `trajkit::primitives`; evaluation over arrays releases the GIL. Objects pickle by the call
//! that made them (`fit` is deterministic).

use std::sync::Arc;

use numpy::PyUntypedArrayMethods;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use trajkit::primitives::{
    Demo, Dmp, DmpConfig, ForcingScaling, GmmConfig, Kmp, KmpConfig, KmpReference, KmpVia, ProMp,
    ProMpConfig, RolloutOptions, ViaPoint,
};
use trajkit::rng::SplitMix64;
use trajkit::{Order, Trajectory};

use crate::convert::{bad, eval_times, obj, order, table, vector, Floats, IntoPy};
use crate::traj::{eval_traj, with_recipe, PyTrajectory};

type Recipe = (Py<PyAny>, Py<PyTuple>);

fn recipe<'py>(
    py: Python<'py>,
    class: &str,
    method: &str,
    args: Bound<'py, PyTuple>,
) -> PyResult<Recipe> {
    let f = py
        .import("trajkit.primitives")?
        .getattr(class)?
        .getattr(method)?;
    Ok((f.unbind(), args.unbind()))
}

fn reduce<'py>(py: Python<'py>, r: &Recipe) -> (Py<PyAny>, Py<PyTuple>) {
    (r.0.clone_ref(py), r.1.clone_ref(py))
}

/// Demonstrations as `[(t, q), ...]` with `t` of shape `(n,)` and `q` `(n, dof)`.
/// `dof × dof` covariances of position (`order=0`) or velocity (`order=1`) at every time of
/// `t`, shape `t.shape + (dof, dof)`.
fn covariances<'py>(
    py: Python<'py>,
    t: &Floats<'py>,
    order: i64,
    d: usize,
    f: impl Fn(f64, Order, &mut [f64]) + Sync + Send,
) -> PyResult<Bound<'py, PyAny>> {
    let o = Order::from_index(self::order(order, 1)?).expect("checked");
    let flat = eval_times(py, t, d * d, false, |ti, out| f(ti, o, out))?;
    let mut shape: Vec<usize> = t.shape().to_vec();
    shape.extend([d, d]);
    flat.call_method1("reshape", (shape,))
}

/// Demonstrations as owned `(t, q)` data.
type Demos = Vec<(Vec<f64>, Vec<f64>)>;

fn demos(list: &[(Floats<'_>, Floats<'_>)]) -> PyResult<(Demos, usize)> {
    let mut out = Vec::with_capacity(list.len());
    let mut dof = 0;
    for (i, (t, q)) in list.iter().enumerate() {
        let tt = vector(t, &format!("demos[{i}] t"), None)?;
        let qt = table(q, &format!("demos[{i}] q"))?;
        if i == 0 {
            dof = qt.dim;
        } else if qt.dim != dof {
            return Err(bad(format!(
                "demos[{i}] q: expected {dof} columns (as demos[0]), found {}",
                qt.dim
            )));
        }
        out.push((tt, qt.data.into_owned()));
    }
    if out.is_empty() {
        return Err(bad("demos: at least one demonstration (t, q) is needed"));
    }
    Ok((out, dof))
}

/// A discrete dynamic movement primitive.
#[pyclass(module = "trajkit.primitives", name = "DMP", frozen)]
pub struct PyDmp {
    dmp: Arc<Dmp>,
    recipe: Recipe,
}

fn config(n_basis: usize, alpha_z: f64, beta_z: Option<f64>, scaling: &str) -> PyResult<DmpConfig> {
    Ok(DmpConfig {
        n_basis,
        alpha_z,
        beta_z: beta_z.unwrap_or(alpha_z / 4.0),
        scaling: ForcingScaling::from_name(scaling).py()?,
        ..DmpConfig::default()
    })
}

#[pymethods]
impl PyDmp {
    /// Fits a DMP to one demonstration: times `t` `(n,)`, positions `q` `(n, dof)`.
    /// `scaling`: `'hoffmann'` (default, Hoffmann/Pastor 2009) or `'ijspeert'`.
    #[staticmethod]
    #[pyo3(signature = (t, q, n_basis = 50, alpha_z = 25.0, beta_z = None, scaling = "hoffmann"))]
    fn fit(
        py: Python<'_>,
        t: Floats<'_>,
        q: Floats<'_>,
        n_basis: usize,
        alpha_z: f64,
        beta_z: Option<f64>,
        scaling: &str,
    ) -> PyResult<Self> {
        let tt = vector(&t, "t", None)?;
        let qt = table(&q, "q")?;
        let cfg = config(n_basis, alpha_z, beta_z, scaling)?;
        let dmp = Dmp::fit(&tt, &qt.data, qt.dim, &cfg).py()?;
        let args = (obj(&t), obj(&q), n_basis, alpha_z, beta_z, scaling).into_pyobject(py)?;
        Ok(PyDmp {
            dmp: Arc::new(dmp),
            recipe: recipe(py, "DMP", "fit", args)?,
        })
    }

    /// A DMP from forcing-term weights `(dof, n_basis)`, duration `tau`, start and goal.
    #[staticmethod]
    #[pyo3(signature = (weights, tau, start, goal, alpha_z = 25.0, beta_z = None, scaling = "hoffmann"))]
    fn from_weights(
        py: Python<'_>,
        weights: Floats<'_>,
        tau: f64,
        start: Floats<'_>,
        goal: Floats<'_>,
        alpha_z: f64,
        beta_z: Option<f64>,
        scaling: &str,
    ) -> PyResult<Self> {
        let w = table(&weights, "weights")?;
        let cfg = config(w.dim, alpha_z, beta_z, scaling)?;
        let s = vector(&start, "start", None)?;
        let g = vector(&goal, "goal", None)?;
        let dmp = Dmp::from_weights(&cfg, tau, &s, &g, &w.data).py()?;
        let args = (
            obj(&weights),
            tau,
            obj(&start),
            obj(&goal),
            alpha_z,
            beta_z,
            scaling,
        )
            .into_pyobject(py)?;
        Ok(PyDmp {
            dmp: Arc::new(dmp),
            recipe: recipe(py, "DMP", "from_weights", args)?,
        })
    }

    /// Plays the DMP: optional new `goal`, `start`, `start_velocity`, temporal scaling `tau`
    /// (seconds) and `duration` (default `tau`). Returns a `trajkit.Trajectory`.
    #[pyo3(signature = (goal = None, start = None, tau = None, duration = None, start_velocity = None))]
    fn rollout<'py>(
        slf: &Bound<'py, Self>,
        goal: Option<Floats<'py>>,
        start: Option<Floats<'py>>,
        tau: Option<f64>,
        duration: Option<f64>,
        start_velocity: Option<Floats<'py>>,
    ) -> PyResult<Bound<'py, PyTrajectory>> {
        let py = slf.py();
        let dmp = slf.get().dmp.clone();
        let n = dmp.dof();
        let o = |a: &Option<Floats<'py>>, name: &str| {
            a.as_ref().map(|a| vector(a, name, Some(n))).transpose()
        };
        let (g, s, v) = (
            o(&goal, "goal")?,
            o(&start, "start")?,
            o(&start_velocity, "start_velocity")?,
        );
        let roll = py
            .detach(move || {
                dmp.rollout(&RolloutOptions {
                    goal: g,
                    start: s,
                    start_velocity: v,
                    tau,
                    duration,
                    ..RolloutOptions::default()
                })
            })
            .py()?;
        let args = (
            slf.clone(),
            goal.as_ref().map(obj),
            start.as_ref().map(obj),
            tau,
            duration,
            start_velocity.as_ref().map(obj),
        )
            .into_pyobject(py)?;
        with_recipe(py, Arc::new(roll), "trajkit.primitives", "_rollout", args)
    }

    /// Number of joints.
    #[getter]
    fn dof(&self) -> usize {
        self.dmp.dof()
    }

    /// Demonstrated duration τ (seconds).
    #[getter]
    fn tau(&self) -> f64 {
        self.dmp.tau()
    }

    /// Demonstrated start.
    #[getter]
    fn start(&self) -> Vec<f64> {
        self.dmp.start().to_vec()
    }

    /// Demonstrated goal.
    #[getter]
    fn goal(&self) -> Vec<f64> {
        self.dmp.goal().to_vec()
    }

    /// Forcing-term weights, shape `(dof, n_basis)`.
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let w = self.dmp.weights().to_vec();
        let n = self.dmp.dof();
        let k = w.len() / n.max(1);
        crate::convert::array(py, w, &[n, k])
    }

    fn __reduce__(&self, py: Python<'_>) -> (Py<PyAny>, Py<PyTuple>) {
        reduce(py, &self.recipe)
    }
}

/// A probabilistic movement primitive: a Gaussian over basis weights.
#[pyclass(module = "trajkit.primitives", name = "ProMP", frozen)]
pub struct PyProMp {
    promp: Arc<ProMp>,
    recipe: Recipe,
}

fn vias(dof: usize, via: &[(f64, Floats<'_>, f64)]) -> PyResult<Vec<ViaPoint>> {
    via.iter()
        .enumerate()
        .map(|(i, (t, q, var))| {
            let v = vector(q, &format!("via[{i}] value"), Some(dof))?;
            Ok(ViaPoint::position(*t, &v, *var))
        })
        .collect()
}

#[pymethods]
impl PyProMp {
    /// Fits a ProMP to demonstrations `[(t, q), ...]` (`q` of shape `(n, dof)`).
    #[staticmethod]
    #[pyo3(signature = (demos, n_basis = 20, ridge = 1e-12, prior_variance = 1e-6))]
    fn fit(
        py: Python<'_>,
        demos: Vec<(Floats<'_>, Floats<'_>)>,
        n_basis: usize,
        ridge: f64,
        prior_variance: f64,
    ) -> PyResult<Self> {
        let (d, dof) = self::demos(&demos)?;
        let ds: Vec<Demo<'_>> = d.iter().map(|(t, q)| Demo { t, q }).collect();
        let cfg = ProMpConfig {
            n_basis,
            ridge,
            prior_variance,
            ..ProMpConfig::default()
        };
        let p = ProMp::fit(&ds, dof, &cfg).py()?;
        let list: Vec<(Bound<'_, PyAny>, Bound<'_, PyAny>)> =
            demos.iter().map(|(t, q)| (obj(t), obj(q))).collect();
        let args = (list, n_basis, ridge, prior_variance).into_pyobject(py)?;
        Ok(PyProMp {
            promp: Arc::new(p),
            recipe: recipe(py, "ProMP", "fit", args)?,
        })
    }

    /// The ProMP conditioned on via points `[(t, q, variance), ...]` (position `q` at time
    /// `t`, isotropic variance; 0 passes exactly).
    fn condition<'py>(slf: &Bound<'py, Self>, via: Vec<(f64, Floats<'py>, f64)>) -> PyResult<Self> {
        let py = slf.py();
        let me = slf.get();
        let v = vias(me.promp.dof(), &via)?;
        let p = me.promp.condition(&v).py()?;
        let list: Vec<(f64, Bound<'_, PyAny>, f64)> =
            via.iter().map(|(t, q, s)| (*t, obj(q), *s)).collect();
        let args = (slf.clone(), list).into_pyobject(py)?;
        let f = py.import("trajkit.primitives")?.getattr("_condition")?;
        Ok(PyProMp {
            promp: Arc::new(p),
            recipe: (f.unbind(), args.unbind()),
        })
    }

    /// The mean's `order`-th derivative at `t` (scalar or array), shape `t.shape + (dof,)`.
    #[pyo3(signature = (t, order = 0))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        t: Floats<'py>,
        order: i64,
    ) -> PyResult<Bound<'py, PyAny>> {
        eval_traj(py, self.promp.as_ref(), &t, order)
    }

    /// Per-joint variance of position (`order=0`) or velocity (`order=1`) at `t`.
    #[pyo3(signature = (t, order = 0))]
    fn variance<'py>(
        &self,
        py: Python<'py>,
        t: Floats<'py>,
        order: i64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let o = Order::from_index(self::order(order, 1)?).expect("checked");
        let p = self.promp.as_ref();
        eval_times(py, &t, p.dof(), false, |ti, out| p.variance(ti, o, out))
    }

    /// Joint covariance `(dof, dof)` of position or velocity at each `t`: shape
    /// `t.shape + (dof * dof,)` reshaped to `t.shape + (dof, dof)`.
    #[pyo3(signature = (t, order = 0))]
    fn covariance<'py>(
        &self,
        py: Python<'py>,
        t: Floats<'py>,
        order: i64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let p = self.promp.as_ref();
        covariances(py, &t, order, p.dof(), |ti, o, out| {
            p.covariance(ti, o, out)
        })
    }

    /// A trajectory drawn from the distribution with a seeded generator.
    fn sample<'py>(slf: &Bound<'py, Self>, seed: u64) -> PyResult<Bound<'py, PyTrajectory>> {
        let py = slf.py();
        let mut rng = SplitMix64::new(seed);
        let w = slf.get().promp.sample(&mut rng).py()?;
        let args = (slf.clone(), seed).into_pyobject(py)?;
        with_recipe(py, Arc::new(w), "trajkit.primitives", "_sample", args)
    }

    /// Number of joints.
    #[getter]
    fn dof(&self) -> usize {
        self.promp.dof()
    }

    /// Duration of the phase (seconds).
    #[getter]
    fn duration(&self) -> f64 {
        self.promp.duration()
    }

    /// Mean of the weights, shape `(dof * n_basis,)`.
    #[getter]
    fn weight_mean<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let w = self.promp.weight_mean().to_vec();
        let n = w.len();
        crate::convert::array(py, w, &[n])
    }

    fn __reduce__(&self, py: Python<'_>) -> (Py<PyAny>, Py<PyTuple>) {
        reduce(py, &self.recipe)
    }
}

/// A kernelized movement primitive.
#[pyclass(module = "trajkit.primitives", name = "KMP", frozen)]
pub struct PyKmp {
    kmp: Arc<Kmp>,
    recipe: Recipe,
}

#[pymethods]
impl PyKmp {
    /// Fits a KMP to demonstrations `[(t, q), ...]`: a GMM of `components` components over
    /// `(t, q)`, regressed at `points` times (the reference), then the KMP with kernel width
    /// `kernel_h` (1/s²) and regularizations `lam`, `lam_c`.
    #[staticmethod]
    #[pyo3(signature = (demos, components = 8, points = 100, kernel_h = 6.0, lam = 1.0, lam_c = 60.0))]
    fn fit(
        py: Python<'_>,
        demos: Vec<(Floats<'_>, Floats<'_>)>,
        components: usize,
        points: usize,
        kernel_h: f64,
        lam: f64,
        lam_c: f64,
    ) -> PyResult<Self> {
        let (d, dof) = self::demos(&demos)?;
        let ds: Vec<Demo<'_>> = d.iter().map(|(t, q)| Demo { t, q }).collect();
        let gmm = GmmConfig {
            components,
            ..GmmConfig::default()
        };
        let cfg = KmpConfig {
            kernel_h,
            lambda: lam,
            lambda_c: lam_c,
            ..KmpConfig::default()
        };
        let k = py
            .detach(|| {
                let r = KmpReference::from_demos(&ds, dof, &gmm, points)?;
                Kmp::fit(&r, &cfg)
            })
            .py()?;
        let list: Vec<(Bound<'_, PyAny>, Bound<'_, PyAny>)> =
            demos.iter().map(|(t, q)| (obj(t), obj(q))).collect();
        let args = (list, components, points, kernel_h, lam, lam_c).into_pyobject(py)?;
        Ok(PyKmp {
            kmp: Arc::new(k),
            recipe: recipe(py, "KMP", "fit", args)?,
        })
    }

    /// The KMP through via points `[(t, q, variance), ...]` (isotropic covariance).
    fn with_via_points<'py>(
        slf: &Bound<'py, Self>,
        via: Vec<(f64, Floats<'py>, f64)>,
    ) -> PyResult<Self> {
        let py = slf.py();
        let me = slf.get();
        let d = me.kmp.dof();
        let v = via
            .iter()
            .enumerate()
            .map(|(i, (t, q, var))| {
                let mean = vector(q, &format!("via[{i}] value"), Some(d))?;
                let mut cov = vec![0.0; d * d];
                for j in 0..d {
                    cov[j * d + j] = *var;
                }
                Ok(KmpVia { t: *t, mean, cov })
            })
            .collect::<PyResult<Vec<_>>>()?;
        let k = me.kmp.with_via_points(&v).py()?;
        let list: Vec<(f64, Bound<'_, PyAny>, f64)> =
            via.iter().map(|(t, q, s)| (*t, obj(q), *s)).collect();
        let args = (slf.clone(), list).into_pyobject(py)?;
        let f = py
            .import("trajkit.primitives")?
            .getattr("_with_via_points")?;
        Ok(PyKmp {
            kmp: Arc::new(k),
            recipe: (f.unbind(), args.unbind()),
        })
    }

    /// The mean's `order`-th derivative at `t`, shape `t.shape + (dof,)`.
    #[pyo3(signature = (t, order = 0))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        t: Floats<'py>,
        order: i64,
    ) -> PyResult<Bound<'py, PyAny>> {
        eval_traj(py, self.kmp.as_ref(), &t, order)
    }

    /// Covariance `(dof, dof)` of position (`order=0`) or velocity (`order=1`) at each `t`.
    #[pyo3(signature = (t, order = 0))]
    fn covariance<'py>(
        &self,
        py: Python<'py>,
        t: Floats<'py>,
        order: i64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let k = self.kmp.as_ref();
        covariances(py, &t, order, k.dof(), |ti, o, out| {
            k.covariance(ti, o, out)
        })
    }

    /// Number of joints.
    #[getter]
    fn dof(&self) -> usize {
        self.kmp.dof()
    }

    /// Duration of the reference (seconds).
    #[getter]
    fn duration(&self) -> f64 {
        self.kmp.duration()
    }

    fn __reduce__(&self, py: Python<'_>) -> (Py<PyAny>, Py<PyTuple>) {
        reduce(py, &self.recipe)
    }
}

/// Registers the primitive classes.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyDmp>()?;
    m.add_class::<PyProMp>()?;
    m.add_class::<PyKmp>()?;
    Ok(())
}
