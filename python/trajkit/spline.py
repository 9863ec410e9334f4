"""scipy-like splines and curves on trajkit's implementations.

Names and call conventions follow ``scipy.interpolate``: ``CubicSpline(x, y, bc_type=...)``,
``PchipInterpolator(x, y)``, ``Akima1DInterpolator(x, y, method='akima'|'makima')``,
``CubicHermiteSpline(x, y, dydx)``, ``BSpline(t, c, k)``, ``make_interp_spline(x, y, k=3,
bc_type=None)``; every curve is called as ``curve(x, nu=0)`` with ``x`` a scalar or an array of
any shape (the result has shape ``x.shape + (dim,)``, or ``x.shape`` when ``y`` was 1-D).
trajkit adds ``CatmullRom``, ``Bezier``, ``NURBS`` (exact circles and arcs), ``minimum_jerk``,
``minimum_snap`` and ``SO3Spline``.

One difference from scipy: outside the interval the parameter is clamped (trajkit's policy);
scipy extrapolates. ``extrapolate=True`` is refused rather than ignored.
"""

from ._trajkit import spline as _s

Curve = _s.Curve
CubicSpline = _s.CubicSpline
PchipInterpolator = _s.PchipInterpolator
Akima1DInterpolator = _s.Akima1DInterpolator
CubicHermiteSpline = _s.CubicHermiteSpline
BSpline = _s.BSpline
make_interp_spline = _s.make_interp_spline
minimum_jerk = _s.minimum_jerk
minimum_snap = _s.minimum_snap
CatmullRom = _s.CatmullRom
Bezier = _s.Bezier
NURBS = _s.NURBS
SO3Spline = _s.SO3Spline

__all__ = [
    "Curve",
    "CubicSpline",
    "PchipInterpolator",
    "Akima1DInterpolator",
    "CubicHermiteSpline",
    "BSpline",
    "make_interp_spline",
    "minimum_jerk",
    "minimum_snap",
    "CatmullRom",
    "Bezier",
    "NURBS",
    "SO3Spline",
]
