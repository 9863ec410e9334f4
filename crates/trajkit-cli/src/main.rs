//! `trajkit`: plan, check and inspect robot trajectories from the command line.
//!
//! Exit status: 0 success; 1 a checked trajectory exceeds its limits; 2 bad input (one line on
//! standard error naming the file, line and field; no output file is left behind).

#![forbid(unsafe_code)]

mod cmd;
mod studio;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Robot paths in, trajectories out.
#[derive(Parser)]
#[command(
    name = "trajkit",
    version,
    about = "Robot paths in, trajectories out: time-parameterize waypoints within joint limits, check and plot trajectories.",
    after_help = "Examples:\n  trajkit plan                       # embedded 7-joint Panda path -> trajectory.csv\n  trajkit plan --waypoints path.csv --limits ur5e --plot traj.svg\n  trajkit poly --table               # peak coefficients of cubic/quintic/septic moves\n  trajkit check trajectory.csv --limits panda\n  trajkit spline --points path.csv --curve minimum-jerk --duration 4 --plot s.svg\n  trajkit otg problem.json --plot otg.svg     # state-to-state jerk-limited motion"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Turn waypoints into a trajectory within the robot's limits (the main job).
    Plan(cmd::plan::PlanArgs),
    /// One point-to-point polynomial move, or the table of peak coefficients.
    Poly(cmd::poly::PolyArgs),
    /// Check a sampled trajectory (from any tool) against joint limits.
    Check(cmd::check::CheckArgs),
    /// Learn a dynamic movement primitive from a demonstration; reproduce it with a new start,
    /// goal or duration.
    Dmp(cmd::dmp::DmpArgs),
    /// Learn a probabilistic movement primitive from demonstrations; condition on via points.
    Promp(cmd::promp::PrompArgs),
    /// Learn a kernelized movement primitive from demonstrations; adapt it to via points.
    Kmp(cmd::kmp::KmpArgs),
    /// Fit a curve (cubic, PCHIP, Akima, Catmull-Rom, B-spline, minimum jerk/snap) through
    /// points and sample it with its derivatives.
    Spline(cmd::spline::SplineArgs),
    /// Online generation: time-optimal jerk-limited motion from any state to a target state.
    Otg(cmd::otg::OtgArgs),
    /// The interactive lessons in a browser: a local web server on the library (and its JSON
    /// API).
    Studio(studio::StudioArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            use clap::error::ErrorKind::*;
            if matches!(
                e.kind(),
                DisplayHelp | DisplayVersion | DisplayHelpOnMissingArgumentOrSubcommand
            ) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            // One line: clap's first line, without its usage block.
            let text = e.render().to_string();
            let first = text.lines().next().unwrap_or("invalid arguments");
            eprintln!(
                "trajkit: {} (see 'trajkit --help')",
                first.trim_start_matches("error: ")
            );
            return ExitCode::from(2);
        }
    };
    let result = match &cli.command {
        Command::Plan(a) => cmd::plan::run(a),
        Command::Poly(a) => cmd::poly::run(a),
        Command::Check(a) => cmd::check::run(a),
        Command::Dmp(a) => cmd::dmp::run(a),
        Command::Promp(a) => cmd::promp::run(a),
        Command::Kmp(a) => cmd::kmp::run(a),
        Command::Spline(a) => cmd::spline::run(a),
        Command::Otg(a) => cmd::otg::run(a),
        Command::Studio(a) => studio::run(a),
    };
    match result {
        Ok(code) => ExitCode::from(code),
        Err(e) => {
            eprintln!("trajkit: {e}");
            ExitCode::from(2)
        }
    }
}
