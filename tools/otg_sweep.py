"""Sweep: trajkit's online generator against the Ruckig wheel, with an independent checker.

    python3 tools/otg_sweep.py --count 1000000 --seed 1 --out /tmp/sweep
    python3 tools/otg_sweep.py --count 20000 --seed 7 --categories general,phase
    python3 tools/otg_sweep.py --count 20000 --seed 16 --around /tmp/sweep/failures.jsonl

For every problem of every category (seeded, fresh seeds give fresh problems) it
  1. solves it with trajkit (`trajkit otg --batch --profiles`, the release binary, built
     here if missing),
  2. solves it with Ruckig (the PyPI wheel, pinned below, in its own virtual environment),
  3. checks trajkit's trajectory with its own integrator: it starts from the problem's
     current state, integrates the reported segments (only the jerk; the jumps that second-
     and first-order profiles allow are taken from the segment data and nothing else), samples
     every segment densely (and at its interior velocity extremum), and checks the limits
     (velocity, acceleration, jerk; the brake pre-profile is exempt from what it repairs, and
     afterwards a value may only return towards its limit) and the final state against the
     target, with the scale-relative tolerance of trajkit's precision contract;
  4. compares: trajkit's duration must be at most Ruckig's × (1 + 1e-9) wherever Ruckig
     succeeds; for phase synchronization, per-DOF options and zero limits the durations must
     be equal and the states equal at sampled times.
Ruckig succeeds when its final positions meet the same scale-relative tolerance as trajkit's
(its velocities and accelerations are not judged, so that no problem leaves the comparison
for a rounding of Ruckig's end state); otherwise it is counted in `ruckig_misses_target`. Where Ruckig is
shorter than trajkit but trajkit, given the final positions Ruckig actually reached as its
target (and its final velocities and accelerations where they miss trajkit's tolerances,
1e-10), is at most Ruckig's duration × (1 + 1e-9), Ruckig stopped short of the target
(within the tolerance) rather than found a faster motion: counted in
`longer_by_ruckig_error` (and listed in failures.jsonl), apart from `longer`. (Near a
tangent root the end position moves slowly with the duration, so an error well inside the
tolerance can be worth 1e-8 of the duration.)
The category `step1_property` is one DOF whose target is the end state of a step-1 family
profile built forward (levels next to each other, to a limit or to zero), the generator of
tests/otg_step1_shapes.rs; the other categories draw 1, 3 or 7 DOFs.
The summary (per category: counts, failures, worst ratios) is written to OUT/summary.json and
printed; every problem that breaks a rule is written, with Ruckig's duration, to
OUT/failures.jsonl. `--fixture FILE` appends the problems where trajkit was longer than Ruckig
or failed where Ruckig succeeded to FILE in the format of
crates/trajkit/tests/fixtures/otg/regressions.jsonl (category, Ruckig's duration, problem),
which tests/otg_regressions.rs replays, and those counted in `longer_by_ruckig_error` with
`ruckig_end_position` too (the final positions Ruckig reached; null for a DOF without a
position target), and `ruckig_end_velocity` / `ruckig_end_acceleration` where Ruckig's final
velocities / accelerations missed (null for the DOFs that did not). `--replay FILE` runs FILE's problems themselves (e.g. a failures.jsonl),
each once.
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pyenv import use_venv  # noqa: E402

RUCKIG = "ruckig==0.19.4"
use_venv("otg-sweep", [RUCKIG])

import ruckig  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INF = float("inf")
EPS = 2.220446049250313e-16

# ---------------------------------------------------------------- problem generation


def logu(r, lo, hi):
    return math.exp(math.log(lo) + (math.log(hi) - math.log(lo)) * r.random())


def inside(r, vmax, vmin, amax, amin, j):
    """A state (v, a) inside the limits that stays inside when a ramps to zero."""
    for _ in range(100):
        v = r.uniform(vmin, vmax)
        a = r.uniform(amin, amax)
        s = a * abs(a) / (2 * j)
        if vmin <= v + s <= vmax and vmin <= v - s <= vmax:
            return v, a
    return 0.0, 0.0


def base(r, n, big=False, directional=False):
    p = {k: [0.0] * n for k in ("current_position", "current_velocity", "current_acceleration",
                                "target_position", "target_velocity", "target_acceleration")}
    p["max_velocity"], p["max_acceleration"], p["max_jerk"] = [], [], []
    for i in range(n):
        if big:
            v, a, j = logu(r, 1, 1e6), logu(r, 1, 1e6), logu(r, 1, 1e6)
        else:
            v, a, j = logu(r, 0.1, 5), logu(r, 0.1, 10), logu(r, 0.1, 100)
        p["max_velocity"].append(v)
        p["max_acceleration"].append(a)
        p["max_jerk"].append(j)
        p["current_position"][i] = r.uniform(-5, 5)
        p["target_position"][i] = r.uniform(-5, 5)
    if directional:
        p["min_velocity"] = [-logu(r, 0.1, 5) for _ in range(n)]
        p["min_acceleration"] = [-logu(r, 0.1, 10) for _ in range(n)]
    return p


def lims(p, i):
    vmax, amax, j = p["max_velocity"][i], p["max_acceleration"][i], p["max_jerk"][i]
    vmin = p["min_velocity"][i] if "min_velocity" in p else -vmax
    amin = p["min_acceleration"][i] if "min_acceleration" in p else -amax
    return vmax, vmin, amax, amin, j


def general_states(r, p, big=False):
    n = len(p["current_position"])
    for i in range(n):
        vmax, vmin, amax, amin, j = lims(p, i)
        if big:
            cap = min(math.sqrt(2 * amax * 1e3), (j * 1e6) ** (1 / 3))
            vmax, vmin = min(vmax, cap), max(vmin, -cap)
        p["current_velocity"][i], p["current_acceleration"][i] = inside(r, vmax, vmin, amax, amin, j)
        p["target_velocity"][i], p["target_acceleration"][i] = inside(r, vmax, vmin, amax, amin, j)


def perturbed(base, r):
    """A copy of problem `base` with every number of its lists scaled: by 1 ± 1 % (70 %) or
    by [0.5, 2] (30 %); signs, structure and options are kept."""
    p = json.loads(json.dumps(base))
    wide = r.random() < 0.3
    for k, v in p.items():
        if isinstance(v, list) and v and all(isinstance(x, (int, float)) for x in v):
            p[k] = [x * (r.uniform(0.5, 2.0) if wide else 1 + r.uniform(-0.01, 0.01)) for x in v]
    return p


REPLAY = {}


def use_around(args, exact=False):
    """`--around FILE`: the categories are those of FILE's problems, and each category's
    problems are perturbed copies of FILE's problems of that category (round robin).
    `--replay FILE` (`exact`): FILE's problems themselves, each once."""
    global gen
    bases = {}
    for line in open(args.replay if exact else args.around):
        d = json.loads(line)
        bases.setdefault(d["category"], []).append(d["problem"])
    args.categories = ",".join(bases)
    if exact:
        REPLAY.update({c: len(b) for c, b in bases.items()})
    counter = {}

    def around(cat, r, n):
        k = counter.get(cat, 0)
        counter[cat] = k + 1
        b = bases[cat]
        return json.loads(json.dumps(b[k % len(b)])) if exact else perturbed(b[k % len(b)], r)
    gen = around


