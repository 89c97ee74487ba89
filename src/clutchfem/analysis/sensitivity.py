"""The sensitivity of the main answers to the drum's ASSUMED wall: what the answers would be
with a thinner and a thicker drum, shown apart from the model error (issue 20).

The best-estimate path models the drum as a steel ring of 2 mm wall (ASSUMED: a pressed cup
of a 60 cc saw, :data:`clutchfem.loadcase.BEST_DRUM_WALL`); a real drum may be thinner or
thicker, which is an input the designer knows better than the tool, not an error of the
model.  The step solves the same design (same FE model and factorisation: only the drum's
compliance in the contact problem changes) with the wall -+ ``DRUM_WALL_DELTA`` and reports
each main answer there: engagement (moves only for a spinning drum), slip speed (its
crossings bracketed every :data:`~.torque.GRID_RPM_SENSITIVITY` rpm, as the mu
sensitivity's, and refined to 1e-9), torque at the rpm of maximum engine torque, peak stress
at the engine's maximum speed.  The friction
coefficient's sensitivity (mu x 0.7 / x 1.3) is :func:`~.torque.mu_sensitivity_step`'s.
"""

from __future__ import annotations

import math

from ..clutch import EngineCurve
from ..loadcase import sweep
from .torque import GRID_RPM_SENSITIVITY, FETorque, slip_step

#: the drum wall is varied by -+ this [m] (a 1.5-2.5 mm pressed cup around the 2 mm ASSUMED)
DRUM_WALL_DELTA = 0.5e-3
#: thinner walls than this are not varied below it [m] (the ring model's range)
MIN_WALL = 0.2e-3


def drum_sensitivity_step(design, engine: EngineCurve, rpm_torque: float, rpm_stress: float) -> dict | None:
    """The main answers with the drum wall -+ :data:`DRUM_WALL_DELTA` (module docstring):
    {"drum_wall_m": [thin, thick], "engagement_rpm": [..], "slip_rpm": [..],
    "torque_at_max_engine_torque_Nm": [..], "max_von_mises_Pa": [..]} (None where an answer
    does not exist), or None for a rigid drum (the fast path: its drum is a model-form term)."""
    wall = design.op.drum_wall_m
    if wall is None or design.nodes is None:
        return None
    walls = [max(wall - DRUM_WALL_DELTA, MIN_WALL), wall + DRUM_WALL_DELTA]
    out = {"drum_wall_m": walls, "engagement_rpm": [], "slip_rpm": [], "torque_at_max_engine_torque_Nm": [],
           "max_von_mises_Pa": []}
    for w in walls:
        case = design.case(drum_wall=w)
        out["engagement_rpm"].append(case.engagement_rpm)
        out["slip_rpm"].append(slip_step(case, engine, GRID_RPM_SENSITIVITY).rpm)
        out["torque_at_max_engine_torque_Nm"].append(float(FETorque(case)(float(rpm_torque))[0]))
        vm = float(sweep(case, [rpm_stress]).curve["max_von_mises_Pa"].iloc[0])
        out["max_von_mises_Pa"].append(vm if math.isfinite(vm) else None)
    return out
