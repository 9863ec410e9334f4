//! Refinement between sweeps: the event check of every step (analytic bounds with the knots'
//! tightening, or sampled checks), the cut of steps into new knots, the cut threshold, and
//! the a-posteriori loss estimate.

use super::rows::{is_break, Rows, Scratch, View};
use super::sweep::{sweep, Sweep};
use super::{
    CleanSteps, Constraint, StepBound, BOUND_TOL, CHECK_POINTS, CHECK_TOL, COARSEN, TIGHTEN_CAP,
    TIGHTEN_MARGIN, TIGHTEN_MAX, TIGHTEN_SHARE,
};
use crate::Path;

/// What the event check of one sweep asks for.
pub(super) struct Check {
    /// Per knot step: into how many equal parts to cut it (1: keep).
    pub(super) parts: Vec<usize>,
    /// Per knot: the tightening for the next sweep.
    pub(super) next_eps: Vec<f64>,
    /// Per knot step: the largest analytic bound of a step cut for it.
    pub(super) cut_bound: Vec<f64>,
    /// The largest excess found and where (0 when clean).
    pub(super) worst: (f64, f64),
    /// A step is cut because its bound is above the corrective round's threshold.
    pub(super) forced: bool,
}

/// Whether knot `k` keeps its exact limits (the ends and interior breakpoints).
pub(super) fn fixed_knot(knots: &[f64], breaks: &[f64], k: usize) -> bool {
    k == 0 || k == knots.len() - 1 || is_break(breaks, knots[k])
}

