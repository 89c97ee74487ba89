"""Slip heat (a pipeline stage below durability): transient heat conduction in a one-piece
clutch while it slips in a held drum.

The shoes rub the held drum at v = omega R_d; the friction power mu v lam_i of every contact
node is split between the shoe and the drum (Blok's equal patch temperatures); the shoe's
share conducts into the part, a plate of thickness h (scalar P2 on the clutch mesh), which
loses heat through its two faces and into the crankshaft.  Repeated slip events with
cooling pauses show whether heat accumulates.  By job:

* :mod:`.params` -- :class:`ThermalMaterial`, :class:`DrumThermal`, :class:`ThermalEnvironment`,
  :class:`SlipScenario` and the hot yield strength (every ASSUMED value with its source);
* :mod:`.load` -- the heat load Q_i = gamma mu v lam_i from the contact forces;
* :mod:`.partition` -- the drum's conduction (analytic) and the shoe/drum heat partition;
* :mod:`.assembly` -- the FE operators M, K, H, f and the cyclic map of a sector;
* :mod:`.stepping` -- Crank-Nicolson with a Rannacher start, energy tallies, steady state;
* :mod:`.result` -- :class:`SlipHeatResult`;
* :mod:`.slip` -- :func:`heat_transient`, the slip test step by step;
* :mod:`.output` -- .vtu and PNG.

The model's derivation, its limits and the verification: ``docs/durability_theory.md``.
"""

from .assembly import HeatModel, build_heat_model
from .load import SlipHeatLoad, slip_heat_load
from .output import render_png, write_series, write_vtu
from .params import (
    HOT_YIELD_TABLE,
    MAX_TIME_STEPS,
    DrumThermal,
    SlipScenario,
    ThermalEnvironment,
    ThermalMaterial,
    hot_yield_ratio,
)
from .partition import PERIODIC_PASSES, HeatPartition, drum_patch_response, heat_partition, wall_step_response
from .result import SlipHeatResult
from .slip import heat_transient
from .validity import EXPANSION_PER_K, MELTING_C, PHASE_CHANGE_C, slip_heat_validity

__all__ = [
    "ThermalMaterial", "DrumThermal", "ThermalEnvironment", "SlipScenario", "SlipHeatLoad",
    "slip_heat_load", "HeatPartition", "heat_partition", "wall_step_response",
    "drum_patch_response", "HeatModel", "build_heat_model", "heat_transient", "SlipHeatResult",
    "write_vtu", "write_series", "render_png", "slip_heat_validity", "PHASE_CHANGE_C", "MELTING_C", "EXPANSION_PER_K",
    "hot_yield_ratio", "HOT_YIELD_TABLE", "PERIODIC_PASSES", "MAX_TIME_STEPS",
]
