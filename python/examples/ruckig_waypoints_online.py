"""Ruckig Pro's online waypoint example (a calculation budget of 500 µs, intermediate
waypoints, the update loop) with trajkit.otg: only the import differs from a Ruckig script.

With a budget, trajkit's waypoint planner returns the best motion it has found when the
budget runs out (stopping at every waypoint at worst) and says so in
``out.was_calculation_interrupted``; the following updates refine it from the current state
and switch to a shorter motion when they find one (``out.new_calculation``).

    python examples/ruckig_waypoints_online.py
"""
from copy import copy

from trajkit.otg import InputParameter, OutputParameter, Result, Ruckig

if __name__ == "__main__":
    otg = Ruckig(3, 0.01, 10)  # DOFs, control period [s], Ruckig Pro's storage hint
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

    inp.interrupt_calculation_duration = 500  # [µs]

    print("\t".join(["t"] + [str(i) for i in range(otg.degrees_of_freedom)]))
    outputs, res = [], Result.Working
    while res == Result.Working:
        res = otg.update(inp, out)
        if out.new_calculation:
            print("Updated the trajectory:")
            print(f"  Calculation duration: {out.calculation_duration:0.1f} [µs]")
            print(f"  Interrupted: {out.was_calculation_interrupted}")
            print(f"  Trajectory duration: {out.trajectory.duration:0.4f} [s]")
        print("\t".join([f"{out.time:0.3f}"] + [f"{p:0.3f}" for p in out.new_position]))
        outputs.append(copy(out))
        out.pass_to_input(inp)
