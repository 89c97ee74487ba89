"""``clutchfem reduce``: build (or load) the reduced model of a design's region and print its
measured accuracy."""

from __future__ import annotations

from typing import List, Optional

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError
from . import options as O
from .common import (
    check_cluster,
    console,
    design_from,
    engine_from,
    fail,
    names_from,
    operating_point,
    quantity,
    ranges_from,
    requirements_from,
)


@O.takes("concept", "set_", "mesh_size", "mu", "engine", "a", "b", "workers", "scheduler", "json_")
def reduce(
    o,
    range_: List[str] = typer.Option([], "--range", help="the region's bounds of a parameter, name=LO:HI with units, "
                                     "e.g. flexure_thickness=1.6mm:2.0mm (default: +-span of each free parameter)",
                                     rich_help_panel="Region"),
    span: str = typer.Option("0.05", "--span", help="the region: +- this share of each free parameter's value, "
                             "within its declared range", rich_help_panel="Region"),
    free: Optional[str] = typer.Option(None, "--free", help="comma-separated free parameters (default: the "
                                       "concept's shape parameters)", rich_help_panel="Region"),
    n: Optional[int] = typer.Option(None, "--n", help="training designs (full best path each; default 330, half "
                                    "of them where the first half's fit knows least)",
                                    rich_help_panel="Build"),
    held_out: int = typer.Option(30, "--held-out", help="designs the model's own error is measured on (never "
                                 "fitted to)", rich_help_panel="Build"),
):
    """Build (once, on the study engine; resumable) or load the reduced model of the region
    around a design, and print its accuracy measured on held-out designs: the model that
    --fidelity live answers from."""
    from .. import dumps
    from .. import reduce as run

    try:
        o.scheduler = check_cluster(o.workers, o.scheduler)
        s = quantity("--span", span, "-", above=0.0)
        eng, _ = engine_from(o.engine)
        req = requirements_from(o.a, o.b)
        design = design_from(o.concept, o.set_, None, op=operating_point(mu=o.mu, fidelity="live"),
                             mesh_size=o.mesh_size, mesh_allowed=False)
        ranges = ranges_from(type(design.params), range_)
        names = names_from(free)
        m = run(design, span=s, ranges=ranges or None, free=names, held_out=held_out, engine=eng,
                **({} if n is None else {"n": n}),
                requirements=req, workers=o.workers, scheduler=o.scheduler, progress=True)
        if o.json_:
            print(dumps(m.to_json()))
            return
        _print(m)
    except ClutchfemError as exc:
        fail(exc)


def _print(m) -> None:
    console.print(escape(f"reduced model of {m.region.concept} over {m.region.describe()}"), soft_wrap=True)
    info = m.info
    console.print(f"{info.get('fe_designs')} best-path designs ({info.get('fe_ok')} answered by the FE; "
                  f"{info.get('n_train')} fitted, {info.get('n_adaptive', 0)} of them where the others' fit knew "
                  f"least; {info.get('n_held_out')} held out), built in "
                  f"{info.get('build_s', 0):.0f} s; cached (key {m.region.key()})")
    t = Table(title="its own error, measured on the held-out designs (relative)")
    for c in ("answer", "designs", "95th percentile", "largest", "band holds the FE"):
        t.add_column(c, justify="left" if c == "answer" else "right")
    for a, acc in m.accuracy.items():
        if a == "status":
            continue
        t.add_row(escape(a), str(acc["n"]), f"{100 * acc['p95_rel']:.2f} %", f"{100 * acc['max_rel']:.2f} %",
                  f"{100 * acc.get('within', float('nan')):.0f} %")
    console.print(t)
    s = m.accuracy.get("status")
    if s:
        console.print(f"where the FE answers: {s['fe_answers']} of {s['n']} held-out designs; the reduced model told "
                      f"{100 * s['agree']:.0f} % of them apart")
