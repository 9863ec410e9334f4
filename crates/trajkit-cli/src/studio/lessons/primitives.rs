//! Lesson 6: movement primitives. A DMP learned from one demonstration and replayed towards a
//! new goal (`POST /api/dmp`); a ProMP learned from several demonstrations, its mean and
//! ±2σ band, conditioned on via points (`POST /api/promp`).

use super::{to_rows, uniform_times};
use crate::studio::caps;
use crate::studio::error::{ApiError, ApiResult};
use serde::{Deserialize, Serialize};
use serde_json::json;
use trajkit::primitives::{Demo, Dmp, DmpConfig, ProMp, ProMpConfig, RolloutOptions, ViaPoint};
use trajkit::{Order, Trajectory};

/// One demonstration: sample times (seconds, strictly increasing) and positions (a row per
/// sample).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DemoIn {
    /// Times.
    pub t: Vec<f64>,
    /// Positions, one row per time.
    pub q: Vec<Vec<f64>>,
}

impl DemoIn {
    /// Checks the caps and flattens: (t, q row-major, dof).
    fn flat(&self, field: &str, min: usize) -> ApiResult<(Vec<f64>, Vec<f64>, usize)> {
        let n = caps::count(
            &format!("{field}.t (count)"),
            self.t.len(),
            min,
            caps::MAX_DEMO_SAMPLES,
        )?;
        if self.q.len() != n {
            return Err(ApiError::bad(
                &format!("{field}.q (row count)"),
                json!(self.q.len()),
                format!("differs from the {n} times"),
            ));
        }
        let (q, dof) = caps::rows(&format!("{field}.q"), &self.q, n, n, caps::MAX_JOINTS)?;
        let t = self
            .t
            .iter()
            .enumerate()
            .map(|(k, &v)| caps::finite(&format!("{field}.t[{k}]"), v))
            .collect::<ApiResult<Vec<f64>>>()?;
        Ok((t, q, dof))
    }
}

/// `POST /api/dmp`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DmpRequest {
    /// The demonstration (3 to 5000 samples).
    pub demo: DemoIn,
    /// New goal (default: the demonstration's last position).
    pub goal: Option<Vec<f64>>,
    /// New start (default: the demonstration's first position).
    pub start: Option<Vec<f64>>,
    /// New duration τ in seconds (default: the demonstration's).
    pub duration: Option<f64>,
    /// Basis functions per joint, 1..=200 (default 50).
    #[serde(default = "fifty")]
    pub n_basis: usize,
    /// Samples of each rollout, 2..=5000 (default 201).
    #[serde(default = "super::default_samples")]
    pub samples: usize,
}

fn fifty() -> usize {
    50
}

/// The DMP answer: the rollout with the new goal/start/duration, and the reproduction of the
/// demonstration (rollout with nothing changed), sampled at the same count.
#[derive(Debug, Serialize)]
pub struct DmpResponse {
    /// The goal used.
    pub goal: Vec<f64>,
    /// The start used.
    pub start: Vec<f64>,
    /// The rollout.
    pub rollout: Rollout,
    /// The reproduction of the demonstration.
    pub reproduction: Rollout,
}

/// A sampled rollout.
#[derive(Debug, Serialize)]
pub struct Rollout {
    /// Duration, seconds.
    pub duration: f64,
    /// Times.
    pub t: Vec<f64>,
    /// Positions, a row per time.
    pub q: Vec<Vec<f64>>,
    /// Velocities, a row per time.
    pub qd: Vec<Vec<f64>>,
}

fn vector(field: &str, v: &[f64], dof: usize) -> ApiResult<Vec<f64>> {
    if v.len() != dof {
        return Err(ApiError::bad(
            &format!("{field} (length)"),
            json!(v.len()),
            format!("differs from the demonstration's {dof} joints"),
        ));
    }
    v.iter()
        .enumerate()
        .map(|(j, &x)| caps::finite(&format!("{field}[{j}]"), x))
        .collect()
}

fn rollout(dmp: &Dmp, opts: &RolloutOptions<'_>, samples: usize) -> ApiResult<Rollout> {
    let r = dmp
        .rollout(opts)
        .map_err(|e| ApiError::from_lib("rollout", e))?;
    let times = uniform_times(r.duration(), samples);
    let table =
        trajkit::sample::sample_at(&r, times).map_err(|e| ApiError::from_lib("samples", e))?;
    let dof = table.dof();
    Ok(Rollout {
        duration: r.duration(),
        t: table.times().to_vec(),
        q: to_rows(table.matrix(Order::Position).unwrap_or(&[]), dof),
        qd: to_rows(table.matrix(Order::Velocity).unwrap_or(&[]), dof),
    })
}

/// Answers `POST /api/dmp`.
pub fn dmp(req: DmpRequest) -> ApiResult<DmpResponse> {
    let (t, q, dof) = req.demo.flat("demo", 3)?;
    let samples = caps::count("samples", req.samples, 2, caps::MAX_PLOT_SAMPLES)?;
    let cfg = DmpConfig {
        n_basis: caps::count("n_basis", req.n_basis, 1, caps::MAX_BASIS)?,
        ..Default::default()
    };
    let goal = req
        .goal
        .as_deref()
        .map(|g| vector("goal", g, dof))
        .transpose()?;
    let start = req
        .start
        .as_deref()
        .map(|s| vector("start", s, dof))
        .transpose()?;
    let tau = req
        .duration
        .map(|d| caps::positive("duration", d))
        .transpose()?;
    let model = Dmp::fit(&t, &q, dof, &cfg).map_err(|e| ApiError::from_lib("demo", e))?;
    let opts = RolloutOptions {
        goal: goal.clone(),
        start: start.clone(),
        tau,
        ..Default::default()
    };
    Ok(DmpResponse {
        goal: goal.unwrap_or_else(|| model.goal().to_vec()),
        start: start.unwrap_or_else(|| model.start().to_vec()),
        rollout: rollout(&model, &opts, samples)?,
        reproduction: rollout(&model, &RolloutOptions::default(), samples)?,
    })
}

