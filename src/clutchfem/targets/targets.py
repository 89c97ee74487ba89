"""The targets of a design-to-targets search: the constraints (engagement with ripple,
slip speed, safety factors) and the objective, each design's assessment against them, and
targets that contradict each other refused at once.

Each constraint is scored as a relative violation v_j = max(0, (limit - value)/limit) (sign
by sense); a design's infeasibility is h = sum_j v_j (:mod:`.optimization` has the search).

Contradictions refused before any design is analysed (issue 24: they were searched for
seconds and then answered "no feasible design"): an engagement window LO >= HI, and a slip
maximum at or below the engagement minimum -- a clutch holds only once engaged, so its slip
speed is always above its static engagement speed, itself above the engagement with the
speed ripple (:func:`clutchfem.clutch.effective_engagement_rpm`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..analysis import DEFAULT_IDLE_RPM
from ..core import ParameterError

#: a constraint "binds" when its slack is below this share of its limit
BIND_SHARE = 0.02
OBJECTIVES = ("mass", "torque-margin")

__all__ = ["BIND_SHARE", "DIMENSIONLESS", "OBJECTIVES", "Targets"]

#: constraint keys without a unit (the safety factors; the others are speeds in rpm)
DIMENSIONLESS = ("safety_factor", "fatigue_safety_factor")


@dataclass(frozen=True)
class Targets:
    """The targets of an optimisation (limits in rpm, factors dimensionless); None: no such
    target.

    Parameters
    ----------
    engage_rpm_lo, engage_rpm_hi : float or None
        Engagement speed with the 2-stroke ripple within lo..hi (rpm).
    slip_rpm_max : float or None
        Slip speed (drum held, full throttle) at most this [rpm].
    safety_factor_min : float or None
        Safety factor against yield at the engine's maximum speed at least this.
    objective : {"mass", "torque-margin"}
    fatigue_min : float or None
        Fatigue safety factor at least this.

    Examples
    --------
    >>> import clutchfem as cf
    >>> t = cf.Targets(3510, None, 8000, 1.5)
    >>> [c[1] for c in t.constraints()]
    ['engagement_rpm_with_ripple', 'slip_rpm', 'safety_factor']
    """

    engage_rpm_lo: float | None
    engage_rpm_hi: float | None
    slip_rpm_max: float | None
    safety_factor_min: float | None
    objective: str = "mass"
    #: fatigue safety factor (analyze's step 10: Goodman, Miner, ASSUMED duty) >= this; None: no target
    fatigue_min: float | None = None

    def __post_init__(self):
        if self.objective not in OBJECTIVES:
            raise ParameterError("objective", self.objective, "one of " + ", ".join(OBJECTIVES), "optimize")
        for name in ("engage_rpm_lo", "engage_rpm_hi", "slip_rpm_max", "safety_factor_min", "fatigue_min"):
            v = getattr(self, name)
            if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v)
                                  or v <= 0):
                raise ParameterError(name, v, "a finite number > 0 (or no target)", "optimize")
        if self.engage_rpm_lo and self.engage_rpm_hi and self.engage_rpm_lo >= self.engage_rpm_hi:
            raise ParameterError("engage_rpm", f"{self.engage_rpm_lo:g}:{self.engage_rpm_hi:g}",
                                 "LO:HI with LO < HI [rpm]", "optimize")
        # a clutch slips only once engaged: slip > static engagement > engagement with
        # ripple, so a slip maximum at or below the engagement minimum has no design
        if self.engage_rpm_lo and self.slip_rpm_max and self.slip_rpm_max <= self.engage_rpm_lo:
            raise ParameterError("slip_rpm_max", f"{self.slip_rpm_max:g} rpm", f"a slip maximum above the engagement "
                                 f"minimum {self.engage_rpm_lo:g} rpm: contradictory targets (the clutch holds only "
                                 "above its engagement speed, so its slip speed is always higher); no design can "
                                 "meet both", "optimize")

    @classmethod
    def defaults(cls, settings, safety_factor_min: float = 1.5, objective: str = "mass") -> "Targets":
        """The requirement checks of ``settings`` (:class:`~clutchfem.evaluation.EvalSettings`):
        engagement with ripple >= a x idle rpm, slip <= b x rpm of max engine torque, and
        the safety factor against yield >= ``safety_factor_min``."""
        eng = settings.engine()
        idle = settings.idle_rpm or eng.idle_rpm or DEFAULT_IDLE_RPM
        return cls(settings.a * idle, None, settings.b * float(eng.rpm_max_torque), safety_factor_min, objective)

    def moved_inward(self, margins: dict) -> "Targets":
        """These targets with every limit moved inward by its margin (answer key -> margin in
        the answer's unit, >= 0; missing: 0)."""
        m = margins
        return replace(
            self,
            engage_rpm_lo=None if self.engage_rpm_lo is None else self.engage_rpm_lo + m.get("engagement_rpm_with_ripple", 0.0),
            engage_rpm_hi=None if self.engage_rpm_hi is None else self.engage_rpm_hi - m.get("engagement_rpm_with_ripple", 0.0),
            slip_rpm_max=None if self.slip_rpm_max is None else self.slip_rpm_max - m.get("slip_rpm", 0.0),
            safety_factor_min=None if self.safety_factor_min is None else self.safety_factor_min + m.get("safety_factor", 0.0),
            fatigue_min=None if self.fatigue_min is None else self.fatigue_min + m.get("fatigue_safety_factor", 0.0))

    def constraints(self) -> list[tuple[str, str, float, str]]:
        """(name, answer key, limit, sense '>=' or '<=')."""
        out = []
        if self.engage_rpm_lo is not None:
            out.append(("engagement with ripple >= LO", "engagement_rpm_with_ripple", self.engage_rpm_lo, ">="))
        if self.engage_rpm_hi is not None:
            out.append(("engagement with ripple <= HI", "engagement_rpm_with_ripple", self.engage_rpm_hi, "<="))
        if self.slip_rpm_max is not None:
            out.append(("slip speed <= max", "slip_rpm", self.slip_rpm_max, "<="))
        if self.safety_factor_min is not None:
            out.append(("safety factor at engine max >= min", "safety_factor", self.safety_factor_min, ">="))
        if self.fatigue_min is not None:
            out.append(("fatigue safety factor >= min", "fatigue_safety_factor", self.fatigue_min, ">="))
        return out

    def assess(self, row: dict) -> dict:
        """Constraint values, slacks, violations, infeasibility h and objective of a row
        (None for rows that are not 'ok')."""
        if row.get("status") != "ok":
            return {"h": math.inf, "objective": math.inf, "constraints": []}
        cons, h = [], 0.0
        for name, key, limit, sense in self.constraints():
            v = row.get(key)
            if v is None or not math.isfinite(v):
                # never engages / never holds / no slip speed / no fatigue answer: the target is missed outright
                miss = (key in ("slip_rpm", "fatigue_safety_factor")
                        or (key == "engagement_rpm_with_ripple" and sense == "<="))
                viol = 1.0 if miss else 0.0
                slack = -math.inf if miss else math.inf
            else:
                slack = (v - limit) if sense == ">=" else (limit - v)
                viol = max(0.0, -slack / limit)
            cons.append({"name": name, "key": key, "unit": "-" if key in DIMENSIONLESS else "rpm", "limit": limit,
                         "sense": sense, "value": v, "slack": slack,
                         "violation": viol, "violated": bool(viol > 0),
                         "binds": bool(math.isfinite(slack) and abs(slack) <= BIND_SHARE * limit)})
            h += viol
        obj = row["mass_kg"] if self.objective == "mass" else -row["torque_margin_Nm"]
        return {"h": h, "objective": float(obj), "constraints": cons}
