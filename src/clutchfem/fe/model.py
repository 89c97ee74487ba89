"""The FE model of one design: linear elasticity of the spinning part (scikit-fem, P2 on the
curved ``MeshTri2``), built once per (mesh, material, thickness, formulation) and shared by
every load case of that design (speeds, friction coefficients, softening strategies).

Unknowns: the in-plane displacement u, P2 vector field, axial thickness h.  Operators (all
multiplied by h):

* ``K``  stiffness.  *Plane stress* (thin plate, s_zz = 0): Lame pair (lambda*, mu) =
  (E nu / (1 - nu^2), E / (2 (1 + nu))).  *Plane strain* (long prism, e_zz = 0): (lambda, mu)
  = (E nu / ((1 + nu)(1 - 2 nu)), E / (2 (1 + nu))) and s_zz = nu (s_xx + s_yy).  Both are
  computed in :class:`~clutchfem.core.Material` (skfem's ``plane_stress`` helper changed
  meaning between releases).  The true 11 mm plate with 1.75 mm flexures lies between them;
  the model-form error is measured in BENCHMARKS.md;
* ``M``  in-plane mass rho h int u.v: the *spin-softening* operator, because the centrifugal
  load acts on the deformed position, f = rho w^2 (x + u).  Assembled on first use only
  (a load case without spin softening never needs it);
* ``f1`` centrifugal load at w = 1 rad/s: rho h int x.v (rotation about z through the origin).

Constraints: the bore is clamped (u = 0); a one-sector model of n identical shoes gets the
cyclic (rotated periodic) constraint u(cut_b) = R(2 pi/n) u(cut_a).  Both are applied by a
sparse map ``T`` from independent dofs to all dofs, u = T a; the reduced stiffness T' K T is
factorised once, on first use, by the injected sparse solver (:mod:`clutchfem.fe.linsolve`).
"""

from __future__ import annotations

import math
import time
from functools import cached_property
from typing import Literal

import numpy as np
import scipy.sparse as sp
from skfem import Basis, BilinearForm, ElementTriP2, ElementVector, FacetBasis, LinearForm, asm
from skfem.helpers import ddot, dot, sym_grad, trace

from ..core import Material, MeshError, ParameterError, SolverError
from ..mesh import ClutchMesh, cyclic_pairing
from .linsolve import COUNTS, Solver, factorize
from .stress import VertexStress, von_mises

Formulation = Literal["plane-stress", "plane-strain"]
FORMULATIONS: tuple[str, ...] = ("plane-stress", "plane-strain")


class ConstrainedOperators:
    """What every FE model (2-D :class:`FEModel`, 3-D :class:`clutchfem.fe.FEModel3D`)
    derives the same way from its ``K``, ``M``, ``f1``, constraint map ``T``, ``basis`` and
    injected ``solver``: the reduced operators, the one factorisation, solves and u1."""

    @property
    def ndofs(self) -> int:
        return self.basis.N

    @cached_property
    def Kr(self) -> sp.csc_matrix:
        return (self.T.T @ self.K @ self.T).tocsc()

    @cached_property
    def Mr(self) -> sp.csc_matrix:
        return (self.T.T @ self.M @ self.T).tocsc()

    @cached_property
    def factor(self):
        """Factorisation of T' K T by the injected solver (computed on first use)."""
        t0 = time.perf_counter()
        f = factorize(self.Kr, self.solver)
        self.timings["factorize_s"] = time.perf_counter() - t0
        return f

    def solve(self, F: np.ndarray) -> np.ndarray:
        """Displacements (all dofs) for load(s) F (N or N x k), no contact, no softening."""
        return self.T @ self.factor.solve(self.T.T @ F)

    @cached_property
    def u1(self) -> np.ndarray:
        """Free displacement at w = 1 rad/s (no contact, no softening): u(w) = w^2 u1."""
        t0 = time.perf_counter()
        u = self.solve(self.f1)
        self.timings["solve_u1_s"] = time.perf_counter() - t0
        return u


