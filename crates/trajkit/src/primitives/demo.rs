//! Demonstrations as the primitives receive them: input checks and finite-difference
//! derivatives of sampled trajectories.
//!
//! # Precision contract
//! [`derivative_rows`] is the exact derivative of the parabola through each sample and its
//! neighbours: second-order accurate in the sample spacing (first order at non-uniform ends
//! is not lost: the one-sided parabola is also second order).

use crate::error::{Error, Result};

/// Velocities and accelerations (row-major, like `q`) of a demonstration sampled at times
/// `ts`, by [`derivative_rows`] applied twice.
pub(crate) fn demo_derivatives(ts: &[f64], q: &[f64], dof: usize) -> (Vec<f64>, Vec<f64>) {
    let mut vel = vec![0.0; ts.len() * dof];
    let mut acc = vec![0.0; ts.len() * dof];
    derivative_rows(ts, q, dof, &mut vel);
    derivative_rows(ts, &vel, dof, &mut acc);
    (vel, acc)
}

/// Second-order finite-difference derivative on a possibly non-uniform grid of every column of
/// the row-major `t.len() × cols` table `y` into `out` (same layout): at each sample, the
/// derivative of the parabola through it and its neighbours (one-sided at the ends; a straight
/// line for two samples). The three weights are computed once per sample for all columns.
pub(crate) fn derivative_rows(t: &[f64], y: &[f64], cols: usize, out: &mut [f64]) {
    let n = t.len();
    if n == 2 {
        let inv = 1.0 / (t[1] - t[0]);
        for c in 0..cols {
            let d = (y[cols + c] - y[c]) * inv;
            out[c] = d;
            out[cols + c] = d;
        }
        return;
    }
    for k in 0..n {
        // Parabola through samples b, b+1, b+2, differentiated at t[k].
        let b = k.clamp(1, n - 2) - 1;
        let (ta, tb, tc, at) = (t[b], t[b + 1], t[b + 2], t[k]);
        let la = (2.0 * at - tb - tc) / ((ta - tb) * (ta - tc));
        let lb = (2.0 * at - ta - tc) / ((tb - ta) * (tb - tc));
        let lc = (2.0 * at - ta - tb) / ((tc - ta) * (tc - tb));
        let (ya, rest) = y[b * cols..].split_at(cols);
        let (yb, yc) = rest.split_at(cols);
        for (((o, &va), &vb), &vc) in out[k * cols..(k + 1) * cols]
            .iter_mut()
            .zip(ya)
            .zip(yb)
            .zip(&yc[..cols])
        {
            *o = la * va + lb * vb + lc * vc;
        }
    }
}

/// Validates a demonstration `t` (strictly increasing, finite) and `q` (`rows × dof`).
pub(crate) fn check_demo(t: &[f64], q: &[f64], dof: usize, min_rows: usize) -> Result<()> {
    if dof == 0 {
        return Err(Error::DimensionMismatch {
            what: "demonstration joint count".into(),
            expected: 1,
            found: 0,
        });
    }
    if t.len() < min_rows {
        return Err(Error::TooFewWaypoints {
            needed: min_rows,
            found: t.len(),
        });
    }
    if q.len() != t.len() * dof {
        return Err(Error::DimensionMismatch {
            what: format!("demonstration entries ({} samples × {dof} joints)", t.len()),
            expected: t.len() * dof,
            found: q.len(),
        });
    }
    for (k, &tk) in t.iter().enumerate() {
        crate::error::finite(|| format!("demonstration sample {k} time"), tk)?;
        if k > 0 && tk <= t[k - 1] {
            return Err(Error::InvalidValue {
                field: format!("demonstration sample {k} time"),
                value: tk,
                reason: "does not increase strictly",
            });
        }
    }
    if let Some(i) = q.iter().position(|v| !v.is_finite()) {
        return Err(Error::InvalidValue {
            field: format!("demonstration sample {} joint {}", i / dof, i % dof + 1),
            value: q[i],
            reason: "is not a finite number",
        });
    }
    Ok(())
}
