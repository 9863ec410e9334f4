//! Unit tests of synchronization (`super`): the step-1 profile kept for the minimum duration,
//! the duration bounds, the lazy step 1, the budget's cut of the bisection, the bounded mode.

use super::*;
use crate::otg::problem::ProfileOrder;
use crate::otg::step1::step1;

/// Step 1 into an output profile, as `calculate` does; returns the scratch, the spare and
/// a copy of the step-1 profile.
fn setup(d: Dof1, out: &mut Profile) -> (Scratch, Spare, Profile) {
    let mut s = Scratch {
        dof: d,
        ..Scratch::default()
    };
    let mut spare = None;
    s.ncand = step1_into(&d, out, &mut spare, &mut s.cand).unwrap();
    s.step1_in_out = true;
    s.step1_kept = false;
    s.brake = out.brake_duration() != 0.0;
    s.t_min = out.duration();
    s.sync = true;
    s.solved = Solved::Full;
    (s, spare, *out)
}

#[test]
fn back_at_the_minimum_duration_the_step1_profile_returns() {
    // Without a brake (the step-1 profile is not kept but calculated again) and with one
    // (it is copied aside before step 2).
    let rest = Dof1::rest_to_rest(0.1, 1.3, 1.0, 2.0, 10.0);
    let mut braking = Dof1::rest_to_rest(0.1, 1.3, 1.0, 2.0, 10.0);
    braking.v0 = 1.6;
    braking.a0 = 0.5;
    for (d, has_brake) in [(rest, false), (braking, true)] {
        let mut out = Profile::default();
        let (mut s, mut spare, first) = setup(d, &mut out);
        assert_eq!(s.brake, has_brake);
        let t = 1.5 * s.t_min;
        assert!(replan_into(&mut s, &mut spare, t, &mut out));
        assert!((out.duration() - t).abs() <= 1e-12 * t);
        assert!(out != first);
        if has_brake {
            assert_eq!(out.brake_duration(), first.brake_duration());
        }
        let t_min = s.t_min;
        assert!(replan_into(&mut s, &mut spare, t_min, &mut out));
        assert_eq!(out, first);
        // And step 2 again from there.
        assert!(replan_into(&mut s, &mut spare, t, &mut out));
        assert!((out.duration() - t).abs() <= 1e-12 * t);
    }
}

/// Random problems (Panda-like limits, random scale, general states, moving targets,
/// direction-dependent limits).
fn random_dof(r: &mut crate::rng::SplitMix64, general: bool, asym: bool) -> Dof1 {
    let vmax = r.uniform(0.2, 3.0);
    let amax = r.uniform(0.5, 20.0);
    let jmax = r.uniform(2.0, 5000.0);
    let mut d = Dof1::rest_to_rest(r.uniform(-3.0, 3.0), r.uniform(-3.0, 3.0), vmax, amax, jmax);
    if asym {
        d.vmin = -r.uniform(0.2, 3.0);
        d.amin = -r.uniform(0.5, 20.0);
    }
    if general {
        loop {
            let v0 = r.uniform(d.vmin, d.vmax) * 0.9;
            let a0 = r.uniform(d.amin, d.amax) * 0.9;
            let vf = r.uniform(d.vmin, d.vmax) * 0.9;
            let af = r.uniform(d.amin, d.amax) * 0.9;
            let vl = d.vmax.min(-d.vmin);
            let ok = |v: f64, a: f64| v.abs() + a * a / (2.0 * jmax) <= vl;
            if ok(v0, a0) && ok(vf, af) {
                (d.v0, d.a0, d.vf, d.af) = (v0, a0, vf, af);
                break;
            }
        }
    }
    d
}

#[test]
fn the_duration_bound_bounds_the_minimum_is_exact_from_rest_to_rest_and_leaves_no_gap_above() {
    let mut r = crate::rng::SplitMix64::new(41);
    let mut finite = 0;
    for k in 0..6000 {
        let (general, asym) = (k % 3 != 0, k % 2 == 0);
        let mut d = random_dof(&mut r, general, asym);
        // Every fifth problem second order, every seventh first order.
        if k % 5 == 4 {
            (d.jmax, d.a0, d.af) = (f64::INFINITY, 0.0, 0.0);
        } else if k % 7 == 6 {
            (d.amax, d.amin, d.jmax, d.a0, d.af) =
                (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, 0.0, 0.0);
        }
        let b = duration_bound(&d);
        let t = step1(&d).unwrap().t_min();
        assert!(
            b >= t * (1.0 - 1e-12),
            "case {k}: bound {b} < minimum {t}\n{d:?}"
        );
        if b.is_finite() {
            finite += 1;
            // Every duration from the bound on is feasible: step 2 plans it.
            for f in [1.0 + 1e-9, 1.05, 1.5, 3.0] {
                let p = crate::otg::with_duration(&d, b * f);
                assert!(p.is_some(), "case {k}: no profile of {} s\n{d:?}", b * f);
            }
        }
        if !general && !asym || d.order() == ProfileOrder::First {
            assert!(
                (b - t).abs() <= 1e-12 * t,
                "case {k}: bound {b}, minimum {t}\n{d:?}"
            );
        }
    }
    // The bound applies to most problems (infinite only where a third-order stop or
    // start would leave the velocity limits).
    assert!(finite > 5500, "{finite}");
}

