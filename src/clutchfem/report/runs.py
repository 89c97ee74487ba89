"""Run folders: every file of a design's report, an analysis, an optimisation, a tolerance
study, a profile compensation or a slip-heat run written into one folder, with its page
(``report.html``, ``report.md``, ``page.json``) and ``inputs.json`` (the design, its hash,
the clutchfem version).  One public function, :func:`write_report`, dispatches on what it is
given; the command line and the Python API write the same folders through it.  Each writer
returns the paths it wrote."""

from __future__ import annotations

import math
import os
import shutil
from functools import singledispatch
from pathlib import Path

import pandas as pd

from ..analysis import Analysis, Requirements, SlipHeatRun, analyze
from ..clutch import EngineCurve
from ..core import ClutchfemError, InputError, as_path, write
from ..loadcase import Design, design_inputs
from ..targets import Compensation, OptimizationResult
from ..thermal import render_png, write_series, write_vtu
from ..tolerances import ToleranceResult
from .design import write_analysis
from .html import folder_page, write_page
from .pages import compensation_page, design_page, optimization_page, tolerance_page

__all__ = ["write_report"]


def _page(out: Path, page, files: list[Path]) -> list[Path]:
    h, m = write_page(page, out)
    return files + [h, m, out / "inputs.json", out / "page.json"]


@singledispatch
def write_report(result, out, **context) -> list[Path]:
    """Write the run folder of a design or of any answer: its files and its one-page report
    (``report.html``, self-contained, and ``report.md``) where it has one.

    What is written depends on what ``result`` is (one function for every answer):

    * a :class:`~clutchfem.Design`: analysed (``engine``, ``requirements``, ``errors``; or
      its ``analysis`` if done), then the answers (``analysis.json``), the curves
      (``curves.csv``), the torque-speed and contact arc/stress charts, the drawing,
      ``inputs.json`` and the page;
    * an :class:`~clutchfem.Analysis`: ``<label>_analysis.json``, ``<label>_curves.csv`` and
      the torque-speed and arc/stress charts (``engine``: the curve it was analysed against);
    * an :class:`~clutchfem.OptimizationResult`: ``optimization.json``, the path (CSV and
      chart) and the page (``final``: the final design's analysis; default: the one the
      optimiser's check made, else a new best estimate);
    * a :class:`~clutchfem.ToleranceResult`: ``tolerance.json``, the samples, histograms,
      ranking and the page (``design``: the nominal design; ``run``: the run's settings as a
      dict; ``engine``: the curve's file name; ``requirements``);
    * a :class:`~clutchfem.Compensation`: ``compensation.json``, the pressure along the shoe
      before and after (CSV), the profile, torque and convergence charts and the page
      (``before``, ``after``: the two designs' analyses; ``engine``);
    * a :class:`~clutchfem.SlipHeatRun`: its ``.vtu``, ``.pvd`` series, picture and JSON;
    * a folder (``str`` or ``Path``) of an earlier run: its page rendered again from the
      files there (its pictures copied along when ``out`` is another folder).

    Parameters
    ----------
    result : Design, Analysis, OptimizationResult, ToleranceResult, Compensation, SlipHeatRun or path
        What to report.
    out : path
        The folder to write (created if missing).
    **context
        What the kind of ``result`` needs besides itself (see above).

    Returns
    -------
    list of Path
        The files written.

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> files = cf.write_report(d, tempfile.mkdtemp(), errors=False)
    >>> sorted(p.name for p in files if p.suffix in (".html", ".md"))
    ['report.html', 'report.md']
    >>> a = cf.analyze(d, errors=False)
    >>> sorted(p.suffix for p in cf.write_report(a, tempfile.mkdtemp()))
    ['.csv', '.json', '.png', '.png']
    """
    raise InputError(f"write_report: a Design, Analysis, OptimizationResult, ToleranceResult, Compensation, "
                     f"SlipHeatRun or a run folder, not {type(result).__name__}")


@write_report.register
def _(design: Design, out, *, engine: EngineCurve | None = None, requirements: Requirements | None = None,
      errors: bool = True, analysis=None) -> list[Path]:
    return _design_report(design, out, engine=engine, requirements=requirements, errors=errors, analysis=analysis)


@write_report.register
def _(analysis: Analysis, out, *, engine: EngineCurve | None = None, label: str | None = None) -> list[Path]:
    out = as_path(out, "out", "the folder to write")
    return write_analysis(analysis, EngineCurve.of(engine), out, label or analysis.label)


@write_report.register
def _(res: OptimizationResult, out, *, final=None) -> list[Path]:
    if final is None:
        final = res.final_analysis()
    return optimization_report(res, final, out)


