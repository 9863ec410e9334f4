"""The original TOTG (PyPI tesseract-robotics 0.5.1) as trajkit's TOTG scripts call it: the
Franka Panda limits they use and the construction of the instruction list. Shared by
tools/totg_fixtures.py and tools/bench_totg_peer.py; import it after `use_venv("totg", ...)`.
"""
import numpy as np

VMAX = np.array([2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61])
AMAX = np.array([15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0])
JMAX = np.array([7500.0, 3750.0, 5000.0, 6250.0, 7500.0, 10000.0, 10000.0])
QMIN = np.array([-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973])
QMAX = np.array([2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973])


def bounds(vmax, amax):
    """The (velocity, acceleration, jerk) limit arrays compute() takes: one [min, max] row per
    joint."""
    return (
        np.column_stack([-vmax, vmax]),
        np.column_stack([-amax, amax]),
        np.column_stack([-JMAX, JMAX]),
    )


def program(waypoints):
    """The freespace program through `waypoints` and its InstructionsTrajectory (the object
    compute() times in place)."""
    from tesseract_robotics import tesseract_command_language as cl
    from tesseract_robotics import tesseract_time_parameterization as tp

    names = [f"panda_joint{i + 1}" for i in range(7)]
    prog = cl.CompositeInstruction("DEFAULT")
    for w in waypoints:
        sw = cl.StateWaypoint(names, np.array(w, dtype=float))
        mi = cl.MoveInstruction(
            cl.StateWaypointPoly_wrap_StateWaypoint(sw), cl.MoveInstructionType_FREESPACE, "DEFAULT"
        )
        prog.appendMoveInstruction(cl.MoveInstructionPoly_wrap_MoveInstruction(mi))
    return prog, tp.InstructionsTrajectory(prog)
