"""Designer-facing plots, the summary table and the one-page report of analysed designs.

Every plot labels its assumptions (engine curve shape, requirement factors a and b) and every
number in :func:`~.answer_rows.summary_rows` carries its unit."""

from __future__ import annotations

import logging
import math
from pathlib import Path

import numpy as np

from ..analysis import analyze, slip_answer
from ..clutch import BaselineClutch, EngineCurve
from ..core import write as write_json
from ..core.figures import RPM_MARGIN, figure, save_figure
from ..geometry import MeshSettings, concepts
from ..loadcase import Design, OperatingPoint
from .answer_rows import corrections_text, summary_rows

log = logging.getLogger("clutchfem")

__all__ = ["torque_plot", "arc_stress_plot", "torque_speed_plot", "write_analysis",
           "markdown_summary", "default_design_report"]

_COLORS = {"concept1": "tab:blue", "concept4": "tab:red", "concept2": "tab:purple",
           "concept3": "tab:brown", "concept3.1": "tab:olive", "concept5": "tab:cyan"}


def _requirement_bands(ax, req, rpm_max, label=True):
    ax.axvspan(0, req["engagement_limit_rpm"], color="red", alpha=0.07,
               label=(f"engagement forbidden: below a x idle = {req['engagement_limit_rpm']:.0f} rpm "
                      f"(a = {req['a']:g}{', ASSUMED' if 'ASSUMED' in req['assumed'] else ''})") if label else None)
    ax.axvspan(req["slip_limit_rpm"], rpm_max, color="orange", alpha=0.08,
               label=(f"slip forbidden: above b x rpm(max torque) = {req['slip_limit_rpm']:.0f} rpm "
                      f"(b = {req['b']:g}{', ASSUMED' if 'ASSUMED' in req['assumed'] else ''})") if label else None)


def _engine_line(ax, engine):
    r = np.linspace(*engine.rpm_range, 300)
    lab = "engine, full throttle" + (" (ASSUMED shape)" if engine.assumed else f" ({Path(engine.source).name})")
    ax.plot(r, engine.torque_at(r), "g-", lw=2.5, label=lab)


