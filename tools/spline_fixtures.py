#!/usr/bin/env python3
"""Reference fixtures for trajkit::spline from scipy.interpolate and geomdl.

Writes small JSON files under crates/trajkit/tests/fixtures/spline/. Matrices are flattened
row-major with their `dim`; `values[k]` holds the k-th derivative at every query point
(`len(s) × dim`). Floats are written with Python's shortest round-trip repr, so the files are
exact.

Usage: python3 tools/spline_fixtures.py            (creates tools/.venv-spline on first run)
       python3 tools/spline_fixtures.py --no-venv  (uses the current interpreter)
"""
import json
import os
from pyenv import use_venv

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "crates", "trajkit", "tests", "fixtures", "spline")
PACKAGES = ["numpy", "scipy==1.17.1", "geomdl==5.4.0"]


use_venv("spline", PACKAGES)

import numpy as np  # noqa: E402
import scipy  # noqa: E402
from scipy import interpolate as si  # noqa: E402

RNG = np.random.default_rng(20261122)


def flat(a):
    return [float(v) for v in np.asarray(a, dtype=float).ravel()]


def nonuniform(n, lo=0.0):
    return np.concatenate([[lo], lo + np.cumsum(RNG.uniform(0.2, 1.5, n - 1))])


def queries(x, m=41):
    """Interior points, every break, and both ends."""
    s = np.sort(np.concatenate([RNG.uniform(x[0], x[-1], m), x]))
    return s


def derivs(f, s, orders):
    return [flat(f(s, nu=k) if k else f(s)) for k in orders]


def write(name, doc):
    doc["generator"] = f"tools/spline_fixtures.py (scipy {scipy.__version__})"
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, name), "w") as fh:
        json.dump(doc, fh, separators=(",", ":"))
        fh.write("\n")
    print("wrote", name, os.path.getsize(os.path.join(OUT, name)), "bytes")


def ppoly_eval(p, s, orders):
    return [flat(p(s, k, extrapolate=True)) for k in orders]


def cubic():
    cases = []
    for n, dim in [(2, 2), (3, 2), (4, 1), (9, 3), (25, 2)]:
        x = nonuniform(n, RNG.uniform(-2, 2))
        y = RNG.uniform(-3, 3, (n, dim))
        yp = y.copy()
        yp[-1] = yp[0]
        ds = RNG.uniform(-2, 2, dim)
        de = RNG.uniform(-2, 2, dim)
        s = queries(x)
        for bc, yy, kw in [
            ("natural", y, "natural"),
            ("clamped", y, ((1, ds), (1, de))),
            ("not-a-knot", y, "not-a-knot"),
            ("periodic", yp, "periodic"),
        ]:
            sp = si.CubicSpline(x, yy, bc_type=kw)
            case = {"bc": bc, "dim": dim, "x": flat(x), "y": flat(yy), "s": flat(s),
                    "values": ppoly_eval(sp, s, range(4))}
            if bc == "clamped":
                case["d_start"] = flat(ds)
                case["d_end"] = flat(de)
            cases.append(case)
    write("cubic.json", {"cases": cases})


def hermite():
    cases = []
    for n, dim in [(2, 1), (6, 3)]:
        x = nonuniform(n)
        y = RNG.uniform(-3, 3, (n, dim))
        dy = RNG.uniform(-3, 3, (n, dim))
        s = queries(x)
        sp = si.CubicHermiteSpline(x, y, dy)
        cases.append({"kind": "cubic", "dim": dim, "x": flat(x), "y": flat(y), "dydx": flat(dy),
                      "s": flat(s), "values": ppoly_eval(sp, s, range(4))})
        # Quintic Hermite: scipy's BPoly.from_derivatives with value, slope, curvature.
        d2 = RNG.uniform(-3, 3, (n, dim))
        yi = [[list(np.column_stack([y[i], dy[i], d2[i]])[d]) for d in range(dim)] for i in range(n)]
        vals = [[] for _ in range(6)]
        for d in range(dim):
            bp = si.BPoly.from_derivatives(x, [yi[i][d] for i in range(n)])
            for k in range(6):
                vals[k].append(bp(s, k))
        values = [flat(np.column_stack(v)) for v in vals]
        cases.append({"kind": "quintic", "dim": dim, "x": flat(x), "y": flat(y), "dydx": flat(dy),
                      "d2ydx2": flat(d2), "s": flat(s), "values": values})
    write("hermite.json", {"cases": cases})


