//! `trajkit.otg.InputParameter`: the library's `DynInputParameter` and, for motions through
//! intermediate waypoints, its `Waypoints` (Ruckig Pro's field names).

use pyo3::prelude::*;
use pyo3::types::{PyTuple, PyType};
use trajkit::otg::{
    ControlInterface as CI, DurationDiscretization as DD, DynInputParameter, Waypoints,
};

use super::{
    interface_from, interface_to, sync_from, sync_to, PyDiscretization, PyInterface, PySync,
};
use crate::convert::{bad, floats};

/// Ruckig Pro's per-section fields that the library does not support: setting one to anything
/// but `None` raises `TrajkitError` naming it.
const NOT_SUPPORTED: &str = "is a Ruckig (Pro) field that trajkit does not support yet \
     (per-section minimum velocity and acceleration and per-section position limits are \
     refused, never ignored; the global min_velocity, min_acceleration, min_position and \
     max_position apply to every section)";

/// Reads a list of rows (a list of sequences or a 2-D array) of floats.
fn rows(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<Vec<f64>>> {
    let items: Vec<Bound<'_, PyAny>> = obj
        .extract()
        .map_err(|e| bad(format!("{name}: not a list of arrays of numbers ({e})")))?;
    items
        .iter()
        .enumerate()
        .map(|(k, r)| floats(r, &format!("{name}[{k}]"), None))
        .collect()
}

fn optional_rows(obj: Option<Bound<'_, PyAny>>, name: &str) -> PyResult<Option<Vec<Vec<f64>>>> {
    obj.filter(|o| !o.is_none())
        .map(|o| rows(&o, name))
        .transpose()
}

/// Refuses a value for a per-section field the library does not support.
fn refuse(name: &str, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
    match v {
        Some(v) if !v.is_none() => Err(bad(format!("field '{name}': {NOT_SUPPORTED}"))),
        _ => Ok(()),
    }
}
/// Ruckig's `InputParameter(dofs)`: current and target state, limits, options, and Ruckig
/// Pro's intermediate waypoints with per-section limits and minimum durations.
#[pyclass(module = "trajkit.otg", name = "InputParameter", from_py_object)]
#[derive(Clone)]
pub struct PyInput {
    /// The library's input.
    pub inner: DynInputParameter,
    /// Intermediate waypoints and per-section fields (empty: none).
    pub wp: Waypoints,
}

impl PyInput {
    /// A fresh input for `dofs` degrees of freedom.
    pub fn with_dofs(dofs: usize) -> Self {
        PyInput {
            inner: DynInputParameter::new(dofs),
            wp: Waypoints::default(),
        }
    }

    /// The waypoints when this is a motion through waypoints: `intermediate_positions` is not
    /// empty or a per-section field is set (with no waypoint left, one section).
    pub fn waypoints(&self) -> Option<&Waypoints> {
        let w = &self.wp;
        let any = !w.intermediate_positions.is_empty()
            || w.per_section_max_velocity.is_some()
            || w.per_section_max_acceleration.is_some()
            || w.per_section_max_jerk.is_some()
            || w.per_section_minimum_duration.is_some();
        any.then_some(w)
    }
}

#[pymethods]
impl PyInput {
    /// `dofs` degrees of freedom: states zero, limits infinite (set them), all enabled, no
    /// waypoints. `max_number_of_waypoints` (Ruckig Pro's storage hint) is accepted and
    /// unused: trajkit sizes its storage per calculation.
    #[new]
    #[pyo3(signature = (dofs, max_number_of_waypoints = 0))]
    fn new(dofs: usize, max_number_of_waypoints: usize) -> Self {
        let _ = max_number_of_waypoints;
        PyInput::with_dofs(dofs)
    }

    /// Ruckig Pro's `intermediate_positions`: the positions to pass through on the way to the
    /// target, in order (a list of per-DOF lists, or a 2-D array, one row per waypoint).
    #[getter]
    fn intermediate_positions(&self) -> Vec<Vec<f64>> {
        self.wp.intermediate_positions.clone()
    }
    #[setter]
    fn set_intermediate_positions(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.wp.intermediate_positions = if v.is_none() {
            Vec::new()
        } else {
            rows(v, "intermediate_positions")?
        };
        Ok(())
    }

    /// Velocity limit per section (waypoints + 1) and DOF (> 0 or inf), or `None` for
    /// `max_velocity` in every section.
    #[getter]
    fn per_section_max_velocity(&self) -> Option<Vec<Vec<f64>>> {
        self.wp.per_section_max_velocity.clone()
    }
    #[setter]
    fn set_per_section_max_velocity(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        self.wp.per_section_max_velocity = optional_rows(v, "per_section_max_velocity")?;
        Ok(())
    }

    /// Acceleration limit per section and DOF (> 0 or inf), or `None` for `max_acceleration`.
    #[getter]
    fn per_section_max_acceleration(&self) -> Option<Vec<Vec<f64>>> {
        self.wp.per_section_max_acceleration.clone()
    }
    #[setter]
    fn set_per_section_max_acceleration(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        self.wp.per_section_max_acceleration = optional_rows(v, "per_section_max_acceleration")?;
        Ok(())
    }

    /// Jerk limit per section and DOF (> 0 or inf), or `None` for `max_jerk`.
    #[getter]
    fn per_section_max_jerk(&self) -> Option<Vec<Vec<f64>>> {
        self.wp.per_section_max_jerk.clone()
    }
    #[setter]
    fn set_per_section_max_jerk(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        self.wp.per_section_max_jerk = optional_rows(v, "per_section_max_jerk")?;
        Ok(())
    }

    /// Minimum duration per section in seconds (≥ 0), or `None`.
    #[getter]
    fn per_section_minimum_duration(&self) -> Option<Vec<f64>> {
        self.wp.per_section_minimum_duration.clone()
    }
    #[setter]
    fn set_per_section_minimum_duration(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        self.wp.per_section_minimum_duration = v
            .filter(|o| !o.is_none())
            .map(|o| floats(&o, "per_section_minimum_duration", None))
            .transpose()?;
        Ok(())
    }

    /// Ruckig Pro's per-section minimum velocity: not supported (always `None`; setting a
    /// value raises `TrajkitError`).
    #[getter]
    fn per_section_min_velocity(&self) -> Option<Vec<Vec<f64>>> {
        None
    }
    #[setter]
    fn set_per_section_min_velocity(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        refuse("per_section_min_velocity", v)
    }

    /// Ruckig Pro's per-section minimum acceleration: not supported (always `None`; setting
    /// a value raises `TrajkitError`).
    #[getter]
    fn per_section_min_acceleration(&self) -> Option<Vec<Vec<f64>>> {
        None
    }
    #[setter]
    fn set_per_section_min_acceleration(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        refuse("per_section_min_acceleration", v)
    }

    /// Ruckig Pro's per-section position limit: not supported (always `None`; setting a value
    /// raises `TrajkitError`; `max_position` applies to every section).
    #[getter]
    fn per_section_max_position(&self) -> Option<Vec<Vec<f64>>> {
        None
    }
    #[setter]
    fn set_per_section_max_position(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        refuse("per_section_max_position", v)
    }

    /// Ruckig Pro's per-section position limit: not supported (always `None`; setting a value
    /// raises `TrajkitError`; `min_position` applies to every section).
    #[getter]
    fn per_section_min_position(&self) -> Option<Vec<Vec<f64>>> {
        None
    }
    #[setter]
    fn set_per_section_min_position(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        refuse("per_section_min_position", v)
    }

    /// Reads a problem in the JSON format of `trajkit otg` (Ruckig's field names; the same
    /// strict reader and error messages as the command line). `source` names the text in
    /// errors. The control period `dt` of the file, if any, is dropped: `read_problem`
    /// returns it too.
    #[classmethod]
    #[pyo3(signature = (text, source = "<json>"))]
    fn from_json(_cls: &Bound<'_, PyType>, text: &str, source: &str) -> PyResult<Self> {
        Ok(super::json::parse(text, source)?.0)
    }

    /// This input in the JSON format of `trajkit otg` (every field written, infinite limits
    /// as `"inf"` / `"-inf"`, numbers exactly: reading it back gives an equal input), with
    /// `dt` when `delta_time` is given; `indent` spaces per level (None: one line).
    #[pyo3(signature = (delta_time = None, indent = None))]
    fn to_json(&self, delta_time: Option<f64>, indent: Option<usize>) -> PyResult<String> {
        super::json::write(self, delta_time, indent)
    }

    /// Number of degrees of freedom.
    #[getter]
    fn degrees_of_freedom(&self) -> usize {
        self.inner.dof()
    }

    /// `current_position`: a list, one value per DOF.
    #[getter]
    fn current_position(&self) -> Vec<f64> {
        self.inner.current_position.clone()
    }
    #[setter]
    fn set_current_position(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.current_position = floats(v, "current_position", None)?;
        Ok(())
    }

    /// `current_velocity`: a list, one value per DOF.
    #[getter]
    fn current_velocity(&self) -> Vec<f64> {
        self.inner.current_velocity.clone()
    }
    #[setter]
    fn set_current_velocity(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.current_velocity = floats(v, "current_velocity", None)?;
        Ok(())
    }

    /// `current_acceleration`: a list, one value per DOF.
    #[getter]
    fn current_acceleration(&self) -> Vec<f64> {
        self.inner.current_acceleration.clone()
    }
    #[setter]
    fn set_current_acceleration(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.current_acceleration = floats(v, "current_acceleration", None)?;
        Ok(())
    }

    /// `target_position`: a list, one value per DOF.
    #[getter]
    fn target_position(&self) -> Vec<f64> {
        self.inner.target_position.clone()
    }
    #[setter]
    fn set_target_position(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.target_position = floats(v, "target_position", None)?;
        Ok(())
    }

    /// `target_velocity`: a list, one value per DOF.
    #[getter]
    fn target_velocity(&self) -> Vec<f64> {
        self.inner.target_velocity.clone()
    }
    #[setter]
    fn set_target_velocity(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.target_velocity = floats(v, "target_velocity", None)?;
        Ok(())
    }

    /// `target_acceleration`: a list, one value per DOF.
    #[getter]
    fn target_acceleration(&self) -> Vec<f64> {
        self.inner.target_acceleration.clone()
    }
    #[setter]
    fn set_target_acceleration(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.target_acceleration = floats(v, "target_acceleration", None)?;
        Ok(())
    }

    /// `max_velocity`: a list, one value per DOF.
    #[getter]
    fn max_velocity(&self) -> Vec<f64> {
        self.inner.max_velocity.clone()
    }
    #[setter]
    fn set_max_velocity(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.max_velocity = floats(v, "max_velocity", None)?;
        Ok(())
    }

    /// `max_acceleration`: a list, one value per DOF.
    #[getter]
    fn max_acceleration(&self) -> Vec<f64> {
        self.inner.max_acceleration.clone()
    }
    #[setter]
    fn set_max_acceleration(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.max_acceleration = floats(v, "max_acceleration", None)?;
        Ok(())
    }

    /// `max_jerk`: a list, one value per DOF.
    #[getter]
    fn max_jerk(&self) -> Vec<f64> {
        self.inner.max_jerk.clone()
    }
    #[setter]
    fn set_max_jerk(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.max_jerk = floats(v, "max_jerk", None)?;
        Ok(())
    }

    /// Direction-dependent minimum velocity (negative), or `None` for `-max_velocity`.
    #[getter]
    fn min_velocity(&self) -> Option<Vec<f64>> {
        self.inner.min_velocity.clone()
    }
    #[setter]
    fn set_min_velocity(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        self.inner.min_velocity = v.map(|v| floats(&v, "min_velocity", None)).transpose()?;
        Ok(())
    }

    /// Direction-dependent minimum acceleration (negative), or `None` for `-max_acceleration`.
    #[getter]
    fn min_acceleration(&self) -> Option<Vec<f64>> {
        self.inner.min_acceleration.clone()
    }
    #[setter]
    fn set_min_acceleration(&mut self, v: Option<Bound<'_, PyAny>>) -> PyResult<()> {
        self.inner.min_acceleration = v
            .map(|v| floats(&v, "min_acceleration", None))
            .transpose()?;
        Ok(())
    }

    /// Ruckig Pro's `max_position`: the largest position of each DOF along the whole motion
    /// (a list, `inf` = none, the default).
    #[getter]
    fn max_position(&self) -> Vec<f64> {
        self.inner.max_position.clone()
    }
    #[setter]
    fn set_max_position(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.max_position = floats(v, "max_position", None)?;
        Ok(())
    }

    /// Ruckig Pro's `min_position`: the smallest position of each DOF along the whole motion
    /// (a list, `-inf` = none, the default).
    #[getter]
    fn min_position(&self) -> Vec<f64> {
        self.inner.min_position.clone()
    }
    #[setter]
    fn set_min_position(&mut self, v: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.min_position = floats(v, "min_position", None)?;
        Ok(())
    }

    /// Ruckig Pro's calculation budget in microseconds, or `None` (no budget, the default):
    /// when it runs out the calculation returns the shortest valid trajectory found so far,
    /// or raises `RuckigError` with `kind == 'interrupted'` when it has none.
    #[getter]
    fn interrupt_calculation_duration(&self) -> Option<f64> {
        self.inner.options.interrupt_calculation_duration
    }
    #[setter]
    fn set_interrupt_calculation_duration(&mut self, v: Option<f64>) {
        self.inner.options.interrupt_calculation_duration = v;
    }

    /// Which DOFs are planned (a disabled one keeps its current acceleration).
    #[getter]
    fn enabled(&self) -> Vec<bool> {
        self.inner.enabled.clone()
    }
    #[setter]
    fn set_enabled(&mut self, v: Vec<bool>) {
        self.inner.enabled = v;
    }

    /// The trajectory lasts at least this long (seconds), or `None`.
    #[getter]
    fn minimum_duration(&self) -> Option<f64> {
        self.inner.options.minimum_duration
    }
    #[setter]
    fn set_minimum_duration(&mut self, v: Option<f64>) {
        self.inner.options.minimum_duration = v;
    }

    /// Time synchronization of the DOFs.
    #[getter]
    fn synchronization(&self) -> PySync {
        sync_from(self.inner.options.synchronization)
    }
    #[setter]
    fn set_synchronization(&mut self, s: PySync) {
        self.inner.options.synchronization = sync_to(s);
    }

    /// Synchronization per DOF (Ruckig's `per_dof_synchronization`; None: `synchronization`
    /// for all). `StraightLine` is for all DOFs only.
    #[getter]
    fn per_dof_synchronization(&self) -> Option<Vec<PySync>> {
        self.inner
            .per_dof_synchronization
            .as_ref()
            .map(|v| v.iter().map(|&s| sync_from(s)).collect())
    }
    #[setter]
    fn set_per_dof_synchronization(&mut self, v: Option<Vec<PySync>>) {
        self.inner.per_dof_synchronization = v.map(|v| v.into_iter().map(sync_to).collect());
    }

    /// Control interface per DOF (Ruckig's `per_dof_control_interface`; None:
    /// `control_interface` for all).
    #[getter]
    fn per_dof_control_interface(&self) -> Option<Vec<PyInterface>> {
        self.inner
            .per_dof_control_interface
            .as_ref()
            .map(|v| v.iter().map(|&c| interface_from(c)).collect())
    }
    #[setter]
    fn set_per_dof_control_interface(&mut self, v: Option<Vec<PyInterface>>) {
        self.inner.per_dof_control_interface = v.map(|v| v.into_iter().map(interface_to).collect());
    }

    /// Position or velocity control.
    #[getter]
    fn control_interface(&self) -> PyInterface {
        interface_from(self.inner.options.control_interface)
    }
    #[setter]
    fn set_control_interface(&mut self, c: PyInterface) {
        self.inner.options.control_interface = interface_to(c);
    }

    /// Continuous duration, or a multiple of the control period.
    #[getter]
    fn duration_discretization(&self) -> PyDiscretization {
        match self.inner.options.duration_discretization {
            DD::Discrete => PyDiscretization::Discrete,
            _ => PyDiscretization::Continuous,
        }
    }
    #[setter]
    fn set_duration_discretization(&mut self, d: PyDiscretization) {
        self.inner.options.duration_discretization = match d {
            PyDiscretization::Continuous => DD::Continuous,
            PyDiscretization::Discrete => DD::Discrete,
        };
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.inner == other.inner && self.wp == other.wp
    }

    fn __getnewargs__(&self) -> (usize,) {
        (self.inner.dof(),)
    }

    fn __getstate__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let i = &self.inner;
        let o = &i.options;
        (
            (
                i.current_position.clone(),
                i.current_velocity.clone(),
                i.current_acceleration.clone(),
                i.target_position.clone(),
                i.target_velocity.clone(),
                i.target_acceleration.clone(),
            ),
            (
                i.max_velocity.clone(),
                i.max_acceleration.clone(),
                i.max_jerk.clone(),
                i.min_velocity.clone(),
                i.min_acceleration.clone(),
                i.enabled.clone(),
            ),
            (
                o.minimum_duration,
                sync_from(o.synchronization) as i64,
                matches!(o.control_interface, CI::Velocity),
                matches!(o.duration_discretization, DD::Discrete),
            ),
            (
                self.per_dof_synchronization()
                    .map(|v| v.into_iter().map(|s| s as i64).collect::<Vec<_>>()),
                i.per_dof_control_interface.as_ref().map(|v| {
                    v.iter()
                        .map(|c| matches!(c, CI::Velocity))
                        .collect::<Vec<_>>()
                }),
            ),
            (
                i.min_position.clone(),
                i.max_position.clone(),
                o.interrupt_calculation_duration,
            ),
            (
                self.wp.intermediate_positions.clone(),
                self.wp.per_section_max_velocity.clone(),
                self.wp.per_section_max_acceleration.clone(),
                self.wp.per_section_max_jerk.clone(),
                self.wp.per_section_minimum_duration.clone(),
            ),
        )
            .into_pyobject(py)
    }

    fn __setstate__(&mut self, state: &Bound<'_, PyTuple>) -> PyResult<()> {
        type States = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);
        type Limits = (
            Vec<f64>,
            Vec<f64>,
            Vec<f64>,
            Option<Vec<f64>>,
            Option<Vec<f64>>,
            Vec<bool>,
        );
        type PerDof = (Option<Vec<i64>>, Option<Vec<bool>>);
        type Options = (Option<f64>, i64, bool, bool);
        type Pro = (Vec<f64>, Vec<f64>, Option<f64>);
        type Rows = Option<Vec<Vec<f64>>>;
        type Sections = (Vec<Vec<f64>>, Rows, Rows, Rows, Option<Vec<f64>>);
        let (s, l, o, d, pro, w): (States, Limits, Options, PerDof, Pro, Sections) =
            state.extract()?;
        let wp = &mut self.wp;
        (
            wp.intermediate_positions,
            wp.per_section_max_velocity,
            wp.per_section_max_acceleration,
            wp.per_section_max_jerk,
            wp.per_section_minimum_duration,
        ) = w;
        let i = &mut self.inner;
        (
            i.current_position,
            i.current_velocity,
            i.current_acceleration,
            i.target_position,
            i.target_velocity,
            i.target_acceleration,
        ) = s;
        (
            i.max_velocity,
            i.max_acceleration,
            i.max_jerk,
            i.min_velocity,
            i.min_acceleration,
            i.enabled,
        ) = l;
        i.options.minimum_duration = o.0;
        let sync_of = |k: i64| {
            sync_to(match k {
                1 => PySync::TimeIfNecessary,
                2 => PySync::Phase,
                3 => PySync::No,
                4 => PySync::StraightLine,
                _ => PySync::Time,
            })
        };
        let iface_of = |v: bool| if v { CI::Velocity } else { CI::Position };
        i.options.synchronization = sync_of(o.1);
        i.options.control_interface = iface_of(o.2);
        i.options.duration_discretization = if o.3 { DD::Discrete } else { DD::Continuous };
        i.per_dof_synchronization = d.0.map(|v| v.into_iter().map(sync_of).collect());
        i.per_dof_control_interface = d.1.map(|v| v.into_iter().map(iface_of).collect());
        (
            i.min_position,
            i.max_position,
            i.options.interrupt_calculation_duration,
        ) = pro;
        Ok(())
    }

    fn __repr__(&self) -> String {
        let i = &self.inner;
        let mut s = String::new();
        let limits = [
            ("max_velocity", &i.max_velocity),
            ("max_acceleration", &i.max_acceleration),
            ("max_jerk", &i.max_jerk),
            ("min_position", &i.min_position),
            ("max_position", &i.max_position),
        ];
        for (name, v) in super::json::states(i).into_iter().chain(limits) {
            s.push_str(&format!("inp.{name} = {v:?}\n"));
        }
        if !self.wp.intermediate_positions.is_empty() {
            let w = &self.wp.intermediate_positions;
            s.push_str(&format!("inp.intermediate_positions = {w:?}\n"));
        }
        s
    }
}
