"""A CAD part (STEP or DXF) as planar surfaces of the current gmsh model, in metres.

* **STEP** is read in the length unit the file declares (its LENGTH_UNIT entity: SI prefixes
  of the metre, inch, foot), converted to metres: a part drawn in millimetres by any CAD
  system comes in at its true size.  OCC is told to keep the file's own unit
  (``Geometry.OCCTargetUnit`` = the declared unit) and the model is scaled here: OCC 7.8's
  own conversion (target unit "M") silently skips files with B-spline curves (measured:
  a millimetre file of a table-profile part came in 1000 x too large).  A planar part (surfaces in a plane z = const) is taken as it is; a
  solid must be a *prism along z* -- what ``clutchfem export`` writes and what a plate cut
  through its thickness is (every face flat at the top or bottom or parallel to z, top and
  bottom of one area): its faces at the lowest z are the part, and its height is the part's
  thickness.  Anything else (a solid with a hole drilled at an angle, a chamfer) is
  refused, saying why; so is a prism whose height disagrees with a thickness the user gave.
* **DXF**: the outline loops of :func:`~clutchfem.mesh.dxf.read_dxf` become one OCC face.
"""

from __future__ import annotations

import re
from pathlib import Path

import gmsh
import numpy as np

from ..core import MeshError
from .dxf import read_dxf
from .outline import loops_to_occ

#: STEP length units: SI prefix of the metre or conversion-based unit -> (OCC name, metres)
SI_PREFIX = {"$": ("M", 1.0), ".MILLI.": ("MM", 1e-3), ".CENTI.": ("CM", 1e-2), ".MICRO.": ("UM", 1e-6),
             ".DECI.": ("DM", 0.1), ".KILO.": ("KM", 1e3)}
CONVERTED = {"INCH": ("INCH", 0.0254), "FOOT": ("FT", 0.3048), "MILLIMETRE": ("MM", 1e-3)}
#: relative tolerance of the prism checks (faces at z = const or parallel to z, top = bottom
#: area).  Not the solid's volume: OCC integrates a solid with B-spline sides only to ~2e-4
#: (measured on a table-profile part), its plane faces to ~2e-7
PRISM_TOL = 1e-6


def import_planar(path: Path, thickness: float | None) -> float | None:
    """Import ``path`` into the current gmsh model as x-y surfaces at z = 0; returns the
    part's thickness (a prism's height, else ``thickness`` as given)."""
    occ = gmsh.model.occ
    if path.suffix.lower() == ".dxf":
        loops_to_occ(read_dxf(path))
        occ.synchronize()
        return thickness
    name, metres = step_unit(path)
    gmsh.option.setString("Geometry.OCCTargetUnit", name)
    try:
        occ.importShapes(str(path))
        occ.synchronize()
    except Exception as exc:
        raise MeshError(f"{path}: gmsh cannot import the STEP file ({exc})") from None
    if metres != 1.0:
        occ.dilate(gmsh.model.getEntities(), 0.0, 0.0, 0.0, metres, metres, metres)
        occ.synchronize()
    vols = gmsh.model.getEntities(3)
    if not vols:
        return thickness
    return _prism_face(path, vols, thickness)


