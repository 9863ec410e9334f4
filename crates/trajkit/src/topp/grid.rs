//! Gridpoints: where along the path TOPP-RA enforces the constraints.
//!
//! Four ways to choose them ([`Gridpoints`]): automatically from a tolerance on the duration
//! (the default), `n` equal intervals, a grid from a tolerance on the path's deviation from its
//! chords, or a list given by the caller. All but the last always contain the path's
//! breakpoints (segment joints of a spline, corners of a piecewise-linear path), where
//! derivatives may jump.
//!
//! # How `Auto` chooses
//! TOPP-RA's duration converges to the continuous optimum T* as the grid spacing h shrinks,
//! at least at first order once the grid resolves the path (T(h) − T* ≈ C·h^p with p ≈ 1–1.8
//! on the Panda suites, see BENCHMARKS.md): with s̈ constant between gridpoints and the limits
//! held everywhere, the acceleration-limited stretches lose O(h) of ṡ². The error is not
//! spread evenly: it comes from the acceleration-limited ramps and the switching points of the
//! profile, so the grid is graded (module `topp::toppra::auto`):
//! 1. [`AUTO_START`] equal intervals on every piece between breakpoints (so the grid, and the
//!    cost, grow linearly with the number of waypoints), solved;
//! 2. every interval halved and solved again. The time the profile spends on each coarse
//!    interval, before and after, gives its share of the error: under the first-order model
//!    an interval cut into k parts keeps |t − t′|/(k − 1) of error;
//! 3. while these estimates sum to more than `tolerance`·T: each interval j is cut into
//!    k_j ∝ ∛e_j parts (the fewest intervals that bring Σ e_j/k_j², the second-order
//!    prediction, to half of `tolerance`·T), and into enough parts that none takes more than
//!    T/1000 (the jerk stages need that resolution in time; see `toppra/auto.rs`), solved, and
//!    its estimate renewed from the change as in step 2 (an interval not cut keeps its
//!    estimate).
//!
//! The grid is accepted on the first-order estimate, the conservative one; the second-order
//! model only chooses the counts. Every grid keeps the breakpoints, so the between-gridpoint
//! guarantee holds on all of them.
//!
//! Why two models: the guaranteed duration's error is the sum of two parts (measured on the
//! range-repaired standard problem against 2·10⁵ intervals): the unguaranteed solve's error,
//! first order and not local (refining one interval moves time between its neighbours, with
//! both signs), and the cost of the guarantee, O(h²), local and positive (x linear in s cannot
//! follow a curved limit inside an interval; rows at each interval's exact worst point instead
//! of the sufficient rows give nearly the same durations). The second dominates on coarse
//! grids (288 equal intervals: 9.8e-4 of 1.2e-3) and is about 40 % on the returned grid
//! (1.3e-5 of 3.7e-5); their mix is the "order 1.3–1.8" seen on fine grids. The first-order
//! estimate of the returned grid was 1.24× to 6.8× its measured error on the long suite (44
//! problems). Estimates that credit the faster convergence were measured and rejected
//! (BENCHMARKS.md): an order fitted to three grids and a fixed order of 1.25 both let errors
//! above 1e-4 through.
//!
//! # Cost
//! On the standard problem (6 pieces) the three solves have 288, 576 and 2331 intervals,
//! 3195 in all (before: 768 + 3072 equal intervals); on the range-repaired path of the
//! `toppra_default/std7` benchmark 288 + 576 + 2234 = 3098 against 3840. Each solve is linear
//! in its grid; the grids are linear in the number of pieces (the benchmark's random paths:
//! 450, 535 and 537 intervals solved per waypoint at 10, 100 and 1000 waypoints). Memory is
//! linear too: on a 7-joint path the workspace writes about 0.8 kB per gridpoint (the rows at
//! the gridpoints and between them, 336 and 344 bytes), plus 336 bytes of Taylor data per
//! gridpoint on grids up to 50 000 gridpoints (`topp::between`); up to 64 MB of it is kept for
//! the next solve on the thread, so longer grids pay fresh pages on every solve.
//!
//! # Precision contract
//! The returned gridpoints increase strictly, start at `s_start` and end at `s_end` exactly,
//! and contain every breakpoint exactly. Uniform points closer than `1e-9·(s_end − s_start)` to
//! a breakpoint are dropped in its favour. With [`Gridpoints::Chord`], on every interval
//! `[s_i, s_{i+1}]` the midpoint deviation `‖σ(mid) − (σ(s_i) + σ(s_{i+1}))/2‖∞` is at most
//! `tolerance`, unless the interval count hit [`MAX_AUTO_INTERVALS`]. With
//! [`Gridpoints::Auto`] the duration is within `tolerance` (relative) of the converged optimum
//! where the error model above holds, and never below it (every grid's profile is feasible);
//! the tests check 1e-4 against grids of 2·10⁵ intervals on the fixture problems and seeded
//! random Panda paths (measured 6.0e-6 to 7.4e-5 above; the first-order estimate that
//! accepted each grid was 1.24× to 6.8× the measured error).

