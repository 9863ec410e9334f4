//! Multi-waypoint piecewise polynomials: one synchronized polynomial segment between each pair
//! of consecutive waypoints, with chosen velocities at the via points.

use super::{
    min_duration, min_duration_rest_to_rest, worst_ratio_of, Degree, EndState, JointTable,
    Polynomial,
};
use crate::error::{Error, Result};
use crate::limits::Limits;
use crate::traj::{find_piece, Order, Trajectory};

/// Velocities at the interior waypoints (the first and last are always at rest).
#[derive(Debug, Clone, PartialEq)]
pub enum ViaVelocities {
    /// Stop at every waypoint (as MATLAB's `quinticpolytraj` does by default).
    Zero,
    /// Continuous-velocity heuristic: per joint, the mean of the average velocities of the
    /// segments before and after the waypoint, or zero where they differ in sign (the joint
    /// turns around there) or either is zero. Average velocities come from the rest-to-rest
    /// timing of each segment; each segment is then re-timed for its actual end velocities.
    Heuristic,
    /// Given velocities, row-major `(waypoints − 2) × dof` for the interior waypoints.
    Given(Vec<f64>),
}

/// How segment durations are chosen.
#[derive(Debug, Clone, PartialEq)]
pub enum ViaTiming<'a> {
    /// Given durations, one per segment.
    Durations(Vec<f64>),
    /// The shortest duration of each segment that keeps every joint within these limits (all
    /// joints of a segment arrive together).
    Limits(&'a Limits),
}

/// Piecewise polynomial through waypoints: segment i joins waypoint i to i+1 over
/// `[breaks[i], breaks[i+1]]`, accelerations (and jerks) zero at every waypoint, velocities per
/// [`ViaVelocities`]. Position, velocity and acceleration are continuous at the waypoints
/// (jerk too for septic segments, acceleration not for cubic ones).
///
/// ```
/// use trajkit::poly::{Degree, ViaTrajectory, ViaTiming, ViaVelocities};
/// use trajkit::{Limits, Trajectory};
/// let limits = Limits::uniform(2, 1.0, 5.0, 50.0)?;
/// let waypoints = [0.0, 0.0, 1.0, 0.5, 2.0, 0.0]; // 3 waypoints × 2 joints, row-major
/// let tr = ViaTrajectory::new(&waypoints, 2, Degree::Quintic, ViaVelocities::Heuristic,
///                             ViaTiming::Limits(&limits))?;
/// assert_eq!(tr.segments(), 2);
/// assert!(tr.worst_limit_ratio(&limits)? <= 1.0 + 1e-9);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ViaTrajectory {
    dof: usize,
    breaks: Vec<f64>,
    /// `segments × dof` polynomials, row-major.
    polys: Vec<Polynomial>,
    /// One evaluation table per segment.
    tables: Vec<JointTable>,
    /// Velocities at the interior waypoints, row-major `(waypoints − 2) × dof`.
    vias: Vec<f64>,
}

impl ViaTrajectory {
    /// Builds the trajectory through `waypoints` (row-major, `n × dof`, n ≥ 2). Consecutive
    /// identical waypoints are an error ([`Error::DuplicateWaypoint`]); remove them first with
    /// [`crate::io::Waypoints::dedup`] if the input may hold them.
    pub fn new(
        waypoints: &[f64],
        dof: usize,
        degree: Degree,
        velocities: ViaVelocities,
        timing: ViaTiming<'_>,
    ) -> Result<Self> {
        ViaTrajectory::with_accelerations(waypoints, dof, degree, velocities, None, timing)
    }

