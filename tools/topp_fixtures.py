#!/usr/bin/env python3
"""Reference fixtures for trajkit's TOPP-RA from PyPI `toppra`.

Creates its own virtualenv at tools/.venv-topp (toppra, numpy, scipy) on first run, then
re-executes itself inside it. Writes crates/trajkit/tests/fixtures/topp/toppra_panda.json:
a seeded suite of Panda problems (3 to 20 waypoints; repeated waypoints, exact and near
reversals, very short segments, a static joint, a near-closed loop, full-range moves, non-zero
boundary path velocities, directional acceleration limits). Each problem stores the path as
scipy PPoly coefficients (so trajkit evaluates exactly the same cubic), the gridpoints, the
limits, and toppra's result with `ParametrizeConstAccel` (duration, path velocities). It also
records, per problem, how far toppra's default spline re-fit (`ParametrizeSpline`) exceeds
the acceleration limits, sampled at 1 kHz.

Usage: python3 tools/topp_fixtures.py
"""
import json
import os
from pyenv import use_venv

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "trajkit", "tests", "fixtures", "topp", "toppra_panda.json")


use_venv("topp", ["toppra==0.6.10", "numpy==2.4.6", "scipy==1.17.1"])

import numpy as np  # noqa: E402
import toppra as ta  # noqa: E402
import toppra.algorithm as algo  # noqa: E402
import toppra.constraint as constraint  # noqa: E402
from scipy.interpolate import CubicSpline  # noqa: E402
from panda import AMAX, QMAX, QMIN, VMAX, random_waypoints  # noqa: E402

ta.setup_logging("WARNING")


def make_problems():
    rng = np.random.default_rng(20261122)
    probs = []

    def add(name, wp, bc="not-a-knot", n=None, sd=(0.0, 0.0), amin_scale=None):
        probs.append(dict(name=name, wp=np.array(wp, float), bc=bc, n=n or int(rng.integers(50, 1001)),
                          sd=sd, amin_scale=amin_scale))

    # Plain random problems, 3..20 waypoints, mixed end conditions.
    for k, n in enumerate([3, 5, 7, 7, 10, 14, 20]):
        add(f"random_{n}wp_{k}", random_waypoints(rng, n), bc=["natural", "not-a-knot", "clamped"][k % 3])
    # The benchmark problem: natural spline through 7 random waypoints, N = 1000.
    add("standard_7wp_natural_N1000", random_waypoints(np.random.default_rng(7), 7), bc="natural", n=1000)
    # Repeated waypoints (the spline passes through the same point twice).
    w = random_waypoints(rng, 6)
    w[3] = w[2]
    add("repeated_waypoint", w)
    w = random_waypoints(rng, 8)
    w[5] = w[4]
    w[6] = w[4]
    add("triple_waypoint", w, bc="natural")
    # Exact reversal A -> B -> A (all joints reverse at the same parameter).
    a, b = random_waypoints(rng, 2)
    add("exact_reversal", [a, b, a], bc="natural")
    c = random_waypoints(rng, 1)[0]
    add("exact_reversal_then_move", [a, b, a, c])
    # Near reversal: come back almost to where we started.
    add("near_reversal", [a, b, a + 1e-3 * (c - a), c])
    # Very short segments between ordinary ones.
    w = random_waypoints(rng, 6)
    w[3] = w[2] + 1e-4
    add("very_short_segment", w)
    w = random_waypoints(rng, 9)
    w[5] = w[4] + 1e-6 * rng.standard_normal(7)
    add("tiny_segment_1e-6", w, bc="natural")
    # One static joint.
    w = random_waypoints(rng, 6)
    w[:, 3] = -1.5
    add("static_joint", w)
    # A near-closed loop.
    w = random_waypoints(rng, 9)
    w[-1] = w[0] + 1e-3
    add("near_closed_loop", w, bc="natural")
    # Full-range moves: extreme to extreme.
    add("full_range", [QMIN + 1e-3, QMAX - 1e-3], bc="clamped")
    add("full_range_back_and_forth", [QMIN + 1e-3, QMAX - 1e-3, QMIN + 1e-3], bc="natural")
    # Nearly collinear waypoints.
    a, b = random_waypoints(rng, 2)
    w = np.array([a + t * (b - a) for t in np.linspace(0.0, 1.0, 6)])
    w[2] += 1e-7
    add("nearly_collinear", w)
    # Non-zero path velocity at start and end.
    w = random_waypoints(rng, 5)
    add("moving_start", w, sd=(0.03, 0.0))
    add("moving_start_too_fast", w, sd=(0.05, 0.0))
    add("moving_end", random_waypoints(rng, 5), sd=(0.0, 0.05))
    add("moving_both", random_waypoints(rng, 4), sd=(0.04, 0.03))
    # Direction-dependent acceleration minima.
    add("directional_accel", random_waypoints(rng, 6), amin_scale=0.5)
    # Coarse and fine grids on the same problem.
    w = random_waypoints(rng, 5)
    add("coarse_grid_N20", w, n=20)
    add("fine_grid_N3000", w, n=3000)
    return probs


