//! TOPP-RA between gridpoints: the exact extrema and sufficient rows of the joint velocity and
//! acceleration constraints on cubic pieces against dense sampling, the limits on the
//! continuous trajectory of seeded random Panda paths sampled at high rate (C² and C¹ splines,
//! polylines, collocation, a given grid without the breakpoints), and the duration of the
//! default grid against very fine grids.

mod topp_common;

use topp_common::{fixture_path, fixture_waypoints, fixtures, floats, worst_ratios};
use trajkit::rng::SplitMix64;
use trajkit::spline::{BoundedSpline, CubicSpline, PchipSpline};
use trajkit::topp::{
    messy, Constraint, ConstraintRows, CubicPiece, Discretization, Gridpoints, JointAcceleration,
    JointVelocity, LinearPath, Toppra, ToppraOptions,
};
use trajkit::{Limits, Order, Path, Trajectory};

/// A random cubic piece's data for `dim` joints on [s0, s0 + h].
struct PieceData {
    s0: f64,
    h: f64,
    d: [Vec<f64>; 6],
}

impl PieceData {
    /// A random cubic piece, or with `quintic` one of degree 5 (σ⁗ and σ⁽⁵⁾ nonzero, scaled
    /// to the piece's length so that they shape it).
    fn random(rng: &mut SplitMix64, dim: usize, quintic: bool) -> Self {
        let s0 = rng.uniform(-1.0, 1.0);
        let h = 10f64.powf(rng.uniform(-3.0, 0.0));
        let mut v = |r: f64| (0..dim).map(|_| rng.uniform(-r, r)).collect::<Vec<f64>>();
        let (r4, r5) = if quintic {
            (300.0 / h, 300.0 / (h * h))
        } else {
            (0.0, 0.0)
        };
        let d = [vec![0.0; dim], v(3.0), v(30.0), v(300.0), v(r4), v(r5)];
        PieceData { s0, h, d }
    }

    fn piece(&self) -> CubicPiece<'_> {
        CubicPiece {
            s0: self.s0,
            s1: self.s0 + self.h,
            d0: &self.d[0],
            d1: &self.d[1],
            d2: &self.d[2],
            d3: &self.d[3],
            d4: &self.d[4],
            d5: &self.d[5],
        }
    }
}

/// Worst relative excess of velocity (|v|/limit − 1) and acceleration (|a|/limit − 1) over
/// `samples` points of the piece.
fn sampled(
    piece: &CubicPiece<'_>,
    u: f64,
    x0: f64,
    vlim: &[f64],
    alim: &[f64],
    samples: usize,
) -> (f64, f64) {
    let (mut ev, mut ea) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    for k in 0..=samples {
        let s = piece.s0 + (piece.s1 - piece.s0) * k as f64 / samples as f64;
        let x = (x0 + 2.0 * u * (s - piece.s0)).max(0.0);
        for j in 0..vlim.len() {
            // σ′ and σ″ from the Taylor data directly (not the library's evaluation).
            let t = s - piece.s0;
            let (c1, c2, c3) = (piece.d1[j], piece.d2[j], piece.d3[j]);
            let (c4, c5) = (piece.d4[j], piece.d5[j]);
            let d1 = c1 + c2 * t + c3 * t * t / 2.0 + c4 * t.powi(3) / 6.0 + c5 * t.powi(4) / 24.0;
            let d2 = c2 + c3 * t + c4 * t * t / 2.0 + c5 * t.powi(3) / 6.0;
            ev = ev.max((d1 * x.sqrt()).abs() / vlim[j] - 1.0);
            let a = d1 * u + d2 * x;
            ea = ea.max(a.abs() / alim[j] - 1.0);
        }
    }
    (ev, ea)
}

/// Symmetric limits of three joints: velocity, acceleration, and the two constraints.
const VLIM: [f64; 3] = [1.0, 2.0, 0.5];
const ALIM: [f64; 3] = [4.0, 1.0, 2.5];

fn three_joint_constraints() -> (JointVelocity, JointAcceleration) {
    let neg = |l: [f64; 3]| l.map(|v| -v);
    (
        JointVelocity::new(&neg(VLIM), &VLIM).unwrap(),
        JointAcceleration::new(&neg(ALIM), &ALIM).unwrap(),
    )
}

#[test]
fn exact_extrema_match_dense_sampling() {
    exact_extrema_suite(false);
}

