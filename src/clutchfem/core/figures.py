"""Figures without pyplot: :func:`figure` returns a matplotlib ``Figure`` and its axes;
:func:`save_figure` writes it as a PNG that records what it shows.

A ``matplotlib.figure.Figure`` draws with the Agg canvas when saved, so clutchfem never
selects a backend (no ``matplotlib.use`` at import: a user's notebook or GUI backend stays
as it is) and keeps no global pyplot state (no figure to close, nothing leaks in a long
sweep).

**The picture rule** (issue 25): every picture states its quantity with its unit in the unit a
designer uses (MPa, mm, rpm, N m), marks the answer it exists to show, keeps legends off the
data and agrees with the tables to the digits it shows.  :func:`save_figure` makes the last two
checkable: it stores in the PNG (a ``tEXt`` chunk ``clutchfem``, JSON) the texts a reader
sees -- per axes its title, axis labels, annotations, legend entries and view limits (a colour
bar's: its range), and the figure's
own texts and legends -- per legend, how many data points it covers (lines sampled along
their segments, scatter points; inside the axes only), and the texts a reader would see cut
(:func:`clipped_texts`: leaving the figure, or an annotation leaving its axes, and
:func:`clipped_markers`: a marked point cut by its axes' edge; issue 37).  :func:`figure_record` reads it back
(the tests compare the annotated numbers with the answers' JSON).  :func:`tag_png` adds the
same record to a PNG drawn by another library (pyvista's renders).
"""

from __future__ import annotations

import json
import struct
import zlib
from pathlib import Path

import numpy as np

#: the PNG text chunk's keyword
KEY = "clutchfem"
#: an rpm axis runs this far past its last speed, so a point marked there is drawn whole
#: (:func:`clipped_markers`)
RPM_MARGIN = 1.04


