//! `trajkit.Limits`: per-joint limits from a preset, a dict, a URDF, a MoveIt
//! `joint_limits.yaml` or a trajkit limits file; each constructor is one library loader.
//!
//! Functions that take limits accept a `Limits`, a preset name or file path (`str`, as the
//! CLI's `--limits`), or a dict in trajkit's limits-file format (read by the library's JSON
//! reader, so unknown fields and bad values are refused with its messages).

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use trajkit::Limits;

use crate::convert::{array, bad, IntoPy};

/// Per-joint limits (position range, velocity, acceleration, jerk, optional effort).
#[pyclass(module = "trajkit", name = "Limits", frozen, from_py_object)]
#[derive(Clone)]
pub struct PyLimits {
    /// The library's limits.
    pub inner: Limits,
}

fn column(l: &Limits, f: impl Fn(&trajkit::JointLimits) -> f64) -> Vec<f64> {
    l.joints().iter().map(f).collect()
}

#[pymethods]
impl PyLimits {
    /// Limits from a preset name (`'panda'`, `'ur5e'`, `'iiwa14'`), a file path (`.urdf`,
    /// `.xml`, MoveIt `joint_limits.yaml`, trajkit `.json`/`.yaml`) or a dict in trajkit's
    /// limits-file format (`{"joints": [{"name", "position": [lo, hi], "velocity", ...}]}`).
    #[new]
    fn new(spec: &Bound<'_, PyAny>) -> PyResult<Self> {
        Ok(PyLimits {
            inner: limits_of(spec)?,
        })
    }

    /// A robot preset by name.
    #[staticmethod]
    fn preset(name: &str) -> PyResult<Self> {
        Ok(PyLimits {
            inner: Limits::preset(name).py()?,
        })
    }

    /// Limits from a file: URDF, MoveIt `joint_limits.yaml`, trajkit JSON/YAML.
    #[staticmethod]
    fn from_file(path: std::path::PathBuf) -> PyResult<Self> {
        Ok(PyLimits {
            inner: trajkit::limits::load::from_file(&path).py()?,
        })
    }

    /// The same limits for `dof` joints (no position range).
    #[staticmethod]
    #[pyo3(signature = (dof, velocity, acceleration, jerk = f64::INFINITY))]
    fn uniform(dof: usize, velocity: f64, acceleration: f64, jerk: f64) -> PyResult<Self> {
        Ok(PyLimits {
            inner: Limits::uniform(dof, velocity, acceleration, jerk).py()?,
        })
    }

    /// Number of joints.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }

    /// Joint names.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.inner.joints().iter().map(|j| j.name.clone()).collect()
    }

    /// Position ranges, shape `(dof, 2)`.
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self
            .inner
            .joints()
            .iter()
            .flat_map(|j| [j.position_min, j.position_max])
            .collect();
        array(py, v, &[self.inner.dof(), 2])
    }

    /// Velocity limits, shape `(dof,)` (`inf` = unlimited).
    #[getter]
    fn velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(py, column(&self.inner, |j| j.velocity), &[self.inner.dof()])
    }

    /// Acceleration limits, shape `(dof,)`.
    #[getter]
    fn acceleration<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(
            py,
            column(&self.inner, |j| j.acceleration),
            &[self.inner.dof()],
        )
    }

    /// Jerk limits, shape `(dof,)`.
    #[getter]
    fn jerk<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(py, column(&self.inner, |j| j.jerk), &[self.inner.dof()])
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (Vec<Joint>,))> {
        let joints = self
            .inner
            .joints()
            .iter()
            .map(|j| {
                (
                    j.name.clone(),
                    [
                        j.position_min,
                        j.position_max,
                        j.velocity,
                        j.acceleration,
                        j.jerk,
                    ],
                    [j.min_velocity, j.min_acceleration, j.effort],
                )
            })
            .collect();
        let from = py
            .import("trajkit._trajkit")?
            .getattr("_limits_from_joints")?;
        Ok((from, (joints,)))
    }

    fn __repr__(&self) -> String {
        format!(
            "trajkit.Limits(dof={}, names={:?})",
            self.inner.dof(),
            self.names()
        )
    }
}

/// One joint's limits as pickled: name, `[position_min, position_max, velocity, acceleration,
/// jerk]`, `[min_velocity, min_acceleration, effort]`.
type Joint = (String, [f64; 5], [Option<f64>; 3]);

/// Limits from pickled joints (validated again by `Limits::new`).
#[pyfunction]
fn _limits_from_joints(joints: Vec<Joint>) -> PyResult<PyLimits> {
    let joints = joints
        .into_iter()
        .map(|(name, a, b)| trajkit::JointLimits {
            name,
            position_min: a[0],
            position_max: a[1],
            velocity: a[2],
            acceleration: a[3],
            jerk: a[4],
            min_velocity: b[0],
            min_acceleration: b[1],
            effort: b[2],
        })
        .collect();
    Ok(PyLimits {
        inner: Limits::new(joints).py()?,
    })
}

/// Limits from a trajkit limits-file JSON text.
#[pyfunction]
fn limits_from_json(text: &str) -> PyResult<PyLimits> {
    Ok(PyLimits {
        inner: trajkit::limits::load::from_json_str(text, "<dict>").py()?,
    })
}

/// Reads limits from a `Limits`, a preset name or path, or a dict.
pub fn limits_of(obj: &Bound<'_, PyAny>) -> PyResult<Limits> {
    if let Ok(l) = obj.cast::<PyLimits>() {
        return Ok(l.get().inner.clone());
    }
    if let Ok(s) = obj.extract::<String>() {
        return trajkit::limits::load::from_spec(&s).py();
    }
    if obj.is_instance_of::<PyDict>() || obj.is_instance_of::<PyList>() {
        let json = obj.py().import("json")?.getattr("dumps")?.call1((obj,))?;
        let text: String = json.extract()?;
        return trajkit::limits::load::from_json_str(&text, "<dict>").py();
    }
    Err(bad(format!(
        "limits: expected a trajkit.Limits, a preset name or file path, or a dict; found {}",
        obj.get_type().name()?
    )))
}

/// Registers `Limits`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyLimits>()?;
    m.add_function(wrap_pyfunction!(limits_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(_limits_from_joints, m)?)?;
    Ok(())
}