use crate::error::{Error, Result};
use crate::Path;

/// Upper bound on the number of intervals [`Gridpoints::Chord`] creates, and on the grids
/// [`Gridpoints::Auto`] tries (it returns the finest grid below the bound when the estimated
/// error is not within the tolerance by then).
pub const MAX_AUTO_INTERVALS: usize = 1 << 22;

/// Equal intervals per piece between breakpoints on [`Gridpoints::Auto`]'s first grid (the
/// second halves them; later ones are graded).
pub const AUTO_START: usize = 48;

/// How to choose gridpoints.
#[derive(Debug, Clone, PartialEq)]
pub enum Gridpoints {
    /// From a tolerance on the duration (the default, `tolerance: 1e-4`): equal intervals on
    /// every piece between breakpoints, [`AUTO_START`] per piece first, halved, then refined
    /// where the duration is sensitive until the estimated error is within `tolerance`
    /// relative (see the module documentation). [`Gridpoints::points`] returns the first grid.
    Auto {
        /// Relative duration tolerance, > 0.
        tolerance: f64,
    },
    /// `n` equal intervals (1 ≤ n ≤ 2²⁶) over the path interval, plus the path's breakpoints.
    Uniform(usize),
    /// At least 100 equal intervals plus the breakpoints, then each interval halved until the
    /// path's midpoint deviation from the chord is at most `tolerance` (joint units).
    Chord {
        /// Largest midpoint deviation from the chord allowed, > 0.
        tolerance: f64,
    },
    /// Exactly these points (strictly increasing, from `s_start` to `s_end`).
    Given(Vec<f64>),
}

impl Gridpoints {
    /// The gridpoints for `path`.
    pub fn points<P: Path + ?Sized>(&self, path: &P) -> Result<Vec<f64>> {
        let (a, b) = path.interval();
        match self {
            Gridpoints::Uniform(n) => {
                if *n == 0 {
                    return Err(Error::InvalidValue {
                        field: "gridpoint interval count".into(),
                        value: 0.0,
                        reason: "is not at least 1",
                    });
                }
                if *n > 1 << 26 {
                    return Err(Error::InvalidValue {
                        field: "gridpoint interval count".into(),
                        value: *n as f64,
                        reason: "is too large (at most 67108864)",
                    });
                }
                Ok(uniform_with_breaks(a, b, *n, &path.breakpoints()))
            }
            Gridpoints::Auto { tolerance } => {
                crate::error::positive(|| "gridpoint tolerance".into(), *tolerance)?;
                Ok(per_piece(&piece_breaks(path), AUTO_START))
            }
            Gridpoints::Chord { tolerance } => {
                crate::error::positive(|| "gridpoint chord tolerance".into(), *tolerance)?;
                Ok(chord(path, *tolerance))
            }
            Gridpoints::Given(pts) => {
                check_given(pts, a, b)?;
                Ok(pts.clone())
            }
        }
    }
}

