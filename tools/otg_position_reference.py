#!/usr/bin/env python3
"""Reference durations of jerk-limited motions under position limits, by brute force: a
fine-grid linear program (scipy's HiGHS, PyPI), for trajkit's online generator.

Problems: seeded single-DOF motions (general start and target states inside the velocity and
acceleration limits) whose unconstrained time-optimal motion (the Ruckig wheel, PyPI) leaves
the span of its start and target; a position limit is put between that span and the
motion's extreme, so that it binds. Some problems get a `minimum_duration` instead of the
shortest one (a motion stretched as in synchronization).

The reference: N uniform intervals of constant jerk u_k ∈ [−J, J] over a duration T, the
states (p, v, a) at the N + 1 nodes integrated exactly, velocity, acceleration and position
limits at every node, start and target state fixed. Feasibility is a linear program; the
shortest feasible T is found by scanning T upwards from the unconstrained minimum in steps of
2 % (feasible durations need not form one interval when the target moves), then bisecting
the first feasible step. Limits hold at the nodes only and the jerk is piecewise constant on
a fixed grid, so the reference is near-optimal from both sides; with N = 1500 it is within a
few 1e-4 of the continuous optimum (checked on the unconstrained problems, where the exact
minimum is Ruckig's). A problem whose constrained motion needs more than 4× the
unconstrained duration (or none is feasible) is recorded as infeasible.

Then `binding` problems: the unconstrained motion goes further than the least overshoot
before turning (from the start, and time-reversed into the target), and the limit cuts into
that excursion but holds the least overshoots: a motion inside may exist, longer than the
unconstrained one (the reference decides; such problems are rare among random ones).

Writes crates/trajkit/tests/fixtures/otg/position_reference.json (the committed one:
`otg_position_reference.py 20 400 8`).

Usage: python3 tools/otg_position_reference.py [count] [N] [binding] [--binding-only]
(--binding-only: recompute only the binding cases of the existing fixture)
"""
import json
import os
import random
import sys
import time
from pyenv import use_venv

use_venv("otg-position", ["ruckig==0.19.4", "numpy==2.4.6", "scipy==1.17.1"])

import numpy as np  # noqa: E402
import scipy.sparse as sp  # noqa: E402
from scipy.optimize import linprog  # noqa: E402
import ruckig  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "trajkit", "tests", "fixtures", "otg",
                   "position_reference.json")


def feasible(pr, T, N):
    """Whether a grid motion of duration T exists (see the module docstring)."""
    h = T / N
    n = 4 * N + 3  # p, v, a at N + 1 nodes, then u at N intervals
    P, V, A, U = 0, N + 1, 2 * (N + 1), 3 * (N + 1)
    rows, cols, vals = [], [], []
    r = 0
    for k in range(N):
        # a_{k+1} - a_k - h u_k = 0
        rows += [r, r, r]; cols += [A + k + 1, A + k, U + k]; vals += [1, -1, -h]; r += 1
        # v_{k+1} - v_k - h a_k - h²/2 u_k = 0
        rows += [r] * 4; cols += [V + k + 1, V + k, A + k, U + k]
        vals += [1, -1, -h, -h * h / 2]; r += 1
        # p_{k+1} - p_k - h v_k - h²/2 a_k - h³/6 u_k = 0
        rows += [r] * 5; cols += [P + k + 1, P + k, V + k, A + k, U + k]
        vals += [1, -1, -h, -h * h / 2, -h ** 3 / 6]; r += 1
    Aeq = sp.csr_matrix((vals, (rows, cols)), shape=(r, n))
    beq = np.zeros(r)
    lo = np.empty(n)
    hi = np.empty(n)
    lo[P:V], hi[P:V] = pr["min_position"], pr["max_position"]
    lo[V:A], hi[V:A] = -pr["vmax"], pr["vmax"]
    lo[A:U], hi[A:U] = -pr["amax"], pr["amax"]
    lo[U:], hi[U:] = -pr["jmax"], pr["jmax"]
    for idx, x in [(P, pr["p0"]), (V, pr["v0"]), (A, pr["a0"]),
                   (P + N, pr["pf"]), (V + N, pr["vf"]), (A + N, pr["af"])]:
        lo[idx] = hi[idx] = x
    res = linprog(np.zeros(n), A_eq=Aeq, b_eq=beq, bounds=np.column_stack([lo, hi]),
                  method="highs")
    return res.status == 0


