"""``clutchfem demo``: every concept at its defaults, then the default design's report."""

from __future__ import annotations

from pathlib import Path

import typer

from ..core import ClutchfemError
from ..core import write as write_json
from .common import check_out_dir, console, fail
from .geometry_cmd import _geometry_table, build_geometry


def demo(out: Path = typer.Option(Path("out/demo"), "--out", help="output folder")):
    """Build every concept at its defaults, then sweep the default design and plot torque vs rpm."""
    from ..geometry import concepts

    try:
        check_out_dir(out)
    except ClutchfemError as exc:
        fail(exc)
    rows = []
    for name, c in concepts().items():
        try:
            rows.append(build_geometry(c, c.params(), out / "geometry", None, "full", True))
        except ClutchfemError as exc:  # record and go on
            rows.append({"concept": name, "error": str(exc)})
    _geometry_table(rows)
    write_json(out / "geometry" / "summary.json", rows, indent=2)
    from ..report import default_design_report

    try:
        files = default_design_report(out / "design")
        for f in files:
            console.print(f"wrote {f}")
    except ClutchfemError as exc:
        fail(exc)
