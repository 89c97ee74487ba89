"""User geometry import: a gmsh ``.msh`` (any order) or a STEP file becomes a
:class:`~clutchfem.mesh.ClutchMesh`.

Conventions the file must follow: metres (a STEP file's own unit is converted), the part in
the x-y plane, the rotation axis through the origin at the centre of the bore, physical
curve groups ``bore`` (clamped) and optionally ``contact``; one piece of triangles.  What
is checked, and why: :mod:`.user_checks`.  A STEP part is meshed here with second-order triangles; its bore is the boundary loop
around the origin and, with a drum radius, its contact group the outward-facing boundary
curves within 25 % of the largest radius (a heuristic: name the groups in a ``.msh`` to be
exact).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import gmsh
import numpy as np

from ..core import MeshError
from ..geometry import gmsh_session
from .cad import import_planar
from .clutch_mesh import ClutchMesh
from .convert import meshio_to_skfem, read_msh
from .generate import MAX_ELEMENTS
from .user_checks import check_axis, check_cell_types, check_connected, check_size, step_length_unit


def load_user_geometry(path: str | Path, *, mesh_size: float | None = None,
                       thickness: float | None = None, drum_radius: float | None = None) -> ClutchMesh:
    """Import a user's part: a gmsh ``.msh`` (any order; P1 is lifted to straight P2) with
    physical curve groups ``bore`` (clamped) and optionally ``contact`` (metres); or a STEP
    or DXF file in its declared unit (meshed here with second-order triangles; the bore is
    the boundary loop around the origin and, if ``drum_radius`` is given, the contact group
    is the set of boundary curves facing outward within 25 % of the largest radius; a STEP
    prism's height is the thickness).  x-y plane, rotation axis through the origin."""
    path = Path(path)
    if not path.exists():
        raise MeshError(f"mesh file {path} does not exist")
    suffix = path.suffix.lower()
    if suffix in (".step", ".stp", ".dxf"):
        return _load_step(path, mesh_size, thickness, drum_radius)
    if suffix != ".msh":
        raise MeshError(f"{path}: unsupported file type '{suffix}' (use a gmsh .msh, a STEP or a DXF file)")
    return _load_msh(path, str(path), thickness, drum_radius)


def _load_msh(path: Path, source: str, thickness, drum_radius, step: bool = False, unit=None) -> ClutchMesh:
    """A ``.msh`` file (``source``: the name the user gave; ``step``: the meshed copy of a STEP
    or DXF file whose length ``unit`` is named in refusals)."""
    try:
        m = read_msh(path)
    except (Exception, SystemExit) as exc:  # meshio calls sys.exit() on files it cannot identify
        raise MeshError(f"{source}: meshio cannot read it as a gmsh mesh ({exc or type(exc).__name__})") from None
    check_cell_types(m.cells_dict, source)
    names: dict[str, tuple[int, int]] = {k: (int(v[0]), int(v[1])) for k, v in (m.field_data or {}).items()}
    curves = {k: {tag} for k, (tag, dim) in names.items() if dim == 1}
    surfaces = {k: {tag} for k, (tag, dim) in names.items() if dim == 2}
    if "bore" not in curves:
        raise MeshError(f"{source}: no physical curve group named 'bore' (the clamped crankshaft bore); "
                        f"groups found: {sorted(names) or 'none'}")
    key = "gmsh:physical"
    if m.cell_sets and all(k in m.cell_sets for k in names):
        # msh4: an element may sit in several physical groups (contact and contact_0, solid
        # and shoe_0), but meshio's per-cell 'gmsh:physical' keeps only one of them; its
        # cell_sets keep them all.  Label every cell by its index and map groups to indices.
        key = "clutchfem:cell"
        ids, off = [], 0
        for c in m.cells:
            ids.append(np.arange(off, off + len(c.data)))
            off += len(c.data)
        m.cell_data[key] = ids

        def members(name: str) -> set[int]:
            return {int(k) for blk, sel in zip(ids, m.cell_sets[name]) if sel is not None
                    for k in blk[np.asarray(sel, dtype=np.int64)]}

        curves = {k: members(k) for k in curves}
        surfaces = {k: members(k) for k in surfaces}
    elif key not in m.cell_data:
        raise MeshError(f"{source}: the file carries no physical tags")
    mesh = meshio_to_skfem(m, curves, surfaces, key, source)
    bnd = mesh.boundaries or {}
    if len(bnd.get("bore", [])) == 0:
        raise MeshError(f"{source}: the 'bore' group has no edges on the triangle mesh")
    if "contact" in curves and len(bnd.get("contact", [])) == 0:
        raise MeshError(f"{source}: the 'contact' group has no edges on the triangle mesh")
    if "contact" in bnd and "contact_0" not in bnd:
        mesh = mesh.with_boundaries({"contact_0": mesh.boundaries["contact"]})
    check_size(mesh.p, source, unit, step=step)
    check_connected(mesh, source)
    check_axis(mesh, source)
    return ClutchMesh(mesh=mesh, source=source, thickness=thickness, drum_radius=drum_radius)


def _load_step(path: Path, mesh_size, thickness, drum_radius) -> ClutchMesh:
    unit = step_length_unit(path)
    with gmsh_session("step"):
        # the file's own length unit, converted to metres (cad.import_planar: OCC keeps the
        # declared unit and the model is scaled, OCC's own conversion skips B-spline files)
        thickness = import_planar(path, thickness)
        surfaces = [t for d, t in gmsh.model.getEntities(2)]
        if not surfaces or gmsh.model.getEntities(3):
            raise MeshError(f"{path}: expected a planar 2-D part (surfaces in the x-y plane, no solids)")
        # planarity from points on the boundary curves (OCC's bounding box is padded by its
        # tolerance, ~1e-7 m, so it cannot tell a flat part from a slightly tilted one)
        bnd = gmsh.model.getBoundary([(2, t) for t in surfaces], combined=True, oriented=False)
        curves = sorted({abs(t) for d, t in bnd})
        samples = []
        for c in curves:
            lo, hi = gmsh.model.getParametrizationBounds(1, c)
            samples.append(np.asarray(gmsh.model.getValue(1, c, np.linspace(lo[0], hi[0], 9))).reshape(-1, 3))
        xyz = np.vstack(samples)
        check_size(xyz.T, str(path), unit, step=True)
        size = float(np.ptp(xyz[:, :2], axis=0).max())
        if np.ptp(xyz[:, 2]) > 1e-9 * size:
            raise MeshError(f"{path}: the part is not planar (z varies by {np.ptp(xyz[:, 2]):.3g} m); "
                            "expected a 2-D part in the x-y plane")
        polys = []  # the boundary, finely sampled, for the material side of a curve
        for c in curves:
            lo, hi = gmsh.model.getParametrizationBounds(1, c)
            polys.append(np.asarray(gmsh.model.getValue(1, c, np.linspace(lo[0], hi[0], 257))).reshape(-1, 3)[:, :2])
        rmin, rmax, bore, contact = [], [], [], []
        for xy in samples:
            r = np.hypot(xy[:, 0], xy[:, 1])
            rmin.append(r.min())
            rmax.append(r.max())
        r_in = min(rmin)
        R_out = max(rmax)
        for c, a, b in zip(curves, rmin, rmax):
            if b < r_in + 0.25 * (R_out - r_in) and b < 0.5 * R_out:
                bore.append(c)
            elif drum_radius is not None and a > R_out - 0.25 * (R_out - r_in) and _faces_out(c, size, polys):
                contact.append(c)
        if not bore:
            raise MeshError(f"{path}: no boundary loop around the origin to take as the bore (the clamped "
                            "crankshaft bore): is the part centred on the rotation axis (the origin)?")
        gmsh.model.addPhysicalGroup(2, surfaces, name="solid")
        gmsh.model.addPhysicalGroup(1, bore, name="bore")
        if contact:
            gmsh.model.addPhysicalGroup(1, contact, name="contact")
        h = mesh_size or (R_out / 40.0)
        area = sum(gmsh.model.occ.getMass(2, t) for t in surfaces)
        n_est = int(2.3 * area / h ** 2)
        if n_est > MAX_ELEMENTS:
            raise MeshError(f"{path}: mesh size {h * 1e3:g} mm would give about {n_est:,} elements (estimate), "
                            f"more than the limit {MAX_ELEMENTS:,}; use a mesh size of at least "
                            f"{h * (n_est / MAX_ELEMENTS) ** 0.5 * 1e3:.2g} mm")
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        try:
            gmsh.model.mesh.generate(2)
        except Exception as exc:
            raise MeshError(f"{path}: gmsh could not mesh the part ({exc})") from None
        fd, tmp = tempfile.mkstemp(suffix=".msh")
        os.close(fd)
        gmsh.write(tmp)
    try:
        return _load_msh(Path(tmp), str(path), thickness, drum_radius, step=True, unit=unit)
    finally:
        os.unlink(tmp)


def _faces_out(c: int, size: float, polys: list[np.ndarray]) -> bool:
    """Does boundary curve ``c`` face away from the axis (its outward normal within 60 degrees
    of the radial direction at its middle)?  The material side is the side of the curve
    whose probe point lies inside the part (even-odd count of the boundary, sampled finely
    in ``polys``): an inner face of a shoe, a radial flank, are not contact surface."""
    lo, hi = gmsh.model.getParametrizationBounds(1, c)
    u = [0.5 * (lo[0] + hi[0])]
    x = np.asarray(gmsh.model.getValue(1, c, u))[:2]
    t = np.asarray(gmsh.model.getDerivative(1, c, u))[:2]
    n = np.array([t[1], -t[0]]) / max(float(np.hypot(t[0], t[1])), 1e-300)
    probe = x + 1e-3 * size * n
    crossings = 0
    for xy in polys:
        a, b = xy[:-1], xy[1:]
        cond = (a[:, 1] > probe[1]) != (b[:, 1] > probe[1])
        with np.errstate(divide="ignore", invalid="ignore"):
            xs = a[:, 0] + (probe[1] - a[:, 1]) * (b[:, 0] - a[:, 0]) / (b[:, 1] - a[:, 1])
        crossings += int(np.count_nonzero(cond & (xs > probe[0])))
    if crossings % 2:  # the probe is in the material: the outward normal is -n
        n = -n
    return float(n @ x) > 0.5 * float(np.hypot(x[0], x[1]))
