//! TOPP-RA: analytic cases, convergence, torque and end-effector constraints on a two-link
//! planar arm, and a seeded random suite with invariants on every case.

mod topp_common;

use topp_common::worst_for;
use trajkit::rng::SplitMix64;
use trajkit::spline::CubicSpline;
use trajkit::topp::{
    Discretization, EndEffectorSpeed, Gridpoints, InverseDynamics, Jacobian, JointAcceleration,
    JointTorque, JointVelocity, LinearPath, Toppra, ToppraOptions,
};
use trajkit::{Limits, Order, Path, Trajectory};

fn line(d: f64) -> LinearPath {
    LinearPath::new(&[0.0, d], 1).unwrap()
}

fn opts(n: usize) -> ToppraOptions {
    ToppraOptions {
        gridpoints: Gridpoints::Uniform(n),
        ..ToppraOptions::default()
    }
}

#[test]
fn straight_line_trapezoid_and_triangle_are_exact() {
    // D = 1, v = 1, a = 2: accelerate over 0.25, cruise 0.5, brake 0.25: T = D/v + v/a = 1.5.
    let lim = Limits::uniform(1, 1.0, 2.0, f64::INFINITY).unwrap();
    let traj = Toppra::with_limits(line(1.0), &lim)
        .unwrap()
        .options(opts(1000))
        .solve()
        .unwrap();
    assert!((traj.duration() - 1.5).abs() < 1e-9, "{}", traj.duration());
    // D = 1, v = 10, a = 1: triangle, T = 2·√(D/a) = 2.
    let lim = Limits::uniform(1, 10.0, 1.0, f64::INFINITY).unwrap();
    let traj = Toppra::with_limits(line(1.0), &lim)
        .unwrap()
        .options(opts(1000))
        .solve()
        .unwrap();
    assert!((traj.duration() - 2.0).abs() < 1e-9, "{}", traj.duration());
    // Mid-time: half-way, at peak velocity √(a·D) = 1, accelerating then braking.
    let mut v = [0.0];
    traj.eval(1.0, Order::Position, &mut v);
    assert!((v[0] - 0.5).abs() < 1e-9);
    traj.eval(1.0, Order::Velocity, &mut v);
    assert!((v[0] - 1.0).abs() < 1e-9);
    traj.eval(0.5, Order::Acceleration, &mut v);
    assert!((v[0] - 1.0).abs() < 1e-12);
    traj.eval(1.5, Order::Acceleration, &mut v);
    assert!((v[0] + 1.0).abs() < 1e-12);
    // Ends at rest at the end point.
    traj.eval(traj.duration(), Order::Position, &mut v);
    assert!((v[0] - 1.0).abs() < 1e-12);
    traj.eval(traj.duration(), Order::Velocity, &mut v);
    assert_eq!(v[0], 0.0);
}

#[test]
fn directional_limits_and_boundary_velocities() {
    // Accelerate at 2, brake at only 0.5: triangle with switch at D·amin/(amax + amin) from end.
    let acc = JointAcceleration::new(&[-0.5], &[2.0]).unwrap();
    let traj = Toppra::new(line(1.0))
        .constraint(acc.clone())
        .unwrap()
        .options(opts(1000))
        .solve()
        .unwrap();
    // x_peak = 2·2·s1 = 2·0.5·(1 − s1) → s1 = 0.2, v_peak = √0.8; T = v/2 + v/0.5.
    let vp = 0.8f64.sqrt();
    assert!(
        (traj.duration() - (vp / 2.0 + vp / 0.5)).abs() < 1e-9,
        "{}",
        traj.duration()
    );
    // Start moving at ṡ = 0.5, end at ṡ = 0.3 (no cap on ṡ; the line has no velocity limit).
    let traj = Toppra::new(line(1.0))
        .constraint(JointAcceleration::new(&[-1.0], &[1.0]).unwrap())
        .unwrap()
        .options(opts(1000))
        .boundary_velocities(0.5, 0.3)
        .solve()
        .unwrap();
    // Peak x from both sides: 0.25 + 2s = 0.09 + 2(1 − s) → s = 0.46, x = 1.17.
    let xp: f64 = 1.17;
    let t = (xp.sqrt() - 0.5) + (xp.sqrt() - 0.3);
    assert!(
        (traj.duration() - t).abs() < 1e-9,
        "{} vs {t}",
        traj.duration()
    );
    let mut v = [0.0];
    traj.eval(0.0, Order::Velocity, &mut v);
    assert!((v[0] - 0.5).abs() < 1e-12);
    traj.eval(traj.duration(), Order::Velocity, &mut v);
    assert!((v[0] - 0.3).abs() < 1e-12);
    // A large path velocity is not capped (toppra's C++ port caps ṡ at 10).
    let traj = Toppra::new(line(1000.0))
        .constraint(JointAcceleration::new(&[-1.0], &[1.0]).unwrap())
        .unwrap()
        .options(opts(1000))
        .solve()
        .unwrap();
    assert!((traj.duration() - 2.0 * 1000f64.sqrt()).abs() < 1e-6);
}

