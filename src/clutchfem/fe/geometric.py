"""Total-Lagrangian kinematics of the 2-D P2 model and the geometric (stress) stiffness.

:class:`Kinematics` evaluates, vectorised over elements and quadrature points, the
deformation gradient F = I + grad u, the Green-Lagrange strain E = (F'F - I)/2, the St.
Venant-Kirchhoff stress S = lambda* tr(E) I + 2 mu E (times the thickness h), the internal
force and its consistent tangent: the machinery of the geometrically non-linear reference
(:mod:`clutchfem.accuracy.nonlinear`).

:func:`geometric_stiffness` is its linearisation about a pre-stress: with sigma1 the linear
stress of the centrifugal field at w = 1, K_sigma1 = h int sigma1 : (grad du' grad v), and the
prestressed linear operator at speed w is K + w^2 (K_sigma1 - M) (used by
:mod:`clutchfem.softening.prestress`).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementTriP2

from ..core import SolverError
from .model3d import geometric_stiffness_3d

__all__ = ["Kinematics", "geometric_stiffness"]


class Kinematics:
    """Vectorised total-Lagrangian plane-stress SVK on the P2 basis of a 2-D model."""

    def __init__(self, basis: Basis, lam: float, mu: float, h: float):
        sb = basis.with_element(ElementTriP2())
        off = np.array([[0], [1]])
        if not (np.array_equal(basis.nodal_dofs, 2 * sb.nodal_dofs + off)
                and np.array_equal(basis.facet_dofs, 2 * sb.facet_dofs + off)):  # pragma: no cover
            raise SolverError("unexpected scikit-fem dof layout for ElementVector(ElementTriP2)")
        nb = sb.Nbfun
        self.G = np.stack([sb.basis[k][0].grad for k in range(nb)], axis=2)  # (2, ne, nb, nq)
        self.G = np.ascontiguousarray(self.G.transpose(1, 3, 2, 0))  # (ne, nq, nb, 2)
        self.dx = sb.dx * h  # (ne, nq)
        ed = sb.element_dofs.T  # (ne, nb)
        self.dofs = (2 * ed[:, :, None] + np.arange(2)[None, None, :]).reshape(len(ed), -1)
        n = self.dofs.shape[1]
        self.rows = np.repeat(self.dofs, n, axis=1).ravel()
        self.cols = np.tile(self.dofs, (1, n)).ravel()
        self.N = basis.N
        self.lam, self.mu = lam, mu

    def gradient(self, u: np.ndarray) -> np.ndarray:
        """H[e, q, c, a] = d u_c / d X_a."""
        U = u[self.dofs].reshape(len(self.dofs), -1, 2)  # (ne, nb, 2)
        return np.einsum("ekc,eqka->eqca", U, self.G)

    def stress(self, H: np.ndarray):
        F = H + np.eye(2)
        E = 0.5 * (np.einsum("eqca,eqcb->eqab", F, F) - np.eye(2))
        tr = E[..., 0, 0] + E[..., 1, 1]
        S = 2 * self.mu * E + self.lam * tr[..., None, None] * np.eye(2)
        return F, E, S

    def residual_and_tangent(self, u: np.ndarray, tangent: bool = True):
        """Internal force r (N,) and tangent K (N x N sparse)."""
        F, _, S = self.stress(self.gradient(u))
        P = np.einsum("eqcb,eqba->eqca", F, S)
        re = np.einsum("eq,eqca,eqka->ekc", self.dx, P, self.G).reshape(len(self.dofs), -1)
        r = np.bincount(self.dofs.ravel(), weights=re.ravel(), minlength=self.N)
        if not tangent:
            return r, None
        G, dx = self.G, self.dx
        # geometric: delta_cd G_k . S . G_l
        GS = np.einsum("eqka,eqab->eqkb", G, S)
        kg = np.einsum("eq,eqkb,eqlb->ekl", dx, GS, G)
        # material: dE(k, c)_ab = sym(F_ca G_kb), in Voigt form B = (dE_xx, dE_yy, 2 dE_xy)
        # (ne, nq, 3, nb, 2); km = sum_q dx B' D B with D the plane Lame matrix (batched matmul)
        ne, nq, nb = G.shape[0], G.shape[1], G.shape[2]
        B = np.empty((ne, nq, 3, nb, 2))
        B[:, :, 0] = F[:, :, None, :, 0] * G[:, :, :, None, 0]
        B[:, :, 1] = F[:, :, None, :, 1] * G[:, :, :, None, 1]
        B[:, :, 2] = F[:, :, None, :, 0] * G[:, :, :, None, 1] + F[:, :, None, :, 1] * G[:, :, :, None, 0]
        lm, mu = self.lam, self.mu
        D = np.array([[lm + 2 * mu, lm, 0.0], [lm, lm + 2 * mu, 0.0], [0.0, 0.0, mu]])
        Bm = B.reshape(ne, nq * 3, nb * 2)
        DB = np.einsum("ij,eqjm->eqim", D, B.reshape(ne, nq, 3, nb * 2)).reshape(ne, nq * 3, nb * 2)
        DB *= np.repeat(dx, 3, axis=1)[:, :, None]
        km = np.matmul(Bm.transpose(0, 2, 1), DB).reshape(ne, nb, 2, nb, 2)
        km[:, :, 0, :, 0] += kg
        km[:, :, 1, :, 1] += kg
        Ke = km.reshape(len(self.dofs), 2 * nb, 2 * nb)
        K = sp.coo_matrix((Ke.ravel(), (self.rows, self.cols)), shape=(self.N, self.N)).tocsr()
        return r, K

    def linear_stress(self, u: np.ndarray) -> np.ndarray:
        """Small-strain plane stress sigma (ne, nq, 2, 2) of u."""
        H = self.gradient(u)
        e = 0.5 * (H + H.transpose(0, 1, 3, 2))
        tr = e[..., 0, 0] + e[..., 1, 1]
        return 2 * self.mu * e + self.lam * tr[..., None, None] * np.eye(2)


def geometric_stiffness(fe, u1: np.ndarray) -> sp.csr_matrix:
    """Geometric stiffness of the pre-stress sigma1 of the displacement u1 (the linear
    centrifugal field at w = 1): K_sigma1 = h int sigma1 : (grad du' grad v), N x N (2-D,
    with the model's Lame pair; a 3-D model gets the volume form, :mod:`clutchfem.fe.model3d`).
    The linearised prestressed operator at speed w is K + w^2 (K_sigma1 - M)."""
    if fe.basis.mesh.dim() == 3:
        return geometric_stiffness_3d(fe, u1)
    if getattr(fe, "formulation", "") == "thick":
        return fe.geometric_stiffness(u1)
    lam, mu = fe.lame if hasattr(fe, "lame") else fe.material.lame_plane_stress()
    kin = Kinematics(fe.basis, lam, mu, fe.thickness)
    s = kin.linear_stress(u1)
    GS = np.einsum("eqka,eqab->eqkb", kin.G, s)
    kg = np.einsum("eq,eqkb,eqlb->ekl", kin.dx, GS, kin.G)
    nb = kin.G.shape[2]
    Ke = np.zeros((len(kin.dofs), nb, 2, nb, 2))
    Ke[:, :, 0, :, 0] = kg
    Ke[:, :, 1, :, 1] = kg
    return sp.coo_matrix((Ke.ravel(), (kin.rows, kin.cols)), shape=(kin.N, kin.N)).tocsr()
