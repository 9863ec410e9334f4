//! Rhythmic (periodic) dynamic movement primitive, learned from one period of a demonstration.
//!
//! ```text
//! τ φ̇  = 1                                          (phase angle, 2π per period)
//! τ² ÿ = α_z (β_z (g − y) − τ ẏ) + r · Σ_i ψ_i(φ) w_i / Σ_i ψ_i(φ)
//! ψ_i(φ) = exp(h (cos(φ − c_i) − 1)),  c_i = 2π i / n,  h = 2.5 n
//! ```
//!
//! `g` is the anchor (the demonstration's mean), `r` an amplitude factor (1 = as demonstrated),
//! `τ = T / 2π` for a period `T` in seconds, so velocities are per second. The rollout starts
//! from the demonstration's first position and velocity and can run for any number of periods.
//!
//! # Precision contract
//! Integration as for the discrete [`crate::primitives::Dmp`] (RK4, forcing term evaluated at
//! each stage's time, `steps_per_period` steps, default 2000; quintic Hermite dense output).
//! A smooth periodic demonstration with 50 basis functions is reproduced, period after
//! period, with an RMS error ≤ 1e-3 of its range (tests).

use crate::error::{Error, Result};
use crate::primitives::demo::{check_demo, demo_derivatives};
use crate::primitives::dmp::DmpRollout;
use crate::primitives::ridge::ridge_fit;
use crate::traj::Trajectory;

/// A rhythmic DMP for `dof` joints.
///
/// ```
/// use trajkit::primitives::RhythmicDmp;
/// use trajkit::{Order, Trajectory};
/// // One period (1 s) of a 1-joint oscillation.
/// let t: Vec<f64> = (0..=500).map(|k| k as f64 / 500.0).collect();
/// let q: Vec<f64> = t.iter().map(|s| (std::f64::consts::TAU * s).sin()).collect();
/// let dmp = RhythmicDmp::fit(&t, &q, 1, 50)?;
/// let roll = dmp.rollout(3.0, None, None, None)?; // three periods
/// let mut y = [0.0];
/// roll.eval(2.25, Order::Position, &mut y);
/// assert!((y[0] - 1.0).abs() < 1e-2);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct RhythmicDmp {
    dof: usize,
    n: usize,
    h: f64,
    alpha_z: f64,
    beta_z: f64,
    period: f64,
    anchor: Vec<f64>,
    start: Vec<f64>,
    start_velocity: Vec<f64>,
    weights: Vec<f64>,
}

