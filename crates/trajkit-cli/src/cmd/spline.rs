//! `trajkit spline`: fit a chosen curve through points, sample values and derivatives.

use super::common::{finite_list, CliError, CliResult, OutputArgs, Outputs};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use trajkit::io::Waypoints;
use trajkit::spline::{
    AkimaSpline, BSpline, CatmullRom, CatmullRomKind, CubicSpline, PchipSpline, PiecewisePolynomial,
};
use trajkit::Path;

/// Which curve to fit.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Curve {
    /// Straight segments between the points (velocity jumps at the points).
    Linear,
    /// Cubic spline, zero second derivative at the ends.
    Natural,
    /// Cubic spline with given end velocities (--start-velocity, --end-velocity; default 0).
    Clamped,
    /// Cubic spline, third derivative continuous at the second and second-to-last points.
    NotAKnot,
    /// Cubic spline, periodic (first point must equal the last).
    Periodic,
    /// Shape-preserving PCHIP (no overshoot between points).
    Pchip,
    /// Akima's original spline.
    Akima,
    /// Modified Akima (makima): no overshoot on flat runs.
    Makima,
    /// Uniform Catmull-Rom (α = 0); the parameter is the knot index.
    CatmullRomUniform,
    /// Centripetal Catmull-Rom (α = ½); the parameter is Σ‖ΔP‖^½.
    CatmullRomCentripetal,
    /// Chordal Catmull-Rom (α = 1); the parameter is the chord length.
    CatmullRomChordal,
    /// Interpolating B-spline of --degree (scipy's make_interp_spline knots).
    Bspline,
    /// Quintic spline with end velocity and acceleration (default rest): minimum jerk.
    MinimumJerk,
    /// Degree-7 spline with end velocity, acceleration and jerk (default rest): minimum snap.
    MinimumSnap,
}

/// Arguments of `trajkit spline`.
#[derive(Args, Debug)]
#[command(
    after_help = "Examples:\n  trajkit spline --points path.csv --curve minimum-jerk --duration 4 --out traj.csv --plot traj.svg\n  trajkit spline --points path.csv --curve pchip --times 0,0.5,2,3 --rate 100\n  trajkit spline --points xy.json --curve catmull-rom-centripetal --format json"
)]
pub struct SplineArgs {
    /// Points: CSV (a row per point, a column per coordinate, optional header) or JSON.
    #[arg(long, value_name = "FILE")]
    pub points: PathBuf,
    /// The curve to fit.
    #[arg(long, value_enum, default_value = "natural")]
    pub curve: Curve,
    /// Parameters (times) of the points, increasing, comma-separated. Default: 0, 1, 2, …
    /// (or spread evenly over --duration). Not used by Catmull-Rom.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        conflicts_with = "duration"
    )]
    pub times: Vec<f64>,
    /// Spread the points evenly over this duration instead of one second apart.
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub duration: Option<f64>,
    /// B-spline degree (--curve bspline).
    #[arg(long, default_value_t = 3)]
    pub degree: usize,
    /// Start velocity (clamped, minimum-jerk, minimum-snap), one per coordinate; default 0.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub start_velocity: Vec<f64>,
    /// End velocity, one per coordinate; default 0.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub end_velocity: Vec<f64>,
    /// Output table: t and the value, first, second and third derivatives of every coordinate
    /// (CSV or JSON by extension; '-' for standard output).
    #[arg(long, short, value_name = "FILE", default_value = "-")]
    pub out: PathBuf,
    #[command(flatten)]
    pub output: OutputArgs,
}

fn or_zero(v: &[f64], dim: usize, flag: &str) -> CliResult<Vec<f64>> {
    finite_list(flag, v)?;
    match v.len() {
        0 => Ok(vec![0.0; dim]),
        n if n == dim => Ok(v.to_vec()),
        n => Err(CliError(format!(
            "--{flag} has {n} values, the points have {dim} coordinates"
        ))),
    }
}

/// The curve's name as given on the command line.
fn curve_name(c: Curve) -> String {
    c.to_possible_value()
        .map(|v| v.get_name().to_string())
        .unwrap_or_default()
}

/// The curve parameters of the `n` points of `src`: `--times`, else spread over
/// `--duration`, else 0, 1, 2, …
fn parameters(a: &SplineArgs, n: usize, src: &str) -> CliResult<Vec<f64>> {
    Ok(if !a.times.is_empty() {
        finite_list("times", &a.times)?;
        if a.times.len() != n {
            return Err(CliError(format!(
                "--times has {} values, {src} has {n} points",
                a.times.len()
            )));
        }
        if let Some(i) = (1..n).find(|&i| a.times[i] <= a.times[i - 1]) {
            return Err(CliError(format!(
                "--times: value {} = {} does not increase",
                i + 1,
                a.times[i]
            )));
        }
        a.times.clone()
    } else if let Some(t) = a.duration {
        if !(t.is_finite() && t > 0.0) {
            return Err(CliError(format!(
                "--duration = {t} is not a positive number"
            )));
        }
        (0..n)
            .map(|i| t * i as f64 / (n.max(2) - 1) as f64)
            .collect()
    } else {
        (0..n).map(|i| i as f64).collect()
    })
}

