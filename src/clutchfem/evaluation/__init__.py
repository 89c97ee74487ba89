"""The study engine: designs through the analysis on Dask (local or remote), each finished row
committed to a resumable SQLite store.  Every layer that evaluates many designs stands on
it: parameter studies (:mod:`clutchfem.studies`), design to targets
(:mod:`clutchfem.targets`), tolerances (:mod:`clutchfem.tolerances`) and design guidelines
(:mod:`clutchfem.guidelines`).

* one point -> one row: :mod:`.point` (the only module that calls the analysis; the row's
  columns), :mod:`.hashing` (a point's design hash);
* running points: :mod:`.store` (the SQLite store), :mod:`.runner` (:func:`run_points`:
  scheduling, resume, progress), :mod:`.cluster` (the Dask side: addresses, worker counts,
  faults);
* :mod:`.batch`: the design and how its variants are evaluated (:class:`EvalSettings`), and
  batches of designs on one cluster;
* :mod:`.sensitivity`: derivatives of the answers on morphed meshes (a batch of designs).

The names are imported on first use (PEP 562): a command that needs only the store does not
load the analysis stack (~3 s).
"""

from __future__ import annotations

from ..core import lazy_names

#: public name -> the module of this package it lives in
_NAMES: dict[str, str] = {
    "ANSWERS": "point",
    "check_scheduler": "cluster",
    "ClusterError": "cluster",
    "COLUMNS": "point",
    "context_hash": "hashing",
    "design_hash": "hashing",
    "ERROR_COLUMNS": "point",
    "EvalSettings": "settings",
    "evaluate": "point",
    "evaluate_many": "batch",
    "model_version": "point",
    "operating_inputs": "sensitivity",
    "ResultStore": "store",
    "run_points": "runner",
    "RunResult": "runner",
    "Sensitivities": "sensitivity",
    "sensitivities": "sensitivity",
    "Settings": "settings",
    "shared_cluster": "batch",
    "step_for": "sensitivity",
    "STORE_NAME": "store",
    "StoreLocked": "store",
    "StudyInterrupted": "runner",
    "workers_machine_holds": "cluster",
}

__all__ = sorted(_NAMES)


__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
