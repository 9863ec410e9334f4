//! Tests of the dynamics model: closed forms, hand computations, structure, bad input.

use super::spatial::rpy_matrix;
use super::*;
use crate::error::Error;
use crate::rng::SplitMix64;

const G: f64 = 9.81;

fn link(name: &str, inertial: &str) -> String {
    format!("<link name=\"{name}\">{inertial}</link>")
}

fn inertial(xyz: &str, mass: f64, izz: f64) -> String {
    format!(
        "<inertial><origin xyz=\"{xyz}\"/><mass value=\"{mass}\"/>\
         <inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"{izz}\"/></inertial>"
    )
}

fn joint(name: &str, kind: &str, parent: &str, child: &str, origin: &str, axis: &str) -> String {
    format!(
        "<joint name=\"{name}\" type=\"{kind}\"><parent link=\"{parent}\"/>\
         <child link=\"{child}\"/><origin {origin}/><axis xyz=\"{axis}\"/></joint>"
    )
}

/// Two-link planar arm in the x-y plane (joint axes z): link lengths l1, centres of mass
/// at lc1, lc2 along each link, masses m1, m2, inertias i1, i2 about z.
const ARM: (f64, f64, f64, f64, f64, f64, f64) = (0.7, 0.3, 0.25, 2.0, 1.5, 0.04, 0.02);

fn arm_urdf() -> String {
    let (l1, lc1, lc2, m1, m2, i1, i2) = ARM;
    format!(
        "<robot name=\"arm\">{}{}{}{}{}</robot>",
        link("base", ""),
        link("l1", &inertial(&format!("{lc1} 0 0"), m1, i1)),
        link("l2", &inertial(&format!("{lc2} 0 0"), m2, i2)),
        joint("j1", "revolute", "base", "l1", "xyz=\"0 0 0\"", "0 0 1"),
        joint(
            "j2",
            "continuous",
            "l1",
            "l2",
            &format!("xyz=\"{l1} 0 0\""),
            "0 0 1"
        ),
    )
}

fn tau(chain: &SerialChain, q: &[f64], qd: &[f64], qdd: &[f64]) -> Vec<f64> {
    let mut t = vec![0.0; q.len()];
    chain.torque(q, qd, qdd, &mut t);
    t
}

#[test]
fn two_link_planar_arm_matches_closed_form() {
    let (l1, lc1, lc2, m1, m2, i1, i2) = ARM;
    let chain = SerialChain::from_urdf_str(&arm_urdf(), "arm.urdf")
        .unwrap()
        .with_gravity([0.0, -G, 0.0])
        .unwrap();
    assert_eq!(chain.joint_names(), vec!["j1", "j2"]);
    let mut rng = SplitMix64::new(7);
    for _ in 0..50 {
        let q: Vec<f64> = (0..2).map(|_| rng.uniform(-3.0, 3.0)).collect();
        let qd: Vec<f64> = (0..2).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let qdd: Vec<f64> = (0..2).map(|_| rng.uniform(-5.0, 5.0)).collect();
        let (c1, c2, c12) = (q[0].cos(), q[1].cos(), (q[0] + q[1]).cos());
        let s2 = q[1].sin();
        let m11 = m1 * lc1 * lc1 + i1 + m2 * (l1 * l1 + lc2 * lc2 + 2.0 * l1 * lc2 * c2) + i2;
        let m12 = m2 * (lc2 * lc2 + l1 * lc2 * c2) + i2;
        let m22 = m2 * lc2 * lc2 + i2;
        let h = m2 * l1 * lc2 * s2;
        let g1 = (m1 * lc1 + m2 * l1) * G * c1 + m2 * lc2 * G * c12;
        let g2 = m2 * lc2 * G * c12;
        let want = [
            m11 * qdd[0] + m12 * qdd[1] - h * (2.0 * qd[0] * qd[1] + qd[1] * qd[1]) + g1,
            m12 * qdd[0] + m22 * qdd[1] + h * qd[0] * qd[0] + g2,
        ];
        let got = tau(&chain, &q, &qd, &qdd);
        for j in 0..2 {
            assert!(
                (got[j] - want[j]).abs() <= 1e-12 * want[j].abs().max(1.0),
                "joint {j}: {} vs {}",
                got[j],
                want[j]
            );
        }
    }
}