/// The event check of `sweep` between its knots: every output step either bounded
/// analytically by `step_bound` (then the free knots are tightened by the bound, or the step
/// cut where that would cost more than `tmax`; above `cut_above` always cut) or checked at
/// sample points (cut by the excess found). Steps found clean are remembered in `clean`.
#[allow(clippy::too_many_arguments)]
pub(super) fn check_steps<P: Path + ?Sized>(
    path: &P,
    cons: &[Box<dyn Constraint + '_>],
    sweep: &Sweep,
    knots: &[f64],
    breaks: &[f64],
    eps: &[f64],
    step_bound: Option<StepBound<'_>>,
    (tmax, cut_above): (f64, f64),
    clean: &mut CleanSteps,
    sc: &mut Scratch,
) -> Check {
    clean.start_round();
    let n = knots.len() - 1;
    let mut check = Check {
        parts: vec![1usize; n],
        next_eps: eps.to_vec(),
        cut_bound: vec![0.0f64; n],
        worst: (0.0f64, 0.0f64),
        forced: false,
    };
    let (s, x) = (&sweep.s, &sweep.x);
    for j in 0..s.len() - 1 {
        let i = sweep.step[j];
        let d = s[j + 1] - s[j];
        let u = (x[j + 1] - x[j]) / (2.0 * d);
        if let Some(b) = step_bound {
            // The step's u holds at both ends of the knot step it lies in (crossings
            // are inside knot steps): bound over the whole knot step.
            let (k0, k1) = (knots[i], knots[i + 1]);
            let xa = x[j] + 2.0 * u * (k0 - s[j]);
            let xb = x[j] + 2.0 * u * (k1 - s[j]);
            let bound = b(k0, k1, u, xa.max(xb).max(0.0));
            let free = [0, 1].map(|e| !fixed_knot(knots, breaks, i + e));
            if check.bounded(i, s[j], bound, eps, free, (tmax, cut_above)) {
                continue;
            }
        }
        let step = [s[j], s[j + 1], x[j], x[j + 1]];
        if clean.unchanged(step) {
            continue;
        }
        let mut e = CHECK_TOL;
        for f in CHECK_POINTS {
            let si = s[j] + f * d;
            if !(si > s[j] && si < s[j + 1]) {
                continue;
            }
            let xs = (x[j] + 2.0 * u * f * d).max(0.0);
            e = e.max(sc.excess(path, cons, si, u, xs));
        }
        if e > CHECK_TOL {
            if e > check.worst.0 {
                check.worst = (e, s[j]);
            }
            check.parts[i] = check.parts[i].max(parts_for(e));
        } else {
            clean.mark(step);
        }
    }
    check
}

impl Check {
    /// A step at `s` in knot step `i` with the analytic `bound` (`free`: its end knots may be
    /// tightened). Returns whether the bound settled it (accepted, tightened or cut); `false`
    /// for an infinite bound, which leaves the step to the sampled check.
    fn bounded(
        &mut self,
        i: usize,
        s: f64,
        bound: f64,
        eps: &[f64],
        free: [bool; 2],
        (tmax, cut_above): (f64, f64),
    ) -> bool {
        let (e0, e1) = (eps[i], eps[i + 1]);
        let excess = excess_between(bound, e0, e1);
        if excess <= BOUND_TOL && bound <= cut_above {
            return true;
        }
        if !bound.is_finite() {
            return false;
        }
        // A rigorous bound that shrinks with the square of the step: tighten the limits at
        // the step's free knots by it, or cut the step where that would cost more than
        // TIGHTEN_MAX of the limits. No sampling needed.
        if excess > self.worst.0 {
            self.worst = (excess, s);
        }
        let need = if free[0] && free[1] {
            bound
        } else {
            4.0 * bound
        };
        if bound <= tmax && (free[0] || free[1]) {
            for (k, f) in [(i, free[0]), (i + 1, free[1])] {
                if f {
                    self.next_eps[k] = self.next_eps[k].max(need * (1.0 + TIGHTEN_MARGIN));
                }
            }
        } else {
            let m = (need / (0.5 * tmax)).sqrt().ceil();
            self.parts[i] = self.parts[i].max(if m.is_finite() {
                (m as usize).clamp(2, 64)
            } else {
                64
            });
            self.cut_bound[i] = self.cut_bound[i].max(bound);
            self.forced |= bound > cut_above;
        }
        true
    }
}

/// The knots after cutting the steps `check` asks to cut, with their tightening, and per new
/// knot where it was among `knots` (`NEW_KNOT` for a new one) in `origin`.
///
/// The new knots of a cut step start tightened by its bound shrunk by the square of the cut
/// (four times that next to a fixed knot), and so do its free end knots (an untightened end
/// would leave the end parts above the limits: one more round).
pub(super) fn cut_knots(
    knots: &[f64],
    breaks: &[f64],
    check: &mut Check,
    total: usize,
    origin: &mut Vec<usize>,
) -> (Vec<f64>, Vec<f64>) {
    let n = knots.len() - 1;
    let (parts, cut_bound) = (&check.parts, &check.cut_bound);
    let fixed = |k: usize| fixed_knot(knots, breaks, k);
    for i in 0..n {
        if parts[i] > 1 {
            let per = cut_bound[i] / (parts[i] * parts[i]) as f64 * (1.0 + TIGHTEN_MARGIN);
            for k in [i, i + 1] {
                if !fixed(k) {
                    check.next_eps[k] = check.next_eps[k].max(per);
                }
            }
        }
    }
    let next_eps = &check.next_eps;
    let mut next = Vec::with_capacity(total + 1);
    let mut next_e = Vec::with_capacity(total + 1);
    origin.clear();
    for i in 0..n {
        next.push(knots[i]);
        next_e.push(next_eps[i]);
        origin.push(i);
        let per = cut_bound[i] / (parts[i] * parts[i]) as f64 * (1.0 + TIGHTEN_MARGIN);
        for k in 1..parts[i] {
            let si = knots[i] + (knots[i + 1] - knots[i]) * (k as f64 / parts[i] as f64);
            if si > next[next.len() - 1] && si < knots[i + 1] {
                let edge = (k == 1 && fixed(i)) || (k + 1 == parts[i] && fixed(i + 1));
                next.push(si);
                next_e.push(if edge { 4.0 * per } else { per });
                origin.push(super::rows::NEW_KNOT);
            }
        }
    }
    next.push(knots[n]);
    next_e.push(next_eps[n]);
    origin.push(n);
    (next, next_e)
}

/// The cut threshold of bounded steps for this problem (see [`TIGHTEN_MAX`]), from the first
/// sweep: [`TIGHTEN_SHARE`]·(T/T_v)², T the whole duration and T_v the time spent on varying
/// (not closed-form) steps, clamped to [[`TIGHTEN_MAX`], [`TIGHTEN_CAP`]].
///
/// Why: with s̈ constant between knots the duration loss on varying steps is first order in
/// the knot spacing, about C·(T_v/T)·√threshold relative to the whole duration (C measured
/// 0.06–0.15 on Panda paths). Where the varying steps are a small share of the duration (long
/// straight segments, short blends) their loss is diluted by it, and a coarser spacing keeps
/// the same relative loss: C·√TIGHTEN_SHARE ≤ 6e-5 once scaled; paths that spend more than
/// √(TIGHTEN_SHARE/TIGHTEN_MAX) ≈ 28 % of their time on arcs keep [`TIGHTEN_MAX`].
pub(super) fn tighten_max(sweep: &Sweep, constant: &[bool]) -> f64 {
    let (mut all, mut varying) = (0.0, 0.0);
    for (j, dt) in step_times(sweep) {
        all += dt;
        if !constant[sweep.step[j]] {
            varying += dt;
        }
    }
    if varying > 0.0 && all.is_finite() {
        (TIGHTEN_SHARE * (all / varying).powi(2)).clamp(TIGHTEN_MAX, TIGHTEN_CAP)
    } else {
        TIGHTEN_MAX
    }
}

/// The duration of every output step of `sweep` (x linear in s: Δt = 2Δs/(√x₀ + √x₁)), with
/// its index; steps with ṡ = 0 at both ends are skipped.
pub(super) fn step_times(sweep: &Sweep) -> impl Iterator<Item = (usize, f64)> + '_ {
    (0..sweep.s.len() - 1).filter_map(|j| {
        let root = sweep.x[j].max(0.0).sqrt() + sweep.x[j + 1].max(0.0).sqrt();
        (root > 0.0).then(|| (j, 2.0 * (sweep.s[j + 1] - sweep.s[j]) / root))
    })
}

