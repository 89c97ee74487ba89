"""Responses of a bound softening strategy: the free normal displacement, the lazy LCP
matrix and the fields of every state, for mode acceleration (:class:`ModalResponse`: ``Off``,
``Ritz``, ``prestress``) and the per-speed factorisation (:class:`ExactResponse`).

Mode acceleration: u = w^2 u1 + W lam + Phi c(w) (w^2 Phi' f1 + Phi' D lam), with the
weights c_j = w^2 / (w_j^2 (w_j^2 - w^2)); the interface is described in
:mod:`clutchfem.softening.strategies`.
"""

from __future__ import annotations

import math

import numpy as np

from ..contact import Compliance, lazy
from ..core import SolverError, rad_s_to_rpm
from ..fe import available, factorize
from .krylov import divergence_omega

__all__ = ["ExactResponse", "ModalResponse", "POLE_BAND", "model_compliance"]


#: relative distance |w^2 - w_j^2| / w_j^2 to a natural speed of the free part within which a
#: speed is refused (K - w^2 M singular there)
POLE_BAND = 1e-6


class ModalResponse:
    """Off (no vectors) and Ritz: u = w^2 u1 + W lam + Phi c(w) (w^2 Phi' f1 + Phi' D lam)."""

    def __init__(self, model, contact, w2: np.ndarray, Phi: np.ndarray):
        self.model = model
        self.contact = contact
        self.w2 = w2
        self.Phi = Phi
        self.u1 = model.u1
        self.Phi_f1 = Phi.T @ model.f1
        self.linear = len(w2) == 0
        self.omega_limit = float(math.sqrt(w2[0])) if len(w2) else None
        if contact is not None:
            nd = contact.nodes
            self.compliance = model_compliance(model, nd)
            self.friction = contact.friction
            # what depends on the space and the nodes only is shared by the load cases of every
            # friction coefficient (Phi' D(f) = Phi' N + f Phi' Tt)
            cache = model.__dict__.setdefault("_modal_cache", {})
            key = (id(Phi), id(nd))
            if key not in cache:
                cache[key] = (Phi, nd, nd.normal_displacement(self.u1), nd.normal_displacement(Phi).reshape(nd.m, -1),
                              (nd.normal_load.T @ Phi).T, (nd.tangent_load.T @ Phi).T)  # (Phi, nd kept: ids)
            _, _, self.Bu1, self.BPhi, PhiN, PhiT = cache[key]
            self.PhiD = PhiN + self.friction * PhiT if self.friction != 0.0 else PhiN  # r x m

    def coefficients(self, omega: float) -> np.ndarray:
        """The mode-acceleration weights at ``omega`` (:meth:`_coefficients`; the last speed's
        are kept: a contact solve asks for them twice).  Read only."""
        if omega != self.__dict__.get("_c_omega"):
            self._c = self._coefficients(omega)
            self._c_omega = omega
        return self._c

    def _coefficients(self, omega: float) -> np.ndarray:
        """Mode-acceleration weights c_j = w^2 / (w_j^2 (w_j^2 - w^2))."""
        if self.linear:
            return np.zeros(0)
        w2 = omega * omega
        j = int(np.argmin(np.abs(self.w2 - w2)))
        if abs(self.w2[j] - w2) < POLE_BAND * self.w2[j]:
            raise SolverError(f"speed {rad_s_to_rpm(omega):.0f} rpm is a natural speed "
                              f"({rad_s_to_rpm(math.sqrt(self.w2[j])):.0f} rpm) of the free part: K - w^2 M is "
                              "singular there; solve a speed next to it")
        return w2 / (self.w2 * (self.w2 - w2))

    def unstable_count(self, omega: float) -> int:
        """Negative eigenvalues of K - w^2 M in the Ritz space: the free part's modes past
        their divergence speed (the drum must hold them)."""
        return int(np.count_nonzero(self.w2 < omega * omega)) if not self.linear else 0

    def free_normal(self, omega: float) -> np.ndarray:
        c = self.coefficients(omega)
        return omega * omega * (self.Bu1 + self.BPhi @ (c * self.Phi_f1))

    def columns(self, omega: float):
        BPc = self.BPhi * self.coefficients(omega)
        comp, fr = self.compliance, self.friction

        def cols(idx):
            return -(comp.BW(idx, fr) + BPc @ self.PhiD[:, idx])

        return lazy(cols)

    def fields(self, omegas: np.ndarray, lams: np.ndarray):
        """(basis, coef, None): every state's displacement is basis @ coef[:, k]; only the
        columns some state uses are kept."""
        r = self.Phi.shape[1]
        nw, pos = self.compliance.positions() if self.contact is not None else (0, None)
        coef = np.zeros((1 + r + nw, len(omegas)))
        for j, (w, lam) in enumerate(zip(omegas, lams)):
            w2 = w * w
            coef[0, j] = w2
            A = np.nonzero(lam)[0] if lam.size else np.zeros(0, dtype=np.int64)
            if len(A):
                ca, cb = self.compliance.weights(self.friction)
                coef[1 + r + pos["a"][A], j] = ca * lam[A]
                if cb != 0.0:
                    coef[1 + r + pos["b"][A], j] = cb * lam[A]
            if r:
                load = w2 * self.Phi_f1
                if len(A):
                    load = load + self.PhiD[:, A] @ lam[A]
                coef[1:1 + r, j] = self.coefficients(w) * load
        used = np.any(coef != 0.0, axis=1)
        used[0] = True
        parts = [self.u1[:, None], self.Phi[:, used[1:1 + r]]]
        if nw:
            parts.append(self.compliance.columns(np.nonzero(used[1 + r:])[0]))
        return np.hstack(parts), coef[used], None