/// `POST /api/promp`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrompRequest {
    /// The demonstrations (2 to 50, same joint count, 2 to 5000 samples each).
    pub demos: Vec<DemoIn>,
    /// Via points to condition on (default none).
    #[serde(default)]
    pub via: Vec<ViaIn>,
    /// Basis functions per joint, 1..=200 (default 20).
    #[serde(default = "twenty")]
    pub n_basis: usize,
    /// Samples of the mean and band, 2..=5000 (default 201).
    #[serde(default = "super::default_samples")]
    pub samples: usize,
}

fn twenty() -> usize {
    20
}

/// A position via point.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViaIn {
    /// Time, seconds.
    pub t: f64,
    /// Position, one entry per joint.
    pub q: Vec<f64>,
    /// Variance of the via point (0 = pass exactly; default 1e-6).
    #[serde(default = "via_variance")]
    pub variance: f64,
}

fn via_variance() -> f64 {
    1e-6
}

/// The ProMP answer.
#[derive(Debug, Serialize)]
pub struct PrompResponse {
    /// Duration T (mean of the demonstrations').
    pub duration: f64,
    /// Times of the samples.
    pub t: Vec<f64>,
    /// The learned distribution.
    pub prior: Band,
    /// The distribution conditioned on the via points (when any).
    pub posterior: Option<Band>,
}

/// Mean and standard deviation of the position per joint, and the ±2σ band.
#[derive(Debug, Serialize)]
pub struct Band {
    /// `mean[j][k]`: joint j at `t[k]`.
    pub mean: Vec<Vec<f64>>,
    /// Standard deviation, same layout.
    pub std: Vec<Vec<f64>>,
    /// mean − 2σ.
    pub lower: Vec<Vec<f64>>,
    /// mean + 2σ.
    pub upper: Vec<Vec<f64>>,
}

fn band(p: &ProMp, t: &[f64]) -> Band {
    let dof = p.dof();
    let mut out = Band {
        mean: vec![Vec::with_capacity(t.len()); dof],
        std: vec![Vec::with_capacity(t.len()); dof],
        lower: vec![Vec::with_capacity(t.len()); dof],
        upper: vec![Vec::with_capacity(t.len()); dof],
    };
    let (mut m, mut v) = (vec![0.0; dof], vec![0.0; dof]);
    for &tk in t {
        p.eval(tk, Order::Position, &mut m);
        p.variance(tk, Order::Position, &mut v);
        for j in 0..dof {
            let s = v[j].sqrt();
            out.mean[j].push(m[j]);
            out.std[j].push(s);
            out.lower[j].push(m[j] - 2.0 * s);
            out.upper[j].push(m[j] + 2.0 * s);
        }
    }
    out
}

/// Answers `POST /api/promp`.
pub fn promp(req: PrompRequest) -> ApiResult<PrompResponse> {
    caps::count("demos (count)", req.demos.len(), 2, caps::MAX_DEMOS)?;
    caps::count("via (count)", req.via.len(), 0, caps::MAX_VIA_POINTS)?;
    let samples = caps::count("samples", req.samples, 2, caps::MAX_PLOT_SAMPLES)?;
    let cfg = ProMpConfig {
        n_basis: caps::count("n_basis", req.n_basis, 1, caps::MAX_BASIS)?,
        ..Default::default()
    };
    let mut flat = Vec::with_capacity(req.demos.len());
    for (i, d) in req.demos.iter().enumerate() {
        flat.push(d.flat(&format!("demos[{i}]"), 2)?);
    }
    let dof = flat[0].2;
    if let Some(i) = flat.iter().position(|d| d.2 != dof) {
        return Err(ApiError::bad(
            &format!("demos[{i}].q[0] (length)"),
            json!(flat[i].2),
            format!("differs from demos[0]'s {dof} joints"),
        ));
    }
    let demos: Vec<Demo> = flat.iter().map(|(t, q, _)| Demo { t, q }).collect();
    let prior = ProMp::fit(&demos, dof, &cfg).map_err(|e| ApiError::from_lib("demos", e))?;
    let mut via = Vec::with_capacity(req.via.len());
    for (i, v) in req.via.iter().enumerate() {
        let f = format!("via[{i}]");
        let t = caps::finite(&format!("{f}.t"), v.t)?;
        if !(0.0..=prior.duration()).contains(&t) {
            return Err(ApiError::bad(
                &format!("{f}.t"),
                json!(t),
                format!("is outside the primitive's [0, {}] s", prior.duration()),
            ));
        }
        let q = vector(&format!("{f}.q"), &v.q, dof)?;
        let var = caps::finite(&format!("{f}.variance"), v.variance)?;
        if var < 0.0 {
            return Err(ApiError::bad(
                &format!("{f}.variance"),
                json!(var),
                "is negative",
            ));
        }
        via.push(ViaPoint::position(t, &q, var));
    }
    let t = uniform_times(prior.duration(), samples);
    let posterior = if via.is_empty() {
        None
    } else {
        let p = prior
            .condition(&via)
            .map_err(|e| ApiError::from_lib("via", e))?;
        Some(band(&p, &t))
    };
    Ok(PrompResponse {
        duration: prior.duration(),
        prior: band(&prior, &t),
        posterior,
        t,
    })
}
