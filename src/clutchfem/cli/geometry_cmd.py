"""``clutchfem geometry``: build one concept, write its mesh and drawing (or list concepts
and parameters)."""

from __future__ import annotations

from pathlib import Path

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError, format_quantity
from . import options as O
from .common import build_geometry, check_out_dir, console, err, fail, geometry_table, wrote


@O.takes("concept", "set_", "mesh_size", "model", "out")
def geometry(
    o,
    list_: bool = typer.Option(False, "--list", help="print the concept names, one a line"),
    list_params: bool = typer.Option(False, "--list-params", help="show the concept's parameters: name, unit, "
                                     "default, allowed range, meaning"),
    no_drawing: bool = typer.Option(False, "--no-drawing", help="skip the PNG/SVG drawing"),
):
    """Build one concept: write its .msh mesh (with physical groups), a labelled drawing and a
    summary (mass, mesh size)."""
    from .. import broken_concepts, concepts, get_concept

    try:
        if list_:
            for name in concepts():
                print(name)
            for path, error in broken_concepts().items():  # on stderr: stdout stays one name a line
                err.print(escape(f"not loaded: {path}: {error}"), soft_wrap=True)
            return
        if o.concept is None:
            raise ClutchfemError("give a concept name (see clutchfem geometry --list)")
        c = get_concept(o.concept)
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
        out = o.out if o.out is not None else Path("out/geometry")  # (the documented default)
        check_out_dir(out)
        info = build_geometry(c, o.set_, out, o.mesh_size, o.model, not no_drawing)
        geometry_table([info])
        wrote(info["files"])
    except ClutchfemError as exc:
        fail(exc)


def _display_unit(unit: str) -> str:
    return {"m": "mm", "Pa": "MPa"}.get(unit, unit)