fn check_given(pts: &[f64], a: f64, b: f64) -> Result<()> {
    if pts.len() < 2 {
        return Err(Error::DimensionMismatch {
            what: "gridpoint count".into(),
            expected: 2,
            found: pts.len(),
        });
    }
    if pts[0] != a {
        return Err(Error::InvalidValue {
            field: "first gridpoint".into(),
            value: pts[0],
            reason: "is not the start of the path interval",
        });
    }
    if pts[pts.len() - 1] != b {
        return Err(Error::InvalidValue {
            field: "last gridpoint".into(),
            value: pts[pts.len() - 1],
            reason: "is not the end of the path interval",
        });
    }
    for i in 1..pts.len() {
        if pts[i].partial_cmp(&pts[i - 1]) != Some(std::cmp::Ordering::Greater)
            || !pts[i].is_finite()
        {
            return Err(Error::InvalidValue {
                field: format!("gridpoint {i}"),
                value: pts[i],
                reason: "does not increase",
            });
        }
    }
    Ok(())
}

fn uniform_with_breaks(a: f64, b: f64, n: usize, breaks: &[f64]) -> Vec<f64> {
    let len = b - a;
    let tol = 1e-9 * len;
    // (point, is_breakpoint); the two ends count as breakpoints.
    let mut cand: Vec<(f64, bool)> = breaks
        .iter()
        .copied()
        .filter(|&x| x > a + tol && x < b - tol)
        .map(|x| (x, true))
        .collect();
    cand.extend((1..n).map(|i| (a + len * (i as f64 / n as f64), false)));
    cand.sort_by(|p, q| p.0.total_cmp(&q.0));
    cand.push((b, true));
    let mut out: Vec<(f64, bool)> = vec![(a, true)];
    for (x, brk) in cand {
        let (last, last_brk) = out[out.len() - 1];
        if x - last > tol {
            out.push((x, brk));
        } else if brk && !last_brk {
            // A breakpoint replaces a uniform point just before it.
            let k = out.len() - 1;
            out[k] = (x, true);
        }
    }
    out.into_iter().map(|p| p.0).collect()
}

/// The path's breakpoints inside its interval, with both ends, increasing, none closer than
/// `1e-9·(s_end − s_start)` to the previous one.
pub(crate) fn piece_breaks<P: Path + ?Sized>(path: &P) -> Vec<f64> {
    let (a, b) = path.interval();
    uniform_with_breaks(a, b, 1, &path.breakpoints())
}

/// `m` equal intervals on every piece between consecutive `breaks`.
pub(crate) fn per_piece(breaks: &[f64], m: usize) -> Vec<f64> {
    let m = m.max(1);
    let mut out = Vec::with_capacity((breaks.len() - 1) * m + 1);
    for w in breaks.windows(2) {
        out.push(w[0]);
        for k in 1..m {
            let s = w[0] + (w[1] - w[0]) * (k as f64 / m as f64);
            if s > out[out.len() - 1] && s < w[1] {
                out.push(s);
            }
        }
    }
    out.push(breaks[breaks.len() - 1]);
    out
}

/// `grid` with interval i cut into `parts[i]` equal intervals (`parts[i]` ≤ 1: kept whole).
/// Every point of `grid` stays; a cut closer to a neighbour than rounding allows is dropped.
pub(crate) fn subdivide(grid: &[f64], parts: &[usize]) -> Vec<f64> {
    let n = grid.len() - 1;
    let total: usize = parts.iter().map(|&m| m.max(1)).sum();
    let mut next = Vec::with_capacity(total + 1);
    for i in 0..n {
        next.push(grid[i]);
        let m = parts[i];
        for k in 1..m {
            let s = grid[i] + (grid[i + 1] - grid[i]) * (k as f64 / m as f64);
            if s > next[next.len() - 1] && s < grid[i + 1] {
                next.push(s);
            }
        }
    }
    next.push(grid[n]);
    next
}

