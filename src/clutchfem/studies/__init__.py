"""Studies over many designs, all on one study engine (Dask, local or remote, with a
resumable SQLite store):

* parameter studies: :mod:`.spec` (the resolved :class:`StudySpec` and its points),
  :mod:`.schema` (the raw TOML structure and its errors), :mod:`.resolve` (a TOML spec ->
  a validated :class:`StudySpec`), :mod:`.sampling` (Latin hypercube, Sobol),
  :mod:`.point` (one point -> one row: the only module that calls the analysis),
  :mod:`.hashing`, :mod:`.store`, :mod:`.runner` (scheduling, resume, progress, summary),
  :mod:`.cluster` (the Dask side: addresses, worker counts, faults),
  :mod:`.charts`;
* design guidelines: :mod:`.guidelines` (elasticities with a step-stability check,
  one-at-a-time sweeps), :mod:`.guideline_study` (running one), :mod:`.guideline_charts`;
* design to targets: :mod:`.batch` (batches of designs), :mod:`.optimization` (targets, the
  search and its pattern-search method), :mod:`.gradient` (the gradient method on morphed
  meshes, with :mod:`.sqp` its model pieces and :mod:`.rules` the concept's rules as linear
  constraints), :mod:`.tolerancing` (Monte Carlo of manufacturing
  tolerances), :mod:`.compensation` (shoe-profile compensation), :mod:`.values` (values
  that survive ``--set``), :mod:`.target_charts`, :mod:`.sensitivity` (derivatives of the
  answers on morphed meshes), :mod:`.robust` (targets that hold for a share of made parts), :mod:`.allocation`
  (tolerance allocation for a yield, the mass-yield trade-off) with its algebra
  :mod:`.tolerance_algebra`;
* a finished study recognised without loading the FE stack: :mod:`.rerun`.

The names are imported on first use (PEP 562, as :mod:`clutchfem` does): a command that
only needs the store or a finished study's summary does not load the analysis stack
(~3 s), so a rerun of a finished study costs a fraction of its first run.
"""

from __future__ import annotations

from ..core import lazy_names

#: public name -> the module of this package it lives in (None: the module itself)
_NAMES: dict[str, str | None] = {
    "allocate_linear": "tolerance_algebra",
    "allocate_tolerances": "allocation",
    "best_estimate": "best_check",
    "Allocation": "allocation",
    "check_address": "cluster",
    "ClusterError": "cluster",
    "COLUMNS": "point",
    "compensate": "compensation",
    "Compensation": "compensation",
    "default_free": "search_space",
    "default_out": "rerun",
    "finished_summary": "rerun",
    "fingerprint": "rerun",
    "geometry_dirs": "rerun",
    "design_hash": "hashing",
    "DIMENSIONLESS": "optimization",
    "EvalSettings": "batch",
    "evaluate": "point",
    "evaluate_many": "batch",
    "EXAMPLE_SPEC": "spec",
    "fatigue_note": "optimization",
    "GuidelineResult": "guidelines",
    "GuidelineSettings": "guidelines",
    "joint_scale": "tolerance_algebra",
    "joint_yield": "tolerance_algebra",
    "load_spec": "resolve",
    "model_version": "point",
    "OptimizationResult": "optimization",
    "optimize": "optimization",
    "param_bounds": "values",
    "parse_spec": "resolve",
    "parse_tolerance": "tolerancing",
    "resolution": "values",
    "ResultStore": "store",
    "RobustResult": "robust",
    "robust_optimize": "robust",
    "run_grid": "grid",
    "run_guidelines": "guideline_study",
    "run_points": "runner",
    "run_study": "runner",
    "RunResult": "runner",
    "Sensitivities": "sensitivity",
    "sensitivities": "sensitivity",
    "Settings": "point",
    "shown": "allocation",
    "SpecError": "schema",
    "STORE_NAME": "store",
    "StoreLocked": "store",
    "StudyInterrupted": "runner",
    "StudySpec": "spec",
    "summary_table": "guideline_charts",
    "target_charts": None,
    "Targets": "targets",
    "tolerance": "tolerancing",
    "ToleranceResult": "tolerancing",
    "why_no_answer": "guideline_study",
    "yield_front": "allocation",
    "workers_machine_holds": "cluster",
}

__all__ = sorted(_NAMES)


__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