@write_report.register
def _(res: ToleranceResult, out, *, design: Design, run: dict | None = None, engine: str = "",
      requirements: Requirements | None = None) -> list[Path]:
    return tolerance_report(res, out, design, run or {}, engine=engine, requirements=requirements)


@write_report.register
def _(res: Compensation, out, *, before, after, engine: EngineCurve | None = None) -> list[Path]:
    return compensation_report(res, before, after, EngineCurve.of(engine), out)


@write_report.register
def _(run: SlipHeatRun, out) -> list[Path]:
    return slip_heat_files(run, out)


@write_report.register(str)
@write_report.register(Path)
def _(folder, out=None) -> list[Path]:
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError(f"write_report: {folder} is not a folder (a run folder: analyze/optimize/tolerance/"
                         "compensate --out)")
    target = Path(out) if out is not None else folder
    target.mkdir(parents=True, exist_ok=True)
    page = folder_page(folder)
    if target.resolve() != folder.resolve():  # figures travel with the page
        for f in folder.glob("*.png"):
            shutil.copy2(f, target / f.name)
    return list(write_page(page, target))


def _design_report(design: Design, out, *, engine: EngineCurve | None = None,
                  requirements: Requirements | None = None, errors: bool = True, analysis=None) -> list[Path]:
    """The one-page report of a design (:func:`write_report`)."""
    if not isinstance(design, Design):
        raise InputError(f"report: design must be a clutchfem Design (Design.from_concept or Design.from_mesh), "
                         f"not {type(design).__name__}")
    out = as_path(out, "out", "the folder to write")
    out.mkdir(parents=True, exist_ok=True)
    engine = EngineCurve.of(engine)
    an = analysis if analysis is not None else analyze(design, engine=engine, requirements=requirements,
                                                       errors=errors)
    if "fe_torque_Nm" not in an.curve_names:  # a live answer: its page's charts need the FE's curves
        raise ClutchfemError(f"write_report: {design.name} was answered by the {an.answered_by}, which gives no "
                             "torque, contact arc or stress against rpm and no fields for the report's page; "
                             "report the design with fidelity 'best' (Design.from_concept(..., fidelity='best')), "
                             "or write_report(cf.analyze(design), out) for its answers (JSON and CSV)")
    concept = design.concept if design.params is not None else None
    page = design_page(an, design, engine, out, concept, design.params)
    files = [write(out / "analysis.json", an.to_json(), indent=1)]
    an.curves.to_csv(out / "curves.csv", index=False)
    files += [out / "curves.csv", out / "torque_rpm.png", out / "arc_stress_rpm.png"]
    return _page(out, page, files)


def optimization_report(res, final, out) -> list[Path]:
    """The folder of an optimisation: its path (``optimization.json``,
    ``optimization_path.csv``, the chart) and the page; ``final`` the final design's analysis."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    files = [write(out / "optimization.json", res.to_json(), indent=1)]
    keys = ("engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm", "torque_at_max_engine_torque_Nm",
            "max_von_mises_Pa", "safety_factor", "fatigue_safety_factor", "mass_kg", "message")
    df = pd.DataFrame([{**{"n": r["n"], "phase": r.get("phase"), "status": r["status"],
                           "feasible": r.get("assessment", {}).get("h", math.inf) <= 0},
                        **{f"param:{k}": v for k, v in r["params"].items()},
                        **{k: r.get(k) for k in keys}} for r in res.path])
    df.to_csv(out / "optimization_path.csv", index=False)
    files.append(out / "optimization_path.csv")
    page = optimization_page(res, final, out)
    files.append(out / "optimization_path.png")
    return _page(out, page, files)


def tolerance_report(res, out, nominal_design: Design, run: dict, *, engine: str = "",
                     requirements: Requirements | None = None) -> list[Path]:
    """The folder of a tolerance study: ``tolerance.json``, the samples, the histograms and
    the ranking, and the page with the nominal design's inputs and the run's settings."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    files = [write(out / "tolerance.json", res.to_json(), indent=1)]
    keys = ("engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm", "max_von_mises_Pa", "safety_factor",
            "torque_at_max_engine_torque_Nm", "mass_kg")
    pd.DataFrame([{**{f"d:{k}": v for k, v in r.get("d", {}).items()}, "status": r["status"],
                   **{k: r.get(k) for k in keys}, **{f"param:{k}": v for k, v in r["params"].items()}}
                  for r in res.rows]).to_csv(out / "tolerance_samples.csv", index=False)
    files += [out / "tolerance_samples.csv", out / "tolerance_histograms.png", out / "tolerance_ranking.png"]
    req = requirements if requirements is not None else Requirements()
    inputs = {"nominal_design": {**design_inputs(nominal_design), "engine": engine or "built-in (ASSUMED shape)",
                                 "requirements": {"a": req.a, "b": req.b}}, "run": run}
    page = tolerance_page(res, out, inputs)
    return _page(out, page, files)


