"""The drive line of seed 000's saw (Husqvarna 357 XP, 56.5 cc, 3/8" chain on a 15" bar): the
inertia the clutch drives, in one place for the fatigue loads, the whirl layout and the
seed-000 validation.

J_b = 85.10e-6 kg m^2 (drum and sprockets reduced to the clutch axis), chain m_p = 0.273 kg
on the drive sprocket's pitch radius r_k = 21.2 mm (seed 000, eq 11):
J = J_b + m_p r_k^2 = 2.078e-4 kg m^2.
"""

from __future__ import annotations

import math

from ..core import ParameterError

__all__ = ["SEED_CHAIN_MASS", "SEED_DRIVE_INERTIA", "SEED_J_B", "SEED_SPROCKET_PITCH_RADIUS", "reduced_inertia"]

#: drum + sprockets reduced to the clutch axis [kg m^2] (seed 000)
SEED_J_B = 85.10e-6
#: chain mass on the 15" bar [kg] (seed 000)
SEED_CHAIN_MASS = 0.273
#: drive sprocket pitch radius [m] (seed 000)
SEED_SPROCKET_PITCH_RADIUS = 0.0212


def reduced_inertia(J_b: float, m_p: float, r_k: float) -> float:
    """``J_b + m_p r_k^2`` [kg m^2]: drum, sprockets and chain reduced to the clutch axis."""
    for name, v in (("J_b", J_b), ("m_p", m_p), ("r_k", r_k)):
        if not (math.isfinite(v) and v >= 0):
            raise ParameterError(name, v, "finite and >= 0")
    return J_b + m_p * r_k**2


#: J_b + m_p r_k^2 of seed 000 [kg m^2]
SEED_DRIVE_INERTIA = reduced_inertia(SEED_J_B, SEED_CHAIN_MASS, SEED_SPROCKET_PITCH_RADIUS)
