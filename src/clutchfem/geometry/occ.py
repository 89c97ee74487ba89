"""Small gmsh-OCC drawing primitives used by the concept files in ``geometries/``.

All functions add entities to the current gmsh model (``gmsh.model.occ``) and return the tag
of a plane surface.  Angles in radians, lengths in metres, z = 0 plane.

The cut-outs of a one-piece clutch (slots, reliefs) are built as *rounded* annular sectors:
their corners become the fillets of the material's concave corners, which is where flexure
stresses concentrate.  The fillet arcs are exact circles tangent to the radial sides and to
the bounding circles (closed-form tangent points below).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import gmsh
import numpy as np

from ..core import wrap_angle
from .profile import TABLE_N

occ = gmsh.model.occ


def _pt(x: float, y: float) -> int:
    return occ.addPoint(x, y, 0.0)


def _ang(p, ref: float) -> float:
    """Polar angle of point p, unwrapped to lie within pi of ``ref``."""
    return wrap_angle(math.atan2(p[1], p[0]), ref)


def _fillet_corner(R: float, side_angle: float, rho: float, inner: bool, into: float):
    """Fillet circle of radius rho tangent to the radial line at ``side_angle`` and to the
    circle of radius R (``inner``: region outside that circle; else inside).  ``into`` is +1
    when the region lies on the ccw side of the line, -1 otherwise.

    Returns (centre, tangent point on the line, tangent point on the circle).
    """
    u = np.array([math.cos(side_angle), math.sin(side_angle)])
    v = into * np.array([-math.sin(side_angle), math.cos(side_angle)])
    rc = R + rho if inner else R - rho
    d = math.sqrt(rc * rc - rho * rho)
    c = d * u + rho * v
    t_line = d * u
    t_circ = R * c / np.linalg.norm(c)
    return c, t_line, t_circ


def annular_sector(r0: float, r1: float, t0: float, t1: float, fillet: float = 0.0) -> int:
    """Plane surface {r0 <= r <= r1, t0 <= theta <= t1}, corners rounded with ``fillet``.

    ``r0`` may be 0 (a circular sector, then only the outer corners are rounded).  The span
    ``t1 - t0`` must lie in (0, 2 pi).
    """
    if not (0.0 <= r0 < r1) or not (0.0 < t1 - t0 < 2 * math.pi):
        raise ValueError(f"bad annular sector r=[{r0}, {r1}] t=[{t0}, {t1}]")
    o = _pt(0.0, 0.0)
    curves: list[int] = []
    rho = float(fillet)
    if rho > 0 and (2 * rho > r1 - r0 + 1e-15):
        raise ValueError("fillet larger than half the sector height")

    def polar(r, t):
        return (r * math.cos(t), r * math.sin(t))

    if rho == 0.0:
        i0 = _pt(*polar(r0, t0)) if r0 > 0 else o
        i1 = _pt(*polar(r0, t1)) if r0 > 0 else o
        o1 = _pt(*polar(r1, t1))
        o0 = _pt(*polar(r1, t0))
        if r0 > 0:
            curves += _arc_pts(i0, i1, r0, t0, t1, o)
        curves.append(occ.addLine(i1, o1))
        curves += _arc_pts(o1, o0, r1, t1, t0, o)
        curves.append(occ.addLine(o0, i0))
    else:
        # corner fillets: (radius, side angle, inner?, into)
        c_o1, l_o1, k_o1 = _fillet_corner(r1, t1, rho, False, -1.0)
        c_o0, l_o0, k_o0 = _fillet_corner(r1, t0, rho, False, +1.0)
        P = {}
        P["k_o1"], P["l_o1"], P["c_o1"] = _pt(*k_o1), _pt(*l_o1), _pt(*c_o1)
        P["k_o0"], P["l_o0"], P["c_o0"] = _pt(*k_o0), _pt(*l_o0), _pt(*c_o0)
        if r0 > 0:
            c_i0, l_i0, k_i0 = _fillet_corner(r0, t0, rho, True, +1.0)
            c_i1, l_i1, k_i1 = _fillet_corner(r0, t1, rho, True, -1.0)
            P["k_i0"], P["l_i0"], P["c_i0"] = _pt(*k_i0), _pt(*l_i0), _pt(*c_i0)
            P["k_i1"], P["l_i1"], P["c_i1"] = _pt(*k_i1), _pt(*l_i1), _pt(*c_i1)
            a0 = _ang(k_i0, t0)
            a1 = _ang(k_i1, t1)
            curves += _arc_pts(P["k_i0"], P["k_i1"], r0, a0, a1, o)
            curves.append(occ.addCircleArc(P["k_i1"], P["c_i1"], P["l_i1"]))
            curves.append(occ.addLine(P["l_i1"], P["l_o1"]))
        else:
            curves.append(occ.addLine(o, P["l_o1"]))
        curves.append(occ.addCircleArc(P["l_o1"], P["c_o1"], P["k_o1"]))
        b1 = _ang(k_o1, t1)
        b0 = _ang(k_o0, t0)
        curves += _arc_pts(P["k_o1"], P["k_o0"], r1, b1, b0, o)
        curves.append(occ.addCircleArc(P["k_o0"], P["c_o0"], P["l_o0"]))
        if r0 > 0:
            curves.append(occ.addLine(P["l_o0"], P["l_i0"]))
            curves.append(occ.addCircleArc(P["l_i0"], P["c_i0"], P["k_i0"]))
        else:
            curves.append(occ.addLine(P["l_o0"], o))
    loop = occ.addCurveLoop(curves)
    return occ.addPlaneSurface([loop])


def _arc_pts(p_start: int, p_end: int, r: float, a_start: float, a_end: float, centre: int) -> list[int]:
    """Arc of radius r about the origin between two existing points (split if long)."""
    span = a_end - a_start
    # take the short way round consistent with the sign of span, splitting long arcs
    n = max(1, math.ceil(abs(span) / math.radians(170.0)))
    tags = [p_start]
    for k in range(1, n):
        a = a_start + span * k / n
        tags.append(_pt(r * math.cos(a), r * math.sin(a)))
    tags.append(p_end)
    return [occ.addCircleArc(tags[k], centre, tags[k + 1]) for k in range(n)]


def disk(r: float, x: float = 0.0, y: float = 0.0) -> int:
    """Full disc of radius r centred at (x, y)."""
    return occ.addDisk(x, y, 0.0, r, r)


def shoe_body(r_in: float, t0: float, t1: float, profile: Callable[[np.ndarray], np.ndarray],
              kind: str, eccentric_centre: tuple[float, float] | None = None, n_spline: int = 33) -> int:
    """A shoe: inner arc at r_in, radial sides at t0 < t1, outer profile r = profile(theta).

    ``kind`` 'concentric' draws an exact circle arc about the origin, 'eccentric' an exact
    circle arc about ``eccentric_centre``, anything else an interpolating spline through
    ``n_spline`` profile points (error ~1e-9 m for the smooth profiles used here).
    """
    o = _pt(0.0, 0.0)
    r_t0 = float(profile(np.array([t0]))[0])
    r_t1 = float(profile(np.array([t1]))[0])
    pi0 = _pt(r_in * math.cos(t0), r_in * math.sin(t0))
    pi1 = _pt(r_in * math.cos(t1), r_in * math.sin(t1))
    po0 = _pt(r_t0 * math.cos(t0), r_t0 * math.sin(t0))
    po1 = _pt(r_t1 * math.cos(t1), r_t1 * math.sin(t1))
    curves = _arc_pts(pi0, pi1, r_in, t0, t1, o)
    curves.append(occ.addLine(pi1, po1))
    if kind == "concentric":
        curves += _arc_pts(po1, po0, r_t1, t1, t0, o)
    elif kind == "eccentric":
        assert eccentric_centre is not None
        c = _pt(*eccentric_centre)
        curves.append(occ.addCircleArc(po1, c, po0))
    else:
        if kind == "table":  # 8 points per interval of the table's spline
            n_spline = max(n_spline, 8 * (TABLE_N - 1) + 1)
        th = np.linspace(t1, t0, n_spline)
        r = profile(th)
        inner_tags = [_pt(float(ri * math.cos(ti)), float(ri * math.sin(ti))) for ri, ti in zip(r[1:-1], th[1:-1])]
        curves.append(occ.addSpline([po1] + inner_tags + [po0]))
    curves.append(occ.addLine(po0, pi0))
    return occ.addPlaneSurface([occ.addCurveLoop(curves)])


def cut(objects: list[int], tools: list[int]) -> list[int]:
    """Boolean difference of surfaces; returns the resulting surface tags."""
    out, _ = occ.cut([(2, t) for t in objects], [(2, t) for t in tools])
    return [t for d, t in out if d == 2]


def fuse(objects: list[int]) -> list[int]:
    """Boolean union of surfaces; returns the resulting surface tags."""
    if len(objects) == 1:
        return objects
    out, _ = occ.fuse([(2, objects[0])], [(2, t) for t in objects[1:]])
    return [t for d, t in out if d == 2]
