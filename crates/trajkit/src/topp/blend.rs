//! TOTG's path: straight segments between waypoints joined by circular blends.
//!
//! [`BlendedPath`] runs along the polyline through the waypoints but replaces each corner by a
//! circular arc tangent to both segments, so the path is C¹ (its unit tangent is continuous)
//! and can be followed without stopping. The arc at an interior waypoint w with incoming
//! direction d₀, outgoing direction d₁ and turning angle α = ∠(d₀, d₁) keeps a distance
//!
//! ```text
//!     ℓ = min(L₀/2, L₁/2, δ·sin(α/2) / (1 − cos(α/2)))
//! ```
//!
//! from w to each tangent point (L₀, L₁: adjacent segment lengths, δ: the maximum deviation),
//! has radius r = ℓ / tan(α/2) and passes at distance r·(1/cos(α/2) − 1) ≤ δ from w. The half
//! segment bound keeps neighbouring arcs apart. The path is parameterized by arc length in joint
//! space (‖σ′‖ = 1), so σ″ = 0 on segments and ‖σ″‖ = 1/r on arcs.
//!
//! Input handling: consecutive repeated waypoints (within `1e-12` of the previous kept one) are
//! removed; collinear waypoints (turning angle below `1e-9` rad) get no arc; an exact reversal
//! (turning angle within `1e-6` of π) cannot be blended and is refused by [`BlendedPath::new`]
//! with [`Error::Infeasible`] naming the waypoint, as is a corner whose blend radius would be
//! below `1e-5·(1 + polyline length)` (followed at ṡ ≈ √(a·r), practically a stop).
//! [`crate::topp::plan_totg`] splits waypoints at those corners first ([`stop_indices`])
//! and plays the rest-to-rest pieces as a [`crate::topp::messy::Sequence`].
//!
//! # Precision contract
//! σ and its derivatives are evaluated in closed form (segment: `p + s·d`; arc:
//! `c + r(cos θ·x + sin θ·y)`, θ = s/r), exact up to rounding. [`Path::breakpoints`] lists every
//! segment/arc junction: there σ″ jumps (0 ↔ 1/r) and σ‴ is undefined; `eval` at a junction
//! returns the values of the piece that starts there (the last piece at the end), and
//! [`BlendedPath::eval_left`] those of the piece that ends there. Evaluation never allocates.

use super::paths::{check_waypoints, seg_len};
use crate::error::{Error, Result};
use crate::traj::find_piece;
use crate::Path;

/// Turning angle below which a waypoint is treated as collinear (no arc).
pub const COLLINEAR_ANGLE: f64 = 1e-9;

/// Turning angle within this of π is an exact reversal (the same tolerance as the default
/// [`crate::topp::messy::PlanOptions::reversal_angle`]).
pub const REVERSAL_ANGLE: f64 = 1e-6;

/// Distance below which a waypoint repeats the previous one.
pub const REPEAT_DISTANCE: f64 = 1e-12;

/// One piece of a blended path.
#[derive(Debug, Clone, PartialEq)]
enum Piece {
    /// `start + (s − s0)·dir`, unit `dir`.
    Line { start: usize, dir: usize },
    /// `center + r(cos θ·x + sin θ·y)` with θ = (s − s0)/r, unit orthogonal x, y.
    Arc {
        center: usize,
        x: usize,
        y: usize,
        radius: f64,
    },
}

/// Straight segments joined by circular blends, arc-length parameterized (see the module
/// documentation).
///
/// ```
/// use trajkit::{topp::BlendedPath, Path};
/// // A right-angle corner in 2-D, blended with at most 0.1 deviation.
/// let p = BlendedPath::new(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0], 2, 0.1)?;
/// assert_eq!(p.breakpoints().len(), 4); // line, arc, line
/// let r = p.arc_radii()[0];
/// // The arc passes exactly 0.1 from the corner: r(√2 − 1) = 0.1.
/// assert!((r * (2f64.sqrt() - 1.0) - 0.1).abs() < 1e-12);
/// # Ok::<(), trajkit::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BlendedPath {
    dim: usize,
    /// Vectors referenced by the pieces, `dim` values each.
    vecs: Vec<f64>,
    pieces: Vec<Piece>,
    /// Piece start parameters, then the total length.
    s: Vec<f64>,
    /// Kept waypoints (row-major) and their input indices.
    waypoints: Vec<f64>,
    kept: Vec<usize>,
}

