"""The original TOTG (PyPI tesseract-robotics 0.5.1) as trajkit's TOTG scripts call it: the
limit arrays and the construction of the instruction list. Shared by
tools/totg_fixtures.py and tools/bench_totg_peer.py; import it after `use_venv("totg", ...)`.
"""
import numpy as np
from panda import JMAX


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
