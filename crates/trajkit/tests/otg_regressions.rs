//! Regression problems found by the Ruckig sweep (`tools/otg_sweep.py`): each line of
//! `fixtures/otg/regressions.jsonl` is a problem, its category and the Ruckig wheel's
//! duration. trajkit must solve each, within its contract, in at most Ruckig's duration
//! (× (1 + 1e-9)).

mod otg_common;
use trajkit::otg::json::parse_problem;
use trajkit::otg::{calculate_dyn, ControlInterface};

const FIXTURE: &str = include_str!("fixtures/otg/regressions.jsonl");

#[test]
fn sweep_reproducers_are_never_longer_than_ruckig() {
    let mut n = 0;
    for (k, line) in FIXTURE.lines().enumerate() {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        let problem = v["problem"].to_string();
        let p = parse_problem(&problem, "regressions.jsonl", k + 1).unwrap();
        let ruckig = v["ruckig_duration"].as_f64().unwrap();
        let tr =
            calculate_dyn(&p.input, p.delta_time).unwrap_or_else(|e| panic!("line {}: {e}", k + 1));
        let t = tr.duration();
        let mut mins = vec![0.0; tr.dof()];
        tr.independent_min_durations(&mut mins);
        assert!(
            t <= ruckig * (1.0 + 1e-9),
            "line {} ({}): trajkit {t} > Ruckig {ruckig}; minima {mins:?}",
            k + 1,
            v["category"]
        );
        // The target is reached.
        for (i, d) in tr.dofs().iter().enumerate() {
            let e = d.profile.end();
            let iface = p
                .input
                .per_dof_control_interface
                .as_ref()
                .map_or(p.input.options.control_interface, |c| c[i]);
            if p.input.enabled[i] && iface == ControlInterface::Position {
                assert!(
                    (e.p - p.input.target_position[i]).abs() <= 1e-8,
                    "line {}",
                    k + 1
                );
            }
            assert!(
                (e.v - p.input.target_velocity[i]).abs() <= 1e-9,
                "line {}",
                k + 1
            );
        }
        n += 1;
    }
    assert!(n >= 2);
}
