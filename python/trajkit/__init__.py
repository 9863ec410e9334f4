"""trajkit: robot paths to trajectories, from Python.

A thin layer over the trajkit Rust library. The main job is one call::

    import trajkit
    p = trajkit.plan(waypoints, limits="panda")      # TOPP-RA, jerk bounded, every limit kept
    p.duration, p(t), p(t, order=1), p.sample(1000), p.report, p.notes

Families live in submodules:

- ``trajkit.spline``: scipy-like interpolators (``CubicSpline``, ``PchipInterpolator``,
  ``Akima1DInterpolator``, ``BSpline``, ``make_interp_spline``) plus Catmull-Rom, Bézier,
  NURBS, minimum-jerk/snap splines and SO(3) orientation splines;
- ``trajkit.poly``: point-to-point and via-point polynomial moves;
- ``trajkit.otg``: online jerk-limited generation with Ruckig's Python API;
- ``trajkit.topp``: time-optimal path parameterization (TOPP-RA, TOTG, numerical integration)
  with toppra-like building blocks;
- ``trajkit.primitives``: movement primitives (DMP, ProMP, KMP);
- ``trajkit.batch``: many independent problems across all cores in one call.

Arrays in are anything numpy converts to float64 (a C-contiguous float64 array is read
without a copy); arrays out are numpy arrays. Every error is a ``trajkit.TrajkitError``
(a ``ValueError``) carrying the Rust library's message.
"""

from ._trajkit import TrajkitError, Trajectory, Plan, plan
from .limits import Limits
from . import spline, poly, otg, topp, primitives, batch


def _replan(waypoints, limits, kwargs):
    """Rebuilds a plan (pickling): the same call."""
    return plan(waypoints, limits, **kwargs)


__version__ = "0.1.0"

__all__ = [
    "TrajkitError",
    "Trajectory",
    "Plan",
    "plan",
    "Limits",
    "spline",
    "poly",
    "otg",
    "topp",
    "primitives",
    "batch",
]
