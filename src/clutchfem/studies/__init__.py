"""Studies over many designs, all on one study engine (Dask, local or remote, with a
resumable SQLite store):

* parameter studies: :mod:`.spec` (a TOML spec -> validated :class:`StudySpec` -> points),
  :mod:`.point` (one point -> one row: the only module that calls the analysis),
  :mod:`.hashing`, :mod:`.store`, :mod:`.runner` (scheduling, resume, progress, summary),
  :mod:`.charts`;
* :mod:`.guidelines`: elasticities with a step-stability check, one-at-a-time sweeps;
* design to targets: :mod:`.evaluate` (batches of designs), :mod:`.optimize` (targets and a
  derivative-free search), :mod:`.tolerance` (Monte Carlo of manufacturing tolerances),
  :mod:`.compensate` (shoe-profile compensation), :mod:`.values` (values that survive
  ``--set``), :mod:`.target_charts`.
"""

from .batch import EvalSettings, evaluate_many
from .compensation import Compensation, compensate
from .guidelines import GuidelineResult, GuidelineSettings, run_guidelines, summary_table
from .optimization import DIMENSIONLESS, OptimizationResult, Targets, default_free, fatigue_note, optimize
from .point import COLUMNS, Settings, evaluate, model_version
from .runner import RunResult, StudyInterrupted, default_out, run_grid, run_points, run_study
from .spec import EXAMPLE_SPEC, SpecError, StudySpec, load_spec, parse_spec
from .store import STORE_NAME, ResultStore
from .tolerancing import ToleranceResult, parse_tolerance, tolerance

__all__ = ["COLUMNS", "DIMENSIONLESS", "EXAMPLE_SPEC", "STORE_NAME", "Compensation", "EvalSettings",
           "GuidelineResult", "GuidelineSettings", "OptimizationResult", "ResultStore", "RunResult", "Settings",
           "SpecError", "StudyInterrupted", "StudySpec", "Targets", "ToleranceResult", "compensate",
           "default_free", "default_out", "evaluate", "evaluate_many", "fatigue_note", "load_spec",
           "model_version", "optimize", "parse_spec", "parse_tolerance", "run_grid", "run_guidelines",
           "run_points", "run_study", "summary_table", "tolerance"]