def shortest(pr, t0, N, t_fixed=None):
    """The shortest feasible duration from t0 on (None if none up to 4·t0); with t_fixed,
    only whether that duration is feasible (then t_fixed or None)."""
    if t_fixed is not None:
        return t_fixed if feasible(pr, t_fixed, N) else None
    prev = t0
    t = t0
    while t <= 4.0 * t0:
        if feasible(pr, t, N):
            break
        prev, t = t, t + 0.02 * t0
    else:
        return None
    if t == t0:
        return t0
    lo, hi = prev, t
    for _ in range(12):  # 2 % / 4096: below the grid error
        mid = 0.5 * (lo + hi)
        if feasible(pr, mid, N):
            hi = mid
        else:
            lo = mid
    return hi


def ruckig_free(pr):
    """Ruckig's unconstrained motion: duration and position extrema (min, max)."""
    otg = ruckig.Ruckig(1)
    inp = ruckig.InputParameter(1)
    inp.current_position = [pr["p0"]]
    inp.current_velocity = [pr["v0"]]
    inp.current_acceleration = [pr["a0"]]
    inp.target_position = [pr["pf"]]
    inp.target_velocity = [pr["vf"]]
    inp.target_acceleration = [pr["af"]]
    inp.max_velocity = [pr["vmax"]]
    inp.max_acceleration = [pr["amax"]]
    inp.max_jerk = [pr["jmax"]]
    traj = ruckig.Trajectory(1)
    res = otg.calculate(inp, traj)
    if res not in (ruckig.Result.Working, ruckig.Result.Finished):
        return None
    ext = traj.position_extrema[0]
    return traj.duration, ext.min, ext.max


def stop_extent(p, v, a, pr):
    """Position extrema (min, max) of Ruckig's fastest stop from (p, v, a)."""
    otg = ruckig.Ruckig(1)
    inp = ruckig.InputParameter(1)
    inp.control_interface = ruckig.ControlInterface.Velocity
    inp.current_position = [p]
    inp.current_velocity = [v]
    inp.current_acceleration = [a]
    inp.target_velocity = [0.0]
    inp.target_acceleration = [0.0]
    inp.max_velocity = [pr["vmax"]]
    inp.max_acceleration = [pr["amax"]]
    inp.max_jerk = [pr["jmax"]]
    traj = ruckig.Trajectory(1)
    otg.calculate(inp, traj)
    ext = traj.position_extrema[0]
    return ext.min, ext.max


def turn_extent(p, v, a, pr):
    """Position extrema (min, max) of the least overshoot from (p, v, a) before the velocity
    is zero (any acceleration then): jerk at its limit against the velocity, the acceleration
    clamped at its limit; integrated in small steps (it only places a limit)."""
    s = 1.0 if v > 0 or (v == 0 and a > 0) else -1.0
    v, a = s * v, s * a
    x, h = 0.0, 1e-5
    while v > 0 or (v == 0 and a > 0):
        a2 = max(a - pr["jmax"] * h, -pr["amax"])
        x += h * v + h * h / 2 * a
        v += h * (a + a2) / 2
        a = a2
    return (p, p + s * x) if s > 0 else (p + s * x, p)


def witness_span(pr):
    """A span every motion covers: start, target, the least overshoot before turning from
    the start and (time-reversed) into the target state."""
    lo1, hi1 = turn_extent(pr["p0"], pr["v0"], pr["a0"], pr)
    lo2, hi2 = turn_extent(pr["pf"], -pr["vf"], pr["af"], pr)
    return min(lo1, lo2, pr["pf"]), max(hi1, hi2, pr["pf"])


def inside(rng, vmax, amax, jmax):
    """A state (v, a) inside the limits with v ± a|a|/(2j) inside too."""
    while True:
        v, a = rng.uniform(-vmax, vmax), rng.uniform(-amax, amax)
        w = a * abs(a) / (2 * jmax)
        if abs(v + w) <= vmax and abs(v - w) <= vmax:
            return v, a


def problem(rng):
    vmax, amax, jmax = rng.uniform(0.5, 2.0), rng.uniform(1.0, 5.0), rng.uniform(5.0, 50.0)
    v0, a0 = inside(rng, vmax, amax, jmax)
    vf, af = inside(rng, vmax, amax, jmax)
    return {"p0": 0.0, "v0": v0, "a0": a0, "pf": rng.uniform(-1.0, 1.0), "vf": vf, "af": af,
            "vmax": vmax, "amax": amax, "jmax": jmax,
            "min_position": -np.inf, "max_position": np.inf}


