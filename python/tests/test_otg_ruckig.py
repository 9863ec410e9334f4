"""trajkit.otg against the ruckig wheel: the same seeded random problems through both.

Durations must agree within 1e-9 (relative to the duration, at least 1e-9 absolute) on every
problem Ruckig solves; the API (names, return types, errors) must be Ruckig's.
"""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

ruckig = pytest.importorskip("ruckig")
import trajkit  # noqa: E402
from trajkit import otg as tk  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
N_PROBLEMS = int(os.environ.get("TRAJKIT_OTG_PROBLEMS", "3000"))


def random_problem(rng, mod, dofs, kind):
    inp = mod.InputParameter(dofs)
    vmax = rng.uniform(0.5, 4.0, dofs)
    amax = rng.uniform(0.5, 8.0, dofs)
    jmax = rng.uniform(1.0, 40.0, dofs)
    inp.current_position = list(rng.uniform(-5, 5, dofs))
    inp.target_position = list(rng.uniform(-5, 5, dofs))
    if kind == "general":
        # States within the limits (Ruckig's target states must be).
        inp.current_velocity = list(rng.uniform(-0.9, 0.9, dofs) * vmax)
        inp.current_acceleration = list(rng.uniform(-0.9, 0.9, dofs) * amax)
        inp.target_velocity = list(rng.uniform(-0.5, 0.5, dofs) * vmax)
        inp.target_acceleration = list(rng.uniform(-0.3, 0.3, dofs) * amax)
    inp.max_velocity = list(vmax)
    inp.max_acceleration = list(amax)
    inp.max_jerk = list(jmax)
    return inp


def same_problem(mod, src):
    inp = mod.InputParameter(src.degrees_of_freedom)
    for f in ["current_position", "current_velocity", "current_acceleration",
              "target_position", "target_velocity", "target_acceleration",
              "max_velocity", "max_acceleration", "max_jerk"]:
        setattr(inp, f, list(getattr(src, f)))
    return inp


