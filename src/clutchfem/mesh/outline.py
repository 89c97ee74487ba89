"""A part's exact 2-D outline: closed loops of lines, circle arcs and B-splines, and the OCC
face they bound.

What a cutter's CAD file holds (``clutchfem.cutting`` writes it as DXF and STEP, :mod:`.dxf`
reads a DXF back), and what a user part's DXF becomes before it is meshed like a STEP file.
Lengths in metres, the part in the x-y plane.

Conventions: a :class:`Segment` runs from ``start`` to ``end``; an arc turns by ``sweep``
radians about ``centre`` (ccw > 0; a full circle is one arc of sweep +-2 pi whose start and
end coincide); a spline is a clamped B-spline of ``degree`` with its full knot vector over
[0, 1].  A :class:`Loop` is a closed chain of segments (:func:`chain_loops` chains loose
segments -- a DXF's entities, an OCC model's boundary curves -- end to start, reversing a
segment where its other end fits); the *outer* loop runs ccw and every hole cw, so the
material always lies on the left ("material on the left", the orientation the offsets of
the cutting stage assume).  Areas are exact for lines and arcs (Green's
theorem, closed form) and exact to rounding for splines (Gauss-Legendre of the polynomial
integrand on each knot span).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import gmsh
import numpy as np
from scipy.interpolate import BSpline, make_interp_spline

from ..core import GeometryError

__all__ = ["Loop", "Segment", "chain_loops", "fit_spline", "loops_to_occ", "orient_loops"]

#: relative tolerance (of the part's size) at which two end points are the same point
JOIN_TOL = 1e-9
_GAUSS = np.polynomial.legendre.leggauss(4)


@dataclass(frozen=True)
class Segment:
    """One curve of an outline (see module docstring)."""

    kind: str  # "line" | "arc" | "spline"
    start: tuple[float, float]
    end: tuple[float, float]
    centre: tuple[float, float] | None = None
    radius: float = 0.0
    sweep: float = 0.0
    control: tuple[tuple[float, float], ...] = ()
    knots: tuple[float, ...] = ()
    degree: int = 3
    #: where the segment came from (a curve group of the model, e.g. "contact", "bore"),
    #: or "" -- carried through offsets
    tag: str = field(default="", compare=False)

    # -- geometry ---------------------------------------------------------------------
    @property
    def start_angle(self) -> float:
        cx, cy = self.centre
        return math.atan2(self.start[1] - cy, self.start[0] - cx)

    def _spline(self, nu: int = 0) -> BSpline:
        """The spline (``nu`` = 0) or its ``nu``-th derivative, made once per segment: a
        segment never changes, and making the BSpline from the control tuples cost more than
        evaluating it (the features' and the drawing's samples ask for it thousands of times)."""
        cache = self.__dict__.setdefault("_bsplines", {})  # (not a field: equality, hash, repr ignore it)
        if nu not in cache:
            cache[nu] = (BSpline(np.asarray(self.knots), np.asarray(self.control), self.degree) if nu == 0
                         else self._spline(0).derivative(nu))
        return cache[nu]

    def __getstate__(self) -> dict:
        """Pickled without the splines made (they are made again on first use)."""
        return {k: v for k, v in self.__dict__.items() if k != "_bsplines"}

    def point(self, t) -> np.ndarray:
        """Points at the normalised parameter(s) t in [0, 1] (arc: angle, spline: knot)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if self.kind == "line":
            a, b = np.asarray(self.start), np.asarray(self.end)
            return a + t[:, None] * (b - a)
        if self.kind == "arc":
            ang = self.start_angle + t * self.sweep
            return np.asarray(self.centre) + self.radius * np.column_stack([np.cos(ang), np.sin(ang)])
        return self._spline()(t)

    def derivative(self, t) -> np.ndarray:
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if self.kind == "line":
            return np.tile(np.asarray(self.end) - np.asarray(self.start), (len(t), 1))
        if self.kind == "arc":
            ang = self.start_angle + t * self.sweep
            return self.radius * self.sweep * np.column_stack([-np.sin(ang), np.cos(ang)])
        return self._spline(1)(t)

    def tangent(self, t: float) -> np.ndarray:
        d = self.derivative([t])[0]
        return d / np.linalg.norm(d)

    def sample(self, n: int | None = None, spacing: float | None = None) -> np.ndarray:
        """n points (or points at most ``spacing`` apart) from start to end, both included."""
        if n is None:
            n = max(2, int(math.ceil(self.length / spacing)) + 1) if spacing else 33
            if self.kind == "arc":
                n = max(n, int(abs(self.sweep) / math.radians(5.0)) + 2)
        return self.point(np.linspace(0.0, 1.0, n))

    @property
    def length(self) -> float:
        if self.kind == "line":
            return float(math.dist(self.start, self.end))
        if self.kind == "arc":
            return abs(self.sweep) * self.radius
        x, w = _GAUSS
        total = 0.0
        for a, b in self._spans():
            t = 0.5 * (b - a) * x + 0.5 * (a + b)
            total += 0.5 * (b - a) * float(np.sum(w * np.linalg.norm(self.derivative(t), axis=1)))
        return total

    def _spans(self):
        k = np.unique(np.asarray(self.knots))
        return zip(k[:-1], k[1:])

    def green(self) -> float:
        """The segment's share of the enclosed area, 1/2 int (x dy - y dx) (exact)."""
        if self.kind == "line":
            (x0, y0), (x1, y1) = self.start, self.end
            return 0.5 * (x0 * y1 - x1 * y0)
        if self.kind == "arc":
            cx, cy = self.centre
            r, a0 = self.radius, self.start_angle
            a1 = a0 + self.sweep
            return 0.5 * (r * cx * (math.sin(a1) - math.sin(a0)) - r * cy * (math.cos(a1) - math.cos(a0))
                          + r * r * self.sweep)
        x, w = _GAUSS
        total = 0.0
        for a, b in self._spans():
            t = 0.5 * (b - a) * x + 0.5 * (a + b)
            p, d = self.point(t), self.derivative(t)
            total += 0.25 * (b - a) * float(np.sum(w * (p[:, 0] * d[:, 1] - p[:, 1] * d[:, 0])))
        return total

    def curvature(self, t) -> np.ndarray:
        """Signed curvature (left turn > 0) at the normalised parameter(s) t [1/m]."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if self.kind == "line":
            return np.zeros(len(t))
        if self.kind == "arc":
            return np.full(len(t), math.copysign(1.0 / self.radius, self.sweep))
        d1 = self.derivative(t)
        d2 = self._spline(2)(t)
        return (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3

    def sub(self, t0: float, t1: float) -> "Segment":
        """The part of the segment between the normalised parameters t0 < t1 (a spline's
        part is fitted again through 4 points per knot span; error ~1e-12 of its size)."""
        p0, p1 = (tuple(float(v) for v in self.point([t])[0]) for t in (t0, t1))
        if self.kind == "line":
            return replace(self, start=p0, end=p1)
        if self.kind == "arc":
            return replace(self, start=p0, end=p1, sweep=self.sweep * (t1 - t0))
        n = max(33, 8 * len(self.control))
        u = np.linspace(t0, t1, n)
        return fit_spline(self.point(u), self.tag, params=u)

    # -- transformations --------------------------------------------------------------
    def reversed(self) -> "Segment":
        if self.kind == "line":
            return replace(self, start=self.end, end=self.start)
        if self.kind == "arc":
            return replace(self, start=self.end, end=self.start, sweep=-self.sweep)
        knots = tuple(1.0 - k for k in reversed(self.knots))
        return replace(self, start=self.end, end=self.start, control=tuple(reversed(self.control)), knots=knots)

    def mapped(self, scale: float = 1.0, mirror_y: bool = False) -> "Segment":
        """The segment scaled about the origin and/or reflected y -> -y (a reflection turns
        an arc's sense; the loop it belongs to must then be reversed to keep its sense)."""
        sy = -1.0 if mirror_y else 1.0

        def m(p):
            return (scale * p[0], sy * scale * p[1])

        return replace(self, start=m(self.start), end=m(self.end),
                       centre=None if self.centre is None else m(self.centre), radius=scale * self.radius,
                       sweep=sy * self.sweep, control=tuple(m(c) for c in self.control))


def fit_spline(points: np.ndarray, tag: str = "", params: np.ndarray | None = None) -> Segment:
    """A cubic B-spline segment interpolating ``points`` (n x 2) at ``params`` (default:
    chord length, normalised to [0, 1]); not-a-knot end conditions."""
    pts = np.asarray(points, dtype=float)
    if params is None:
        d = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))]
        params = d / d[-1]
    else:
        params = (params - params[0]) / (params[-1] - params[0])
    k = min(3, len(pts) - 1)
    sp = make_interp_spline(params, pts, k=k)
    return Segment("spline", tuple(pts[0]), tuple(pts[-1]), control=tuple(map(tuple, sp.c)),
                   knots=tuple(float(x) for x in sp.t), degree=k, tag=tag)


