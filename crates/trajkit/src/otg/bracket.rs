//! The one bracketed solve of the profile families that have no closed form (step 1's
//! fallback families, step 2's cruise and hold families): the residual of a family's free
//! parameter is bracketed on the pieces between its cut points ([`crate::roots`]), and each
//! root, in increasing order per piece, is handed to the family, which builds (and offers or
//! verifies) its profile there.
//!
//! Precision: that of [`crate::roots::find_roots`] (a root to adjacent floating-point numbers);
//! every profile built from a root is verified by the caller, so a missed root can cost
//! optimality, never correctness.

use crate::roots::{find_roots, find_roots_coarse, for_each_piece, MAX_ROOTS};

/// The sampling grid of a bracketed solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Grid {
    /// [`find_roots`]: dense near the ends, finds the edges of a residual's valid domain.
    Fine,
    /// [`find_roots_coarse`]: for a residual valid on the whole piece.
    Coarse,
}

/// Brackets `residual` on each piece between `cuts` (sorted and clipped to
/// `[cuts[0], cuts[1]]`, see [`for_each_piece`]) and calls `at_root` at every root found,
/// pieces in increasing order, until it returns `Some`: that value is the result (`None` when
/// no root gave one; then every root was visited).
pub(super) fn first_at_root<const N: usize, T>(
    mut cuts: [f64; N],
    grid: Grid,
    mut residual: impl FnMut(f64) -> Option<f64>,
    mut at_root: impl FnMut(f64) -> Option<T>,
) -> Option<T> {
    let mut roots = [0.0; MAX_ROOTS];
    let mut found = None;
    for_each_piece(&mut cuts, |lo, hi| {
        if found.is_some() {
            return;
        }
        let n = match grid {
            Grid::Fine => find_roots(&mut residual, lo, hi, &mut roots),
            Grid::Coarse => find_roots_coarse(&mut residual, lo, hi, &mut roots),
        };
        for &x in &roots[..n] {
            if let r @ Some(_) = at_root(x) {
                found = r;
                return;
            }
        }
    });
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn visits_roots_in_order_across_pieces_and_stops_at_the_first_accepted() {
        let f = |x: f64| Some((x - 0.1) * (x - 0.5) * (x - 0.9));
        let mut seen = Vec::new();
        let none: Option<()> = first_at_root([0.0, 1.0, 0.3], Grid::Fine, f, |x| {
            seen.push(x);
            None
        });
        assert!(none.is_none());
        assert_eq!(seen.len(), 3);
        for (x, r) in seen.iter().zip([0.1, 0.5, 0.9]) {
            assert!((x - r).abs() < 1e-14, "{x} vs {r}");
        }
        let first_above =
            first_at_root([0.0, 1.0, 0.3], Grid::Coarse, f, |x| (x > 0.3).then_some(x));
        assert!((first_above.unwrap() - 0.5).abs() < 1e-14);
        // An empty window (lo > hi) has no root.
        assert!(first_at_root([1.0, 0.0], Grid::Fine, f, Some).is_none());
    }
}
