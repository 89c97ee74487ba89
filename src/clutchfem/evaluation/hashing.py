"""The design hash: which stored row answers which point.

A point is keyed in the store by ``(design_hash, model_version)``.  The design hash is the
SHA-256 (first 16 hex digits) of a canonical JSON document of everything that defines the
design's answers, computed *before* any work (so a finished point is skipped without
meshing it):

* the concept and its **full** parameter set: the fixed ``[design.set]`` values and the
  point's varied values over the concept's defaults (so giving a default explicitly or
  leaving it out is the same design); for a user mesh, the SHA-256 of the file's content;
* the operating point (material with its constants, mu, rotation, softening, formulation,
  drum wall ...) with the point's operating-point values, the mesh settings, the engine
  curve's numbers (not its file name), the idle speed and the requirement factors;
* for a study that morphs its meshes (:attr:`~clutchfem.evaluation.Settings.morph`), the full
  parameter set of the reference design.

Floats are written with 12 significant digits, so ``1.5mm`` parsed as 0.0015000000000000002
and 0.0015 typed in metres are one design.  The model version (see
:func:`clutchfem.evaluation.point.model_version`) is kept apart: the same design under a new
model is a new row, not a changed hash.
"""

from __future__ import annotations

import hashlib
import json
import math
from typing import Any

from ..core import get_material, round12
from ..geometry import get_concept
from .point import split_point


def _norm(x: Any) -> Any:
    if isinstance(x, bool) or x is None or isinstance(x, str):
        return x
    if isinstance(x, int):
        return x
    if isinstance(x, float):
        return round12(x) if math.isfinite(x) else str(x)
    if isinstance(x, dict):
        return {str(k): _norm(v) for k, v in sorted(x.items())}
    if isinstance(x, (list, tuple)):
        return [_norm(v) for v in x]
    if hasattr(x, "item"):  # numpy scalar
        return _norm(x.item())
    return str(x)


def canonical_inputs(point: dict, settings) -> dict:
    """The canonical document hashed for ``point`` under ``settings`` (see module docstring)."""
    base = settings.canonical()
    geo, opv = split_point(point, settings)
    doc: dict = {"design": base["concept"], "mesh_file_sha256": base["mesh_file_sha256"]}
    if settings.concept is not None:
        fields = get_concept(settings.concept).Params.model_fields
        params = {k: f.default for k, f in fields.items()}
        params.update(dict(settings.fixed))
        params.update(geo)
        doc["params"] = params
    op = dict(base["op"])
    for k, v in opv.items():
        if k == "material" and isinstance(v, str):
            v = get_material(v).model_dump(mode="json")
        op[k] = v
    doc.update(op=op, mesh=base["mesh"], engine=base["engine"], idle_rpm=base["idle_rpm"],
               requirements=base["requirements"])
    if "morph_reference" in base:  # a morphed mesh: another discretisation, another row
        ref = {k: f.default for k, f in get_concept(settings.concept).Params.model_fields.items()}
        ref.update(base["morph_reference"])
        doc["morph_reference"] = ref
    return _norm(doc)


def design_hash(point: dict, settings) -> str:
    """16 hex digits of SHA-256 over :func:`canonical_inputs`."""
    text = json.dumps(canonical_inputs(point, settings), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]
