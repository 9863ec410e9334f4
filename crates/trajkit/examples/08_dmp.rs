//! 08 — Learning from a demonstration: a DMP fitted to one 2-joint motion, replayed with a new
//! goal and twice as slow, then checked against limits like any other trajectory.
//!
//! Run: `cargo run -p trajkit --example 08_dmp`

use trajkit::check::check_trajectory;
use trajkit::primitives::{Dmp, DmpConfig, RolloutOptions};
use trajkit::{Limits, Order, Trajectory};

fn main() -> Result<(), trajkit::Error> {
    // A demonstration: 2 joints over 1 s, 200 samples (minimum-jerk plus a bump), at rest with
    // zero acceleration at both ends.
    let n = 200;
    let t: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    let mut q = Vec::with_capacity(2 * n);
    for &ti in &t {
        let s = 10.0 * ti.powi(3) - 15.0 * ti.powi(4) + 6.0 * ti.powi(5);
        q.push(0.8 * s + 0.1 * (std::f64::consts::PI * ti).sin().powi(4));
        q.push(-0.5 * s);
    }
    let dmp = Dmp::fit(&t, &q, 2, &DmpConfig::default())?; // α_z = 25, β_z = 6.25, 50 basis
                                                           // Replay as demonstrated: reproduces the demonstration.
    let same = dmp.rollout(&RolloutOptions::default())?;
    let mut y = [0.0; 2];
    let mut worst: f64 = 0.0;
    for (i, &ti) in t.iter().enumerate() {
        same.eval(ti, Order::Position, &mut y);
        worst = worst
            .max((y[0] - q[2 * i]).abs())
            .max((y[1] - q[2 * i + 1]).abs());
    }
    println!("reproduction: largest error {worst:.2e} rad");
    // New goal, twice as slow: same shape, scaled to the new goal.
    let opts = RolloutOptions {
        goal: Some(vec![1.2, -0.2]),
        tau: Some(2.0),
        duration: Some(3.0), // run past τ: a DMP converges to its goal asymptotically
        ..Default::default()
    };
    let replay = dmp.rollout(&opts)?;
    replay.eval(2.0, Order::Position, &mut y);
    println!("new goal [1.2, -0.2], τ = 2 s: at t = τ {y:.4?}");
    replay.eval(replay.duration(), Order::Position, &mut y);
    println!(
        "                         at t = {:.1} s {y:.4?}",
        replay.duration()
    );
    let limits = Limits::uniform(2, 2.0, 10.0, 200.0)?;
    let report = check_trajectory(&replay, &limits, 1000.0)?;
    println!("worst limit ratio of the replay: {:.3}", report.worst());
    Ok(())
}
