"""Polynomial moves: cubic, quintic (minimum jerk) and septic, between states and through
waypoints. Every function returns a ``trajkit.Trajectory`` (or a number).

- ``rest_to_rest(q0, q1, duration, degree='quintic')``
- ``between(q0, q1, duration, degree, qd0=, qd1=, qdd0=, qdd1=, qddd0=, qddd1=)``
- ``min_duration(q0, q1, limits, degree='quintic')``: the shortest rest-to-rest duration
- ``peak_coefficients(degree)``: peak |q̇|·T/D, |q̈|·T²/D, |q⃛|·T³/D of the unit profile
- ``via(waypoints, limits=None, durations=None, degree='quintic', velocities='heuristic')``
"""

from ._trajkit import poly as _p

rest_to_rest = _p.rest_to_rest
between = _p.between
min_duration = _p.min_duration
peak_coefficients = _p.peak_coefficients
via = _p.via

__all__ = ["rest_to_rest", "between", "min_duration", "peak_coefficients", "via"]
