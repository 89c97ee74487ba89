"""Tolerances: what the made parts do, and the design that holds for a share of them.

* :mod:`.tolerancing` (:func:`tolerance`: Monte Carlo of manufacturing tolerances on the
  study engine, the share of parts out of spec with its interval, the ranking of the
  dimensions; :mod:`.ranking`: the dimensions' standardised regression coefficients with
  their bootstrap intervals);
* :mod:`.algebra` (the linearised algebra of joint yields and tolerance scales);
* :mod:`.allocation` (:func:`allocate_tolerances`: the widest tolerance per dimension for
  a yield; :func:`yield_front`: part mass against yield over a set of designs);
* :mod:`.robust` (:func:`robust_optimize`: the lightest design that meets every target
  for a share of made parts, by shifted deterministic rounds).

It stands on design to targets (:mod:`clutchfem.targets`) and the study engine
(:mod:`clutchfem.studies`).
"""

from .algebra import allocate_linear, check_yield, joint_scale, joint_yield
from .allocation import Allocation, YieldFront, allocate_tolerances, yield_front
from .robust import RobustResult, model_bands, robust_optimize
from .tolerancing import ToleranceResult, parse_tolerance, tolerance

__all__ = ["Allocation", "RobustResult", "ToleranceResult", "allocate_linear", "allocate_tolerances",
           "check_yield", "joint_scale", "joint_yield", "model_bands", "parse_tolerance", "robust_optimize",
           "tolerance", "YieldFront", "yield_front"]
