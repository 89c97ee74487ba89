"""From a design to the answers a clutch designer asks for: the steps of an analysis, in order.

:func:`run_steps` runs, on one :class:`~clutchfem.loadcase.Design` (one FE model, one
factorisation for everything below; :func:`clutchfem.analysis.analyze` checks the inputs and
hands a live design to the reduced model instead, without loading this module):

1. :func:`~.torque.slip_step`: the slip speed with the drum held, from the *exact* FE
   torque (crossings bracketed on a fixed internal grid and refined by bisection with FE
   solves: the answer does not depend on the speeds the user asked to tabulate);
2. :func:`~.torque.fe_sweep`: the FE speed sweep with stresses on the output speeds, to
   which the engagement and slip speeds, the rpm of maximum engine torque and the engine's
   maximum speed are added (every answer is read at a solved speed, never interpolated);
3. :func:`~.torque.engagement_step`: static engagement (FE, closed form) and with the
   2-stroke ripple;
4. :func:`~.torque.character_step`: plus/minus character per shoe (normal force with and
   without friction at the rpm of maximum engine torque, :func:`~.torque.probe_speed`);
5. :func:`~.torque.mu_sensitivity_step`: torque and slip speed at mu x 0.7 and x 1.3;
6. :func:`~.coupling.coupling_step`: the analytical plus/minus shoe model fitted to the FE,
   and the part's mass properties (:func:`clutchfem.mesh.mesh_mass_properties`);
7. :func:`~.strength.stress_step`: peak stress and safety factor at the engine's maximum
   speed (re-solved there with the per-speed factorisation where the pre-stress Ritz space
   leaves a residual, :func:`~.strength.peak_sweep`);
8. :func:`~.requirements.requirements_step`: engagement > a x idle, slip < b x rpm of max
   engine torque;
9. :func:`~.error_band.error_step`: the error of engagement, slip, torque and peak stress
   (:mod:`clutchfem.accuracy`: a mesh twice as fine, measured model-form terms) and their
   sensitivity to the assumed drum wall (:func:`~.sensitivity.drum_sensitivity_step`) and
   friction coefficient, apart from the band.  On the best-estimate path
   (:func:`~.strength.best_estimate`) the peak stress and the torque are corrected there,
   not only banded: their geometric non-linearity per design
   (:func:`~.strength.nonlinearity_step`, total-Lagrangian solves of the plane-stress twin
   at the engine's maximum speed and the rpm of its maximum torque) and the peak's
   discretisation (the finer mesh also refines the disc at the peak; Richardson's
   extrapolation from the two levels); the peak, safety factor, torque and torque margin
   reported are the corrected ones (the curves stay the linear model's).  An answer whose
   band exceeds its accuracy target because of its discretisation is computed once more on
   a mesh four times as fine and reported from there (:mod:`.refinement`; engagement and slip
   so refined also replace the analysis's, and the requirement checks are redone);
10. :func:`~.requirements.whirl_step`: the crankshaft's first critical speed with this
    clutch on its overhang (:mod:`clutchfem.clutch.crankshaft`) against the engine's
    maximum speed;
11. :func:`~.strength.fatigue_step`: the fatigue safety factor (Goodman, Miner) at the
    worst point, named, under start-stop and running-revolution cycles built from solved
    states (:mod:`clutchfem.durability`).

Each step is a small function ``(design or results, inputs) -> frozen answer``
(:mod:`.answers`); the warnings and notes are written from the answers at the end
(:mod:`.messages`), and :class:`~.answers.Analysis` collects what the report renders
(:mod:`clutchfem.report`).  The order is the order of the FE work: later steps reuse the
contact states the earlier ones solved (memoised per load case).
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from ..clutch import EngineCurve
from ..core import EquilibriumError, rpm_to_rad_s
from ..loadcase import design_inputs, design_label
from ..mesh import mesh_mass_properties
from .answers import Analysis, Requirements
from .coupling import answer_curves, coupling_step, torque_models
from .error_band import error_step
from .idle import idle_speed
from .messages import design_notes, design_warnings
from .requirements import requirements_step, whirl_step
from .sensitivity import drum_sensitivity_step
from .strength import fatigue_step, nonlinearity_step, peak_sweep, stress_step
from .torque import (
    character_step,
    check_speeds,
    contact_sets_step,
    engagement_step,
    fe_sweep,
    mu_sensitivity_step,
    probe_speed,
    slip_step,
)


def run_steps(design, engine: EngineCurve, req: Requirements, idle_rpm, ripple_model, errors: bool, fatigue_loads,
              fatigue_params) -> Analysis:
    """The steps (module docstring) on the inputs :func:`~.front.analyze` checked; a design whose
    pre-stress Ritz space misses equilibrium is solved again with the per-speed factorisation
    (said in the notes)."""
    try:
        return _steps(design, engine, req, idle_rpm, ripple_model, errors, fatigue_loads, fatigue_params)
    except EquilibriumError as exc:
        if design.op.softening != "prestress":
            raise
        # the pre-stress Ritz space misses equilibrium (a soft design far past engagement):
        # the same design with the per-speed factorisation, said in the notes
        t = time.perf_counter()
        an = _steps(design.with_softening("prestress-exact"), engine, req, idle_rpm, ripple_model, errors,
                    fatigue_loads, fatigue_params)
        an.notes.append(f"spin softening: the pre-stress Ritz space missed equilibrium ({str(exc).split(':')[0]}); "
                        f"solved with the per-speed factorisation instead (softening prestress-exact, "
                        f"{time.perf_counter() - t:.1f} s)")
        return an


def refined_answers(err: dict, t_nom, eng, slip, checks, check):
    """(torque, engagement, slip, requirement checks) with the answers the error step refined
    once more to meet their accuracy target (:mod:`.refinement`: ``corrections`` holding
    ``mesh_refinement``) taken from it; the engagement with ripple moves by the same ratio as
    the static one (it is computed from it), and the checks are redone (``check(eng, slip)``)."""
    def refined(q):
        e = err.get(q) or {}
        return e.get("value") if "mesh_refinement" in (e.get("corrections") or {}) else None

    t = refined("torque_at_max_engine_torque_Nm")
    w0, ws = refined("engagement_rpm"), refined("slip_rpm")
    if w0 is not None and eng.static_rpm:
        r = w0 / eng.static_rpm
        eng = replace(eng, static_rpm=w0, with_ripple_rpm=None if eng.with_ripple_rpm is None else eng.with_ripple_rpm * r,
                      with_ripple_typical_rpm=None if eng.with_ripple_typical_rpm is None
                      else eng.with_ripple_typical_rpm * r)
    if ws is not None:
        slip = replace(slip, rpm=ws)
    if w0 is not None or ws is not None:
        checks = check(eng, slip)
    return (t_nom if t is None else t), eng, slip, checks


def _steps(design, engine, req, idle_rpm, ripple_model, errors, fatigue_loads, fatigue_params) -> Analysis:
    """The steps of :func:`run_steps` on checked inputs."""
    idle_rpm, idle_assumed = idle_speed(engine, idle_rpm)
    hi = engine.rpm_range[1]
    op, material = design.op, design.model.material
    rpm = check_speeds(None if op.rpm is None else op.speeds(), engine)
    case = design.case()
    # 1-3: slip (exact FE crossings), the sweep (output speeds plus the engagement and slip
    # speeds, so the curves hold the exact answers), engagement with ripple
    slip = slip_step(case, engine)
    in_range = slip.status != "never engages"
    key = [x for x in (case.engagement_rpm, slip.rpm) if x is not None and 0 <= x <= hi]
    res = fe_sweep(design, np.union1d(rpm, key))
    eng = engagement_step(res, ripple_model, in_range, slip)
    # 4-5: character and mu sensitivity at the rpm of max engine torque (engine max if the
    # clutch is not engaged there)
    probe = probe_speed(res, engine)
    ch = character_step(design, probe)
    character = ch.overall if in_range else "never engages"
    sens = mu_sensitivity_step(design, engine, probe, slip)
    # 6: analytical coupling, the part's mass (3-D: its own basis)
    coupling, curves = coupling_step(design, res)
    basis = design.model.basis if design.model.basis.mesh is design.cm.mesh else None
    part = mesh_mass_properties(design.cm, material.rho, design.thickness, basis)
    models, arc_probe = torque_models(res, curves, float(engine.rpm_max_torque))
    t_nom = models["fe_torque_Nm"]
    # 7: stress at the engine's maximum speed
    res_peak, peak_exact = peak_sweep(design, res, hi)
    st = stress_step(res_peak, hi, material)
    curves = answer_curves(res, curves, coupling, engine)
    # 8-11: requirements, error of the main answers, crankshaft whirl, fatigue
    checks = requirements_step(req, idle_rpm, engine, eng, slip, in_range)
    drum = drum_sensitivity_step(design, engine, float(engine.rpm_max_torque), hi) if errors else None
    t_rpm = float(engine.rpm_max_torque)
    nl, nl_why = nonlinearity_step(design, hi, t_rpm if t_nom is not None and t_nom > 0 else None) if errors else (None, None)
    err = error_step(design, engine, {"engagement_rpm": eng.static_rpm, "slip_rpm": slip.rpm,
                                      "torque_at_max_engine_torque_Nm": t_nom,
                                      "max_von_mises_Pa": st.max_von_mises_Pa},
                     eng.static_rpm, slip.rpm, drum=drum, mu=sens.to_json(),
                     peak_at=st.location_m, nl=nl, peak_exact=peak_exact,
                     # (the pre-stress check's residual is the displacement error; another's is a force)
                     residual=(res.rpm, res.curve["residual"].to_numpy())
                     if getattr(case.response, "precondition_check", False) else None) if errors else {}
    if nl is not None:  # the best estimate's peak and torque: corrected in the error step
        st = st.corrected(err["max_von_mises_Pa"]["value"])
        t_nom = err["torque_at_max_engine_torque_Nm"]["value"]
    # the contact sets of the design mesh's own states (before an answer is refined on a finer mesh)
    sets = contact_sets_step(case, {"slip": slip.rpm, "torque": t_rpm, "peak": float(hi)})
    t_nom, eng, slip, checks = refined_answers(err, t_nom, eng, slip, checks,
                                               lambda e, s: requirements_step(req, idle_rpm, engine, e, s, in_range))
    slip_power = None if slip.rpm is None else float(engine.torque_at(slip.rpm) * rpm_to_rad_s(slip.rpm))
    wh = whirl_step(design, hi)
    fat = fatigue_step(design, res, engine, loads=fatigue_loads, params=fatigue_params, ripple_model=ripple_model)
    warnings = design_warnings(res=res, material=material, mu=op.mu, slip=slip, eng=eng, ch=ch, character=character,
                               coupling=coupling, st=st, wh=wh, fat=fat, checks=checks)
    if nl_why:
        warnings.append(nl_why)
    notes = design_notes(engine=engine, req=req, idle_assumed=idle_assumed, ch=ch, cm=design.cm, sens=sens,
                         coupling=coupling, fat=fat)
    eng_info = {"source": engine.source, "assumed_shape": engine.assumed, "rpm_range": list(engine.rpm_range),
                "max_torque_Nm": engine.max_torque, "rpm_max_torque": float(engine.rpm_max_torque),
                "idle_rpm": float(idle_rpm)}
    return Analysis(design=design.name, engagement_rpm=eng.static_rpm,
                    engagement_rpm_with_ripple=eng.with_ripple_rpm,
                    engagement_rpm_with_ripple_typical=eng.with_ripple_typical_rpm, engagement_note=eng.note,
                    slip_rpm=slip.rpm, slip_status=slip.status, slip_note=slip.note,
                    slip_crossings_rpm=[{"rpm": r, "direction": d} for r, d in slip.crossings],
                    rpm_max_engine_torque=float(engine.rpm_max_torque), max_engine_torque_Nm=engine.max_torque,
                    torque_at_max_engine_torque_Nm=t_nom, torque_margin_Nm=t_nom - engine.max_torque,
                    max_engine_rpm=float(hi), max_von_mises_Pa=st.max_von_mises_Pa, safety_factor=st.safety_factor,
                    max_stress_rpm=st.rpm, max_stress_location_m=list(st.location_m),
                    yield_strength_Pa=st.yield_strength_Pa, slip_power_W=slip_power, shoe_character=character,
                    shoe_character_per_shoe=list(ch.per_shoe), mu=float(op.mu), mu_sensitivity=sens.to_json(),
                    torque_models_at_max_engine_torque_Nm=models, contact_arc_at_max_engine_torque_deg=arc_probe,
                    requirements=checks, engine=eng_info, coupling=coupling, curves=curves,
                    first_touch=res.first_touch, warnings=warnings, notes=notes, part=part,
                    analytical_available=bool(coupling.get("kind")), first_touch_angle_deg=res.first_touch_angle_deg,
                    inputs={**design_inputs(design), "engine": eng_info, "requirements": {"a": req.a, "b": req.b}},
                    label=design_label(design), design_hash=design.hash, whirl=wh.to_json(), fatigue_safety_factor=fat.safety_factor,
                    fatigue_location=fat.location, fatigue_governing_cycle=fat.governing_cycle,
                    fatigue=fat.to_json(), errors=err, contact_sets=sets)
