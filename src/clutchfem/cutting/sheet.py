"""The workshop drawing (A3 landscape, PDF/SVG/PNG, pyplot-free matplotlib).

Laid out as a workshop expects (ISO 5457 frame, ISO 7200 title block, first-angle
projection, ISO 129 dimensions), drawn in sheet millimetres on one axes:

* the **main view**: the whole part at a standard scale (2:1 for the ~69 mm parts), viewed
  from the engine side, centre lines, the drum (dash-dot, for reference), the tool path
  (thin red, with a process), and the dimensions that need the axis: bore, every radius
  about it, the shoe arc, the pitch of the shoes, the beam's angular position;
* the **side view** (to the right, first-angle) with the plate thickness;
* **detail A**: shoe 0's flexure at a larger standard scale, with the beam's length,
  thickness at both ends and angle, every fillet and slot-end round, the measured webs and
  slots and the thinnest ligament (:mod:`.ligament`);
* the **notes** (general tolerances, material and heat treatment, the DXF as the geometry
  master, reference dimensions), the **predicted answers** with their error bands and the
  fidelity they came from (the model that answered, never a fixed "FE, plane stress"), and
  the **title block**: title, drawing number (= the design hash), material, mass, scale,
  units, projection symbol, date, general tolerances, clutchfem version.

Each feature is dimensioned once (:mod:`.dimensions`), with its ``--tol`` tolerance where
given; every label is horizontal (never upside down), placed outside the part's material and
clear of the other labels, views and blocks, with a leader to its feature.  The SVG keeps
its text as text (``svg.fonttype = "none"``) and the PDF embeds TrueType (Type 42) fonts,
so both are searchable; each dimension is an SVG group ``dim:<key>``, each title-block field
``title:<field>``.
"""

from __future__ import annotations

import datetime as _dt
import math
from pathlib import Path

import numpy as np
from matplotlib import rc_context
from matplotlib.patches import Arc, Circle, FancyArrowPatch, Rectangle
from matplotlib.path import Path as MPath
from matplotlib.transforms import Bbox

from ..core import figure
from .dimensions import dimensions as make_dimensions
from .titleblock import (
    DETAIL_BOX,
    FRAME,
    FS_DIM,
    FS_HEAD,
    FS_TAB,
    SHEET,
    TB,
    answers_block,
    general_tolerance,
    notes_block,
    scale_text,
    title_block,
)

MM = 1 / 25.4
#: standard scales (ISO 5455), largest first
SCALES = (10.0, 5.0, 2.0, 1.0, 0.5, 0.2)
MAIN_BOX = (20.0, 10.0, 236.0, 287.0)
#: a drawn line is tested against a label's place when a run of LINE_RUN of its segments comes
#: within REACH [sheet mm] of it (far above rounding: the same answers as testing every line)
LINE_RUN, REACH = 16, 1e-6


