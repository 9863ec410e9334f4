//! Property tests with shrinking for the interpolating spline constructors: for any input —
//! finite or not, sorted or not, duplicate parameters, mismatched lengths — a constructor
//! returns a typed error or a curve that passes through every data point (within 1e-9 of the
//! data's scale, relative to the conditioning of the parameter spacing) and whose interval is
//! the data's. A failure is shrunk by proptest to a minimal case.

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use trajkit::spline::{AkimaSpline, CubicSpline, PchipSpline};
use trajkit::{Error, Path};

/// A parameter gap: mostly ordinary, sometimes tiny, zero, negative or not finite.
fn gap() -> impl Strategy<Value = f64> {
    prop_oneof![
        12 => 1e-2f64..5.0,
        1 => Just(1e-6),
        1 => Just(0.0),
        1 => Just(-0.5),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
    ]
}

/// A data value: mostly ordinary, sometimes large or not finite.
fn value() -> impl Strategy<Value = f64> {
    prop_oneof![
        12 => -100.0f64..100.0,
        1 => Just(1e6),
        1 => Just(f64::NAN),
        1 => Just(f64::NEG_INFINITY),
    ]
}

/// Parameters (from a start and gaps), row-major values (`dim` columns, possibly a row short
/// or long), and `dim` (0 included).
#[allow(clippy::type_complexity)]
fn data() -> impl Strategy<Value = (Vec<f64>, Vec<f64>, usize)> {
    (0usize..=3, 0usize..=7, -10.0f64..10.0, -1i32..=1).prop_flat_map(|(dim, n, x0, extra)| {
        let len = (n * dim) as i64 + extra as i64 * (dim as i64).min(1);
        (
            prop::collection::vec(gap(), n.saturating_sub(1)),
            prop::collection::vec(value(), len.max(0) as usize),
            Just((x0, dim)),
        )
            .prop_map(|(gaps, y, (x0, dim))| {
                let mut x = vec![x0];
                for g in gaps {
                    x.push(x[x.len() - 1] + g);
                }
                (x, y, dim)
            })
    })
}

/// The curve passes through every data point: relative to the data's scale, with room for
/// the rounding that unequal spacing (the ratio of the largest to the smallest gap) brings.
fn interpolates<P: Path>(curve: &P, x: &[f64], y: &[f64], dim: usize) -> Result<(), TestCaseError> {
    prop_assert_eq!(curve.dim(), dim);
    let (a, b) = curve.interval();
    prop_assert_eq!((a, b), (x[0], x[x.len() - 1]));
    let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let gaps: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let ratio = gaps.iter().fold(1.0f64, |m, g| m.max(*g))
        / gaps.iter().fold(f64::INFINITY, |m, g| m.min(*g));
    let tol = 1e-12 * scale * ratio.max(1.0) * 1e3;
    let mut out = vec![0.0; dim];
    for (k, &xk) in x.iter().enumerate() {
        curve.eval(xk, 0, &mut out);
        for j in 0..dim {
            let d = (out[j] - y[k * dim + j]).abs();
            prop_assert!(
                d <= tol,
                "x[{k}] = {xk}, joint {j}: {} vs {} (tolerance {tol})",
                out[j],
                y[k * dim + j]
            );
        }
    }
    Ok(())
}

/// Either a typed error (with a message) or an interpolating curve.
fn check<P: Path>(
    built: trajkit::Result<P>,
    x: &[f64],
    y: &[f64],
    dim: usize,
) -> Result<(), TestCaseError> {
    match built {
        Ok(curve) => {
            // Accepted input must have been valid: finite, increasing, matching lengths.
            prop_assert!(
                x.iter().chain(y).all(|v| v.is_finite()),
                "accepted non-finite data"
            );
            prop_assert!(
                x.windows(2).all(|w| w[1] > w[0]),
                "accepted unsorted parameters"
            );
            prop_assert_eq!(y.len(), x.len() * dim);
            interpolates(&curve, x, y, dim)
        }
        Err(e) => typed(e),
    }
}

fn typed(e: Error) -> Result<(), TestCaseError> {
    prop_assert!(!e.to_string().is_empty());
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 128,
        // Reproducible runs, no failure files: a failure prints its shrunk case.
        rng_seed: RngSeed::Fixed(0x7370_6c6e),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn cubic_constructors_err_or_interpolate((x, y, dim) in data()) {
        check(CubicSpline::natural(&x, &y, dim), &x, &y, dim)?;
        check(CubicSpline::not_a_knot(&x, &y, dim), &x, &y, dim)?;
        check(CubicSpline::periodic(&x, &y, dim), &x, &y, dim)?;
        // The same data closed (last row = first row) for the periodic spline.
        if dim > 0 && y.len() == x.len() * dim && x.len() >= 2 {
            let mut closed = y.clone();
            let n = closed.len();
            closed.copy_within(0..dim, n - dim);
            check(CubicSpline::periodic(&x, &closed, dim), &x, &closed, dim)?;
        }
    }

    #[test]
    fn local_constructors_err_or_interpolate((x, y, dim) in data()) {
        check(AkimaSpline::original(&x, &y, dim), &x, &y, dim)?;
        check(AkimaSpline::modified(&x, &y, dim), &x, &y, dim)?;
        check(PchipSpline::new(&x, &y, dim), &x, &y, dim)?;
    }
}