@dataclass(frozen=True)
class Loop:
    """A closed chain of segments (see module docstring)."""

    segments: tuple[Segment, ...]
    layer: str = ""

    @property
    def area(self) -> float:
        """Signed enclosed area (ccw > 0) [m^2]."""
        return float(sum(s.green() for s in self.segments))

    def reversed(self) -> "Loop":
        return replace(self, segments=tuple(s.reversed() for s in reversed(self.segments)))

    def points(self, spacing: float | None = None) -> np.ndarray:
        pts = [s.sample(spacing=spacing)[:-1] for s in self.segments]
        return np.vstack(pts)

    def gap(self) -> float:
        """Largest distance between one segment's end and the next one's start [m]."""
        segs = self.segments
        return max(math.dist(a.end, b.start) for a, b in zip(segs, segs[1:] + segs[:1]))

    def contains(self, p) -> bool:
        """Is point p inside (even-odd rule on a fine polygon)?"""
        poly = self.points(spacing=None)
        x, y = poly[:, 0], poly[:, 1]
        x2, y2 = np.roll(x, -1), np.roll(y, -1)
        cond = (y > p[1]) != (y2 > p[1])
        xs = x + (p[1] - y) * (x2 - x) / np.where(y2 != y, y2 - y, 1.0)
        return bool(np.count_nonzero(cond & (p[0] < xs)) % 2)


