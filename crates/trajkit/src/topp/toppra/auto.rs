//! [`Gridpoints::Auto`](crate::topp::Gridpoints::Auto): a graded grid from a duration
//! tolerance (the method, its error model and its cost are in the `topp::grid` module docs).
//!
//! Each round cuts interval i of the current grid into k_i equal parts and solves the new grid
//! (with the between-gridpoint guarantee, which may add points of its own). The time the
//! profile spends on interval i before, t_i, and on its parts after, t_i′, give the interval's
//! share of the error: under the first-order model (error c·h on an interval of width h) the
//! parts carry |t_i − t_i′|/(k_i − 1) together. Intervals not cut keep their previous estimate.
//! When the estimates of the new grid sum to at most `tolerance`·T it is returned; otherwise
//! the next round cuts each interval j into k_j ∝ ∛e_j parts (the counts that minimize the
//! number of intervals for a given Σ e_j/k_j², the error of a second-order method), aiming at
//! [`AUTO_AIM`] of the tolerance. The choice of counts assumes the faster convergence measured
//! on fine grids; the acceptance does not (first order, as on uniform grids).
//!
//! A graded round also cuts every interval that takes more than T/[`AUTO_STEPS`] into parts
//! below that. The duration does not need it, the jerk stages do: they sample the law twice
//! per interval and lower its velocities at gridpoints ([`crate::topp::jerk_local`]), and
//! without the cap the long intervals a graded grid leaves where the duration is insensitive
//! (up to 61 ms on the path with 1e-3 rad segments) made the local slow-down +3.3 % over raw
//! TOPP-RA instead of +1.9–2.0 % (equal grids of 1000–8000 intervals).

use super::{profile_from, Toppra, Workspace};
use crate::error::{Error, Result};
use crate::topp::grid::{per_piece, piece_breaks, subdivide, AUTO_START, MAX_AUTO_INTERVALS};
use crate::topp::PhaseProfile;
use crate::Path;

/// Refinement rounds after the first grid; the finest grid is returned after the last.
const MAX_AUTO_ROUNDS: usize = 10;

/// Share of the tolerance a graded round aims at under its second-order model (the rest
/// absorbs the gap to the first-order estimate that accepts the grid).
const AUTO_AIM: f64 = 0.5;

/// A graded round leaves no interval longer than T/`AUTO_STEPS` in time.
const AUTO_STEPS: f64 = 1000.0;

/// Most parts one interval is cut into in one round.
const MAX_PARTS: usize = 256;

/// A solved grid: the grid asked for, the time spent on each of its intervals, the profile.
struct Solved {
    grid: Vec<f64>,
    dt: Vec<f64>,
    profile: PhaseProfile,
}

impl<P: Path> Toppra<'_, P> {
    /// The rounds of [`Toppra::solve_auto`] on the workspace `ws` (see the module docs).
    pub(super) fn auto_loop(&self, ws: &mut Workspace, tolerance: f64) -> Result<PhaseProfile> {
        let breaks = piece_breaks(&self.path);
        let pieces = breaks.len() - 1;
        let mut m = AUTO_START;
        let mut cur = loop {
            match self.solve_design(ws, per_piece(&breaks, m)) {
                Ok(s) => break s,
                // A coarse grid can miss a narrow feasible passage: try finer ones first.
                Err(Error::Infeasible(_))
                    if m < 16 * AUTO_START && 2 * m * pieces <= MAX_AUTO_INTERVALS =>
                {
                    m *= 2
                }
                Err(e) => return Err(e),
            }
        };
        // The first round halves every interval; its grid's error is not known yet.
        let mut parts = vec![2; cur.dt.len()];
        let mut err: Vec<f64> = Vec::new();
        for _ in 0..MAX_AUTO_ROUNDS {
            let total: usize = parts.iter().sum();
            if total > MAX_AUTO_INTERVALS {
                break;
            }
            let next = self.solve_design(ws, subdivide(&cur.grid, &parts))?;
            err = part_errors(&cur, &err, &next);
            let t = next.profile.duration();
            let estimate: f64 = err.iter().sum();
            cur = next;
            if estimate <= tolerance * t {
                break;
            }
            parts = grading(&err, AUTO_AIM * tolerance * t);
            // No interval longer than T/AUTO_STEPS in time (see the module docs).
            let longest = t / AUTO_STEPS;
            for (k, &d) in parts.iter_mut().zip(&cur.dt) {
                *k = (*k).max((d / longest).ceil().min(MAX_PARTS as f64) as usize);
            }
        }
        Ok(cur.profile)
    }

    /// Solves on `grid` and returns the time spent on each of its intervals.
    fn solve_design(&self, ws: &mut Workspace, grid: Vec<f64>) -> Result<Solved> {
        let mut solved = grid.clone();
        let x = self.solve_on(ws, &mut solved)?;
        let profile = profile_from(solved, x)?;
        let dt = interval_times(&grid, &profile);
        Ok(Solved { grid, dt, profile })
    }
}

/// The time `profile` spends on each interval of `grid` (whose points are among the
/// profile's gridpoints: the between-gridpoint check only adds points).
fn interval_times(grid: &[f64], profile: &PhaseProfile) -> Vec<f64> {
    let (s, t) = (profile.gridpoints(), profile.times());
    if s.len() == grid.len() {
        // No point added: the profile's intervals are the grid's (the same differences as
        // the walk below takes).
        return t.windows(2).map(|w| w[1] - w[0]).collect();
    }
    walk_times(grid, s, t)
}

