//! One TOPP-RA stage as half-planes in (u, x_i) read straight from the gridpoint rows, the
//! greedy forward step on them, and the record of steps already checked between gridpoints.
//! Shared with the numerical-integration solver (`topp/ni`).

use crate::topp::lp;

/// Steps (s_i, s_{i+1}, x_i, x_{i+1}) found within the limits by the last check between
/// gridpoints, in path order. A step unchanged since (same ends, x within 1e-9 relative) is
/// not checked again.
#[derive(Default)]
pub(crate) struct CleanSteps {
    previous: Vec<[f64; 4]>,
    current: Vec<[f64; 4]>,
    p: usize,
}

impl CleanSteps {
    /// Starts a check round: the steps marked in the last round become the reference.
    pub(crate) fn start_round(&mut self) {
        self.previous = std::mem::take(&mut self.current);
        self.p = 0;
    }

    /// Whether `step` was found clean in the last round (it is then marked clean again).
    /// Steps must be asked in path order.
    pub(crate) fn unchanged(&mut self, step: [f64; 4]) -> bool {
        let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
        while self.p < self.previous.len() && self.previous[self.p][0] < step[0] {
            self.p += 1;
        }
        if let Some(c) = self.previous.get(self.p) {
            if c[0] == step[0] && c[1] == step[1] && same(c[2], step[2]) && same(c[3], step[3]) {
                self.current.push(step);
                return true;
            }
        }
        false
    }

    /// Records `step` as found within the limits.
    pub(crate) fn mark(&mut self, step: [f64; 4]) {
        self.current.push(step);
    }
}

/// The half-planes of one stage, computed on the fly from the gridpoint rows: the rows at s_i,
/// the rows at s_{i+1} with x_{i+1} = x + 2Δu substituted, rows of interior points already in
/// (u, x_i) (added where the check between gridpoints found an excess), and
/// x_{i+1} ∈ [klo, khi].
pub(crate) struct Stage<'a> {
    pub(crate) here: &'a [[f64; 3]],
    pub(crate) next: &'a [[f64; 3]],
    pub(crate) mid: &'a [[f64; 3]],
    pub(crate) two_delta: f64,
    pub(crate) khi: f64,
    pub(crate) klo: f64,
}

impl lp::HalfPlanes for Stage<'_> {
    #[inline]
    fn count(&self) -> usize {
        self.here.len() + self.next.len() + self.mid.len() + 2
    }
    #[inline]
    fn get(&self, k: usize) -> [f64; 3] {
        let h = self.here.len();
        let n = self.next.len();
        let m = self.mid.len();
        if k < h {
            self.here[k]
        } else if k < h + n {
            let [a, b, g] = self.next[k - h];
            [a + self.two_delta * b, b, g]
        } else if k < h + n + m {
            self.mid[k - h - n]
        } else if k == h + n + m {
            [self.two_delta, 1.0, self.khi]
        } else {
            [-self.two_delta, -1.0, -self.klo]
        }
    }
    /// Scans the row slices directly (the solver's hot loop).
    #[inline]
    fn first_violated(&self, from: usize, v: [f64; 2], tol: f64) -> Option<usize> {
        let h = self.here.len();
        let n = self.next.len();
        let m = self.mid.len();
        if from < h {
            for (j, &r) in self.here[from..].iter().enumerate() {
                if lp::violates(r, v, tol) {
                    return Some(from + j);
                }
            }
        }
        let start = from.max(h) - h;
        if start < n {
            for (j, &[a, b, g]) in self.next[start..].iter().enumerate() {
                if lp::violates([a + self.two_delta * b, b, g], v, tol) {
                    return Some(h + start + j);
                }
            }
        }
        let start = from.max(h + n) - h - n;
        if start < m {
            for (j, &r) in self.mid[start..].iter().enumerate() {
                if lp::violates(r, v, tol) {
                    return Some(h + n + start + j);
                }
            }
        }
        (from.max(h + n + m)..h + n + m + 2).find(|&k| lp::violates(self.get(k), v, tol))
    }
}

/// The largest constant path acceleration u ≤ `cap` on an interval of length Δ (`two_delta` =
/// 2Δ) from x = `x` at its start, holding the rows `here` at the start (a·u + b·x ≤ g) and
/// `next` at the end, where x becomes x + 2Δu. Only rows that bound u from above are used.
pub(crate) fn largest_step(
    here: &[[f64; 3]],
    next: &[[f64; 3]],
    two_delta: f64,
    x: f64,
    cap: f64,
) -> f64 {
    let mut u = cap;
    // rhs/a < u ⇔ rhs < u·a for a > 0: divide only where the bound improves.
    let mut bound = |a: f64, rhs: f64| {
        if a > 0.0 && rhs < u * a {
            let v = rhs / a;
            if v < u {
                u = v;
            }
        }
    };
    for &[a, b, g] in here {
        bound(a, g - b * x);
    }
    for &[a, b, g] in next {
        bound(a + two_delta * b, g - b * x);
    }
    u
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use crate::topp::lp::BOX;

    /// The stage's direct row scan finds the same violated rows as the generic one, so the
    /// programs solved through it give the same optimum as on the materialized rows.
    #[test]
    fn stage_scan_equals_materialized_rows() {
        let mut rng = SplitMix64::new(5);
        for _ in 0..2000 {
            let row = |rng: &mut SplitMix64| {
                [
                    rng.uniform(-3.0, 3.0),
                    rng.uniform(-3.0, 3.0),
                    rng.uniform(-1.0, 4.0),
                ]
            };
            let here: Vec<[f64; 3]> = (0..rng.below(6)).map(|_| row(&mut rng)).collect();
            let next: Vec<[f64; 3]> = (0..rng.below(6)).map(|_| row(&mut rng)).collect();
            let mid: Vec<[f64; 3]> = (0..rng.below(4)).map(|_| row(&mut rng)).collect();
            let stage = Stage {
                here: &here,
                next: &next,
                mid: &mid,
                two_delta: rng.uniform(0.001, 0.5),
                khi: rng.uniform(0.5, 3.0),
                klo: rng.uniform(-0.5, 0.4),
            };
            let rows: Vec<[f64; 3]> = (0..lp::HalfPlanes::count(&stage))
                .map(|k| lp::HalfPlanes::get(&stage, k))
                .collect();
            let v = [rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)];
            for from in 0..=rows.len() {
                assert_eq!(
                    lp::HalfPlanes::first_violated(&stage, from, v, 1e-10),
                    lp::HalfPlanes::first_violated(rows.as_slice(), from, v, 1e-10)
                );
            }
            let hint = [rng.below(rows.len() as u64 + 1) as usize, BOX];
            for c in [[0.0, 1.0], [0.0, -1.0], [1.0, 0.3]] {
                let a = lp::maximize(c, &stage, [-5.0, 0.0], [5.0, 5.0], hint, 1e-10);
                let b = lp::maximize(c, rows.as_slice(), [-5.0, 0.0], [5.0, 5.0], hint, 1e-10);
                assert_eq!(a, b);
            }
        }
    }
}
