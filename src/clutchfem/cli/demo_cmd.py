"""``clutchfem demo``: every concept at its defaults, then the default designs' answers and
the torque-speed comparison against today's spring clutch."""

from __future__ import annotations

from pathlib import Path

import typer

from .. import ClutchfemError
from .common import build_geometry, check_out_dir, fail, geometry_table, working, wrote


def demo(out: Path = typer.Option(Path("out/demo"), "--out", help="output folder")):
    """Build every concept at its defaults, then analyse the default designs of concepts 1 and
    4 and plot torque vs rpm against the engine and today's spring clutch."""
    from .. import concepts, default_design_report, dumps

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
    summary = out / "geometry" / "summary.json"
    summary.write_text(dumps(rows, indent=2))
    wrote([f for r in rows for f in r.get("files", [])] + [summary])
    try:
        with working("demo: the design report of concepts 1-4") as stage:
            stage("analyses, charts and pictures")
            files = default_design_report(out / "design")
        wrote(files)
    except ClutchfemError as exc:
        fail(exc)
