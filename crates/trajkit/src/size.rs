//! Size limits: every count a caller controls is checked against what it implies before
//! anything is allocated.
//!
//! Waypoints, gridpoints, samples (duration × rate), basis functions, kernel points, demos:
//! each entry point that allocates in proportion to such a count (or to its square) first
//! computes the bytes it will need and refuses the input with [`Error::TooLarge`] when they
//! exceed [`MEMORY_BUDGET`]. The error names the count, its value, the largest allowed value
//! and the reason, e.g. `sample count (duration × rate) = 3.6e10 is above the limit of 4628197
//! (a sample of 7 joints takes 232 bytes; budget 1 GiB)`. Where the work grows faster than the
//! memory (a dense factorization is cubic in its size), the entry point also states a work cap
//! of its own with [`check`].
//!
//! The budget is per data structure, not per process: a run may hold a few such structures at
//! once (a sample table and its text, for example).

use crate::error::{Error, Result};

/// Bytes one user-sized data structure may take: 1 GiB.
pub const MEMORY_BUDGET: usize = 1 << 30;

/// Bytes as people read them: `232 bytes`, `1.5 KiB`, `1 GiB`.
pub fn human_bytes(bytes: f64) -> String {
    const UNITS: [&str; 5] = ["KiB", "MiB", "GiB", "TiB", "PiB"];
    if bytes < 1024.0 {
        return format!("{} bytes", bytes.round());
    }
    let mut v = bytes / 1024.0;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < UNITS.len() {
        v /= 1024.0;
        u += 1;
    }
    let s = format!("{v:.1}");
    let s = s.strip_suffix(".0").unwrap_or(&s);
    format!("{s} {}", UNITS[u])
}

/// The largest count of items of `bytes_each` bytes that fits in [`MEMORY_BUDGET`].
pub fn max_count(bytes_each: f64) -> f64 {
    (MEMORY_BUDGET as f64 / bytes_each.max(1.0)).floor()
}

/// Refuses `count` items of `bytes_each` bytes each when they exceed [`MEMORY_BUDGET`];
/// `what` names the count, `item` the item (e.g. `"a sample of 7 joints"`). Returns the count
/// as a `usize` when it fits. NaN and negative counts are refused too.
pub fn check_memory(what: &str, count: f64, bytes_each: f64, item: &str) -> Result<usize> {
    let limit = max_count(bytes_each);
    let reason = format!(
        "{item} takes {}; budget {}",
        human_bytes(bytes_each),
        human_bytes(MEMORY_BUDGET as f64)
    );
    check(what, count, limit, &reason)
}

/// Refuses `count` when it is above `limit` (or NaN or negative), saying `reason`; returns it
/// as a `usize` otherwise.
pub fn check(what: &str, count: f64, limit: f64, reason: &str) -> Result<usize> {
    if count.is_nan() || count < 0.0 {
        return Err(Error::InvalidValue {
            field: what.to_string(),
            value: count,
            reason: "is not a count (a number >= 0)",
        });
    }
    if count > limit {
        return Err(Error::TooLarge {
            what: what.to_string(),
            value: count,
            limit,
            reason: reason.to_string(),
        });
    }
    Ok(count as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn human_units() {
        assert_eq!(human_bytes(232.0), "232 bytes");
        assert_eq!(human_bytes(1536.0), "1.5 KiB");
        assert_eq!(human_bytes(MEMORY_BUDGET as f64), "1 GiB");
        assert_eq!(human_bytes(8e12), "7.3 TiB");
    }

    #[test]
    fn counts_are_checked_against_the_budget() {
        assert_eq!(check_memory("n", 1000.0, 8.0, "a number").unwrap(), 1000);
        let e = check_memory("sample count", 1e10, 232.0, "a sample of 7 joints").unwrap_err();
        match &e {
            Error::TooLarge {
                value, limit, what, ..
            } => {
                assert_eq!(*value, 1e10);
                assert_eq!(*limit, (MEMORY_BUDGET as f64 / 232.0).floor());
                assert_eq!(what, "sample count");
            }
            other => panic!("{other:?}"),
        }
        let text = e.to_string();
        assert!(
            text.starts_with("sample count = 10000000000 is above the limit of 4628197")
                && text.contains("a sample of 7 joints takes 232 bytes; budget 1 GiB"),
            "{text}"
        );
        assert!(check("n", f64::NAN, 10.0, "x").is_err());
        assert!(check("n", -1.0, 10.0, "x").is_err());
        assert_eq!(check("n", 10.0, 10.0, "x").unwrap(), 10);
    }
}
