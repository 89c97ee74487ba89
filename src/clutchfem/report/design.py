"""Designer-facing plots, the summary table and the one-page report of analysed designs.

Every plot labels its assumptions (engine curve shape, requirement factors a and b) and every
number in :func:`summary_rows` carries its unit."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..analysis import analyze, slip_answer
from ..clutch import BaselineClutch, EngineCurve
from ..core import write as write_json
from ..core.figures import RPM_MARGIN, figure, save_figure
from ..geometry import MeshSettings, concepts
from ..loadcase import Design, OperatingPoint

__all__ = ["summary_rows", "torque_plot", "arc_stress_plot", "torque_speed_plot", "write_analysis",
           "markdown_summary", "default_design_report"]

_COLORS = {"concept1": "tab:blue", "concept4": "tab:red", "concept2": "tab:purple",
           "concept3": "tab:brown", "concept3.1": "tab:olive", "concept5": "tab:cyan"}


def _fmt(v, f: str, unit: str) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return f"{v:{f}} {unit}".rstrip()


def _err(an, key: str, scale: float = 1.0, unit: str | None = None, fmt: str = ".0f") -> str:
    """' (+- x unit: discretisation d, model form m)' for an answer with an error estimate."""
    e = (getattr(an, "errors", None) or {}).get(key)
    if not e or e.get("total") is None or e.get("value") is None:
        return ""
    u = unit or e["unit"]
    if e.get("model_form") is None:  # a live answer: the best path's band plus the model's own error
        own = e.get("reduced_model_rel")
        return f" +- {e['total'] * scale:{fmt}} {u} (live: the best path's band" + \
            (f" + the reduced model's own {100 * own:.2g} %)" if own is not None else ")")
    d = "n/a" if e["discretisation"] is None else f"{e['discretisation'] * scale:{fmt}}"
    corr = corrections_text(e)
    return f" +- {e['total'] * scale:{fmt}} {u} (mesh {d}, model {e['model_form'] * scale:{fmt}}" + \
        (f"; {corr})" if corr else ")")


def corrections_text(e: dict) -> str:
    """'corrected: non-linearity +1.1 %, mesh extrapolation +1.5 %' for an answer the best path
    corrected (its ``corrections``; 'mesh refined once more': reported from a mesh four times
    as fine to meet its accuracy target, :mod:`clutchfem.analysis.refinement`), else ''."""
    fix = e.get("corrections") or {}
    how = [f"{lab} {100 * fix[k]:+.1f} %" for k, lab in (("geometric_nonlinearity", "non-linearity"),
                                                         ("discretisation_extrapolation", "mesh extrapolation"),
                                                         ("mesh_refinement", "mesh refined once more"))
           if fix.get(k) is not None and (k != "discretisation_extrapolation" or fix.get("extrapolated"))]
    return f"corrected: {', '.join(how)}" if how else ""


def model_row(an) -> tuple[str, str] | None:
    """('model', what answered): the fidelity and what it resolved to (design inputs)."""
    m = (getattr(an, "inputs", None) or {}).get("model")
    if not m:
        return None
    form = {"thick": "thick plane model (3-D thickness effect)", "3d": "3-D tetrahedra",
            "plane-stress": "plane stress", "plane-strain": "plane strain"}.get(m["formulation"], m["formulation"])
    drum = "rigid drum" if m["drum_wall_m"] is None else \
        f"elastic drum, {m['drum_wall_m'] * 1e3:g} mm steel wall ({m['drum_state']}; ASSUMED)"
    what = {"best": "best estimate", "fast": "fast, uncorrected (larger error band)"}.get(m["fidelity"], m["fidelity"])
    return ("model", f"{what}: {form}, {drum}, softening {m['softening']}")


def sensitivity_rows(an) -> list[tuple[str, str]]:
    """The main answers at the drum wall's low and high value (an ASSUMED input, apart from the error band)."""
    errs = getattr(an, "errors", None) or {}
    parts, label = [], None
    for key, name, scale, unit, fmt in (("engagement_rpm", "engagement", 1.0, "rpm", ".0f"),
                                        ("slip_rpm", "slip", 1.0, "rpm", ".0f"),
                                        ("torque_at_max_engine_torque_Nm", "torque", 1.0, "N m", ".2f"),
                                        ("max_von_mises_Pa", "stress", 1e-6, "MPa", ".0f")):
        sens = (errs.get(key) or {}).get("sensitivities") or {}
        for lab, vals in sens.items():
            if lab.startswith("drum wall") and all(v is not None for v in vals):
                label = lab
                parts.append(f"{name} {vals[0] * scale:{fmt}} / {vals[1] * scale:{fmt}} {unit}")
    if not parts:
        return []
    return [(f"answers with the {label} (2 mm ASSUMED; not in the error band)", "; ".join(parts))]


