"""Labelled drawings of concepts (PNG + SVG, matplotlib Agg).

:func:`draw_concept` rebuilds the concept's OCC model (full 360 degrees) in a private gmsh
session with :func:`~clutchfem.geometry.build.build_model`, samples every curve with
``gmsh.model.getValue`` and draws, in the *final* frame (reflected y -> -y for the minus
arrangement, like the mesh):

* the part outline, the bore, the drum circle (dashed) and the contact surfaces (red);
* the shoe and flexure zones hatched in colour, the hub in grey;
* each shoe's centroid (R_Tp) and nominal pivot;
* the concept's :meth:`~clutchfem.geometry.concept.Concept.annotations` (canonical frame,
  mirrored here for minus);
* the direction of rotation (ccw) with the arrangement, and a parameter table.

"""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import gmsh
import numpy as np

from ..core import figure
from .build import build_model
from .concept import Annotation, Concept, ConceptParams, MeshSettings
from .session import gmsh_session

_ZONE_STYLE = {
    "shoe": dict(facecolor="#f4a582", edgecolor="#b2182b", hatch="///"),
    "flexure": dict(facecolor="#92c5de", edgecolor="#2166ac", hatch="xxx"),
    "hub": dict(facecolor="#e0e0e0", edgecolor="#808080", hatch=""),
}


def _chain(segments: list[np.ndarray], tol: float) -> list[np.ndarray]:
    """Join sampled curves (k x 2 arrays) into closed loops by matching end points."""
    segs = [s for s in segments if len(s) >= 2]
    loops = []
    while segs:
        cur = segs.pop(0)
        grown = True
        while grown and np.linalg.norm(cur[0] - cur[-1]) > tol:
            grown = False
            for k, s in enumerate(segs):
                if np.linalg.norm(s[0] - cur[-1]) <= tol:
                    cur = np.vstack([cur, s[1:]])
                elif np.linalg.norm(s[-1] - cur[-1]) <= tol:
                    cur = np.vstack([cur, s[::-1][1:]])
                else:
                    continue
                segs.pop(k)
                grown = True
                break
        loops.append(cur)
    return loops


def sample_concept(concept: Concept, p: ConceptParams, n_per_curve: int = 64) -> dict:
    """Sampled geometry of the full part in the final frame (metres).

    Returns ``{"curves": {tag: xy}, "groups": {name: [curve tags]}, "zones": {name: [loops]},
    "mass": ..., "pivots": ..., "contact_arcs": ...}`` where ``zones`` maps ``shoe_i``,
    ``flexure_i`` and ``hub`` to closed polylines (list of k x 2 arrays)."""
    flip = np.array([1.0, -1.0]) if p.arrangement == "minus" else np.array([1.0, 1.0])
    with gmsh_session(f"draw-{concept.name}"):
        gmsh.option.setNumber("Geometry.Tolerance", 1e-10)
        gmsh.option.setNumber("Geometry.ToleranceBoolean", 1e-10)
        built = build_model(concept, p, MeshSettings(model="full"))
        curves: dict[int, np.ndarray] = {}
        for _, c in gmsh.model.getEntities(1):
            lo, hi = gmsh.model.getParametrizationBounds(1, c)
            xyz = np.asarray(gmsh.model.getValue(1, c, np.linspace(lo[0], hi[0], n_per_curve))).reshape(-1, 3)
            curves[c] = xyz[:, :2] * flip
        tol = 1e-7 * p.drum_radius
        zones: dict[str, list[np.ndarray]] = {}
        for name, tags in built.entity_groups.items():
            if built.group_dims.get(name) != 2 or name == "solid":
                continue
            loops = []
            for t in tags:
                bnd = gmsh.model.getBoundary([(2, t)], combined=False, oriented=False)
                loops += _chain([curves[abs(c)] for _, c in bnd], tol)
            zones[name] = loops
        solid_bnd = gmsh.model.getBoundary([(2, t) for t in built.entity_groups["solid"]],
                                           combined=True, oriented=False)
        groups = {name: list(tags) for name, tags in built.entity_groups.items() if built.group_dims.get(name) == 1}
        groups["outline"] = sorted({abs(c) for _, c in solid_bnd})
    return {"curves": curves, "groups": groups, "zones": zones, "mass": built.mass,
            "pivots": built.pivots, "contact_arcs": built.contact_arcs}


def fmt_param_value(p, name: str) -> str:
    v = getattr(p, name)
    unit = type(p).unit(name)
    if isinstance(v, str):
        return v
    if unit == "m":
        return f"{v * 1e3:.4g} mm"
    if unit in ("-", ""):
        return f"{v:.4g}"
    return f"{v:.4g} {unit}"