#[test]
fn exact_extrema_match_dense_sampling_on_quintic_pieces() {
    exact_extrema_suite(true);
}

fn exact_extrema_suite(quintic: bool) {
    let mut rng = SplitMix64::new(21);
    let dim = 3;
    let (vlim, alim) = (VLIM, ALIM);
    let (vel, acc) = three_joint_constraints();
    let mut found = [0usize; 2];
    for case in 0..400 {
        let data = PieceData::random(&mut rng, dim, quintic);
        let (piece, h) = (data.piece(), data.h);
        assert_eq!(piece.is_cubic(), !quintic);
        let x0 = rng.uniform(0.0, 0.5);
        let u = rng.uniform(-0.5, 0.5) * (x0 + 0.1) / h;
        if x0 + 2.0 * u * h < 0.0 {
            continue;
        }
        let (sv, sa) = sampled(&piece, u, x0, &vlim, &alim, 20_000);
        let (ev, at_v) = vel.excess_on_cubic(&piece, u, x0).unwrap();
        let (ea, at_a) = acc.excess_on_cubic(&piece, u, x0).unwrap();
        // Rigorous: never below what any sample shows.
        assert!(
            ev >= sv - 1e-12,
            "case {case}: velocity {ev} < sampled {sv}"
        );
        assert!(
            ea >= sa - 1e-12,
            "case {case}: acceleration {ea} < sampled {sa}"
        );
        // Exact where the limit is exceeded: dense sampling comes within its resolution.
        if ev > 0.0 {
            found[0] += 1;
            assert!(ev - sv < 1e-6 * (1.0 + ev), "case {case}: {ev} vs {sv}");
            assert!(at_v >= piece.s0 && at_v <= piece.s1);
        }
        if ea > 0.0 {
            found[1] += 1;
            assert!(ea - sa < 1e-6 * (1.0 + ea), "case {case}: {ea} vs {sa}");
            assert!(at_a >= piece.s0 && at_a <= piece.s1);
        }
    }
    assert!(found[0] > 50 && found[1] > 50, "{found:?}");
}

/// Rows of `c` at the ends of the piece, written in (u, x0) as the interpolation scheme does.
fn end_rows(c: &dyn Constraint, piece: &CubicPiece<'_>, out: &mut Vec<[f64; 3]>) {
    let dim = piece.d1.len();
    let (mut q, mut dq, mut ddq) = (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]);
    for (end, two_t) in [(piece.s0, 0.0), (piece.s1, 2.0 * (piece.s1 - piece.s0))] {
        piece.eval_into(end, &mut q, &mut dq, &mut ddq);
        let mut r = ConstraintRows::new();
        c.write(
            &trajkit::topp::PathPoint {
                s: end,
                q: &q,
                dq: &dq,
                ddq: &ddq,
            },
            &mut r,
        );
        for &[a, b, g] in r.half_planes() {
            out.push([a + two_t * b, b, g]);
        }
        let (_, x_max) = r.x_bounds();
        if x_max.is_finite() {
            out.push([two_t, 1.0, x_max]);
        }
    }
}

#[test]
fn sufficient_rows_imply_the_limits_on_the_whole_piece() {
    sufficient_rows_suite(false);
}

#[test]
fn sufficient_rows_imply_the_limits_on_the_whole_quintic_piece() {
    sufficient_rows_suite(true);
}

fn sufficient_rows_suite(quintic: bool) {
    let mut rng = SplitMix64::new(22);
    let dim = 3;
    let (vlim, alim) = (VLIM, ALIM);
    let (vel, acc) = three_joint_constraints();
    let mut tested = 0;
    for case in 0..300 {
        let data = PieceData::random(&mut rng, dim, quintic);
        let (piece, h) = (data.piece(), data.h);
        let mut rows = Vec::new();
        for c in [&vel as &dyn Constraint, &acc] {
            end_rows(c, &piece, &mut rows);
            let mut r = ConstraintRows::new();
            // Rows that cannot bind while x ≤ 0.3 at both ends may be left out.
            assert!(c.hold_on_cubic(&piece, [0.3, 0.3], &mut r));
            rows.extend_from_slice(r.half_planes());
        }
        // Random points of (u, x0); those meeting every row must hold the limits everywhere.
        // (Quintic pieces bend more: fewer points meet their rows, so draw more.)
        for _ in 0..if quintic { 80 } else { 40 } {
            let x0 = rng.uniform(0.0, 0.3);
            let u = rng.uniform(-0.5, 0.5) * (x0 + 0.05) / h;
            let x1 = x0 + 2.0 * u * h;
            if !(0.0..=0.3).contains(&x1) || rows.iter().any(|r| r[0] * u + r[1] * x0 > r[2]) {
                continue;
            }
            tested += 1;
            let (sv, sa) = sampled(&piece, u, x0, &vlim, &alim, 2_000);
            assert!(sv <= 1e-12 && sa <= 1e-12, "case {case}: {sv} {sa}");
        }
    }
    assert!(tested > 300, "{tested}");
}

