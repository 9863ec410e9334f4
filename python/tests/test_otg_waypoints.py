"""trajkit.otg: Ruckig Pro's intermediate waypoints and the JSON problem format from Python.

Seeded random 7-DOF problems through 1-6 waypoints (bent joint-space paths, random
states at the ends): the motion passes every waypoint at the end of its section (to the
generator's tolerance), holds every limit, per-section ones included, at dense samples,
and is never longer than stopping at every waypoint (computed here independently: one
trajkit calculation per section, at rest at each waypoint). `update` follows the motion to
the end without a new calculation while the output is fed back. Bad fields raise
`TrajkitError` with the library's message (the one the command line prints). A problem
written with `InputParameter.to_json` reads back equal, and the command line reads the same
file to the same duration.
"""
import json
import pathlib
import pickle
import subprocess
import sys
import copy

import numpy as np
import pytest

import trajkit
from trajkit import otg as tk
from test_plan import cli  # the trajkit CLI binary, as test_plan finds it

TOL = 1e-8


def waypoint_problem(rng, dofs=7, waypoints=None, rest=False):
    """A bent path: waypoints spread along a random direction with sideways offsets."""
    m = int(rng.integers(1, 7)) if waypoints is None else waypoints
    inp = tk.InputParameter(dofs)
    start = rng.uniform(-1, 1, dofs)
    step = rng.uniform(0.3, 1.0, dofs) * rng.choice([-1, 1], dofs)
    pts = [start + (k + 1) * step + rng.uniform(-0.3, 0.3, dofs) for k in range(m + 1)]
    inp.current_position = list(start)
    inp.intermediate_positions = np.array(pts[:-1])  # a 2-D array is accepted
    inp.target_position = list(pts[-1])
    vmax = rng.uniform(0.5, 2.0, dofs)
    amax = rng.uniform(1.0, 5.0, dofs)
    jmax = rng.uniform(5.0, 40.0, dofs)
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = list(vmax), list(amax), list(jmax)
    if not rest:
        inp.current_velocity = list(rng.uniform(-0.3, 0.3, dofs) * vmax)
        inp.target_velocity = list(rng.uniform(-0.3, 0.3, dofs) * vmax)
    return inp


def calculate(inp, dt=0.001):
    tr = tk.Trajectory(inp.degrees_of_freedom)
    assert tk.Ruckig(inp.degrees_of_freedom, dt).calculate(inp, tr) == tk.Result.Working
    return tr


def section_limits(inp, s):
    """Velocity, acceleration and jerk limits of section `s`."""
    out = []
    for name in ["max_velocity", "max_acceleration", "max_jerk"]:
        per = getattr(inp, "per_section_" + name)
        out.append(np.array(per[s] if per is not None else getattr(inp, name)))
    return out


def stop_at_every_waypoint(inp):
    """The duration of stopping at every waypoint: one calculation per section."""
    pts = [inp.current_position] + inp.intermediate_positions + [inp.target_position]
    total = 0.0
    for s in range(len(pts) - 1):
        sec = tk.InputParameter(inp.degrees_of_freedom)
        sec.current_position, sec.target_position = pts[s], pts[s + 1]
        if s == 0:
            sec.current_velocity = inp.current_velocity
            sec.current_acceleration = inp.current_acceleration
        if s == len(pts) - 2:
            sec.target_velocity = inp.target_velocity
            sec.target_acceleration = inp.target_acceleration
        sec.max_velocity, sec.max_acceleration, sec.max_jerk = map(list, section_limits(inp, s))
        if inp.per_section_minimum_duration is not None:
            sec.minimum_duration = inp.per_section_minimum_duration[s]
        total += calculate(sec).duration
    return total


