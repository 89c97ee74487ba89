"""Analysis stage: from a design to the answers a clutch designer asks for (engagement, slip,
torque, character, stresses, fatigue, whirl, requirements, each with its error), as a
sequence of small steps run by :func:`analyze`."""

from .pipeline import (
                       DEFAULT_A,
                       DEFAULT_B,
                       DEFAULT_IDLE_RPM,
                       WHIRL_MARGIN,
                       Analysis,
                       CharacterAnswer,
                       EngagementAnswer,
                       FatigueAnswer,
                       MuSensitivity,
                       Requirements,
                       SlipAnswer,
                       StressAnswer,
                       analyze,
                       bracket_grid,
                       check_speeds,
                       mesh_mass_properties,
                       slip_answer,
                       slip_step,
)

__all__ = ["DEFAULT_A", "DEFAULT_B", "DEFAULT_IDLE_RPM", "WHIRL_MARGIN", "Analysis", "CharacterAnswer",
           "EngagementAnswer", "FatigueAnswer", "MuSensitivity", "Requirements", "SlipAnswer", "StressAnswer",
           "analyze", "bracket_grid", "check_speeds", "mesh_mass_properties", "slip_answer", "slip_step"]
