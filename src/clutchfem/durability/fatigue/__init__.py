"""High-cycle fatigue of the clutch from stress states (moved from ``durability/fatigue.py``;
split by job in the following commits)."""

from .check import *  # noqa: F403
from .check import __all__  # noqa: F401