def assert_valid(inp, tr):
    ends = tr.intermediate_durations
    m = len(inp.intermediate_positions)
    assert len(ends) == m + 1 and len(tr.profiles) == m + 1
    assert ends[-1] == tr.duration and np.all(np.diff([0.0] + ends) > 0)
    for k, w in enumerate(inp.intermediate_positions):
        p, v, a, section = tr.at_time(ends[k], return_section=True)
        assert np.allclose(p, w, atol=TOL, rtol=0), (k, p, w)
        assert section == k + 1
        assert np.allclose(a, 0.0, atol=1e-9)  # the method's waypoint states: a = 0
    p, v, a = tr.at_time(tr.duration)
    assert np.allclose(p, inp.target_position, atol=TOL, rtol=0)
    assert np.allclose(v, inp.target_velocity, atol=TOL, rtol=0)
    starts = [0.0] + ends[:-1]
    for s in range(m + 1):
        vmax, amax, jmax = section_limits(inp, s)
        t = np.linspace(starts[s], ends[s], 401)[1:-1]
        assert np.all(np.abs(tr(t, 1)) <= vmax * (1 + 1e-9) + 1e-12)
        assert np.all(np.abs(tr(t, 2)) <= amax * (1 + 1e-9) + 1e-12)
        assert np.all(np.abs(tr(t, 3)) <= jmax * (1 + 1e-9))
    # Continuous position, velocity and acceleration across each waypoint.
    for e in ends[:-1]:
        for order in range(3):
            lo, hi = tr(np.array([e - 1e-9, e + 1e-9]), order)
            assert np.allclose(lo, hi, atol=1e-6)


def test_waypoints_pass_hold_limits_and_beat_stopping():
    rng = np.random.default_rng(1707)
    ratios = []
    for _ in range(40):
        inp = waypoint_problem(rng)
        tr = calculate(inp)
        assert_valid(inp, tr)
        stop = stop_at_every_waypoint(inp)
        assert tr.duration <= stop * (1 + 1e-9), (tr.duration, stop)
        ratios.append(tr.duration / stop)
    print(f"duration / stopping at every waypoint: median {np.median(ratios):.3f}, "
          f"max {max(ratios):.3f}")
    assert np.median(ratios) < 1.0  # bent paths: not stopping pays off


def test_per_section_limits_and_minimum_durations():
    rng = np.random.default_rng(1708)
    for _ in range(10):
        inp = waypoint_problem(rng, dofs=3, waypoints=2, rest=True)
        v = np.array(inp.max_velocity)
        inp.per_section_max_velocity = [list(v), list(0.4 * v), list(v)]
        inp.per_section_max_acceleration = np.array([inp.max_acceleration] * 3) * [[1], [0.5], [1]]
        inp.per_section_max_jerk = [inp.max_jerk] * 3
        free = calculate(inp)
        last = free.intermediate_durations[2] - free.intermediate_durations[1]
        inp.per_section_minimum_duration = [0.0, 0.0, 2 * last]
        tr = calculate(inp)
        assert_valid(inp, tr)
        assert tr.duration <= stop_at_every_waypoint(inp) * (1 + 1e-9)
        ends = [0.0] + tr.intermediate_durations
        assert ends[3] - ends[2] >= inp.per_section_minimum_duration[2] * (1 - 1e-9)


