//! The choice of the waypoint velocities (see the module docs of `otg::waypoints` for the
//! method): stop at every waypoint, tangent directions, coordinate descent with a
//! golden-section search on each waypoint's speed scale.
//!
//! Every evaluation solves whole sections with the generator into buffers the planner
//! reuses: the search rates candidate velocities with the synchronization's bounded mode
//! (`sync::calculate` with `Search::Bounded`: no bisection, no durations past the last
//! candidate, never shorter than the full solve; it returns the duration alone and builds
//! only the profiles that decide it), the reference (stopping at every waypoint)
//! and the final trajectory are full solves (`Search::Full`), each chosen section once more into its
//! own storage. A full solve is never longer than the bounded rating the search kept (to
//! round-off), so the result is never longer than the search believed; the final check
//! against stopping at every waypoint uses the built durations.
//!
//! With a calculation budget (`budget.rs`) the reference sections are kept as built, every
//! section solve is timed, the search checks the clock before every rating and stops when
//! what is left would not pay for the final build (estimated from those times) and the tail,
//! each build section's own deadline leaves what the later ones need, and a build that runs
//! out of time (or comes out longer) gives way to the kept reference: the result is the best
//! valid motion found in time.

use super::budget::Clock;
use super::trajectory::WaypointTrajectory;
use super::{section_inputs, Waypoints};
use crate::num::clamp_in;
use crate::otg::input::DynInputParameter;
use crate::otg::result::OtgError;
use crate::otg::sync::{calculate, calculate_status, Scratch, Search, Spare};
use crate::otg::trajectory::{DofTrajectory, DynTrajectory, OtgTrajectory};

/// Golden-section evaluations per waypoint in the first sweep (whole scale range) and in the
/// second (a window around the first sweep's choice).
const EVALS: [usize; 2] = [7, 4];
/// Half-width of the second sweep's window, relative to the first sweep's scale.
const WINDOW: f64 = 0.3;
/// The largest speed scale tried when no velocity limit bounds it (the direction is built
/// from the average velocities of stopping at every waypoint; a rest-to-rest motion peaks at
/// about twice its average).
const SCALE_CAP: f64 = 4.0;
/// The inverse golden ratio.
const INV_PHI: f64 = 0.618_033_988_749_894_8;
/// What the final build is expected to cost, relative to the latest measured solve of each
/// section (the search's ratings give no duration past the first success and build only the
/// profiles that decide it; a full solve builds every profile and bisects).
const BUILD_FACTOR: f64 = 2.0;
/// The share of the budget the search and the final build leave unused (with a budget): the
/// planner's own work after its deadline (one section's closed-form step 1 and step-2 attempt,
/// the end of a bisection, assembling the kept motion) must fit in it.
const TAIL: f64 = 0.05;

/// The limits, minimum duration and options of section `s` (the input's, with the section's
/// own limits where given); the boundary states are the input's.
pub(crate) fn section_template(
    input: &DynInputParameter,
    waypoints: &Waypoints,
    s: usize,
) -> DynInputParameter {
    let mut si = input.clone();
    if let Some(v) = &waypoints.per_section_max_velocity {
        si.max_velocity.clone_from(&v[s]);
    }
    if let Some(v) = &waypoints.per_section_max_acceleration {
        si.max_acceleration.clone_from(&v[s]);
    }
    if let Some(v) = &waypoints.per_section_max_jerk {
        si.max_jerk.clone_from(&v[s]);
    }
    if let Some(d) = &waypoints.per_section_minimum_duration {
        si.options.minimum_duration = Some(d[s]);
    }
    si
}