def shape_preserving():
    data = []
    x = np.array([0.0, 1.0, 2.0, 3.0, 4.5, 5.0, 6.0, 8.0, 9.0, 10.0])
    y1 = np.array([0.0, 0.1, 0.1, 0.1, 2.0, 2.5, 2.6, 2.6, 5.0, 5.0])  # monotone with flats
    y2 = np.array([1.0, -1.0, 0.5, 0.5, 3.0, -2.0, -2.0, 0.0, 1.0, 0.2])  # oscillating
    y = np.column_stack([y1, y2])
    data.append((x, y))
    xr = nonuniform(12)
    data.append((xr, RNG.uniform(-1, 1, (12, 3))))
    data.append((np.array([0.0, 1.0, 3.0]), np.array([[0.0], [1.0], [0.5]])))
    data.append((np.array([0.0, 2.0]), np.array([[1.0, 3.0], [2.0, -1.0]])))
    cases = []
    for x, y in data:
        s = queries(x)
        dim = y.shape[1]
        p = si.PchipInterpolator(x, y)
        cases.append({"kind": "pchip", "dim": dim, "x": flat(x), "y": flat(y), "s": flat(s),
                      "values": ppoly_eval(p, s, range(4))})
        if len(x) >= 2:
            for method in ["akima", "makima"]:
                a = si.Akima1DInterpolator(x, y, method=method)
                cases.append({"kind": method, "dim": dim, "x": flat(x), "y": flat(y), "s": flat(s),
                              "values": ppoly_eval(a, s, range(4))})
    write("shape_preserving.json", {"cases": cases})


def bspline_case(b, s, extra=None):
    k = b.k
    dim = 1 if b.c.ndim == 1 else b.c.shape[1]
    case = {"k": int(k), "dim": dim, "t": flat(b.t), "c": flat(b.c), "s": flat(s),
            "values": [flat(b(s, nu=j)) for j in range(k + 2)]}
    if extra:
        case.update(extra)
    return case


def interp():
    cases = []
    # make_interp_spline: default (not-a-knot for odd k), and end-derivative conditions.
    for k, n, dim in [(1, 6, 2), (2, 7, 1), (3, 8, 3), (5, 10, 2), (7, 12, 2), (3, 4, 1)]:
        x = nonuniform(n)
        y = RNG.uniform(-2, 2, (n, dim))
        b = si.make_interp_spline(x, y, k=k)
        cases.append(bspline_case(b, queries(x), {"x": flat(x), "y": flat(y), "bc": "default"}))
    for k, n, dim in [(3, 6, 2), (5, 7, 3), (7, 9, 2), (5, 2, 2), (7, 2, 1), (3, 2, 1)]:
        x = nonuniform(n)
        y = RNG.uniform(-2, 2, (n, dim))
        nd = (k - 1) // 2
        left = [(j, RNG.uniform(-1, 1, dim)) for j in range(1, nd + 1)]
        right = [(j, RNG.uniform(-1, 1, dim)) for j in range(1, nd + 1)]
        b = si.make_interp_spline(x, y, k=k, bc_type=(left, right))
        cases.append(bspline_case(b, queries(x), {
            "x": flat(x), "y": flat(y), "bc": "derivatives",
            "d_start": [flat(v) for _, v in left], "d_end": [flat(v) for _, v in right]}))
    for bc in ["natural", "clamped"]:
        x = nonuniform(7)
        y = RNG.uniform(-2, 2, (7, 2))
        b = si.make_interp_spline(x, y, k=3, bc_type=bc)
        cases.append(bspline_case(b, queries(x), {"x": flat(x), "y": flat(y), "bc": bc}))
    write("interp.json", {"cases": cases})


def lsq():
    cases = []
    for k, dim in [(3, 2), (2, 1), (5, 3)]:
        x = np.sort(RNG.uniform(0, 10, 60))
        x[0], x[-1] = 0.0, 10.0
        y = np.column_stack([np.sin(x * (d + 1) * 0.4) + 0.05 * RNG.normal(size=60) for d in range(dim)])
        inner = np.array([1.5, 3.0, 4.2, 6.0, 7.7, 8.5])
        t = np.concatenate([[0.0] * (k + 1), inner, [10.0] * (k + 1)])
        b = si.make_lsq_spline(x, y, t, k=k)
        cases.append(bspline_case(b, queries(np.array([0.0, 10.0]), 30), {"x": flat(x), "y": flat(y)}))
    write("lsq.json", {"cases": cases})