@pytest.mark.parametrize("kind", ["rest", "general"])
def test_durations_match_ruckig(kind):
    rng = np.random.default_rng(17 if kind == "rest" else 18)
    compared, worst = 0, 0.0
    failures = []
    for k in range(N_PROBLEMS // 2):
        dofs = [1, 3, 7][k % 3]
        a = random_problem(rng, ruckig, dofs, kind)
        b = same_problem(tk, a)
        tr_r, tr_t = ruckig.Trajectory(dofs), tk.Trajectory(dofs)
        try:
            res = ruckig.Ruckig(dofs, 0.001).calculate(a, tr_r)
        except ruckig.RuckigError:
            continue
        if res != ruckig.Result.Working:
            continue
        tk.Ruckig(dofs, 0.001).calculate(b, tr_t)
        d_r, d_t = tr_r.duration, tr_t.duration
        err = abs(d_r - d_t) / max(1.0, d_r)
        worst = max(worst, err)
        compared += 1
        if err > 1e-9:
            failures.append((k, dofs, d_r, d_t))
    print(f"{kind}: {compared} problems compared, worst relative difference {worst:.2e}")
    assert compared >= 0.9 * (N_PROBLEMS // 2)
    assert not failures, f"{len(failures)} differ, first: {failures[:5]}"


def test_api_matches_ruckig_on_the_readme_problem():
    out = {}
    for mod in (ruckig, tk):
        otg = mod.Ruckig(3, 0.01)
        inp = mod.InputParameter(3)
        inp.current_position = [0.0, 0.0, 0.5]
        inp.current_velocity = [0.0, -2.2, -0.5]
        inp.current_acceleration = [0.0, 2.5, -0.5]
        inp.target_position = [5.0, -2.0, -3.5]
        inp.target_velocity = [0.0, -0.5, -2.0]
        inp.target_acceleration = [0.0, 0.0, 0.5]
        inp.max_velocity = [3.0, 1.0, 3.0]
        inp.max_acceleration = [3.0, 2.0, 1.0]
        inp.max_jerk = [4.0, 3.0, 2.0]
        tr = mod.Trajectory(3)
        assert otg.calculate(inp, tr) == mod.Result.Working
        p, v, a = tr.at_time(1.0)
        assert isinstance(p, list) and len(p) == 3
        ext = tr.position_extrema
        out[mod.__name__] = dict(
            duration=tr.duration, at=(p, v, a),
            mins=tr.independent_min_durations,
            ext=[(b.min, b.max) for b in ext],
            first=tr.get_first_time_at_position(0, 1.0),
            none=tr.get_first_time_at_position(0, 50.0),
        )
        o = mod.OutputParameter(3)
        steps, res = 0, mod.Result.Working
        while res == mod.Result.Working:
            res = otg.update(inp, o)
            if steps == 0:
                assert o.new_calculation
            o.pass_to_input(inp)
            steps += 1
        assert res == mod.Result.Finished and not o.new_calculation
        out[mod.__name__]["steps"] = steps
        out[mod.__name__]["final"] = list(o.new_position)
    r, t = out["ruckig"], out["trajkit.otg"]
    assert abs(r["duration"] - t["duration"]) < 1e-12
    assert r["steps"] == t["steps"]
    assert np.allclose(r["at"], t["at"], atol=1e-9)
    assert np.allclose(r["mins"], t["mins"], atol=1e-9)
    assert np.allclose(r["ext"], t["ext"], atol=1e-9)
    assert abs(r["first"] - t["first"]) < 1e-9 and t["none"] is None
    assert np.allclose(r["final"], t["final"], atol=1e-9)


def test_update_finishes_after_the_cycle_landing_on_the_duration():
    # 5 s at dt = 0.25 s (exact sums): Working up to cycle 20 at time 5.0 (on the target),
    # Finished at cycle 21; every cycle reports its wall-clock time, calculating or not.
    seen = {}
    for mod in (ruckig, tk):
        otg, inp, o = mod.Ruckig(1, 0.25), mod.InputParameter(1), mod.OutputParameter(1)
        inp.target_position = [1.0]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1.0], [1.0], [1.0]
        inp.minimum_duration = 5.0
        cycles = []
        for _ in range(30):
            res = otg.update(inp, o)
            cycles.append((res, o.time, o.new_position[0], o.calculation_duration))
            o.pass_to_input(inp)
            if res != mod.Result.Working:
                break
        assert len(cycles) == 21 and cycles[-1][0] == mod.Result.Finished
        assert cycles[19][1] == 5.0 and abs(cycles[19][2] - 1.0) < 1e-9
        assert all(c[3] > 0.0 for c in cycles)
        seen[mod.__name__] = [(c[1], c[2]) for c in cycles]
    assert np.allclose(seen["ruckig"], seen["trajkit.otg"], atol=1e-9)


def test_invalid_input_raises_ruckig_error_with_trajkit_message():
    otg = tk.Ruckig(1, 0.01)
    inp = tk.InputParameter(1)
    inp.target_position = [1.0]
    inp.max_velocity = [1.0]
    inp.max_acceleration = [1.0]
    inp.max_jerk = [-1.0]
    with pytest.raises(tk.RuckigError, match=r"max_jerk\[0\] = -1") as e:
        otg.calculate(inp, tk.Trajectory(1))
    assert isinstance(e.value, ValueError) and isinstance(e.value, trajkit.TrajkitError)
    assert e.value.result == tk.Result.ErrorInvalidInput
    assert e.value.kind == "invalid_input" and e.value.dof == 0
    with pytest.raises(trajkit.TrajkitError):
        otg.update(inp, tk.OutputParameter(1))
    inp.max_jerk = [float("nan")]
    with pytest.raises(trajkit.TrajkitError, match="max_jerk"):
        otg.calculate(inp, tk.Trajectory(1))
    with pytest.raises(trajkit.TrajkitError, match="degrees of freedom"):
        tk.Ruckig(2, 0.01).calculate(inp, tk.Trajectory(1))
    with pytest.raises(trajkit.TrajkitError, match="per_section_min_velocity"):
        inp.per_section_min_velocity = [[-1.0]]  # refused by name, not silently ignored


def test_enums_and_options():
    assert tk.Synchronization.No != tk.Synchronization.Time
    assert int(tk.Result.Working) == 0 and int(tk.Result.ErrorInvalidInput) == -100
    for mode_r, mode_t in [(ruckig.Synchronization.Time, tk.Synchronization.Time),
                           (ruckig.Synchronization.No, tk.Synchronization.No),
                           (ruckig.Synchronization.TimeIfNecessary, tk.Synchronization.TimeIfNecessary)]:
        d = []
        for mod, mode in ((ruckig, mode_r), (tk, mode_t)):
            inp = mod.InputParameter(2)
            inp.target_position = [1.0, 3.0]
            inp.max_velocity = [1.0, 1.0]
            inp.max_acceleration = [1.0, 1.0]
            inp.max_jerk = [1.0, 1.0]
            inp.synchronization = mode
            tr = mod.Trajectory(2)
            mod.Ruckig(2, 0.01).calculate(inp, tr)
            d.append((tr.duration, tr.at_time(1.0)[0]))
        assert abs(d[0][0] - d[1][0]) < 1e-9 and np.allclose(d[0][1], d[1][1], atol=1e-9)
    # Velocity interface and minimum duration and discrete durations.
    for mod in (ruckig, tk):
        inp = mod.InputParameter(1)
        inp.control_interface = mod.ControlInterface.Velocity
        inp.target_velocity = [1.0]
        inp.max_velocity = [2.0]
        inp.max_acceleration = [1.0]
        inp.max_jerk = [1.0]
        inp.minimum_duration = 3.0
        inp.duration_discretization = mod.DurationDiscretization.Discrete
        tr = mod.Trajectory(1)
        mod.Ruckig(1, 0.1).calculate(inp, tr)
        d.append(tr.duration)
    assert abs(d[-1] - d[-2]) < 1e-9 and abs(d[-1] / 0.1 - round(d[-1] / 0.1)) < 1e-9


def test_ruckig_example_runs_after_changing_its_import(tmp_path):
    src = open(os.path.join(HERE, "..", "examples", "ruckig_position.py")).read()
    assert "from ruckig import" in src
    ported = tmp_path / "ported.py"
    ported.write_text(src.replace("from ruckig import", "from trajkit.otg import"))
    original = tmp_path / "original.py"
    original.write_text(src)
    run = lambda p: subprocess.run([sys.executable, str(p)], capture_output=True, text=True,
                                   check=True).stdout
    a, b = run(original), run(ported)
    la, lb = a.strip().splitlines(), b.strip().splitlines()
    assert len(la) == len(lb) and len(la) > 10
    # Same samples to printing precision except the measured calculation time.
    diff = [(x, y) for x, y in zip(la, lb) if x != y and "Calculation duration" not in x]
    assert not diff, diff[:3]


def test_vectorized_evaluation_and_pickling():
    import pickle
    inp = tk.InputParameter(2)
    inp.target_position = [1.0, -2.0]
    inp.max_velocity = [1.0, 1.0]
    inp.max_acceleration = [2.0, 2.0]
    inp.max_jerk = [5.0, 5.0]
    tr = tk.Trajectory(2)
    tk.Ruckig(2, 0.001).calculate(inp, tr)
    t = np.linspace(0, tr.duration, 7)
    q = tr(t)
    assert q.shape == (7, 2)
    for i, ti in enumerate(t):
        assert np.allclose(q[i], tr.at_time(ti)[0], atol=1e-15)
    tr2 = pickle.loads(pickle.dumps(tr))
    assert tr2.duration == tr.duration
    inp2 = pickle.loads(pickle.dumps(inp))
    assert inp2 == inp and inp2.target_position == [1.0, -2.0]


def per_dof_problem(rng, mod, dofs, syncs, ifaces):
    inp = random_problem(rng, mod, dofs, "general")
    # Velocity control aims at a velocity within the limits.
    inp.per_dof_synchronization = [getattr(mod.Synchronization, s) for s in syncs]
    inp.per_dof_control_interface = [getattr(mod.ControlInterface, c) for c in ifaces]
    return inp


def test_per_dof_options_match_ruckig():
    """Per-DOF synchronization and control interface: durations within 1e-9 of Ruckig's on
    seeded random problems, and the options survive pickling."""
    import pickle
    rng = np.random.default_rng(23)
    names = ["Time", "TimeIfNecessary", "Phase", "No"]
    compared = 0
    for k in range(600):
        dofs = [2, 3, 7][k % 3]
        syncs = [names[i] for i in rng.integers(0, 4, dofs)]
        ifaces = ["Velocity" if x < 0.3 else "Position" for x in rng.uniform(0, 1, dofs)]
        a = per_dof_problem(rng, ruckig, dofs, syncs, ifaces)
        b = same_problem(tk, a)
        b.per_dof_synchronization = [getattr(tk.Synchronization, s) for s in syncs]
        b.per_dof_control_interface = [getattr(tk.ControlInterface, c) for c in ifaces]
        assert pickle.loads(pickle.dumps(b)) == b
        tr_r, tr_t = ruckig.Trajectory(dofs), tk.Trajectory(dofs)
        try:
            ruckig.Ruckig(dofs, 0.001).calculate(a, tr_r)
        except ruckig.RuckigError:
            continue
        tk.Ruckig(dofs, 0.001).calculate(b, tr_t)
        d = tr_r.duration
        assert abs(tr_t.duration - d) <= 1e-9 * max(1.0, d), (k, syncs, ifaces, tr_t.duration, d)
        compared += 1
    assert compared > 500


def test_first_time_at_position_after_matches_ruckig():
    """At or after `time_after`, at the position, the first such time on trajkit's own
    trajectory; equal to Ruckig's where the two trajectories of the DOF coincide
    (synchronized DOFs may take different profiles of the same duration) and start without a
    brake."""
    rng = np.random.default_rng(31)
    checked = compared = 0
    for k in range(300):
        a = random_problem(rng, ruckig, 3, "general")
        b = same_problem(tk, a)
        tr_r, tr_t = ruckig.Trajectory(3), tk.Trajectory(3)
        ruckig.Ruckig(3, 0.001).calculate(a, tr_r)
        tk.Ruckig(3, 0.001).calculate(b, tr_t)
        T = tr_t.duration
        grid = np.linspace(0, T, 201)
        q = tr_t(grid)[:, 0]
        # Ruckig's answer leaves out the brake before the profile (its time is then the brake's
        # duration early, at another position): compared without one.
        same = tr_t.profiles[0][0].brake_duration == 0.0 and all(
            abs(tr_r.at_time(float(x))[0][0] - y) < 1e-7 for x, y in zip(grid[::10], q[::10]))
        lo, hi = tr_t.position_extrema[0].min, tr_t.position_extrema[0].max
        for _ in range(4):
            p = float(rng.uniform(lo, hi))
            after = float(rng.uniform(0, T))
            got = tr_t.get_first_time_at_position(0, p, after)
            later = grid[grid >= after]
            side = np.sign(tr_t(later)[:, 0] - p)
            if got is None:
                assert np.all(side == side[0]) or np.min(np.abs(tr_t(later)[:, 0] - p)) < 1e-9
                continue
            assert after <= got <= T + 1e-12
            assert abs(tr_t.at_time(got)[0][0] - p) < 1e-9
            before = later[later < got - 1e-9]
            if len(before):
                s = np.sign(tr_t(before)[:, 0] - p)
                assert np.all(s == s[0]), (k, p, after, got)
            checked += 1
            if same:
                want = tr_r.get_first_time_at_position(0, p, after)
                assert want is not None and abs(got - want) < 1e-7 * max(1.0, want), (k, p, after, want, got)
                compared += 1
    assert checked > 500 and compared > 200, (checked, compared)


def test_validate_input_profiles_and_sections_like_ruckig():
    for mod in (ruckig, tk):
        inp = mod.InputParameter(2)
        inp.current_position, inp.target_position = [0.0, 1.0], [1.0, -1.0]
        inp.current_velocity = [1.5, 0.0]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1.0, 1.0], [2.0, 2.0], [10.0, 10.0]
        otg = mod.Ruckig(2, 0.01)
        assert otg.validate_input(inp) is True
        assert otg.validate_input(inp, False, True) is True
        with pytest.raises(mod.RuckigError, match="velocity"):
            otg.validate_input(inp, True, True)
        inp.current_velocity = [0.5, 0.0]
        inp.target_acceleration = [0.0, 3.0]
        with pytest.raises(mod.RuckigError, match="acceleration"):
            otg.validate_input(inp)
        if mod is ruckig:
            assert otg.validate_input(inp, False, False) is True
        else:
            # trajkit's calculation refuses a target acceleration outside the limits, so its
            # validation does too, whatever the flags.
            with pytest.raises(mod.RuckigError, match="target_acceleration"):
                otg.validate_input(inp, False, False)
        inp.target_acceleration = [0.0, 0.0]
        inp.max_jerk = [10.0, -1.0]
        with pytest.raises(mod.RuckigError, match="jerk"):
            otg.validate_input(inp)
        inp.max_jerk = [10.0, 10.0]
        tr = mod.Trajectory(2)
        otg.calculate(inp, tr)
        assert len(tr.intermediate_durations) == 1
        assert tr.intermediate_durations[0] == pytest.approx(tr.duration)
        assert len(tr.profiles) == 1 and len(tr.profiles[0]) == 2
        if mod is tk:
            for dof, pr in enumerate(tr.profiles[0]):
                assert pr.t_sum[-1] == pytest.approx(tr.duration, abs=1e-12)
                assert np.allclose(np.cumsum(pr.t), pr.t_sum)
                assert len(pr.p) == len(pr.t) + 1 == len(pr.j) + 1
                assert pr.pf == pytest.approx(inp.target_position[dof], abs=1e-9)
                # Each segment integrates to the next start state.
                for k in range(len(pr.t)):
                    d = pr.t[k]
                    p1 = pr.p[k] + pr.v[k] * d + pr.a[k] * d * d / 2 + pr.j[k] * d ** 3 / 6
                    assert p1 == pytest.approx(pr.p[k + 1], abs=1e-9)
