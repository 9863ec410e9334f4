//! The grid: where along the path the planner places its gridpoints.
//!
//! The grid is laid out evenly in the *time* of a reference timing (the raw TOPP-RA timing
//! for the first grid, the previous grid's jerk-limited solution for the next ones): a
//! gridpoint where the reference is at time k·T/steps. Evenly in time puts the points where
//! the motion needs them — transitions of the path acceleration take a time of the order of
//! an acceleration change over the jerk limit, and the discretization error of an interval is
//! of second order in its duration ([`super::shape`]). The path's breakpoints are always
//! gridpoints (σ‴ jumps there and the certification needs one smooth piece per interval); a
//! time-even point closer to a breakpoint than a fifth of its step gives way to it. The first
//! and last intervals, where the planner starts and ends with constant path jerk in time, are
//! subdivided geometrically (halved `levels` times) so that the rest pieces are short
//! compared with the ramps they begin and end.
//!
//! How many steps: [`super::JerkOptions::tolerance`] chooses (see the driver in
//! [`super`]).

/// A grid: gridpoints and whether each is a breakpoint of the path.
pub(crate) struct Grid {
    pub(crate) s: Vec<f64>,
    pub(crate) brk: Vec<bool>,
}

/// s at time `t` of a reference given by its gridpoints `s` and their times `t` (linear in
/// between).
fn s_at(rs: &[f64], rt: &[f64], t: f64) -> f64 {
    let i = crate::traj::find_piece(rt, t);
    let (t0, t1) = (rt[i], rt[i + 1]);
    let f = if t1 > t0 {
        ((t - t0) / (t1 - t0)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    rs[i] + f * (rs[i + 1] - rs[i])
}

/// Gridpoints evenly spaced in the time of the reference (`rs`, `rt`: its gridpoints and the
/// times it reaches them, from 0), `steps` intervals, with the path's `breaks` and a
/// geometric refinement of `levels` halvings at both ends.
pub(crate) fn time_grid(
    rs: &[f64],
    rt: &[f64],
    breaks: &[f64],
    steps: usize,
    levels: usize,
) -> Grid {
    let (a, b) = (rs[0], rs[rs.len() - 1]);
    let big_t = rt[rt.len() - 1];
    let mut even: Vec<f64> = (0..=steps)
        .map(|k| s_at(rs, rt, big_t * k as f64 / steps as f64))
        .collect();
    even[0] = a;
    even[steps] = b;
    even.dedup_by(|x, y| *x <= *y);
    let inner: Vec<f64> = breaks.iter().copied().filter(|&x| x > a && x < b).collect();
    let keep = keep_off_breaks(&even, &inner);
    let mut pts: Vec<(f64, bool)> = even
        .iter()
        .zip(&keep)
        .filter(|(_, &k)| k)
        .map(|(&s, _)| (s, false))
        .chain(inner.iter().map(|&s| (s, true)))
        .collect();
    pts.sort_by(|p, q| p.0.total_cmp(&q.0));
    pts.dedup_by(|x, y| {
        if x.0 <= y.0 {
            y.1 |= x.1;
            true
        } else {
            false
        }
    });
    if pts.len() < 4 {
        // At least three intervals.
        let extra: Vec<(f64, bool)> = (1..3)
            .map(|k| (a + (b - a) * k as f64 / 3.0, false))
            .collect();
        pts.extend(extra);
        pts.sort_by(|p, q| p.0.total_cmp(&q.0));
        pts.dedup_by(|x, y| x.0 <= y.0);
    }
    let mut out = refine_ends(&pts, a, b, levels);
    out.dedup_by(|x, y| {
        if x.0 <= y.0 {
            y.1 |= x.1;
            true
        } else {
            false
        }
    });
    Grid {
        s: out.iter().map(|p| p.0).collect(),
        brk: out.iter().map(|p| p.1).collect(),
    }
}

/// Which time-even points to keep: not those too close to an inner breakpoint (never the
/// ends).
fn keep_off_breaks(even: &[f64], inner: &[f64]) -> Vec<bool> {
    let mut keep = vec![true; even.len()];
    for &x in inner {
        let k = even.partition_point(|&e| e < x);
        for j in [k.wrapping_sub(1), k] {
            if j == 0 || j + 1 >= even.len() {
                continue;
            }
            let h = (even[j + 1] - even[j - 1]) * 0.5;
            if (even[j] - x).abs() < 0.2 * h {
                keep[j] = false;
            }
        }
    }
    keep
}

/// The points `pts` (sorted, from a to b) with the first and last intervals refined
/// geometrically: `levels` halvings towards each end.
fn refine_ends(pts: &[(f64, bool)], a: f64, b: f64, levels: usize) -> Vec<(f64, bool)> {
    let n = pts.len();
    let (h0, h1) = (pts[1].0 - a, b - pts[n - 2].0);
    let mut out: Vec<(f64, bool)> = Vec::with_capacity(n + 2 * levels);
    out.push((a, false));
    for k in (1..=levels).rev() {
        out.push((a + h0 * 0.5f64.powi(k as i32), false));
    }
    out.extend_from_slice(&pts[1..n - 1]);
    for k in 1..=levels {
        out.push((b - h1 * 0.5f64.powi(k as i32), false));
    }
    out.push((b, false));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_even_with_breaks_and_end_refinement() {
        // Reference: constant speed 1 over [0, 10].
        let g = time_grid(&[0.0, 10.0], &[0.0, 10.0], &[0.0, 3.05, 7.5, 10.0], 10, 3);
        // The breakpoints are kept and flagged; 3.0 gives way to 3.05.
        assert!(g.s.contains(&3.05) && g.s.contains(&7.5) && !g.s.contains(&3.0));
        for (s, b) in g.s.iter().zip(&g.brk) {
            assert_eq!(*b, *s == 3.05 || *s == 7.5, "{s}");
        }
        assert!(g.s.windows(2).all(|w| w[1] > w[0]));
        assert_eq!(&g.s[..5], &[0.0, 0.125, 0.25, 0.5, 1.0]);
        assert_eq!(g.s[g.s.len() - 1], 10.0);
    }
}