#: displacements :meth:`ExactResponse.keep` holds for a sweep's fields at most (a sweep's
#: speeds; more, e.g. left by a sweep stopped by a refusal, are dropped)
KEPT_STATES = 512


class ExactResponse:
    """K - w^2 M factorised per speed (the reference); fields kept explicitly per state.
    A speed at which K - w^2 M is no longer positive definite (a negative pivot of its
    symmetric, unpivoted LU: Sylvester's law of inertia) is past divergence: refused."""

    linear = False

    def __init__(self, model, contact):
        self.model = model
        self.contact = contact
        self._omega = None
        self._f = None
        self._cols: dict[int, np.ndarray] = {}
        self._kept: dict[tuple, np.ndarray] = {}
        self.omega_limit = divergence_omega(model, contact)

    def coefficients(self, omega: float) -> np.ndarray:
        self._factor(omega)  # refuses a singular K - w^2 M
        return np.zeros(0)

    def unstable_count(self, omega: float) -> int:
        self._factor(omega)
        return self._neg

    def _factor(self, omega: float):
        if self._omega != omega:
            m = self.model
            A = (m.Kr - omega * omega * m.Mr).tocsc()
            f = None
            if "cholmod" in available():
                # CHOLMOD's simplicial LDL' (~3.5x SuperLU's LU on the thick model); its supernodal
                # LL' (above SIMPLICIAL_MAX_N unknowns) refuses an indefinite A: then SuperLU
                try:
                    f = factorize(A, "cholmod", kind="shifted")
                except SolverError:
                    f = None
            if f is None:
                try:
                    f = factorize(A, "superlu", kind="shifted")
                except SolverError:
                    raise SolverError(f"K - w^2 M is singular at {rad_s_to_rpm(omega):.0f} rpm: the speed of a "
                                      "natural mode of the free part (divergence)") from None
            # Sylvester's law of inertia: negative pivots of the symmetric factorisation =
            # negative eigenvalues of K - w^2 M (the free part's modes past divergence)
            self._neg = f.negative_pivots() if hasattr(f, "negative_pivots") else 0
            self._f = f
            self._omega, self._cols = omega, {}
        return self._f

    def free(self, omega: float) -> np.ndarray:
        m = self.model
        return m.T @ self._factor(omega).solve(m.T.T @ (omega * omega * m.f1))

    def free_normal(self, omega: float) -> np.ndarray:
        return self.contact.nodes.normal_displacement(self.free(omega))

    def _column(self, omega: float, idx) -> np.ndarray:
        m = self.model
        f = self._factor(omega)
        new = [int(i) for i in idx if int(i) not in self._cols]
        if new:
            Wn = (m.T @ f.solve(m.T.T @ self.contact.load[:, new].toarray())).reshape(m.ndofs, -1)
            self._cols.update({i: Wn[:, k] for k, i in enumerate(new)})
        return np.column_stack([self._cols[int(i)] for i in idx]) if len(idx) else np.zeros((m.ndofs, 0))

    def columns(self, omega: float):
        nd = self.contact.nodes
        return lazy(lambda idx: -nd.normal_displacement(self._column(omega, idx)).reshape(nd.m, -1))

    def displacement(self, omega: float, lam: np.ndarray) -> np.ndarray:
        if omega == 0:
            return np.zeros(self.model.ndofs)
        u = self.free(omega)
        A = np.nonzero(lam)[0] if lam.size else np.zeros(0, dtype=np.int64)
        return u + (self._column(omega, A) @ lam[A] if len(A) else 0.0)

    def keep(self, omega: float, lam: np.ndarray) -> None:
        """The displacement of the state ``lam`` just solved at ``omega``, computed while the
        speed's factorisation is the current one, for :meth:`fields` (a sweep asks for every
        speed's fields after its last solve: each engaged speed was factorised twice).  Computed
        as :meth:`fields` computes it after a new factorisation (its contact columns afresh, all
        at once: the same numbers); the solves' own state is left as it was.  Nothing without
        the speed's factorisation at hand (then :meth:`fields` makes it, as before)."""
        if omega == 0 or omega != self._omega:
            return
        if len(self._kept) >= KEPT_STATES:
            self._kept.clear()
        cols, self._cols = self._cols, {}
        try:
            self._kept[(float(omega), np.asarray(lam, dtype=float).tobytes())] = self.displacement(omega, lam)
        finally:
            self._cols = cols

    def _fresh(self, omega: float, lam: np.ndarray) -> np.ndarray:
        """The displacement as computed after a new factorisation at ``omega`` (contact columns
        afresh), without one if the current factorisation is that speed's."""
        if omega == self._omega:
            self._cols = {}
        return self.displacement(omega, lam)

    def fields(self, omegas: np.ndarray, lams: np.ndarray):
        ws = [float(w) for w in omegas]
        if not self._kept or len(set(ws)) < len(ws):
            U = np.column_stack([self.displacement(w, lam) for w, lam in zip(omegas, lams)]) if len(omegas) \
                else np.zeros((self.model.ndofs, 0))
            return None, None, U
        # the speeds a sweep kept (:meth:`keep`), all distinct: every speed as the loop above would
        # compute it (the first speed on the factorisation the solves left, with their columns, if
        # it is that speed's; every other one afresh), and the state it would leave (the last)
        nz = [i for i, w in enumerate(ws) if w != 0]
        cols = []
        for i, (w, lam) in enumerate(zip(ws, lams)):
            kept = self._kept.pop((w, np.asarray(lam, dtype=float).tobytes()), None)
            if w == 0:
                cols.append(self.displacement(w, lam))
            elif i == nz[0] and w == self._omega:
                cols.append(self.displacement(w, lam))
            elif kept is not None and i != nz[-1]:
                cols.append(kept)
            else:
                cols.append(self._fresh(w, lam))
        self._kept.clear()
        return None, None, np.column_stack(cols)


def model_compliance(model, nodes):
    """The :class:`~clutchfem.contact.Compliance` of (model, nodes), created once."""
    cache = model.__dict__.setdefault("_compliance_cache", {})
    key = id(nodes)
    if key not in cache:
        cache[key] = (nodes, Compliance(model, nodes))  # keep nodes alive: ids are not reused
    return cache[key][1]
