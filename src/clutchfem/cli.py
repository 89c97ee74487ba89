"""Command line: a thin layer over the Python API (parse, call, print)."""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path
from typing import List, Optional

import typer
from rich.console import Console
from rich.table import Table

from .errors import ClutchfemError

app = typer.Typer(add_completion=False, no_args_is_help=True,
                  help="clutchfem: design one-piece compliant centrifugal clutches (FEM + plus/minus shoe model).")
console = Console()
err = Console(stderr=True)


def _fail(exc: Exception) -> None:
    err.print(f"[bold red]error:[/] {exc}")
    raise typer.Exit(code=2)


def _mesh_settings(size: Optional[float], model: str):
    from .geometry import MeshSettings

    kw = {"model": model}
    if size is not None:
        kw["size"] = size
    return MeshSettings(**kw)


@app.command()
def geometry(
    concept: Optional[str] = typer.Argument(None, help="concept name (concept1, 4, concept3.1, ...)"),
    set_: List[str] = typer.Option([], "--set", help="parameter override name=value (units: m or mm suffix, deg)"),
    out: Path = typer.Option(Path("out/geometry"), "--out", help="output folder"),
    list_: bool = typer.Option(False, "--list", help="print the concept names, one a line"),
    list_params: bool = typer.Option(False, "--list-params", help="show parameters: name, unit, default, range"),
    mesh_size: Optional[float] = typer.Option(None, "--mesh-size", help="global element size [m]"),
    model: str = typer.Option("full", "--model", help="sector or full"),
    no_drawing: bool = typer.Option(False, "--no-drawing", help="skip the PNG/SVG drawing"),
):
    """Build one concept: write its .msh mesh (with physical groups) and a labelled drawing."""
    from .geometry import concepts, get_concept

    try:
        if list_:
            for name in concepts():
                print(name)
            return
        if concept is None:
            _fail(ClutchfemError("give a concept name (see --list)"))
        c = get_concept(concept)
        if list_params:
            t = Table(title=f"{c.name}: parameters")
            for col in ("name", "unit", "default", "allowed", "description"):
                t.add_column(col)
            for row in c.Params.describe():
                d = row["default"]
                t.add_row(row["name"], row["unit"], f"{d:g}" if isinstance(d, (int, float)) else str(d),
                          row["allowed"], row["description"])
            console.print(t)
            return
        info = build_geometry(c, c.Params.from_assignments(set_), out, mesh_size, model, not no_drawing)
        _geometry_table([info])
    except ClutchfemError as exc:
        _fail(exc)


def build_geometry(c, p, out: Path, mesh_size, model: str, drawing: bool) -> dict:
    """Mesh one concept and write its files into ``out``; returns a summary row."""
    import shutil

    from .mesh import groups_msh_path, mesh_concept

    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    cm = mesh_concept(c, p, _mesh_settings(mesh_size, model))
    wall = time.perf_counter() - t0
    stem = out / c.name
    msh = out / f"{c.name}.msh"  # not with_suffix: 'concept3.1' would lose its '.1'
    shutil.copyfile(groups_msh_path(cm.msh_path), msh)
    files = [msh]
    if drawing:
        try:
            from .geometry.drawing import draw_concept
        except ImportError:  # drawing module not available
            draw_concept = None
        if draw_concept is not None:
            files += draw_concept(c, p, stem, cm)
    rho, h = 7850.0, p.thickness
    shoe = cm.mass.get("shoe_0", {})
    info = {"concept": c.name, "elements": cm.n_elements, "nodes": cm.n_nodes,
            "shoe_mass_kg": shoe.get("area", math.nan) * rho * h, "R_Tp_m": shoe.get("radius", math.nan),
            "part_mass_kg": cm.mass["solid"]["area"] * rho * h * (cm.n_shoes_total if cm.sector_angle else 1),
            "mesh_time_s": cm.mesh_time_s if not cm.cached else wall, "cached": cm.cached,
            "files": [str(f) for f in files]}
    (out / f"{c.name}.json").write_text(json.dumps({**info, "params": p.model_dump(), "mass": cm.mass}, indent=2))
    return info


