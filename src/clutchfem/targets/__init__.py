"""Design to targets: the lightest design (or the largest torque margin) that meets a
designer's targets, and the shoe profile that spreads the contact evenly.

* :mod:`.targets` (:class:`Targets`: the constraints, the objective, each design's
  assessment against them, contradictions refused at once);
* :mod:`.search_space` (the free parameters and their ranges on the unit box);
* :mod:`.optimization` (:func:`optimize`: a space-filling sample, then the pattern search or
  :mod:`.gradient`, the gradient method on morphed meshes with :mod:`.sqp` its model pieces
  and :mod:`.rules` the concept's rules as linear constraints);
* :mod:`.best_check` (the optimum checked with :func:`~clutchfem.analyze`'s own answers);
* :mod:`.life_design` (:func:`optimize_for_life`: ``optimize --life N``, the targets tightened
  by the wear allowance of a life run and the optimum checked by a full one);
* :mod:`.compensation` (:func:`compensate`: the shoe-profile table that evens the contact
  pressure at one speed).

Every design is evaluated on the study engine (:mod:`clutchfem.studies`: Dask, the
resumable store); the made parts' tolerances are the layer above (:mod:`clutchfem.tolerances`).
"""

from .best_check import analysed_answers, best_estimate, check_optimum, correction_ratios, start_targets
from .compensation import Compensation, CompensationStep, ShoeState, compensate, evenness, shoe_state
from .life_design import LifeDesign, WearAllowance, life_check, optimize_for_life, wear_allowance
from .optimization import METHODS, optimize
from .result import OptimizationResult, better, fatigue_note
from .rules import bisect
from .search_space import Space, make_space
from .targets import DIMENSIONLESS, OBJECTIVES, Targets

__all__ = ["DIMENSIONLESS", "METHODS", "OBJECTIVES", "Compensation", "CompensationStep", "LifeDesign", "WearAllowance", "life_check", "optimize_for_life", "wear_allowance", "OptimizationResult",
           "ShoeState", "Space", "Targets", "analysed_answers", "best_estimate", "better", "bisect",
           "check_optimum", "compensate", "correction_ratios", "evenness", "fatigue_note",
           "make_space", "optimize", "shoe_state", "start_targets"]
