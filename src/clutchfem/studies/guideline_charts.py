"""Charts and the terminal table of a guideline study (:mod:`.guidelines`).

* :func:`summary_table`: a rich table, parameters ranked, the elasticity of each answer
  marked ``~`` (unstable derivative), ``?`` (unchecked: a step has no answer), ``1``
  (one-sided: one side refused), ``-`` (no answer);
* :func:`oat_chart`: small multiples, one panel per answer: the answer against x / x0 for
  every parameter (one at a time), dotted where a design has no answer;
* :func:`elasticity_chart`: small multiples, one per answer: each parameter's elasticity
  as a bar with the spread of the step check as its error bar, coloured by verdict.

Figures are drawn with matplotlib's Agg canvas chosen inside :func:`clutchfem.core.figure`
(no backend is selected at import, no pyplot state is kept).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from rich.markup import escape
from rich.table import Table

from ..core import figure
from .guidelines import ANSWERS, SHORT, STABLE_ABS, STABLE_REL, GuidelineResult
from .spec import display_value


def summary_table(res: GuidelineResult):
    """A rich table: parameters ranked, elasticity of each answer (~: unstable derivative)."""
    t = Table(title=escape(f"{res.concept}: elasticities d ln(answer) / d ln(parameter) at the design point"),
              caption=escape(f"engage: engagement rpm; slip: slip rpm; torque: at the rpm of max engine torque; "
                             f"stress: peak von Mises at max rpm; shoe m: shoe mass; arc: contact arc.  "
                             f"Step h = {res.step:.0%}; ~: unstable (E at h/2, 2h or the fit differs from E at h "
                             f"by more than {STABLE_ABS} + {STABLE_REL:.0%}); ?: unchecked (a step has no answer); "
                             "1: one-sided (one side refused); -: no answer"))
    t.add_column("rank")
    t.add_column("parameter", no_wrap=True)
    t.add_column("value", justify="right")
    for col, _ in ANSWERS:
        t.add_column(SHORT[col], justify="right")
    for k, n in enumerate(res.ranking, start=1):
        cells = []
        unit = x0 = None
        for col, _ in ANSWERS:
            e = next(r for r in res.table if r["parameter"] == n and r["answer"] == col)
            unit, x0 = e["unit"], e["x0"]
            v = e["E"]
            mark = {"stable": "", "unchecked": "?", "unstable": "~"}.get(e["verdict"], "")
            side = "" if e["method"] == "central" else "1"
            cells.append("-" if not math.isfinite(v) else f"{mark}{v:+.2f}{side}")
        shown = {"m": "mm", "-": ""}.get(unit, unit)
        t.add_row(str(k), escape(n), escape(f"{display_value(x0, unit):.4g} {shown}".strip()), *cells)
    return t


def oat_chart(res: GuidelineResult, path: str | Path) -> Path:
    """Small multiples, one panel per answer: the answer against x / x0 for every parameter."""
    from matplotlib import colormaps

    path = Path(path)
    oat = res.oat
    cmap = colormaps["tab20"]
    fig, axes = figure(2, 3, figsize=(14.0, 7.5), squeeze=False)
    for k, (col, label) in enumerate(ANSWERS):
        ax = axes.flat[k]
        for j, n in enumerate(res.ranking):
            d = oat[oat["parameter"] == n]
            okd = d[d["status"] == "ok"]
            y = okd[col].astype(float)
            colour = cmap((2 * j) % 20 + (j // 10) % 2)
            ax.plot(okd["relative"], y, "-o", ms=3, lw=1.1, color=colour, label=n if k == 0 else None)
            bad = d[d["status"] != "ok"]
            if len(bad):
                for xr in bad["relative"]:
                    ax.axvline(xr, color=colour, lw=0.5, ls=":", alpha=0.6)
        ax.axvline(1.0, color="0.3", lw=0.8)
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("parameter / design value [-]", fontsize=8)
        ax.grid(alpha=0.3)
        ax.tick_params(labelsize=7)
    axes.flat[0].legend(fontsize=7, loc="best")
    fig.suptitle(f"{res.concept}: one parameter at a time around the design point (dotted: no answer there)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path


def elasticity_chart(res: GuidelineResult, path: str | Path) -> Path:
    """Small multiples, one per answer: the elasticity of each parameter as a bar with the
    spread of the step check as its error bar (hatched: unstable)."""
    path = Path(path)
    fig, axes = figure(2, 3, figsize=(14.0, 7.5), squeeze=False)
    names = res.ranking
    for k, (col, label) in enumerate(ANSWERS):
        ax = axes.flat[k]
        rows = [next(r for r in res.table if r["parameter"] == n and r["answer"] == col) for n in names]
        e = np.array([r["E"] for r in rows], dtype=float)
        sp = np.array([r["spread"] for r in rows], dtype=float)
        y = np.arange(len(names))
        colours = [{"stable": "C0", "unchecked": "C1"}.get(r["verdict"], "0.7") for r in rows]
        ax.barh(y, np.nan_to_num(e), xerr=np.nan_to_num(sp), color=colours, ecolor="0.3", capsize=2,
                hatch=None)
        ax.set_yticks(y, names, fontsize=7)
        ax.invert_yaxis()
        ax.axvline(0, color="0.3", lw=0.8)
        ax.set_title(f"{label}: d ln A / d ln x", fontsize=9)
        ax.grid(alpha=0.3, axis="x")
        ax.tick_params(labelsize=7)
    fig.suptitle(f"{res.concept}: elasticities at the design point (blue: stable; orange: unchecked, a step "
                 f"refused; grey: unstable against mesh noise; error bar: spread of E over h/2, 2h and the fit)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path