fn random_waypoints(seed: u64, n: usize, lim: &Limits) -> Vec<f64> {
    let mut rng = SplitMix64::new(seed);
    let mut wp = Vec::new();
    for _ in 0..n {
        for j in lim.joints() {
            wp.push(rng.uniform(j.position_min + 0.1, j.position_max - 0.1));
        }
    }
    wp
}

fn panda_ranges(lim: &Limits, order: Order) -> (Vec<f64>, Vec<f64>) {
    lim.joints().iter().map(|j| j.range(order)).unzip()
}

/// Samples `traj` every `dt` (and finite differences) and checks the Panda's velocity and
/// acceleration limits within `tol` relative; returns the worst ratio.
fn assert_within<T: Trajectory>(traj: &T, lim: &Limits, dt: f64, tol: f64, what: &str) -> f64 {
    let (vlo, vhi) = panda_ranges(lim, Order::Velocity);
    let (alo, ahi) = panda_ranges(lim, Order::Acceleration);
    let w = worst_ratios(traj, &vlo, &vhi, &alo, &ahi, dt);
    let worst = w.velocity.max(w.acceleration);
    eprintln!(
        "{what}: duration {:.6} s, worst v {:.12} a {:.12} (fd {:.9} {:.9})",
        traj.duration(),
        w.velocity,
        w.acceleration,
        w.fd_velocity,
        w.fd_acceleration
    );
    assert!(
        worst <= 1.0 + tol,
        "{what}: {} {}",
        w.velocity,
        w.acceleration
    );
    assert!(
        w.fd_velocity.max(w.fd_acceleration) <= 1.0 + tol,
        "{what}: fd {} {}",
        w.fd_velocity,
        w.fd_acceleration
    );
    assert!(worst > 0.999, "{what}: not time-optimal ({worst})");
    worst
}

/// The precision contract's tolerance on piecewise-cubic paths (joint velocity and
/// acceleration, everywhere).
const EXACT: f64 = 1e-8;

fn continuous_suite(cases: u64, dt: f64) {
    let lim = Limits::preset("panda").unwrap();
    for case in 0..cases {
        let n = 3 + (case as usize % 5);
        let wp = random_waypoints(2000 + case, n, &lim);
        let ss: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
        let solve = |path: &dyn Path, opts: ToppraOptions| {
            Toppra::with_limits(path, &lim)
                .unwrap()
                .options(opts)
                .solve_profile()
                .unwrap_or_else(|e| panic!("case {case}: {e}"))
        };
        let natural = CubicSpline::natural(&ss, &wp, 7).unwrap();
        let traj = Toppra::with_limits(&natural, &lim)
            .unwrap()
            .solve()
            .unwrap();
        assert_within(
            &traj,
            &lim,
            dt,
            EXACT,
            &format!("case {case} natural, default"),
        );
        // A C¹ spline: σ″ jumps at the breakpoints (checked exactly there).
        let pchip = PchipSpline::new(&ss, &wp, 7).unwrap();
        let opts = ToppraOptions {
            gridpoints: Gridpoints::Uniform(300),
            ..ToppraOptions::default()
        };
        let traj = Toppra::with_limits(&pchip, &lim)
            .unwrap()
            .options(opts.clone())
            .solve()
            .unwrap();
        assert_within(&traj, &lim, dt, EXACT, &format!("case {case} pchip"));
        // Collocation: no rows at the interval's end, every interval verified exactly.
        let law = solve(
            &natural,
            ToppraOptions {
                discretization: Discretization::Collocation,
                ..opts.clone()
            },
        );
        let traj = trajkit::topp::Retimed::new(&natural, law).unwrap();
        assert_within(&traj, &lim, dt, EXACT, &format!("case {case} collocation"));
        // Given gridpoints that miss the breakpoints: those intervals are sampled and cut.
        let given: Vec<f64> = (0..=250).map(|k| k as f64 / 250.0 + 0.0).collect();
        let law = solve(
            &natural,
            ToppraOptions {
                gridpoints: Gridpoints::Given(given),
                ..ToppraOptions::default()
            },
        );
        let traj = trajkit::topp::Retimed::new(&natural, law).unwrap();
        let (vlo, vhi) = panda_ranges(&lim, Order::Velocity);
        let (alo, ahi) = panda_ranges(&lim, Order::Acceleration);
        let w = worst_ratios(&traj, &vlo, &vhi, &alo, &ahi, dt);
        // The sampled check's contract (3e-7 at its points, 1e-6 tested).
        assert!(
            w.velocity.max(w.acceleration) <= 1.0 + 1e-6,
            "case {case} given grid: {} {}",
            w.velocity,
            w.acceleration
        );
        // A polyline of collinear segments (a corner would need a stop: `messy` does that).
        let (a, b) = (&wp[..7], &wp[7..14]);
        let mut line_wp = a.to_vec();
        for f in [0.3, 0.35, 1.0] {
            line_wp.extend((0..7).map(|j| a[j] + f * (b[j] - a[j])));
        }
        let line = LinearPath::new(&line_wp, 7).unwrap();
        let traj = Toppra::with_limits(&line, &lim).unwrap().solve().unwrap();
        assert_within(&traj, &lim, dt, EXACT, &format!("case {case} polyline"));
    }
}