class FEModel(ConstrainedOperators):
    """Assembled operators of one meshed part, material, thickness and formulation.

    ``solver``: the sparse direct solver back-end (a name or a factory ``A -> .solve(B)``;
    None: the default of :func:`clutchfem.fe.factorize`).  Built once per design; the
    factorisation of T' K T happens on the first :meth:`solve`.
    """

    def __init__(self, cm: ClutchMesh, material: Material, thickness: float | None = None, *,
                 formulation: Formulation = "plane-stress", solver: Solver = None):
        if formulation not in FORMULATIONS:
            raise ParameterError("formulation", formulation, "one of " + ", ".join(FORMULATIONS))
        h = thickness if thickness is not None else cm.thickness
        if h is None:
            raise SolverError("the axial thickness is unknown: give thickness (m) for a user mesh")
        h = float(h)
        if not (math.isfinite(h) and h > 0):
            raise ParameterError("thickness", h, "an axial thickness > 0 m")
        t0 = time.perf_counter()
        self.cm = cm
        self.material = material
        self.thickness = h
        self.formulation = formulation
        self.solver = solver
        self.timings: dict[str, float] = {}
        self.basis = Basis(cm.mesh, ElementVector(ElementTriP2()), intorder=4)
        lam, mu = self.lame
        rho = material.rho

        @BilinearForm
        def stiffness(u, v, w):
            eu, ev = sym_grad(u), sym_grad(v)
            return h * (2.0 * mu * ddot(eu, ev) + lam * trace(eu) * trace(ev))

        @LinearForm
        def centrifugal(v, w):
            return h * rho * (w.x[0] * v[0] + w.x[1] * v[1])

        self.K = asm(stiffness, self.basis).tocsr()
        self.f1 = asm(centrifugal, self.basis)
        COUNTS["assemble"] += 1
        t1 = time.perf_counter()
        self.T = constraint_map(cm, self.basis)
        self.timings.update({"assemble_s": t1 - t0, "constraints_s": time.perf_counter() - t1})

    # -- material law -------------------------------------------------------------------
    @property
    def lame(self) -> tuple[float, float]:
        """(lambda, mu) [Pa] of the formulation (see module docstring)."""
        if self.formulation == "plane-strain":
            return self.material.lame_plane_strain()
        return self.material.lame_plane_stress()

    @property
    def szz_factor(self) -> float:
        """s_zz = factor * (s_xx + s_yy): 0 in plane stress, nu in plane strain."""
        return self.material.nu if self.formulation == "plane-strain" else 0.0

    # -- operators ----------------------------------------------------------------------
    @cached_property
    def M(self) -> sp.csr_matrix:
        """Mass matrix rho h int u.v (spin softening); assembled on first use."""
        t0 = time.perf_counter()
        h, rho = self.thickness, self.material.rho
        basis = self.basis
        sb = basis.with_element(ElementTriP2())

        @BilinearForm
        def mass(u, v, w):  # scalar P2 mass; the vector one is kron(M, I2) (dof 2 i + component)
            return h * rho * u * v

        if (np.array_equal(basis.nodal_dofs, 2 * sb.nodal_dofs + np.array([[0], [1]]))
                and np.array_equal(basis.facet_dofs, 2 * sb.facet_dofs + np.array([[0], [1]]))):
            M = sp.kron(asm(mass, sb), sp.identity(2, format="csr"), format="csr")
        else:  # another dof layout: assemble the vector form directly
            M = asm(BilinearForm(lambda u, v, w: h * rho * dot(u, v)), basis).tocsr()
        self.timings["mass_s"] = time.perf_counter() - t0
        return M


    # -- post-processing ----------------------------------------------------------------
    @cached_property
    def stress(self):
        """Raw vertex stress recovery (:class:`clutchfem.fe.stress.VertexStress`)."""
        return VertexStress(self)

    @cached_property
    def _vertex_basis(self) -> Basis:
        X = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
        W = np.full(3, 1.0 / 6.0)
        return Basis(self.cm.mesh, ElementVector(ElementTriP2()), quadrature=(X, W))

    def stress_at_vertices(self, u: np.ndarray) -> np.ndarray:
        """Raw stresses (sxx, syy, sxy) [Pa] at each element's three vertices from
        scikit-fem's own interpolation: array (3, nelem, 3).  The reference for the fast
        :class:`~clutchfem.fe.VertexStress` (which must equal it to round-off)."""
        g = self._vertex_basis.interpolate(u).grad  # (2, 2, nelem, 3)
        lam, mu = self.lame
        exx, eyy = g[0, 0], g[1, 1]
        exy = 0.5 * (g[0, 1] + g[1, 0])
        tr = exx + eyy
        return np.stack([2 * mu * exx + lam * tr, 2 * mu * eyy + lam * tr, 2 * mu * exy])

    def von_mises(self, s: np.ndarray) -> np.ndarray:
        """von Mises stress of (sxx, syy, sxy) stacked on the first axis, with the
        formulation's s_zz."""
        return von_mises(s, self.szz_factor)


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
        idx = cyclic_pairing(basis.doflocs[:, ax], basis.doflocs[:, bx], cm.sector_angle,
                             scale=float(np.max(np.abs(basis.doflocs))),
                             what=f"{cm.source}: the sector cut lines")
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
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(N, len(indep)))


def contact_weights(cm: ClutchMesh, basis: Basis, facets: np.ndarray) -> np.ndarray:
    """int phi_i ds over the given facets for every dof (length N, x and y dofs equal):
    the tributary length of each P2 node, used to turn nodal forces into pressures."""
    try:
        fb = FacetBasis(cm.mesh, basis.elem, facets=facets, intorder=6)
    except Exception:  # skfem's inverse isoparametric map (Newton) fails on some curved P2 facets
        return _edge_weights(basis, np.asarray(facets))

    @LinearForm
    def length(v, w):
        return v[0] + v[1]

    return asm(length, fb)


def _edge_weights(basis: Basis, facets: np.ndarray) -> np.ndarray:
    """:func:`contact_weights` without the inverse map: each P2 facet is the quadratic curve
    x(s) = sum N_i(s) x_i (s in [-1, 1]; N = s(s-1)/2, s(s+1)/2, 1 - s^2 at its two vertices
    and its mid node, the isoparametric trace), int N_i |x'(s)| ds by 6-point Gauss."""
    m = basis.mesh
    s, wq = np.polynomial.legendre.leggauss(6)
    N = np.stack([0.5 * s * (s - 1), 0.5 * s * (s + 1), 1 - s ** 2])  # (3, nq)
    dN = np.stack([s - 0.5, s + 0.5, -2 * s])
    out = np.zeros(basis.N)
    for comp in range(2):
        va, vb = basis.nodal_dofs[comp][m.facets[0, facets]], basis.nodal_dofs[comp][m.facets[1, facets]]
        vm = basis.facet_dofs[comp][facets]
        X = basis.doflocs[:, np.stack([va, vb, vm])]  # (2, 3, nf)
        jac = np.sqrt(((X[:, :, :, None] * dN[None, :, None, :]).sum(axis=1) ** 2).sum(axis=0))  # (nf, nq)
        for k, dofs in enumerate((va, vb, vm)):
            np.add.at(out, dofs, (N[k][None, :] * jac * wq[None, :]).sum(axis=1))
    return out