def summary_rows(an) -> list[tuple[str, str]]:
    """(quantity, value with unit) rows of one design's answers, the main ones with their error band.

    Parameters
    ----------
    an : Analysis

    Returns
    -------
    list of tuple of str

    Examples
    --------
    >>> a = analyze(Design.from_concept("concept1", mesh=MeshSettings(size="3mm")), errors=False)
    >>> dict(summary_rows(a))["engagement speed (static, FE)"] == f"{a.engagement_rpm:.0f} rpm"
    True"""
    req = an.requirements
    mrow = model_row(an)
    live = getattr(an, "answered_by", "FE") == "reduced model"
    rows = ([mrow] if mrow else []) + [
        ("engagement speed (static, live)" if live else "engagement speed (static, FE)", _fmt(an.engagement_rpm, ".0f", "rpm") + _err(an, "engagement_rpm")
         + (f" (above the engine curve's top speed {an.max_engine_rpm:.0f} rpm: never engages on this engine)"
            if an.slip_status == "never engages" else "")
         if an.engagement_rpm is not None else "never engages"),
        ("engagement speed with 2-stroke ripple (3 sigma cycle / typical cycle)",
         f"{_fmt(an.engagement_rpm_with_ripple, '.0f', 'rpm')} / "
         f"{_fmt(an.engagement_rpm_with_ripple_typical, '.0f', 'rpm')}"
         if an.engagement_rpm_with_ripple is not None else "never engages"),
        ("first contact on the shoe", "not computed (live: --fidelity best gives it)" if live else str(an.first_touch)
         + (f" (polar angle {an.first_touch_angle_deg:.1f} deg)"
            if an.first_touch == "unknown" and getattr(an, "first_touch_angle_deg", None) is not None else "")),
    ]
    if an.slip_status in ("never holds", "never engages"):
        rows.append(("slip speed (drum held, full throttle)", an.slip_status.upper()))
    else:
        rows.append(("slip speed (drum held, full throttle)", _fmt(an.slip_rpm, ".0f", "rpm") + _err(an, "slip_rpm")))
    if len(an.slip_crossings_rpm) > 1:
        rows.append(("clutch/engine torque crossings",
                     ", ".join(f"{c['rpm']:.0f} rpm ({c['direction']})" for c in an.slip_crossings_rpm)))
    # (a band below 0.05 N m, e.g. a design engaging just below the rpm of max torque, shows 3 decimals)
    t_band = ((getattr(an, "errors", None) or {}).get("torque_at_max_engine_torque_Nm") or {}).get("total")
    t_fmt = ".3f" if t_band is not None and t_band < 0.05 else ".2f"
    rows += [
        (f"clutch torque at {an.rpm_max_engine_torque:.0f} rpm (max engine torque "
         f"{an.max_engine_torque_Nm:.2f} N m)", _fmt(an.torque_at_max_engine_torque_Nm, t_fmt, "N m")
         + _err(an, "torque_at_max_engine_torque_Nm", fmt=t_fmt)),
        ("torque margin over max engine torque", _fmt(an.torque_margin_Nm, "+.2f", "N m")),
        ("slip power (heat) at slip speed", _fmt(an.slip_power_W, ".0f", "W") if an.slip_power_W is not None
         else f"- ({an.slip_status})"),
        (f"max von Mises at {an.max_stress_rpm:.0f} rpm (engine max)", _fmt(an.max_von_mises_Pa / 1e6, ".0f", "MPa")
         + _err(an, "max_von_mises_Pa", 1e-6, "MPa")),
        (f"safety factor against yield ({an.yield_strength_Pa / 1e6:.0f} MPa)",
         _fmt(an.safety_factor, ".2f", "(-)") + ("  ABOVE YIELD" if an.safety_factor < 1 else "")),
    ]
    rows += sensitivity_rows(an)
    rows += fatigue_rows(an)
    per = an.shoe_character_per_shoe
    if per:
        rows.append((f"shoe character (FE: normal force with/without friction at {per[0]['rpm']:.0f} rpm)",
                     "; ".join(f"shoe {p['shoe']}: {p['character']} (N ratio {p['normal_force_ratio']:.2f})"
                               for p in per)))
    else:
        rows.append(("shoe character (FE, friction on vs off)", an.shoe_character))
    s = an.mu_sensitivity
    t = s.get("torque_Nm", {})
    gone = s.get("not_available") or {}
    if ("x0.7" in t or "x0.7" in gone) and ("x1.3" in t or "x1.3" in gone):
        pct = s.get("torque_change_pct", {})
        rows.append((f"torque at {s['rpm']:.0f} rpm, mu x0.7 / x1.0 / x1.3 (mu = {an.mu:.3g})",
                     " / ".join(f"{t[k]:.2f}" if k in t else "n/a" for k in ("x0.7", "x1.0", "x1.3")) + " N m"
                     + (f" ({pct['x0.7']:+.0f} % / {pct['x1.3']:+.0f} %)" if pct else "")))
        sl = s.get("slip_rpm", {})
        rows.append(("slip speed, mu x0.7 / x1.0 / x1.3",
                     " / ".join("n/a" if k in gone else _fmt(sl.get(k), ".0f", "rpm") if sl.get(k) is not None
                                else "none" for k in ("x0.7", "x1.0", "x1.3"))))
        for k, why in gone.items():
            rows.append((f"mu sensitivity {k}", f"not available: {why}"))
    m = an.torque_models_at_max_engine_torque_Nm
    if getattr(an, "analytical_available", True):
        rows.append((f"torque at {m['rpm']:.0f} rpm: FE / analytical FE arc / analytical nominal arc",
                     " / ".join(_fmt(m[k], ".2f", "") or "-" for k in
                                ("fe_torque_Nm", "analytic_fe_arc_Nm", "analytic_nominal_arc_Nm")) + " N m"))
        nominal = an.coupling.get("phi2_deg", math.nan) - an.coupling.get("phi1_deg", math.nan)
        rows.append((f"contact arc per shoe at {m['rpm']:.0f} rpm (nominal shoe arc)",
                     f"{an.contact_arc_at_max_engine_torque_deg:.2f} deg{_arc_err(an, m['rpm'])} ({nominal:.0f} deg)"))
    else:
        rows.append(("analytical shoe model (eqs 2-8)",
                     "not computed (live: --fidelity best gives it)" if live
                     else "not available (user mesh: no shoe pivot or nominal shoe arc)"))
        arc = an.contact_arc_at_max_engine_torque_deg
        rows.append((f"contact arc of shoe 0 at {m['rpm']:.0f} rpm",
                     f"{arc:.2f} deg{_arc_err(an, m['rpm'])}" if arc is not None and math.isfinite(arc)
                     else "- (not given live: --fidelity best gives it)" if an.answered_by == "reduced model"
                     else "-"))
    part = getattr(an, "part", None) or {}
    if "mass_kg" in part:
        rows.append((f"part mass (mesh area x rho x thickness {part['thickness_m'] * 1e3:g} mm)",
                     _fmt(part["mass_kg"] * 1e3, ".1f", "g")))
        if part.get("shoes"):
            rows.append(("shoe zone mass / centre-of-mass radius (from the mesh)",
                         "; ".join(f"shoe {s_['shoe']}: {s_['mass_kg'] * 1e3:.2f} g / {s_['R_Tp_m'] * 1e3:.2f} mm"
                                   for s_ in part["shoes"])))
    wh = getattr(an, "whirl", None) or {}
    if wh:
        rows.append(("crankshaft first critical speed (whirl; drum, sprocket, crankshaft ASSUMED)",
                     f"{wh['rpm_crit_lowest']:,.0f} rpm ({100 * wh['margin']:+.0f} % over {wh['max_engine_rpm']:,.0f} rpm)"))
    eng_chk = req.get("engagement_checked_rpm")
    rows.append((f"requirement: engagement > a x idle = {req['a']:g} x {req['idle_rpm']:.0f} rpm",
                 ("PASS" if req["engagement_ok"] else "FAIL")
                 + (f" ({eng_chk:.0f} rpm vs {req['engagement_limit_rpm']:.0f} rpm)" if eng_chk else "")))
    rows.append((f"requirement: slip < b x rpm(max torque) = {req['b']:g} x {req['rpm_max_torque']:.0f} rpm",
                 ("PASS" if req["slip_ok"] else "FAIL")
                 + (f" ({an.slip_rpm:.0f} rpm vs {req['slip_limit_rpm']:.0f} rpm)" if an.slip_rpm is not None
                    else f" ({an.slip_status})")))
    return rows