/// A-posteriori estimate of the duration's loss against the converged optimum, relative to
/// the duration of `fine` (the converged sweep on `knots` with `rows`):
/// - **discretization**: the same problem integrated again on every [`COARSEN`]-th knot (m)
///   inside each stretch between fixed knots (breakpoints, the ends; the kept knots' rows
///   are used as they are, with their tightening: no path evaluation, no copy). With s̈
///   constant between knots the loss is first order in the spacing, so
///   T(mh) − T(h) ≈ (m − 1)·(T(h) − T(0)) (Richardson);
/// - **tightening**: the knots' limits are tightened by ε, which slows the motion where they
///   bind by at most about ε/2 of the time: Σ Δt·max(ε₀, ε₁)/2 over the steps.
///
/// `None` where nothing can be dropped (no varying stretch with interior knots) or the coarse
/// integration fails.
#[allow(clippy::too_many_arguments)]
pub(super) fn loss_estimate<P: Path + ?Sized>(
    path: &P,
    cons: &[Box<dyn Constraint + '_>],
    knots: &[f64],
    breaks: &[f64],
    constant: &[bool],
    rows: &Rows,
    fine: &Sweep,
    velocities: (f64, f64),
    sc: &mut Scratch,
) -> Option<f64> {
    let n = knots.len() - 1;
    let mut sub = Vec::with_capacity(n / 2 + 2);
    let mut run = 0usize;
    for k in 0..=n {
        if k == 0 || k == n || is_break(breaks, knots[k]) {
            run = 0;
        } else {
            run += 1;
        }
        if run % COARSEN == 0 {
            sub.push(k);
        }
    }
    if sub.len() == knots.len() {
        return None;
    }
    let coarse: Vec<f64> = sub.iter().map(|&k| knots[k]).collect();
    let coarse_constant: Vec<bool> = sub
        .windows(2)
        .map(|w| w[1] == w[0] + 1 && constant[w[0]])
        .collect();
    let view = View {
        rows,
        map: Some(&sub),
    };
    let wide = sweep(
        path,
        cons,
        &coarse,
        breaks,
        view,
        &coarse_constant,
        velocities,
        sc,
    )
    .ok()?;
    let (mut t_fine, mut tight) = (0.0, 0.0);
    for (j, dt) in step_times(fine) {
        let i = fine.step[j];
        t_fine += dt;
        tight += dt * 0.5 * rows.applied[i].max(rows.applied[i + 1]);
    }
    let t_wide: f64 = step_times(&wide).map(|(_, dt)| dt).sum();
    let est = (t_wide / t_fine - 1.0).max(0.0) / (COARSEN - 1) as f64 + tight / t_fine;
    est.is_finite().then_some(est)
}

/// The largest relative excess over the true limits between two knots whose limits are
/// tightened by `e0` and `e1`, for a step whose excess over the chord is at most `bound`: the
/// chord sits at −(e0·(1 − t) + e1·t) and the excess over it at most 4·bound·t·(1 − t)
/// (t ∈ [0, 1] along the step; the largest value of t(1 − t) is 1/4).
pub(super) fn excess_between(bound: f64, e0: f64, e1: f64) -> f64 {
    if bound <= 0.0 {
        return -e0.min(e1);
    }
    let t = ((4.0 * bound + e0 - e1) / (8.0 * bound)).clamp(0.0, 1.0);
    4.0 * bound * t * (1.0 - t) - e0 * (1.0 - t) - e1 * t
}

/// Into how many equal parts to cut a step whose excess `e` shrinks with the square of its
/// length, to bring it a few times below the tolerance.
pub(super) fn parts_for(e: f64) -> usize {
    let m = (e / (0.5 * CHECK_TOL)).sqrt().ceil();
    if m.is_finite() {
        (m as usize).clamp(2, 64)
    } else {
        64
    }
}

#[cfg(test)]
mod tests {
    use super::{excess_between, tighten_max, Sweep, TIGHTEN_CAP, TIGHTEN_MAX, TIGHTEN_SHARE};

    /// A sweep at ṡ = 1 over steps of the given lengths (one knot step each).
    fn unit_speed(lengths: &[f64]) -> Sweep {
        let mut s = vec![0.0];
        for l in lengths {
            s.push(s[s.len() - 1] + l);
        }
        Sweep {
            x: vec![1.0; s.len()],
            step: (0..lengths.len()).collect(),
            s,
            switching: Vec::new(),
        }
    }

    /// The cut threshold against hand-computed durations (ṡ = 1: time = length).
    #[test]
    fn cut_threshold_scales_with_the_share_of_varying_steps() {
        // 10 s straight, 1 s varying: (11/1)² times the share.
        let t = tighten_max(&unit_speed(&[10.0, 1.0]), &[true, false]);
        assert!((t - TIGHTEN_SHARE * 121.0).abs() < 1e-18, "{t}");
        // Mostly varying: the floor; almost all straight: the cap; nothing varying: the floor.
        assert_eq!(
            tighten_max(&unit_speed(&[1.0, 1.0]), &[true, false]),
            TIGHTEN_MAX
        );
        assert_eq!(
            tighten_max(&unit_speed(&[100.0, 1.0]), &[true, false]),
            TIGHTEN_CAP
        );
        assert_eq!(
            tighten_max(&unit_speed(&[1.0, 1.0]), &[true, true]),
            TIGHTEN_MAX
        );
        // Time, not length: a varying step at ṡ² going 0 → 4 over length 1 lasts
        // 2·1/(0 + 2) = 1 s; a straight one of length 9 at ṡ = 2 lasts 4.5 s.
        let mut sw = unit_speed(&[1.0, 9.0]);
        sw.x = vec![0.0, 4.0, 4.0];
        let t = tighten_max(&sw, &[false, true]);
        assert!((t - TIGHTEN_SHARE * 5.5 * 5.5).abs() < 1e-18, "{t}");
    }

    /// The closed form against a dense scan of 4b·t(1 − t) − e₀(1 − t) − e₁·t over t ∈ [0, 1].
    #[test]
    fn excess_between_matches_a_scan() {
        let b = 1e-5;
        for (e0, e1) in [
            (0.0, 0.0),
            (b, b),
            (0.0, 4.0 * b),
            (0.0, 2.0 * b),
            (3e-6, 4e-5),
            (5e-5, 0.0),
        ] {
            let scan = (0..=100_000)
                .map(|k| {
                    let t = k as f64 / 100_000.0;
                    4.0 * b * t * (1.0 - t) - e0 * (1.0 - t) - e1 * t
                })
                .fold(f64::NEG_INFINITY, f64::max);
            let closed = excess_between(b, e0, e1);
            assert!(
                (closed - scan).abs() < 1e-14,
                "{e0} {e1}: {closed} vs {scan}"
            );
        }
        // Equal tightening by the bound leaves no excess; none either next to an untightened
        // knot when the other takes 4b.
        assert!(excess_between(b, b, b).abs() < 1e-18);
        assert!(excess_between(b, 0.0, 4.0 * b) <= 0.0);
        assert!(excess_between(b, 0.0, b) > 0.0);
    }
}
