//! Integration of a DMP: the inputs checked once ([`Setup`]), then the exponential integrator
//! ([`super::exact`]) when nothing couples the joints, else classical RK4 ([`Rk4`]) with the
//! forcing term at each stage's own time.

use super::exact::EXP_NODES;
use super::options::{Coupling, GoalChange, PhaseStop, RolloutOptions};
use super::{check_vec, Dmp, DmpRollout, ForcingScaling};
use crate::error::{Error, Result};

/// The checked inputs of a rollout: start, start velocity, goal, τ, duration, step, goal
/// changes in time order and the per-joint forcing scale.
pub(super) struct Setup {
    pub(super) y0: Vec<f64>,
    pub(super) v0: Vec<f64>,
    pub(super) g0: Vec<f64>,
    pub(super) tau: f64,
    pub(super) duration: f64,
    /// The step `τ / steps_per_tau`; the last step ends at `duration` (it may be shorter).
    pub(super) h: f64,
    pub(super) nsteps: usize,
    pub(super) changes: Vec<GoalChange>,
    /// Per-joint forcing scale: 1 (Hoffmann), `g − y₀` (Ijspeert; 1 for a joint learned
    /// unscaled).
    pub(super) scale: Vec<f64>,
}

impl Dmp {
    /// Integrates the DMP (see the module's precision contract) and returns the rollout as a
    /// [`Trajectory`](crate::Trajectory).
    pub fn rollout(&self, opts: &RolloutOptions<'_>) -> Result<DmpRollout> {
        let setup = self.setup(opts)?;
        // Uncoupled and unfiltered: the exact exponential integrator.
        if opts.coupling.is_none()
            && opts.phase_stop.is_none()
            && opts.goal_filter.is_none()
            && setup.nsteps >= EXP_NODES
        {
            return Ok(self.rollout_exact(&setup));
        }
        self.rollout_rk4(opts, setup)
    }

    /// Checks the rollout options against this DMP and sizes the integration grid.
    fn setup(&self, opts: &RolloutOptions<'_>) -> Result<Setup> {
        let dof = self.dof;
        let y0 = opts.start.clone().unwrap_or_else(|| self.start.clone());
        check_vec("start", &y0, dof)?;
        let v0 = opts
            .start_velocity
            .clone()
            .unwrap_or_else(|| self.start_velocity.clone());
        check_vec("start velocity", &v0, dof)?;
        let g0 = opts.goal.clone().unwrap_or_else(|| self.goal.clone());
        check_vec("goal", &g0, dof)?;
        self.check_reach("start", &y0, &self.start)?;
        self.check_reach("goal", &g0, &self.goal)?;
        let tau = match opts.tau {
            Some(v) => crate::error::positive(|| "tau".into(), v)?,
            None => self.tau,
        };
        let duration = match opts.duration {
            Some(v) => crate::error::positive(|| "duration".into(), v)?,
            None => tau,
        };
        let spt = opts.steps_per_tau.unwrap_or(500);
        if spt == 0 || spt > 100_000_000 {
            return Err(Error::InvalidValue {
                field: "steps_per_tau".into(),
                value: spt as f64,
                reason: "is not in 1..=1e8",
            });
        }
        let mut changes = opts.goal_changes.clone();
        for (i, c) in changes.iter().enumerate() {
            crate::error::finite(|| format!("goal change {i} time"), c.t)?;
            check_vec(&format!("goal change {i} goal"), &c.goal, dof)?;
            self.check_reach(&format!("goal change {i} goal"), &c.goal, &self.goal)?;
        }
        changes.sort_by(|a, b| a.t.total_cmp(&b.t));
        if let Some(a) = opts.goal_filter {
            crate::error::positive(|| "goal filter gain".into(), a)?;
        }
        if let Some(ps) = &opts.phase_stop {
            crate::error::positive(|| "phase stopping gain".into(), ps.gain)?;
        }
        let h = tau / spt as f64;
        // Round near-integers down so the last step is never a sliver of roundoff size.
        let steps = (duration / h - 1e-9).ceil().max(1.0);
        // Per step: time, position, velocity, acceleration of every joint (and the exact
        // integrator's forcing values).
        let nsteps = crate::size::check_memory(
            "rollout integration steps (duration × steps per τ / τ)",
            steps,
            8.0 * (1.0 + 4.0 * dof as f64),
            &format!("a step of {dof} joint(s)"),
        )?;
        // Per-joint forcing scale (Ijspeert) and the start used by the Hoffmann term.
        let scale: Vec<f64> = (0..dof)
            .map(|j| match self.cfg.scaling {
                ForcingScaling::Hoffmann2009 => 1.0,
                ForcingScaling::Ijspeert2013 => {
                    if self.amplitude[j] == 0.0 {
                        1.0
                    } else {
                        g0[j] - y0[j]
                    }
                }
            })
            .collect();
        Ok(Setup {
            y0,
            v0,
            g0,
            tau,
            duration,
            h,
            nsteps,
            changes,
            scale,
        })
    }

