"""Movement primitives learned from demonstrations.

- ``DMP.fit(t, q, n_basis=50)`` (or ``DMP.from_weights(...)``), then
  ``dmp.rollout(goal=..., start=..., tau=..., duration=...)`` → ``trajkit.Trajectory``;
- ``ProMP.fit([(t, q), ...], n_basis=20)``, ``promp.condition([(t, q, variance), ...])``, the
  mean ``promp(t, order=0)``, ``promp.variance(t)``, ``promp.covariance(t)``,
  ``promp.sample(seed)``;
- ``KMP.fit([(t, q), ...])``, ``kmp.with_via_points([(t, q, variance), ...])``, the mean
  ``kmp(t, order=0)``, ``kmp.covariance(t)``.
"""

from ._trajkit import primitives as _m

DMP = _m.DMP
ProMP = _m.ProMP
KMP = _m.KMP


def _rollout(dmp, goal, start, tau, duration, start_velocity):
    """Rebuilds a rollout (pickling)."""
    return dmp.rollout(goal=goal, start=start, tau=tau, duration=duration,
                       start_velocity=start_velocity)


def _condition(promp, via):
    """Rebuilds a conditioned ProMP (pickling)."""
    return promp.condition(via)


def _sample(promp, seed):
    """Rebuilds a sample (pickling)."""
    return promp.sample(seed)


def _with_via_points(kmp, via):
    """Rebuilds a KMP with via points (pickling)."""
    return kmp.with_via_points(via)


__all__ = ["DMP", "ProMP", "KMP"]