/// The search state: one input per section, the generator's buffers, and per waypoint the
/// direction, the largest scale and the chosen scale.
pub(super) struct Planner<'a> {
    waypoints: &'a Waypoints,
    dt: f64,
    n: usize,
    m: usize,
    secs: Vec<DynInputParameter>,
    dofs: Vec<DofTrajectory>,
    scratch: Vec<Scratch>,
    spare: Vec<Spare>,
    dir: Vec<f64>,
    cap: Vec<f64>,
    scale: Vec<f64>,
    dur: Vec<f64>,
    /// The calculation budget, when one is given.
    clock: Option<Clock>,
    /// Microseconds of the latest solve or rating of every section (with a budget): the
    /// estimate of what the final build costs.
    cost: Vec<f64>,
    /// Microseconds per section that the reference spent outside the generator (keeping the
    /// section's trajectory): the final build spends them too.
    keep_us: f64,
    /// While building (with a budget): the microseconds the sections after the one being
    /// solved are expected to need, kept out of its own budget.
    later_us: Option<f64>,
    /// The longest section solve so far in microseconds (with a budget): what the search
    /// expects its next step to cost.
    step_us: f64,
    /// Whether the budget cut the planning (or a section's own search) short.
    interrupted: bool,
}

impl<'a> Planner<'a> {
    /// A planner for a validated problem, every waypoint velocity zero, with the
    /// calculation budget `clock` when one is given.
    pub(super) fn new(
        input: &DynInputParameter,
        waypoints: &'a Waypoints,
        dt: f64,
        clock: Option<Clock>,
    ) -> Self {
        let n = input.dof();
        let m = waypoints.intermediate_positions.len();
        Planner {
            waypoints,
            dt,
            n,
            m,
            secs: section_inputs(input, waypoints, &vec![0.0; m * n]),
            dofs: vec![DofTrajectory::default(); n],
            scratch: vec![Scratch::default(); n],
            spare: vec![None; n],
            dir: vec![0.0; m * n],
            cap: vec![0.0; m],
            scale: vec![0.0; m],
            dur: vec![0.0; m + 1],
            clock,
            cost: vec![0.0; m + 1],
            keep_us: 0.0,
            later_us: None,
            step_us: 0.0,
            interrupted: false,
        }
    }

    /// Sets waypoint `w`'s velocity to its direction times `s` in both adjacent sections.
    fn set_scale(&mut self, w: usize, s: f64) {
        let n = self.n;
        let (before, after) = self.secs.split_at_mut(w + 1);
        let d = &self.dir[w * n..(w + 1) * n];
        for (i, &di) in d.iter().enumerate() {
            let v = di * s;
            before[w].target_velocity[i] = v;
            after[0].current_velocity[i] = v;
        }
    }

    /// Duration of section `s` with the current waypoint velocities.
    fn solve(&mut self, s: usize) -> Result<f64, OtgError> {
        self.run(s, Search::Full)
    }

    /// The search's rating of section `s` with the current waypoint velocities: its duration
    /// from the bounded synchronization (at least the full solve's), ∞ when that cannot plan it
    /// (or its own deadline cut it: then the result is marked interrupted).
    fn rate(&mut self, s: usize) -> f64 {
        let r = self.run(s, Search::Bounded);
        self.interrupted |= matches!(r, Err(OtgError::Interrupted { .. }));
        r.unwrap_or(f64::INFINITY)
    }

    /// Section `s` through the synchronization in mode `search`, with what is left of the
    /// budget as its own budget: for the reference all of it; for a rating or a section of the
    /// final build less the tail and what comes after it (the build, or its later sections),
    /// but at least this section's latest measured cost.
    fn run(&mut self, s: usize, search: Search) -> Result<f64, OtgError> {
        let Some(clock) = self.clock else {
            return self.run_in(s, search);
        };
        let left = clock.left_us()?;
        let after = match self.later_us {
            Some(later) => Some(later),
            None if search == Search::Bounded => Some(self.build_us()),
            None => None,
        };
        let own = after.map_or(left, |after| {
            (left - after - self.tail_us(clock))
                .max(self.cost[s])
                .min(left)
        });
        self.secs[s].options.interrupt_calculation_duration = Some(own);
        let t0 = clock.elapsed_us();
        let r = self.run_in(s, search);
        let took = clock.elapsed_us() - t0;
        self.cost[s] = took;
        self.step_us = self.step_us.max(took);
        // A section that ran out of what was left of the budget: the budget ran out.
        r.map_err(|e| match e {
            OtgError::Interrupted { .. } => clock.interrupted(),
            e => e,
        })
    }

