"""The workshop drawing's text blocks (:mod:`.sheet` draws the views): the notes (general
tolerances, material and heat treatment, the DXF as the geometry master), the predicted
answers with their bands and the fidelity that answered, and the ISO 7200 title block with
its first-angle projection symbol; and the sheet's layout constants [mm] and text sizes [pt]."""

from __future__ import annotations

from matplotlib.patches import Circle, Polygon, Rectangle
from matplotlib.transforms import Bbox

from .._version import __version__

#: sheet size [mm] (A3 landscape) and the frame (ISO 5457: 20 mm filing margin, 10 mm others)
SHEET = (420.0, 297.0)
FRAME = (20.0, 10.0, 410.0, 287.0)
#: text sizes [pt]: dimensions, tables, headings
FS_DIM, FS_TAB, FS_HEAD = 8.5, 7.0, 9.0
#: the title block, notes and answers column and the detail box [mm]
TB = (238.0, 10.0, 410.0, 62.0)
COL_X = 240.0
DETAIL_BOX = (238.0, 166.0, 410.0, 287.0)


def _band(an, key: str, scale: float = 1.0, unit: str = "rpm", fmt: str = ".0f") -> str:
    e = (getattr(an, "errors", None) or {}).get(key) or {}
    v = getattr(an, key, None)
    if v is None:
        return "-"
    tot = e.get("total")
    return f"{v * scale:{fmt}} {unit}" + (f" ± {tot * scale:{fmt}} {unit}" if tot is not None else "")


def scale_text(s: float) -> str:
    return f"{s:g}:1" if s >= 1 else f"1:{1 / s:g}"



def general_tolerance(rules, units) -> str:
    if rules is None:
        return "ISO 2768-mK"
    t = rules.tolerance * 1e3 if units == "mm" else rules.tolerance / 0.0254
    return f"contour ±{t:g} {units} ({rules.process}); ISO 2768-mK otherwise"


def notes_block(sh, outline, rules, material, units, violations, ligament, dims) -> float:
    y = DETAIL_BOX[1] - 2
    sh.text(COL_X, y - 3, "NOTES", size=FS_HEAD, weight="bold", va="center")
    lines = [f"1. General tolerances: {general_tolerance(rules, units)}; angles ±0.5° unless stated.",
             f"2. Material: {material}.",
             "3. Cut from the DXF (layers OUTER, BORE"
             + (", TOOLPATH kerf-compensated" if rules is not None else "") + "): the DXF is the geometry;",
             "    dimensions are for inspection. Deburr all edges, do not round the contact face.",
             f"4. ( ): reference dimension. 3x: on each of the {getattr(outline.params, 'n_shoes', 1)} shoes. "
             f"Unit {units}.",
             ]
    if ligament is not None:
        lines.append(f"5. Thinnest ligament {_len(ligament.width, units)} {units} ({ligament.where}, r = "
                     f"{_len(ligament.radius, units)} {units}): no nicks or burrs there.")
    if rules is not None:
        lim = rules.limits(outline.thickness)
        lines.append(f"6. {rules.process}: kerf {_len(rules.kerf, units)} {units}; limits: inside radius >= "
                     f"{_len(lim['min_inside_radius'], units)}, slot >= {_len(lim['min_slot'], units)}, web >= "
                     f"{_len(lim['min_web'], units)} {units}.")
    lines += [f"NOT CUTTABLE: {v}" for v in violations]
    for k, t in enumerate(lines):
        sh.text(COL_X, y - 8 - 4.2 * k, t, size=FS_TAB - 0.5, va="center", gid=f"note:{k + 1}",
                color="#c0392b" if t.startswith("NOT") else "black")
    return y - 8 - 4.2 * len(lines)


def _len(x: float, units: str) -> str:
    v = x * 1e3 if units == "mm" else x / 0.0254
    return f"{v:.3f}".rstrip("0").rstrip(".")


