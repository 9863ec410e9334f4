#!/usr/bin/env python3
"""Reference fixtures for trajkit's movement primitives, from movement_primitives (PyPI
`movement-primitives`), numpy and scipy.

Creates its own virtualenv tools/.venv-mp on first use, then writes small JSON files under
crates/trajkit/tests/fixtures/primitives/. Run from the repository root:

    python3 tools/primitives_fixtures.py

Fixtures:
- dmp_basis.json: the DMP forcing-term basis (centers, widths) for 50 functions.
- dmp_rollout.json: a 3-joint demonstration, movement_primitives' fitted weights (its
  smooth-scaling = Hoffmann 2009 form), the solution of the same ODE with scipy's DOP853 at
  rtol 1e-12 ("exact"), and movement_primitives' own Euler and RK4 rollouts with their errors
  against the exact solution (its RK4 evaluates the forcing term one step ahead).
- promp.json: ten 3-joint demonstrations, per-demo ridge weights, a conditioned mean and
  variance from movement_primitives' ProMP.
"""
import json
import os
from pyenv import use_venv

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "crates", "trajkit", "tests", "fixtures", "primitives")


def demo(n_steps, dur, n_dims):
    import numpy as np
    T = np.linspace(0.0, dur, n_steps)
    s = T / dur
    mj = 10 * s**3 - 15 * s**4 + 6 * s**5
    Y = np.empty((n_steps, n_dims))
    for j in range(n_dims):
        Y[:, j] = 0.1 * j - 0.3 + [0.8, -0.5, 1.2][j] * mj \
            + 0.2 * np.sin(np.pi * s)**2 * np.sin(3 * s + j)
    return T, Y


def dmp_fixtures():
    import numpy as np
    from scipy.integrate import solve_ivp
    from movement_primitives.dmp import DMP
    from movement_primitives.dmp._forcing_term import ForcingTerm
    from movement_primitives.dmp._canonical_system import canonical_system_alpha

    alpha_x = canonical_system_alpha(0.01, 1.0, 0.0)
    ft = ForcingTerm(1, 50, 1.0, 0.0, 0.8, alpha_x)
    with open(os.path.join(OUT, "dmp_basis.json"), "w") as f:
        json.dump({"n": 50, "alpha_x": alpha_x, "overlap": 0.8,
                   "centers": ft.centers.tolist(), "widths": ft.widths.tolist()}, f)

    n_dims, dur = 3, 1.0
    T, Y = demo(201, dur, n_dims)
    dmp = DMP(n_dims=n_dims, execution_time=dur, dt=0.005, n_weights_per_dim=20,
              smooth_scaling=True)
    dmp.imitate(T.copy(), Y.copy())
    W = dmp.forcing_term.weights_.copy()
    y0, g = Y[0].copy(), Y[-1].copy()
    az, bz = 25.0, 6.25

    def rhs(t, s):
        y, v = s[:n_dims], s[n_dims:]
        z = dmp.forcing_term.phase(t)
        f = dmp.forcing_term.forcing_term(z).squeeze()
        a = (az * (bz * (g - y) - dur * v - bz * (g - y0) * z) + f) / dur**2
        return np.concatenate([v, a])

    s0 = np.concatenate([y0, np.zeros(n_dims)])
    sol = solve_ivp(rhs, (0.0, dur), s0, method="DOP853", rtol=1e-12, atol=1e-14,
                    dense_output=True)
    exact = sol.sol(T)[:n_dims].T

    out = {"t": T.tolist(), "q": Y.ravel().tolist(), "dof": n_dims, "n_basis": 20,
           "tau": dur, "start": y0.tolist(), "goal": g.tolist(),
           "weights": W.ravel().tolist(), "exact": exact.ravel().tolist()}
    for mode in ["euler", "rk4"]:
        dmp.configure(start_y=y0, goal_y=g, start_yd=np.zeros(n_dims))
        Tr, Yr = dmp.open_loop(step_function=mode)
        ex = sol.sol(np.clip(Tr, 0.0, dur))[:n_dims].T
        err = np.sqrt(np.mean((Yr - ex)**2, axis=0)) / (Y.max(0) - Y.min(0))
        out["mp_" + mode + "_rel_rms_vs_exact"] = err.tolist()
        n = min(len(Yr), len(T))
        assert np.allclose(Tr[:n], T[:n])
        rep = np.sqrt(np.mean((Yr[:n] - Y[:n])**2, axis=0)) / (Y.max(0) - Y.min(0))
        out["mp_" + mode + "_rel_rms_vs_demo"] = rep.tolist()
    with open(os.path.join(OUT, "dmp_rollout.json"), "w") as f:
        json.dump(out, f)
    print("dmp: mp rk4 vs exact", out["mp_rk4_rel_rms_vs_exact"],
          "euler vs exact", out["mp_euler_rel_rms_vs_exact"])


def promp_fixtures():
    import numpy as np
    from movement_primitives.promp import ProMP

    rng = np.random.RandomState(0)
    n_dims, n_w, n_steps, n_demos = 3, 10, 50, 10
    T = np.linspace(0.0, 1.0, n_steps)
    demos = []
    for _ in range(n_demos):
        amp = rng.uniform(0.7, 1.3, n_dims)
        off = rng.uniform(-0.1, 0.1, n_dims)
        Y = off + amp * np.sin(2 * T[:, None] + 0.3 * np.arange(n_dims)) * T[:, None]
        demos.append(Y)
    promp = ProMP(n_dims=n_dims, n_weights_per_dim=n_w)
    T2 = 2.0 * T  # a 2 s demonstration: movement_primitives normalizes the array in place
    T2_copy = T2.copy()
    promp.weights(T2_copy, demos[0])
    mutates = bool(not np.array_equal(T2_copy, T2))
    W = np.array([promp.weights(T.copy(), Y, lmbda=1e-12) for Y in demos])
    prior = 1e-6
    mean = W.mean(0)
    cov = np.cov(W.T) + prior * np.eye(W.shape[1])
    promp.from_weight_distribution(mean, cov)
    y_star = np.array([0.4, -0.1, 0.6])
    y_cov = 1e-4 * np.eye(n_dims)
    cond = promp.condition_position(y_star, y_cov=y_cov, t=0.3, t_max=1.0)
    out = {"t": T.tolist(), "dof": n_dims, "n_basis": n_w, "ridge": 1e-12,
           "prior_variance": prior,
           "demos": [Y.ravel().tolist() for Y in demos],
           "weights": [w.tolist() for w in W],
           "via_t": 0.3, "via_value": y_star.tolist(), "via_cov": y_cov.ravel().tolist(),
           "cond_mean": cond.mean_trajectory(T.copy()).ravel().tolist(),
           "cond_var": cond.var_trajectory(T.copy()).ravel().tolist(),
           "mean": promp.mean_trajectory(T.copy()).ravel().tolist(),
           "mp_mutates_time_array": mutates}
    with open(os.path.join(OUT, "promp.json"), "w") as f:
        json.dump(out, f)
    print("promp: mp mutates the caller's time array:", mutates)


if __name__ == "__main__":
    use_venv("mp", ["numpy", "scipy", "pytransform3d", "movement-primitives"])
    os.makedirs(OUT, exist_ok=True)
    dmp_fixtures()
    promp_fixtures()