/// The benchmark problem: Panda, natural spline through 7 waypoints.
fn standard_problem() -> CubicSpline {
    let mut rng = SplitMix64::new(7);
    let lim = Limits::preset("panda").unwrap();
    let mut wp = Vec::new();
    for _ in 0..7 {
        for j in lim.joints() {
            wp.push(rng.uniform(j.position_min + 0.1, j.position_max - 0.1));
        }
    }
    let ss: Vec<f64> = (0..7).map(|i| i as f64 / 6.0).collect();
    CubicSpline::natural(&ss, &wp, 7).unwrap()
}

#[test]
fn duration_converges_with_the_grid() {
    let lim = Limits::preset("panda").unwrap();
    let path = standard_problem();
    let mut d = Vec::new();
    for n in [100, 1000, 10000] {
        let prof = Toppra::with_limits(&path, &lim)
            .unwrap()
            .options(ToppraOptions {
                refine: false,
                ..opts(n)
            })
            .solve_profile()
            .unwrap();
        eprintln!("N = {n}: duration {:.6} s", prof.duration());
        d.push(prof.duration());
    }
    // Differences shrink by about 10× per decade of N.
    let (e1, e2) = ((d[0] - d[2]).abs(), (d[1] - d[2]).abs());
    assert!(e2 < e1 / 5.0, "{d:?}");
    assert!(e2 / d[2] < 1e-3, "{d:?}");
}

#[test]
fn collocation_is_selectable() {
    let lim = Limits::preset("panda").unwrap();
    let path = standard_problem();
    let t = |disc| {
        Toppra::with_limits(&path, &lim)
            .unwrap()
            .options(ToppraOptions {
                discretization: disc,
                refine: false,
                ..opts(300)
            })
            .solve_profile()
            .unwrap()
            .duration()
    };
    let (ti, tc) = (
        t(Discretization::Interpolation),
        t(Discretization::Collocation),
    );
    // Collocation checks each interval at its start only; the durations differ little.
    assert!((tc - ti).abs() < 0.01 * ti, "{tc} vs {ti}");
}

/// Two-link planar arm, point masses m1, m2 at the ends of links l1, l2, gravity along −y.
struct TwoLink {
    m1: f64,
    m2: f64,
    l1: f64,
    l2: f64,
    g: f64,
}

impl TwoLink {
    fn arm() -> Self {
        TwoLink {
            m1: 1.0,
            m2: 0.8,
            l1: 0.5,
            l2: 0.4,
            g: 9.81,
        }
    }
}

impl InverseDynamics for TwoLink {
    fn dof(&self) -> usize {
        2
    }
    fn torque(&self, q: &[f64], qd: &[f64], qdd: &[f64], tau: &mut [f64]) {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        let (c2, s2) = (q[1].cos(), q[1].sin());
        let m11 = (m1 + m2) * l1 * l1 + m2 * l2 * l2 + 2.0 * m2 * l1 * l2 * c2;
        let m12 = m2 * l2 * l2 + m2 * l1 * l2 * c2;
        let m22 = m2 * l2 * l2;
        let h = m2 * l1 * l2 * s2;
        let g1 = (m1 + m2) * g * l1 * q[0].cos() + m2 * g * l2 * (q[0] + q[1]).cos();
        let g2 = m2 * g * l2 * (q[0] + q[1]).cos();
        tau[0] = m11 * qdd[0] + m12 * qdd[1] - h * (2.0 * qd[0] * qd[1] + qd[1] * qd[1]) + g1;
        tau[1] = m12 * qdd[0] + m22 * qdd[1] + h * qd[0] * qd[0] + g2;
    }
}

impl Jacobian for TwoLink {
    fn dof(&self) -> usize {
        2
    }
    fn rows(&self) -> usize {
        2
    }
    fn jacobian(&self, q: &[f64], out: &mut [f64]) {
        let (l1, l2) = (self.l1, self.l2);
        let (s1, c1) = q[0].sin_cos();
        let (s12, c12) = (q[0] + q[1]).sin_cos();
        out.copy_from_slice(&[-l1 * s1 - l2 * s12, -l2 * s12, l1 * c1 + l2 * c12, l2 * c12]);
    }
}

