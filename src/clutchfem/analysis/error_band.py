"""The error step: the error of the main answers (engagement, slip, torque at the rpm of
maximum engine torque, peak stress), :mod:`clutchfem.accuracy`, and their sensitivity to the
assumed inputs, reported apart from the band.

Discretisation: the same answers on a mesh twice as fine (:func:`~clutchfem.accuracy.refined_design`:
a second design, one more assembly and factorisation; its slip crossings bracketed every
:data:`~.torque.GRID_RPM_SENSITIVITY` rpm, as the sensitivities', and refined to 1e-9),
Richardson's estimate at p = 1; a
user mesh (one level) is not estimated; a 3-D model's is the sum of a layers term (one layer
more) and an in-plane term (the thick plane model on the same mesh and one twice as fine),
:func:`~clutchfem.accuracy.discretisation_3d`.  Model form: the measured terms
(best-estimate path: the thick plane model's residual against 3-D and the pre-stress
softening's against the non-linear reference; fast path: axial thickness 2-D vs 3-D,
geometric non-linearity of the softening model, rigid vs 2 mm steel drum), relative.  The
total band of an answer is the sum of the magnitudes.  Sensitivities (not in the band): the
answers with the drum wall -+ 0.5 mm (:func:`~.sensitivity.drum_sensitivity_step`) and with
mu x 0.7 / x 1.3 (:func:`~.torque.mu_sensitivity_step`).

Accuracy targets (:mod:`.refinement`): an answer (engagement, slip, torque) whose band exceeds
its target (:data:`~.refinement.ACCURACY_TARGET`) while its model form alone fits is computed
once more on a mesh four times as fine (one level, shared) and reported from there with
discretisation 2 |a_h/2 - a_h/4|; a note says so, and whether the target is then met.
"""

from __future__ import annotations

import math

import numpy as np

from ..accuracy import (
    ANSWERS,
    NOT_ESTIMATED,
    AnswerError,
    AnswerNonlinearity,
    discretisation,
    discretisation_3d,
    extrapolated_peak,
    model_form,
    refined_design,
)
from ..clutch import EngineCurve
from ..fe import peak_disc
from .refinement import ACCURACY_TARGET, REFINABLE, FinerLevel, level_answer, needs_refinement, refine_answer

#: a sweep's relative equilibrium residual at an answer's speed from which it is a term of
#: that answer's band (below, < 0.01 %: negligible against the bands, >= 0.3 %)
SOFTENING_RESIDUAL_TERM = 1e-4
#: the peak stress's error from the pre-stress Ritz space / its (global) residual: measured
#: 0.6-14.8x against the per-speed solve (concepts 1, 2, 3.1, 4 and the soft concept4-lhs06,
#: 6000-14 000 rpm, 22 states, benchmarks/bench_ritz_residual.py; concept 4 at 14 000 rpm:
#: 5.5x), so a bound just above the largest is taken.  The contact forces' (torque, slip)
#: error is ~1e-2 x the residual: the residual itself is their term
PEAK_RESIDUAL_FACTOR = 15.0


