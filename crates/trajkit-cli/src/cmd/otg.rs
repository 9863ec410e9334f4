//! `trajkit otg`: one online-generation problem (Ruckig's field names) → result, duration and
//! samples; or `--batch FILE.jsonl`, one problem per line → one JSON line per problem.

use super::common::{CliError, CliResult, Format, Outputs};
use clap::Args;
use serde_json::{json, Map, Value};
use std::path::{Path, PathBuf};
use trajkit::otg::{
    calculate_dyn, ControlInterface, DurationDiscretization, DynInputParameter, DynTrajectory,
    OtgResult, Synchronization,
};

/// Arguments of `trajkit otg`.
#[derive(Args, Debug)]
#[command(
    after_help = "Input: a JSON object with Ruckig's field names: current_position, current_velocity, current_acceleration, target_position, target_velocity, target_acceleration, max_velocity, max_acceleration, max_jerk, min_velocity, min_acceleration, enabled, minimum_duration, synchronization (time | time_if_necessary | phase | none), control_interface (position | velocity), duration_discretization (continuous | discrete), dt. Only current_position and target_position are required; a missing or null limit means unlimited; unknown fields are ignored.\n\nExamples:\n  echo '{\"current_position\":[0],\"target_position\":[1],\"max_velocity\":[0.6],\"max_acceleration\":[1],\"max_jerk\":[4]}' | trajkit otg -\n  trajkit otg problem.json --out samples.csv --plot otg.svg\n  trajkit otg --batch problems.jsonl --out results.jsonl"
)]
pub struct OtgArgs {
    /// The problem as a JSON file ('-' for standard input).
    #[arg(value_name = "PROBLEM.json", required_unless_present = "batch")]
    pub problem: Option<PathBuf>,
    /// Solve one problem per line of a JSON-lines file instead; prints one JSON line each.
    #[arg(long, value_name = "FILE.jsonl", conflicts_with = "problem")]
    pub batch: Option<PathBuf>,
    /// Output (samples for one problem, result lines for --batch; '-' for standard output).
    #[arg(long, short, value_name = "FILE", default_value = "-")]
    pub out: PathBuf,
    /// Sample table format for one problem (default: from the extension, else JSON).
    #[arg(long, value_enum)]
    pub format: Option<Format>,
    /// Also write an SVG plot of the sampled trajectory with the limits drawn.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

/// A parsed problem and its sample period.
struct Problem {
    input: DynInputParameter,
    dt: f64,
}

fn err(what: impl std::fmt::Display) -> CliError {
    CliError(what.to_string())
}

/// Reads a list of numbers; `null` entries and a missing or null field give `default`.
fn numbers(
    obj: &Map<String, Value>,
    key: &str,
    n: usize,
    default: f64,
    src: &str,
) -> CliResult<Vec<f64>> {
    match obj.get(key) {
        None | Some(Value::Null) => Ok(vec![default; n]),
        Some(Value::Array(a)) => {
            if a.len() != n {
                return Err(err(format!(
                    "{src}: field '{key}' has {} values, current_position has {n}",
                    a.len()
                )));
            }
            a.iter()
                .enumerate()
                .map(|(i, v)| match v {
                    Value::Null => Ok(default),
                    Value::Number(x) => Ok(x.as_f64().unwrap_or(f64::NAN)),
                    other => Err(err(format!(
                        "{src}: field '{key}[{i}]' = {other} is not a number"
                    ))),
                })
                .collect()
        }
        Some(other) => Err(err(format!(
            "{src}: field '{key}' = {other} is not a list of numbers"
        ))),
    }
}

fn word<'a>(obj: &'a Map<String, Value>, key: &str, src: &str) -> CliResult<Option<&'a str>> {
    match obj.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::String(s)) => Ok(Some(s.as_str())),
        Some(other) => Err(err(format!(
            "{src}: field '{key}' = {other} is not a string"
        ))),
    }
}

