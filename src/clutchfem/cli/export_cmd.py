"""``clutchfem export``: cutting files (DXF, STEP), the manufacturability check and the
drawing sheet of a concept design, an optimize/compensate result (``--from DIR``) or a study
row (``--study DIR --row HASH``)."""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer
from rich.markup import escape

from .. import ClutchfemError, InputError, ParameterError
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
    tolerances_from,
    working,
    wrote,
)

PANEL = "Cutting"


@O.takes("concept", "set_", "mesh_size", "fidelity", "engine", "out", "json_")
def export(
    o,
    from_: Optional[Path] = typer.Option(None, "--from", metavar="DIR", help="the design of a run folder's "
                                         "inputs.json (analyze/report/export --out, optimize --out: the final "
                                         "design, compensate --out: the compensated one)", rich_help_panel=O.DESIGN),
    study: Optional[Path] = typer.Option(None, "--study", metavar="DIR", help="a study's folder (results.sqlite); "
                                         "with --row", rich_help_panel=O.DESIGN),
    row: Optional[str] = typer.Option(None, "--row", metavar="HASH", help="the study row: 6+ hex digits of its "
                                      "design_hash", rich_help_panel=O.DESIGN),
    dxf: Optional[Path] = typer.Option(None, "--dxf", metavar="FILE", help="DXF cutting file (layers OUTER, INNER, "
                                       "BORE, TOOLPATH, TEXT)", rich_help_panel=O.OUTPUT),
    step: Optional[Path] = typer.Option(None, "--step", metavar="FILE", help="STEP solid (mm)",
                                        rich_help_panel=O.OUTPUT),
    drawing: Optional[Path] = typer.Option(None, "--drawing", metavar="FILE", help="drawing sheet: .pdf, .svg or "
                                           ".png (a PNG preview is written beside a PDF/SVG)",
                                           rich_help_panel=O.OUTPUT),
    process: Optional[str] = typer.Option(None, "--process", metavar="laser|waterjet|wire-edm",
                                          help="cutting process: its limits check the part, its kerf gives the "
                                               "tool path (ASSUMED typical values, sourced: docs/cutting.md)",
                                          rich_help_panel=PANEL),
    kerf: Optional[str] = typer.Option(None, "--kerf", metavar="LENGTH", help="kerf, e.g. 0.3mm (overrides the "
                                       "process's)", rich_help_panel=PANEL),
    min_inside_radius: Optional[str] = typer.Option(None, "--min-inside-radius", metavar="LENGTH",
                                                    help="smallest inside radius the shop cuts", rich_help_panel=PANEL),
    min_slot: Optional[str] = typer.Option(None, "--min-slot", metavar="LENGTH", help="narrowest slot the shop "
                                           "cuts", rich_help_panel=PANEL),
    min_web: Optional[str] = typer.Option(None, "--min-web", metavar="LENGTH", help="narrowest web the shop leaves",
                                          rich_help_panel=PANEL),
    units: str = typer.Option("mm", "--units", metavar="mm|in", help="unit of the DXF and the drawing (STEP: mm)",
                              rich_help_panel=O.OUTPUT),
    as_cut: bool = typer.Option(False, "--as-cut", help="also analyse the part cut with a kerf error of "
                                "+- --kerf-error (and the process's taper)", rich_help_panel=PANEL),
    kerf_error: Optional[str] = typer.Option(None, "--kerf-error", metavar="LENGTH", help="kerf error for --as-cut, "
                                             "e.g. 0.02mm (default: the process's)", rich_help_panel=PANEL),
    tol: List[str] = typer.Option([], "--tol", help="a tolerance on the drawing: name=+-value with its unit, e.g. "
                                  "flexure_thickness=+-0.02mm (printed on the dimensions equal to that parameter)",
                                  rich_help_panel=O.OUTPUT),
    no_analysis: bool = typer.Option(False, "--no-analysis", help="draw the sheet without the predicted answers "
                                     "(faster)", rich_help_panel=PANEL),
):
    """DXF and STEP of the whole part, the manufacturability check, the drawing sheet."""
    from .. import MeshSettings, ProcessRules, design_from_run, design_from_study, dumps
    from .. import export as run

    try:
        check_out_dir(o.out)
        if o.out is None and dxf is None and step is None and drawing is None:
            raise InputError("nothing to write: give --out DIR and/or --dxf FILE, --step FILE, --drawing FILE")
        if units not in ("mm", "in"):
            raise ParameterError("units", units, "'mm' or 'in'", "option --units")
        if process is not None and process not in ("laser", "waterjet", "wire-edm"):
            raise ParameterError("process", process, "one of 'laser', 'waterjet', 'wire-edm'", "option --process")
        limits = {k: quantity(f"--{k.replace('_', '-')}", v, "m", above=0.0) if k == "kerf" else
                  quantity(f"--{k.replace('_', '-')}", v, "m", 0.0, 1.0)
                  for k, v in (("kerf", kerf), ("min_inside_radius", min_inside_radius), ("min_slot", min_slot),
                               ("min_web", min_web))}
        kerr = quantity("--kerf-error", kerf_error, "m", 0.0, 1e-3)
        if kerr is not None and not as_cut:  # (an option that does not apply is refused, not dropped)
            raise InputError(f"option --kerf-error {kerf_error} applies to --as-cut (the part analysed cut with "
                             "that kerf error): add --as-cut, or leave --kerf-error out")
        try:
            rules = ProcessRules.of(process or "custom", **limits) \
                if (process or any(v is not None for v in limits.values())) else None
            if rules is not None and kerr is not None:  # before any work: the narrow variant is a cut
                rules.check_kerf_error(kerr)
        except ParameterError as exc:
            raise ParameterError(exc.name, exc.value, exc.allowed, f"option --{exc.name.replace('_', '-')}",
                                 shown=exc.shown) from None
        eng, _ = engine_from(o.engine)
        sources = [x for x in (o.concept is not None, from_ is not None, study is not None) if x]
        if len(sources) != 1:
            raise InputError("give exactly one design: CONCEPT [--set ...], --from DIR, or --study DIR --row HASH")
        if (study is None) != (row is None):
            raise InputError("--study DIR and --row HASH go together")
        if o.set_ and o.concept is None:
            raise InputError("--set changes a CONCEPT's parameters; --from/--study read the whole design")
        if o.fidelity is not None and o.concept is None:
            raise InputError(f"option --fidelity {o.fidelity} applies to a CONCEPT design; --from/--study read the "
                             "whole design, its fidelity included")
        ms = None if o.mesh_size is None else MeshSettings(size=MeshSettings.parse_value("size", o.mesh_size))
        if from_ is not None:
            design = design_from_run(from_, ms)
        elif study is not None:
            design = design_from_study(study, row, ms)
        else:
            design = design_from(o.concept, o.set_, None, op=operating_point(fidelity=o.fidelity),
                                 mesh_size=o.mesh_size, mesh_allowed=False)
        tols = tolerances_from(type(design.params), tol) if tol and design.params is not None else None
        err.print(escape(f"{design.name}: outline, features and checks ..."))
        with working(f"export {design.name}") as stage:  # a spinner with the elapsed time (issue 24)
            stage("outline, checks, files" + ("" if no_analysis else " and the analysis"))
            res = run(design, o.out, dxf=dxf, step=step, drawing=drawing, process=process, units=units,
                      analyze_design=not no_analysis, as_cut=as_cut, kerf_error=kerr, engine=eng, tolerances=tols,
                      **limits)
        wrote(res.files)
        if o.json_:
            print(dumps(res.to_json()))
            return
        _print(res)
    except ClutchfemError as exc:
        fail(exc)