class _Sheet:
    """The drawing being built: one axes in sheet millimetres, the obstacles labels avoid."""

    def __init__(self, units: str):
        self.fig, _ = figure(1, 1, figsize=(SHEET[0] * MM, SHEET[1] * MM))
        self.fig.clear()
        ax = self.fig.add_axes([0, 0, 1, 1])
        ax.set_xlim(0, SHEET[0])
        ax.set_ylim(0, SHEET[1])
        ax.set_aspect("equal")
        ax.axis("off")
        self.ax = ax
        self.units = units
        self.renderer = self.fig.canvas.get_renderer()
        self.taken: list[Bbox] = []  # label boxes placed
        self.blocks: list[Bbox] = []  # areas no label may enter
        self.material: list[tuple[MPath, Bbox | None]] = []  # filled part regions (clip box)
        self.lines: list[MPath] = []  # drawn part outlines and dimension lines
        self._pieces, self._piece_line = np.zeros((0, 4)), np.zeros(0, dtype=int)  # runs of lines: extents, line
        self._ext: dict[int, tuple[MPath, Bbox]] = {}  # material regions' extents (with the path: its id)
        self.queue: list = []  # label placements, made once every line is drawn

    def line(self, xs, ys, gid=None, **kw):
        """A thin drawn line that labels keep clear of."""
        kw.setdefault("color", "black")
        kw.setdefault("lw", 0.35)
        self.ax.plot(xs, ys, gid=gid, **kw)
        self.lines.append(MPath(np.column_stack([xs, ys])))

    def arrow(self, a, b, gid, style="<|-|>", lw=0.45, color="black"):
        self.ax.add_patch(FancyArrowPatch(a, b, arrowstyle=style, mutation_scale=6, lw=lw, color=color, shrinkA=0,
                                          shrinkB=0, gid=gid))
        self.lines.append(MPath([a, b]))

    def arc(self, c, r, a0, a1, gid):
        """An arc (angles in rad, a0 < a1) of a dimension line."""
        self.ax.add_patch(Arc(c, 2 * r, 2 * r, theta1=math.degrees(a0), theta2=math.degrees(a1), lw=0.45, gid=gid))
        t = np.linspace(a0, a1, 60)
        self.lines.append(MPath(np.column_stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)])))

    def later(self, *args, **kw):
        self.queue.append((args, kw))

    def flush(self):
        for args, kw in self.queue:
            self.place(*args, **kw)
        self.queue = []

    # -- text -------------------------------------------------------------------------
    def text(self, x, y, s, *, size=FS_TAB, gid=None, **kw):
        t = self.ax.text(x, y, s, fontsize=size, gid=gid, **kw)
        return t

    def extent(self, t) -> Bbox:
        return t.get_window_extent(self.renderer).transformed(self.ax.transData.inverted())

    def free(self, box: Bbox, region: Bbox) -> bool:
        """Is ``box`` (sheet mm, with a margin) inside ``region`` and clear of labels, blocks,
        outlines and material?"""
        m = box.expanded(1.0, 1.0).padded(0.8)
        if not (region.x0 <= box.x0 and box.x1 <= region.x1 and region.y0 <= box.y0 and box.y1 <= region.y1):
            return False
        if any(m.overlaps(b) for b in self.taken) or any(box.overlaps(b) for b in self.blocks):
            return False
        if any(self.lines[k].intersects_bbox(m, filled=False) for k in self._lines_near(m)):
            return False
        for path, clip in self.material:
            b = m if clip is None else Bbox.intersection(m, clip)
            ext = self._ext.get(id(path)) or self._ext.setdefault(id(path), (path, path.get_extents()))
            if b is not None and _near(ext[1], b) and path.intersects_bbox(b, filled=True):
                return False
        return True

    def _lines_near(self, m: Bbox) -> list[int]:
        """The lines (indices, in order) with a run of LINE_RUN segments whose extents reach
        ``m`` (widened by REACH): the others cannot cross it, and testing the whole outline
        (thousands of segments) at every candidate place was most of the drawing's time."""
        for k in range(len(self._piece_line) and int(self._piece_line[-1]) + 1, len(self.lines)):
            v = np.asarray(self.lines[k].vertices, dtype=float)
            if self.lines[k].codes is not None or len(v) < 2 or not np.all(np.isfinite(v)):
                e = np.array([[-np.inf, -np.inf, np.inf, np.inf]])  # (curves, gaps: always tested)
            else:
                cut = [(a, min(a + LINE_RUN, len(v) - 1) + 1) for a in range(0, len(v) - 1, LINE_RUN)]
                e = np.array([[*v[a:b].min(axis=0), *v[a:b].max(axis=0)] for a, b in cut])
            self._pieces, self._piece_line = np.vstack([self._pieces, e]), np.r_[self._piece_line, [k] * len(e)]
        e, (x0, y0, x1, y1) = self._pieces, _widened(m)
        hit = (e[:, 0] <= x1) & (e[:, 2] >= x0) & (e[:, 1] <= y1) & (e[:, 3] >= y0)
        return np.unique(self._piece_line[hit]).tolist()

    def place(self, s: str, anchor, direction: float, region: Bbox, *, gid: str, start: float = 4.0,
              color="black", arrow_from_text=True, arrow=True, leader=True, size=FS_DIM):
        """A horizontal label near ``anchor`` (sheet mm), searched outward along
        ``direction`` (rad) and fanned to either side, in the first free place; a leader (with
        an arrowhead at the anchor) joins them.  Returns the Text."""
        t = self.text(0, 0, s, size=size, gid=gid, ha="center", va="center", color=color)
        w = self.extent(t)
        hw, hh = 0.5 * w.width, 0.5 * w.height
        ax0, ay0 = anchor
        best = None
        for dist in np.arange(start, 90.0, 2.0):
            for dev in (0, 10, -10, 20, -20, 30, -30, 45, -45, 60, -60, 80, -80, 100, -100, 130, -130, 180):
                a = direction + math.radians(dev)
                cx = ax0 + (dist + hw * abs(math.cos(a)) + hh * abs(math.sin(a))) * math.cos(a)
                cy = ay0 + (dist + hw * abs(math.cos(a)) + hh * abs(math.sin(a))) * math.sin(a)
                box = Bbox.from_extents(cx - hw, cy - hh, cx + hw, cy + hh)
                if self.free(box, region) and (not leader or self._leader_clear(anchor, box)):
                    best = (cx, cy, box)
                    break
            if best is not None:
                break
        if best is None:  # no free place: the far corner of the region (never silently on the part)
            cx, cy = region.x0 + hw + 1, region.y1 - hh - 1
            best = (cx, cy, Bbox.from_extents(cx - hw, cy - hh, cx + hw, cy + hh))
        cx, cy, box = best
        t.set_position((cx, cy))
        self.taken.append(box)
        if leader:
            end = _box_point(box, anchor)
            self.ax.add_patch(FancyArrowPatch(end, anchor, arrowstyle="-|>" if arrow else "-", mutation_scale=6,
                                              lw=0.45, color=color, shrinkA=0, shrinkB=0, gid=gid + "/leader"))
        return t

    def _leader_clear(self, anchor, box: Bbox) -> bool:
        """The leader does not cross another label."""
        end = _box_point(box, anchor)
        seg = MPath([anchor, end])
        return not any(seg.intersects_bbox(b.padded(0.3), filled=True) for b in self.taken)