/// Parses one problem from JSON text; `src` names the file (and line) in messages.
fn parse(text: &str, src: &str) -> CliResult<Problem> {
    let v: Value = serde_json::from_str(text).map_err(|e| err(format!("{src}: {e}")))?;
    let Value::Object(obj) = v else {
        return Err(err(format!("{src}: the problem must be a JSON object")));
    };
    let n = match obj.get("current_position") {
        Some(Value::Array(a)) => a.len(),
        _ => {
            return Err(err(format!(
                "{src}: field 'current_position' (a list of numbers) is required"
            )))
        }
    };
    if n == 0 {
        return Err(err(format!("{src}: field 'current_position' is empty")));
    }
    if !obj.contains_key("target_position") {
        return Err(err(format!("{src}: field 'target_position' is required")));
    }
    let mut input = DynInputParameter::new(n);
    input.current_position = numbers(&obj, "current_position", n, 0.0, src)?;
    input.current_velocity = numbers(&obj, "current_velocity", n, 0.0, src)?;
    input.current_acceleration = numbers(&obj, "current_acceleration", n, 0.0, src)?;
    input.target_position = numbers(&obj, "target_position", n, 0.0, src)?;
    input.target_velocity = numbers(&obj, "target_velocity", n, 0.0, src)?;
    input.target_acceleration = numbers(&obj, "target_acceleration", n, 0.0, src)?;
    input.max_velocity = numbers(&obj, "max_velocity", n, f64::INFINITY, src)?;
    input.max_acceleration = numbers(&obj, "max_acceleration", n, f64::INFINITY, src)?;
    input.max_jerk = numbers(&obj, "max_jerk", n, f64::INFINITY, src)?;
    if obj.get("min_velocity").is_some_and(|v| !v.is_null()) {
        let mut m = numbers(&obj, "min_velocity", n, f64::NAN, src)?;
        for (x, vmax) in m.iter_mut().zip(&input.max_velocity) {
            if x.is_nan() {
                *x = -vmax;
            }
        }
        input.min_velocity = Some(m);
    }
    if obj.get("min_acceleration").is_some_and(|v| !v.is_null()) {
        let mut m = numbers(&obj, "min_acceleration", n, f64::NAN, src)?;
        for (x, amax) in m.iter_mut().zip(&input.max_acceleration) {
            if x.is_nan() {
                *x = -amax;
            }
        }
        input.min_acceleration = Some(m);
    }
    match obj.get("enabled") {
        None | Some(Value::Null) => {}
        Some(Value::Array(a)) if a.len() == n && a.iter().all(Value::is_boolean) => {
            input.enabled = a.iter().map(|b| b.as_bool().unwrap_or(true)).collect();
        }
        Some(other) => {
            return Err(err(format!(
                "{src}: field 'enabled' = {other} is not a list of {n} booleans"
            )))
        }
    }
    match obj.get("minimum_duration") {
        None | Some(Value::Null) => {}
        Some(Value::Number(x)) => input.options.minimum_duration = x.as_f64(),
        Some(other) => {
            return Err(err(format!(
                "{src}: field 'minimum_duration' = {other} is not a number"
            )))
        }
    }
    input.options.synchronization = match word(&obj, "synchronization", src)? {
        None | Some("time") => Synchronization::Time,
        Some("time_if_necessary") => Synchronization::TimeIfNecessary,
        Some("phase") => Synchronization::Phase,
        Some("none") => Synchronization::None,
        Some(w) => {
            return Err(err(format!(
                "{src}: field 'synchronization' = \"{w}\" is not one of time, time_if_necessary, phase, none"
            )))
        }
    };
    input.options.control_interface = match word(&obj, "control_interface", src)? {
        None | Some("position") => ControlInterface::Position,
        Some("velocity") => ControlInterface::Velocity,
        Some(w) => {
            return Err(err(format!(
                "{src}: field 'control_interface' = \"{w}\" is not one of position, velocity"
            )))
        }
    };
    input.options.duration_discretization = match word(&obj, "duration_discretization", src)? {
        None | Some("continuous") => DurationDiscretization::Continuous,
        Some("discrete") => DurationDiscretization::Discrete,
        Some(w) => {
            return Err(err(format!(
            "{src}: field 'duration_discretization' = \"{w}\" is not one of continuous, discrete"
        )))
        }
    };
    let dt = match obj.get("dt") {
        None | Some(Value::Null) => 0.001,
        Some(Value::Number(x)) => x.as_f64().unwrap_or(f64::NAN),
        Some(other) => return Err(err(format!("{src}: field 'dt' = {other} is not a number"))),
    };
    if !(dt.is_finite() && dt > 0.0) {
        return Err(err(format!(
            "{src}: field 'dt' = {dt} is not a positive number"
        )));
    }
    Ok(Problem { input, dt })
}

/// Final-state error (position, velocity, acceleration) and worst limit ratio, checked at every
/// segment boundary and interior velocity extremum after the brake pre-profile.
fn own_check(inp: &DynInputParameter, tr: &DynTrajectory) -> ([f64; 3], f64) {
    let mut e = [0.0f64; 3];
    let mut worst = 0.0f64;
    for (i, d) in tr.dofs().iter().enumerate() {
        if !inp.enabled[i] {
            continue;
        }
        let p = &d.profile;
        let end = p.end();
        if inp.options.control_interface == ControlInterface::Position {
            e[0] = e[0].max((end.p - inp.target_position[i]).abs());
        }
        e[1] = e[1].max((end.v - inp.target_velocity[i]).abs());
        if inp.max_jerk[i].is_finite() {
            e[2] = e[2].max((end.a - inp.target_acceleration[i]).abs());
        }
        let vmax = inp.max_velocity[i];
        let vmin = inp.min_velocity.as_ref().map_or(-vmax, |m| m[i]);
        let amax = inp.max_acceleration[i];
        let amin = inp.min_acceleration.as_ref().map_or(-amax, |m| m[i]);
        let ratio = |x: f64, hi: f64, lo: f64| if x >= 0.0 { x / hi } else { x / lo };
        let tb = p.brake_duration();
        for k in 0..p.segments() {
            let Some((t0, dur, s, j)) = p.segment(k) else {
                break;
            };
            if t0 + dur <= tb {
                continue;
            }
            let mut vs = [s.v, s.v + dur * (s.a + dur * j / 2.0), s.v];
            if j != 0.0 && -s.a / j > 0.0 && -s.a / j < dur {
                let r = -s.a / j;
                vs[2] = s.v + r * (s.a + r * j / 2.0);
            }
            if inp.options.control_interface == ControlInterface::Position {
                for v in vs {
                    worst = worst.max(ratio(v, vmax, vmin));
                }
            }
            if amax.is_finite() {
                for a in [s.a, s.a + dur * j] {
                    worst = worst.max(ratio(a, amax, amin));
                }
            }
        }
    }
    (e, worst)
}

