"""Time-optimal path parameterization with toppra-like building blocks.

    import numpy as np
    from trajkit import topp
    path = topp.SplineInterpolator(np.linspace(0, 1, 5), way_pts)   # any trajkit.spline curve
    vel = topp.JointVelocityConstraint(vlim)                        # (dof, 2) or (dof,)
    acc = topp.JointAccelerationConstraint(alim)
    traj = topp.TOPPRA([vel, acc], path, gridpoints=1000).compute_trajectory(0, 0)
    traj.duration, traj(t), traj(t, 1)

``NumericalIntegration`` solves the same problem by phase-plane integration; ``totg``
blends straight segments with circular arcs (TOTG); ``plan_waypoints`` times raw planner
waypoints (duplicates removed, stops at reversals, a spline per piece). Differences from
toppra: gridpoints default to 1000 uniform intervals (plus the path's breakpoints) and the
grid is refined where a limit would be exceeded between gridpoints (``refine=False``
disables that).
"""

from ._trajkit import topp as _t
from .spline import CubicSpline

LinearPath = _t.LinearPath
JointVelocityConstraint = _t.JointVelocityConstraint
JointAccelerationConstraint = _t.JointAccelerationConstraint
TOPPRA = _t.TOPPRA
NumericalIntegration = _t.NumericalIntegration
totg = _t.totg
plan_waypoints = _t.plan_waypoints


def SplineInterpolator(ss_waypoints, waypoints, bc_type="not-a-knot"):
    """toppra's ``SplineInterpolator``: the cubic spline through ``waypoints`` (``(n, dof)``)
    at path positions ``ss_waypoints``, as a ``trajkit.spline.CubicSpline``."""
    return CubicSpline(ss_waypoints, waypoints, bc_type=bc_type)


def _solve(problem, sd_start, sd_end):
    """Rebuilds a solved trajectory (pickling)."""
    return problem.compute_trajectory(sd_start, sd_end)


__all__ = [
    "SplineInterpolator",
    "LinearPath",
    "JointVelocityConstraint",
    "JointAccelerationConstraint",
    "TOPPRA",
    "NumericalIntegration",
    "totg",
    "plan_waypoints",
]
