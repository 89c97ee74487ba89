"""Reproductions of the source papers' numbers, one module per paper.

A validation module defines ``records() -> list[ValidationRecord]`` (and ``SOURCE``, the
paper in one line; optionally ``ORDER``, ``figures(out_dir)``, ``report_notes(records)``).
Drop it into this package and :mod:`clutchfem.validation.runner` (``clutchfem validate``)
discovers and runs it: the rules are in the runner's docstring.  A module of model code
that a paper module uses (``wiesik_model``) defines no ``records`` and is not run.

Re-exported here: the record (:class:`ValidationRecord`), the tolerance of a printed number
(:func:`printed_value`) and :func:`validate`, which runs them all (``clutchfem validate``).
"""

from .records import ValidationRecord, printed_value
from .runner import ValidationRun, validate

__all__ = ["ValidationRecord", "ValidationRun", "printed_value", "validate"]
