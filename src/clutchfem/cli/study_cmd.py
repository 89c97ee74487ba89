"""``clutchfem study`` and ``clutchfem guidelines``: parametric studies on the study engine
(:mod:`clutchfem.study`).  Parse, call, print."""

from __future__ import annotations

import contextlib
import signal
import sys
import threading
from pathlib import Path
from typing import Optional

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError, ParameterError
from . import options as O
from .common import (
    check_cluster,
    check_out_dir,
    console,
    design_from,
    engine_from,
    err,
    fail,
    material_from,
    operating_point,
    wrote,
)


@contextlib.contextmanager
def _ctrl_c_as_keyboard_interrupt():
    """During a study, Ctrl-C raises KeyboardInterrupt (the CLI's own handler exits at once
    with "unfinished work is not written"): the runner then cancels the pending points,
    shuts its cluster down and says how many finished points are stored."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)




@O.takes("workers", "scheduler")
def study(
    o,
    spec: Optional[Path] = typer.Argument(None, help="study spec (TOML); see --example"),
    example: bool = typer.Option(False, "--example", help="print a commented example spec (12 designs of "
                                 "concept 4) that runs as it is, and exit"),
    out: Optional[Path] = typer.Option(None, "--out", help="output folder: results.sqlite (the store), results.csv, "
                                       "charts/, summary.json (default: ./<spec name>-study)",
                                       rich_help_panel=O.OUTPUT),
    retry_failed: bool = typer.Option(False, "--retry-failed", help="recompute the points stored as failed "
                                      "(finished points are otherwise skipped)"),
    charts: bool = typer.Option(True, "--charts/--no-charts", help="draw the charts at the end"),
    json_: bool = typer.Option(False, "--json", help="print one JSON summary object at the end (points, done, ok, "
                               "refused, failed, store, ...)"),
):
    """Parameter study: every point of SPEC through the full analysis, on Dask, stored as it
    finishes (rerun to resume).  Status per point: ok, refused (input refused, with its
    message) or failed (no answer: solver refusal, error, crashed worker)."""
    from .. import finished_summary

    try:
        if example:
            if spec is not None:
                raise _usage("--example prints a spec; give either --example or SPEC")
            from .. import example_study

            sys.stdout.write(example_study())
            return
        if spec is None:
            raise _usage("give a study spec (TOML), or --example to print one")
        o.scheduler = check_cluster(o.workers, o.scheduler)
        out = check_out_dir(out if out is not None else Path(f"{Path(spec).stem}-study"))
        # a finished study: its summary, without loading the FE stack (studies.rerun)
        done = finished_summary(spec, out, retry_failed=retry_failed, charts=charts)
        if done is not None:
            if json_:
                from .. import dumps

                print(dumps(done))
            else:
                _print_summary(done)
            return
        from .. import StudyInterrupted, draw_study_charts, load_study, run_study

        sp = load_study(spec)
        try:
            with _ctrl_c_as_keyboard_interrupt():
                res = run_study(sp, out, workers=o.workers, scheduler=o.scheduler, retry_failed=retry_failed,
                                progress=True)
            if charts:
                res = draw_study_charts(res)
        except StudyInterrupted as exc:
            err.print(f"[yellow]{escape(str(exc))}[/]")
            if json_:
                from .. import dumps

                print(dumps(exc.result.to_json()))
            raise typer.Exit(code=130) from None
        if json_:
            from .. import dumps

            print(dumps(res.to_json()))
            return
        _print_summary(res.to_json())
    except ClutchfemError as exc:
        fail(exc)


def _usage(msg: str):
    from .. import InputError

    return InputError(msg)


def _print_summary(s: dict) -> None:
    t = Table(title=escape(f"study {s['spec']}: {s['design']}, {s['method']}"))
    t.add_column("quantity")
    t.add_column("value", justify="right")
    rate = s.get("designs_per_min")
    listed = s.get("listed", s["points"])
    rows = [("points in the spec", f"{s['points']}" + (f" distinct designs ({listed} listed: repeats count once)"
                                                       if listed != s["points"] else "")), ("done (any status)", f"{s['done']}"),
            ("  ok", f"{s['ok']}"), ("  refused (input)", f"{s['refused']}"), ("  failed", f"{s['failed']}"),
            ("feasible (all requirements met)", f"{s['feasible']}"),
            ("computed in this run", f"{s['computed']}"), ("finished before (skipped)", f"{s['skipped']}"),
            ("wall time", f"{s['wall_s']:.1f} s"),
            ("rate", f"{rate:.0f} designs/min" if rate else "-"),
            ("ran on", s["scheduler"]), ("store", s["store"])]
    e = s.get("errors") or {}
    if e.get("sampled"):
        names = {"engagement_rpm": "engagement", "slip_rpm": "slip rpm", "torque_at_max_engine_torque_Nm": "torque",
                 "max_von_mises_MPa": "peak stress"}
        for ans, label in names.items():
            x = e.get(ans) or {}
            if x.get("band_median_pct") is not None:
                rows.append((f"error of {label} ({e['sampled']} sampled designs)",
                             f"+- {x['band_median_pct']:.1f} % median, {x['band_max_pct']:.1f} % max "
                             f"(mesh {x['discretisation_median_pct']:.1f} %)"))
    for q, v in rows:
        t.add_row(escape(q), escape(v))
    console.print(t)
    wrote(s.get("files", []))


@O.takes("concept", "set_", "mesh_size", "mu", "fidelity", "material", "engine", "workers", "scheduler", "out",
         "json_", live=True)
def guidelines(
    o,
    params: Optional[str] = typer.Option(None, "--params", help="parameters to study, comma separated (default: "
                                         "every continuous parameter with a non-zero value)",
                                         rich_help_panel="Guidelines"),
    step: float = typer.Option(0.02, "--step", help="with --remeshed-check: its relative step h (central "
                               "differences at h, h/2 and 2h on remeshed designs and a fit)",
                               rich_help_panel="Guidelines"),
    inputs: Optional[str] = typer.Option(None, "--inputs", help="operating inputs to differentiate on the design's "
                                         "own mesh, comma separated: mu, drum_wall (elastic drum only), idle_rpm; "
                                         "'none' for none (default: every one available)",
                                         rich_help_panel="Guidelines"),
    remeshed_check: bool = typer.Option(False, "--remeshed-check", help="also the former seven-point fit on "
                                        "remeshed designs (E_remeshed and its verdict next to the morphed "
                                        "elasticity; six more meshed designs per parameter)",
                                        rich_help_panel="Guidelines"),
    points: int = typer.Option(7, "--points", help="points of each one-at-a-time sweep", rich_help_panel="Guidelines"),
    span: float = typer.Option(0.5, "--span", help="one-at-a-time range: design value x (1 -+ span), within the "
                               "parameter's declared range", rich_help_panel="Guidelines"),
    check: int = typer.Option(2, "--check", help="with --fidelity live: the parameters (strongest first) also "
                              "differentiated by the full FE to check the live elasticities (0: none)",
                              rich_help_panel="Guidelines"),
):
    """Design guidelines: per parameter, elasticities (x / A) dA/dx of engagement, slip rpm,
    torque at max engine torque, peak stress, shoe mass and contact arc at the design point
    (central differences on meshes morphed from the design, checked at ten times the step,
    the method named per row), the same for the operating inputs (mu, drum wall, idle speed)
    on the design's own mesh, and a one-at-a-time sweep of each parameter over its range;
    ranked table and small-multiple charts."""
    from .. import GuidelineSettings, StudyInterrupted, draw_guideline_charts, guideline_table, run_guidelines

    try:
        o.scheduler = check_cluster(o.workers, o.scheduler)
        eng = engine_from(o.engine)[0] if o.engine is not None else None
        design = design_from(o.concept, o.set_, None, op=operating_point(mu=o.mu, material=material_from(o.material), fidelity=o.fidelity),
                             mesh_size=o.mesh_size, mesh_allowed=False)
        if design.op.fidelity == "live":
            _live_guidelines(o, design, eng, params, check)
            return
        names = None if params is None else [x.strip() for x in params.split(",") if x.strip()]
        ins = None if inputs is None else [x.strip() for x in inputs.split(",") if x.strip()]
        if ins is not None and [x.lower() for x in ins] == ["none"]:
            ins = []
        elif ins is not None and not ins:
            raise ParameterError("--inputs", inputs, "operating inputs, comma separated (mu, drum_wall, idle_rpm), "
                                 "or none", "guidelines")
        gs = GuidelineSettings.from_design(design, names, engine=eng, step=step, points=points, span=span,
                                           inputs=ins, remeshed_check=remeshed_check)
        o.out = check_out_dir(o.out if o.out is not None else Path(f"{gs.concept}-guidelines"))
        try:
            with _ctrl_c_as_keyboard_interrupt():
                res = run_guidelines(gs, o.out, workers=o.workers, scheduler=o.scheduler, progress=True)
        except StudyInterrupted as exc:
            err.print(f"[yellow]{escape(str(exc))}[/]")
            raise typer.Exit(code=130) from None
        res = draw_guideline_charts(res)
        if o.json_:
            from .. import dumps

            print(dumps(res.to_json()))
            return
        console.print(guideline_table(res))
        for n in res.notes:
            console.print(f"[dim]note: {escape(n)}[/]")
        wrote(res.files)
    except ClutchfemError as exc:
        fail(exc)


def _live_guidelines(o, design, eng, params, check) -> None:
    """``guidelines --fidelity live``: the reduced model's elasticities with their band, a
    few checked by the FE."""
    from .. import dumps, run_guidelines

    names = None if params is None else [x.strip() for x in params.split(",") if x.strip()]
    o.out = check_out_dir(o.out if o.out is not None else Path(f"{design.name}-guidelines"))
    res = run_guidelines(design, o.out, params=names, engine=eng, workers=o.workers or 0, live_check=check)
    if o.json_:
        print(dumps(res.to_json()))
        return
    t = Table(title=escape(f"{res.concept}: elasticities (x / A) dA/dx at the design point, live (reduced model)"))
    for c in ("parameter", "answer", "E", "+- band", "FE check"):
        t.add_column(c, justify="right" if c in ("E", "+- band") else "left")
    for r in sorted(res.table, key=lambda r: res.ranking.index(r["parameter"])):
        fe = r.get("fe_check")
        t.add_row(escape(r["parameter"]), escape(r["answer"]), f"{r['E']:+.3f}",
                  f"{r['E_band']:.3f}" if r["E_band"] == r["E_band"] else "-",
                  escape(f"{fe}: E_fe {r['E_fe']:+.3f}" if fe in ("agrees", "differs") else (fe or "-")))
    console.print(t)
    for n in res.notes:
        console.print(f"[dim]note: {escape(n)}[/]")
    wrote(res.files)