def test_update_follows_the_waypoints_like_ruckig_pro():
    inp = tk.InputParameter(3, 10)
    inp.current_position = [0.2, 0, -0.3]
    inp.current_velocity = [0, 0.2, 0]
    inp.current_acceleration = [0, 0.6, 0]
    inp.intermediate_positions = [[1.4, -1.6, 1.0], [-0.6, -0.5, 0.4], [-0.4, -0.35, 0.0],
                                  [0.8, 1.8, -0.1]]
    inp.target_position = [0.5, 1, 0]
    inp.target_velocity = [0.2, 0, 0.3]
    inp.target_acceleration = [0, 0.1, -0.1]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1, 2, 1], [3, 2, 2], [6, 10, 20]
    reference = calculate(inp, 0.01)
    otg, out = tk.Ruckig(3, 0.01, 10), tk.OutputParameter(3, 10)
    res, steps, calculations, changes = tk.Result.Working, 0, 0, []
    while res == tk.Result.Working:
        res = otg.update(inp, out)
        steps += 1
        calculations += out.new_calculation
        p, v, a = reference.at_time(out.time)
        assert np.allclose(out.new_position, p, atol=1e-12)
        assert np.allclose(out.new_velocity, v, atol=1e-12)
        if out.did_section_change:
            changes.append((out.new_section, len(inp.intermediate_positions)))
        out.pass_to_input(inp)
    assert res == tk.Result.Finished and calculations == 1
    assert steps == int(np.floor(reference.duration / 0.01)) + 1
    # Each passed waypoint is removed from the input, as in Ruckig Pro.
    assert changes == [(1, 4), (2, 3), (3, 2), (4, 1), (5, 0)]
    assert inp.intermediate_positions == []
    assert out.trajectory.duration == reference.duration
    # A new target restarts from the current state (no waypoints left: the plain generator).
    inp.target_position = [0.0, 0.0, 0.0]
    otg.update(inp, out)
    assert out.new_calculation and out.new_section == 0


def outside(inp):
    """Position limits that hold the ends and the second waypoint but not the first."""
    pts = np.array([inp.current_position, inp.target_position] + inp.intermediate_positions)
    inp.max_position = list(pts.max(axis=0) + 0.1)
    inp.min_position = list(pts.min(axis=0) - 0.1)
    w = inp.intermediate_positions
    w[0][0] = inp.max_position[0] + 1.0
    inp.intermediate_positions = w


def test_bad_fields_raise_the_library_message():
    base = waypoint_problem(np.random.default_rng(5), dofs=2, waypoints=2, rest=True)
    cases = {
        "intermediate_positions": lambda i: setattr(i, "intermediate_positions", [[0.0, 1.0, 2.0]]),
        "duplicate": lambda i: setattr(i, "intermediate_positions",
                                       [i.intermediate_positions[0]] * 2),
        "per_section_max_velocity": lambda i: setattr(i, "per_section_max_velocity", [[1.0, 1.0]]),
        "per_section_max_jerk": lambda i: setattr(i, "per_section_max_jerk",
                                                  [[1.0, 1.0], [1.0, -2.0], [1.0, 1.0]]),
        "per_section_minimum_duration": lambda i: setattr(i, "per_section_minimum_duration",
                                                          [0.0, float("nan"), 0.0]),
        "minimum_duration": lambda i: setattr(i, "minimum_duration", 1.0),
        "synchronization": lambda i: setattr(i, "synchronization", tk.Synchronization.No),
        "outside": outside,
    }
    exe = cli()
    assert tk.Ruckig(2, 0.01).validate_input(base, True, True)
    for name, spoil in cases.items():
        inp = pickle.loads(pickle.dumps(base))
        spoil(inp)
        with pytest.raises(trajkit.TrajkitError) as e:
            calculate(inp)
        msg = str(e.value)
        field = {"duplicate": "intermediate_positions", "outside": "intermediate_positions"}
        assert field.get(name, name) in msg, msg
        # Ruckig's validate_input checks the waypoints too, with calculate's message.
        for flags in [(False, True), (True, True)]:
            with pytest.raises(trajkit.TrajkitError) as v:
                tk.Ruckig(2, 0.01).validate_input(inp, *flags)
            assert str(v.value) == msg and v.value.kind == e.value.kind
        assert e.value.result in (tk.Result.ErrorInvalidInput, tk.Result.Error)
        with pytest.raises(trajkit.TrajkitError):
            tk.Ruckig(2, 0.01).update(inp, tk.OutputParameter(2))
        if exe and name != "per_section_minimum_duration":  # NaN has no JSON form
            try:
                text = inp.to_json()
            except trajkit.TrajkitError:
                continue
            r = subprocess.run([exe, "otg", "-"], input=text, capture_output=True, text=True)
            try:
                tk.read_problem(text, "<stdin>")
            except trajkit.TrajkitError as read_error:
                # A shape the reader refuses first: the reader's message, as the CLI's.
                msg = f"trajkit: {read_error}"
            assert r.returncode == 2 and r.stderr.strip().endswith(msg), (r.stderr, msg)
    # Ruckig Pro's fields trajkit does not support: refused by name, never ignored.
    for name in ["per_section_min_velocity", "per_section_min_acceleration",
                 "per_section_max_position", "per_section_min_position"]:
        inp = tk.InputParameter(2)
        with pytest.raises(trajkit.TrajkitError, match=name + "': is a Ruckig"):
            setattr(inp, name, [[-1.0, -1.0]])
        setattr(inp, name, None)  # Ruckig's default is accepted
        assert getattr(inp, name) is None


