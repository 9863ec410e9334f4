#!/usr/bin/env python3
"""Speed of the trajkit Python package next to the Python peers, in one run, one process.

- OTG: ``calculate`` per call on the same seeded 7-DOF problems, trajkit.otg vs the ruckig
  wheel (rest to rest and general states), median over repeated passes, and the mean of each
  problem's fastest call (the load-robust statistic on a shared machine);
- OTG through 5 intermediate waypoints (7 DOF, trajkit only: the ruckig wheel has no local
  waypoint calculation);
- splines: vectorized evaluation of a 7-joint not-a-knot cubic spline (100 waypoints) at
  10^6 times, trajkit.spline.CubicSpline vs scipy.interpolate.CubicSpline (values);
- TOPP: the standard problem of tools/bench_topp_peer.py (7-DOF Panda limits, natural cubic
  spline through the 7 waypoints of the `standard_7wp_natural_N1000` fixture, 1000 uniform
  intervals plus breakpoints): trajkit.topp.TOPPRA(...).compute_trajectory() vs toppra's
  TOPPRA constructor + compute_parameterization (seidel); trajkit on the same grid
  (refine=False), and once more with its default grid refinement;
- plan: trajkit.plan on the same waypoints and limits (+ the Panda jerk limits), without
  the jerk stage on 1000 intervals, and with the defaults. plan's job is waypoints in, a
  trajectory sampled at 1 kHz with every sample checked against every limit out; the like
  peer is toppra doing that same job: the chord-length natural spline through the waypoints,
  the constraints, TOPPRA + compute_trajectory, then the 1 kHz samples (position, velocity,
  acceleration) and the same velocity / acceleration check in numpy. toppra's solve alone
  (spline + TOPPRA + compute_trajectory, no samples, no check) is printed too, marked as
  unlike work; the defaults row runs plan's jerk stage, which toppra does not have (unlike
  work too, printed for the record).

Run inside an environment with the package and the peers (python/requirements-test.txt):
    python tools/bench_python.py [repeats]
"""
import json
import os
import statistics
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


class Times(list):
    """Seconds per call of each pass; compared by median and by minimum (the minimum is the
    least disturbed pass on a loaded machine)."""

    def med(self):
        return statistics.median(self)


def timeit(f, repeats, inner=1):
    ts = Times()
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(inner):
            f()
        ts.append((time.perf_counter() - t0) / inner)
    return ts


def otg_problems(mod, n, general, seed=3):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        inp = mod.InputParameter(7)
        vmax, amax, jmax = rng.uniform(0.5, 3, 7), rng.uniform(1, 8, 7), rng.uniform(5, 40, 7)
        inp.current_position = list(rng.uniform(-3, 3, 7))
        inp.target_position = list(rng.uniform(-3, 3, 7))
        if general:
            inp.current_velocity = list(rng.uniform(-0.9, 0.9, 7) * vmax)
            inp.current_acceleration = list(rng.uniform(-0.9, 0.9, 7) * amax)
            inp.target_velocity = list(rng.uniform(-0.5, 0.5, 7) * vmax)
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = list(vmax), list(amax), list(jmax)
        out.append(inp)
    return out


def bench_otg(repeats):
    import ruckig
    from trajkit import otg as tk
    rows = []
    for general in (False, True):
        runs = {}
        for mod in (ruckig, tk):
            probs = otg_problems(mod, 500, general)
            gen, traj = mod.Ruckig(7, 0.001), mod.Trajectory(7)
            runs[mod.__name__] = (lambda g=gen, tr=traj, ps=probs: [g.calculate(p, tr) for p in ps])
        res = {k: Times() for k in runs}
        # Passes alternate between the two, so that both see the same load.
        for _ in range(repeats):
            for k, run in runs.items():
                res[k].append(timeit(run, 1)[0] / 500)
        rows.append(("OTG calculate, 7 DOF, " + ("general states" if general else "rest to rest"),
                     res["trajkit.otg"], res["ruckig"]))
        rows.append(("  the same, mean of per-problem minima",) + otg_per_problem_min(runs_of(general), repeats))
    return rows


def runs_of(general):
    """Per library: a generator, a trajectory and the seeded problems (as in bench_otg)."""
    import ruckig
    from trajkit import otg as tk
    return {mod.__name__: (mod.Ruckig(7, 0.001), mod.Trajectory(7), otg_problems(mod, 500, general))
            for mod in (ruckig, tk)}


