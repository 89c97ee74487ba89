"""The whole part's exact outline, read from the OCC model the concept builds.

:func:`part_outline` builds the concept's full 360 degree model with the generic pipeline
(:func:`clutchfem.geometry.build_model`, ``MeshSettings(model="full")``: every shoe, the
bore cut), takes the boundary of the union of its surfaces (the zone partition's inner
edges cancel), and turns every OCC curve into an exact :class:`~clutchfem.mesh.Segment`:

* the OCC type (``gmsh.model.getType``: Line, Circle, Ellipse -- a disc's rim --,
  TrimmedCurve, BSpline) is a hint only; each curve is *measured*: a line if every sample lies
  on its chord, a circle arc if every sample lies on the circle through its ends and its
  middle (centre and radius from those three points), both to 1 nm; anything else (the table
  profile's spline) becomes a cubic B-spline interpolating the OCC curve at its own
  parameters, refined until it deviates less than :data:`SPLINE_TOL` from the OCC curve at
  every mid-parameter;
* the curves are chained end to end into closed loops (the outer contour with the slots that
  open to it, the bore, any closed inner cut), pieces that OCC split on one line or one
  circle are merged (no polyline soup), and the outer loop runs ccw, holes cw;
* each segment carries the zone it bounds (``shoe_0``, ``flexure_1``, ``hub``) and whether
  it is contact surface or bore (the model's physical groups), for the manufacturability
  messages;
* the minus arrangement is the canonical model reflected y -> -y (exactly, on the segments):
  the outline is in the final frame, as the part is cut.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import gmsh
import numpy as np

from ..core import GeometryError
from ..geometry import MeshSettings, build_model, gmsh_session
from ..mesh import Loop, Segment, chain_loops, fit_spline, orient_loops

#: largest deviation [m] of an exported spline from the OCC curve it stands for
SPLINE_TOL = 1e-9
#: a sample farther than this [m] from a line / circle makes the curve a spline
SHAPE_TOL = 1e-9


@dataclass(frozen=True)
class PartOutline:
    """The part as a cutter sees it (final frame, metres): loops with layers, and what it is.

    ``loops[0]`` is the outer contour (layer OUTER, ccw), the others holes (BORE or INNER,
    cw).  ``occ_area`` is the OCC-exact area of the built model, the cross-check of the
    outline's own (Green's theorem) area."""

    loops: tuple[Loop, ...]
    concept: str
    params: object
    occ_area: float
    mirrored: bool
    zones: dict = field(default_factory=dict)

    @property
    def area(self) -> float:
        return float(sum(lp.area for lp in self.loops))

    @property
    def thickness(self) -> float:
        return float(self.params.thickness)

    def segments(self):
        for lp in self.loops:
            yield from lp.segments

    def max_radius(self) -> float:
        """Largest distance of the outline from the axis [m] (sampled at 1 um; arcs exact)."""
        best = 0.0
        for s in self.segments():
            if s.kind == "arc":
                c = np.asarray(s.centre)
                d = float(np.hypot(*c))
                if d < 1e-12:
                    best = max(best, s.radius)
                    continue
            best = max(best, float(np.hypot(*s.sample(spacing=1e-6).T).max()))
        return best


def part_outline(concept, params) -> PartOutline:
    """The exact outline of ``concept`` built with ``params`` (see module docstring)."""
    with gmsh_session("export"):
        bm = build_model(concept, params, MeshSettings(model="full"))
        zone_of = {}
        for name, tags in bm.entity_groups.items():
            if bm.group_dims.get(name) == 2 and name != "solid":
                for t in tags:
                    zone_of[t] = name
        contact = set(bm.entity_groups.get("contact", []))
        bore = set(bm.entity_groups.get("bore", []))
        surfaces = bm.entity_groups["solid"]
        bnd = gmsh.model.getBoundary([(2, s) for s in surfaces], combined=True, oriented=False)
        segs = []
        for c in sorted({abs(t) for _, t in bnd}):
            up, _ = gmsh.model.getAdjacencies(1, c)
            zones = sorted({zone_of.get(int(s), "hub") for s in up if int(s) in surfaces})
            tag = "+".join(zones) + ("/contact" if c in contact else "") + ("/bore" if c in bore else "")
            s = _segment(c, tag)
            segs.append(s)
        occ_area = float(bm.mass["solid"]["area"])
        mirrored = bm.mirrored
    scale = float(params.drum_radius)
    # chained to 1e-7 of the drum radius, OCC's orientation signs not relied on
    loops = [Loop(tuple(_merge(lp, scale))) for lp in chain_loops(segs, 1e-7 * scale)]
    if mirrored:
        loops = [Loop(tuple(s.mapped(mirror_y=True) for s in lp.segments)).reversed() for lp in loops]
    loops = orient_loops(loops)
    named = [Loop(loops[0].segments, "OUTER")]
    for lp in loops[1:]:
        bore_loop = all(s.tag.endswith("/bore") for s in lp.segments)
        named.append(Loop(lp.segments, "BORE" if bore_loop else "INNER"))
    return PartOutline(tuple(named), concept.name, params, occ_area, mirrored)


def _segment(c: int, tag: str) -> Segment:
    """The exact segment of OCC curve ``c`` in its own parameter direction (measured: see
    module docstring)."""
    lo, hi = (float(v[0]) for v in gmsh.model.getParametrizationBounds(1, c))
    u = np.linspace(lo, hi, 33)
    xy = np.asarray(gmsh.model.getValue(1, c, u)).reshape(-1, 3)[:, :2]
    p0, p1, pm = xy[0], xy[-1], xy[16]
    chord = p1 - p0
    L = float(np.linalg.norm(chord))
    kind = gmsh.model.getType(1, c)
    if L > 0 and kind != "BSpline":
        n = np.array([-chord[1], chord[0]]) / L
        if np.max(np.abs((xy - p0) @ n)) < SHAPE_TOL:
            return Segment("line", tuple(p0), tuple(p1), tag=tag)
    centre = _circumcentre(p0, pm, p1) if L > 0 else _circumcentre(xy[0], xy[11], xy[22])
    if centre is not None and kind != "BSpline":
        r = float(np.linalg.norm(xy[0] - centre))
        if np.max(np.abs(np.linalg.norm(xy - centre, axis=1) - r)) < SHAPE_TOL:
            ang = np.unwrap(np.arctan2(xy[:, 1] - centre[1], xy[:, 0] - centre[0]))
            sweep = float(ang[-1] - ang[0])
            if L == 0:  # a full circle
                sweep = math.copysign(2 * math.pi, sweep)
            return Segment("arc", tuple(p0), tuple(p1), centre=tuple(centre), radius=r, sweep=sweep, tag=tag)
    return _spline_of(c, lo, hi, tag)


def _circumcentre(a, b, c):
    d = 2.0 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]))
    if abs(d) < 1e-30:
        return None
    ux = ((a @ a) * (b[1] - c[1]) + (b @ b) * (c[1] - a[1]) + (c @ c) * (a[1] - b[1])) / d
    uy = ((a @ a) * (c[0] - b[0]) + (b @ b) * (a[0] - c[0]) + (c @ c) * (b[0] - a[0])) / d
    return np.array([ux, uy])


def _spline_of(c: int, lo: float, hi: float, tag: str) -> Segment:
    """A cubic B-spline through the OCC curve at its own parameters, refined until it lies
    within :data:`SPLINE_TOL` of the curve at every mid-parameter."""
    for n in (65, 129, 257, 513, 1025, 2049, 4097):
        u = np.linspace(lo, hi, n)
        xy = np.asarray(gmsh.model.getValue(1, c, u)).reshape(-1, 3)[:, :2]
        seg = fit_spline(xy, tag, params=u)
        um = 0.5 * (u[1:] + u[:-1])
        ref = np.asarray(gmsh.model.getValue(1, c, um)).reshape(-1, 3)[:, :2]
        dev = float(np.max(np.linalg.norm(seg.point((um - lo) / (hi - lo)) - ref, axis=1)))
        if dev < SPLINE_TOL:
            return seg
    raise GeometryError(f"curve {c}: no spline within {SPLINE_TOL:g} m of the OCC curve (last {dev:.3g} m)")


def _merge(loop: list[Segment], scale: float) -> list[Segment]:
    """Consecutive pieces of one line or one circle (same zone tag) joined into one."""
    tol = 1e-9 * max(scale, 1.0)
    out: list[Segment] = []
    for s in loop + ([] if len(loop) < 2 else []):
        if out and _same_carrier(out[-1], s, tol):
            out[-1] = _joined(out[-1], s)
        else:
            out.append(s)
    while len(out) > 1 and _same_carrier(out[-1], out[0], tol):
        out[0] = _joined(out.pop(), out[0])
    return out


def _same_carrier(a: Segment, b: Segment, tol: float) -> bool:
    if a.kind != b.kind or a.tag != b.tag or a.kind == "spline":
        return False
    if a.kind == "line":
        da, db = np.subtract(a.end, a.start), np.subtract(b.end, b.start)
        da, db = da / np.linalg.norm(da), db / np.linalg.norm(db)
        return abs(da[0] * db[1] - da[1] * db[0]) < 1e-12 and da @ db > 0
    return (math.dist(a.centre, b.centre) < tol and abs(a.radius - b.radius) < tol
            and a.sweep * b.sweep > 0 and abs(a.sweep + b.sweep) < 2 * math.pi - 1e-9)


def _joined(a: Segment, b: Segment) -> Segment:
    if a.kind == "line":
        return Segment("line", a.start, b.end, tag=a.tag)
    return Segment("arc", a.start, b.end, centre=a.centre, radius=a.radius, sweep=a.sweep + b.sweep, tag=a.tag)