def error_step(design, engine: EngineCurve, values: dict, w0_rpm: float | None,
               slip_rpm_value: float | None, drum: dict | None = None, mu: dict | None = None,
               peak_at: tuple[float, float] | None = None,
               nl: dict[str, AnswerNonlinearity] | None = None, residual=None,
               peak_exact: bool = False, targets: dict | None = None) -> dict:
    """The error of the main answers ``values`` (module docstring): per answer its value,
    discretisation, model-form terms, total and sensitivities.  ``w0_rpm``: the engagement
    speed and ``slip_rpm_value``: the slip speed, which the thickness term of the slip speed
    scales with (that of the torque with the rpm of maximum engine torque); ``drum``: the
    drum-wall sensitivity step's answers, ``mu``: the mu sensitivity's (``MuSensitivity.to_json``).
    ``nl`` (best-estimate path): the geometric non-linearity of the peak stress and the
    torque (:func:`~clutchfem.accuracy.answer_nonlinearity`), corrected here; the peak
    together with its discretisation (the refined mesh also refines the disc at ``peak_at``
    [m], and the peak is extrapolated from the two levels,
    :func:`~clutchfem.accuracy.extrapolated_peak`).  A corrected answer's ``value`` is the
    corrected one and its ``corrections`` say by how much.  ``residual``: (rpm, relative
    equilibrium residual) of the sweep the answers come from; where it reaches
    :data:`SOFTENING_RESIDUAL_TERM` at an answer's speed (the pre-stress Ritz space on a soft
    design far past engagement: the residual is the displacement error it leaves, measured,
    :data:`~clutchfem.loadcase.checks.RESIDUAL_FAIL_RITZ`), it is a model-form term of that
    answer, ``softening_residual``.  ``peak_exact``: the peak stress was re-solved at its speed
    with the per-speed factorisation (:func:`~.strength.peak_sweep`): so is the finer mesh's,
    and the peak has no such term.  ``targets`` (default
    :data:`~.refinement.ACCURACY_TARGET`): an answer whose band exceeds its relative target
    because of its discretisation is computed once more on a mesh four times as fine and
    reported from there (:mod:`.refinement`; its ``corrections`` say so)."""
    lo, hi = engine.rpm_range

    def answers(d):
        case = d.case()
        eng = case.engagement_rpm  # (first: a per-speed re-solve's engagement search starts from it)
        row = (d.with_softening("prestress-exact") if peak_exact else d).sweep([hi]).curve.iloc[0]
        return {"engagement_rpm": eng, "slip_rpm": level_answer(case, engine, "slip_rpm"),
                "torque_at_max_engine_torque_Nm": level_answer(case, engine, "torque_at_max_engine_torque_Nm"),
                "max_von_mises_Pa": float(row["max_von_mises_Pa"]),
                "peak_at": (float(row["max_vm_x_m"]), float(row["max_vm_y_m"]))}

    three_d = design.op.model_formulation == "3d"
    nl = nl or {}
    finer = None  # the h/4 level, built only if an answer needs it (.refinement)
    cd = refined_design(design, peak_at=peak_at if "max_von_mises_Pa" in nl else None)
    coarse = answers(cd) if cd is not None else {}
    disc3 = discretisation_3d(design, lambda d: values if d is design else answers(d)) if three_d else {}
    out = {}
    for q, unit in ANSWERS.items():
        v = values.get(q)
        w = {"slip_rpm": slip_rpm_value, "torque_at_max_engine_torque_Nm": float(engine.rpm_max_torque)}.get(q)
        fixed = q in nl and v is not None
        terms, notes = model_form(design, q, v, w0=w0_rpm, w=w, corrected=fixed)
        at = {"engagement_rpm": w0_rpm, "max_von_mises_Pa": hi}.get(q, w)
        if residual is not None and v is not None and at is not None and len(residual[0]) \
                and not (peak_exact and q == "max_von_mises_Pa"):
            r = float(np.interp(at, *residual))
            t = r * (PEAK_RESIDUAL_FACTOR if q == "max_von_mises_Pa" else 1.0)
            if t >= SOFTENING_RESIDUAL_TERM:
                terms["softening_residual"] = t
                notes = notes + (f"spin softening: the pre-stress Ritz space's error at {at:.0f} rpm (its equilibrium "
                                 f"residual {r:.2g}" + (f" x {PEAK_RESIDUAL_FACTOR:g} for a local peak" if t != r else "")
                                 + ") is in the band",)
        d = discretisation(v, coarse.get(q)) if cd is not None else None
        fix = None
        if fixed:
            v, d, fix = (corrected_peak(design, v, d, coarse, peak_at, nl[q]) if q == "max_von_mises_Pa"
                         else corrected_answer(v, d, nl[q]))
            notes = notes + (fix["note"],)
        if not three_d and cd is not None and q in REFINABLE and v is not None:
            mf = abs(v) * sum(abs(x) for x in terms.values())
            if needs_refinement(q, v, d, mf, targets):
                finer = finer or FinerLevel(cd, engine)
                v, d, fix, more = target_step(q, unit, v, coarse.get(q), fix, mf / abs(v), finer, targets)
                notes = notes + more
        if three_d and q in disc3:
            d = disc3[q][0]
            notes = notes + (disc3[q][3],)
        elif cd is None:
            notes = notes + (NOT_ESTIMATED[three_d],)
        sens = sensitivities(q, drum, mu)
        if fix is not None:  # the inputs' effect on the corrected answer: the same correction, ASSUMED
            f = v / fix["uncorrected"]
            sens = {k: [None if x is None else x * f for x in vals] for k, vals in sens.items()}
            notes = notes + ("sensitivities scaled by the same correction (its dependence on the drum wall "
                             "and mu is not computed)",)
        out[q] = AnswerError(q, v, unit, d, terms, notes, sens).to_json()
        if fix is not None:
            out[q]["corrections"] = {k: x for k, x in fix.items() if k != "note"}
        if three_d and q in disc3:
            out[q]["discretisation_layers"], out[q]["discretisation_in_plane"] = disc3[q][1:3]
    fast = design.op.model_formulation in ("plane-stress", "plane-strain")
    out["method"] = (("discretisation: layers (Richardson, p = 1, against one layer more) + in plane (the thick "
                      "plane model's relative 2 |a_h - a_h/2| on the same mesh and one twice as fine)" if three_d else
                      "discretisation: 2 |a_h - a_h/2| (Richardson, p = 1) against the same design on a mesh twice "
                      "as fine") + "; model form: measured terms, relative ("
                     + ("fast path: axial thickness 2-D vs 3-D, geometric non-linearity of the softening model, rigid "
                        "vs 2 mm steel drum" if fast else
                        "3-D elasticity: the geometric non-linearity left by the softening model, the rigid drum "
                        "where no drum wall is modelled" if three_d else
                        "the thick plane model's residual against 3-D elasticity, the geometric non-linearity left "
                        "by the softening model")
                     + "); total = sum of magnitudes; sensitivities to the assumed inputs (drum wall, mu) apart, "
                     "not in the total")
    return out


