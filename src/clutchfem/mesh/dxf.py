"""A DXF drawing's part outline as :class:`~clutchfem.mesh.Loop` s (metres), for meshing a
user's DXF like a STEP file.

Read: LINE, ARC, CIRCLE, SPLINE (control points and knots; rational splines are refused),
LWPOLYLINE and POLYLINE (straight and bulged segments) of the modelspace.  When the drawing
has any of clutchfem's part layers (OUTER, INNER, BORE: a file ``clutchfem export`` wrote)
only those are read, so its TOOLPATH and TEXT layers are not mistaken for the part;
otherwise every curve entity is.  The unit comes from ``$INSUNITS`` (mm, cm, m, in, ft,
um); a drawing without a unit is refused (a part in the wrong unit by 25.4 or 1000 is the
error this prevents).  Entities are chained end to end into closed loops (to 1e-7 of the
part's size, reversing an entity where its other end fits); an open chain is refused,
naming where it ends.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..core import MeshError
from .outline import Loop, Segment, chain_loops, orient_loops

#: $INSUNITS code -> metres per unit
INSUNITS = {1: 0.0254, 2: 0.3048, 4: 1e-3, 5: 1e-2, 6: 1.0, 13: 1e-6, 14: 0.1}
PART_LAYERS = ("OUTER", "INNER", "BORE")


def read_dxf(path) -> list[Loop]:
    """The closed loops of the part drawn in ``path`` (metres; outer ccw, holes cw)."""
    import ezdxf

    path = Path(path)
    try:
        doc = ezdxf.readfile(str(path))
    except (OSError, ezdxf.DXFError) as exc:
        raise MeshError(f"{path}: ezdxf cannot read it as a DXF drawing ({exc})") from None
    code = int(doc.header.get("$INSUNITS", 0))
    if code not in INSUNITS:
        raise MeshError(f"{path}: the drawing declares no length unit ($INSUNITS = {code}); set it to mm (4) or "
                        "inches (1) in the CAD program: a part read in the wrong unit is off by 25.4 or 1000")
    s = INSUNITS[code]
    msp = doc.modelspace()
    layers = {e.dxf.layer.upper() for e in msp}
    only = set(PART_LAYERS) if layers & set(PART_LAYERS) else None
    segs = []
    for e in msp:
        if only is not None and e.dxf.layer.upper() not in only:
            continue
        segs += _segments(e, s, path)
    if not segs:
        raise MeshError(f"{path}: no LINE, ARC, CIRCLE, SPLINE or POLYLINE entities" +
                        (" on the layers OUTER, INNER, BORE" if only else ""))
    size = max(max(abs(v) for v in seg.start + seg.end) for seg in segs)
    return orient_loops(_chain(segs, 1e-7 * size, path))


def _segments(e, s: float, path) -> list[Segment]:
    kind = e.dxftype()
    if kind == "LINE":
        a, b = e.dxf.start, e.dxf.end
        return [Segment("line", (a.x * s, a.y * s), (b.x * s, b.y * s))]
    if kind in ("ARC", "CIRCLE"):
        c, r = e.dxf.center, e.dxf.radius * s
        cx, cy = c.x * s, c.y * s
        if kind == "CIRCLE":
            a0, sweep = 0.0, 2 * math.pi
        else:
            a0 = math.radians(e.dxf.start_angle)
            sweep = (math.radians(e.dxf.end_angle) - a0) % (2 * math.pi) or 2 * math.pi
        p0 = (cx + r * math.cos(a0), cy + r * math.sin(a0))
        p1 = (cx + r * math.cos(a0 + sweep), cy + r * math.sin(a0 + sweep))
        return [Segment("arc", p0, p1 if kind == "ARC" else p0, centre=(cx, cy), radius=r, sweep=sweep)]
    if kind == "SPLINE":
        if e.dxf.flags & 4 and any(w != 1.0 for w in e.weights):
            raise MeshError(f"{path}: a rational SPLINE (weights) is not supported; convert it to a plain B-spline")
        ctrl = [(p[0] * s, p[1] * s) for p in e.control_points]
        knots = list(e.knots)
        if not ctrl or len(knots) != len(ctrl) + e.dxf.degree + 1:
            raise MeshError(f"{path}: a SPLINE without control points and a full knot vector (fit-point splines "
                            "are not read: convert them to control points)")
        k0, k1 = knots[0], knots[-1]
        kn = tuple((k - k0) / (k1 - k0) for k in knots)
        seg = Segment("spline", ctrl[0], ctrl[-1], control=tuple(ctrl), knots=kn, degree=int(e.dxf.degree))
        end = tuple(float(v) for v in seg.point([1.0])[0])
        return [Segment("spline", ctrl[0], end, control=tuple(ctrl), knots=kn, degree=int(e.dxf.degree))]
    if kind in ("LWPOLYLINE", "POLYLINE"):
        from ezdxf.math import bulge_to_arc

        pts = [(v[0], v[1], v[4] if kind == "LWPOLYLINE" else 0.0) for v in
               (e.get_points("xyseb") if kind == "LWPOLYLINE" else
                [(p.dxf.location.x, p.dxf.location.y, 0, 0, p.dxf.bulge) for p in e.vertices])]
        if e.is_closed:
            pts.append(pts[0])
        out = []
        for (x0, y0, b), (x1, y1, _) in zip(pts, pts[1:]):
            p0, p1 = (x0 * s, y0 * s), (x1 * s, y1 * s)
            if abs(b) < 1e-12:
                out.append(Segment("line", p0, p1))
            else:
                c, _, _, r = bulge_to_arc((x0, y0), (x1, y1), b)
                out.append(Segment("arc", p0, p1, centre=(c.x * s, c.y * s), radius=r * s, sweep=4 * math.atan(b)))
        return out
    return []


def _chain(segs: list[Segment], tol: float, path) -> list[Loop]:
    """The entities' closed loops (:func:`~clutchfem.mesh.outline.chain_loops`); an open
    chain or a loop without area is refused naming the file (an open chain's end in mm)."""

    def refuse(end, n):
        return MeshError(f"{path}: the outline is not closed: a chain of {n} entities ends at "
                         f"({end[0] * 1e3:.4g}, {end[1] * 1e3:.4g}) mm with nothing joined to it")

    loops = [Loop(tuple(lp)) for lp in chain_loops(segs, tol, refuse)]
    areas = np.array([abs(lp.area) for lp in loops])
    if np.any(areas <= 0):
        raise MeshError(f"{path}: a closed chain encloses no area")
    return loops