def _widened(b: Bbox) -> tuple[float, float, float, float]:
    return (min(b.x0, b.x1) - REACH, min(b.y0, b.y1) - REACH, max(b.x0, b.x1) + REACH, max(b.y0, b.y1) + REACH)


def _near(ext: Bbox, b: Bbox) -> bool:
    """Do the extents ``ext`` reach ``b``?  A path whose extents do not cannot cross or enclose it."""
    x0, y0, x1, y1 = _widened(b)
    return ext.x0 <= x1 and ext.x1 >= x0 and ext.y0 <= y1 and ext.y1 >= y0


def _box_point(box: Bbox, p) -> tuple[float, float]:
    """The point of ``box``'s edge (middle of its left or right side, or top/bottom) nearest
    the leader's direction from ``p``."""
    cx, cy = 0.5 * (box.x0 + box.x1), 0.5 * (box.y0 + box.y1)
    if p[0] < box.x0:
        return (box.x0 - 0.5, cy)
    if p[0] > box.x1:
        return (box.x1 + 0.5, cy)
    return (cx, box.y0 - 0.5 if p[1] < cy else box.y1 + 0.5)


def draw_sheet(paths, *, outline, features, rules, toolpath, label: str, design_hash: str, material: str,
               analysis=None, as_cut=None, units: str = "mm", violations=(), mass_kg: float | None = None,
               tolerances: dict | None = None, fidelity: str = "", ligament=None, date: str | None = None,
               title: str | None = None) -> list[Path]:
    """Draw the workshop drawing once and save it to every path in ``paths`` (.pdf, .svg,
    .png); text stays text in the PDF and SVG (module docstring)."""
    fig = build_sheet(outline=outline, features=features, rules=rules, toolpath=toolpath, label=label,
                      design_hash=design_hash, material=material, analysis=analysis, as_cut=as_cut, units=units,
                      violations=violations, mass_kg=mass_kg, tolerances=tolerances, fidelity=fidelity,
                      ligament=ligament, date=date, title=title)
    out = []
    with rc_context({"svg.fonttype": "none", "pdf.fonttype": 42, "ps.fonttype": 42, "svg.hashsalt": design_hash}):
        for path in paths:
            path = Path(path)
            fig.savefig(path, dpi=110 if path.suffix.lower() == ".png" else 150,
                        metadata=None if path.suffix.lower() == ".png" else {"Title": f"{label} {design_hash}"})
            out.append(path)
    return out


