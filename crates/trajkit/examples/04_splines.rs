//! 04 — Splines through timed waypoints: a natural cubic spline, shape-preserving PCHIP and the
//! minimum-jerk quintic spline through the same points, compared on overshoot and peak jerk and
//! checked against a robot's limits; then a C² orientation spline through three keyframes.
//!
//! Run: `cargo run -p trajkit --example 04_splines`.

use trajkit::spline::{BSpline, CubicSpline, PchipSpline, Quat, SO3Spline};
use trajkit::{Limits, Path, PathAsTrajectory};

fn main() -> Result<(), trajkit::Error> {
    // 2 joints, 5 waypoints at t = 0, 1, 2, 3.5, 4.5 s (row-major: a row per waypoint).
    let t = [0.0, 1.0, 2.0, 3.5, 4.5];
    let q = [0.0, 0.0, 0.5, -0.2, 0.5, 0.4, 1.2, 0.4, 1.2, 0.0];
    let z = [0.0, 0.0];
    let curves: Vec<(&str, Box<dyn Path>)> = vec![
        ("natural cubic", Box::new(CubicSpline::natural(&t, &q, 2)?)),
        ("PCHIP", Box::new(PchipSpline::new(&t, &q, 2)?)),
        (
            "minimum jerk",
            Box::new(BSpline::minimum_jerk(&t, &q, 2, &z, &z, &z, &z)?),
        ),
    ];
    let limits = Limits::new(Limits::preset("panda")?.joints()[..2].to_vec())?;
    for (name, c) in &curves {
        // Overshoot of joint 1 on the flat stretch between t = 1 and t = 2 (both at 0.5).
        let mut p = [0.0; 2];
        let mut over = 0.0f64;
        let mut jerk = 0.0f64;
        for i in 0..=4500 {
            let s = i as f64 / 1000.0;
            c.eval(s, 0, &mut p);
            if (1.0..=2.0).contains(&s) {
                over = over.max((p[0] - 0.5).abs());
            }
            c.eval(s, 3, &mut p);
            jerk = jerk.max(p[0].abs()).max(p[1].abs());
        }
        let report =
            trajkit::check::check_trajectory(&PathAsTrajectory(c.as_ref()), &limits, 1000.0)?;
        println!(
            "{name:>14}: overshoot on the flat stretch {over:.4} rad, peak |jerk| {jerk:8.3} rad/s³, worst limit ratio {:.3}",
            report.worst()
        );
    }
    // Orientation: three keyframes one second apart, C² with angular velocity and acceleration.
    let keys = [
        Quat::IDENTITY,
        Quat::from_axis_angle([0.0, 0.0, 1.0], 0.8)?,
        Quat::from_axis_angle([1.0, 0.0, 0.0], 0.5)?,
    ];
    let so3 = SO3Spline::interpolate_uniform(0.0, 1.0, &keys)?;
    let (qm, w, a) = so3.eval_all(0.5);
    println!(
        "SO(3) spline at t = 0.5 s: q = {:?}, ω = {:.3?} rad/s, α = {:.3?} rad/s²",
        qm.to_array().map(|v| (v * 1e4).round() / 1e4),
        w,
        a
    );
    Ok(())
}