fn arm_path() -> CubicSpline {
    // From hanging-ish to raised, through a bend.
    let wp = [-1.2, 0.3, 0.0, 1.0, 0.9, -0.4, 1.4, 0.2];
    CubicSpline::natural(&[0.0, 0.4, 0.7, 1.0], &wp, 2).unwrap()
}

#[test]
fn torque_rows_match_the_analytic_arm() {
    use trajkit::topp::{Constraint, ConstraintRows, PathPoint};
    let arm = TwoLink::arm();
    let c = JointTorque::new(TwoLink::arm(), &[-20.0, -8.0], &[20.0, 8.0]).unwrap();
    let path = arm_path();
    let (mut q, mut dq, mut ddq) = ([0.0; 2], [0.0; 2], [0.0; 2]);
    for &s in &[0.1, 0.5, 0.85] {
        path.eval(s, 0, &mut q);
        path.eval(s, 1, &mut dq);
        path.eval(s, 2, &mut ddq);
        let mut rows = ConstraintRows::new();
        c.write(
            &PathPoint {
                s,
                q: &q,
                dq: &dq,
                ddq: &ddq,
            },
            &mut rows,
        );
        let hp = rows.half_planes();
        assert_eq!(hp.len(), 4);
        // For any (u, x), the upper rows say τ_j(u, x) ≤ limit with τ from the analytic model.
        for &(u, x) in &[(0.3f64, 2.0f64), (-1.0, 0.5)] {
            let qd = [dq[0] * x.sqrt(), dq[1] * x.sqrt()];
            let qdd = [dq[0] * u + ddq[0] * x, dq[1] * u + ddq[1] * x];
            let mut tau = [0.0; 2];
            arm.torque(&q, &qd, &qdd, &mut tau);
            for j in 0..2 {
                let [a, b, g] = hp[2 * j];
                let lim = [20.0, 8.0][j];
                // a·u + b·x ≤ g ⇔ τ ≤ lim, so τ = a·u + b·x + (lim − g).
                assert!(
                    (a * u + b * x + lim - g - tau[j]).abs() < 1e-12,
                    "s {s} joint {j}"
                );
            }
        }
    }
}

#[test]
fn torque_and_end_effector_limits_hold_on_the_output() {
    let arm = TwoLink::arm();
    let tmax = [14.0, 4.5];
    let vee = 1.2;
    let traj = Toppra::new(arm_path())
        .constraint(JointTorque::new(TwoLink::arm(), &[-tmax[0], -tmax[1]], &tmax).unwrap())
        .unwrap()
        .constraint(EndEffectorSpeed::new(TwoLink::arm(), vee).unwrap())
        .unwrap()
        .options(opts(300))
        .solve()
        .unwrap();
    let (mut q, mut qd, mut qdd, mut tau, mut jm) =
        ([0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2], [0.0; 4]);
    let (mut worst_tau, mut worst_v): (f64, f64) = (0.0, 0.0);
    let n = (traj.duration() / 1e-3) as usize;
    for k in 0..=n {
        let t = (k as f64 * 1e-3).min(traj.duration());
        traj.eval(t, Order::Position, &mut q);
        traj.eval(t, Order::Velocity, &mut qd);
        traj.eval(t, Order::Acceleration, &mut qdd);
        arm.torque(&q, &qd, &qdd, &mut tau);
        arm.jacobian(&q, &mut jm);
        let v = ((jm[0] * qd[0] + jm[1] * qd[1]).powi(2) + (jm[2] * qd[0] + jm[3] * qd[1]).powi(2))
            .sqrt();
        worst_v = worst_v.max(v / vee);
        for j in 0..2 {
            worst_tau = worst_tau.max(tau[j].abs() / tmax[j]);
        }
    }
    eprintln!("worst torque ratio {worst_tau}, end-effector speed ratio {worst_v}");
    assert!(worst_tau <= 1.0 + 1e-6 && worst_v <= 1.0 + 1e-6);
    assert!(
        worst_tau.max(worst_v) > 0.999,
        "time-optimal: a limit is reached"
    );
}

#[test]
fn coulomb_friction_costs_time() {
    let t = |fc: [f64; 2]| {
        Toppra::new(arm_path())
            .constraint(
                JointTorque::new(TwoLink::arm(), &[-14.0, -4.5], &[14.0, 4.5])
                    .unwrap()
                    .with_coulomb_friction(&fc)
                    .unwrap(),
            )
            .unwrap()
            .options(ToppraOptions {
                refine: false,
                ..opts(200)
            })
            .solve_profile()
            .unwrap()
            .duration()
    };
    assert!(t([1.0, 0.5]) > t([0.0, 0.0]));
    assert!(JointTorque::new(TwoLink::arm(), &[-1.0], &[1.0]).is_err());
}

