//! Real-time paths allocate nothing: trajectory evaluation is run under a counting global
//! allocator and must not allocate once constructed.

mod alloc_counter;
use alloc_counter::{allocations, exercise};

use trajkit::poly::{Degree, PolyMove, ViaTiming, ViaTrajectory, ViaVelocities};
use trajkit::{Limits, Trajectory};

#[test]
fn evaluation_allocates_nothing() {
    let limits = Limits::preset("panda").unwrap();
    let q0 = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];
    let q1 = [1.2, 0.3, -0.5, -1.2, 0.6, 2.2, -0.4];
    let mv = PolyMove::rest_to_rest(Degree::Septic, &q0, &q1, 2.0).unwrap();
    let mut wps = q0.to_vec();
    wps.extend_from_slice(&q1);
    wps.extend_from_slice(&q0);
    let via = ViaTrajectory::new(
        &wps,
        7,
        Degree::Quintic,
        ViaVelocities::Heuristic,
        ViaTiming::Limits(&limits),
    )
    .unwrap();
    let path_traj = trajkit::PathAsTrajectory(LinePath);
    let cases: [(&str, &dyn Trajectory); 3] = [
        ("PolyMove", &mv),
        ("ViaTrajectory", &via),
        ("PathAsTrajectory", &path_traj),
    ];
    for (name, tr) in cases {
        let mut sink = 0.0;
        let n = allocations(|| sink = exercise(tr, 2000));
        assert!(sink.is_finite() || sink.is_nan());
        assert_eq!(n, 0, "{name} allocated {n} times during evaluation");
    }
    // The counter works: a Vec allocates.
    assert!(allocations(|| drop(std::hint::black_box(vec![1u8; 10]))) >= 1);
}

/// A straight line in 2-D as a path, to cover the adapter.
struct LinePath;
impl trajkit::Path for LinePath {
    fn dim(&self) -> usize {
        2
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        let s = s.clamp(0.0, 1.0);
        match order {
            0 => out[..2].copy_from_slice(&[s, 2.0 * s]),
            1 => out[..2].copy_from_slice(&[1.0, 2.0]),
            _ => out[..2].fill(0.0),
        }
    }
}