def near_pick(r, lo, hi):
    """A level in [lo, hi]: uniform, next to one end (1e-7 to 1e-1 of the range away) or, when
    the range holds it, next to zero, a third of the time each (as tests/otg_step1_shapes.rs)."""
    w = hi - lo
    off = w * 10 ** r.uniform(-7, -1)
    u = r.random()
    if u < 1 / 3:
        x = r.uniform(lo, hi)
    elif u < 2 / 3:
        x = lo + off if r.random() < 0.5 else hi - off
    elif lo < 0 < hi:
        x = math.copysign(off, r.uniform(-1, 1))
    else:
        x = r.uniform(lo, hi)
    return min(max(x, lo), hi)


def step1_property(r):
    """One DOF whose target is the end state of a profile of a step-1 family (none, acc0, acc1,
    acc0_acc1, cruise at the velocity limit) built forward from a random state, with levels
    next to each other, to a limit or to zero and holds from 1e-4 to 10 of a_max/j: the
    generator of tests/otg_step1_shapes.rs, so that any seed gives fresh problems of that
    kind (the constructed profile is feasible, so its duration bounds the minimum)."""
    while True:
        j = 10 ** r.uniform(-1.5, 2)
        am = 10 ** r.uniform(-1, 1)
        kind = r.randrange(5)
        hold = lambda: am / j * 10 ** r.uniform(-4, 1)  # noqa: E731
        if kind == 0:
            l1 = near_pick(r, -am, am)
            a0 = near_pick(r, -am, l1)
            l2 = near_pick(r, -am, l1)
            steps = [(l1, 0), (l2, 0), (near_pick(r, l2, am), 0)]
        elif kind == 1:
            a0, l2 = near_pick(r, -am, am), near_pick(r, -am, am)
            steps = [(am, hold()), (l2, 0), (near_pick(r, l2, am), 0)]
        elif kind == 2:
            l1 = near_pick(r, -am, am)
            a0 = near_pick(r, -am, l1)
            steps = [(l1, 0), (-am, hold()), (near_pick(r, -am, am), 0)]
        elif kind == 3:
            a0 = near_pick(r, -am, am)
            steps = [(am, hold()), (-am, hold()), (near_pick(r, -am, am), 0)]
        else:
            a0 = near_pick(r, -am, am)
            pl1, pl2 = r.random() < 0.5, r.random() < 0.5
            l1 = am if pl1 else near_pick(r, max(a0, 0), am)
            l2 = -am if pl2 else near_pick(r, -am, 0)
            steps = [(l1, hold() if pl1 else 0), (0, hold()), (l2, hold() if pl2 else 0),
                     (near_pick(r, l2, am), 0)]
        v0 = r.uniform(-2, 2)
        phases, a = [], a0
        for level, h in steps:
            phases.append((abs(level - a) / j, math.copysign(j, level - a)))
            if h > 0:
                phases.append((h, 0.0))
            a = level
        pp, v, a, vpeak, vcruise = 0.0, v0, a0, abs(v0), None
        # The cruise (kind 4) is the hold before the last ramps (and the plateau at −a_max).
        n1 = len(phases) - (4 if kind == 4 and steps[2][1] > 0 else 3)
        for k, (d, jj) in enumerate(phases):
            if kind == 4 and k == n1:
                vcruise = v
            if jj != 0 and a / jj < 0 and -a / jj < d:
                s = -a / jj
                vpeak = max(vpeak, abs(v + a * s + jj * s * s / 2))
            pp, v, a = pp + d * (v + d * (a / 2 + d * jj / 6)), v + d * (a + d * jj / 2), a + d * jj
            vpeak = max(vpeak, abs(v))
        if kind == 4:
            if vcruise is None or not (vcruise > 0 and vpeak <= vcruise * (1 + 1e-13)):
                continue
            vmax = vcruise * (1 + 1e-13)
        else:
            vmax = (vpeak + max(a0 * a0, a * a) / (2 * j)) * r.uniform(1, 2) + 1e-3
        if vpeak > 300 or abs(pp) > 1e4:
            continue
        sg = 1 if r.random() < 0.5 else -1
        p0 = r.uniform(-100, 100)
        return {"current_position": [sg * p0], "current_velocity": [sg * v0],
                "current_acceleration": [sg * a0], "target_position": [sg * (p0 + pp)],
                "target_velocity": [sg * v], "target_acceleration": [sg * a],
                "max_velocity": [vmax], "max_acceleration": [am], "max_jerk": [j]}