impl BlendedPath {
    /// Blends the corners of the polyline through `waypoints` (row-major `count × dim`) with
    /// arcs deviating at most `max_deviation` (> 0, finite) from each corner.
    ///
    /// Errors: bad waypoints or deviation ([`Error::InvalidValue`], [`Error::TooFewWaypoints`]
    /// after removing repeats), an exact reversal ([`Error::Infeasible`]).
    pub fn new(waypoints: &[f64], dim: usize, max_deviation: f64) -> Result<Self> {
        check_waypoints(waypoints, dim)?;
        if !(max_deviation > 0.0 && max_deviation.is_finite()) {
            return Err(Error::InvalidValue {
                field: "max deviation".into(),
                value: max_deviation,
                reason: "is not a finite number > 0",
            });
        }
        let (w, kept) = super::messy::dedup_waypoints(waypoints, dim, REPEAT_DISTANCE)?;
        let count = w.len() / dim;
        if count < 2 {
            return Err(Error::TooFewWaypoints {
                needed: 2,
                found: count,
            });
        }
        let mut b = Builder {
            dim,
            vecs: Vec::new(),
            pieces: Vec::new(),
            s: vec![0.0],
        };
        let min_radius = min_blend_radius(&w, dim);
        // Where the current straight segment starts (the previous arc's end).
        let mut seg_start = w[..dim].to_vec();
        for i in 1..count {
            if i + 1 == count {
                let end = &w[i * dim..];
                b.line(&seg_start, end);
                break;
            }
            let c = corner(&w, dim, i, max_deviation);
            let (angle, radius) = (c.angle, c.radius);
            if angle >= std::f64::consts::PI - REVERSAL_ANGLE {
                return Err(Error::Infeasible(format!(
                    "waypoint {} reverses the path exactly (turning angle {angle} rad): it cannot be blended; split there (plan_totg does)",
                    kept[i]
                )));
            }
            if angle < COLLINEAR_ANGLE {
                // Collinear: the segment simply continues.
                continue;
            }
            if radius < min_radius {
                return Err(Error::Infeasible(format!(
                    "the blend at waypoint {} would have radius {radius:e} < {min_radius:e}: the robot must stop there; split there (plan_totg does)",
                    kept[i]
                )));
            }
            seg_start = b.blend(&seg_start, &w[i * dim..(i + 1) * dim], &c);
        }
        Ok(BlendedPath {
            dim,
            vecs: b.vecs,
            pieces: b.pieces,
            s: b.s,
            waypoints: w,
            kept,
        })
    }

    /// Radii of the arcs, in path order.
    pub fn arc_radii(&self) -> Vec<f64> {
        self.pieces
            .iter()
            .filter_map(|p| match p {
                Piece::Arc { radius, .. } => Some(*radius),
                Piece::Line { .. } => None,
            })
            .collect()
    }