/// Seeded random Panda problems: spline through 3..8 random waypoints; invariants on each.
fn random_suite(cases: u64) {
    let lim = Limits::preset("panda").unwrap();
    for case in 0..cases {
        let mut rng = SplitMix64::new(1000 + case);
        let n = 3 + rng.below(6) as usize;
        let mut wp = Vec::new();
        for _ in 0..n {
            for j in lim.joints() {
                wp.push(rng.uniform(j.position_min, j.position_max));
            }
        }
        let ss: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
        let path = CubicSpline::natural(&ss, &wp, 7).unwrap();
        let grid = 50 + rng.below(300) as usize;
        let traj = Toppra::with_limits(&path, &lim)
            .unwrap()
            .options(opts(grid))
            .solve()
            .unwrap_or_else(|e| panic!("case {case}: {e}"));
        let w = worst_for(&traj, &lim);
        let lim1 = 1.0 + 1e-6;
        assert!(
            w.velocity <= lim1 && w.acceleration <= lim1,
            "case {case}: {} {}",
            w.velocity,
            w.acceleration
        );
        assert!(
            w.fd_velocity <= lim1 && w.fd_acceleration <= lim1,
            "case {case}"
        );
        assert!(
            w.velocity.max(w.acceleration) > 0.999,
            "case {case}: not time-optimal"
        );
        // Starts and ends at rest on the waypoints.
        let mut q = [0.0; 7];
        traj.eval(traj.duration(), Order::Position, &mut q);
        for j in 0..7 {
            assert!((q[j] - wp[(n - 1) * 7 + j]).abs() < 1e-9, "case {case}");
        }
        traj.eval(0.0, Order::Velocity, &mut q);
        assert!(q.iter().all(|v| *v == 0.0));
    }
}

#[test]
fn seeded_random_panda_problems() {
    random_suite(1);
}

#[test]
#[ignore = "long: 100 random problems with 1 ms sampling"]
fn seeded_random_panda_problems_long() {
    random_suite(100);
}

#[test]
fn bad_input_is_a_typed_error() {
    let lim = Limits::uniform(2, 1.0, 1.0, 1.0).unwrap();
    let e = Toppra::with_limits(line(1.0), &lim).err().unwrap();
    assert!(e.to_string().contains("expected 1, found 2"), "{e}");
    let e = Toppra::new(line(1.0))
        .constraint(JointVelocity::new(&[-1.0], &[1.0]).unwrap())
        .unwrap()
        .boundary_velocities(f64::NAN, 0.0)
        .solve_profile()
        .unwrap_err();
    assert!(e.to_string().contains("start path velocity = NaN"), "{e}");
    let e = Toppra::new(line(1.0))
        .constraint(JointVelocity::new(&[-1.0], &[1.0]).unwrap())
        .unwrap()
        .gridpoints(Gridpoints::Uniform(0))
        .solve_profile()
        .unwrap_err();
    assert!(
        e.to_string().contains("gridpoint interval count = 0"),
        "{e}"
    );
    // Only a velocity limit: nothing bounds the acceleration, the profile jumps to the limit.
    let t = Toppra::new(line(1.0))
        .constraint(JointVelocity::new(&[-1.0], &[1.0]).unwrap())
        .unwrap()
        .boundary_velocities(1.0, 1.0)
        .solve()
        .unwrap();
    assert!((t.duration() - 1.0).abs() < 1e-12);
    // No constraint at all: unbounded, an error (not a made-up duration).
    let e = Toppra::new(line(1.0)).solve_profile().unwrap_err();
    assert!(
        e.to_string()
            .contains("no constraint bounds the path velocity"),
        "{e}"
    );
}

#[test]
fn without_refinement_the_excess_between_gridpoints_shrinks_with_n() {
    let lim = Limits::preset("panda").unwrap();
    let path = standard_problem();
    let excess = |n: usize| {
        let traj = Toppra::with_limits(&path, &lim)
            .unwrap()
            .options(ToppraOptions {
                refine: false,
                ..opts(n)
            })
            .solve()
            .unwrap();
        let w = worst_for(&traj, &lim);
        w.velocity.max(w.acceleration) - 1.0
    };
    let (e1, e2, e3) = (excess(100), excess(400), excess(1600));
    eprintln!("excess over the limits between gridpoints: N=100 {e1:.2e}, N=400 {e2:.2e}, N=1600 {e3:.2e}");
    assert!(e1 > 0.0, "coarse grids do exceed between gridpoints: {e1}");
    assert!(e2 < e1 / 2.0 && e3 < e2 / 2.0, "{e1} {e2} {e3}");
}
