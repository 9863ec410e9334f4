#!/usr/bin/env python3
"""Exact jerk-limited optima of straight-line paths, for trajkit's jerk-limited planner.

On a straight line in joint space the path problem is the 1-D third-order one: with s the arc
length along direction d (unit vector), joint limits project onto the line as
v = min_j V_j/|d_j|, a = min_j A_j/|d_j|, j = min_j J_j/|d_j|. Ruckig (PyPI `ruckig`, the
reference online generator) solves the 1-D rest-to-rest problem exactly; a path through
collinear waypoints that reverses stops at every reversal, so its optimum is the sum of its
pieces'. Cases: 2 waypoints, several collinear waypoints, reversing pieces, at the Panda's
limits and at 1 % of its jerk, and the 1-joint example (1 rad, v = 1, a = 2, j = 10: 1.7 s).

Writes crates/trajkit/tests/fixtures/jerk/lines.json.

Usage: python3 tools/jerk_line_fixtures.py
"""
import json
import os
from pyenv import use_venv

use_venv("jerk", ["ruckig==0.19.4", "numpy"])

import numpy as np  # noqa: E402
import ruckig  # noqa: E402
from panda import VMAX, AMAX, JMAX, QMIN, QMAX  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "trajkit", "tests", "fixtures", "jerk", "lines.json")


def one_d(length, v, a, j):
    """Ruckig's time-optimal rest-to-rest duration over `length` with limits v, a, j."""
    inp = ruckig.InputParameter(1)
    inp.current_position = [0.0]
    inp.current_velocity = [0.0]
    inp.current_acceleration = [0.0]
    inp.target_position = [length]
    inp.target_velocity = [0.0]
    inp.target_acceleration = [0.0]
    inp.max_velocity = [v]
    inp.max_acceleration = [a]
    inp.max_jerk = [j]
    traj = ruckig.Trajectory(1)
    res = ruckig.Ruckig(1).calculate(inp, traj)
    assert res == ruckig.Result.Working, res
    return traj.duration


def pieces(waypoints):
    """Split collinear waypoints at reversals: list of (start, end) index pairs."""
    w = np.asarray(waypoints)
    cuts = [0]
    for i in range(1, len(w) - 1):
        a, b = w[i] - w[i - 1], w[i + 1] - w[i]
        if np.dot(a, b) < 0:
            cuts.append(i)
    cuts.append(len(w) - 1)
    return list(zip(cuts[:-1], cuts[1:]))


def case(name, waypoints, vmax, amax, jmax):
    w = np.asarray(waypoints, dtype=float)
    durs = []
    for i0, i1 in pieces(w):
        delta = w[i1] - w[i0]
        length = float(np.linalg.norm(delta))
        d = np.abs(delta) / length
        with np.errstate(divide="ignore"):
            v = float(np.min(np.where(d > 0, vmax / d, np.inf)))
            a = float(np.min(np.where(d > 0, amax / d, np.inf)))
            j = float(np.min(np.where(d > 0, jmax / d, np.inf)))
        durs.append(one_d(length, v, a, j))
    return {
        "name": name,
        "dof": int(w.shape[1]),
        "waypoints": w.tolist(),
        "vmax": list(map(float, vmax)),
        "amax": list(map(float, amax)),
        "jmax": list(map(float, jmax)),
        "piece_durations": durs,
        "duration": float(sum(durs)),
    }


def main():
    rng = np.random.default_rng(14)
    cases = [case("one_joint_a2_j10", [[0.0], [1.0]], np.array([1.0]), np.array([2.0]), np.array([10.0]))]
    for scale, tag in ((1.0, "panda"), (0.01, "panda_jerk1pct")):
        jm = JMAX * scale
        for k in range(3):
            q0 = QMIN + 0.2 + (QMAX - QMIN - 0.4) * rng.random(7)
            q1 = QMIN + 0.2 + (QMAX - QMIN - 0.4) * rng.random(7)
            cases.append(case(f"{tag}_line2_{k}", [q0, q1], VMAX, AMAX, jm))
            mids = [q0 + f * (q1 - q0) for f in (0.0, 0.2, 0.45, 0.8, 1.0)]
            cases.append(case(f"{tag}_collinear5_{k}", mids, VMAX, AMAX, jm))
            back = [q0, q1, q0 + 0.3 * (q1 - q0), q0 + 0.9 * (q1 - q0)]
            cases.append(case(f"{tag}_reversing_{k}", back, VMAX, AMAX, jm))
        # A short move (the jerk phases dominate).
        q0 = np.array([0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0])
        cases.append(case(f"{tag}_short", [q0, q0 + 0.05], VMAX, AMAX, jm))
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as f:
        json.dump({"generator": "tools/jerk_line_fixtures.py", "ruckig": "0.19.4", "cases": cases}, f, indent=1)
    for c in cases:
        print(f"{c['name']:32s} {c['duration']:.6f} s ({len(c['piece_durations'])} pieces)")


if __name__ == "__main__":
    main()
