//! Input checks shared by the curve constructors; every failure is a typed [`Error`] naming
//! the field and the value.

use crate::error::{Error, Result};

/// `dim` must be at least 1.
pub(crate) fn dim(dim: usize) -> Result<()> {
    if dim == 0 {
        return Err(Error::DimensionMismatch {
            what: "curve dimension".into(),
            expected: 1,
            found: 0,
        });
    }
    Ok(())
}

/// Parameters (`what` names them, e.g. `"x"`): at least `min` of them, finite, strictly
/// increasing. A repeated value is [`Error::DuplicateWaypoint`], a decrease
/// [`Error::InvalidValue`].
pub(crate) fn increasing(what: &str, x: &[f64], min: usize) -> Result<()> {
    if x.len() < min {
        return Err(Error::TooFewWaypoints {
            needed: min,
            found: x.len(),
        });
    }
    for (i, &v) in x.iter().enumerate() {
        if !v.is_finite() {
            return Err(Error::InvalidValue {
                field: format!("{what}[{i}]"),
                value: v,
                reason: "is not a finite number",
            });
        }
        if i > 0 {
            if v == x[i - 1] {
                return Err(Error::DuplicateWaypoint { index: i });
            }
            if v < x[i - 1] {
                return Err(Error::InvalidValue {
                    field: format!("{what}[{i}]"),
                    value: v,
                    reason: "is smaller than the value before it (must increase)",
                });
            }
        }
    }
    Ok(())
}

/// Knots: finite and non-decreasing.
pub(crate) fn nondecreasing(what: &str, t: &[f64]) -> Result<()> {
    for (i, &v) in t.iter().enumerate() {
        if !v.is_finite() {
            return Err(Error::InvalidValue {
                field: format!("{what}[{i}]"),
                value: v,
                reason: "is not a finite number",
            });
        }
        if i > 0 && v < t[i - 1] {
            return Err(Error::InvalidValue {
                field: format!("{what}[{i}]"),
                value: v,
                reason: "is smaller than the knot before it (knots must not decrease)",
            });
        }
    }
    Ok(())
}

/// A row-major `n × dim` block of values (`what` names it): right size, all finite.
pub(crate) fn values(what: &str, y: &[f64], n: usize, dim: usize) -> Result<()> {
    if y.len() != n * dim {
        return Err(Error::DimensionMismatch {
            what: format!("{what} length (rows × dim = {n} × {dim})"),
            expected: n * dim,
            found: y.len(),
        });
    }
    finite(what, y, dim)
}

/// All entries finite; the error names row and column of the first bad one.
pub(crate) fn finite(what: &str, y: &[f64], dim: usize) -> Result<()> {
    if let Some(k) = y.iter().position(|v| !v.is_finite()) {
        return Err(Error::InvalidValue {
            field: format!("{what}[{}][{}]", k / dim.max(1), k % dim.max(1)),
            value: y[k],
            reason: "is not a finite number",
        });
    }
    Ok(())
}

/// A slice that must have exactly `len` entries.
pub(crate) fn len(what: &str, v: &[f64], len: usize) -> Result<()> {
    if v.len() != len {
        return Err(Error::DimensionMismatch {
            what: what.into(),
            expected: len,
            found: v.len(),
        });
    }
    Ok(())
}

/// Interpolation data: `dim >= 1`, at least `min` increasing finite `x`, `y` of `x.len() × dim`
/// finite values.
pub(crate) fn interpolation_data(x: &[f64], y: &[f64], dim: usize, min: usize) -> Result<()> {
    self::dim(dim)?;
    increasing("x", x, min)?;
    values("y", y, x.len(), dim)
}