    /// The pieces as `(s_start, s_end, radius)`, radius `∞` for a straight segment.
    pub fn pieces(&self) -> Vec<(f64, f64, f64)> {
        self.pieces
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let r = match p {
                    Piece::Arc { radius, .. } => *radius,
                    Piece::Line { .. } => f64::INFINITY,
                };
                (self.s[k], self.s[k + 1], r)
            })
            .collect()
    }

    /// Per piece and joint (row-major `pieces × dim`): the amplitude √(x_j² + y_j²) of the
    /// joint's circular motion on an arc (an upper bound of |σ′_j|, r·|σ″_j|, r²·|σ‴_j|), 0 on
    /// straight segments.
    pub fn arc_amplitudes(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.pieces.len() * self.dim);
        for p in &self.pieces {
            match p {
                Piece::Arc { x, y, .. } => {
                    let (x, y) = (self.v(*x), self.v(*y));
                    out.extend((0..self.dim).map(|j| x[j].hypot(y[j])));
                }
                Piece::Line { .. } => out.extend(std::iter::repeat_n(0.0, self.dim)),
            }
        }
        out
    }

    /// The waypoints kept after removing repeats (row-major) and their input indices.
    pub fn waypoints(&self) -> (&[f64], &[usize]) {
        (&self.waypoints, &self.kept)
    }

    /// Like [`Path::eval`], but at a junction uses the piece that ends there.
    pub fn eval_left(&self, s: f64, order: usize, out: &mut [f64]) {
        let (a, b) = self.interval();
        let s = s.clamp(a, b);
        let mut k = find_piece(&self.s, s);
        if k > 0 && s == self.s[k] {
            k -= 1;
        }
        self.eval_piece(k, s, order, out);
    }

    fn v(&self, k: usize) -> &[f64] {
        &self.vecs[k..k + self.dim]
    }

    fn eval_piece(&self, k: usize, s: f64, order: usize, out: &mut [f64]) {
        let n = self.dim;
        let out = &mut out[..n];
        let ds = s - self.s[k];
        match &self.pieces[k] {
            Piece::Line { start, dir } => {
                let (p, d) = (self.v(*start), self.v(*dir));
                match order {
                    0 => (0..n).for_each(|j| out[j] = p[j] + ds * d[j]),
                    1 => out.copy_from_slice(d),
                    _ => out.iter_mut().for_each(|v| *v = 0.0),
                }
            }
            Piece::Arc {
                center,
                x,
                y,
                radius,
            } => {
                let (c, x, y, r) = (self.v(*center), self.v(*x), self.v(*y), *radius);
                let (sn, cs) = (ds / r).sin_cos();
                if order == 0 {
                    (0..n).for_each(|j| out[j] = c[j] + r * (cs * x[j] + sn * y[j]));
                } else {
                    arc_derivative(order, sn, cs, r, x, y, out);
                }
            }
        }
    }

    /// σ′ and σ″ of piece `k` at `s`: one sin_cos on an arc, the same arithmetic as
    /// [`BlendedPath::eval_piece`] orders 1 and 2 (so bitwise equal).
    fn eval_piece_derivatives(&self, k: usize, s: f64, first: &mut [f64], second: &mut [f64]) {
        let n = self.dim;
        let (first, second) = (&mut first[..n], &mut second[..n]);
        match &self.pieces[k] {
            Piece::Line { dir, .. } => {
                first.copy_from_slice(self.v(*dir));
                second.iter_mut().for_each(|v| *v = 0.0);
            }
            Piece::Arc { x, y, radius, .. } => {
                let (x, y, r) = (self.v(*x), self.v(*y), *radius);
                let (sn, cs) = ((s - self.s[k]) / r).sin_cos();
                arc_derivative(1, sn, cs, r, x, y, first);
                arc_derivative(2, sn, cs, r, x, y, second);
            }
        }
    }
}

/// Writes d^k/ds^k (k ≥ 1) of r(cos θ·x + sin θ·y), θ = s/r, given (sin θ, cos θ): the
/// (cos, sin) pair rotates a quarter turn per derivative and picks up a factor 1/r.
fn arc_derivative(order: usize, sn: f64, cs: f64, r: f64, x: &[f64], y: &[f64], out: &mut [f64]) {
    let (fx, fy) = match order % 4 {
        0 => (cs, sn),
        1 => (-sn, cs),
        2 => (-cs, -sn),
        _ => (sn, -cs),
    };
    let scale = r.powi(1 - order as i32);
    (0..out.len()).for_each(|j| out[j] = scale * (fx * x[j] + fy * y[j]));
}

/// The smallest blend radius used: `1e-5·(1 + polyline length)`. A smaller arc is followed at
/// ṡ ≈ √(a·r), practically a stop, and its knots would be too close for the arc-length
/// parameter's rounding; such corners are stops ([`stop_indices`]).
fn min_blend_radius(w: &[f64], dim: usize) -> f64 {
    let count = w.len() / dim;
    let total: f64 = (0..count - 1).map(|i| seg_len(w, dim, i)).sum();
    1e-5 * (1.0 + total)
}

/// The blend at interior waypoint `i` of deduplicated waypoints.
struct Corner {
    dir: Vec<f64>,
    next: Vec<f64>,
    angle: f64,
    ell: f64,
    radius: f64,
}

fn corner(w: &[f64], dim: usize, i: usize, max_deviation: f64) -> Corner {
    let (len, next_len) = (seg_len(w, dim, i - 1), seg_len(w, dim, i));
    let dir: Vec<f64> = (0..dim)
        .map(|j| (w[i * dim + j] - w[(i - 1) * dim + j]) / len)
        .collect();
    let next: Vec<f64> = (0..dim)
        .map(|j| (w[(i + 1) * dim + j] - w[i * dim + j]) / next_len)
        .collect();
    // α = 2·atan2(‖d₁ − d₀‖, ‖d₁ + d₀‖): accurate near 0 and near π (unlike acos).
    let (mut dm, mut dp) = (0.0, 0.0);
    for j in 0..dim {
        dm += (next[j] - dir[j]) * (next[j] - dir[j]);
        dp += (next[j] + dir[j]) * (next[j] + dir[j]);
    }
    let angle = 2.0 * dm.sqrt().atan2(dp.sqrt());
    let half = 0.5 * angle;
    let ell = (0.5 * len)
        .min(0.5 * next_len)
        // δ·sin(α/2)/(1 − cos(α/2)) = δ/tan(α/4), without cancellation.
        .min(max_deviation / (0.5 * half).tan());
    Corner {
        dir,
        next,
        angle,
        ell,
        radius: ell / half.tan(),
    }
}