#[test]
fn single_pendulum() {
    // Arm along x, hinge about y, default gravity −z (a positive angle lowers the arm):
    // τ = (m l² + Iyy) q̈ − m g l cos q.
    let (m, l, iyy) = (2.0, 0.5, 0.03);
    let urdf = format!(
        "<robot name=\"p\"><link name=\"base\"/><link name=\"arm\"><inertial>\
         <origin xyz=\"{l} 0 0\" rpy=\"0.3 0 0.2\"/><mass value=\"{m}\"/>\
         <inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"{iyy}\" iyz=\"0\" izz=\"0\"/>\
         </inertial></link>{}</robot>",
        joint("hinge", "revolute", "base", "arm", "xyz=\"0 0 1\"", "0 2 0")
    );
    // The inertial frame's rotation must not change Iyy about y only if it is a rotation
    // about y; use rpy = 0 for the closed form and check the rotated one separately.
    let plain = urdf.replace("rpy=\"0.3 0 0.2\"", "");
    let chain = SerialChain::from_urdf_str(&plain, "p.urdf").unwrap();
    assert_eq!(chain.gravity(), [0.0, 0.0, -G]);
    assert_eq!(chain.moving_mass(), m);
    for &(q, qd, qdd) in &[(0.0, 0.0, 0.0), (0.7, 1.3, -2.0), (-2.5, -0.4, 3.0)] {
        let want = (m * l * l + iyy) * qdd - m * G * l * f64::cos(q);
        let got = tau(&chain, &[q], &[qd], &[qdd])[0];
        assert!(
            (got - want).abs() <= 1e-12 * want.abs().max(1.0),
            "{got} vs {want}"
        );
    }
    // Rotated inertial frame: the moment of inertia about y becomes
    // Iyy·(R_y·y)² summed over the rotated axes: only the y row of R matters.
    let rotated = SerialChain::from_urdf_str(&urdf, "p.urdf").unwrap();
    let r = rpy_matrix([0.3, 0.0, 0.2]);
    let iyy_rot = r[1][1] * r[1][1] * iyy;
    let want = m * l * l + iyy_rot;
    let got = tau(&rotated, &[0.4], &[0.0], &[1.0])[0] - tau(&rotated, &[0.4], &[0.0], &[0.0])[0];
    assert!((got - want).abs() < 1e-12, "{got} vs {want}");
}

/// Three revolute joints about y, fixed joints in between (one with a yaw), masses on the
/// fixed links too.
fn three_joint_urdf() -> String {
    let full = |xyz: &str, mass: f64| {
        format!(
            "<inertial><origin xyz=\"{xyz}\" rpy=\"0.1 -0.2 0.3\"/><mass value=\"{mass}\"/>\
             <inertia ixx=\"0.02\" ixy=\"0.001\" ixz=\"-0.002\" iyy=\"0.03\" iyz=\"0.003\" \
             izz=\"0.025\"/></inertial>"
        )
    };
    format!(
        "<robot name=\"three\">\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n{}\n</robot>",
        link("base", ""),
        link("l1", &full("0.2 0 0", 2.0)),
        link("l1b", &full("0.1 0 0", 1.0)),
        link("l2", &full("0.25 0 0", 1.5)),
        link("l2b", ""),
        link("l3", &full("0 0.2 0", 0.5)),
        joint("j1", "revolute", "base", "l1", "xyz=\"0 0 0.5\"", "0 1 0"),
        joint("f1", "fixed", "l1", "l1b", "xyz=\"0.4 0 0\"", "1 0 0"),
        joint("j2", "revolute", "l1b", "l2", "xyz=\"0.3 0 0\"", "0 1 0"),
        joint(
            "f2",
            "fixed",
            "l2",
            "l2b",
            "xyz=\"0.5 0 0\" rpy=\"0 0 1.5707963267948966\"",
            "1 0 0"
        ),
        joint("j3", "revolute", "l2b", "l3", "xyz=\"0 0 0\"", "1 0 0"),
        // A massless tool flange after the last joint.
        joint("f3", "fixed", "l3", "tool", "xyz=\"0 0 0.1\"", "1 0 0"),
    )
    .replace("</robot>", &format!("{}</robot>", link("tool", "")))
}

