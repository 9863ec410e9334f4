//! The exponential integrator of uncoupled rollouts (see the precision contract of
//! [`super`]): the homogeneous part propagated exactly, the forcing term integrated as its
//! quintic interpolant through [`EXP_NODES`] neighbouring grid values.

use super::rollout::Setup;
use super::{Dmp, DmpRollout, ForcingScaling};

/// Forcing samples per step of the exponential integrator (a quintic interpolant).
pub(super) const EXP_NODES: usize = 6;

/// Steps of length `h` of the transformation system `τ² ÿ = α_z(β_z(g − y) − τẏ) + F(t)` with
/// constant `g`, exact for the homogeneous part: in `u = y − g`, `v = ẏ`,
/// `(u, v)(t + h) = Φ (u, v)(t) + Σ_i W_i F(t_i)`, where the forcing over the step is the
/// polynomial interpolating [`EXP_NODES`] nearby grid values `F(t_i)` and
/// `W_i = ∫₀ʰ e^{M(h−s)} b ℓ_i(s) ds` (`ℓ_i` its Lagrange basis, `b = (0, 1/τ²)`). `Φ = e^{Mh}`
/// and the moments `∫₀ʰ e^{M(h−s)} b (s/h)^p ds` come from one exponential of the augmented
/// matrix `[[hM, h b e₀ᵀ], [0, N]]` (`N` the nilpotent shift), by scaling and squaring.
struct ExpStep {
    phi: [[f64; 2]; 2],
    /// Moments `∫₀ʰ e^{M(h−s)} b (s/h)^p ds`, `p < EXP_NODES`.
    gam: [[f64; 2]; EXP_NODES],
}

impl ExpStep {
    fn new(az: f64, bz: f64, tau: f64, h: f64) -> ExpStep {
        const Q: usize = EXP_NODES;
        const D: usize = 2 + Q;
        let mut z = [[0.0f64; D]; D];
        z[0][1] = h;
        z[1][0] = -az * bz / (tau * tau) * h;
        z[1][1] = -az / tau * h;
        z[1][2] = h / (tau * tau);
        for p in 0..Q - 1 {
            z[2 + p][3 + p] = 1.0;
        }
        let e = expm(&z);
        let phi = [[e[0][0], e[0][1]], [e[1][0], e[1][1]]];
        // p! times the top-right block's column p.
        let mut gam = [[0.0f64; 2]; Q];
        let mut fact = 1.0;
        for p in 0..Q {
            if p > 0 {
                fact *= p as f64;
            }
            gam[p] = [fact * e[0][2 + p], fact * e[1][2 + p]];
        }
        ExpStep { phi, gam }
    }

    /// The weights `W_i` on `(u, v)` of the forcing at nodes `σ_i` (positions in units of the
    /// step, the step being `[0, 1]`).
    fn weights(&self, nodes: &[f64; EXP_NODES]) -> [[f64; 2]; EXP_NODES] {
        let mut w = [[0.0f64; 2]; EXP_NODES];
        for (i, wi) in w.iter_mut().enumerate() {
            // Monomial coefficients of ℓ_i(σ) = Π_{j≠i} (σ − σ_j) / (σ_i − σ_j).
            let mut c = [0.0f64; EXP_NODES];
            c[0] = 1.0;
            let mut deg = 0;
            for (jn, &sj) in nodes.iter().enumerate() {
                if jn == i {
                    continue;
                }
                let den = nodes[i] - sj;
                for p in (0..=deg + 1).rev() {
                    let lower = if p > 0 { c[p - 1] } else { 0.0 };
                    c[p] = (lower - sj * c[p]) / den;
                }
                deg += 1;
            }
            for (cp, gp) in c.iter().zip(&self.gam) {
                wi[0] += cp * gp[0];
                wi[1] += cp * gp[1];
            }
        }
        w
    }
}