def chain_loops(segs: list[Segment], tol: float, refuse=None) -> list[list[Segment]]:
    """Closed loops (lists of segments) from unordered segments, chained end to start.

    A segment that closes on itself (a full circle) is a loop of its own.  Otherwise the
    loop grows by the remaining segment whose start or end lies nearest to the loop's end,
    reversed where its end fits (the input's orientation is not relied on: the loops are
    oriented by their areas afterwards, :func:`orient_loops`); it is closed once its end is
    within ``tol`` [m] of its start.  A chain whose end has no segment within ``tol`` is
    refused: ``refuse(end, n)`` (the loose end point and the chain's segment count) gives
    the exception to raise (default: a :class:`~clutchfem.core.GeometryError` naming the
    point), so each reader names its own input.
    """
    left = list(segs)
    loops = []
    while left:
        loop = [left.pop(0)]
        if math.dist(loop[0].start, loop[0].end) < tol:  # a full circle is a loop of its own
            loops.append(loop)
            continue
        while math.dist(loop[-1].end, loop[0].start) > tol:
            end = loop[-1].end
            cands = [(math.dist(s.start, end), i, False) for i, s in enumerate(left)]
            cands += [(math.dist(s.end, end), i, True) for i, s in enumerate(left)]
            if not cands or min(cands)[0] > tol:
                if refuse is None:
                    raise GeometryError(f"the part's boundary does not close near ({end[0]:.6g}, {end[1]:.6g}) m")
                raise refuse(end, len(loop))
            _, i, rev = min(cands)
            s = left.pop(i)
            loop.append(s.reversed() if rev else s)
        loops.append(loop)
    return loops


def orient_loops(loops: list[Loop]) -> list[Loop]:
    """The loops with the outer one (largest |area|) first and ccw, every other one cw."""
    if not loops:
        raise GeometryError("the outline has no closed loop")
    order = sorted(loops, key=lambda lp: -abs(lp.area))
    out = []
    for i, lp in enumerate(order):
        want_ccw = i == 0
        out.append(lp if (lp.area > 0) == want_ccw else lp.reversed())
    return out


def loops_to_occ(loops: list[Loop]) -> int:
    """Build the loops as one OCC plane surface (the first loop the outer one, the others
    holes) in the *current* gmsh model; returns the surface tag.  Points shared by consecutive segments are one OCC
    point, so the curve loops close exactly."""
    occ = gmsh.model.occ
    scale = max(float(np.ptp(lp.points()[:, k])) for lp in loops for k in (0, 1))
    tol = JOIN_TOL * max(scale, 1e-9) * 1e3
    wires, helpers = [], []
    for lp in loops:  # OCC's face builder wants every wire, hole or not, in one sense
        segs = (lp if lp.area > 0 else lp.reversed()).segments
        if lp.gap() > tol:
            raise GeometryError(f"an outline loop is not closed (gap {lp.gap():.3g} m)")
        first = occ.addPoint(*segs[0].start, 0.0)
        cur = first
        curves = []
        for k, s in enumerate(segs):
            nxt = first if k == len(segs) - 1 else occ.addPoint(*s.end, 0.0)
            if s.kind == "line":
                curves.append(occ.addLine(cur, nxt))
            elif s.kind == "arc":
                curves += _occ_arc(s, cur, nxt, helpers)
            else:
                inner = [occ.addPoint(*c, 0.0) for c in s.control[1:-1]]
                helpers += inner
                uniq, mult = np.unique(np.round(np.asarray(s.knots), 14), return_counts=True)
                curves.append(occ.addBSpline([cur] + inner + [nxt], degree=s.degree, knots=list(uniq),
                                             multiplicities=[int(m) for m in mult]))
            cur = nxt
        wires.append(occ.addCurveLoop(curves))
    face = occ.addPlaneSurface(wires)
    # arc centres and spline control points only define curves: left in the model they are
    # free vertices, which a STEP file would carry as a second shape
    occ.remove([(0, t) for t in helpers])
    return face


def _occ_arc(s: Segment, p0: int, p1: int, helpers: list[int]) -> list[int]:
    """An arc as OCC circle arcs of at most 170 degrees each (a circle arc through a centre
    point is ambiguous beyond pi)."""
    occ = gmsh.model.occ
    n = max(1, math.ceil(abs(s.sweep) / math.radians(170.0)))
    c = occ.addPoint(*s.centre, 0.0)
    helpers.append(c)
    tags = [p0] + [occ.addPoint(*s.point(k / n)[0], 0.0) for k in range(1, n)] + [p1]
    return [occ.addCircleArc(tags[k], c, tags[k + 1]) for k in range(n)]
