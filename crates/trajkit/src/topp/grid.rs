//! Gridpoints: where along the path TOPP-RA enforces the constraints.
//!
//! Four ways to choose them ([`Gridpoints`]): automatically from a tolerance on the duration
//! (the default), `n` equal intervals, a grid from a tolerance on the path's deviation from its
//! chords, or a list given by the caller. All but the last always contain the path's
//! breakpoints (segment joints of a spline, corners of a piecewise-linear path), where
//! derivatives may jump.
//!
//! # How `Auto` chooses
//! TOPP-RA's duration converges to the continuous optimum T* at first order in the grid
//! spacing h once the grid resolves the path (T(h) − T* ≈ C·h; measured on the Panda suites,
//! see BENCHMARKS.md): with s̈ constant between gridpoints and the limits held everywhere,
//! the acceleration-limited stretches lose O(h) of ṡ². So T(h) − T(h/2) ≈ T(h/2) − T* and,
//! wherever the error falls at least that fast, |T(h) − T(h/2)| bounds the finer grid's error.
//! The solver starts with [`AUTO_START`] equal intervals on every piece between breakpoints
//! (so the grid, and the cost, grow linearly with the number of waypoints), solves, then
//! solves with four times as many, then doubles, until a grid r times finer than the previous
//! one changes the duration by at most (r − 1)·`tolerance` (relative): under the model, that
//! bounds its own error by `tolerance`. It returns the finer solution. On the Panda suites
//! the first check (128 → 512 intervals per piece) settles and the result is 2–5e-5 above
//! the optimum.
//!
//! # Precision contract
//! The returned gridpoints increase strictly, start at `s_start` and end at `s_end` exactly,
//! and contain every breakpoint exactly. Uniform points closer than `1e-9·(s_end − s_start)` to
//! a breakpoint are dropped in its favour. With [`Gridpoints::Chord`], on every interval
//! `[s_i, s_{i+1}]` the midpoint deviation `‖σ(mid) − (σ(s_i) + σ(s_{i+1}))/2‖∞` is at most
//! `tolerance`, unless the interval count hit [`MAX_AUTO_INTERVALS`]. With
//! [`Gridpoints::Auto`] the duration is within `tolerance` (relative) of the converged optimum
//! where the error model above holds; the tests check 1e-4 against grids of 2·10⁵ intervals on
//! the fixture problems and seeded random Panda paths.

use crate::error::{Error, Result};
use crate::Path;

/// Upper bound on the number of intervals [`Gridpoints::Chord`] creates, and on the grids
/// [`Gridpoints::Auto`] tries (it returns the finest grid below the bound when the duration
/// has not settled by then: beyond about 8000 waypoints at the default tolerance).
pub const MAX_AUTO_INTERVALS: usize = 1 << 22;

/// Equal intervals per piece between breakpoints on [`Gridpoints::Auto`]'s first grid.
pub const AUTO_START: usize = 128;

/// How to choose gridpoints.
#[derive(Debug, Clone, PartialEq)]
pub enum Gridpoints {
    /// From a tolerance on the duration (the default, `tolerance: 1e-4`): equal intervals on
    /// every piece between breakpoints, [`AUTO_START`] per piece first, refined until the
    /// duration settles within `tolerance` relative (see the module documentation).
    /// [`Gridpoints::points`] returns the first grid.
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
