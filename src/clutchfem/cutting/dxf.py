"""The DXF cutting file (ezdxf): true LINE, ARC, CIRCLE and SPLINE entities, layers, units.

Layers: ``OUTER`` (the outer contour, with every slot that opens to it), ``INNER`` (closed
inner cuts), ``BORE`` (the crankshaft bore), ``TOOLPATH`` (the kerf-compensated path of the
beam, wire or jet centre, only when a process or kerf is given: the nominal layers are the
part itself, never moved) and ``TEXT`` (design label, hash, concept, material, thickness,
units, process, clutchfem version).  ``$INSUNITS`` is 4 (millimetres, the default) or 1
(inches), ``$MEASUREMENT`` 1 or 0 to match; coordinates are written in that unit.

Each loop is closed exactly: a segment starts at the very coordinates where the previous
one ended (arcs are stored by centre, radius and angles, so their ends agree to rounding,
~1e-13 of the radius).  A DXF ARC always turns ccw from its start angle to its end angle:
a cw arc of the outline is written with its ends swapped.  Splines are clamped cubic
B-splines with their control points and full knot vector (no fit points: a CAD system
reproduces exactly the curve written).
"""

from __future__ import annotations

import math
from pathlib import Path

#: $INSUNITS codes and the metres in one unit
UNITS = {"mm": (4, 1e-3), "in": (1, 0.0254)}
LAYERS = {"OUTER": 7, "INNER": 5, "BORE": 3, "TOOLPATH": 1, "TEXT": 8}


def write_dxf(path, loops, *, units: str = "mm", toolpath=None, text: list[str] = ()) -> Path:
    """Write ``loops`` (the part, layers from each loop's ``layer``) and optionally the tool
    path loops and text lines to ``path``; returns the path."""
    import ezdxf

    code, metres = UNITS[units]
    s = 1.0 / metres
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = code
    doc.header["$MEASUREMENT"] = 1 if units == "mm" else 0
    for name, color in LAYERS.items():
        doc.layers.add(name, color=color)
    msp = doc.modelspace()
    for lp in loops:
        _loop(msp, lp, lp.layer or "OUTER", s)
    for lp in toolpath or ():
        _loop(msp, lp, "TOOLPATH", s)
    if text:
        xs = [p for lp in loops for p in lp.points()[:, 0]]
        ys = [p for lp in loops for p in lp.points()[:, 1]]
        x0, y0 = min(xs) * s, min(ys) * s
        h = 0.04 * (max(ys) - min(ys)) * s
        for k, line in enumerate(text):
            msp.add_text(line, height=h, dxfattribs={"layer": "TEXT"}).set_placement((x0, y0 - (k + 2) * 1.6 * h))
    path = Path(path)
    doc.saveas(path)
    return path


def _loop(msp, lp, layer: str, s: float) -> None:
    att = {"layer": layer}
    prev_end = None
    for seg in lp.segments:
        start = prev_end if prev_end is not None else (seg.start[0] * s, seg.start[1] * s)
        end = (seg.end[0] * s, seg.end[1] * s)
        if seg.kind == "line":
            msp.add_line(start, end, dxfattribs=att)
        elif seg.kind == "arc":
            c = (seg.centre[0] * s, seg.centre[1] * s)
            r = seg.radius * s
            if abs(abs(seg.sweep) - 2 * math.pi) < 1e-12:
                msp.add_circle(c, r, dxfattribs=att)
            else:
                a0 = math.degrees(math.atan2(seg.start[1] - seg.centre[1], seg.start[0] - seg.centre[0]))
                a1 = a0 + math.degrees(seg.sweep)
                lo, hi = (a0, a1) if seg.sweep > 0 else (a1, a0)
                msp.add_arc(c, r, lo % 360.0, hi % 360.0, dxfattribs=att)
        else:
            ctrl = [(x * s, y * s) for x, y in seg.control]
            ctrl[0] = start
            msp.add_open_spline(ctrl, degree=seg.degree, knots=list(seg.knots), dxfattribs=att)
        prev_end = end