    /// Like [`ViaTrajectory::new`], with given accelerations at the interior waypoints
    /// (row-major `(waypoints − 2) × dof`; quintic and septic only). `None` means zero.
    pub fn with_accelerations(
        waypoints: &[f64],
        dof: usize,
        degree: Degree,
        velocities: ViaVelocities,
        accelerations: Option<&[f64]>,
        timing: ViaTiming<'_>,
    ) -> Result<Self> {
        let n = check_waypoints(waypoints, dof)?;
        let wp = |i: usize| &waypoints[i * dof..(i + 1) * dof];
        if let ViaTiming::Limits(l) = &timing {
            l.expect_dof(dof, "waypoints")?;
        }
        let segs = n - 1;
        let base = rest_durations(waypoints, dof, degree, &timing)?;
        let vel = interior_velocities(waypoints, dof, velocities, &base)?;
        if let Some(acc) = accelerations {
            check_interior(acc, n, dof, "acceleration")?;
        }
        let end_state = |k: usize| -> EndState {
            let interior = k != 0 && k != n - 1;
            let qd = if interior {
                vel[(k - 1) * dof..k * dof].to_vec()
            } else {
                Vec::new()
            };
            let qdd = match accelerations {
                Some(a) if interior => a[(k - 1) * dof..k * dof].to_vec(),
                _ => Vec::new(),
            };
            EndState {
                q: wp(k).to_vec(),
                qd,
                qdd,
                ..Default::default()
            }
        };
        for k in 1..n - 1 {
            let st = end_state(k);
            st.validate("via point", dof, degree)?;
        }
        let all_rest = vel.iter().all(|&v| v == 0.0)
            && accelerations.is_none_or(|a| a.iter().all(|&x| x == 0.0));
        let durations: Vec<f64> = match &timing {
            ViaTiming::Durations(d) => d.clone(),
            ViaTiming::Limits(l) if !all_rest => (0..segs)
                .map(|i| min_duration(degree, &end_state(i), &end_state(i + 1), l))
                .collect::<Result<_>>()?,
            ViaTiming::Limits(_) => base,
        };
        let m = degree.conditions_per_end();
        let mut breaks = Vec::with_capacity(n);
        breaks.push(0.0);
        let mut polys = Vec::with_capacity(segs * dof);
        for i in 0..segs {
            let (s, e) = (end_state(i), end_state(i + 1));
            for j in 0..dof {
                let sc: Vec<f64> = (0..m).map(|k| s.get(k, j)).collect();
                let ec: Vec<f64> = (0..m).map(|k| e.get(k, j)).collect();
                polys.push(Polynomial::from_boundary(&sc, &ec, durations[i])?);
            }
            breaks.push(breaks[i] + durations[i]);
        }
        let tables = polys.chunks(dof).map(JointTable::new).collect();
        Ok(ViaTrajectory {
            dof,
            breaks,
            polys,
            tables,
            vias: vel,
        })
    }

