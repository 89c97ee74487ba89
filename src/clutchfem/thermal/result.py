"""The answer of a slip-heat run: :class:`SlipHeatResult`, its probes' time series, peaks
and their places, the hot yield strength, the heat partition and the energy balance, and
its JSON form.

Temperatures in C, energies in J for the whole part (a sector's values x n_total / n_model),
times in s from the start of the first slip event.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .partition import HeatPartition

__all__ = ["SlipHeatResult"]


@dataclass(frozen=True)
class SlipHeatResult:
    """What :func:`heat_transient` returns.  Temperatures in C, energies in J for the whole part;
    ``peak_location`` / ``flexure_peak_location`` name the zone, the flexure end and the
    boundary of the hottest points (e.g. concept 2's 'in-shoe flexure').

    Probes (time series over ``times_s``):
    * ``flexure_C``: the hottest node of all ``flexure_<i>`` zones at each time (None if the
      mesh has no flexure zone);
    * ``shoe_face_C``: the hottest node of the ``contact`` surface (the shoes' friction face);
    * ``hub_C``: the area-weighted mean temperature of the ``hub`` zone (of the bore edge if
      the mesh has no hub zone: see ``probe_definitions``);
    * ``part_max_C``: the hottest node anywhere;
    * ``part_mean_C``: the area-weighted mean temperature of the part (its heat content).
    """

    times_s: np.ndarray
    flexure_C: np.ndarray | None
    shoe_face_C: np.ndarray
    hub_C: np.ndarray
    part_max_C: np.ndarray
    probe_definitions: dict
    peak_temperature_C: float
    peak_time_s: float
    peak_xy_m: tuple[float, float]
    peak_zone: str
    peak_location: str
    flexure_peak_C: float | None
    flexure_peak_time_s: float | None
    flexure_peak_xy_m: tuple[float, float] | None
    flexure_peak_location: str | None
    limit_temperature_C: float
    time_to_limit_s: float | None
    yield_ratio_at_limit: float
    yield_strength_at_limit_Pa: float
    yield_strength_at_limit_bounds_Pa: tuple[float, float]
    yield_strength_at_flexure_peak_Pa: float | None
    slip_rpm: float
    slip_power_W: float
    friction_work_J: float
    heat_into_part_J: float
    partition: HeatPartition
    energy: dict
    cycles: list
    initial_field_C: np.ndarray
    final_field_C: np.ndarray
    nodal_max_C: np.ndarray
    ambient_temperature_C: float
    initial_state: str
    dt_s: float
    n_steps: int
    time_error_estimate_K: float | None
    scenario: dict
    timings: dict
    assumed: tuple[str, ...]
    #: area-weighted mean temperature of the part over ``times_s`` (its heat content): what
    #: a thermometer on the whole clutch would read after the heat has spread
    part_mean_C: np.ndarray | None = None
    #: times [s] of the full fields ``frames_C`` (frames x nodes, C) kept over the run: its time
    #: series (``clutchfem.durability.write_series``)
    frame_times_s: np.ndarray | None = None
    frames_C: np.ndarray | None = None

    @property
    def seconds(self) -> float:
        return float(self.scenario["seconds"])

    def to_json(self) -> dict:
        def r(x):
            return None if x is None else [float(v) for v in x]

        return {
            "seconds": self.seconds, "cycles": int(self.scenario["cycles"]), "pause_s": float(self.scenario["pause"]),
            "slip_rpm": self.slip_rpm, "slip_power_W": self.slip_power_W, "friction_work_J": self.friction_work_J,
            "heat_into_part_J": self.heat_into_part_J, "heat_fraction_part": self.partition.fraction_part,
            "flexure_temperature_C": self.flexure_peak_C, "flexure_peak_time_s": self.flexure_peak_time_s,
            "peak_temperature_C": self.peak_temperature_C, "peak_time_s": self.peak_time_s,
            "peak_xy_m": list(self.peak_xy_m), "peak_zone": self.peak_zone, "peak_location": self.peak_location,
            "flexure_peak_xy_m": None if self.flexure_peak_xy_m is None else list(self.flexure_peak_xy_m),
            "flexure_peak_location": self.flexure_peak_location,
            "ambient_temperature_C": self.ambient_temperature_C,
            "limit_temperature_C": self.limit_temperature_C, "time_to_limit_s": self.time_to_limit_s,
            "yield_strength_at_limit_Pa": self.yield_strength_at_limit_Pa,
            "yield_strength_at_limit_bounds_Pa": list(self.yield_strength_at_limit_bounds_Pa),
            "yield_strength_at_flexure_peak_Pa": self.yield_strength_at_flexure_peak_Pa,
            "energy_J": dict(self.energy), "partition": self.partition.to_json(), "cycles_table": self.cycles,
            "dt_s": self.dt_s, "n_steps": self.n_steps, "time_error_estimate_K": self.time_error_estimate_K,
            "initial_state": self.initial_state, "probe_definitions": dict(self.probe_definitions),
            "series": {"times_s": r(self.times_s), "flexure_C": r(self.flexure_C),
                       "shoe_face_C": r(self.shoe_face_C), "hub_C": r(self.hub_C),
                       "part_mean_C": r(self.part_mean_C),
                       "part_max_C": r(self.part_max_C)},
            "timings_s": dict(self.timings), "assumed": list(self.assumed),
        }
