from ._trajkit import Limits as Limits
