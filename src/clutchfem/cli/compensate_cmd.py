"""``clutchfem compensate``: the shoe profile that spreads the contact pressure evenly at one
speed."""

from __future__ import annotations

from typing import Optional

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError
from . import options as O
from .common import (
    check_out_dir,
    console,
    design_from,
    engine_from,
    err,
    fail,
    operating_point,
    quantity,
    working,
    wrote,
)


@O.takes("concept", "set_", "mesh_size", "mu", "fidelity", "engine", "out", "json_")
def compensate(
    o,
    rpm: str = typer.Option(..., "--rpm", help="speed at which the pressure should be even, e.g. 8000rpm",
                            rich_help_panel="Compensation"),
    target_arc: str = typer.Option("0.8", "--target-arc", help="share of the nominal shoe arc to load evenly",
                                   rich_help_panel="Compensation"),
    arc_start: Optional[str] = typer.Option(None, "--arc-start", help="start of the target arc as a share of the "
                                            "shoe from its root (default: placed for the most even pressure)",
                                            rich_help_panel="Compensation"),
    mean_clearance: Optional[str] = typer.Option(None, "--mean-clearance", help="mean clearance over the target arc, "
                                                 "e.g. 0.5mm (default: the design's own there)",
                                                 rich_help_panel="Compensation"),
    max_iter: int = typer.Option(8, "--max-iter", help="most rebuilds of the fixed point",
                                 rich_help_panel="Compensation"),
):
    """Shoe profile (a table of clearances) that spreads the contact pressure evenly at --rpm."""
    from .. import Design, analyze, dumps, write_report
    from .. import compensate as run

    try:
        check_out_dir(o.out)
        w = quantity("--rpm", rpm, "rpm", above=0.0)
        share = quantity("--target-arc", target_arc, "-")
        start = quantity("--arc-start", arc_start, "-")
        eng, _ = engine_from(o.engine)
        with working(f"compensate {o.concept}") as stage:
            stage("meshing")
            design = design_from(o.concept, o.set_, None, op=operating_point(mu=o.mu, fidelity=o.fidelity), mesh_size=o.mesh_size,
                                 mesh_allowed=False)
        mc = design.params.parse_value("clearance", mean_clearance) if mean_clearance is not None else None
        res = run(design, rpm=w, target_arc=share, arc_start=start, mean_clearance=mc, max_iter=max_iter,
                  log=lambda m: err.print(escape(m)))  # one line per iteration: its own progress
        ms = design.cm.mesh_settings
        with working(f"compensate {o.concept}") as stage:
            stage("analysing the design before and after")
            before = analyze(design, engine=eng, errors=False)
            after = analyze(Design.from_concept(design.concept, res.after, design.op, _mesh(ms, design.op.fidelity)), engine=eng,
                            errors=False)
        rows = res.compare(before, after)
        if o.out is not None:
            wrote(write_report(res, o.out, before=before, after=after, engine=eng))
        if o.json_:
            print(dumps(res.to_json(before, after)))
            return
        t = Table(title=escape(f"{res.concept}: profile compensated at {res.rpm:.0f} rpm over "
                               f"{100 * res.target_arc:.0f} % of the shoe arc"))
        t.add_column("answer")
        t.add_column("before", justify="right")
        t.add_column("after", justify="right")
        for q, x, y in rows:
            t.add_row(escape(q), escape(x), escape(y))
        console.print(t)
        console.print(f"{'converged' if res.converged else 'NOT converged'} in {len(res.steps) - 1} rebuilds, "
                      f"{res.seconds:.0f} s; pressure cv over the target arc {res.steps[-1].measured_cv:.3f}")
        console.print("profile: " + " ".join(f"--set {escape(k)}={escape(v)}" for k, v in res.after_texts.items()),
                      soft_wrap=True)
        for n_ in res.notes:
            console.print(f"[dim]note: {escape(n_)}[/]")
    except ClutchfemError as exc:
        fail(exc)


def _mesh(ms: dict, fidelity: str = "fast"):
    from .. import MeshSettings

    return MeshSettings(**ms) if ms else MeshSettings.preset(fidelity)
