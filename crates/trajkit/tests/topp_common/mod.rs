//! Shared helpers of the TOPP integration tests.
#![allow(dead_code)]

use serde_json::Value;
use trajkit::spline::PiecewisePolynomial;
use trajkit::{Limits, Order, Trajectory};

/// The toppra fixture file.
pub fn fixtures() -> Vec<Value> {
    let p = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/topp/toppra_panda.json"
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
    v["problems"].as_array().unwrap().clone()
}

pub fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The waypoints (row-major) of the fixture problem `name`.
pub fn fixture_waypoints(name: &str) -> Vec<f64> {
    let problem = fixtures().into_iter().find(|p| p["name"] == name);
    let rows = problem.expect("a fixture problem of that name")["waypoints"].clone();
    rows.as_array().unwrap().iter().flat_map(floats).collect()
}

/// The fixture's cubic as a trajkit piecewise polynomial (same coefficients).
pub fn fixture_path(p: &Value) -> PiecewisePolynomial {
    let breaks = floats(&p["breaks"]);
    let dim = p["dof"].as_u64().unwrap() as usize;
    let mut coeffs = Vec::new();
    for piece in p["coefficients"].as_array().unwrap() {
        for joint in piece.as_array().unwrap() {
            coeffs.extend(floats(joint));
        }
    }
    PiecewisePolynomial::new(breaks, dim, 3, coeffs).unwrap()
}

/// Worst use of the limits over 1 ms samples (both ends included): pointwise velocity and
/// acceleration ratios, and finite-difference ratios of positions (velocity) and of sampled
/// velocities (acceleration). Limits are directional: `lo[j] <= value <= hi[j]`.
pub struct Worst {
    pub velocity: f64,
    pub acceleration: f64,
    pub fd_velocity: f64,
    pub fd_acceleration: f64,
}

fn ratio(v: f64, lo: f64, hi: f64) -> f64 {
    if v >= 0.0 {
        if hi.is_infinite() {
            0.0
        } else {
            v / hi
        }
    } else if lo.is_infinite() {
        0.0
    } else {
        v / lo
    }
}

/// [`worst_ratios`] against the velocity and acceleration limits of `lim`, 1 ms samples.
pub fn worst_for<T: Trajectory>(traj: &T, lim: &trajkit::Limits) -> Worst {
    let (vlo, vhi): (Vec<f64>, Vec<f64>) = lim
        .joints()
        .iter()
        .map(|j| j.range(Order::Velocity))
        .unzip();
    let (alo, ahi): (Vec<f64>, Vec<f64>) = lim
        .joints()
        .iter()
        .map(|j| j.range(Order::Acceleration))
        .unzip();
    worst_ratios(traj, &vlo, &vhi, &alo, &ahi, 1e-3)
}

pub fn worst_ratios<T: Trajectory>(
    traj: &T,
    vlo: &[f64],
    vhi: &[f64],
    alo: &[f64],
    ahi: &[f64],
    dt: f64,
) -> Worst {
    let n = traj.dof();
    let big_t = traj.duration();
    let steps = (big_t / dt).ceil() as usize;
    let times: Vec<f64> = (0..=steps).map(|k| (k as f64 * dt).min(big_t)).collect();
    let mut q = vec![vec![0.0; n]; times.len()];
    let mut qd = vec![vec![0.0; n]; times.len()];
    let mut w = Worst {
        velocity: 0.0,
        acceleration: 0.0,
        fd_velocity: 0.0,
        fd_acceleration: 0.0,
    };
    let mut a = vec![0.0; n];
    for (k, &t) in times.iter().enumerate() {
        traj.eval(t, Order::Position, &mut q[k]);
        traj.eval(t, Order::Velocity, &mut qd[k]);
        traj.eval(t, Order::Acceleration, &mut a);
        for j in 0..n {
            assert!(q[k][j].is_finite() && qd[k][j].is_finite() && a[j].is_finite());
            w.velocity = w.velocity.max(ratio(qd[k][j], vlo[j], vhi[j]));
            w.acceleration = w.acceleration.max(ratio(a[j], alo[j], ahi[j]));
        }
    }
    for k in 1..times.len() {
        let h = times[k] - times[k - 1];
        if h < 1e-9 {
            continue;
        }
        for j in 0..n {
            w.fd_velocity = w
                .fd_velocity
                .max(ratio((q[k][j] - q[k - 1][j]) / h, vlo[j], vhi[j]));
            w.fd_acceleration =
                w.fd_acceleration
                    .max(ratio((qd[k][j] - qd[k - 1][j]) / h, alo[j], ahi[j]));
        }
    }
    w
}

/// Largest ratio |value| / limit of velocity, acceleration and jerk at `rate` Hz, and of the
/// position's distance outside its range.
pub fn worst_ratio_with_range(
    traj: &dyn Trajectory,
    limits: &Limits,
    rate: f64,
) -> ([f64; 3], f64) {
    let n = traj.dof();
    let mut buf = vec![0.0; n];
    let mut worst = [0.0f64; 3];
    let mut outside = 0.0f64;
    let count = (traj.duration() * rate).ceil() as usize;
    for k in 0..=count {
        let t = (k as f64 / rate).min(traj.duration());
        traj.eval(t, Order::Position, &mut buf);
        for (j, &q) in buf.iter().enumerate() {
            let jl = limits.joint(j);
            outside = outside.max(jl.position_min - q).max(q - jl.position_max);
        }
        for (o, order) in [Order::Velocity, Order::Acceleration, Order::Jerk]
            .into_iter()
            .enumerate()
        {
            traj.eval(t, order, &mut buf);
            for (j, &v) in buf.iter().enumerate() {
                worst[o] = worst[o].max(limits.joint(j).ratio(order, v));
            }
        }
    }
    (worst, outside)
}

/// Central differences of position, velocity and acceleration against the evaluated next
/// derivative (relative to 1 + its size), at `count` times away from the ends.
pub fn finite_difference_error(traj: &dyn Trajectory, count: usize) -> [f64; 3] {
    let n = traj.dof();
    let h = 1e-6;
    let (mut a, mut b, mut c) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let orders = [
        Order::Position,
        Order::Velocity,
        Order::Acceleration,
        Order::Jerk,
    ];
    let mut err = [0.0f64; 3];
    for k in 1..count {
        // Irrational fractions: away from the profile's segment boundaries.
        let t = traj.duration() * (k as f64 + 0.381_966) / (count as f64 + 1.0);
        for o in 0..3 {
            traj.eval(t + h, orders[o], &mut a);
            traj.eval(t - h, orders[o], &mut b);
            traj.eval(t, orders[o + 1], &mut c);
            for j in 0..n {
                let num = (a[j] - b[j]) / (2.0 * h);
                err[o] = err[o].max((num - c[j]).abs() / (1.0 + c[j].abs()));
            }
        }
    }
    err
}

/// A two-link arm moving in the vertical x-z plane (joint axes y, gravity −z), with effort
/// limits that bind (shared with the CLI's torque tests).
pub const ARM: &str = include_str!("../fixtures/two_link_arm.urdf");

/// The straight-line cases of `tools/jerk_line_fixtures.py` (Ruckig's exact optima).
pub fn line_cases() -> Vec<Value> {
    let p = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/jerk/lines.json"
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap();
    v["cases"].as_array().unwrap().clone()
}
