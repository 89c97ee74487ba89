"""The drawing sheet for review (A3 landscape, PDF/SVG/PNG, pyplot-free matplotlib): the part
at scale with its key dimensions, the parameter table, the process and tolerances, the
measured features and the predicted answers with their bands.

Left: the whole part in the final frame (every shoe), the drum circle it runs in (dash-dot),
the tool path (thin red, when a process is chosen), dimensions of the outer radius (drum
radius minus clearance), the drum and the bore, and callouts at the smallest inside radius,
slot and web with their sizes.  Right: the concept's parameters (as in ``--set``), the
process rules and the general tolerance, the predicted answers (engagement static and with
ripple, slip, peak stress and safety factor at the engine's maximum speed, part mass), each
with its error band, the as-cut table when computed, and the title block (label, hash,
material, thickness, unit, date, clutchfem version).  Dimensions are in the sheet's unit
(mm, or inches with ``units="in"``).
"""

from __future__ import annotations

import datetime as _dt
import math
from pathlib import Path

import numpy as np

from .._version import __version__
from ..core import figure
from ..geometry import fmt_param_value

A3 = (16.54, 11.69)


def _u(x_m: float, units: str, digits: int = 3) -> str:
    return f"{x_m / 0.0254:.{digits + 1}f} in" if units == "in" else f"{x_m * 1e3:.{digits}f} mm"


def _band(an, key: str, scale: float = 1.0, unit: str = "rpm", fmt: str = ".0f") -> str:
    e = (getattr(an, "errors", None) or {}).get(key) or {}
    v = getattr(an, key, None)
    if v is None:
        return "-"
    tot = e.get("total")
    return f"{v * scale:{fmt}} {unit}" + (f" +- {tot * scale:{fmt}}" if tot is not None else "")


def draw_sheet(paths, *, outline, features, rules, toolpath, label: str, design_hash: str, material: str,
               analysis=None, as_cut=None, units: str = "mm", violations=()) -> list[Path]:
    """Draw the sheet once and save it to every path in ``paths`` (.pdf, .svg, .png)."""
    fig, _ = figure(1, 1, figsize=A3)
    fig.clear()
    ax = fig.add_axes([0.02, 0.06, 0.56, 0.88])
    s = 1e3 if units == "mm" else 1 / 0.0254
    p = outline.params
    for lp in outline.loops:
        xy = lp.points(spacing=0.05e-3) * s
        xy = np.vstack([xy, xy[:1]])
        ax.plot(xy[:, 0], xy[:, 1], color="black", lw=0.9)
    for lp in toolpath or ():
        xy = lp.points(spacing=0.05e-3) * s
        xy = np.vstack([xy, xy[:1]])
        ax.plot(xy[:, 0], xy[:, 1], color="#c0392b", lw=0.4, ls="-")
    R = p.drum_radius * s
    th = np.linspace(0, 2 * np.pi, 721)
    ax.plot(R * np.cos(th), R * np.sin(th), color="#888", lw=0.6, ls="-.")
    ax.plot([-1.2 * R, 1.2 * R], [0, 0], color="#aaa", lw=0.4, ls="-.")
    ax.plot([0, 0], [-1.2 * R, 1.2 * R], color="#aaa", lw=0.4, ls="-.")
    ro = outline.max_radius()
    a = math.radians(200)
    _dim(ax, (0, 0), (ro * s * math.cos(a), ro * s * math.sin(a)), f"R {_u(ro, units)} (drum - clearance)")
    a = math.radians(135)
    _dim(ax, (0, 0), (R * math.cos(a), R * math.sin(a)), f"drum R {_u(p.drum_radius, units)}", color="#777")
    rb = p.bore_radius * s
    ax.annotate(f"bore Ø {_u(2 * p.bore_radius, units)}", (rb * math.cos(-0.8), rb * math.sin(-0.8)),
                (0.45 * R, -0.55 * R), fontsize=8, arrowprops={"arrowstyle": "->", "lw": 0.6})
    callouts = []
    for kind, feats in features.items():
        useful = [f for f in feats if not f.where.startswith("bore") and (kind != "inside radius" or f.detail == "fillet")]
        callouts += useful[:1]
    callouts.sort(key=lambda f: f.at[0])
    n = len(callouts)
    for k, f in enumerate(callouts):  # a row of labels under the part, in the order of their x
        x, y = f.at[0] * s, f.at[1] * s
        tx = (-1.0 + 2.0 * k / max(n - 1, 1)) * R if n > 1 else 0.0
        ty = -1.38 * R - 0.14 * R * (k % 2)
        ax.annotate(f.text(), (x, y), (tx, ty), fontsize=7.5, color="#1f4e79", ha="center", va="top",
                    arrowprops={"arrowstyle": "->", "lw": 0.5, "color": "#1f4e79"})
        ax.plot([x], [y], "o", ms=3, color="#1f4e79")
    ax.set_aspect("equal")
    lim = 1.75 * R
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, 1.3 * R)
    ax.axis("off")
    ax.set_title(f"{label}: the whole part, {outline.thickness * 1e3:g} mm thick, viewed from the engine side "
                 f"(ccw rotation)\nunit {units}; black: part (DXF layers OUTER/INNER/BORE)"
                 + ("; red: tool path (kerf-compensated)" if toolpath else "")
                 + "; dash-dot: drum", fontsize=9)
    _tables(fig, outline, rules, label, design_hash, material, analysis, as_cut, units, violations)
    out = []
    for path in paths:
        path = Path(path)
        fig.savefig(path, dpi=110 if path.suffix.lower() == ".png" else 150)
        out.append(path)
    return out


