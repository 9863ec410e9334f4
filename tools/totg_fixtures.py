#!/usr/bin/env python3
"""Reference fixtures for trajkit's TOTG from the original TOTG, as shipped in PyPI
`tesseract-robotics` (tesseract_time_parameterization.TimeOptimalTrajectoryGeneration, the
MoveIt-derived port of Kunz & Stilman's code: same blend geometry, phase-plane integration
at a fixed 1 ms step).

Creates its own virtualenv at tools/.venv-totg (tesseract-robotics, numpy) on first run, then
re-executes itself inside it. Writes crates/trajkit/tests/fixtures/totg/totg_panda.json: a
seeded suite of Panda problems (the embedded default path, random waypoints, uneven spacing
with very short segments, joints that stay still on some segments, repeated waypoints, an
exact reversal, collinear waypoints, two-waypoint lines, tiny and large max deviations). Each
problem stores the waypoints, the max deviation and the original's result: status (`ok`,
`failed` when compute() returns False, `nan` when a time is not finite, `not-increasing`,
`exception`, `timeout` after 20 s in a child process), its duration (time stamp of the last
waypoint), its compute time, and the largest acceleration ratio among the joint states it
reports at the waypoints.

The binding exposes only the time stamps and states at the input waypoints, not the
trajectory between them, so the original's limit compliance cannot be sampled here; the
Rust test uses that the time-optimal duration on the same path is a lower bound for any
trajectory within the limits (see crates/trajkit/tests/topp_totg_fixtures.rs).

Usage: python3 tools/totg_fixtures.py
"""
import json
import os
import sys
from pyenv import use_venv

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "trajkit", "tests", "fixtures", "totg", "totg_panda.json")
DEFAULT = os.path.join(HERE, "..", "crates", "trajkit-cli", "src", "default_waypoints.csv")


use_venv("totg", ["tesseract-robotics==0.5.1", "numpy"])

import multiprocessing as mp  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from panda import AMAX, QMAX, QMIN, VMAX, random_waypoints  # noqa: E402
from totg_peer import bounds, program  # noqa: E402


def original_totg(waypoints, max_deviation):
    """Runs the original TOTG; returns (status, duration, times, seconds, the largest
    |acceleration| / limit among the states it reports at the waypoints)."""
    from tesseract_robotics import tesseract_command_language as cl
    from tesseract_robotics import tesseract_time_parameterization as tp

    prog, traj = program(waypoints)
    v, a, j = bounds(VMAX, AMAX)
    t0 = time.perf_counter()
    ok = tp.TimeOptimalTrajectoryGeneration(max_deviation, 0.001).compute(traj, v, a, j)
    seconds = time.perf_counter() - t0
    if not ok:
        return "failed", None, [], seconds, None
    times = [traj.getTimeFromStart(i) for i in range(traj.size())]
    if not all(np.isfinite(times)):
        return "nan", None, [], seconds, None
    # The states the original reports at the waypoints (its only samples we can read).
    acc_ratio = 0.0
    ins = prog.getInstructions()
    for i in range(len(ins)):
        mi = cl.InstructionPoly_as_MoveInstructionPoly(ins[i])
        sw = cl.WaypointPoly_as_StateWaypointPoly(mi.getWaypoint())
        acc_ratio = max(acc_ratio, float(np.max(np.abs(np.array(sw.getAcceleration()).ravel()) / AMAX)))
    if any(b < a for a, b in zip(times, times[1:])):
        return "not-increasing", times[-1], times, seconds, acc_ratio
    return "ok", times[-1], times, seconds, acc_ratio


def _child(queue, waypoints, max_deviation):
    try:
        queue.put(original_totg(waypoints, max_deviation))
    except Exception as e:  # noqa: BLE001 - any failure of the original is a result here
        queue.put(("exception: " + str(e).splitlines()[0][:200], None, [], 0.0, None))