def build_sheet(*, outline, features, rules, toolpath, label: str, design_hash: str, material: str, analysis=None,
                as_cut=None, units: str = "mm", violations=(), mass_kg: float | None = None,
                tolerances: dict | None = None, fidelity: str = "", ligament=None, date: str | None = None,
                title: str | None = None):
    """The drawing as a matplotlib Figure (A3 in sheet millimetres; :func:`draw_sheet` saves it)."""
    sh = _Sheet(units)
    ax = sh.ax
    dims = make_dimensions(outline, features, ligament, tolerances)
    # -- frame, centring marks ----------------------------------------------------------
    x0, y0, x1, y1 = FRAME
    ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, lw=1.4, gid="frame"))
    for x, y, dx, dy in ((0.5 * (x0 + x1), y0, 0, -5), (0.5 * (x0 + x1), y1, 0, 5), (x0, 0.5 * (y0 + y1), -5, 0),
                         (x1, 0.5 * (y0 + y1), 5, 0)):
        ax.plot([x, x + dx], [y, y + dy], color="black", lw=1.0)
    sh.blocks += [Bbox.from_extents(*TB), Bbox.from_extents(TB[0], TB[3], x1, DETAIL_BOX[1])]
    # -- main view -----------------------------------------------------------------------
    R_env = outline.max_radius()
    drum = float(getattr(outline.params, "drum_radius", R_env))
    scale = next(s for s in SCALES if 2 * drum * 1e3 * s <= 150.0) if units else 1.0
    cx, cy = 100.0, 160.0
    k_main = scale * 1e3

    def to_main(q):
        q = np.asarray(q, float)
        return np.column_stack([cx + k_main * q[..., 0], cy + k_main * q[..., 1]]) if q.ndim > 1 else \
            np.array([cx + k_main * q[0], cy + k_main * q[1]])

    outer_path = None
    for lp in outline.loops:
        xy = to_main(lp.points(spacing=0.05e-3))
        xy = np.vstack([xy, xy[:1]])
        ax.plot(xy[:, 0], xy[:, 1], color="black", lw=0.9, gid=f"outline:main:{lp.layer}")
        sh.lines.append(MPath(xy))
        if outer_path is None:
            outer_path = MPath(xy, closed=True)
    sh.material.append((outer_path, None))
    for lp in toolpath or ():
        xy = to_main(lp.points(spacing=0.05e-3))
        ax.plot(*np.vstack([xy, xy[:1]]).T, color="#c0392b", lw=0.3)
    Rd = drum * k_main
    ax.add_patch(Circle((cx, cy), Rd, fill=False, lw=0.4, ls=(0, (12, 3, 2, 3)), color="#777"))
    ext = Rd + 5
    for a, b in (((cx - ext, cy), (cx + ext, cy)), ((cx, cy - ext), (cx, cy + ext))):
        ax.plot(*zip(a, b), color="#555", lw=0.35, ls=(0, (12, 3, 2, 3)))
    region_main = Bbox.from_extents(FRAME[0] + 1, FRAME[1] + 1, MAIN_BOX[2] - 30, FRAME[3] - 9)
    ax.text(cx, FRAME[3] - 5, f"{label}: view from the engine side   scale {scale_text(scale)}",
            ha="center", va="center", fontsize=FS_HEAD, gid="view:main")
    # -- side view (first angle: the view from the left is drawn on the right) -----------
    t_mm = outline.thickness * k_main
    sx = MAIN_BOX[2] - 14
    top, bot = cy + R_env * k_main, cy - R_env * k_main
    side = np.array([[sx - t_mm / 2, bot], [sx + t_mm / 2, bot], [sx + t_mm / 2, top], [sx - t_mm / 2, top],
                     [sx - t_mm / 2, bot]])
    ax.plot(side[:, 0], side[:, 1], color="black", lw=0.9, gid="outline:side")
    sh.lines.append(MPath(side))
    sh.material.append((MPath(side, closed=True), None))
    rb = float(getattr(outline.params, "bore_radius", 0.0)) * k_main
    for yy in (cy - rb, cy + rb):
        ax.plot([sx - t_mm / 2, sx + t_mm / 2], [yy, yy], color="black", lw=0.5, ls=(0, (3, 2)))
    ax.plot([sx - t_mm / 2 - 4, sx + t_mm / 2 + 4], [cy, cy], color="#555", lw=0.35, ls=(0, (12, 3, 2, 3)))
    region_side = Bbox.from_extents(sx - 30, FRAME[1] + 1, MAIN_BOX[2] + 1, FRAME[3] - 9)
    # -- detail A ------------------------------------------------------------------------
    det = [d for d in dims if d.view == "detail"]
    win = _detail_window(outline, dims, ligament)
    k_det, dwin, to_det = None, None, None
    if win is not None and det:
        bw, bh = DETAIL_BOX[2] - DETAIL_BOX[0] - 50, DETAIL_BOX[3] - DETAIL_BOX[1] - 42
        wx, wy = win[2] - win[0], win[3] - win[1]
        s_det = next((s for s in SCALES if wx * 1e3 * s <= bw and wy * 1e3 * s <= bh), SCALES[-1])
        k_det = s_det * 1e3
        dcx, dcy = 0.5 * (DETAIL_BOX[0] + DETAIL_BOX[2]), 0.5 * (DETAIL_BOX[1] + DETAIL_BOX[3]) - 3
        mx, my = 0.5 * (win[0] + win[2]), 0.5 * (win[1] + win[3])

        def to_det(q):
            q = np.asarray(q, float)
            if q.ndim > 1:
                return np.column_stack([dcx + k_det * (q[:, 0] - mx), dcy + k_det * (q[:, 1] - my)])
            return np.array([dcx + k_det * (q[0] - mx), dcy + k_det * (q[1] - my)])

        dwin = Bbox.from_extents(dcx - 0.5 * wx * k_det, dcy - 0.5 * wy * k_det, dcx + 0.5 * wx * k_det,
                                 dcy + 0.5 * wy * k_det)
        ax.add_patch(Rectangle((dwin.x0, dwin.y0), dwin.width, dwin.height, fill=False, lw=0.35,
                               ls=(0, (6, 2)), color="#555"))
        for lp in outline.loops:
            xy = to_det(lp.points(spacing=0.01e-3))
            inside = (xy[:, 0] >= dwin.x0) & (xy[:, 0] <= dwin.x1) & (xy[:, 1] >= dwin.y0) & (xy[:, 1] <= dwin.y1)
            for run in _runs(inside):
                seg = xy[run]
                ax.plot(seg[:, 0], seg[:, 1], color="black", lw=0.9, gid=f"outline:detail:{lp.layer}")
                sh.lines.append(MPath(seg))
            if lp.layer == "OUTER":
                xy = np.vstack([xy, xy[:1]])
                sh.material.append((MPath(xy, closed=True), dwin))
        ax.text(dcx, DETAIL_BOX[3] - 5, f"DETAIL A   scale {scale_text(s_det)}", ha="center", va="center",
                fontsize=FS_HEAD, weight="bold", gid="view:detail")
        # the detail's window marked on the main view
        c0 = to_main((mx, my))
        rr = 0.5 * math.hypot(wx, wy) * k_main + 1.5
        ax.add_patch(Circle(tuple(c0), rr, fill=False, lw=0.5, color="#555"))
        sh.place("A", (c0[0] + rr * math.cos(math.radians(-60)), c0[1] + rr * math.sin(math.radians(-60))),
                 math.radians(-60), region_main, gid="view:detail-mark", start=2.0, arrow=False, size=FS_HEAD)
        region_det = Bbox.from_extents(DETAIL_BOX[0] + 1, DETAIL_BOX[1] + 1, DETAIL_BOX[2] - 1, DETAIL_BOX[3] - 9)
    # -- dimensions ----------------------------------------------------------------------
    ang_r = {"shoe_arc": 7.0, "tip_gap": 7.0, "pitch": 14.0, "flexure_position": 14.0}
    for d in dims:
        gid = f"dim:{d.key}"
        txt = d.text(units)
        if d.view == "side":
            y = bot - 7
            sh.arrow((sx - t_mm / 2, y), (sx + t_mm / 2, y), gid + "/line")
            for xx in (sx - t_mm / 2, sx + t_mm / 2):
                sh.line([xx, xx], [bot - 1, y - 2])
            sh.later(txt, (sx, y - 1.0), -math.pi / 2, region_side, gid=gid, start=1.0, leader=False)
            continue
        if d.view == "main" or to_det is None:
            _dim_main(sh, d, txt, gid, to_main, k_main, R_env, region_main, ang_r, cx, cy)
        else:
            _dim_detail(sh, d, txt, gid, to_det, k_det, region_det, dwin, outline)
    sh.flush()
    # -- notes, answers, title block -------------------------------------------------------
    y = notes_block(sh, outline, rules, material, units, violations, ligament, dims)
    answers_block(sh, analysis, fidelity, ligament, as_cut, mass_kg, material, y - 5)
    title_block(sh, title or f"Clutch part {label}", design_hash, material, mass_kg, scale, units,
                 date or _dt.date.today().isoformat(), general_tolerance(rules, units), outline)
    return sh.fig