def gen(cat, r, n):
    if cat == "step1_property":
        return step1_property(r)
    p = base(r, n, big=(cat == "big_limits"), directional=(cat == "directional"))
    if cat == "rest_to_rest":
        pass
    elif cat in ("general", "discrete", "velocity_interface", "time_if_necessary", "none",
                 "minimum_duration", "per_dof_sync", "per_dof_interface"):
        general_states(r, p)
    elif cat in ("big_limits", "directional"):
        if r.random() < 0.5:
            general_states(r, p, big=(cat == "big_limits"))
    elif cat == "beyond_limits":
        for i in range(n):
            vmax, vmin, amax, amin, j = lims(p, i)
            p["current_velocity"][i] = r.uniform(-2, 2) * vmax
            p["current_acceleration"][i] = r.uniform(-2, 2) * amax
            if r.random() < 0.5:
                p["target_velocity"][i], p["target_acceleration"][i] = inside(r, vmax, vmin, amax, amin, j)
    elif cat == "target_velocity":
        for i in range(n):
            vmax, vmin, *_ = lims(p, i)
            p["target_velocity"][i] = r.uniform(vmin, vmax)
    elif cat == "target_at_vmax":
        for i in range(n):
            vmax, vmin, *_ = lims(p, i)
            p["target_velocity"][i] = vmax if r.random() < 0.5 else vmin
    elif cat == "tiny":
        for i in range(n):
            d = logu(r, 1e-12, 1e-4) * (1 if r.random() < 0.5 else -1)
            p["target_position"][i] = p["current_position"][i] + d
            if r.random() < 0.5:
                p["current_velocity"][i] = r.uniform(-1, 1) * logu(r, 1e-20, 1e-10)
                p["target_velocity"][i] = r.uniform(-1, 1) * logu(r, 1e-20, 1e-10)
    elif cat == "huge":
        for i in range(n):
            p["target_position"][i] = r.uniform(-1e4, 1e4)
    elif cat == "identical":
        for i in range(n):
            p["target_position"][i] = p["current_position"][i]
            u = r.random()
            vmax, vmin, amax, amin, j = lims(p, i)
            if u < 0.4:
                v, a = inside(r, vmax, vmin, amax, amin, j)
                p["current_velocity"][i] = p["target_velocity"][i] = v
                p["current_acceleration"][i] = p["target_acceleration"][i] = a
            elif u < 0.7:
                a = r.uniform(amin, amax) * 0.5
                p["current_acceleration"][i] = p["target_acceleration"][i] = a
    elif cat == "second_order":
        for i in range(n):
            vmax, vmin, *_ = lims(p, i)
            p["max_jerk"][i] = INF
            p["current_velocity"][i] = r.uniform(vmin, vmax)
            if r.random() < 0.5:
                p["target_velocity"][i] = r.uniform(vmin, vmax)
    elif cat == "first_order":
        for i in range(n):
            p["max_jerk"][i] = INF
            p["max_acceleration"][i] = INF
    elif cat == "phase":
        s = r.uniform(-0.2, 0.2)
        vm = min(p["max_velocity"])
        for i in range(n):
            u = p["target_position"][i] - p["current_position"][i]
            p["current_velocity"][i] = s * u * vm / 10
        if r.random() < 0.3:
            tv = r.uniform(-0.2, 0.2)
            for i in range(n):
                u = p["target_position"][i] - p["current_position"][i]
                p["target_velocity"][i] = tv * u * vm / 10
    elif cat == "zero_limits":
        general_states(r, p) if r.random() < 0.3 else None
        for i in range(n):
            if r.random() < 0.5:
                k = r.choice(["max_jerk", "max_acceleration", "max_velocity"])
                p[k][i] = 0.0
                if k == "max_velocity" or r.random() < 0.5:
                    # Coasting DOFs: a consistent coast, or none at all.
                    if r.random() < 0.5:
                        p["current_velocity"][i] = p["target_velocity"][i] = 0.0
                        p["current_acceleration"][i] = p["target_acceleration"][i] = 0.0
                        p["target_position"][i] = p["current_position"][i]
                    else:
                        v = r.uniform(-1, 1) * min(p["max_velocity"][i], 1.0)
                        t = r.uniform(0.1, 3)
                        p["current_velocity"][i] = p["target_velocity"][i] = v
                        p["current_acceleration"][i] = p["target_acceleration"][i] = 0.0
                        p["target_position"][i] = p["current_position"][i] + v * t
    else:
        raise ValueError(cat)
    if cat == "discrete":
        p["duration_discretization"] = "discrete"
    if cat == "velocity_interface":
        p["control_interface"] = "velocity"
    if cat == "phase":
        p["synchronization"] = "phase"
    if cat == "time_if_necessary":
        p["synchronization"] = "time_if_necessary"
    if cat == "none":
        p["synchronization"] = "none"
    if cat == "minimum_duration":
        p["minimum_duration"] = r.uniform(0, 8)
    if cat == "per_dof_sync":
        p["per_dof_synchronization"] = [r.choice(["time", "time_if_necessary", "none"]) for _ in range(n)]
    if cat == "per_dof_interface":
        p["per_dof_control_interface"] = [r.choice(["position", "velocity"]) for _ in range(n)]
    if r.random() < 0.2 and cat in ("general", "target_velocity", "discrete"):
        p["enabled"] = [r.random() < 0.8 for _ in range(n)]
    return p


