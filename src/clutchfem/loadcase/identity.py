"""One design, one name: the design identity, computed here and nowhere else.

A design's identity is everything that defines its answers:

* the concept and its **full** parameter set (defaults filled in, each value in the
  parameter's own unit m, deg or -, numbers rounded to 12 significant digits, so ``"1.9mm"``
  and ``0.0019`` typed in metres are one design); for a user mesh, the SHA-256 of the file's
  content (not where it lies) and its drum radius and thickness;
* the operating point: material with its constants, friction, rotation, spin softening,
  fidelity and the model settings (formulation, layers, drum wall and state, contact
  smoothing); not the speeds asked for (``rpm``: the same design answered at other speeds);
* the mesh settings (sizes, sector or full model);
* the code version (:func:`model_version`: the clutchfem version and a hash of every source
  file that shapes an answer, with the gmsh and scikit-fem versions).

Not in it: the engine curve, the idle speed and the requirement factors (the duty a design
is checked against: the same part, the same drawing), a study's morph reference (the same
design on another discretisation); a study row keeps those in its own ``context_hash``.

:func:`identity_of` is the one function that builds the document and its hash (12 hex
digits of SHA-256); :attr:`clutchfem.Design.identity` and a study's row hash
(:func:`clutchfem.evaluation.design_hash`) both call it, so ``analyze``, ``solve``,
``report``, ``export``, the app and a study row name one design alike.
"""

from __future__ import annotations

import hashlib
import importlib.metadata
import json
import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

from .._version import __version__
from ..core import ClutchfemError, get_material, round12
from ..geometry import Concept, MeshSettings, get_concept, source_hash
from .operating import OperatingPoint

#: operating-point fields that are not part of the design: the speeds an answer is asked at
NOT_DESIGN = ("rpm",)

#: the versions of the mesher and the FE library, part of every design's identity: read from
#: their installed metadata (the same as their ``__version__``), so that a design's identity
#: does not import them (a live design is never meshed)
GMSH_VERSION = importlib.metadata.version("gmsh")
SKFEM_VERSION = importlib.metadata.version("scikit-fem")
#: parts of the package that only present results (they do not change an answer): left out of
#: :func:`model_version`
PRESENTATION = ("cli/", "app/", "studies/", "targets/", "tolerances/", "guidelines/", "reduced/", "validation/",
                "report/", "export/", "cutting/", "fe/vtu.py", "core/figures.py", "core/jsonio.py", "loadcase/record.py",
                "loadcase/identity.py",
                # the study engine's machinery (scheduling, store, batches): not the row of a design
                "evaluation/cluster.py", "evaluation/store.py", "evaluation/runner.py", "evaluation/batch.py",
                "evaluation/sensitivity.py", "evaluation/hashing.py", "evaluation/settings.py")


@lru_cache(maxsize=None)
def model_version(concept: str | None = None) -> str:
    """The code version of an answer: ``<clutchfem version>+<12 hex>``.

    A hash of every source file that shapes an answer (the package without its presentation
    modules, :data:`PRESENTATION`), the concept's geometry source and the gmsh and
    scikit-fem versions.  Stored results are reused only under the same model version, so
    editing the core never serves stale answers; it is part of every design's identity.

    Parameters
    ----------
    concept : str, optional
        The concept's name (its geometry source counts); None for a user mesh.

    Returns
    -------
    str

    Examples
    --------
    >>> from clutchfem.loadcase import model_version
    >>> import clutchfem as cf
    >>> model_version("concept4").startswith(cf.__version__ + "+")
    True
    """
    root = Path(__file__).resolve().parents[1]
    h = hashlib.sha256()
    for f in sorted(root.rglob("*.py")):
        rel = f.relative_to(root).as_posix()
        if rel.startswith(PRESENTATION):
            continue
        h.update(rel.encode())
        h.update(f.read_bytes())
    if concept:
        h.update(source_hash(get_concept(concept)).encode())
    h.update(f"gmsh {GMSH_VERSION} scikit-fem {SKFEM_VERSION}".encode())
    return f"{__version__}+{h.hexdigest()[:12]}"


def normalised(x: Any) -> Any:
    """``x`` as canonical JSON data: numbers as floats rounded to 12 significant digits
    (``3`` and ``3.0``, ``0.0019000000000000002`` and ``0.0019`` alike), mappings sorted."""
    if isinstance(x, bool) or x is None or isinstance(x, str):
        return x
    if isinstance(x, (int, float)):
        return round12(float(x)) if math.isfinite(x) else str(float(x))
    if isinstance(x, dict):
        return {str(k): normalised(v) for k, v in sorted(x.items())}
    if isinstance(x, (list, tuple)):
        return [normalised(v) for v in x]
    if hasattr(x, "model_dump"):
        return normalised(x.model_dump(mode="json"))
    if hasattr(x, "item"):  # a numpy scalar
        return normalised(x.item())
    return str(x)