/// `e^A` of a small square matrix by scaling and squaring with a degree-18 Taylor polynomial
/// (the scaled norm is at most 1/2, so truncation is below 2e-23 relative).
fn expm<const D: usize>(a: &[[f64; D]; D]) -> [[f64; D]; D] {
    let norm = (0..D)
        .map(|j| (0..D).map(|i| a[i][j].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut sq = 0;
    while norm / 2f64.powi(sq) > 0.5 {
        sq += 1;
    }
    let f = 2f64.powi(-sq);
    let mut term = [[0.0f64; D]; D];
    let mut sum = [[0.0f64; D]; D];
    for i in 0..D {
        term[i][i] = 1.0;
        sum[i][i] = 1.0;
    }
    let mul = |x: &[[f64; D]; D], y: &[[f64; D]; D]| {
        let mut r = [[0.0f64; D]; D];
        for i in 0..D {
            for k in 0..D {
                for j in 0..D {
                    r[i][j] += x[i][k] * y[k][j];
                }
            }
        }
        r
    };
    let mut scaled = *a;
    scaled.iter_mut().flatten().for_each(|v| *v *= f);
    for n in 1..=18 {
        term = mul(&term, &scaled);
        term.iter_mut().flatten().for_each(|v| *v /= n as f64);
        for i in 0..D {
            for j in 0..D {
                sum[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..sq {
        sum = mul(&sum, &sum);
    }
    sum
}

/// The exponential integrator's grid `t_k = k h` (`k < nsteps`), `t_nsteps = duration`, with
/// the phase and the learned forcing at every grid point and the stencil weights of the
/// uniform steps.
struct Grid {
    ts: Vec<f64>,
    /// Phase at the grid points.
    xs: Vec<f64>,
    /// Learned forcing at the grid points, row-major (without the Hoffmann goal term, which
    /// depends on the current goal).
    fpart: Vec<f64>,
    step: ExpStep,
    /// The last step's propagator when it is shorter than `h`.
    last: Option<ExpStep>,
    /// Whether the duration is a whole number of steps.
    uniform_end: bool,
    /// Weights of the stencils on the uniform part of the grid, by the number `o` of nodes
    /// before the step's start.
    uniform_w: [[[f64; 2]; EXP_NODES]; EXP_NODES - 1],
}

impl Grid {
    fn new(dmp: &Dmp, s: &Setup) -> Grid {
        let (az, bz, ax) = (dmp.cfg.alpha_z, dmp.cfg.beta_z, dmp.cfg.alpha_x);
        let (tau, h, duration, nsteps) = (s.tau, s.h, s.duration, s.nsteps);
        let uniform_end = (duration - nsteps as f64 * h).abs() <= 1e-12 * duration;
        let ts: Vec<f64> = (0..=nsteps)
            .map(|k| if k == nsteps { duration } else { k as f64 * h })
            .collect();
        let xs: Vec<f64> = ts.iter().map(|&t| (-ax * t / tau).exp()).collect();
        let mut fpart = vec![0.0; (nsteps + 1) * dmp.dof];
        for (f, &x) in fpart.chunks_exact_mut(dmp.dof).zip(&xs) {
            dmp.forcing(x, &s.scale, f);
        }
        let step = ExpStep::new(az, bz, tau, h);
        let mut uniform_w = [[[0.0f64; 2]; EXP_NODES]; EXP_NODES - 1];
        for (o, w) in uniform_w.iter_mut().enumerate() {
            *w = step.weights(&std::array::from_fn(|i| i as f64 - o as f64));
        }
        let last = (!uniform_end).then(|| ExpStep::new(az, bz, tau, duration - ts[nsteps - 1]));
        Grid {
            ts,
            xs,
            fpart,
            step,
            last,
            uniform_end,
            uniform_w,
        }
    }

    /// The step from node `k` (`< nsteps`): its propagator, the stencil's first node and the
    /// weights of the stencil's forcing values. Stencil nodes `k − o .. k − o + EXP_NODES − 1`
    /// lie inside `0..=nsteps`, centred when possible.
    fn stencil(&self, k: usize) -> (&ExpStep, usize, [[f64; 2]; EXP_NODES]) {
        let nsteps = self.ts.len() - 1;
        let o = (EXP_NODES / 2 - 1)
            .min(k)
            .max((k + EXP_NODES - 1).saturating_sub(nsteps));
        let first = k - o;
        // The last node may be closer than h (a duration that is not a whole number of
        // steps): stencils that reach it, and the last step, get their own weights.
        if first + EXP_NODES - 1 < nsteps || self.uniform_end {
            return (&self.step, first, self.uniform_w[o]);
        }
        let st = match &self.last {
            Some(l) if k + 1 == nsteps => l,
            _ => &self.step,
        };
        let ts = &self.ts;
        let hk = ts[k + 1] - ts[k];
        let w = st.weights(&std::array::from_fn(|i| (ts[first + i] - ts[k]) / hk));
        (st, first, w)
    }

    /// The whole forcing `F` (learned part minus the Hoffmann goal term `hoff`) into `ftot`
    /// at every grid point a stencil from node `k` on can reach (`EXP_NODES − 2` nodes back).
    fn refresh_forcing(&self, k: usize, hoff: &[f64], ftot: &mut [f64]) {
        let dof = hoff.len();
        let from = k.saturating_sub(EXP_NODES);
        for (i, (ft, fp)) in ftot
            .chunks_exact_mut(dof)
            .zip(self.fpart.chunks_exact(dof))
            .enumerate()
            .skip(from)
        {
            for j in 0..dof {
                ft[j] = fp[j] - hoff[j] * self.xs[i];
            }
        }
    }
}

impl Dmp {
    /// The rollout by [`ExpStep`] on the grid `t_k = k h` (`k < nsteps`), `t_nsteps =
    /// duration`: the forcing values at every grid point first, then per step the exact
    /// propagator plus the interpolated forcing's weights. Goal changes are applied like in
    /// the RK4 path.
    pub(super) fn rollout_exact(&self, s: &Setup) -> DmpRollout {
        let dof = self.dof;
        let (az, bz, tau, nsteps) = (self.cfg.alpha_z, self.cfg.beta_z, s.tau, s.nsteps);
        let hoffmann = self.cfg.scaling == ForcingScaling::Hoffmann2009;
        let grid = Grid::new(self, s);
        // The whole forcing F at the grid points for the current goal (the Hoffmann term
        // changes with it).
        let mut ftot = vec![0.0; (nsteps + 1) * dof];
        let mut ys = Vec::with_capacity((nsteps + 1) * dof);
        let mut vs = Vec::with_capacity((nsteps + 1) * dof);
        let mut accs = Vec::with_capacity((nsteps + 1) * dof);
        let mut y = s.y0.clone();
        let mut v = s.v0.clone();
        let mut g = s.g0.clone();
        let mut hoff = vec![0.0; dof];
        let mut next_change = 0;
        let inv_tau2 = 1.0 / (tau * tau);
        for k in 0..=nsteps {
            let mut changed = k == 0;
            while next_change < s.changes.len()
                && s.changes[next_change].t <= grid.ts[k] + 1e-12 * s.h
            {
                g.copy_from_slice(&s.changes[next_change].goal);
                next_change += 1;
                changed = true;
            }
            if changed {
                for j in 0..dof {
                    hoff[j] = if hoffmann {
                        az * bz * (g[j] - s.y0[j])
                    } else {
                        0.0
                    };
                }
                grid.refresh_forcing(k, &hoff, &mut ftot);
            }
            for j in 0..dof {
                let f = ftot[k * dof + j];
                accs.push((az * (bz * (g[j] - y[j]) - tau * v[j]) + f) * inv_tau2);
            }
            ys.extend_from_slice(&y);
            vs.extend_from_slice(&v);
            if k == nsteps {
                break;
            }
            let (st, first, w) = grid.stencil(k);
            for j in 0..dof {
                let u = y[j] - g[j];
                let (mut un, mut vn) = (
                    st.phi[0][0] * u + st.phi[0][1] * v[j],
                    st.phi[1][0] * u + st.phi[1][1] * v[j],
                );
                for (i, wi) in w.iter().enumerate() {
                    let f = ftot[(first + i) * dof + j];
                    un += wi[0] * f;
                    vn += wi[1] * f;
                }
                y[j] = un + g[j];
                v[j] = vn;
            }
        }
        DmpRollout::from_states(dof, grid.ts, ys, vs, accs)
    }
}