    /// The rollout by classical RK4 on the grid `t_k = k h`, the last step ending at the
    /// duration. Goal changes are applied at the first step at or after their time.
    fn rollout_rk4(&self, opts: &RolloutOptions<'_>, setup: Setup) -> Result<DmpRollout> {
        let Setup {
            y0,
            v0,
            g0,
            tau,
            duration,
            h,
            nsteps,
            changes,
            scale,
        } = setup;
        let dof = self.dof;
        let mut ts = Vec::with_capacity(nsteps + 1);
        let mut ys = Vec::with_capacity((nsteps + 1) * dof);
        let mut vs = Vec::with_capacity((nsteps + 1) * dof);
        let mut accs = Vec::with_capacity((nsteps + 1) * dof);
        let ctx = Ctx {
            dmp: self,
            tau,
            y0: &y0,
            scale: &scale,
            goal_filter: opts.goal_filter,
            coupling: opts.coupling,
            phase_stop: opts.phase_stop,
        };
        let mut st = Rk4::new(&y0, v0, g0);
        self.forcing(1.0, &scale, &mut st.f_cur);
        let mut next_change = 0;
        let mut t = 0.0;
        for step in 0..=nsteps {
            // Goal changes due now.
            while next_change < changes.len() && changes[next_change].t <= t + 1e-12 * h {
                st.target.copy_from_slice(&changes[next_change].goal);
                if opts.goal_filter.is_none() {
                    st.g.copy_from_slice(&st.target);
                }
                next_change += 1;
            }
            // The first RK4 stage is the state's own derivative: it also gives the
            // acceleration stored for the dense output.
            st.first_stage(&ctx, t);
            ts.push(t);
            ys.extend_from_slice(&st.y);
            vs.extend_from_slice(&st.v);
            accs.extend_from_slice(&st.k[0].1);
            if step == nsteps {
                break;
            }
            let hs = if step + 1 == nsteps { duration - t } else { h };
            let t_end = if step + 1 == nsteps {
                duration
            } else {
                (step + 1) as f64 * h
            };
            st.step(&ctx, t, hs, t_end)?;
            t = t_end;
        }
        Ok(DmpRollout::from_states(dof, ts, ys, vs, accs))
    }
}

/// One stage's derivatives of `(y, v, g)`.
type Stage = (Vec<f64>, Vec<f64>, Vec<f64>);

/// The RK4 integrator's state (position, velocity, goal and, with phase stopping, phase) and
/// its stage buffers, allocated once per rollout.
struct Rk4 {
    y: Vec<f64>,
    v: Vec<f64>,
    g: Vec<f64>,
    /// The goal the filter pulls `g` towards (`g` itself without a filter).
    target: Vec<f64>,
    x: f64,
    /// Forcing at the step's start, midpoint and end, and at a stage's own phase (phase
    /// stopping).
    f_cur: Vec<f64>,
    f_mid: Vec<f64>,
    f_end: Vec<f64>,
    f_stage: Vec<f64>,
    /// The state at the stage being evaluated.
    tmp: Stage,
    k: [Stage; 4],
    /// The phase's rate at each stage (phase stopping).
    xs: [f64; 4],
    scratch: Vec<f64>,
}

