"""Geometrically non-linear reference: total Lagrangian plane stress with the centrifugal
load on the deformed position and contact with the exact drum circle.

What it is for
--------------
The fast path (:mod:`clutchfem.loadcase`) is linear: small displacements, the gap measured
along the initial normal, the centrifugal load on the undeformed position (plus the
spin-softening term -w^2 M u).  This module drops those assumptions to *measure* their
error over the speed range; it is a reference, not the production path.

Kinematics and material
-----------------------
Reference position X, displacement u (P2 on the curved ``MeshTri2``), F = I + grad u,
Green-Lagrange strain E = (F'F - I)/2, St. Venant-Kirchhoff S = lambda* tr(E) I + 2 mu E with
the plane-stress Lame pair (lambda* = E nu / (1 - nu^2)), first Piola-Kirchhoff P = F S, all
times the thickness h.  Why St. Venant-Kirchhoff: the clutch's strains stay below ~0.7 %
(the yield strain of 51CrV4) while the shoe rotates by a few degrees as a rigid body; SVK is
exactly frame-invariant (rotations are handled exactly) and agrees with any hyperelastic
law to O(strain^2) relative, ~1e-2 of the already small non-linear correction.  The
thickness change under in-plane strain (a plane-stress membrane's e_zz) is neglected: an
O(strain) effect on the load-carrying area, the same order as SVK's own error.

Loads and contact
-----------------
* Centrifugal load per reference volume rho w^2 (X + u)_perp (mass is conserved), i.e.
  f(u) = w^2 (f1 + M u): exactly linear in u, so its tangent is -w^2 M (no approximation).
* Contact nodes (the P2 nodes of the ``contact`` group, :func:`clutchfem.contact.contact_nodes`)
  must stay inside the drum circle: g_i(u) = R_d - |X_i + u_i| >= 0 (exact, after any
  tangential motion; the linear path uses g0_i - n_i . u_i).  The drum pushes with lam_i >= 0
  along -n_i(u) = -(X_i + u_i)/|X_i + u_i|; full-slip Coulomb friction (drum held, hub
  turning in sense s) adds -s mu lam_i t_i(u), t_i = e_z x n_i, as in :mod:`clutchfem.contact`.
* Complementarity 0 <= lam perp g >= 0 by a semismooth Newton (primal-dual active set):
  at each iteration the active set is {i : lam_i - c g_i > 0} (c = mean stiffness diagonal),
  the active gaps are linearised exactly (dg_i = -n_i . du_i) and the non-linear residual
  with contact forces is solved as one bordered sparse system (unsymmetric with friction:
  SuperLU).  The contact force's own tangent (the normal turns with the node,
  d n / d x = (I - n n') / |x|) is included, so the iteration converges quadratically.

Convergence: Newton correction max|du| <= ``tol`` max|u| (1e-10), force residual
||T' r|| <= ``res_tol`` ||T' f_ext|| (1e-7: its round-off floor is ~1e-10, element forces
cancel), the active set unchanged, penetration <= ``tol`` R_d, lam >= 0.  Speeds are stepped upwards from the last
converged state (continuation); a step that does not converge in ``max_iter`` iterations is
halved (at most ``max_halvings`` times).

Fast-path corrections (linear in w^2, for the one-factorisation machinery)
-------------------------------------------------------------------------
* geometric (stress) stiffness of the centrifugal pre-stress: with sigma1 the linear
  stress at w = 1, K_sigma1 = h int sigma1 : (grad du' grad v) (:func:`clutchfem.fe.geometric_stiffness`);
  the prestressed linear operator is K + w^2 (K_sigma1 - M): the same form as spin
  softening with M replaced by M - K_sigma1.
* second-order gap: |X + u| = r + u_n + u_t^2 / (2 r) + O(u^3 / r^2), so the gap of the free
  part is g0 - w^2 u1_n - w^4 u1_t^2 / (2 r): the engagement speed solves a quadratic in w^2.
:func:`fast_path_variants` evaluates both; ``benchmarks/bench_modelform.py`` measures them.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import ClassVar, Literal

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..contact import contact_nodes, lazy, solve_lcp
from ..core import ParameterError, ParamSet, SolverError, choice, param, rad_s_to_rpm
from ..fe import Kinematics, von_mises

__all__ = ["NonlinearSettings", "NonlinearModel", "NLState", "second_order_engagement"]


class NonlinearSettings(ParamSet):
    """Convergence controls of the non-linear reference."""

    context: ClassVar[str] = "non-linear reference"
    tol: float = param(1e-10, "-", 1e-14, 1e-4,
                       "Newton correction / displacement (max norms) and penetration / R_d")
    res_tol: float = param(1e-7, "-", 1e-12, 1e-3, "relative force residual (its round-off floor "
                           "is ~1e-10 on clutch meshes: element forces cancel)")
    max_iter: int = param(40, "-", 3, 500, "Newton iterations per speed step")
    max_halvings: int = param(8, "-", 0, 30, "speed-step halvings before giving up")
    contact_solver: Literal["lcp", "pdas"] = choice(
        "lcp", doc="per Newton iteration: 'lcp' solves the linearised contact problem exactly "
        "(condensed on the contact nodes, :func:`clutchfem.contact.solve_lcp`); 'pdas' updates the "
        "active set by {lam - c g > 0} (one node per iteration leaves an elastic drum's arc)")


@dataclass
class NLState:
    """A converged non-linear state at one speed."""

    omega: float
    u: np.ndarray  # all dofs [m]
    lam: np.ndarray  # (m,) contact forces on the model [N]
    iterations: int
    residual: float  # relative force residual reached

    @property
    def rpm(self) -> float:
        return rad_s_to_rpm(self.omega)


def second_order_engagement(gap0: np.ndarray, un: np.ndarray, ut: np.ndarray,
                            r: np.ndarray) -> tuple[float, int]:
    """Engagement speed [rad/s] with the second-order gap of the free part,
    g_i(w) = g0_i - w^2 un_i - w^4 ut_i^2 / (2 r_i) (un, ut: normal and tangential
    displacement per w^2, r: node radius): smallest positive root over nodes of the
    quadratic in x = w^2.  Returns (w0, node index); (nan, -1) if no node closes."""
    a = ut * ut / (2 * r)
    x = np.full(len(gap0), np.inf)
    quad = a > 1e-300
    # a x^2 + un x - g0 = 0, positive root (stable form)
    disc = un * un + 4 * a * gap0
    xq = 2 * gap0[quad] / (un[quad] + np.sqrt(disc[quad]))
    x[quad] = np.where(xq > 0, xq, np.inf)
    lin = ~quad & (un > 0)
    x[lin] = gap0[lin] / un[lin]
    i = int(np.argmin(x))
    if not np.isfinite(x[i]):
        return math.nan, -1
    return math.sqrt(x[i]), i


class NonlinearModel:
    """Total-Lagrangian reference of a 2-D (plane-stress) model ``fe`` (a
    :class:`clutchfem.fe.FEModel`: basis, M, f1, T, material, thickness, cm) against a rigid
    drum of radius ``drum_radius`` (None: free part); see the module docstring."""

    def __init__(self, fe, drum_radius: float | None = None, mu: float = 0.0,
                 rotation: Literal["ccw", "cw"] = "ccw",
                 settings: NonlinearSettings | None = None,
                 drum_compliance=None):
        if not (0.0 <= mu <= 1.0):
            raise ParameterError("mu", mu, "a friction coefficient in [0, 1]")
        if rotation not in ("ccw", "cw"):
            raise ParameterError("rotation", rotation, "'ccw' or 'cw'")
        if drum_radius is not None and not (drum_radius > 0 and math.isfinite(drum_radius)):
            raise ParameterError("drum_radius", drum_radius, "a radius > 0 m")
        self.fe = fe
        self.settings = settings or NonlinearSettings()
        self.mu, self.s = float(mu), (1.0 if rotation == "ccw" else -1.0)
        if getattr(fe, "formulation", "plane-stress") != "plane-stress":
            raise ParameterError("formulation", fe.formulation, "'plane-stress' (the non-linear "
                                 "reference is a plane-stress membrane)")
        lam, mu_ = fe.material.lame_plane_stress()
        self.kin = Kinematics(fe.basis, lam, mu_, fe.thickness)
        self.T = fe.T.tocsr()
        self.TT = self.T.T.tocsr()
        self.M = fe.M.tocsr()
        self.f1 = fe.f1
        self.R = drum_radius
        self.nodes = contact_nodes(fe, drum_radius) if drum_radius is not None else None
        self.timings: dict[str, float] = {}
        self.scale = float(fe.cm.sector_copies)
        self._c_value: float | None = None
        #: optional drum compliance C (m x m, [m/N]): the drum's inner wall moves out by C lam
        #: (the gap gains C lam); see :mod:`clutchfem.contact.ring`
        self.Cd = None if drum_compliance is None else np.asarray(drum_compliance, dtype=float)
        self.drum_free = None  # optional (m,) free drum expansion [m] (spinning drum)

    @property
    def _c(self) -> float:
        """The active-set constant c of 'pdas': the mean positive stiffness diagonal (lazy:
        one tangent assembly, which the 'lcp' update does not need)."""
        if self._c_value is None:
            kdiag = self.kin.residual_and_tangent(np.zeros(self.fe.basis.N))[1].diagonal()
            self._c_value = float(np.mean(kdiag[kdiag > 0]))
        return self._c_value

    # -- contact geometry ---------------------------------------------------------------
    def positions(self, u: np.ndarray) -> np.ndarray:
        nd = self.nodes
        return nd.xy + np.vstack([u[nd.dof_x], u[nd.dof_y]])

    def gaps(self, u: np.ndarray, lam: np.ndarray | None = None) -> np.ndarray:
        """Exact gaps R_d - |X_i + u_i| (+ the drum's own displacement if elastic)."""
        g = self.R - np.hypot(*self.positions(u))
        if self.drum_free is not None:
            g = g + self.drum_free
        if self.Cd is not None and lam is not None:
            g = g + self.Cd @ lam
        return g

    # -- one speed ----------------------------------------------------------------------
    def solve(self, omega: float, u0: np.ndarray | None = None, lam0: np.ndarray | None = None,
              contact: bool = True, extra_load: np.ndarray | None = None) -> NLState:
        """Converged state at speed ``omega`` [rad/s], stepping from (u0, lam0) at a lower
        speed if Newton needs it (``u0`` is then taken to be the state at speed 0 unless
        it comes with the speed it belongs to through :meth:`sweep`).  Raises
        :class:`~clutchfem.core.SolverError` when Newton's method does not converge."""
        N = self.fe.basis.N
        u0 = np.zeros(N) if u0 is None else u0
        try:
            return self._solve_at(omega, u0, lam0, contact, extra_load)
        except _NoConvergence as exc:  # (sweep's continuation halves its step on it instead)
            raise SolverError(f"non-linear reference: {exc}") from None

    def _solve_at(self, omega, u, lam, contact, extra_load):
        st = self.settings
        use_c = contact and self.nodes is not None
        m = self.nodes.m if use_c else 0
        lam = np.zeros(m) if (lam is None or not use_c) else lam.copy()
        w2 = omega * omega
        fext = w2 * self.f1 + (0.0 if extra_load is None else extra_load)
        ref = max(float(np.linalg.norm(self.TT @ fext)), 1e-300)
        pdas = use_c and st.contact_solver == "pdas"
        c = self._c if pdas else 0.0
        u = u.copy()
        if use_c:
            active = (lam - c * self.gaps(u, lam)) > 0
        res = math.inf
        r_int, K = self.kin.residual_and_tangent(u)
        for it in range(1, st.max_iter + 1):
            if K is None:  # (the tangent at a state that did not converge)
                K = self.kin.residual_and_tangent(u)[1]
            r0 = r_int - w2 * (self.M @ u) - fext  # residual without contact forces
            A = K - w2 * self.M
            if use_c:
                _, Kc, Dn, Nn = self._contact_terms(u, lam)
                A = A - Kc  # the contact force turns with the node (at the current lam)
            Ar = (self.TT @ A @ self.T).tocsc()
            if use_c and st.contact_solver == "lcp":
                da, new_lam = self._lcp_step(Ar, r0, u, lam, omega)
                idx = None
            elif use_c and active.any():
                # unknowns (da, lam_A), lam = 0 off the active set:
                #   T'r0 + Ar da - D_A lam_A = 0
                #   g_A(u) - N_A' T da + C_AA lam_A = 0   (exact gaps, linearised)
                idx = np.nonzero(active)[0]
                Dr = (self.TT @ Dn[:, idx]).tocsc()
                Nr = (self.TT @ Nn[:, idx]).tocsc()
                Cd = np.zeros((len(idx), len(idx))) if self.Cd is None else self.Cd[np.ix_(idx, idx)]
                Big = sp.bmat([[Ar, -Dr], [Nr.T, sp.csc_matrix(-Cd)]], format="csc")
                rhs = np.concatenate([-(self.TT @ r0), self.gaps(u)[idx]])
            else:
                idx = np.zeros(0, dtype=np.int64)
                Big, rhs = Ar, -(self.TT @ r0)
            if idx is not None:
                try:
                    sol = spla.splu(Big, permc_spec="COLAMD").solve(rhs)
                except RuntimeError:
                    raise SolverError(f"non-linear system singular at {rad_s_to_rpm(omega):.0f} rpm") from None
                nr = Ar.shape[0]
                da = sol[:nr]
                new_lam = np.zeros(m)
                new_lam[idx] = sol[nr:]
            u = u + self.T @ da
            res_prev = res
            if use_c:
                lam = new_lam
                g_new = self.gaps(u, lam)
                new_active = (lam - c * g_new) > 0
            # converged?  residual at the new state (its tangent, for the next iteration only)
            r_int, K = self.kin.residual_and_tangent(u, tangent=False)
            r = r_int - w2 * (self.M @ u) - fext
            if use_c:
                r = r - self._contact_terms(u, lam, forces_only=True)
            res = float(np.linalg.norm(self.TT @ r)) / ref
            inc = float(np.abs(da).max()) / max(float(np.abs(u).max()), 1e-300)
            ok = res <= st.res_tol and inc <= st.tol
            if use_c:
                pen = float(np.max(-g_new, initial=0.0))
                same = st.contact_solver == "lcp" or np.array_equal(new_active, active)
                ok = ok and same and pen <= st.tol * self.R \
                    and float(np.min(lam, initial=0.0)) >= -st.tol * max(float(np.max(lam, initial=0.0)), 1e-300)
                active = new_active
            if ok:
                return NLState(omega, u, lam, it, res)
            if not math.isfinite(res) or (it > 8 and res > res_prev * 10 and res > 1e-3):
                break
        raise _NoConvergence(omega, res)

    def _lcp_step(self, Ar, r0, u, lam, omega):
        """One Newton step with the linearised contact problem solved exactly: with da0 =
        Ar^-1 (-T' r0) and the force directions D, gap gradients N (reduced), the gaps after
        the step are w = q + G lam with q = g(u) - N' da0 and G = -N' Ar^-1 D + C_d (the
        drum's compliance), 0 <= lam perp w >= 0 (:func:`~clutchfem.contact.solve_lcp`,
        condensing only the columns its active set asks for); da = da0 + Ar^-1 D lam."""
        _, _, Dn, Nn = self._contact_terms(u, lam)
        try:
            lu = spla.splu(Ar, permc_spec="COLAMD")
        except RuntimeError:
            raise SolverError(f"non-linear system singular at {rad_s_to_rpm(omega):.0f} rpm") from None
        Dr = (self.TT @ Dn).tocsc()
        Nr = (self.TT @ Nn).tocsc()
        da0 = lu.solve(-(self.TT @ r0))
        q = self.gaps(u) - Nr.T @ da0
        cache: dict[int, np.ndarray] = {}

        def columns(idx):
            idx = np.atleast_1d(np.asarray(idx, dtype=np.int64))
            new = [int(j) for j in idx if int(j) not in cache]
            if new:
                X = lu.solve(np.asarray(Dr[:, new].todense()))
                for k, j in enumerate(new):
                    cache[j] = X[:, k]
            Y = np.column_stack([cache[int(j)] for j in idx]) if len(idx) else np.zeros((Ar.shape[0], 0))
            Gc = -(Nr.T @ Y)
            if self.Cd is not None:
                Gc = Gc + self.Cd[:, idx]
            return Gc

        act0 = lam > 0 if lam is not None and np.any(lam > 0) else None
        new_lam, _ = solve_lcp(lazy(columns), q, act0)
        nz = np.nonzero(new_lam)[0]
        da = da0 + (lu.solve(Dr[:, nz] @ new_lam[nz]) if len(nz) else 0.0)
        return da, new_lam

    def _contact_terms(self, u, lam, forces_only: bool = False):
        """Contact force on the part fc (N,), its tangent Kc = d fc / d u at fixed lam, the
        force directions D (N x m: fc = D lam) and the gap-gradient directions Nn (N x m:
        dg = -Nn' du)."""
        nd = self.nodes
        N = self.fe.basis.N
        x = self.positions(u)
        r = np.hypot(*x)
        n = x / r
        t = np.vstack([-n[1], n[0]])
        d = -(n + self.s * self.mu * t)  # force direction per unit lam
        fc = np.zeros(N)
        np.add.at(fc, nd.dof_x, d[0] * lam)
        np.add.at(fc, nd.dof_y, d[1] * lam)
        if forces_only:
            return fc
        m = nd.m
        rows = np.concatenate([nd.dof_x, nd.dof_y])
        colsm = np.concatenate([np.arange(m)] * 2)
        D = sp.csc_matrix((np.concatenate([d[0], d[1]]), (rows, colsm)), shape=(N, m))
        Nn = sp.csc_matrix((np.concatenate([n[0], n[1]]), (rows, colsm)), shape=(N, m))
        # d d / d x = -(I + s mu J)(I - n n') / r, J = [[0, -1], [1, 0]]
        P = np.stack([np.stack([1 - n[0] * n[0], -n[0] * n[1]]), np.stack([-n[1] * n[0], 1 - n[1] * n[1]])])
        J = np.array([[0.0, -1.0], [1.0, 0.0]])
        Q = np.eye(2) + self.s * self.mu * J
        blk = -np.einsum("ab,bcm->acm", Q, P) * (lam / r)  # (2, 2, m)
        dofs = [nd.dof_x, nd.dof_y]
        rr, cc, vv = [], [], []
        for a in range(2):
            for b in range(2):
                rr.append(dofs[a])
                cc.append(dofs[b])
                vv.append(blk[a, b])
        Kc = sp.csr_matrix((np.concatenate(vv), (np.concatenate(rr), np.concatenate(cc))), shape=(N, N))
        return fc, Kc, D, Nn

    # -- speed stepping -----------------------------------------------------------------
    def sweep(self, omegas, contact: bool = True, extra_load=None) -> list[NLState]:
        """Continuation over ascending speeds [rad/s] from the unloaded state."""
        omegas = np.asarray(omegas, dtype=float)
        if np.any(np.diff(omegas) < 0):
            raise ParameterError("omegas", omegas.tolist(), "ascending speeds")
        N = self.fe.basis.N
        u, lam, w_prev = np.zeros(N), None, 0.0
        out = []
        t0 = time.perf_counter()
        for w in omegas:
            st = self._step_to(w_prev, w, u, lam, contact, extra_load)
            out.append(st)
            u, lam, w_prev = st.u, st.lam, w
        self.timings["sweep_s"] = time.perf_counter() - t0
        return out

    def _step_to(self, w_from, w_to, u, lam, contact, extra_load):
        """Reach w_to from a converged state at w_from, halving the step if needed."""
        targets = [w_to]
        halvings = 0
        w_cur = w_from
        while targets:
            w = targets[-1]
            try:
                st = self._solve_at(w, u, lam, contact, extra_load)
            except _NoConvergence:
                halvings += 1
                if halvings > self.settings.max_halvings:
                    raise SolverError(f"non-linear reference: no convergence at {rad_s_to_rpm(w):.0f} rpm "
                                      f"after {self.settings.max_halvings} step halvings") from None
                targets.append(0.5 * (w_cur + w))
                continue
            targets.pop()
            u, lam, w_cur = st.u, st.lam, w
        return st

    def engagement(self, w_hint: float, rtol: float = 1e-9) -> tuple[float, NLState]:
        """Speed [rad/s] at which the free non-linear part first touches the exact drum circle
        (min gap = 0), by secant/bisection on continuation states from ``w_hint`` (e.g. the
        linear engagement speed)."""
        if self.nodes is None:
            raise ParameterError("drum_radius", None, "a drum radius (engagement needs a drum)")

        cache: dict[float, NLState] = {}

        def gmin(w, start):
            st = self._step_to(start[0], w, start[1], None, False, None)
            cache[w] = st
            return float(np.min(self.gaps(st.u))), st

        N = self.fe.basis.N
        lo, st_lo = 0.0, NLState(0.0, np.zeros(N), np.zeros(0), 0, 0.0)
        g_lo = float(np.min(self.gaps(st_lo.u)))
        hi = w_hint
        g_hi, st_hi = gmin(hi, (lo, st_lo.u))
        while g_hi > 0:  # bracket
            lo, st_lo, g_lo = hi, st_hi, g_hi
            hi *= 1.1
            g_hi, st_hi = gmin(hi, (lo, st_lo.u))
        for _ in range(100):
            # secant on g(w^2) (nearly linear in w^2), safeguarded by bisection
            x0, x1 = lo * lo, hi * hi
            x = x0 - g_lo * (x1 - x0) / (g_hi - g_lo)
            w = math.sqrt(x) if x0 < x < x1 else 0.5 * (lo + hi)
            g, st = gmin(w, (lo, st_lo.u))
            if g > 0:
                lo, st_lo, g_lo = w, st, g
            else:
                hi, st_hi, g_hi = w, st, g
            if hi - lo <= rtol * hi or abs(g) <= 1e-12 * self.R:
                return w, st
        raise SolverError("non-linear engagement search did not converge")

    # -- answers ------------------------------------------------------------------------
    def normal_force(self, st: NLState) -> float:
        """Total normal force [N] on the drum (all shoes)."""
        return float(st.lam.sum() * self.scale)

    def torque(self, st: NLState) -> float:
        """Friction torque [N m] about the axis: mu lam_i acting tangentially at radius |x_i|
        (= R_d on the contact nodes, which sit on the circle)."""
        if not st.lam.any():
            return 0.0
        r = np.hypot(*self.positions(st.u))
        return float(self.mu * np.sum(st.lam * r) * self.scale)

    def vertex_von_mises(self, u: np.ndarray) -> np.ndarray:
        """Cauchy von Mises stress at every element's vertices (plane stress, J = det F in
        plane): array (nelem * 3,).  At small strain it equals the PK2 one to O(strain)."""
        vb = self.fe._vertex_basis
        g = vb.interpolate(u).grad  # (2, 2, ne, 3)
        H = np.moveaxis(g, (0, 1), (-2, -1))  # (ne, 3, 2, 2): H[c, a]
        F, _, S = self.kin.stress(H)
        J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        sig = np.einsum("eqca,eqab,eqdb->eqcd", F, S, F) / J[..., None, None]
        return von_mises(np.stack([sig[..., 0, 0], sig[..., 1, 1], sig[..., 0, 1]])).ravel()


class _NoConvergence(Exception):
    def __init__(self, omega, res):
        super().__init__(f"no convergence at {omega} rad/s (residual {res:.3g})")


