//! Quaternions, slerp and the C² SO(3) spline: keyframes, continuity, angular velocity and
//! acceleration against finite differences, and the single-axis case against the natural cubic
//! spline of the angles.

use std::ops::Mul;
use trajkit::rng::SplitMix64;
use trajkit::spline::{CubicSpline, Quat, SO3Spline};
use trajkit::Path;

fn random_quat(r: &mut SplitMix64) -> Quat {
    Quat::new(r.normal(), r.normal(), r.normal(), r.normal()).unwrap()
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[test]
fn exp_log_rotate_and_slerp() {
    let mut r = SplitMix64::new(31);
    for _ in 0..200 {
        let q = random_quat(&mut r);
        let back = Quat::exp(q.log());
        assert!(q.angle_to(back) < 1e-14);
        let v = [r.normal(), r.normal(), r.normal()];
        let rv = q.rotate(v);
        assert!((norm(rv) - norm(v)).abs() < 1e-14 * norm(v).max(1.0));
        assert!(norm(sub(q.conj().rotate(rv), v)) < 1e-13);
        let p = random_quat(&mut r);
        assert!(q.slerp(p, 0.0).angle_to(q) < 1e-14);
        assert!(q.slerp(p, 1.0).angle_to(p) < 1e-14);
        let th = q.angle_to(p);
        let m = q.slerp(p, 0.3);
        assert!(
            (q.angle_to(m) - 0.3 * th).abs() < 1e-13 && (m.angle_to(p) - 0.7 * th).abs() < 1e-13
        );
        // Constant angular velocity: finite difference of the orientation.
        let w = q.slerp_velocity(p);
        let h = 1e-6;
        let d = q.slerp(p, 0.5 + h).mul(q.slerp(p, 0.5 - h).conj()).log();
        assert!(
            norm(sub(
                w,
                [d[0] / (2.0 * h), d[1] / (2.0 * h), d[2] / (2.0 * h)]
            )) < 1e-7
        );
    }
    // Small angles.
    let tiny = Quat::exp([1e-10, -2e-10, 3e-10]);
    let l = tiny.log();
    assert!((l[0] - 1e-10).abs() < 1e-24 && (l[2] - 3e-10).abs() < 1e-24);
    assert!(Quat::new(0.0, 0.0, 0.0, 0.0).is_err() && Quat::new(f64::NAN, 1.0, 0.0, 0.0).is_err());
    assert!(Quat::from_axis_angle([0.0; 3], 1.0).is_err());
}

#[test]
fn so3_spline_hits_keyframes_is_c2_and_derivatives_match_differences() {
    let mut r = SplitMix64::new(32);
    for case in 0..15 {
        let n = 2 + case % 8;
        let mut keys = vec![random_quat(&mut r)];
        for _ in 1..n {
            let step = [
                r.uniform(-1.0, 1.0),
                r.uniform(-1.0, 1.0),
                r.uniform(-1.0, 1.0),
            ];
            keys.push(keys.last().unwrap().mul(Quat::exp(step)));
        }
        let dt = r.uniform(0.2, 2.0);
        let sp = SO3Spline::interpolate_uniform(1.0, dt, &keys).unwrap();
        assert_eq!(sp.interval(), (1.0, 1.0 + (n - 1) as f64 * dt));
        for (i, k) in keys.iter().enumerate() {
            assert!(
                sp.eval(1.0 + i as f64 * dt).angle_to(*k) < 1e-12,
                "keyframe {i}"
            );
        }
        // Natural ends: zero angular acceleration.
        let (a, e) = sp.interval();
        assert!(norm(sp.angular_acceleration(a)) < 1e-9);
        assert!(norm(sp.angular_acceleration(e)) < 1e-9);
        // Continuity of ω and α across knots.
        for i in 1..n - 1 {
            let t = 1.0 + i as f64 * dt;
            let (_, w0, a0) = sp.eval_all(t - 1e-12);
            let (_, w1, a1) = sp.eval_all(t);
            assert!(
                norm(sub(w0, w1)) < 1e-9 && norm(sub(a0, a1)) < 1e-8,
                "C2 at knot {i}"
            );
        }
        // Finite differences.
        let h = 1e-6;
        for k in 0..10 {
            let t = a + (e - a) * (k as f64 + 0.5) / 10.0;
            let d = sp.eval(t + h).mul(sp.eval(t - h).conj()).log();
            let fd_w = [d[0] / (2.0 * h), d[1] / (2.0 * h), d[2] / (2.0 * h)];
            let (_, w, al) = sp.eval_all(t);
            assert!(
                norm(sub(fd_w, w)) < 1e-6 * (1.0 + norm(w)),
                "ω: {fd_w:?} vs {w:?}"
            );
            let (wp, wm) = (sp.angular_velocity(t + h), sp.angular_velocity(t - h));
            let fd_a = [
                (wp[0] - wm[0]) / (2.0 * h),
                (wp[1] - wm[1]) / (2.0 * h),
                (wp[2] - wm[2]) / (2.0 * h),
            ];
            assert!(
                norm(sub(fd_a, al)) < 1e-5 * (1.0 + norm(al)),
                "α: {fd_a:?} vs {al:?}"
            );
        }
    }
}

#[test]
fn single_axis_spline_is_the_natural_cubic_spline_of_the_angles() {
    let angles = [0.0, 0.7, 1.1, 0.4, -0.3, 0.2];
    let axis = [0.0, 0.6, 0.8];
    let keys: Vec<Quat> = angles
        .iter()
        .map(|&a| Quat::from_axis_angle(axis, a).unwrap())
        .collect();
    let dt = 0.5;
    let sp = SO3Spline::interpolate_uniform(0.0, dt, &keys).unwrap();
    let x: Vec<f64> = (0..angles.len()).map(|i| i as f64 * dt).collect();
    let cs = CubicSpline::natural(&x, &angles, 1).unwrap();
    let mut v = [0.0];
    for k in 0..=50 {
        let t = x[x.len() - 1] * k as f64 / 50.0;
        let (q, w, a) = sp.eval_all(t);
        let phi = q.log();
        let ang = phi[1] / axis[1];
        cs.eval(t, 0, &mut v);
        assert!(
            (ang - v[0]).abs() < 1e-12,
            "angle at {t}: {ang} vs {}",
            v[0]
        );
        cs.eval(t, 1, &mut v);
        assert!((w[1] / axis[1] - v[0]).abs() < 1e-11 && w[0].abs() < 1e-12);
        cs.eval(t, 2, &mut v);
        assert!((a[2] / axis[2] - v[0]).abs() < 1e-10);
    }
}

#[test]
fn so3_bad_input_and_clamping() {
    let q = Quat::IDENTITY;
    assert!(SO3Spline::interpolate_uniform(0.0, 1.0, &[q]).is_err());
    assert!(SO3Spline::interpolate_uniform(0.0, 0.0, &[q, q]).is_err());
    assert!(SO3Spline::interpolate_uniform(f64::NAN, 1.0, &[q, q]).is_err());
    assert!(SO3Spline::from_control_rotations(0.0, 1.0, &[q, q, q]).is_err());
    let k = Quat::from_axis_angle([1.0, 0.0, 0.0], 1.0).unwrap();
    let sp = SO3Spline::interpolate_uniform(0.0, 1.0, &[q, k]).unwrap();
    assert!(sp.eval(-5.0).angle_to(q) < 1e-14 && sp.eval(9.0).angle_to(k) < 1e-14);
    assert!(sp.eval(f64::NAN).w.is_nan());
}

#[test]
fn so3_spline_at_uneven_times() {
    let mut r = SplitMix64::new(33);
    for case in 0..15 {
        let n = 2 + case % 7;
        let mut times = vec![r.uniform(-1.0, 1.0)];
        for _ in 1..n {
            let l = *times.last().unwrap();
            times.push(l + r.uniform(0.3, 1.5));
        }
        let mut keys = vec![random_quat(&mut r)];
        for _ in 1..n {
            let step = [
                r.uniform(-0.5, 0.5),
                r.uniform(-0.5, 0.5),
                r.uniform(-0.5, 0.5),
            ];
            keys.push(keys.last().unwrap().mul(Quat::exp(step)));
        }
        let sp = SO3Spline::interpolate(&times, &keys).unwrap();
        assert_eq!(sp.interval(), (times[0], times[n - 1]));
        for i in 0..n {
            assert!(
                sp.eval(times[i]).angle_to(keys[i]) < 1e-12,
                "case {case} keyframe {i}"
            );
        }
        for i in 1..n - 1 {
            let (_, w0, a0) = sp.eval_all(times[i] - 1e-12);
            let (_, w1, a1) = sp.eval_all(times[i]);
            assert!(
                norm(sub(w0, w1)) < 1e-8 && norm(sub(a0, a1)) < 1e-7,
                "C2 at {i}"
            );
        }
        let h = 1e-6;
        for k in 0..10 {
            let t = times[0] + (times[n - 1] - times[0]) * (k as f64 + 0.5) / 10.0;
            let d = sp.eval(t + h).mul(sp.eval(t - h).conj()).log();
            let fd_w = [d[0] / (2.0 * h), d[1] / (2.0 * h), d[2] / (2.0 * h)];
            let (_, w, al) = sp.eval_all(t);
            assert!(norm(sub(fd_w, w)) < 1e-6 * (1.0 + norm(w)), "ω");
            let (wp, wm) = (sp.angular_velocity(t + h), sp.angular_velocity(t - h));
            let fd_a = [
                (wp[0] - wm[0]) / (2.0 * h),
                (wp[1] - wm[1]) / (2.0 * h),
                (wp[2] - wm[2]) / (2.0 * h),
            ];
            assert!(norm(sub(fd_a, al)) < 1e-5 * (1.0 + norm(al)), "α");
        }
    }
    // Evenly spaced times give the uniform spline.
    let keys = [
        Quat::IDENTITY,
        Quat::exp([0.2, 0.4, 0.0]),
        Quat::exp([0.0, 0.3, 0.9]),
    ];
    let a = SO3Spline::interpolate(&[1.0, 1.5, 2.0], &keys).unwrap();
    let b = SO3Spline::interpolate_uniform(1.0, 0.5, &keys).unwrap();
    for k in 0..=10 {
        let t = 1.0 + 0.1 * k as f64;
        assert!(a.eval(t).angle_to(b.eval(t)) < 1e-14);
    }
    assert!(matches!(
        SO3Spline::interpolate(&[0.0, 1.0, 1.0], &keys),
        Err(trajkit::Error::DuplicateWaypoint { .. })
    ));
    assert!(SO3Spline::interpolate(&[0.0, 1.0], &keys).is_err());
}

#[test]
fn sharply_turning_keyframes_are_refused_with_a_typed_error() {
    // A zig-zag of 1.4 rad about one axis: the interpolating control polygon would need
    // rotations 4.2 rad apart (three times the zig-zag, as for a Euclidean cubic spline).
    let keys: Vec<Quat> = (0..8)
        .map(|i| {
            Quat::from_axis_angle([0.0, 0.0, 1.0], if i % 2 == 0 { 0.0 } else { 1.4 }).unwrap()
        })
        .collect();
    let e = SO3Spline::interpolate_uniform(0.0, 1.0, &keys).unwrap_err();
    assert!(matches!(e, trajkit::Error::Infeasible(_)), "{e}");
    // Half the amplitude is fine.
    let keys: Vec<Quat> = (0..8)
        .map(|i| {
            Quat::from_axis_angle([0.0, 0.0, 1.0], if i % 2 == 0 { 0.0 } else { 0.7 }).unwrap()
        })
        .collect();
    assert!(SO3Spline::interpolate_uniform(0.0, 1.0, &keys).is_ok());
}

#[test]
fn quaternion_derivatives_match_differences_along_a_spline() {
    // q̇ = ½ ω ∗ q and q̈ = ½ (ω̇ ∗ q + ω ∗ q̇) with the spline's own ω, ω̇ against central
    // differences of its quaternion components; products and log/exp against their
    // definitions.
    let mut r = SplitMix64::new(33);
    let keys: Vec<Quat> = (0..6).map(|_| random_quat(&mut r)).collect();
    let mut keys_near = vec![keys[0]];
    for i in 1..6 {
        let step = [0.6 * keys[i].x, -0.5 * keys[i].y, 0.7 * keys[i].z];
        keys_near.push(keys_near[i - 1].mul(Quat::exp(step)));
    }
    let sp = SO3Spline::interpolate_uniform(0.0, 0.5, &keys_near).unwrap();
    let h = 1e-5;
    for k in 1..50 {
        let t = 2.5 * k as f64 / 50.0;
        let (q, w, dw) = sp.eval_all(t);
        let (qm, qp) = (sp.eval(t - h).to_array(), sp.eval(t + h).to_array());
        let q0 = q.to_array();
        let d1 = q.derivative(w);
        let d2 = q.second_derivative(w, dw);
        for c in 0..4 {
            let fd1 = (qp[c] - qm[c]) / (2.0 * h);
            let fd2 = (qp[c] - 2.0 * q0[c] + qm[c]) / (h * h);
            assert!(
                (d1[c] - fd1).abs() < 1e-8,
                "t={t} q̇[{c}]: {} vs {fd1}",
                d1[c]
            );
            assert!(
                (d2[c] - fd2).abs() < 2e-4,
                "t={t} q̈[{c}]: {} vs {fd2}",
                d2[c]
            );
        }
        // q̇ is tangent to the unit sphere: q · q̇ = 0.
        let dot: f64 = (0..4).map(|c| q0[c] * d1[c]).sum();
        assert!(dot.abs() < 1e-14, "{dot}");
    }
    // A constant rate about a fixed axis: q(t) = exp(ωt) q₀, so q̇(0) = ½ ω ∗ q₀ exactly and
    // q̈(0) = −¼ ‖ω‖² q₀.
    let q0 = random_quat(&mut r);
    let w = [0.3, -1.1, 0.4];
    let d2 = q0.second_derivative(w, [0.0; 3]);
    let w2 = 0.3 * 0.3 + 1.1 * 1.1 + 0.4 * 0.4;
    for (c, v) in q0.to_array().iter().enumerate() {
        assert!((d2[c] + 0.25 * w2 * v).abs() < 1e-15);
    }
    let step = Quat::exp([0.3e-7, -1.1e-7, 0.4e-7]).mul(q0).to_array();
    let d1 = q0.derivative(w);
    for c in 0..4 {
        assert!((d1[c] - (step[c] - q0.to_array()[c]) / 1e-7).abs() < 1e-6);
    }
    // exp of a rotation vector about z is (cos θ/2, 0, 0, sin θ/2); log inverts it; the
    // product composes angles about one axis.
    let a = Quat::exp([0.0, 0.0, 0.8]);
    assert!((a.w - 0.4f64.cos()).abs() < 1e-16 && (a.z - 0.4f64.sin()).abs() < 1e-16);
    assert!((a.log()[2] - 0.8).abs() < 1e-15);
    let b = a.mul(Quat::exp([0.0, 0.0, 0.5]));
    assert!((b.log()[2] - 1.3).abs() < 1e-15 && b.log()[0].abs() < 1e-16);
}
