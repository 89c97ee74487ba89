"""Clutch physics outside the FE model: engine curve and slip crossings, plus/minus shoe
integrals, 2-stroke speed ripple, today's spring clutch, crankshaft whirl (overhung shaft).
"""

from ..core import lazy_names

#: public name -> the module of this package it lives in (imported on first use: PEP 562)
_NAMES: dict[str, str] = {
    "apply_force": "shoe",
    "arc_torque": "shoe",
    "BaselineClutch": "baseline",
    "CentrifugalShoe": "shoe",
    "ChainsawLayout": "crankshaft",
    "crankshaft_whirl": "crankshaft",
    "cycle_time": "ripple",
    "effective_engagement_rpm": "ripple",
    "EngineCurve": "engine",
    "EngineTable": "engine_csv",
    "fe_frequency_coefficients": "shaft",
    "first_slip_rpm": "engine",
    "frequency_coefficients": "shaft",
    "holds": "engine",
    "lining_integrals": "shoe",
    "MAX_ROWS": "engine_csv",
    "OverhungShaft": "shaft",
    "read_engine_csv": "engine_csv",
    "reduced_inertia": "drive",
    "RippleModel": "ripple",
    "SEED_CHAIN_MASS": "drive",
    "SEED_DRIVE_INERTIA": "drive",
    "SEED_J_B": "drive",
    "SEED_SPROCKET_PITCH_RADIUS": "drive",
    "ShaftModel": "shaft",
    "shoe_kind": "shoe",
    "shoe_torque": "shoe",
    "ShoeGeometry": "shoe",
    "simplified_torque": "shoe",
    "slip_rpm": "engine",
    "speed": "ripple",
    "torque_crossings": "engine",
    "torque_factor": "shoe",
    "whirl": "crankshaft",
    "WhirlAnswer": "crankshaft",
}

__all__ = ["MAX_ROWS", "EngineTable", "read_engine_csv", "SEED_CHAIN_MASS", "SEED_DRIVE_INERTIA", "SEED_J_B", "SEED_SPROCKET_PITCH_RADIUS", "reduced_inertia", "ShaftModel", "holds", "ChainsawLayout", "WhirlAnswer", "crankshaft_whirl", "whirl", "BaselineClutch", "CentrifugalShoe", "EngineCurve", "OverhungShaft", "RippleModel", "ShoeGeometry", "apply_force", "arc_torque", "cycle_time", "effective_engagement_rpm", "fe_frequency_coefficients", "first_slip_rpm", "frequency_coefficients", "lining_integrals", "shoe_kind", "shoe_torque", "simplified_torque", "slip_rpm", "speed", "torque_crossings", "torque_factor"]

__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
