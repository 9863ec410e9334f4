//! `trajkit.Limits`: per-joint limits as their sources give them, from a preset, a dict, a
//! URDF, a MoveIt `joint_limits.yaml` or a trajkit limits file; each constructor and method is
//! one library call on `trajkit::limits::PartialLimits`.
//!
//! An absent limit is **not** "unlimited": a URDF has no acceleration or jerk limit, and an
//! operation that needs one refuses it ([`complete`], `trajkit::Error::MissingLimit` naming
//! the joint and the field) unless another source supplies it (`fill_from`, `with_overrides`,
//! a MoveIt file) or it is stated infinite on purpose. Functions that take limits accept a
//! `Limits`, a preset name or file path (`str`, as the CLI's `--limits`), or a dict in
//! trajkit's limits-file format (read by the library's JSON reader, so unknown fields and bad
//! values are refused with its messages).
//!
//! [`LimitsArgs`] is the one conversion of the CLI-style keyword arguments of `trajkit.plan`
//! (`joint_limits`, `fill_from`, `max_velocity`, ..., scales) into limits for the waypoint
//! columns, in the CLI's order (`trajkit plan`'s `LimitsArgs::resolve`).

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use trajkit::limits::{load, FillBy, Given, Needs, PartialLimits};
use trajkit::{JointLimits, Limits, Order};

use crate::convert::{array, bad, floats, IntoPy};

/// Per-joint limits (position range, velocity, acceleration, jerk, optional effort) and which
/// of them were given.
#[pyclass(module = "trajkit", name = "Limits", frozen, from_py_object)]
#[derive(Clone)]
pub struct PyLimits {
    /// The library's limits with what each source gave.
    pub inner: PartialLimits,
}

impl PyLimits {
    fn wrap(inner: PartialLimits) -> Self {
        PyLimits { inner }
    }

    /// One value per joint; absent ones (not given) are NaN.
    fn column(&self, f: impl Fn(&JointLimits, &Given) -> f64) -> Vec<f64> {
        self.inner
            .joints()
            .iter()
            .zip(self.inner.given())
            .map(|(j, g)| f(j, g))
            .collect()
    }
}

fn or_nan(given: bool, v: f64) -> f64 {
    if given {
        v
    } else {
        f64::NAN
    }
}

/// What an operation needs, from keyword flags.
fn needs(position: bool, velocity: bool, acceleration: bool, jerk: bool) -> Needs {
    Needs {
        position,
        velocity,
        acceleration,
        jerk,
    }
}

/// `FillBy` from `'name'` / `'index'`.
fn fill_by(by: &str) -> PyResult<FillBy> {
    match by {
        "name" => Ok(FillBy::Name),
        "index" => Ok(FillBy::Index),
        other => Err(bad(format!("by = '{other}' is not 'name' or 'index'"))),
    }
}

