//! `trajkit otg`: one online-generation problem (Ruckig's field names) → result, duration and
//! samples; or `--batch FILE.jsonl`, one problem per line → one JSON line per problem.

use super::common::{CliError, CliResult, Format, Outputs};
use clap::Args;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use trajkit::otg::json::{parse_problem, OtgProblem};
use trajkit::otg::{
    calculate_dyn, check_waypoints, plan_waypoints, DynInputParameter, DynTrajectory, OtgError,
    WaypointTrajectory, Waypoints,
};
use trajkit::Trajectory;

/// Arguments of `trajkit otg`.
#[derive(Args, Debug)]
#[command(
    after_help = "Input: a JSON object with Ruckig's field names: current_position, current_velocity, current_acceleration, target_position, target_velocity, target_acceleration, max_velocity, max_acceleration, max_jerk, min_velocity, min_acceleration, enabled, minimum_duration, max_position, min_position (position limits, \"inf\"/\"-inf\" for none), interrupt_calculation_duration (calculation budget in microseconds), synchronization (time | time_if_necessary | phase | none | straight_line), control_interface (position | velocity), duration_discretization (continuous | discrete), per_dof_synchronization, per_dof_control_interface, dt. current_position, target_position and the limits max_velocity, max_acceleration, max_jerk are required (write \"inf\" for a DOF without a limit: infinite jerk gives trapezoidal profiles, infinite acceleration first-order ones); states default to zero. An unknown field is an error naming the closest known one; intermediate_positions (waypoints to pass through) with per_section_max_velocity, per_section_max_acceleration, per_section_max_jerk (one list per section, waypoints + 1) and per_section_minimum_duration plan a motion through the waypoints (never longer than stopping at each); Ruckig Pro's fields not supported yet (per_section_min_velocity, per_section_min_acceleration, per_section_max_position, per_section_min_position) are refused by name. --batch exits 1 when any line failed.\n\nExamples:\n  echo '{\"current_position\":[0],\"target_position\":[1],\"max_velocity\":[0.6],\"max_acceleration\":[1],\"max_jerk\":[4]}' | trajkit otg -\n  trajkit otg problem.json --out samples.csv --plot otg.svg\n  trajkit otg --batch problems.jsonl --out results.jsonl"
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
    /// With --batch: add every DOF's profile segments to each result line (for independent
    /// checkers).
    #[arg(long, requires = "batch")]
    pub profiles: bool,
}

fn err(what: impl std::fmt::Display) -> CliError {
    CliError(what.to_string())
}

/// Parses one problem (the library's strict reader); `line` is 0 for a whole file.
fn parse(text: &str, src: &str, line: usize) -> CliResult<OtgProblem> {
    parse_problem(text, src, line).map_err(err)
}

/// A solved problem: the generator's trajectory, or a motion through waypoints.
enum Solved<'a> {
    Plain(DynTrajectory),
    Waypoints(WaypointTrajectory, &'a Waypoints),
}

impl Solved<'_> {
    fn trajectory(&self) -> &dyn Trajectory {
        match self {
            Solved::Plain(t) => t,
            Solved::Waypoints(t, _) => t,
        }
    }
}

fn solve(p: &OtgProblem) -> Result<Solved<'_>, OtgError> {
    Ok(match &p.waypoints {
        None => Solved::Plain(calculate_dyn(&p.input, p.delta_time)?),
        Some(w) => Solved::Waypoints(plan_waypoints(&p.input, w, p.delta_time)?, w),
    })
}

