//! The grid: where along the path the planner places its gridpoints.
//!
//! Transitions of the jerk-limited optimum (the path acceleration ramping between the
//! TOPP-RA optimum's constant values) take a fixed *time*, of the order of an acceleration
//! change divided by the jerk limit, so the grid is laid out evenly in time along the raw
//! TOPP-RA timing: gridpoint k sits where TOPP-RA is at time k·T/steps. The path's
//! breakpoints are always gridpoints (σ‴ jumps there and the certification needs one smooth
//! piece per interval). The first and last intervals, where the planner starts and ends with
//! constant path jerk in time, are subdivided geometrically (halved `levels` times), so that
//! the rest pieces are short compared with the ramps they begin and end.
//!
//! The duration tolerance chooses `steps` ([`super::JerkOptions::tolerance`]): the solve is
//! repeated with twice as many steps until two successive durations agree within it.

use crate::topp::rescale::TimeLaw;
use crate::topp::PhaseProfile as Profile;

/// Gridpoints evenly spaced in the time of `law` (`steps` intervals), with the path's
/// `breaks` and a geometric refinement of `levels` halvings at both ends.
pub(crate) fn time_grid(law: &Profile, breaks: &[f64], steps: usize, levels: usize) -> Vec<f64> {
    let s = law.gridpoints();
    let (a, b) = (s[0], s[s.len() - 1]);
    let big_t = law.duration();
    let mut pts: Vec<f64> = Vec::with_capacity(steps + breaks.len() + 2 * levels + 2);
    for k in 0..=steps {
        let t = big_t * k as f64 / steps as f64;
        pts.push(law.eval(t)[0]);
    }
    pts.extend(breaks.iter().copied().filter(|&x| x > a && x < b));
    pts.push(a);
    pts.push(b);
    pts.sort_by(f64::total_cmp);
    let tol = 1e-12 * (b - a);
    pts.dedup_by(|x, y| (*x - *y).abs() <= tol);
    // Keep the exact ends and the breakpoints (dedup kept the first of each close pair).
    pts[0] = a;
    let last = pts.len() - 1;
    pts[last] = b;
    if pts.len() < 4 {
        // At least three intervals.
        pts.extend((1..3).map(|k| a + (b - a) * k as f64 / 3.0));
        pts.sort_by(f64::total_cmp);
        pts.dedup_by(|x, y| (*x - *y).abs() <= tol);
    }
    // Geometric refinement of the two end intervals.
    let mut head = Vec::with_capacity(levels);
    let h0 = pts[1] - pts[0];
    for k in (1..=levels).rev() {
        head.push(a + h0 * 0.5f64.powi(k as i32));
    }
    let n = pts.len();
    let h1 = pts[n - 1] - pts[n - 2];
    let mut tail = Vec::with_capacity(levels);
    for k in 1..=levels {
        tail.push(b - h1 * 0.5f64.powi(k as i32));
    }
    let mut out = Vec::with_capacity(n + 2 * levels);
    out.push(a);
    out.extend(head);
    out.extend_from_slice(&pts[1..n - 1]);
    out.extend(tail);
    out.push(b);
    out.dedup_by(|x, y| *x <= *y);
    out
}
