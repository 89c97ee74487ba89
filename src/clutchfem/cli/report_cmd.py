"""``clutchfem report``: the one-page report of a design, or of a run folder again."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from .. import ClutchfemError, InputError
from . import options as O
from .common import check_out_dir, design_from, engine_from, fail, requirements_from, working, wrote


@O.takes("concept", "set_", "mesh", "mesh_size", "drum_radius", "thickness", "fidelity", "engine", "a", "b", "out")
def report(
    o,
    run_dir: Optional[Path] = typer.Option(None, "--run", help="render a run folder (optimize / tolerance / "
                                           "compensate / any folder of CSV and PNG) again", rich_help_panel=O.DESIGN),
    errors: bool = typer.Option(True, "--errors/--no-errors", help="estimate the error of the main answers (a mesh "
                                "twice as fine: ~3x the time)", rich_help_panel=O.MODEL),
):
    """One-page report (self-contained HTML + Markdown) of a design (CONCEPT or --mesh) or of a
    run folder (--run)."""
    from .. import write_report
    from .common import operating_point

    try:
        if run_dir is not None:
            if o.concept is not None or o.mesh is not None:
                raise InputError("give exactly one of a design (CONCEPT or --mesh FILE) or --run DIR")
            if not Path(run_dir).is_dir():
                raise InputError(f"--run {run_dir}: not a folder")
            wrote(write_report(Path(run_dir), check_out_dir(o.out) or Path(run_dir)))
            return
        if o.out is None:
            raise InputError("--out DIR is required: the folder for report.html, report.md, the images and inputs.json")
        check_out_dir(o.out)
        if o.mesh is not None and o.drum_radius is None:
            raise InputError("report --mesh needs --drum-radius (the drum's inner radius, e.g. 35mm)")
        eng, _ = engine_from(o.engine)
        req = requirements_from(o.a, o.b)
        with working(f"report {o.concept or o.mesh}") as stage:
            stage("meshing")
            design = design_from(o.concept, o.set_, o.mesh, op=operating_point(fidelity=o.fidelity),
                                 mesh_size=o.mesh_size, drum_radius=o.drum_radius, thickness=o.thickness)
            stage("analysis, charts and pictures")
            files = write_report(design, o.out, engine=eng, requirements=req, errors=errors)
        wrote(files)
    except ClutchfemError as exc:
        fail(exc)