    /// [`Planner::run`] without the clock.
    fn run_in(&mut self, s: usize, search: Search) -> Result<f64, OtgError> {
        let view = self.secs[s].view();
        if search == Search::Bounded {
            return calculate(
                &view,
                self.dt,
                &mut self.dofs,
                &mut self.scratch,
                &mut self.spare,
                search,
            );
        }
        let c = calculate_status(
            &view,
            self.dt,
            &mut self.dofs,
            &mut self.scratch,
            &mut self.spare,
        )?;
        self.interrupted |= c.interrupted;
        Ok(c.duration)
    }

    /// What solving and keeping sections `from..` in the final build is expected to cost in
    /// microseconds ([`BUILD_FACTOR`] times their latest measured solves, and what keeping a
    /// section took in the reference).
    fn build_us_from(&self, from: usize) -> f64 {
        let rest = &self.cost[from.min(self.m + 1)..];
        BUILD_FACTOR * rest.iter().sum::<f64>() + self.keep_us * rest.len() as f64
    }

    /// What the whole final build is expected to cost in microseconds.
    fn build_us(&self) -> f64 {
        self.build_us_from(0)
    }

    /// The microseconds of the budget the search and the build leave unused ([`TAIL`]).
    fn tail_us(&self, clock: Clock) -> f64 {
        TAIL * clock.budget_us()
    }

    /// Whether the budget leaves too little for the search's next step (at most two section
    /// ratings), the final build ([`BUILD_FACTOR`] times the latest measured cost of every
    /// section) and the tail (then the search stops and the result is marked interrupted).
    fn out_of_time(&mut self) -> bool {
        let tail = self.clock.map_or(0.0, |c| self.tail_us(c));
        let need = self.build_us() + tail + 2.0 * self.step_us;
        let late = self
            .clock
            .is_some_and(|c| c.left_us().map_or(true, |left| left < need));
        self.interrupted |= late;
        late
    }

    /// The two sections around waypoint `w` at scale `s`: their ratings ([`Planner::rate`]).
    /// When the first alone is longer than `beaten` the second is not rated: ∞ stands for it
    /// (the pair is worse than a total of `beaten` either way). Out of time (with a budget):
    /// both ∞, nothing solved.
    fn around(&mut self, w: usize, s: f64, beaten: f64) -> (f64, f64) {
        if self.out_of_time() {
            return (f64::INFINITY, f64::INFINITY);
        }
        self.set_scale(w, s);
        let a = self.rate(w);
        if a.is_infinite() || a > beaten {
            return (a, f64::INFINITY);
        }
        (a, self.rate(w + 1))
    }