/// Interior waypoints of `waypoints` (row-major, consecutive repeats already removed) where a
/// blended path must stop: exact reversals (turning angle within [`REVERSAL_ANGLE`] of π) and
/// corners whose blend radius for `max_deviation` would be below `1e-5·(1 + polyline
/// length)`. [`crate::topp::plan_totg`] splits there into rest-to-rest pieces.
pub(crate) fn stop_indices(waypoints: &[f64], dim: usize, max_deviation: f64) -> Vec<usize> {
    let count = waypoints.len() / dim.max(1);
    if count < 3 {
        return Vec::new();
    }
    let min_radius = min_blend_radius(waypoints, dim);
    (1..count - 1)
        .filter(|&i| {
            let c = corner(waypoints, dim, i, max_deviation);
            c.angle >= std::f64::consts::PI - REVERSAL_ANGLE
                || (c.angle >= COLLINEAR_ANGLE && c.radius < min_radius)
        })
        .collect()
}

struct Builder {
    dim: usize,
    vecs: Vec<f64>,
    pieces: Vec<Piece>,
    s: Vec<f64>,
}

impl Builder {
    fn push(&mut self, v: &[f64]) -> usize {
        let k = self.vecs.len();
        self.vecs.extend_from_slice(&v[..self.dim]);
        k
    }

    /// A straight segment from `a` to `b` (skipped when shorter than rounding).
    fn line(&mut self, a: &[f64], b: &[f64]) {
        let len = a
            .iter()
            .zip(b)
            .map(|(p, q)| (q - p) * (q - p))
            .sum::<f64>()
            .sqrt();
        let scale = a.iter().chain(b).fold(1.0f64, |m, v| m.max(v.abs()));
        if len <= 1e-14 * scale {
            return;
        }
        let d: Vec<f64> = a.iter().zip(b).map(|(p, q)| (q - p) / len).collect();
        let start = self.push(a);
        let dir = self.push(&d);
        self.pieces.push(Piece::Line { start, dir });
        let s0 = self.s[self.s.len() - 1];
        self.s.push(s0 + len);
    }

    /// The segment from `seg_start` to the arc of corner `c` at waypoint `corner`, then the
    /// arc; returns the arc's end, where the next segment starts.
    fn blend(&mut self, seg_start: &[f64], corner: &[f64], c: &Corner) -> Vec<f64> {
        let Corner {
            dir,
            next,
            angle,
            ell,
            radius,
        } = c;
        let (dim, angle, ell, radius) = (self.dim, *angle, *ell, *radius);
        let half = 0.5 * angle;
        let arc_start: Vec<f64> = (0..dim).map(|j| corner[j] - ell * dir[j]).collect();
        let arc_end: Vec<f64> = (0..dim).map(|j| corner[j] + ell * next[j]).collect();
        self.line(seg_start, &arc_start);
        // Centre: from the corner along the bisector (d₁ − d₀)/‖d₁ − d₀‖, at r / cos(α/2).
        let mut bis: Vec<f64> = (0..dim).map(|j| next[j] - dir[j]).collect();
        let nb = bis.iter().map(|v| v * v).sum::<f64>().sqrt();
        bis.iter_mut().for_each(|v| *v /= nb);
        let cdist = radius / half.cos();
        let center: Vec<f64> = (0..dim).map(|j| corner[j] + cdist * bis[j]).collect();
        let x: Vec<f64> = (0..dim)
            .map(|j| (arc_start[j] - center[j]) / radius)
            .collect();
        self.arc(&center, &x, dir, radius, angle);
        arc_end
    }

    fn arc(&mut self, center: &[f64], x: &[f64], y: &[f64], radius: f64, angle: f64) {
        let center = self.push(center);
        let x = self.push(x);
        let y = self.push(y);
        self.pieces.push(Piece::Arc {
            center,
            x,
            y,
            radius,
        });
        let s0 = self.s[self.s.len() - 1];
        self.s.push(s0 + radius * angle);
    }
}