def _geometry_table(rows: list[dict]) -> None:
    t = Table(title="concept geometries (steel, rho = 7850 kg/m^3)")
    for col in ("concept", "elements", "nodes", "shoe mass [g]", "R_Tp [mm]", "part mass [g]", "mesh time [s]"):
        t.add_column(col, justify="right")
    for r in rows:
        if "error" in r:
            t.add_row(r["concept"], "-", "-", "-", "-", "-", f"[red]{r['error'][:60]}[/]")
            continue
        t.add_row(r["concept"], str(r["elements"]), str(r["nodes"]), f"{r['shoe_mass_kg'] * 1e3:.2f}",
                  f"{r['R_Tp_m'] * 1e3:.2f}", f"{r['part_mass_kg'] * 1e3:.1f}",
                  f"{r['mesh_time_s']:.2f}" + (" (cached)" if r.get("cached") else ""))
    console.print(t)


def _material(material: Optional[str], E, nu, rho):
    from .materials import Material, get_material

    if E is not None or nu is not None or rho is not None:
        base = get_material(material) if material else get_material("51CrV4")
        return Material(name="user", E=E if E is not None else base.E, nu=nu if nu is not None else base.nu,
                        rho=rho if rho is not None else base.rho, yield_strength=base.yield_strength)
    return get_material(material or "51CrV4")


def _load_design(concept, set_, mesh, mesh_size, model, thickness, drum_radius):
    from .geometry import get_concept
    from .mesh import load_user_geometry, mesh_concept

    if (concept is None) == (mesh is None):
        raise ClutchfemError("give exactly one of --concept NAME or --mesh FILE")
    if concept is not None:
        c = get_concept(concept)
        p = c.Params.from_assignments(set_)
        cm = mesh_concept(c, p, _mesh_settings(mesh_size, model))
        return cm, (drum_radius if drum_radius is not None else p.drum_radius), (thickness or p.thickness), c, p
    if set_:
        raise ClutchfemError("--set applies to --concept designs only")
    if thickness is None:
        thickness = 11e-3
    cm = load_user_geometry(mesh, mesh_size=mesh_size, thickness=thickness, drum_radius=drum_radius)
    return cm, drum_radius, thickness, None, None


@app.command()
def solve(
    concept: Optional[str] = typer.Option(None, "--concept", help="concept name"),
    set_: List[str] = typer.Option([], "--set", help="concept parameter override name=value"),
    mesh: Optional[Path] = typer.Option(None, "--mesh", help="user mesh (.msh with groups bore/contact) or STEP"),
    drum_radius: Optional[float] = typer.Option(None, "--drum-radius", help="drum inner radius [m]"),
    mu: float = typer.Option(0.165, "--mu", help="shoe-drum friction coefficient [-]"),
    rotation: str = typer.Option("ccw", "--rotation", help="hub rotation: ccw or cw"),
    material: Optional[str] = typer.Option(None, "--material", help="51CrV4, titanium, aluminium"),
    E: Optional[float] = typer.Option(None, "--E", help="Young's modulus [Pa]"),
    nu: Optional[float] = typer.Option(None, "--nu", help="Poisson's ratio [-]"),
    rho: Optional[float] = typer.Option(None, "--rho", help="density [kg/m^3]"),
    thickness: Optional[float] = typer.Option(None, "--thickness", help="axial thickness [m] (user mesh default 0.011)"),
    rpm: str = typer.Option("0:14000:250", "--rpm", help="speeds: 8000 | 1000,2000 | start:stop:step [rpm]"),
    vtk: bool = typer.Option(False, "--vtk", help="write .vtu fields (and PNG renders) for the speeds in --vtk-rpm"),
    vtk_rpm: Optional[str] = typer.Option(None, "--vtk-rpm", help="speeds for VTK output (default: max of --rpm)"),
    out: Optional[Path] = typer.Option(None, "--out", help="output folder for tables/fields"),
    json_: bool = typer.Option(False, "--json", help="print one JSON object to stdout"),
    mesh_size: Optional[float] = typer.Option(None, "--mesh-size", help="global element size [m]"),
    model: str = typer.Option("sector", "--model", help="sector (cyclic) or full"),
    softening: str = typer.Option("modal", "--spin-softening", help="modal | exact | off"),
    no_stress: bool = typer.Option(False, "--no-stress", help="skip stress recovery"),
):
    """Speed sweep: engagement, contact forces and arc, friction torque (drum held), stresses."""
    from .materials import Material  # noqa: F401
    from .solver import ClutchSolver, parse_rpm

    try:
        mat = _material(material, E, nu, rho)
        speeds = parse_rpm(rpm)
        cm, R, h, c, p = _load_design(concept, set_, mesh, mesh_size, model, thickness, drum_radius)
        solver = ClutchSolver(cm, mat, drum_radius=R, mu=mu, rotation=rotation,
                              spin_softening=softening, thickness=h)
        res = solver.sweep(speeds, stresses=not no_stress)
        if out is not None:
            out.mkdir(parents=True, exist_ok=True)
            res.curve.to_csv(out / "curve.csv", index=False)
            if not res.shoes.empty:
                res.shoes.to_csv(out / "shoes.csv", index=False)
            (out / "result.json").write_text(json.dumps(res.to_json(), indent=2))
        if vtk:
            from .output import write_vtk

            target = out or Path("out/solve")
            which = parse_rpm(vtk_rpm) if vtk_rpm else [float(speeds.max())]
            files = write_vtk(solver, which, target)
            if not json_:
                for f in files:
                    console.print(f"wrote {f}")
        if json_:
            print(json.dumps(res.to_json()))
        else:
            _print_sweep(res, mat)
    except ClutchfemError as exc:
        _fail(exc)


