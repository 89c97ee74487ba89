"""Stress recovery: raw stresses at element vertices straight from the P2 displacement (2-D
and 3-D), and the one von Mises stress.

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
from skfem import ElementTetP2

from ..core import SolverError

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
        return von_mises(s, self.szz_factor)

    @cached_property
    def points(self) -> np.ndarray:
        """(2, nelem * 3) positions [m] of the stress points (element vertices)."""
        return self._mesh.p[:, self._mesh.t.T.ravel()]

    @cached_property
    def element(self) -> np.ndarray:
        """(npts,) the element of the 2-D mesh each stress point belongs to."""
        return np.arange(self._mesh.t.shape[1]).repeat(3)

    @cached_property
    def _gradients(self):
        """(Gx, Gy, ex, ey): d/dx and d/dy [1/m] of the 6 scalar P2 shape functions at each
        element's 3 vertices, (nelem, 3, 6) each; ex, ey the element dofs (nelem, 6) of the x
        and y displacement (:func:`p2_vertex_gradients`)."""
        return p2_vertex_gradients(self._basis, self._source)[:4]


def p2_vertex_gradients(b, source: str = "mesh"):
    """(Gx, Gy, ex, ey, Jinv) of the vector P2 basis ``b`` on a curved triangle mesh: the x and
    y derivatives [1/m] of the 6 scalar P2 shape functions at each element's 3 vertices
    (nelem, 3, 6) each, the element dofs (nelem, 6) of the x and y components, and the inverse
    Jacobian (nelem, 3, 2, 2) of the curved map at the vertices (d xi_a / d x_b: the gradient
    of any other shape function there is its reference gradient times it)."""
    ed = b.element_dofs  # (12, ne): local dof 2k + c = shape function k, component c
    ex, ey = ed[0::2], ed[1::2]
    X = b.doflocs[:, ex]  # (2, 6, ne) node positions (curved mid-edge nodes included)
    J = np.einsum("ake,vkb->evab", X, _R)  # (ne, 3, 2, 2): dx_a / dxi_b
    det = J[..., 0, 0] * J[..., 1, 1] - J[..., 0, 1] * J[..., 1, 0]
    if np.any(det == 0):
        raise SolverError(f"{source}: a degenerate element (zero Jacobian at a vertex); remesh")
    Jinv = np.stack([np.stack([J[..., 1, 1], -J[..., 0, 1]], -1),
                     np.stack([-J[..., 1, 0], J[..., 0, 0]], -1)], -2) / det[..., None, None]
    G = _R[None] @ Jinv  # (ne, 3, 6, 2): grad phi_k = J^-T grad_ref phi_k
    return (np.ascontiguousarray(G[..., 0]), np.ascontiguousarray(G[..., 1]), ex.T.copy(), ey.T.copy(), Jinv)


class VertexStress3D:
    """Raw stress recovery of a 3-D model: the 3-D twin of :class:`clutchfem.fe.VertexStress`
    (``__call__(U)`` -> (6, npts[, ncols]) Voigt xx, yy, zz, yz, xz, xy; ``von_mises``;
    ``points`` (3, npts)).  The gradients of the 10 scalar P2 shape functions at each
    tetrahedron's 4 vertices are computed once through the curved map."""

    def __init__(self, model):
        self._basis = model.basis
        self._mesh = model.em.mesh
        self._ne2 = model.cm.n_elements
        self._source = model.cm.source
        self.lame = model.lame

    @cached_property
    def _gradients(self):
        b = self._basis
        ed = b.element_dofs  # (30, ne): local dof 3 k + c
        X = b.doflocs[:, ed[0::3]]  # (3, 10, ne)
        el = ElementTetP2()
        V = np.array([[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
        R = np.stack([el.lbasis(V, q)[1] for q in range(10)], axis=1).transpose(2, 1, 0)  # (4, 10, 3)
        J = np.einsum("ake,vkb->evab", X, R)  # (ne, 4, 3, 3)
        det = np.linalg.det(J)
        if np.any(np.abs(det) <= 1e-14 * np.median(np.abs(det))):
            raise SolverError(f"{self._source}: a degenerate tetrahedron (zero Jacobian at a vertex)")
        G = np.einsum("vkb,evba->aevk", R, np.linalg.inv(J))  # grad phi_k = J^-T grad_ref phi_k
        return np.ascontiguousarray(G), np.stack([ed[0::3].T, ed[1::3].T, ed[2::3].T])

    def __call__(self, U: np.ndarray) -> np.ndarray:
        U = np.asarray(U)
        one = U.ndim == 1
        U = U.reshape(U.shape[0], -1)
        G, ed = self._gradients
        lam, mu = self.lame
        g = [[G[a] @ U[ed[c]] for c in range(3)] for a in range(3)]  # d u_c / d x_a
        tr = g[0][0] + g[1][1] + g[2][2]
        s = np.stack([2 * mu * g[0][0] + lam * tr, 2 * mu * g[1][1] + lam * tr,
                      2 * mu * g[2][2] + lam * tr, mu * (g[1][2] + g[2][1]),
                      mu * (g[0][2] + g[2][0]), mu * (g[0][1] + g[1][0])])
        s = s.reshape(6, -1, U.shape[1])
        return s[..., 0] if one else s

    def von_mises(self, s: np.ndarray) -> np.ndarray:
        return von_mises(s)

    @cached_property
    def points(self) -> np.ndarray:
        """(3, nelem * 4) positions [m] of the stress points (tetrahedron vertices)."""
        return self._mesh.doflocs[:, self._mesh.t.T.ravel()]

    @cached_property
    def element(self) -> np.ndarray:
        """(npts,) the element of the 2-D mesh under each stress point (the extrusion stacks
        the tetrahedra of every layer and split in the 2-D elements' order)."""
        return (np.arange(self._mesh.t.shape[1]) % self._ne2).repeat(4)


def von_mises(s: np.ndarray, szz_factor: float = 0.0) -> np.ndarray:
    """von Mises stress, the one definition in clutchfem.

    ``s``: stresses stacked on the first axis, either in-plane (sxx, syy, sxy), with
    s_zz = ``szz_factor`` (s_xx + s_yy) (0: plane stress, nu: plane strain), or 3-D Voigt
    (xx, yy, zz, yz, xz, xy).  Rounding cannot make it imaginary (clipped at 0)."""
    s = np.asarray(s)
    if s.shape[0] == 6:
        xx, yy, zz, yz, xz, xy = s
        return np.sqrt(np.maximum(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                                  + 3.0 * (yz * yz + xz * xz + xy * xy), 0.0))
    if s.shape[0] != 3:
        raise ValueError(f"von_mises: {s.shape[0]} stress components; expected 3 (plane) or 6 (3-D Voigt)")
    sxx, syy, sxy = s[0], s[1], s[2]
    if szz_factor == 0.0:
        return np.sqrt(np.maximum(sxx * sxx - sxx * syy + syy * syy + 3.0 * sxy * sxy, 0.0))
    szz = szz_factor * (sxx + syy)
    return np.sqrt(np.maximum(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
                              + 3.0 * sxy * sxy, 0.0))