/// The curve sampled over its own parameter (the times of the points), ends included, with
/// every derivative.
fn sample_curve(curve: &dyn Path, dim: usize, rate: f64) -> CliResult<trajkit::SampleTable> {
    let (s0, s1) = curve.interval();
    // Sample over the curve's own parameter (the times of the points), ends included.
    let mut ts: Vec<f64> = trajkit::sample::sample_times(s1 - s0, rate)?
        .into_iter()
        .map(|t| (s0 + t).min(s1))
        .collect();
    ts.dedup();
    let mut data: [Option<Vec<f64>>; 4] = Default::default();
    for (k, col) in data.iter_mut().enumerate() {
        let mut m = vec![0.0; ts.len() * dim];
        for (i, &t) in ts.iter().enumerate() {
            curve.eval(t, k, &mut m[i * dim..(i + 1) * dim]);
        }
        *col = Some(m);
    }
    Ok(trajkit::SampleTable::new(dim, ts, data)?)
}

/// Runs `trajkit spline`.
pub fn run(a: &SplineArgs) -> CliResult<u8> {
    let w = Waypoints::from_file(&a.points)?;
    let src = a.points.display().to_string();
    let (n, dim) = (w.len(), w.dof());
    let y = w.points();
    let cr = matches!(
        a.curve,
        Curve::CatmullRomUniform | Curve::CatmullRomCentripetal | Curve::CatmullRomChordal
    );
    if cr && (!a.times.is_empty() || a.duration.is_some()) {
        return Err(CliError(
            "--times/--duration do not apply to Catmull-Rom: its parameter comes from the points"
                .into(),
        ));
    }
    let x = parameters(a, n, &src)?;
    let v0 = or_zero(&a.start_velocity, dim, "start-velocity")?;
    let v1 = or_zero(&a.end_velocity, dim, "end-velocity")?;
    let z = vec![0.0; dim];
    let e = |r: trajkit::Error| CliError(format!("{src}: {r}"));
    let curve: Box<dyn Path> = match a.curve {
        Curve::Linear => Box::new(PiecewisePolynomial::linear(&x, y, dim).map_err(e)?),
        Curve::Natural => Box::new(CubicSpline::natural(&x, y, dim).map_err(e)?),
        Curve::Clamped => Box::new(CubicSpline::clamped(&x, y, dim, &v0, &v1).map_err(e)?),
        Curve::NotAKnot => Box::new(CubicSpline::not_a_knot(&x, y, dim).map_err(e)?),
        Curve::Periodic => Box::new(CubicSpline::periodic(&x, y, dim).map_err(e)?),
        Curve::Pchip => Box::new(PchipSpline::new(&x, y, dim).map_err(e)?),
        Curve::Akima => Box::new(AkimaSpline::original(&x, y, dim).map_err(e)?),
        Curve::Makima => Box::new(AkimaSpline::modified(&x, y, dim).map_err(e)?),
        Curve::CatmullRomUniform => {
            Box::new(CatmullRom::new(y, dim, CatmullRomKind::Uniform).map_err(e)?)
        }
        Curve::CatmullRomCentripetal => {
            Box::new(CatmullRom::new(y, dim, CatmullRomKind::Centripetal).map_err(e)?)
        }
        Curve::CatmullRomChordal => {
            Box::new(CatmullRom::new(y, dim, CatmullRomKind::Chordal).map_err(e)?)
        }
        Curve::Bspline => Box::new(BSpline::interpolate(&x, y, dim, a.degree).map_err(e)?),
        Curve::MinimumJerk => {
            Box::new(BSpline::minimum_jerk(&x, y, dim, &v0, &z, &v1, &z).map_err(e)?)
        }
        Curve::MinimumSnap => {
            Box::new(BSpline::minimum_snap(&x, y, dim, [&v0, &z, &z], [&v1, &z, &z]).map_err(e)?)
        }
    };
    let (s0, s1) = curve.interval();
    let table = sample_curve(&*curve, dim, a.output.rate)?;
    let table = table.with_names(w.names().to_vec())?;
    let mut outputs = Outputs::default();
    outputs.add(&a.out, a.output.render(&table, &a.out));
    if let Some(p) = &a.output.plot {
        let opts = trajkit::plot::PlotOptions {
            title: format!("trajkit spline ({}) — {src}", curve_name(a.curve)),
            ..Default::default()
        };
        outputs.add(p, trajkit::plot::svg(&table, None, &opts)?);
    }
    outputs.commit()?;
    eprintln!(
        "{} through {n} points ({dim} coordinates), parameter {s0} .. {s1}, {} samples",
        curve_name(a.curve),
        table.len()
    );
    Ok(0)
}
