"""``clutchfem geometry``: build one concept, write its mesh and drawing (or list concepts
and parameters)."""

from __future__ import annotations

import math
import shutil
import time
from pathlib import Path

import typer
from rich.markup import escape
from rich.table import Table

from ..core import ClutchfemError, format_quantity
from ..core import write as write_json
from . import options as O
from .common import check_out_dir, console, design_from, err, fail, working, wrote


def geometry(
    concept: O.Concept = None,
    set_: O.Set = [],
    mesh_size: O.MeshSize = None,
    model: O.Model = "full",
    out: O.Out = Path("out/geometry"),
    list_: bool = typer.Option(False, "--list", help="print the concept names, one a line"),
    list_params: bool = typer.Option(False, "--list-params", help="show the concept's parameters: name, unit, "
                                     "default, allowed range, meaning"),
    no_drawing: bool = typer.Option(False, "--no-drawing", help="skip the PNG/SVG drawing"),
):
    """Build one concept: write its .msh mesh (with physical groups), a labelled drawing and a
    summary (mass, mesh size)."""
    from ..geometry import broken_concepts, concepts, get_concept

    try:
        if list_:
            for name in concepts():
                print(name)
            for path, error in broken_concepts().items():  # on stderr: stdout stays one name a line
                err.print(escape(f"not loaded: {path}: {error}"), soft_wrap=True)
            return
        if concept is None:
            raise ClutchfemError("give a concept name (see clutchfem geometry --list)")
        c = get_concept(concept)
        if list_params:
            t = Table(title=f"{c.name}: parameters (lengths in mm, stresses in MPa)")
            for col in ("name", "unit", "default", "allowed", "description"):
                t.add_column(col)
            for row in c.Params.describe():
                t.add_row(row["name"], escape(_display_unit(row["unit"])), escape(format_quantity(row["default"],
                                                                                                   row["unit"])),
                          escape(row["allowed"]), escape(row["description"]))
            console.print(t)
            return
        check_out_dir(out)
        info = build_geometry(c, set_, out, mesh_size, model, not no_drawing)
        geometry_table([info])
        wrote(info["files"])
    except ClutchfemError as exc:
        fail(exc)


def _display_unit(unit: str) -> str:
    return {"m": "mm", "Pa": "MPa"}.get(unit, unit)


def build_geometry(c, set_, out: Path, mesh_size, model: str, drawing: bool) -> dict:
    """Mesh one concept (its ``--set`` texts) and write its files into ``out``, named after the
    design's label; returns a summary row with the files."""
    from ..geometry import draw_concept
    from ..loadcase import design_label
    from ..mesh import groups_msh_path

    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    with working(f"geometry {c.name}") as stage:
        stage("building and meshing")
        design = design_from(c.name, list(set_), None, mesh_size=mesh_size, model=model)
    wall = time.perf_counter() - t0
    cm, p = design.cm, design.params
    label = design_label(design)
    msh = out / f"{label}.msh"  # not with_suffix: 'concept3.1' would lose its '.1'
    shutil.copyfile(groups_msh_path(cm.msh_path), msh)
    files = [msh]
    if drawing:
        files += draw_concept(c, p, out / label, cm)
    rho, h = design.op.material.rho, p.thickness
    shoe = cm.mass.get("shoe_0", {})
    info = {"concept": c.name, "label": label, "elements": cm.n_elements, "nodes": cm.n_nodes,
            "material": design.op.material.name, "density_kg_m3": rho,
            "shoe_mass_kg": shoe.get("area", math.nan) * rho * h, "R_Tp_m": shoe.get("radius", math.nan),
            "part_mass_kg": cm.mass["solid"]["area"] * rho * h * (cm.n_shoes_total if cm.sector_angle else 1),
            "mesh_time_s": cm.mesh_time_s, "cached": cm.cached, "wall_time_s": wall}
    summary = out / f"{label}.json"
    files.append(summary)
    info["files"] = [str(f) for f in files]
    write_json(summary, {**info, "params": p.model_dump(), "mass": cm.mass}, indent=2)
    return info


def geometry_table(rows: list[dict]) -> None:
    """The summary table of built concepts (an error row says why a concept failed)."""
    t = Table(title="concept geometries (51CrV4 steel, rho = 7850 kg/m^3)")
    for col in ("concept", "elements", "nodes", "shoe mass [g]", "R_Tp [mm]", "part mass [g]", "mesh time [s]"):
        # escaped: rich would eat '[g]' as markup; names never wrap ('concept3.1')
        t.add_column(escape(col), justify="right", no_wrap=col == "concept", min_width=10 if col == "concept" else None)
    for r in rows:
        if "error" in r:
            t.add_row(r["concept"], "-", "-", "-", "-", "-", f"[red]{escape(r['error'][:60])}[/]")
            continue
        t.add_row(r["concept"], str(r["elements"]), str(r["nodes"]), f"{r['shoe_mass_kg'] * 1e3:.2f}",
                  f"{r['R_Tp_m'] * 1e3:.2f}", f"{r['part_mass_kg'] * 1e3:.1f}",
                  f"{r['mesh_time_s']:.2f}" + ("*" if r.get("cached") else ""))
    if any(r.get("cached") for r in rows):
        t.caption = "* mesh read from the cache; the time is that of its original meshing"
    console.print(t)
