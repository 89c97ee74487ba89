"""Charts and the terminal table of a guideline study (:mod:`.guidelines`).

* :func:`guideline_table`: a rich table, parameters ranked (then the operating inputs), the
  elasticity of each answer marked ``~`` (unstable: its check at ten times the step
  differs), ``?`` (unchecked: the wider step has no answer), ``1`` (one-sided: one side
  refused), ``k`` (a contact node enters or leaves inside the step: the answer kinks there;
  the row's ``E_left`` / ``E_right`` are the two sides), ``-`` (no answer), and the method of each row in words;
* :func:`oat_chart`: small multiples, one panel per parameter: each answer's change from the
  design point [%] against the parameter in its own unit (mm, deg) with its declared limits
  drawn, the design point marked (the answers' values in the legend), dotted where a design
  has no answer;
* :func:`elasticity_chart`: small multiples, one per answer: each parameter's (and
  operating input's) elasticity as a bar labelled with its value, the spread of the step
  check as its error bar, coloured by verdict, the method under each name.

Legends sit beside the panels (never on the data); parameters a design does not use (the
other profiles' controls) are not studied, and the charts say so under their title.

Figures are drawn with matplotlib's Agg canvas chosen inside :func:`clutchfem.core.figure`
(no backend is selected at import, no pyplot state is kept).
"""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np
from rich.markup import escape
from rich.table import Table

from ..core import figure, save_figure
from ..core.values import param_bounds
from ..geometry import get_concept
from ..guidelines import ANSWERS, CHECK_FACTOR, SHORT, STABLE_ABS, STABLE_REL, GuidelineResult
from ..studies import display_value
from ..studies.spec import axis_label

#: unit of each guideline answer (as its label states it)
UNITS = {"engagement_rpm": "rpm", "slip_rpm": "rpm", "torque_at_max_engine_torque_Nm": "N m",
         "max_von_mises_MPa": "MPa", "shoe_mass_g": "g", "contact_arc_deg": "deg"}


def short_method(method: str) -> str:
    """A table cell's short form of an elasticity's method (:func:`.guidelines.method_text`)."""
    if "operating input" in method:
        return "same mesh"
    if "meshed from scratch" in method:
        return "from scratch"
    return "morphed" if "morphed" in method else method[:24]


def guideline_table(res: GuidelineResult) -> Table:
    """A rich table: parameters ranked, then the operating inputs; elasticity of each answer
    (~: unstable derivative) and the method of each row.

    Parameters
    ----------
    res : GuidelineResult
        A guideline study's result (:func:`~clutchfem.run_guidelines`).

    Returns
    -------
    rich.table.Table
        One row per parameter: rank, name, design value (mm, deg), the elasticity of each
        answer with its marks (module docstring) and the method; print it with rich.

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.guidelines import ANSWERS, GuidelineResult
    >>> rows = [{"parameter": "flexure_thickness", "answer": a, "unit": "m", "x0": 0.0022, "E": 0.9,
    ...          "verdict": "stable", "method": "central difference on morphed meshes"} for a, _ in ANSWERS]
    >>> t = cf.guideline_table(GuidelineResult("concept1", {}, 0.02, rows, ["flexure_thickness"], oat=None))
    >>> [list(c.cells) for c in t.columns[:4]]
    [['1'], ['flexure_thickness'], ['2.2 mm'], ['+0.90']]
    """
    t = Table(title=escape(f"{res.concept}: elasticities (x / A) dA/dx at the design point"),
              caption=escape(f"engage: engagement rpm; slip: slip rpm; torque: at the rpm of max engine torque; "
                             f"stress: peak von Mises at max rpm; shoe m: shoe mass; arc: contact arc.  "
                             f"method: morphed = central difference on meshes morphed from the design; same mesh = "
                             f"an operating input on the design's own mesh; from scratch = a morph was refused "
                             f"(remeshing noise; the notes say why).  ~: unstable (E at {CHECK_FACTOR:g}x the step "
                             f"differs by more than {STABLE_ABS} + {STABLE_REL:.0%}); ?: unchecked (the wider step "
                             "has no answer); 1: one-sided (one side refused); k: a contact node enters or leaves inside the step (the "
                             "answer kinks there; both one-sided E in the JSON); -: no answer; rank -: an operating input (not "
                             "ranked)"))
    t.add_column("rank")
    t.add_column("parameter", no_wrap=True)
    t.add_column("value", justify="right")
    for col, _ in ANSWERS:
        t.add_column(SHORT[col], justify="right")
    t.add_column("method")
    rows = [(str(k), n) for k, n in enumerate(res.ranking, start=1)] + [("-", n) for n in res.inputs]
    for k, n in rows:
        cells = []
        unit = x0 = None
        for col, _ in ANSWERS:
            e = next(r for r in res.table if r["parameter"] == n and r["answer"] == col)
            unit, x0 = e["unit"], e["x0"]
            v = e["E"]
            mark = {"stable": "", "unchecked": "?", "unstable": "~"}.get(e["verdict"], "")
            side = ("1" if e["method"].startswith("one-sided") else "") + ("k" if "kink" in e else "")
            cells.append("-" if not math.isfinite(v) else f"{mark}{v:+.2f}{side}")
        shown = {"m": "mm", "-": ""}.get(unit, unit)
        t.add_row(k, escape(n), escape(f"{display_value(x0, unit):.4g} {shown}".strip()), *cells,
                  escape(short_method(res.methods.get(n, ""))))
    return t