def compensation_report(res, before, after, engine: EngineCurve, out) -> list[Path]:
    """The folder of a profile compensation: ``compensation.json``, the pressure along the
    shoe before and after (CSV), the profile, torque and convergence charts, the page."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    doc = res.to_json(before, after)
    files = [write(out / "compensation.json", doc, indent=1)]
    for tag, st in (("before", res.state_before), ("after", res.state_after)):
        pd.DataFrame({"s": st.s, "clearance_m": st.clearance_m, "free_displacement_m": st.free_m,
                      "pressure_Pa": st.pressure_Pa, "force_N": st.force_N}).to_csv(out / f"pressure_{tag}.csv",
                                                                                    index=False)
        files.append(out / f"pressure_{tag}.csv")
    page = compensation_page(res, before, after, engine, out, {"before": before.inputs, "after": after.inputs,
                                                                "run": doc["run"]})
    files += [out / "compensation_profile.png", out / "compensation_torque.png", out / "compensation_convergence.png"]
    return _page(out, page, files)


def _fresh_dir(p: Path) -> None:
    """An empty folder at ``p`` (a leftover of an interrupted run removed)."""
    if p.exists():
        shutil.rmtree(p)
    p.mkdir()


def slip_heat_files(run, out) -> list[Path]:
    """``<label>_slip_heat.vtu`` (final and maximum temperature on the P2 mesh),
    ``<label>_slip_heat.pvd`` with its folder ``<label>_slip_heat_series/`` (the transient
    as a ParaView time series of the whole part), ``<label>_slip_heat.png`` (maximum
    temperature map and probe histories) and ``<label>_slip_heat.json`` (the document, with
    the design inputs).  All are written to hidden temporary names first and renamed
    together at the end, so an interrupted run leaves none of them (and no half file).
    ``run``: a :class:`~clutchfem.analysis.SlipHeatRun`."""
    doc, result, design = run.doc, run.result, run.design
    out = Path(out)
    stem = f"{doc['label']}_slip_heat"
    jobs = []
    if result is not None:
        title = (f"{doc['design']}: {result.slip_power_W:.0f} W slip at {result.slip_rpm:.0f} rpm, "
                 f"{result.partition.fraction_part:.0%} into the part; {result.seconds:g} s x {doc['cycles']}")
        if doc.get("validity"):  # where the model stops holding (thermal.validity)
            title += "\nMODEL LIMITS: " + ", ".join(f"{f['flag']} at {f['time_s']:.1f} s" for f in doc["validity"])
            if doc.get("stopped_at_s") is not None:
                title += f"; answers cut at {doc['stopped_at_s']:.1f} s (curves beyond: not valid)"
        jobs.append((".vtu", lambda p: write_vtu(design.cm, result, p)))
        if result.frames_C is not None and len(result.frames_C):
            series = f"{stem}_series"
            jobs.append(("_series", _fresh_dir))  # (filled by the .pvd's job)
            jobs.append((".pvd", lambda p: write_series(design.cm, result, p, out / f".{stem}.partial_series",
                                                        name=series)))
        jobs.append((".png", lambda p: render_png(design.cm, result, p, title=title, answer=doc)))
    jobs.append((".json", lambda p: write(p, doc, indent=2)))

    for suffix, _ in jobs:  # a folder (or anything but a file) in the way: refuse before writing any
        final = out / f"{stem}{suffix}"
        if suffix == "_series":
            if final.exists() and not (final.is_dir() and all(f.suffix == ".vtu" for f in final.iterdir())):
                raise InputError(f"--out {out}: {final.name} exists and is not a folder of a slip-heat series: "
                                 "cannot write the series there; remove it or choose another --out")
            continue
        if final.exists() and not final.is_file():
            raise InputError(f"--out {out}: {final.name} exists and is not a file (a folder?): cannot write the "
                             "result there; remove it or choose another --out")
    done = []
    try:
        for suffix, job in jobs:
            tmp = out / f".{stem}.partial{suffix}"
            done.append((tmp, out / f"{stem}{suffix}"))
            job(tmp)
        for tmp, final in done:
            if tmp.is_dir() and final.is_dir():  # the series of an earlier run: replaced whole
                shutil.rmtree(final)
            os.replace(tmp, final)
    except OSError as exc:
        raise InputError(f"--out {out}: cannot write {Path(exc.filename or out).name} ({exc.strerror})") from None
    finally:
        for tmp, _ in done:
            if tmp.is_dir():
                shutil.rmtree(tmp)
            elif tmp.exists():
                tmp.unlink()
    return [final for _, final in done]