def test_pickle_and_batch_with_waypoints():
    rng = np.random.default_rng(1709)
    inputs = [waypoint_problem(rng, dofs=3) for _ in range(6)]
    bad = pickle.loads(pickle.dumps(inputs[0]))
    bad.intermediate_positions = [bad.current_position]
    results = trajkit.batch.otg(inputs + [bad], delta_time=0.001, threads=2)
    assert isinstance(results[-1], trajkit.TrajkitError)
    for inp, tr in zip(inputs, results):
        assert pickle.loads(pickle.dumps(inp)) == inp
        one = calculate(inp)
        assert tr.duration == one.duration
        back = pickle.loads(pickle.dumps(tr))
        assert back.duration == tr.duration
        assert back.intermediate_durations == tr.intermediate_durations
        t = np.linspace(0, tr.duration, 50)
        assert np.array_equal(back(t), tr(t))


def test_json_round_trip_equals_the_cli_reading(tmp_path):
    rng = np.random.default_rng(1710)
    exe = cli()
    for k in range(8):
        inp = waypoint_problem(rng, dofs=3)
        if k % 2:
            inp.per_section_max_velocity = [list(np.array(inp.max_velocity) * 0.8)] * (
                len(inp.intermediate_positions) + 1)
            inp.per_section_max_jerk = [[float("inf")] * 3] * (len(inp.intermediate_positions) + 1)
            inp.max_position = [10.0, float("inf"), 10.0]
        text = inp.to_json(delta_time=0.002, indent=2)
        back, dt = tk.read_problem(text)
        assert back == inp and dt == 0.002
        assert tk.InputParameter.from_json(text) == inp
        path = tmp_path / f"p{k}.json"
        path.write_text(text)
        loaded, dt2 = tk.load_problem(path)
        assert loaded == inp and dt2 == 0.002
        tr = calculate(inp, 0.002)
        if exe:
            r = subprocess.run([exe, "otg", str(path), "--out", str(tmp_path / "a.json")],
                               capture_output=True, text=True, check=True)
            answer = json.loads((tmp_path / "a.json").read_text())
            assert answer["duration"] == tr.duration
            # Section ends are cumulative sums here: equal to rounding.
            assert np.allclose(answer["section_durations"],
                               np.diff([0.0] + tr.intermediate_durations), rtol=0, atol=1e-12)
    # Plain problems too, with every option written.
    inp = tk.InputParameter(2)
    inp.current_position, inp.target_position = [0.0, 1.0], [1.0, 0.0]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1.0, 1.0], [2.0, float("inf")], [5.0, 5.0]
    inp.min_velocity = [-0.5, float("-inf")]
    inp.synchronization = tk.Synchronization.Phase
    inp.per_dof_control_interface = [tk.ControlInterface.Position, tk.ControlInterface.Position]
    inp.minimum_duration = 3.0
    inp.interrupt_calculation_duration = 1000.0
    back, dt = tk.read_problem(inp.to_json())
    assert back == inp and dt == 0.001
    # The reader's messages are the command line's.
    text = '{"current_position":[0],"target_position":[1],"max_velocity":[1],"max_acceleration":[1],"max_jerks":[1]}'
    with pytest.raises(trajkit.TrajkitError) as e:
        tk.read_problem(text, "p.json")
    assert str(e.value) == "p.json field 'max_jerks': is not a known field (did you mean 'max_jerk'?)"
    if exe:
        path = tmp_path / "bad.json"
        path.write_text(text)
        r = subprocess.run([exe, "otg", str(path)], capture_output=True, text=True)
        with pytest.raises(trajkit.TrajkitError) as e:
            tk.load_problem(path)
        assert r.returncode == 2 and r.stderr.strip() == f"trajkit: {e.value}"
    # Values JSON cannot hold are refused by name.
    inp.current_velocity = [float("nan"), 0.0]
    with pytest.raises(trajkit.TrajkitError, match=r"current_velocity\[0\] = NaN"):
        inp.to_json()