def bspline():
    cases = []
    for k, ncp, dim, clamped in [(3, 8, 2, True), (2, 6, 1, False), (4, 9, 3, True), (1, 5, 2, True),
                                  (5, 10, 2, False), (3, 7, 1, False)]:
        if clamped:
            inner = np.sort(RNG.uniform(0, 5, ncp - k - 1))
            t = np.concatenate([[0.0] * (k + 1), inner, [5.0] * (k + 1)])
        else:
            t = np.sort(RNG.uniform(0, 5, ncp + k + 1))
        c = RNG.uniform(-2, 2, (ncp, dim))
        b = si.BSpline(t, c, k, extrapolate=False)
        lo, hi = t[k], t[ncp]
        s = queries(np.array([lo] + [v for v in t[k + 1:ncp] if lo < v < hi] + [hi]), 30)
        case = bspline_case(b, s)
        inserts = []
        for xi in [lo + 0.3 * (hi - lo), t[k + 1] if ncp > k + 1 else lo + 0.5 * (hi - lo)]:
            if not (lo < xi < hi):
                continue
            bi = b.insert_knot(xi, m=1)
            inserts.append({"x": float(xi), "t": flat(bi.t), "c": flat(bi.c)})
        case["insert_knot"] = inserts
        dm = si.BSpline.design_matrix(s, t, k).toarray()
        case["design_matrix"] = flat(dm)
        cases.append(case)
    write("bspline.json", {"cases": cases})


def nurbs():
    from geomdl import NURBS, BSpline as GB, operations
    import geomdl
    cases = {}
    # 9-point unit circle (degree 2).
    w = np.sqrt(0.5)
    pts = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
    wts = [1, w, 1, w, 1, w, 1, w, 1]
    kv = [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1]
    crv = NURBS.Curve()
    crv.degree = 2
    crv.ctrlptsw = [[p[0] * wi, p[1] * wi, wi] for p, wi in zip(pts, wts)]
    crv.knotvector = kv
    s = np.sort(np.concatenate([RNG.uniform(0, 1, 20), [0, 0.25, 0.5, 0.75, 1.0]]))
    vals = [[], [], []]
    for u in s:
        d = crv.derivatives(float(u), order=2)
        for j in range(3):
            vals[j].extend(float(v) for v in d[j])
    cases["circle"] = {"degree": 2, "dim": 2, "knots": kv, "points": flat(pts), "weights": flat(wts),
                       "s": flat(s), "values": vals}
    # A general rational curve in 3-D with derivatives.
    c3 = NURBS.Curve()
    c3.degree = 3
    p3 = RNG.uniform(-2, 2, (7, 3))
    w3 = RNG.uniform(0.3, 2.0, 7)
    c3.ctrlptsw = [list(p * wi) + [wi] for p, wi in zip(p3, w3)]
    c3.knotvector = [0, 0, 0, 0, 0.2, 0.45, 0.7, 1, 1, 1, 1]
    vals = [[], [], [], []]
    for u in s:
        d = c3.derivatives(float(u), order=3)
        for j in range(4):
            vals[j].extend(float(v) for v in d[j])
    cases["rational3d"] = {"degree": 3, "dim": 3, "knots": c3.knotvector, "points": flat(p3),
                           "weights": flat(w3), "s": flat(s), "values": vals}
    # Degree elevation by one (geomdl) of a single-segment curve (a Bezier curve written as a
    # B-spline). geomdl 5.4's elevation of curves with interior knots changes the curve (it
    # replaces the knot vector by a uniform one), so multi-span elevation is checked in Rust by
    # evaluating both curves, not against geomdl.
    b = GB.Curve()
    b.degree = 3
    pb = RNG.uniform(-2, 2, (4, 3))
    b.ctrlpts = [list(map(float, p)) for p in pb]
    b.knotvector = [0, 0, 0, 0, 1, 1, 1, 1]
    kv0 = list(b.knotvector)
    b2 = operations.degree_operations(b, [2])  # in place
    cases["elevate"] = {"degree": 3, "dim": 3, "knots": kv0, "points": flat(pb), "times": 2,
                        "elevated_degree": b2.degree, "elevated_knots": list(map(float, b2.knotvector)),
                        "elevated_points": flat(b2.ctrlpts)}
    doc = {"cases": cases, "geomdl": geomdl.__version__}
    write("nurbs.json", doc)


if __name__ == "__main__":
    cubic()
    hermite()
    shape_preserving()
    interp()
    lsq()
    bspline()
    nurbs()
