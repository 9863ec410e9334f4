#!/usr/bin/env python3
"""Times trajkit's B-spline evaluation benchmark and scipy's vectorized BSpline on the same
data in one run, and prints both with their ratio.

Data (identical in crates/trajkit/benches/spline.rs): clamped uniform cubic B-spline on [0, 1],
100 control points c[i][d] = sin(0.37 i + 1.3 d) in 7 dimensions, 10^6 equally spaced sorted
parameters.

Usage: python3 tools/bench_spline_peer.py [--no-venv] [--skip-cargo]
"""
import os
import re
import statistics
import subprocess
import sys
import time
from pyenv import use_venv

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


use_venv("spline", ["numpy", "scipy==1.17.1", "geomdl==5.4.0"])

import numpy as np  # noqa: E402
import scipy  # noqa: E402
from scipy.interpolate import BSpline  # noqa: E402


def scipy_rate(reps=15):
    n, dim, k = 100, 7, 3
    inner = n - k - 1
    t = np.r_[[0.0] * (k + 1), [i / (inner + 1) for i in range(1, inner + 1)], [1.0] * (k + 1)]
    i = np.arange(n)[:, None]
    d = np.arange(dim)[None, :]
    c = np.sin(0.37 * i + 1.3 * d)
    b = BSpline(t, c, k)
    s = np.arange(1_000_000) / 999_999.0
    out = b(s)
    times = []
    cpu = []
    for _ in range(reps):
        t0 = time.perf_counter()
        c0 = time.thread_time()
        out = b(s)
        cpu.append(time.thread_time() - c0)
        times.append(time.perf_counter() - t0)
    med = statistics.median(times)
    return med, s.size / med / 1e6, statistics.median(cpu)


def cargo_rate():
    """Criterion medians (seconds) of the wall-time and the CPU-time benchmarks."""
    env = dict(os.environ)
    env.setdefault("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    r = subprocess.run(["cargo", "bench", "-p", "trajkit", "--bench", "spline", "--", "bspline_eval"],
                       cwd=ROOT, env=env, capture_output=True, text=True)
    text = r.stdout + r.stderr
    res = []
    for name in ["cubic_100cp_7d_1e6_sorted", "cubic_100cp_7d_1e6_sorted_cputime"]:
        m = re.search(r"bspline_eval/" + name + r"\s+time:\s+\[\S+ \S+ (\S+) (\S+)", text)
        if not m:
            print(text[-3000:])
            sys.exit("could not read criterion's output")
        val, unit = float(m.group(1)), m.group(2)
        res.append(val * {"s": 1.0, "ms": 1e-3, "µs": 1e-6, "us": 1e-6, "ns": 1e-9}[unit])
    return res


if __name__ == "__main__":
    print(f"scipy {scipy.__version__}, numpy {np.__version__}")
    with open("/proc/loadavg") as fh:
        print("load average:", " ".join(fh.read().split()[:3]))
    before = scipy_rate()
    print(f"scipy BSpline vectorized (before): wall median {before[0]*1e3:.1f} ms = {before[1]:.1f} M points/s;"
          f" CPU median {before[2]*1e3:.1f} ms = {1/before[2]:.1f} M points/s")
    if "--skip-cargo" not in sys.argv:
        wall, cpu = cargo_rate()
        print(f"trajkit BSpline::eval_many (criterion medians): wall {wall*1e3:.1f} ms = {1.0/wall:.1f} M points/s;"
              f" CPU {cpu*1e3:.1f} ms = {1.0/cpu:.1f} M points/s")
    after = scipy_rate()
    print(f"scipy BSpline vectorized (after):  wall median {after[0]*1e3:.1f} ms = {after[1]:.1f} M points/s;"
          f" CPU median {after[2]*1e3:.1f} ms = {1/after[2]:.1f} M points/s")
    if "--skip-cargo" not in sys.argv:
        peer_wall = statistics.mean([before[1], after[1]])
        peer_cpu = statistics.mean([1 / before[2], 1 / after[2]])
        print(f"ratio trajkit / scipy: wall {1.0/wall/peer_wall:.2f}, CPU {1.0/cpu/peer_cpu:.2f}")