    /// Like [`ViaTrajectory::new`] timed by `limits` ([`ViaTiming::Limits`]), and kept inside
    /// every joint's position range: where a segment of a joint leaves its range (exact
    /// extrema of the segment's polynomial), that joint's velocity at the segment's interior
    /// waypoints becomes 0 and the trajectory is built again, until no segment leaves. A
    /// segment at rest at both ends moves monotonically between its two waypoints, so this
    /// ends with every segment inside (at worst every via velocity of that joint zero).
    /// Returns the trajectory and how many via velocities were set to 0.
    ///
    /// Errors: [`Error::WaypointOutOfRange`] for a waypoint outside its joint's range, and
    /// those of [`ViaTrajectory::new`].
    ///
    /// ```
    /// use trajkit::poly::{Degree, ViaTrajectory, ViaVelocities};
    /// use trajkit::{JointLimits, Limits};
    /// let mut j = JointLimits::symmetric(1.0, 5.0, 50.0);
    /// (j.position_min, j.position_max) = (-1.0, 1.0);
    /// let limits = Limits::new(vec![j])?;
    /// // Rises to 0.99, then on to 1.0: the heuristic velocity at 0.99 overshoots 1.0.
    /// let w = [0.0, 0.99, 1.0];
    /// let (tr, zeroed) =
    ///     ViaTrajectory::within_limits(&w, 1, Degree::Quintic, ViaVelocities::Heuristic, &limits)?;
    /// assert_eq!(zeroed, 1);
    /// assert!(tr.position_ranges()[0].1 <= 1.0);
    /// # Ok::<(), trajkit::Error>(())
    /// ```
    pub fn within_limits(
        waypoints: &[f64],
        dof: usize,
        degree: Degree,
        velocities: ViaVelocities,
        limits: &Limits,
    ) -> Result<(Self, usize)> {
        limits.expect_dof(dof, "waypoints")?;
        limits.check_waypoints(waypoints, None)?;
        let mut tr = ViaTrajectory::new(
            waypoints,
            dof,
            degree,
            velocities,
            ViaTiming::Limits(limits),
        )?;
        let mut zeroed = 0;
        loop {
            let mut vel = tr.vias.clone();
            let mut changed = false;
            for (i, seg) in tr.polys.chunks(dof).enumerate() {
                for (j, p) in seg.iter().enumerate() {
                    let jl = limits.joint(j);
                    let tol = 1e-12
                        * [1.0, jl.position_min.abs(), jl.position_max.abs()]
                            .into_iter()
                            .filter(|x| x.is_finite())
                            .fold(0.0, f64::max);
                    let (lo, hi) = p.position_range();
                    if lo >= jl.position_min - tol && hi <= jl.position_max + tol {
                        continue;
                    }
                    // Interior waypoints i and i + 1 hold vias[(i - 1)..] and vias[i..].
                    let mut here = false;
                    for k in [i, i + 1] {
                        if k >= 1 && k + 1 < tr.breaks.len() && vel[(k - 1) * dof + j] != 0.0 {
                            vel[(k - 1) * dof + j] = 0.0;
                            zeroed += 1;
                            here = true;
                        }
                    }
                    if !here {
                        // At rest at both ends: monotone, so only rounding could get here.
                        let (value, tau) = if hi > jl.position_max + tol {
                            (hi, p.duration())
                        } else {
                            (lo, 0.0)
                        };
                        return Err(Error::OutOfRange {
                            joint: j,
                            name: jl.name.clone(),
                            time: tr.breaks[i] + tau,
                            value,
                            lo: jl.position_min,
                            hi: jl.position_max,
                        });
                    }
                    changed = true;
                }
            }
            if !changed {
                break;
            }
            tr = ViaTrajectory::new(
                waypoints,
                dof,
                degree,
                ViaVelocities::Given(vel),
                ViaTiming::Limits(limits),
            )?;
        }
        Ok((tr, zeroed))
    }

    /// Velocities at the interior waypoints, row-major `(waypoints − 2) × dof`.
    pub fn via_velocities(&self) -> &[f64] {
        &self.vias
    }

    /// Number of segments.
    pub fn segments(&self) -> usize {
        self.breaks.len() - 1
    }

    /// Segment boundaries in time, `segments() + 1` values starting at 0.
    pub fn breaks(&self) -> &[f64] {
        &self.breaks
    }

    /// The exact worst ratio of velocity, acceleration or jerk to the limits over the whole
    /// trajectory (from each segment's polynomial extrema).
    pub fn worst_limit_ratio(&self, limits: &Limits) -> Result<f64> {
        limits.expect_dof(self.dof, "via-point trajectory")?;
        Ok(self
            .polys
            .chunks(self.dof)
            .map(|seg| worst_ratio_of(seg, limits))
            .fold(0.0, f64::max))
    }

    /// Smallest and largest position of every joint over the trajectory (exact).
    pub fn position_ranges(&self) -> Vec<(f64, f64)> {
        let mut r = vec![(f64::INFINITY, f64::NEG_INFINITY); self.dof];
        for seg in self.polys.chunks(self.dof) {
            for (j, p) in seg.iter().enumerate() {
                let (lo, hi) = p.position_range();
                r[j].0 = r[j].0.min(lo);
                r[j].1 = r[j].1.max(hi);
            }
        }
        r
    }
}

