"""The requirement steps: the designer's engagement and slip factors, and the crankshaft
whirl against the engine's maximum speed.

* :func:`requirements_step`: engagement with ripple > a x idle rpm (the chain must not move
  at idle) and slip < b x rpm of maximum engine torque (the clutch must hold the engine
  before it reaches its torque peak), with the values checked and the limits
  (:class:`~clutchfem.analysis.Requirements`: a = 1.3, b = 1.0 ASSUMED, the thesis keeps
  them confidential);
* :func:`whirl_step`: the crankshaft's first critical speed with this clutch, drum and
  sprocket on its overhang (:func:`clutchfem.clutch.whirl`), wanted at least
  :data:`WHIRL_MARGIN` above the engine's maximum speed.
"""

from __future__ import annotations

from ..clutch import EngineCurve, whirl
from .answers import EngagementAnswer, Requirements, SlipAnswer

#: required margin of the first crankshaft critical speed over the engine's maximum speed
#: (ASSUMED: the usual 20-30 % separation rule for rotors running below their first critical)
WHIRL_MARGIN = 0.25


def requirements_step(req: Requirements, idle_rpm: float, engine: EngineCurve, eng: EngagementAnswer,
                      slip: SlipAnswer, in_range: bool) -> dict:
    """The two requirement checks (with the values checked and the limits; ``in_range``: the
    clutch engages within the engine's speed range, else the engagement check is void)."""
    eng_limit = req.a * idle_rpm
    slip_limit = req.b * engine.rpm_max_torque
    eng_r = eng.with_ripple_rpm
    return {"a": req.a, "b": req.b, "idle_rpm": float(idle_rpm), "rpm_max_torque": float(engine.rpm_max_torque),
            "engagement_limit_rpm": eng_limit, "engagement_checked_rpm": eng_r,
            "engagement_checked_with": "engagement with ripple (3 sigma cycle)",
            "slip_limit_rpm": slip_limit,
            "engagement_ok": bool((not in_range) or (eng_r is not None and eng_r > eng_limit)),
            "slip_ok": bool(slip.rpm is not None and slip.rpm < slip_limit),
            "assumed": ("a = 1.3 and b = 1.0 are ASSUMED defaults (confidential in the thesis)" if req.assumed
                        else "user factors a, b")}


def whirl_step(design, max_rpm: float):
    """The crankshaft's first critical (whirl) speed with this clutch, drum and sprocket
    (ASSUMED layout) on its overhang, against the engine's maximum speed ``max_rpm`` (a
    :class:`~clutchfem.clutch.WhirlAnswer`)."""
    return whirl(design, max_rpm=max_rpm)