def figure(nrows: int = 1, ncols: int = 1, *, figsize=(8.0, 5.0), layout: str | None = None, **subplot_kw):
    """(fig, axes) like ``plt.subplots``, without pyplot; ``layout="constrained"`` places
    legends and colour bars outside the axes (``fig.legend(loc="outside ...")``)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout=layout)
    FigureCanvasAgg(fig)  # this figure's own canvas (text extents for layout); no global backend
    return fig, fig.subplots(nrows, ncols, **subplot_kw)


def _texts(artists) -> list[str]:
    return [t.get_text() for t in artists if t.get_visible() and t.get_text().strip()]


def _data_points(ax):
    """Display coordinates of the data an axes shows: its lines sampled along their segments
    (10 points a segment), its scatter points and its bars (a 5 x 5 grid over each; shaded
    bands across the whole axes are no data), clipped to the axes."""
    pts = []
    for ln in ax.lines:
        if not ln.get_visible():
            continue
        xy = np.asarray(ln.get_xydata(), dtype=float)
        xy = xy[np.isfinite(xy).all(axis=1)]
        if len(xy) == 0:
            continue
        d = ln.get_transform().transform(xy)
        if len(d) > 1 and ln.get_linestyle() not in ("None", "", " "):
            t = np.linspace(0.0, 1.0, 10, endpoint=False)[None, :, None]
            d = np.concatenate([(d[:-1, None, :] * (1 - t) + d[1:, None, :] * t).reshape(-1, 2), d[-1:]])
        pts.append(d)
    for c in ax.collections:
        off = c.get_offsets()
        if c.get_visible() and len(off) and type(c).__name__ == "PathCollection":
            o = np.asarray(off, dtype=float)
            pts.append(c.get_offset_transform().transform(o[np.isfinite(o).all(axis=1)]))
    bb = ax.get_window_extent()
    g = np.linspace(0.0, 1.0, 5)
    for r in ax.patches:
        if not r.get_visible() or type(r).__name__ != "Rectangle":
            continue
        e = r.get_window_extent()
        if e.width >= 0.95 * bb.width or e.height >= 0.95 * bb.height or e.width * e.height <= 0:
            continue
        gx, gy = np.meshgrid(e.x0 + g * e.width, e.y0 + g * e.height)
        pts.append(np.column_stack([gx.ravel(), gy.ravel()]))
    if not pts:
        return np.zeros((0, 2))
    p = np.concatenate(pts)
    inside = (p[:, 0] >= bb.x0) & (p[:, 0] <= bb.x1) & (p[:, 1] >= bb.y0) & (p[:, 1] <= bb.y1)
    return p[inside]


def _ticklabels(ax):
    """The tick labels an axes draws (those of ticks inside its view)."""
    out = []
    for axis in (ax.xaxis, ax.yaxis):
        if not axis.get_visible():
            continue
        lo, hi = sorted(axis.get_view_interval())
        span = (hi - lo) or 1.0
        for loc, lab in zip(axis.get_majorticklocs(), axis.get_majorticklabels()):
            if lo - 1e-9 * span <= loc <= hi + 1e-9 * span:
                out.append(lab)
    return out


def clipped_texts(fig, tol: float = 1.0) -> list[str]:
    """The texts of a drawn ``fig`` that a reader sees cut: any text (titles, axis and tick
    labels, legends, annotations, the figure's own) whose box leaves the figure, and any text
    placed on an axes' data (``ax.text``, ``ax.annotate``) whose box leaves that axes; each as
    "'text': leaves the figure|its axes" (``tol`` pixels of slack)."""
    r = fig.canvas.get_renderer()
    fb = fig.bbox

    def out_of(e, b) -> bool:
        return e.x0 < b.x0 - tol or e.x1 > b.x1 + tol or e.y0 < b.y0 - tol or e.y1 > b.y1 + tol

    texts = list(fig.texts) + [t for lg in fig.legends for t in lg.get_texts()]
    on_axes = []
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        texts += [ax.xaxis.label, ax.yaxis.label] + _ticklabels(ax)
        texts += [ax.title, ax._left_title, ax._right_title] if hasattr(ax, "_left_title") else []
        leg = ax.get_legend()
        texts += list(leg.get_texts()) if leg is not None and leg.get_visible() else []
        on_axes += [(t, ax) for t in ax.texts]
    bad = []
    for t in texts + [t for t, _ in on_axes]:
        if not t.get_visible() or not t.get_text().strip():
            continue
        e = t.get_window_extent(r)
        if e.width <= 0:
            continue
        if out_of(e, fb):
            bad.append(f"{t.get_text()!r}: leaves the figure")
    for t, ax in on_axes:
        if t.get_visible() and t.get_text().strip() and out_of(t.get_window_extent(r), ax.bbox):
            bad.append(f"{t.get_text()!r}: leaves its axes")
    return bad + clipped_markers(fig, tol)


def clipped_markers(fig, tol: float = 1.0) -> list[str]:
    """The marked points of a drawn ``fig`` that a reader sees cut: a line's marker (the
    answer a picture marks, e.g. the peak at the engine's maximum speed) whose centre lies in
    its axes but whose marker reaches beyond the axes' edge; each as "marker of 'label' at
    (x, y): cut by its axes" (``tol`` pixels of slack).  Lines of many points (a curve drawn
    with markers) are checked at every point."""
    bad = []
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        b = ax.bbox
        for ln in ax.lines:
            if not ln.get_visible() or ln.get_marker() in (None, "None", "", " ", ",") or not ln.get_clip_on():
                continue
            xy = np.asarray(ln.get_xydata(), dtype=float)
            xy = xy[np.isfinite(xy).all(axis=1)]
            if not len(xy):
                continue
            d = ln.get_transform().transform(xy)
            half = 0.5 * ln.get_markersize() * fig.dpi / 72.0 + 0.5 * ln.get_markeredgewidth() * fig.dpi / 72.0
            # (a centre on the edge itself is inside: half its marker is cut)
            inside = ((d[:, 0] >= b.x0 - tol) & (d[:, 0] <= b.x1 + tol) & (d[:, 1] >= b.y0 - tol)
                      & (d[:, 1] <= b.y1 + tol))
            cut = inside & ((d[:, 0] - half < b.x0 - tol) | (d[:, 0] + half > b.x1 + tol)
                            | (d[:, 1] - half < b.y0 - tol) | (d[:, 1] + half > b.y1 + tol))
            for (x, y) in xy[cut][:3]:
                bad.append(f"marker of {ln.get_label()!r} at ({x:.4g}, {y:.4g}): cut by its axes")
    return bad


def describe(fig, *, drawn: bool = False) -> dict:
    """What ``fig`` shows (module docstring): its texts and, per legend, the data points under it.
    Draws the figure first (the legends' places are known after a draw) unless ``drawn``: it
    was just drawn (saved), and a draw costs ~0.5 s for a figure of many axes."""
    if not drawn:
        fig.canvas.draw()
    axes, legends = [], []
    for ax in fig.axes + [c for a in fig.axes for c in a.child_axes]:  # (secondary axes are children)
        if not ax.get_visible():
            continue
        leg = ax.get_legend()
        titled = hasattr(ax, "get_title")  # (a secondary axis has labels only)
        entry = {"title": " ".join(t for t in (ax.get_title(loc) for loc in ("left", "center", "right")) if t)
                 if titled else "",
                 "xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(), "texts": _texts(ax.texts),
                 "legend": _texts(leg.get_texts()) if leg is not None else [],
                 "xticks": bool(ax.xaxis.get_visible() and len(ax.get_xticklabels())),
                 "yticks": bool(ax.yaxis.get_visible() and len(ax.get_yticklabels())),
                 "xlim": [float(v) for v in ax.get_xlim()], "ylim": [float(v) for v in ax.get_ylim()]}
        axes.append(entry)
        if leg is not None and leg.get_visible():
            legends.append(leg)
    legends += [lg for lg in fig.legends if lg.get_visible()]
    covered = []
    for leg in legends:
        bb = leg.get_window_extent()
        n = 0
        for ax in fig.axes:
            if ax.get_visible():
                p = _data_points(ax)
                n += int(((p[:, 0] >= bb.x0) & (p[:, 0] <= bb.x1) & (p[:, 1] >= bb.y0) & (p[:, 1] <= bb.y1)).sum())
        covered.append(n)
    sup = fig.get_suptitle()
    fig_texts = ([sup] if sup else []) + [t for t in _texts(fig.texts) if t != sup]
    return {"figure": fig_texts, "axes": axes,
            "figure_legends": [_texts(lg.get_texts()) for lg in fig.legends if lg.get_visible()],
            "legend_covers": covered, "clipped": clipped_texts(fig)}


def save_figure(fig, path, dpi: int = 110, **kw) -> Path:
    """Write ``fig`` as a PNG at ``path`` with its :func:`describe` record in the file; returns
    the path.  Other keywords go to ``Figure.savefig``."""
    path = Path(path)
    if kw or path.suffix.lower() != ".png":  # another format or savefig's options: its own drawing
        meta = describe(fig)
        fig.savefig(path, dpi=dpi, metadata={KEY: json.dumps(meta, ensure_ascii=True)}, **kw)
        return path
    # a PNG is drawn once, at the resolution written: the record describes that very drawing and
    # the pixels are written from it (savefig would draw the figure again: ~0.5 s a busy figure)
    from PIL import Image, PngImagePlugin

    old = fig.dpi
    fig.set_dpi(dpi)
    try:
        meta = describe(fig)
        w, h = fig.canvas.get_width_height(physical=True)
        img = Image.frombuffer("RGBA", (w, h), fig.canvas.buffer_rgba(), "raw", "RGBA", 0, 1)
        info = PngImagePlugin.PngInfo()
        info.add_text("Software", "matplotlib")
        info.add_text(KEY, json.dumps(meta, ensure_ascii=True))
        img.save(path, format="png", pnginfo=info, dpi=(dpi, dpi))
    finally:
        fig.set_dpi(old)
    return path


def figure_record(path) -> dict | None:
    """The record :func:`save_figure` (or :func:`tag_png`) stored in a PNG, None if it has none."""
    data = Path(path).read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    i = 8
    while i + 8 <= len(data):
        n, kind = struct.unpack(">I4s", data[i:i + 8])
        body = data[i + 8:i + 8 + n]
        if kind == b"tEXt":
            k, _, v = body.partition(b"\x00")
            if k.decode("latin-1") == KEY:
                return json.loads(v.decode("latin-1"))
        if kind == b"zTXt":
            k, _, v = body.partition(b"\x00")
            if k.decode("latin-1") == KEY:
                return json.loads(zlib.decompress(v[1:]).decode("latin-1"))
        i += 12 + n
    return None


def tag_png(path, meta: dict) -> Path:
    """Add ``meta`` (JSON) to the PNG at ``path`` as its ``clutchfem`` record (a tEXt chunk
    before IEND); for pictures another library drew."""
    path = Path(path)
    data = path.read_bytes()
    body = KEY.encode("latin-1") + b"\x00" + json.dumps(meta, ensure_ascii=True).encode("latin-1")
    chunk = struct.pack(">I", len(body)) + b"tEXt" + body + struct.pack(">I", zlib.crc32(b"tEXt" + body) & 0xFFFFFFFF)
    end = data.rfind(b"IEND") - 4
    path.write_bytes(data[:end] + chunk + data[end:])
    return path
