//! Roots of a scalar residual on an interval by sampling: sign changes bracketed and
//! refined (Illinois steps with bisections, to adjacent doubles), and tangent roots (a local
//! minimum of |f| between samples of one sign, found by golden sections) offered too, since a
//! residual that touches zero within the tolerance may never change sign. Used by step 1's
//! rescue of the none family in the middle ramp's duration (`closed.rs`), where the closed
//! form's polynomial is ill-conditioned; every root found is verified by the caller.
//!
//! Cost: 21 evaluations per interval, about 10–60 per sign change and ~90 per local minimum.

/// Samples `f` on `[lo, hi]` (both ends, and points crowding towards each end: log-spaced
/// when the piece spans more than a factor 10) and calls `root` with every root bracketed
/// by a sign change, bisected to adjacent doubles, and with every local minimum of |f|
/// between samples of one sign (a tangent root, whose residual may stay within the
/// tolerance without changing sign; minimized by golden sections) and at an end of the
/// piece. The caller verifies each.
pub(super) fn scan_piece(lo: f64, hi: f64, f: impl Fn(f64) -> f64, mut root: impl FnMut(f64)) {
    const U: [f64; 21] = [
        0.0,
        1e-12,
        1e-9,
        1e-6,
        1e-4,
        1e-2,
        0.05,
        0.15,
        0.3,
        0.4,
        0.5,
        0.6,
        0.7,
        0.85,
        0.95,
        0.99,
        0.9999,
        0.999999,
        0.999999999,
        0.999999999999,
        1.0,
    ];
    let log = lo > 0.0 && hi > 10.0 * lo;
    let at = |u: f64| {
        if u >= 1.0 {
            hi
        } else if log {
            lo * (hi / lo).powf(u)
        } else {
            lo + (hi - lo) * u
        }
    };
    let mut xs = [(0.0, f64::NAN); 21];
    let mut n = 0;
    for u in U {
        let t = at(u);
        if t <= 0.0 || (n > 0 && t <= xs[n - 1].0) {
            continue;
        }
        xs[n] = (t, f(t));
        n += 1;
    }
    let xs = &xs[..n];
    for (i, &(t, ft)) in xs.iter().enumerate() {
        if ft == 0.0 {
            root(t);
            continue;
        }
        if let Some(&(ta, fa)) = i.checked_sub(1).map(|k| &xs[k]) {
            if fa != 0.0 && (fa < 0.0) != (ft < 0.0) {
                root(bracketed_root(&f, ta, t, fa));
            }
        }
        let below = |k: Option<usize>| {
            k.and_then(|k| xs.get(k))
                .is_none_or(|&(_, g)| g.abs() > ft.abs() && (g < 0.0) == (ft < 0.0))
        };
        if below(i.checked_sub(1)) && below(Some(i + 1)) {
            if i == 0 || i + 1 == n {
                root(t);
                continue;
            }
            let (a, b) = (xs[i - 1].0, xs[i + 1].0);
            let sg = ft.signum();
            let m = golden_min(|x| sg * f(x), a, b);
            let fm = f(m);
            if (fm < 0.0) != (ft < 0.0) && fm != 0.0 {
                root(bracketed_root(&f, a, m, xs[i - 1].1));
                root(bracketed_root(&f, m, b, fm));
            } else {
                root(m);
            }
        }
    }
}

/// A root of `f` between `a` and `b` (f(a) = `fa` and f(b) of opposite signs): Illinois
/// steps, with a bisection whenever they stall, to adjacent doubles.
fn bracketed_root(f: impl Fn(f64) -> f64, a: f64, b: f64, fa: f64) -> f64 {
    let (mut x0, mut x1, mut g0) = (a, b, fa);
    let mut g1 = f(b);
    let mut side = 0i8;
    for i in 0..200 {
        if (x1 - x0).abs() <= 4.0 * f64::EPSILON * x0.abs().max(x1.abs()) {
            break;
        }
        let m = if i % 4 == 3 || g0 == g1 {
            0.5 * (x0 + x1)
        } else {
            let m = x1 - g1 * (x1 - x0) / (g1 - g0);
            if m > x0.min(x1) && m < x0.max(x1) {
                m
            } else {
                0.5 * (x0 + x1)
            }
        };
        if m <= x0.min(x1) || m >= x0.max(x1) {
            break;
        }
        let gm = f(m);
        if gm == 0.0 {
            return m;
        }
        if (gm < 0.0) == (g0 < 0.0) {
            (x0, g0) = (m, gm);
            if side == -1 {
                g1 *= 0.5;
            }
            side = -1;
        } else {
            (x1, g1) = (m, gm);
            if side == 1 {
                g0 *= 0.5;
            }
            side = 1;
        }
    }
    if g0.abs() < g1.abs() {
        x0
    } else {
        x1
    }
}

/// The minimizer of a unimodal `g` on `[a, b]` by golden sections, to adjacent doubles (at
/// most 90 steps).
fn golden_min(g: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    const R: f64 = 0.618_033_988_749_894_8;
    let mut c = b - R * (b - a);
    let mut d = a + R * (b - a);
    let (mut gc, mut gd) = (g(c), g(d));
    for _ in 0..90 {
        if gc < gd {
            b = d;
            (d, gd) = (c, gc);
            c = b - R * (b - a);
            gc = g(c);
        } else {
            a = c;
            (c, gc) = (d, gd);
            d = a + R * (b - a);
            gd = g(d);
        }
        if !(c > a && d < b && c < d) {
            break;
        }
    }
    if gc < gd {
        c
    } else {
        d
    }
}
