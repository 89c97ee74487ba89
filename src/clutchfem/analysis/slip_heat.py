"""Slip heat of a design: the thesis's slip test (drum held, full throttle) from the
mechanical answer to the temperatures.

The engine settles at the slip speed, where the clutch's FE friction torque meets the
engine curve (:func:`~clutchfem.analysis.slip_step`, the step ``analyze`` uses); the FE
contact forces at that speed (full-slip Coulomb friction, ``design.case().solve``) give the
friction heat node by node; :func:`clutchfem.thermal.heat_transient` conducts the part's
share through the plate.  Designs that never slip or never touch the drum get an answer
saying so, and what happens instead.  Where the answer leaves the range its model holds
(tempering, phase change, melting, the clearance closed by thermal growth) it carries
``validity`` flags, and it is cut at a phase change or melting
(:func:`clutchfem.thermal.slip_heat_validity`).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..clutch import EngineCurve
from ..core import rpm_to_rad_s
from ..loadcase import Design, design_inputs, design_label
from ..thermal import (
    DrumThermal,
    SlipHeatLoad,
    SlipHeatResult,
    SlipScenario,
    ThermalEnvironment,
    ThermalMaterial,
    heat_transient,
    slip_heat_validity,
)
from .torque import slip_step

__all__ = ["SlipHeatRun", "slip_heat"]


@dataclass(frozen=True)
class SlipHeatRun:
    """A slip-heat answer (:func:`slip_heat`): ``doc`` (JSON-ready), ``result`` (the
    transient, None without heat) and the ``design``.

    Attributes
    ----------
    doc : dict
        The answers (``slip_status``, ``slip_note``, ``slip_rpm``, ``slip_power_W``,
        ``peak_temperature_C``, ``flexure_temperature_C``, ``time_to_limit_s``, ``validity``,
        ...) with the design's and the thermal inputs; :meth:`to_json` returns it.
    result : SlipHeatResult or None
        The transient (temperature fields over time); None when nothing slips or touches.
    design : Design

    Examples
    --------
    An engine curve that ends below the engagement speed: the shoes never touch, no heat.

    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> run = cf.slip_heat(d, cf.EngineCurve((1000, 2000), (1.0, 1.5)))
    >>> run.doc["slip_status"], run.result is None, run.to_json()["slip_power_W"]
    ('never engages', True, 0.0)
    """

    doc: dict
    result: SlipHeatResult | None
    design: Design

    def to_json(self) -> dict:
        return self.doc


def slip_heat(design: Design, engine: EngineCurve | None = None, *, part: ThermalMaterial | None = None,
              drum: DrumThermal | None = None, env: ThermalEnvironment | None = None,
              scenario: SlipScenario | None = None, heat_fraction: float | None = None) -> SlipHeatRun:
    """How hot the clutch gets while it slips in a held drum at full throttle (the thesis's
    slip test): the slip speed where the FE friction torque meets the engine curve, the
    friction heat node by node from the FE contact forces there, and the transient
    conduction of the part's share through the plate (module docstring).

    Parameters
    ----------
    design : Design
        The design (a concept's or a user mesh's).
    engine : EngineCurve, optional
        Full-throttle torque (default: the built-in 56.5 cc saw curve, its shape ASSUMED).
    part, drum, env, scenario : optional
        Thermal material of the part, the drum, the surroundings and the slip scenario
        (events, durations, pauses); defaults ASSUMED and sourced in docs/durability.md.
    heat_fraction : float, optional
        The part's share of the friction heat in [0, 1] (default: from the shoe/drum partition).

    Returns
    -------
    SlipHeatRun
        ``doc``: the answers (JSON-ready: slip speed and power, peak and flexure
        temperatures, time to the limit, yield strength left, with the design inputs);
        ``result``: the transient (None when nothing slips or touches); ``design``.

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="2.5mm"))
    >>> run = cf.slip_heat(d, scenario=cf.SlipScenario(seconds=2))
    >>> run.doc["slip_status"], run.doc["peak_temperature_C"] > run.doc["ambient_temperature_C"]
    ('slips', True)
    """
    engine = EngineCurve.of(engine)
    part = part or ThermalMaterial()
    env = env or ThermalEnvironment()
    scenario = scenario or SlipScenario()
    case = design.case()
    slip = slip_step(case, engine)
    lo, hi = engine.rpm_range
    mu = design.op.mu
    eng_info = {"source": engine.source, "assumed_shape": engine.assumed, "rpm_range": [lo, hi]}
    thermal_inputs = {"part": part.model_dump(), "drum": (drum or DrumThermal()).model_dump(),
                      "environment": env.model_dump(), "scenario": scenario.model_dump(),
                      "heat_fraction": "from the partition" if heat_fraction is None else heat_fraction}
    doc = {"design": design.name, "label": design_label(design), "slip_status": slip.status,
           "engagement_rpm": case.engagement_rpm, "mu": mu,
           "inputs": {**design_inputs(design), "engine": eng_info, "thermal": thermal_inputs},
           "units": {"temperature": "C", "time": "s", "energy": "J", "power": "W", "torque": "N m",
                     "speed": "rpm", "stress": "Pa", "lengths": "m"}}
    rpm = None
    if slip.status == "slips":
        rpm = float(slip.rpm)
        note = (f"the engine settles at the slip speed {rpm:.0f} rpm, where the clutch's friction torque meets the "
                "engine's full-throttle torque")
    elif slip.status == "never holds" and mu > 0:
        rpm = float(hi)
        note = (f"the clutch never holds the engine: with the drum held the engine runs to its maximum speed "
                f"{hi:.0f} rpm and the shoes slip there with the clutch torque at that speed (below the engine's)")
    elif slip.status == "never engages":
        note = (f"no slip heat: the shoes never touch the drum within the engine's speed range (up to {hi:.0f} rpm): "
                "no friction, no heat; the engine runs free up to its maximum speed and the chain does not move")
    elif slip.status == "holds at start":
        note = (f"no slip-heat answer from this engine curve: the clutch already holds the engine torque at "
                f"{lo:.0f} rpm, the curve's lowest speed, so with the drum held the engine is pulled below the "
                "curve (it stalls, or slips at a speed the curve does not cover): give an engine curve that starts "
                "lower (--engine)")
    else:  # never holds with mu = 0
        note = ("no slip heat: mu = 0, the clutch transmits no torque and makes no friction heat; the engine runs "
                f"free up to its maximum speed {hi:.0f} rpm with the drum held")
    doc["slip_note"] = note
    empty = {"seconds": scenario.seconds, "cycles": scenario.cycles, "pause_s": scenario.pause, "slip_rpm": rpm,
             "slip_power_W": 0.0, "friction_work_J": 0.0, "heat_into_part_J": 0.0, "flexure_temperature_C": None,
             "peak_temperature_C": None, "ambient_temperature_C": env.ambient_temperature,
             "time_to_limit_s": None, "limit_temperature_C": part.limit_temperature, "validity": [], "valid": True}
    if rpm is None:
        doc.update(empty)
        doc["heat"] = False
        return SlipHeatRun(doc, None, design)
    w = rpm_to_rad_s(rpm)
    lam, _ = case.solve(w)
    nodes = design.nodes
    clutch_torque = case.friction_torque(lam)
    doc.update({"slip_rpm": rpm, "clutch_torque_Nm": clutch_torque,
                "engine_torque_at_slip_Nm": float(engine.torque_at(rpm)),
                "contact_nodes": int((lam > 0).sum())})
    if not lam.any():
        doc.update(empty)
        doc["heat"] = False
        doc["slip_note"] = note + f"; but no contact force at {rpm:.0f} rpm: no heat"
        return SlipHeatRun(doc, None, design)
    load = SlipHeatLoad(node_index=nodes.dof_x // 2, lam_N=lam, mu=mu, omega_rad_s=w,
                        drum_radius_m=design.drum_radius)
    r = heat_transient(design.cm, design.thickness, part, load, scenario=scenario, env=env, drum=drum,
                 heat_fraction=heat_fraction)
    doc.update(r.to_json())
    doc["heat"] = True
    g0 = case.contact.nodes.gap0
    clearance = float(g0.min()) if len(g0) else None
    doc.update(slip_heat_validity(doc, limit_C=part.limit_temperature, clearance_m=clearance,
                                  contact_radius_m=None if clearance is None else design.drum_radius - clearance,
                                  phase_change_C=part.phase_change_temperature,
                                  melting_C=part.melting_temperature))
    if not doc["valid"] and doc.get("flexure_temperature_C") is not None:
        doc["yield_strength_at_flexure_peak_Pa"] = float(part.yield_ratio(doc["flexure_temperature_C"])
                                                         * part.yield_strength)
    return SlipHeatRun(doc, r, design)
