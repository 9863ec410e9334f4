//! Ruckig-style JSON problems: the one reader that the CLI (and any other front end: a Python
//! package, an HTTP server) calls.
//!
//! A problem is a JSON object with Ruckig's field names:
//!
//! | field | value | required |
//! |---|---|---|
//! | `current_position` | list of numbers; its length is the number of DOFs | yes |
//! | `target_position` | list | when a DOF uses the position interface |
//! | `current_velocity`, `current_acceleration`, `target_velocity`, `target_acceleration` | lists | no (zeros) |
//! | `max_velocity` | list of numbers ≥ 0 or `"inf"` | when a DOF uses the position interface |
//! | `max_acceleration`, `max_jerk` | lists of numbers ≥ 0 or `"inf"` | yes |
//! | `min_velocity`, `min_acceleration` | lists of numbers ≤ 0 or `"-inf"` | no (negated maxima) |
//! | `enabled` | list of booleans | no (all) |
//! | `synchronization` | `"time"`, `"time_if_necessary"`, `"phase"`, `"none"`, `"straight_line"` | no (`"time"`) |
//! | `control_interface` | `"position"`, `"velocity"` | no (`"position"`) |
//! | `duration_discretization` | `"continuous"`, `"discrete"` | no (`"continuous"`) |
//! | `per_dof_synchronization`, `per_dof_control_interface` | lists of the words above | no |
//! | `minimum_duration` | number ≥ 0 | no |
//! | `max_position`, `min_position` | lists of numbers or `"inf"` / `"-inf"` (Ruckig Pro's position limits) | no (none) |
//! | `interrupt_calculation_duration` | calculation budget in µs, number > 0 (Ruckig Pro's name) | no (none) |
//! | `dt` | the control period, number > 0 | no (0.001) |
//! | `intermediate_positions` | list of waypoints, each a list of numbers (Ruckig Pro's name) | no (none) |
//! | `per_section_max_velocity`, `per_section_max_acceleration`, `per_section_max_jerk` | one list per section (waypoints + 1) of numbers > 0 or `"inf"` | no (the global limits) |
//! | `per_section_minimum_duration` | one number ≥ 0 per section | no |
//!
//! The reader is strict. A limit that is missing is an error, never "unlimited": JSON has no
//! infinity, so an unlimited limit is written as the string `"inf"` (`"-inf"` for the
//! minima), and as in Ruckig an infinite jerk limit selects second-order (trapezoidal)
//! profiles and an infinite acceleration limit first-order ones. An unknown field is an error
//! that names the closest known one (`'max_jerks' is not a known field (did you mean
//! 'max_jerk'?)`), and Ruckig's fields that trajkit does not support yet (Ruckig Pro's
//! per-section minimum velocity and acceleration and per-section position limits) are
//! refused by name. A problem with `intermediate_positions` is planned with
//! [`super::plan_waypoints`] (the answer: [`answer_waypoints`]). Values are checked for type and length here and for range by the
//! generator (which names DOF, field and value).

use super::input::{ControlInterface, DurationDiscretization, DynInputParameter, Synchronization};
use super::waypoints::Waypoints;
use crate::error::{Error, Location};
use serde_json::{Map, Value};

/// A parsed problem: the input, the control period and the waypoints, if any.
#[derive(Debug, Clone, PartialEq)]
pub struct OtgProblem {
    /// The input, with a run-time number of degrees of freedom.
    pub input: DynInputParameter,
    /// The control period in seconds (`dt`; default 0.001).
    pub delta_time: f64,
    /// `intermediate_positions` and the per-section fields, when given (plan with
    /// [`super::plan_waypoints`]).
    pub waypoints: Option<Waypoints>,
}

/// The per-section fields (they need `intermediate_positions`).
pub const SECTION_FIELDS: [&str; 4] = [
    "per_section_max_velocity",
    "per_section_max_acceleration",
    "per_section_max_jerk",
    "per_section_minimum_duration",
];