def torque_plot(an, engine, path: Path, title: str) -> Path:
    """Torque vs rpm: FE and both analytical curves, engine, baseline, engagement/slip markers, requirement bands."""
    c = an.curves
    fig, ax = figure(figsize=(8.5, 6.6), layout="constrained")
    e = (getattr(an, "errors", None) or {}).get("torque_at_max_engine_torque_Nm") or {}
    fix = e.get("corrections") or {}
    ax.plot(c["rpm"], c["fe_torque_Nm"], "k-", lw=2, label="FE (contact + friction" +
            (";\nthe design mesh's linear model: the point is corrected)" if fix else ")"))
    if getattr(an, "analytical_available", True):
        ax.plot(c["rpm"], c["analytic_fe_arc_Nm"], "b--", label="analytical, FE contact arc")
        ax.plot(c["rpm"], c["analytic_nominal_arc_Nm"], "r:", lw=2, label="analytical, nominal full arc (thesis)")
    else:
        ax.plot([], [], " ", label="analytical shoe model: not available (user mesh)")
    _engine_line(ax, engine)
    ax.plot(c["rpm"], BaselineClutch.new().torque_at_rpm(c["rpm"].to_numpy()), color="0.6", lw=1,
            label="today's spring clutch, new shoes (seed 000)")
    if an.engagement_rpm:
        ax.axvline(an.engagement_rpm, color="m", ls="--", lw=1, label=f"engagement {an.engagement_rpm:.0f} rpm")
    if an.engagement_rpm_with_ripple:
        ax.axvline(an.engagement_rpm_with_ripple, color="m", ls=":", lw=1,
                   label=f"engagement with ripple (3 sigma) {an.engagement_rpm_with_ripple:.0f} rpm")
    if an.slip_rpm is not None:
        ax.plot([an.slip_rpm], [engine.torque_at(an.slip_rpm)], "o", ms=9, mfc="none", mec="k", mew=2,
                label=f"slip {an.slip_rpm:.0f} rpm")
    else:
        ax.text(0.98, 0.5, an.slip_status.upper(), transform=ax.transAxes, ha="right", color="k", fontsize=12)
    t = an.torque_at_max_engine_torque_Nm
    if fix and t is not None and math.isfinite(t):  # the reported answer, where it is not the curve's point
        f = ".3f" if e.get("total") is not None and e["total"] < 0.05 else ".2f"
        band = f" +- {e['total']:{f}} N m" if e.get("total") is not None else ""
        ax.plot([an.rpm_max_engine_torque], [t], "ks", mfc="none", ms=7, mew=1.5,
                label=f"torque {t:{f}} N m{band} at {an.rpm_max_engine_torque:.0f} rpm\n({corrections_text(e)})")
    _requirement_bands(ax, an.requirements, c["rpm"].max())
    finite = c[["fe_torque_Nm", "analytic_fe_arc_Nm"]].replace([np.inf], np.nan).max().max()
    ax.set_ylim(0, max(8.0, min(1.3 * float(finite or 8.0), 60)))
    ax.set_xlim(0, c["rpm"].max())
    ax.set_xlabel("engine speed [rpm]")
    ax.set_ylabel("torque [N m]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    fig.legend(*ax.get_legend_handles_labels(), fontsize=7, loc="outside lower center", ncol=2)
    return save_figure(fig, path)


def arc_stress_plot(an, path: Path, title: str | None = None) -> Path:
    """Contact arc per shoe vs rpm with its error band (the ends between the nodes: :mod:`clutchfem.contact.arc`),
    its share of the nominal shoe arc on the right axis and its value at the rpm of maximum engine torque
    marked; peak von Mises vs rpm with the error band of the peak at the engine's maximum speed (relative,
    applied to every speed), the yield line and the answer at the engine's maximum speed marked."""
    c = an.curves
    fig, (a1, a2) = figure(1, 2, figsize=(12, 5.4), layout="constrained")
    nominal = an.coupling.get("phi2_deg", math.nan) - an.coupling.get("phi1_deg", math.nan)
    rpm = c["rpm"].to_numpy(dtype=float)
    arc = c["contact_arc_deg"].to_numpy(dtype=float)
    err = c["contact_arc_error_deg"].to_numpy(dtype=float) if "contact_arc_error_deg" in c else np.zeros(len(arc))
    on = arc > 0
    a1.fill_between(rpm, np.where(on, np.maximum(arc - err, 0.0), np.nan), np.where(on, arc + err, np.nan),
                    color="0.8", label="error band (ends +- 0.4 node spacings)")
    a1.plot(rpm, np.where(on, arc, np.nan), "k-", lw=1.8, label="FE contact arc per shoe (ends between nodes)")
    m = an.torque_models_at_max_engine_torque_Nm
    k = int(np.argmin(np.abs(rpm - m["rpm"])))
    a_probe = an.contact_arc_at_max_engine_torque_deg
    a1.plot([m["rpm"]], [a_probe], "o", ms=8, mfc="none", mec="C0", mew=2,
            label=f"{a_probe:.2f} deg +- {err[k]:.2f} deg at {m['rpm']:.0f} rpm (max engine torque)")
    if an.engagement_rpm:
        a1.axvline(an.engagement_rpm, color="m", ls="--", lw=1, label=f"engagement {an.engagement_rpm:.0f} rpm")
    a1.set_xlabel("engine speed [rpm]")
    a1.set_ylabel("contact arc per shoe [deg]")
    a1.set_xlim(0, RPM_MARGIN * rpm.max())  # the marks at the last speed whole (issue 37)
    a1.set_ylim(0, max(1.15 * float(np.nanmax(np.where(on, arc + err, 0.0), initial=0.0)), 0.5))
    if math.isfinite(nominal) and nominal > 0:
        a1.secondary_yaxis("right", functions=(lambda d: 100 * d / nominal, lambda q: q * nominal / 100)) \
            .set_ylabel(f"share of the nominal shoe arc ({nominal:.0f} deg) [%]")
        a1.plot([], [], " ", label=f"nominal shoe arc {nominal:.0f} deg (thesis assumption); prototypes touched "
                                   f"on ~1/3 = {nominal / 3:.0f} deg")
    a1.set_title("contact arc (shoe vs drum)")
    a1.grid(alpha=0.3)
    a1.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1)
    vm = c["max_von_mises_Pa"].to_numpy(dtype=float) / 1e6
    e = (getattr(an, "errors", None) or {}).get("max_von_mises_Pa") or {}
    rel = e["total"] / e["value"] if e.get("total") is not None and e.get("value") else None
    if rel is not None:
        d = "n/a" if e.get("discretisation") is None else f"{e['discretisation'] / 1e6:.0f}"
        a2.fill_between(rpm, vm * (1 - rel), vm * (1 + rel), color="mistyrose",
                        label=f"error band +- {100 * rel:.0f} % (the peak's at {an.max_stress_rpm:.0f} rpm: mesh "
                              f"{d} MPa, model {e['model_form'] / 1e6:.0f} MPa)")
    fix = e.get("corrections") or {}
    a2.plot(rpm, vm, "r-", label="peak von Mises (FE, unaveraged element vertices" +
            ("; the linear model: the point is corrected)" if fix else ")"))
    a2.axhline(an.yield_strength_Pa / 1e6, color="k", ls="--", label=f"yield {an.yield_strength_Pa / 1e6:.0f} MPa")
    band = f" +- {e['total'] / 1e6:.0f} MPa" if rel is not None else ""
    a2.plot([an.max_stress_rpm], [an.max_von_mises_Pa / 1e6], "ko", mfc="none", ms=8, mew=2,
            label=f"{an.max_von_mises_Pa / 1e6:.0f} MPa{band} at {an.max_stress_rpm:.0f} rpm, "
                  f"safety factor {an.safety_factor:.2f}" + (f"\n({corrections_text(e)})" if fix else ""))
    if an.safety_factor < 1:
        a2.set_title("peak stress: ABOVE YIELD at engine max speed", color="r", fontweight="bold")
    else:
        a2.set_title("peak stress")
    a2.set_xlabel("engine speed [rpm]")
    a2.set_ylabel("max von Mises [MPa]")
    a2.set_xlim(0, RPM_MARGIN * rpm.max())
    a2.set_ylim(0, max(1.1 * an.yield_strength_Pa / 1e6, 1.1 * float(np.nanmax(vm * (1 + (rel or 0.0))))))
    a2.grid(alpha=0.3)
    a2.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1)
    if title:
        fig.suptitle(title)
    return save_figure(fig, path)


