"""trajkit.topp against toppra (PyPI): the same path (a natural cubic spline through seeded
Panda waypoints), the same velocity and acceleration limits, the same gridpoints. Durations
agree within 1e-4 relative (toppra lowers each forward step by up to 1e-4 on purpose)."""
import pickle

import numpy as np
import pytest

ta = pytest.importorskip("toppra")
import toppra.algorithm as algo  # noqa: E402
import toppra.constraint as constraint  # noqa: E402

import trajkit  # noqa: E402
from trajkit import topp  # noqa: E402

ta.setup_logging("WARNING")
PANDA = trajkit.Limits("panda")


def waypoints(seed, n=7):
    rng = np.random.default_rng(seed)
    lo, hi = PANDA.position[:, 0], PANDA.position[:, 1]
    mid, half = (lo + hi) / 2, (hi - lo) / 2
    return mid + 0.6 * half * rng.uniform(-1, 1, (n, 7))


def grid_with_breaks(ss, n):
    g = np.linspace(0.0, 1.0, n + 1)
    return np.array(sorted(set(list(ss) + [x for x in g if np.min(np.abs(ss - x)) > 1e-9])))


@pytest.mark.parametrize("seed", range(8))
def test_toppra_durations_match(seed):
    wp = waypoints(seed)
    ss = np.linspace(0.0, 1.0, len(wp))
    grid = grid_with_breaks(ss, 1000)
    vmax, amax = PANDA.velocity, PANDA.acceleration
    vlim, alim = np.vstack([-vmax, vmax]).T, np.vstack([-amax, amax]).T

    path_ref = ta.SplineInterpolator(ss, wp, bc_type="natural")
    inst = algo.TOPPRA([constraint.JointVelocityConstraint(vlim),
                        constraint.JointAccelerationConstraint(
                            alim, discretization_scheme=constraint.DiscretizationType.Interpolation)],
                       path_ref, gridpoints=grid, solver_wrapper="seidel")
    _, sd, _ = inst.compute_parameterization(0.0, 0.0)
    want = float(np.sum(2.0 * np.diff(grid) / (sd[:-1] + sd[1:])))

    path = topp.SplineInterpolator(ss, wp, bc_type="natural")
    cons = [topp.JointVelocityConstraint(vlim), topp.JointAccelerationConstraint(alim)]
    got = topp.TOPPRA(cons, path, gridpoints=grid, refine=False).compute_trajectory(0.0, 0.0)
    assert abs(got.duration - want) / want < 1e-4, (got.duration, want)

    # The default (refined) solve never breaks a limit at 1 kHz; NI agrees with TOPP-RA.
    ref = topp.TOPPRA(cons, path).compute_trajectory()
    t = np.linspace(0, ref.duration, int(ref.duration * 1000) + 1)
    assert np.all(np.abs(ref(t, 1)) <= vmax * (1 + 1e-6))
    assert np.all(np.abs(ref(t, 2)) <= amax * (1 + 1e-6))
    ni = topp.NumericalIntegration(cons, path).compute_trajectory()
    assert abs(ni.duration - ref.duration) / ref.duration < 1e-3
    again = pickle.loads(pickle.dumps(ref))
    assert again.duration == ref.duration


def test_totg_and_plan_waypoints_keep_limits():
    wp = waypoints(3)
    no_jerk = trajkit.Limits({"joints": [
        {"name": n, "position": [float(lo), float(hi)], "velocity": float(v), "acceleration": float(a)}
        for n, (lo, hi), v, a in zip(PANDA.names, PANDA.position, PANDA.velocity, PANDA.acceleration)]})
    for traj in [topp.totg(wp, no_jerk, max_deviation=0.1), topp.plan_waypoints(wp, PANDA)]:
        t = np.linspace(0, traj.duration, int(traj.duration * 1000) + 1)
        assert np.all(np.abs(traj(t, 1)) <= PANDA.velocity * (1 + 1e-6))
        assert np.all(np.abs(traj(t, 2)) <= PANDA.acceleration * (1 + 1e-6))
        assert np.allclose(traj(0.0), wp[0]) and np.allclose(traj(traj.duration), wp[-1])


def test_topp_errors():
    with pytest.raises(trajkit.TrajkitError, match="dof|joint"):
        topp.TOPPRA([topp.JointVelocityConstraint([1.0, 1.0])],
                    topp.SplineInterpolator([0, 1, 2], np.eye(3))).compute_trajectory()
    with pytest.raises(ValueError):
        topp.JointVelocityConstraint([[1.0, -1.0]])
