//! An exact linear program in two variables (Seidel's incremental algorithm).
//!
//! TOPP-RA solves, at every stage of the path, small linear programs in the two unknowns
//! (u, x) = (s̈, ṡ²): a few dozen half-planes `a0·v0 + a1·v1 ≤ b` and a bounding box. For two
//! variables the optimum is a vertex of the feasible polygon, and Seidel's incremental algorithm
//! finds it in time linear in the number of half-planes for a good constraint order: keep the
//! optimum of the half-planes seen so far; when a new half-plane cuts it off, the new optimum
//! lies on that half-plane's boundary line and is found by a one-variable program over the
//! half-planes seen before. Warm starts (the two constraints active at a neighbouring stage's
//! optimum, processed first) make consecutive stages cheap.
//!
//! # Precision contract
//! Half-planes need not be normalised: the tolerance `tol` is a distance in the (v0, v1) plane
//! measured with the 1-norm of each row's normal (a row `a·v ≤ b` counts as satisfied when
//! `a·v − b ≤ tol·(|a0| + |a1|)`). The returned point violates no half-plane and no box side by
//! more than that (plus floating-point rounding of the intersection of two lines), and its
//! objective value is within about `tol·|c|` of the true optimum. A problem is reported
//! infeasible only when its feasible set is empty even after every half-plane is relaxed by
//! `tol`. No allocation: the caller passes the half-planes as a slice.

/// A read-only list of half-planes `(a0, a1, b)`: a slice, or rows computed on the fly.
pub(crate) trait HalfPlanes {
    /// Number of half-planes.
    fn count(&self) -> usize;
    /// Half-plane `k` (`k < count()`).
    fn get(&self, k: usize) -> [f64; 3];

    /// The first half-plane `k ≥ from` that `v` violates by more than `tol` (measured as in the
    /// module's precision contract: `a·v − b > tol·(|a0| + |a1|)`, NaN counting as violated).
    /// Override when the rows can be scanned faster than through [`HalfPlanes::get`].
    #[inline]
    fn first_violated(&self, from: usize, v: [f64; 2], tol: f64) -> Option<usize> {
        (from..self.count()).find(|&k| violates(self.get(k), v, tol))
    }
}

/// Whether `v` violates the half-plane `r` by more than `tol` (scaled by the 1-norm of the
/// row's normal). NaN counts as a violation.
#[inline]
pub(crate) fn violates(r: [f64; 3], v: [f64; 2], tol: f64) -> bool {
    let lhs = r[0] * v[0] + r[1] * v[1];
    let rhs = r[2] + tol * (r[0].abs() + r[1].abs());
    !matches!(
        lhs.partial_cmp(&rhs),
        Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)
    )
}

impl HalfPlanes for [[f64; 3]] {
    #[inline]
    fn count(&self) -> usize {
        self.len()
    }
    #[inline]
    fn get(&self, k: usize) -> [f64; 3] {
        self[k]
    }
}

impl<const N: usize> HalfPlanes for [[f64; 3]; N] {
    #[inline]
    fn count(&self) -> usize {
        N
    }
    #[inline]
    fn get(&self, k: usize) -> [f64; 3] {
        self[k]
    }
}

impl HalfPlanes for Vec<[f64; 3]> {
    #[inline]
    fn count(&self) -> usize {
        self.len()
    }
    #[inline]
    fn get(&self, k: usize) -> [f64; 3] {
        self[k]
    }
}

/// Marks a box side (not a half-plane from the slice) in [`LpSolution::active`].
pub(crate) const BOX: usize = usize::MAX;

/// The optimum of a two-variable linear program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LpSolution {
    /// The optimal point (v0, v1).
    pub v: [f64; 2],
    /// Indices of the (up to) two half-planes active at the optimum, [`BOX`] for a box side.
    /// Pass them back as the hint of the next, similar problem.
    pub active: [usize; 2],
}

