"""``clutchfem slip-heat``: how hot the clutch gets while it slips in a held drum.

The thesis's slip test (issue 14): chain brake on (drum held), full throttle.  The engine
settles at the slip speed, where the clutch's FE friction torque meets the engine curve
(:func:`clutchfem.clutch.analyze.slip_step`, the step ``analyze`` uses); the FE contact
forces at that speed (full-slip Coulomb friction, :meth:`Design.case().solve`) give the
friction heat node by node; :func:`clutchfem.durability.heat.slip_heat` conducts the
part's share through the plate.  Designs that never slip or never touch the drum get an
answer saying so, and what happens instead.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import List, Optional

import typer
from rich.markup import escape
from rich.table import Table

from ..core import ClutchfemError
from ..loadcase import OperatingPoint as _OP
from .common import (
    build_params,
    check_out_dir,
    console,
    describe_groups,
    err,
    fail,
    grouped_assignments,
    length_option,
    mesh_settings,
    operating_point,
)


def thermal_groups() -> dict:
    """The parameter sets --thermal writes into (prefix -> ParamSet class)."""
    from ..durability import DrumThermal, SlipScenario, ThermalEnvironment, ThermalMaterial

    return {"part": ThermalMaterial, "drum": DrumThermal, "env": ThermalEnvironment, "scenario": SlipScenario}


def slip_heat(
    concept: str = typer.Argument(..., help="concept name (clutchfem geometry --list)"),
    set_: List[str] = typer.Option([], "--set", help="concept parameter override name=value (unit suffix: mm, deg)"),
    seconds: Optional[float] = typer.Option(None, "--seconds", help="duration of one slip event [s] (default 10 s; "
                                            "0.001..3600 s)"),
    cycles: Optional[int] = typer.Option(None, "--cycles", help="number of slip events [-] (default 1; 1..1000)"),
    pause: Optional[float] = typer.Option(None, "--pause", help="cooling pause after each event [s] (idle, no "
                                          "friction; needed with --cycles > 1; 0..36000 s)"),
    thermal: List[str] = typer.Option([], "--thermal", help="thermal setting name=value: part (conductivity, "
                                      "limit_temperature, ...), drum.* (wall_thickness, ...), environment (face_htc, "
                                      "bore_conductance, ambient_temperature, ...), scenario (steps_per_event); "
                                      "--list-thermal lists them with units and defaults (all ASSUMED)"),
    list_thermal: bool = typer.Option(False, "--list-thermal", help="list the --thermal settings and exit"),
    heat_fraction: Optional[float] = typer.Option(None, "--heat-fraction", help="share of the friction heat that "
                                                  "enters the part [-] in 0..1 (default: from the shoe/drum "
                                                  "partition, Blok's equal temperatures)"),
    engine: Optional[Path] = typer.Option(None, "--engine", help="engine torque CSV (columns rpm, torque [N m]); "
                                          "default: the built-in 56.5 cc saw curve (ASSUMED shape)"),
    mu: Optional[str] = typer.Option(None, "--mu", help=_OP.help("mu")),
    rotation: Optional[str] = typer.Option(None, "--rotation", help=_OP.help("rotation")),
    mesh_size: Optional[str] = typer.Option(None, "--mesh-size", help="global element size [m] (unit suffix: mm)"),
    model: str = typer.Option("sector", "--model", help="sector (cyclic) or full"),
    json_: bool = typer.Option(False, "--json", help="print the JSON document"),
    out: Optional[Path] = typer.Option(None, "--out", help="folder for the temperature field (.vtu), the picture "
                                       "(PNG) and the JSON with the design inputs"),
):
    """Slip heat with the drum held at full throttle: temperatures of flexure, shoe face and
    hub against time, time to the limit (tempering) temperature, yield strength left."""
    from ..core import InputError, ParameterError

    try:
        groups = thermal_groups()
        if list_thermal:
            t = Table(title="--thermal settings (name=value; ASSUMED defaults, sources in docs/durability.md)")
            for col in ("name", "unit", "default", "allowed: meaning"):
                t.add_column(col)
            for row in describe_groups(groups):
                t.add_row(*(escape(x) for x in row))
            console.print(t)
            return
        check_out_dir(out)
        # every input checked before meshing
        th = grouped_assignments(thermal, groups, "--thermal")
        for name, v in (("seconds", seconds), ("cycles", cycles), ("pause", pause)):
            if v is not None:
                if name in th["scenario"]:
                    raise InputError(f"--{name} and --thermal {name}=... both given: give it once")
                th["scenario"][name] = v
        part = build_params(groups["part"], th["part"], "--thermal")
        drum = build_params(groups["drum"], th["drum"], "--thermal")
        env = build_params(groups["env"], th["env"], "--thermal")
        try:
            scenario = build_params(groups["scenario"], th["scenario"], "--thermal")
        except ParameterError as exc:  # name the option the user typed
            if exc.name in ("seconds", "cycles", "pause") and f"{exc.name}=" not in " ".join(thermal):
                raise ParameterError(exc.name, exc.value, exc.allowed, f"option --{exc.name}") from None
            raise
        if heat_fraction is not None and not (math.isfinite(heat_fraction) and 0.0 <= heat_fraction <= 1.0):
            raise ParameterError("heat_fraction", heat_fraction, "a share of the friction heat in [0, 1]",
                                 "option --heat-fraction")
        if model not in ("sector", "full"):
            raise ParameterError("model", model, "'sector' or 'full'", "option --model")
        from ..clutch import EngineCurve

        eng = EngineCurve.from_csv(engine) if engine else EngineCurve.default()
        op = operating_point(None, mu=mu, rotation=rotation)
        from ..geometry import get_concept

        c = get_concept(concept)
        p = c.Params.from_assignments(set_)
        size = length_option("size", mesh_size)
        ms = mesh_settings(size, model)
        doc, result, design = run_slip_heat(c, p, op, ms, eng, part=part, drum=drum, env=env, scenario=scenario,
                                            heat_fraction=heat_fraction)
        if out is not None:
            for f in write_outputs(doc, result, design, out):
                err.print(f"wrote {escape(str(f))}")
        if json_:
            from ..core import dumps

            print(dumps(doc))
            return
        print_table(doc)
    except ClutchfemError as exc:
        fail(exc)
    except KeyboardInterrupt:  # typer would exit 130 silently
        err.print("interrupted (Ctrl-C): stopped; no file of this run was written (outputs are written whole "
                  "or not at all)")
        raise typer.Exit(code=130) from None


# ---------------------------------------------------------------------------------------
# the work (also used by scripts/make_durability_docs.py)
# ---------------------------------------------------------------------------------------
def run_slip_heat(concept, params, op, mesh_settings_, engine, *, part=None, drum=None, env=None, scenario=None,
                  heat_fraction=None, design=None):
    """(JSON document, SlipHeatResult or None, Design): mesh, the slip speed with the drum
    held (FE torque against ``engine``), the contact forces there, the heat run."""
    from ..analysis import slip_step
    from ..core import rpm_to_rad_s
    from ..durability import SlipHeatLoad, SlipScenario, ThermalEnvironment, ThermalMaterial
    from ..durability import slip_heat as run_heat
    from ..loadcase import Design, design_inputs, design_label
    from ..mesh import mesh_concept

    part = part or ThermalMaterial()
    env = env or ThermalEnvironment()
    scenario = scenario or SlipScenario()
    if design is None:
        cm = mesh_concept(concept, params, mesh_settings_)
        design = Design(cm, op, params=params, name=concept.name)
    case = design.case()
    slip = slip_step(case, engine)
    lo, hi = engine.rpm_range
    mu = design.op.mu
    eng_info = {"source": engine.source, "assumed_shape": engine.assumed, "rpm_range": [lo, hi]}
    from ..durability import DrumThermal

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
             "time_to_limit_s": None, "limit_temperature_C": part.limit_temperature}
    if rpm is None:
        doc.update(empty)
        doc["heat"] = False
        return doc, None, design
    w = rpm_to_rad_s(rpm)
    lam, _ = case.solve(w)
    nodes = design.nodes
    clutch_torque = float(mu * design.drum_radius * lam.sum() * case.scale)
    doc.update({"slip_rpm": rpm, "clutch_torque_Nm": clutch_torque,
                "engine_torque_at_slip_Nm": float(engine.torque_at(rpm)),
                "contact_nodes": int((lam > 0).sum())})
    if not lam.any():
        doc.update(empty)
        doc["heat"] = False
        doc["slip_note"] = note + f"; but no contact force at {rpm:.0f} rpm: no heat"
        return doc, None, design
    load = SlipHeatLoad(node_index=nodes.dof_x // 2, lam_N=lam, mu=mu, omega_rad_s=w,
                        drum_radius_m=design.drum_radius)
    r = run_heat(design.cm, design.thickness, part, load, scenario=scenario, env=env, drum=drum,
                 heat_fraction=heat_fraction)
    doc.update(r.to_json())
    doc["heat"] = True
    return doc, r, design


def write_outputs(doc: dict, result, design, out: Path) -> list[Path]:
    """``<label>_slip_heat.vtu`` (final and maximum temperature on the P2 mesh),
    ``<label>_slip_heat.png`` (maximum temperature map and probe histories) and
    ``<label>_slip_heat.json`` (the document, with the design inputs).  All are written to
    hidden temporary names first and renamed together at the end, so an interrupted run
    leaves none of them (and no half file)."""
    from ..core import write
    from ..durability import render_png, write_vtu

    out = Path(out)
    stem = f"{doc['label']}_slip_heat"
    jobs = []
    if result is not None:
        title = (f"{doc['design']}: {result.slip_power_W:.0f} W slip at {result.slip_rpm:.0f} rpm, "
                 f"{result.partition.fraction_part:.0%} into the part; {result.seconds:g} s x {doc['cycles']}")
        jobs.append((".vtu", lambda p: write_vtu(design.cm, result, p)))
        jobs.append((".png", lambda p: render_png(design.cm, result, p, title=title)))
    jobs.append((".json", lambda p: write(p, doc, indent=2)))
    from ..core import InputError

    for suffix, _ in jobs:  # a folder (or anything but a file) in the way: refuse before writing any
        final = out / f"{stem}{suffix}"
        if final.exists() and not final.is_file():
            raise InputError(f"--out {out}: {final.name} exists and is not a file (a folder?): cannot write the "
                             "result there; remove it or choose another --out")
    done = []
    try:
        for suffix, job in jobs:
            tmp = out / f".{stem}.partial{suffix}"
            done.append((tmp, out / f"{stem}{suffix}"))
            job(tmp)
        for tmp, final in done:
            os.replace(tmp, final)
    except OSError as exc:
        raise InputError(f"--out {out}: cannot write {Path(exc.filename or out).name} ({exc.strerror})") from None
    finally:
        for tmp, _ in done:
            if tmp.exists():
                tmp.unlink()
    return [final for _, final in done]


def _f(v, fmt: str, unit: str) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return f"{v:{fmt}} {unit}".rstrip()


def print_table(doc: dict) -> None:
    t = Table(title=escape(f"{doc['design']}: slip heat, drum held, full throttle (mu = {doc['mu']:g})"))
    t.add_column("quantity")
    t.add_column("value", justify="right")
    rpm = doc.get("slip_rpm")
    rows = [("slip speed", _f(rpm, ".0f", "rpm") if rpm else doc["slip_status"].upper())]
    if not doc["heat"]:
        rows += [("slip power", "0 W"), ("heat into the part", "0 J")]
    else:
        part = doc["partition"]
        lim = doc["limit_temperature_C"]
        rows += [
            ("clutch torque / engine torque at the slip speed",
             f"{doc['clutch_torque_Nm']:.2f} N m / {doc['engine_torque_at_slip_Nm']:.2f} N m"),
            ("slip power (clutch torque x slip speed)", _f(doc["slip_power_W"], ".0f", "W")),
            ("slip events", f"{doc['cycles']} x {doc['seconds']:g} s" + (f", {doc['pause_s']:g} s pauses"
                                                                          if doc["cycles"] > 1 else "")),
            ("friction work", _f(doc["friction_work_J"], ".0f", "J")),
            ("heat into the part (share)", f"{doc['heat_into_part_J']:.0f} J ({100 * part['fraction_part']:.1f} %)"),
            ("flexure: hottest point, peak",
             f"{doc['flexure_temperature_C']:.0f} C at {doc['flexure_peak_time_s']:.1f} s"
             if doc.get("flexure_temperature_C") is not None else "- (no flexure zone)"),
            ("flexure: where", str(doc.get("flexure_peak_location") or "-")),
            (f"time until the flexure reaches {lim:.0f} C (limit)",
             _f(doc["time_to_limit_s"], ".1f", "s") if doc["time_to_limit_s"] is not None
             else f"not reached in {doc['seconds'] * doc['cycles']:g} s of slip"),
            (f"yield strength left at {lim:.0f} C (EN 1993-1-2 k_p / k_y)",
             f"{doc['yield_strength_at_limit_bounds_Pa'][0] / 1e6:.0f} / "
             f"{doc['yield_strength_at_limit_bounds_Pa'][1] / 1e6:.0f} MPa"),
            ("yield strength left at the flexure peak", _f(
                None if doc.get("yield_strength_at_flexure_peak_Pa") is None
                else doc["yield_strength_at_flexure_peak_Pa"] / 1e6, ".0f", "MPa")),
            ("shoe face, hottest point, peak", _f(max(doc["series"]["shoe_face_C"]), ".0f", "C")),
            ("hub (mean) at the end", _f(doc["series"]["hub_C"][-1], ".0f", "C")),
            ("whole part (mean) at the start / peak", f"{doc['series']['part_mean_C'][0]:.0f} C / "
             f"{max(doc['series']['part_mean_C']):.0f} C"),
            ("peak temperature anywhere", f"{doc['peak_temperature_C']:.0f} C at {doc['peak_time_s']:.1f} s "
             f"({doc['peak_location']})"),
            ("ambient / initial state", f"{doc['ambient_temperature_C']:.0f} C / {doc['initial_state']}"),
            ("time step / time-error estimate", f"{doc['dt_s']:.3g} s / "
             + _f(doc["time_error_estimate_K"], ".2g", "K")),
            ("energy balance error (relative)", f"{doc['energy_J']['balance_error_rel']:.1e}"),
        ]
        for c in doc["cycles_table"]:
            if doc["cycles"] > 1 and "end_of_slip_flexure_C" in c:
                rows.append((f"event {c['cycle']}: flexure at end of slip / of pause",
                             f"{c['end_of_slip_flexure_C']:.0f} C / {c.get('end_of_pause_flexure_C', math.nan):.0f} C"))
    for q, v in rows:
        t.add_row(escape(q), escape(v))
    console.print(t)
    console.print(f"[dim]{escape(doc['slip_note'])}[/]")
    if doc["heat"]:
        console.print("[dim]ASSUMED: " + escape("; ".join(doc["assumed"])) + "[/]")
