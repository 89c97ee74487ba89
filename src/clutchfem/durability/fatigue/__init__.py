"""High-cycle fatigue of the clutch from stress states: pure functions, no FE solve inside.

For every cycle type the plane stresses at the same points in the cycle's two extreme
states and its number of cycles in the clutch's life; out comes the load factor at which
Miner's sum over the cycle types reaches 1, at the worst point, named.  By job:

* :mod:`.strength` -- :class:`FatigueParams`, the strength data and rules (ASSUMED, sourced);
* :mod:`.stresses` -- amplitude and mean tensors, their equivalent (von Mises) values;
* :mod:`.criteria` -- Marin factors and endurance limit, Haigh (Goodman/Gerber), Basquin
  S-N curve with its knee, allowed amplitude, the one-cycle-type load factor;
* :mod:`.check` -- :class:`LoadCycle`, Miner's damage, the load factor per point,
  :func:`fatigue_check` and :class:`FatigueResult`;
* the worst point's name comes from :mod:`clutchfem.durability.location`.
"""

from ..location import Location, name_location
from .check import FatigueResult, LoadCycle, candidate_points, fatigue_check
from .criteria import (
                       allowed_amplitude,
                       cycles_to_failure,
                       endurance_limit,
                       haigh_safety_factor,
                       marin_factors,
                       reversed_equivalent,
                       single_cycle_factor,
)
from .strength import ASSUMED, SURFACE_TABLE, FatigueParams
from .stresses import amplitude_mean, equivalent_stresses

__all__ = [
    "FatigueParams", "LoadCycle", "FatigueResult", "Location", "amplitude_mean",
    "equivalent_stresses", "marin_factors", "endurance_limit", "reversed_equivalent",
    "cycles_to_failure", "haigh_safety_factor", "fatigue_check", "name_location", "SURFACE_TABLE",
    "allowed_amplitude", "single_cycle_factor", "candidate_points", "ASSUMED",
]
