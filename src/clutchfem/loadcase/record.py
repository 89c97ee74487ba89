"""Every result can be traced to its design: the full inputs and a hash of them.

:func:`design_inputs` records what defines an answer: the concept and every parameter (or
the user mesh file and its SHA-256), the mesh settings and size, the operating point
(material included), the software versions and the design hash.  :func:`design_hash` is the
hash of the design's identity (:mod:`.identity`, the one place it is computed), and :func:`design_label` a file-name
stem that tells two designs in one folder apart: the concept name alone at its defaults,
the name plus the hash otherwise.
"""

from __future__ import annotations

from .._version import __version__
from ..core import clean
from ..geometry import MeshSettings
from .identity import GMSH_VERSION, SKFEM_VERSION, design_identity, file_sha256, identity_of
from .operating import OperatingPoint


def design_inputs(design) -> dict:
    """The inputs that define ``design``'s answers (JSON-ready).  A concept's design that has
    not been meshed (a live answer needs no mesh) records its mesh settings, not the mesh."""
    meshed = getattr(design, "meshed", True)
    cm = design.cm if meshed else None
    ident = design_identity(design)
    d: dict = {"name": design.name, "design_hash": ident.hash, "model_version": ident.model_version,
               "clutchfem": __version__, "gmsh": GMSH_VERSION, "scikit-fem": SKFEM_VERSION}
    if design.params is not None:
        d["concept"] = design.name
        d["params"] = design.params.model_dump()
        d["mesh_settings"] = dict(cm.mesh_settings) if cm is not None else design.mesh_settings.model_dump()
        if cm is not None and (cm.morph or {}).get("morphed"):  # another discretisation of the same design
            d["mesh_morphed_from"] = dict(cm.morph["reference"])
    else:
        d["mesh_file"] = cm.source
        d["mesh_sha256"] = file_sha256(cm.source)
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
    """12 hex digits of SHA-256 over the design's identity (:mod:`.identity`: parameters,
    operating point, mesh settings, code version): ``design.identity.hash``."""
    return design_identity(design).hash


def design_label(design) -> str:
    """File-name stem: the concept name at its defaults (parameters, operating point but the
    speeds asked for, and mesh settings: ``concept4``, or ``concept4-fast`` at the other
    fidelity's defaults), else the name plus the design hash (``concept4-3fa9c2d41e77``)."""
    ident = design_identity(design)
    if design.params is not None:
        fid = design.op.fidelity
        if ident.hash == identity_of(design.concept, {}, OperatingPoint(fidelity=fid),
                                     MeshSettings.preset(fid, model="sector")).hash:
            return design.name if fid == OperatingPoint().fidelity else f"{design.name}-{fid}"
    return f"{design.name}-{ident.hash}"