CATEGORIES = ["rest_to_rest", "general", "beyond_limits", "target_velocity", "target_at_vmax",
              "tiny", "huge", "identical", "directional", "big_limits", "second_order",
              "first_order", "velocity_interface", "phase", "discrete", "time_if_necessary",
              "none", "minimum_duration", "per_dof_sync", "per_dof_interface", "zero_limits",
              "step1_property"]
# Categories where trajkit must give Ruckig's motion itself (equal durations and states).
SAME_MOTION = {"phase", "per_dof_sync", "per_dof_interface", "zero_limits"}

# ---------------------------------------------------------------- JSON for trajkit


def to_json(p):
    def num(x):
        if x == INF:
            return "inf"
        if x == -INF:
            return "-inf"
        return x
    q = {}
    for k, v in p.items():
        if k.startswith(("max_", "min_")):
            q[k] = [num(x) for x in v]
        else:
            q[k] = v
    return json.dumps(q)

# ---------------------------------------------------------------- Ruckig


SYNC = {"time": ruckig.Synchronization.Time, "time_if_necessary": ruckig.Synchronization.TimeIfNecessary,
        "phase": ruckig.Synchronization.Phase, "none": ruckig.Synchronization.No}
IFACE = {"position": ruckig.ControlInterface.Position, "velocity": ruckig.ControlInterface.Velocity}


def ruckig_solve(p, dt, times, want_states):
    n = len(p["current_position"])
    inp = ruckig.InputParameter(n)
    for k in ("current_position", "current_velocity", "current_acceleration", "target_position",
              "target_velocity", "target_acceleration", "max_velocity", "max_acceleration", "max_jerk"):
        setattr(inp, k, p[k])
    if "min_velocity" in p:
        inp.min_velocity = p["min_velocity"]
    if "min_acceleration" in p:
        inp.min_acceleration = p["min_acceleration"]
    if "enabled" in p:
        inp.enabled = p["enabled"]
    inp.synchronization = SYNC[p.get("synchronization", "time")]
    inp.control_interface = IFACE[p.get("control_interface", "position")]
    if p.get("duration_discretization") == "discrete":
        inp.duration_discretization = ruckig.DurationDiscretization.Discrete
    if "minimum_duration" in p:
        inp.minimum_duration = p["minimum_duration"]
    if "per_dof_synchronization" in p:
        inp.per_dof_synchronization = [SYNC[s] for s in p["per_dof_synchronization"]]
    if "per_dof_control_interface" in p:
        inp.per_dof_control_interface = [IFACE[s] for s in p["per_dof_control_interface"]]
    otg = ruckig.Ruckig(n, dt)
    traj = ruckig.Trajectory(n)
    try:
        res = otg.calculate(inp, traj)
    except Exception:  # the wheel raises for some errors instead of returning a code
        return None, None, None
    if res not in (ruckig.Result.Working, ruckig.Result.Finished):
        return None, None, None
    states = [traj.at_time(t * traj.duration) for t in times] if want_states else None
    arrives, ends = ruckig_arrives(p, traj)
    if not arrives:
        return "misses", None, None
    return traj.duration, states, ends