def _runs(mask):
    """Index arrays of the consecutive True stretches of ``mask`` (cyclic)."""
    idx = np.nonzero(mask)[0]
    if len(idx) == 0:
        return []
    splits = np.nonzero(np.diff(idx) > 1)[0] + 1
    runs = np.split(idx, splits)
    if len(runs) > 1 and runs[0][0] == 0 and runs[-1][-1] == len(mask) - 1:
        runs[0] = np.concatenate([runs[-1], runs[0]])
        runs.pop()
    return [r for r in runs if len(r) > 1]


def _detail_window(outline, dims, ligament):
    """The part region of detail A [m]: shoe 0's flexure zone with the detail dimensions'
    anchors, and a margin; None if the part has no flexure zone."""
    pts = [s.point(np.linspace(0, 1, 9)) for s in outline.segments() if s.tag.split("/")[0].split("+")[0]
           in ("flexure_0",)]
    if not pts:
        return None
    P = np.vstack(pts)
    for d in dims:
        if d.view == "detail" and d.kind == "length":
            P = np.vstack([P, [d.anchor[:2], d.anchor[2:4]]])
    x0, y0 = P.min(axis=0)
    x1, y1 = P.max(axis=0)
    m = 0.08 * max(x1 - x0, y1 - y0) + 0.5e-3
    return (x0 - m, y0 - m, x1 + m, y1 + m)


