"""Per-joint limits: ``trajkit.Limits``.

``Limits('panda')`` (a preset), ``Limits('robot.urdf')`` / ``Limits('joint_limits.yaml')`` /
``Limits('limits.json')`` (files), ``Limits({"joints": [...]})`` (trajkit's limits-file format
as a dict), ``Limits.uniform(dof, velocity, acceleration, jerk)``. Every function that takes
``limits=`` accepts any of these forms directly.
"""

from ._trajkit import Limits

__all__ = ["Limits"]
