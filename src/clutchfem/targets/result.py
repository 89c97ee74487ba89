"""What :func:`~clutchfem.targets.optimize` returns (the FE search and the live one alike),
and how two assessed designs compare."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..core import clean
from ..evaluation import EvalSettings
from .best_check import best_estimate
from .targets import Targets

__all__ = ["NOISE_H", "NOISE_OBJ", "OptimizationResult", "better", "fatigue_note"]

#: an objective improvement smaller than this share is noise, not success
NOISE_OBJ = 1e-3
#: an infeasibility improvement smaller than this is noise
NOISE_H = 1e-4


def better(a: dict, b: dict | None) -> bool:
    """Is assessment ``a`` better than ``b`` by more than the noise margins (module docstring)?"""
    if b is None:
        return math.isfinite(a["h"])
    if not math.isfinite(a["h"]):
        return False
    fa, fb = a["h"] <= 0.0, b["h"] <= 0.0
    if fa != fb:
        return fa
    if not fa:
        return a["h"] < b["h"] - NOISE_H
    return a["objective"] < b["objective"] - NOISE_OBJ * max(abs(b["objective"]), 1e-12)


@dataclass
class OptimizationResult:
    """What :func:`optimize` returns: the best design found and how the search went.

    Attributes
    ----------
    best : dict
        The final design's study row (answers in SI, ``params``; its ``assessment`` against
        the targets: ``objective``, ``constraints``).
    feasible : bool
        The final design meets every target.
    params_texts, set_args : dict, list of str
        Its changed parameters as ``--set`` texts (``set_args``: base and final).
    path : list of dict
        Every evaluated row in order; ``evaluations``: status -> count.
    message, at_bounds, seconds, iterations
        Why the search stopped, the free parameters at a range end, the wall time [s].
    best_estimate : dict or None
        The final design checked with ``analyze``'s error step (:mod:`.best_check`).

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.targets import OptimizationResult
    >>> best = {"params": {}, "mass_kg": 0.0512, "fatigue_safety_factor": 0.8,
    ...         "assessment": {"objective": 0.0512, "constraints": []}}
    >>> r = OptimizationResult("concept4", cf.Targets(3510, None, 8000, 1.5), ["flexure_thickness"], {}, best, True,
    ...                        {"flexure_thickness": "1.8mm"}, ["flexure_thickness=1.8mm"], [],
    ...                        {"ok": 9, "refused": 2}, 12.0, 3, "converged")
    >>> j = r.to_json()
    >>> j["objective_value"], j["objective_unit"], j["evaluations_total"], j["set"]
    (0.0512, 'kg', 11, ['flexure_thickness=1.8mm'])
    >>> print(r.fatigue_note)                       # fatigue was no target, and the part fails it
    note: fatigue was not a target; the final design's fatigue safety factor is 0.80 < 1 ...
    """

    concept: str
    targets: Targets
    free: list[str]
    start_texts: dict
    best: dict  # the final row (with its assessment under "assessment")
    feasible: bool
    params_texts: dict  # the final design's changed parameters, --set texts
    set_args: list[str]  # base + final
    path: list[dict]
    evaluations: dict  # status -> count
    seconds: float
    iterations: int
    message: str
    at_bounds: list[str] = field(default_factory=list)
    settings: EvalSettings | None = None
    #: the final design checked with analyze and its error step (:mod:`.best_check`), and that
    #: Analysis (not in the JSON)
    best_estimate: dict | None = None
    best_analysis: object = field(default=None, repr=False)
    #: what answered the search: "FE", or (``fidelity="live"``) the reduced model, verified by the FE
    answered_by: str = "FE"
    #: a live search's region, live answers, counts, rounds and FE verification (:mod:`.live`)
    live: dict | None = None

    def final_analysis(self):
        """The final design's analysis with its errors: the one the optimiser's check made
        (:attr:`best_analysis`), else a new best estimate (:func:`best_estimate`)."""
        if self.best_analysis is not None:
            return self.best_analysis
        return best_estimate(self.settings, self.best["params"])

    @property
    def fatigue_note(self) -> str | None:
        """A warning when fatigue was not a target and the final design's fatigue safety
        factor is below 1 (None otherwise): :func:`fatigue_note`."""
        return fatigue_note(self)

    def to_json(self) -> dict:
        a = self.best.get("assessment", {})
        return clean({
            "concept": self.concept, "feasible": self.feasible, "message": self.message,
            "params": self.params_texts, "set": self.set_args, "free": self.free,
            "objective": self.targets.objective,
            "objective_value": a.get("objective") if self.targets.objective == "mass" else -a.get("objective", 0.0),
            "objective_unit": "kg" if self.targets.objective == "mass" else "N m",
            "constraints": a.get("constraints", []), "at_bounds": self.at_bounds,
            "answers": {k: self.best.get(k) for k in ("engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm",
                                                      "slip_status", "torque_at_max_engine_torque_Nm",
                                                      "torque_margin_Nm", "max_von_mises_Pa", "safety_factor",
                                                      "fatigue_safety_factor", "mass_kg", "contact_arc_deg")},
            "notes": [n for n in (fatigue_note(self),) if n],
            "evaluations": self.evaluations, "evaluations_total": sum(self.evaluations.values()),
            "seconds": self.seconds, "iterations": self.iterations, "start": self.start_texts,
            "targets": {"engage_rpm_lo": self.targets.engage_rpm_lo, "engage_rpm_hi": self.targets.engage_rpm_hi,
                        "slip_rpm_max": self.targets.slip_rpm_max,
                        "safety_factor_min": self.targets.safety_factor_min,
                        "fatigue_min": self.targets.fatigue_min},
            "units": {"rpm": "1/min", "stress": "Pa", "mass": "kg", "torque": "N m", "seconds": "s"},
            "best_estimate": self.best_estimate, "answered_by": self.answered_by,
            **({"live": self.live} if self.live is not None else {}),
            "path": [{k: v for k, v in r.items() if k != "warnings"} for r in self.path],
        })


def fatigue_note(res: "OptimizationResult") -> str | None:
    """A warning when fatigue was not a target and the final design's fatigue safety factor
    is below 1 (None otherwise)."""
    f = res.best.get("fatigue_safety_factor")
    if res.targets.fatigue_min is not None or f is None or f >= 1.0:
        return None
    return (f"note: fatigue was not a target; the final design's fatigue safety factor is {f:.2f} < 1 (ASSUMED "
            "duty, analyze's fatigue step): add --fatigue-min 1 to make it one")