impl Path for BlendedPath {
    fn dim(&self) -> usize {
        self.dim
    }
    fn interval(&self) -> (f64, f64) {
        (0.0, self.s[self.s.len() - 1])
    }
    fn eval(&self, s: f64, order: usize, out: &mut [f64]) {
        let (a, b) = self.interval();
        let s = s.clamp(a, b);
        let k = find_piece(&self.s, s);
        self.eval_piece(k, s, order, out);
    }
    fn eval_derivatives(&self, s: f64, first: &mut [f64], second: &mut [f64]) {
        let (a, b) = self.interval();
        let s = s.clamp(a, b);
        let k = find_piece(&self.s, s);
        self.eval_piece_derivatives(k, s, first, second);
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.s.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_geometry_and_errors() {
        let p = BlendedPath::new(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0], 2, 0.1).unwrap();
        let pieces = p.pieces();
        assert_eq!(pieces.len(), 3);
        let r = pieces[1].2;
        // Tangent points at distance r from the corner (α = 90°: ℓ = r).
        let mut q = [0.0; 2];
        p.eval(pieces[1].0, 0, &mut q);
        assert!(
            (q[0] - (1.0 - r)).abs() < 1e-12 && q[1].abs() < 1e-12,
            "{q:?}"
        );
        p.eval(pieces[1].1, 0, &mut q);
        assert!(
            (q[0] - 1.0).abs() < 1e-12 && (q[1] - r).abs() < 1e-12,
            "{q:?}"
        );
        // Closest approach to the corner at mid-arc: exactly the max deviation.
        p.eval(0.5 * (pieces[1].0 + pieces[1].1), 0, &mut q);
        let d = ((q[0] - 1.0).powi(2) + q[1].powi(2)).sqrt();
        assert!((d - 0.1).abs() < 1e-12, "{d}");
        // Left and right curvature at a junction.
        let mut dd = [0.0; 2];
        p.eval(pieces[1].0, 2, &mut dd);
        assert!((dd[1] - 1.0 / r).abs() < 1e-12, "{dd:?}");
        p.eval_left(pieces[1].0, 2, &mut dd);
        assert_eq!(dd, [0.0, 0.0]);
        // Collinear and repeated waypoints: one straight segment.
        let p = BlendedPath::new(&[0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0, 2.0], 2, 0.1).unwrap();
        assert_eq!(p.pieces().len(), 1);
        assert_eq!(p.waypoints().1, &[0, 1, 3]);
        let e = BlendedPath::new(&[0.0, 1.0, 0.0], 1, 0.1).unwrap_err();
        assert!(e.to_string().contains("waypoint 1 reverses"), "{e}");
        let e = BlendedPath::new(&[0.0, 1.0], 1, f64::NAN).unwrap_err();
        assert!(e.to_string().contains("max deviation = NaN"), "{e}");
        assert!(BlendedPath::new(&[0.0, 1.0], 1, -1.0).is_err());
        assert!(BlendedPath::new(&[1.0, 1.0], 1, 0.1).is_err());
    }

    #[test]
    fn eval_derivatives_is_bitwise_eval_orders_1_and_2() {
        // A 3-D zig-zag with arcs of several radii; every junction, points inside each piece
        // and beyond both ends (clamped).
        let w = [
            0.0, 0.0, 0.0, 1.0, 0.2, -0.3, 1.5, 1.4, 0.1, 0.2, 2.0, 0.9, 0.4, 0.5, 2.5,
        ];
        let p = BlendedPath::new(&w, 3, 0.15).unwrap();
        assert!(p.arc_radii().len() == 3);
        let (a, b) = p.interval();
        let mut ss: Vec<f64> = p.breakpoints();
        ss.extend((0..=997).map(|i| a + (b - a) * i as f64 / 997.0));
        ss.extend([a - 1.0, b + 1.0]);
        let (mut d1, mut d2, mut e1, mut e2) = ([0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]);
        for s in ss {
            p.eval_derivatives(s, &mut d1, &mut d2);
            p.eval(s, 1, &mut e1);
            p.eval(s, 2, &mut e2);
            for j in 0..3 {
                assert_eq!(d1[j].to_bits(), e1[j].to_bits(), "σ′ at {s}");
                assert_eq!(d2[j].to_bits(), e2[j].to_bits(), "σ″ at {s}");
            }
        }
    }
}
