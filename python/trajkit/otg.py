"""Online jerk-limited trajectory generation with Ruckig's Python API.

A Ruckig script runs after changing ``from ruckig import ...`` to
``from trajkit.otg import ...``::

    from trajkit.otg import InputParameter, OutputParameter, Result, Ruckig

    otg = Ruckig(3, 0.01)
    inp, out = InputParameter(3), OutputParameter(3)
    inp.current_position = [0.0, 0.0, 0.5]
    inp.target_position = [5.0, -2.0, -3.5]
    inp.max_velocity = [3.0, 1.0, 3.0]
    inp.max_acceleration = [3.0, 2.0, 1.0]
    inp.max_jerk = [4.0, 3.0, 2.0]
    res = Result.Working
    while res == Result.Working:
        res = otg.update(inp, out)
        out.pass_to_input(inp)

Same names as Ruckig: ``Ruckig``, ``InputParameter``, ``OutputParameter``, ``Trajectory``
(``duration``, ``at_time``, ``position_extrema``, ``independent_min_durations``,
``intermediate_durations``, ``profiles``, ``get_first_time_at_position(dof, p,
time_after)``), ``Profile``, ``Bound``, ``Result``, ``Synchronization`` (``Time``,
``TimeIfNecessary``, ``Phase``, ``No``, and trajkit's ``StraightLine``), ``ControlInterface``,
``DurationDiscretization``, ``InputParameter.per_dof_synchronization`` and
``per_dof_control_interface``, ``Ruckig.validate_input`` and ``RuckigError`` (here the same
class as ``trajkit.TrajkitError``, a ``ValueError``). A ``Profile`` lists one DOF's jerk
segments (``t`` durations, ``t_sum``, ``j``, and ``p``, ``v``, ``a`` at each segment start
and the end); trajkit's segments are not Ruckig's seven fixed phases.
Ruckig Pro's position limits (``InputParameter.min_position`` / ``max_position``, per DOF,
``-inf`` / ``inf`` by default: positions stay inside along the whole motion) and calculation
budget (``InputParameter.interrupt_calculation_duration``, microseconds, ``None`` by default:
the shortest valid trajectory found within it, ``OutputParameter.was_calculation_interrupted``
and ``Trajectory.was_interrupted`` when it cut the calculation short; with intermediate
waypoints the best motion found in time, which the following ``update`` calls refine) are
supported. ``Ruckig.validate_input`` checks intermediate waypoints and per-section fields
too. Failures raise ``RuckigError`` with the
library's message and ``result`` (the ``Result`` member: ``ErrorInvalidInput``,
``ErrorPositionalLimits``, ``ErrorZeroLimits``, ``ErrorExecutionTimeCalculation``,
``ErrorSynchronizationCalculation``), ``kind`` (``'invalid_input'``, ``'position_limits'``,
``'zero_limits'``, ``'interrupted'``, ``'calculation_failed'``, ``'synchronization_failed'``)
and ``dof`` (or ``None``). A budget that runs out before any valid trajectory is known raises
with ``kind == 'interrupted'`` and ``result == Result.ErrorExecutionTimeCalculation``.
Ruckig Pro's intermediate waypoints are supported: ``InputParameter.intermediate_positions``
(a list of per-DOF lists or a 2-D array) with ``per_section_max_velocity``,
``per_section_max_acceleration``, ``per_section_max_jerk`` (one row per section, waypoints + 1)
and ``per_section_minimum_duration``. ``Ruckig.calculate`` fills a ``Trajectory`` with one
section per waypoint + 1 (``intermediate_durations``: the time each section ends;
``at_time(t, return_section=True)``: the number of sections ended at ``t``), and
``Ruckig.update`` follows it cycle by cycle (``OutputParameter.new_section``,
``did_section_change``; ``pass_to_input`` removes a passed waypoint, and the first entry of
each per-section list). The motion passes every waypoint, holds each section's limits and is
never longer than stopping at every waypoint (the library's ``plan_waypoints``). Ruckig Pro's
``per_section_min_velocity``, ``per_section_min_acceleration``, ``per_section_max_position``
and ``per_section_min_position`` are not supported: setting one raises ``RuckigError`` naming
it (the global ``min_velocity``, ``min_acceleration`` and position limits apply to every
section). ``max_number_of_waypoints`` (of ``Ruckig``, ``InputParameter``, ``OutputParameter``,
``Trajectory``) is accepted as a storage hint and is not a limit. ``filter_intermediate_positions``
does not exist here.

Problem files: ``read_problem(text)`` / ``load_problem(path)`` read the JSON format of
``trajkit otg`` (the same reader and error messages as the command line) and return
``(InputParameter, delta_time)``; ``InputParameter.from_json(text)`` and
``InputParameter.to_json(delta_time=None, indent=None)`` convert one input (the text reads
back as an equal input).

trajkit adds vectorized evaluation: ``trajectory(t, order=0)`` for an array ``t``.
"""

from ._trajkit import TrajkitError
from ._trajkit import otg as _o

Ruckig = _o.Ruckig
InputParameter = _o.InputParameter
OutputParameter = _o.OutputParameter
Trajectory = _o.Trajectory
Bound = _o.Bound
Profile = _o.Profile
Result = _o.Result
Synchronization = _o.Synchronization
ControlInterface = _o.ControlInterface
DurationDiscretization = _o.DurationDiscretization
RuckigError = TrajkitError
read_problem = _o.read_problem


def load_problem(path):
    """Reads the problem file ``path`` (the JSON format of ``trajkit otg``, read by the same
    reader with the same messages, the path naming the source): ``(InputParameter,
    delta_time)``."""
    with open(path, encoding="utf-8") as f:
        return read_problem(f.read(), str(path))


# Ruckig also exports the enum members at module level.
Working = Result.Working
Finished = Result.Finished
Error = Result.Error
ErrorInvalidInput = Result.ErrorInvalidInput
ErrorPositionalLimits = Result.ErrorPositionalLimits
ErrorZeroLimits = Result.ErrorZeroLimits
ErrorExecutionTimeCalculation = Result.ErrorExecutionTimeCalculation
ErrorSynchronizationCalculation = Result.ErrorSynchronizationCalculation
Time = Synchronization.Time
TimeIfNecessary = Synchronization.TimeIfNecessary
Phase = Synchronization.Phase
No = Synchronization.No
StraightLine = Synchronization.StraightLine
Position = ControlInterface.Position
Velocity = ControlInterface.Velocity
Continuous = DurationDiscretization.Continuous
Discrete = DurationDiscretization.Discrete

__all__ = [
    "Ruckig",
    "InputParameter",
    "OutputParameter",
    "Trajectory",
    "Bound",
    "Profile",
    "Result",
    "Synchronization",
    "ControlInterface",
    "DurationDiscretization",
    "RuckigError",
    "read_problem",
    "load_problem",
]
