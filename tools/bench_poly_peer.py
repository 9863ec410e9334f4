#!/usr/bin/env python3
"""Peer timing for trajkit's poly_eval benchmark: the same 7-joint quintic rest-to-rest move
(q0 -> q1 in T = 2 s) evaluated at the same 100 000 sorted times with NumPy, vectorized
(numpy.polynomial.polynomial.polyval over the whole time array, one call per joint and
derivative order).

Usage: tools/bench_poly_peer.py   (creates tools/.venv-bench with numpy on first run)
Prints medians in ns per time point (all 7 joints), for position only and for position
through jerk, to compare with `cargo bench -p trajkit --bench poly_eval`.
"""
import os
import sys
from pyenv import use_venv

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    import timeit
    import numpy as np
    from numpy.polynomial import polynomial as P

    q0 = np.array([0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785])
    q1 = np.array([1.2, 0.3, -0.5, -1.2, 0.6, 2.2, -0.4])
    T = 2.0
    n = 100_000
    t = np.linspace(0.0, T, n)
    # Per joint: q(t) = q0 + dq * (10 tau^3 - 15 tau^4 + 6 tau^5), tau = t / T, in time units.
    unit = np.array([0, 0, 0, 10.0, -15.0, 6.0])
    scale = T ** -np.arange(6)
    coeffs = [np.concatenate(([q0[j]], np.zeros(5))) + (q1[j] - q0[j]) * unit * scale for j in range(7)]
    derivs = [[c] + [P.polyder(c, k) for k in (1, 2, 3)] for c in coeffs]

    def pos():
        return [P.polyval(t, d[0]) for d in derivs]

    def all4():
        return [P.polyval(t, dk) for d in derivs for dk in d]

    # Sanity: matches the closed form at mid-time.
    mid = P.polyval(1.0, coeffs[0])
    assert abs(mid - (q0[0] + 0.5 * (q1[0] - q0[0]))) < 1e-12

    for name, f in [("position", pos), ("pos_vel_acc_jerk", all4)]:
        reps = timeit.repeat(f, number=5, repeat=15)
        med = sorted(reps)[len(reps) // 2] / 5
        print(f"numpy quintic_move_7dof/{name}: median {med * 1e3:.3f} ms per 1e5 points = "
              f"{med / n * 1e9:.2f} ns/point ({n / med / 1e6:.2f} M points/s)")
    print(f"numpy {np.__version__}, python {sys.version.split()[0]}")


if __name__ == "__main__":
    use_venv("bench", ["numpy==2.*"])
    main()
