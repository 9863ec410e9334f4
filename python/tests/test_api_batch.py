"""The package's conventions: arrays in and out, errors, pickling, poly, batches across cores
and the Dask example on a local cluster."""
import os
import pickle
import subprocess
import sys

import numpy as np
import pytest

import trajkit
from trajkit import batch, otg, poly

HERE = os.path.dirname(os.path.abspath(__file__))


def test_error_type_and_message():
    assert issubclass(trajkit.TrajkitError, ValueError)
    with pytest.raises(trajkit.TrajkitError, match="unknown robot preset 'nope'"):
        trajkit.Limits("nope")
    with pytest.raises(trajkit.TrajkitError, match="move duration = -1"):
        poly.rest_to_rest([0.0], [1.0], -1.0)
    with pytest.raises(trajkit.TrajkitError, match="expected 2 values"):
        poly.rest_to_rest([0.0, 0.0], [1.0], 1.0)
    with pytest.raises(trajkit.TrajkitError, match="velocity"):
        trajkit.Limits({"joints": [{"velocity": -1.0, "acceleration": 1.0}]})


def test_poly_analytic_values():
    m = poly.rest_to_rest([0.0, 1.0], [2.0, -1.0], 2.0)
    assert m.duration == 2.0 and m.dof == 2
    # Quintic: peak velocity 1.875·D/T at mid-time.
    assert np.allclose(m(1.0, 1), [1.875, -1.875], atol=1e-12)
    assert poly.peak_coefficients("cubic") == pytest.approx((1.5, 6.0, 12.0))
    t, q, qd, qdd, qddd = m.sample(100)
    assert t.shape == (201,) and q.shape == (201, 2) and np.allclose(q[-1], [2.0, -1.0])
    panda = trajkit.Limits("panda")
    q0, q1 = np.zeros(7), np.full(7, 0.5)
    d = poly.min_duration(q0, q1, panda)
    fast = poly.rest_to_rest(q0, q1, d)
    tt = np.linspace(0, d, 2001)
    assert np.max(np.abs(fast(tt, 1)) / panda.velocity) <= 1 + 1e-9
    v = poly.via(np.array([[0, 0], [1, 0.5], [2, 0]]), durations=[1.0, 2.0])
    assert v.duration == pytest.approx(3.0)
    assert np.allclose(pickle.loads(pickle.dumps(v))(1.3), v(1.3))


def test_array_inputs_and_outputs():
    m = poly.rest_to_rest(np.array([0, 0]), (1, 2), 1)  # ints, tuples
    assert isinstance(m(0.5), np.ndarray) and m(0.5).dtype == np.float64
    t = np.linspace(0, 1, 12).reshape(3, 4)
    assert m(t).shape == (3, 4, 2)
    t_strided = np.linspace(0, 1, 24)[::2]
    assert np.array_equal(m(t_strided), m(np.ascontiguousarray(t_strided)))
    big = np.linspace(0, 1, 200_001)  # split across threads
    assert np.array_equal(m(big)[::1000], m(big[::1000]))
    with pytest.raises(trajkit.TrajkitError, match="order"):
        m(0.5, 4)


def test_limits_forms_and_pickling(tmp_path):
    urdf = tmp_path / "r.urdf"
    urdf.write_text('<robot name="r"><link name="a"/><link name="b"/>'
                    '<joint name="j1" type="revolute"><parent link="a"/><child link="b"/>'
                    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="2" effort="5"/></joint></robot>')
    lu = trajkit.Limits(str(urdf))
    assert lu.names == ["j1"] and lu.velocity[0] == 2.0
    p = trajkit.Limits.preset("ur5e")
    assert pickle.loads(pickle.dumps(p)).names == p.names
    assert trajkit.Limits.uniform(3, 1.0, 2.0).dof == 3


def inputs(n, bad=()):
    out = []
    rng = np.random.default_rng(5)
    for i in range(n):
        inp = otg.InputParameter(7)
        inp.current_position = list(rng.uniform(-1, 1, 7))
        inp.target_position = list(rng.uniform(-1, 1, 7))
        inp.max_velocity = [2.0] * 7
        inp.max_acceleration = [5.0] * 7
        inp.max_jerk = [-1.0 if i in bad else 50.0] * 7
        out.append(inp)
    return out


def test_batch_otg_in_order_with_per_item_errors():
    ins = inputs(300, bad={7, 123})
    res = batch.otg(ins, delta_time=0.001)
    assert len(res) == 300
    for i, (inp, r) in enumerate(zip(ins, res)):
        if i in (7, 123):
            assert isinstance(r, trajkit.TrajkitError) and "max_jerk" in str(r)
            # As Ruckig.calculate raises it.
            assert r.result == otg.Result.ErrorInvalidInput and r.kind == "invalid_input"
            continue
        one = otg.Trajectory(7)
        otg.Ruckig(7, 0.001).calculate(inp, one)
        assert r.duration == one.duration
    assert pickle.loads(pickle.dumps(res[0])).duration == res[0].duration
    key = lambda r: str(r) if isinstance(r, Exception) else r.duration
    assert [key(r) for r in batch.otg(ins[:20], threads=1)] == [key(r) for r in res[:20]]


def test_batch_waypoints_in_order():
    rng = np.random.default_rng(1)
    sets = [rng.uniform(-1, 1, (5, 7)) for _ in range(12)]
    sets[4] = sets[4][:1]  # one waypoint: an error in its place
    res = batch.plan_waypoints(sets, "panda", gridpoints=200)
    assert isinstance(res[4], trajkit.TrajkitError)
    for w, r in zip(sets, res):
        if isinstance(r, Exception):
            continue
        one = trajkit.topp.plan_waypoints(w, "panda", gridpoints=200)
        assert r.duration == one.duration
        assert np.allclose(r(0.0), w[0])


def test_dask_example_on_a_local_cluster():
    pytest.importorskip("distributed")
    script = os.path.join(HERE, "..", "examples", "dask_batch.py")
    out = subprocess.run([sys.executable, script, "--problems", "400", "--workers", "2"],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "400 problems" in out.stdout and "match the local batch" in out.stdout
