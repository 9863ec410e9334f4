"""The Franka Panda as trajkit's fixture and peer-benchmark scripts use it (the values of
trajkit's `panda` limits preset), and the seeded random waypoints they draw inside its
position range. Needs only numpy; import it after the script's `use_venv(...)`.
"""
import numpy as np

VMAX = np.array([2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61])
AMAX = np.array([15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0])
JMAX = np.array([7500.0, 3750.0, 5000.0, 6250.0, 7500.0, 10000.0, 10000.0])
QMIN = np.array([-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973])
QMAX = np.array([2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973])


def random_waypoints(rng, n, margin=0.1):
    """`n` waypoints uniform in the position range shrunk by `margin` on each side."""
    lo, hi = QMIN + margin, QMAX - margin
    return lo + (hi - lo) * rng.random((n, 7))
