//! Banded linear systems: LU factorization with partial pivoting, O(n·kl·(kl+ku)) time.
//!
//! Used by every interpolating spline (tridiagonal for cubic splines, bandwidth = degree for
//! B-spline interpolation), so construction is linear in the number of points.

/// A square `n × n` matrix with `kl` sub- and `ku` super-diagonals, stored by columns with room
/// for the `kl` extra super-diagonals that row interchanges create (the LAPACK layout).
#[derive(Debug, Clone)]
pub(crate) struct Banded {
    n: usize,
    kl: usize,
    ku: usize,
    ld: usize,
    ab: Vec<f64>,
    piv: Vec<usize>,
    factored: bool,
}

/// The system is singular (a zero pivot at the given row).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Singular(pub usize);

impl Banded {
    /// A zero matrix.
    pub(crate) fn zeros(n: usize, kl: usize, ku: usize) -> Self {
        let ld = 2 * kl + ku + 1;
        Banded {
            n,
            kl,
            ku,
            ld,
            ab: vec![0.0; ld * n],
            piv: vec![0; n],
            factored: false,
        }
    }

    #[inline]
    fn idx(&self, i: usize, j: usize) -> usize {
        // Row i of column j lives at offset kl + ku + i - j (i - j in -(kl+ku)..=kl).
        j * self.ld + self.kl + self.ku + i - j
    }

    /// Sets entry (i, j); it must lie within the band (`j <= i + ku`, `i <= j + kl`).
    pub(crate) fn set(&mut self, i: usize, j: usize, v: f64) {
        debug_assert!(j <= i + self.ku && i <= j + self.kl && !self.factored);
        let k = self.idx(i, j);
        self.ab[k] = v;
    }

    /// Reads entry (i, j) of the (unfactored) matrix; zero outside the band.
    #[cfg(test)]
    pub(crate) fn get(&self, i: usize, j: usize) -> f64 {
        if j > i + self.ku || i > j + self.kl {
            0.0
        } else {
            self.ab[self.idx(i, j)]
        }
    }

    /// LU factorization with partial pivoting, in place.
    pub(crate) fn factor(&mut self) -> Result<(), Singular> {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        let scale = self.ab.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let tiny = scale * f64::EPSILON * 1e-3;
        for k in 0..n {
            let last = (k + kl).min(n - 1);
            let mut p = k;
            let mut best = self.ab[self.idx(k, k)].abs();
            for i in k + 1..=last {
                let v = self.ab[self.idx(i, k)].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if best.is_nan() || best <= tiny {
                return Err(Singular(k));
            }
            self.piv[k] = p;
            let jmax = (k + kl + ku).min(n - 1);
            if p != k {
                for j in k..=jmax {
                    let a = self.idx(k, j);
                    let b = self.idx(p, j);
                    self.ab.swap(a, b);
                }
            }
            let pivot = self.ab[self.idx(k, k)];
            for i in k + 1..=last {
                let ik = self.idx(i, k);
                let l = self.ab[ik] / pivot;
                self.ab[ik] = l;
                if l != 0.0 {
                    for j in k + 1..=jmax {
                        let kj = self.ab[self.idx(k, j)];
                        let ij = self.idx(i, j);
                        self.ab[ij] -= l * kj;
                    }
                }
            }
        }
        self.factored = true;
        Ok(())
    }

    /// Solves `A X = B` in place for `B` row-major `n × m` (m right-hand sides), after
    /// [`Banded::factor`].
    pub(crate) fn solve(&self, b: &mut [f64], m: usize) {
        debug_assert!(self.factored && b.len() == self.n * m);
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        // Forward: apply the interchanges and L.
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                for c in 0..m {
                    b.swap(k * m + c, p * m + c);
                }
            }
            let last = (k + kl).min(n - 1);
            for i in k + 1..=last {
                let l = self.ab[self.idx(i, k)];
                if l != 0.0 {
                    for c in 0..m {
                        b[i * m + c] -= l * b[k * m + c];
                    }
                }
            }
        }
        // Backward: U has kl + ku super-diagonals.
        for k in (0..n).rev() {
            let jmax = (k + kl + ku).min(n - 1);
            let d = self.ab[self.idx(k, k)];
            for c in 0..m {
                let mut s = b[k * m + c];
                for j in k + 1..=jmax {
                    s -= self.ab[self.idx(k, j)] * b[j * m + c];
                }
                b[k * m + c] = s / d;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    #[test]
    fn random_banded_systems_match_dense_products() {
        let mut rng = SplitMix64::new(7);
        for &(n, kl, ku) in &[
            (1, 0, 0),
            (5, 1, 1),
            (9, 2, 3),
            (12, 3, 1),
            (20, 5, 5),
            (3, 4, 4),
        ] {
            let mut a = Banded::zeros(n, kl, ku);
            for i in 0..n {
                for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                    a.set(i, j, rng.uniform(-1.0, 1.0));
                }
            }
            let dense: Vec<Vec<f64>> = (0..n)
                .map(|i| (0..n).map(|j| a.get(i, j)).collect())
                .collect();
            let m = 3;
            let x: Vec<f64> = (0..n * m).map(|_| rng.uniform(-2.0, 2.0)).collect();
            let mut b = vec![0.0; n * m];
            for i in 0..n {
                for c in 0..m {
                    b[i * m + c] = (0..n).map(|j| dense[i][j] * x[j * m + c]).sum();
                }
            }
            a.factor().unwrap();
            a.solve(&mut b, m);
            for k in 0..n * m {
                assert!((b[k] - x[k]).abs() < 1e-9, "n={n} kl={kl} ku={ku}");
            }
        }
    }

    #[test]
    fn singular_is_reported() {
        let mut a = Banded::zeros(3, 1, 1);
        a.set(0, 0, 1.0);
        a.set(0, 1, 2.0);
        a.set(1, 0, 2.0);
        a.set(1, 1, 4.0);
        a.set(2, 2, 1.0);
        assert!(a.factor().is_err());
    }
}
