"""What a live answer needs of the analysis stage, without the FE stack: the idle speed of the
requirement checks, and the registry of the live answerer.

* :func:`idle_speed`: the idle speed of the check: the caller's, else the engine curve's,
  else :data:`DEFAULT_IDLE_RPM` (ASSUMED);
* :data:`LIVE`: the answerer of designs whose fidelity is ``"live"`` (the reduced model's,
  :func:`clutchfem.reduced.live_analysis`, registered by that stage when it is imported: it
  sits above this one, trained from these answers).

Nothing here imports the mesh or the FE model: a live ``analyze`` of a design a cached
reduced model holds loads neither (docs/reduced.md).
"""

from __future__ import annotations

import math

from ..clutch import EngineCurve
from ..core import ParameterError, UnitError, parse_quantity

__all__ = ["DEFAULT_IDLE_RPM", "LIVE", "idle_speed"]

#: the answerer of designs whose operating point's fidelity is ``"live"``: the reduced model's
#: (:func:`clutchfem.reduced.live_analysis`), registered by that stage when it is imported
#: (it sits above this one: it is trained from these answers).  ``import clutchfem`` and
#: ``clutchfem.analyze`` load it.
LIVE: list = []

#: Idle speed used when the engine curve carries none (typical saw idle): ASSUMED.
DEFAULT_IDLE_RPM = 2700.0


def idle_speed(engine: EngineCurve, idle_rpm: float | None = None) -> tuple[float, bool]:
    """(idle speed [rpm], True if it is the ASSUMED default): ``idle_rpm`` if given (a number
    in rpm or a string with its unit, ``"2700rpm"``), else the engine curve's, else
    :data:`DEFAULT_IDLE_RPM`; refuses anything but a finite speed > 0 below the engine
    curve's top speed (an engine idles below its full-throttle range's end)."""
    assumed = False
    if idle_rpm is None:
        idle_rpm = engine.idle_rpm
        if idle_rpm is None:
            idle_rpm, assumed = DEFAULT_IDLE_RPM, True
    raw = idle_rpm
    try:
        idle_rpm = parse_quantity(idle_rpm, "rpm")
    except UnitError:
        raise ParameterError("idle_rpm", raw, "an idle speed > 0 rpm (a number in rpm or a string with its "
                             "unit, e.g. '2700rpm')") from None
    if not (math.isfinite(idle_rpm) and idle_rpm > 0):
        raise ParameterError("idle_rpm", raw, "an idle speed > 0 rpm")
    top = engine.rpm_range[1]
    if idle_rpm >= top:
        raise ParameterError("idle_rpm", raw, f"an idle speed below the engine curve's top speed {top:g} rpm "
                             f"({engine.source}): is the idle speed or the curve in other units?")
    return idle_rpm, assumed
