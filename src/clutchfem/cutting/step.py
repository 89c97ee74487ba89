"""The STEP solid: the outline's face extruded through the part's thickness, written by gmsh
(OpenCASCADE's STEP writer), in millimetres, with the design in its header; its volume read
back from the file (:func:`step_volume`).

gmsh keeps OCC's default length unit, the millimetre, whatever the model's numbers mean:
a model drawn in metres (as clutchfem's is) comes out as a part 1000 times too small that
says ``SI_UNIT(.MILLI.,.METRE.)``.  So the outline is scaled to millimetres before it is
built, and the file's unit is then true for every CAD system; :mod:`clutchfem.mesh.cad`
reads STEP files in their declared unit.  OCC writes a generic header (``'Open CASCADE
Shape Model'``, author ``'Author'``, product ``'Open CASCADE STEP translator ...'``): the
header's FILE_NAME, FILE_DESCRIPTION and the PRODUCT entity are patched afterwards (plain
text substitutions, checked) to carry the design's label, hash and the unit.  OCC's transfer
statistics, which it prints on the process's standard output, are silenced (the command
line's stdout carries one JSON document).
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import tempfile
from pathlib import Path

import gmsh

from .._version import __version__
from ..core import GeometryError
from ..geometry import gmsh_session
from ..mesh import Loop, import_planar, loops_to_occ


@contextlib.contextmanager
def quiet_stdout():
    """Send file descriptor 1 to /dev/null (C libraries print there, not to sys.stdout)."""
    sys.stdout.flush()
    saved = os.dup(1)
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(null)


def _ascii(text: str) -> str:
    """A STEP string's content: ASCII, apostrophes doubled."""
    return text.encode("ascii", "replace").decode("ascii").replace("'", "''")


def write_step(path, loops: list[Loop], thickness: float, *, label: str, description: list[str]) -> tuple[Path, float]:
    """Extrude ``loops`` (metres) by ``thickness`` [m], write the solid to ``path`` in mm with
    ``label`` and ``description`` lines in the header; returns (path, OCC volume [m^3])."""
    mm = [Loop(tuple(s.mapped(scale=1e3) for s in lp.segments), lp.layer) for lp in loops]
    path = Path(path)
    fd, tmp = tempfile.mkstemp(suffix=".step", dir=path.parent if path.parent.exists() else None)
    os.close(fd)
    try:
        with gmsh_session("step-export"):
            face = loops_to_occ(mm)
            out = gmsh.model.occ.extrude([(2, face)], 0.0, 0.0, thickness * 1e3)
            gmsh.model.occ.synchronize()
            vols = [t for d, t in out if d == 3]
            if len(vols) != 1:
                raise GeometryError(f"the extruded part is {len(vols)} solids, expected one")
            with quiet_stdout():
                gmsh.write(tmp)
        text = Path(tmp).read_text(encoding="ascii", errors="replace")
        text = _patch_header(text, label, description)
        path.write_text(text, encoding="ascii")
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path, step_volume(path)


def step_volume(path) -> float:
    """The volume [m^3] of the prism in a STEP file, read back: its base area (OCC, plane
    face) x its height, after :func:`clutchfem.mesh.import_planar` has checked that it is a
    prism along z (OCC's own volume integral is good to ~2e-4 only for B-spline sides)."""
    with gmsh_session("step-volume"):
        with quiet_stdout():
            h = import_planar(Path(path), None)
        return float(sum(gmsh.model.occ.getMass(2, s) for _, s in gmsh.model.getEntities(2)) * h)


def _patch_header(text: str, label: str, description: list[str]) -> str:
    lab = _ascii(label)
    desc = ",".join(f"'{_ascii(d)}'" for d in description)
    new, n1 = re.subn(r"FILE_NAME\('[^']*',", f"FILE_NAME('{lab}',", text, count=1)
    new, n2 = re.subn(r"\('Author'\)", f"('clutchfem {_ascii(__version__)}')", new, count=1)
    new, n3 = re.subn(r"FILE_DESCRIPTION\(\('[^']*'\)", f"FILE_DESCRIPTION(({desc})", new, count=1)
    new, n4 = re.subn(r"PRODUCT\('[^']*',\s*'[^']*'", f"PRODUCT('{lab}','{lab}'", new, count=1)
    if (n1, n3, n4) != (1, 1, 1) or "SI_UNIT(.MILLI.,.METRE.)" not in new:
        raise GeometryError("the STEP writer's header has an unexpected form: cannot put the design label in it "
                            f"(FILE_NAME {n1}, FILE_DESCRIPTION {n3}, PRODUCT {n4}, author {n2})")
    return new