#[test]
fn limits_hold_on_the_continuous_trajectory() {
    continuous_suite(3, 1e-4);
}

#[test]
#[ignore = "long: 20 random paths, five schemes each, sampled at 50 kHz"]
fn limits_hold_on_the_continuous_trajectory_50khz() {
    continuous_suite(20, 2e-5);
}

/// The duration on the default grid against a grid of `reference` equal intervals (with the
/// same guarantee): at most `Gridpoints::Auto`'s 1e-4 above, never meaningfully below.
fn check_auto(name: &str, path: &dyn Path, lim_rows: (&[f64], &[f64], &[f64]), reference: usize) {
    let (vmax, amin, amax) = lim_rows;
    let vmin: Vec<f64> = vmax.iter().map(|v| -v).collect();
    let problem = || {
        Toppra::new(path)
            .constraint(JointVelocity::new(&vmin, vmax).unwrap())
            .unwrap()
            .constraint(JointAcceleration::new(amin, amax).unwrap())
            .unwrap()
    };
    let auto = problem().solve_profile().unwrap();
    let fine = problem()
        .gridpoints(Gridpoints::Uniform(reference))
        .solve_profile()
        .unwrap();
    let rel = (auto.duration() - fine.duration()) / fine.duration();
    eprintln!(
        "{name:30} auto {:.9} s ({} gridpoints), N = {reference}: {:.9} s, above by {rel:.2e}",
        auto.duration(),
        auto.gridpoints().len(),
        fine.duration()
    );
    assert!(rel <= 1e-4, "{name}: {rel}");
    assert!(rel >= -1e-6, "{name}: below the fine grid by {rel}");
}

fn auto_suite(fixture_names: Option<&[&str]>, random: u64, reference: usize) {
    for p in fixtures() {
        let name = p["name"].as_str().unwrap();
        if !p["toppra_ok"].as_bool().unwrap()
            || p["sd_start"].as_f64() != Some(0.0)
            || p["sd_end"].as_f64() != Some(0.0)
            || fixture_names.is_some_and(|f| !f.contains(&name))
        {
            continue;
        }
        let path = fixture_path(&p);
        let (vmax, amin, amax) = (floats(&p["vmax"]), floats(&p["amin"]), floats(&p["amax"]));
        check_auto(name, &path, (&vmax, &amin, &amax), reference);
    }
    let lim = Limits::preset("panda").unwrap();
    let (_, vmax) = panda_ranges(&lim, Order::Velocity);
    let (amin, amax) = panda_ranges(&lim, Order::Acceleration);
    for case in 0..random {
        let n = 3 + (case as usize * 7) % 18;
        let wp = random_waypoints(3000 + case, n, &lim);
        let ss: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
        let path = CubicSpline::natural(&ss, &wp, 7).unwrap();
        check_auto(
            &format!("random {case} ({n} waypoints)"),
            &path,
            (&vmax, &amin, &amax),
            reference,
        );
    }
}

