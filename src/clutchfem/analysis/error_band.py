"""The error step: the error of the main answers (engagement, slip, torque at the rpm of
maximum engine torque, peak stress), :mod:`clutchfem.accuracy`.

Discretisation: the same answers on a mesh twice as fine (:func:`~clutchfem.accuracy.refined_design`:
a second design, one more assembly and factorisation), Richardson's estimate at p = 1; a
user mesh (one level) and a 3-D model are not estimated.  Model form: the measured terms
(axial thickness 2-D vs 3-D, geometric non-linearity of the softening model, rigid vs 2 mm
steel drum), relative.  The total band of an answer is the sum of the magnitudes.
"""

from __future__ import annotations

from ..accuracy import ANSWERS, NOT_ESTIMATED, AnswerError, discretisation, model_form, refined_design
from ..clutch import EngineCurve
from .torque import FETorque, slip_step


def error_step(design, engine: EngineCurve, values: dict, w0_rpm: float | None,
               slip_rpm_value: float | None) -> dict:
    """The error of the main answers ``values`` (module docstring): per answer its value,
    discretisation, model-form terms and total.  ``w0_rpm``: the engagement speed and
    ``slip_rpm_value``: the slip speed, which the thickness term of the slip speed scales
    with (that of the torque with the rpm of maximum engine torque)."""
    lo, hi = engine.rpm_range
    coarse = {}
    cd = refined_design(design)
    if cd is not None:
        case = cd.case()
        coarse["engagement_rpm"] = case.engagement_rpm
        coarse["slip_rpm"] = slip_step(case, engine).rpm
        coarse["torque_at_max_engine_torque_Nm"] = float(FETorque(case)(float(engine.rpm_max_torque))[0])
        coarse["max_von_mises_Pa"] = float(cd.sweep([hi]).curve["max_von_mises_Pa"].iloc[0])
    out = {}
    for q, unit in ANSWERS.items():
        v = values.get(q)
        w = {"slip_rpm": slip_rpm_value, "torque_at_max_engine_torque_Nm": float(engine.rpm_max_torque)}.get(q)
        terms, notes = model_form(design, q, v, w0=w0_rpm, w=w)
        d = discretisation(v, coarse.get(q)) if cd is not None else None
        if cd is None:
            notes = notes + (NOT_ESTIMATED[design.op.formulation == "3d"],)
        out[q] = AnswerError(q, v, unit, d, terms, notes).as_dict()
    out["method"] = ("discretisation: 2 |a_h - a_h/2| (Richardson, p = 1) against the same design on a mesh twice "
                     "as fine; model form: measured terms (axial thickness 2-D vs 3-D, geometric non-linearity of "
                     "the softening model, rigid vs 2 mm steel drum), relative; total = sum of magnitudes")
    return out
