"""``clutchfem demo``: every concept at its defaults, then the default design's report."""

from __future__ import annotations

import json
from pathlib import Path

import typer

from ..errors import ClutchfemError
from .common import console, fail
from .geometry_cmd import _geometry_table, build_geometry


def demo(out: Path = typer.Option(Path("out/demo"), "--out", help="output folder")):
    """Build every concept at its defaults, then sweep the default design and plot torque vs rpm."""
    from ..geometry import concepts

    rows = []
    for name, c in concepts().items():
        try:
            rows.append(build_geometry(c, c.params(), out / "geometry", None, "full", True))
        except ClutchfemError as exc:  # record and go on
            rows.append({"concept": name, "error": str(exc)})
    _geometry_table(rows)
    (out / "geometry" / "summary.json").write_text(json.dumps(rows, indent=2, default=str))
    from ..report import default_design_report

    try:
        files = default_design_report(out / "design")
        for f in files:
            console.print(f"wrote {f}")
    except ClutchfemError as exc:
        fail(exc)
