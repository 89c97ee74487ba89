"""Element quality of a quadratic triangle mesh, and of a moved mesh against the mesh it was
moved from: the criterion that decides between a morphed mesh and a new one.

* **Scaled Jacobian** of a curved P2 element: min / max of det J over a lattice of 15 points
  of the reference triangle (its corners, edge points and interior: det J is a quadratic
  polynomial there, and the 4th-order lattice resolves it), signed by the element's own
  orientation.  1 for a straight-sided triangle, 0 for a degenerate element, < 0 for a
  folded one.  gmsh's mesher fixes elements below 0.2 (:mod:`.generate`).  One
  computation, :func:`~clutchfem.mesh.highorder.p2_scaled_jacobian`, from the six node
  positions of each element (x = sum_i N_i(s, t) x_i with the P2 shape functions N_i,
  J = [dx/ds dx/dt]): the high-order guard measures gmsh's nodes with it before a
  scikit-fem mesh exists, :func:`scaled_jacobian` a ``MeshTri2``.  It lives with the
  guard because the guard's source is part of the mesh cache key
  (:func:`~clutchfem.geometry.build.source_hash`): a change to the measure must not serve
  a cached mesh.
* **Distortion** of a moved element: the corner triangle's affine map F from its reference
  position to the moved one (F = E_new E_ref^-1, E the two edge vectors) and its singular
  values s1 >= s2.  s1 / s2 = 1: the element kept its shape (it may have grown, shrunk or
  turned); s1 / s2 = 1.5: a right isosceles triangle sheared to angles of about 34-56-90
  deg, or stretched by half in one direction.

The criterion (:data:`MAX_DISTORTION`, :data:`MIN_SCALED_JACOBIAN`) and the measurements
that chose it: :mod:`.morph`.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
from skfem import MeshTri2

from .highorder import p2_scaled_jacobian
from .topology import p2_nodes

#: the largest shape distortion s1/s2 of a moved element (see :mod:`.morph` for the measurements)
MAX_DISTORTION = 2.5
#: the smallest scaled Jacobian of a curved element (the mesher's own fix-up threshold)
MIN_SCALED_JACOBIAN = 0.2


def scaled_jacobian(mesh: MeshTri2) -> np.ndarray:
    """(nelements,) the scaled Jacobian of every element of ``mesh`` (module docstring),
    signed so that an element with one orientation throughout is positive: its corners and
    its mid-edge nodes (facets 01, 12, 20: ``mesh.t2f``) into :func:`p2_scaled_jacobian`."""
    cells = np.vstack([mesh.t, mesh.nvertices + mesh.t2f])  # (6, ne)
    return p2_scaled_jacobian(p2_nodes(mesh)[:, cells].transpose(2, 1, 0))


def distortion(ref: MeshTri2, moved: MeshTri2) -> np.ndarray:
    """(nelements,) s1/s2 of the corner map of every element from ``ref`` to ``moved`` (two
    meshes with one connectivity); inf for a collapsed or turned-over corner triangle."""
    t = ref.t
    def edges(p):
        a, b, c = p[:, t[0]], p[:, t[1]], p[:, t[2]]
        return np.stack([b - a, c - a], axis=2).transpose(1, 0, 2)  # (ne, 2, 2): columns = edges

    E0, E1 = edges(ref.p), edges(moved.p)
    F = E1 @ np.linalg.inv(E0)
    s = np.linalg.svd(F, compute_uv=False)
    det = np.linalg.det(F)
    with np.errstate(divide="ignore"):
        ratio = s[:, 0] / s[:, 1]
    return np.where(det > 0, ratio, np.inf)


@dataclass(frozen=True)
class MorphQuality:
    """The quality of a moved mesh against its reference, and the verdict."""

    min_scaled_jacobian: float
    reference_min_scaled_jacobian: float
    max_distortion: float
    max_area_ratio: float
    min_area_ratio: float
    ok: bool
    reason: str

    def to_json(self) -> dict:
        return asdict(self)


def assess(ref: MeshTri2, moved: MeshTri2, ref_sj: np.ndarray | None = None, *,
           max_distortion: float = MAX_DISTORTION, min_sj: float = MIN_SCALED_JACOBIAN) -> MorphQuality:
    """Accept or refuse a moved mesh: every element's shape distortion <= ``max_distortion``
    and its scaled Jacobian at least half of ``min_sj`` or of its reference value, whichever
    is smaller (a curved element may lose up to half of its quality, never more)."""
    ref_sj = scaled_jacobian(ref) if ref_sj is None else ref_sj
    sj = scaled_jacobian(moved)
    dist = distortion(ref, moved)
    ratio = _areas(moved) / _areas(ref)
    floor = 0.5 * np.minimum(min_sj, ref_sj)
    bad_sj = np.nonzero(sj < floor)[0]
    worst_d = float(np.max(dist)) if dist.size else 1.0
    reason = ""
    if bad_sj.size:
        e = int(bad_sj[np.argmin(sj[bad_sj])])
        reason = (f"element {e} would be nearly degenerate (scaled Jacobian {sj[e]:.3f} < {floor[e]:.3f}); "
                  f"{bad_sj.size} element(s) below the limit")
    elif worst_d > max_distortion:
        e = int(np.argmax(dist))
        reason = (f"element {e} would be distorted by {worst_d:.2f} (shape ratio s1/s2 of its move; the limit is "
                  f"{max_distortion:g}); {int(np.sum(dist > max_distortion))} element(s) above the limit")
    return MorphQuality(min_scaled_jacobian=float(np.min(sj)), reference_min_scaled_jacobian=float(np.min(ref_sj)),
                        max_distortion=worst_d, max_area_ratio=float(np.max(ratio)),
                        min_area_ratio=float(np.min(ratio)), ok=not reason, reason=reason)


def _areas(mesh: MeshTri2) -> np.ndarray:
    p, t = mesh.p, mesh.t
    a, b, c = p[:, t[0]], p[:, t[1]], p[:, t[2]]
    return 0.5 * np.abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
