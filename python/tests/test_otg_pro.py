"""trajkit.otg: Ruckig Pro's position limits and calculation budget from Python.

Position limits (``InputParameter.min_position`` / ``max_position``): on seeded random
problems whose unconstrained optimum leaves the box, every result stays inside (sampled
densely and at its exact extrema), reaches the target and is never shorter than the
unconstrained optimum; a target that cannot be reached inside raises ``RuckigError`` with
``Result.ErrorPositionalLimits``. Calculation budget (``interrupt_calculation_duration``,
µs): a tiny budget either raises with ``kind == 'interrupted'`` or returns a valid
trajectory; a generous one changes nothing.
"""
import math
import pickle

import numpy as np
import pytest

import trajkit
from trajkit import otg as tk
from test_otg_ruckig import random_problem  # the same random problems as the Ruckig suite


def general_problem(rng, dofs):
    """A random problem with any states, drawn again until the input is valid and the
    current state does not force the velocity beyond its limit (where the acceleration
    reaches zero at full jerk): no brake pre-profile, every limit holds throughout."""
    while True:
        inp = random_problem(rng, tk, dofs, "general")
        v, a = np.array(inp.current_velocity), np.array(inp.current_acceleration)
        peak = v + np.sign(a) * a * a / (2 * np.array(inp.max_jerk))
        if np.any(np.abs(peak) > np.array(inp.max_velocity)):
            continue
        try:
            tk.Ruckig(dofs, 0.001).validate_input(inp, True, True)
            return inp
        except tk.RuckigError:
            pass


def calculate(inp):
    tr = tk.Trajectory(inp.degrees_of_freedom)
    res = tk.Ruckig(inp.degrees_of_freedom, 0.001).calculate(inp, tr)
    assert res == tk.Result.Working
    return tr


def assert_reaches_target(tr, inp):
    p, v, a = tr.at_time(tr.duration)
    assert np.allclose(p, inp.target_position, atol=1e-8)
    assert np.allclose(v, inp.target_velocity, atol=1e-8)
    assert np.allclose(a, inp.target_acceleration, atol=1e-8)


def limited_problem(rng, dofs, tighten):
    """A general problem and its unconstrained optimum, with one position limit placed where
    that optimum overshoots its end points most: at a fraction `tighten` of the overshoot
    (1: touching the optimum's extremum). The other limits are loose."""
    inp = general_problem(rng, dofs)
    free = calculate(inp)
    emin = np.array([b.min for b in free.position_extrema])
    emax = np.array([b.max for b in free.position_extrema])
    lo = np.minimum(inp.current_position, inp.target_position)
    hi = np.maximum(inp.current_position, inp.target_position)
    over = np.concatenate([lo - emin, emax - hi])
    k = int(np.argmax(over))
    pmin, pmax = emin - 1.0, emax + 1.0
    if over[k] > 1e-6:
        if k < dofs:
            pmin[k] = lo[k] - tighten * over[k]
        else:
            pmax[k - dofs] = hi[k - dofs] + tighten * over[k]
    inp.min_position, inp.max_position = list(pmin), list(pmax)
    return inp, free, pmin, pmax


def assert_within_limits(tr, inp):
    """No brake (see `general_problem`), and velocity and acceleration within their limits."""
    assert all(p.brake_duration == 0.0 for p in tr.profiles[0])
    t = np.linspace(0.0, tr.duration, 1001)
    assert np.all(np.abs(tr(t, 1)) <= np.array(inp.max_velocity) * (1 + 1e-9))
    assert np.all(np.abs(tr(t, 2)) <= np.array(inp.max_acceleration) * (1 + 1e-9))


def test_position_limited_problems_stay_inside():
    """Most overshoots of a general problem are its brake's (unavoidable): a limit inside
    them is refused with ErrorPositionalLimits. A limit at the optimum's extremum keeps the
    optimum; a limit slightly inside it, where it can be held, gives a longer motion that
    stays inside."""
    rng = np.random.default_rng(2026)
    dofs, inside, longer, refused = 3, 0, 0, 0
    for k in range(1000):
        tighten = 1.0 if k % 2 == 0 else rng.uniform(0.99, 1.0)
        inp, free, lo, hi = limited_problem(rng, dofs, tighten)
        try:
            tr = calculate(inp)
        except tk.RuckigError as e:
            assert e.result == tk.Result.ErrorPositionalLimits, str(e)
            assert e.kind == "position_limits" and 0 <= e.dof < dofs
            assert f"DOF {e.dof}" in str(e)
            assert tighten < 1.0  # the optimum itself is inside: never refused
            refused += 1
            continue
        t = np.linspace(0.0, tr.duration, 2001)
        q = tr(t)
        tol = 1e-9 * max(1.0, float(np.max(np.abs(q))))
        assert np.all(q >= lo - tol) and np.all(q <= hi + tol)
        for i, b in enumerate(tr.position_extrema):
            assert lo[i] - tol <= b.min and b.max <= hi[i] + tol
        assert_reaches_target(tr, inp)
        assert tr.duration >= free.duration * (1 - 1e-9)
        if tighten == 1.0:
            assert tr.duration == pytest.approx(free.duration, rel=1e-12)
        assert_within_limits(tr, inp)
        inside += 1
        longer += tr.duration > free.duration * (1 + 1e-9)
    assert inside >= 500 and longer >= 5, (inside, longer, refused)