impl RhythmicDmp {
    /// Learns from one period: times `t` (strictly increasing; the period is `t_last − t_0`)
    /// and positions `q` (row-major `t.len() × dof`), with `n_basis` basis functions per joint
    /// and the defaults `α_z = 25`, `β_z = 6.25`.
    pub fn fit(t: &[f64], q: &[f64], dof: usize, n_basis: usize) -> Result<RhythmicDmp> {
        check_demo(t, q, dof, 3)?;
        crate::primitives::basis::check_basis_count(n_basis)?;
        crate::size::check_memory(
            "demonstration samples × basis functions",
            t.len() as f64 * n_basis as f64,
            8.0,
            "a design-matrix entry",
        )?;
        if n_basis < 2 {
            return Err(Error::DimensionMismatch {
                what: "rhythmic DMP basis function count (at least 2)".into(),
                expected: 2,
                found: n_basis,
            });
        }
        let rows = t.len();
        let period = t[rows - 1] - t[0];
        let tau = period / std::f64::consts::TAU;
        let ts: Vec<f64> = t.iter().map(|v| v - t[0]).collect();
        let (az, bz) = (25.0, 6.25);
        let (vel, acc) = demo_derivatives(&ts, q, dof);
        let anchor: Vec<f64> = (0..dof)
            .map(|j| (0..rows - 1).map(|k| q[k * dof + j]).sum::<f64>() / (rows - 1) as f64)
            .collect();
        let mut me = RhythmicDmp {
            dof,
            n: n_basis,
            h: 2.5 * n_basis as f64,
            alpha_z: az,
            beta_z: bz,
            period,
            anchor: anchor.clone(),
            start: q[..dof].to_vec(),
            start_velocity: vel[..dof].to_vec(),
            weights: vec![],
        };
        let mut phi = vec![0.0; rows * n_basis];
        let mut targets = vec![0.0; rows * dof];
        for k in 0..rows {
            me.activations(ts[k] / tau, &mut phi[k * n_basis..(k + 1) * n_basis]);
            for j in 0..dof {
                let (y, v, a) = (q[k * dof + j], vel[k * dof + j], acc[k * dof + j]);
                targets[k * dof + j] = tau * tau * a - az * (bz * (anchor[j] - y) - tau * v);
            }
        }
        me.weights = ridge_fit(&phi, rows, n_basis, &targets, dof, 1e-10, true)?;
        Ok(me)
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }
    /// Demonstrated period in seconds.
    pub fn period(&self) -> f64 {
        self.period
    }
    /// Anchor (the demonstration's mean position).
    pub fn anchor(&self) -> &[f64] {
        &self.anchor
    }
    /// Weights, row-major `dof × n_basis`.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    fn activations(&self, phase: f64, out: &mut [f64]) {
        let mut s = 0.0;
        for i in 0..self.n {
            let c = std::f64::consts::TAU * i as f64 / self.n as f64;
            let p = (self.h * ((phase - c).cos() - 1.0)).exp();
            out[i] = p;
            s += p;
        }
        out.iter_mut().for_each(|v| *v /= s);
    }

    fn forcing(&self, phase: f64, r: f64, buf: &mut [f64], out: &mut [f64]) {
        self.activations(phase, buf);
        for j in 0..self.dof {
            out[j] = r * crate::linalg::dot(buf, &self.weights[j * self.n..(j + 1) * self.n]);
        }
    }

    /// Integrates for `duration` seconds. Optional new `period` (seconds), `anchor` (one value
    /// per joint) and `amplitude` factor `r` (default 1).
    pub fn rollout(
        &self,
        duration: f64,
        period: Option<f64>,
        anchor: Option<&[f64]>,
        amplitude: Option<f64>,
    ) -> Result<DmpRollout> {
        crate::error::positive(|| "duration".into(), duration)?;
        let period = match period {
            Some(p) => crate::error::positive(|| "period".into(), p)?,
            None => self.period,
        };
        let r = match amplitude {
            Some(a) => crate::error::finite(|| "amplitude".into(), a)?,
            None => 1.0,
        };
        let dof = self.dof;
        let g = self.anchor_or(anchor)?;
        let tau = period / std::f64::consts::TAU;
        let steps_per_period = 2000usize;
        let h = period / steps_per_period as f64;
        // Round near-integers down so the last step is never a sliver of roundoff size.
        let nsteps = ((duration / h - 1e-9).ceil() as usize).max(1);
        if nsteps > 100_000_000 {
            return Err(Error::InvalidValue {
                field: "duration".into(),
                value: duration,
                reason: "needs more than 1e8 integration steps",
            });
        }
        let sys = Transformation {
            az: self.alpha_z,
            bz: self.beta_z,
            tau,
            g: &g,
        };
        // The start keeps its offset from the anchor and scales with the amplitude.
        let mut y: Vec<f64> = (0..dof)
            .map(|j| g[j] + r * (self.start[j] - self.anchor[j]))
            .collect();
        let mut v: Vec<f64> = (0..dof)
            .map(|j| r * self.start_velocity[j] * self.period / period)
            .collect();
        let mut buf = vec![0.0; self.n];
        let (mut f0, mut fm, mut f1) = (vec![0.0; dof], vec![0.0; dof], vec![0.0; dof]);
        let mut a = vec![0.0; dof];
        let (mut ts, mut ys, mut vs, mut as_) = (
            Vec::with_capacity(nsteps + 1),
            Vec::with_capacity((nsteps + 1) * dof),
            Vec::with_capacity((nsteps + 1) * dof),
            Vec::with_capacity((nsteps + 1) * dof),
        );
        self.forcing(0.0, r, &mut buf, &mut f0);
        let mut t = 0.0;
        let mut stages = Stages::new(dof);
        for step in 0..=nsteps {
            sys.acc(&y, &v, &f0, &mut a);
            ts.push(t);
            ys.extend_from_slice(&y);
            vs.extend_from_slice(&v);
            as_.extend_from_slice(&a);
            if step == nsteps {
                break;
            }
            let t_end = if step + 1 == nsteps {
                duration
            } else {
                (step + 1) as f64 * h
            };
            let hs = t_end - t;
            self.forcing((t + 0.5 * hs) / tau, r, &mut buf, &mut fm);
            self.forcing(t_end / tau, r, &mut buf, &mut f1);
            sys.rk4_step(&mut y, &mut v, &a, [&fm, &f1], hs, &mut stages);
            std::mem::swap(&mut f0, &mut f1);
            t = t_end;
        }
        let roll = DmpRollout::from_states(dof, ts, ys, vs, as_);
        debug_assert!(roll.duration() > 0.0);
        Ok(roll)
    }

    /// The given anchor (checked: one finite value per joint), or the demonstrated one.
    fn anchor_or(&self, anchor: Option<&[f64]>) -> Result<Vec<f64>> {
        let Some(a) = anchor else {
            return Ok(self.anchor.clone());
        };
        if a.len() != self.dof {
            return Err(Error::DimensionMismatch {
                what: "anchor joint count".into(),
                expected: self.dof,
                found: a.len(),
            });
        }
        for (j, &v) in a.iter().enumerate() {
            crate::error::finite(|| format!("anchor of joint {}", j + 1), v)?;
        }
        Ok(a.to_vec())
    }
}

