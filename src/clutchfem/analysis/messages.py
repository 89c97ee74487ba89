"""The warnings and notes of an analysis, written from the step answers.

A **warning** says that an answer fails a check or that the model may not apply: a strongly
self-energising shoe (friction multiplies the normal force by more than
:data:`SELF_ENERGISING_WARN`, near self-locking), an FE character that contradicts the
flexure arrangement, the sweep's own numerical and model-applicability warnings
(:func:`clutchfem.loadcase.model_warnings`), stress above yield at the engine's maximum
speed, a crankshaft whirl margin below :data:`~clutchfem.analysis.WHIRL_MARGIN`, a fatigue
safety factor below 1, and each requirement not met.  A **note** says what was ASSUMED or
left out (idle speed, engine curve shape, requirement factors, a skipped mu point, the
analytical curves of a user mesh, fatigue details).  Both keep the order in which the steps
run, so a report reads them top down.
"""

from __future__ import annotations

from ..clutch import EngineCurve
from ..loadcase import model_warnings
from .answers import (
    CharacterAnswer,
    EngagementAnswer,
    FatigueAnswer,
    MuSensitivity,
    Requirements,
    SlipAnswer,
    StressAnswer,
)
from .idle import DEFAULT_IDLE_RPM
from .requirements import WHIRL_MARGIN

#: normal force with / without friction above which a plus shoe is called strongly
#: self-energising (near self-locking) in the warnings
SELF_ENERGISING_WARN = 1.5


def design_warnings(*, res, material, mu: float, slip: SlipAnswer, eng: EngagementAnswer, ch: CharacterAnswer,
                    character: str, coupling: dict, st: StressAnswer, wh, fat: FatigueAnswer,
                    checks: dict) -> list[str]:
    """The warnings of one analysis (module docstring), from the sweep ``res``, the design's
    ``material`` and friction coefficient ``mu`` and the step answers (``character``: the
    shoes' overall character, 'never engages' outside the engine range; ``wh``: the
    :class:`~clutchfem.clutch.WhirlAnswer`; ``checks``: the requirement checks)."""
    warnings: list[str] = []
    strong = [p_ for p_ in ch.per_shoe if p_["normal_force_ratio"] > SELF_ENERGISING_WARN]
    if strong:
        r = max(p_["normal_force_ratio"] for p_ in strong)
        warnings.append(f"STRONGLY SELF-ENERGISING (plus) shoe: friction multiplies the normal force by {r:.2f} "
                        f"at {ch.probe_rpm:.0f} rpm (mu = {mu:g}): the torque is very sensitive to mu and the clutch "
                        "grabs, near self-locking; a minus arrangement or lower mu is the robust choice")
    if coupling.get("kind") and character in ("plus", "minus") and coupling["kind"] != character:
        warnings.append(f"the FE model behaves as a {character} shoe but the flexure arrangement "
                        f"suggests a {coupling['kind']} shoe: the analytical curves assume "
                        f"{coupling['kind']}; trust the FE")
    # the sweep's own numerical and model-applicability warnings (stress is checked below
    # at the engine's maximum speed)
    warnings += list(res.warnings) + [w for w in model_warnings(res, material.yield_strength)
                                      if not w.startswith("STRESS ABOVE YIELD")]
    if st.safety_factor < 1.0:
        warnings.append(f"STRESS ABOVE YIELD: peak von Mises {st.max_von_mises_Pa / 1e6:.0f} MPa at {st.rpm:.0f} "
                        f"rpm (engine maximum) exceeds the yield strength {st.yield_strength_Pa / 1e6:.0f} MPa of "
                        f"{material.name} (safety factor {st.safety_factor:.2f} < 1): this design would yield at "
                        "full speed")
    if wh.margin < WHIRL_MARGIN:
        warnings.append(f"CRANKSHAFT WHIRL: the first critical speed {wh.rpm_crit_lowest:,.0f} rpm is only "
                        f"{100 * wh.margin:+.0f} % above the engine's maximum {wh.max_engine_rpm:,.0f} rpm (wanted "
                        f">= {100 * WHIRL_MARGIN:.0f} %, ASSUMED); crankshaft, drum and sprocket are ASSUMED")
    if fat.safety_factor is not None and fat.safety_factor < 1.0:
        warnings.append(f"FATIGUE: safety factor {fat.safety_factor:.2f} < 1 at {fat.location}, governed by "
                        f"{fat.governing_cycle}: the part is expected to crack within the ASSUMED service life "
                        "(start-stop and running cycles, Goodman, Miner; see fatigue details)")
    if not checks["engagement_ok"]:
        warnings.append(f"REQUIREMENT NOT MET: engagement with ripple {eng.with_ripple_rpm:.0f} rpm is not above "
                        f"a x idle = {checks['a']:g} x {checks['idle_rpm']:.0f} = "
                        f"{checks['engagement_limit_rpm']:.0f} rpm (chain may move at idle)")
    if not checks["slip_ok"]:
        got = {"never holds": "the clutch never holds the engine (slips at every speed)",
               "never engages": "never engages"}.get(
            slip.status, f"slip {slip.rpm:.0f} rpm" if slip.rpm is not None else "no slip speed")
        warnings.append(f"REQUIREMENT NOT MET: {got}; required slip below b x rpm(max torque) = "
                        f"{checks['b']:g} x {checks['rpm_max_torque']:.0f} = {checks['slip_limit_rpm']:.0f} rpm")
    return warnings


def design_notes(*, engine: EngineCurve, req: Requirements, idle_assumed: bool, ch: CharacterAnswer, cm,
                 sens: MuSensitivity, coupling: dict, fat: FatigueAnswer) -> list[str]:
    """The notes of one analysis (module docstring): what was ASSUMED or left out, from the
    inputs (``idle_assumed``: the idle speed is :data:`DEFAULT_IDLE_RPM`; ``cm``: the
    design's mesh) and the step answers."""
    notes: list[str] = []
    if idle_assumed:
        notes.append(f"idle speed {DEFAULT_IDLE_RPM:.0f} rpm ASSUMED (the engine curve gives none)")
    if ch.probe_rpm != float(engine.rpm_max_torque):
        notes.append(f"not engaged at the rpm of max engine torque: plus/minus character and mu "
                     f"sensitivity evaluated at {ch.probe_rpm:.0f} rpm")
    if ch.per_shoe and cm.sector_angle:
        notes.append(f"sector model: shoe 0 stands for all {cm.n_shoes_total} identical shoes")
    notes += list(sens.notes)
    if not coupling.get("kind"):
        notes.append("analytical shoe-model curves (eqs 2-8) not available: a user mesh carries no shoe "
                     "pivot or nominal shoe arc (shoe mass from the mesh is reported for information); "
                     "every FE answer (engagement, slip, torque, stress, shoe character, mu sensitivity) "
                     "is given")
    if not fat.details.get("available", True):
        notes.append("fatigue: " + fat.details["reason"])
    notes += ["fatigue: " + n_ for n_ in fat.details.get("notes", [])]
    if engine.assumed:
        notes.append("engine curve: built-in 56.5 cc saw curve; its SHAPE IS ASSUMED (anchors 3.40 N m at "
                     "8000 rpm and 3.20 N m at 9072 rpm from seed 000); use --engine CSV for design work")
    if req.assumed:
        notes.append("requirement factors a = 1.3, b = 1.0 are ASSUMED defaults (the thesis keeps them confidential)")
    return notes