/// Every field the reader accepts.
pub const KNOWN_FIELDS: [&str; 28] = [
    "current_position",
    "current_velocity",
    "current_acceleration",
    "target_position",
    "target_velocity",
    "target_acceleration",
    "max_velocity",
    "max_acceleration",
    "max_jerk",
    "min_velocity",
    "min_acceleration",
    "enabled",
    "synchronization",
    "control_interface",
    "duration_discretization",
    "per_dof_synchronization",
    "per_dof_control_interface",
    "minimum_duration",
    "max_position",
    "min_position",
    "interrupt_calculation_duration",
    "dt",
    "delta_time",
    "intermediate_positions",
    "per_section_max_velocity",
    "per_section_max_acceleration",
    "per_section_max_jerk",
    "per_section_minimum_duration",
];

/// Ruckig's input fields that trajkit does not support yet (refused by name).
pub const NOT_SUPPORTED_YET: [&str; 4] = [
    "per_section_min_velocity",
    "per_section_min_acceleration",
    "per_section_max_position",
    "per_section_min_position",
];

/// The answer to one solved problem, as `trajkit otg` writes it: `result`, `duration`,
/// `independent_min_durations`, `final_error`, `worst_limit_ratio` and `position_excess`
/// ([`super::check`]), and
/// the `samples` of the trajectory every `delta_time` seconds (the JSON sample table of
/// [`crate::io::table_to_json`]). The caller caps the sample count (duration / `delta_time`).
pub fn answer(problem: &OtgProblem, trajectory: &super::DynTrajectory) -> crate::Result<Value> {
    let table = crate::sample::sample(trajectory, 1.0 / problem.delta_time)?;
    let samples = samples_json(&table)?;
    let mut mins = vec![0.0; trajectory.dof()];
    trajectory.independent_min_durations(&mut mins);
    let c = super::check::check(&problem.input, trajectory);
    Ok(serde_json::json!({
        "result": "working",
        "duration": trajectory.duration(),
        "independent_min_durations": mins,
        "final_error": {"position": c.final_error[0], "velocity": c.final_error[1],
                        "acceleration": c.final_error[2]},
        "worst_limit_ratio": c.worst_limit_ratio,
        "position_excess": c.position_excess,
        "samples": samples,
    }))
}

/// The answer to a problem with waypoints (the same fields as [`answer`], with the checks
/// taken over every section, and `waypoint_error`, `stop_at_every_waypoint_duration`,
/// `section_durations`).
pub fn answer_waypoints(
    problem: &OtgProblem,
    waypoints: &Waypoints,
    trajectory: &super::WaypointTrajectory,
) -> crate::Result<Value> {
    let table = crate::sample::sample(trajectory, 1.0 / problem.delta_time)?;
    let samples = samples_json(&table)?;
    let c = super::check_waypoints(&problem.input, waypoints, trajectory)?;
    let s = &c.solution;
    let durations: Vec<f64> = trajectory.sections().iter().map(|t| t.duration()).collect();
    Ok(serde_json::json!({
        "result": "working",
        "duration": trajectory.duration(),
        "stop_at_every_waypoint_duration": trajectory.stop_at_every_waypoint_duration(),
        "section_durations": durations,
        "final_error": {"position": s.final_error[0], "velocity": s.final_error[1],
                        "acceleration": s.final_error[2]},
        "waypoint_error": c.waypoint_error,
        "worst_limit_ratio": s.worst_limit_ratio,
        "position_excess": s.position_excess,
        "samples": samples,
    }))
}

fn samples_json(table: &crate::sample::SampleTable) -> crate::Result<Value> {
    serde_json::from_str(&crate::io::table_to_json(table)).map_err(|e| Error::Parse {
        location: Location {
            source: "otg answer".into(),
            line: 0,
            field: "samples".into(),
        },
        message: format!("the sampled trajectory is not finite JSON: {e}"),
    })
}