    /// Plans the motion (see the module docs).
    pub(super) fn plan(&mut self) -> Result<WaypointTrajectory, OtgError> {
        let mut reference = Vec::new();
        for s in 0..=self.m {
            self.dur[s] = self.solve(s).map_err(|e| self.section_error(s, e))?;
            if self.clock.is_some() {
                reference.push(self.section(self.dur[s]));
            }
        }
        if let Some(c) = self.clock {
            let solving: f64 = self.cost.iter().sum();
            self.keep_us = ((c.elapsed_us() - solving) / (self.m + 1) as f64).max(0.0);
        }
        let stop: Vec<f64> = self.dur.clone();
        let stop_total: f64 = stop.iter().sum();
        if self.m > 0 && !self.out_of_time() {
            self.directions(&stop);
            self.start_from_tangent();
            'search: for (sweep, &evals) in EVALS.iter().enumerate() {
                for w in 0..self.m {
                    if self.out_of_time() {
                        break 'search;
                    }
                    let (lo, hi) = if sweep == 0 {
                        (0.0, self.cap[w])
                    } else {
                        let s = self.scale[w];
                        ((s * (1.0 - WINDOW)), (s * (1.0 + WINDOW)).min(self.cap[w]))
                    };
                    self.golden(w, lo, hi, evals);
                }
            }
        }
        let total: f64 = self.dur.iter().sum();
        if total.is_nan() || total >= stop_total {
            self.scale.iter_mut().for_each(|s| *s = 0.0);
        }
        for w in 0..self.m {
            self.set_scale(w, self.scale[w]);
        }
        let moving = self.scale.iter().any(|&s| s != 0.0);
        if !moving && !reference.is_empty() {
            return Ok(self.assemble(reference, stop_total));
        }
        match self.build(stop_total) {
            // The full solve plans whatever the bounded rating planned, at most as long (to
            // round-off); should it ever not (or should the budget run out while building),
            // stopping at every waypoint is the answer: with a budget, the kept reference.
            r if moving && !r.as_ref().is_ok_and(|t| t.duration <= stop_total) => {
                for w in 0..self.m {
                    self.scale[w] = 0.0;
                    self.set_scale(w, 0.0);
                }
                if reference.is_empty() {
                    return self.build(stop_total);
                }
                self.interrupted |= matches!(r, Err(OtgError::Interrupted { .. }));
                Ok(self.assemble(reference, stop_total))
            }
            r => r,
        }
    }

    /// The section just solved into the planner's buffers, `d` long.
    fn section(&self, d: f64) -> DynTrajectory {
        OtgTrajectory {
            dofs: self.dofs.clone(),
            duration: d,
            interrupted: false,
        }
    }

    /// The tangent direction of every waypoint and its largest scale, from the section
    /// durations of stopping at every waypoint.
    fn directions(&mut self, stop: &[f64]) {
        let (n, wp) = (self.n, &self.waypoints.intermediate_positions);
        for w in 0..self.m {
            let prev = if w == 0 {
                &self.secs[0].current_position
            } else {
                &wp[w - 1]
            };
            let next = if w + 1 == self.m {
                &self.secs[self.m].target_position
            } else {
                &wp[w + 1]
            };
            let (tin, tout) = (stop[w], stop[w + 1]);
            let mut cap = SCALE_CAP;
            for i in 0..n {
                let (din, dout) = (wp[w][i] - prev[i], next[i] - wp[w][i]);
                let d = if din * dout > 0.0 && tin > 0.0 && tout > 0.0 {
                    let (vin, vout) = (din / tin, dout / tout);
                    let t = (vin * tout + vout * tin) / (tin + tout);
                    let cap = 3.0 * vin.abs().min(vout.abs());
                    // NaN (overflowed differences): stop at the waypoint, always valid.
                    clamp_in(t, -cap, cap).unwrap_or(0.0)
                } else {
                    0.0
                };
                self.dir[w * n + i] = d;
                if d != 0.0 {
                    let (a, b) = (&self.secs[w], &self.secs[w + 1]);
                    let lim = if d > 0.0 {
                        a.max_velocity[i].min(b.max_velocity[i])
                    } else {
                        min_velocity(a, i).max(min_velocity(b, i))
                    };
                    cap = cap.min(lim / d);
                }
            }
            self.cap[w] = cap.max(0.0);
        }
    }

    /// Starts the descent from the tangent velocities at scale 1 (within the caps) when every
    /// section can be planned with them and the total is shorter; otherwise from stopping at
    /// every waypoint.
    fn start_from_tangent(&mut self) {
        for w in 0..self.m {
            self.set_scale(w, self.cap[w].min(1.0));
        }
        let mut dur = vec![0.0; self.m + 1];
        let mut ok = true;
        // (Rating stops once the sum cannot be shorter.)
        let (stop, mut sum) = (self.dur.iter().sum::<f64>(), 0.0);
        for s in 0..=self.m {
            if self.out_of_time() {
                ok = false;
                break;
            }
            dur[s] = self.rate(s);
            sum += dur[s];
            if dur[s].is_infinite() || sum >= stop {
                ok = false;
                break;
            }
        }
        if ok && dur.iter().sum::<f64>() < self.dur.iter().sum::<f64>() {
            for w in 0..self.m {
                self.scale[w] = self.cap[w].min(1.0);
            }
            self.dur = dur;
        }
        for w in 0..self.m {
            self.set_scale(w, self.scale[w]);
        }
    }

    /// Golden-section search of waypoint `w`'s scale over `[lo, hi]` with `evals`
    /// evaluations; keeps the best of them and the current scale.
    ///
    /// Each new point only has to be compared with the other inner point (and the best so
    /// far, never longer than either), so its second section is not rated when its first
    /// already exceeds the other point's total ([`Planner::around`]): the search takes the
    /// same steps and keeps the same scale as with both ratings.
    fn golden(&mut self, w: usize, lo: f64, hi: f64, evals: usize) {
        let mut best = (self.scale[w], self.dur[w], self.dur[w + 1]);
        let consider = |s: f64, d: (f64, f64), best: &mut (f64, f64, f64)| {
            if d.0 + d.1 < best.1 + best.2 {
                *best = (s, d.0, d.1);
            }
        };
        if hi > lo && evals >= 2 {
            let (mut a, mut b) = (lo, hi);
            let mut x1 = b - INV_PHI * (b - a);
            let mut x2 = a + INV_PHI * (b - a);
            let mut f1 = self.around(w, x1, f64::INFINITY);
            let mut f2 = self.around(w, x2, f1.0 + f1.1);
            consider(x1, f1, &mut best);
            consider(x2, f2, &mut best);
            for _ in 2..evals {
                if f1.0 + f1.1 <= f2.0 + f2.1 {
                    (b, x2, f2) = (x2, x1, f1);
                    x1 = b - INV_PHI * (b - a);
                    f1 = self.around(w, x1, f2.0 + f2.1);
                    consider(x1, f1, &mut best);
                } else {
                    (a, x1, f1) = (x1, x2, f2);
                    x2 = a + INV_PHI * (b - a);
                    f2 = self.around(w, x2, f1.0 + f1.1);
                    consider(x2, f2, &mut best);
                }
            }
        }
        self.scale[w] = best.0;
        self.dur[w] = best.1;
        self.dur[w + 1] = best.2;
        self.set_scale(w, best.0);
    }

    /// Solves every section once more into its own trajectory (with a budget, each section's
    /// own search leaves what the later ones are expected to need: see [`Planner::run`]).
    fn build(&mut self, stop_total: f64) -> Result<WaypointTrajectory, OtgError> {
        let mut sections = Vec::with_capacity(self.m + 1);
        for s in 0..=self.m {
            if self.clock.is_some() {
                self.later_us = Some(self.build_us_from(s + 1));
            }
            let d = self.solve(s);
            self.later_us = None;
            let d = d.map_err(|e| self.section_error(s, e))?;
            sections.push(self.section(d));
        }
        Ok(self.assemble(sections, stop_total))
    }

    /// The motion of `sections` (solved for the current waypoint velocities).
    fn assemble(&self, sections: Vec<DynTrajectory>, stop_total: f64) -> WaypointTrajectory {
        let mut starts = Vec::with_capacity(sections.len());
        let mut t = 0.0;
        for sec in &sections {
            starts.push(t);
            t += sec.duration;
        }
        let mut velocities = vec![0.0; self.m * self.n];
        for w in 0..self.m {
            velocities[w * self.n..(w + 1) * self.n].copy_from_slice(&self.secs[w].target_velocity);
        }
        WaypointTrajectory {
            sections,
            starts,
            duration: t,
            stop_duration: stop_total,
            velocities,
            interrupted: self.interrupted,
        }
    }

    /// The error of a section that cannot be planned (input errors pass through).
    fn section_error(&self, s: usize, e: OtgError) -> OtgError {
        if let OtgError::InvalidInput { .. } | OtgError::Interrupted { .. } = e {
            return e;
        }
        let min = self
            .waypoints
            .per_section_minimum_duration
            .as_ref()
            .map(|d| d[s]);
        let (field, value) = match min {
            Some(d) if d > 0.0 => ("per_section_minimum_duration", d),
            _ => ("intermediate_positions", f64::NAN),
        };
        let reason = match e {
            OtgError::PositionLimits { .. } => {
                "section cannot be planned inside [min_position, max_position]"
            }
            OtgError::ZeroLimits { .. } => "section cannot be planned with its zero limits",
            _ if min.is_some_and(|d| d > 0.0) => {
                "section cannot be planned with this minimum duration"
            }
            _ => "section cannot be planned (the generator found no trajectory)",
        };
        OtgError::Waypoints {
            index: s,
            dof: e.dof(),
            field,
            value,
            reason,
        }
    }
}

/// The minimum velocity of DOF `i` in a section's input.
fn min_velocity(si: &DynInputParameter, i: usize) -> f64 {
    si.min_velocity
        .as_ref()
        .map_or(-si.max_velocity[i], |m| m[i])
}