def _param_lines(p) -> list[str]:
    rows = []
    off = set(p.inactive())
    for name in type(p).model_fields:
        if name in off:
            continue
        rows.append(f"{name} = {fmt_param_value(p, name)}")
    return rows


def _nobreak(text: str) -> str:
    """Keep numbers with their units when a label is wrapped."""
    for unit in ("mm", "deg", "rpm", "g"):
        text = text.replace(f" {unit}", f"\u00a0{unit}")
    return text


def _common_annotations(concept, p, geo) -> list:
    """Labels every concept gets (canonical frame, shoe 0): the clearance / shoe profile."""
    root, tip = concept.shoe_arc(p)
    tm = root + 0.8 * (tip - root)  # off the shoe's middle, where the concepts label the shoe
    if p.profile == "linear":
        text = f"clearance c = {p.clearance * 1e3:.2f} mm at the root, c_tip = {p.clearance_tip * 1e3:.2f} mm"
    elif p.profile == "table":
        tab = p.table
        text = (f"table profile: clearance {tab[0] * 1e3:.2f} mm at the root -> {tab[-1] * 1e3:.2f} mm at the tip "
                f"(min {min(tab) * 1e3:.2f}, max {max(tab) * 1e3:.2f} mm, {len(tab)} values)")
    elif p.profile == "eccentric":
        text = (f"eccentric profile: e = {p.eccentricity * 1e3:.2f} mm at psi_e = {p.eccentric_angle:.0f} deg, "
                f"c = {p.clearance * 1e3:.2f} mm mid-shoe")
    else:
        text = f"clearance c = {p.clearance * 1e3:.2f} mm"
    r = p.drum_radius - 0.5 * p.clearance
    return [Annotation(text, (r * math.cos(tm), r * math.sin(tm)),
                       (1.4 * p.drum_radius * math.cos(tm), 1.4 * p.drum_radius * math.sin(tm)))]


def _place_labels(fig, ax, anns, flip, R_mm: float, lim: float, n: int) -> None:
    """Draw the callouts outside the drum circle, inside the axes and clear of each other.

    The part has n identical sectors, so a label about shoe 0 may point at the same feature
    on any shoe: each label tries, in order, small angle offsets from the radial line through
    its feature on every shoe, at growing radii, then larger offsets; the first free spot
    wins.  Arrows then run radially outwards and do not cross each other."""
    renderer = fig.canvas.get_renderer()
    inv = ax.transData.inverted()
    placed: list[tuple[float, float, float, float]] = []
    mm = 1e3

    arrows: list[tuple[np.ndarray, np.ndarray]] = []

    def crosses(seg, bb, pad=0.3) -> bool:
        """Does the segment seg = (p, q) pass through the box bb (Liang-Barsky clipping)?"""
        (px, py), (qx, qy) = seg
        dx, dy = qx - px, qy - py
        lo, hi = 0.0, 1.0
        for pk, qk in ((-dx, px - (bb[0] - pad)), (dx, (bb[2] + pad) - px),
                       (-dy, py - (bb[1] - pad)), (dy, (bb[3] + pad) - py)):
            if abs(pk) < 1e-12:
                if qk < 0:
                    return False
                continue
            t = qk / pk
            if pk < 0:
                lo = max(lo, t)
            else:
                hi = min(hi, t)
            if lo > hi:
                return False
        return True

    def fits(bb, seg) -> bool:
        x0, y0, x1, y1 = bb
        if x0 < -lim or x1 > lim or y0 < -lim or y1 > lim:
            return False
        nx = min(max(0.0, x0), x1)  # nearest point of the box to the centre
        ny = min(max(0.0, y0), y1)
        if math.hypot(nx, ny) < 1.04 * R_mm:
            return False
        if not all(x1 + 0.6 < a0 or a1 + 0.6 < x0 or y1 + 0.6 < b0 or b1 + 0.6 < y0 for a0, b0, a1, b1 in placed):
            return False
        return not any(crosses(seg, b) for b in placed) and not any(crosses(a, bb) for a in arrows)

    radii = (1.15 * R_mm, 1.3 * R_mm, 1.45 * R_mm)
    offsets = [(0.0, 0.15, -0.15), (0.3, -0.3, 0.5, -0.5, 0.7, -0.7)]
    for a in anns:
        at0 = np.array(a.at) * flip * mm
        text = textwrap.fill(_nobreak(a.text), 32)
        cands = [(k, d, r) for group in offsets for d in group for k in range(n) for r in radii]
        for j, (k, d, r) in enumerate(cands):
            c, s_ = math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n)
            at = np.array([c * at0[0] - s_ * at0[1], s_ * at0[0] + c * at0[1]])
            th = math.atan2(at[1], at[0]) + d
            xy = (r * math.cos(th), r * math.sin(th))
            probe = ax.text(*xy, text, fontsize=8, ha="center", va="center")  # measures the box
            ext = probe.get_window_extent(renderer).expanded(1.08, 1.3).transformed(inv)
            probe.remove()
            bb = (ext.x0, ext.y0, ext.x1, ext.y1)
            # the arrow, from the box's edge towards the feature (its start is inside the box)
            c = np.array(xy)
            v = at - c
            t_edge = min(0.5 * (bb[2] - bb[0]) / max(abs(v[0]), 1e-9), 0.5 * (bb[3] - bb[1]) / max(abs(v[1]), 1e-9))
            seg = (c + min(t_edge, 1.0) * v, at)
            if fits(bb, seg) or j == len(cands) - 1:
                placed.append(bb)
                arrows.append(seg)
                ax.annotate(text, xy=at, xytext=xy, fontsize=8, ha="center", va="center", zorder=8,
                            bbox=dict(boxstyle="round,pad=0.25", fc="white", ec="0.6", lw=0.6),
                            arrowprops=dict(arrowstyle="->", lw=0.8, color="0.2", shrinkA=2))
                break


