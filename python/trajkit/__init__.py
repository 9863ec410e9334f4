"""trajkit: robot paths to trajectories, from Python.

A thin layer over the trajkit Rust library. Families live in submodules:

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

from ._trajkit import TrajkitError, Trajectory
from .limits import Limits
from . import spline, poly, otg, topp, primitives, batch

__version__ = "0.1.0"

__all__ = [
    "TrajkitError",
    "Trajectory",
    "Limits",
    "spline",
    "poly",
    "otg",
    "topp",
    "primitives",
    "batch",
]