def test_ruckig_waypoint_example_runs_unchanged():
    import copy
    import sys
    script = pathlib.Path(__file__).resolve().parents[1] / "examples" / "ruckig_waypoints.py"
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                       timeout=120, check=True)
    lines = r.stdout.strip().splitlines()
    last = [float(x) for x in lines[-4].split("\t")[1:]]
    assert np.allclose(last, [0.5, 1.0, 0.0], atol=0.01)  # one control period past the end
    assert lines[-2].startswith("Trajectory duration:")
    # copy(out) keeps its own trajectory (Ruckig's __copy__).
    inp = waypoint_problem(np.random.default_rng(3), dofs=2, waypoints=1, rest=True)
    otg, out = tk.Ruckig(2, 0.01), tk.OutputParameter(2)
    otg.update(inp, out)
    kept = copy.copy(out)
    inp.intermediate_positions = []
    otg.update(inp, out)
    assert kept.trajectory.duration != out.trajectory.duration
    assert len(kept.trajectory.intermediate_durations) == 2


def test_sections_without_waypoints_as_in_ruckig():
    ruckig = pytest.importorskip("ruckig")
    for mod in (ruckig, tk):
        inp = mod.InputParameter(2)
        inp.current_position, inp.target_position = [0.0, 1.0], [1.0, -1.0]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1.0, 1.0], [2.0, 2.0], [10.0, 10.0]
        tr = mod.Trajectory(2)
        mod.Ruckig(2, 0.01).calculate(inp, tr)
        d = tr.duration
        sections = [tr.at_time(t, return_section=True)[3] for t in [0.0, d / 2, d, d + 1.0]]
        assert sections == [0, 0, 1, 1], (mod.__name__, sections)


def follow_with_budget(inp, dt):
    """Ruckig Pro's online loop on `inp` (it has a budget): returns the inputs of the
    calculations with their trajectories, every output state, and the sections passed."""
    otg, out = tk.Ruckig(inp.degrees_of_freedom, dt), tk.OutputParameter(inp.degrees_of_freedom)
    plans, states, passed, res = [], [], 0, tk.Result.Working
    # The budget is wall-clock time: on a busy machine even stopping at every waypoint can miss
    # it, and then the first calculation is refused as interrupted (what the library promises);
    # the first update is tried again, a few times at most.
    for attempt in range(5):
        try:
            res = otg.update(inp, out)
            break
        except trajkit.TrajkitError as e:
            if e.kind != "interrupted" or attempt == 4:
                raise
    while True:
        if out.new_calculation:
            plans.append((pickle.loads(pickle.dumps(inp)), copy.copy(out)))
        passed += out.did_section_change
        states.append(out.new_position)
        out.pass_to_input(inp)
        assert len(states) < 100_000
        if res != tk.Result.Working:
            break
        res = otg.update(inp, out)
    return plans, np.array(states), passed, out


