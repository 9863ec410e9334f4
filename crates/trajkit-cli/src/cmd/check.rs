//! `trajkit check`: a sampled trajectory (any tool's CSV/JSON) against limits.

use super::common::{CliError, CliResult, LimitsArgs};
use clap::Args;
use std::path::PathBuf;
use trajkit::check::{check_samples, Tolerance};

/// Arguments of `trajkit check`.
#[derive(Args, Debug)]
#[command(
    after_help = "Exit status: 0 within limits, 1 a limit is exceeded beyond the tolerance, 2 bad input.\n\nExamples:\n  trajkit check trajectory.csv                    # against the Panda preset\n  trajkit plan --out - | trajkit check            # standard input\n  trajkit check other_tool.csv --limits robot.urdf --fill-from panda --json"
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
    let limits = a.limits.load()?;
    limits
        .expect_dof(table.dof(), "the trajectory")
        .map_err(|e| {
            let src = if a.file.as_os_str() == "-" {
                "<stdin>".to_string()
            } else {
                a.file.display().to_string()
            };
            CliError(format!("{src}: {e}"))
        })?;
    let report = check_samples(&table, &limits)?;
    let tol = Tolerance {
        ratio: a.tolerance,
        position: a.position_tolerance,
    };
    if a.json {
        let mut v = report.to_json();
        if let Some(o) = v.as_object_mut() {
            o.insert("passes".into(), report.passes(&tol).into());
            o.insert("violations".into(), report.violations(&tol).into());
        }
        println!("{v}");
    } else {
        print!("{}", report.to_text());
        let bad = report.violations(&tol);
        if bad.is_empty() {
            println!(
                "PASS: worst ratio {:.6} (tolerance {})",
                report.worst(),
                a.tolerance
            );
        } else {
            for b in &bad {
                println!("FAIL: {b}");
            }
        }
    }
    Ok(if report.passes(&tol) { 0 } else { 1 })
}
