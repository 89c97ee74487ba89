"""Live answers: ``analyze`` of a design whose fidelity is ``"live"``, from the reduced model of
a region that contains it, in milliseconds and without a mesh.

:func:`live_analysis` looks for a cached reduced model whose region holds the design
(:func:`~.build.find`), builds one around it if there is none (:func:`~.build.reduce`, with
progress: minutes, once), and answers from it: an :class:`~clutchfem.Analysis` like the FE
path's, the main answers with their bands (the best path's band plus the reduced model's own
measured error), ``answered_by="reduced model"`` and a note naming the region.  What the
reduced model does not give (the curves against rpm, the plus/minus character, the fields,
the crankshaft whirl) is empty, and said so in the notes.

Where it cannot answer, it says which and falls back to the FE (the same design on the best
path, ``answered_by="FE (fallback)"``): a design whose free parameters lie outside the
region it was found in (never: a region is chosen because it holds the design), a design
where the full FE gives no answer (the status model), or an answer a design next to it does
not have.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..analysis import LIVE, Analysis, Requirements, analyze, idle_speed
from ..clutch import EngineCurve
from ..loadcase import design_inputs, design_label
from .build import find, reduce
from .model import ANSWERS

__all__ = ["MAIN", "live_analysis"]

#: the answers a live analysis needs (without one, the FE answers instead)
MAIN = ("engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm", "torque_at_max_engine_torque_Nm",
        "max_von_mises_Pa")


def _inputs(design, model, eng_info: dict, req: Requirements) -> dict:
    """The inputs that define a live answer: the design's (no mesh), the engine, the
    requirements and the reduced model's region."""
    return {**design_inputs(design), "engine": eng_info, "requirements": {"a": req.a, "b": req.b},
            "reduced_model": {"region": model.region.to_json(), "accuracy": model.accuracy}}


def live_analysis(design, *, engine: EngineCurve | None = None, requirements: Requirements | None = None,
                  idle_rpm: float | None = None, build: bool = True, progress: bool = True, **_ignored) -> Analysis:
    """The live answers of ``design`` (its operating point's fidelity ``"live"``): from the
    reduced model of a cached region that holds it, built first if there is none (module
    docstring); where the reduced model cannot answer, the FE's (said in ``answered_by`` and
    the notes)."""
    given = engine  # the region's key knows the built-in curve as "none given"
    engine = EngineCurve.of(engine)
    req = requirements or Requirements()
    model = find(design, engine=given, requirements=req)
    if model is None:
        if not build:
            return _fallback(design, engine, req, idle_rpm, "no reduced model holds this design (build=False)")
        model = reduce(design, engine=given, requirements=req, progress=progress)
    values = model.region.design_values(design)
    u = model.region.unit_of(values)[None, :]
    pred = model.predict(u)
    v = {a: float(pred["value"][a][0]) for a in pred["value"]}
    band = {a: float(pred["band"][a][0]) for a in pred["band"]}
    why = {a: str(pred["why"][a][0]) for a in pred["why"]}
    missing = [a for a in MAIN if not math.isfinite(v.get(a, math.nan))]
    if missing:
        reasons = sorted({why.get(a) or "not modelled" for a in missing})
        return _fallback(design, engine, req, idle_rpm, f"the reduced model gives no {', '.join(missing)} here: "
                         + "; ".join(reasons))
    return _answers(design, model, engine, req, idle_rpm, v, band, why)


def _fallback(design, engine, req, idle_rpm, why: str) -> Analysis:
    an = analyze(design.with_fidelity("best"), engine=engine, requirements=req, idle_rpm=idle_rpm)
    an.notes.append(f"answered by the FE (best path), not live: {why}")
    return replace(an, answered_by="FE (fallback)")


