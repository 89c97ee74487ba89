"""Slip heat: transient heat conduction in a one-piece clutch while it slips in a held drum
(moved from ``durability/heat.py``; split by job in the following commits)."""

from .slip import *  # noqa: F403
from .slip import __all__  # noqa: F401
