#!/usr/bin/env python3
"""Times PyPI toppra on trajkit's TOPP benchmark input, for BENCHMARKS.md.

The input is the `standard_7wp_natural_N1000` fixture problem: 7-DOF Panda velocity and
acceleration limits, natural cubic spline through 7 random waypoints at s = 0, 1/6, ..., 1,
N uniform intervals plus the spline's breakpoints (as trajkit's `Gridpoints::Uniform(N)`).
It times what `Toppra::solve_profile` does: evaluating the constraints on the grid and both
passes (toppra: the `TOPPRA` constructor plus `compute_parameterization`), seidel solver.

Uses the virtualenv of tools/topp_fixtures.py (created on first run).

Usage: python3 tools/bench_topp_peer.py [repeats]
"""
import json
import os
import sys
import time
from pyenv import use_venv

HERE = os.path.dirname(os.path.abspath(__file__))
FIX = os.path.join(HERE, "..", "crates", "trajkit", "tests", "fixtures", "topp", "toppra_panda.json")


use_venv("topp", ["toppra==0.6.10", "numpy==2.4.6", "scipy==1.17.1"])

import numpy as np  # noqa: E402
import toppra as ta  # noqa: E402
import toppra.algorithm as algo  # noqa: E402
import toppra.constraint as constraint  # noqa: E402

ta.setup_logging("WARNING")


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 21
    prob = next(p for p in json.load(open(FIX))["problems"] if p["name"] == "standard_7wp_natural_N1000")
    wp = np.array(prob["waypoints"])
    ss = np.linspace(0.0, 1.0, len(wp))
    path = ta.SplineInterpolator(ss, wp, bc_type="natural")
    vmax, amax = np.array(prob["vmax"]), np.array(prob["amax"])
    pc_vel = constraint.JointVelocityConstraint(np.vstack([-vmax, vmax]).T)
    pc_acc = constraint.JointAccelerationConstraint(
        np.vstack([-amax, amax]).T, discretization_scheme=constraint.DiscretizationType.Interpolation)
    print(f"toppra (PyPI), seidel solver, {repeats} repeats; median / min in ms")
    for n in (100, 1000, 10000):
        g = np.linspace(0.0, 1.0, n + 1)
        grid = np.array(sorted(set(list(ss) + [x for x in g if np.min(np.abs(ss - x)) > 1e-9])))
        times = []
        duration = None
        reps = repeats if n < 10000 else max(5, repeats // 4)
        for _ in range(reps):
            t0 = time.perf_counter()
            inst = algo.TOPPRA([pc_vel, pc_acc], path, gridpoints=grid, solver_wrapper="seidel",
                               parametrizer="ParametrizeConstAccel")
            _, sd, _ = inst.compute_parameterization(0.0, 0.0)
            times.append(time.perf_counter() - t0)
            d = np.diff(grid)
            duration = float(np.sum(2.0 * d / (sd[:-1] + sd[1:])))
        times.sort()
        print(f"N={n:6d} gridpoints={len(grid):6d} median {1e3 * times[len(times) // 2]:8.3f} ms"
              f"  min {1e3 * times[0]:8.3f} ms  duration {duration:.6f} s")


if __name__ == "__main__":
    main()
