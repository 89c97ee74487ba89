"""Offset outlines: the kerf-compensated tool path and the as-cut part.

A loop runs with the material on its left (outer contour ccw, holes cw), so an offset by
``d`` to the *right* of every segment moves into the waste (d > 0: the tool path, the
centre of the beam, wire or jet at d = kerf / 2) and an offset to the left (d < 0) into the
material (the part a kerf wider than planned by ``delta`` leaves: d = -delta / 2).

Per segment the offset is exact for lines (shifted) and arcs (same centre, radius r +- d);
a spline is offset point by point along its normal and fitted again (its deviation from
the exact offset is checked at every mid-parameter against :data:`OFFSET_TOL`).  Where two
segments meet at a corner the offsets are joined as a cutter's compensation joins them: on
the side where they part, by an arc of radius |d| about the corner (an outside corner of the
path: the beam turns about the corner, whose material edge stays sharp); on the side where
they cross, they are trimmed at their intersection (an inside corner: the beam cannot reach
it, and the part keeps a round of radius |d| there).  Tangent joins (the fillets) need
neither.  An arc or spline whose radius on the offset side is smaller than |d| has no offset
(a cusp): refused, naming the place.  The finished path is verified to keep at least
|d| (less 0.1 %) from every point of the nominal outline: a gap narrower than the kerf shows
as a refusal, never as a gouged part.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial import cKDTree

from ..core import GeometryError
from ..mesh import Loop, Segment, fit_spline

#: largest deviation [m] of an offset spline from the exact offset curve
OFFSET_TOL = 1e-9
#: turns below this angle [rad] are tangent joins
TANGENT = 1e-6


def _normal_right(t: np.ndarray) -> np.ndarray:
    return np.column_stack([t[:, 1], -t[:, 0]])


def offset_segment(s: Segment, d: float) -> Segment:
    """The segment offset by ``d`` to its right (d < 0: to its left)."""
    if s.kind == "line":
        t = np.subtract(s.end, s.start)
        n = np.array([t[1], -t[0]]) / np.linalg.norm(t)
        return Segment("line", tuple(np.add(s.start, d * n)), tuple(np.add(s.end, d * n)), tag=s.tag)
    if s.kind == "arc":
        r = s.radius + d * math.copysign(1.0, s.sweep)
        if r <= 1e-12:
            cx, cy = s.centre
            raise GeometryError(f"an offset of {abs(d) * 1e3:.4g} mm does not fit in the arc of radius "
                                f"{s.radius * 1e3:.4g} mm centred at ({cx * 1e3:.3f}, {cy * 1e3:.3f}) mm")
        c = np.asarray(s.centre)

        def moved(p):
            v = np.subtract(p, c)
            return tuple(c + r * v / np.linalg.norm(v))

        return Segment("arc", moved(s.start), moved(s.end), centre=s.centre, radius=r, sweep=s.sweep, tag=s.tag)
    k = s.curvature(np.linspace(0, 1, 401))
    if np.any(k * d < 0) and np.max(np.abs(k[k * d < 0])) * abs(d) >= 1.0:  # turning towards the offset side
        raise GeometryError(f"an offset of {abs(d) * 1e3:.4g} mm does not fit in a curve of the profile near "
                            f"({s.start[0] * 1e3:.3f}, {s.start[1] * 1e3:.3f}) mm (its radius is smaller)")
    for n in (65, 129, 257, 513, 1025, 2049):
        u = np.linspace(0.0, 1.0, n)
        pts = s.point(u) + d * _normal_right(np.apply_along_axis(lambda v: v / np.linalg.norm(v), 1, s.derivative(u)))
        seg = fit_spline(pts, s.tag, params=u)
        um = 0.5 * (u[1:] + u[:-1])
        der = s.derivative(um)
        exact = s.point(um) + d * _normal_right(der / np.linalg.norm(der, axis=1)[:, None])
        if np.max(np.linalg.norm(seg.point(um) - exact, axis=1)) < OFFSET_TOL:
            return seg
    raise GeometryError("an offset spline could not be fitted within 1 nm")


def _intersect(a: Segment, b: Segment) -> tuple[float, float]:
    """Parameters (s, t) with a(s) = b(t) near a's end and b's start (Newton, 2 x 2)."""
    s, t = 1.0, 0.0
    for _ in range(60):
        r = a.point([s])[0] - b.point([t])[0]
        J = np.column_stack([a.derivative([s])[0], -b.derivative([t])[0]])
        try:
            ds, dt = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError:
            break
        s, t = s + ds, t + dt
        if abs(ds) + abs(dt) < 1e-15:
            break
    ok = 0.0 <= s <= 1.0 + 1e-9 and -1e-9 <= t <= 1.0 and np.linalg.norm(a.point([s])[0] - b.point([t])[0]) < 1e-10
    if not ok:
        raise GeometryError(f"the offset curves do not meet near ({a.end[0] * 1e3:.3f}, {a.end[1] * 1e3:.3f}) mm: "
                            "a feature there is smaller than the offset")
    return min(s, 1.0), max(t, 0.0)


def offset_loop(loop: Loop, d: float) -> Loop:
    """The loop offset by ``d`` to the right of travel (see module docstring)."""
    segs = loop.segments
    off = [offset_segment(s, d) for s in segs]
    n = len(segs)
    joins: list[Segment | None] = [None] * n
    for i in range(n):
        j = (i + 1) % n
        if n == 1:
            break
        ta, tb = segs[i].tangent(1.0), segs[j].tangent(0.0)
        ang = math.atan2(ta[0] * tb[1] - ta[1] * tb[0], ta @ tb)
        if abs(ang) < TANGENT:
            mid = tuple(0.5 * (np.asarray(off[i].end) + np.asarray(off[j].start)))
            off[i], off[j] = _with_end(off[i], mid), _with_start(off[j], mid)
        elif (d > 0) == (ang > 0):  # the offsets part: an arc about the corner
            joins[i] = Segment("arc", off[i].end, off[j].start, centre=segs[i].end, radius=abs(d), sweep=ang,
                               tag=segs[i].tag)
        else:  # the offsets cross: trim both at the intersection
            s, t = _intersect(off[i], off[j])
            off[i], off[j] = off[i].sub(0.0, s), off[j].sub(t, 1.0)
            p = off[i].end
            off[j] = _with_start(off[j], p)
    out = []
    for i in range(n):
        out.append(off[i])
        if joins[i] is not None:
            out.append(joins[i])
    new = Loop(tuple(out), loop.layer)
    _verify(loop, new, d)
    return new


def _with_start(s: Segment, p) -> Segment:
    if s.kind == "spline":
        c = list(s.control)
        c[0] = tuple(p)
        return Segment("spline", tuple(p), s.end, control=tuple(c), knots=s.knots, degree=s.degree, tag=s.tag)
    return Segment(s.kind, tuple(p), s.end, centre=s.centre, radius=s.radius, sweep=s.sweep, tag=s.tag)


def _with_end(s: Segment, p) -> Segment:
    if s.kind == "spline":
        c = list(s.control)
        c[-1] = tuple(p)
        return Segment("spline", s.start, tuple(p), control=tuple(c), knots=s.knots, degree=s.degree, tag=s.tag)
    return Segment(s.kind, s.start, tuple(p), centre=s.centre, radius=s.radius, sweep=s.sweep, tag=s.tag)


def _verify(nominal: Loop, new: Loop, d: float) -> None:
    """Every point of the offset keeps >= |d| (1 - 1e-3) from the nominal loop."""
    if d == 0:
        return
    h = min(abs(d) * 0.1, 20e-6)
    ref = nominal.points(spacing=h)
    pts = new.points(spacing=4 * h)
    dist, idx = cKDTree(ref).query(pts)
    k = int(np.argmin(dist))
    if dist[k] < abs(d) * (1 - 1e-3):
        x, y = pts[k]
        raise GeometryError(f"the {'tool path' if d > 0 else 'as-cut outline'} offset by {abs(d) * 1e3:.4g} mm "
                            f"comes within {dist[k] * 1e3:.4g} mm of the part at ({x * 1e3:.3f}, {y * 1e3:.3f}) mm: "
                            f"a gap or strip there is narrower than {2 * abs(d) * 1e3:.4g} mm")


def offset_loops(loops, d: float) -> list[Loop]:
    """Every loop offset by ``d`` (see :func:`offset_loop`)."""
    return [offset_loop(lp, d) for lp in loops]

