"""Speed sweeps of a spinning clutch against a rigid drum: one factorisation for all speeds.

Equations at speed w (rad/s), after the bore clamp and cyclic constraints (u = T a):

    (K - w^2 M) u = w^2 f1 + D lam,      gaps  g = g0 - B u >= 0,  lam >= 0,  g . lam = 0

(:mod:`clutchfem.fem` for K, M, f1; :mod:`clutchfem.contact` for B, D and the LCP).

Spin softening (-w^2 M u: the centrifugal load follows the deformed position) by *mode
acceleration*: with the lowest r eigenpairs (w_j, phi_j) of K phi = w^2 M phi, M-normalised,

    (K - w^2 M)^-1 = K^-1 + sum_j phi_j phi_j' w^2 / (w_j^2 (w_j^2 - w^2))     (exact for r = all)

so one factorisation of K serves every speed; the truncation error scales like
(w / w_{r+1})^2 times the small high-mode share and is measured against a per-speed exact
factorisation in ``benchmarks/bench_sweep.py``.  ``spin_softening='off'`` drops M
(u linear in w^2); ``'exact'`` factorises K - w^2 M at every speed (reference, slow).

Per speed the work is O(m^2 r + m^3) for m contact nodes (tens to a few hundred): the LCP is
solved exactly, warm-started from the previous speed; below the closed-form engagement speed
nothing is solved at all.  Stresses, when asked for, come from one sparse operator applied
to all displacement columns at once.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
import pandas as pd
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.optimize import brentq

from .contact import ContactNodes, contact_nodes, solve_lcp
from .errors import InputError, ParameterError, SolverError
from .fem import FEModel, build_fe_model, von_mises
from .materials import Material
from .mesh import ClutchMesh
from .units import rad_s_to_rpm, rpm_to_rad_s

Softening = Literal["modal", "exact", "off"]


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
                 spin_softening: Softening = "modal", n_modes: int = 12,
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
        # spin-softening modes
        t2 = time.perf_counter()
        self.w2 = np.zeros(0)
        self.Phi = np.zeros((fe.ndofs, 0))
        if spin_softening == "modal":
            self.w2, self.Phi = self._modes(n_modes)
        self.timings["modes_s"] = time.perf_counter() - t2
        self.Phi_f1 = self.Phi.T @ fe.f1
        self.omega_diverge = float(np.sqrt(self.w2[0])) if len(self.w2) else None
        # contact condensation
        t3 = time.perf_counter()
        self.nodes: ContactNodes | None = None
        if drum_radius is not None:
            self.nodes = contact_nodes(cm, fe.basis, drum_radius)
            nd = self.nodes
            m = nd.m
            D = sp.lil_matrix((fe.ndofs, m))
            fx = -nd.normal[0] - self.s * self.mu * nd.tangent[0]
            fy = -nd.normal[1] - self.s * self.mu * nd.tangent[1]
            D = sp.csc_matrix((np.concatenate([fx, fy]),
                               (np.concatenate([nd.dof_x, nd.dof_y]), np.concatenate([np.arange(m)] * 2))),
                              shape=(fe.ndofs, m))
            self.D = D
            self.W = fe.solve(D.toarray())  # N x m: K^-1 D (m back-substitutions)
            self.BW = self._B(self.W)
            self.Bu1 = self._B(self.u1)
            self.BPhi = self._B(self.Phi)
            self.PhiD = (D.T @ self.Phi).T  # r x m
        self.timings["condense_s"] = time.perf_counter() - t3
        self.timings["setup_s"] = time.perf_counter() - t0

    # -- helpers ------------------------------------------------------------------------
    def _B(self, U: np.ndarray) -> np.ndarray:
        """Outward normal displacement at the contact nodes (rows) of U's columns."""
        nd = self.nodes
        U = np.asarray(U)
        if U.ndim == 1:
            return nd.normal[0] * U[nd.dof_x] + nd.normal[1] * U[nd.dof_y]
        return nd.normal[0][:, None] * U[nd.dof_x] + nd.normal[1][:, None] * U[nd.dof_y]

    def _modes(self, r: int) -> tuple[np.ndarray, np.ndarray]:
        fe = self.fe
        n = fe.Kr.shape[0]
        r = max(1, min(r, n - 2))
        op = spla.LinearOperator((n, n), matvec=fe.factor.solve, dtype=float)
        try:
            vals, vecs = spla.eigsh(fe.Kr, k=r, M=fe.Mr, sigma=0.0, OPinv=op, which="LM",
                                    tol=1e-10)
        except spla.ArpackNoConvergence as exc:  # pragma: no cover - rare
            raise SolverError(f"eigen-solve for spin softening did not converge: {exc}") from None
        order = np.argsort(vals)
        return vals[order], fe.T @ vecs[:, order]

    def coefficients(self, omega: float) -> np.ndarray:
        """Mode-acceleration weights c_j = w^2 / (w_j^2 (w_j^2 - w^2))."""
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
        G = -(self.BW + (self.BPhi * c) @ self.PhiD)
        lam, active = solve_lcp(G, q, active0)
        return SpeedState(omega, lam, c), active

    def _exact_state(self, omega, active0):
        fe = self.fe
        f = self._exact_factor(omega)
        u_f = fe.T @ f.solve(fe.T.T @ (omega * omega * fe.f1))
        W = fe.T @ f.solve(fe.T.T @ self.D.toarray())
        q = self.nodes.gap0 - self._B(u_f)
        G = -self._B(W)
        lam, active = solve_lcp(G, q, active0)
        st = SpeedState(omega, lam, np.zeros(0))
        st.u_exact = u_f + W @ lam  # type: ignore[attr-defined]
        return st, active

    def displacement(self, st: SpeedState) -> np.ndarray:
        """Full displacement vector (all dofs) at a solved state."""
        if hasattr(st, "u_exact"):
            return st.u_exact
        w2 = st.omega ** 2
        u = w2 * self.u1
        if self.nodes is not None and st.lam.any():
            u = u + self.W @ st.lam
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
        U = np.column_stack([self.displacement(st) for st in states]) if len(states) else np.zeros((self.fe.ndofs, 0))
        t3 = time.perf_counter()
        curve = self._curve(rpm, states, U, stresses)
        t4 = time.perf_counter()
        first, first_angle = self._first_touch(i_eng)
        res = SweepResult(curve=curve, shoes=self._shoe_table(rpm, states),
                          engagement_rpm=None if w_eng is None else rad_s_to_rpm(w_eng),
                          first_touch=first, first_touch_angle_deg=first_angle, states=states, solver=self,
                          timings={"engagement_s": t1 - t0, "contact_s": t2 - t1, "fields_s": t3 - t2,
                                   "post_s": t4 - t3, "sweep_s": t4 - t0, **self.timings},
                          displacements=U if keep_displacements else None)
        return res

    def _curve(self, rpm, states, U, stresses) -> pd.DataFrame:
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
            S = self._stress_operator @ U  # (3 * nelem * 3, ns)
            ne = fe.cm.mesh.t.shape[1]
            S = S.reshape(3, ne * 3, -1)
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

    @property
    def _stress_operator(self) -> sp.csr_matrix:
        """Sparse map u -> (sxx, syy, sxy) at every element's 3 vertices, row order
        (component, element, vertex)."""
        if hasattr(self, "_S_op"):
            return self._S_op
        fe = self.fe
        vb = fe._vertex_basis
        lam, mu = fe.material.lame_plane_stress()
        ne = fe.cm.mesh.t.shape[1]
        rows, cols, vals = [], [], []
        base = np.arange(ne)[:, None] * 3 + np.arange(3)[None, :]  # (ne, 3)
        for j in range(vb.Nbfun):
            g = vb.basis[j][0].grad  # (2, 2, ne, 3)
            exx, eyy = g[0, 0], g[1, 1]
            exy = 0.5 * (g[0, 1] + g[1, 0])
            comps = (2 * mu * exx + lam * (exx + eyy), 2 * mu * eyy + lam * (exx + eyy), 2 * mu * exy)
            dof = np.broadcast_to(vb.element_dofs[j][:, None], (ne, 3))
            for ci, val in enumerate(comps):
                rows.append((ci * ne * 3 + base).ravel())
                cols.append(dof.ravel())
                vals.append(np.asarray(val).ravel())
        self._S_op = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                                   shape=(3 * ne * 3, fe.ndofs))
        return self._S_op

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
