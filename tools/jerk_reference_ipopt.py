#!/usr/bin/env python3
"""Near-optimal jerk-limited timings of curved 7-DOF paths, from an independent fine-grid
optimization (CasADi + IPOPT, PyPI), for trajkit's jerk-limited planner.

Path: natural cubic spline (chord-length parameter s) through seeded random Panda waypoints,
built here with numpy (the same interpolant as trajkit's `CubicSpline::natural`).
Transcription in the path parameter on N uniform intervals, unknowns at the nodes
y_i = ṡ ≥ 0 and a_i = s̈, path jerk in time c_i = s⃛ per interval:
  y_{i+1}² − y_i² = Δ(a_i + a_{i+1})          (trapezoid on d(ṡ²)/ds = 2s̈)
  a_{i+1} − a_i   = Δ·c_i / ((y_i + y_{i+1})/2) (midpoint on ds̈/ds = s⃛/ṡ)
joint velocity σ′y and acceleration σ″y² + σ′a within limits at every node, joint jerk
σ‴ȳ³ + 3σ″ȳā + σ′c within ±J at every interval midpoint (ȳ, ā the interval means), rest at
both ends (y = a = 0), minimum T = Σ 2Δ/(y_i + y_{i+1}). Limits hold at nodes and midpoints
only, so on a fine grid this is a near-optimal reference from slightly below as well as above.

Writes crates/trajkit/tests/fixtures/jerk/curved_ipopt.json.

Usage: python3 tools/jerk_reference_ipopt.py [N]
"""
import json
import os
import sys
import time
from pyenv import use_venv

use_venv("jerk", ["ruckig==0.19.4", "numpy", "casadi==3.7.2"])

import numpy as np  # noqa: E402
import casadi as ca  # noqa: E402
from panda import VMAX, AMAX, JMAX, random_waypoints  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "trajkit", "tests", "fixtures", "jerk", "curved_ipopt.json")


def natural_spline(s, w):
    """Second derivatives M (n × dof) of the natural cubic spline through w at s."""
    n = len(s)
    h = np.diff(s)
    A = np.zeros((n, n))
    rhs = np.zeros((n, w.shape[1]))
    A[0, 0] = A[-1, -1] = 1.0
    for i in range(1, n - 1):
        A[i, i - 1], A[i, i], A[i, i + 1] = h[i - 1], 2 * (h[i - 1] + h[i]), h[i]
        rhs[i] = 6 * ((w[i + 1] - w[i]) / h[i] - (w[i] - w[i - 1]) / h[i - 1])
    return np.linalg.solve(A, rhs)


def derivs(s, w, M, x):
    """σ′, σ″, σ‴ at parameters x (len(x) × dof)."""
    k = np.clip(np.searchsorted(s, x, side="right") - 1, 0, len(s) - 2)
    h = s[k + 1] - s[k]
    a, b = s[k + 1] - x, x - s[k]
    d1 = (-M[k] * (a**2)[:, None] / (2 * h[:, None]) + M[k + 1] * (b**2)[:, None] / (2 * h[:, None])
          + (w[k + 1] - w[k]) / h[:, None] - (M[k + 1] - M[k]) * h[:, None] / 6)
    d2 = (M[k] * a[:, None] + M[k + 1] * b[:, None]) / h[:, None]
    d3 = (M[k + 1] - M[k]) / h[:, None]
    return d1, d2, d3


def solve(w, jmax, n_int):
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(w, axis=0), axis=1))])
    M = natural_spline(s, w)
    L = s[-1]
    nodes = np.linspace(0.0, L, n_int + 1)
    mids = 0.5 * (nodes[:-1] + nodes[1:])
    d1n, d2n, _ = derivs(s, w, M, nodes)
    d1m, d2m, d3m = derivs(s, w, M, mids)
    dl = L / n_int
    opti = ca.Opti()
    y = opti.variable(n_int + 1)
    a = opti.variable(n_int + 1)
    c = opti.variable(n_int)
    opti.subject_to(y >= 0)
    opti.subject_to([y[0] == 0, y[-1] == 0, a[0] == 0, a[-1] == 0])
    opti.subject_to(y[1:] ** 2 - y[:-1] ** 2 == dl * (a[:-1] + a[1:]))
    ym = 0.5 * (y[:-1] + y[1:])
    am = 0.5 * (a[:-1] + a[1:])
    opti.subject_to((a[1:] - a[:-1]) * ym == dl * c)
    for j in range(7):
        opti.subject_to(opti.bounded(-VMAX[j], d1n[:, j] * y, VMAX[j]))
        opti.subject_to(opti.bounded(-AMAX[j], d2n[:, j] * y**2 + d1n[:, j] * a, AMAX[j]))
        q3 = d3m[:, j] * ym**3 + 3 * d2m[:, j] * ym * am + d1m[:, j] * c
        opti.subject_to(opti.bounded(-jmax[j], q3, jmax[j]))
    opti.minimize(ca.sum1(2 * dl / (y[:-1] + y[1:] + 1e-12)))
    # Start from a slow, smooth, feasible-looking profile.
    y0 = 0.2 * np.sin(np.pi * nodes / L) ** 2 + 1e-3
    opti.set_initial(y, y0)
    opti.set_initial(a, np.gradient(y0**2, nodes) / 2)
    opti.set_initial(c, 0.0)
    opti.solver("ipopt", {"print_time": False}, {"print_level": 0, "max_iter": 3000, "tol": 1e-9})
    t0 = time.time()
    sol = opti.solve()
    yv = sol.value(y)
    T = float(np.sum(2 * dl / (yv[:-1] + yv[1:])))
    return T, time.time() - t0, sol.stats()["return_status"]


def main():
    n_int = int(sys.argv[1]) if len(sys.argv) > 1 else 1500
    rng = np.random.default_rng(1414)
    cases = []
    for k in range(3):
        w = random_waypoints(rng, 5)
        for scale in (0.01, 1.0):
            T, secs, status = solve(w, JMAX * scale, n_int)
            cases.append({"name": f"random5_{k}", "jerk_scale": scale, "waypoints": w.tolist(),
                          "intervals": n_int, "duration": T, "ipopt_status": status})
            print(f"random5_{k} jerk x{scale}: T = {T:.5f} s ({status}, {secs:.1f} s)", flush=True)
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as f:
        json.dump({"generator": "tools/jerk_reference_ipopt.py", "casadi": "3.7.2", "cases": cases}, f, indent=1)


if __name__ == "__main__":
    main()