/// Position ranges from `(lo, hi)` (every joint) or a sequence of pairs / a `(dof, 2)` array.
fn ranges(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<(f64, f64)>> {
    let v = floats(
        &obj.py().import("numpy")?.call_method1("ravel", (obj,))?,
        name,
        None,
    )?;
    if v.len() % 2 != 0 || v.is_empty() {
        return Err(bad(format!(
            "{name}: expected (lo, hi) or one (lo, hi) per joint, found {} values",
            v.len()
        )));
    }
    Ok(v.chunks_exact(2).map(|p| (p[0], p[1])).collect())
}

#[pymethods]
impl PyLimits {
    /// Limits from a preset name (`'panda'`, `'ur5e'`, `'iiwa14'`), a file path (`.urdf`,
    /// `.xml`, MoveIt `joint_limits.yaml`, trajkit `.json`/`.yaml`) or a dict in trajkit's
    /// limits-file format (`{"joints": [{"name", "position": [lo, hi], "velocity", ...}]}`).
    /// Only what the source gives is given (a URDF has no acceleration or jerk limits).
    #[new]
    fn new(spec: &Bound<'_, PyAny>) -> PyResult<Self> {
        Ok(PyLimits::wrap(limits_of(spec)?))
    }

    /// A robot preset by name (every limit given).
    #[staticmethod]
    fn preset(name: &str) -> PyResult<Self> {
        Ok(PyLimits::wrap(Limits::preset(name).py()?.into()))
    }

    /// Limits from a file: URDF, MoveIt `joint_limits.yaml`, trajkit JSON/YAML.
    #[staticmethod]
    fn from_file(path: std::path::PathBuf) -> PyResult<Self> {
        Ok(PyLimits::wrap(load::from_file(&path).py()?))
    }

    /// The same symmetric limits on `dof` unnamed joints. Velocity and acceleration are given;
    /// jerk and the position range only when passed (`float('inf')` / `(-inf, inf)` state
    /// "unlimited"); an absent one is refused by operations that need it.
    #[staticmethod]
    #[pyo3(signature = (dof, velocity, acceleration, jerk = None, position = None))]
    fn uniform(
        dof: usize,
        velocity: f64,
        acceleration: f64,
        jerk: Option<f64>,
        position: Option<(f64, f64)>,
    ) -> PyResult<Self> {
        let mut l = PartialLimits::unnamed(dof)
            .py()?
            .with_override(Order::Velocity, &[velocity])
            .py()?
            .with_override(Order::Acceleration, &[acceleration])
            .py()?;
        if let Some(j) = jerk {
            l = l.with_override(Order::Jerk, &[j]).py()?;
        }
        if let Some(r) = position {
            l = l.with_position_range(&[r]).py()?;
        }
        Ok(PyLimits::wrap(l))
    }

    /// Number of joints.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }

    /// Joint names (empty strings for unnamed joints).
    #[getter]
    fn names(&self) -> Vec<String> {
        self.inner.names()
    }

    /// Position ranges, shape `(dof, 2)`; an end not given is NaN.
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self
            .inner
            .joints()
            .iter()
            .zip(self.inner.given())
            .flat_map(|(j, g)| {
                [
                    or_nan(g.position_min, j.position_min),
                    or_nan(g.position_max, j.position_max),
                ]
            })
            .collect();
        array(py, v, &[self.inner.dof(), 2])
    }

    /// Velocity limits, shape `(dof,)` (`inf` = stated unlimited, NaN = not given).
    #[getter]
    fn velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = self.column(|j, g| or_nan(g.velocity, j.velocity));
        array(py, v, &[self.inner.dof()])
    }

    /// Acceleration limits, shape `(dof,)` (`inf` = stated unlimited, NaN = not given).
    #[getter]
    fn acceleration<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = self.column(|j, g| or_nan(g.acceleration, j.acceleration));
        array(py, v, &[self.inner.dof()])
    }

    /// Jerk limits, shape `(dof,)` (`inf` = stated unlimited, NaN = not given).
    #[getter]
    fn jerk<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = self.column(|j, g| or_nan(g.jerk, j.jerk));
        array(py, v, &[self.inner.dof()])
    }

    /// Effort (torque or force) limits, shape `(dof,)`; NaN where the source has none.
    #[getter]
    fn effort<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = self.column(|j, _| j.effort.unwrap_or(f64::NAN));
        array(py, v, &[self.inner.dof()])
    }

    /// The limits no source gave, as `(joint, name, field)` with `field` one of
    /// `'velocity'`, `'acceleration'`, `'jerk'`, `'position range'`, for the fields asked for.
    #[pyo3(signature = (position = true, velocity = true, acceleration = true, jerk = true))]
    fn missing(
        &self,
        position: bool,
        velocity: bool,
        acceleration: bool,
        jerk: bool,
    ) -> Vec<(usize, String, &'static str)> {
        let n = needs(position, velocity, acceleration, jerk);
        self.inner
            .missing(n)
            .into_iter()
            .map(|(j, f)| (j, self.inner.joint(j).name.clone(), f))
            .collect()
    }

    /// Complete limits: every field asked for must have been given (else `TrajkitError`
    /// naming the first joint and field that was not); fields not asked for and absent
    /// become unlimited, stated.
    #[pyo3(signature = (position = true, velocity = true, acceleration = true, jerk = true))]
    fn complete(
        &self,
        position: bool,
        velocity: bool,
        acceleration: bool,
        jerk: bool,
    ) -> PyResult<Self> {
        let l = complete(&self.inner, needs(position, velocity, acceleration, jerk))?;
        Ok(PyLimits::wrap(l.into()))
    }

    /// Absent acceleration and jerk limits filled from `source` (any limits form), joint by
    /// joint by name (`by='name'`) or position (`by='index'`). Velocities and ranges are never
    /// filled.
    #[pyo3(signature = (source, by = "name"))]
    fn fill_from(&self, source: &Bound<'_, PyAny>, by: &str) -> PyResult<Self> {
        let from = limits_of(source)?;
        Ok(PyLimits::wrap(
            self.inner.fill_from(&from, fill_by(by)?).py()?,
        ))
    }

    /// These limits with a MoveIt `joint_limits.yaml` applied on top (joints by name).
    fn with_joint_limits(&self, path: std::path::PathBuf) -> PyResult<Self> {
        let text = trajkit::io::read_text(&path).py()?;
        let l = load::apply_moveit_joint_limits(&self.inner, &text, &path.display().to_string())
            .py()?;
        Ok(PyLimits::wrap(l))
    }

    /// These limits with some fields replaced (one value for every joint or one per joint;
    /// `inf` states "unlimited"): `max_velocity`, `max_acceleration`, `max_jerk`, and
    /// `position_range` (`(lo, hi)` or one pair per joint). Replaced fields count as given.
    #[pyo3(signature = (max_velocity = None, max_acceleration = None, max_jerk = None, position_range = None))]
    fn with_overrides(
        &self,
        max_velocity: Option<Bound<'_, PyAny>>,
        max_acceleration: Option<Bound<'_, PyAny>>,
        max_jerk: Option<Bound<'_, PyAny>>,
        position_range: Option<Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let args = LimitsArgs {
            max_velocity: max_velocity
                .map(|v| floats(&v, "max_velocity", None))
                .transpose()?,
            max_acceleration: max_acceleration
                .map(|v| floats(&v, "max_acceleration", None))
                .transpose()?,
            max_jerk: max_jerk.map(|v| floats(&v, "max_jerk", None)).transpose()?,
            position_range: position_range
                .map(|v| ranges(&v, "position_range"))
                .transpose()?,
            ..LimitsArgs::default()
        };
        Ok(PyLimits::wrap(args.overrides(self.inner.clone())?))
    }

    /// Every given velocity, acceleration and jerk limit multiplied by its scale.
    #[pyo3(signature = (velocity = 1.0, acceleration = 1.0, jerk = 1.0))]
    fn scaled(&self, velocity: f64, acceleration: f64, jerk: f64) -> PyResult<Self> {
        Ok(PyLimits::wrap(
            self.inner.scaled(velocity, acceleration, jerk).py()?,
        ))
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (Vec<Joint>,))> {
        let joints = self
            .inner
            .joints()
            .iter()
            .zip(self.inner.given())
            .map(|(j, g)| {
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
                    [
                        g.position_min,
                        g.position_max,
                        g.velocity,
                        g.acceleration,
                        g.jerk,
                    ],
                )
            })
            .collect();
        let from = py
            .import("trajkit._trajkit")?
            .getattr("_limits_from_joints")?;
        Ok((from, (joints,)))
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner
    }

    fn __repr__(&self) -> String {
        let missing = self.inner.missing(Needs::ALL).len();
        format!(
            "trajkit.Limits(dof={}, names={:?}, missing={missing})",
            self.inner.dof(),
            self.inner.names()
        )
    }
}

