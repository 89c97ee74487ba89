"""Load-case stage: one :class:`Design` (a meshed part at an :class:`OperatingPoint`) builds
its FE model and contact nodes once and hands out load cases (friction coefficient, spin
softening) that share them; a speed sweep of a load case is a frozen :class:`SweepResult`
with its tables and self-checks; the design record (inputs + hash) travels with every answer."""

from .case import LoadCase, sweep
from .checks import condition_estimate, drum_intrusion, equilibrium, model_warnings
from .design import USER_THICKNESS, Design
from .identity import DesignIdentity, design_identity, identity_of, model_version
from .morphing import morph
from .operating import BEST_DRUM_WALL, FIDELITY, MAX_RPM, MAX_SPEEDS, OperatingPoint, check_rpm_range, parse_rpm
from .record import design_hash, design_inputs, design_label
from .results import Fields, SweepResult, contact_arcs_deg, contact_extent, first_touch, pressure_table

__all__ = ["BEST_DRUM_WALL", "FIDELITY", "MAX_RPM", "MAX_SPEEDS", "USER_THICKNESS", "Design", "DesignIdentity", "Fields", "LoadCase", "OperatingPoint", "SweepResult",
           "check_rpm_range", "condition_estimate", "contact_arcs_deg", "contact_extent", "design_hash",
           "design_identity", "design_inputs", "design_label", "identity_of", "drum_intrusion", "equilibrium", "first_touch", "model_warnings",
           "model_version", "morph", "parse_rpm", "pressure_table", "sweep"]