/// The input of the per-DOF problems `ds`.
fn input_of<const N: usize>(ds: &[Dof1; N]) -> crate::otg::InputParameter<N> {
    let mut inp = crate::otg::InputParameter::<N>::new();
    for (i, d) in ds.iter().enumerate() {
        inp.current_position[i] = d.p0;
        inp.current_velocity[i] = d.v0;
        inp.current_acceleration[i] = d.a0;
        inp.target_position[i] = d.pf;
        inp.target_velocity[i] = d.vf;
        inp.target_acceleration[i] = d.af;
        inp.max_velocity[i] = d.vmax;
        inp.max_acceleration[i] = d.amax;
        inp.max_jerk[i] = d.jmax;
    }
    inp.min_velocity = Some(ds.map(|d| d.vmin));
    inp.min_acceleration = Some(ds.map(|d| d.amin));
    inp
}

/// Synchronized results equal the largest minimum duration when no DOF has a blocked
/// interval there, whichever DOF's step 1 ran: here the DOF with the largest bound (a
/// start moving fast towards the target: a loose bound) is not the one that sets the
/// duration, so the other one's step 1 runs when its bound exceeds the trial duration.
#[test]
fn a_wrong_first_guess_still_gives_the_largest_minimum() {
    let mut fast = Dof1::rest_to_rest(0.0, 3.0, 2.0, 4.0, 20.0);
    fast.v0 = 1.9;
    let slow = Dof1::rest_to_rest(0.0, 2.6, 2.0, 4.0, 20.0);
    let (tf, ts) = (step1(&fast).unwrap().t_min(), step1(&slow).unwrap().t_min());
    assert!(
        duration_bound(&fast) > duration_bound(&slow) && tf < ts,
        "{tf} {ts}"
    );
    let inp = input_of(&[fast, slow]);
    let tr = crate::otg::Otg::<2>::new(0.001).calculate(&inp).unwrap();
    assert!((tr.duration() - ts).abs() <= 1e-12 * ts);
    let mut mins = [0.0; 2];
    tr.independent_min_durations(&mut mins);
    assert_eq!(mins, [tf, ts]);
}

/// A budget that is spent when the bisection starts keeps the success it was given and
/// says so (`interrupted`); with budget left the bisection runs and nothing is flagged.
#[test]
fn a_spent_budget_stops_the_bisection_and_is_reported() {
    let ds = [
        Dof1::rest_to_rest(0.0, 1.0, 1.0, 2.0, 10.0),
        Dof1::rest_to_rest(0.0, 0.5, 1.0, 2.0, 10.0),
    ];
    let inp = input_of(&ds);
    let view = inp.view();
    let t_min = step1(&ds[0]).unwrap().t_min();
    let run = |budget: Option<Budget>| {
        let mut out = [DofTrajectory::default(); 2];
        let mut scratch = [Scratch::default(); 2];
        let mut spare: [Spare; 2] = [None, None];
        for i in 0..2 {
            scratch[i].dof = ds[i];
            scratch[i].sync = true;
            assert!(solve(
                &mut scratch[i],
                &mut spare[i],
                &mut out[i].profile,
                true
            ));
        }
        let mut p = Planner {
            view: &view,
            delta_time: 0.001,
            out: &mut out,
            scratch: &mut scratch,
            spare: &mut spare,
            n: 2,
            discrete: false,
            min_dur: 0.0,
            budget,
            interrupted: false,
            bounded: false,
            unbuilt: false,
        };
        // As `search` calls it: after a success at `hi`. Every duration from the minimum
        // on is feasible, so bisecting from below it ends at the minimum unless stopped.
        assert!(try_each(p.scratch, p.spare, p.out, 2.0 * t_min, 0..2, false).is_ok());
        let t = p.bisect(0.5 * t_min, 2.0 * t_min, 0).unwrap();
        (t, p.interrupted, out[1].profile.duration())
    };
    let (t, cut, d1) = run(None);
    assert!(!cut && (t - t_min).abs() <= 1e-9 * t_min, "{t} vs {t_min}");
    assert!((d1 - t).abs() <= 1e-12 * t);
    let spent = Budget {
        deadline: Instant::now(),
        us: 1.0,
    };
    let (t, cut, d1) = run(Some(spent));
    assert!(cut && t == 2.0 * t_min);
    assert!((d1 - t).abs() <= 1e-12 * t);
}

