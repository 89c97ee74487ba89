"""``clutchfem demo``: every concept at its defaults, then the default designs' answers and
the torque-speed comparison against today's spring clutch."""

from __future__ import annotations

from pathlib import Path

import typer

from ..core import ClutchfemError
from ..core import write as write_json
from .common import check_out_dir, fail, working, wrote
from .geometry_cmd import build_geometry, geometry_table


def demo(out: Path = typer.Option(Path("out/demo"), "--out", help="output folder")):
    """Build every concept at its defaults, then analyse the default designs of concepts 1 and
    4 and plot torque vs rpm against the engine and today's spring clutch."""
    from ..geometry import concepts
    from ..report import default_design_report

    try:
        check_out_dir(out)
    except ClutchfemError as exc:
        fail(exc)
    rows = []
    for name, c in concepts().items():
        try:
            rows.append(build_geometry(c, [], out / "geometry", None, "full", True))
        except ClutchfemError as exc:  # record and go on
            rows.append({"concept": name, "error": str(exc)})
    geometry_table(rows)
    summary = write_json(out / "geometry" / "summary.json", rows, indent=2)
    wrote([f for r in rows for f in r.get("files", [])] + [summary])
    try:
        with working("demo: the design report of concepts 1-4") as stage:
            stage("analyses, charts and pictures")
            files = default_design_report(out / "design")
        wrote(files)
    except ClutchfemError as exc:
        fail(exc)