fn batch(path: &Path, out: &Path) -> CliResult<u8> {
    let text = trajkit::io::read_text(path)?;
    let mut lines = String::new();
    let name = path.display().to_string();
    for (k, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let src = format!("{name}:{}", k + 1);
        let record = match parse(line, &src) {
            Err(e) => json!({"line": k + 1, "result": "invalid_input", "message": e.0}),
            Ok(p) => match calculate_dyn(&p.input, p.dt) {
                Err(e) => json!({"line": k + 1, "result": e.name(), "message": e.to_string()}),
                Ok(tr) => {
                    let (e, worst) = own_check(&p.input, &tr);
                    json!({
                        "line": k + 1,
                        "result": "working",
                        "duration": tr.duration(),
                        "final_error": {"position": e[0], "velocity": e[1], "acceleration": e[2]},
                        "worst_limit_ratio": worst,
                    })
                }
            },
        };
        lines.push_str(&record.to_string());
        lines.push('\n');
    }
    let mut outputs = Outputs::default();
    outputs.add(out, lines);
    outputs.commit()?;
    Ok(0)
}

/// Runs `trajkit otg`.
pub fn run(a: &OtgArgs) -> CliResult<u8> {
    if let Some(b) = &a.batch {
        return batch(b, &a.out);
    }
    let path = a.problem.as_deref().unwrap_or(Path::new("-"));
    let (text, src) = if path.as_os_str() == "-" {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut s)
            .map_err(|e| err(format!("<stdin>: {e}")))?;
        (s, "<stdin>".to_string())
    } else {
        (trajkit::io::read_text(path)?, path.display().to_string())
    };
    let p = parse(&text, &src)?;
    let tr = calculate_dyn(&p.input, p.dt).map_err(|e: OtgResult| err(format!("{src}: {e}")))?;
    let count = tr.duration() / p.dt;
    if count > 1e7 {
        return Err(err(format!(
            "{src}: field 'dt' = {} gives {count:.3e} samples for a {:.6} s trajectory (limit 1e7); use a larger dt or --batch",
            p.dt,
            tr.duration()
        )));
    }
    let table = trajkit::sample::sample(&tr, 1.0 / p.dt)?;
    let fmt = a
        .format
        .unwrap_or(if a.out.extension().is_some_and(|e| e == "csv") {
            Format::Csv
        } else {
            Format::Json
        });
    let body = match fmt {
        Format::Csv => trajkit::io::table_to_csv(&table),
        Format::Json => {
            let samples: Value = serde_json::from_str(&trajkit::io::table_to_json(&table))
                .map_err(|e| err(format!("internal: {e}")))?;
            let mut mins = vec![0.0; tr.dof()];
            tr.independent_min_durations(&mut mins);
            let (e, worst) = own_check(&p.input, &tr);
            let mut s = json!({
                "result": "working",
                "duration": tr.duration(),
                "independent_min_durations": mins,
                "final_error": {"position": e[0], "velocity": e[1], "acceleration": e[2]},
                "worst_limit_ratio": worst,
                "samples": samples,
            })
            .to_string();
            s.push('\n');
            s
        }
    };
    let mut outputs = Outputs::default();
    outputs.add(&a.out, body);
    if let Some(plot) = &a.plot {
        let limits = limits_of(&p.input)?;
        let opts = trajkit::plot::PlotOptions {
            title: format!("trajkit otg (T = {:.4} s)", tr.duration()),
            ..Default::default()
        };
        outputs.add(plot, trajkit::plot::svg(&table, Some(&limits), &opts)?);
    }
    outputs.commit()?;
    eprintln!(
        "otg: duration {:.9} s, {} samples",
        tr.duration(),
        table.len()
    );
    Ok(0)
}

/// The problem's limits as trajkit `Limits` (for drawing them on the plot).
fn limits_of(inp: &DynInputParameter) -> CliResult<trajkit::Limits> {
    let joints = (0..inp.dof())
        .map(|i| trajkit::JointLimits {
            velocity: inp.max_velocity[i],
            acceleration: inp.max_acceleration[i],
            jerk: inp.max_jerk[i],
            min_velocity: inp.min_velocity.as_ref().map(|m| m[i]),
            min_acceleration: inp.min_acceleration.as_ref().map(|m| m[i]),
            ..Default::default()
        })
        .collect();
    Ok(trajkit::Limits::new(joints)?)
}