def _answers(design, model, engine, req, idle_rpm, v: dict, band: dict, why: dict) -> Analysis:
    idle, idle_assumed = idle_speed(engine, idle_rpm)
    hi = float(engine.rpm_range[1])
    ys = float(design.op.material.yield_strength)
    peak = v["max_von_mises_Pa"]
    eng_limit, slip_limit = req.a * idle, req.b * float(engine.rpm_max_torque)
    checks = {"a": req.a, "b": req.b, "idle_rpm": float(idle), "rpm_max_torque": float(engine.rpm_max_torque),
              "engagement_limit_rpm": eng_limit, "engagement_checked_rpm": v["engagement_rpm_with_ripple"],
              "engagement_checked_with": "engagement with ripple (3 sigma cycle), live",
              "slip_limit_rpm": slip_limit, "engagement_ok": bool(v["engagement_rpm_with_ripple"] > eng_limit),
              "slip_ok": bool(v["slip_rpm"] < slip_limit),
              "assumed": ("a = 1.3 and b = 1.0 are ASSUMED defaults (confidential in the thesis)" if req.assumed
                          else "user factors a, b")}
    eng_info = {"source": engine.source, "assumed_shape": engine.assumed, "rpm_range": list(engine.rpm_range),
                "max_torque_Nm": engine.max_torque, "rpm_max_torque": float(engine.rpm_max_torque),
                "idle_rpm": float(idle)}
    errors = {}
    for a, (_, _, unit, _) in ANSWERS.items():
        if a not in v or not math.isfinite(v[a]):
            continue
        own = model.accuracy.get(a, {}).get("max_rel")
        errors[a] = {"value": v[a], "unit": unit, "total": band[a], "discretisation": None,
                     "model_form": None, "reduced_model_rel": own,
                     "notes": [f"live: the best path's band of the designs next to it plus the reduced model's own "
                               f"error ({100 * own:.2g} %, the largest on {model.accuracy[a]['n']} held-out designs)"
                               if own is not None else "live"]}
    if "max_von_mises_Pa" in errors:
        rel = band["max_von_mises_Pa"] / peak
        errors["safety_factor"] = {"value": ys / peak, "unit": "-", "total": ys / peak * rel,
                                   "notes": ["yield strength / the live peak, its band"]}
    reg = model.region
    not_live = sorted(a for a in ANSWERS if a not in MAIN and not math.isfinite(v.get(a, math.nan)))
    notes = [f"live: answered by the reduced model of {reg.concept} over {reg.describe()} ({model.info.get('n_train')}"
             f" best-path designs; its error measured on {model.info.get('n_held_out')} others, in every band); the "
             "curves against rpm, the plus/minus character, the fields and the crankshaft whirl need the FE "
             "(--fidelity best)"]
    for a in not_live:
        notes.append(f"{a}: not given live ({why.get(a) or 'not modelled'}); --fidelity best gives it")
    if idle_assumed:
        notes.append(f"idle speed {idle:.0f} rpm ASSUMED (the engine curve gives none)")
    warnings = []
    if not checks["engagement_ok"]:
        warnings.append(f"ENGAGEMENT TOO EARLY (live): with ripple {v['engagement_rpm_with_ripple']:.0f} rpm <= "
                        f"{eng_limit:.0f} rpm (a x idle)")
    if not checks["slip_ok"]:
        warnings.append(f"SLIP TOO LATE (live): {v['slip_rpm']:.0f} rpm >= {slip_limit:.0f} rpm (b x rpm of max "
                        "engine torque)")
    if peak > ys:
        warnings.append(f"STRESS ABOVE YIELD (live): peak von Mises {peak / 1e6:.0f} MPa at {hi:.0f} rpm exceeds "
                        f"the yield strength {ys / 1e6:.0f} MPa")
    t = v["torque_at_max_engine_torque_Nm"]
    mass = v.get("mass_kg", math.nan)
    an = Analysis(design=design.name, engagement_rpm=v["engagement_rpm"],
                  engagement_rpm_with_ripple=v["engagement_rpm_with_ripple"], engagement_rpm_with_ripple_typical=None,
                  engagement_note="live (reduced model)", slip_rpm=v["slip_rpm"], slip_status="slips",
                  slip_note="live (reduced model)", slip_crossings_rpm=[],
                  rpm_max_engine_torque=float(engine.rpm_max_torque), max_engine_torque_Nm=engine.max_torque,
                  torque_at_max_engine_torque_Nm=t, torque_margin_Nm=t - engine.max_torque, max_engine_rpm=hi,
                  max_von_mises_Pa=peak, safety_factor=ys / peak, max_stress_rpm=hi, max_stress_location_m=[],
                  yield_strength_Pa=ys, slip_power_W=float(engine.torque_at(v["slip_rpm"]) * v["slip_rpm"] * np.pi / 30),
                  shoe_character="not computed (live)", shoe_character_per_shoe=[], mu=float(design.op.mu),
                  mu_sensitivity={}, torque_models_at_max_engine_torque_Nm={"rpm": float(engine.rpm_max_torque), "fe_torque_Nm": t},
                  contact_arc_at_max_engine_torque_deg=v.get("contact_arc_deg", math.nan), requirements=checks,
                  engine=eng_info, coupling={}, curves=_engine_only(engine), first_touch=None,
                  warnings=warnings, notes=notes,
                  part=({"mass_kg": mass, "thickness_m": float(design.thickness), "source": "live (reduced model)"}
                        if math.isfinite(mass) else {}), analytical_available=False,
                  inputs=_inputs(design, model, eng_info, req), label=design_label(design), design_hash=design.hash,
                  fatigue_safety_factor=v.get("fatigue_safety_factor"), errors=errors,
                  answered_by="reduced model", region_key=reg.key())
    return an


def _engine_only(engine: EngineCurve) -> dict:
    """The curves of a live answer: the engine's only (the clutch's against rpm needs the FE), as
    columns (:attr:`Analysis.curves` makes the DataFrame when it is read: no pandas at start-up)."""
    rpm = np.linspace(*map(float, engine.rpm_range), 61)
    return {"rpm": rpm, "engine_torque_Nm": np.asarray(engine.torque_at(rpm), float)}


LIVE.append(live_analysis)