# ---------------------------------------------------------------- the independent checker


def integ(p, v, a, j, t):
    return (p + t * (v + t * (a / 2 + t * j / 6)), v + t * (a + t * j / 2), a + t * j)


def check(prob, rec, samples=12):
    """Integrates trajkit's segments from the problem's start state; returns a list of
    problems found (empty when the trajectory holds the limits and reaches the target)."""
    bad = []
    n = len(prob["current_position"])
    iface_all = prob.get("control_interface", "position")
    ifaces = prob.get("per_dof_control_interface", [iface_all] * n)
    enabled = prob.get("enabled", [True] * n)
    for i in range(n):
        if not enabled[i]:
            continue
        d = rec["profiles"][i]
        vmax, vmin, amax, amin, jmax = lims(prob, i)
        order = 3 if jmax < INF else (2 if amax < INF else 1)
        pos_if = ifaces[i] == "position"
        p, v, a = prob["current_position"][i], prob["current_velocity"][i], prob["current_acceleration"][i]
        if order == 2:
            a = d["a0"]
        scale_v = max(abs(v), abs(vmax) if vmax < INF else 0, abs(vmin) if vmin > -INF else 0, 1e-300)
        if abs(d["p0"] - p) > 0 or (order >= 2 and abs(d["v0"] - v) > 0) or (order == 3 and d["a0"] != a):
            bad.append(f"dof {i}: profile does not start at the current state")
        nb = d["brake_segments"]
        # After the brake, values may exceed a limit only by what the brake left.
        vhi, vlo, ahi, alo = vmax, vmin, amax, amin
        excursion = 0.0
        for k, (dur, j, vs, as_) in enumerate(d["segments"]):
            # Continuity is checked (to 1e-9 of the velocity / acceleration scale); the
            # segment's own start values are then used, so that round-off removed by the
            # solver (exact values snapped in) is not integrated over a long cruise. Position
            # is always this integrator's own.
            if order == 3:
                if abs(vs - v) > 1e-9 * scale_v + 1e-12 * abs(v) or abs(as_ - a) > 1e-9 * max(abs(a), abs(amax) if amax < INF else 1, 1e-300):
                    bad.append(f"dof {i}: jump at segment {k} of a third-order profile")
                    break
                v, a = vs, as_
            elif order == 2:
                if abs(vs - v) > 1e-9 * scale_v:
                    bad.append(f"dof {i}: velocity jump at segment {k}")
                    break
                v, a = vs, as_
            else:
                v = vs
            if k == nb:
                vhi, vlo = max(vmax, v), min(vmin, v)
                ahi, alo = max(amax, a), min(amin, a)
            if k >= nb:
                if order == 3 and abs(j) > jmax * (1 + 1e-9):
                    bad.append(f"dof {i}: jerk {j} beyond {jmax}")
                ts = [dur * s / samples for s in range(samples + 1)]
                if j != 0 and 0 < -a / j < dur:
                    ts.append(-a / j)
                for t in ts:
                    pp, vv, aa = integ(p, v, a, j, t)
                    excursion = max(excursion, abs(pp - prob["current_position"][i]))
                    tol_v = 1e-9 * max(abs(vhi), abs(vlo), 1e-300) if pos_if else INF
                    tol_a = 1e-9 * max(abs(ahi), abs(alo), 1e-300)
                    if pos_if and (vv > vhi + tol_v or vv < vlo - tol_v):
                        bad.append(f"dof {i}: velocity {vv} outside [{vlo}, {vhi}] at segment {k}")
                        break
                    if order >= 2 and (aa > ahi + tol_a or aa < alo - tol_a):
                        bad.append(f"dof {i}: acceleration {aa} outside [{alo}, {ahi}] at segment {k}")
                        break
                    # Once back inside, stay inside.
                    if vlo <= vv <= vhi and vv <= vmax and vv >= vmin:
                        pass
            p, v, a = integ(p, v, a, j, dur)
            if k >= nb:
                if vmin <= v <= vmax:
                    vhi, vlo = vmax, vmin
                if amin <= a <= amax:
                    ahi, alo = amax, amin
        # Final state: trajkit's contract, relative to the motion's scale.
        pf, vf, af = prob["target_position"][i], prob["target_velocity"][i], prob["target_acceleration"][i]
        if order == 2:
            a = 0.0
        if order == 1:
            v = vf
        tol_p = position_tolerance(prob["current_position"][i], pf, excursion)
        if pos_if and abs(p - pf) > tol_p:
            bad.append(f"dof {i}: final position {p} misses {pf} by {p - pf:.3e} (tolerance {tol_p:.1e})")
        if order >= 2 and abs(v - vf) > 1e-10 + 1e-13 * scale_v:
            bad.append(f"dof {i}: final velocity {v} misses {vf} by {v - vf:.3e}")
        if order == 3 and abs(a - af) > 1e-10:
            bad.append(f"dof {i}: final acceleration {a} misses {af} by {a - af:.3e}")
    return bad


