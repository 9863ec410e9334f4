//! B-spline basis functions (Cox–de Boor recursion) and their derivatives, evaluated into
//! fixed-size stack buffers: no allocation for any degree up to [`MAX_DEGREE`].

/// The largest B-spline degree trajkit evaluates (stack buffers are sized by it).
pub const MAX_DEGREE: usize = 20;

pub(crate) const K1: usize = MAX_DEGREE + 1;

/// The knot span `l` with `t[l] <= s < t[l+1]` among the spans of the domain
/// `[t[k], t[n]]` (`n = t.len() − k − 1` basis functions); `s` at or beyond the right end gives
/// the last non-empty span, below the left end (or NaN) the first. Binary search.
#[inline]
pub(crate) fn find_span(t: &[f64], k: usize, s: f64) -> usize {
    let n = t.len() - k - 1;
    // Number of knots t[k+1..n] that are <= s.
    let c = t[k + 1..n].partition_point(|&v| v <= s);
    let mut l = k + c;
    while l > k && t[l] == t[l + 1] {
        l -= 1;
    }
    l
}

/// Like [`find_span`], trying span `hint` and the one after it first (sorted sweeps).
#[inline]
pub(crate) fn find_span_from(t: &[f64], k: usize, s: f64, hint: usize) -> usize {
    let n = t.len() - k - 1;
    if hint >= k && hint < n && t[hint] <= s {
        if s < t[hint + 1] || hint + 1 == n {
            return hint;
        }
        if hint + 2 <= n && s < t[hint + 2] {
            return hint + 1;
        }
    }
    find_span(t, k, s)
}

/// The `k + 1` non-zero basis functions `N_{l−k..=l, k}(s)` on span `l` into `nb[..=k]`.
#[inline(always)]
pub(crate) fn basis_funs(t: &[f64], k: usize, l: usize, s: f64, nb: &mut [f64; K1]) {
    let mut left = [0.0; K1];
    let mut right = [0.0; K1];
    nb[0] = 1.0;
    for j in 1..=k {
        left[j] = s - t[l + 1 - j];
        right[j] = t[l + j] - s;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = nb[r] / (right[r + 1] + left[j - r]);
            nb[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        nb[j] = saved;
    }
}

/// The `order`-th derivatives of the `k + 1` non-zero basis functions on span `l` into
/// `out[..=k]` (zeros when `order > k`).
pub(crate) fn basis_ders(t: &[f64], k: usize, l: usize, s: f64, order: usize, out: &mut [f64]) {
    if order == 0 {
        let mut nb = [0.0; K1];
        basis_funs(t, k, l, s, &mut nb);
        out[..=k].copy_from_slice(&nb[..=k]);
        return;
    }
    if order > k {
        out[..=k].fill(0.0);
        return;
    }
    // ndu[j][r]: basis functions (upper triangle incl. diagonal) and knot differences (lower).
    let mut ndu = [[0.0; K1]; K1];
    let mut left = [0.0; K1];
    let mut right = [0.0; K1];
    ndu[0][0] = 1.0;
    for j in 1..=k {
        left[j] = s - t[l + 1 - j];
        right[j] = t[l + j] - s;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let n = order;
    let ki = k as isize;
    let mut a = [[0.0; K1]; 2];
    for r in 0..=k {
        let ri = r as isize;
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        let mut d = 0.0;
        for kk in 1..=n {
            let kki = kk as isize;
            d = 0.0;
            let rk = ri - kki;
            let pk = ki - kki;
            if ri >= kki {
                a[s2][0] = a[s1][0] / ndu[(pk + 1) as usize][rk as usize];
                d = a[s2][0] * ndu[rk as usize][pk as usize];
            }
            let j1: isize = if rk >= -1 { 1 } else { -rk };
            let j2: isize = if ri - 1 <= pk { kki - 1 } else { ki - ri };
            let mut j = j1;
            while j <= j2 {
                let ju = j as usize;
                a[s2][ju] = (a[s1][ju] - a[s1][ju - 1]) / ndu[(pk + 1) as usize][(rk + j) as usize];
                d += a[s2][ju] * ndu[(rk + j) as usize][pk as usize];
                j += 1;
            }
            if ri <= pk {
                a[s2][kk] = -a[s1][kk - 1] / ndu[(pk + 1) as usize][r];
                d += a[s2][kk] * ndu[r][pk as usize];
            }
            std::mem::swap(&mut s1, &mut s2);
        }
        out[r] = d;
    }
    // Multiply by k! / (k − n)!.
    let mut f = 1.0;
    for m in 0..n {
        f *= (k - m) as f64;
    }
    for v in out[..=k].iter_mut() {
        *v *= f;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_basis_matches_differences() {
        let t = [0.0, 0.0, 0.0, 0.0, 0.5, 1.2, 1.2, 2.0, 3.0, 3.0, 3.0, 3.0];
        let k = 3;
        for &s in &[0.1, 0.7, 1.5, 2.5] {
            let l = find_span(&t, k, s);
            let mut d1 = [0.0; K1];
            basis_ders(&t, k, l, s, 1, &mut d1);
            let h = 1e-6;
            let mut a = [0.0; K1];
            let mut b = [0.0; K1];
            basis_funs(&t, k, l, s + h, &mut a);
            basis_funs(&t, k, l, s - h, &mut b);
            for r in 0..=k {
                assert!((d1[r] - (a[r] - b[r]) / (2.0 * h)).abs() < 1e-6);
            }
            let mut sum = 0.0;
            basis_funs(&t, k, l, s, &mut a);
            for r in 0..=k {
                sum += a[r];
            }
            assert!((sum - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn span_search_handles_repeated_knots() {
        let t = [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0];
        let k = 2;
        assert_eq!(find_span(&t, k, 0.0), 2);
        assert_eq!(find_span(&t, k, 0.5), 2);
        assert_eq!(find_span(&t, k, 1.0), 4);
        assert_eq!(find_span(&t, k, 2.0), 4);
        assert_eq!(find_span(&t, k, 5.0), 4);
        assert_eq!(find_span(&t, k, -1.0), 2);
        for h in 0..t.len() {
            for i in 0..=40 {
                let s = -0.5 + i as f64 * 0.075;
                assert_eq!(
                    find_span_from(&t, k, s, h),
                    find_span(&t, k, s),
                    "s={s} h={h}"
                );
            }
        }
    }
}