def _print(res) -> None:
    console.print(f"[bold]{escape(res.label)}[/] (design hash {res.design_hash}): area {res.area_m2 * 1e6:.2f} mm^2, "
                  f"thickness {res.thickness_m * 1e3:g} mm, mass {res.mass_kg * 1e3:.2f} g, outer radius "
                  f"{res.outer_radius_m * 1e3:.4f} mm" + (f", STEP volume {res.volume_m3 * 1e9:.2f} mm^3"
                                                         if res.volume_m3 else ""))
    for kind, feats in res.features.items():
        for f in feats[:3]:
            console.print(f"  {kind}: {escape(f.text())}")
    if res.ligament is not None:
        console.print(f"  {escape(res.ligament.text())}")
    if res.rules is None:
        console.print("[yellow]no process chosen: nominal contour only, no manufacturability check (--process)[/]")
    else:
        console.print(f"cuttable by {res.rules.process} (kerf {res.rules.kerf * 1e3:g} mm; {escape(res.rules.sources())})")
    if res.as_cut:
        b = res.as_cut.get("band") or {}
        for r in res.as_cut["rows"]:
            e = "-" if r["engagement_rpm"] is None else f"{r['engagement_rpm']:.0f} rpm"
            s = "-" if r["slip_rpm"] is None else f"{r['slip_rpm']:.0f} rpm"
            console.print(f"  as cut, {escape(r['variant'])}: engagement {e}, slip {s}, mass {r['mass_kg'] * 1e3:.2f} g")
        if b:
            console.print(f"  (discretisation band of the as-cut pipeline: engagement +- {b['engagement_rpm']:.0f} rpm, "
                          f"slip +- {(b['slip_rpm'] or 0):.0f} rpm)")
