"""Clutch physics outside the FE model: engine curve and slip crossings, plus/minus shoe
integrals, 2-stroke speed ripple, today's spring clutch, crankshaft whirl (overhung shaft).
"""

from .baseline import BaselineClutch
from .crankshaft import ChainsawLayout, WhirlAnswer, crankshaft_whirl, whirl
from .drive import SEED_CHAIN_MASS, SEED_DRIVE_INERTIA, SEED_J_B, SEED_SPROCKET_PITCH_RADIUS, reduced_inertia
from .engine import EngineCurve, first_slip_rpm, holds, slip_rpm, torque_crossings
from .engine_csv import MAX_ROWS, EngineTable, read_engine_csv
from .ripple import RippleModel, cycle_time, effective_engagement_rpm, speed
from .shaft import OverhungShaft, ShaftModel, fe_frequency_coefficients, frequency_coefficients
from .shoe import (
    CentrifugalShoe,
    ShoeGeometry,
    apply_force,
    arc_torque,
    lining_integrals,
    shoe_kind,
    shoe_torque,
    simplified_torque,
    torque_factor,
)

__all__ = ["MAX_ROWS", "EngineTable", "read_engine_csv", "SEED_CHAIN_MASS", "SEED_DRIVE_INERTIA", "SEED_J_B", "SEED_SPROCKET_PITCH_RADIUS", "reduced_inertia", "ShaftModel", "holds", "ChainsawLayout", "WhirlAnswer", "crankshaft_whirl", "whirl", "BaselineClutch", "CentrifugalShoe", "EngineCurve", "OverhungShaft", "RippleModel", "ShoeGeometry", "apply_force", "arc_torque", "cycle_time", "effective_engagement_rpm", "fe_frequency_coefficients", "first_slip_rpm", "frequency_coefficients", "lining_integrals", "shoe_kind", "shoe_torque", "simplified_torque", "slip_rpm", "speed", "torque_crossings", "torque_factor"]