/// Maximises `c·v` subject to `rows[k][0]·v0 + rows[k][1]·v1 ≤ rows[k][2]` for every k and
/// `lo ≤ v ≤ hi` (componentwise; bounds must be finite and `lo ≤ hi`). Rows must have a
/// non-zero normal `(rows[k][0], rows[k][1])`. `hint` lists rows to process first (indices out
/// of range are ignored). Returns `None` when infeasible.
pub(crate) fn maximize<R: HalfPlanes + ?Sized>(
    c: [f64; 2],
    rows: &R,
    lo: [f64; 2],
    hi: [f64; 2],
    hint: [usize; 2],
    tol: f64,
) -> Option<LpSolution> {
    if !(lo[0] <= hi[0] + tol && lo[1] <= hi[1] + tol) {
        return None;
    }
    // Optimum over the box alone: the best corner (ties go to the lower side).
    let mut v = [0.0; 2];
    for k in 0..2 {
        v[k] = if c[k] > 0.0 { hi[k] } else { lo[k] };
    }
    let mut active = [BOX, BOX];
    let m = rows.count();
    // Processing order: the (valid, distinct) hints first, then every row in index order.
    let mut hints = [BOX; 2];
    let mut nh = 0;
    for h in hint {
        if h < m && (nh == 0 || hints[0] != h) {
            hints[nh] = h;
            nh += 1;
        }
    }
    // The hints are met again in index order; they hold then (the optimum respects every row
    // processed so far), so they cost one test each and need no skipping.
    for pos in 0..nh {
        let k = hints[pos];
        if violates(rows.get(k), v, tol) {
            (v, active) = on_line(c, rows, k, &hints[..pos], 0, lo, hi, tol)?;
        }
    }
    let mut from = 0;
    while let Some(k) = rows.first_violated(from, v, tol) {
        (v, active) = on_line(c, rows, k, &hints[..nh], k, lo, hi, tol)?;
        from = k + 1;
    }
    Some(LpSolution { v, active })
}

