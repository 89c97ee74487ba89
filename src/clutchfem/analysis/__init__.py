"""Analysis stage: from a design to the answers a clutch designer asks for (engagement, slip,
torque, character, stresses, fatigue, whirl, requirements, each with its error), as a
sequence of small steps run by :func:`analyze`.

Modules, one job each: :mod:`.pipeline` (:func:`analyze`: the steps in order),
:mod:`.answers` (the frozen answer records and :class:`Analysis`), :mod:`.torque` (slip,
FE sweep, engagement, character, mu sensitivity), :mod:`.coupling` (the analytical shoe
model next to the FE torque, the answer's curves), :mod:`.strength` (stress and fatigue),
:mod:`.requirements` (the designer's factors, crankshaft whirl), :mod:`.error_band` (the error of
the main answers), :mod:`.refinement` (their accuracy targets: one more mesh level where the
discretisation puts a band over its target), :mod:`.messages` (warnings and notes), :mod:`.slip_heat` (the slip test's
temperatures)."""

from ..mesh import mesh_mass_properties  # (its home is clutchfem.mesh; exported here as before)
from .answers import (
    DEFAULT_A,
    DEFAULT_B,
    Analysis,
    CharacterAnswer,
    EngagementAnswer,
    FatigueAnswer,
    MuSensitivity,
    Requirements,
    SlipAnswer,
    StressAnswer,
)
from .coupling import answer_curves, coupling_step, torque_models
from .error_band import error_step
from .messages import SELF_ENERGISING_WARN, design_notes, design_warnings
from .pipeline import LIVE, analyze
from .refinement import ACCURACY_TARGET
from .requirements import DEFAULT_IDLE_RPM, WHIRL_MARGIN, idle_speed, requirements_step, whirl_step
from .slip_heat import SlipHeatRun, slip_heat
from .strength import fatigue_cycles, fatigue_step, stress_step
from .torque import (
    CONTACT_SPEED_OF,
    GRID_RPM,
    MU_FACTORS,
    FETorque,
    bracket_grid,
    character_step,
    check_speeds,
    contact_sets_step,
    engagement_step,
    fe_sweep,
    mu_sensitivity_step,
    probe_speed,
    secondary_case,
    slip_answer,
    slip_step,
)

__all__ = ["LIVE", "ACCURACY_TARGET", "SlipHeatRun", "slip_heat", "DEFAULT_A", "DEFAULT_B", "DEFAULT_IDLE_RPM", "CONTACT_SPEED_OF", "GRID_RPM", "MU_FACTORS", "SELF_ENERGISING_WARN",
           "WHIRL_MARGIN", "Analysis", "CharacterAnswer", "EngagementAnswer", "FETorque", "FatigueAnswer",
           "MuSensitivity", "Requirements", "SlipAnswer", "StressAnswer", "analyze", "answer_curves", "bracket_grid",
           "character_step", "check_speeds", "contact_sets_step", "coupling_step", "design_notes", "design_warnings", "engagement_step",
           "error_step", "fatigue_cycles", "fatigue_step", "fe_sweep", "idle_speed", "mesh_mass_properties",
           "mu_sensitivity_step", "probe_speed", "requirements_step", "secondary_case", "slip_answer", "slip_step",
           "stress_step", "torque_models", "whirl_step"]
