"""trajkit.spline against scipy.interpolate: same data, same calls, values and derivatives
equal to 1e-12 (relative to the data's scale) inside the interval."""
import pickle

import numpy as np
import pytest

si = pytest.importorskip("scipy.interpolate")
import trajkit  # noqa: E402
from trajkit import spline as ts  # noqa: E402


def data(seed, n=12, dim=3):
    rng = np.random.default_rng(seed)
    x = np.cumsum(rng.uniform(0.1, 1.0, n))
    y = rng.normal(size=(n, dim))
    xs = np.linspace(x[0], x[-1], 997)
    return x, y, xs


def close(a, b, scale=1.0):
    err = np.max(np.abs(np.asarray(a) - np.asarray(b)))
    assert err <= 1e-12 * scale, err


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.parametrize("bc", ["not-a-knot", "natural", "clamped", ((1, [0.3, 0.1, 0.0]), (1, [-0.7, 0.2, 1.0])), "periodic"])
def test_cubic_spline(seed, bc):
    x, y, xs = data(seed)
    if bc == "periodic":
        y[-1] = y[0]
    ours, ref = ts.CubicSpline(x, y, bc_type=bc), si.CubicSpline(x, y, bc_type=bc)
    for nu in range(4):
        # scipy's periodic spline wraps x[-1] to x[0]; the third derivative jumps there, and
        # trajkit reports the last piece's (left) value at the end: compare inside.
        t = xs[:-1] if bc == "periodic" and nu == 3 else xs
        scale = np.max(np.abs(ref(t, nu))) + 1
        close(ours(t, nu), ref(t, nu), scale)


@pytest.mark.parametrize("seed", range(5))
def test_pchip_akima_hermite_1d_and_nd(seed):
    x, y, xs = data(seed)
    for ours, ref in [
        (ts.PchipInterpolator(x, y), si.PchipInterpolator(x, y)),
        (ts.Akima1DInterpolator(x, y), si.Akima1DInterpolator(x, y)),
        (ts.Akima1DInterpolator(x, y, method="makima"), si.Akima1DInterpolator(x, y, method="makima")),
        (ts.CubicHermiteSpline(x, y, np.cos(y)), si.CubicHermiteSpline(x, y, np.cos(y))),
        (ts.PchipInterpolator(x, y[:, 0]), si.PchipInterpolator(x, y[:, 0])),
    ]:
        for nu in range(3):
            a, b = ours(xs, nu), ref(xs, nu)
            assert a.shape == b.shape
            close(a, b, np.max(np.abs(b)) + 1)


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
def test_make_interp_spline_and_bspline(k):
    x, y, xs = data(k, n=15)
    ours, ref = ts.make_interp_spline(x, y, k=k), si.make_interp_spline(x, y, k=k)
    assert isinstance(ours, ts.BSpline) and ours.k == k
    for nu in range(min(k, 3) + 1):
        close(ours(xs, nu), ref(xs, nu), np.max(np.abs(ref(xs, nu))) + 1)
    # BSpline(t, c, k) from scipy's own knots and coefficients.
    direct = ts.BSpline(ref.t, ref.c, k)
    close(direct(xs), ref(xs), np.max(np.abs(ref(xs))) + 1)


def test_make_interp_spline_with_end_derivatives():
    x, y, xs = data(9, n=10, dim=2)
    bc = ([(1, 0.0), (2, 0.0)], [(1, 0.0), (2, 0.0)])
    ours, ref = ts.make_interp_spline(x, y, k=5, bc_type=bc), si.make_interp_spline(x, y, k=5, bc_type=bc)
    close(ours(xs), ref(xs), np.max(np.abs(ref(xs))) + 1)


def test_shapes_scalars_and_inputs():
    x, y, xs = data(1)
    s = ts.CubicSpline(x, y)
    assert s(x[2]).shape == (3,)
    assert s(xs.reshape(997, 1)).shape == (997, 1, 3)
    s1 = ts.CubicSpline(list(x), list(y[:, 0]))  # lists of Python floats
    assert isinstance(s1(x[3]), float) and s1(xs).shape == (997,)
    xi = np.arange(10)  # integers are converted
    assert ts.CubicSpline(xi, xi**2)(2.5) == pytest.approx(6.25)
    ys = np.asfortranarray(y)  # not C-contiguous: copied, same result
    close(ts.CubicSpline(x, ys)(xs), s(xs))
    assert np.all(s(x[-1] + 5) == s(x[-1]))  # clamped outside the interval