def target_step(q: str, unit: str, v: float, a1: float | None, fix: dict | None, mf_rel: float, finer: FinerLevel,
                targets: dict | None = None):
    """(value, discretisation, corrections, notes) of answer ``q`` (value ``v``, its h/2 value
    ``a1`` as computed, its corrections ``fix`` so far) reported from the h/4 level ``finer``
    (:func:`~.refinement.refine_answer`), with a note where its band (model form ``mf_rel``,
    relative) still exceeds the target; the h-level answer, noted, if that level failed."""
    t = (ACCURACY_TARGET if targets is None else targets)[q]
    a0 = fix["uncorrected"] if fix is not None else v
    f = v / a0 if fix is not None else 1.0
    a2 = finer.get(q)
    d = None
    notes: tuple = ()
    if a1 is not None and a2 is not None and math.isfinite(a2):
        r = refine_answer(q, unit, (a0, a1, a2), f, t, finer)
        v, d = r["value"], r["discretisation"]
        fix = {**(fix or {"uncorrected": a0}), **r["correction"]}
        notes = (r["note"],)
    else:
        d = 2.0 * abs(a0 - a1) * abs(f) if a1 is not None else None
        notes = (f"the mesh four times as fine has no answer ({finer.error or 'none found'}): reported from the design "
                 f"mesh",)
    band = (d or 0.0) + mf_rel * abs(v)
    if band > t * abs(v):
        notes = notes + (f"accuracy target {100 * t:g} % not met: band {100 * band / abs(v):.2f} %",)
    return v, d, fix, notes


