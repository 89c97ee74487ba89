"""``clutchfem slip-heat``: how hot the clutch gets while it slips in a held drum (the
thesis's slip test, :func:`clutchfem.analysis.slip_heat`)."""

from __future__ import annotations

import math
from typing import List, Optional

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError, InputError, ParameterError
from . import options as O
from .common import (
    build_params,
    check_out_dir,
    console,
    design_from,
    engine_from,
    err,
    fail,
    grouped_assignments,
    operating_point,
    print_settings,
    quantity,
    working,
    wrote,
)


def thermal_groups() -> dict:
    """The parameter sets --thermal writes into (prefix -> ParamSet class)."""
    from .. import DrumThermal, SlipScenario, ThermalEnvironment, ThermalMaterial

    return {"part": ThermalMaterial, "drum": DrumThermal, "env": ThermalEnvironment, "scenario": SlipScenario}


@O.takes("concept", "set_", "mesh", "mesh_size", "model", "drum_radius", "thickness", "mu", "fidelity",
         "rotation", "engine", "out", "json_")
def slip_heat(
    o,
    seconds: Optional[str] = typer.Option(None, "--seconds", help="duration of one slip event, e.g. 10s (default "
                                          "10 s; 0.001..3600 s)", rich_help_panel="Slip test"),
    cycles: Optional[str] = typer.Option(None, "--cycles", help="number of slip events (default 1; 1..1000)",
                                         rich_help_panel="Slip test"),
    pause: Optional[str] = typer.Option(None, "--pause", help="cooling pause after each event, e.g. 20s (idle, no "
                                        "friction; needed with --cycles > 1; 0..36000 s)", rich_help_panel="Slip test"),
    thermal: List[str] = typer.Option([], "--thermal", help="thermal setting name=value with its unit: part "
                                      "(conductivity, limit_temperature, ...), drum.* (wall_thickness, ...), environment "
                                      "(face_htc, bore_conductance, ambient_temperature, ...), scenario "
                                      "(steps_per_event); see --list-thermal", rich_help_panel="Slip test"),
    list_thermal: bool = typer.Option(False, "--list-thermal", help="list the --thermal settings and exit",
                                      rich_help_panel="Slip test"),
    heat_fraction: Optional[str] = typer.Option(None, "--heat-fraction", help="share of the friction heat that "
                                                "enters the part in 0..1 (default: from the shoe/drum partition)",
                                                rich_help_panel="Slip test"),
):
    """Slip heat with the drum held at full throttle: temperatures of flexure, shoe face and
    hub against time, time to the limit (tempering) temperature, yield strength left."""
    from .. import dumps, write_report
    from .. import slip_heat as run

    try:
        groups = thermal_groups()
        if list_thermal:
            print_settings(groups, "--thermal")
            return
        check_out_dir(o.out)
        # every input checked before meshing
        th = grouped_assignments(thermal, groups, "--thermal")
        for name, raw in (("seconds", seconds), ("cycles", cycles), ("pause", pause)):
            if raw is not None:
                if name in th["scenario"]:
                    raise InputError(f"--{name} and --thermal {name}=... both given: give it once")
                try:
                    th["scenario"][name] = groups["scenario"].parse_value(name, raw)
                except ParameterError as exc:
                    raise ParameterError(exc.name, exc.value, exc.allowed, f"option --{name}") from None
        part = build_params(groups["part"], th["part"], "--thermal")
        drum = build_params(groups["drum"], th["drum"], "--thermal")
        env = build_params(groups["env"], th["env"], "--thermal")
        try:
            scenario = build_params(groups["scenario"], th["scenario"], "--thermal")
        except ParameterError as exc:  # name the option the user typed
            if exc.name in ("seconds", "cycles", "pause") and f"{exc.name}=" not in " ".join(thermal):
                raise ParameterError(exc.name, exc.value, exc.allowed, f"option --{exc.name}",
                                     shown=exc.shown) from None
            raise
        fraction = quantity("--heat-fraction", heat_fraction, "-", 0.0, 1.0)
        eng, _ = engine_from(o.engine)
        op = operating_point(mu=o.mu, rotation=o.rotation, fidelity=o.fidelity)
        with working(f"slip-heat {o.concept or o.mesh}") as stage:
            stage("meshing")
            design = design_from(o.concept, o.set_, o.mesh, op=op, mesh_size=o.mesh_size, model=o.model,
                                 drum_radius=o.drum_radius, thickness=o.thickness)
            stage("slip speed, contact forces and the heat transient")
            result = run(design, eng, part=part, drum=drum, env=env, scenario=scenario, heat_fraction=fraction)
        if o.out is not None:
            wrote(write_report(result, o.out))
        if o.json_:
            print(dumps(result.doc))
            return
        print_table(result.doc)
    except ClutchfemError as exc:
        fail(exc)
    except KeyboardInterrupt:  # typer would exit 130 silently
        err.print("interrupted (Ctrl-C): stopped; no file of this run was written (outputs are written whole "
                  "or not at all)")
        raise typer.Exit(code=130) from None


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
             else (f"not reached before the stop at {doc['stopped_at_s']:.2f} s" if doc.get("stopped_at_s")
                   is not None else f"not reached in {doc['seconds'] * doc['cycles']:g} s of slip")),
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
    for f in doc.get("validity") or []:  # where the model stops holding (thermal.validity)
        rows.append((f"MODEL LIMIT: {f['flag']} ({f['level_C']:.0f} C)", f"reached at {f['time_s']:.2f} s"))
    if doc.get("stopped_at_s") is not None:
        rows.append(("TRANSIENT STOPPED", f"at {doc['stopped_at_s']:.2f} s (answers above: up to there)"))
    for q, v in rows:
        t.add_row(escape(q), escape(v))
    console.print(t)
    for f in doc.get("validity") or []:
        console.print(f"[bold red]WARNING:[/] {escape(f['meaning'])}")
    console.print(f"[dim]{escape(doc['slip_note'])}[/]")
    if doc["heat"]:
        console.print("[dim]ASSUMED: " + escape("; ".join(doc["assumed"])) + "[/]")