#[test]
fn gravity_torques_with_fixed_joints_match_hand_computation() {
    let chain = SerialChain::from_urdf_str(&three_joint_urdf(), "three.urdf").unwrap();
    assert_eq!(chain.joint_names(), vec!["j1", "j2", "j3"]);
    // At q = 0 along x: l1 com 0.2, l1b com 0.5, j2 at 0.7, l2 com 0.95, j3 at 1.2, l3 com
    // at 1.2 − 0.2 = 1.0 (its +y is the world's −x after the yaw). A mass m at horizontal
    // offset dx from a y axis needs τ = −m g dx (a positive angle about y lowers +x).
    let want0 = [
        -G * (2.0 * 0.2 + 1.0 * 0.5 + 1.5 * 0.95 + 0.5 * 1.0),
        -G * (1.5 * 0.25 + 0.5 * 0.3),
        -G * (0.5 * -0.2),
    ];
    let got = tau(&chain, &[0.0; 3], &[0.0; 3], &[0.0; 3]);
    for j in 0..3 {
        assert!(
            (got[j] - want0[j]).abs() < 1e-12,
            "{j}: {} vs {}",
            got[j],
            want0[j]
        );
    }
    // All axes are parallel (world y): with q1 = 0.3 every horizontal offset shrinks by
    // cos 0.3, with q2 = -0.5 as well the offsets beyond joint 2 follow the sum.
    let (a, b) = (0.3_f64, -0.5_f64);
    let x1 = |d: f64| d * a.cos();
    let x2 = |d: f64| d * (a + b).cos();
    let want = [
        -G * (2.0 * x1(0.2)
            + 1.0 * x1(0.5)
            + 1.5 * (x1(0.7) + x2(0.25))
            + 0.5 * (x1(0.7) + x2(0.3))),
        -G * (1.5 * x2(0.25) + 0.5 * x2(0.3)),
        -G * 0.5 * x2(-0.2),
    ];
    let got = tau(&chain, &[a, b, 0.0], &[0.0; 3], &[0.0; 3]);
    for j in 0..3 {
        assert!(
            (got[j] - want[j]).abs() < 1e-12,
            "{j}: {} vs {}",
            got[j],
            want[j]
        );
    }
}

#[test]
fn torque_is_affine_in_acceleration_with_spd_mass_matrix() {
    let mut urdf = three_joint_urdf();
    // Make the last joint prismatic too, to cover that branch.
    urdf = urdf.replace(
        "name=\"j3\" type=\"revolute\"",
        "name=\"j3\" type=\"prismatic\"",
    );
    let chain = SerialChain::from_urdf_str(&urdf, "three.urdf").unwrap();
    let n = 3;
    let mut rng = SplitMix64::new(42);
    for _ in 0..30 {
        let mut v = |k: f64| -> Vec<f64> { (0..n).map(|_| rng.uniform(-k, k)).collect() };
        let (q, qd, qdd1, qdd2) = (v(2.5), v(2.0), v(4.0), v(4.0));
        let zero = vec![0.0; n];
        let bias = tau(&chain, &q, &zero, &zero);
        let mut m = vec![0.0; n * n];
        for c in 0..n {
            let mut e = zero.clone();
            e[c] = 1.0;
            let col = tau(&chain, &q, &zero, &e);
            for r in 0..n {
                m[r * n + c] = col[r] - bias[r];
            }
        }
        for r in 0..n {
            for c in 0..n {
                assert!(
                    (m[r * n + c] - m[c * n + r]).abs() < 1e-12,
                    "M not symmetric"
                );
            }
        }
        crate::linalg::Cholesky::factor(&m, n).expect("M positive definite");
        let sum: Vec<f64> = qdd1.iter().zip(&qdd2).map(|(a, b)| a + b).collect();
        let t12 = tau(&chain, &q, &qd, &sum);
        let t2 = tau(&chain, &q, &qd, &qdd2);
        for r in 0..n {
            let mq: f64 = (0..n).map(|c| m[r * n + c] * qdd1[c]).sum();
            assert!((t12[r] - t2[r] - mq).abs() < 1e-11, "row {r}");
        }
    }
    // Wrong slice lengths give NaN, not a panic.
    let mut t = [0.0; 2];
    chain.torque(&[0.0; 2], &[0.0; 2], &[0.0; 2], &mut t);
    assert!(t.iter().all(|x| x.is_nan()));
}

fn parse_err(text: &str) -> (usize, String, String) {
    match SerialChain::from_urdf_str(text, "bad.urdf").unwrap_err() {
        Error::Parse { location, message } => {
            assert_eq!(location.source, "bad.urdf");
            (location.line, location.field, message)
        }
        e => panic!("not a parse error: {e}"),
    }
}

