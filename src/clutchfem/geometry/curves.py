"""The curves of a built concept as a frame for mesh morphing: their topology signature, and
points on them at normalised curve parameters.

:func:`curve_frame` builds a concept's model (:func:`~.build.build_model`, the same OCC
operations and tolerances as the mesher, :func:`occ_tolerances`) in one gmsh session and
returns a :class:`CurveFrame`:

* the **signature**: every surface with its oriented loop of curve tags, every curve with its
  OCC type and its two end points, every physical group with its entity tags.  Two parameter
  sets with equal signatures have the same curves in the same order: a mesh of one can be
  moved onto the other (:mod:`clutchfem.mesh.morph`).  A concept that adds or drops a curve
  (a fillet radius going to 0, a profile spline with another number of pieces) gives another
  signature, and the mesh is then made from scratch;
* ``project``: points (final frame) on given curves -> their normalised parameters
  s = (u - u_0) / (u_1 - u_0) in [0, 1] (gmsh's ``getParametrization``: an exact inverse on
  lines and circle arcs, an orthogonal projection on splines);
* ``evaluate``: normalised parameters on given curves -> points (final frame).

The *final frame*: a minus-arrangement part is the canonical model reflected y -> -y after
meshing (:class:`~.build.BuiltModel.mirrored`); points are reflected on the way in and out.
"""

from __future__ import annotations

from dataclasses import dataclass

import gmsh
import numpy as np

from .build import BuiltModel, build_model
from .concept import Concept, ConceptParams, MeshSettings
from .session import gmsh_session

#: OCC's geometric and boolean tolerances used whenever a concept is built for meshing [m]
OCC_TOLERANCE = 1e-10


def occ_tolerances() -> None:
    """Set the OCC tolerances of every concept build (the mesher's and the morph frame's: the
    same operations must give the same curves)."""
    gmsh.option.setNumber("Geometry.Tolerance", OCC_TOLERANCE)
    gmsh.option.setNumber("Geometry.ToleranceBoolean", OCC_TOLERANCE)


@dataclass(frozen=True)
class CurveFrame:
    """What :func:`curve_frame` returns (module docstring)."""

    built: BuiltModel
    signature: tuple
    #: curve tag -> normalised parameters of the projected points (``project``), else empty
    params: dict
    #: curve tag -> (2, n) points at the given parameters, final frame (``evaluate``), else empty
    points: dict


def signature(built: BuiltModel) -> tuple:
    """The topology signature of the model in the current gmsh session (module docstring)."""
    surfaces = tuple((t, tuple(c for _, c in gmsh.model.getBoundary([(2, t)], oriented=True)))
                     for _, t in gmsh.model.getEntities(2))
    curves = tuple((t, gmsh.model.getType(1, t), tuple(p for _, p in gmsh.model.getBoundary([(1, t)], oriented=True)))
                   for _, t in gmsh.model.getEntities(1))
    groups = tuple(sorted((k, tuple(v)) for k, v in built.entity_groups.items()))
    return (surfaces, curves, groups, built.n_shoes_model, built.mirrored)


def _bounds(tag: int) -> tuple[float, float]:
    lo, hi = gmsh.model.getParametrizationBounds(1, tag)
    return float(lo[0]), float(hi[0])


def curve_frame(concept: Concept, p: ConceptParams, ms: MeshSettings, *, project: dict | None = None,
                evaluate: dict | None = None, expect: tuple | None = None) -> CurveFrame:
    """Build ``concept`` with ``p`` and read its curves (module docstring).

    Parameters
    ----------
    concept, p, ms
        The concept, its parameters and the mesh settings (sector or full model).
    project : dict, optional
        curve tag -> (2, n) points [m], final frame, lying on that curve.
    evaluate : dict, optional
        curve tag -> (n,) normalised parameters in [0, 1].
    expect : tuple, optional
        A signature: where the model's differs, nothing is projected or evaluated (the
        curves are not the expected ones).

    Returns
    -------
    CurveFrame
        The built model's facts, its signature, and the parameters or points asked for.
    """
    params, points = {}, {}
    with gmsh_session(f"{concept.name}-curves"):
        occ_tolerances()
        built = build_model(concept, p, ms)
        sig = signature(built)
        if expect is not None and sig != expect:
            project = evaluate = None
        flip = -1.0 if built.mirrored else 1.0
        for tag, xy in (project or {}).items():
            xy = np.asarray(xy, dtype=float)
            xyz = np.column_stack([xy[0], flip * xy[1], np.zeros(xy.shape[1])]).ravel()
            u = np.asarray(gmsh.model.getParametrization(1, int(tag), xyz), dtype=float)
            lo, hi = _bounds(int(tag))
            params[tag] = (u - lo) / (hi - lo)
        for tag, s in (evaluate or {}).items():
            lo, hi = _bounds(int(tag))
            u = lo + np.asarray(s, dtype=float) * (hi - lo)
            v = np.asarray(gmsh.model.getValue(1, int(tag), u), dtype=float).reshape(-1, 3)
            points[tag] = np.vstack([v[:, 0], flip * v[:, 1]])
    return CurveFrame(built=built, signature=sig, params=params, points=points)