def _print_sweep(res, mat) -> None:
    eng = res.engagement_rpm
    console.print(f"engagement speed: {eng:.0f} rpm (first touch at the shoe {res.first_touch})" if eng
                  else "engagement speed: none in the speed range (never touches the drum)")
    t = Table(title=f"speed sweep ({mat.name})")
    for col in ("rpm", "normal force [N]", "torque [N m]", "contact arc [deg]", "max von Mises [MPa]",
                "safety factor", "max displ. [mm]"):
        t.add_column(col, justify="right")
    df = res.curve
    step = max(1, len(df) // 15)
    for _, r in df.iloc[::step].iterrows():
        t.add_row(f"{r.rpm:.0f}", f"{r.normal_force_N:.1f}", f"{r.torque_Nm:.3f}", f"{r.contact_arc_deg:.1f}",
                  f"{r.max_von_mises_Pa / 1e6:.0f}" if not math.isnan(r.max_von_mises_Pa) else "-",
                  f"{r.safety_factor:.2f}" if not math.isnan(r.safety_factor) else "-",
                  f"{r.max_displacement_m * 1e3:.3f}")
    console.print(t)
    console.print(f"wall time: setup {res.timings['setup_s']:.2f} s, sweep {res.timings['sweep_s']:.2f} s")


@app.command()
def analyze(
    concept: Optional[str] = typer.Option(None, "--concept", help="concept name"),
    set_: List[str] = typer.Option([], "--set", help="concept parameter override name=value"),
    mesh: Optional[Path] = typer.Option(None, "--mesh", help="(not yet: analyze needs concept mass properties)"),
    engine: Optional[Path] = typer.Option(None, "--engine", help="engine torque CSV (rpm, torque N m)"),
    mu: float = typer.Option(0.165, "--mu", help="friction coefficient [-]"),
    rotation: str = typer.Option("ccw", "--rotation", help="ccw or cw"),
    a: float = typer.Option(1.3, "--a", help="requirement: engagement > a x idle rpm (ASSUMED default)"),
    b: float = typer.Option(1.0, "--b", help="requirement: slip < b x rpm of max torque (ASSUMED default)"),
    material: Optional[str] = typer.Option(None, "--material", help="51CrV4, titanium, aluminium"),
    json_: bool = typer.Option(False, "--json", help="print the JSON document"),
    out: Optional[Path] = typer.Option(None, "--out", help="folder for plots and tables"),
    mesh_size: Optional[float] = typer.Option(None, "--mesh-size", help="global element size [m]"),
):
    """Engagement (static, with ripple), slip rpm, torque margin, stress, plus/minus character."""
    from .clutch.analyze import Requirements, analyze as run
    from .clutch.engine import EngineCurve
    from .geometry import get_concept
    from .mesh import mesh_concept

    try:
        if mesh is not None or concept is None:
            raise ClutchfemError("analyze needs --concept NAME (user meshes carry no shoe mass properties yet; "
                                 "use 'clutchfem solve --mesh' for their FE curves)")
        c = get_concept(concept)
        p = c.Params.from_assignments(set_)
        cm = mesh_concept(c, p, _mesh_settings(mesh_size, "sector"))
        eng = EngineCurve.from_csv(engine) if engine else EngineCurve.default()
        an = run(cm, p, _material(material, None, None, None), mu=mu, rotation=rotation, engine=eng,
                 requirements=Requirements(a=a, b=b), design=c.name)
        if out is not None:
            from .report import arc_stress_plot, torque_plot

            out.mkdir(parents=True, exist_ok=True)
            torque_plot(an, eng, out / f"{c.name}_torque_rpm.png", f"{c.name}: torque vs engine speed")
            an.curves.to_csv(out / f"{c.name}_curves.csv", index=False)
            (out / f"{c.name}_analysis.json").write_text(json.dumps(an.to_json(), indent=2))
        if json_:
            print(json.dumps(an.to_json()))
            return
        t = Table(title=f"{c.name}: clutch answers")
        t.add_column("quantity")
        t.add_column("value", justify="right")
        fmt = lambda v, f, u: "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:{f}} {u}"
        t.add_row("engagement speed (static)", fmt(an.engagement_rpm, ".0f", "rpm"))
        t.add_row("engagement speed (with 2-stroke ripple, 3 sigma)", fmt(an.engagement_rpm_with_ripple, ".0f", "rpm"))
        t.add_row("slip speed (drum held, full throttle)", fmt(an.slip_rpm, ".0f", "rpm") + f"  ({an.slip_note})")
        t.add_row("torque at rpm of max engine torque", fmt(an.torque_at_max_engine_torque_Nm, ".2f", "N m"))
        t.add_row("torque margin over max engine torque", fmt(an.torque_margin_Nm, ".2f", "N m"))
        t.add_row(f"max von Mises at {an.max_stress_rpm:.0f} rpm", fmt(an.max_von_mises_Pa / 1e6, ".0f", "MPa"))
        t.add_row("safety factor against yield", fmt(an.safety_factor, ".2f", ""))
        t.add_row("slip power (heat) at slip speed", fmt(an.slip_power_W, ".0f", "W"))
        t.add_row("shoe character (FE, friction on vs off)", an.shoe_character)
        t.add_row("first contact on the shoe", str(an.first_touch))
        t.add_row("engagement > a x idle", str(an.requirements["engagement_ok"]))
        t.add_row("slip < b x rpm(max torque)", str(an.requirements["slip_ok"]))
        console.print(t)
    except ClutchfemError as exc:
        _fail(exc)


@app.command()
def validate(
    json_: bool = typer.Option(False, "--json", help="print a JSON list of records"),
    out: Path = typer.Option(Path("out/validation"), "--out", help="folder for figures"),
    docs: Optional[Path] = typer.Option(None, "--docs", help="write the Markdown report here (e.g. docs/validation.md)"),
):
    """Reproduce the source papers' numbers (spring clutch, chain impact, shaft whirl, thesis)."""
    from .validation import runner

    try:
        records = runner.run_all()
        if docs is not None:
            runner.write_report(out, docs)
        if json_:
            print(json.dumps([r.to_json() for r in records]))
        else:
            console.print(runner.rich_table(records))
    except ClutchfemError as exc:
        _fail(exc)


@app.command()
def demo(out: Path = typer.Option(Path("out/demo"), "--out", help="output folder")):
    """Build every concept at its defaults, then sweep the default design and plot torque vs rpm."""
    from .geometry import concepts

    rows = []
    for name, c in concepts().items():
        try:
            rows.append(build_geometry(c, c.params(), out / "geometry", None, "full", True))
        except ClutchfemError as exc:  # record and go on
            rows.append({"concept": name, "error": str(exc)})
    _geometry_table(rows)
    (out / "geometry" / "summary.json").write_text(json.dumps(rows, indent=2, default=str))
    from .report import default_design_report

    try:
        files = default_design_report(out / "design")
        for f in files:
            console.print(f"wrote {f}")
    except ClutchfemError as exc:
        _fail(exc)


def main() -> None:  # pragma: no cover
    app()


if __name__ == "__main__":  # pragma: no cover
    main()
