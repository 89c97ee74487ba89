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
    mesh: Optional[Path] = typer.Option(None, "--mesh", help="user mesh (.msh with curve groups bore, contact "
                                        "[, contact_0, contact_1, ...]) or STEP; metres, x-y plane, axis at the origin"),
    drum_radius: Optional[float] = typer.Option(None, "--drum-radius", help="drum inner radius [m] (required with --mesh; "
                                                "concepts: use --set drum_radius=...)"),
    thickness: Optional[float] = typer.Option(None, "--thickness", help="axial thickness [m] (--mesh only; default 0.011)"),
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
    from ..errors import InputError, ParameterError

    try:
        if (concept is None) == (mesh is None):
            raise InputError("give exactly one of --concept NAME or --mesh FILE")
        if concept is not None and (drum_radius is not None or thickness is not None):
            raise InputError("--drum-radius and --thickness apply to --mesh only; for a concept use "
                             "--set drum_radius=... / --set thickness=...")
        if mesh is not None:
            if drum_radius is None:
                raise InputError("analyze --mesh needs --drum-radius M: the drum's inner radius in metres "
                                 "(> 0 and larger than the outer radius of the 'contact' curves, e.g. 0.035); "
                                 "without a drum there is no friction torque to analyse")
            if not (math.isfinite(drum_radius) and drum_radius > 0):
                raise ParameterError("--drum-radius", drum_radius, "a radius > 0 m (metres: 0.035 for 35 mm)")
            if thickness is not None and not (math.isfinite(thickness) and thickness > 0):
                raise ParameterError("--thickness", thickness, "a thickness > 0 m (metres: 0.011 for 11 mm)")
        # cheap input checks first, before any meshing
        req = Requirements(a=a, b=b)
        if idle_rpm is not None and not (math.isfinite(idle_rpm) and idle_rpm > 0):
            raise ParameterError("idle_rpm", idle_rpm, "an idle speed > 0 rpm")
        eng = EngineCurve.from_csv(engine, idle_rpm=idle_rpm) if engine else EngineCurve.default()
        speeds = None
        if rpm is not None:
            from ..solver import parse_rpm

            speeds = check_speeds(parse_rpm(rpm), eng)
        mat = material_from(material, None, None, None)
        cm, R, h, c, p = load_design(concept, set_, mesh, mesh_size, "sector", thickness, drum_radius)
        name = c.name if c is not None else mesh.name.rsplit(".", 1)[0]
        if c is not None:
            an = run(cm, p, mat, mu=mu, rotation=rotation, engine=eng,
                     requirements=req, design=name, rpm=speeds, idle_rpm=idle_rpm)
        else:
            if "contact" not in (cm.mesh.boundaries or {}):
                raise InputError(f"{mesh}: analyze needs a physical curve group 'contact' (the shoe surfaces "
                                 f"facing the drum); groups found: {sorted(cm.mesh.boundaries or {})}")
            an = run(cm, None, mat, mu=mu, rotation=rotation, engine=eng, requirements=req, design=name,
                     rpm=speeds, idle_rpm=idle_rpm, drum_radius=R, thickness=h)
        if out is not None:
            from ..report import write_analysis

            for f in write_analysis(an, eng, out, name):
                err.print(f"wrote {f}")
        if json_:
            print(json.dumps(an.to_json()))
            return
        from ..report import summary_rows

        t = Table(title=f"{name}: clutch answers (mu = {an.mu:g}, {rotation})")
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
