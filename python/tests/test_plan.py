"""trajkit.plan: the main job from Python.

The same problems through ``trajkit.plan`` and through the ``trajkit plan`` command line (both
call ``trajkit::plan``): durations and every sample agree to rounding. The CLI binary is
``$TRAJKIT_BIN``, else ``target/release/trajkit`` or ``target/debug/trajkit`` of this
checkout (``.ci/run`` builds it before the Python suite); without one those tests skip.
Against toppra (PyPI): the same natural chord-length spline and the same velocity and
acceleration limits give the same time-optimal duration. Missing limits are refused, never
read as unlimited.
"""
import os
import pathlib
import pickle
import shutil
import subprocess

import numpy as np
import pytest

import trajkit

ROOT = pathlib.Path(__file__).resolve().parents[2]
PANDA = trajkit.Limits("panda")


def cli():
    env = os.environ.get("TRAJKIT_BIN")
    if env:
        return env
    for p in [ROOT / "target" / "release" / "trajkit", ROOT / "target" / "debug" / "trajkit"]:
        if p.exists():
            return str(p)
    return shutil.which("trajkit")


def waypoints(seed, n=5, spread=0.5):
    rng = np.random.default_rng(seed)
    lo, hi = PANDA.position[:, 0], PANDA.position[:, 1]
    return (lo + hi) / 2 + spread * (hi - lo) / 2 * rng.uniform(-1, 1, (n, 7))


def run_cli(tmp_path, wp, args):
    exe = cli()
    if exe is None:
        pytest.skip("no trajkit CLI binary (set TRAJKIT_BIN or build trajkit-cli)")
    src, out = tmp_path / "wp.csv", tmp_path / "out.csv"
    np.savetxt(src, wp, delimiter=",", fmt="%.17g")
    subprocess.run([exe, "plan", "--waypoints", str(src), "--out", str(out), *args],
                   check=True, capture_output=True)
    table = np.loadtxt(out, delimiter=",", skiprows=1, ndmin=2)
    return table


CASES = [
    ("toppra", {}, ["--limits", "panda"]),
    ("toppra", {"jerk_limit": False}, ["--limits", "panda", "--no-jerk-limit"]),
    ("toppra", {"path": "linear"}, ["--limits", "panda", "--path", "linear"]),
    ("toppra", {"jerk_stage": "auto"}, ["--limits", "panda", "--jerk-stage", "auto"]),
    ("toppra", {"jerk_stage": "filter"}, ["--limits", "panda", "--jerk-stage", "filter"]),
    ("toppra", {"jerk_stage": "third-order"},
     ["--limits", "panda", "--jerk-stage", "third-order"]),
    ("ni", {"jerk_stage": "filter"}, ["--limits", "panda", "--method", "ni", "--jerk-stage", "filter"]),
    ("ni", {}, ["--limits", "panda", "--method", "ni"]),
    ("poly", {"degree": "septic"}, ["--limits", "panda", "--method", "poly", "--degree", "septic"]),
    ("totg", {"jerk_limit": False, "max_deviation": 0.05},
     ["--limits", "panda", "--method", "totg", "--no-jerk-limit", "--max-deviation", "0.05"]),
    ("toppra", {"max_velocity": 1.0, "max_acceleration": [2.0] * 7, "max_jerk": 20.0,
                "position_range": (-3.0, 3.0), "velocity_scale": 0.8},
     ["--max-velocity", "1", "--max-acceleration", "2", "--max-jerk", "20",
      "--position-range=-3:3", "--velocity-scale", "0.8"]),
]


@pytest.mark.parametrize("case", range(len(CASES)))
@pytest.mark.parametrize("seed", [0, 1])
def test_plan_matches_cli(tmp_path, case, seed):
    method, kwargs, args = CASES[case]
    wp = waypoints(seed)
    limits = None if "max_velocity" in kwargs else "panda"
    p = trajkit.plan(wp, limits, method=method, **kwargs)
    table = run_cli(tmp_path, wp, args + ["--rate", "250"])
    t, q, qd, qdd, qddd = p.sample(250)
    assert p.method == method and p.dof == 7
    assert table.shape == (len(t), 1 + 4 * 7)
    assert abs(table[-1, 0] - p.duration) <= 1e-12 * p.duration
    for k, got in enumerate([q, qd, qdd, qddd]):
        want = table[:, 1 + 7 * k: 1 + 7 * (k + 1)]
        scale = max(1.0, float(np.max(np.abs(want))))
        assert np.max(np.abs(got - want)) <= 1e-12 * scale, (method, k)
    # The plan keeps every limit it was given, and says so in its report.
    assert p.worst_ratio <= 1.0 + 1e-9
    assert p.report["worst"] == pytest.approx(p.worst_ratio)
    assert np.allclose(p(0.0), wp[0], atol=1e-9) and np.allclose(p(p.duration), wp[-1], atol=1e-9)