def torque_speed_plot(analyses: dict, engine, path: Path, title: str | None = None,
                    baseline: bool = True) -> Path:
    """The thesis's figure 25: FE torque vs rpm of several designs and today's spring clutch
    (new and worn shoes) against the engine curve, with engagement and slip markers and the
    requirement bands of the first design's requirement factors.

    Parameters
    ----------
    analyses : dict of str to Analysis
    engine : EngineCurve
    path : path
        The PNG to write.
    title : str, optional
    baseline : bool
        Draw today's spring clutch (seed 000) too.

    Returns
    -------
    Path

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> a = cf.analyze(cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm")), errors=False)
    >>> cf.torque_speed_plot({"concept1": a}, cf.EngineCurve.default(),
    ...                      pathlib.Path(tempfile.mkdtemp()) / "t.png").suffix
    '.png'"""
    fig, ax = figure(figsize=(12.5, 5.8), layout="constrained")
    rpm_max = engine.rpm_range[1]
    r = np.linspace(0, rpm_max, 561)
    ymax = 8.0
    for i, (name, an) in enumerate(analyses.items()):
        c = an.curves
        col = _COLORS.get(name, f"C{i}")
        ax.plot(c["rpm"], c["fe_torque_Nm"], "-", color=col, lw=2, label=f"{name} (FE)")
        if an.engagement_rpm:
            ax.plot([an.engagement_rpm], [0], "^", color=col, ms=9, clip_on=False,
                    label=f"{name} engagement {an.engagement_rpm:.0f} rpm")
        if an.slip_rpm is not None:
            ax.plot([an.slip_rpm], [engine.torque_at(an.slip_rpm)], "o", color=col, ms=9, mfc="none", mew=2,
                    label=f"{name} slip {an.slip_rpm:.0f} rpm")
        else:
            ax.plot([], [], " ", label=f"{name}: {an.slip_status}")
        ymax = max(ymax, float(np.nanmax(c["fe_torque_Nm"].replace([np.inf], np.nan))))
    if baseline:
        for clutch, ls in ((BaselineClutch.new(), "-"), (BaselineClutch.worn(), "--")):
            t = clutch.torque_at_rpm(r)
            lab = f"today's spring clutch, {clutch.label} shoes (seed 000, k = {clutch.k})"
            ax.plot(r, t, ls, color="0.45", lw=1.5, label=lab)
            s = slip_answer(engine, clutch.torque_at_rpm, clutch.engagement_rpm)
            if s.rpm is not None:
                ax.plot([s.rpm], [engine.torque_at(s.rpm)], "s", color="0.45", ms=7, mfc="none", mew=1.5,
                        label=f"spring clutch ({clutch.label}) slip {s.rpm:.0f} rpm")
    _engine_line(ax, engine)
    first = next(iter(analyses.values()), None)
    if first is not None:
        _requirement_bands(ax, first.requirements, rpm_max)
    ax.set_xlim(0, rpm_max)
    ax.set_ylim(0, min(1.1 * ymax, 25.0))
    ax.set_xlabel("engine speed [rpm]")
    ax.set_ylabel("clutch slip torque / engine torque [N m]")
    ax.set_title(title or "Torque vs engine speed, drum held (cf. thesis fig. 25)")
    ax.grid(alpha=0.3)
    fig.legend(*ax.get_legend_handles_labels(), fontsize=7, loc="outside right upper", ncol=1)
    return save_figure(fig, path)


