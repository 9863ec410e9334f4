//! A DMP whose rollouts stay inside joint position limits.
//!
//! Each joint with finite limits `[lo, hi]` is learned and integrated in the unbounded
//! coordinate `ξ = atanh((y − c) / r)` (`c` the middle, `r` the half range) and mapped back by
//! `y = c + r tanh ξ`, so every rollout stays strictly inside the limits whatever the new goal,
//! start, τ or coupling, and stays smooth. Joints with an infinite limit are left as they are.
//!
//! # Precision contract
//! - `lo < y(t) < hi` for every `t` (up to the rounding of `tanh` at `|ξ| > 19`).
//! - Derivatives are the exact chain rule of the map applied to the inner rollout's
//!   consistent derivatives, so velocity, acceleration and jerk stay mutually consistent.
//! - A demonstration strictly inside the limits is reproduced like by [`Dmp`] (the fit happens
//!   in `ξ`; tests check 1e-4 of the range).

use crate::error::{Error, Result};
use crate::limits::Limits;
use crate::primitives::demo::check_demo;
use crate::primitives::dmp::{Dmp, DmpConfig, DmpRollout, RolloutOptions};
use crate::traj::{Order, Trajectory};

/// A [`Dmp`] learned and integrated in joint-limit-respecting coordinates.
///
/// ```
/// use trajkit::primitives::{BoundedDmp, DmpConfig, RolloutOptions};
/// use trajkit::{Limits, JointLimits, Order, Trajectory};
/// let t: Vec<f64> = (0..=500).map(|k| k as f64 / 500.0).collect();
/// let q: Vec<f64> = t.iter().map(|&s| 0.9 * (10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5))).collect();
/// let limits = Limits::new(vec![JointLimits { position_min: -1.0, position_max: 1.0, ..JointLimits::default() }])?;
/// let dmp = BoundedDmp::fit(&t, &q, 1, &DmpConfig::default(), &limits)?;
/// // A goal beyond the limit: the rollout approaches the limit but never crosses it.
/// let roll = dmp.rollout(&RolloutOptions { goal: Some(vec![0.99999]), ..Default::default() })?;
/// let mut y = [0.0];
/// for k in 0..=100 {
///     roll.eval(k as f64 / 100.0, Order::Position, &mut y);
///     assert!(y[0] < 1.0);
/// }
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct BoundedDmp {
    inner: Dmp,
    /// Per joint `Some((c, r))` for finite limits.
    maps: Vec<Option<(f64, f64)>>,
}

fn to_xi(m: Option<(f64, f64)>, y: f64) -> f64 {
    match m {
        Some((c, r)) => ((y - c) / r).atanh(),
        None => y,
    }
}

/// `ξ` of positions `q` (row-major, `dof` per row); refuses values on or outside the limits.
fn map_positions(
    maps: &[Option<(f64, f64)>],
    q: &[f64],
    dof: usize,
    what: &str,
) -> Result<Vec<f64>> {
    if q.len() % dof != 0 {
        return Err(Error::DimensionMismatch {
            what: format!("{what} entries (a multiple of {dof})"),
            expected: dof,
            found: q.len(),
        });
    }
    q.iter()
        .enumerate()
        .map(|(i, &y)| {
            let j = i % dof;
            if let Some((c, r)) = maps[j] {
                if y.is_nan() || (y - c).abs() >= r {
                    return Err(Error::InvalidValue {
                        field: format!("{what} {} joint {}", i / dof, j + 1),
                        value: y,
                        reason: "is not strictly inside the joint's position limits",
                    });
                }
            }
            Ok(to_xi(maps[j], y))
        })
        .collect()
}

impl BoundedDmp {
    /// Learns from a demonstration that lies strictly inside `limits` (position limits of the
    /// first `dof` joints).
    pub fn fit(
        t: &[f64],
        q: &[f64],
        dof: usize,
        cfg: &DmpConfig,
        limits: &Limits,
    ) -> Result<BoundedDmp> {
        check_demo(t, q, dof, 3)?;
        if limits.dof() < dof {
            return Err(Error::DimensionMismatch {
                what: "limits joint count".into(),
                expected: dof,
                found: limits.dof(),
            });
        }
        let maps: Vec<Option<(f64, f64)>> = (0..dof)
            .map(|j| {
                let l = limits.joint(j);
                if l.position_min.is_finite() && l.position_max.is_finite() {
                    Some((
                        0.5 * (l.position_min + l.position_max),
                        0.5 * (l.position_max - l.position_min),
                    ))
                } else {
                    None
                }
            })
            .collect();
        let xi = map_positions(&maps, q, dof, "demonstration sample")?;
        Ok(BoundedDmp {
            inner: Dmp::fit(t, &xi, dof, cfg)?,
            maps,
        })
    }