def run_isolated(waypoints, max_deviation, timeout=20.0):
    q = mp.Queue()
    p = mp.Process(target=_child, args=(q, waypoints, max_deviation))
    p.start()
    p.join(timeout)
    if p.is_alive():
        p.kill()
        p.join()
        return "timeout", None, [], timeout, None
    if q.empty():
        return "crashed (exit code %s)" % p.exitcode, None, [], 0.0, None
    return q.get()


def make_problems():
    rng = np.random.default_rng(20261122)
    probs = []
    default = np.loadtxt(DEFAULT, delimiter=",", comments="#", skiprows=3)
    probs.append(("default path", default, 0.1))
    for k in range(10):
        n = int(rng.integers(3, 11))
        w = random_waypoints(rng, n)
        # Moderate steps, as a planner produces after shortcutting.
        w = w[0] + np.cumsum(np.vstack([np.zeros(7), 0.3 * (w[1:] - w[:-1])]), axis=0)
        w = np.clip(w, QMIN + 0.05, QMAX - 0.05)
        probs.append((f"random {k}", w, float(rng.choice([0.02, 0.05, 0.1, 0.2]))))
    for k in range(3):
        # Uneven spacing: long segments with very short ones in between.
        w = [random_waypoints(rng, 1)[0]]
        for i in range(6):
            step = rng.normal(size=7)
            step *= (0.005 if i % 2 else 0.6) / np.linalg.norm(step)
            w.append(np.clip(w[-1] + step, QMIN + 0.05, QMAX - 0.05))
        probs.append((f"uneven {k}", np.array(w), 0.1))
    for k in range(3):
        # Some joints still on some segments (a joint starts or stops moving at a blend).
        w = random_waypoints(rng, 5)
        for i in range(1, 5):
            still = rng.random(7) < 0.5
            w[i, still] = w[i - 1, still]
        probs.append((f"still joints {k}", w, 0.1))
    w = random_waypoints(rng, 4)
    probs.append(("repeated waypoint", np.vstack([w[:2], w[1:2], w[2:]]), 0.1))
    a, b = random_waypoints(rng, 2)
    probs.append(("exact reversal", np.vstack([a, b, a, random_waypoints(rng, 1)[0]]), 0.1))
    a, b = random_waypoints(rng, 2)
    probs.append(("collinear", np.vstack([a, a + 0.3 * (b - a), a + 0.7 * (b - a), b, random_waypoints(rng, 1)[0]]), 0.1))
    for k in range(2):
        probs.append((f"line {k}", random_waypoints(rng, 2), 0.1))
    probs.append(("tiny deviation", random_waypoints(rng, 5) * 0.5, 1e-3))
    probs.append(("large deviation", random_waypoints(rng, 5) * 0.5, 1.0))
    return probs


def main():
    problems = []
    for name, w, dev in make_problems():
        w = np.asarray(w, dtype=float)
        status, duration, times, seconds, acc_ratio = run_isolated(w.tolist(), dev)
        print(f"{name:20s} {status:16s} {duration}", file=sys.stderr)
        problems.append(
            {
                "name": name,
                "waypoints": w.tolist(),
                "max_deviation": dev,
                "original": {
                    "status": status,
                    "duration": duration,
                    "waypoint_times": times,
                    "seconds": seconds,
                    "waypoint_acceleration_ratio": acc_ratio,
                },
            }
        )
    out = {
        "source": "tesseract-robotics 0.5.1, tesseract_time_parameterization.TimeOptimalTrajectoryGeneration(path_tolerance=max_deviation, min_angle_change=0.001), limits +-vmax, +-amax, +-jmax",
        "limits": {"velocity": VMAX.tolist(), "acceleration": AMAX.tolist()},
        "problems": problems,
    }
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as f:
        json.dump(out, f, indent=1)
    print("wrote", os.path.relpath(OUT), file=sys.stderr)


if __name__ == "__main__":
    main()
