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

from .cycles import FatigueLoads, ServiceStates, ripple_classes, service_cycles
from .engagement import DriveLine, Engagement, engagement_transient
from .fatigue import (
                      FatigueParams,
                      FatigueResult,
                      LoadCycle,
                      Location,
                      candidate_points,
                      endurance_limit,
                      fatigue_check,
                      name_location,
                      single_cycle_factor,
)
from .heat import (
                      DrumThermal,
                      HeatPartition,
                      SlipHeatLoad,
                      SlipHeatResult,
                      SlipScenario,
                      ThermalEnvironment,
                      ThermalMaterial,
                      heat_partition,
                      heat_transient,
                      render_png,
                      slip_heat_load,
                      slip_heat_validity,
                      write_series,
                      write_vtu,
)
from .start_heat import StartHeating, start_heating
from .wear import WearParams, WearRun, integrate_wear, wear_rate

__all__ = ["DriveLine", "Engagement", "engagement_transient", "StartHeating", "start_heating", "WearParams",
           "WearRun", "integrate_wear", "wear_rate", "DrumThermal", "FatigueLoads", "FatigueParams", "FatigueResult", "HeatPartition", "LoadCycle",
           "Location", "ServiceStates", "SlipHeatLoad", "SlipHeatResult", "SlipScenario", "ThermalEnvironment",
           "ThermalMaterial", "candidate_points", "endurance_limit", "fatigue_check", "heat_partition",
           "name_location", "render_png", "ripple_classes", "service_cycles", "single_cycle_factor",
           "heat_transient", "slip_heat_load", "slip_heat_validity", "write_series", "write_vtu"]