impl Rk4 {
    fn new(y0: &[f64], v0: Vec<f64>, g0: Vec<f64>) -> Rk4 {
        let dof = y0.len();
        let stage = || (vec![0.0; dof], vec![0.0; dof], vec![0.0; dof]);
        Rk4 {
            y: y0.to_vec(),
            v: v0,
            g: g0.clone(),
            target: g0,
            x: 1.0,
            f_cur: vec![0.0; dof],
            f_mid: vec![0.0; dof],
            f_end: vec![0.0; dof],
            f_stage: vec![0.0; dof],
            tmp: stage(),
            k: [stage(), stage(), stage(), stage()],
            xs: [0.0; 4],
            scratch: vec![0.0; dof],
        }
    }

    /// The derivative at the current state: the first stage.
    fn first_stage(&mut self, ctx: &Ctx<'_, '_>, t: f64) {
        let k0 = &mut self.k[0];
        ctx.deriv(
            t,
            self.x,
            &self.y,
            &self.v,
            &self.g,
            &self.target,
            &self.f_cur,
            &mut k0.0,
            &mut k0.1,
            &mut k0.2,
        );
    }

    /// One RK4 step of length `hs` from `t` to `t_end` (the first stage already evaluated).
    fn step(&mut self, ctx: &Ctx<'_, '_>, t: f64, hs: f64, t_end: f64) -> Result<()> {
        let stop = ctx.phase_stop.is_some();
        // Without phase stopping the phase is the exact exponential and the two midpoint
        // stages share one forcing evaluation.
        if !stop {
            ctx.forcing(ctx.phase(t + 0.5 * hs), &mut self.f_mid);
            ctx.forcing(ctx.phase(t_end), &mut self.f_end);
        }
        // RK4 on (y, v, g) and, with phase stopping, x.
        self.xs[0] = if stop {
            ctx.phase_rate(t, self.x, &self.y, &mut self.scratch)
        } else {
            0.0
        };
        for stage in 1..4 {
            self.stage(ctx, stage, t, hs, t_end);
        }
        let (y, v, g, k) = (&mut self.y, &mut self.v, &mut self.g, &self.k);
        for j in 0..y.len() {
            y[j] += hs / 6.0 * (k[0].0[j] + 2.0 * k[1].0[j] + 2.0 * k[2].0[j] + k[3].0[j]);
            v[j] += hs / 6.0 * (k[0].1[j] + 2.0 * k[1].1[j] + 2.0 * k[2].1[j] + k[3].1[j]);
            g[j] += hs / 6.0 * (k[0].2[j] + 2.0 * k[1].2[j] + 2.0 * k[2].2[j] + k[3].2[j]);
        }
        if stop {
            let xs = &self.xs;
            self.x += hs / 6.0 * (xs[0] + 2.0 * xs[1] + 2.0 * xs[2] + xs[3]);
            ctx.forcing(self.x, &mut self.f_end);
        } else {
            self.x = ctx.phase(t_end);
        }
        if !self.y.iter().chain(&self.v).all(|x| x.is_finite()) {
            return Err(Error::Infeasible(format!(
                "DMP rollout diverged at t = {t} s (coupling term or parameters)"
            )));
        }
        std::mem::swap(&mut self.f_cur, &mut self.f_end);
        Ok(())
    }

