"""The thick plane model: the 2-D mesh with polynomial through-thickness modes, a reduced
3-D basis that gives the 3-D answer of an extruded part at 2-D cost plus a few fields.

Why
---
Plane stress (s_zz = 0) is the thin limit, plane strain (e_zz = 0) the long-prism limit; the
11 mm thick clutch with ~2 mm flexures bent in their plane is neither.  In a flexure's
interior the anticlastic deformation is free (the Saint-Venant bending solution: plane
stress), but within about one thickness of its ends the thick hub and shoe hold the
transverse strain (plane-strain-like): the 3-D part engages 1.6-2.3 % above plane stress,
a per-design amount (``benchmarks/results_modelform.md``).  Where the restraint sits and
how far it reaches is a solution of 3-D elasticity, not of the local geometry alone, so it
is computed here, not fitted.

Kinematics (mid-plane symmetric part, z in [-h/2, h/2], zeta = 2 z / h)
---------------------------------------------------------------------
The part, its loads, the bore clamp, the cyclic cuts and the drum are symmetric about z = 0,
so u_x, u_y are even and u_z odd in z (:mod:`clutchfem.fe.model3d`).  The displacement is
expanded in polynomials of zeta (Vekua / hierarchical plate theory; Szabo and Babuska,
*Finite Element Analysis*, 1991, ch. 14):

    u_a(x, y, z) = a0_a(x, y) + sum_{p = 2, 4, ..} (zeta^p - 1 / (p + 1)) ap_a(x, y)   (a = x, y)
    u_z(x, y, z) = sum_{q = 1, 3, ..} (h / 2) zeta^q cq(x, y)

up to ``order`` (the highest even power; u_z to order - 1).  The in-plane modes have zero
mean through the thickness, so a0 *is* the thickness-averaged in-plane displacement: the
contact with the drum (a uniform line load through the thickness) and the centrifugal load
rho w^2 (x + u) act on a0 exactly as on the 2-D model's u, and the contact machinery runs
unchanged.  Strains (Voigt xx, yy, zz, yz, xz, xy, engineering shears):

    e_ab = sym grad a0 + sum_p phi_p sym grad ap,   e_zz = sum_q q zeta^(q-1) cq,
    g_az = sum_p phi_p'(z) ap_a + sum_q (h / 2) zeta^q d_a cq,

with the 3-D isotropic law; the energy is integrated over z exactly (Gauss-Legendre).
``order`` 2 is exact for Saint-Venant bending (the anticlastic mode u_y ~ z^2, u_z ~ y z),
and order 4 adds the end restraint's boundary layer: the engagement speed of concepts 1 and
4 at 4-16 mm thickness is within 0.05 % of order 6 and of P2 tetrahedra converged in
layers (``benchmarks/results_accuracy.md``), order 2 is 0.3-0.5 % too stiff.

Discretisation: a0 in P2 (the 2-D model's element and dof layout, dofs first), the
higher modes in P1 on the same mesh (P2 there moved the engagement by 0.05 %, measured).
Unknowns: 2-D + (order / 2 - 1) x 2 + order / 2 per vertex, ~1.8 x the 2-D count at order 4.

Operators: ``K`` (3-D law integrated over z), ``f1`` (rho h int x . a0: the higher modes
have zero mean), ``M`` (in-plane mass of every in-plane mode: rho int u_a v_a dV), ``T``
(bore clamped: every mode; cyclic: in-plane modes rotate, cq copied), the pre-stress
stiffness :meth:`FEModelThick.geometric_stiffness` (the membrane forces N_ab = int s_ab dz
of the linear centrifugal state acting on grad a0; the u_z and higher-mode rotations are
O(nu e h) and left out).  Stresses: the 3-D tensor at every element vertex on the mid-plane
and on the free face z = h/2 (the peak sits on one of them: the in-plane modes are even
polynomials), 6 Voigt components like :class:`~clutchfem.fe.VertexStress3D`.
"""

from __future__ import annotations

import math
import time
from functools import cached_property
from typing import ClassVar

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementTriP1, ElementTriP2, ElementVector

