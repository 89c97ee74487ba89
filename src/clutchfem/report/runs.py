"""Run folders: every file of a design's report, an optimisation, a tolerance study or a
profile compensation written into one folder, with its page (``report.html``,
``report.md``, ``page.json``) and ``inputs.json`` (the design, its hash, the clutchfem
version).  The command line and the Python API write the same folders through these
functions; each returns the paths it wrote."""

from __future__ import annotations

import math
import os
from pathlib import Path

import pandas as pd

from ..analysis import Requirements, analyze
from ..clutch import EngineCurve
from ..core import InputError, as_path, clean, write
from ..durability import render_png, write_vtu
from ..loadcase import Design, design_inputs
from .html import write_page
from .pages import compensation_page, design_page, optimization_page, tolerance_page

__all__ = ["compensation_json", "slip_heat_files", "compensation_report", "design_report", "optimization_report", "tolerance_report"]


def _page(out: Path, page, files: list[Path]) -> list[Path]:
    h, m = write_page(page, out)
    return files + [h, m, out / "inputs.json", out / "page.json"]


def design_report(design: Design, out, *, engine: EngineCurve | None = None,
                  requirements: Requirements | None = None, errors: bool = True, analysis=None) -> list[Path]:
    """The one-page report of a design: ``report.html`` (self-contained), ``report.md``, the
    answers (``analysis.json``), the curves (``curves.csv``), the torque-speed and contact
    arc/stress charts, the drawing and ``inputs.json``.

    Parameters
    ----------
    design : Design
        The design (a concept's or a user mesh's).
    out : path
        The folder to write (created if missing).
    engine : EngineCurve, optional
        The engine's full-throttle torque curve (default: the built-in 56.5 cc saw curve,
        its shape ASSUMED).
    requirements : Requirements, optional
        The requirement factors a and b (default: 1.3 and 1.0, ASSUMED).
    errors : bool
        Estimate the error of the main answers (a mesh twice as fine: ~3x the time).
    analysis : Analysis, optional
        The design's analysis if it is already done (it is not repeated).

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
    """
    if not isinstance(design, Design):
        raise InputError(f"report: design must be a clutchfem Design (Design.from_concept or Design.from_mesh), "
                         f"not {type(design).__name__}")
    out = as_path(out, "out", "the folder to write")
    out.mkdir(parents=True, exist_ok=True)
    engine = EngineCurve.of(engine)
    an = analysis if analysis is not None else analyze(design, engine=engine, requirements=requirements,
                                                       errors=errors)
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


def compensation_json(res, rows) -> dict:
    """The JSON document of a profile compensation (``compensation.json``, ``--json``)."""
    return clean({
        "concept": res.concept, "rpm": res.rpm, "target_arc": res.target_arc, "arc": list(res.arc),
        "mean_clearance_m": res.mean_clearance_m, "converged": res.converged, "seconds": res.seconds,
        "params": res.after_texts, "set": [f"{k}={v}" for k, v in res.after_texts.items()],
        "before_after": [{"answer": q, "before": x, "after": y} for q, x, y in rows],
        "contact_share_before": res.state_before.contact_share, "contact_share_after": res.state_after.contact_share,
        "torque_at_rpm_before_Nm": res.state_before.torque_Nm, "torque_at_rpm_after_Nm": res.state_after.torque_Nm,
        "steps": [dict(s.__dict__) for s in res.steps], "notes": res.notes,
        "run": {"rpm": res.rpm, "target_arc": res.target_arc, "arc": list(res.arc),
                "mean_clearance_m": res.mean_clearance_m},
        "units": {"rpm": "1/min", "lengths": "m", "pressure": "Pa", "torque": "N m", "share": "-"}})


def compensation_report(res, before, after, rows, engine: EngineCurve, out) -> list[Path]:
    """The folder of a profile compensation: ``compensation.json``, the pressure along the
    shoe before and after (CSV), the profile, torque and convergence charts, the page."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    doc = compensation_json(res, rows)
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


def slip_heat_files(run, out) -> list[Path]:
    """``<label>_slip_heat.vtu`` (final and maximum temperature on the P2 mesh),
    ``<label>_slip_heat.png`` (maximum temperature map and probe histories) and
    ``<label>_slip_heat.json`` (the document, with the design inputs).  All are written to
    hidden temporary names first and renamed together at the end, so an interrupted run
    leaves none of them (and no half file).  ``run``: a :class:`~clutchfem.analysis.SlipHeatRun`."""
    doc, result, design = run.doc, run.result, run.design
    out = Path(out)
    stem = f"{doc['label']}_slip_heat"
    jobs = []
    if result is not None:
        title = (f"{doc['design']}: {result.slip_power_W:.0f} W slip at {result.slip_rpm:.0f} rpm, "
                 f"{result.partition.fraction_part:.0%} into the part; {result.seconds:g} s x {doc['cycles']}")
        if doc.get("validity"):  # where the model stops holding (durability.heat.validity)
            title += "\nMODEL LIMITS: " + ", ".join(f"{f['flag']} at {f['time_s']:.1f} s" for f in doc["validity"])
            if doc.get("stopped_at_s") is not None:
                title += f"; answers cut at {doc['stopped_at_s']:.1f} s (curves beyond: not valid)"
        jobs.append((".vtu", lambda p: write_vtu(design.cm, result, p)))
        jobs.append((".png", lambda p: render_png(design.cm, result, p, title=title)))
    jobs.append((".json", lambda p: write(p, doc, indent=2)))

    for suffix, _ in jobs:  # a folder (or anything but a file) in the way: refuse before writing any
        final = out / f"{stem}{suffix}"
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
            os.replace(tmp, final)
    except OSError as exc:
        raise InputError(f"--out {out}: cannot write {Path(exc.filename or out).name} ({exc.strerror})") from None
    finally:
        for tmp, _ in done:
            if tmp.exists():
                tmp.unlink()
    return [final for _, final in done]