impl Trajectory for ViaTrajectory {
    fn dof(&self) -> usize {
        self.dof
    }
    fn duration(&self) -> f64 {
        *self.breaks.last().expect("at least two breaks")
    }
    fn eval(&self, t: f64, order: Order, out: &mut [f64]) {
        let t = crate::traj::clamp_time(t, self.duration());
        let i = find_piece(&self.breaks, t);
        let local = t - self.breaks[i];
        self.tables[i].eval(local, order.index(), out);
    }
}

/// Checks row-major `waypoints` of `dof` joints (a whole number of rows, at least two, finite,
/// no two consecutive equal) and returns their count.
fn check_waypoints(waypoints: &[f64], dof: usize) -> Result<usize> {
    if dof == 0 || waypoints.len() % dof != 0 {
        return Err(Error::DimensionMismatch {
            what: "waypoint values (a multiple of the joint count)".into(),
            expected: dof.max(1) * (waypoints.len() / dof.max(1)).max(2),
            found: waypoints.len(),
        });
    }
    let n = waypoints.len() / dof;
    if n < 2 {
        return Err(Error::TooFewWaypoints {
            needed: 2,
            found: n,
        });
    }
    for (i, &v) in waypoints.iter().enumerate() {
        crate::error::finite(|| format!("waypoint {} joint {}", i / dof, i % dof + 1), v)?;
    }
    let wp = |i: usize| &waypoints[i * dof..(i + 1) * dof];
    for i in 1..n {
        if wp(i) == wp(i - 1) {
            return Err(Error::DuplicateWaypoint { index: i });
        }
    }
    Ok(n)
}

/// Rest-to-rest segment durations: the given ones (checked), or the minimal ones under the
/// limits.
fn rest_durations(
    waypoints: &[f64],
    dof: usize,
    degree: Degree,
    timing: &ViaTiming<'_>,
) -> Result<Vec<f64>> {
    let segs = waypoints.len() / dof - 1;
    let wp = |i: usize| &waypoints[i * dof..(i + 1) * dof];
    match timing {
        ViaTiming::Durations(d) => {
            if d.len() != segs {
                return Err(Error::DimensionMismatch {
                    what: "segment durations".into(),
                    expected: segs,
                    found: d.len(),
                });
            }
            for (i, &x) in d.iter().enumerate() {
                crate::error::positive(|| format!("duration of segment {i}"), x)?;
            }
            Ok(d.clone())
        }
        ViaTiming::Limits(l) => (0..segs)
            .map(|i| min_duration_rest_to_rest(degree, wp(i), wp(i + 1), l))
            .collect(),
    }
}

/// The velocities at the interior waypoints (row-major `(n − 2) × dof`): zero, the given
/// ones (checked), or the heuristic (the mean of the neighbouring segments' slopes over the
/// rest-to-rest durations `base` where they agree in sign, else zero).
fn interior_velocities(
    waypoints: &[f64],
    dof: usize,
    velocities: ViaVelocities,
    base: &[f64],
) -> Result<Vec<f64>> {
    let n = waypoints.len() / dof;
    let wp = |i: usize| &waypoints[i * dof..(i + 1) * dof];
    match velocities {
        ViaVelocities::Zero => Ok(vec![0.0; (n - 2) * dof]),
        ViaVelocities::Given(v) => {
            check_interior(&v, n, dof, "velocity")?;
            Ok(v)
        }
        ViaVelocities::Heuristic => {
            let mut v = vec![0.0; (n - 2) * dof];
            for k in 1..n - 1 {
                for j in 0..dof {
                    let s0 = (wp(k)[j] - wp(k - 1)[j]) / base[k - 1];
                    let s1 = (wp(k + 1)[j] - wp(k)[j]) / base[k];
                    if s0 * s1 > 0.0 {
                        v[(k - 1) * dof + j] = 0.5 * (s0 + s1);
                    }
                }
            }
            Ok(v)
        }
    }
}