/// One joint's limits as pickled: name, `[position_min, position_max, velocity, acceleration,
/// jerk]`, `[min_velocity, min_acceleration, effort]`, what was given (same order as the
/// first array).
type Joint = (String, [f64; 5], [Option<f64>; 3], [bool; 5]);

/// Limits from pickled joints (validated again by `PartialLimits::new`).
#[pyfunction]
fn _limits_from_joints(joints: Vec<Joint>) -> PyResult<PyLimits> {
    let mut given = Vec::with_capacity(joints.len());
    let joints = joints
        .into_iter()
        .map(|(name, a, b, g)| {
            given.push(Given {
                position_min: g[0],
                position_max: g[1],
                velocity: g[2],
                acceleration: g[3],
                jerk: g[4],
            });
            JointLimits {
                name,
                position_min: a[0],
                position_max: a[1],
                velocity: a[2],
                acceleration: a[3],
                jerk: a[4],
                min_velocity: b[0],
                min_acceleration: b[1],
                effort: b[2],
            }
        })
        .collect();
    Ok(PyLimits::wrap(PartialLimits::new(joints, given).py()?))
}

/// Limits from a trajkit limits-file JSON text.
#[pyfunction]
fn limits_from_json(text: &str) -> PyResult<PyLimits> {
    Ok(PyLimits::wrap(load::from_json_str(text, "<dict>").py()?))
}

