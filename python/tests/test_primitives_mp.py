"""trajkit.primitives against movement_primitives (PyPI) on the same demonstrations: the DMP
rollout from movement_primitives' weights against the exact ODE solution (scipy DOP853), the
DMP fit's reproduction, ProMP weights and conditioning."""
import pickle

import numpy as np
import pytest

mp_dmp = pytest.importorskip("movement_primitives.dmp")
from movement_primitives.promp import ProMP as MpProMP  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

import trajkit  # noqa: E402
from trajkit import primitives as pr  # noqa: E402


def demo(n_steps=201, dur=1.0, n_dims=3):
    T = np.linspace(0.0, dur, n_steps)
    s = T / dur
    mj = 10 * s**3 - 15 * s**4 + 6 * s**5
    Y = np.empty((n_steps, n_dims))
    for j in range(n_dims):
        Y[:, j] = 0.1 * j - 0.3 + [0.8, -0.5, 1.2][j] * mj + 0.2 * np.sin(np.pi * s)**2 * np.sin(3 * s + j)
    return T, Y


def rel_rms(a, b, Y):
    return np.sqrt(np.mean((a - b)**2, axis=0)) / (Y.max(0) - Y.min(0))


def test_dmp_rollout_is_closer_to_the_exact_solution_than_movement_primitives():
    T, Y = demo()
    dmp = mp_dmp.DMP(n_dims=3, execution_time=1.0, dt=0.005, n_weights_per_dim=20, smooth_scaling=True)
    dmp.imitate(T.copy(), Y.copy())
    W = dmp.forcing_term.weights_.copy()
    y0, g = Y[0].copy(), Y[-1].copy()

    def rhs(t, s):
        y, v = s[:3], s[3:]
        z = dmp.forcing_term.phase(t)
        f = dmp.forcing_term.forcing_term(z).squeeze()
        return np.concatenate([v, (25 * (6.25 * (g - y) - v - 6.25 * (g - y0) * z) + f)])

    sol = solve_ivp(rhs, (0.0, 1.0), np.concatenate([y0, np.zeros(3)]), method="DOP853",
                    rtol=1e-12, atol=1e-14, dense_output=True)
    exact = sol.sol(T)[:3].T
    ours = pr.DMP.from_weights(W, 1.0, y0, g).rollout()
    err = rel_rms(ours(T), exact, Y)
    dmp.configure(start_y=y0, goal_y=g, start_yd=np.zeros(3))
    Tr, Yr = dmp.open_loop(step_function="rk4")
    err_mp = rel_rms(Yr, sol.sol(np.clip(Tr, 0, 1))[:3].T, Y)
    print("relative RMS vs exact: trajkit", err, "movement_primitives rk4", err_mp)
    assert np.all(err < 1e-8) and np.all(err * 1e4 < err_mp)

    fit = pr.DMP.fit(T, Y, n_basis=20).rollout()
    n = min(len(Yr), len(T))
    assert np.all(rel_rms(fit(T), Y, Y) < rel_rms(Yr[:n], Y[:n], Y) / 5)


def test_promp_matches_movement_primitives():
    rng = np.random.RandomState(0)
    T = np.linspace(0.0, 1.0, 50)
    demos = []
    for _ in range(10):
        amp, off = rng.uniform(0.7, 1.3, 3), rng.uniform(-0.1, 0.1, 3)
        demos.append(off + amp * np.sin(2 * T[:, None] + 0.3 * np.arange(3)) * T[:, None])
    ref = MpProMP(n_dims=3, n_weights_per_dim=10)
    W = np.array([ref.weights(T.copy(), Y, lmbda=1e-12) for Y in demos])
    ref.from_weight_distribution(W.mean(0), np.cov(W.T) + 1e-6 * np.eye(W.shape[1]))
    ours = pr.ProMP.fit([(T, Y) for Y in demos], n_basis=10, ridge=1e-12, prior_variance=1e-6)
    assert np.max(np.abs(ours(T) - ref.mean_trajectory(T.copy()))) < 1e-9
    y_star = np.array([0.4, -0.1, 0.6])
    cref = ref.condition_position(y_star, y_cov=1e-4 * np.eye(3), t=0.3, t_max=1.0)
    cours = ours.condition([(0.3, y_star, 1e-4)])
    assert np.max(np.abs(cours(T) - cref.mean_trajectory(T.copy()))) < 1e-8
    var_ref = cref.var_trajectory(T.copy())
    assert np.all(np.abs(cours.variance(T) - var_ref) < 1e-8 * (1 + var_ref))
    again = pickle.loads(pickle.dumps(cours))
    assert np.array_equal(again(T), cours(T))


def test_kmp_and_errors():
    T = np.linspace(0, 2, 100)
    demos = [(T, np.c_[np.sin(T) * (1 + 0.05 * k), np.cos(T)]) for k in range(4)]
    kmp = pr.KMP.fit(demos, components=5, points=50)
    via = kmp.with_via_points([(1.0, [0.5, 0.2], 1e-6)])
    target = np.array([0.5, 0.2])
    assert np.all(np.abs(via(1.0) - target) < 0.1 * np.abs(kmp(1.0) - target) + 1e-3)
    assert kmp.covariance(np.array([0.5, 1.0])).shape == (2, 2, 2)
    with pytest.raises(trajkit.TrajkitError):
        pr.DMP.fit(T, np.c_[T, np.full_like(T, np.nan)])
    with pytest.raises(trajkit.TrajkitError, match="demos"):
        pr.ProMP.fit([])