def write_analysis(an, engine, out: Path, name: str) -> list[Path]:
    """Plots (torque vs rpm; contact arc and stress vs rpm), the curves CSV and the JSON.  A
    live answer (the reduced model's: no clutch curves against rpm) gets the CSV of the engine
    curve and the JSON, and a note that the plots need the FE."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    files = []
    if "fe_torque_Nm" in an.curve_names:
        files += [torque_plot(an, engine, out / f"{name}_torque_rpm.png", f"{name}: torque vs engine speed (drum held)"),
                  arc_stress_plot(an, out / f"{name}_arc_stress_rpm.png", f"{name}: contact arc and peak stress vs rpm")]
    else:
        log.info(f"{name}: answered by the {an.answered_by}: no torque, arc or stress against rpm to plot "
                 "(the plots need the FE: --fidelity best)")
    an.curves.to_csv(out / f"{name}_curves.csv", index=False)
    files.append(out / f"{name}_curves.csv")
    write_json(out / f"{name}_analysis.json", an.to_json(), indent=2)
    files.append(out / f"{name}_analysis.json")
    return files


def markdown_summary(analyses: dict, engine, figures: dict | None = None) -> str:
    """One-page Markdown report: a table of answers per design, warnings first."""
    lines = ["# Clutch performance report", ""]
    for name, an in analyses.items():
        lines += [f"## {name}", ""]
        for w in an.warnings:
            lines += [f"> **WARNING:** {w}", ""]
        lines += ["| quantity | value |", "|---|---|"]
        lines += [f"| {q} | {v} |" for q, v in summary_rows(an)]
        lines.append("")
        for n in an.notes:
            lines.append(f"* {n}")
        lines.append("")
    if figures:
        lines += ["## Figures", ""]
        lines += [f"![{k}]({v})" for k, v in figures.items()]
        lines.append("")
    return "\n".join(lines)


def default_design_report(out: Path, concept_names: tuple[str, ...] | str | None = None,
                          mesh_size: float | None = None) -> list[Path]:
    """Analyse the default designs (concepts 1 and 4, with error bands, ``mesh_size`` [m] elements), write per
    design its plots, JSON and CSV, the comparison chart (thesis fig. 25, with today's spring clutch), ``report.md``.

    Parameters
    ----------
    out : path
    concept_names : str or tuple of str, optional
    mesh_size : float, optional

    Returns
    -------
    list of Path

    Examples
    --------
    >>> import tempfile
    >>> [f.name for f in default_design_report(tempfile.mkdtemp(), ())]   # (): today's spring clutch alone
    ['clutch_torque_comparison.png', 'report.md']"""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    if concept_names is None:
        concept_names = tuple(n for n in ("concept1", "concept4") if n in concepts())
    elif isinstance(concept_names, str):
        concept_names = (concept_names,)
    engine = EngineCurve.default()
    analyses, files = {}, []
    for name in concept_names:
        # the shipped default (the best estimate; CLUTCHFEM_FIDELITY sets another) on its mesh
        op = OperatingPoint()
        ms = MeshSettings.preset(op.fidelity, **({} if mesh_size is None else {"size": mesh_size}))
        an = analyze(Design.from_concept(name, operating=op, mesh=ms), engine=engine)
        analyses[name] = an
        files += write_analysis(an, engine, out, name)
    fig25 = torque_speed_plot(analyses, engine, out / "clutch_torque_comparison.png")
    files.insert(0, fig25)
    figs = {"torque comparison (cf. thesis fig. 25)": fig25.name}
    for name in analyses:
        figs[f"{name} torque"] = f"{name}_torque_rpm.png"
        figs[f"{name} contact arc and stress"] = f"{name}_arc_stress_rpm.png"
    md = out / "report.md"
    md.write_text(markdown_summary(analyses, engine, figs))
    files.append(md)
    return files
