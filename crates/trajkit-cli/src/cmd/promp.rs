//! `trajkit promp`: learn a ProMP from several demonstrations, condition it on via points,
//! write the mean trajectory and its ±kσ band.

use super::common::{CliError, CliResult};
use super::dmp::{read_demos, DemosArgs, MeanBandArgs};
use clap::Args;
use trajkit::primitives::{Demo, ProMp, ProMpConfig, ViaPoint};
use trajkit::{Order, Trajectory};

/// Arguments of `trajkit promp`.
#[derive(Args, Debug)]
#[command(
    after_help = "Examples:\n  trajkit promp --demo d1.csv --demo d2.csv --demo d3.csv --band band.csv --plot promp.svg\n  trajkit promp --demo d1.csv --demo d2.csv --via 0.5:0.3,-0.2 --via 1.0:0.0,0.1"
)]
pub struct PrompArgs {
    #[command(flatten)]
    pub demos: DemosArgs,
    /// Variance of every via point (0 = pass exactly).
    #[arg(
        long,
        value_name = "V",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    pub via_variance: f64,
    /// Basis functions per joint.
    #[arg(long, value_name = "N", default_value_t = 20)]
    pub basis: usize,
    /// Prior variance added to the weight covariance's diagonal.
    #[arg(
        long,
        value_name = "V",
        default_value_t = 1e-6,
        allow_hyphen_values = true
    )]
    pub prior_variance: f64,
    /// New duration in seconds (default: the mean of the demonstrations').
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub duration: Option<f64>,
    #[command(flatten)]
    pub out: MeanBandArgs,
}

/// Runs `trajkit promp`.
pub fn run(a: &PrompArgs) -> CliResult<u8> {
    if a.demos.demo.len() < 2 {
        return Err(CliError(format!(
            "--demo: {} demonstration given, at least 2 needed",
            a.demos.demo.len()
        )));
    }
    if !(a.via_variance.is_finite() && a.via_variance >= 0.0) {
        return Err(CliError(format!(
            "--via-variance = {} is not a non-negative number",
            a.via_variance
        )));
    }
    let demos = read_demos(&a.demos.demo)?;
    let dof = demos[0].dof;
    let ds: Vec<Demo> = demos.iter().map(|d| Demo { t: &d.t, q: &d.q }).collect();
    let cfg = ProMpConfig {
        n_basis: a.basis,
        prior_variance: a.prior_variance,
        ..Default::default()
    };
    let mut p = ProMp::fit(&ds, dof, &cfg)?;
    if let Some(d) = a.duration {
        p = p.with_duration(d)?;
    }
    let via = a
        .demos
        .vias(dof, |t, q| ViaPoint::position(t, &q, a.via_variance))?;
    let p = p.condition(&via)?;
    let title = format!("trajkit promp — mean of {} demonstrations", demos.len());
    let wrote = a.out.write(&p, &demos[0].names, title, |t, sd| {
        p.variance(t, Order::Position, sd);
        sd.iter_mut().for_each(|v| *v = v.sqrt());
    })?;
    let head = format!(
        "demonstrations: {} ({} joints), duration {:.6} s, {} basis functions per joint",
        demos.len(),
        dof,
        p.duration(),
        p.n_basis()
    );
    let points: Vec<(f64, &[f64])> = via.iter().map(|v| (v.t, &v.value[..])).collect();
    a.out.print_summary(&head, &p, &points, &wrote);
    Ok(0)
}