/// Reads one problem from JSON text. `source` and `line` (0 when unknown) name where it came
/// from in error messages.
///
/// ```
/// use trajkit::otg::json::parse_problem;
/// let p = parse_problem(
///     r#"{"current_position":[0],"target_position":[1],
///         "max_velocity":[0.6],"max_acceleration":[1],"max_jerk":["inf"]}"#,
///     "<example>", 0,
/// )?;
/// assert_eq!(p.input.max_jerk, vec![f64::INFINITY]);
/// let e = parse_problem(r#"{"current_position":[0],"target_position":[1],"max_velocity":[1],
///     "max_acceleration":[1],"max_jerks":[1]}"#, "<example>", 0).unwrap_err();
/// assert!(e.to_string().contains("did you mean 'max_jerk'"));
/// # Ok::<(), trajkit::Error>(())
/// ```
pub fn parse_problem(text: &str, source: &str, line: usize) -> crate::Result<OtgProblem> {
    let fail = |field: &str, message: String| Error::Parse {
        location: Location {
            source: source.to_string(),
            line,
            field: field.to_string(),
        },
        message,
    };
    let v: Value = serde_json::from_str(text).map_err(|e| fail("", e.to_string()))?;
    let Value::Object(obj) = v else {
        return Err(fail("", "the problem must be a JSON object".into()));
    };
    Reader {
        obj: &obj,
        fail: &fail,
    }
    .problem()
}

struct Reader<'a> {
    obj: &'a Map<String, Value>,
    fail: &'a dyn Fn(&str, String) -> Error,
}

