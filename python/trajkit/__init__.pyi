from ._trajkit import TrajkitError as TrajkitError, Trajectory as Trajectory, Limits as Limits, Plan as Plan, plan as plan
from . import spline as spline, poly as poly, otg as otg, topp as topp, primitives as primitives, batch as batch
__version__: str