/// The optimum on the boundary line of row `k` (which the current optimum violates), subject
/// to the box, the rows `hints` and the rows `0..before_rows`: a one-variable program.
#[allow(clippy::too_many_arguments)]
#[inline]
fn on_line<R: HalfPlanes + ?Sized>(
    c: [f64; 2],
    rows: &R,
    k: usize,
    hints: &[usize],
    before_rows: usize,
    lo: [f64; 2],
    hi: [f64; 2],
    tol: f64,
) -> Option<([f64; 2], [usize; 2])> {
    let r = rows.get(k);
    let rn = r[0].abs() + r[1].abs();
    // New optimum on the line r0·v0 + r1·v1 = r2: v = p + t·d.
    let f = r[2] / (r[0] * r[0] + r[1] * r[1]);
    let p = [r[0] * f, r[1] * f];
    let d = [-r[1], r[0]];
    // Parameter tolerance matching a distance tol along the line.
    let ttol = tol / rn;
    let mut tlo = f64::NEG_INFINITY;
    let mut thi = f64::INFINITY;
    let mut alo = BOX;
    let mut ahi = BOX;
    // Box sides.
    for q in 0..2 {
        if d[q].abs() > 1e-14 * rn {
            let t1 = (lo[q] - p[q]) / d[q];
            let t2 = (hi[q] - p[q]) / d[q];
            let (a, b) = if d[q] > 0.0 { (t1, t2) } else { (t2, t1) };
            if a > tlo {
                tlo = a;
            }
            if b < thi {
                thi = b;
            }
        } else if p[q] < lo[q] - tol || p[q] > hi[q] + tol {
            return None;
        }
    }
    // Every row processed before this one.
    let prev = hints.iter().copied().chain(0..before_rows);
    for j in prev {
        let s = rows.get(j);
        let sn = s[0].abs() + s[1].abs();
        let ad = s[0] * d[0] + s[1] * d[1];
        let rhs = s[2] - (s[0] * p[0] + s[1] * p[1]);
        if ad.abs() <= 1e-14 * sn * rn {
            if rhs < -tol * sn {
                return None;
            }
        } else if ad > 0.0 {
            let t = rhs / ad;
            if t < thi {
                thi = t;
                ahi = j;
            }
        } else {
            let t = rhs / ad;
            if t > tlo {
                tlo = t;
                alo = j;
            }
        }
    }
    if tlo > thi + ttol {
        return None;
    }
    let cd = c[0] * d[0] + c[1] * d[1];
    let (t, a) = if cd > 0.0 { (thi, ahi) } else { (tlo, alo) };
    // When tlo and thi cross by less than tol, take their midpoint.
    let t = if tlo > thi { 0.5 * (tlo + thi) } else { t };
    Some(([p[0] + t * d[0], p[1] + t * d[1]], [k, a]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// Rows scaled by arbitrary factors: the solver must not depend on normalisation.
    fn norm(rows: &[[f64; 3]]) -> Vec<[f64; 3]> {
        rows.iter()
            .enumerate()
            .map(|(k, &r)| {
                let f = [1.0, 1e-3, 7.0, 1e4][k % 4];
                [r[0] * f, r[1] * f, r[2] * f]
            })
            .collect()
    }

    #[test]
    fn square_with_a_cut_corner() {
        // max v0 + v1 in [0,1]² with v0 + v1 <= 1.5: optimum value 1.5.
        let rows = norm(&[[1.0, 1.0, 1.5]]);
        let s = maximize([1.0, 1.0], &rows, [0.0, 0.0], [1.0, 1.0], [BOX, BOX], 1e-12).unwrap();
        assert!((s.v[0] + s.v[1] - 1.5).abs() < 1e-12);
        // max v1 with v1 <= 0.25 + v0/2 and v1 <= 1 - v0: vertex at v0 = 0.5, v1 = 0.5.
        let rows = norm(&[[-0.5, 1.0, 0.25], [1.0, 1.0, 1.0]]);
        let s = maximize(
            [0.0, 1.0],
            &rows,
            [-9.0, -9.0],
            [9.0, 9.0],
            [BOX, BOX],
            1e-12,
        )
        .unwrap();
        assert!(
            (s.v[0] - 0.5).abs() < 1e-12 && (s.v[1] - 0.5).abs() < 1e-12,
            "{s:?}"
        );
        let mut act = s.active;
        act.sort();
        assert_eq!(act, [0, 1]);
        // Same with hints in the other order.
        let s2 = maximize([0.0, 1.0], &rows, [-9.0, -9.0], [9.0, 9.0], [1, 0], 1e-12).unwrap();
        assert!((s2.v[1] - 0.5).abs() < 1e-12);
    }

    #[test]
    fn infeasible_and_degenerate() {
        let rows = norm(&[[1.0, 0.0, -1.0]]);
        assert!(maximize([1.0, 0.0], &rows, [0.0, 0.0], [1.0, 1.0], [BOX, BOX], 1e-12).is_none());
        // An equality as two opposite half-planes: v0 + v1 = 1.
        let rows = norm(&[[1.0, 1.0, 1.0], [-1.0, -1.0, -1.0]]);
        let s = maximize([0.0, 1.0], &rows, [0.0, 0.0], [2.0, 2.0], [BOX, BOX], 1e-12).unwrap();
        assert!(
            (s.v[1] - 1.0).abs() < 1e-12 && s.v[0].abs() < 1e-12,
            "{s:?}"
        );
        let s = maximize(
            [0.0, -1.0],
            &rows,
            [0.0, 0.0],
            [2.0, 2.0],
            [BOX, BOX],
            1e-12,
        )
        .unwrap();
        assert!(
            s.v[1].abs() < 1e-12 && (s.v[0] - 1.0).abs() < 1e-12,
            "{s:?}"
        );
    }

    /// Brute force: the best feasible vertex among all pairwise intersections.
    fn brute(c: [f64; 2], rows: &[[f64; 3]], lo: [f64; 2], hi: [f64; 2]) -> Option<f64> {
        let mut all: Vec<[f64; 3]> = rows.to_vec();
        all.push([1.0, 0.0, hi[0]]);
        all.push([-1.0, 0.0, -lo[0]]);
        all.push([0.0, 1.0, hi[1]]);
        all.push([0.0, -1.0, -lo[1]]);
        let mut best: Option<f64> = None;
        for i in 0..all.len() {
            for j in i + 1..all.len() {
                let (a, b) = (all[i], all[j]);
                let det = a[0] * b[1] - a[1] * b[0];
                if det.abs() < 1e-12 {
                    continue;
                }
                let v0 = (a[2] * b[1] - a[1] * b[2]) / det;
                let v1 = (a[0] * b[2] - a[2] * b[0]) / det;
                if all
                    .iter()
                    .all(|r| r[0] * v0 + r[1] * v1 <= r[2] + 1e-9 * (r[0].abs() + r[1].abs()))
                {
                    let f = c[0] * v0 + c[1] * v1;
                    best = Some(best.map_or(f, |b: f64| b.max(f)));
                }
            }
        }
        best
    }

    #[test]
    fn seeded_random_programs_match_vertex_enumeration() {
        let mut rng = SplitMix64::new(5);
        for case in 0..400 {
            let m = 1 + rng.below(12) as usize;
            let rows: Vec<[f64; 3]> = (0..m)
                .map(|_| {
                    let a = rng.uniform(0.0, std::f64::consts::TAU);
                    let scale = 10f64.powf(rng.uniform(-3.0, 3.0));
                    [
                        scale * a.cos(),
                        scale * a.sin(),
                        scale * rng.uniform(-1.0, 2.0),
                    ]
                })
                .collect();
            let c = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)];
            let lo = [-3.0, -2.0];
            let hi = [2.0, 3.0];
            let hint = [
                rng.below(m as u64 + 2) as usize,
                rng.below(m as u64 + 2) as usize,
            ];
            let got = maximize(c, &rows, lo, hi, hint, 1e-12);
            let want = brute(c, &rows, lo, hi);
            match (got, want) {
                (Some(s), Some(w)) => {
                    let f = c[0] * s.v[0] + c[1] * s.v[1];
                    assert!((f - w).abs() < 1e-9, "case {case}: {f} vs {w}");
                    for r in &rows {
                        let n = r[0].abs() + r[1].abs();
                        assert!(
                            r[0] * s.v[0] + r[1] * s.v[1] <= r[2] + 1e-9 * n,
                            "case {case}"
                        );
                    }
                }
                (None, None) => {}
                (g, w) => panic!("case {case}: solver {g:?}, enumeration {w:?}"),
            }
        }
    }
}