/// Checks values given at the interior waypoints (`what`: "velocity" or "acceleration"):
/// `(n − 2) × dof` of them, all finite.
fn check_interior(values: &[f64], n: usize, dof: usize, what: &str) -> Result<()> {
    if values.len() != (n - 2) * dof {
        let plural = if what == "velocity" {
            "velocities"
        } else {
            "accelerations"
        };
        return Err(Error::DimensionMismatch {
            what: format!("interior waypoint {plural} ((waypoints − 2) × joints)"),
            expected: (n - 2) * dof,
            found: values.len(),
        });
    }
    for (i, &x) in values.iter().enumerate() {
        crate::error::finite(
            || format!("{what} at waypoint {} joint {}", i / dof + 1, i % dof + 1),
            x,
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wps() -> Vec<f64> {
        vec![0.0, 0.0, 1.0, 0.5, 2.0, 0.2, 2.5, -0.5]
    }

    #[test]
    fn passes_through_waypoints_with_continuity() {
        let l = Limits::uniform(2, 1.0, 4.0, 40.0).unwrap();
        for deg in Degree::ALL {
            for vel in [ViaVelocities::Zero, ViaVelocities::Heuristic] {
                let tr =
                    ViaTrajectory::new(&wps(), 2, deg, vel.clone(), ViaTiming::Limits(&l)).unwrap();
                let mut q = [0.0; 2];
                for (k, &b) in tr.breaks().iter().enumerate() {
                    tr.eval(b, Order::Position, &mut q);
                    assert!(
                        (q[0] - wps()[2 * k]).abs() < 1e-12
                            && (q[1] - wps()[2 * k + 1]).abs() < 1e-12
                    );
                }
                // Continuity of position, velocity, acceleration across breaks.
                let max_cont = if deg == Degree::Cubic { 2 } else { 3 };
                for &b in &tr.breaks()[1..tr.segments()] {
                    for k in 0..max_cont {
                        let o = Order::from_index(k).unwrap();
                        let (mut a, mut c) = ([0.0; 2], [0.0; 2]);
                        tr.eval(b - 1e-9, o, &mut a);
                        tr.eval(b + 1e-9, o, &mut c);
                        for j in 0..2 {
                            assert!(
                                (a[j] - c[j]).abs() < 1e-5 * (1.0 + a[j].abs()),
                                "{:?} order {k}",
                                deg
                            );
                        }
                    }
                }
                let w = tr.worst_limit_ratio(&l).unwrap();
                let w = if deg == Degree::Cubic { w.min(1.0) } else { w };
                assert!(w <= 1.0 + 1e-9, "{deg:?} {vel:?} worst {w}");
            }
        }
    }

    #[test]
    fn heuristic_stops_where_a_joint_turns() {
        let l = Limits::uniform(2, 1.0, 4.0, 40.0).unwrap();
        let tr = ViaTrajectory::new(
            &wps(),
            2,
            Degree::Quintic,
            ViaVelocities::Heuristic,
            ViaTiming::Limits(&l),
        )
        .unwrap();
        let mut v = [0.0; 2];
        // Joint 2 goes 0 -> 0.5 -> 0.2: turns at waypoint 1, so velocity 0 there.
        tr.eval(tr.breaks()[1], Order::Velocity, &mut v);
        assert!(v[0] > 0.0 && v[1].abs() < 1e-12, "{v:?}");
        // Faster than stopping everywhere.
        let stop = ViaTrajectory::new(
            &wps(),
            2,
            Degree::Quintic,
            ViaVelocities::Zero,
            ViaTiming::Limits(&l),
        )
        .unwrap();
        assert!(tr.duration() < stop.duration());
    }

    #[test]
    fn within_limits_keeps_every_joint_in_range() {
        use crate::rng::SplitMix64;
        let panda = Limits::preset("panda").unwrap();
        let mut rng = SplitMix64::new(7);
        let mut zeroed_total = 0;
        for case in 0..4 {
            let n = 3 + case % 4;
            let w: Vec<f64> = (0..n * 7)
                .map(|i| {
                    let jl = panda.joint(i % 7);
                    // Near the ends of the range, where overshoot matters.
                    let u = if rng.next_f64() < 0.5 {
                        0.97 + 0.03 * rng.next_f64()
                    } else {
                        rng.next_f64()
                    };
                    jl.position_min + (jl.position_max - jl.position_min) * u
                })
                .collect();
            for deg in Degree::ALL {
                let (tr, zeroed) =
                    ViaTrajectory::within_limits(&w, 7, deg, ViaVelocities::Heuristic, &panda)
                        .unwrap();
                zeroed_total += zeroed;
                for (j, (lo, hi)) in tr.position_ranges().into_iter().enumerate() {
                    let jl = panda.joint(j);
                    assert!(
                        lo >= jl.position_min - 1e-12 && hi <= jl.position_max + 1e-12,
                        "case {case} {deg:?} joint {j}: [{lo}, {hi}]"
                    );
                }
                // Still through every waypoint.
                let mut q = [0.0; 7];
                for (k, &b) in tr.breaks().iter().enumerate() {
                    tr.eval(b, Order::Position, &mut q);
                    for j in 0..7 {
                        assert!((q[j] - w[k * 7 + j]).abs() < 1e-9);
                    }
                }
            }
        }
        assert!(zeroed_total > 0, "the suite never needed a repair");
        let out = [0.0; 7];
        let mut w = out.to_vec();
        w.extend([0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0]);
        let e = ViaTrajectory::within_limits(&w, 7, Degree::Quintic, ViaVelocities::Zero, &panda)
            .unwrap_err();
        assert!(
            matches!(
                e,
                Error::WaypointOutOfRange {
                    waypoint: 0,
                    joint: 3,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn bad_input() {
        let l = Limits::uniform(2, 1.0, 4.0, 40.0).unwrap();
        let e = ViaTrajectory::new(
            &[0.0, 0.0, 0.0, 0.0],
            2,
            Degree::Quintic,
            ViaVelocities::Zero,
            ViaTiming::Limits(&l),
        )
        .unwrap_err();
        assert_eq!(e, Error::DuplicateWaypoint { index: 1 });
        assert!(matches!(
            ViaTrajectory::new(
                &[0.0, 0.0],
                2,
                Degree::Quintic,
                ViaVelocities::Zero,
                ViaTiming::Limits(&l)
            ),
            Err(Error::TooFewWaypoints { .. })
        ));
        assert!(ViaTrajectory::new(
            &[0.0, 0.0, 1.0],
            2,
            Degree::Quintic,
            ViaVelocities::Zero,
            ViaTiming::Limits(&l)
        )
        .is_err());
        assert!(ViaTrajectory::new(
            &[0.0, 0.0, 1.0, f64::INFINITY],
            2,
            Degree::Quintic,
            ViaVelocities::Zero,
            ViaTiming::Limits(&l)
        )
        .is_err());
        assert!(ViaTrajectory::new(
            &wps(),
            2,
            Degree::Quintic,
            ViaVelocities::Zero,
            ViaTiming::Durations(vec![1.0, 1.0])
        )
        .is_err());
        let tr = ViaTrajectory::new(
            &wps(),
            2,
            Degree::Quintic,
            ViaVelocities::Given(vec![0.1; 4]),
            ViaTiming::Durations(vec![1.0, 2.0, 1.5]),
        )
        .unwrap();
        assert!((tr.duration() - 4.5).abs() < 1e-15);
    }
}
