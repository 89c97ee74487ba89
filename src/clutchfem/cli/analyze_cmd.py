"""``clutchfem analyze``: the clutch designer's answers for one design."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import List, Optional

import typer
from rich.table import Table

from ..errors import ClutchfemError
from .common import console, err, fail, load_design, material_from


def analyze(
    concept: Optional[str] = typer.Option(None, "--concept", help="concept name"),
    set_: List[str] = typer.Option([], "--set", help="concept parameter override name=value"),
    mesh: Optional[Path] = typer.Option(None, "--mesh", help="(not yet: analyze needs concept mass properties)"),
    engine: Optional[Path] = typer.Option(None, "--engine", help="engine torque CSV (columns rpm, torque [N m])"),
    idle_rpm: Optional[float] = typer.Option(None, "--idle-rpm", help="engine idle speed [rpm] (default: 2700, ASSUMED)"),
    mu: float = typer.Option(0.165, "--mu", help="friction coefficient [-]"),
    rotation: str = typer.Option("ccw", "--rotation", help="ccw or cw"),
    a: float = typer.Option(1.3, "--a", help="requirement: engagement > a x idle rpm (ASSUMED default)"),
    b: float = typer.Option(1.0, "--b", help="requirement: slip < b x rpm of max torque (ASSUMED default)"),
    rpm: Optional[str] = typer.Option(None, "--rpm", help="sweep speeds, e.g. 0:14000:125 (default: 0..engine max, 125 rpm steps)"),
    material: Optional[str] = typer.Option(None, "--material", help="51CrV4, titanium, aluminium"),
    json_: bool = typer.Option(False, "--json", help="print the JSON document"),
    out: Optional[Path] = typer.Option(None, "--out", help="folder for plots and tables"),
    mesh_size: Optional[float] = typer.Option(None, "--mesh-size", help="global element size [m]"),
):
    """Engagement (static, with ripple), slip rpm, torque margin, stress, plus/minus character."""
    from ..clutch.analyze import Requirements, analyze as run, check_speeds
    from ..clutch.engine import EngineCurve
    from ..errors import ParameterError

    try:
        if mesh is not None:
            raise ClutchfemError("analyze needs --concept NAME (user meshes carry no shoe mass properties yet; "
                                 "use 'clutchfem solve --mesh' for their FE curves)")
        # cheap input checks first, before any meshing
        req = Requirements(a=a, b=b)
        if idle_rpm is not None and not (math.isfinite(idle_rpm) and idle_rpm > 0):
            raise ParameterError("idle_rpm", idle_rpm, "an idle speed > 0 rpm")
        eng = EngineCurve.from_csv(engine, idle_rpm=idle_rpm) if engine else EngineCurve.default()
        speeds = None
        if rpm is not None:
            from ..solver import parse_rpm

            speeds = check_speeds(parse_rpm(rpm), eng)
        cm, _, _, c, p = load_design(concept, set_, None, mesh_size, "sector", None, None)
        an = run(cm, p, material_from(material, None, None, None), mu=mu, rotation=rotation, engine=eng,
                 requirements=req, design=c.name, rpm=speeds, idle_rpm=idle_rpm)
        if out is not None:
            from ..report import write_analysis

            for f in write_analysis(an, eng, out, c.name):
                err.print(f"wrote {f}")
        if json_:
            print(json.dumps(an.to_json()))
            return
        from ..report import summary_rows

        t = Table(title=f"{c.name}: clutch answers (mu = {an.mu:g}, {rotation})")
        t.add_column("quantity")
        t.add_column("value", justify="right")
        for q, v in summary_rows(an):
            t.add_row(q, v)
        console.print(t)
        for w in an.warnings:
            console.print(f"[bold red]WARNING:[/] {w}")
        for n in an.notes:
            console.print(f"[dim]note: {n}[/]")
    except ClutchfemError as exc:
        fail(exc)
