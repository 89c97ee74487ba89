"""Speed sweeps of a spinning clutch against a rigid drum: one factorisation for all speeds.

Equations at speed w (rad/s), after the bore clamp and cyclic constraints (u = T a):

    (K - w^2 M) u = w^2 f1 + D lam,      gaps  g = g0 - B u >= 0,  lam >= 0,  g . lam = 0

(:mod:`clutchfem.fem` for K, M, f1; :mod:`clutchfem.contact` for B, D and the LCP).

Spin softening (-w^2 M u: the centrifugal load follows the deformed position) by *mode
acceleration* on load-dependent Ritz pairs (w_j, phi_j), M-normalised:

    (K - w^2 M)^-1 ~ K^-1 + sum_j phi_j phi_j' w^2 / (w_j^2 (w_j^2 - w^2))

The pairs come from a block Krylov space of K^-1 M seeded with the loads the sweep applies
(centrifugal, and per shoe a uniform and a tip-heavy contact load), ``ritz_depth`` blocks
deep: a few blocked back-solves with the one factorisation of K, and the space holds what
the loads excite (which the lowest eigenmodes need not: an annulus' breathing mode lies
above its torsion modes).  Its error against a per-speed factorisation of K - w^2 M
(``spin_softening='exact'``) is measured in ``benchmarks/bench_sweep.py`` (~1e-8 in the
normal force at the default depth).  ``'off'`` drops M (u linear in w^2).

Contact is condensed lazily: the LCP matrix G = B K^-1 D is m x m for m contact nodes, but
the active-set method only needs the columns of the nodes it makes active (the shoes touch
the drum on a short arc), so K^-1 D is computed column block by column block as nodes enter
contact, with their neighbours along the shoe prefetched.  Per speed the work is then a few
small dense solves; below the closed-form engagement speed nothing is solved at all.

Every displacement of a sweep lies in span[u1, Phi, K^-1 D_condensed]: fields and vertex
stresses of all speeds are one small dense product with that basis.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
import pandas as pd
import scipy.sparse as sp
from scipy.optimize import brentq

from .contact import ContactNodes, contact_nodes, lazy, solve_lcp
from .errors import InputError, ParameterError, SolverError
from .fem import FEModel, build_fe_model, von_mises
from .materials import Material
from .mesh import ClutchMesh
from .units import rad_s_to_rpm, rpm_to_rad_s

Softening = Literal["modal", "exact", "off"]

#: contact-node columns condensed on each side of a newly needed one (see ClutchSolver._w)
_PREFETCH = 8


@dataclass
class SpeedState:
    """Contact state at one speed (model = sector or full part)."""

    omega: float
    lam: np.ndarray  # nodal contact forces [N] (model)
    c: np.ndarray  # modal softening coefficients


@dataclass
class SweepResult:
    """What a sweep returns.  Totals are for the whole clutch (all shoes)."""

    curve: pd.DataFrame
    shoes: pd.DataFrame
    engagement_rpm: float | None
    first_touch: str | None
    first_touch_angle_deg: float | None
    states: list[SpeedState]
    solver: "ClutchSolver"
    timings: dict = field(default_factory=dict)
    displacements: np.ndarray | None = None  # (N, nspeeds) if kept
    vm_max_points: np.ndarray | None = None

    def pressure(self, rpm: float) -> pd.DataFrame:
        """Contact pressure along the contact surface at the sweep speed nearest ``rpm``."""
        k = int(np.argmin(np.abs(self.curve["rpm"].to_numpy() - rpm)))
        return self.solver.pressure_table(self.states[k])

    def to_json(self) -> dict:
        cols = ["rpm", "normal_force_N", "torque_Nm", "contact_arc_deg", "max_von_mises_Pa",
                "max_displacement_m"]
        rec = []
        for row in self.curve.to_dict("records"):
            r = {k: (None if (isinstance(row.get(k), float) and math.isnan(row[k])) else row.get(k))
                 for k in self.curve.columns}
            rec.append(r)
        return {"engagement_rpm": self.engagement_rpm, "first_touch": self.first_touch,
                "curve": rec, "required_columns": cols}


class ClutchSolver:
    """Assembles once, then answers engagement speed, contact state and fields at any speed."""

    def __init__(self, cm: ClutchMesh, material: Material, *, drum_radius: float | None = None,
                 mu: float = 0.0, rotation: Literal["ccw", "cw"] = "ccw",
                 spin_softening: Softening = "modal", ritz_depth: int = 3,
                 thickness: float | None = None):
        if mu < 0 or not math.isfinite(mu):
            raise ParameterError("mu", mu, "a friction coefficient >= 0")
        if mu > 1.0:
            raise ParameterError("mu", mu, "a friction coefficient in [0, 1]")
        if rotation not in ("ccw", "cw"):
            raise ParameterError("rotation", rotation, "'ccw' or 'cw'")
        if spin_softening not in ("modal", "exact", "off"):
            raise ParameterError("spin_softening", spin_softening, "'modal', 'exact' or 'off'")
        if drum_radius is not None and not (drum_radius > 0 and math.isfinite(drum_radius)):
            raise ParameterError("drum_radius", drum_radius, "a radius > 0 m")
        self.timings: dict[str, float] = {}
        t0 = time.perf_counter()
        self.cm = cm
        self.material = material
        self.mu = float(mu)
        self.rotation = rotation
        self.s = 1.0 if rotation == "ccw" else -1.0
        self.softening = spin_softening
        self.fe: FEModel = build_fe_model(cm, material, thickness)
        self.timings.update(self.fe.timings)
        self.scale = cm.n_shoes_total / cm.n_shoes_model if cm.sector_angle else 1.0
        self.drum_radius = drum_radius
        fe = self.fe
        t1 = time.perf_counter()
        self.u1 = fe.solve(fe.f1)
        self.timings["factorize_s"] = fe.timings.get("factorize_s", 0.0)
        self.timings["solve_u1_s"] = time.perf_counter() - t1 - self.timings["factorize_s"]
        # contact condensation
        t3 = time.perf_counter()
        self.nodes: ContactNodes | None = None
        if drum_radius is not None:
            self.nodes = contact_nodes(cm, fe.basis, drum_radius)
            nd = self.nodes
            m = nd.m
            fx = -nd.normal[0] - self.s * self.mu * nd.tangent[0]
            fy = -nd.normal[1] - self.s * self.mu * nd.tangent[1]
            D = sp.csc_matrix((np.concatenate([fx, fy]),
                               (np.concatenate([nd.dof_x, nd.dof_y]), np.concatenate([np.arange(m)] * 2))),
                              shape=(fe.ndofs, m))
            self.D = D
            # K^-1 D is condensed lazily, column by column as nodes become active (see _w)
            self._colpos = -np.ones(m, dtype=np.int64)
            # neighbours along each shoe's contact surface, for prefetching columns
            self._rank = np.empty(m, dtype=np.int64)
            self._by_arc = np.lexsort((nd.angle, nd.shoe))
            self._rank[self._by_arc] = np.arange(m)
            self._Wc = np.zeros((fe.ndofs, 0))
            self._BWc = np.zeros((m, 0))
        self.timings["contact_setup_s"] = time.perf_counter() - t3
        # spin softening: load-dependent Ritz pairs (after the contact nodes: their loads seed them)
        t2 = time.perf_counter()
        self.w2 = np.zeros(0)
        self.Phi = np.zeros((fe.ndofs, 0))
        if spin_softening == "modal":
            self.w2, self.Phi = self._ritz(ritz_depth)
        self.timings["modes_s"] = time.perf_counter() - t2
        self.Phi_f1 = self.Phi.T @ fe.f1
        self.omega_diverge = float(np.sqrt(self.w2[0])) if len(self.w2) else None
        if self.nodes is not None:
            self.Bu1 = self._B(self.u1)
            self.BPhi = self._B(self.Phi)
            self.PhiD = (self.D.T @ self.Phi).T  # r x m
        self.timings["setup_s"] = time.perf_counter() - t0

    # -- helpers ------------------------------------------------------------------------
    def _B(self, U: np.ndarray) -> np.ndarray:
        """Outward normal displacement at the contact nodes (rows) of U's columns."""
        nd = self.nodes
        U = np.asarray(U)
        if U.ndim == 1:
            return nd.normal[0] * U[nd.dof_x] + nd.normal[1] * U[nd.dof_y]
        return nd.normal[0][:, None] * U[nd.dof_x] + nd.normal[1][:, None] * U[nd.dof_y]

    def _w(self, idx: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Columns ``idx`` of W = K^-1 D and of B W, condensing (one blocked back-solve) those
        not done yet.  Only the nodes the contact solve makes active are ever condensed: a
        few of the m candidates, since the shoes touch the drum on a short arc."""
        idx = np.asarray(idx, dtype=np.int64)
        missing = idx[self._colpos[idx] < 0]
        if len(missing):
            # the contact arc grows node by node with speed: condense the PREFETCH nearest
            # nodes on either side along the same shoe too (one blocked solve is ~2.5x
            # cheaper per column than single ones)
            nd = self.nodes
            near = self._rank[missing][:, None] + np.arange(-_PREFETCH, _PREFETCH + 1)[None, :]
            near = self._by_arc[np.clip(near, 0, nd.m - 1)]
            near = near[nd.shoe[near] == nd.shoe[missing][:, None]]
            missing = np.unique(np.concatenate([missing, near]))
            missing = missing[self._colpos[missing] < 0]
            t = time.perf_counter()
            Wn = self.fe.solve(self.D[:, missing].toarray()).reshape(self.fe.ndofs, -1)
            self._colpos[missing] = self._Wc.shape[1] + np.arange(len(missing))
            self._Wc = np.hstack([self._Wc, Wn])
            self._BWc = np.hstack([self._BWc, self._B(Wn).reshape(self.nodes.m, -1)])
            self.timings["condense_s"] = self.timings.get("condense_s", 0.0) + time.perf_counter() - t
        pos = self._colpos[idx]
        return self._Wc[:, pos], self._BWc[:, pos]

    def _bw(self, idx: np.ndarray) -> np.ndarray:
        """Columns ``idx`` of B W (normal displacements at the contact nodes), condensing as
        needed; cheaper than :meth:`_w` when the full columns are not wanted."""
        idx = np.asarray(idx, dtype=np.int64)
        if np.any(self._colpos[idx] < 0):
            self._w(idx[self._colpos[idx] < 0])
        return self._BWc[:, self._colpos[idx]]

    @property
    def n_condensed(self) -> int:
        """Contact nodes condensed so far (columns of K^-1 D computed)."""
        return 0 if self.nodes is None else int(self._Wc.shape[1])

    def _g_columns(self, c: np.ndarray):
        """Provider of the LCP matrix columns G[:, idx] = -(B W + B Phi diag(c) Phi' D)[:, idx]."""
        BPc = self.BPhi * c

        def cols(idx):
            return -(self._bw(idx) + BPc @ self.PhiD[:, idx])

        return lazy(cols)

    def _ritz(self, depth: int) -> tuple[np.ndarray, np.ndarray]:
        """Load-dependent Ritz pairs (Wilson, Yuan & Dickens 1982) for the mode-acceleration
        formula: a block Krylov space of K^-1 M seeded with the loads the sweep applies,

            V = span{X, (K^-1 M) X, ..., (K^-1 M)^(depth-1) X},  X = K^-1 [f1, contact loads],

        M-orthonormalised, then the Rayleigh-Ritz pairs of (K, M) on V.  The contact seeds are,
        per shoe, a uniform and a linearly varying (tip-heavy) load along its contact surface.
        Unlike the lowest eigenmodes, the space holds what the loads excite (an annulus'
        breathing mode above its torsion modes), for ``depth`` blocked back-solves; the error
        against the exact K - w^2 M is measured in BENCHMARKS.md."""
        fe = self.fe
        seeds = [fe.f1]
        nd = self.nodes
        if nd is not None:
            for s_ in np.unique(nd.shoe):
                sel = np.nonzero(nd.shoe == s_)[0]
                a = nd.angle[sel]
                a = (a - a.mean() + math.pi) % (2 * math.pi) - math.pi
                for wgt in (np.ones(len(sel)), a / max(np.abs(a).max(), 1e-300)):
                    seeds.append(self.D[:, sel] @ wgt)
        Mr, Kr = fe.Mr, fe.Kr
        blocks: list[np.ndarray] = []

        def m_orthonormal(X):
            for _ in range(2):  # block Gram-Schmidt in the M inner product, twice for stability
                for Vb in blocks:
                    X = X - Vb @ (Vb.T @ (Mr @ X))
            G = X.T @ (Mr @ X)
            d, Q = np.linalg.eigh((G + G.T) / 2)
            keep = d > max(d.max(), 0.0) * 1e-12
            return X @ (Q[:, keep] / np.sqrt(d[keep]))

        X = fe.factor.solve(fe.T.T @ np.column_stack(seeds))
        for _ in range(max(1, depth)):
            X = m_orthonormal(X)
            if X.shape[1] == 0:
                break
            blocks.append(X)
            X = fe.factor.solve(Mr @ X)
        V = np.hstack(blocks)
        Kv = V.T @ (Kr @ V)
        vals, Y = np.linalg.eigh((Kv + Kv.T) / 2)
        if vals[0] <= 0:
            raise SolverError("spin-softening Ritz space is not positive definite: is the part clamped?")
        return vals, fe.T @ (V @ Y)

    def coefficients(self, omega: float) -> np.ndarray:
        """Mode-acceleration weights c_j = w^2 / (w_j^2 (w_j^2 - w^2)) of the Ritz pairs."""
        if not len(self.w2):
            return np.zeros(0)
        w2 = omega * omega
        if w2 >= self.w2[0] * (1 - 1e-9):
            raise SolverError(f"speed {rad_s_to_rpm(omega):.0f} rpm reaches the spin-softening divergence "
                              f"speed {rad_s_to_rpm(math.sqrt(self.w2[0])):.0f} rpm of the free part: the "
                              "shoes would fly out (stiffer flexures or lower speed)")
        return w2 / (self.w2 * (self.w2 - w2))

    def _free_normal(self, omega: float, c: np.ndarray) -> np.ndarray:
        w2 = omega * omega
        return w2 * (self.Bu1 + self.BPhi @ (c * self.Phi_f1))

    # -- engagement ---------------------------------------------------------------------
    def engagement(self) -> tuple[float | None, int | None]:
        """(engagement speed [rad/s], index of the first contact node), or (None, None)."""
        if self.nodes is None:
            return None, None
        g0 = self.nodes.gap0
        out = self.Bu1
        pos = out > 0
        if not pos.any():
            return None, None
        ratio = np.full_like(g0, np.inf)
        ratio[pos] = g0[pos] / out[pos]
        i0 = int(np.argmin(ratio))
        w0 = math.sqrt(ratio[i0])
        if self.softening == "off":
            return w0, i0
        if self.softening == "exact":
            h = lambda w: float(np.min(g0 - self._exact_free_normal(w)))
        else:
            h = lambda w: float(np.min(g0 - self._free_normal(w, self.coefficients(w))))
        hi = w0
        limit = math.sqrt(self.w2[0]) * (1 - 1e-6) if len(self.w2) else 10 * w0
        while h(hi) > 0:
            hi = min(hi * 1.05, limit)
            if hi >= limit:
                return None, None
        w = brentq(h, 0.0, hi, xtol=1e-10 * hi, rtol=1e-13)
        gaps = g0 - (self._exact_free_normal(w) if self.softening == "exact"
                     else self._free_normal(w, self.coefficients(w)))
        return w, int(np.argmin(gaps))

    def _exact_factor(self, omega: float):
        from .linsolve import factorize

        fe = self.fe
        A = (fe.Kr - omega * omega * fe.Mr).tocsc()
        try:
            return factorize(A, "superlu")
        except SolverError:
            raise SolverError(f"K - w^2 M is singular at {rad_s_to_rpm(omega):.0f} rpm") from None

    def _exact_free_normal(self, omega: float) -> np.ndarray:
        fe = self.fe
        f = self._exact_factor(omega)
        u = fe.T @ f.solve(fe.T.T @ (omega * omega * fe.f1))
        return self._B(u)

    # -- one speed ----------------------------------------------------------------------
    def state(self, omega: float, active0: np.ndarray | None = None,
              engaged: bool = True) -> tuple[SpeedState, np.ndarray | None]:
        c = self.coefficients(omega) if self.softening == "modal" else np.zeros(0)
        if self.nodes is None or not engaged:
            m = 0 if self.nodes is None else self.nodes.m
            st = SpeedState(omega, np.zeros(m), c)
            if self.softening == "exact" and omega > 0:  # free part, softened: (K - w^2 M) u = w^2 f1
                fe = self.fe
                f = self._exact_factor(omega)
                st.u_exact = fe.T @ f.solve(fe.T.T @ (omega * omega * fe.f1))  # type: ignore[attr-defined]
            return st, None
        if self.softening == "exact":
            return self._exact_state(omega, active0)
        q = self.nodes.gap0 - self._free_normal(omega, c)
        if active0 is None or not active0.any():  # first contact: start from the deepest node
            active0 = np.zeros(len(q), dtype=bool)  # (every node with q < 0 would condense
            active0[int(np.argmin(q))] = True  # many columns the solution does not need)
        lam, active = solve_lcp(self._g_columns(c), q, active0)
        return SpeedState(omega, lam, c), active

    def _exact_state(self, omega, active0):
        """Reference path: K - w^2 M factorised at this speed; columns of its condensed
        compliance computed only for the nodes the LCP asks for."""
        fe = self.fe
        f = self._exact_factor(omega)
        u_f = fe.T @ f.solve(fe.T.T @ (omega * omega * fe.f1))
        cache: dict[int, np.ndarray] = {}

        def column(idx):
            new = [int(i) for i in idx if int(i) not in cache]
            if new:
                Wn = (fe.T @ f.solve(fe.T.T @ self.D[:, new].toarray())).reshape(fe.ndofs, -1)
                cache.update({i: Wn[:, k] for k, i in enumerate(new)})
            return np.column_stack([cache[int(i)] for i in idx]) if len(idx) else np.zeros((fe.ndofs, 0))

        q = self.nodes.gap0 - self._B(u_f)
        if active0 is None or not active0.any():
            active0 = np.zeros(len(q), dtype=bool)
            active0[int(np.argmin(q))] = True
        lam, active = solve_lcp(lazy(lambda idx: -self._B(column(idx)).reshape(len(q), -1)), q, active0)
        st = SpeedState(omega, lam, np.zeros(0))
        A = np.nonzero(lam)[0]
        st.u_exact = u_f + (column(A) @ lam[A] if len(A) else 0.0)  # type: ignore[attr-defined]
        return st, active

    def displacement(self, st: SpeedState) -> np.ndarray:
        """Full displacement vector (all dofs) at a solved state."""
        if hasattr(st, "u_exact"):
            return st.u_exact
        w2 = st.omega ** 2
        u = w2 * self.u1
        if self.nodes is not None and st.lam.any():
            A = np.nonzero(st.lam)[0]
            u = u + self._w(A)[0] @ st.lam[A]
        if len(st.c):
            load = w2 * self.Phi_f1
            if self.nodes is not None and st.lam.any():
                load = load + self.PhiD @ st.lam
            u = u + self.Phi @ (st.c * load)
        return u

    # -- sweep --------------------------------------------------------------------------
    def sweep(self, rpm, *, stresses: bool = True, keep_displacements: bool = False) -> SweepResult:
        """Solve every speed in ``rpm`` (ascending or not); return a :class:`SweepResult`."""
        t0 = time.perf_counter()
        rpm = parse_rpm(rpm)
        omegas = rpm_to_rad_s(rpm)
        w_eng, i_eng = self.engagement()
        t1 = time.perf_counter()
        states: list[SpeedState] = []
        active = None
        for w in omegas:
            engaged = w_eng is not None and w >= w_eng * (1 - 1e-12)
            st, act = self.state(float(w), active, engaged)
            if act is not None:
                active = act
            states.append(st)
        t2 = time.perf_counter()
        basis, coef = self._reduced_fields(states)
        U = basis @ coef if basis is not None else (
            np.column_stack([self.displacement(st) for st in states]) if states else np.zeros((self.fe.ndofs, 0)))
        t3 = time.perf_counter()
        curve = self._curve(rpm, states, U, stresses, basis, coef)
        t4 = time.perf_counter()
        first, first_angle = self._first_touch(i_eng)
        res = SweepResult(curve=curve, shoes=self._shoe_table(rpm, states),
                          engagement_rpm=None if w_eng is None else rad_s_to_rpm(w_eng),
                          first_touch=first, first_touch_angle_deg=first_angle, states=states, solver=self,
                          timings={"engagement_s": t1 - t0, "contact_s": t2 - t1, "fields_s": t3 - t2,
                                   "post_s": t4 - t3, "sweep_s": t4 - t0, **self.timings},
                          displacements=U if keep_displacements else None)
        return res

    def _reduced_fields(self, states) -> tuple[np.ndarray | None, np.ndarray | None]:
        """Every displacement of the sweep lies in span[u1, Phi, W_condensed]:
        U = basis @ coef with a few columns (1 + modes + condensed nodes), so fields and
        stresses cost one small dense product instead of one assembly per speed.
        (None, None) for the 'exact' softening, whose states carry their own fields."""
        if not states or any(hasattr(st, "u_exact") for st in states):
            return None, None
        r = self.Phi.shape[1]
        k = self.n_condensed
        coef = np.zeros((1 + r + k, len(states)))
        for j, st in enumerate(states):
            w2 = st.omega ** 2
            coef[0, j] = w2
            A = np.nonzero(st.lam)[0]
            if len(A):
                coef[1 + r + self._colpos[A], j] = st.lam[A]
            if r:
                load = w2 * self.Phi_f1
                if len(A):
                    load = load + self.PhiD[:, A] @ st.lam[A]
                coef[1:1 + r, j] = st.c * load
        parts = [self.u1[:, None], self.Phi] + ([self._Wc] if k else [])
        return np.hstack(parts), coef

    def _curve(self, rpm, states, U, stresses, basis=None, coef=None) -> pd.DataFrame:
        fe = self.fe
        b = fe.basis
        ux = U[np.concatenate([b.nodal_dofs[0], b.facet_dofs[0]])]
        uy = U[np.concatenate([b.nodal_dofs[1], b.facet_dofs[1]])]
        umax = np.sqrt(ux * ux + uy * uy).max(axis=0) if U.size else np.zeros(0)
        rows = []
        R = self.drum_radius or 0.0
        for k, st in enumerate(states):
            lam = st.lam
            row = {"rpm": float(rpm[k]), "omega_rad_s": st.omega,
                   "normal_force_N": float(lam.sum() * self.scale) if lam.size else 0.0,
                   "torque_Nm": float(self.mu * R * lam.sum() * self.scale) if lam.size else 0.0,
                   "contact_arc_deg": self._arc(lam)[2] if lam.size else 0.0,
                   "contact_nodes": int((lam > 0).sum()) if lam.size else 0,
                   "max_displacement_m": float(umax[k])}
            rows.append(row)
        df = pd.DataFrame(rows)
        if stresses and len(states):
            if basis is not None:
                S = self.vertex_stresses(basis) @ coef
            else:
                S = self.vertex_stresses(U)
            vm = von_mises(S)  # (ne*3, ns)
            kmax = vm.argmax(axis=0)
            pts = self._vertex_points
            df["max_von_mises_Pa"] = vm.max(axis=0)
            df["max_vm_x_m"] = pts[0, kmax]
            df["max_vm_y_m"] = pts[1, kmax]
            df["safety_factor"] = np.where(df["max_von_mises_Pa"] > 0,
                                           self.material.yield_strength / np.maximum(df["max_von_mises_Pa"], 1e-300),
                                           np.inf)
        else:
            df["max_von_mises_Pa"] = np.nan
            df["safety_factor"] = np.nan
        return df

    def vertex_stresses(self, U: np.ndarray) -> np.ndarray:
        """Raw stresses (sxx, syy, sxy) [Pa] at every element's three vertices for the
        displacement column(s) U: array (3, nelem * 3, ncols), rows ordered (element, vertex)
        like :attr:`_vertex_points`.  No averaging: the P2 strain peaks at the vertices."""
        U = np.asarray(U)
        one = U.ndim == 1
        U = U.reshape(U.shape[0], -1)
        Gx, Gy, ex, ey = self._vertex_gradients
        Ux, Uy = U[ex], U[ey]  # (ne, 6, ncols)
        lam, mu = self.material.lame_plane_stress()
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

    @property
    def _vertex_gradients(self):
        """(Gx, Gy, ex, ey): d/dx and d/dy [1/m] of the 6 scalar P2 shape functions at each
        element's 3 vertices, (nelem, 3, 6) each, through the isoparametric (curved) map;
        ex, ey the element dofs (nelem, 6) of the x and y displacement."""
        if not hasattr(self, "_vg"):
            b = self.fe.basis
            ed = b.element_dofs  # (12, ne): local dof 2k + c = shape function k, component c
            ex, ey = ed[0::2], ed[1::2]
            X = b.doflocs[:, ex]  # (2, 6, ne) node positions (curved mid-edge nodes included)
            # reference gradients of the P2 shape functions (skfem ElementTriP2 order) at the
            # vertices (0,0), (1,0), (0,1): R[v, k, :]
            R = np.array([[[-3, -3], [-1, 0], [0, -1], [4, 0], [0, 0], [0, 4]],
                          [[1, 1], [3, 0], [0, -1], [-4, -4], [0, 4], [0, 0]],
                          [[1, 1], [-1, 0], [0, 3], [0, 0], [4, 0], [-4, -4]]], dtype=float)
            J = np.einsum("ake,vkb->evab", X, R)  # (ne, 3, 2, 2): dx_a / dxi_b
            det = J[..., 0, 0] * J[..., 1, 1] - J[..., 0, 1] * J[..., 1, 0]
            if np.any(det == 0):
                raise SolverError(f"{self.cm.source}: a degenerate element (zero Jacobian at a "
                                  "vertex); remesh")
            Jinv = np.stack([np.stack([J[..., 1, 1], -J[..., 0, 1]], -1),
                             np.stack([-J[..., 1, 0], J[..., 0, 0]], -1)], -2) / det[..., None, None]
            G = R[None] @ Jinv  # (ne, 3, 6, 2): grad phi_k = J^-T grad_ref phi_k
            self._vg = (np.ascontiguousarray(G[..., 0]), np.ascontiguousarray(G[..., 1]), ex.T.copy(), ey.T.copy())
        return self._vg

    @property
    def _vertex_points(self) -> np.ndarray:
        mesh = self.fe.cm.mesh
        return mesh.p[:, mesh.t.T.ravel()]

    def _arc(self, lam: np.ndarray, shoe: int | None = None) -> tuple[float, float, float]:
        """(start, end, span) in degrees of the nodes in contact (one shoe, or the mean span
        over shoes)."""
        nd = self.nodes
        if nd is None:
            return (math.nan, math.nan, 0.0)
        shoes = [shoe] if shoe is not None else sorted(set(nd.shoe.tolist()))
        spans = []
        first = (math.nan, math.nan)
        for s_ in shoes:
            sel = (nd.shoe == s_) & (lam > 0)
            if not sel.any():
                spans.append(0.0)
                continue
            ang = nd.angle[sel]
            ref = float(np.mean(ang))
            a = ref + (ang - ref + math.pi) % (2 * math.pi) - math.pi
            lo, hi = math.degrees(a.min()), math.degrees(a.max())
            spans.append(hi - lo)
            if s_ == shoes[0]:
                first = (lo, hi)
        return first[0], first[1], float(np.mean(spans))

    def _shoe_table(self, rpm, states) -> pd.DataFrame:
        nd = self.nodes
        if nd is None:
            return pd.DataFrame()
        rows = []
        R = self.drum_radius
        arcs = self.cm.contact_arcs
        for k, st in enumerate(states):
            for s_ in sorted(set(nd.shoe.tolist())):
                sel = nd.shoe == s_
                N = float(st.lam[sel].sum())
                lo, hi, span = self._arc(st.lam, s_)
                nominal = abs(math.degrees(arcs[s_][1] - arcs[s_][0])) if s_ < len(arcs) else math.nan
                rows.append({"rpm": float(rpm[k]), "shoe": int(s_), "normal_force_N": N,
                             "torque_Nm": self.mu * R * N, "arc_start_deg": lo, "arc_end_deg": hi,
                             "contact_arc_deg": span, "arc_fraction": span / nominal if nominal else math.nan})
        return pd.DataFrame(rows)

    def _first_touch(self, i_eng) -> tuple[str | None, float | None]:
        if i_eng is None or self.nodes is None:
            return None, None
        nd = self.nodes
        ang = float(nd.angle[i_eng])
        s_ = int(nd.shoe[i_eng])
        if s_ < 0 or s_ >= len(self.cm.contact_arcs):
            return "unknown", math.degrees(ang)
        root, tip = self.cm.contact_arcs[s_]
        a = root + ((ang - root) + math.pi) % (2 * math.pi) - math.pi
        frac = (a - root) / (tip - root)
        where = "tip" if frac > 2 / 3 else ("root" if frac < 1 / 3 else "middle")
        return where, math.degrees(ang)

    def pressure_table(self, st: SpeedState) -> pd.DataFrame:
        nd = self.nodes
        if nd is None:
            return pd.DataFrame()
        p = st.lam / (self.fe.thickness * np.maximum(nd.weight, 1e-300))
        order = np.lexsort((nd.angle, nd.shoe))
        return pd.DataFrame({"shoe": nd.shoe[order], "angle_deg": np.degrees(nd.angle[order]),
                             "x_m": nd.xy[0, order], "y_m": nd.xy[1, order],
                             "force_N": st.lam[order], "pressure_Pa": p[order],
                             "gap0_m": nd.gap0[order]})


def parse_rpm(spec) -> np.ndarray:
    """rpm values from a number, a list/array, or a string '8000', '1000,2000', '0:14000:250'
    (start:stop:step, stop included)."""
    if isinstance(spec, str):
        s = spec.strip()
        try:
            if ":" in s:
                parts = [float(x) for x in s.split(":")]
                if len(parts) != 3:
                    raise ValueError
                a, b, step = parts
                if step <= 0 or b < a:
                    raise InputError(f"rpm spec '{spec}': need start <= stop and step > 0 "
                                     "(form start:stop:step, e.g. 0:14000:250)")
                n = int(math.floor((b - a) / step + 1e-9)) + 1
                vals = a + step * np.arange(n)
            else:
                vals = np.array([float(x) for x in s.split(",") if x.strip()])
        except ValueError:
            raise InputError(f"rpm spec '{spec}' is not understood: use 8000, 1000,2000,3000 or "
                             "0:14000:250 (rpm)") from None
    else:
        vals = np.atleast_1d(np.asarray(spec, dtype=float))
    if vals.size == 0:
        raise InputError(f"rpm spec '{spec}' gives no speed")
    if not np.all(np.isfinite(vals)) or np.any(vals < 0):
        raise InputError(f"rpm spec '{spec}': speeds must be finite and >= 0 rpm")
    if vals.max() > 1e6:
        raise InputError(f"rpm spec '{spec}': speeds above 1e6 rpm are not physical here")
    return vals