def position_tolerance(p0, pf, excursion):
    """trajkit's contract: 1e-8 for motions of at least 1e-3, below 1e-5 of the motion's
    scale, plus 16 rounding units (and 1e-14 of the scale for this integrator's own
    round-off)."""
    s = max(abs(pf - p0), excursion)
    tol = 1e-8 if abs(pf - p0) >= 1e-3 else min(1e-8, 1e-5 * s)
    return tol + 16 * EPS * max(abs(p0), abs(pf), s) + 1e-14 * s


class Ends(list):
    """The final positions Ruckig reached (None for DOFs without a position target), with the
    final velocities and accelerations where they miss trajkit's tolerances in `velocity` and
    `acceleration` (None elsewhere)."""


def velocity_tolerance(p, i):
    """The tolerance of a final velocity judged against trajkit's contract (1e-10, and 1e-13 of
    the velocity scale for round-off, as tools/otg_step1_misses.py)."""
    return 1e-10 + 1e-13 * max(abs(p["current_velocity"][i]), abs(p["max_velocity"][i]))


def ruckig_arrives(p, traj):
    """Whether Ruckig's final position meets the same tolerance as trajkit's (relative to the
    motion's scale: Ruckig's own is 1e-8 absolute, so a motion of 1e-11 may end where it
    started), and the final positions it reached
    (None for DOFs without a position target), with the final velocities and accelerations
    that miss trajkit's tolerances (`Ends`; they are not judged here). A DOF that is not synchronized ends at its own
    minimum duration (and then moves on with its target velocity)."""
    n = len(p["current_position"])
    ifaces = p.get("per_dof_control_interface", [p.get("control_interface", "position")] * n)
    syncs = p.get("per_dof_synchronization", [p.get("synchronization", "time")] * n)
    enabled = p.get("enabled", [True] * n)
    mins = traj.independent_min_durations
    ends = Ends([None] * n)
    ends.velocity, ends.acceleration = [None] * n, [None] * n
    for i in range(n):
        if not enabled[i] or ifaces[i] != "position":
            continue
        own = syncs[i] == "none" or (syncs[i] == "time_if_necessary" and p["target_velocity"][i] == 0
                                     and p["target_acceleration"][i] == 0)
        end = traj.at_time(mins[i] if own else traj.duration)
        p0, pf, pe = p["current_position"][i], p["target_position"][i], end[0][i]
        if abs(pe - pf) > position_tolerance(p0, pf, abs(pe - p0)):
            return False, None
        ends[i] = pe
        ve, ae = end[1][i], end[2][i]
        if abs(ve - p["target_velocity"][i]) > velocity_tolerance(p, i):
            ends.velocity[i] = ve
        if abs(ae - p["target_acceleration"][i]) > 1e-10:
            ends.acceleration[i] = ae
    return True, ends


def trajkit_duration(exe, p):
    """trajkit's duration for problem `p` (None when it fails), from the CLI."""
    with tempfile.NamedTemporaryFile("w", suffix=".jsonl", delete=False) as f:
        f.write(to_json(p) + "\n")
    r = subprocess.run([exe, "otg", "--batch", f.name, "--out", "-"], capture_output=True, text=True)
    os.unlink(f.name)
    try:
        rec = json.loads(r.stdout.splitlines()[0])
    except (IndexError, ValueError):
        return None
    return rec["duration"] if rec.get("result") == "working" else None


def by_ruckig_error(exe, p, ends, tr, t):
    """Whether Ruckig (duration `tr`, trajkit's `t`) is shorter only because it stops short of
    the target (within the tolerance): trajkit, given the final positions Ruckig actually
    reached as the target (and the final velocities and accelerations where Ruckig's miss
    trajkit's tolerances, `Ends`: e.g. a single ramp 1.3e-9 off the target velocity, 7.9e-9
    shorter than any profile that reaches it), is at most Ruckig's duration × (1 + 1e-9), and
    Ruckig is shorter by at most 1e-5 of it (the relative position tolerance of the smallest
    motions; a solver that misses a profile by far at one target and finds it at a nearby one
    is not excused). Returns that duration when so."""
    q = json.loads(json.dumps(p))
    changed = False
    for key, new in (("target_position", ends), ("target_velocity", getattr(ends, "velocity", None)),
                     ("target_acceleration", getattr(ends, "acceleration", None))):
        if new is not None and any(e is not None and e != x for e, x in zip(new, q[key])):
            q[key] = [x if e is None else e for e, x in zip(new, q[key])]
            changed = True
    if t > tr * (1 + 1e-5) or not changed:
        return None
    t = trajkit_duration(exe, q)
    return t if t is not None and t <= tr * (1 + 1e-9) + 1e-15 else None