/// A DOF planned without its step 1 reports the minimum duration step 1 gives.
#[test]
fn minimum_durations_of_unsolved_dofs_are_computed_on_request() {
    let mut r = crate::rng::SplitMix64::new(5);
    for _ in 0..200 {
        let ds = [
            random_dof(&mut r, true, false),
            random_dof(&mut r, false, false),
            random_dof(&mut r, true, true),
        ];
        let inp = input_of(&ds);
        let Ok(tr) = crate::otg::Otg::<3>::new(0.001).calculate(&inp) else {
            continue;
        };
        let mut mins = [0.0; 3];
        tr.independent_min_durations(&mut mins);
        for i in 0..3 {
            assert_eq!(mins[i], step1(&ds[i]).unwrap().t_min());
            assert!(tr.duration() >= mins[i] * (1.0 - 1e-12));
        }
    }
}

/// The bounded mode is never shorter than the full search, its duration is feasible for
/// every DOF (step 2 plans it, or it is the DOF's minimum), it equals the full search on most problems and is
/// longer, or gives up, only where the full search bisects or walks past the candidates.
#[test]
fn the_bounded_mode_is_never_shorter_and_its_profiles_are_valid() {
    let mut r = crate::rng::SplitMix64::new(16);
    let (mut equal, mut longer, mut gave_up) = (0, 0, 0);
    for _ in 0..400 {
        // Waypoint-like sections: DOF 0 rests at both ends and sets a long duration; the
        // others move a little, along their velocities, and pass their ends at speed
        // (blocked intervals below DOF 0's minimum, where the full search bisects).
        let mut ds = [
            random_dof(&mut r, false, false),
            random_dof(&mut r, false, false),
            random_dof(&mut r, false, true),
        ];
        ds[0].pf = ds[0].p0 + r.uniform(1.0, 4.0);
        for d in &mut ds[1..] {
            d.pf = d.p0 + r.uniform(0.01, 0.5);
            d.v0 = r.uniform(0.0, 0.9) * d.vmax;
            d.vf = r.uniform(0.0, 0.9) * d.vmax;
        }
        let inp = input_of(&ds);
        let view = inp.view();
        let mut out = [DofTrajectory::default(); 3];
        let mut scratch = [Scratch::default(); 3];
        let mut spare: [Spare; 3] = [None, None, None];
        let full = calculate(
            &view,
            0.001,
            &mut out,
            &mut scratch,
            &mut spare,
            Search::Full,
        );
        let Ok(tb) = calculate(
            &view,
            0.001,
            &mut out,
            &mut scratch,
            &mut spare,
            Search::Bounded,
        ) else {
            gave_up += 1;
            continue;
        };
        let tf = full.expect("the full search plans what the bounded mode plans");
        // (Each profile's duration is the common one to 1e-12 relative.)
        assert!(tb >= tf * (1.0 - 4e-12), "bounded {tb} < full {tf}");
        if (tb - tf).abs() <= 4e-12 * tf {
            equal += 1;
        } else {
            longer += 1;
        }
        // Its duration is feasible for every DOF (it builds only the profiles it needs, so
        // each DOF is checked on its own): its minimum, or step 2 plans it.
        for (i, d) in ds.iter().enumerate() {
            let t_min = step1(d).unwrap().t_min();
            if (tb - t_min).abs() <= 1e-12 * tb {
                continue;
            }
            let p = step2(d, tb).unwrap_or_else(|| panic!("dof {i}: no profile at {tb}"));
            let e = p.end();
            assert!(
                (e.p - d.pf).abs() <= 1e-8 && (e.v - d.vf).abs() <= 1e-8,
                "dof {i}"
            );
        }
    }
    eprintln!("bounded mode: {equal} equal, {longer} longer, {gave_up} gave up");
    assert!(
        equal > 300 && longer + gave_up > 0,
        "{equal} {longer} {gave_up}"
    );
}

/// The closed form of the bound's stop and start changes between zero accelerations is
/// the fastest change itself (duration and displacement to round-off), on both sides of
/// the acceleration limit and with direction-dependent limits.
#[test]
fn the_bounds_flat_change_is_the_fastest_change() {
    let mut r = crate::rng::SplitMix64::new(43);
    for k in 0..4000 {
        let (j, amax, amin) = (
            r.uniform(2.0, 5000.0),
            r.uniform(0.5, 20.0),
            -r.uniform(0.5, 20.0),
        );
        let (va, vb) = (r.uniform(-3.0, 3.0), r.uniform(-3.0, 3.0));
        let c = crate::otg::velocity_change::fastest3(va, 0.0, vb, 0.0, j, amax, amin).unwrap();
        let (t, dist) = super::bound::flat_change(va, vb, j, amax, amin);
        assert!((t - c.t).abs() <= 1e-12 * c.t, "case {k}: {t} vs {}", c.t);
        let scale = c.t * va.abs().max(vb.abs());
        assert!(
            (dist - c.dist).abs() <= 1e-12 * scale,
            "case {k}: {dist} vs {}",
            c.dist
        );
    }
}