def answers_block(sh, an, fidelity, ligament, as_cut, mass_kg, material, y: float) -> None:
    head = "PREDICTED ANSWERS" + (f" ({fidelity})" if fidelity else "")
    sh.text(COL_X, y, head, size=FS_HEAD - 0.5, weight="bold", va="center", gid="answers:head")
    rows = []
    if an is not None:
        rows = [("engagement (static)", _band(an, "engagement_rpm")),
                ("engagement with 2-stroke ripple", "never engages" if an.engagement_rpm_with_ripple is None
                 else f"{an.engagement_rpm_with_ripple:.0f} rpm"),
                ("slip speed (drum held, full throttle)", _band(an, "slip_rpm") if an.slip_rpm is not None
                 else an.slip_status),
                (f"peak von Mises at {an.max_engine_rpm:.0f} rpm", _band(an, "max_von_mises_Pa", 1e-6, "MPa")),
                ("safety factor (yield / peak)", f"{an.safety_factor:.2f}")]
    else:
        rows = [("answers", "not analysed (export --no-analysis)")]
    if ligament is not None:
        rows.append(("thinnest ligament", f"{ligament.width * 1e3:.3f} mm at r = {ligament.radius * 1e3:.2f} mm, "
                                          f"{ligament.angle_deg:.1f}° ({ligament.where})"))
    if mass_kg is not None:
        rows.append(("part mass", f"{mass_kg * 1e3:.1f} g"))
    for k, (a, b) in enumerate(rows):
        yy = y - 5 - 4.0 * k
        sh.text(COL_X, yy, a, size=FS_TAB, va="center", gid=f"answer:{k + 1}:name")
        sh.text(COL_X + 58, yy, b, size=FS_TAB, va="center", gid=f"answer:{k + 1}")
    if as_cut:
        yy = y - 5 - 4.0 * len(rows) - 1
        for r in as_cut["rows"]:
            e = "-" if r["engagement_rpm"] is None else f"{r['engagement_rpm']:.0f} rpm"
            sl = "-" if r["slip_rpm"] is None else f"{r['slip_rpm']:.0f} rpm"
            sh.text(COL_X, yy, f"as cut, {r['variant']}: engagement {e}, slip {sl}, mass {r['mass_kg'] * 1e3:.1f} g",
                    size=FS_TAB - 0.5, va="center")
            yy -= 3.6
    sh.blocks.append(Bbox.from_extents(TB[0], TB[3], FRAME[2], DETAIL_BOX[1]))


def title_block(sh, title, design_hash, material, mass_kg, scale, units, date, gen_tol, outline) -> None:
    ax = sh.ax
    x0, y0, x1, y1 = TB
    ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, lw=1.0))
    rows = [y1 - 12, y1 - 22, y1 - 32, y1 - 42]
    for y in rows:
        ax.plot([x0, x1], [y, y], color="black", lw=0.5)

    def field(xa, xb, ya, yb, caption, value, key, size=FS_TAB + 0.5, **kw):
        ax.plot([xa, xa], [ya, yb], color="black", lw=0.5) if xa > x0 else None
        sh.text(xa + 1.2, yb - 2.2, caption, size=5.0, color="#444", va="center")
        sh.text(xa + 1.2, 0.5 * (ya + yb) - 1.2, value, size=size, va="center", gid=f"title:{key}", **kw)

    field(x0, x1, rows[0], y1, "TITLE", title, "title", size=FS_HEAD + 1, weight="bold")
    field(x0, x0 + 100, rows[1], rows[0], "DRAWING NO. (design hash)", design_hash, "drawing_number",
          family="monospace")
    field(x0 + 100, x1, rows[1], rows[0], "MASS", "-" if mass_kg is None else f"{mass_kg * 1e3:.1f} g", "mass")
    field(x0, x1, rows[2], rows[1], "MATERIAL AND HEAT TREATMENT", material, "material", size=FS_TAB)
    field(x0, x0 + 32, rows[3], rows[2], "SCALE", scale_text(scale), "scale")
    field(x0 + 32, x0 + 56, rows[3], rows[2], "UNITS", units, "units")
    field(x0 + 56, x0 + 92, rows[3], rows[2], "PROJECTION", "", "projection")
    _projection_symbol(ax, x0 + 74, 0.5 * (rows[3] + rows[2]) - 1.0)
    field(x0 + 92, x0 + 127, rows[3], rows[2], "DATE", date, "date")
    field(x0 + 127, x1, rows[3], rows[2], "THICKNESS", f"{_len(outline.thickness, units)} {units}", "thickness")
    field(x0, x0 + 118, y0, rows[3], "GENERAL TOLERANCES", gen_tol, "general_tolerances", size=FS_TAB - 0.5)
    field(x0 + 118, x1, y0, rows[3], "SHEET / SOFTWARE", f"1/1  clutchfem {__version__}", "software",
          size=FS_TAB - 0.5)


def _projection_symbol(ax, x, y) -> None:
    """ISO 128 / ISO 5456-2 first-angle projection symbol (truncated cone), ~4 mm high."""
    h = 4.0
    # the cone seen from the front, small end on the left; its view from the left (the small
    # end: both circles visible) is drawn on the right: first angle
    ax.add_patch(Polygon([(x - 7, y - h / 4), (x - 1, y - h / 2), (x - 1, y + h / 2), (x - 7, y + h / 4)],
                         closed=True, fill=False, lw=0.5, gid="projection:first-angle"))
    ax.add_patch(Circle((x + 4, y), h / 2, fill=False, lw=0.5))
    ax.add_patch(Circle((x + 4, y), h / 4, fill=False, lw=0.5))
    ax.plot([x - 8, x + 7], [y, y], color="black", lw=0.25, ls=(0, (6, 1.5, 1, 1.5)))