def as_json(pr, minimum_duration):
    inf = lambda x: x if np.isfinite(x) else ("inf" if x > 0 else "-inf")  # noqa: E731
    j = {"current_position": [pr["p0"]], "current_velocity": [pr["v0"]],
         "current_acceleration": [pr["a0"]], "target_position": [pr["pf"]],
         "target_velocity": [pr["vf"]], "target_acceleration": [pr["af"]],
         "max_velocity": [pr["vmax"]], "max_acceleration": [pr["amax"]],
         "max_jerk": [pr["jmax"]], "min_position": [inf(pr["min_position"])],
         "max_position": [inf(pr["max_position"])]}
    if minimum_duration is not None:
        j["minimum_duration"] = minimum_duration
    return j


def main():
    count = int(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1].isdigit() else 60
    N = int(sys.argv[2]) if len(sys.argv) > 2 and sys.argv[2].isdigit() else 1500
    n_binding = int(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[3].isdigit() else 8
    if "--binding-only" in sys.argv:
        with open(OUT) as f:
            out = json.load(f)
        out["cases"] = [c for c in out["cases"] if not c.get("binding")]
        add_binding(out, N, n_binding, time.time() - out["seconds"])
        return
    rng = random.Random(20261126)
    cases = []
    t_start = time.time()
    # Grid accuracy on unconstrained problems (the exact minimum is Ruckig's).
    accuracy = []
    while len(accuracy) < 5:
        pr = problem(rng)
        free = ruckig_free(pr)
        if free is None:
            continue
        t = shortest(pr, free[0] * 0.97, N)
        accuracy.append(t / free[0] - 1.0)
    print("grid accuracy (reference/exact - 1):", ["%.1e" % a for a in accuracy])
    while len(cases) < count:
        pr = problem(rng)
        free = ruckig_free(pr)
        if free is None:
            continue
        t_free, lo, hi = free
        top, bottom = max(pr["p0"], pr["pf"]), min(pr["p0"], pr["pf"])
        stretched = len(cases) % 4 == 3
        minimum = None
        if stretched:
            minimum = t_free * rng.uniform(1.2, 2.5)
            # The stretched motion may move anywhere: limit the side the free one uses, or
            # a random side, just outside the span.
            if hi - top >= bottom - lo:
                pr["max_position"] = top + rng.uniform(0.0, 0.5) * max(hi - top, 0.05)
            else:
                pr["min_position"] = bottom - rng.uniform(0.0, 0.5) * max(bottom - lo, 0.05)
        else:
            over, under = hi - top, bottom - lo
            if max(over, under) < 1e-3:
                continue
            f = rng.choice([0.98, 0.9, 0.7])
            if over >= under:
                pr["max_position"] = top + f * over
            else:
                pr["min_position"] = bottom - f * under
        ref = shortest(pr, t_free, N, minimum)
        cases.append({"problem": as_json(pr, minimum), "free_duration": t_free,
                      "reference_duration": ref, "stretched": stretched})
        print(len(cases), "free %.6f" % t_free, "minimum" if stretched else "",
              "reference", "infeasible" if ref is None else "%.6f" % ref, flush=True)
    out = {"generator": "tools/otg_position_reference.py", "intervals": N,
           "grid_accuracy": accuracy, "seconds": time.time() - t_start, "cases": cases}
    with open(OUT, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print("wrote", OUT)
    add_binding(out, N, n_binding, t_start)



def add_binding(out, N, n_binding, t_start):
    """Appends the binding cases (see the module docstring) to `out` and writes it."""
    # Binding cases: the unconstrained optimum leaves the span every motion covers, and the
    # limit cuts into that excursion but holds the span: a motion inside may exist (the
    # reference decides), longer than the unconstrained one.
    rng = random.Random(20261127)
    binding = []
    tried = 0
    while len(binding) < n_binding:
        tried += 1
        pr = problem(rng)
        free = ruckig_free(pr)
        if free is None:
            continue
        t_free, lo, hi = free
        bottom, top = witness_span(pr)
        if hi - top > 1e-3:
            pr["max_position"] = top + rng.uniform(0.1, 0.9) * (hi - top)
        elif bottom - lo > 1e-3:
            pr["min_position"] = bottom - rng.uniform(0.1, 0.9) * (bottom - lo)
        else:
            continue
        ref = shortest(pr, t_free, N)
        binding.append({"problem": as_json(pr, None), "free_duration": t_free,
                        "reference_duration": ref, "stretched": False, "binding": True})
        print("binding", len(binding), "of", tried, "free %.6f" % t_free, "reference",
              "infeasible" if ref is None else "%.6f" % ref, flush=True)
    out["cases"] += binding
    out["binding_tried"] = tried
    out["seconds"] = time.time() - t_start
    with open(OUT, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print("wrote", OUT)


if __name__ == "__main__":
    main()