impl Reader<'_> {
    fn problem(&self) -> crate::Result<OtgProblem> {
        self.known_fields()?;
        let n = self.dof_count()?;
        let mut input = DynInputParameter::new(n);
        self.options(&mut input)?;
        self.states_and_limits(&mut input, n)?;
        match self.obj.get("enabled") {
            None => {}
            Some(Value::Array(a)) if a.len() == n && a.iter().all(Value::is_boolean) => {
                input.enabled = a.iter().map(|b| b.as_bool() == Some(true)).collect();
            }
            Some(other) => {
                return Err((self.fail)(
                    "enabled",
                    format!("= {other} is not a list of {n} booleans"),
                ))
            }
        }
        let delta_time = self.delta_time()?;
        let waypoints = self.waypoints(n)?;
        Ok(OtgProblem {
            input,
            delta_time,
            waypoints,
        })
    }

    /// Every key is known (Ruckig's fields that trajkit does not support are named).
    fn known_fields(&self) -> crate::Result<()> {
        for key in self.obj.keys() {
            if NOT_SUPPORTED_YET.contains(&key.as_str()) {
                return Err((self.fail)(
                    key,
                    "is a Ruckig (Pro) field that trajkit does not support yet".into(),
                ));
            }
            if !KNOWN_FIELDS.contains(&key.as_str()) {
                let hint = match crate::error::closest_name(key, &KNOWN_FIELDS) {
                    Some(near) => format!(" (did you mean '{near}'?)"),
                    None => " (see the field table of `trajkit otg --help`)".into(),
                };
                return Err((self.fail)(key, format!("is not a known field{hint}")));
            }
        }
        Ok(())
    }

    /// The number of DOFs: the length of `current_position`.
    fn dof_count(&self) -> crate::Result<usize> {
        match self.obj.get("current_position") {
            Some(Value::Array(a)) if !a.is_empty() => Ok(a.len()),
            Some(Value::Array(_)) => Err((self.fail)("current_position", "is empty".into())),
            Some(other) => Err((self.fail)(
                "current_position",
                format!("= {other} is not a list of numbers"),
            )),
            None => Err((self.fail)(
                "current_position",
                "is required (a list of numbers, one per DOF)".into(),
            )),
        }
    }

    /// The words (synchronization, interface, discretization, per DOF too), the minimum
    /// duration and the budget.
    fn options(&self, input: &mut DynInputParameter) -> crate::Result<()> {
        let n = input.dof();
        input.options.synchronization = match self.word("synchronization")? {
            None => Synchronization::Time,
            Some(w) => sync_word(w).ok_or_else(|| self.bad_word("synchronization", w, SYNC))?,
        };
        input.options.control_interface = match self.word("control_interface")? {
            None => ControlInterface::Position,
            Some(w) => iface_word(w).ok_or_else(|| self.bad_word("control_interface", w, IFACE))?,
        };
        input.options.duration_discretization = match self.word("duration_discretization")? {
            None | Some("continuous") => DurationDiscretization::Continuous,
            Some("discrete") => DurationDiscretization::Discrete,
            Some(w) => return Err(self.bad_word("duration_discretization", w, DISC)),
        };
        input.per_dof_synchronization =
            self.words("per_dof_synchronization", n, sync_word, SYNC)?;
        input.per_dof_control_interface =
            self.words("per_dof_control_interface", n, iface_word, IFACE)?;
        if let Some(v) = self.obj.get("minimum_duration") {
            input.options.minimum_duration = Some(self.number("minimum_duration", v)?);
        }
        if let Some(v) = self.obj.get("interrupt_calculation_duration") {
            input.options.interrupt_calculation_duration =
                Some(self.positive("interrupt_calculation_duration", v)?);
        }
        Ok(())
    }

    /// Current and target states, velocity, acceleration, jerk and position limits.
    fn states_and_limits(&self, input: &mut DynInputParameter, n: usize) -> crate::Result<()> {
        let position_dofs = match &input.per_dof_control_interface {
            Some(c) => c.contains(&ControlInterface::Position),
            None => input.options.control_interface == ControlInterface::Position,
        };
        input.current_position = self.numbers("current_position", n, Some(0.0), None)?;
        input.current_velocity = self.numbers("current_velocity", n, Some(0.0), None)?;
        input.current_acceleration = self.numbers("current_acceleration", n, Some(0.0), None)?;
        let target_default = (!position_dofs).then_some(0.0);
        input.target_position = self.numbers("target_position", n, target_default, None)?;
        input.target_velocity = self.numbers("target_velocity", n, Some(0.0), None)?;
        input.target_acceleration = self.numbers("target_acceleration", n, Some(0.0), None)?;
        let vel_default = (!position_dofs).then_some(f64::INFINITY);
        input.max_velocity = self.numbers("max_velocity", n, vel_default, Some("inf"))?;
        input.max_acceleration = self.numbers("max_acceleration", n, None, Some("inf"))?;
        input.max_jerk = self.numbers("max_jerk", n, None, Some("inf"))?;
        if self.obj.contains_key("min_velocity") {
            input.min_velocity = Some(self.numbers("min_velocity", n, None, Some("-inf"))?);
        }
        if self.obj.contains_key("min_acceleration") {
            input.min_acceleration =
                Some(self.numbers("min_acceleration", n, None, Some("-inf"))?);
        }
        input.max_position = self.numbers("max_position", n, Some(f64::INFINITY), Some("inf"))?;
        input.min_position =
            self.numbers("min_position", n, Some(f64::NEG_INFINITY), Some("-inf"))?;
        Ok(())
    }

    /// The control period: `dt` or `delta_time` (not both); 0.001 by default.
    fn delta_time(&self) -> crate::Result<f64> {
        match (self.obj.get("dt"), self.obj.get("delta_time")) {
            (Some(_), Some(_)) => Err((self.fail)(
                "delta_time",
                "is given twice (as 'dt' and as 'delta_time')".into(),
            )),
            (Some(v), None) => self.positive("dt", v),
            (None, Some(v)) => self.positive("delta_time", v),
            (None, None) => Ok(0.001),
        }
    }

    /// `intermediate_positions` and the per-section fields; `None` without waypoints (a
    /// per-section field without `intermediate_positions` is an error).
    fn waypoints(&self, n: usize) -> crate::Result<Option<Waypoints>> {
        let Some(v) = self.obj.get("intermediate_positions") else {
            if let Some(k) = SECTION_FIELDS.iter().find(|k| self.obj.contains_key(**k)) {
                return Err((self.fail)(
                    k,
                    "needs intermediate_positions (one entry per section)".into(),
                ));
            }
            return Ok(None);
        };
        let key = "intermediate_positions";
        let rows = self.list(key, v)?;
        let mut w = Waypoints::new(
            rows.iter()
                .enumerate()
                .map(|(k, r)| self.row(&format!("{key}[{k}]"), r, n, None))
                .collect::<crate::Result<_>>()?,
        );
        let limit = |key: &str| -> crate::Result<Option<Vec<Vec<f64>>>> {
            let Some(v) = self.obj.get(key) else {
                return Ok(None);
            };
            self.list(key, v)?
                .iter()
                .enumerate()
                .map(|(k, r)| self.row(&format!("{key}[{k}]"), r, n, Some("inf")))
                .collect::<crate::Result<_>>()
                .map(Some)
        };
        w.per_section_max_velocity = limit("per_section_max_velocity")?;
        w.per_section_max_acceleration = limit("per_section_max_acceleration")?;
        w.per_section_max_jerk = limit("per_section_max_jerk")?;
        if let Some(v) = self.obj.get("per_section_minimum_duration") {
            let key = "per_section_minimum_duration";
            w.per_section_minimum_duration = Some(
                self.list(key, v)?
                    .iter()
                    .enumerate()
                    .map(|(k, x)| self.number(&format!("{key}[{k}]"), x))
                    .collect::<crate::Result<_>>()?,
            );
        }
        Ok(Some(w))
    }

    fn list<'v>(&self, key: &str, v: &'v Value) -> crate::Result<&'v Vec<Value>> {
        match v {
            Value::Array(a) => Ok(a),
            other => Err((self.fail)(key, format!("= {other} is not a list"))),
        }
    }

    /// One list of `n` numbers (a waypoint, a section's limits); `infinite` as in `numbers`.
    fn row(
        &self,
        key: &str,
        v: &Value,
        n: usize,
        infinite: Option<&str>,
    ) -> crate::Result<Vec<f64>> {
        let Value::Array(a) = v else {
            return Err((self.fail)(key, format!("= {v} is not a list of numbers")));
        };
        if a.len() != n {
            return Err((self.fail)(
                key,
                format!(
                    "has {} values, current_position has {n} (one per DOF)",
                    a.len()
                ),
            ));
        }
        a.iter()
            .enumerate()
            .map(|(i, x)| self.value(&format!("{key}[{i}]"), x, infinite))
            .collect()
    }

    /// One number, or the string `infinite` stands for.
    fn value(&self, key: &str, v: &Value, infinite: Option<&str>) -> crate::Result<f64> {
        match (v, infinite) {
            (Value::Number(x), _) => Ok(x.as_f64().unwrap_or(f64::NAN)),
            (Value::String(s), Some(w)) if s == w => Ok(if w.starts_with('-') {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            }),
            (other, Some(w)) => Err((self.fail)(
                key,
                format!("= {other} is not a number (or \"{w}\")"),
            )),
            (other, None) => Err((self.fail)(key, format!("= {other} is not a number"))),
        }
    }

    fn number(&self, key: &str, v: &Value) -> crate::Result<f64> {
        match v {
            Value::Number(x) => x
                .as_f64()
                .ok_or_else(|| (self.fail)(key, format!("= {x} is not a number"))),
            other => Err((self.fail)(key, format!("= {other} is not a number"))),
        }
    }

    fn positive(&self, key: &str, v: &Value) -> crate::Result<f64> {
        let x = self.number(key, v)?;
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err((self.fail)(key, format!("= {x} is not a positive number")))
        }
    }

    /// A list of `n` numbers; `infinite` names the string that stands for the infinite limit
    /// of this field; `default` applies when the field is absent.
    fn numbers(
        &self,
        key: &str,
        n: usize,
        default: Option<f64>,
        infinite: Option<&str>,
    ) -> crate::Result<Vec<f64>> {
        match self.obj.get(key) {
            None => default.map(|d| vec![d; n]).ok_or_else(|| {
                let hint = match infinite {
                    Some(w) => format!(
                        " (a list of {n} numbers; write \"{w}\" for a DOF without this limit)"
                    ),
                    None => format!(" (a list of {n} numbers)"),
                };
                (self.fail)(key, format!("is required{hint}"))
            }),
            Some(v) => self.row(key, v, n, infinite),
        }
    }

    fn word(&self, key: &str) -> crate::Result<Option<&str>> {
        match self.obj.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.as_str())),
            Some(other) => Err((self.fail)(key, format!("= {other} is not a string"))),
        }
    }

    fn words<T>(
        &self,
        key: &str,
        n: usize,
        f: impl Fn(&str) -> Option<T>,
        options: &str,
    ) -> crate::Result<Option<Vec<T>>> {
        let a = match self.obj.get(key) {
            None => return Ok(None),
            Some(Value::Array(a)) if a.len() == n => a,
            Some(other) => {
                return Err((self.fail)(
                    key,
                    format!("= {other} is not a list of {n} strings"),
                ))
            }
        };
        a.iter()
            .enumerate()
            .map(|(i, v)| {
                let key = format!("{key}[{i}]");
                match v {
                    Value::String(w) => f(w).ok_or_else(|| self.bad_word(&key, w, options)),
                    other => Err((self.fail)(&key, format!("= {other} is not a string"))),
                }
            })
            .collect::<crate::Result<Vec<T>>>()
            .map(Some)
    }

    fn bad_word(&self, key: &str, w: &str, options: &str) -> Error {
        (self.fail)(key, format!("= \"{w}\" is not one of {options}"))
    }
}

