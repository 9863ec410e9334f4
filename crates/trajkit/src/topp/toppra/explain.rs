//! Why TOPP-RA found no profile: the constraints to name in the typed error when a stage's
//! controllable set is empty or the path cannot leave rest on an interval.

use super::{Toppra, Workspace, X_BIG};
use crate::error::Error;
use crate::topp::constraint::PathPoint;
use crate::topp::lp::{self, BOX};
use crate::Path;

impl Workspace {
    pub(super) fn name_of<P: Path>(&self, prob: &Toppra<'_, P>, k: usize) -> String {
        prob.constraints
            .get(k)
            .map_or_else(|| "no constraint".into(), |c| c.name())
    }

    /// Why stage i has an empty controllable set.
    pub(super) fn explain_stage<P: Path>(
        &mut self,
        prob: &Toppra<'_, P>,
        grid: &[f64],
        i: usize,
    ) -> Error {
        let delta = grid[i + 1] - grid[i];
        let (klo, khi) = (self.klo[i + 1], self.khi[i + 1]);
        let xhi = self.pts.xhi[i].min(X_BIG);
        let xlo = self.pts.xlo[i];
        let lo = [(klo - xhi) / (2.0 * delta), xlo];
        let hi = [(khi - xlo) / (2.0 * delta), xhi];
        let tol = 1e-10 * (self.scale + khi);
        let mut culprits = Vec::new();
        for k in 0..self.nc {
            let stage = self.stage(i, delta, prob.options.discretization, Some(k), khi, klo);
            if lp::maximize([0.0, 1.0], &stage, lo, hi, [BOX, BOX], tol).is_none() {
                culprits.push(prob.constraints[k].name());
            }
        }
        let who = if culprits.is_empty() {
            "the constraints together".to_string()
        } else {
            format!("'{}'", culprits.join("', '"))
        };
        Error::Infeasible(format!(
            "at s = {} (between gridpoints {i} and {}): {who} leave no admissible path acceleration that reaches the velocities controllable at s = {} (ṡ in [{}, {}])",
            grid[i],
            i + 1,
            grid[i + 1],
            klo.sqrt(),
            khi.sqrt()
        ))
    }

    /// Why the path cannot move on interval i (x = 0 at both ends).
    pub(super) fn explain_stall<P: Path>(
        &mut self,
        prob: &Toppra<'_, P>,
        grid: &[f64],
        i: usize,
    ) -> Error {
        let mut who: Vec<String> = Vec::new();
        // Joint-level explanations from the constraints themselves.
        for &s in &grid[i..=i + 1] {
            prob.path.eval(s, 0, &mut self.q);
            prob.path.eval(s, 1, &mut self.dq);
            prob.path.eval(s, 2, &mut self.ddq);
            let p = PathPoint {
                s,
                q: &self.q,
                dq: &self.dq,
                ddq: &self.ddq,
            };
            for c in &prob.constraints {
                if let Some(why) = c.diagnose(&p) {
                    if !who.contains(&why) {
                        who.push(why);
                    }
                }
            }
        }
        if who.is_empty() {
            for j in [i, i + 1] {
                if self.pts.xhi[j] <= 0.0 {
                    who.push(format!(
                        "'{}' allows only ṡ = 0",
                        self.name_of(prob, self.pts.xhi_by[j])
                    ));
                }
            }
            for k in 0..self.nc {
                // From rest (x = 0), a row a·u ≤ g with a > 0 and g ≤ 0 forbids starting.
                if self.rows_of(i, k).iter().any(|r| r[0] > 0.0 && r[2] <= 0.0) {
                    who.push(format!(
                        "'{}' allows no path acceleration from rest",
                        prob.constraints[k].name()
                    ));
                }
            }
            who.dedup();
        }
        let who = if who.is_empty() {
            "the constraints allow only ṡ = 0".to_string()
        } else {
            who.join("; ")
        };
        Error::Infeasible(format!(
            "the path cannot move between s = {} and s = {}: {who}",
            grid[i],
            grid[i + 1]
        ))
    }
}
