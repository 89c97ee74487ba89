"""Plane-stress linear elasticity of the spinning part (scikit-fem, P2 on curved MeshTri2).

Unknowns: the in-plane displacement u, P2 vector field, thickness h.  Operators (all
multiplied by h):

* ``K``  stiffness, plane stress (Lame pair computed in :class:`~clutchfem.materials.Material`);
* ``M``  in-plane mass matrix rho h int u.v: the *spin-softening* operator, because the
  centrifugal load acts on the deformed position, f = rho w^2 (x + u);
* ``f1`` centrifugal load at w = 1 rad/s: rho h int x.v (rotation about z through the origin).

Constraints: the bore is clamped (u = 0); a one-sector model of n identical shoes gets the
cyclic (rotated periodic) constraint u(cut_b) = R(2 pi/n) u(cut_a).  Both are applied by a
sparse map ``T`` from independent dofs to all dofs, u = T a, and the reduced stiffness
T' K T is factorised once (:mod:`clutchfem.linsolve`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree
from skfem import (Basis, BilinearForm, ElementTriP2, ElementVector, FacetBasis, LinearForm,
                   asm)
from skfem.helpers import ddot, dot, sym_grad, trace

from .errors import MeshError, SolverError
from .linsolve import factorize
from .materials import Material
from .mesh import ClutchMesh


@dataclass
class FEModel:
    """Assembled operators of one meshed part and material (see module docstring)."""

    cm: ClutchMesh
    material: Material
    thickness: float
    basis: Basis
    K: sp.csr_matrix
    M: sp.csr_matrix
    f1: np.ndarray
    T: sp.csr_matrix
    timings: dict = field(default_factory=dict)
    _factor: object = None

    @property
    def ndofs(self) -> int:
        return self.basis.N

    @property
    def factor(self):
        """Factorisation of T' K T (computed on first use)."""
        if self._factor is None:
            import time

            t0 = time.perf_counter()
            self._factor = factorize(self.Kr)
            self.timings["factorize_s"] = time.perf_counter() - t0
        return self._factor

    @property
    def Kr(self) -> sp.csc_matrix:
        if not hasattr(self, "_Kr"):
            self._Kr = (self.T.T @ self.K @ self.T).tocsc()
        return self._Kr

    @property
    def Mr(self) -> sp.csc_matrix:
        if not hasattr(self, "_Mr"):
            self._Mr = (self.T.T @ self.M @ self.T).tocsc()
        return self._Mr

    def solve(self, F: np.ndarray) -> np.ndarray:
        """Displacements (all dofs) for load(s) F (N or N x k), no contact, no softening."""
        return self.T @ self.factor.solve(self.T.T @ F)

    def stress_at_vertices(self, u: np.ndarray) -> np.ndarray:
        """Raw (unaveraged) stresses at each element's three vertices: array (3, nelem, 3)
        of (sxx, syy, sxy) [Pa].  The P2 strain is linear on a straight element, so its
        extremes sit at the vertices; no smoothing hides a peak."""
        b = self._vertex_basis
        g = b.interpolate(u).grad  # (2, 2, nelem, 3)
        lam, mu = self.material.lame_plane_stress()
        exx, eyy = g[0, 0], g[1, 1]
        exy = 0.5 * (g[0, 1] + g[1, 0])
        tr = exx + eyy
        return np.stack([2 * mu * exx + lam * tr, 2 * mu * eyy + lam * tr, 2 * mu * exy])

    @property
    def _vertex_basis(self) -> Basis:
        if not hasattr(self, "_vb"):
            X = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
            W = np.full(3, 1.0 / 6.0)
            self._vb = Basis(self.cm.mesh, ElementVector(ElementTriP2()), quadrature=(X, W))
        return self._vb


def von_mises(s: np.ndarray) -> np.ndarray:
    """Plane-stress von Mises stress from (sxx, syy, sxy) stacked on the first axis."""
    sxx, syy, sxy = s[0], s[1], s[2]
    return np.sqrt(np.maximum(sxx * sxx - sxx * syy + syy * syy + 3.0 * sxy * sxy, 0.0))


