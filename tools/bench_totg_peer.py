#!/usr/bin/env python3
"""Times the original TOTG (PyPI tesseract-robotics 0.5.1, TimeOptimalTrajectoryGeneration)
on trajkit's TOTG benchmark inputs (crates/trajkit/benches/totg.rs), for BENCHMARKS.md:

- the 7 waypoints of the `standard_7wp_natural_N1000` TOPP-RA fixture problem, Panda velocity
  and acceleration limits, max deviation 0.1;
- the same with velocity limits / 10 and acceleration limits / 100 (10x longer motion);
- trajkit's embedded default Panda path (8 waypoints).

It times compute() on a fresh InstructionsTrajectory each repeat (building the instruction
list is outside the timing) and prints the median, minimum and the resulting duration.
Uses the virtualenv of tools/totg_fixtures.py (created on first run).

Usage: python3 tools/bench_totg_peer.py [repeats]
"""
import json
import os
import sys
import time
from pyenv import use_venv

HERE = os.path.dirname(os.path.abspath(__file__))
FIX = os.path.join(HERE, "..", "crates", "trajkit", "tests", "fixtures", "topp", "toppra_panda.json")
DEFAULT = os.path.join(HERE, "..", "crates", "trajkit-cli", "src", "default_waypoints.csv")


use_venv("totg", ["tesseract-robotics==0.5.1", "numpy"])

import numpy as np  # noqa: E402
from tesseract_robotics import tesseract_time_parameterization as tp  # noqa: E402
from panda import AMAX, VMAX  # noqa: E402
from totg_peer import bounds, program  # noqa: E402


def bench(name, waypoints, vmax, amax, repeats):
    v, a, j = bounds(vmax, amax)
    totg = tp.TimeOptimalTrajectoryGeneration(0.1, 0.001)
    times, duration = [], None
    for _ in range(repeats):
        _, traj = program(waypoints)
        t0 = time.perf_counter()
        ok = totg.compute(traj, v, a, j)
        times.append(time.perf_counter() - t0)
        duration = traj.getTimeFromStart(traj.size() - 1) if ok else float("nan")
    times.sort()
    print(
        f"{name:32s} median {1e3 * times[len(times) // 2]:8.3f} ms  min {1e3 * times[0]:8.3f} ms  duration {duration:.6f} s"
    )


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 50
    fix = json.load(open(FIX))
    prob = next(p for p in fix["problems"] if p["name"] == "standard_7wp_natural_N1000")
    w7 = prob["waypoints"]
    default = np.loadtxt(DEFAULT, delimiter=",", comments="#", skiprows=3).tolist()
    bench("panda_7wp_dev0.1", w7, VMAX, AMAX, repeats)
    bench("panda_7wp_dev0.1_10x_slower", w7, VMAX / 10, AMAX / 100, max(5, repeats // 5))
    bench("default_path_dev0.1", default, VMAX, AMAX, repeats)


if __name__ == "__main__":
    main()
