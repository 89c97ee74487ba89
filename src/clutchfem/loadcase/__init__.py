"""Load-case stage: one :class:`Design` (a meshed part at an :class:`OperatingPoint`) builds
its FE model and contact nodes once and hands out load cases (friction coefficient, spin
softening) that share them; a speed sweep of a load case is a frozen :class:`SweepResult`
with its tables and self-checks; the design record (inputs + hash) travels with every answer."""

from ..core import lazy_names

#: public name -> the module of this package it lives in (imported on first use: PEP 562)
_NAMES: dict[str, str] = {
    "BEST_DRUM_WALL": "operating",
    "check_rpm_range": "operating",
    "condition_estimate": "checks",
    "contact_arcs_deg": "results",
    "contact_extent": "results",
    "Design": "design",
    "design_hash": "record",
    "design_identity": "identity",
    "design_inputs": "record",
    "design_label": "record",
    "DesignIdentity": "identity",
    "drum_intrusion": "checks",
    "equilibrium": "checks",
    "FIDELITY": "operating",
    "Fields": "results",
    "first_touch": "results",
    "identity_of": "identity",
    "LoadCase": "case",
    "MAX_RPM": "operating",
    "MAX_SPEEDS": "operating",
    "model_version": "identity",
    "model_warnings": "checks",
    "morph": "morphing",
    "OperatingPoint": "operating",
    "parse_rpm": "operating",
    "pressure_table": "results",
    "sweep": "case",
    "SweepResult": "results",
    "USER_THICKNESS": "design",
}

__all__ = ["BEST_DRUM_WALL", "FIDELITY", "MAX_RPM", "MAX_SPEEDS", "USER_THICKNESS", "Design", "DesignIdentity", "Fields", "LoadCase", "OperatingPoint", "SweepResult",
           "check_rpm_range", "condition_estimate", "contact_arcs_deg", "contact_extent", "design_hash",
           "design_identity", "design_inputs", "design_label", "identity_of", "drum_intrusion", "equilibrium", "first_touch", "model_warnings",
           "model_version", "morph", "parse_rpm", "pressure_table", "sweep"]

__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