def test_ruckig_online_waypoint_example_with_a_budget_reaches_the_target():
    """A port of Ruckig's example 04 (budget 500 µs, four waypoints, the update loop): the
    loop reaches the target through every waypoint; each motion it follows is valid."""
    script = pathlib.Path(__file__).resolve().parents[1] / "examples" / "ruckig_waypoints_online.py"
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                       timeout=120, check=True)
    assert "Updated the trajectory:" in r.stdout
    rows = [line.split("\t") for line in r.stdout.splitlines() if "\t" in line][1:]
    assert np.allclose([float(x) for x in rows[-1][1:]], [0.5, 1.0, 0.0], atol=0.01)
    # The same loop here, checked.
    inp = tk.InputParameter(3)
    inp.current_position = [0.2, 0, -0.3]
    inp.current_velocity = [0, 0.2, 0]
    inp.current_acceleration = [0, 0.6, 0]
    wps = [[1.4, -1.6, 1.0], [-0.6, -0.5, 0.4], [-0.4, -0.35, 0.0], [0.8, 1.8, -0.1]]
    inp.intermediate_positions = wps
    inp.target_position = [0.5, 1, 0]
    inp.target_velocity = [0.2, 0, 0.3]
    inp.target_acceleration = [0, 0.1, -0.1]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1, 2, 1], [3, 2, 2], [6, 10, 20]
    inp.interrupt_calculation_duration = 500
    plans, states, passed, out = follow_with_budget(inp, 0.01)
    assert passed == len(wps) + 1
    for plan_inp, plan_out in plans:
        assert_valid(plan_inp, plan_out.trajectory)
    # Each waypoint is passed: the followed states come within one cycle's travel of it.
    for w in wps:
        assert np.min(np.linalg.norm(states - w, axis=1)) < 0.05, w
    assert np.allclose(out.new_position, inp.target_position, atol=0.01)


def test_a_short_budget_gives_a_valid_motion_then_refines_it():
    """30 waypoints on 7 DOF: the planning takes longer than 600 µs, so the first calculation
    is interrupted with a valid motion (never longer than stopping at every waypoint); the
    following updates refine it (each switch shortens the rest of the motion) and the loop
    ends at the target having passed every waypoint. The budget holds (least calculation
    ≤ 1.1× the budget; a thread preempted past its deadline overruns by the preemption)."""
    inp = waypoint_problem(np.random.default_rng(77), dofs=7, waypoints=30, rest=True)
    free = calculate(inp, 0.004)
    # Stopping at every waypoint (what must fit) takes about 150 µs here and the whole search
    # about 3 ms: 600 µs leaves the first a margin against a noisy machine and cuts the second.
    budget = 600.0
    inp.interrupt_calculation_duration = budget
    first = calculate(inp, 0.004)
    assert first.was_interrupted and not free.was_interrupted
    assert_valid(inp, first)
    assert first.duration <= stop_at_every_waypoint(inp) * (1 + 1e-9)
    wps = np.array(inp.intermediate_positions)
    plans, states, passed, out = follow_with_budget(inp, 0.004)
    assert passed == len(wps) + 1
    assert plans[0][1].was_calculation_interrupted
    for plan_inp, plan_out in plans:
        assert_valid(plan_inp, plan_out.trajectory)
    # Switching only to motions that end sooner: the loop ends no later than the first motion.
    assert len(states) * 0.004 <= plans[0][1].trajectory.duration + 0.004 + 1e-9
    assert np.allclose(out.new_position, inp.target_position, atol=1e-6)
    least = min(o.calculation_duration for _, o in plans)
    print(f"{len(plans)} calculations; first motion {first.duration:.3f} s, arrival after "
          f"{len(states) * 0.004:.3f} s (without a budget {free.duration:.3f} s); "
          f"calculation least {least:.0f} µs, most "
          f"{max(o.calculation_duration for _, o in plans):.0f} µs")
    assert least <= 1.1 * budget