def corrected_answer(a0: float, disc: float | None, nl: AnswerNonlinearity):
    """(value, discretisation, corrections) of an answer ``a0`` corrected for its geometric
    non-linearity ``nl``: a0 (1 + d_NL)."""
    f = 1.0 + nl.delta
    note = (f"corrected for geometric non-linearity {100 * nl.delta:+.2f} % (total-Lagrangian / linear "
            f"pre-stressed plane-stress twin at {nl.rpm:.0f} rpm, {nl.iterations} Newton iterations)")
    fix = {"uncorrected": a0, "geometric_nonlinearity": nl.delta, "geometric_nonlinearity_iterations": nl.iterations,
           "note": note}
    return a0 * f, None if disc is None else disc * f, fix


def corrected_peak(design, a0: float, disc: float | None, fine: dict, peak_at, nl: AnswerNonlinearity):
    """(value, discretisation, corrections) of the best-estimate peak stress: the design
    mesh's peak ``a0`` [Pa] extrapolated with the refined mesh's (``fine``: its answers and
    peak point) when the peak stayed on the same feature (within the refined disc), times
    (1 + d_NL) of ``nl``."""
    f = 1.0 + nl.delta
    a1, at1 = fine.get("max_von_mises_Pa"), fine.get("peak_at")
    same = False
    if a1 is not None and math.isfinite(a1) and at1 is not None and peak_at is not None:
        radius, h0 = peak_disc(design.cm, tuple(peak_at), design.params.drum_radius)
        same = math.hypot(at1[0] - peak_at[0], at1[1] - peak_at[1]) <= radius + h0
    if same:
        v_ext, e_ext = extrapolated_peak(a0, a1)
        how = (f"extrapolated from the design mesh and one twice as fine with the peak's disc refined "
               f"({a0 / 1e6:.1f} / {a1 / 1e6:.1f} MPa, Richardson p = 2: {100 * (v_ext / a0 - 1):+.2f} %)")
    else:
        v_ext, e_ext = a0, disc
        how = ("not extrapolated: " + ("no finer mesh (a user mesh has one level)" if a1 is None else
               "the refined mesh's peak is on another feature") + "; discretisation 2 |a_h - a_h/2|")
    note = (f"peak stress corrected: discretisation {how}; geometric non-linearity {100 * nl.delta:+.2f} % "
            f"(total-Lagrangian / linear pre-stressed plane-stress twin at {nl.rpm:.0f} rpm, "
            f"{nl.iterations} Newton iterations, {nl.time_s:.2f} s)")
    fix = {"uncorrected": a0, "discretisation_extrapolation": v_ext / a0 - 1.0, "extrapolated": same,
           "geometric_nonlinearity": nl.delta, "geometric_nonlinearity_iterations": nl.iterations, "note": note}
    return v_ext * f, None if e_ext is None else e_ext * f, fix


def sensitivities(q: str, drum: dict | None, mu: dict | None) -> dict:
    """Per assumed input, the answer ``q`` at its low and high value (absolute, the answer's
    unit): the drum wall -+ 0.5 mm, mu x 0.7 / x 1.3 (where the step computed them)."""
    out = {}
    if drum is not None and q in drum:
        lo, hi = drum["drum_wall_m"]
        out[f"drum wall {lo * 1e3:g} / {hi * 1e3:g} mm"] = list(drum[q])
    if mu is not None:
        key = {"slip_rpm": "slip_rpm", "torque_at_max_engine_torque_Nm": "torque_Nm"}.get(q)
        if key and key in mu:
            vals = mu[key]
            lo_hi = [vals.get(k) for k in ("x0.7", "x1.3")] if isinstance(vals, dict) else None
            if lo_hi and all(v is not None for v in lo_hi):
                out["mu x0.7 / x1.3"] = lo_hi
    return out