#[test]
fn bad_input_names_file_line_field_value() {
    let arm = arm_urdf().replace("><", ">\n<");
    let line_with = |s: &str, needle: &str| s.lines().position(|l| l.contains(needle)).unwrap() + 1;
    // Missing mass.
    let t = arm.replace("<mass value=\"1.5\"/>", "");
    let (line, field, msg) = parse_err(&t);
    assert_eq!(field, "link 'l2' <mass>");
    assert!(msg.contains("no <mass>"), "{msg}");
    assert!(line > 0);
    // Non-finite and non-numeric values.
    let t = arm.replace("izz=\"0.02\"", "izz=\"NaN\"");
    let (line, field, msg) = parse_err(&t);
    assert_eq!(field, "link 'l2' <inertia izz>");
    assert!(msg.contains("'NaN'"), "{msg}");
    assert_eq!(line, line_with(&t, "izz=\"NaN\""));
    let t = arm.replace("xyz=\"0.7 0 0\"", "xyz=\"0.7 zero 0\"");
    let (_, field, msg) = parse_err(&t);
    assert_eq!(field, "joint 'j2' <origin xyz>");
    assert!(msg.contains("'zero'"), "{msg}");
    let t = arm.replace("xyz=\"0.7 0 0\"", "xyz=\"0.7 0\"");
    assert!(parse_err(&t).2.contains("expected 3"));
    let t = arm.replace("<mass value=\"2\"/>", "<mass value=\"-2\"/>");
    assert!(parse_err(&t).2.contains("-2 is negative"));
    // Unknown and unsupported joint types.
    let t = arm.replace("type=\"continuous\"", "type=\"hinge\"");
    let (line, field, msg) = parse_err(&t);
    assert_eq!(field, "joint 'j2' type");
    assert!(msg.contains("'hinge'"), "{msg}");
    assert_eq!(line, line_with(&t, "type=\"hinge\""));
    let t = arm.replace("type=\"continuous\"", "type=\"floating\"");
    assert!(parse_err(&t).2.contains("not supported"));
    // No movable joint.
    let t = arm
        .replace("type=\"continuous\"", "type=\"fixed\"")
        .replace("type=\"revolute\"", "type=\"fixed\"");
    assert!(parse_err(&t).2.contains("no movable joint"));
    // A branching tree names the link.
    let t = arm.replace(
        "</robot>",
        &format!(
            "{}{}</robot>",
            link("l3", ""),
            joint("j3", "revolute", "l1", "l3", "xyz=\"0 0 0\"", "0 0 1")
        ),
    );
    let (_, field, msg) = parse_err(&t);
    assert_eq!(field, "link 'l1'");
    assert!(msg.contains("not a serial chain"), "{msg}");
    // Chain order differing from the file order.
    let j1 = joint("j1", "revolute", "base", "l1", "xyz=\"0 0 0\"", "0 0 1").replace("><", ">\n<");
    let t = arm
        .replace(&j1, "")
        .replace("</robot>", &format!("{j1}</robot>"));
    assert!(parse_err(&t)
        .2
        .contains("differs from their order in the file"));
    // Zero axis, undefined link, bad gravity, too many joints.
    let t = arm.replacen("<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 0 0\"/>", 1);
    assert!(parse_err(&t).2.contains("not a direction"));
    let t = arm.replace("<child link=\"l2\"/>", "<child link=\"nowhere\"/>");
    assert!(parse_err(&t).2.contains("'nowhere' is not defined"));
    assert!(SerialChain::from_urdf_str(&arm, "a")
        .unwrap()
        .with_gravity([0.0, f64::INFINITY, 0.0])
        .is_err());
    let mut long = String::from("<robot name=\"long\"><link name=\"l0\"/>");
    for i in 1..=MAX_JOINTS + 1 {
        long += &link(&format!("l{i}"), "");
        long += &joint(
            &format!("j{i}"),
            "revolute",
            &format!("l{}", i - 1),
            &format!("l{i}"),
            "xyz=\"0 0 0\"",
            "0 0 1",
        );
    }
    long += "</robot>";
    assert!(parse_err(&long).2.contains("more than 32"));
    assert!(parse_err("<robot").2.contains("not well-formed"));
    assert!(matches!(
        SerialChain::from_urdf_file(std::path::Path::new("/nonexistent/robot.urdf")),
        Err(Error::Io { .. })
    ));
}
