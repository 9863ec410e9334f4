//! Torque-limited planning through waypoints with a URDF dynamics model.

mod topp_common;

use topp_common::ARM;

use trajkit::dynamics::SerialChain;
use trajkit::topp::messy::{plan_waypoints, PlanOptions, TorqueModel};
use trajkit::topp::InverseDynamics;
use trajkit::{Limits, Order, Trajectory};

fn limits() -> Limits {
    let urdf = trajkit::limits::load::from_urdf_str(ARM, "arm.urdf").unwrap();
    let with_acc = urdf
        .joints()
        .iter()
        .map(|j| trajkit::JointLimits {
            acceleration: 40.0,
            ..j.clone()
        })
        .collect();
    Limits::new(with_acc).unwrap()
}

/// Worst |τ_j| / effort_j over 1 ms samples.
fn worst_torque_ratio(traj: &impl Trajectory, chain: &SerialChain, effort: &[f64]) -> f64 {
    let n = traj.dof();
    let (mut q, mut qd, mut qdd, mut tau) =
        (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let steps = (traj.duration() / 1e-3).ceil() as usize;
    let mut worst: f64 = 0.0;
    for k in 0..=steps {
        let t = (k as f64 * 1e-3).min(traj.duration());
        traj.eval(t, Order::Position, &mut q);
        traj.eval(t, Order::Velocity, &mut qd);
        traj.eval(t, Order::Acceleration, &mut qdd);
        chain.torque(&q, &qd, &qdd, &mut tau);
        for j in 0..n {
            worst = worst.max(tau[j].abs() / effort[j]);
        }
    }
    worst
}

#[test]
fn torque_limits_bind_and_hold_on_samples() {
    let chain = SerialChain::from_urdf_str(ARM, "arm.urdf").unwrap();
    let limits = limits();
    let effort: Vec<f64> = limits.joints().iter().map(|j| j.effort.unwrap()).collect();
    let w = [0.0, 0.0, 1.2, -1.0, 0.3, 1.0, -0.5, 0.2];
    let free = plan_waypoints(&w, 2, &limits, &PlanOptions::default()).unwrap();
    let opts = PlanOptions {
        torque: Some(TorqueModel::new(chain.clone())),
        ..PlanOptions::default()
    };
    let held = plan_waypoints(&w, 2, &limits, &opts).unwrap();
    let free_ratio = worst_torque_ratio(&free, &chain, &effort);
    let held_ratio = worst_torque_ratio(&held, &chain, &effort);
    assert!(
        free_ratio > 1.05,
        "the torque limits do not bind ({free_ratio})"
    );
    assert!(
        held_ratio <= 1.0 + 1e-6,
        "torque exceeded: ratio {held_ratio}"
    );
    assert!(
        held.duration() > free.duration() * 1.05,
        "{} vs {}",
        held.duration(),
        free.duration()
    );
    assert_eq!(opts.clone(), opts);
    assert!(format!("{opts:?}").contains("TorqueModel { dof: 2 }"));
}

#[test]
fn torque_limits_need_efforts_and_matching_joints() {
    let chain = SerialChain::from_urdf_str(ARM, "arm.urdf").unwrap();
    let w = [0.0, 0.0, 1.0, 1.0];
    let opts = PlanOptions {
        torque: Some(TorqueModel::new(chain)),
        ..PlanOptions::default()
    };
    let no_effort = Limits::uniform(2, 1.0, 2.0, f64::INFINITY).unwrap();
    let e = plan_waypoints(&w, 2, &no_effort, &opts).unwrap_err();
    assert!(e.to_string().contains("joint 1 effort limit"), "{e}");
    let three = Limits::uniform(3, 1.0, 2.0, f64::INFINITY).unwrap();
    let three = three.with_override(Order::Velocity, &[1.0]).unwrap();
    let three = Limits::new(
        three
            .joints()
            .iter()
            .map(|j| trajkit::JointLimits {
                effort: Some(5.0),
                ..j.clone()
            })
            .collect(),
    )
    .unwrap();
    let e = plan_waypoints(&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 3, &three, &opts).unwrap_err();
    assert!(e.to_string().contains("joint count"), "{e}");
}
