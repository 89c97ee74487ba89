"""Every result can be traced to its design: the full inputs and a hash of them.

:func:`design_inputs` records what defines an answer: the concept and every parameter (or
the user mesh file and its SHA-256), the mesh settings and size, the operating point
(material included), and the software versions.  :func:`design_hash` is a short stable hash
of the defining part (no timings, no paths of caches), and :func:`design_label` a file-name
stem that tells two designs in one folder apart: the concept name alone at its defaults,
the name plus the hash otherwise.
"""

from __future__ import annotations

import hashlib
import json
from functools import lru_cache
from pathlib import Path

import gmsh
import skfem

from .._version import __version__
from ..core import clean
from ..geometry import MeshSettings


def _file_sha256(path) -> str | None:
    try:
        h = hashlib.sha256()
        with open(path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                h.update(block)
        return h.hexdigest()
    except OSError:
        return None


def design_inputs(design) -> dict:
    """The inputs that define ``design``'s answers (JSON-ready).  A concept's design that has
    not been meshed (a live answer needs no mesh) records its mesh settings, not the mesh."""
    meshed = getattr(design, "meshed", True)
    cm = design.cm if meshed else None
    d: dict = {"name": design.name, "clutchfem": __version__, "gmsh": gmsh.__version__,
               "scikit-fem": getattr(skfem, "__version__", "?")}
    if design.params is not None:
        d["concept"] = design.name
        d["params"] = design.params.model_dump()
        d["mesh_settings"] = dict(cm.mesh_settings) if cm is not None else design.mesh_settings.model_dump()
        if cm is not None and (cm.morph or {}).get("morphed"):  # another discretisation of the same design
            d["mesh_morphed_from"] = dict(cm.morph["reference"])
    else:
        d["mesh_file"] = cm.source
        d["mesh_sha256"] = _file_sha256(cm.source)
    if cm is not None:
        d["mesh"] = {"elements": cm.n_elements, "nodes": cm.n_nodes, "model": "sector" if cm.sector_angle else "full"}
    op = design.op.model_dump()
    op["drum_radius"] = design.drum_radius
    op["thickness"] = design.thickness
    d["operating_point"] = op
    # what the fidelity resolved to (formulation "auto", drum wall None)
    d["model"] = {"fidelity": design.op.fidelity, "formulation": design.op.model_formulation,
                  "drum_wall_m": design.op.drum_wall_m, "drum_state": design.op.drum_state,
                  "softening": design.op.softening}
    if cm is not None:
        d["model"]["dofs"] = int(design.model.ndofs)
    return clean(d)


def design_hash(design) -> str:
    """12 hex digits of SHA-256 over the defining inputs (versions included)."""
    d = design_inputs(design)
    d.pop("name", None)
    if "mesh_file" in d:  # the content defines it, not where the file lies
        d["mesh_file"] = Path(d["mesh_file"]).name
    return hashlib.sha256(json.dumps(d, sort_keys=True).encode()).hexdigest()[:12]


def design_label(design) -> str:
    """File-name stem: the concept name at its defaults (parameters, operating point and mesh
    settings), else the name plus the design hash."""
    default = False
    if design.params is not None:
        params0, op0 = _defaults(type(design.params), type(design.op))
        mesh0 = MeshSettings.preset(design.op.fidelity, model="sector").model_dump()
        # the other fidelity at its defaults is a default design too (its own name tag)
        same_op = design.op == op0 or design.op == op0.replace(fidelity=design.op.fidelity)
        ms = design.cm.mesh_settings if getattr(design, "meshed", True) else design.mesh_settings.model_dump()
        default = design.params == params0 and same_op and dict(ms) == mesh0
        if default and design.op.fidelity != op0.fidelity:
            return f"{design.name}-{design.op.fidelity}"
    return design.name if default else f"{design.name}-{design_hash(design)}"


@lru_cache(maxsize=64)
def _defaults(params_type, op_type):
    """The default parameter set and operating point (frozen: built once)."""
    return params_type(), op_type()
