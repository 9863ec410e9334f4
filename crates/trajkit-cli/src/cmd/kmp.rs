//! `trajkit kmp`: a KMP from demonstrations (GMM/GMR reference), adapted to via points; writes
//! the mean trajectory and its ±kσ band.

use super::common::{CliError, CliResult};
use super::dmp::{read_demos, DemosArgs, MeanBandArgs};
use clap::Args;
use trajkit::primitives::{Demo, GmmConfig, Kmp, KmpConfig, KmpReference, KmpVia};
use trajkit::{Order, Trajectory};

/// Arguments of `trajkit kmp`.
#[derive(Args, Debug)]
#[command(
    after_help = "Examples:\n  trajkit kmp --demo d1.csv --demo d2.csv --band band.csv --plot kmp.svg\n  trajkit kmp --demo d1.csv --demo d2.csv --via 0.8:0.3,-0.2 --via-variance 1e-6"
)]
pub struct KmpArgs {
    #[command(flatten)]
    pub demos: DemosArgs,
    /// Variance of every via point.
    #[arg(
        long,
        value_name = "V",
        default_value_t = 1e-6,
        allow_hyphen_values = true
    )]
    pub via_variance: f64,
    /// GMM components.
    #[arg(long, value_name = "K", default_value_t = 8)]
    pub components: usize,
    /// Reference points (GMR at equally spaced times).
    #[arg(long, value_name = "N", default_value_t = 100)]
    pub points: usize,
    /// Kernel parameter h of exp(−h (s − s')²), 1/s².
    #[arg(
        long,
        value_name = "H",
        default_value_t = 6.0,
        allow_hyphen_values = true
    )]
    pub kernel_h: f64,
    /// Mean regularization λ.
    #[arg(
        long,
        value_name = "L",
        default_value_t = 1.0,
        allow_hyphen_values = true
    )]
    pub lambda: f64,
    /// Covariance regularization λ_c.
    #[arg(
        long,
        value_name = "L",
        default_value_t = 60.0,
        allow_hyphen_values = true
    )]
    pub lambda_c: f64,
    #[command(flatten)]
    pub out: MeanBandArgs,
}

/// Runs `trajkit kmp`.
pub fn run(a: &KmpArgs) -> CliResult<u8> {
    if !(a.via_variance.is_finite() && a.via_variance > 0.0) {
        return Err(CliError(format!(
            "--via-variance = {} is not a positive number",
            a.via_variance
        )));
    }
    let demos = read_demos(&a.demos.demo)?;
    let dof = demos[0].dof;
    let ds: Vec<Demo> = demos.iter().map(|d| Demo { t: &d.t, q: &d.q }).collect();
    let gmm = GmmConfig {
        components: a.components,
        ..Default::default()
    };
    let reference = KmpReference::from_demos(&ds, dof, &gmm, a.points)?;
    let cfg = KmpConfig {
        kernel_h: a.kernel_h,
        lambda: a.lambda,
        lambda_c: a.lambda_c,
        ..Default::default()
    };
    let mut kmp = Kmp::fit(&reference, &cfg)?;
    let mut cov = vec![0.0; dof * dof];
    for j in 0..dof {
        cov[j * dof + j] = a.via_variance;
    }
    let via = a.demos.vias(dof, |t, mean| KmpVia {
        t,
        mean,
        cov: cov.clone(),
    })?;
    if !via.is_empty() {
        kmp = kmp.with_via_points(&via)?;
    }
    let title = format!("trajkit kmp — mean of {} demonstrations", demos.len());
    let mut c = vec![0.0; dof * dof];
    let wrote = a.out.write(&kmp, &demos[0].names, title, |t, sd| {
        kmp.covariance(t, Order::Position, &mut c);
        for (j, v) in sd.iter_mut().enumerate() {
            *v = c[j * dof + j].max(0.0).sqrt();
        }
    })?;
    let head = format!(
        "demonstrations: {} ({} joints), reference {} points from a {}-component GMM, duration {:.6} s",
        demos.len(),
        dof,
        kmp.reference().t.len(),
        a.components,
        kmp.duration()
    );
    let points: Vec<(f64, &[f64])> = via.iter().map(|v| (v.t, &v.mean[..])).collect();
    a.out.print_summary(&head, &kmp, &points, &wrote);
    Ok(0)
}
