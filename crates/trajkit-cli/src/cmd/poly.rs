//! `trajkit poly`: one point-to-point polynomial move, or the peak-coefficient table.

use super::common::{complete, finite_list, CliError, CliResult, LimitsArgs, OutputArgs, Outputs};
use super::plan::DegreeArg;
use clap::Args;
use std::path::PathBuf;
use trajkit::limits::Needs;
use trajkit::poly::{
    min_duration, min_duration_rest_to_rest, peak_coefficients, Degree, EndState, PolyMove,
};
use trajkit::Limits;

/// Arguments of `trajkit poly`.
#[derive(Args, Debug)]
#[command(
    after_help = "Examples:\n  trajkit poly --table\n  trajkit poly --from 0,0 --to 1,-0.5 --duration 2 --degree septic --out move.csv\n  trajkit poly --from 0 --to 1 --max-velocity 1 --max-acceleration 2 --max-jerk 20   # shortest T within these limits\n  trajkit poly --from 0,0,0,-1.5,0,1.5,0 --to 1,0.5,0,-1,0,2,0.5 --limits panda --plot move.svg"
)]
pub struct PolyArgs {
    /// Print the peak coefficients of the unit rest-to-rest profiles and exit.
    #[arg(long)]
    pub table: bool,
    /// Start positions, comma-separated (one per joint).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required_unless_present = "table"
    )]
    pub from: Vec<f64>,
    /// End positions.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required_unless_present = "table"
    )]
    pub to: Vec<f64>,
    /// Start velocities (default zero).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub start_velocity: Vec<f64>,
    /// End velocities (default zero).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub end_velocity: Vec<f64>,
    /// Start accelerations (quintic, septic; default zero).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub start_acceleration: Vec<f64>,
    /// End accelerations (quintic, septic; default zero).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub end_acceleration: Vec<f64>,
    /// Start jerks (septic; default zero).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub start_jerk: Vec<f64>,
    /// End jerks (septic; default zero).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub end_jerk: Vec<f64>,
    /// Polynomial degree.
    #[arg(long, value_enum, default_value = "quintic")]
    pub degree: DegreeArg,
    /// Duration in seconds. Without it, the shortest duration within --limits is used.
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub duration: Option<f64>,
    #[command(flatten)]
    pub limits: LimitsArgs,
    /// Output table (CSV or JSON by extension; '-' for standard output).
    #[arg(long, short, value_name = "FILE", default_value = "-")]
    pub out: PathBuf,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// The seed's table, computed.
pub fn table_text() -> String {
    let mut s = String::from("degree    peak|q̇|·T/Δq  peak|q̈|·T²/Δq  peak|q⃛|·T³/Δq\n");
    for d in Degree::ALL {
        let c = peak_coefficients(d);
        s.push_str(&format!(
            "{:<9} {:>12.4} {:>14.4} {:>14.4}\n",
            d.name(),
            c[0],
            c[1],
            c[2]
        ));
    }
    s
}

/// The shortest duration of the move within the limits that `--limits` and its flags give,
/// and those limits.
fn shortest(
    a: &PolyArgs,
    degree: Degree,
    start: &EndState,
    end: &EndState,
) -> CliResult<(f64, Limits)> {
    let resolved = a.limits.resolve("waypoint", None, a.from.len(), None)?;
    let needs = Needs {
        position: false,
        jerk: degree != Degree::Cubic,
        ..Needs::ALL
    };
    let l = complete(&resolved.limits, needs)?;
    if degree == Degree::Cubic {
        if let Some((j, jl)) = l
            .joints()
            .iter()
            .enumerate()
            .find(|(_, jl)| jl.jerk.is_finite())
        {
            return Err(CliError(format!(
                "{}: a cubic move jumps in acceleration at both ends (unbounded jerk) and cannot hold the jerk limit {}; use --degree quintic or septic, or --max-jerk inf",
                trajkit::error::joint_label(j, &jl.name),
                jl.jerk
            )));
        }
    }
    let rest = start
        .qd
        .iter()
        .chain(&start.qdd)
        .chain(&start.qddd)
        .chain(&end.qd)
        .chain(&end.qdd)
        .chain(&end.qddd)
        .all(|&x| x == 0.0);
    let t = if rest {
        if a.to.len() != a.from.len() {
            return Err(CliError(format!(
                "--to has {} values, --from has {}",
                a.to.len(),
                a.from.len()
            )));
        }
        min_duration_rest_to_rest(degree, &a.from, &a.to, &l)?
    } else {
        min_duration(degree, start, end, &l)?
    };
    if t == 0.0 {
        return Err(CliError(
            "--from equals --to and the move is at rest: nothing to do".into(),
        ));
    }
    Ok((t, l))
}

