"""Analysis stage: from a design to the answers a clutch designer asks for (engagement, slip,
torque, character, stresses, fatigue, whirl, requirements, each with its error), as a
sequence of small steps run by :func:`analyze`.

Modules, one job each: :mod:`.front` (:func:`analyze`: checks the inputs, hands a live design to
the reduced model), :mod:`.pipeline` (the FE steps in order),
:mod:`.answers` (the frozen answer records and :class:`Analysis`), :mod:`.torque` (slip,
FE sweep, engagement, character, mu sensitivity), :mod:`.coupling` (the analytical shoe
model next to the FE torque, the answer's curves), :mod:`.strength` (stress and fatigue),
:mod:`.requirements` (the designer's factors, crankshaft whirl), :mod:`.error_band` (the error of
the main answers), :mod:`.refinement` (their accuracy targets: one more mesh level where the
discretisation puts a band over its target), :mod:`.messages` (warnings and notes), :mod:`.slip_heat` (the slip test's
temperatures), :mod:`.idle` (the idle speed of the checks, and the live answerer's registry:
what a live answer needs of this stage, without the FE stack)."""

from ..core import lazy_names

#: public name -> the module of this package it lives in (imported on first use: PEP 562)
_NAMES: dict[str, str] = {
    "ACCURACY_TARGET": "refinement",
    "Analysis": "answers",
    "analyze": "front",
    "answer_curves": "coupling",
    "bracket_grid": "torque",
    "character_step": "torque",
    "CharacterAnswer": "answers",
    "check_speeds": "torque",
    "contact_sets_step": "torque",
    "CONTACT_SPEED_OF": "torque",
    "coupling_step": "coupling",
    "DEFAULT_A": "answers",
    "DEFAULT_B": "answers",
    "DEFAULT_IDLE_RPM": "idle",
    "design_notes": "messages",
    "design_warnings": "messages",
    "engagement_step": "torque",
    "EngagementAnswer": "answers",
    "error_step": "error_band",
    "fatigue_cycles": "strength",
    "fatigue_step": "strength",
    "FatigueAnswer": "answers",
    "fe_sweep": "torque",
    "FETorque": "torque",
    "GRID_RPM": "torque",
    "idle_speed": "idle",
    "LIVE": "idle",
    "mesh_mass_properties": "pipeline",  # (its home is clutchfem.mesh; exported here as before)
    "MU_FACTORS": "torque",
    "mu_sensitivity_step": "torque",
    "MuSensitivity": "answers",
    "probe_speed": "torque",
    "Requirements": "answers",
    "requirements_step": "requirements",
    "secondary_case": "torque",
    "SELF_ENERGISING_WARN": "messages",
    "slip_answer": "torque",
    "slip_heat": "slip_heat",
    "slip_step": "torque",
    "SlipAnswer": "answers",
    "SlipHeatRun": "slip_heat",
    "stress_step": "strength",
    "StressAnswer": "answers",
    "torque_models": "coupling",
    "WHIRL_MARGIN": "requirements",
    "whirl_step": "requirements",
}

__all__ = ["LIVE", "ACCURACY_TARGET", "SlipHeatRun", "slip_heat", "DEFAULT_A", "DEFAULT_B", "DEFAULT_IDLE_RPM", "CONTACT_SPEED_OF", "GRID_RPM", "MU_FACTORS", "SELF_ENERGISING_WARN",
           "WHIRL_MARGIN", "Analysis", "CharacterAnswer", "EngagementAnswer", "FETorque", "FatigueAnswer",
           "MuSensitivity", "Requirements", "SlipAnswer", "StressAnswer", "analyze", "answer_curves", "bracket_grid",
           "character_step", "check_speeds", "contact_sets_step", "coupling_step", "design_notes", "design_warnings", "engagement_step",
           "error_step", "fatigue_cycles", "fatigue_step", "fe_sweep", "idle_speed", "mesh_mass_properties",
           "mu_sensitivity_step", "probe_speed", "requirements_step", "secondary_case", "slip_answer", "slip_step",
           "stress_step", "torque_models", "whirl_step"]

__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
