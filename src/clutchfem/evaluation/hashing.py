"""Which stored row answers which point: a study point's design hash and its context.

A row is keyed in the store by ``(design_hash, context_hash, model_version)``, computed
*before* any work (so a finished point is skipped without meshing it):

* ``design_hash`` is the design's identity (:func:`clutchfem.loadcase.identity_of`, the one
  place it is computed): the concept and its **full** parameter set (the fixed
  ``[design.set]`` values and the point's varied values over the concept's defaults, so
  giving a default explicitly or leaving it out is the same design), the operating point
  with the point's operating-point values, the mesh settings and the code version; for a
  user mesh, the SHA-256 of the file's content.  ``clutchfem analyze``, ``solve``,
  ``report``, ``export`` and the app give the same design the same hash
  (:attr:`clutchfem.Design.hash`);
* ``context_hash`` is what the study adds to the design: the engine curve's numbers (not its
  file name), the idle speed, the requirement factors and, for a study that morphs its
  meshes (:attr:`~clutchfem.evaluation.Settings.morph`), the full parameter set of the
  reference design (another discretisation of the same design).

Floats are written with 12 significant digits, so ``1.5mm`` parsed as 0.0015000000000000002
and 0.0015 typed in metres are one design.
"""

from __future__ import annotations

import hashlib
import json

from ..core import ParameterError
from ..geometry import MeshSettings, get_concept
from ..loadcase import USER_THICKNESS, OperatingPoint, identity_of
from ..loadcase.identity import normalised
from .point import split_point


def _op(opv: dict, settings) -> OperatingPoint | dict:
    """The point's operating point (a dict of fields when a value is refused: the refusal is
    said where the design is built, the row still has its hash)."""
    op = settings.op if settings.op is not None else OperatingPoint()
    try:
        return op.replace(**opv) if opv else op
    except ParameterError:
        return {**op.model_dump(mode="json"), **opv}


def design_hash(point: dict, settings) -> str:
    """The design hash of ``point`` under ``settings``: its identity's hash (12 hex).

    Parameters
    ----------
    point : dict
        The varied inputs ``{name: value}`` (the parameter's unit: m, deg, -).
    settings : Settings
        The study's fixed inputs.

    Returns
    -------
    str

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.evaluation import Settings, design_hash
    >>> st = Settings("concept4", op=cf.OperatingPoint(fidelity="fast"))
    >>> d = cf.Design.from_concept("concept4", flexure_thickness="1.9mm", fidelity="live")
    >>> design_hash({"flexure_thickness": 1.9e-3}, st) == d.with_fidelity("fast").hash
    True
    """
    geo, opv = split_point(point, settings)
    op = _op(opv, settings)
    fid = op.fidelity if isinstance(op, OperatingPoint) else op.get("fidelity", "best")
    if settings.concept is not None:
        mesh = settings.mesh if settings.mesh is not None else MeshSettings.preset(fid)
        return identity_of(get_concept(settings.concept), {**dict(settings.fixed), **geo}, op, mesh).hash
    sha = hashlib.sha256(settings.mesh_bytes).hexdigest() if settings.mesh_bytes else None
    if isinstance(op, OperatingPoint) and op.thickness is None:  # (a user mesh's default thickness)
        op = op.replace(thickness=USER_THICKNESS)
    return identity_of(None, None, op, {}, mesh_sha256=sha).hash


def context_hash(settings) -> str:
    """12 hex digits of SHA-256 over what the study adds to its designs (module docstring).

    Examples
    --------
    >>> from clutchfem.evaluation import Settings, context_hash
    >>> context_hash(Settings("concept4")) == context_hash(Settings("concept4", a=1.3))
    True
    >>> context_hash(Settings("concept4")) == context_hash(Settings("concept4", a=1.4))
    False
    """
    base = settings.canonical()
    doc = {"engine": base["engine"], "idle_rpm": base["idle_rpm"], "requirements": base["requirements"]}
    if "morph_reference" in base:  # a morphed mesh: another discretisation, another row
        ref = {k: f.default for k, f in get_concept(settings.concept).Params.model_fields.items()}
        ref.update(base["morph_reference"])
        doc["morph_reference"] = ref
    text = json.dumps(normalised(doc), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:12]
