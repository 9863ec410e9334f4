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
when ``update`` used all of it) are supported. Failures raise ``RuckigError`` with the
library's message and ``result`` (the ``Result`` member: ``ErrorInvalidInput``,
``ErrorPositionalLimits``, ``ErrorZeroLimits``, ``ErrorExecutionTimeCalculation``,
``ErrorSynchronizationCalculation``), ``kind`` (``'invalid_input'``, ``'position_limits'``,
``'zero_limits'``, ``'interrupted'``, ``'calculation_failed'``, ``'synchronization_failed'``)
and ``dof`` (or ``None``). A budget that runs out before any valid trajectory is known raises
with ``kind == 'interrupted'`` and ``result == Result.ErrorExecutionTimeCalculation``.
Not supported (Ruckig Pro features): intermediate waypoints and per-section limits; setting
those attributes raises ``AttributeError``.

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
]