def determined(p, cat):
    """The DOFs whose motion must be Ruckig's: all under phase synchronization; otherwise
    those not planned by step 2 as time-synchronized position DOFs (a profile of a given
    duration is not unique, and Ruckig's choice among them is not part of its contract):
    velocity-interface DOFs, DOFs that are not synchronized, DOFs with a zero limit."""
    n = len(p["current_position"])
    if cat == "phase":
        return range(n)
    ifaces = p.get("per_dof_control_interface", [p.get("control_interface", "position")] * n)
    syncs = p.get("per_dof_synchronization", [p.get("synchronization", "time")] * n)
    out = []
    for i in range(n):
        moving = p["target_velocity"][i] != 0 or p["target_acceleration"][i] != 0
        synced = syncs[i] == "time" or (syncs[i] == "time_if_necessary" and moving)
        zero = p["max_velocity"][i] * p["max_acceleration"][i] * p["max_jerk"][i] == 0
        if ifaces[i] == "velocity" or not synced or zero:
            out.append(i)
    return out


def trajkit_state(prob, rec, t):
    """trajkit's state at t from its segments (integrated here), held after the end."""
    out = []
    for i, d in enumerate(rec["profiles"]):
        p, v, a = d["p0"], d["v0"], d["a0"]
        left = t
        for dur, j, vs, as_ in d["segments"]:
            v, a = vs, as_
            if left <= dur:
                out.append(integ(p, v, a, j, left))
                break
            p, v, a = integ(p, v, a, j, dur)
            left -= dur
        else:
            e = d["end"]
            out.append(integ(e[0], e[1], e[2], 0.0, left))
    return out

# ---------------------------------------------------------------- the sweep


def binary():
    exe = os.path.join(ROOT, "target", "release", "trajkit")
    subprocess.check_call(["cargo", "build", "--release", "-q", "-p", "trajkit-cli"], cwd=ROOT)
    return exe


