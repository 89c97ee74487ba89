"""The study engine: many designs through the analysis on Dask (local or remote), each
finished row committed to a resumable SQLite store.

* a parameter study: :mod:`.spec` (the resolved :class:`StudySpec` and its points),
  :mod:`.schema` (the raw TOML structure and its errors), :mod:`.resolve` (a TOML spec ->
  a validated :class:`StudySpec`), :mod:`.sampling` (Latin hypercube, Sobol),
  :mod:`.grid` (a grid study without a TOML file);
* one point -> one row: :mod:`.point` (the only module that calls the analysis),
  :mod:`.values` (values that survive ``--set``), :mod:`.hashing`;
* running points: :mod:`.store`, :mod:`.runner` (scheduling, resume, progress, summary),
  :mod:`.cluster` (the Dask side: addresses, worker counts, faults), :mod:`.batch`
  (batches of designs for the layers above: design to targets, tolerances, guidelines);
* :mod:`.sensitivity`: derivatives of the answers on morphed meshes (a batch of designs);
* a finished study recognised without loading the FE stack: :mod:`.rerun`.

The layers above run on this engine: design to targets (:mod:`clutchfem.targets`),
tolerances (:mod:`clutchfem.tolerances`), design guidelines (:mod:`clutchfem.guidelines`);
the charts of a study are the report stage's (:mod:`clutchfem.report`), drawn by the faces.

The names are imported on first use (PEP 562, as :mod:`clutchfem` does): a command that
only needs the store or a finished study's summary does not load the analysis stack
(~3 s), so a rerun of a finished study costs a fraction of its first run.
"""

from __future__ import annotations

from ..core import lazy_names

#: public name -> the module of this package it lives in (None: the module itself)
_NAMES: dict[str, str | None] = {
    "ANSWERS": "point",
    "check_scheduler": "cluster",
    "ClusterError": "cluster",
    "COLUMNS": "point",
    "changed_texts": "values",
    "default_out": "rerun",
    "design_hash": "hashing",
    "display_value": "spec",
    "ERROR_COLUMNS": "runner",
    "EvalSettings": "batch",
    "evaluate": "point",
    "evaluate_many": "batch",
    "EXAMPLE_SPEC": "spec",
    "example_study": "spec",
    "finished_summary": "rerun",
    "fingerprint": "rerun",
    "geometry_dirs": "rerun",
    "GridResult": "grid",
    "load_study": "resolve",
    "model_version": "point",
    "operating_inputs": "sensitivity",
    "param_bounds": "values",
    "parse_spec": "resolve",
    "resolution": "values",
    "ResultStore": "store",
    "round12": "values",
    "run_grid": "grid",
    "run_points": "runner",
    "run_study": "runner",
    "RunResult": "runner",
    "Sensitivities": "sensitivity",
    "sensitivities": "sensitivity",
    "Settings": "point",
    "shared_cluster": "batch",
    "SpecError": "schema",
    "step_for": "sensitivity",
    "STORE_NAME": "store",
    "StoreLocked": "store",
    "StudyInterrupted": "runner",
    "StudyResult": "runner",
    "StudySpec": "spec",
    "values": None,
    "workers_machine_holds": "cluster",
}

__all__ = sorted(_NAMES)


__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
