"""Charts of a study: every answer against every varied input, and parallel coordinates.

* :func:`answers_vs_inputs`: one PNG per varied input, small multiples (one panel per
  answer: engagement static and with ripple, slip speed, torque at the rpm of maximum engine
  torque, peak von Mises and safety factor at the engine's maximum speed, shoe and part
  mass, contact arc), the requirement limits drawn as dashed lines and named with their
  value in the panel's title (a x idle, b x rpm of max torque, the engine's maximum torque,
  yield / min safety factor), feasible designs filled, the rest hollow; a refused or failed
  design has no answer and is not drawn as one: an x on the x axis line (in its series'
  colour) marks its input value; the legend sits under the panels;
* :func:`parallel_coordinates`: one line per answered design over the varied inputs and
  the main answers (each axis scaled to its own range, its ends labelled with units),
  feasible designs in green, the others coloured by their largest requirement shortfall
  (a colour bar in %: how far the nearest miss is from meeting every requirement); the
  title counts them and names the requirement that failed most often.

Figures are drawn with matplotlib's Agg canvas chosen inside :func:`clutchfem.core.figure`
(no backend is selected at import, no pyplot state is kept).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ..core import figure, save_figure
from ..evaluation import ANSWERS
from ..studies import StudyResult, display_value

#: panels of the answers-vs-input charts: (columns drawn, title, limit column, limit label)
PANELS = (
    (("engagement_rpm", "engagement_ripple_rpm"), "engagement [rpm]", "engagement_limit_rpm", "a x idle"),
    (("slip_rpm",), "slip speed [rpm]", "slip_limit_rpm", "b x rpm(max torque)"),
    (("torque_at_max_engine_torque_Nm",), "torque at rpm of max engine torque [N m]", "max_engine_torque_Nm",
     "engine max torque"),
    (("max_von_mises_MPa",), "peak von Mises at max rpm [MPa]", "_stress_limit", "yield / min SF"),
    (("safety_factor",), "safety factor at max rpm [-]", "min_safety_factor", "min SF"),
    (("shoe_mass_g",), "shoe mass [g]", None, None),
    (("part_mass_g",), "part mass [g]", None, None),
    (("contact_arc_deg",), "contact arc at max engine torque [deg]", None, None),
)


def _x(frame, axis):
    """(x values as floats, tick labels or None) of a varied input; choices become indices."""
    raw = [json.loads(p).get(axis.name) for p in frame["point_json"]]
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in raw):
        return np.array([display_value(v, axis.unit) for v in raw], dtype=float), None
    cats = list(dict.fromkeys(str(v) for v in raw))
    return np.array([cats.index(str(v)) for v in raw], dtype=float), cats


def _limit(frame, col):
    if col == "_stress_limit":
        y, s = frame["yield_strength_MPa"], frame["min_safety_factor"]
        v = (y / s.where(s > 0)).dropna()
    elif col is None or col not in frame:
        return None
    else:
        v = frame[col].dropna()
    return float(v.iloc[0]) if len(v) else None


def _groups(frame, axis, spec):
    """Series of one chart: rows that differ only in ``axis`` (one line each), and a colour
    per row from the first other varied input (discrete for <= 8 values, else a colour map)."""
    from matplotlib import colormaps

    others = [a for a in spec.axes if a.name != axis.name]
    pts = [json.loads(p) for p in frame["point_json"]]
    keys = [tuple(str(p.get(a.name)) for a in others) for p in pts]
    series: dict = {}
    for i, k in enumerate(keys):
        series.setdefault(k, []).append(i)
    if not others:
        return series, ["C0"] * len(pts), [], None
    g = others[0]
    gv, cats = _x(frame, g)
    distinct = sorted(set(gv.tolist()))
    if len(distinct) <= 8:
        colours = [f"C{distinct.index(v)}" for v in gv]
        handles = [(f"C{k}", f"{g.label()} = {cats[int(v)] if cats else f'{v:.4g}'}") for k, v in enumerate(distinct)]
        return series, colours, handles, None
    cmap = colormaps["viridis"]
    lo, hi = min(distinct), max(distinct)
    colours = [cmap((v - lo) / (hi - lo)) for v in gv]
    return {k: [i] for k, idx in series.items() for i in idx}, colours, [], (g, lo, hi)


def answers_vs_inputs(frame, spec, outdir: str | Path) -> list[Path]:
    """One PNG per varied input (see module docstring); returns the paths."""
    from matplotlib.lines import Line2D

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    ok = (frame["status"] == "ok").to_numpy()
    feas = (frame["feasible"].fillna(0).astype(int) == 1).to_numpy()
    bad = ~ok
    paths = []
    for axis in spec.axes:
        x, cats = _x(frame, axis)
        series, colours, handles, cmap_info = _groups(frame, axis, spec)
        ncol = 4
        nrow = math.ceil(len(PANELS) / ncol)
        fig, axes = figure(nrow, ncol, figsize=(4.2 * ncol, 3.4 * nrow + 0.9), layout="constrained", squeeze=False)
        for k, (cols, title, lim_col, lim_label) in enumerate(PANELS):
            ax = axes.flat[k]
            for j, col in enumerate(cols):
                y = frame[col].to_numpy(dtype=float)
                mk = "o" if j == 0 else "^"
                for idx in series.values():
                    idx = [i for i in idx if ok[i]]
                    if not idx:
                        continue
                    idx = sorted(idx, key=lambda i: x[i])
                    c = colours[idx[0]]
                    if len(idx) > 1:
                        ax.plot(x[idx], y[idx], color=c, lw=0.9, alpha=0.6, ls="-" if j == 0 else ":")
                    for i in idx:
                        ax.scatter([x[i]], [y[i]], marker=mk, s=24, zorder=3, edgecolors=[colours[i]],
                                   facecolors=[colours[i]] if feas[i] else "none", linewidths=1.1)
            lim = _limit(frame, lim_col)
            head = title + ("  (o static, ^ with ripple)" if len(cols) > 1 else "")
            if lim is not None and math.isfinite(lim):
                ax.axhline(lim, color="C3", ls="--", lw=1.2)
                head += f"\n- - {lim_label} = {_fmt_limit(lim, title)}"
            if bad.any():  # no answer there: marked on the x axis line, never at a value
                ax.scatter(x[bad], np.zeros(int(bad.sum())), marker="x", s=36, linewidths=1.6, zorder=5,
                           c=[colours[i] for i in np.nonzero(bad)[0]], clip_on=False,
                           transform=ax.get_xaxis_transform())
            ax.set_title(head, fontsize=9)
            ax.set_xlabel(axis.label(), fontsize=8)
            ax.set_ylabel(title, fontsize=8)
            ax.tick_params(labelsize=7)
            if cats is not None:
                ax.set_xticks(range(len(cats)), cats)
            ax.grid(alpha=0.3)
        legend = [Line2D([], [], color=c, marker="o", lw=0.9, label=lab) for c, lab in handles]
        legend += [Line2D([], [], ls="", marker="o", color="0.3", label="feasible (filled)"),
                   Line2D([], [], ls="", marker="o", mfc="none", color="0.3", label="not feasible (hollow)"),
                   Line2D([], [], color="C3", ls="--", label="requirement limit")]
        if bad.any():
            legend.append(Line2D([], [], color="0.3", ls="", marker="x", mew=1.6,
                                 label=f"on the x axis: refused / failed ({int(bad.sum())}), no answer"))
        if cmap_info is not None:
            g, lo, hi = cmap_info
            legend.append(Line2D([], [], ls="", label=f"colour: {g.label()} {lo:.4g} (purple) .. {hi:.4g} (yellow)"))
        fig.legend(handles=legend, loc="outside lower center", ncol=min(4, len(legend)), fontsize=8)
        for ax in list(axes.flat)[len(PANELS):]:
            ax.set_visible(False)
        nfeas = int((ok & feas).sum())
        fig.suptitle(f"{spec.design}: answers vs {axis.label()} ({int(ok.sum())} answered, {nfeas} feasible, "
                     f"{int(bad.sum())} refused/failed)", fontsize=10)
        path = outdir / f"answers_vs_{axis.name}.png"
        save_figure(fig, path)
        paths.append(path)
    return paths


def _fmt_limit(v: float, title: str) -> str:
    """A limit with the unit of its panel (rpm, N m, MPa or none)."""
    unit = title[title.rfind("[") + 1:title.rfind("]")] if "[" in title else ""
    fmt = {"rpm": ".0f", "MPa": ".0f", "N m": ".2f"}.get(unit, ".3g")
    return f"{v:{fmt}} {unit}".replace(" -", "").strip()


#: answers on the parallel-coordinates axes
PC_ANSWERS = ("engagement_ripple_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm", "max_von_mises_MPa",
              "safety_factor", "shoe_mass_g", "contact_arc_deg")


def parallel_coordinates(frame, spec, path: str | Path) -> Path:
    """Parallel coordinates of the answered designs, feasible ones in colour (see module
    docstring)."""
    from matplotlib import colormaps

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    ok = frame[frame["status"] == "ok"].reset_index(drop=True)
    labels = dict(ANSWERS)
    cols, names = [], []
    for a in spec.axes:
        x, cats = _x(ok, a)
        cols.append((x, cats))
        names.append(a.label())
    for c in PC_ANSWERS:
        cols.append((ok[c].to_numpy(dtype=float), None))
        names.append(labels.get(c, c))
    fig, ax = figure(figsize=(max(8.0, 1.5 * len(cols)) + 1.2, 5.4), layout="constrained")
    n = len(ok)
    feas = (ok["feasible"].fillna(0).astype(int) == 1).to_numpy() if n else np.zeros(0, bool)
    scaled = np.full((n, len(cols)), np.nan)
    limits = {c: _limit(ok, lc) for cs, _, lc, _ in PANELS for c in cs} if n else {}
    box = {"fc": "white", "ec": "none", "pad": 0.6}
    n_in = len(spec.axes)
    for j, (v, cats) in enumerate(cols):
        lo, hi = (np.nanmin(v), np.nanmax(v)) if n and np.isfinite(v).any() else (0.0, 1.0)
        span = hi - lo if hi > lo else 1.0
        scaled[:, j] = (v - lo) / span if hi > lo else 0.5
        ax.axvline(j, color="0.3", lw=0.8)
        fmt = (lambda q: cats[int(q)]) if cats else (lambda q: f"{q:.4g}")
        if n and np.isfinite(v).any():
            ax.text(j, 1.03, fmt(hi), ha="center", va="bottom", fontsize=7, bbox=box)
            ax.text(j, -0.03, fmt(lo), ha="center", va="top", fontsize=7, bbox=box)
        lim = limits.get(PC_ANSWERS[j - n_in]) if j >= n_in else None
        if lim is not None and math.isfinite(lim) and n and np.isfinite(v).any():
            if hi > lo and lo <= lim <= hi:  # the requirement limit on its axis
                ax.plot([j - 0.12, j + 0.12], [(lim - lo) / span] * 2, color="C3", lw=2.2, zorder=4)
            else:
                where = "above" if lim > hi else "below"
                ax.text(j, 1.09 if where == "above" else -0.09, f"limit {lim:.4g} {where}", ha="center",
                        va="center", fontsize=6, color="C3")
    xs = np.arange(len(cols))
    short = shortfall(ok) if n else np.zeros(0)
    cmap = colormaps["plasma_r"]
    nf = np.nonzero(~feas)[0]
    top = max(float(np.nanmax(short[nf], initial=0.0)), 1e-9) if len(nf) else 1.0
    for i in nf[np.argsort(-short[nf])]:  # the nearest misses drawn last, on top
        ax.plot(xs, scaled[i], color=cmap(min(short[i] / top, 1.0)), lw=0.9, alpha=0.85, zorder=1)
    fi = np.nonzero(feas)[0]
    for i in fi:
        ax.plot(xs, scaled[i], color="tab:green", lw=2.0, zorder=3)
    if len(nf):
        from matplotlib.cm import ScalarMappable
        from matplotlib.colors import Normalize

        sm = ScalarMappable(norm=Normalize(0.0, 100.0 * top), cmap=cmap)
        fig.colorbar(sm, ax=ax, fraction=0.03, pad=0.01,
                     label="not feasible: largest requirement shortfall [%]")
    ax.set_xticks(xs, names, rotation=25, ha="right", fontsize=8)
    ax.set_yticks([])
    ax.set_ylim(-0.14, 1.14)
    ax.set_xlim(-0.3, len(cols) - 0.7)
    for s in ("top", "right", "left"):
        ax.spines[s].set_visible(False)
    n_bad = int((frame["status"] != "ok").sum())
    refused = f" ({n_bad} refused/failed: no answer, not drawn)" if n_bad else ""
    title = (f"{spec.design}: {len(fi)} of {n} answered designs feasible{refused} (green; the others coloured by "
             "how far they miss); red: requirement limits")
    if n and not len(fi):
        why = {"engagement": int((ok["engagement_ok"] == 0).sum()), "slip": int((ok["slip_ok"] == 0).sum()),
               "stress": int((ok["stress_ok"] == 0).sum())}
        worst = max(why, key=why.get)
        title = (f"{spec.design}: no feasible design among {n} answered{refused}; requirements missed: "
                 + ", ".join(f"{k} {v}" for k, v in why.items()) + f" (most often: {worst})")
    ax.set_title(title, fontsize=10)
    save_figure(fig, path)
    return path


def shortfall(frame) -> np.ndarray:
    """Per answered design, its largest requirement shortfall [-]: (limit - engagement with
    ripple) / limit, (slip - limit) / limit, (min SF - SF) / min SF, 0 where met; a missed
    requirement without a number (never holds) counts 1."""
    def col(c):
        return frame[c].to_numpy(dtype=float) if c in frame else np.full(len(frame), np.nan)

    with np.errstate(invalid="ignore", divide="ignore"):
        parts = [(col("engagement_limit_rpm") - col("engagement_ripple_rpm")) / col("engagement_limit_rpm"),
                 (col("slip_rpm") - col("slip_limit_rpm")) / col("slip_limit_rpm"),
                 (col("min_safety_factor") - col("safety_factor")) / col("min_safety_factor")]
    out = np.zeros(len(frame))
    for v, flag in zip(parts, ("engagement_ok", "slip_ok", "stress_ok")):
        missed = (frame[flag].fillna(1).astype(int) == 0).to_numpy() if flag in frame else np.zeros(len(frame), bool)
        v = np.where(missed & ~np.isfinite(v), 1.0, np.where(missed, np.maximum(v, 0.0), 0.0))
        out = np.maximum(out, v)
    return out


def draw_study_charts(result: StudyResult) -> StudyResult:
    r"""Draw a parameter study's charts into its folder (``charts/``: every answer against
    every varied input, and the parallel coordinates) and record them in its
    ``summary.json``.

    Parameters
    ----------
    result : StudyResult
        From :func:`~clutchfem.run_study`.

    Returns
    -------
    StudyResult
        The same study with the chart files added to its record.

    Examples
    --------
    >>> import clutchfem as cf, tempfile
    >>> from clutchfem.studies import parse_spec
    >>> spec = parse_spec('[design]\nconcept = "concept1"\n[settings]\nmesh_size = "3mm"\n[errors]\nsample = 0\n'
    ...                   '[vary]\nmethod = "list"\n[vary.params]\nflexure_thickness = {values = ["2.2mm"]}')
    >>> s = cf.draw_study_charts(cf.run_study(spec, tempfile.mkdtemp(), workers=0, progress=False))
    >>> s.charts, sorted(f.name for f in s.files if f.suffix == ".png")
    (True, ['answers_vs_flexure_thickness.png', 'parallel_coordinates.png'])
    """
    files = answers_vs_inputs(result.frame, result.spec, result.out / "charts")
    files.append(parallel_coordinates(result.frame, result.spec, result.out / "charts" / "parallel_coordinates.png"))
    return result.with_files(files, charts=True)