def gridpoints(n, ss):
    g = np.linspace(0.0, 1.0, n + 1)
    keep = [x for x in g if np.min(np.abs(ss - x)) > 1e-9]
    return np.array(sorted(set(list(ss) + keep)))


def main():
    out = []
    for p in make_problems():
        wp = p["wp"]
        ss = np.linspace(0.0, 1.0, len(wp))
        spl = CubicSpline(ss, wp, bc_type=p["bc"])
        path = ta.SplineInterpolator(ss, wp, bc_type=p["bc"])
        assert np.allclose(path.cspl.c, spl.c)
        amax_hi = AMAX.copy()
        amax_lo = -AMAX.copy() if p["amin_scale"] is None else -AMAX * p["amin_scale"]
        pc_vel = constraint.JointVelocityConstraint(np.vstack([-VMAX, VMAX]).T)
        pc_acc = constraint.JointAccelerationConstraint(
            np.vstack([amax_lo, amax_hi]).T, discretization_scheme=constraint.DiscretizationType.Interpolation)
        grid = gridpoints(p["n"], ss)
        inst = algo.TOPPRA([pc_vel, pc_acc], path, gridpoints=grid, solver_wrapper="seidel",
                           parametrizer="ParametrizeConstAccel")
        traj = inst.compute_trajectory(p["sd"][0], p["sd"][1])
        rec = dict(name=p["name"], bc=p["bc"], dof=7, waypoints=wp.tolist(), breaks=spl.x.tolist(),
                   # coefficients[piece][joint] = ascending powers of (s - breaks[piece])
                   coefficients=[[spl.c[::-1, i, j].tolist() for j in range(7)] for i in range(len(spl.x) - 1)],
                   gridpoints=grid.tolist(), vmax=VMAX.tolist(), amax=amax_hi.tolist(), amin=amax_lo.tolist(),
                   sd_start=p["sd"][0], sd_end=p["sd"][1])
        if traj is None:
            rec["toppra_ok"] = False
        else:
            rec["toppra_ok"] = True
            rec["duration"] = float(traj.duration)
            rec["sd"] = inst.problem_data.sd_vec.tolist()
            # toppra's default output: a spline re-fit of the same profile.
            inst2 = algo.TOPPRA([pc_vel, pc_acc], path, gridpoints=grid, solver_wrapper="seidel")
            t2 = inst2.compute_trajectory(p["sd"][0], p["sd"][1])
            ts = np.arange(0.0, t2.duration, 1e-3)
            qdd = t2(ts, 2)
            ratio = np.maximum(qdd / amax_hi, qdd / amax_lo).max()
            rec["toppra_spline_refit_max_accel_ratio"] = float(ratio)
        out.append(rec)
        print(f"{p['name']:32s} N={len(grid) - 1:5d} ok={rec['toppra_ok']} T={rec.get('duration', float('nan')):.6f}"
              f" refit accel ratio={rec.get('toppra_spline_refit_max_accel_ratio', float('nan')):.4f}")
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as f:
        json.dump(dict(generator="tools/topp_fixtures.py", toppra="PyPI toppra, seidel solver, ParametrizeConstAccel",
                       problems=out), f)
    print("wrote", os.path.relpath(OUT))


if __name__ == "__main__":
    main()