def test_errors_are_trajkit_errors():
    with pytest.raises(trajkit.TrajkitError, match="repeats"):
        ts.CubicSpline([0, 1, 1], [1, 2, 3])
    with pytest.raises(ValueError, match="not a finite"):
        ts.PchipInterpolator([0, 1, np.nan], [1, 2, 3])
    with pytest.raises(trajkit.TrajkitError, match="bc_type"):
        ts.CubicSpline([0, 1, 2], [1, 2, 3], bc_type="bogus")
    with pytest.raises(trajkit.TrajkitError, match="extrapolat"):
        ts.CubicSpline([0, 1, 2], [1, 2, 3], extrapolate=True)
    with pytest.raises(trajkit.TrajkitError, match="order"):
        ts.CubicSpline([0, 1, 2], [1, 2, 3])(0.5, -1)


def test_more_curves_and_pickling():
    pts = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [3.0, 1.0]])
    cr = ts.CatmullRom(pts, "centripetal")
    assert np.allclose(cr(cr.x[2]), pts[2], atol=1e-15)
    bz = ts.Bezier(pts)
    assert np.allclose(bz(0.0), pts[0]) and np.allclose(bz(1.0), pts[-1])
    circle = ts.NURBS.circle((1.0, 2.0), 3.0)
    u = np.linspace(*circle.interval, 101)
    assert np.allclose(np.linalg.norm(circle(u) - [1.0, 2.0], axis=1), 3.0, atol=1e-14)
    x = np.array([0.0, 1.0, 2.5, 3.0])
    mj = ts.minimum_jerk(x, pts)
    assert np.allclose(mj(x), pts, atol=1e-12) and np.allclose(mj(x[[0, -1]], 1), 0, atol=1e-12)
    ms = ts.minimum_snap(x, pts)
    assert np.allclose(ms(x), pts, atol=1e-12)
    keys = np.array([[1, 0, 0, 0], [np.cos(0.3), np.sin(0.3), 0, 0], [np.cos(0.6), 0, np.sin(0.6), 0]])
    so3 = ts.SO3Spline([0.0, 1.0, 2.0], keys)
    assert np.allclose(np.abs(np.sum(so3([0.0, 1.0, 2.0]) * keys, axis=1)), 1.0, atol=1e-12)
    assert so3.angular_velocity(np.linspace(0, 2, 5)).shape == (5, 3)
    for c in [ts.CubicSpline(x, pts), ts.PchipInterpolator(x, pts), ts.Akima1DInterpolator(x, pts, method="makima"),
              ts.make_interp_spline(x, pts, k=3), cr, bz, circle, mj, so3]:
        c2 = pickle.loads(pickle.dumps(c))
        t = np.linspace(*c.interval, 9)
        assert np.array_equal(c(t), c2(t)), type(c)
    traj = ts.CubicSpline(x, pts).as_trajectory()
    assert traj.duration == 3.0 and traj(1.0).shape == (2,)


@pytest.mark.parametrize("dim", [1, 2, 7, 12, 20])
def test_many_times_any_order(dim):
    """Evaluation over arrays (each time's piece found from the previous one, large arrays
    split across threads) equals scipy on sorted, reversed, random and out-of-range times,
    and equals one-time evaluation bitwise."""
    rng = np.random.default_rng(dim)
    x = np.cumsum(rng.uniform(0.1, 1.0, 40))
    y = rng.normal(size=(40, dim))
    sorted_t = np.linspace(x[0], x[-1], 60_001)
    random_t = rng.uniform(x[0] - 0.5, x[-1] + 0.5, 50_000)
    for ours, ref in [(ts.CubicSpline(x, y), si.CubicSpline(x, y)),
                      (ts.PchipInterpolator(x, y), si.PchipInterpolator(x, y)),
                      (ts.make_interp_spline(x, y, k=5), si.make_interp_spline(x, y, k=5))]:
        for t in [sorted_t, sorted_t[::-1], random_t]:
            inside = np.clip(t, x[0], x[-1])  # trajkit clamps; scipy extrapolates
            for nu in (0, 1, 3):
                got = ours(t, nu)
                want = ref(inside, nu)
                close(got, want, np.max(np.abs(want)) + 1)
                for i in rng.integers(0, len(t), 20):
                    assert np.array_equal(np.asarray(ours(t[i], nu)), got[i])
