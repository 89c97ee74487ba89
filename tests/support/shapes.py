"""Verification geometries with closed-form solutions, written as gmsh ``.msh`` files with
physical groups and read back through the user-mesh path (:func:`clutchfem.mesh.load_user_geometry`).

* :func:`annulus_msh` -- a flat ring a <= r <= b (or a sector of it with rotated-periodic
  cut lines): groups ``bore`` (r = a), ``contact`` (r = b), ``solid`` and, for a sector,
  ``cut_a`` (polar angle 0) and ``cut_b`` (= cut_a rotated by +sector_deg).  The Lame
  (rotating disc) solutions of ``tests/test_fem_verification.py`` refer to it.
* :func:`ring_segment_msh` -- a segment of a ring (inner radius a, outer radius b, +-half
  angle about the +x axis) centred at (x_c, 0): ``bore`` is its inner arc (clamped),
  ``contact`` its outer arc, meshed finer near it; placed inside the drum it is a cylinder
  in a cylindrical hole, whose contact width under a force is Hertz's
  (``tests/test_contact_arc.py``).
* :func:`cantilever_msh` -- a rectangle 0 <= x <= L, -t/2 <= y <= t/2: ``bore`` is the
  clamped edge x = 0, ``tip`` the loaded edge x = L, ``solid`` the surface.

:func:`load_annulus` and :func:`load_cantilever` build the file and return a
:class:`~clutchfem.mesh.ClutchMesh`; for a sector the cyclic data (``sector_angle``,
``n_shoes_total``, ``n_shoes_model = 1``) are set, which the user-mesh loader cannot know.
Metres throughout; the rotation axis is z through the origin.
"""

from __future__ import annotations

import math
from pathlib import Path

import gmsh

from clutchfem.core import GeometryError
from clutchfem.geometry import gmsh_session
from clutchfem.mesh import ClutchMesh, load_user_geometry

__all__ = ["annulus_msh", "cantilever_msh", "load_annulus", "load_cantilever", "ring_segment_msh"]


def _mesh_and_write(path: Path, size: float, order: int) -> None:
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.ElementOrder", order)
    gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.SaveAll", 0)  # only physical groups: all saved cells are tagged
    path.parent.mkdir(parents=True, exist_ok=True)
    gmsh.write(str(path))