const SYNC: &str = "time, time_if_necessary, phase, none, straight_line";
const IFACE: &str = "position, velocity";
const DISC: &str = "continuous, discrete";

fn sync_word(w: &str) -> Option<Synchronization> {
    Some(match w {
        "time" => Synchronization::Time,
        "time_if_necessary" => Synchronization::TimeIfNecessary,
        "phase" => Synchronization::Phase,
        "none" => Synchronization::None,
        "straight_line" => Synchronization::StraightLine,
        _ => return None,
    })
}

fn iface_word(w: &str) -> Option<ControlInterface> {
    Some(match w {
        "position" => ControlInterface::Position,
        "velocity" => ControlInterface::Velocity,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: &str = r#""current_position":[0,1],"target_position":[1,2],"max_velocity":[1,1],"max_acceleration":[2,2],"max_jerk":[3,"inf"]"#;

    fn parse(extra: &str) -> crate::Result<OtgProblem> {
        let sep = if extra.is_empty() { "" } else { "," };
        parse_problem(&format!("{{{BASE}{sep}{extra}}}"), "p.json", 3)
    }

    fn message(extra: &str) -> String {
        parse(extra).unwrap_err().to_string()
    }

    #[test]
    fn a_full_problem_is_read() {
        let p = parse(
            r#""current_velocity":[0.1,0],"min_velocity":[-0.5,"-inf"],"enabled":[true,false],
            "synchronization":"phase","per_dof_control_interface":["position","velocity"],
            "minimum_duration":2,"dt":0.01"#,
        )
        .unwrap();
        let i = &p.input;
        assert_eq!(i.max_jerk, vec![3.0, f64::INFINITY]);
        assert_eq!(i.min_velocity, Some(vec![-0.5, f64::NEG_INFINITY]));
        assert_eq!(i.enabled, vec![true, false]);
        assert_eq!(i.options.synchronization, Synchronization::Phase);
        assert_eq!(
            i.per_dof_control_interface,
            Some(vec![ControlInterface::Position, ControlInterface::Velocity])
        );
        assert_eq!(i.options.minimum_duration, Some(2.0));
        assert_eq!(p.delta_time, 0.01);
        assert_eq!(i.current_velocity, vec![0.1, 0.0]);
        // Absent position limits are none; no budget.
        assert_eq!(i.max_position, vec![f64::INFINITY; 2]);
        assert_eq!(i.min_position, vec![f64::NEG_INFINITY; 2]);
        assert_eq!(i.options.interrupt_calculation_duration, None);
        let p = parse(
            r#""max_position":[2,"inf"],"min_position":["-inf",-1],
            "interrupt_calculation_duration":500"#,
        )
        .unwrap();
        assert_eq!(p.input.max_position, vec![2.0, f64::INFINITY]);
        assert_eq!(p.input.min_position, vec![f64::NEG_INFINITY, -1.0]);
        assert_eq!(p.input.options.interrupt_calculation_duration, Some(500.0));
    }

    #[test]
    fn mistakes_are_named_with_field_and_value() {
        assert_eq!(
            message(r#""max_jerks":[1,1]"#),
            "p.json:3 field 'max_jerks': is not a known field (did you mean 'max_jerk'?)"
        );
        assert!(message(r#""per_section_min_velocity":[[-1,-1]]"#)
            .contains("field 'per_section_min_velocity': is a Ruckig (Pro) field"));
        assert!(message(r#""per_section_max_position":[[1,1]]"#).contains("does not support yet"));
        assert!(message(r#""per_section_max_jerk":[[1,1]]"#)
            .contains("field 'per_section_max_jerk': needs intermediate_positions"));
        assert!(message(r#""intermediate_positions":[[0.5]]"#)
            .contains("field 'intermediate_positions[0]': has 1 values"));
        assert!(message(r#""intermediate_positions":[[0.5,"x"]]"#)
            .contains("field 'intermediate_positions[0][1]': = \"x\" is not a number"));
        assert!(message(r#""intermediate_positions":[[0.5,1]],"per_section_max_velocity":[[1,"inf"],[1,"-inf"]]"#)
            .contains("field 'per_section_max_velocity[1][1]': = \"-inf\" is not a number (or \"inf\")"));
        assert!(message(r#""intermediate_positions":{"a":1}"#)
            .contains("field 'intermediate_positions': = {\"a\":1} is not a list"));
        assert!(message(r#""max_position":[1,"-inf"]"#)
            .contains("field 'max_position[1]': = \"-inf\" is not a number (or \"inf\")"));
        assert!(message(r#""interrupt_calculation_duration":-5"#)
            .contains("field 'interrupt_calculation_duration': = -5 is not a positive number"));
        let e = parse_problem(
            r#"{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1]}"#,
            "p.json",
            0,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("field 'max_jerk': is required") && e.contains("\"inf\""),
            "{e}"
        );
        assert!(message(r#""min_velocity":[-1,"inf"]"#)
            .contains("field 'min_velocity[1]': = \"inf\" is not a number (or \"-inf\")"));
        assert!(message(r#""current_velocity":["inf",0]"#).contains("is not a number"));
        assert!(message(r#""synchronization":"Time""#).contains("is not one of time,"));
        assert!(message(r#""per_dof_synchronization":["time","phasee"]"#)
            .contains("'per_dof_synchronization[1]': = \"phasee\""));
        assert!(message(r#""enabled":[true]"#).contains("is not a list of 2 booleans"));
        assert!(message(r#""dt":0"#).contains("'dt': = 0 is not a positive number"));
        assert!(message(r#""target_velocity":[1]"#).contains("has 1 values"));
        // Velocity interface: no target position or velocity limit needed.
        let p = parse_problem(
            r#"{"current_position":[0],"target_velocity":[1],"max_acceleration":[1],"max_jerk":[1],"control_interface":"velocity"}"#,
            "v.json",
            0,
        )
        .unwrap();
        assert_eq!(p.input.max_velocity, vec![f64::INFINITY]);
    }

    #[test]
    fn waypoints_are_read() {
        let p = parse(
            r#""intermediate_positions":[[0.5,1.5],[0.7,1.8]],
            "per_section_max_velocity":[[1,1],[2,"inf"],[1,1]],
            "per_section_max_jerk":[[3,3],[3,3],[4,4]],
            "per_section_minimum_duration":[0,0.5,0]"#,
        )
        .unwrap();
        let w = p.waypoints.unwrap();
        assert_eq!(
            w.intermediate_positions,
            vec![vec![0.5, 1.5], vec![0.7, 1.8]]
        );
        assert_eq!(
            w.per_section_max_velocity.unwrap()[1],
            vec![2.0, f64::INFINITY]
        );
        assert_eq!(w.per_section_max_acceleration, None);
        assert_eq!(w.per_section_max_jerk.unwrap()[2], vec![4.0, 4.0]);
        assert_eq!(w.per_section_minimum_duration, Some(vec![0.0, 0.5, 0.0]));
        assert_eq!(parse("").unwrap().waypoints, None);
    }

    #[test]
    fn closest_field_by_edit_distance() {
        assert!(message(r#""current_positon":[0,0]"#).contains("did you mean 'current_position'"));
        assert!(message(r#""synchronisation":"time""#).contains("did you mean 'synchronization'"));
        assert!(message(r#""colour":"red""#).contains("is not a known field (see the field table"));
    }
}