def draw_concept(concept: Concept, params: ConceptParams, out_stem: Path,
                 mesh=None, dpi: int = 110) -> list[Path]:
    """Draw ``concept`` with ``params``; write ``<out_stem>.png`` and ``<out_stem>.svg``
    (``clutchfem geometry``): the part with its zones, contact surfaces, drum circle, shoe
    centroids and pivots, labelled dimensions and the parameter table with derived masses.

    Parameters
    ----------
    concept : Concept
        The concept (:func:`~clutchfem.get_concept`).
    params : ConceptParams
        Its parameter set (``concept.Params(...)`` or ``concept.params(...)``).
    out_stem : path
        The files' path without suffix (its folder is made).
    mesh : ClutchMesh, optional
        Overlaid faintly, its size quoted in the title (read only through its ``mesh``,
        ``n_elements`` and ``mesh_settings``: the stage above this one).
    dpi : int
        Resolution of the PNG.

    Returns
    -------
    list of Path
        ``[png, svg]``.

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> c = cf.get_concept("concept1")
    >>> files = cf.draw_concept(c, c.Params(), pathlib.Path(tempfile.mkdtemp()) / "concept1", dpi=40)
    >>> [f.name for f in files], all(f.stat().st_size > 0 for f in files)
    (['concept1.png', 'concept1.svg'], True)
    """
    from matplotlib.patches import FancyArrowPatch, PathPatch
    from matplotlib.path import Path as MPath

    p = params
    out_stem = Path(out_stem)
    out_stem.parent.mkdir(parents=True, exist_ok=True)
    geo = sample_concept(concept, p)
    mm = 1e3
    Rd = p.drum_radius
    minus = p.arrangement == "minus"
    flip = np.array([1.0, -1.0]) if minus else np.array([1.0, 1.0])

    fig, ax = figure(figsize=(12.0, 8.2))
    fig.subplots_adjust(left=0.04, right=0.70, top=0.88 if mesh is not None else 0.91, bottom=0.07)
    # zones (hatched)
    for name, loops in sorted(geo["zones"].items()):
        kind = name.split("_")[0]
        st = _ZONE_STYLE.get(kind)
        if st is None or not loops:
            continue
        verts, codes = [], []
        for lp in loops:
            verts += list(lp * mm) + [lp[0] * mm]
            codes += [MPath.MOVETO] + [MPath.LINETO] * (len(lp) - 1) + [MPath.CLOSEPOLY]
        # add_patch would find the data limits curve by curve through matplotlib's Bezier
        # iteration (a fifth of a drawing's time for these polygons of straight segments):
        # the same limits from the vertices, the same patch on the axes
        ax.add_artist(PathPatch(MPath(np.array(verts), codes), lw=0.0, alpha=0.55, **st))
        ax.update_datalim(np.array(verts))
    # mesh overlay
    if mesh is not None:
        m = mesh.mesh
        ax.triplot(m.p[0] * mm, m.p[1] * mm, m.t[:3].T, lw=0.2, color="0.25", alpha=0.6, zorder=3)
    # outline, bore, contact
    contact = set(geo["groups"].get("contact", []))
    bore = set(geo["groups"].get("bore", []))
    for c in geo["groups"]["outline"]:
        xy = geo["curves"][c] * mm
        if c in contact:
            ax.plot(xy[:, 0], xy[:, 1], color="#d7191c", lw=2.2, zorder=4, solid_capstyle="butt")
        elif c in bore:
            ax.plot(xy[:, 0], xy[:, 1], color="k", lw=1.0, zorder=4)
        else:
            ax.plot(xy[:, 0], xy[:, 1], color="k", lw=1.1, zorder=4)
    th = np.linspace(0, 2 * np.pi, 721)
    ax.plot(Rd * mm * np.cos(th), Rd * mm * np.sin(th), "--", color="0.3", lw=0.9, zorder=3)
    ax.plot([0], [0], "k+", ms=8)
    # centroids and pivots
    for i in range(len(geo["pivots"])):
        sh = geo["mass"].get(f"shoe_{i}")
        if sh:
            cx, cy = np.array(sh["centroid"]) * mm
            ax.plot(cx, cy, marker="o", ms=6, mfc="white", mec="k", zorder=6)
            ax.plot(cx, cy, marker="+", ms=6, color="k", zorder=7)
        px, py = np.array(geo["pivots"][i]) * mm
        ax.plot(px, py, marker="^", ms=7, color="#1a9641", mec="k", zorder=6)
    # annotations (canonical frame -> final frame), placed outside the drum, not overlapping
    lim = 1.62 * Rd * mm
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    anns = list(concept.annotations(p)) + _common_annotations(concept, p, geo)
    _place_labels(fig, ax, anns, flip, Rd * mm, lim, p.n_shoes)
    # rotation arrow (always ccw in the final frame): inside the bore, where nothing else is drawn
    r_arr = 0.6 * p.bore_radius * mm
    th_arr = np.radians(np.linspace(-110.0, 150.0, 60))
    ax.plot(r_arr * np.cos(th_arr), r_arr * np.sin(th_arr), color="#5e3c99", lw=1.6, zorder=8)
    ax.add_patch(FancyArrowPatch((r_arr * math.cos(th_arr[-3]), r_arr * math.sin(th_arr[-3])),
                                 (r_arr * math.cos(th_arr[-1]), r_arr * math.sin(th_arr[-1])),
                                 arrowstyle="-|>", mutation_scale=14, lw=1.6, color="#5e3c99", zorder=8))
    ax.set_title(f"rotation counter-clockwise (arrow in the bore): {p.arrangement} arrangement",
                 fontsize=10, color="#5e3c99")
    # legend
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles = [Patch(alpha=0.55, **_ZONE_STYLE["shoe"], label="shoe zone"),
               Patch(alpha=0.55, **_ZONE_STYLE["flexure"], label="flexure zone"),
               Patch(alpha=0.55, **_ZONE_STYLE["hub"], label="hub"),
               Line2D([], [], color="#d7191c", lw=2.2, label="contact surface"),
               Line2D([], [], color="0.3", ls="--", lw=0.9, label=f"drum, R_d = {Rd * mm:g} mm"),
               Line2D([], [], marker="o", mfc="white", mec="k", ls="", label="shoe centroid (R_Tp)"),
               Line2D([], [], marker="^", color="#1a9641", mec="k", ls="", label="nominal pivot")]
    # outside the axes (below the parameter table), so that all four corners take labels
    fig.legend(handles=handles, loc="lower left", fontsize=7.5, framealpha=0.9, bbox_to_anchor=(0.715, 0.07))
    ax.set_xlabel("x [mm]")
    ax.tick_params(labelsize=7)
    title = concept.title or concept.name
    if mesh is not None:
        title += f"\nmesh: {mesh.n_elements} P{mesh.mesh_settings.get('order', 2) if mesh.mesh_settings else 2} elements"
    fig.suptitle(title, fontsize=12)
    # parameter table
    sh = geo["mass"].get("shoe_0", {})
    rho = 7850.0
    lines = _param_lines(p)
    if sh:
        lines += ["", "derived (steel, 7850 kg/m^3):",
                  f"shoe mass = {sh['area'] * rho * p.thickness * 1e3:.2f} g",
                  f"R_Tp = {sh['radius'] * mm:.2f} mm",
                  f"part mass = {geo['mass']['solid']['area'] * rho * p.thickness * 1e3:.1f} g"]
    fig.text(0.715, 0.90, f"{concept.name} parameters", fontsize=10, fontweight="bold", va="top")
    fig.text(0.715, 0.87, "\n".join(lines), fontsize=8.2, family="monospace", va="top",
             bbox=dict(boxstyle="round,pad=0.5", fc="#f7f7f7", ec="0.6"))
    # not with_suffix: a stem like "out/concept3.1" must give concept3.1.png, not concept3.png
    png, svg = out_stem.parent / f"{out_stem.name}.png", out_stem.parent / f"{out_stem.name}.svg"
    fig.savefig(png, dpi=dpi)
    fig.savefig(svg)
    return [png, svg]