/// Runs `trajkit poly`.
pub fn run(a: &PolyArgs) -> CliResult<u8> {
    if a.table {
        super::common::say(format_args!("{}", table_text()));
        return Ok(0);
    }
    for (flag, v) in [
        ("from", &a.from),
        ("to", &a.to),
        ("start-velocity", &a.start_velocity),
        ("end-velocity", &a.end_velocity),
        ("start-acceleration", &a.start_acceleration),
        ("end-acceleration", &a.end_acceleration),
        ("start-jerk", &a.start_jerk),
        ("end-jerk", &a.end_jerk),
    ] {
        finite_list(flag, v)?;
    }
    let degree: Degree = a.degree.into();
    let start = EndState {
        q: a.from.clone(),
        qd: a.start_velocity.clone(),
        qdd: a.start_acceleration.clone(),
        qddd: a.start_jerk.clone(),
    };
    let end = EndState {
        q: a.to.clone(),
        qd: a.end_velocity.clone(),
        qdd: a.end_acceleration.clone(),
        qddd: a.end_jerk.clone(),
    };
    let (duration, limits) = match a.duration {
        Some(t) => (t, None),
        None => {
            let (t, l) = shortest(a, degree, &start, &end)?;
            (t, Some(l))
        }
    };
    let mv = PolyMove::between(degree, &start, &end, duration)?;
    if let Some(l) = &limits {
        in_range(&mv, l)?;
    }
    let table = trajkit::sample::sample(&mv, a.output.rate)?;
    let mut outputs = Outputs::default();
    outputs.add(&a.out, a.output.render(&table, &a.out));
    if let Some(p) = &a.output.plot {
        let opts = trajkit::plot::PlotOptions {
            title: format!("trajkit poly ({}, T = {duration:.4} s)", degree.name()),
            ..Default::default()
        };
        outputs.add(p, trajkit::plot::svg(&table, limits.as_ref(), &opts)?);
    }
    outputs.commit()?;
    let range_note = match &limits {
        Some(l)
            if l.joints()
                .iter()
                .any(|j| j.position_min.is_infinite() || j.position_max.is_infinite()) =>
        {
            "; position range: not given for every joint (checked where given)"
        }
        _ => "",
    };
    eprintln!(
        "{} move, duration {duration:.6} s, {} samples{range_note}",
        degree.name(),
        table.len()
    );
    Ok(0)
}

/// The move's exact position extrema must lie inside every given position range.
fn in_range(mv: &PolyMove, limits: &Limits) -> CliResult<()> {
    for (j, jl) in limits.joints().iter().enumerate() {
        let (lo, hi) = mv.joint(j).position_range();
        if lo < jl.position_min || hi > jl.position_max {
            let value = if hi > jl.position_max { hi } else { lo };
            return Err(CliError(format!(
                "the move takes {} to {value}, outside its position range [{}, {}] (exact extremum); give other end velocities or a longer --duration",
                trajkit::error::joint_label(j, &jl.name),
                jl.position_min,
                jl.position_max
            )));
        }
    }
    Ok(())
}