def annulus_msh(path: str | Path, r_in: float, r_out: float, size: float, order: int = 2,
                sector_deg: float | None = None) -> Path:
    """Write a meshed ring r_in <= r <= r_out (full, or the sector 0 <= theta <= sector_deg
    with periodic cut lines) to ``path`` and return it.

    Groups: curves ``bore`` (r = r_in), ``contact`` (r = r_out), for a sector ``cut_a``
    (theta = 0) and ``cut_b`` (theta = sector_deg, meshed as the rotated copy of cut_a);
    surface ``solid``."""
    path = Path(path)
    if not 0 < r_in < r_out:
        raise GeometryError(f"annulus needs 0 < r_in < r_out (got {r_in}, {r_out})")
    if sector_deg is not None and not 0 < sector_deg < 360:
        raise GeometryError(f"sector_deg must lie in (0, 360) (got {sector_deg})")
    with gmsh_session("annulus"):
        occ = gmsh.model.occ
        if sector_deg is None:
            outer = occ.addDisk(0, 0, 0, r_out, r_out)
            inner = occ.addDisk(0, 0, 0, r_in, r_in)
            (surf,), _ = occ.cut([(2, outer)], [(2, inner)])
            occ.synchronize()
            bore, contact = [], []
            for _, c in gmsh.model.getBoundary([surf], oriented=False):
                xmin, ymin, _, xmax, ymax, _ = gmsh.model.getBoundingBox(1, abs(c))
                (bore if max(xmax, ymax) < 0.5 * (r_in + r_out) else contact).append(abs(c))
            gmsh.model.addPhysicalGroup(1, bore, name="bore")
            gmsh.model.addPhysicalGroup(1, contact, name="contact")
            gmsh.model.addPhysicalGroup(2, [surf[1]], name="solid")
        else:
            th = math.radians(sector_deg)
            c, s = math.cos(th), math.sin(th)
            o = occ.addPoint(0, 0, 0)
            p1, p2 = occ.addPoint(r_in, 0, 0), occ.addPoint(r_out, 0, 0)
            p3, p4 = occ.addPoint(r_out * c, r_out * s, 0), occ.addPoint(r_in * c, r_in * s, 0)
            cut_a = occ.addLine(p1, p2)
            rim = occ.addCircleArc(p2, o, p3)
            cut_b = occ.addLine(p4, p3)  # same direction as cut_a (inner -> outer)
            bore = occ.addCircleArc(p4, o, p1)
            loop = occ.addCurveLoop([cut_a, rim, -cut_b, bore])
            surf = occ.addPlaneSurface([loop])
            occ.synchronize()
            occ.remove([(0, o)])
            occ.synchronize()
            affine = [c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
            gmsh.model.mesh.setPeriodic(1, [cut_b], [cut_a], affine)
            gmsh.model.addPhysicalGroup(1, [bore], name="bore")
            gmsh.model.addPhysicalGroup(1, [rim], name="contact")
            gmsh.model.addPhysicalGroup(1, [cut_a], name="cut_a")
            gmsh.model.addPhysicalGroup(1, [cut_b], name="cut_b")
            gmsh.model.addPhysicalGroup(2, [surf], name="solid")
        _mesh_and_write(path, size, order)
    return path


def ring_segment_msh(path: str | Path, x_c: float, r_in: float, r_out: float, half_deg: float, size: float,
                     contact_size: float) -> Path:
    """Write a ring segment |x - (x_c, 0)| <= r_out, |polar angle about (x_c, 0)| <= half_deg,
    whose inner side is the arc of radius x_c + r_in about the origin (the rotation axis: a
    user part's bore must be centred on it), to ``path``: groups ``bore`` (that inner arc,
    clamped), ``contact`` (the outer arc), ``solid``; element size ``contact_size`` within
    1.5 mm of the outer arc, growing to ``size``."""
    path = Path(path)
    if not 0 < r_in < r_out:
        raise GeometryError(f"ring segment needs 0 < r_in < r_out (got {r_in}, {r_out})")
    with gmsh_session("ring_segment"):
        occ = gmsh.model.occ
        th = math.radians(half_deg)
        c = occ.addPoint(x_c, 0, 0)
        o = occ.addPoint(0, 0, 0)
        rb = x_c + r_in
        pb = math.atan2(r_in * math.sin(th), x_c + r_in * math.cos(th))  # the bore arc's half angle
        pts = [occ.addPoint(rb * math.cos(-pb), rb * math.sin(-pb), 0),
               occ.addPoint(x_c + r_out * math.cos(-th), r_out * math.sin(-th), 0),
               occ.addPoint(x_c + r_out * math.cos(th), r_out * math.sin(th), 0),
               occ.addPoint(rb * math.cos(pb), rb * math.sin(pb), 0)]
        side_a = occ.addLine(pts[0], pts[1])
        rim = occ.addCircleArc(pts[1], c, pts[2])
        side_b = occ.addLine(pts[2], pts[3])
        bore = occ.addCircleArc(pts[3], o, pts[0])
        surf = occ.addPlaneSurface([occ.addCurveLoop([side_a, rim, side_b, bore])])
        occ.synchronize()
        occ.remove([(0, c), (0, o)])
        occ.synchronize()
        gmsh.model.addPhysicalGroup(1, [bore], name="bore")
        gmsh.model.addPhysicalGroup(1, [rim], name="contact")
        gmsh.model.addPhysicalGroup(2, [surf], name="solid")
        fld = gmsh.model.mesh.field
        dist = fld.add("Distance")
        fld.setNumbers(dist, "CurvesList", [rim])
        fld.setNumber(dist, "Sampling", 400)
        thr = fld.add("Threshold")
        fld.setNumber(thr, "InField", dist)
        fld.setNumber(thr, "SizeMin", contact_size)
        fld.setNumber(thr, "SizeMax", size)
        fld.setNumber(thr, "DistMin", 1.5e-3)
        fld.setNumber(thr, "DistMax", 6e-3)
        fld.setAsBackgroundMesh(thr)
        _mesh_and_write(path, size, 2)
    return path


def cantilever_msh(path: str | Path, length: float, thickness: float, size: float,
                   order: int = 2) -> Path:
    """Write a meshed rectangle 0 <= x <= length, |y| <= thickness/2 to ``path``.

    Groups: ``bore`` = the clamped end x = 0, ``tip`` = the free end x = length, ``solid``."""
    path = Path(path)
    if not (length > 0 and thickness > 0):
        raise GeometryError(f"cantilever needs length, thickness > 0 (got {length}, {thickness})")
    with gmsh_session("cantilever"):
        occ = gmsh.model.occ
        surf = occ.addRectangle(0, -0.5 * thickness, 0, length, thickness)
        occ.synchronize()
        clamp, tip = [], []
        for _, c in gmsh.model.getBoundary([(2, surf)], oriented=False):
            xmin, _, _, xmax, _, _ = gmsh.model.getBoundingBox(1, abs(c))
            if xmax < 0.25 * length:
                clamp.append(abs(c))
            elif xmin > 0.75 * length:
                tip.append(abs(c))
        gmsh.model.addPhysicalGroup(1, clamp, name="bore")
        gmsh.model.addPhysicalGroup(1, tip, name="tip")
        gmsh.model.addPhysicalGroup(2, [surf], name="solid")
        _mesh_and_write(path, size, order)
    return path


def load_annulus(path: str | Path, r_in: float, r_out: float, size: float, *, thickness: float,
                 order: int = 2, sector_deg: float | None = None,
                 drum_radius: float | None = None) -> ClutchMesh:
    """:func:`annulus_msh` then :func:`~clutchfem.mesh.load_user_geometry`; for a sector the
    cyclic data are set (n = 360 / sector_deg identical sectors, one modelled)."""
    p = annulus_msh(path, r_in, r_out, size, order=order, sector_deg=sector_deg)
    cm = load_user_geometry(p, thickness=thickness, drum_radius=drum_radius)
    if sector_deg is not None:
        n = 360.0 / sector_deg
        if abs(n - round(n)) > 1e-9:
            raise GeometryError(f"sector_deg = {sector_deg} does not divide 360")
        cm.sector_angle = math.radians(sector_deg)
        cm.n_shoes_total = int(round(n))
        cm.n_shoes_model = 1
    return cm


def load_cantilever(path: str | Path, length: float, thickness: float, size: float, *,
                    depth: float, order: int = 2) -> ClutchMesh:
    """:func:`cantilever_msh` then :func:`~clutchfem.mesh.load_user_geometry`; ``depth`` is
    the out-of-plane (plane-stress) thickness."""
    p = cantilever_msh(path, length, thickness, size, order=order)
    return load_user_geometry(p, thickness=depth)