def otg_per_problem_min(runs, repeats):
    """The mean over the problems of each problem's fastest call (of `repeats`, the two libraries
    alternating call by call): robust to preemption on a loaded machine, where a whole pass is
    rarely left alone. Each call is timed on its own, so both sides include the timer's own
    cost (~0.1 µs). Returns (trajkit, ruckig) as one-value Times."""
    best = {k: [float("inf")] * 500 for k in runs}
    clock = time.perf_counter
    for _ in range(repeats):
        for i in range(500):
            for k, (gen, traj, probs) in runs.items():
                p = probs[i]
                t0 = clock()
                gen.calculate(p, traj)
                dt = clock() - t0
                if dt < best[k][i]:
                    best[k][i] = dt
    mean = {k: Times([sum(v) / len(v)]) for k, v in best.items()}
    return mean["trajkit.otg"], mean["ruckig"]


def bench_waypoints(repeats):
    """trajkit.otg.Ruckig.calculate through 5 intermediate waypoints, 7 DOF (Ruckig Pro's
    feature; the ruckig wheel sends waypoint problems to a remote service, so there is no
    local peer): 20 seeded bent paths from rest to rest, time per call."""
    from trajkit import otg as tk
    rng = np.random.default_rng(11)
    probs = []
    for _ in range(20):
        inp = tk.InputParameter(7)
        start, step = rng.uniform(-1, 1, 7), rng.uniform(0.3, 1.0, 7) * rng.choice([-1, 1], 7)
        pts = [start + (k + 1) * step + rng.uniform(-0.3, 0.3, 7) for k in range(6)]
        inp.current_position, inp.target_position = list(start), list(pts[-1])
        inp.intermediate_positions = pts[:-1]
        inp.max_velocity = list(rng.uniform(0.5, 2.0, 7))
        inp.max_acceleration = list(rng.uniform(1.0, 5.0, 7))
        inp.max_jerk = list(rng.uniform(5.0, 40.0, 7))
        probs.append(inp)
    gen, traj = tk.Ruckig(7, 0.001), tk.Trajectory(7)
    ts = timeit(lambda: [gen.calculate(p, traj) for p in probs], repeats)
    return [("OTG calculate, 7 DOF, 5 waypoints (no local peer)", Times(t / 20 for t in ts), None)]


def bench_spline(repeats):
    from scipy.interpolate import CubicSpline as SciCS
    from trajkit.spline import CubicSpline
    rng = np.random.default_rng(0)
    x = np.cumsum(rng.uniform(0.1, 1, 100))
    y = rng.normal(size=(100, 7))
    t = np.sort(rng.uniform(x[0], x[-1], 1_000_000))
    ours, ref = CubicSpline(x, y), SciCS(x, y)
    assert np.allclose(ours(t), ref(t), atol=1e-12)
    return [("CubicSpline eval, 7 joints, 1e6 times (per call)",
             timeit(lambda: ours(t), repeats), timeit(lambda: ref(t), repeats))]


