#!/usr/bin/env python3
"""Times trajkit's movement-primitive benchmarks (criterion) and the Python peers on the same
inputs, in one run, and prints a table of medians and ratios.

Peers: movement_primitives (DMP fit + rollout, ProMP fit) and a NumPy/SciPy KMP written here
after Huang et al. 2019 (kernel matrix of the 7-joint, 200-point reference, both systems
inverted as in the authors' reference code; mean and covariance query).

Usage (repository root):  python3 tools/bench_primitives_peer.py [--no-cargo]
Creates tools/.venv-mp on first use. BLAS is pinned to one thread (trajkit is single-threaded).
"""
import json
import os
import subprocess
import sys
import time
from pyenv import use_venv

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def q(m, j, s):
    import numpy as np
    mj = 10 * s**3 - 15 * s**4 + 6 * s**5
    amp = 0.5 + 0.1 * j + 0.02 * m
    return 0.1 * j - 0.3 + amp * mj + 0.2 * np.sin(np.pi * s)**2 * np.sin(3 * s + j + 0.1 * m)


def demo(m, n, dur):
    import numpy as np
    T = np.linspace(0.0, dur, n)
    return T, np.stack([q(m, j, T / dur) for j in range(7)], axis=1)


def median_time(fn, repeat, number=1):
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        ts.append((time.perf_counter() - t0) / number)
    ts.sort()
    return ts[len(ts) // 2]


def peers():
    import numpy as np
    from movement_primitives.dmp import DMP
    from movement_primitives.promp import ProMP
    out = {}

    T, Y = demo(0, 1000, 1.0)

    def dmp_fit_rollout():
        dmp = DMP(n_dims=7, execution_time=1.0, dt=0.001, n_weights_per_dim=50,
                  smooth_scaling=True)
        dmp.imitate(T, Y)
        dmp.configure(start_y=Y[0], goal_y=Y[-1])
        dmp.open_loop()
    out["dmp_fit_rollout_7dof_1000"] = median_time(dmp_fit_rollout, 15)

    demos = [demo(m, 100, 1.0) for m in range(10)]

    def promp_ridge():
        p = ProMP(n_dims=7, n_weights_per_dim=20)
        W = np.array([p.weights(t.copy(), y) for t, y in demos])
        p.from_weight_distribution(W.mean(0), np.cov(W.T) + 1e-6 * np.eye(W.shape[1]))
    out["promp_fit_10x7x100"] = median_time(promp_ridge, 15)

    def promp_em():
        p = ProMP(n_dims=7, n_weights_per_dim=20)
        p.imitate([t.copy() for t, _ in demos], [y for _, y in demos])
    out["promp_fit_10x7x100 (movement_primitives EM imitate)"] = median_time(promp_em, 3)

    # NumPy KMP: reference = sample mean/cov of 10 demos at 200 times over 2 s.
    kd = [demo(m, 200, 2.0) for m in range(10)]
    t = kd[0][0]
    Ys = np.stack([y for _, y in kd])           # (10, 200, 7)
    mu = Ys.mean(0)                             # (200, 7)
    C = np.einsum("kna,knb->nab", Ys - mu, Ys - mu) / 9 + 1e-6 * np.eye(7)
    N, D, h, lam, lamc = 200, 7, 6.0, 1.0, 60.0
    state = {}

    def kmp_fit():
        Kt = np.exp(-h * (t[:, None] - t[None, :])**2)
        K = np.kron(Kt, np.eye(D))
        S = np.zeros((N * D, N * D))
        for n in range(N):
            S[n * D:(n + 1) * D, n * D:(n + 1) * D] = C[n]
        state["A"] = np.linalg.inv(K + lam * S) @ mu.ravel()
        state["B"] = np.linalg.inv(K + lamc * S)
    out["kmp_fit_7dof_200"] = median_time(kmp_fit, 3)

    def kmp_query():
        ks = np.kron(np.exp(-h * (0.77 - t)**2)[None, :], np.eye(D))  # (7, 1400)
        mean = ks @ state["A"]
        cov = N / lamc * (np.eye(D) - ks @ state["B"] @ ks.T)
        return mean, cov
    out["kmp_query_mean_cov_7dof_200"] = median_time(kmp_query, 30, 5)
    return out


def trajkit_medians(run_cargo):
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    started = time.time()
    if run_cargo:
        subprocess.check_call(["cargo", "bench", "-p", "trajkit", "--bench", "primitives",
                               "--", "--noplot"], cwd=ROOT, stdout=subprocess.DEVNULL)
    res = {}
    base = os.path.join(target, "criterion", "primitives")
    for name in sorted(os.listdir(base)):
        f = os.path.join(base, name, "new", "estimates.json")
        # Only results written by this run (older benchmark names may linger in the target).
        if os.path.exists(f) and (not run_cargo or os.path.getmtime(f) >= started):
            with open(f) as fh:
                res[name] = json.load(fh)["median"]["point_estimate"] * 1e-9
    return res


def fmt(s):
    return f"{s * 1e3:.3f} ms" if s >= 1e-4 else f"{s * 1e6:.2f} µs"


if __name__ == "__main__":
    use_venv("mp", ["numpy", "scipy", "pytransform3d", "movement-primitives"])
    run_cargo = "--no-cargo" not in sys.argv
    ours = trajkit_medians(run_cargo)
    theirs = peers()
    print("| benchmark | trajkit median | peer median | peer / trajkit |")
    print("|---|---|---|---|")
    for name, s in ours.items():
        p = theirs.get(name)
        if p is None:
            print(f"| {name} | {fmt(s)} | — | — |")
        else:
            print(f"| {name} | {fmt(s)} | {fmt(p)} | {p / s:.1f}× |")
    for name, p in theirs.items():
        if name not in ours:
            print(f"| {name} | — | {fmt(p)} | — |")
