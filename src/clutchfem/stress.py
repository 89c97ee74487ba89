"""Raw stresses at element vertices, straight from the P2 displacement.

The P2 strain is linear on a straight element, so its extremes sit at the vertices: the
peak von Mises of a field is read there, unaveraged (no smoothing hides a peak).  The
gradients of the six scalar P2 shape functions at the three vertices of every element are
computed once through the isoparametric (curved) map,

    grad phi_k(v) = J(v)^-T grad_ref phi_k(v),   J = sum_k x_k grad_ref phi_k^T,

so the stresses of any number of displacement columns (all speeds of a sweep, or the few
columns of its reduced basis) are one batched small matrix product.  They equal
scikit-fem's own interpolation to round-off (``FEModel.stress_at_vertices``, tested).
"""

from __future__ import annotations

from functools import cached_property

import numpy as np

from .errors import SolverError

# reference gradients of the P2 shape functions (skfem ElementTriP2 order: 3 vertices, then
# mid-edges 01, 12, 20) at the vertices (0,0), (1,0), (0,1): R[v, k, :]
_R = np.array([[[-3, -3], [-1, 0], [0, -1], [4, 0], [0, 0], [0, 4]],
               [[1, 1], [3, 0], [0, -1], [-4, -4], [0, 4], [0, 0]],
               [[1, 1], [-1, 0], [0, 3], [0, 0], [4, 0], [-4, -4]]], dtype=float)


class VertexStress:
    """Stress recovery of one FE model (read-only: results may keep a reference to it)."""

    def __init__(self, model):
        self._basis = model.basis
        self._mesh = model.cm.mesh
        self._source = model.cm.source
        self.lame = model.lame
        self.szz_factor = model.szz_factor

    def __call__(self, U: np.ndarray) -> np.ndarray:
        """Stresses (sxx, syy, sxy) [Pa] at every element's three vertices for the
        displacement column(s) U: array (3, nelem * 3[, ncols]), rows ordered (element,
        vertex) like :attr:`points`."""
        U = np.asarray(U)
        one = U.ndim == 1
        U = U.reshape(U.shape[0], -1)
        Gx, Gy, ex, ey = self._gradients
        Ux, Uy = U[ex], U[ey]  # (ne, 6, ncols)
        lam, mu = self.lame
        out = np.empty((3, len(Gx), 3, U.shape[1]))
        exx = np.matmul(Gx, Ux, out=out[0])
        eyy = np.matmul(Gy, Uy, out=out[1])
        gxy = np.matmul(Gy, Ux, out=out[2])
        gxy += Gx @ Uy
        gxy *= mu
        tr = lam * (exx + eyy)
        exx *= 2 * mu
        exx += tr
        eyy *= 2 * mu
        eyy += tr
        out = out.reshape(3, -1, U.shape[1])
        return out[..., 0] if one else out

    def von_mises(self, s: np.ndarray) -> np.ndarray:
        from .fem import von_mises

        return von_mises(s, self.szz_factor)

    @cached_property
    def points(self) -> np.ndarray:
        """(2, nelem * 3) positions [m] of the stress points (element vertices)."""
        return self._mesh.p[:, self._mesh.t.T.ravel()]

    @cached_property
    def _gradients(self):
        """(Gx, Gy, ex, ey): d/dx and d/dy [1/m] of the 6 scalar P2 shape functions at each
        element's 3 vertices, (nelem, 3, 6) each; ex, ey the element dofs (nelem, 6) of the x
        and y displacement."""
        b = self._basis
        ed = b.element_dofs  # (12, ne): local dof 2k + c = shape function k, component c
        ex, ey = ed[0::2], ed[1::2]
        X = b.doflocs[:, ex]  # (2, 6, ne) node positions (curved mid-edge nodes included)
        J = np.einsum("ake,vkb->evab", X, _R)  # (ne, 3, 2, 2): dx_a / dxi_b
        det = J[..., 0, 0] * J[..., 1, 1] - J[..., 0, 1] * J[..., 1, 0]
        if np.any(det == 0):
            raise SolverError(f"{self._source}: a degenerate element (zero Jacobian at a vertex); remesh")
        Jinv = np.stack([np.stack([J[..., 1, 1], -J[..., 0, 1]], -1),
                         np.stack([-J[..., 1, 0], J[..., 0, 0]], -1)], -2) / det[..., None, None]
        G = _R[None] @ Jinv  # (ne, 3, 6, 2): grad phi_k = J^-T grad_ref phi_k
        return (np.ascontiguousarray(G[..., 0]), np.ascontiguousarray(G[..., 1]), ex.T.copy(), ey.T.copy())