def bench_topp(repeats):
    import toppra as ta
    import toppra.algorithm as algo
    import toppra.constraint as constraint
    from trajkit import topp
    ta.setup_logging("WARNING")
    fix = os.path.join(HERE, "..", "crates", "trajkit", "tests", "fixtures", "topp", "toppra_panda.json")
    prob = next(p for p in json.load(open(fix))["problems"] if p["name"] == "standard_7wp_natural_N1000")
    wp = np.array(prob["waypoints"])
    ss = np.linspace(0.0, 1.0, len(wp))
    vmax, amax = np.array(prob["vmax"]), np.array(prob["amax"])
    vlim, alim = np.vstack([-vmax, vmax]).T, np.vstack([-amax, amax]).T
    g = np.linspace(0.0, 1.0, 1001)
    grid = np.array(sorted(set(list(ss) + [s for s in g if np.min(np.abs(ss - s)) > 1e-9])))
    path_ref = ta.SplineInterpolator(ss, wp, bc_type="natural")
    pc = [constraint.JointVelocityConstraint(vlim),
          constraint.JointAccelerationConstraint(alim, discretization_scheme=constraint.DiscretizationType.Interpolation)]

    def peer():
        algo.TOPPRA(pc, path_ref, gridpoints=grid, solver_wrapper="seidel",
                    parametrizer="ParametrizeConstAccel").compute_parameterization(0.0, 0.0)
    path = topp.SplineInterpolator(ss, wp, bc_type="natural")
    cons = [topp.JointVelocityConstraint(vlim), topp.JointAccelerationConstraint(alim)]

    def ours():
        # Like toppra: the given grid only (refine=False); the default also refines.
        topp.TOPPRA(cons, path, gridpoints=1000, refine=False).compute_trajectory(0.0, 0.0)

    def refined():
        topp.TOPPRA(cons, path, gridpoints=1000).compute_trajectory(0.0, 0.0)
    t_peer = timeit(peer, max(3, repeats // 3))
    return [("TOPP-RA, standard problem (N = 1000), from Python", timeit(ours, repeats), t_peer),
            ("  the same with trajkit's grid refinement (default)", timeit(refined, 3), t_peer)]


def bench_plan(repeats):
    """trajkit.plan on the standard problem's waypoints and velocity/acceleration limits (Panda
    jerk limits, no position ranges) next to toppra doing the same job on the same path: its
    natural cubic spline through the same waypoints with plan's chord-length
    parameterization, the same limits, 1000 intervals plus breakpoints, compute_trajectory,
    then samples at plan's rate (1 kHz) checked against the limits as plan checks its own.
    Everything from the waypoints on is timed on both sides (path and constraints included)."""
    import toppra as ta
    import toppra.algorithm as algo
    import toppra.constraint as constraint
    import trajkit
    ta.setup_logging("WARNING")
    fix = os.path.join(HERE, "..", "crates", "trajkit", "tests", "fixtures", "topp", "toppra_panda.json")
    prob = next(p for p in json.load(open(fix))["problems"] if p["name"] == "standard_7wp_natural_N1000")
    wp = np.array(prob["waypoints"])
    vmax, amax = np.array(prob["vmax"]), np.array(prob["amax"])
    panda = trajkit.Limits("panda")
    # The toppra problem has no position ranges: stated unbounded, so that plan's path is the
    # plain spline (a range repair would reshape it).
    limits = panda.with_overrides(max_velocity=vmax, max_acceleration=amax,
                                  position_range=(-np.inf, np.inf))
    rate = 1000.0

    def solve():
        ss = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(wp, axis=0), axis=1))])
        g = np.linspace(0.0, ss[-1], 1001)
        grid = np.array(sorted(set(list(ss) + [s for s in g if np.min(np.abs(ss - s)) > 1e-9 * ss[-1]])))
        path = ta.SplineInterpolator(ss, wp, bc_type="natural")
        pc = [constraint.JointVelocityConstraint(np.vstack([-vmax, vmax]).T),
              constraint.JointAccelerationConstraint(np.vstack([-amax, amax]).T,
                                                     discretization_scheme=constraint.DiscretizationType.Interpolation)]
        return algo.TOPPRA(pc, path, gridpoints=grid, solver_wrapper="seidel",
                           parametrizer="ParametrizeConstAccel").compute_trajectory(0.0, 0.0)

    def peer_job():
        traj = solve()
        d = traj.duration
        t = np.append(np.arange(0.0, d, 1.0 / rate), d)
        q, qd, qdd = traj(t), traj(t, 1), traj(t, 2)
        # plan's check: every sample within every limit (toppra's answer may exceed them by
        # its discretization; the count is computed, not acted on, as plan would report it).
        over = int(np.sum(np.abs(qd) > vmax * (1 + 1e-9)) + np.sum(np.abs(qdd) > amax * (1 + 1e-9)))
        return q, over

    def raw():
        trajkit.plan(wp, limits, jerk_limit=False, gridpoints=1000, sample_rate=rate)

    def default():
        trajkit.plan(wp, limits, sample_rate=rate)
    n_peer = max(3, repeats // 3)
    t_job = timeit(peer_job, n_peer)
    t_solve = timeit(solve, n_peer)
    t_raw = timeit(raw, repeats)
    return [("plan, N = 1000, no jerk stage (toppra: same job)", t_raw, t_job),
            ("  the same vs toppra's solve only (unlike: no samples)", t_raw, t_solve),
            ("plan, defaults (jerk stage: unlike, toppra has none)", timeit(default, n_peer), t_job)]


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 15
    print(f"load: {os.getloadavg()}")
    rows = (bench_otg(repeats) + bench_waypoints(repeats) + bench_spline(repeats)
            + bench_topp(repeats) + bench_plan(repeats))
    print(f"{'benchmark (median | min per call)':57} {'trajkit':>25} {'peer':>25} {'ratio med|min':>14}")
    for name, ours, peer in rows:
        if peer is None:
            print(f"{name:57} {ours.med() * 1e6:12.2f}|{min(ours) * 1e6:10.2f}us {'-':>25} {'-':>14}")
            continue
        print(f"{name:57} {ours.med() * 1e6:12.2f}|{min(ours) * 1e6:10.2f}us "
              f"{peer.med() * 1e6:12.2f}|{min(peer) * 1e6:10.2f}us "
              f"{peer.med() / ours.med():6.1f}|{min(peer) / min(ours):5.1f}x")
    print(f"load: {os.getloadavg()}")


if __name__ == "__main__":
    main()