/// The transformation system `τ² ÿ = α_z (β_z (g − y) − τ ẏ) + f` around the anchor `g`.
struct Transformation<'a> {
    az: f64,
    bz: f64,
    tau: f64,
    g: &'a [f64],
}

/// RK4 stage derivatives `(ẏ, ÿ)` and the stage state.
struct Stages {
    k: [(Vec<f64>, Vec<f64>); 4],
    tmp: (Vec<f64>, Vec<f64>),
}

impl Stages {
    fn new(dof: usize) -> Stages {
        let pair = || (vec![0.0; dof], vec![0.0; dof]);
        Stages {
            k: [pair(), pair(), pair(), pair()],
            tmp: pair(),
        }
    }
}

impl Transformation<'_> {
    /// `ÿ` for position `y`, velocity `v` and forcing `f`.
    fn acc(&self, y: &[f64], v: &[f64], f: &[f64], out: &mut [f64]) {
        let (az, bz, tau, g) = (self.az, self.bz, self.tau, self.g);
        for j in 0..g.len() {
            out[j] = (az * (bz * (g[j] - y[j]) - tau * v[j]) + f[j]) / (tau * tau);
        }
    }

    /// One classical RK4 step of length `hs` from `(y, v)` with acceleration `a` there, the
    /// forcing at the step's midpoint and end in `f`.
    fn rk4_step(
        &self,
        y: &mut [f64],
        v: &mut [f64],
        a: &[f64],
        f: [&[f64]; 2],
        hs: f64,
        st: &mut Stages,
    ) {
        let dof = y.len();
        let (k, tmp) = (&mut st.k, &mut st.tmp);
        k[0].0.copy_from_slice(v);
        k[0].1.copy_from_slice(a);
        // Stages 2 to 4: from the start along the previous stage, to the midpoint twice,
        // then to the end.
        for stage in 1..4 {
            let c = if stage == 3 { hs } else { 0.5 * hs };
            let (prev, rest) = k.split_at_mut(stage);
            let p = &prev[stage - 1];
            for j in 0..dof {
                tmp.0[j] = y[j] + c * p.0[j];
                tmp.1[j] = v[j] + c * p.1[j];
            }
            let cur = &mut rest[0];
            cur.0.copy_from_slice(&tmp.1);
            self.acc(&tmp.0, &tmp.1, f[usize::from(stage == 3)], &mut cur.1);
        }
        for j in 0..dof {
            y[j] += hs / 6.0 * (k[0].0[j] + 2.0 * k[1].0[j] + 2.0 * k[2].0[j] + k[3].0[j]);
            v[j] += hs / 6.0 * (k[0].1[j] + 2.0 * k[1].1[j] + 2.0 * k[2].1[j] + k[3].1[j]);
        }
    }
}