def test_position_limits_in_the_update_loop_and_pickling():
    rng = np.random.default_rng(11)
    for _ in range(1000):
        inp, free, lo, hi = limited_problem(rng, 3, 0.999)
        try:
            if calculate(inp).duration > free.duration * (1 + 1e-9):
                break  # the limit changed the motion
        except tk.RuckigError:
            pass
    else:
        pytest.fail("no solvable problem whose optimum leaves the limits")
    assert pickle.loads(pickle.dumps(inp)) == inp
    assert tk.InputParameter(2).min_position == [-math.inf] * 2
    assert tk.InputParameter(2).max_position == [math.inf] * 2
    otg, out = tk.Ruckig(3, 0.001), tk.OutputParameter(3)
    res, low, high = tk.Result.Working, np.full(3, math.inf), np.full(3, -math.inf)
    while res == tk.Result.Working:
        res = otg.update(inp, out)
        out.pass_to_input(inp)
        low, high = np.minimum(low, out.new_position), np.maximum(high, out.new_position)
    assert res == tk.Result.Finished
    assert np.all(low >= lo - 1e-9) and np.all(high <= hi + 1e-9)
    # The last update lands up to one control period after the end.
    assert np.allclose(out.new_position, inp.target_position,
                       atol=0.001 * max(inp.max_velocity) + 1e-9)


def test_unreachable_inside_the_limits_raises_positional_limits():
    inp = tk.InputParameter(2)
    inp.current_position, inp.current_velocity = [0.0, 0.99], [0.0, 2.0]
    inp.target_position = [0.5, 0.0]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [3.0, 3.0], [1.0, 1.0], [1.0, 1.0]
    inp.max_position = [math.inf, 1.0]
    with pytest.raises(tk.RuckigError, match="position limits") as e:
        calculate(inp)
    assert e.value.result == tk.Result.ErrorPositionalLimits == tk.ErrorPositionalLimits
    assert e.value.kind == "position_limits" and e.value.dof == 1
    # Bad limits are invalid input naming the field, the DOF and the value.
    inp.max_position = [math.inf, 1.0]
    inp.min_position = [-1.0, 2.0]
    with pytest.raises(trajkit.TrajkitError, match=r"min_position\[1\] = 2") as e:
        calculate(inp)
    assert e.value.result == tk.Result.ErrorInvalidInput
    inp.min_position = [-1.0]
    with pytest.raises(trajkit.TrajkitError, match="min_position"):
        calculate(inp)


@pytest.mark.parametrize("budget", [1e-3, 3.0, 30.0])
def test_tiny_budget_interrupts_or_returns_a_valid_result(budget):
    """Budgets in µs: 1 ns interrupts every search; a few µs (about one calculation on this
    machine class) gives a mix, depending on the load."""
    rng = np.random.default_rng(17)
    interrupted = valid = 0
    for _ in range(200):
        inp = general_problem(rng, 7)
        best = calculate(inp)
        inp.interrupt_calculation_duration = budget
        try:
            tr = calculate(inp)
        except tk.RuckigError as e:
            assert e.kind == "interrupted" and e.dof is None, str(e)
            assert e.result == tk.Result.ErrorExecutionTimeCalculation
            assert f"budget of {budget:g} µs" in str(e)
            interrupted += 1
            continue
        # The shortest valid trajectory found within the budget: valid, never shorter; the
        # optimum itself unless the library reports that the budget cut the search.
        assert_reaches_target(tr, inp)
        assert tr.duration >= best.duration * (1 - 1e-9)
        assert not best.was_interrupted
        if not tr.was_interrupted:
            assert tr.duration == best.duration
        assert_within_limits(tr, inp)
        valid += 1
    assert interrupted + valid == 200


def test_budget_in_update_and_generous_budget_changes_nothing():
    rng = np.random.default_rng(5)
    inp = general_problem(rng, 7)
    best = calculate(inp)
    inp.interrupt_calculation_duration = 1e7  # ten seconds
    assert inp.interrupt_calculation_duration == 1e7
    assert calculate(inp).duration == best.duration
    otg, out = tk.Ruckig(7, 0.001), tk.OutputParameter(7)
    otg.update(inp, out)
    assert out.new_calculation and not out.was_calculation_interrupted
    # A budget of one nanosecond is always used up: reported, whatever the outcome.
    inp.interrupt_calculation_duration = 1e-3
    otg.reset()
    try:
        otg.update(inp, out)
    except tk.RuckigError as e:
        assert e.kind == "interrupted"
    assert out.was_calculation_interrupted
    inp.interrupt_calculation_duration = None
    otg.update(inp, out)
    assert not out.was_calculation_interrupted
    assert pickle.loads(pickle.dumps(inp)).interrupt_calculation_duration is None
    inp.interrupt_calculation_duration = -5.0
    with pytest.raises(tk.RuckigError, match="interrupt_calculation_duration") as e:
        calculate(inp)
    assert e.value.result == tk.Result.ErrorInvalidInput