def run(args):
    cats = args.categories.split(",") if args.categories else CATEGORIES
    os.makedirs(args.out, exist_ok=True)
    exe = args.exe or binary()
    per_cat = max(1, args.count // len(cats))
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    summary = {"ruckig": RUCKIG, "seed": args.seed, "count_per_category": per_cat, "commit": commit,
               "date": time.strftime("%Y-%m-%d %H:%M:%S"), "categories": {}}
    failures = open(os.path.join(args.out, "failures.jsonl"), "w")
    fixture = open(args.fixture, "a") if args.fixture else None
    times = [0.1, 0.3, 0.5, 0.7, 0.9]
    t0 = time.time()
    for ci, cat in enumerate(cats):
        r = random.Random(args.seed * 1000 + CATEGORIES.index(cat))
        st = dict(problems=0, ruckig_ok=0, ruckig_misses_target=0, trajkit_ok=0, trajkit_failed_where_ruckig_ok=0,
                  longer=0, longer_by_ruckig_error=0, equal=0, shorter=0, checker_failures=0, motion_differs=0,
                  worst_ratio=0.0, best_ratio=INF)
        chunk = 20000
        done = 0
        count = REPLAY.get(cat, per_cat)
        while done < count:
            m = min(chunk, count - done)
            probs = []
            for _ in range(m):
                n = r.choice([1, 3, 7])
                probs.append(gen(cat, r, n))
            path = os.path.join(args.out, "batch.jsonl")
            with open(path, "w") as f:
                for p in probs:
                    f.write(to_json(p) + "\n")
            res = os.path.join(args.out, "results.jsonl")
            if os.path.exists(res):
                os.unlink(res)
            run_cli = subprocess.run([exe, "otg", "--batch", path, "--profiles", "--out", res],
                                     stderr=subprocess.PIPE, text=True)
            if run_cli.returncode not in (0, 1):
                # 1: some problems failed (each has its record). Anything else is a crash (a
                # panic exits 101) or a refused batch: stop, never compare stale or partial
                # results.
                sys.exit(f"trajkit otg --batch failed ({run_cli.returncode}) on {path}: "
                         f"{run_cli.stderr.strip()[-2000:]}")
            recs = [json.loads(line) for line in open(res)]
            if len(recs) != len(probs):
                sys.exit(f"trajkit wrote {len(recs)} results for {len(probs)} problems")
            for p, rec in zip(probs, recs):
                st["problems"] += 1
                tr, states, ends = ruckig_solve(p, p.get("dt", 0.001), times, cat in SAME_MOTION)
                if tr == "misses":
                    st["ruckig_misses_target"] += 1
                    tr = None
                ok = rec["result"] == "working"
                reasons = []
                own_end = None
                if tr is not None:
                    st["ruckig_ok"] += 1
                if ok:
                    st["trajkit_ok"] += 1
                    bad = check(p, rec)
                    if bad:
                        st["checker_failures"] += 1
                        reasons += bad[:3]
                if tr is not None and not ok:
                    st["trajkit_failed_where_ruckig_ok"] += 1
                    reasons.append("trajkit failed: " + rec.get("message", ""))
                if tr is not None and ok:
                    t = rec["duration"]
                    ratio = t / tr if tr > 0 else (1.0 if t == 0 else INF)
                    st["worst_ratio"] = max(st["worst_ratio"], ratio)
                    st["best_ratio"] = min(st["best_ratio"], ratio)
                    own_end = (by_ruckig_error(exe, p, ends, tr, t)
                               if t > tr * (1 + 1e-9) + 1e-15 and cat not in SAME_MOTION else None)
                    if own_end is not None:
                        # Ruckig shorter only by stopping short of the target (within the
                        # tolerance): counted apart, and listed.
                        st["longer_by_ruckig_error"] += 1
                        reasons.append(f"longer by Ruckig's error: trajkit {t!r} ruckig {tr!r} "
                                       f"(trajkit to Ruckig's final positions {own_end!r})")
                    elif t > tr * (1 + 1e-9) + 1e-15:
                        st["longer"] += 1
                        reasons.append(f"longer: trajkit {t!r} ruckig {tr!r}")
                    elif t < tr * (1 - 1e-9) - 1e-15:
                        st["shorter"] += 1
                    else:
                        st["equal"] += 1
                    if cat in SAME_MOTION and abs(t - tr) <= 1e-9 * max(tr, 1.0):
                        own = determined(p, cat)
                        for tt, rs in zip(times, states):
                            ks = trajkit_state(p, rec, tt * tr)
                            scale = 1.0 + max(abs(x) for x in p["target_position"] + p["current_position"])
                            if any(abs(ks[i][0] - rs[0][i]) > 1e-7 * scale for i in own):
                                st["motion_differs"] += 1
                                reasons.append(f"state differs at {tt}·T")
                                break
                    elif cat in SAME_MOTION:
                        reasons.append("duration differs")
                if reasons and fixture and tr is not None and any(
                        x.startswith(("longer:", "trajkit failed")) for x in reasons
                    ):
                        fixture.write(json.dumps({"category": cat, "ruckig_duration": tr,
                                                 "problem": json.loads(to_json(p))}) + "\n")
                elif fixture and own_end is not None:
                    # Ruckig shorter by stopping short: with the end positions it reached.
                    line = {"category": cat, "ruckig_duration": tr, "ruckig_end_position": ends}
                    for k in ("velocity", "acceleration"):
                        if any(x is not None for x in getattr(ends, k)):
                            line["ruckig_end_" + k] = getattr(ends, k)
                    line["problem"] = json.loads(to_json(p))  # infinite limits as "inf"
                    fixture.write(json.dumps(line) + "\n")
                if reasons:
                    failures.write(json.dumps({"category": cat, "problem": p, "ruckig_duration": tr,
                                               "trajkit": {k: rec.get(k) for k in ("result", "duration", "message")},
                                               "reasons": reasons}) + "\n")
            done += m
            failures.flush()
        summary["categories"][cat] = st
        print(f"[{time.time() - t0:7.0f} s] {cat:20s} {json.dumps(st)}", flush=True)
    tot = {k: sum(c[k] for c in summary["categories"].values())
           for k in ("problems", "ruckig_ok", "ruckig_misses_target", "trajkit_ok",
                     "trajkit_failed_where_ruckig_ok", "longer", "longer_by_ruckig_error",
                     "checker_failures", "motion_differs")}
    summary["total"] = tot
    summary["seconds"] = round(time.time() - t0, 1)
    json.dump(summary, open(os.path.join(args.out, "summary.json"), "w"), indent=1)
    print(json.dumps(tot))


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=21000, help="problems in all (split over categories)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--categories", default="", help="comma-separated subset")
    ap.add_argument("--out", default="/tmp/otg-sweep")
    ap.add_argument("--fixture", default="", help="append regression problems to this JSONL file")
    ap.add_argument("--exe", default="", help="a trajkit binary to use instead of building one")
    ap.add_argument("--around", default="",
                    help="perturbed copies of the problems of this JSONL file (lines with 'category' and "
                         "'problem', e.g. a failures.jsonl) instead of generated ones")
    ap.add_argument("--replay", default="",
                    help="the problems of this JSONL file themselves, each once (lines with 'category' "
                         "and 'problem')")
    ap.add_argument("--no-venv", action="store_true")
    args = ap.parse_args()
    if args.around:
        use_around(args)
    elif args.replay:
        use_around(args, exact=True)
    run(args)