#: colours of the one-at-a-time lines: matplotlib's tab10, then ten more of distinct hue and
#: lightness (a concept has up to 16 studied parameters: no colour repeats below 20)
COLOURS = ("C0", "C1", "C2", "C3", "C4", "C5", "C6", "C7", "C8", "C9",
           "#000000", "#b8860b", "#000080", "#00a08a", "#ff00ff", "#8b0000", "#556b2f", "#00ced1",
           "#ff7f50", "#4b0082")
#: marker cycle: a new marker for each round of the colours (80 parameters told apart)
MARKERS = ("o", "s", "^", "D")


def _style(j: int) -> dict:
    """Colour and marker of the j-th parameter (ranked): :data:`COLOURS`, a new marker each round."""
    return {"color": COLOURS[j % len(COLOURS)], "marker": MARKERS[(j // len(COLOURS)) % len(MARKERS)]}


def _value_text(v, col: str) -> str:
    """An answer's value with its unit, at the digits the tables show."""
    if v is None or not math.isfinite(v):
        return "no answer"
    unit = UNITS.get(col, "")
    fmt = {"rpm": ".0f", "MPa": ".0f", "N m": ".2f", "g": ".1f", "deg": ".2f"}.get(unit, ".3g")
    return f"{v:{fmt}} {unit}".strip()


def _footnote(res: GuidelineResult) -> str:
    off = [n for n in res.notes if n.startswith("not studied")]
    return ("\n" + off[0]) if off else ""


def _limits(concept: str, name: str, unit: str) -> tuple[float | None, float | None]:
    """The declared limits of parameter ``name`` of ``concept`` in the unit the chart shows
    (mm for lengths); (None, None) for an operating input or an unknown concept."""
    try:
        lo, hi = param_bounds(get_concept(concept).Params, name)
    except Exception:  # not a concept parameter (an operating input) or a concept no longer registered
        return None, None
    return (None if lo is None else display_value(float(lo), unit)), (None if hi is None else display_value(float(hi), unit))


def oat_chart(res: GuidelineResult, path: str | Path) -> Path:
    """Small multiples, one panel per parameter (ranked): each answer's change from its
    design-point value [%] against the parameter in its own unit (mm, deg), the design point
    marked, the parameter's declared limits drawn (the range outside them shaded, their values
    in the panel's title), dotted verticals where a design has no answer (refused or failed);
    the legend beside the panels names each answer with its design-point value and unit."""
    from matplotlib.lines import Line2D

    path = Path(path)
    oat = res.oat
    names = list(res.ranking)
    ncols = max(1, min(4, len(names)))
    nrows = max(1, math.ceil(len(names) / ncols))
    fig, axes = figure(nrows, ncols, figsize=(3.6 * ncols + 3.2, 3.0 * nrows + 1.2), layout="constrained",
                       squeeze=False)
    base = {col: next((r["value_at_x0"] for r in res.table if r["answer"] == col), None) for col, _ in ANSWERS}
    has_base = {col: v is not None and math.isfinite(v) and v != 0 for col, v in base.items()}
    for ax in axes.flat[len(names):]:
        ax.set_visible(False)
    for j, n in enumerate(names):
        ax = axes.flat[j]
        d = oat[oat["parameter"] == n].sort_values("value")
        unit = str(d["unit"].iloc[0]) if len(d) else "-"
        x = np.array([display_value(float(v), unit) for v in d["value"]], dtype=float)
        x0 = next((display_value(float(r["x0"]), unit) for r in res.table if r["parameter"] == n), math.nan)
        ok = (d["status"] == "ok").to_numpy()
        for k, (col, _) in enumerate(ANSWERS):
            if has_base[col]:
                y = 100.0 * (d[col].astype(float).to_numpy() / base[col] - 1.0)
                ax.plot(x[ok], y[ok], "-", marker=MARKERS[0], ms=3.5, lw=1.2, color=COLOURS[k])
        for xr in x[~ok]:
            ax.axvline(xr, color="0.4", lw=0.8, ls=":")
        ax.axhline(0.0, color="0.5", lw=0.6)
        ax.plot([x0], [0.0], "k*", ms=11, zorder=5)
        lo, hi = _limits(res.concept, n, unit)
        span = (float(np.nanmax(x)) - float(np.nanmin(x))) if len(x) else 1.0
        span = span or abs(x0) or 1.0
        left, right = float(np.nanmin(x, initial=x0)) - 0.08 * span, float(np.nanmax(x, initial=x0)) + 0.08 * span
        # a limit within a quarter of the studied span is drawn in the view; a farther one is named
        if lo is not None and lo >= left - 0.25 * span:
            left = min(left, lo - 0.04 * span)
            ax.axvspan(left, lo, color="0.85", zorder=0)
            ax.axvline(lo, color="k", lw=1.0, ls="--")
        if hi is not None and hi <= right + 0.25 * span:
            right = max(right, hi + 0.04 * span)
            ax.axvspan(hi, right, color="0.85", zorder=0)
            ax.axvline(hi, color="k", lw=1.0, ls="--")
        ax.set_xlim(left, right)
        shown = {"m": "mm", "-": ""}.get(unit, unit)
        lim = ", ".join(t for t in (f">= {lo:.4g} {shown}".strip() if lo is not None else "",
                                    f"<= {hi:.4g} {shown}".strip() if hi is not None else "") if t)
        ax.set_title(f"{n}: design {x0:.4g} {shown}".strip() + (f"\nlimits {lim}" if lim else "\nno declared limits"),
                     fontsize=8)
        ax.set_xlabel(axis_label(n, unit), fontsize=8)
        ax.set_ylabel("answer change from the design point [%]", fontsize=8)
        ax.grid(alpha=0.3)
        ax.tick_params(labelsize=7)
    handles = [Line2D([], [], lw=1.2, ms=4, marker=MARKERS[0], color=COLOURS[k],
                      label=f"{label}: design point {_value_text(base[col], col)}" if has_base[col]
                      else f"{label}: no answer at the design point (not drawn)")
               for k, (col, label) in enumerate(ANSWERS)]
    handles += [Line2D([], [], color="k", marker="*", ls="", ms=9, label="design point"),
                Line2D([], [], color="k", ls="--", lw=1.0, label="declared limit (shaded: outside)"),
                Line2D([], [], color="0.4", ls=":", lw=0.8, label="no answer there\n(refused or failed)")]
    fig.legend(handles=handles, loc="outside right upper", fontsize=8, title="answer (its value at the design point)",
               title_fontsize=8)
    width = fig.get_figwidth()  # the note of the parameters not studied wrapped to the figure (~11 characters an inch)
    note = "\n".join(textwrap.fill(line, int(11 * width)) for line in _footnote(res).split("\n"))
    fig.suptitle(f"{res.concept}: one parameter at a time around the design point" + note, fontsize=10)
    return save_figure(fig, path)


def elasticity_chart(res: GuidelineResult, path: str | Path) -> Path:
    """Small multiples, one per answer: the elasticity of each parameter (ranked) as a bar
    labelled with its value, the spread of the step check as its error bar, coloured by
    verdict (the legend beside the panels)."""
    from matplotlib.patches import Patch

    path = Path(path)
    fig, axes = figure(2, 3, figsize=(15.0, 8.0), layout="constrained", squeeze=False)
    names = list(res.ranking) + list(res.inputs)
    colour = {"stable": "C0", "unchecked": "C1"}
    for k, (col, label) in enumerate(ANSWERS):
        ax = axes.flat[k]
        rows = [next(r for r in res.table if r["parameter"] == n and r["answer"] == col) for n in names]
        e = np.array([r["E"] for r in rows], dtype=float)
        sp = np.array([r["spread"] for r in rows], dtype=float)
        y = np.arange(len(names))
        ax.barh(y, np.nan_to_num(e), xerr=np.nan_to_num(sp), color=[colour.get(r["verdict"], "0.7") for r in rows],
                ecolor="0.3", capsize=2)
        span = max(float(np.nanmax(np.abs(np.nan_to_num(e) + np.nan_to_num(sp)), initial=0.0)),
                   float(np.nanmax(np.abs(np.nan_to_num(e) - np.nan_to_num(sp)), initial=0.0)), 0.1)
        for yy, v, d in zip(y, e, sp):
            if not math.isfinite(v):
                ax.text(0.02 * span, yy, "no answer", va="center", ha="left", fontsize=7)
                continue
            end = v + math.copysign(np.nan_to_num(d) + 0.03 * span, v if v != 0 else 1.0)
            ax.text(end, yy, "0.00" if abs(v) < 0.005 else f"{v:+.2f}", va="center",
                    ha="left" if v >= 0 else "right", fontsize=7)
        ax.set_xlim(-1.35 * span, 1.35 * span)
        ax.set_yticks(y, [f"{n} ({short_method(res.methods.get(n, ''))})" for n in names], fontsize=6)
        ax.invert_yaxis()
        ax.axvline(0, color="0.3", lw=0.8)
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("elasticity (x / A) dA/dx [-]", fontsize=8)
        ax.grid(alpha=0.3, axis="x")
        ax.tick_params(labelsize=7)
    handles = [Patch(color="C0", label="stable"), Patch(color="C1", label="unchecked\n(the wider step\nhas no answer)"),
               Patch(color="0.7", label=f"unstable: E at\n{CHECK_FACTOR:g}x the step differs")]
    fig.legend(handles=handles, loc="outside right upper", fontsize=8, title=f"verdict; error bar:\n|E - E at "
               f"{CHECK_FACTOR:g}x step|\n\nmethod under each name:\nmorphed: central difference\non morphed meshes\n"
               "same mesh: operating\ninput, design's mesh\nfrom scratch: morph\nrefused (notes)", title_fontsize=8)
    fig.suptitle(f"{res.concept}: elasticities (x / A) dA/dx at the design point (1 % more parameter: E % more answer)"
                 + _footnote(res), fontsize=10)
    return save_figure(fig, path)


def draw_guideline_charts(result: GuidelineResult) -> GuidelineResult:
    """Draw a guideline study's charts into its folder (``one_at_a_time.png``,
    ``elasticities.png``) and record them in its ``guidelines.json``.

    Parameters
    ----------
    result : GuidelineResult
        From :func:`~clutchfem.run_guidelines`.

    Returns
    -------
    GuidelineResult
        The same result with the chart files added to its record.

    Examples
    --------
    >>> import clutchfem as cf, dataclasses, tempfile
    >>> from clutchfem.guidelines import GuidelineSettings
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> gs = dataclasses.replace(GuidelineSettings.from_design(d, ["clearance"], points=3, inputs=[]), errors=False)
    >>> g = cf.run_guidelines(gs, tempfile.mkdtemp(), workers=0, progress=False)
    >>> [f.name for f in cf.draw_guideline_charts(g).files if f.suffix == ".png"]
    ['one_at_a_time.png', 'elasticities.png']
    """
    out = result.out
    return result.with_files([oat_chart(result, out / "one_at_a_time.png"),
                              elasticity_chart(result, out / "elasticities.png")])
