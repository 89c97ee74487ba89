"""Reproductions of the source papers' numbers, one module per paper.

A validation module defines ``records() -> list[ValidationRecord]`` (and ``SOURCE``, the
paper in one line; optionally ``ORDER``, ``figures(out_dir)``, ``report_notes(records)``).
Drop it into this package and :mod:`clutchfem.validation.runner` (``clutchfem validate``)
discovers and runs it: the rules are in the runner's docstring.
"""
