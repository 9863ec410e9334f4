//! Unit tests of the constraint rows.

use super::*;

#[test]
fn bulk_intervals_equal_single_intervals() {
    let a = [1.0, 0.0, -2.0, 0.0, 0.5];
    let b = [0.5, 0.0, 0.0, 3.0, -1.0];
    let lo = [-1.0, -2.0, f64::NEG_INFINITY, -4.0, 0.0];
    let hi = [2.0, 1.0, 3.0, f64::INFINITY, 0.0];
    let mut bulk = ConstraintRows::new();
    bulk.intervals(&a, &b, &lo, &hi);
    let mut one = ConstraintRows::new();
    for j in 0..a.len() {
        one.interval(a[j], b[j], 0.0, lo[j], hi[j]);
    }
    assert_eq!(bulk.half_planes(), one.half_planes());
    assert!(bulk.broken.is_none());
    // A static joint whose range excludes zero cannot hold; a NaN is reported.
    let mut r = ConstraintRows::new();
    r.intervals(&[0.0], &[0.0], &[0.5], &[1.0]);
    assert!(r.broken.is_some());
    let mut r = ConstraintRows::new();
    r.intervals(&[f64::NAN], &[0.0], &[-1.0], &[1.0]);
    assert!(r.broken.is_some());
}

#[test]
fn rows_from_acceleration_and_velocity() {
    let p = PathPoint {
        s: 0.0,
        q: &[0.0, 0.0],
        dq: &[2.0, -1.0],
        ddq: &[0.5, 0.0],
    };
    let mut r = ConstraintRows::new();
    JointVelocity::new(&[-1.0, -3.0], &[4.0, 1.0])
        .unwrap()
        .write(&p, &mut r);
    // joint 1: ṡ ≤ 4/2 = 2; joint 2 moves negatively: ṡ ≤ -3/-1 = 3 → x ≤ 4.
    assert_eq!(r.x_bounds(), (0.0, 4.0));
    let mut r = ConstraintRows::new();
    JointAcceleration::new(&[-1.0, -2.0], &[3.0, f64::INFINITY])
        .unwrap()
        .write(&p, &mut r);
    assert_eq!(
        r.half_planes(),
        &[[2.0, 0.5, 3.0], [-2.0, -0.5, 1.0], [1.0, -0.0, 2.0]]
    );
    assert!(JointVelocity::new(&[0.5], &[1.0]).is_err());
    let e = JointAcceleration::new(&[-1.0], &[f64::NAN]).unwrap_err();
    assert!(e
        .to_string()
        .contains("joint 1 acceleration upper limit = NaN"));
}

#[test]
fn polytope_and_broken_rows() {
    let mut r = ConstraintRows::new();
    // v = (u, x) itself, F = [1 1], g = [2]: u + x ≤ 2.
    r.polytope(&[1.0, 0.0], &[0.0, 1.0], &[0.0, 0.0], &[1.0, 1.0], &[2.0]);
    assert_eq!(r.half_planes(), &[[1.0, 1.0, 2.0]]);
    r.interval(0.0, 0.0, 1.0, -1.0, 0.5);
    assert!(r.broken.is_some());
}