    /// Stage `stage` (1..=3) of the step from `t`: the state advanced along the previous
    /// stage's derivative, and its derivative.
    fn stage(&mut self, ctx: &Ctx<'_, '_>, stage: usize, t: f64, hs: f64, t_end: f64) {
        let stop = ctx.phase_stop.is_some();
        let c = if stage == 3 { hs } else { 0.5 * hs };
        let (prev, rest) = self.k.split_at_mut(stage);
        let p = &prev[stage - 1];
        let tmp = &mut self.tmp;
        for j in 0..self.y.len() {
            tmp.0[j] = self.y[j] + c * p.0[j];
            tmp.1[j] = self.v[j] + c * p.1[j];
            tmp.2[j] = self.g[j] + c * p.2[j];
        }
        let (xst, f) = if stop {
            let xst = self.x + c * self.xs[stage - 1];
            ctx.forcing(xst, &mut self.f_stage);
            self.xs[stage] = ctx.phase_rate(t + c, xst, &tmp.0, &mut self.scratch);
            if stage == 3 {
                self.f_end.copy_from_slice(&self.f_stage);
            }
            (xst, &self.f_stage)
        } else if stage == 3 {
            (ctx.phase(t_end), &self.f_end)
        } else {
            (ctx.phase(t + 0.5 * hs), &self.f_mid)
        };
        let cur = &mut rest[0];
        ctx.deriv(
            t + c,
            xst,
            &tmp.0,
            &tmp.1,
            &tmp.2,
            &self.target,
            f,
            &mut cur.0,
            &mut cur.1,
            &mut cur.2,
        );
    }
}

/// What the RK4 right-hand side needs besides the state: the DMP, τ, the start (Hoffmann
/// term), the forcing scale and the options that couple.
struct Ctx<'a, 'b> {
    dmp: &'a Dmp,
    tau: f64,
    y0: &'a [f64],
    scale: &'a [f64],
    goal_filter: Option<f64>,
    coupling: Option<Coupling<'b>>,
    phase_stop: Option<PhaseStop<'b>>,
}

impl Ctx<'_, '_> {
    fn phase(&self, t: f64) -> f64 {
        (-self.dmp.cfg.alpha_x * t / self.tau).exp()
    }

    /// The learned forcing at phase `x`, scaled.
    fn forcing(&self, x: f64, out: &mut [f64]) {
        self.dmp.forcing(x, self.scale, out);
    }

    /// `ẋ` with phase stopping: `τ ẋ = −α_x x / (1 + α_px ‖ỹ − y‖²)`.
    fn phase_rate(&self, t: f64, x: f64, y: &[f64], scratch: &mut [f64]) -> f64 {
        let mut slow = 1.0;
        if let Some(ps) = &self.phase_stop {
            (ps.actual)(t, y, scratch);
            let e2: f64 = scratch.iter().zip(y).map(|(a, b)| (a - b) * (a - b)).sum();
            slow += ps.gain * e2;
        }
        -self.dmp.cfg.alpha_x * x / (self.tau * slow)
    }

    /// Time derivatives of (y, v, g) at phase `x`; `f` is the forcing term at that phase.
    #[allow(clippy::too_many_arguments)]
    fn deriv(
        &self,
        t: f64,
        x: f64,
        y: &[f64],
        v: &[f64],
        g: &[f64],
        target: &[f64],
        f: &[f64],
        dy: &mut [f64],
        dv: &mut [f64],
        dg: &mut [f64],
    ) {
        let (az, bz) = (self.dmp.cfg.alpha_z, self.dmp.cfg.beta_z);
        let tau = self.tau;
        for j in 0..y.len() {
            let mut acc = az * (bz * (g[j] - y[j]) - tau * v[j]) + f[j];
            if self.dmp.cfg.scaling == ForcingScaling::Hoffmann2009 {
                acc -= az * bz * (g[j] - self.y0[j]) * x;
            }
            dv[j] = acc;
            dy[j] = v[j];
            dg[j] = match self.goal_filter {
                Some(ag) => ag * (target[j] - g[j]) / tau,
                None => 0.0,
            };
        }
        if let Some(c) = self.coupling {
            c.add(t, y, v, dv);
        }
        let inv = 1.0 / (tau * tau);
        dv.iter_mut().for_each(|a| *a *= inv);
    }
}
