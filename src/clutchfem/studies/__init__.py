"""Studies over many designs, all on one study engine (Dask, local or remote, with a
resumable SQLite store):

* parameter studies: :mod:`.spec` (the resolved :class:`StudySpec` and its points),
  :mod:`.schema` (the raw TOML structure and its errors), :mod:`.resolve` (a TOML spec ->
  a validated :class:`StudySpec`), :mod:`.sampling` (Latin hypercube, Sobol),
  :mod:`.point` (one point -> one row: the only module that calls the analysis),
  :mod:`.hashing`, :mod:`.store`, :mod:`.runner` (scheduling, resume, progress, summary),
  :mod:`.charts`;
* design guidelines: :mod:`.guidelines` (elasticities with a step-stability check,
  one-at-a-time sweeps), :mod:`.guideline_study` (running one), :mod:`.guideline_charts`;
* design to targets: :mod:`.batch` (batches of designs), :mod:`.optimization` (targets and
  a derivative-free search), :mod:`.tolerancing` (Monte Carlo of manufacturing
  tolerances), :mod:`.compensation` (shoe-profile compensation), :mod:`.values` (values
  that survive ``--set``), :mod:`.target_charts`, :mod:`.sensitivity` (derivatives of the
  answers on morphed meshes), :mod:`.robust` (targets that hold for a share of made parts).
"""

from . import target_charts
from .batch import EvalSettings, evaluate_many
from .compensation import Compensation, compensate
from .grid import run_grid
from .guideline_charts import summary_table
from .guideline_study import run_guidelines
from .guidelines import GuidelineResult, GuidelineSettings
from .hashing import design_hash
from .optimization import DIMENSIONLESS, OptimizationResult, Targets, default_free, fatigue_note, optimize
from .point import COLUMNS, Settings, evaluate, model_version
from .resolve import load_spec, parse_spec
from .robust import RobustResult, robust_optimize
from .runner import RunResult, StudyInterrupted, default_out, run_points, run_study
from .schema import SpecError
from .sensitivity import Sensitivities, sensitivities
from .spec import EXAMPLE_SPEC, StudySpec
from .store import STORE_NAME, ResultStore
from .tolerancing import ToleranceResult, parse_tolerance, tolerance
from .values import param_bounds, resolution

__all__ = ["param_bounds", "resolution", "COLUMNS", "DIMENSIONLESS", "EXAMPLE_SPEC", "STORE_NAME", "Compensation", "EvalSettings",
           "GuidelineResult", "GuidelineSettings", "OptimizationResult", "ResultStore", "RobustResult", "RunResult", "Settings",
           "Sensitivities", "SpecError", "StudyInterrupted", "StudySpec", "Targets", "ToleranceResult", "compensate",
           "default_free", "default_out", "design_hash", "evaluate", "evaluate_many", "fatigue_note", "load_spec",
           "model_version", "optimize", "parse_spec", "parse_tolerance", "run_grid", "run_guidelines",
           "robust_optimize", "run_points", "run_study", "sensitivities", "summary_table", "target_charts", "tolerance"]
