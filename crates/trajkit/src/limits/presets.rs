//! Robot presets: joint limits of common arms, with the source of every figure.
//!
//! | name | robot | joints |
//! |------|-------|--------|
//! | `panda` | Franka Emika Panda (FR3's predecessor) | 7 |
//! | `ur5e` | Universal Robots UR5e | 6 |
//! | `iiwa14` | KUKA LBR iiwa 14 R820 | 7 |
//!
//! Where a manufacturer publishes no acceleration or jerk limit (UR5e, iiwa), the preset uses
//! a conservative value chosen by trajkit and says so; override it with a MoveIt
//! `joint_limits.yaml` or explicit values ([`crate::Limits::with_override`]).

use super::{JointLimits, Limits};
use crate::error::{Error, Result};

/// Names accepted by [`by_name`].
pub const NAMES: &str = "panda, ur5e, iiwa14";

/// A preset by name (case-insensitive; `franka` and `kuka_iiwa14` are accepted aliases).
pub fn by_name(name: &str) -> Result<Limits> {
    match name.to_ascii_lowercase().as_str() {
        "panda" | "franka" | "franka_panda" => Ok(panda()),
        "ur5e" => Ok(ur5e()),
        "iiwa14" | "iiwa" | "kuka_iiwa14" | "lbr_iiwa_14_r820" => Ok(iiwa14()),
        _ => Err(Error::UnknownPreset {
            name: name.to_string(),
            known: NAMES,
        }),
    }
}

fn build(
    names: &[&str],
    qmin: &[f64],
    qmax: &[f64],
    v: &[f64],
    a: &[f64],
    j: &[f64],
    effort: &[f64],
) -> Limits {
    let joints = (0..names.len())
        .map(|i| JointLimits {
            name: names[i].to_string(),
            position_min: qmin[i],
            position_max: qmax[i],
            velocity: v[i],
            acceleration: a[i],
            jerk: j[i],
            min_velocity: None,
            min_acceleration: None,
            effort: Some(effort[i]),
        })
        .collect();
    Limits::new(joints).expect("preset data is valid")
}

/// Franka Emika Panda, 7 joints.
///
/// Source: Franka Emika, *Panda Robot and Interface Specifications* ("Limits for Panda",
/// joint space): q_max/q_min, q̇_max 2.175 (joints 1–4) and 2.61 rad/s (5–7), q̈_max
/// 15, 7.5, 10, 12.5, 15, 20, 20 rad/s², q⃛_max 7500, 3750, 5000, 6250, 7500, 10000,
/// 10000 rad/s³, τ_max 87 (1–4) and 12 N·m (5–7).
pub fn panda() -> Limits {
    build(
        &[
            "panda_joint1",
            "panda_joint2",
            "panda_joint3",
            "panda_joint4",
            "panda_joint5",
            "panda_joint6",
            "panda_joint7",
        ],
        &[
            -2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973,
        ],
        &[2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973],
        &[2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61],
        &[15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0],
        &[7500.0, 3750.0, 5000.0, 6250.0, 7500.0, 10000.0, 10000.0],
        &[87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0],
    )
}

/// Universal Robots UR5e, 6 joints.
///
/// Source: Universal Robots, *UR5e technical specifications* (e-Series datasheet): working range
/// ±360° on every joint, maximum speed ±180°/s (π rad/s) on every joint; joint torques from
/// UR's "Max. joint torques" support article: 150 N·m (size-3 joints: base, shoulder, elbow),
/// 28 N·m (size-1 wrist joints).
///
/// Not published by the manufacturer, chosen by trajkit as conservative values: acceleration
/// 10 rad/s² and jerk 5000 rad/s³ on every joint.
pub fn ur5e() -> Limits {
    let tau = std::f64::consts::TAU;
    let pi = std::f64::consts::PI;
    build(
        &[
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint",
        ],
        &[-tau; 6],
        &[tau; 6],
        &[pi; 6],
        &[10.0; 6],
        &[5000.0; 6],
        &[150.0, 150.0, 150.0, 28.0, 28.0, 28.0],
    )
}

/// KUKA LBR iiwa 14 R820, 7 joints.
///
/// Source: KUKA, *LBR iiwa 7 R800, LBR iiwa 14 R820 Specification*: axis ranges ±170°, ±120°,
/// ±170°, ±120°, ±170°, ±120°, ±175°; maximum speeds 85, 85, 100, 75, 130, 135, 135 °/s;
/// maximum torques 320, 320, 176, 176, 110, 40, 40 N·m.
///
/// Not published by the manufacturer, chosen by trajkit as conservative values: acceleration
/// 10 rad/s² and jerk 5000 rad/s³ on every joint.
pub fn iiwa14() -> Limits {
    let d = std::f64::consts::PI / 180.0;
    let range = [170.0, 120.0, 170.0, 120.0, 170.0, 120.0, 175.0].map(|x: f64| x * d);
    let speed = [85.0, 85.0, 100.0, 75.0, 130.0, 135.0, 135.0].map(|x: f64| x * d);
    build(
        &[
            "iiwa_joint_1",
            "iiwa_joint_2",
            "iiwa_joint_3",
            "iiwa_joint_4",
            "iiwa_joint_5",
            "iiwa_joint_6",
            "iiwa_joint_7",
        ],
        &range.map(|x| -x),
        &range,
        &speed,
        &[10.0; 7],
        &[5000.0; 7],
        &[320.0, 320.0, 176.0, 176.0, 110.0, 40.0, 40.0],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_load_and_match_datasheets() {
        let p = by_name("Panda").unwrap();
        assert_eq!(p.dof(), 7);
        assert_eq!(p.joint(3).position_max, -0.0698);
        assert_eq!(p.joint(6).jerk, 10000.0);
        assert_eq!(p.joint(1).acceleration, 7.5);
        let u = by_name("ur5e").unwrap();
        assert_eq!(u.dof(), 6);
        assert!((u.joint(0).velocity - std::f64::consts::PI).abs() < 1e-15);
        let k = by_name("iiwa14").unwrap();
        assert_eq!(k.dof(), 7);
        assert!((k.joint(3).velocity - 75f64.to_radians()).abs() < 1e-15);
        let e = by_name("pr2").unwrap_err().to_string();
        assert!(e.contains("pr2") && e.contains("panda"), "{e}");
    }
}