def _outward(p, c) -> float:
    return math.atan2(p[1] - c[1], p[0] - c[0])


def _dim_main(sh, d, txt, gid, to_main, k, R_env, region, ang_r, cx, cy) -> None:
    if d.kind in ("diameter", "radius"):
        c = np.array(d.anchor[:2])
        r, a = d.anchor[2], d.anchor[3]
        p_arc = to_main(c + r * np.array([math.cos(a), math.sin(a)]))
        c_s = to_main(c)
        if d.kind == "radius":
            sh.arrow(tuple(c_s), tuple(p_arc), gid + "/line", style="-|>")
        else:
            q_arc = to_main(c - r * np.array([math.cos(a), math.sin(a)]))
            sh.arrow(tuple(q_arc), tuple(p_arc), gid + "/line")
        sh.later(txt, tuple(p_arc), _outward(p_arc, (cx, cy)), region, gid=gid, start=R_env * k - r * k + 4,
                 arrow=False)
        return
    if d.kind == "angle":
        c0, c1 = d.anchor[2], d.anchor[3]
        rr = R_env * k + ang_r.get(d.key, 7.0)
        sh.arc((cx, cy), rr, c0, c1, gid + "/arc")
        for a, tip in ((c0, c1), (c1, c0)):
            p = np.array([cx + rr * math.cos(a), cy + rr * math.sin(a)])
            sgn = 1 if tip > a else -1
            tdir = np.array([-math.sin(a), math.cos(a)]) * sgn
            sh.arrow(tuple(p + 2.5 * tdir), tuple(p), gid + "/arrow", style="-|>")
            # extension lines from the part's rim; the beam's position from the axis (centre line)
            r_from = 0.0 if d.key == "flexure_position" and abs(a) > 1e-9 else R_env * k + 1
            sh.line([cx + r_from * math.cos(a), cx + (rr + 2) * math.cos(a)],
                    [cy + r_from * math.sin(a), cy + (rr + 2) * math.sin(a)],
                    ls="-" if r_from else (0, (12, 3, 2, 3)))
        am = 0.5 * (c0 + c1)
        pm = (cx + rr * math.cos(am), cy + rr * math.sin(am))
        sh.later(txt, pm, am, region, gid=gid, start=1.5, arrow=False)
        return
    # a width in the main view (the shoe's radial thickness): arrows from outside, pointing in
    a, b = to_main(d.anchor[:2]), to_main(d.anchor[2:4])
    e = (b - a) / np.linalg.norm(b - a)
    sh.arrow(tuple(a - 5 * e), tuple(a), gid + "/arrow", style="-|>")
    sh.arrow(tuple(b + 5 * e), tuple(b), gid + "/arrow", style="-|>")
    sh.later(txt, tuple(b + 5 * e), _outward(b, (cx, cy)), region, gid=gid, start=1.0, arrow=False)