/// Reads limits from a `Limits`, a preset name or path, or a dict.
pub fn limits_of(obj: &Bound<'_, PyAny>) -> PyResult<PartialLimits> {
    if let Ok(l) = obj.cast::<PyLimits>() {
        return Ok(l.get().inner.clone());
    }
    if let Ok(s) = obj.extract::<String>() {
        return load::from_spec(&s).py();
    }
    if let Ok(p) = obj.extract::<std::path::PathBuf>() {
        return load::from_file(&p).py();
    }
    if obj.is_instance_of::<PyDict>() || obj.is_instance_of::<PyList>() {
        let json = obj.py().import("json")?.getattr("dumps")?.call1((obj,))?;
        let text: String = json.extract()?;
        return load::from_json_str(&text, "<dict>").py();
    }
    Err(bad(format!(
        "limits: expected a trajkit.Limits, a preset name or file path, or a dict; found {}",
        obj.get_type().name()?
    )))
}

/// Complete limits for an operation that needs `needs`; a missing limit is a `TrajkitError`
/// with the library's message (joint, name, field) and the keyword that supplies it.
pub fn complete(l: &PartialLimits, needs: Needs) -> PyResult<Limits> {
    l.complete(needs).map_err(|e| match &e {
        trajkit::Error::MissingLimit { field, .. } => {
            let how = match *field {
                "velocity" => "max_velocity=V, or limits that have it",
                "acceleration" => {
                    "max_acceleration=A, fill_from=PRESET|FILE, or limits that have it"
                }
                "jerk" => {
                    "max_jerk=J (float('inf'): unlimited), fill_from=PRESET|FILE, or limits that have it"
                }
                _ => "position_range=(lo, hi) ((-inf, inf): unbounded), or limits that have it",
            };
            bad(format!("{e}: give {how}"))
        }
        _ => crate::convert::err(e),
    })
}

/// Reads `limits` (any form) and completes it with `needs` (the building blocks that take
/// limits directly: `topp.totg`, `topp.plan_waypoints`, `poly.min_duration`, batches).
pub fn complete_of(obj: &Bound<'_, PyAny>, needs: Needs) -> PyResult<Limits> {
    complete(&limits_of(obj)?, needs)
}

/// The CLI-style limit arguments of `trajkit.plan` (the CLI's `LimitsArgs`), read from Python.
pub struct LimitsArgs {
    /// A MoveIt `joint_limits.yaml` applied on top of the limits.
    pub joint_limits: Option<std::path::PathBuf>,
    /// Limits that fill absent acceleration and jerk limits, and how joints pair.
    pub fill_from: Option<(PartialLimits, String, FillBy)>,
    /// Velocity overrides (one, or one per column).
    pub max_velocity: Option<Vec<f64>>,
    /// Acceleration overrides.
    pub max_acceleration: Option<Vec<f64>>,
    /// Jerk overrides.
    pub max_jerk: Option<Vec<f64>>,
    /// Position ranges (one, or one per column).
    pub position_range: Option<Vec<(f64, f64)>>,
    /// Velocity, acceleration and jerk scales.
    pub scales: (f64, f64, f64),
}

impl Default for LimitsArgs {
    fn default() -> Self {
        LimitsArgs {
            joint_limits: None,
            fill_from: None,
            max_velocity: None,
            max_acceleration: None,
            max_jerk: None,
            position_range: None,
            scales: (1.0, 1.0, 1.0),
        }
    }
}

