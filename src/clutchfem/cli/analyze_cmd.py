"""``clutchfem analyze``: the clutch designer's answers for one design."""

from __future__ import annotations

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
    load_design,
    material_from,
    operating_point,
)


def fatigue_groups() -> dict:
    """The parameter sets --fatigue writes into: service loads and fatigue strength."""
    from ..durability import FatigueLoads, FatigueParams

    return {"loads": FatigueLoads, "strength": FatigueParams}


def _print_settings(groups, option: str) -> None:
    t = Table(title=f"{option} settings (name=value; ASSUMED defaults, sources in the docs)")
    for col in ("name", "unit", "default", "allowed: meaning"):
        t.add_column(col)
    for row in describe_groups(groups):
        t.add_row(*(escape(x) for x in row))
    console.print(t)


def analyze(
    concept: Optional[str] = typer.Option(None, "--concept", help="concept name"),
    set_: List[str] = typer.Option([], "--set", help="concept parameter override name=value (unit suffix: mm, deg)"),
    mesh: Optional[Path] = typer.Option(None, "--mesh", help="user mesh (.msh with curve groups bore, contact "
                                        "[, contact_0, contact_1, ...]) or STEP; metres, x-y plane, axis at the origin"),
    drum_radius: Optional[str] = typer.Option(None, "--drum-radius", help=_OP.help("drum_radius")
                                              + "; required with --mesh; concepts: --set drum_radius=..."),
    thickness: Optional[str] = typer.Option(None, "--thickness", help=_OP.help("thickness") + "; --mesh only"),
    engine: Optional[Path] = typer.Option(None, "--engine", help="engine torque CSV (columns rpm, torque [N m])"),
    idle_rpm: Optional[float] = typer.Option(None, "--idle-rpm", help="engine idle speed [rpm] (default: 2700, ASSUMED)"),
    mu: Optional[str] = typer.Option(None, "--mu", help=_OP.help("mu")),
    rotation: Optional[str] = typer.Option(None, "--rotation", help=_OP.help("rotation")),
    a: float = typer.Option(1.3, "--a", help="requirement: engagement > a x idle rpm [-] (ASSUMED default)"),
    b: float = typer.Option(1.0, "--b", help="requirement: slip < b x rpm of max torque [-] (ASSUMED default)"),
    rpm: Optional[str] = typer.Option(None, "--rpm", help="speeds [rpm] to tabulate, e.g. 0:14000:125 (default: "
                                      "0..engine max, 125 rpm steps); the answers do not depend on them"),
    material: Optional[str] = typer.Option(None, "--material", help=_OP.help("material")),
    softening: Optional[str] = typer.Option(None, "--spin-softening", help=_OP.help("softening")),
    formulation: Optional[str] = typer.Option(None, "--formulation", help=_OP.help("formulation")),
    layers: Optional[str] = typer.Option(None, "--layers", help=_OP.help("layers")),
    drum_wall: Optional[str] = typer.Option(None, "--drum-wall", help=_OP.help("drum_wall")),
    drum_state: Optional[str] = typer.Option(None, "--drum-state", help=_OP.help("drum_state")),
    json_: bool = typer.Option(False, "--json", help="print the JSON document"),
    out: Optional[Path] = typer.Option(None, "--out", help="folder for plots and tables"),
    mesh_size: Optional[str] = typer.Option(None, "--mesh-size", help="global element size [m] (unit suffix: mm)"),
    fatigue: List[str] = typer.Option([], "--fatigue", help="fatigue setting name=value (service loads: start_stops, "
                                      "revolutions, operating_rpm, cutting_torque, drive_inertia, max_rpm, samples; "
                                      "strength: ultimate_strength, edge_finish, reliability, ...); --list-fatigue "
                                      "lists them with units and defaults (all ASSUMED)"),
    list_fatigue: bool = typer.Option(False, "--list-fatigue", help="list the --fatigue settings and exit"),
):
    """Engagement (static, with ripple), slip rpm, torque margin, stress, plus/minus character."""
    from ..analysis import Requirements, check_speeds
    from ..analysis import analyze as run
    from ..clutch import EngineCurve
    from ..core import InputError, ParameterError

    try:
        if list_fatigue:
            _print_settings(fatigue_groups(), "--fatigue")
            return
        check_out_dir(out)
        groups = fatigue_groups()
        fat = grouped_assignments(fatigue, groups, "--fatigue")
        fat_loads = build_params(groups["loads"], fat["loads"], "--fatigue")
        fat_params = build_params(groups["strength"], fat["strength"], "--fatigue") if fat["strength"] else None
        if (concept is None) == (mesh is None):
            raise InputError("give exactly one of --concept NAME or --mesh FILE")
        if concept is not None and (drum_radius is not None or thickness is not None):
            raise InputError("--drum-radius and --thickness apply to --mesh only; for a concept use "
                             "--set drum_radius=... / --set thickness=...")
        if mesh is not None and drum_radius is None:
            raise InputError("analyze --mesh needs --drum-radius: the drum's inner radius (e.g. 0.035 or 35mm), "
                             "larger than the outer radius of the 'contact' curves; without a drum there is no "
                             "friction torque to analyse")
        # cheap input checks first, before any meshing
        req = Requirements(a=a, b=b)
        if idle_rpm is not None and not (idle_rpm > 0 and idle_rpm < 1e6):
            raise ParameterError("idle_rpm", idle_rpm, "an idle speed > 0 rpm")
        eng = EngineCurve.from_csv(engine, idle_rpm=idle_rpm) if engine else EngineCurve.default()
        lo_, hi_ = eng.rpm_range
        for nm in ("operating_rpm", "max_rpm"):
            v = getattr(fat_loads, nm)
            if v is not None and not lo_ <= v <= hi_:
                raise ParameterError(nm, v, f"a speed within the engine curve's range {lo_:g}..{hi_:g} rpm",
                                     "option --fatigue (fatigue loads)")
        mat = material_from(material, None, None, None)
        op = operating_point(mat, drum_radius=drum_radius, mu=mu, rotation=rotation, thickness=thickness,
                             softening=softening, formulation=formulation, rpm=rpm,
                             layers=layers, drum_wall=drum_wall, drum_state=drum_state)
        if op.rpm is not None:
            check_speeds(op.speeds(), eng)
        size = length_option("size", mesh_size)
        design, c, p = load_design(concept, set_, mesh, size, "sector", op)
        if c is None and "contact" not in (design.cm.mesh.boundaries or {}):
            raise InputError(f"{mesh}: analyze needs a physical curve group 'contact' (the shoe surfaces "
                             f"facing the drum); groups found: {sorted(design.cm.mesh.boundaries or {})}")
        an = run(design, engine=eng, requirements=req, idle_rpm=idle_rpm, fatigue_loads=fat_loads,
                 fatigue_params=fat_params)
        name = design.name
        if out is not None:
            from ..report import write_analysis

            for f in write_analysis(an, eng, out, an.label):
                err.print(f"wrote {escape(str(f))}")
        if json_:
            from ..core import dumps

            print(dumps(an.to_json()))
            return
        from ..report import summary_rows

        t = Table(title=escape(f"{name}: clutch answers (mu = {an.mu:g}, {op.rotation})"))
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