@dataclass(frozen=True)
class DesignIdentity:
    """A design's identity: the document of everything that defines its answers and its hash.

    Attributes
    ----------
    hash : str
        12 hex digits of SHA-256 over :attr:`document` (canonical JSON): the design hash every
        file, JSON (``design_hash``), report, drawing, app download and study row carries.
    document : dict
        Concept, full parameter set, operating point, mesh settings and ``model_version``
        (see the module docstring).

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.loadcase import identity_of
    >>> a = identity_of("concept4", {"flexure_thickness": "1.9mm"}, cf.OperatingPoint(fidelity="fast"))
    >>> b = identity_of("concept4", {"flexure_thickness": 0.0019}, cf.OperatingPoint(fidelity="fast"))
    >>> a.hash == b.hash, len(a.hash)
    (True, 12)
    """

    hash: str
    document: dict

    @property
    def model_version(self) -> str:
        """The code version in the identity (:func:`model_version`)."""
        return self.document["model_version"]

    def to_json(self) -> dict:
        """``{"design_hash": ..., "model_version": ..., "identity": document}``."""
        return {"design_hash": self.hash, "model_version": self.model_version, "identity": self.document}


def _params(concept, values: dict) -> dict:
    """The concept's full parameter set: defaults, then ``values`` (strings with a unit parsed
    to the parameter's unit; not checked against the cross-parameter rules, so a refused
    design has its identity too)."""
    P = concept.Params
    full = {k: f.default for k, f in P.model_fields.items()}
    for k, v in values.items():
        if isinstance(v, str) and k in P.model_fields:
            try:
                v = P.parse_value(k, v)
            except ClutchfemError:
                pass  # (refused where the design is built; its identity keeps the text)
        full[k] = v
    return full


def _op(op) -> dict:
    """The operating point's part of the identity (a dict: fields over the defaults)."""
    if isinstance(op, OperatingPoint):
        doc = op.model_dump(mode="json")
    else:
        doc = OperatingPoint().model_dump(mode="json")
        for k, v in dict(op or {}).items():
            if k == "material" and isinstance(v, str):
                v = get_material(v).model_dump(mode="json")
            doc[k] = v
    for k in NOT_DESIGN:
        doc.pop(k, None)
    return doc


def identity_of(concept, params: dict | None = None, op: OperatingPoint | dict | None = None,
                mesh: MeshSettings | dict | None = None, *, mesh_sha256: str | None = None) -> DesignIdentity:
    """The identity of a design given by its inputs (no mesh, no model: said before any work).

    Parameters
    ----------
    concept : str, Concept or None
        The concept (None for a user mesh: give ``mesh_sha256``).
    params : dict, optional
        Concept parameters over its defaults (SI floats or strings with a unit).
    op : OperatingPoint or dict, optional
        The operating point (a dict: fields over the defaults; a material by name).
    mesh : MeshSettings or dict, optional
        The mesh settings (default: the fidelity's preset).
    mesh_sha256 : str, optional
        A user mesh's content hash.

    Returns
    -------
    DesignIdentity

    Examples
    --------
    >>> from clutchfem.loadcase import identity_of
    >>> identity_of("concept4").document["params"]["flexure_thickness"]
    0.00175
    """
    op_doc = _op(op if op is not None else OperatingPoint())
    if mesh is None:
        mesh = MeshSettings.preset(op_doc.get("fidelity") or "best")
    name = None
    doc: dict = {}
    if concept is not None:
        c = concept if isinstance(concept, Concept) else get_concept(concept)
        name = c.name
        doc["params"] = _params(c, dict(params or {}))
    else:
        doc["mesh_file_sha256"] = mesh_sha256
    doc.update(concept=name, op=op_doc, mesh=mesh.model_dump(mode="json") if hasattr(mesh, "model_dump") else mesh,
               model_version=model_version(name))
    doc = normalised(doc)
    text = json.dumps(doc, sort_keys=True, separators=(",", ":"))
    return DesignIdentity(hashlib.sha256(text.encode()).hexdigest()[:12], doc)


def file_sha256(path) -> str | None:
    """The SHA-256 of a file's bytes (None if it cannot be read): a user mesh's identity."""
    try:
        h = hashlib.sha256()
        with open(path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                h.update(block)
        return h.hexdigest()
    except OSError:
        return None


def design_identity(design) -> DesignIdentity:
    """The identity of a :class:`~clutchfem.loadcase.Design` (meshed or not: the mesh is not
    needed; a user mesh is named by its content)."""
    if design.params is not None:
        return identity_of(design.concept, design.params.model_dump(), design.op, design.mesh_settings)
    cm = design.cm
    op = design.op.replace(drum_radius=design.drum_radius, thickness=design.thickness)
    return identity_of(None, None, op, dict(getattr(cm, "mesh_settings", None) or {}),
                       mesh_sha256=file_sha256(cm.source))
