"""Durability of a compliant clutch (issue 14): slip heat and fatigue.

* :mod:`clutchfem.durability.heat` -- transient heat conduction in the part (scikit-fem P2
  on the clutch mesh, the axial thickness as a plate) during slip with the drum held, the
  shoe/drum heat partition, repeated slip events with cooling pauses, .vtu and PNG output.
* :mod:`clutchfem.durability.fatigue` -- stress amplitude and mean from the extreme states
  of load cycles, Haigh (Goodman/Gerber) check with a Marin-corrected endurance limit,
  Basquin S-N curve with its knee, Miner's sum over cycle types.
* :mod:`clutchfem.durability.cycles` -- the service load cycles built from solved FE states.
* :mod:`clutchfem.durability.engagement` -- the engagement transient of one start (engine,
  slipping clutch, drum and chain; slip energy, lock-up, droop), :mod:`.start_heat` its
  shoe-face temperature rise, :mod:`.wear` Archard's wear and its integration over starts.
* :mod:`clutchfem.durability.location` -- the name of a place in the clutch (zone, flexure
  end, boundary): the worst fatigue point, the hottest points.

Heat and fatigue take plain arrays (contact forces, stress states) and a
:class:`~clutchfem.mesh.ClutchMesh`; they never run the elastic FE solver themselves.
"""

from ..core import lazy_names

#: public name -> the module of this package it lives in (imported on first use: PEP 562)
_NAMES: dict[str, str] = {
    "candidate_points": "fatigue.check",
    "DriveLine": "engagement",
    "DrumThermal": "heat",
    "endurance_limit": "fatigue.criteria",
    "Engagement": "engagement",
    "engagement_transient": "engagement",
    "fatigue_check": "fatigue.check",
    "FatigueLoads": "cycles",
    "FatigueParams": "fatigue.strength",
    "FatigueResult": "fatigue.check",
    "heat_partition": "heat",
    "heat_transient": "heat",
    "HeatPartition": "heat",
    "integrate_wear": "wear",
    "LoadCycle": "fatigue.check",
    "Location": "location",
    "name_location": "location",
    "render_png": "heat",
    "ripple_classes": "cycles",
    "service_cycles": "cycles",
    "ServiceStates": "cycles",
    "single_cycle_factor": "fatigue.criteria",
    "slip_heat_load": "heat",
    "slip_heat_validity": "heat",
    "SlipHeatLoad": "heat",
    "SlipHeatResult": "heat",
    "SlipScenario": "heat",
    "start_heating": "start_heat",
    "StartHeating": "start_heat",
    "ThermalEnvironment": "heat",
    "ThermalMaterial": "heat",
    "wear_rate": "wear",
    "WearParams": "wear",
    "WearRun": "wear",
    "write_series": "heat",
    "write_vtu": "heat",
}

__all__ = ["DriveLine", "Engagement", "engagement_transient", "StartHeating", "start_heating", "WearParams",
           "WearRun", "integrate_wear", "wear_rate", "DrumThermal", "FatigueLoads", "FatigueParams", "FatigueResult", "HeatPartition", "LoadCycle",
           "Location", "ServiceStates", "SlipHeatLoad", "SlipHeatResult", "SlipScenario", "ThermalEnvironment",
           "ThermalMaterial", "candidate_points", "endurance_limit", "fatigue_check", "heat_partition",
           "name_location", "render_png", "ripple_classes", "service_cycles", "single_cycle_factor",
           "heat_transient", "slip_heat_load", "slip_heat_validity", "write_series", "write_vtu"]

__getattr__, __dir__ = lazy_names(__name__, globals(), _NAMES)
