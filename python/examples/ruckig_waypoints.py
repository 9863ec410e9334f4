"""Ruckig Pro's intermediate-waypoint example with trajkit.otg: the script is Ruckig's
(only the import differs), and trajkit computes the waypoints locally.

    python examples/ruckig_waypoints.py
"""
from copy import copy

from trajkit.otg import InputParameter, OutputParameter, Result, Ruckig

if __name__ == "__main__":
    ruckig = Ruckig(3, 0.01, 10)  # DOFs, control period, Ruckig Pro's storage hint
    inp = InputParameter(3)
    out = OutputParameter(3, 10)

    inp.current_position = [0.2, 0, -0.3]
    inp.current_velocity = [0, 0.2, 0]
    inp.current_acceleration = [0, 0.6, 0]
    inp.intermediate_positions = [
        [1.4, -1.6, 1.0],
        [-0.6, -0.5, 0.4],
        [-0.4, -0.35, 0.0],
        [0.8, 1.8, -0.1],
    ]
    inp.target_position = [0.5, 1, 0]
    inp.target_velocity = [0.2, 0, 0.3]
    inp.target_acceleration = [0, 0.1, -0.1]
    inp.max_velocity = [1, 2, 1]
    inp.max_acceleration = [3, 2, 2]
    inp.max_jerk = [6, 10, 20]

    print("\t".join(["t"] + [str(i) for i in range(ruckig.degrees_of_freedom)]))
    first_output, res = None, Result.Working
    while res == Result.Working:
        res = ruckig.update(inp, out)
        print("\t".join([f"{out.time:0.3f}"] + [f"{p:0.3f}" for p in out.new_position]))
        out.pass_to_input(inp)
        if not first_output:
            first_output = copy(out)

    print(f"Calculation duration: {first_output.calculation_duration:0.1f} [µs]")
    print(f"Trajectory duration: {first_output.trajectory.duration:0.4f} [s]")
    print(f"Waypoints reached at: {[round(t, 4) for t in out.trajectory.intermediate_durations[:-1]]} [s]")