from ..core import Material, ParameterError, ParamSet, SolverError, param
from ..mesh import ClutchMesh, cyclic_pairing
from .linsolve import COUNTS
from .model import ConstrainedOperators, constraint_map
from .stress import von_mises
from .thick_stress import ThickStress

__all__ = ["ThickSettings", "FEModelThick", "thick_modes"]


class ThickSettings(ParamSet):
    """The through-thickness modes of :class:`FEModelThick`."""

    context: ClassVar[str] = "thick plane model"
    order: int = param(4, "-", 2, 8, "highest even power of z in the in-plane displacement (u_z to order - 1): "
                       "2 = Saint-Venant bending, 4 = with the end restraint (3-D to 0.05 %)")

    def check(self) -> None:
        if self.order % 2:
            self.fail("order", "an even number (the in-plane modes are even in z)")


def thick_modes(order: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """(even powers p >= 2 of the higher in-plane modes, odd powers q of the axial modes)."""
    return tuple(range(2, order + 1, 2)), tuple(range(1, order, 2))


def _c3(E: float, nu: float) -> np.ndarray:
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    C = np.zeros((6, 6))
    C[:3, :3] = lam
    C[range(3), range(3)] += 2 * mu
    C[3:, 3:] = mu * np.eye(3)
    return C


# strain rows (Voigt) hit by (component, op): op 1 = d/dx, 2 = d/dy of an in-plane field
_XX, _YY, _ZZ, _YZ, _XZ, _XY = range(6)


class FEModelThick(ConstrainedOperators):
    """Assembled operators of the thick plane model (module docstring): the interface of
    :class:`clutchfem.fe.FEModel` (``cm, material, thickness, formulation, basis, K, f1, T,
    M, Kr, Mr, factor, solve, u1, stress, ndofs, timings``) so that the contact, softening
    and sweep machinery runs on it unchanged.  ``basis`` is the 2-D vector P2 basis of the
    mean in-plane displacement a0, whose dofs come first (``n_mean`` of ``ndofs``)."""

    formulation = "thick"
    szz_factor = 0.0

    def __init__(self, cm: ClutchMesh, material: Material, thickness: float | None = None, *,
                 settings: ThickSettings | None = None, solver=None):
        h = thickness if thickness is not None else cm.thickness
        if h is None or not (math.isfinite(float(h)) and float(h) > 0):
            raise ParameterError("thickness", h, "an axial thickness > 0 m")
        t0 = time.perf_counter()
        self.cm, self.material, self.thickness, self.solver = cm, material, float(h), solver
        self.settings = settings or ThickSettings()
        self.timings: dict[str, float] = {}
        self.even, self.odd = thick_modes(self.settings.order)
        self.basis = Basis(cm.mesh, ElementVector(ElementTriP2()), intorder=4)
        self._p2 = self.basis.with_element(ElementTriP2())
        self._p1 = self.basis.with_element(ElementTriP1())
        nv = int(cm.mesh.nvertices)
        if not np.array_equal(self._p1.nodal_dofs[0], np.arange(nv)):  # pragma: no cover
            raise SolverError("unexpected scikit-fem dof layout for ElementTriP1")
        self.n_mean = self.basis.N
        # extra fields: (kind, power, component) in dof order after a0
        self.fields = [("a", p, c) for p in self.even for c in (0, 1)] + [("c", q, None) for q in self.odd]
        self.nv = nv
        self._K, self.f1 = self._assemble()
        COUNTS["assemble"] += 1
        t1 = time.perf_counter()
        self.T = self._constraints()
        self.timings.update({"assemble_s": t1 - t0, "constraints_s": time.perf_counter() - t1})

    # -- material law -------------------------------------------------------------------
    @property
    def lame(self) -> tuple[float, float]:
        return self.material.lame_plane_strain()  # the 3-D pair

    @property
    def ndofs(self) -> int:
        return self.n_mean + len(self.fields) * self.nv

    @property
    def K(self) -> sp.csr_matrix:
        return self._K

    def field_dofs(self, i: int) -> np.ndarray:
        """Global dofs (nv,) of extra field ``i`` (order of :attr:`fields`) at every vertex."""
        return self.n_mean + i * self.nv + np.arange(self.nv)

    # -- z integration ------------------------------------------------------------------
    @cached_property
    def _zeta(self):
        return np.polynomial.legendre.leggauss(self.settings.order + 3)

    def _phi(self, p, zeta):
        """(phi_p, d phi_p / dz) of the in-plane mode p at zeta."""
        if p == 0:
            return np.ones_like(zeta), np.zeros_like(zeta)
        return zeta ** p - 1.0 / (p + 1), p * zeta ** (p - 1) * 2.0 / self.thickness

    def _psi(self, q, zeta):
        """(psi_q, d psi_q / dz) of the axial mode q at zeta (psi_q = (h/2) zeta^q)."""
        return 0.5 * self.thickness * zeta ** q, q * zeta ** (q - 1)

    def _strain_maps(self, zeta):
        """Z[(field, op)] (6, nz): the 3-D strain at each zeta per unit of ``op`` (0 value,
        1 d/dx, 2 d/dy) of each field; fields: 0, 1 = a0_x, a0_y, then :attr:`fields`."""
        Z = {}
        nz = len(zeta)
        for fi, (kind, pw, comp) in enumerate([("a", 0, 0), ("a", 0, 1)] + self.fields):
            zv, zx, zy = np.zeros((6, nz)), np.zeros((6, nz)), np.zeros((6, nz))
            if kind == "a":
                v, dv = self._phi(pw, zeta)
                if comp == 0:
                    zx[_XX], zy[_XY], zv[_XZ] = v, v, dv
                else:
                    zy[_YY], zx[_XY], zv[_YZ] = v, v, dv
            else:
                v, dv = self._psi(pw, zeta)
                zv[_ZZ], zx[_XZ], zy[_YZ] = dv, v, v
            Z[(fi, 0)], Z[(fi, 1)], Z[(fi, 2)] = zv, zx, zy
        return Z

    # -- assembly -----------------------------------------------------------------------
    def _assemble(self):
        """K and f1, vectorised: per element the products of shape-function values and
        derivatives of the P2 (a0) and P1 (higher modes) bases, combined with the
        through-thickness moments D[(f, op), (g, op')] = int Z' C Z dz."""
        zeta, w = self._zeta
        wz = 0.5 * self.thickness * w
        C = _c3(self.material.E, self.material.nu)
        Z = self._strain_maps(zeta)
        nf = 2 + len(self.fields)
        D = np.zeros((nf, 3, nf, 3))
        for (f, o), zf in Z.items():
            czf = C @ zf
            for (g, o2), zg in Z.items():
                D[f, o, g, o2] = float(np.sum(wz * np.einsum("iz,iz->z", czf, zg)))
        ops = {}
        dx = self._p2.dx
        for name, b in (("p2", self._p2), ("p1", self._p1)):
            nb = b.Nbfun
            V = np.stack([np.asarray(b.basis[k][0]) for k in range(nb)])  # (nb, ne, nq)
            G = np.stack([b.basis[k][0].grad for k in range(nb)])  # (nb, 2, ne, nq)
            # (3 ops, ne, nb, nq): value, d/dx, d/dy
            ops[name] = np.ascontiguousarray(np.stack([V, G[:, 0], G[:, 1]]).transpose(0, 2, 1, 3))
        prod = {}
        for a in ("p2", "p1"):
            for b_ in ("p2", "p1"):
                # M[o, o2, e, k, l] = int (op_o N_k)(op_o2 N_l): batched products over the quadrature
                Bw = np.ascontiguousarray((ops[b_] * dx[None, :, None, :]).transpose(0, 1, 3, 2))  # (3, ne, nq, nb)
                prod[a, b_] = np.stack([np.stack([ops[a][o] @ Bw[o2] for o2 in range(3)]) for o in range(3)])
        ne = self.cm.n_elements
        el = ["p2", "p2"] + ["p1"] * len(self.fields)
        # local dofs: a0 in the vector basis' element order (2 k + c), then 3 per extra field
        ed = self.basis.element_dofs.T  # (ne, 12)
        e1 = self._p1.element_dofs.T  # (ne, 3): the vertices
        loc = [ed[:, 0::2], ed[:, 1::2]] + [self.n_mean + i * self.nv + e1 for i in range(len(self.fields))]
        sizes = [x.shape[1] for x in loc]
        starts = np.concatenate([[0], np.cumsum(sizes)])
        nl = int(starts[-1])
        Ke = np.zeros((ne, nl, nl))
        for f in range(nf):
            for g in range(nf):
                d = D[f, :, g, :]
                if not d.any():
                    continue
                P = prod[el[f], el[g]]
                for o, o2 in zip(*np.nonzero(d)):
                    Ke[:, starts[f]:starts[f + 1], starts[g]:starts[g + 1]] += d[o, o2] * P[o, o2]
        dofs = np.hstack(loc)  # (ne, nl)
        N = self.ndofs
        K = sp.coo_matrix((Ke.ravel(), (np.repeat(dofs, nl, axis=1).ravel(), np.tile(dofs, (1, nl)).ravel())),
                          shape=(N, N)).tocsr()
        x = self._p2.mapping.F(self._p2.X)  # (2, ne, nq)
        rho_h = self.material.rho * self.thickness
        f1 = np.zeros(N)
        for c in (0, 1):
            fe_ = rho_h * np.einsum("ekq,eq->ek", ops["p2"][0], x[c] * dx)
            np.add.at(f1, loc[c].ravel(), fe_.ravel())
        return K, f1

    @cached_property
    def M(self) -> sp.csr_matrix:
        """In-plane mass rho int u_a v_a dV of every in-plane mode (spin softening)."""
        t0 = time.perf_counter()
        rho, h = self.material.rho, self.thickness
        zeta, w = self._zeta
        m2 = _mass(self._p2)
        blocks = [sp.kron(m2, sp.identity(2), format="csr") * (rho * h)]
        m1 = _mass(self._p1)
        # modes a_p (x and y) couple with each other through int phi_p phi_r dz; cq: no in-plane mass
        pw = [(p, c) for (kind, p, c) in self.fields if kind == "a"]
        A = np.array([[0.5 * h * float(np.sum(w * self._phi(p, zeta)[0] * self._phi(r, zeta)[0])) if c == d else 0.0
                       for (r, d) in pw] for (p, c) in pw])
        ncomp = len(pw)
        ext = sp.kron(sp.csr_matrix(A * rho), m1, format="csr") if ncomp else None
        nq = len(self.odd) * self.nv
        M = sp.block_diag([blocks[0]] + ([ext] if ext is not None else []) + [sp.csr_matrix((nq, nq))],
                          format="csr")
        M.eliminate_zeros()
        self.timings["mass_s"] = time.perf_counter() - t0
        return M

    def _constraints(self) -> sp.csr_matrix:
        """u = T a: every mode clamped on the bore; cyclic: the in-plane modes rotate with
        the sector, the axial ones are copied."""
        cm = self.cm
        T0 = constraint_map(cm, self.basis)
        mesh = cm.mesh
        nv = self.nv
        bore = np.unique(mesh.facets[:, cm.boundary("bore")])
        fixed = np.zeros(nv, dtype=bool)
        fixed[bore] = True
        pairs = None
        if cm.sector_angle is not None:
            va = np.unique(mesh.facets[:, cm.boundary("cut_a")])
            vb = np.unique(mesh.facets[:, cm.boundary("cut_b")])
            idx = cyclic_pairing(mesh.p[:, va], mesh.p[:, vb], cm.sector_angle,
                                 scale=float(np.max(np.abs(mesh.p))), what=f"{cm.source}: the sector cut lines")
            vb = vb[idx]
            clamp = fixed[va] | fixed[vb]
            fixed[va[clamp]] = fixed[vb[clamp]] = True
            pairs = (va[~clamp], vb[~clamp])
        c = s = 0.0
        if cm.sector_angle is not None:
            c, s = math.cos(cm.sector_angle), math.sin(cm.sector_angle)
        slave = np.zeros(nv, dtype=bool)
        if pairs is not None:
            slave[pairs[1]] = True
        free = np.nonzero(~fixed & ~slave)[0]
        col = -np.ones(nv, dtype=np.int64)
        col[free] = np.arange(len(free))
        nfree = len(free)
        rows, cols, vals = [], [], []
        nfld = len(self.fields)
        for i, (kind, p, comp) in enumerate(self.fields):
            base = self.n_mean + i * nv
            rows.append(base + free)
            cols.append(i * nfree + col[free])
            vals.append(np.ones(nfree))
            if pairs is None:
                continue
            va, vb = pairs
            if kind == "c":
                rows.append(base + vb)
                cols.append(i * nfree + col[va])
                vals.append(np.ones(len(va)))
            else:  # u_b = R u_a: x_b = c x_a - s y_a, y_b = s x_a + c y_a (x at field ix, y at ix + 1)
                ix = i - comp
                coefs = (c, -s) if comp == 0 else (s, c)
                for j, coef in zip((ix, ix + 1), coefs):
                    rows.append(base + vb)
                    cols.append(j * nfree + col[va])
                    vals.append(np.full(len(va), coef))
        Te = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows) - self.n_mean, np.concatenate(cols))),
                           shape=(nfld * nv, nfld * nfree))
        return sp.block_diag([T0, Te], format="csr")

    # -- pre-stress -----------------------------------------------------------------------
    def geometric_stiffness(self, u: np.ndarray) -> sp.csr_matrix:
        """Pre-stress stiffness of the state ``u``: int N_ab d_a du_k d_b v_k dA on the mean
        in-plane displacement a0, N_ab = int s_ab dz the membrane forces (module docstring)."""
        lam, mu = self.lame
        h = self.thickness
        b2 = self._p2
        G = np.stack([b2.basis[k][0].grad for k in range(b2.Nbfun)])  # (6, 2, ne, nq)
        ed = self.basis.element_dofs  # (12, ne)
        U = u[ed]  # (12, ne)
        gx = np.einsum("keq,ke->eq", G[:, 0], U[0::2])
        gxy = np.einsum("keq,ke->eq", G[:, 1], U[0::2])
        gyx = np.einsum("keq,ke->eq", G[:, 0], U[1::2])
        gy = np.einsum("keq,ke->eq", G[:, 1], U[1::2])
        V1 = self._p1.basis
        czz = 0.0
        for i, (kind, q, _) in enumerate(self.fields):
            if kind == "c":  # int e_zz dz = h cq for every odd q
                cf = u[self.field_dofs(i)][self.cm.mesh.t[:3]]  # (3, ne)
                czz = czz + np.einsum("keq,ke->eq", np.stack([np.asarray(V1[k][0]) for k in range(3)]), cf)
        tr = gx + gy
        Nxx = h * (2 * mu * gx + lam * (tr + czz))
        Nyy = h * (2 * mu * gy + lam * (tr + czz))
        Nxy = h * mu * (gxy + gyx)
        S = np.stack([np.stack([Nxx, Nxy]), np.stack([Nxy, Nyy])])  # (2, 2, ne, nq)
        kg = np.einsum("kaeq,abeq,lbeq,eq->ekl", G, S, G, b2.dx)  # (ne, 6, 6)
        ne = kg.shape[0]
        Ke = np.zeros((ne, 6, 2, 6, 2))
        Ke[:, :, 0, :, 0] = kg
        Ke[:, :, 1, :, 1] = kg
        dofs = ed.T  # (ne, 12), local 2 k + c
        Ke = Ke.reshape(ne, 12, 12)
        N = self.ndofs
        return sp.coo_matrix((Ke.ravel(), (np.repeat(dofs, 12, axis=1).ravel(), np.tile(dofs, (1, 12)).ravel())),
                             shape=(N, N)).tocsr()

    # -- post-processing ----------------------------------------------------------------
    @cached_property
    def stress(self) -> "ThickStress":
        return ThickStress(self)

    def von_mises(self, s: np.ndarray) -> np.ndarray:
        return von_mises(s)


def _mass(b: Basis) -> sp.csr_matrix:
    nb = b.Nbfun
    V = np.stack([np.asarray(b.basis[k][0]) for k in range(nb)])
    Me = np.einsum("keq,leq,eq->ekl", V, V, b.dx)
    ed = b.element_dofs.T
    return sp.coo_matrix((Me.ravel(), (np.repeat(ed, nb, axis=1).ravel(), np.tile(ed, (1, nb)).ravel())),
                         shape=(b.N, b.N)).tocsr()