def _dim(ax, p0, p1, text: str, color: str = "black") -> None:
    ax.annotate("", p1, p0, arrowprops={"arrowstyle": "<->", "lw": 0.6, "color": color})
    ax.text(0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1]), text, fontsize=7, color=color, ha="center",
            va="bottom", rotation=math.degrees(math.atan2(p1[1] - p0[1], p1[0] - p0[0])) % 180 - 0,
            rotation_mode="anchor")


def _tables(fig, outline, rules, label, design_hash, material, an, as_cut, units, violations) -> None:
    p = outline.params
    P = type(p)
    rows = []
    for name in P.model_fields:
        if name.startswith("table_c") and p.profile != "table":
            continue
        if name == "clearance_tip" and p.profile != "linear":
            continue
        if name in ("eccentricity", "eccentric_angle") and p.profile != "eccentric":
            continue
        rows.append(f"{name} = {fmt_param_value(p, name)}")
    y = 0.95
    fig.text(0.60, y, "Design parameters (--set)", fontsize=9, weight="bold")
    col = 0
    for k, r in enumerate(rows):
        fig.text(0.60 + 0.19 * col, y - 0.018 * (1 + k % 20), r, fontsize=7, family="monospace")
        if k % 20 == 19:
            col += 1
    y -= 0.018 * (min(len(rows), 20) + 2)
    fig.text(0.60, y, "Process and tolerances", fontsize=9, weight="bold")
    lines = []
    if rules is not None:
        lim = rules.limits(outline.thickness)
        lines += [f"{rules.process}: kerf {_u(rules.kerf, units)} (tool path offset {_u(rules.kerf / 2, units)})",
                  f"limits: inside radius >= {_u(lim['min_inside_radius'], units)}, slot >= "
                  f"{_u(lim['min_slot'], units)}, web >= {_u(lim['min_web'], units)}",
                  f"profile tolerance +- {_u(rules.tolerance, units)}; kerf error +- {_u(rules.kerf_error, units)}"
                  + (f"; taper {_u(rules.taper, units)}" if rules.taper else ""),
                  rules.sources()]
    else:
        lines += ["no process chosen: nominal contour only, no manufacturability check (--process)"]
    lines += [f"general tolerance of the contour: +- {_u(rules.tolerance if rules else 0.05e-3, units)}; "
              f"thickness {_u(outline.thickness, units)} (plate)",
              f"contact surface (shoe outer profile): R {_u(outline.max_radius(), units)} to the axis; "
              f"clearance to the drum {_u(p.clearance, units)}"]
    lines += [f"NOT CUTTABLE: {v}" for v in violations]
    for k, t in enumerate(lines):
        fig.text(0.60, y - 0.018 * (k + 1), t, fontsize=7, color="#c0392b" if t.startswith("NOT") else "black")
    y -= 0.018 * (len(lines) + 2)
    fig.text(0.60, y, "Predicted answers (FE, plane stress; +- error band: discretisation + model form)",
             fontsize=9, weight="bold")
    ans = []
    if an is not None:
        ans = [f"engagement (static): {_band(an, 'engagement_rpm')}",
               f"engagement with 2-stroke ripple: {an.engagement_rpm_with_ripple:.0f} rpm"
               if an.engagement_rpm_with_ripple is not None else "engagement with ripple: never engages",
               f"slip speed (drum held, full throttle): {_band(an, 'slip_rpm')}" if an.slip_rpm is not None
               else f"slip: {an.slip_status}",
               f"peak von Mises at {an.max_engine_rpm:.0f} rpm: {_band(an, 'max_von_mises_Pa', 1e-6, 'MPa')}; "
               f"safety factor {an.safety_factor:.2f}",
               f"part mass {an.part['mass_kg'] * 1e3:.1f} g ({material})"]
    else:
        ans = ["not analysed (export without --analysis)"]
    for k, t in enumerate(ans):
        fig.text(0.60, y - 0.018 * (k + 1), t, fontsize=7)
    y -= 0.018 * (len(ans) + 2)
    if as_cut:
        fig.text(0.60, y, "As cut (kerf error; same STEP mesh pipeline for every row)", fontsize=9, weight="bold")
        band = as_cut.get("band") or {}
        head = (f"{'variant':<26}{'engagement':>14}{'slip':>14}{'mass':>10}")
        fig.text(0.60, y - 0.018, head, fontsize=7, family="monospace")
        for k, r in enumerate(as_cut["rows"]):
            e = "-" if r["engagement_rpm"] is None else f"{r['engagement_rpm']:.0f} rpm"
            sl = "-" if r["slip_rpm"] is None else f"{r['slip_rpm']:.0f} rpm"
            fig.text(0.60, y - 0.018 * (k + 2), f"{r['variant']:<26}{e:>14}{sl:>14}{r['mass_kg'] * 1e3:>8.1f} g",
                     fontsize=7, family="monospace")
        if band:
            fig.text(0.60, y - 0.018 * (len(as_cut["rows"]) + 2),
                     f"discretisation band of this pipeline: engagement +- {band['engagement_rpm'] or 0:.0f} rpm, "
                     f"slip +- {band['slip_rpm'] or 0:.0f} rpm", fontsize=7)
    fig.text(0.60, 0.05, f"{label}   design hash {design_hash}   concept {outline.concept}   unit {units}",
             fontsize=8, weight="bold")
    fig.text(0.60, 0.032, f"material {material}", fontsize=7)
    fig.text(0.60, 0.015, f"clutchfem {__version__}   {_dt.date.today().isoformat()}   "
             "drawing for review: the DXF/STEP files are the geometry", fontsize=7, color="#555")
