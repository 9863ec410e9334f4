//! `trajkit check`: a sampled trajectory (any tool's CSV/JSON) against limits.

use super::common::{say, CliError, CliResult, LimitsArgs};
use clap::Args;
use std::path::PathBuf;
use trajkit::check::{check_samples, LimitReport, Tolerance};
use trajkit::limits::{Needs, PartialLimits};

/// Arguments of `trajkit check`.
#[derive(Args, Debug)]
#[command(
    after_help = "Exit status: 0 within limits, 1 a limit is exceeded beyond the tolerance, 2 bad input.\nLimits are required (--limits, or the limits themselves); a limit no source gives is not\nchecked and the report says so. Named columns take the limits of their name.\n\nExamples:\n  trajkit check trajectory.csv --limits panda\n  trajkit plan --out - | trajkit check --limits panda      # standard input\n  trajkit check one_joint.csv --max-velocity 0.6           # velocity only (the rest is reported as not checked)\n  trajkit check other_tool.csv --limits robot.urdf --fill-from ur5e --json"
)]
pub struct CheckArgs {
    /// Sampled trajectory: CSV with a 't' column and q1..qn (optionally qd*, qdd*, qddd*), or
    /// trajkit JSON. A CSV with 't' and other columns is read as positions. '-' (the default)
    /// reads standard input, as JSON if it starts with '{' or '[', else as CSV.
    #[arg(value_name = "FILE", default_value = "-")]
    pub file: PathBuf,
    #[command(flatten)]
    pub limits: LimitsArgs,
    /// Relative tolerance on limit ratios (a ratio up to 1 + tol passes).
    #[arg(long, default_value_t = 1e-6, allow_hyphen_values = true)]
    pub tolerance: f64,
    /// Absolute tolerance on position-range excursions (rad or m).
    #[arg(long, default_value_t = 1e-9, allow_hyphen_values = true)]
    pub position_tolerance: f64,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `trajkit check`.
pub fn run(a: &CheckArgs) -> CliResult<u8> {
    for (flag, v) in [
        ("tolerance", a.tolerance),
        ("position-tolerance", a.position_tolerance),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(CliError(format!(
                "--{flag} = {v} is not a finite non-negative number"
            )));
        }
    }
    let table = if a.file.as_os_str() == "-" {
        let mut text = String::new();
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut text)
            .map_err(|e| CliError(format!("<stdin>: {e}")))?;
        if text.trim_start().starts_with(['{', '[']) {
            trajkit::io::table_from_json(&text, "<stdin>")?
        } else {
            trajkit::io::table_from_csv(&text, "<stdin>")?
        }
    } else {
        trajkit::io::table_from_file(&a.file)?
    };
    let src = if a.file.as_os_str() == "-" {
        "<stdin>".to_string()
    } else {
        a.file.display().to_string()
    };
    let named = table.names().iter().all(|n| !n.is_empty());
    let resolved = a
        .limits
        .resolve("table", named.then_some(table.names()), table.dof(), None)
        .map_err(|e| CliError(format!("{src}: {e}")))?;
    let limits = resolved.limits.complete(Needs::NONE)?;
    let report = check_samples(&table, &limits)?;
    let tol = Tolerance {
        ratio: a.tolerance,
        position: a.position_tolerance,
    };
    print_report(a, &report, &tol, &resolved.limits);
    Ok(if report.passes(&tol) { 0 } else { 1 })
}

/// Prints the report (text or JSON) with what could not be checked.
fn print_report(a: &CheckArgs, report: &LimitReport, tol: &Tolerance, limits: &PartialLimits) {
    if a.json {
        let mut v = report.to_json();
        if let Some(o) = v.as_object_mut() {
            o.insert("passes".into(), report.passes(tol).into());
            o.insert("violations".into(), report.violations(tol).into());
            let nc: Vec<serde_json::Value> = limits
                .missing(Needs::ALL)
                .iter()
                .map(|(j, f)| serde_json::json!({"joint": j, "field": f}))
                .collect();
            o.insert("not_checked".into(), nc.into());
        }
        say(format_args!("{v}\n"));
    } else {
        say(format_args!("{}", report.to_text()));
        let not_checked = not_checked(limits);
        if !not_checked.is_empty() {
            say(format_args!(
                "not checked (no limit given): {}\n",
                not_checked.join("; ")
            ));
        }
        let bad = report.violations(tol);
        if bad.is_empty() {
            say(format_args!(
                "PASS: worst ratio {:.6} (tolerance {})\n",
                report.worst(),
                a.tolerance
            ));
        } else {
            for b in &bad {
                say(format_args!("FAIL: {b}\n"));
            }
        }
    }
}

/// "acceleration of joints 1, 2, 3" for every field no source gave, per field.
fn not_checked(l: &PartialLimits) -> Vec<String> {
    let missing = l.missing(Needs::ALL);
    let mut out = Vec::new();
    for field in ["position range", "velocity", "acceleration", "jerk"] {
        let joints: Vec<String> = missing
            .iter()
            .filter(|(_, f)| *f == field)
            .map(|(j, _)| (j + 1).to_string())
            .collect();
        if joints.len() == l.dof() {
            out.push(format!("{field} of every joint"));
        } else if !joints.is_empty() {
            out.push(format!("{field} of joint(s) {}", joints.join(", ")));
        }
    }
    out
}