    fn map_positions(&self, q: &[f64], dof: usize, what: &str) -> Result<Vec<f64>> {
        map_positions(&self.maps, q, dof, what)
    }

    /// The DMP in the mapped coordinates.
    pub fn inner(&self) -> &Dmp {
        &self.inner
    }

    /// Rolls out like [`Dmp::rollout`]; `start`, `goal` and goal changes are positions and must
    /// lie strictly inside the limits; `start_velocity` is per second in joint space. A coupling
    /// term acts in the mapped coordinates.
    pub fn rollout(&self, opts: &RolloutOptions<'_>) -> Result<BoundedRollout> {
        let dof = self.inner.dof();
        let mut o = opts.clone();
        if let Some(s) = &opts.start {
            o.start = Some(self.map_positions(s, dof, "start")?);
        }
        if let Some(g) = &opts.goal {
            o.goal = Some(self.map_positions(g, dof, "goal")?);
        }
        for (k, c) in o.goal_changes.iter_mut().enumerate() {
            c.goal = self.map_positions(&c.goal, dof, &format!("goal change {k} goal"))?;
        }
        if let Some(v) = &opts.start_velocity {
            let y0 = match &opts.start {
                Some(s) => s.clone(),
                None => (0..dof)
                    .map(|j| match self.maps[j] {
                        Some((c, r)) => c + r * self.inner.start()[j].tanh(),
                        None => self.inner.start()[j],
                    })
                    .collect(),
            };
            o.start_velocity = Some(
                (0..dof)
                    .map(|j| match self.maps[j] {
                        // dξ/dt = ẏ / (r (1 − u²)), u = (y − c)/r.
                        Some((c, r)) => {
                            let u = (y0[j] - c) / r;
                            v.get(j).copied().unwrap_or(f64::NAN) / (r * (1.0 - u * u))
                        }
                        None => v.get(j).copied().unwrap_or(f64::NAN),
                    })
                    .collect(),
            );
        }
        Ok(BoundedRollout {
            inner: self.inner.rollout(&o)?,
            maps: self.maps.clone(),
        })
    }
}

/// A rollout of a [`BoundedDmp`]: `y = c + r tanh ξ(t)` per limited joint.
#[derive(Debug, Clone)]
pub struct BoundedRollout {
    inner: DmpRollout,
    maps: Vec<Option<(f64, f64)>>,
}

impl Trajectory for BoundedRollout {
    fn dof(&self) -> usize {
        self.maps.len()
    }
    fn duration(&self) -> f64 {
        self.inner.duration()
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        let dof = self.maps.len();
        if order == Order::Position {
            self.inner.eval(t, Order::Position, out);
            for j in 0..dof {
                if let Some((c, r)) = self.maps[j] {
                    out[j] = c + r * out[j].tanh();
                }
            }
            return;
        }
        // Chain rule with u = tanh ξ, u' = 1 − u², u'' = −2u(1 − u²), u''' = (6u² − 2)(1 − u²).
        // Per joint (no allocation): evaluate the inner derivatives one joint at a time.
        for j in 0..dof {
            let k = order.index();
            let mut xi = [0.0f64; 4];
            for (m, x) in xi.iter_mut().enumerate().take(k + 1) {
                *x = self
                    .inner
                    .eval_joint(t, Order::from_index(m).unwrap_or(Order::Jerk), j);
            }
            match self.maps[j] {
                None => out[j] = xi[k],
                Some((_, r)) => {
                    let u = xi[0].tanh();
                    let g1 = 1.0 - u * u;
                    let g2 = -2.0 * u * g1;
                    let g3 = (6.0 * u * u - 2.0) * g1;
                    out[j] = r * match k {
                        1 => g1 * xi[1],
                        2 => g2 * xi[1] * xi[1] + g1 * xi[2],
                        _ => g3 * xi[1].powi(3) + 3.0 * g2 * xi[1] * xi[2] + g1 * xi[3],
                    };
                }
            }
        }
    }
}
