import os
from typing import List, Optional, Tuple, Union
from ._trajkit import ArrayLike, FloatArray, TrajkitError

RuckigError = TrajkitError  # otg failures carry `result`, `kind` and `dof` (see TrajkitError)

class Result:
    Working: "Result"; Finished: "Result"; Error: "Result"; ErrorInvalidInput: "Result"
    ErrorPositionalLimits: "Result"; ErrorZeroLimits: "Result"; ErrorExecutionTimeCalculation: "Result"; ErrorSynchronizationCalculation: "Result"
    def __int__(self) -> int: ...
class Synchronization:
    Time: "Synchronization"; TimeIfNecessary: "Synchronization"; Phase: "Synchronization"; No: "Synchronization"
    StraightLine: "Synchronization"
class ControlInterface:
    Position: "ControlInterface"; Velocity: "ControlInterface"
class DurationDiscretization:
    Continuous: "DurationDiscretization"; Discrete: "DurationDiscretization"

class InputParameter:
    current_position: List[float]; current_velocity: List[float]; current_acceleration: List[float]
    target_position: List[float]; target_velocity: List[float]; target_acceleration: List[float]
    max_velocity: List[float]; max_acceleration: List[float]; max_jerk: List[float]
    min_velocity: Optional[List[float]]; min_acceleration: Optional[List[float]]
    min_position: List[float]; max_position: List[float]
    interrupt_calculation_duration: Optional[float]
    enabled: List[bool]; minimum_duration: Optional[float]
    synchronization: Synchronization; control_interface: ControlInterface
    duration_discretization: DurationDiscretization
    per_dof_synchronization: Optional[List[Synchronization]]
    per_dof_control_interface: Optional[List[ControlInterface]]
    intermediate_positions: List[List[float]]
    per_section_max_velocity: Optional[List[List[float]]]
    per_section_max_acceleration: Optional[List[List[float]]]
    per_section_max_jerk: Optional[List[List[float]]]
    per_section_minimum_duration: Optional[List[float]]
    # Ruckig Pro fields trajkit refuses: always None; setting a value raises RuckigError.
    per_section_min_velocity: None
    per_section_min_acceleration: None
    per_section_max_position: None
    per_section_min_position: None
    def __init__(self, dofs: int, max_number_of_waypoints: int = 0) -> None: ...
    @property
    def degrees_of_freedom(self) -> int: ...
    @classmethod
    def from_json(cls, text: str, source: str = "<json>") -> "InputParameter": ...
    def to_json(self, delta_time: Optional[float] = None, indent: Optional[int] = None) -> str: ...

class Bound:
    min: float; max: float; t_min: float; t_max: float

class Profile:
    t: List[float]; t_sum: List[float]; j: List[float]; a: List[float]; v: List[float]; p: List[float]
    pf: float; vf: float; af: float; brake_duration: float

class Trajectory:
    def __init__(self, dofs: int, max_number_of_waypoints: int = 0) -> None: ...
    @property
    def duration(self) -> float: ...
    @property
    def degrees_of_freedom(self) -> int: ...
    @property
    def was_interrupted(self) -> bool: ...
    @property
    def independent_min_durations(self) -> List[float]: ...
    @property
    def position_extrema(self) -> List[Bound]: ...
    @property
    def intermediate_durations(self) -> List[float]: ...
    @property
    def profiles(self) -> List[List[Profile]]: ...
    def at_time(self, time: float, return_section: bool = False) -> Union[Tuple[List[float], List[float], List[float]], Tuple[List[float], List[float], List[float], int]]: ...
    def get_first_time_at_position(self, dof: int, position: float, time_after: float = 0.0) -> Optional[float]: ...
    def __call__(self, t: ArrayLike, order: int = 0) -> FloatArray: ...

class OutputParameter:
    new_position: List[float]; new_velocity: List[float]; new_acceleration: List[float]; new_jerk: List[float]
    time: float; new_calculation: bool; was_calculation_interrupted: bool; calculation_duration: float
    degrees_of_freedom: int; new_section: int; did_section_change: bool; trajectory: Trajectory
    def __init__(self, dofs: int, max_number_of_waypoints: int = 0) -> None: ...
    def pass_to_input(self, input: InputParameter) -> None: ...
    def __copy__(self) -> "OutputParameter": ...

class Ruckig:
    degrees_of_freedom: int
    delta_time: float
    max_number_of_waypoints: int
    def __init__(self, dofs: int, delta_time: float = 0.0, max_number_of_waypoints: int = 0) -> None: ...
    def calculate(self, input: InputParameter, trajectory: Trajectory) -> Result: ...
    def update(self, input: InputParameter, output: OutputParameter) -> Result: ...
    def validate_input(self, input: InputParameter, check_current_state_within_limits: bool = False,
                       check_target_state_within_limits: bool = True) -> bool: ...
    def reset(self) -> None: ...

def read_problem(text: str, source: str = "<json>") -> Tuple[InputParameter, float]: ...
def load_problem(path: Union[str, "os.PathLike[str]"]) -> Tuple[InputParameter, float]: ...
