"""The summary table of an analysed design: every answer a row of text with its unit and its
band (mesh and model form, the best path's corrections, or a live answer's own error)."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["summary_rows", "corrections_text", "model_row", "sensitivity_rows", "fatigue_rows"]


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
    >>> from clutchfem import Design, MeshSettings, analyze
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
    if "contact_arc_error_deg" not in an.curve_names:
        return ""
    c = an.curves
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
