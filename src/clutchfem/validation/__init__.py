"""Reproductions of the source papers' numbers, one module per paper.

A validation module defines ``records() -> list[ValidationRecord]`` (and ``SOURCE``, the
paper in one line; optionally ``ORDER``, ``figures(out_dir)``, ``report_notes(records)``).
Drop it into this package and :mod:`clutchfem.validation.runner` (``clutchfem validate``)
discovers and runs it: the rules are in the runner's docstring.  A module of model code
that a paper module uses (``wiesik_model``) defines no ``records`` and is not run.

Re-exported here: the record (:class:`ValidationRecord`) and the tolerance of a printed
number (:func:`printed_value`).  The runner is used as the module it is
(``from clutchfem.validation import runner``), not re-exported: importing it with the package
would make ``python -m clutchfem.validation.runner`` find it loaded twice.
"""

from .records import ValidationRecord, printed_value

__all__ = ["ValidationRecord", "printed_value"]