def step_unit(path: Path) -> tuple[str, float]:
    """(OCC unit name, metres per unit) of the length unit a STEP file declares; refused if
    it declares none or several."""
    try:
        text = path.read_text(encoding="latin-1")
    except OSError as exc:
        raise MeshError(f"{path}: cannot read the file ({exc.strerror})") from None
    converted, si = set(), set()
    for ent in text.split(";"):
        if "LENGTH_UNIT" not in ent:
            continue
        m = re.search(r"SI_UNIT\(\s*(\$|\.\w+\.)\s*,\s*\.METRE\.\s*\)", ent)
        c = re.search(r"CONVERSION_BASED_UNIT\(\s*'([^']*)'", ent)
        if c and c.group(1).upper() in CONVERTED:
            converted.add(CONVERTED[c.group(1).upper()])
        elif m and m.group(1).upper() in SI_PREFIX:
            si.add(SI_PREFIX[m.group(1).upper()])
        elif m or c:
            raise MeshError(f"{path}: unsupported length unit in {ent.strip()[:80]!r}")
    # a conversion-based unit (INCH) is defined through an SI length unit (its
    # LENGTH_MEASURE_WITH_UNIT: 25.4 MILLI METRE), which the file declares too: that SI unit
    # is the definition, not the part's unit (issue 24: every inch file from CAD was refused
    # as "several length units (INCH, MM)")
    found = converted or si
    if len(found) != 1:
        raise MeshError(f"{path}: the STEP file declares " + ("no length unit" if not found else
                        "several length units (" + ", ".join(sorted(n for n, _ in found)) + ")")
                        + ": cannot tell the part's size")
    return found.pop()


def _vertical(s: int) -> bool:
    """Is face ``s`` parallel to z (normal horizontal at a 5 x 5 grid of its parameters)?"""
    lo, hi = gmsh.model.getParametrizationBounds(2, s)
    uv = [(u, v) for u in np.linspace(lo[0], hi[0], 5) for v in np.linspace(lo[1], hi[1], 5)]
    n = np.asarray(gmsh.model.getNormal(s, [x for p in uv for x in p])).reshape(-1, 3)
    return bool(np.all(np.abs(n[:, 2]) < 1e-6))


def _curve_z(c: int):
    lo, hi = gmsh.model.getParametrizationBounds(1, c)
    xyz = gmsh.model.getValue(1, c, [lo[0], 0.5 * (lo[0] + hi[0]), hi[0]])
    return xyz[2::3]


def _prism_face(path: Path, vols, thickness: float | None) -> float:
    occ = gmsh.model.occ
    box = gmsh.model.getBoundingBox(-1, -1)
    size = max(box[3] - box[0], box[4] - box[1])
    zs = {c: _curve_z(c) for _, c in gmsh.model.getEntities(1)}
    z0 = min(min(v) for v in zs.values())
    z1 = max(max(v) for v in zs.values())
    tol = PRISM_TOL * size
    bottom = []
    for _, s in gmsh.model.getEntities(2):
        _, down = gmsh.model.getAdjacencies(2, s)
        if all(max(abs(z - z0) for z in zs[int(c)]) < tol for c in down):
            bottom.append(s)
    if not bottom:
        raise MeshError(f"{path}: a solid without a flat face at its lowest z: expected a plate part extruded along "
                        "z (its x-y outline cut through the thickness)")
    h = z1 - z0
    top = []
    for _, s in gmsh.model.getEntities(2):
        if s in bottom:
            continue
        _, down = gmsh.model.getAdjacencies(2, s)
        if all(max(abs(z - z1) for z in zs[int(c)]) < tol for c in down):
            top.append(s)
        elif not _vertical(s):
            raise MeshError(f"{path}: the solid is not a prism along z (face {s} is neither flat at its top or "
                            "bottom nor parallel to z): expected a plate part with its outline cut straight through")
    area = sum(occ.getMass(2, s) for s in bottom)
    if abs(sum(occ.getMass(2, s) for s in top) - area) > PRISM_TOL * area:
        raise MeshError(f"{path}: the solid's top and bottom faces differ: not a prism along z")
    if thickness is not None and abs(thickness - h) > PRISM_TOL * h:
        raise MeshError(f"{path}: the solid is {h * 1e3:.6g} mm thick, but the thickness given is "
                        f"{thickness * 1e3:.6g} mm (leave it out to use the solid's)")
    keep = occ.copy([(2, s) for s in bottom])
    occ.remove(vols, recursive=True)
    occ.synchronize()
    rest = [(2, s) for _, s in gmsh.model.getEntities(2) if (2, s) not in keep]
    if rest:
        occ.remove(rest, recursive=True)
    if z0 != 0.0:
        occ.translate(keep, 0.0, 0.0, -z0)
    occ.synchronize()
    return h