fn chord<P: Path + ?Sized>(path: &P, tolerance: f64) -> Vec<f64> {
    let (a, b) = path.interval();
    let mut pts = uniform_with_breaks(a, b, 100, &path.breakpoints());
    let dim = path.dim();
    let (mut qa, mut qb, mut qm) = (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]);
    loop {
        let mut next = Vec::with_capacity(pts.len() * 2);
        let mut split = false;
        for w in pts.windows(2) {
            next.push(w[0]);
            let mid = 0.5 * (w[0] + w[1]);
            path.eval(w[0], 0, &mut qa);
            path.eval(w[1], 0, &mut qb);
            path.eval(mid, 0, &mut qm);
            let dev = (0..dim)
                .map(|j| (qm[j] - 0.5 * (qa[j] + qb[j])).abs())
                .fold(0.0, f64::max);
            if dev > tolerance && mid > w[0] && mid < w[1] && pts.len() < MAX_AUTO_INTERVALS {
                next.push(mid);
                split = true;
            }
        }
        next.push(pts[pts.len() - 1]);
        pts = next;
        if !split || pts.len() > MAX_AUTO_INTERVALS {
            return pts;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Parabola;
    impl Path for Parabola {
        fn dim(&self) -> usize {
            1
        }
        fn interval(&self) -> (f64, f64) {
            (0.0, 2.0)
        }
        fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
            out[0] = match order {
                0 => s * s,
                1 => 2.0 * s,
                2 => 2.0,
                _ => 0.0,
            };
        }
        fn breakpoints(&self) -> Vec<f64> {
            vec![0.0, 0.3, 1.0 + 1e-12, 2.0]
        }
    }

    #[test]
    fn uniform_contains_breakpoints() {
        let g = Gridpoints::Uniform(4).points(&Parabola).unwrap();
        assert_eq!(g, vec![0.0, 0.3, 0.5, 1.0 + 1e-12, 1.5, 2.0]);
        let g = Gridpoints::Uniform(1).points(&Parabola).unwrap();
        assert_eq!(g, vec![0.0, 0.3, 1.0 + 1e-12, 2.0]);
        assert!(Gridpoints::Uniform(0).points(&Parabola).is_err());
        let e = Gridpoints::Uniform(usize::MAX)
            .points(&Parabola)
            .unwrap_err();
        assert!(e.to_string().contains("too large"), "{e}");
    }

    #[test]
    fn auto_starts_with_equal_intervals_per_piece() {
        let g = Gridpoints::Auto { tolerance: 1e-4 }
            .points(&Parabola)
            .unwrap();
        // Three pieces ([0, 0.3], [0.3, 1 + 1e-12], [1 + 1e-12, 2]), AUTO_START intervals each.
        assert_eq!(g.len(), 3 * AUTO_START + 1);
        for b in [0.0, 0.3, 1.0 + 1e-12, 2.0] {
            assert!(g.contains(&b));
        }
        assert!(g.windows(2).all(|w| w[1] > w[0]));
        let h0 = g[1] - g[0];
        assert!((h0 - 0.3 / AUTO_START as f64).abs() < 1e-15);
        assert!(Gridpoints::Auto { tolerance: 0.0 }
            .points(&Parabola)
            .is_err());
    }

    #[test]
    fn chord_meets_tolerance() {
        // For s², the midpoint deviation on an interval of length h is h²/4.
        let g = Gridpoints::Chord { tolerance: 1e-6 }
            .points(&Parabola)
            .unwrap();
        for w in g.windows(2) {
            let h = w[1] - w[0];
            assert!(h * h / 4.0 <= 1e-6 * (1.0 + 1e-9), "{h}");
        }
        assert!(g.contains(&0.3));
    }

    #[test]
    fn given_points_are_validated() {
        assert!(Gridpoints::Given(vec![0.0, 1.0, 2.0])
            .points(&Parabola)
            .is_ok());
        let e = Gridpoints::Given(vec![0.0, 1.0, 1.0, 2.0])
            .points(&Parabola)
            .unwrap_err();
        assert!(e.to_string().contains("gridpoint 2 = 1"), "{e}");
        assert!(Gridpoints::Given(vec![0.1, 2.0]).points(&Parabola).is_err());
    }
}