impl LimitsArgs {
    /// Reads the keyword arguments (`None` = not given).
    #[allow(clippy::type_complexity)]
    pub fn read(
        joint_limits: Option<std::path::PathBuf>,
        fill_from: Option<&Bound<'_, PyAny>>,
        by: &str,
        max_velocity: Option<&Bound<'_, PyAny>>,
        max_acceleration: Option<&Bound<'_, PyAny>>,
        max_jerk: Option<&Bound<'_, PyAny>>,
        position_range: Option<&Bound<'_, PyAny>>,
        scales: (f64, f64, f64),
    ) -> PyResult<Self> {
        let fill_from = match fill_from {
            None => None,
            Some(f) => Some((limits_of(f)?, f.str()?.to_string(), fill_by(by)?)),
        };
        Ok(LimitsArgs {
            joint_limits,
            fill_from,
            max_velocity: max_velocity
                .map(|v| floats(v, "max_velocity", None))
                .transpose()?,
            max_acceleration: max_acceleration
                .map(|v| floats(v, "max_acceleration", None))
                .transpose()?,
            max_jerk: max_jerk.map(|v| floats(v, "max_jerk", None)).transpose()?,
            position_range: position_range
                .map(|v| ranges(v, "position_range"))
                .transpose()?,
            scales,
        })
    }

    fn has_overrides(&self) -> bool {
        self.max_velocity.is_some()
            || self.max_acceleration.is_some()
            || self.max_jerk.is_some()
            || self.position_range.is_some()
    }

    /// The overrides and scales applied to `l`.
    fn overrides(&self, mut l: PartialLimits) -> PyResult<PartialLimits> {
        for (order, v, name) in [
            (Order::Velocity, &self.max_velocity, "max_velocity"),
            (
                Order::Acceleration,
                &self.max_acceleration,
                "max_acceleration",
            ),
            (Order::Jerk, &self.max_jerk, "max_jerk"),
        ] {
            if let Some(v) = v {
                l = l
                    .with_override(order, v)
                    .map_err(|e| bad(format!("{name}: {e}")))?;
            }
        }
        if let Some(r) = &self.position_range {
            l = l
                .with_position_range(r)
                .map_err(|e| bad(format!("position_range: {e}")))?;
        }
        let (sv, sa, sj) = self.scales;
        if (sv, sa, sj) != (1.0, 1.0, 1.0) {
            l = l.scaled(sv, sa, sj).py()?;
        }
        Ok(l)
    }

    /// Limits for data of `dof` joints named `names` (`what`: "waypoint"), as `trajkit plan`
    /// resolves its flags: the source (`limits`, else the overrides alone on unnamed joints,
    /// else an error), the MoveIt file, `fill_from`, pairing with the columns by name or
    /// position, then the overrides (one value, or one per column) and the scales. Returns
    /// the limits in column order and the limit joints left out.
    pub fn resolve(
        &self,
        limits: Option<&Bound<'_, PyAny>>,
        what: &'static str,
        names: Option<&[String]>,
        dof: usize,
    ) -> PyResult<(PartialLimits, Vec<String>)> {
        let mut l = match limits {
            Some(spec) => limits_of(spec)?,
            None if self.has_overrides() => PartialLimits::unnamed(dof).py()?,
            None => {
                return Err(bad(
                    "no limits given: pass limits= (a preset name such as 'panda', a limits file, a MoveIt joint_limits.yaml, a URDF, a dict or a trajkit.Limits) or max_velocity=, max_acceleration=, max_jerk= and position_range=",
                ))
            }
        };
        if let Some(p) = &self.joint_limits {
            let text = trajkit::io::read_text(p).py()?;
            l = load::apply_moveit_joint_limits(&l, &text, &p.display().to_string()).py()?;
        }
        if let Some((from, spec, by)) = &self.fill_from {
            l = l.fill_from(from, *by).map_err(|e| match e {
                trajkit::Error::JointNames { .. } => bad(format!(
                    "fill_from={spec}: {e} (fill_by='index' pairs them by position)"
                )),
                e => bad(format!("fill_from={spec}: {e}")),
            })?;
        }
        let (l, unused) = l.for_joints(what, names).py()?;
        if l.dof() != dof {
            return Err(bad(format!(
                "the limits have {} joints, the {what}s {dof}{}",
                l.dof(),
                if names.is_some() {
                    ""
                } else {
                    " (unnamed columns pair with the limits by position)"
                }
            )));
        }
        Ok((self.overrides(l)?, unused))
    }
}

/// Registers `Limits`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyLimits>()?;
    m.add_function(wrap_pyfunction!(limits_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(_limits_from_joints, m)?)?;
    Ok(())
}