def test_plan_evaluation_sampling_and_pickling():
    wp = waypoints(4)
    p = trajkit.plan(wp, limits=PANDA)
    assert isinstance(p, trajkit.Trajectory) and isinstance(p, trajkit.Plan)
    tt = np.linspace(0.0, p.duration, 301)
    q, qd = p(tt), p(tt, order=1)
    assert q.shape == (301, 7) and qd.shape == (301, 7)
    assert np.array_equal(p(tt[17]), q[17])
    # order=1 is the derivative of order=0 (central differences).
    h = 1e-6
    mid = tt[1:-1]
    fd = (p(mid + h) - p(mid - h)) / (2 * h)
    assert np.max(np.abs(fd - p(mid, 1))) < 1e-5
    t, q2, qd2, qdd2, qddd2 = p.samples
    assert np.allclose(t[-1], p.duration) and q2.shape == (len(t), 7)
    assert np.all(np.abs(qd2) <= PANDA.velocity * (1 + 1e-9))
    assert np.all(np.abs(qdd2) <= PANDA.acceleration * (1 + 1e-9))
    assert p.names == PANDA.names and p.limits == PANDA.complete()
    assert p.waypoints == 5 and p.pieces >= 1 and p.check_scale >= 1.0
    assert any("jerk" in n for n in p.notes)
    again = pickle.loads(pickle.dumps(p))
    assert isinstance(again, trajkit.Plan) and again.duration == p.duration
    assert np.array_equal(again(tt), q)


def test_plan_named_columns_take_their_limits():
    wp = waypoints(2)
    order = [3, 0, 6, 1, 5, 2, 4]
    names = [PANDA.names[i] for i in order]
    p = trajkit.plan(wp[:, order], "panda", joint_names=names)
    ref = trajkit.plan(wp, "panda")
    assert p.names == names
    assert np.array_equal(p.limits.velocity, PANDA.velocity[order])
    assert p.duration == pytest.approx(ref.duration, rel=1e-9)


def test_missing_limits_are_refused(tmp_path):
    urdf = ROOT / "examples" / "robots" / "ur5e" / "ur5e.urdf"
    wp = np.array([[0.0] * 6, [0.5, -0.4, 0.3, -0.2, 0.1, 0.6], [1.0, -0.8, 0.5, 0.1, 0.3, 0.0]])
    lu = trajkit.Limits(str(urdf))
    assert np.all(np.isnan(lu.acceleration)) and np.all(np.isnan(lu.jerk))
    assert len(lu.missing(velocity=False, position=False)) == 2 * 6
    # A URDF has no acceleration limit: refused, naming the joint and the field.
    with pytest.raises(trajkit.TrajkitError, match="acceleration") as e:
        trajkit.plan(wp, str(urdf))
    assert "shoulder_pan_joint" in str(e.value) or "joint 1" in str(e.value)
    # Supplied from the preset by name, it plans.
    p = trajkit.plan(wp, str(urdf), fill_from="ur5e")
    assert p.worst_ratio <= 1.0 + 1e-9
    # Jerk stated unlimited: the plan keeps velocity and acceleration only.
    q = trajkit.plan(wp, lu.with_overrides(max_acceleration=3.0), max_jerk=float("inf"))
    assert np.all(np.isinf(q.limits.jerk))
    with pytest.raises(trajkit.TrajkitError, match="jerk"):
        trajkit.plan(wp, lu.with_overrides(max_acceleration=3.0))
    # Overrides alone are limits on unnamed joints; a missing position range is refused.
    with pytest.raises(trajkit.TrajkitError, match="position"):
        trajkit.plan(wp, max_velocity=1.0, max_acceleration=2.0, max_jerk=10.0)
    with pytest.raises(trajkit.TrajkitError, match="no limits given"):
        trajkit.plan(wp)


def test_plan_bad_input():
    wp = waypoints(0)
    with pytest.raises(trajkit.TrajkitError, match="method"):
        trajkit.plan(wp, "panda", method="fast")
    bad = wp.copy()
    bad[2, 3] = np.nan
    with pytest.raises(ValueError, match="NaN|finite|waypoint"):
        trajkit.plan(bad, "panda")
    with pytest.raises(trajkit.TrajkitError, match="joints|7|6"):
        trajkit.plan(wp[:, :6], "panda")
    with pytest.raises(trajkit.TrajkitError, match="shape"):
        trajkit.plan(wp[0], "panda")
    with pytest.raises(trajkit.TrajkitError, match="velocity_scale|scale"):
        trajkit.plan(wp, "panda", velocity_scale=-1.0)
    with pytest.raises(trajkit.TrajkitError, match="gridpoints"):
        trajkit.plan(wp, "panda", gridpoints=0)
    with pytest.raises(trajkit.TrajkitError, match="jerk_limit"):
        trajkit.plan(wp, "panda", jerk_limit=False, max_jerk=5.0)
    with pytest.raises(trajkit.TrajkitError, match="jerk_stage = 'fast' is not"):
        trajkit.plan(wp, "panda", jerk_stage="fast")
    with pytest.raises(trajkit.TrajkitError, match="jerk_stage = 'filter'.*jerk_limit=False"):
        trajkit.plan(wp, "panda", jerk_limit=False, jerk_stage="filter")


