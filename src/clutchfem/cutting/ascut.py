"""The as-cut part: what a process with a kerf error (or a taper) makes of the design, analysed
like any part.

A kerf wider than the one the tool path was compensated for by ``delta`` moves every cut
wall by delta / 2 into the material (a flexure loses delta, a slot gains delta, an inside
fillet grows by delta / 2, the outer contour shrinks, the bore grows); a narrower one the
other way.  This is a uniform offset of the whole outline (:func:`~.offset.offset_loops`,
exact for lines and arcs), not a change of the concept's parameters: a radial wall offset
sideways is no longer radial, so no parameter set describes the as-cut part exactly.

Taper (waterjet: the kerf differs by ``taper`` between the faces) makes the walls lean by
taper / 4 on each face about the mid-plane outline.  The plane-stress model sees one outline
through the thickness; the two faces' outlines are analysed as two bounding variants (the
real part lies between them: a bound, not an estimate).

Every variant, the nominal one included, goes through the same path as a user's part: the
outline is extruded, written as STEP and read back by :meth:`clutchfem.Design.from_mesh`
(uniform P2 mesh, contact curves found as for any STEP part), so the differences between
variants are the kerf's and not a change of meshing.  The discretisation band of that
pipeline is estimated as analyze does it: the nominal part again on a mesh of half the size,
|a_h - a_h/2| x 2 (Richardson, p = 1).
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass

from ..analysis import slip_step
from ..clutch import EngineCurve
from ..loadcase import Design
from ..mesh import mesh_mass_properties
from .features import widths
from .offset import offset_loops
from .step import write_step

#: default element size of the as-cut meshes: this fraction of the narrowest web (>= 2 P2
#: elements across a flexure), at most 1 mm
WEB_FRACTION = 0.5


@dataclass(frozen=True)
class AsCutRow:
    """One as-cut variant's answers (SI, rpm)."""

    variant: str
    kerf_error_m: float
    wall_offset_m: float
    engagement_rpm: float | None
    slip_rpm: float | None
    slip_status: str
    mass_kg: float

    def to_json(self) -> dict:
        return dict(self.__dict__)


def variants(kerf_error: float, taper: float = 0.0) -> list[tuple[str, float, float]]:
    """(name, kerf error [m], wall offset to the right [m]) of the variants analysed."""
    out = [("nominal", 0.0, 0.0), (f"kerf +{kerf_error * 1e3:g} mm", kerf_error, -0.5 * kerf_error),
           (f"kerf -{kerf_error * 1e3:g} mm", -kerf_error, 0.5 * kerf_error)]
    if taper > 0:
        out += [("taper: wide-kerf face", 0.0, -0.25 * taper), ("taper: narrow-kerf face", 0.0, 0.25 * taper)]
    return out


def analyse_outline(loops, thickness: float, design: Design, engine: EngineCurve, mesh_size: float,
                    label: str = "part") -> tuple[Design, float | None, object]:
    """(design, engagement rpm, slip answer) of the part bounded by ``loops``, meshed from
    its STEP like a user's part, at ``design``'s operating point and drum."""
    fd, tmp = tempfile.mkstemp(suffix=".step")
    os.close(fd)
    try:
        write_step(tmp, loops, thickness, label=label, description=[f"as-cut variant of {label}"])
        op = design.op.replace(drum_radius=design.drum_radius, thickness=thickness)
        d = Design.from_mesh(tmp, operating=op, mesh_size=mesh_size)
    finally:
        os.unlink(tmp)
    case = d.case()
    return d, case.engagement_rpm, slip_step(case, engine)


def as_cut(outline, design: Design, *, kerf_error: float, taper: float = 0.0, mesh_size: float | None = None,
           engine: EngineCurve | None = None, band: bool = True) -> dict:
    """Analyse the variants of :func:`variants` (module docstring); returns a JSON-ready dict
    with the rows, the mesh size, the pipeline's discretisation band and notes."""
    engine = engine or EngineCurve.default()
    h = mesh_size if mesh_size is not None else min(1e-3, WEB_FRACTION * _narrowest_web(outline))
    rows = []
    for name, err, d in variants(kerf_error, taper):
        loops = outline.loops if d == 0 else offset_loops(outline.loops, d)
        dd, eng, slip = analyse_outline(loops, outline.thickness, design, engine, h, label=name)
        mass = mesh_mass_properties(dd.cm, dd.model.material.rho, dd.thickness)["mass_kg"]
        rows.append(AsCutRow(name, err, d, eng, slip.rpm, slip.status, float(mass)))
    result = {"mesh_size_m": h, "rows": [r.to_json() for r in rows], "kerf_error_m": kerf_error, "taper_m": taper,
              "band": None, "notes": [
                  "every variant meshed from its STEP like a user part (uniform P2 mesh): differences are the kerf's",
                  "kerf error: the cut wider (+) or narrower (-) than the tool path's compensation; walls move by "
                  "half of it"]}
    if taper > 0:
        result["notes"].append("taper: the two faces' outlines analysed as whole parts bound the real part")
    if band:
        _, e2, s2 = analyse_outline(outline.loops, outline.thickness, design, engine, 0.5 * h, label="nominal-fine")
        e1, s1 = rows[0].engagement_rpm, rows[0].slip_rpm
        result["band"] = {"engagement_rpm": None if e1 is None or e2 is None else 2 * abs(e1 - e2),
                          "slip_rpm": None if s1 is None or s2.rpm is None else 2 * abs(s1 - s2.rpm),
                          "fine_mesh_size_m": 0.5 * h,
                          "method": "nominal part on a mesh of half the size: 2 |a_h - a_h/2| (Richardson, p = 1)"}
    return result


def _narrowest_web(outline) -> float:
    return min((f.size for f in widths(outline)[1]), default=2e-3)
