"""``clutchfem geometry``: build one concept, write its mesh and drawing."""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import List, Optional

import typer
from rich.markup import escape
from rich.table import Table

from ..core import ClutchfemError
from ..core import write as write_json
from .common import check_out_dir, console, fail, length_option, mesh_settings


def geometry(
    concept: Optional[str] = typer.Argument(None, help="concept name (concept1, 4, concept3.1, ...)"),
    set_: List[str] = typer.Option([], "--set", help="parameter override name=value (units: m or mm suffix, deg)"),
    out: Path = typer.Option(Path("out/geometry"), "--out", help="output folder"),
    list_: bool = typer.Option(False, "--list", help="print the concept names, one a line"),
    list_params: bool = typer.Option(False, "--list-params", help="show parameters: name, unit, default, range"),
    mesh_size: Optional[str] = typer.Option(None, "--mesh-size", help="global element size [m] (unit suffix: mm)"),
    model: str = typer.Option("full", "--model", help="sector or full"),
    no_drawing: bool = typer.Option(False, "--no-drawing", help="skip the PNG/SVG drawing"),
):
    """Build one concept: write its .msh mesh (with physical groups) and a labelled drawing."""
    from ..geometry import concepts, get_concept

    try:
        if list_:
            for name in concepts():
                print(name)
            return
        if concept is None:
            fail(ClutchfemError("give a concept name (see --list)"))
        c = get_concept(concept)
        if not list_params:
            check_out_dir(out)
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
        info = build_geometry(c, c.Params.from_assignments(set_), out, length_option("size", mesh_size), model,
                              not no_drawing)
        _geometry_table([info])
    except ClutchfemError as exc:
        fail(exc)


def build_geometry(c, p, out: Path, mesh_size, model: str, drawing: bool) -> dict:
    """Mesh one concept and write its files into ``out``; returns a summary row."""
    import shutil

    from ..mesh import groups_msh_path, mesh_concept

    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    cm = mesh_concept(c, p, mesh_settings(mesh_size, model))
    wall = time.perf_counter() - t0
    stem = out / c.name
    msh = out / f"{c.name}.msh"  # not with_suffix: 'concept3.1' would lose its '.1'
    shutil.copyfile(groups_msh_path(cm.msh_path), msh)
    files = [msh]
    if drawing:
        try:
            from ..geometry import draw_concept
        except ImportError:  # drawing module not available
            draw_concept = None
        if draw_concept is not None:
            files += draw_concept(c, p, stem, cm)
    rho, h = 7850.0, p.thickness
    shoe = cm.mass.get("shoe_0", {})
    info = {"concept": c.name, "elements": cm.n_elements, "nodes": cm.n_nodes,
            "shoe_mass_kg": shoe.get("area", math.nan) * rho * h, "R_Tp_m": shoe.get("radius", math.nan),
            "part_mass_kg": cm.mass["solid"]["area"] * rho * h * (cm.n_shoes_total if cm.sector_angle else 1),
            "mesh_time_s": cm.mesh_time_s, "cached": cm.cached, "wall_time_s": wall,
            "files": [str(f) for f in files]}
    write_json(out / f"{c.name}.json", {**info, "params": p.model_dump(), "mass": cm.mass}, indent=2)
    return info


def _geometry_table(rows: list[dict]) -> None:
    t = Table(title="concept geometries (steel, rho = 7850 kg/m^3)")
    for col in ("concept", "elements", "nodes", "shoe mass [g]", "R_Tp [mm]", "part mass [g]", "mesh time [s]"):
        # escaped: rich would eat '[g]' as markup; names never wrap ('concept3.1')
        t.add_column(escape(col), justify="right", no_wrap=col == "concept", min_width=10 if col == "concept" else None)
    for r in rows:
        if "error" in r:
            t.add_row(r["concept"], "-", "-", "-", "-", "-", f"[red]{r['error'][:60]}[/]")
            continue
        t.add_row(r["concept"], str(r["elements"]), str(r["nodes"]), f"{r['shoe_mass_kg'] * 1e3:.2f}",
                  f"{r['R_Tp_m'] * 1e3:.2f}", f"{r['part_mass_kg'] * 1e3:.1f}",
                  f"{r['mesh_time_s']:.2f}" + ("*" if r.get("cached") else ""))
    if any(r.get("cached") for r in rows):
        t.caption = "* mesh read from the cache; the time is that of its original meshing"
    console.print(t)