#[test]
fn default_grid_is_within_its_duration_tolerance() {
    auto_suite(
        Some(&["standard_7wp_natural_N1000", "tiny_segment_1e-6"]),
        2,
        50_000,
    );
}

#[test]
#[ignore = "long: every fixture problem and 20 random paths against 2·10⁵ intervals (run with --release)"]
fn default_grid_is_within_its_duration_tolerance_all_problems() {
    auto_suite(None, 20, 200_000);
    repaired_auto_suite(200_000);
}

/// One long path piece and four short ones (the graded grid starts with equal counts per
/// piece, so the short pieces begin over-resolved and the long one under-resolved): within the
/// tolerance of a fine grid, every breakpoint kept.
#[test]
fn default_grid_is_within_its_duration_tolerance_on_unequal_pieces() {
    let lim = Limits::preset("panda").unwrap();
    let (_, vmax) = panda_ranges(&lim, Order::Velocity);
    let (amin, amax) = panda_ranges(&lim, Order::Acceleration);
    let wp = random_waypoints(4242, 6, &lim);
    let ss = [0.0, 0.92, 0.94, 0.96, 0.98, 1.0];
    let path = CubicSpline::natural(&ss, &wp, 7).unwrap();
    check_auto(
        "one long, four short pieces",
        &path,
        (&vmax, &amin, &amax),
        50_000,
    );
    let vmin: Vec<f64> = vmax.iter().map(|v| -v).collect();
    let auto = Toppra::new(&path)
        .constraint(JointVelocity::new(&vmin, &vmax).unwrap())
        .unwrap()
        .constraint(JointAcceleration::new(&amin, &amax).unwrap())
        .unwrap()
        .solve_profile()
        .unwrap();
    for b in path.breakpoints() {
        assert!(auto.gridpoints().contains(&b), "breakpoint {b} missing");
    }
}

/// The pieces `plan` times on the standard problem (range-repaired splines with quintic
/// pieces), where the default grid is graded: at most 1e-4 above `reference` equal intervals.
fn repaired_auto_suite(reference: usize) {
    let lim = Limits::preset("panda").unwrap();
    let (_, vmax) = panda_ranges(&lim, Order::Velocity);
    let (amin, amax) = panda_ranges(&lim, Order::Acceleration);
    let wp = fixture_waypoints("standard_7wp_natural_N1000");
    let paths = messy::piece_paths(&wp, 7, &lim, &messy::PlanOptions::default()).unwrap();
    for (k, piece) in paths.pieces.iter().enumerate() {
        check_auto(
            &format!("standard piece {k}"),
            &piece.path,
            (&vmax, &amin, &amax),
            reference,
        );
    }
}

#[test]
fn default_grid_is_within_its_duration_tolerance_on_repaired_pieces() {
    repaired_auto_suite(50_000);
}

/// Natural splines through random Panda waypoints that leave a position range are repaired
/// into quintic pieces ([`BoundedSpline`]); the default solve holds joint velocity and
/// acceleration on them as exactly as on cubic ones (sampled at 10 kHz).
#[test]
fn limits_hold_on_range_repaired_paths() {
    let lim = Limits::preset("panda").unwrap();
    let lo: Vec<f64> = lim.joints().iter().map(|j| j.position_min).collect();
    let hi: Vec<f64> = lim.joints().iter().map(|j| j.position_max).collect();
    let mut repaired = 0;
    for case in 0..40u64 {
        let n = 4 + (case as usize % 4);
        let wp = random_waypoints(5000 + case, n, &lim);
        let ss: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
        let natural = CubicSpline::natural(&ss, &wp, 7).unwrap();
        let bounded = BoundedSpline::new(natural.as_ppoly(), &lo, &hi).unwrap();
        if bounded.repairs().is_empty() {
            continue;
        }
        assert_eq!(bounded.piecewise_degree(), Some(5));
        repaired += 1;
        let traj = Toppra::with_limits(&bounded, &lim)
            .unwrap()
            .solve()
            .unwrap_or_else(|e| panic!("case {case}: {e}"));
        assert_within(&traj, &lim, 1e-4, EXACT, &format!("case {case} repaired"));
        if repaired == 4 {
            break;
        }
    }
    assert!(repaired >= 2, "only {repaired} paths needed a repair");
}
