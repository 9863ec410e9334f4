"""Many independent problems in one call, in parallel across all cores, GIL released.

- ``otg(inputs, delta_time=0.001, threads=None)``: ``trajkit.otg.InputParameter`` list →
  ``trajkit.otg.Trajectory`` list;
- ``plan_waypoints(waypoint_sets, limits, path='natural', solver='toppra', gridpoints=1000)``
  and ``totg(waypoint_sets, limits, max_deviation=0.1)``: waypoint arrays → ``trajkit.Trajectory``
  list.

Results are in input order. A problem that fails does not abort the batch: its place holds
the ``trajkit.TrajkitError`` instance (use ``isinstance(r, trajkit.TrajkitError)``).
Everything here pickles, so the same calls run on a cluster through Dask or Ray (see
``python/examples/dask_batch.py``).
"""

from ._trajkit import batch as _b

otg = _b.otg
plan_waypoints = _b.plan_waypoints
totg = _b.totg

__all__ = ["otg", "plan_waypoints", "totg"]
