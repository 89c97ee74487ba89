"""``clutchfem analyze``: the clutch designer's answers for one design."""

from __future__ import annotations

from typing import List

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError, ParameterError
from . import options as O
from .common import (
    build_params,
    check_out_dir,
    console,
    design_from,
    engine_from,
    fail,
    grouped_assignments,
    material_from,
    operating_point,
    print_settings,
    requirements_from,
    working,
    wrote,
)


def fatigue_groups() -> dict:
    """The parameter sets --fatigue writes into: service loads and fatigue strength."""
    from .. import FatigueLoads, FatigueParams

    return {"loads": FatigueLoads, "strength": FatigueParams}


def analyze(
    concept: O.Concept = None,
    set_: O.Set = [],
    mesh: O.Mesh = None,
    mesh_size: O.MeshSize = None,
    drum_radius: O.DrumRadius = None,
    thickness: O.Thickness = None,
    mu: O.Mu = None,
    rotation: O.Rotation = None,
    material: O.MaterialName = None,
    drum_wall: O.DrumWall = None,
    drum_state: O.DrumState = None,
    softening: O.Softening = None,
    fidelity: O.Fidelity = None,
    formulation: O.Formulation = None,
    layers: O.Layers = None,
    engine: O.Engine = None,
    idle_rpm: O.IdleRpm = None,
    a: O.A = None,
    b: O.B = None,
    rpm: str = typer.Option(None, "--rpm", help="speeds in rpm to tabulate, e.g. 0:14000:125 (default: 0..engine "
                            "max, 125 rpm steps); the answers do not depend on them", rich_help_panel=O.OUTPUT),
    fatigue: List[str] = typer.Option([], "--fatigue", help="fatigue setting name=value with its unit (service "
                                      "loads: start_stops, revolutions, operating_rpm, cutting_torque, ...; strength: "
                                      "ultimate_strength, edge_finish, reliability, ...); see --list-fatigue",
                                      rich_help_panel=O.MODEL),
    list_fatigue: bool = typer.Option(False, "--list-fatigue", help="list the --fatigue settings and exit",
                                      rich_help_panel=O.MODEL),
    out: O.Out = None,
    json_: O.Json = False,
):
    """Engagement (static, with ripple), slip speed, torque margin, stresses, fatigue,
    plus/minus character, crankshaft whirl and the requirement checks, each with its error."""
    from .. import analyze as run
    from .. import check_speeds, dumps, summary_rows, write_report

    try:
        if list_fatigue:
            print_settings(fatigue_groups(), "--fatigue")
            return
        check_out_dir(out)
        # cheap input checks first, before any meshing
        groups = fatigue_groups()
        fat = grouped_assignments(fatigue, groups, "--fatigue")
        fat_loads = build_params(groups["loads"], fat["loads"], "--fatigue")
        fat_params = build_params(groups["strength"], fat["strength"], "--fatigue") if fat["strength"] else None
        req = requirements_from(a, b)
        eng, idle = engine_from(engine, idle_rpm)
        lo_, hi_ = eng.rpm_range
        for nm in ("operating_rpm", "max_rpm"):
            v = getattr(fat_loads, nm)
            if v is not None and not lo_ <= v <= hi_:
                raise ParameterError(nm, v, f"a speed within the engine curve's range {lo_:g}..{hi_:g} rpm",
                                     "option --fatigue (fatigue loads)")
        mat = material_from(material)
        op = operating_point(mu=mu, rotation=rotation, softening=softening, fidelity=fidelity,
                             formulation=formulation, rpm=rpm,
                             layers=layers, drum_wall=drum_wall, drum_state=drum_state, material=mat)
        if op.rpm is not None:
            check_speeds(op.speeds(), eng)
        if mesh is not None and drum_radius is None:
            raise ClutchfemError("analyze --mesh needs --drum-radius: the drum's inner radius (e.g. 35mm), larger "
                                 "than the outer radius of the 'contact' curves; without a drum there is no "
                                 "friction torque to analyse")
        with working(f"analyze {concept or mesh}") as stage:
            stage("meshing")
            design = design_from(concept, set_, mesh, op=op, mesh_size=mesh_size, drum_radius=drum_radius,
                                 thickness=thickness)
        if design.params is None and "contact" not in (design.cm.mesh.boundaries or {}):
            raise ClutchfemError(f"{mesh}: analyze needs a physical curve group 'contact' (the shoe surfaces facing "
                                 f"the drum); groups found: {sorted(design.cm.mesh.boundaries or {})}")
        with working(f"analyze {design.name}") as stage:
            stage("engagement, torque, slip, fatigue and their errors")
            an = run(design, engine=eng, requirements=req, idle_rpm=idle, fatigue_loads=fat_loads,
                     fatigue_params=fat_params)
        if out is not None:
            wrote(write_report(an, out, engine=eng))
        if json_:
            print(dumps(an.to_json()))
            return
        t = Table(title=escape(f"{design.name}: clutch answers (mu = {an.mu:g}, {op.rotation})"))
        t.add_column("quantity")
        t.add_column("value", justify="right")
        for q, v in summary_rows(an):
            t.add_row(escape(q), escape(v))
        console.print(t)
        for w in an.warnings:
            console.print(f"[bold red]WARNING:[/] {escape(w)}")
        for n in an.notes:
            console.print(f"[dim]note: {escape(n)}[/]")
    except ClutchfemError as exc:
        fail(exc)
