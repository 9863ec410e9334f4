//! Small numeric helpers shared by the whole crate.
//!
//! [`clamp_in`] is the one non-panicking clamp: [`f64::clamp`] panics when its lower end is
//! above its upper end or either is NaN, and trajkit never panics on user input. Every clamp
//! whose ends are computed (controllable sets, brackets, windows) and not ordered by
//! construction goes through it; clamps to constants or to a validated, sorted grid stay
//! [`f64::clamp`].

/// `x` clamped to `[lo, hi]`, or `None` when that range is empty: `lo > hi` (ends crossed by
/// round-off, e.g. a start acceleration one ulp past its limit, or an infeasible set) or
/// either end NaN. A NaN `x` with ordered ends comes back as NaN, as with [`f64::clamp`].
///
/// There is no value that is safe for every caller, so none is invented: each call site says
/// what an empty range means there. A controllable set that round-off made empty is an
/// infeasibility error; a candidate root outside an empty window is dropped (the other
/// candidates still give a result); a blend velocity falls back to stopping at the waypoint.
#[inline]
pub(crate) fn clamp_in(x: f64, lo: f64, hi: f64) -> Option<f64> {
    (lo <= hi).then(|| x.clamp(lo, hi))
}

#[cfg(test)]
mod tests {
    use super::clamp_in;

    #[test]
    fn clamp_in_orders_empty_and_nan() {
        assert_eq!(clamp_in(2.0, 0.0, 1.0), Some(1.0));
        assert_eq!(clamp_in(-2.0, 0.0, 1.0), Some(0.0));
        assert_eq!(clamp_in(0.5, 1.0, 1.0), Some(1.0));
        assert_eq!(clamp_in(0.5, 0.0, f64::INFINITY), Some(0.5));
        // One ulp apart the wrong way: empty, where f64::clamp panics.
        assert_eq!(
            clamp_in(0.5, 1.0, f64::from_bits(1.0f64.to_bits() - 1)),
            None
        );
        assert_eq!(clamp_in(0.5, f64::NAN, 1.0), None);
        assert_eq!(clamp_in(0.5, 0.0, f64::NAN), None);
        assert!(clamp_in(f64::NAN, 0.0, 1.0).unwrap().is_nan());
    }
}