/// [`interval_times`] by walking the profile's gridpoints `s` (times `t`) along `grid`.
fn walk_times(grid: &[f64], s: &[f64], t: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(grid.len() - 1);
    let (mut p, mut t_start) = (0, 0.0);
    for &g in &grid[1..] {
        while p + 1 < s.len() && s[p] < g {
            p += 1;
        }
        out.push(t[p] - t_start);
        t_start = t[p];
    }
    out
}

/// The error estimate of every interval of `next` (a subdivision of `cur`, whose intervals
/// had the estimates `err`, empty when unknown): an interval cut into k > 1 parts passes
/// |t − t′|/(k − 1) to its parts in equal shares; one kept whole keeps its estimate.
fn part_errors(cur: &Solved, err: &[f64], next: &Solved) -> Vec<f64> {
    let mut out = Vec::with_capacity(next.dt.len());
    let mut j = 0;
    for i in 0..cur.dt.len() {
        let end = cur.grid[i + 1];
        let first = j;
        let mut t = 0.0;
        while j < next.dt.len() && next.grid[j] < end {
            t += next.dt[j];
            j += 1;
        }
        let k = j - first;
        let e = match (k, err.get(i)) {
            (1, Some(&e)) => e,
            _ => (cur.dt[i] - t).abs() / (k.max(2) - 1) as f64,
        };
        out.extend(std::iter::repeat_n(e / k.max(1) as f64, k));
    }
    out
}

/// Part counts k_j ∝ ∛e_j with Σ e_j/k_j² = `budget` before rounding up (which only lowers
/// it), at least 1 and at most [`MAX_PARTS`]: the fewest intervals for that budget when the
/// error falls with the square of the spacing. The finer solves converge faster than first
/// order (about 1.3–1.8 on the Panda suites), so this chooses grids near what the tolerance
/// needs; whether one meets it is still judged by the first-order estimate.
fn grading(err: &[f64], budget: f64) -> Vec<usize> {
    // k_j = c·e_j^(1/3): the fewest intervals for Σ e_j/k_j² = budget (each root taken once).
    let roots: Vec<f64> = err.iter().map(|e| e.cbrt()).collect();
    let root_sum: f64 = roots.iter().sum();
    let c = (root_sum / budget).sqrt();
    roots
        .iter()
        .map(|r| {
            let k = (c * r).ceil();
            if k.is_finite() {
                (k as usize).clamp(1, MAX_PARTS)
            } else {
                MAX_PARTS
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grading_meets_its_budget_with_cube_root_counts() {
        let err = [8e-6, 1e-6, 0.0, 1e-9];
        let k = grading(&err, 1e-6);
        let left: f64 = err.iter().zip(&k).map(|(e, &k)| e / (k * k) as f64).sum();
        assert!(left <= 1e-6, "{left}");
        assert_eq!(k[2], 1);
        // ∛e ratios 2 : 1 : 0 : 0.1.
        assert!(k[0] >= 2 * k[1] - 1 && k[0] <= 2 * k[1] + 1, "{k:?}");
        assert!(k[3] <= k[1], "{k:?}");
    }

    #[test]
    fn part_errors_follow_the_first_order_model() {
        let profile = |s: &[f64]| {
            let sd: Vec<f64> = s.iter().map(|_| 1.0).collect();
            PhaseProfile::new(s, &sd).unwrap()
        };
        let cur = Solved {
            grid: vec![0.0, 1.0, 2.0],
            dt: vec![1.3, 1.0],
            profile: profile(&[0.0, 1.0, 2.0]),
        };
        let grid = vec![0.0, 0.25, 0.5, 0.75, 1.0, 2.0];
        let next = Solved {
            dt: vec![0.3, 0.25, 0.25, 0.3, 0.99],
            profile: profile(&grid),
            grid,
        };
        // Interval 0 in four parts: 1.3 → 1.1, error 0.2/3 after; interval 1 kept: 1e-3.
        let e = part_errors(&cur, &[0.5, 1e-3], &next);
        assert_eq!(e.len(), 5);
        for v in &e[..4] {
            assert!((v - 0.2 / 3.0 / 4.0).abs() < 1e-15, "{e:?}");
        }
        assert_eq!(e[4], 1e-3);
    }

    /// On the profile's own grid the times are the walk's, bit for bit.
    #[test]
    fn interval_times_on_the_profiles_grid_are_the_walks() {
        let mut rng = crate::rng::SplitMix64::new(5);
        let mut s = vec![0.0];
        for _ in 0..200 {
            s.push(s[s.len() - 1] + rng.uniform(1e-4, 0.1));
        }
        let sd: Vec<f64> = s.iter().map(|_| rng.uniform(0.0, 3.0)).collect();
        let profile = PhaseProfile::new(&s, &sd).unwrap();
        let fast = interval_times(&s, &profile);
        let walk = walk_times(&s, profile.gridpoints(), profile.times());
        assert_eq!(fast.len(), 200);
        assert!(fast
            .iter()
            .zip(&walk)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
    }

    #[test]
    fn interval_times_sum_the_parts_the_check_added() {
        let s = [0.0, 0.5, 1.0, 1.5, 2.0];
        let sd = [0.0, 1.0, 1.0, 2.0, 0.0];
        let profile = PhaseProfile::new(&s, &sd).unwrap();
        let dt = interval_times(&[0.0, 1.0, 2.0], &profile);
        let t = profile.times();
        assert!((dt[0] - t[2]).abs() < 1e-15 && (dt[1] - (t[4] - t[2])).abs() < 1e-15);
    }
}