/// One `--batch` result line of a solved problem.
fn solved_record(
    line: usize,
    p: &OtgProblem,
    s: &Solved,
    profiles: bool,
) -> Result<Value, OtgError> {
    let (c, duration) = match s {
        Solved::Plain(tr) => (trajkit::otg::check(&p.input, tr), tr.duration()),
        Solved::Waypoints(tr, w) => (check_waypoints(&p.input, w, tr)?.solution, tr.duration()),
    };
    let e = c.final_error;
    let mut r = json!({
        "line": line,
        "result": "working",
        "duration": duration,
        "final_error": {"position": e[0], "velocity": e[1], "acceleration": e[2]},
        "worst_limit_ratio": c.worst_limit_ratio,
        "position_excess": c.position_excess,
    });
    if let Solved::Waypoints(tr, _) = s {
        r["stop_at_every_waypoint_duration"] = json!(tr.stop_at_every_waypoint_duration());
    }
    if profiles {
        r["profiles"] = match s {
            Solved::Plain(tr) => profiles_json(tr),
            Solved::Waypoints(tr, _) => {
                Value::Array(tr.sections().iter().map(profiles_json).collect())
            }
        };
    }
    Ok(r)
}

fn batch(path: &Path, out: &Path, profiles: bool) -> CliResult<u8> {
    let text = trajkit::io::read_text(path)?;
    let mut lines = String::new();
    let name = path.display().to_string();
    let (mut total, mut failed) = (0usize, 0usize);
    for (k, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        total += 1;
        let record = match parse(line, &name, k + 1) {
            Err(e) => {
                failed += 1;
                json!({"line": k + 1, "result": "invalid_input", "message": e.0})
            }
            Ok(p) => match solve(&p).and_then(|tr| solved_record(k + 1, &p, &tr, profiles)) {
                Err(e) => {
                    failed += 1;
                    error_record(k + 1, &e)
                }
                Ok(r) => r,
            },
        };
        lines.push_str(&record.to_string());
        lines.push('\n');
    }
    let mut outputs = Outputs::default();
    outputs.add(out, lines);
    outputs.commit()?;
    if failed > 0 {
        eprintln!("otg --batch: {failed} of {total} problems failed");
        return Ok(1);
    }
    eprintln!("otg --batch: {total} problems solved");
    Ok(0)
}

fn error_record(line: usize, e: &OtgError) -> Value {
    json!({"line": line, "result": e.name(), "dof": e.dof(), "message": e.to_string()})
}

/// Every DOF's segments: start state and, per segment, `[duration, jerk, v_start, a_start]`
/// (the start values show the jumps of second- and first-order profiles), plus the number of
/// brake segments.
fn profiles_json(tr: &DynTrajectory) -> Value {
    let dofs: Vec<Value> = tr
        .dofs()
        .iter()
        .map(|d| {
            let p = &d.profile;
            let s = p.start();
            let segs: Vec<Value> = (0..p.segments())
                .filter_map(|k| p.segment(k))
                .map(|(_, dur, st, j)| json!([dur, j, st.v, st.a]))
                .collect();
            let e = p.end();
            let brake = (0..p.segments())
                .filter_map(|k| p.segment(k))
                .take_while(|(t0, dur, ..)| t0 + dur <= p.brake_duration())
                .count();
            json!({"p0": s.p, "v0": s.v, "a0": s.a, "segments": segs, "brake_segments": brake,
                   "end": [e.p, e.v, e.a]})
        })
        .collect();
    Value::Array(dofs)
}

/// Runs `trajkit otg`.
pub fn run(a: &OtgArgs) -> CliResult<u8> {
    if let Some(b) = &a.batch {
        return batch(b, &a.out, a.profiles);
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
    let p = parse(&text, &src, 0)?;
    let dt = p.delta_time;
    let solved = solve(&p).map_err(|e: OtgError| err(format!("{src}: {e}")))?;
    let tr = solved.trajectory();
    let count = tr.duration() / dt;
    if count > 1e7 {
        return Err(err(format!(
            "{src}: field 'dt' = {} gives {count:.3e} samples for a {:.6} s trajectory (limit 1e7); use a larger dt or --batch",
            dt,
            tr.duration()
        )));
    }
    let table = trajkit::sample::sample(tr, 1.0 / dt)?;
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
            let mut s = match &solved {
                Solved::Waypoints(t, w) => trajkit::otg::json::answer_waypoints(&p, w, t)?,
                Solved::Plain(t) => trajkit::otg::json::answer(&p, t)?,
            }
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