def _arc_err(an, rpm: float) -> str:
    """' +- x deg' of the contact arc at the sweep speed ``rpm`` (its ends between nodes)."""
    c = an.curves
    if "contact_arc_error_deg" not in c:
        return ""
    k = int(np.argmin(np.abs(c["rpm"].to_numpy(dtype=float) - rpm)))
    return f" +- {float(c['contact_arc_error_deg'].iloc[k]):.2f} deg"


def fatigue_rows(an) -> list[tuple[str, str]]:
    """Rows of the fatigue check (analyze step 10): safety factor, where and what governs, cycles counted."""
    f = getattr(an, "fatigue", None) or {}
    if not f:
        return []
    if not f.get("available", True):
        return [("fatigue safety factor", "not available: " + f.get("reason", ""))]
    sf = an.fatigue_safety_factor
    val = "infinite (no stress changes)" if sf is None or not math.isfinite(sf) else f"{sf:.2f} (-)"
    if sf is not None and sf < 1:
        val += "  BELOW 1"
    rows = [("fatigue safety factor (load multiplier to Miner sum 1; Goodman, S_e "
             f"{f['endurance_limit_Pa'] / 1e6:.0f} MPa, {f['params']['edge_finish']} edges)", val),
            ("fatigue: worst point", str(an.fatigue_location)),
            ("fatigue: governing cycle", str(an.fatigue_governing_cycle))]
    cyc = f.get("cycles", {})
    if cyc:
        rows.append(("fatigue cycles counted", f"{cyc['start_stops']:.3g} start-stops (0 -> {cyc['max_speed_rpm']:.0f} rpm "
                     f"-> 0), {cyc['revolutions']:.3g} revolutions at {cyc['operating_rpm']:.0f} rpm (ripple + load "
                     f"torque, mean {cyc['cutting_torque_Nm']:.2f} N m)"))
    return rows


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
    """Plots (torque vs rpm; contact arc and stress vs rpm), the curves CSV and the JSON."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    files = [torque_plot(an, engine, out / f"{name}_torque_rpm.png", f"{name}: torque vs engine speed (drum held)"),
             arc_stress_plot(an, out / f"{name}_arc_stress_rpm.png", f"{name}: contact arc and peak stress vs rpm")]
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
