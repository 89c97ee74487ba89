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


@O.takes("concept", "set_", "mesh", "mesh_size", "drum_radius", "thickness", "mu", "rotation", "material",
         "drum_wall", "drum_state", "softening", "fidelity", "formulation", "layers", "engine", "idle_rpm",
         "a", "b", "out", "json_", live=True)
def analyze(
    o,
    rpm: str = typer.Option(None, "--rpm", help="speeds in rpm to tabulate, e.g. 0:14000:125 (default: 0..engine "
                            "max, 125 rpm steps); the answers do not depend on them", rich_help_panel=O.OUTPUT),
    fatigue: List[str] = typer.Option([], "--fatigue", help="fatigue setting name=value with its unit (service "
                                      "loads: start_stops, revolutions, operating_rpm, cutting_torque, ...; strength: "
                                      "ultimate_strength, edge_finish, reliability, ...); see --list-fatigue",
                                      rich_help_panel=O.MODEL),
    list_fatigue: bool = typer.Option(False, "--list-fatigue", help="list the --fatigue settings and exit",
                                      rich_help_panel=O.MODEL),
):
    """Engagement (static, with ripple), slip speed, torque margin, stresses, fatigue,
    plus/minus character, crankshaft whirl and the requirement checks, each with its error."""
    from .. import dumps

    try:
        if list_fatigue:
            print_settings(fatigue_groups(), "--fatigue")
            return
        check_out_dir(o.out)
        # cheap input checks first, before any meshing
        groups = fatigue_groups()
        fat = grouped_assignments(fatigue, groups, "--fatigue")
        fat_loads = build_params(groups["loads"], fat["loads"], "--fatigue")
        fat_params = build_params(groups["strength"], fat["strength"], "--fatigue") if fat["strength"] else None
        req = requirements_from(o.a, o.b)
        eng, idle = engine_from(o.engine, o.idle_rpm)
        lo_, hi_ = eng.rpm_range
        for nm in ("operating_rpm", "max_rpm"):
            v = getattr(fat_loads, nm)
            if v is not None and not lo_ <= v <= hi_:
                raise ParameterError(nm, v, f"a speed within the engine curve's range {lo_:g}..{hi_:g} rpm",
                                     "option --fatigue (fatigue loads)")
        mat = material_from(o.material)
        op = operating_point(mu=o.mu, rotation=o.rotation, softening=o.softening, fidelity=o.fidelity,
                             formulation=o.formulation, rpm=rpm,
                             layers=o.layers, drum_wall=o.drum_wall, drum_state=o.drum_state, material=mat)
        if op.rpm is not None:
            from .. import check_speeds

            check_speeds(op.speeds(), eng)
        if o.mesh is not None and o.drum_radius is None:
            raise ClutchfemError("analyze --mesh needs --drum-radius: the drum's inner radius (e.g. 35mm), larger "
                                 "than the outer radius of the 'contact' curves; without a drum there is no "
                                 "friction torque to analyse")
        with working(f"analyze {o.concept or o.mesh}") as stage:
            stage("meshing")
            design = design_from(o.concept, o.set_, o.mesh, op=op, mesh_size=o.mesh_size, drum_radius=o.drum_radius,
                                 thickness=o.thickness)
        if design.params is None and "contact" not in (design.cm.mesh.boundaries or {}):
            raise ClutchfemError(f"{o.mesh}: analyze needs a physical curve group 'contact' (the shoe surfaces facing "
                                 f"the drum); groups found: {sorted(design.cm.mesh.boundaries or {})}")
        from .. import analyze as run  # (a live design: the reduced model's answer, without the FE stack)

        with working(f"analyze {design.name}") as stage:
            stage("engagement, torque, slip, fatigue and their errors")
            an = run(design, engine=eng, requirements=req, idle_rpm=idle, fatigue_loads=fat_loads,
                     fatigue_params=fat_params)
        if o.out is not None:
            from .. import write_report

            wrote(write_report(an, o.out, engine=eng))
        if o.json_:
            print(dumps(an.to_json()))
            return
        from .. import summary_rows

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