def _dim_detail(sh, d, txt, gid, to_det, k, region, dwin, outline) -> None:
    ax = sh.ax
    mid = np.array([0.5 * (dwin.x0 + dwin.x1), 0.5 * (dwin.y0 + dwin.y1)])
    if d.kind == "radius" and d.key.startswith("fillet"):
        c = np.array(d.anchor[:2])
        r, a = d.anchor[2], d.anchor[3]
        p = to_det(c + r * np.array([math.cos(a), math.sin(a)]))
        cs = to_det(c)
        # leader along the radius, from the centre's side (ISO 129: arrow on the arc)
        ax.add_patch(FancyArrowPatch(tuple(cs), tuple(p), arrowstyle="-|>", mutation_scale=6, lw=0.45,
                                     shrinkA=0, shrinkB=0, gid=gid + "/line"))
        sh.later(txt, tuple(cs), _outward(cs, p), region, gid=gid, start=2.0, arrow=False)
        return
    if d.kind == "radius":  # a point on the root face at radius r (reference)
        r = d.anchor[2]
        ang = 0.0
        p = to_det(np.array([r * math.cos(ang), r * math.sin(ang)]))
        ax.plot([p[0]], [p[1]], "o", ms=1.8, color="black")
        sh.later(txt, tuple(p), math.pi / 2, region, gid=gid, start=3.0)
        return
    if d.kind == "angle":
        c = to_det(d.anchor[:2])
        a0, a1 = d.anchor[2], d.anchor[3]
        rr = 14.0
        for a in (a0, a1):
            sh.line([c[0], c[0] + (rr + 3) * math.cos(a)], [c[1], c[1] + (rr + 3) * math.sin(a)])
        sh.arc(tuple(c), rr, a0, a1, gid + "/arc")
        for a, sgn in ((a0, 1), (a1, -1)):
            p = c + rr * np.array([math.cos(a), math.sin(a)])
            tdir = sgn * np.array([-math.sin(a), math.cos(a)])
            sh.arrow(tuple(p + 2.5 * tdir), tuple(p), gid + "/arrow", style="-|>")
        am = 0.5 * (a0 + a1)
        sh.later(txt, tuple(c + rr * np.array([math.cos(am), math.sin(am)])), am, region, gid=gid, start=1.5,
                 arrow=False)
        return
    a, b = to_det(d.anchor[:2]), to_det(d.anchor[2:4])
    if np.allclose(a, b):  # a measured web or slot: its place
        ax.plot([a[0]], [a[1]], "o", ms=1.8, color="black")
        sh.later(txt, tuple(a), _outward(a, mid), region, gid=gid, start=3.0)
        return
    v = b - a
    L = float(np.linalg.norm(v))
    e = v / L
    nrm = np.array([-e[1], e[0]])
    if d.key == "flexure_length":  # an aligned dimension beside the beam, on its hub side
        side = 1.0 if float(nrm @ (np.asarray(to_det((0.0, 0.0))) - a)) > 0 else -1.0
        off = side * (0.5 * outline.params.flexure_thickness * max(1.0, getattr(outline.params, "flexure_taper", 1.0))
                      * k + 9.0)
        pa, pb = a + off * nrm, b + off * nrm
        for p, q in ((a, pa), (b, pb)):  # extension lines, a small gap from the part, 2 mm past the line
            g0, g1 = p + 0.1 * (q - p), q + np.sign(off) * 2 * nrm
            sh.line([g0[0], g1[0]], [g0[1], g1[1]])
        sh.arrow(tuple(pa), tuple(pb), gid + "/line")
        m = 0.5 * (pa + pb)
        sh.later(txt, tuple(m), math.atan2(off * nrm[1], off * nrm[0]), region, gid=gid, start=1.0, arrow=False)
        return
    # a short width across material: arrows from outside pointing in, the line carried on
    ext = 6.0
    sh.arrow(tuple(a - ext * e), tuple(a), gid + "/arrow", style="-|>")
    sh.arrow(tuple(b + ext * e), tuple(b), gid + "/arrow", style="-|>")
    sh.line([a[0], b[0]], [a[1], b[1]])
    end = b + ext * e if float((b + ext * e - mid) @ (b + ext * e - mid)) > float((a - ext * e - mid) @ (a - ext * e - mid)) \
        else a - ext * e
    sh.later(txt, tuple(end), _outward(end, mid), region, gid=gid, start=1.0, arrow=False)
