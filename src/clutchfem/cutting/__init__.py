"""Cutting stage: from a design to the part a cutter makes."""

from .features import CuttingError, Feature, check, measure
from .offset import offset_loop, offset_loops
from .outline import PartOutline, part_outline
from .rules import PROCESSES, ProcessRules

__all__ = ["PROCESSES", "CuttingError", "Feature", "PartOutline", "ProcessRules", "check", "measure",
           "offset_loop", "offset_loops", "part_outline"]