def build_fe_model(cm: ClutchMesh, material: Material, thickness: float | None = None) -> FEModel:
    """Assemble K, M and f1 for ``cm`` and build the constraint map T."""
    import time

    t0 = time.perf_counter()
    h = float(thickness if thickness is not None else (cm.thickness or 0.0))
    if not h > 0:
        raise SolverError("the axial thickness is unknown: give thickness (m) for a user mesh")
    mesh = cm.mesh
    basis = Basis(mesh, ElementVector(ElementTriP2()), intorder=4)
    lam, mu = material.lame_plane_stress()
    rho = material.rho

    @BilinearForm
    def stiffness(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        return h * (2.0 * mu * ddot(eu, ev) + lam * trace(eu) * trace(ev))

    @BilinearForm
    def mass(u, v, w):  # scalar P2 mass; the vector one is kron(M, I2) (dof 2 i + component)
        return h * rho * u * v

    @LinearForm
    def centrifugal(v, w):
        return h * rho * (w.x[0] * v[0] + w.x[1] * v[1])

    K = asm(stiffness, basis).tocsr()
    sb = basis.with_element(ElementTriP2())
    if (np.array_equal(basis.nodal_dofs, 2 * sb.nodal_dofs + np.array([[0], [1]]))
            and np.array_equal(basis.facet_dofs, 2 * sb.facet_dofs + np.array([[0], [1]]))):
        M = sp.kron(asm(mass, sb), sp.identity(2, format="csr"), format="csr")
    else:  # another dof layout: assemble the vector form directly
        M = asm(BilinearForm(lambda u, v, w: h * rho * dot(u, v)), basis).tocsr()
    f1 = asm(centrifugal, basis)
    t1 = time.perf_counter()
    T = constraint_map(cm, basis)
    model = FEModel(cm=cm, material=material, thickness=h, basis=basis, K=K, M=M, f1=f1, T=T)
    model.timings.update({"assemble_s": t1 - t0, "constraints_s": time.perf_counter() - t1})
    return model


def constraint_map(cm: ClutchMesh, basis: Basis) -> sp.csr_matrix:
    """Sparse T (ndofs x nindep) with u = T a: clamped bore, cyclic sector constraints."""
    mesh = cm.mesh
    N = basis.N
    if "bore" not in (mesh.boundaries or {}):
        raise MeshError(f"{cm.source}: no 'bore' boundary group: the part must be clamped somewhere")
    fixed = np.unique(basis.get_dofs(cm.boundary("bore")).all())
    slave_x = slave_y = master_x = master_y = np.zeros(0, dtype=np.int64)
    c = s = 0.0
    if cm.sector_angle is not None:
        da = basis.get_dofs(cm.boundary("cut_a"))
        db = basis.get_dofs(cm.boundary("cut_b"))
        ax = np.concatenate([da.nodal["u^1"], da.facet["u^1"]])
        ay = np.concatenate([da.nodal["u^2"], da.facet["u^2"]])
        bx = np.concatenate([db.nodal["u^1"], db.facet["u^1"]])
        by = np.concatenate([db.nodal["u^2"], db.facet["u^2"]])
        c, s = math.cos(cm.sector_angle), math.sin(cm.sector_angle)
        xa = basis.doflocs[:, ax]
        xb = basis.doflocs[:, bx]
        rot = np.array([[c, -s], [s, c]]) @ xa
        dist, idx = cKDTree(xb.T).query(rot.T)
        scale = float(np.max(np.abs(basis.doflocs)))
        if len(ax) != len(bx) or dist.max() > 1e-8 * scale:
            raise MeshError(f"{cm.source}: the sector cut lines do not have matching nodes "
                            f"(worst mismatch {dist.max():.3g} m)")
        master_x, master_y = ax, ay
        slave_x, slave_y = bx[idx], by[idx]
        # a pair where either side is clamped is clamped on both sides
        clamp = np.isin(master_x, fixed) | np.isin(slave_x, fixed)
        fixed = np.unique(np.concatenate([fixed, master_x[clamp], master_y[clamp],
                                          slave_x[clamp], slave_y[clamp]]))
        keep = ~clamp
        master_x, master_y, slave_x, slave_y = (a[keep] for a in (master_x, master_y, slave_x, slave_y))
    dependent = np.zeros(N, dtype=bool)
    dependent[fixed] = True
    dependent[slave_x] = True
    dependent[slave_y] = True
    indep = np.nonzero(~dependent)[0]
    col = -np.ones(N, dtype=np.int64)
    col[indep] = np.arange(len(indep))
    rows = [indep]
    cols = [col[indep]]
    vals = [np.ones(len(indep))]
    if len(slave_x):
        # u_b = R u_a:  ub_x = c ua_x - s ua_y ; ub_y = s ua_x + c ua_y
        rows += [slave_x, slave_x, slave_y, slave_y]
        cols += [col[master_x], col[master_y], col[master_x], col[master_y]]
        vals += [np.full(len(slave_x), c), np.full(len(slave_x), -s),
                 np.full(len(slave_x), s), np.full(len(slave_x), c)]
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(N, len(indep)))
    return T


def contact_weights(cm: ClutchMesh, basis: Basis, facets: np.ndarray) -> np.ndarray:
    """int phi_i ds over the given facets for every dof (length N, x and y dofs equal):
    the tributary length of each P2 node, used to turn nodal forces into pressures."""
    fb = FacetBasis(cm.mesh, basis.elem, facets=facets, intorder=6)

    @LinearForm
    def length(v, w):
        return v[0] + v[1]

    return asm(length, fb)
