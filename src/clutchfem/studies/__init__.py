"""Parameter studies: a study spec (TOML) or a grid of values -> many designs on the study
engine (:mod:`clutchfem.evaluation`) -> a table, a summary and (drawn by the faces, from
:mod:`clutchfem.report`) the charts.

* the spec: :mod:`.schema` (the raw TOML structure and its errors), :mod:`.resolve` (a TOML
  spec -> a validated :class:`StudySpec`), :mod:`.spec` (:class:`StudySpec` and its points),
  :mod:`.sampling` (Latin hypercube, Sobol);
* running one: :mod:`.study` (:func:`run_study` -> :class:`StudyResult`), :mod:`.grid`
  (:func:`run_grid`: a grid without a TOML file);
* a finished study recognised without loading the FE stack: :mod:`.rerun`.

The names are imported on first use (PEP 562, as :mod:`clutchfem` does): a command that
only needs a finished study's summary does not load the analysis stack (~3 s), so a rerun
of a finished study costs a fraction of its first run.
"""

from __future__ import annotations

from ..core import lazy_names

#: public name -> the module of this package it lives in
_NAMES: dict[str, str] = {
    "default_out": "rerun",
    "display_value": "spec",
    "EXAMPLE_SPEC": "spec",
    "example_study": "spec",
    "finished_summary": "rerun",
    "fingerprint": "rerun",
    "geometry_dirs": "rerun",
    "GridResult": "grid",
    "load_study": "resolve",
    "parse_spec": "resolve",
    "run_grid": "grid",
    "run_study": "study",
    "SpecError": "schema",
    "StudyResult": "study",
    "StudySpec": "spec",
}

__all__ = sorted(_NAMES)


__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
