"""Durability of a compliant clutch (issue 14): fatigue, the engagement transient, wear.

The slip heat's transient conduction in the part (the stage below this one) is
:mod:`clutchfem.thermal`; the start's heating here uses its heat partition.

* :mod:`clutchfem.durability.fatigue` -- stress amplitude and mean from the extreme states
  of load cycles, Haigh (Goodman/Gerber) check with a Marin-corrected endurance limit,
  Basquin S-N curve with its knee, Miner's sum over cycle types.
* :mod:`clutchfem.durability.cycles` -- the service load cycles built from solved FE states.
* :mod:`clutchfem.durability.engagement` -- the engagement transient of one start (engine,
  slipping clutch, drum and chain; slip energy, lock-up, droop), :mod:`.start_heat` its
  shoe-face temperature rise, :mod:`.wear` Archard's wear and its integration over starts.
The worst fatigue point is named by :mod:`clutchfem.mesh.location`.

Fatigue takes plain arrays (contact forces, stress states) and a
:class:`~clutchfem.mesh.ClutchMesh`; they never run the elastic FE solver themselves.
"""

from ..core import lazy_names

#: public name -> the module of this package it lives in (imported on first use: PEP 562)
_NAMES: dict[str, str] = {
    "candidate_points": "fatigue.check",
    "DriveLine": "engagement",
    "endurance_limit": "fatigue.criteria",
    "Engagement": "engagement",
    "engagement_transient": "engagement",
    "fatigue_check": "fatigue.check",
    "FatigueLoads": "cycles",
    "FatigueParams": "fatigue.strength",
    "FatigueResult": "fatigue.check",
    "integrate_wear": "wear",
    "LoadCycle": "fatigue.check",
    "ripple_classes": "cycles",
    "service_cycles": "cycles",
    "ServiceStates": "cycles",
    "single_cycle_factor": "fatigue.criteria",
    "start_heating": "start_heat",
    "StartHeating": "start_heat",
    "wear_rate": "wear",
    "WearParams": "wear",
    "WearRun": "wear",
}

__all__ = ["DriveLine", "Engagement", "engagement_transient", "StartHeating", "start_heating", "WearParams",
           "WearRun", "integrate_wear", "wear_rate", "FatigueLoads", "FatigueParams", "FatigueResult", "LoadCycle",
           "ServiceStates", "candidate_points", "endurance_limit", "fatigue_check", "ripple_classes", "service_cycles",
           "single_cycle_factor"]

__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
