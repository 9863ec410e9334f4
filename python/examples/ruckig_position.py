"""A Ruckig-style script: the online loop from any state to a target, 10 ms cycles.

Written against Ruckig's Python API; to run it on trajkit, change the import line to
``from trajkit.otg import InputParameter, OutputParameter, Result, Ruckig``.
"""
from ruckig import InputParameter, OutputParameter, Result, Ruckig

otg = Ruckig(3, 0.01)
inp = InputParameter(3)
out = OutputParameter(3)

inp.current_position = [0.0, 0.0, 0.5]
inp.current_velocity = [0.0, -2.2, -0.5]
inp.current_acceleration = [0.0, 2.5, -0.5]
inp.target_position = [5.0, -2.0, -3.5]
inp.target_velocity = [0.0, -0.5, -2.0]
inp.target_acceleration = [0.0, 0.0, 0.5]
inp.max_velocity = [3.0, 1.0, 3.0]
inp.max_acceleration = [3.0, 2.0, 1.0]
inp.max_jerk = [4.0, 3.0, 2.0]

print("\t".join(["t"] + [f"p{i}" for i in range(3)]))
res = Result.Working
first = None
while res == Result.Working:
    res = otg.update(inp, out)
    if first is None:
        first = (out.calculation_duration, out.trajectory.duration)
    print("\t".join([f"{out.time:0.3f}"] + [f"{p:0.3f}" for p in out.new_position]))
    out.pass_to_input(inp)

print(f"Calculation duration: {first[0]:0.1f} [µs]")
print(f"Trajectory duration: {first[1]:0.4f} [s]")