def test_plan_matches_toppra():
    """The raw TOPP-RA stage against toppra: the same natural spline (chord-length
    parameterized), the same velocity and acceleration limits; toppra on a fine grid is within
    its own grid error of trajkit's converged duration."""
    ta = pytest.importorskip("toppra")
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    ta.setup_logging("WARNING")
    for seed in range(3):
        wp = waypoints(seed + 10, n=6, spread=0.4)
        p = trajkit.plan(wp, "panda", jerk_limit=False)
        assert p.pieces == 1 and not p.range_repairs
        ss = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(wp, axis=0), axis=1))])
        vmax, amax = PANDA.velocity, PANDA.acceleration
        path = ta.SplineInterpolator(ss, wp, bc_type="natural")
        grid = np.unique(np.concatenate([ss, np.linspace(0.0, ss[-1], 4001)]))
        inst = algo.TOPPRA([constraint.JointVelocityConstraint(np.vstack([-vmax, vmax]).T),
                            constraint.JointAccelerationConstraint(
                                np.vstack([-amax, amax]).T,
                                discretization_scheme=constraint.DiscretizationType.Interpolation)],
                           path, gridpoints=grid, solver_wrapper="seidel")
        want = inst.compute_trajectory(0.0, 0.0).duration
        assert abs(p.raw_duration - want) / want < 2e-3, (p.raw_duration, want)


def line_waypoints():
    """Three collinear waypoints in order (one rest-to-rest piece along a straight line)."""
    mid = (PANDA.position[:, 0] + PANDA.position[:, 1]) / 2
    d = np.array([0.9, -0.5, 0.3, 0.6, -0.8, 0.4, -0.2])
    return np.array([mid - d / 2, mid + d / 10, mid + d / 2])


def test_straight_line_auto_is_the_otg_optimum():
    """jerk_stage='auto' on a straight line: the duration of the 1-D jerk-limited optimum
    along it (the joints' limits projected on the line), as trajkit.otg and the Ruckig wheel
    compute it; 'filter' is never shorter."""
    wp = line_waypoints()
    p = trajkit.plan(wp, "panda", jerk_stage="auto")
    assert p.pieces == 1
    length = float(np.linalg.norm(wp[-1] - wp[0]))
    u = np.abs(wp[-1] - wp[0]) / length
    lim = [float(np.min(x / u)) for x in (PANDA.velocity, PANDA.acceleration, PANDA.jerk)]
    durations = {}
    for name, mod in [("trajkit", tk_otg()), ("ruckig", pytest.importorskip("ruckig"))]:
        inp = mod.InputParameter(1)
        inp.current_position, inp.target_position = [0.0], [length]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [lim[0]], [lim[1]], [lim[2]]
        tr = mod.Trajectory(1)
        mod.Ruckig(1, 0.001).calculate(inp, tr)
        durations[name] = tr.duration
    assert durations["trajkit"] == pytest.approx(durations["ruckig"], rel=1e-9)
    # The library plans with the projected limits lowered by 1e-10 relative (LIMIT_MARGIN).
    assert p.duration == pytest.approx(durations["ruckig"], rel=1e-8)
    assert p.duration >= durations["ruckig"] * (1 - 1e-12)
    f = trajkit.plan(wp, "panda", jerk_stage="filter")
    assert f.duration > p.duration * (1 + 1e-6)
    for q in (p, f):
        assert q.worst_ratio <= 1.0 + 1e-9
        assert np.allclose(q(0.0), wp[0], atol=1e-9) and np.allclose(q(q.duration), wp[-1], atol=1e-9)


@pytest.mark.parametrize("stage", ["auto", "filter", "third-order"])
def test_straight_line_stages_match_cli(tmp_path, stage):
    wp = line_waypoints()
    p = trajkit.plan(wp, "panda", jerk_stage=stage)
    table = run_cli(tmp_path, wp, ["--limits", "panda", "--jerk-stage", stage, "--rate", "250"])
    assert abs(table[-1, 0] - p.duration) <= 1e-12 * p.duration
    t, q, qd, qdd, qddd = p.sample(250)
    for k, got in enumerate([q, qd, qdd, qddd]):
        want = table[:, 1 + 7 * k: 1 + 7 * (k + 1)]
        scale = max(1.0, float(np.max(np.abs(want))))
        assert np.max(np.abs(got - want)) <= 1e-12 * scale, (stage, k)
    again = pickle.loads(pickle.dumps(p))
    assert again.duration == p.duration


def tk_otg():
    from trajkit import otg
    return otg
