"""Spin softening as interchangeable strategies: :class:`Off`, :class:`Ritz`, :class:`Exact`.

Equations at speed w (rad/s), after the bore clamp and cyclic constraints (u = T a):

    (K - w^2 M) u = w^2 f1 + D lam,      gaps  g = g0 - B u >= 0,  lam >= 0,  g . lam = 0

(:mod:`clutchfem.fem` for K, M, f1; :mod:`clutchfem.contact` for B and D).  -w^2 M u is the
spin softening: the centrifugal load follows the deformed position.  A strategy decides how
(K - w^2 M)^-1 is applied; ``strategy.bind(model, contact)`` returns a *response* with one
small interface used by :mod:`clutchfem.sweep`:

* ``free_normal(w)``: B u of the part without contact at speed w (the LCP's q = g0 - that);
* ``columns(w)``: a lazy provider of the LCP matrix G = -B (K - w^2 M)^-1 D, column by column;
* ``fields(omegas, lams)``: the displacement of every state, as a reduced basis and
  coefficients (``U = basis @ coef``) or explicit columns;
* ``linear`` (free response exactly w^2 u1: engagement in closed form), ``omega_limit``
  (divergence speed of the free part, rad/s, or None).

``Off``: drops M, u is linear in w^2.  Its error is ~gap / R_cg (~2 % in stiffness near
engagement, ~1 % in engagement speed), measured in BENCHMARKS.md.

``Ritz`` (default): *mode acceleration* on load-dependent Ritz pairs (w_j, phi_j),
M-normalised,

    (K - w^2 M)^-1 ~ K^-1 + sum_j phi_j phi_j' w^2 / (w_j^2 (w_j^2 - w^2)).

The pairs come from a block Krylov space of K^-1 M seeded with the loads the sweep applies
(centrifugal, and per shoe a uniform and a tip-heavy contact load D(mu) 1, D(mu) a),
``depth`` blocks deep (Wilson, Yuan & Dickens 1982): a few blocked back-solves with the one
factorisation of K, and the space holds what the loads excite (which the lowest eigenmodes
need not: an annulus' breathing mode lies above its torsion modes).  Its error against
``Exact`` is ~1e-8 in the normal force at the default depth (BENCHMARKS.md).  The space
depends on mu through the seeds; it is cached on the model per (depth, nodes, s mu), so each
friction coefficient builds it once (~10 ms) and nothing is re-factorised.

``Exact``: the reference: K - w^2 M factorised at every speed it is asked for (SuperLU),
columns of its condensed compliance computed only for the nodes the LCP asks for.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import ParameterError, SolverError
from .lcp import lazy
from .units import rad_s_to_rpm, wrap_angle

__all__ = ["Off", "Ritz", "Exact", "Softening", "get_softening", "SOFTENINGS"]

#: relative distance |w^2 - w_j^2| / w_j^2 to a natural speed of the free part within which a
#: speed is refused (K - w^2 M singular there)
POLE_BAND = 1e-6


@dataclass(frozen=True)
class Off:
    """No spin softening: (K)^-1 only; u(w) = w^2 u1 without contact.  The divergence speed
    of the real (softening) part is still computed (lowest Ritz pair) so that speeds past
    it are refused: the model would answer where the part has flown apart."""

    name = "off"

    def bind(self, model, contact):
        r = _ModalResponse(model, contact, np.zeros(0), np.zeros((model.ndofs, 0)))
        r.omega_limit = divergence_omega(model, contact)
        return r


@dataclass(frozen=True)
class KrylovSpace:
    """What the Ritz strategies share: ``depth`` Krylov blocks, the ``seeds`` rule, and the
    space and its pairs cached on the model per (strategy, depth, seeds, base, contact nodes,
    friction).

    ``base_mu`` (with ``seeds="all"`` only): build the "all" space as the extension of the
    "load" space of friction coefficient ``base_mu`` (the design's own load case, whose space
    is then computed once and shared) by the tangential seeds Tt: the same space as from
    scratch (span{D(mu) w, Tt w} = span{N w, Tt w}), with the back-solves of the Tt seeds
    only.  A subclass supplies ``pairs(model, contact, V)`` (Rayleigh-Ritz on the reduced
    basis V) and ``inner(model)`` (the matrix V is orthonormal in)."""

    depth: int = 3
    seeds: str = "load"
    base_mu: float | None = None
    name = "krylov"

    def __post_init__(self):
        if isinstance(self.depth, bool) or not isinstance(self.depth, int) or not 1 <= self.depth <= 20:
            raise ParameterError("ritz depth", self.depth, "an integer in [1, 20] (Krylov blocks)")
        if self.seeds not in ("load", "all"):
            raise ParameterError("ritz seeds", self.seeds, "'load' or 'all'")
        if self.base_mu is not None and (self.seeds != "all" or isinstance(self.base_mu, bool)
                                         or not isinstance(self.base_mu, (int, float))
                                         or not 0.0 <= self.base_mu <= 1.0):
            raise ParameterError("ritz base_mu", self.base_mu, "None, or a friction coefficient in [0, 1] with "
                                 "seeds='all' (the load space the shared space extends)")

    def operator_model(self, model):
        """The model whose (K, M) the space is built for (PrestressRitz: M - K_sigma1)."""
        return model

    def inner(self, model):
        raise NotImplementedError

    def pairs(self, model, V: np.ndarray):
        raise NotImplementedError

    def cached_pairs(self, model, contact):
        """The pairs of this space on ``model`` (computed once per key; the nodes are kept with
        them: their id is then never reused)."""
        return self._cached(model, contact)[1]

    def _cached(self, model, contact):
        """(blocks of the reduced space, pairs), cached on ``model``."""
        return self._entry(model, contact)[1:3]

    def _entry(self, model, contact):
        """(contact nodes, blocks, pairs, blocks' inner-product images), cached on ``model``."""
        base = self.base_mu if contact is not None else None
        friction = 0.0 if contact is None or self.seeds == "all" else contact.friction
        key = (self.name, self.depth, self.seeds, base, None if contact is None else id(contact.nodes), friction)
        cache = model.__dict__.setdefault("_ritz_cache", {})
        if key not in cache:
            m = self.operator_model(model)
            if base is None:
                blocks, images = krylov_blocks(m, krylov_seeds(m.f1, contact, self.seeds), self.depth,
                                               self.inner(m))
            else:
                from dataclasses import replace

                _, b0, _, i0 = replace(self, seeds="load", base_mu=None)._entry(model, contact.with_mu(base))
                b1, i1 = krylov_blocks(m, krylov_seeds(m.f1, contact, "tangent"), self.depth, self.inner(m),
                                       base=(b0, i0))
                blocks, images = b0 + b1, i0 + i1
            cache[key] = (None if contact is None else contact.nodes, blocks,
                          self.pairs(m, np.hstack(blocks)), images)
        return cache[key]


@dataclass(frozen=True)
class Ritz(KrylovSpace):
    """Mode acceleration on ``depth`` blocks of load-dependent Ritz vectors (default).

    ``seeds``: ``"load"`` seeds the space with the load case's own contact load D(mu) (one
    space per friction coefficient); ``"all"`` with both its parts N and Tt, one space for
    every mu of a design (a superset of each ``"load"`` space's seeds: at least as accurate;
    the two differ by the Ritz truncation error, ~1e-8 in the normal force).  ``analyze``
    uses ``"load"`` for the design's own mu and, for its secondary cases (friction off, mu
    +-30 %), ``"all"`` built as the extension of that space (``base_mu`` = the design's mu)."""

    name = "ritz"

    def inner(self, model):
        return model.Mr

    def pairs(self, model, V):
        return _ritz_pairs_on(model, V)

    def bind(self, model, contact):
        w2, Phi = self.cached_pairs(model, contact)
        return _ModalResponse(model, contact, w2, Phi)


@dataclass(frozen=True)
class Exact:
    """Reference: K - w^2 M factorised at every speed."""

    name = "exact"

    def bind(self, model, contact):
        return _ExactResponse(model, contact)


Softening = Off | Ritz | Exact
SOFTENINGS = {"ritz": Ritz, "modal": Ritz, "exact": Exact, "off": Off}


def get_softening(spec) -> Softening:
    """A strategy from an instance or a name ('ritz' (alias 'modal'), 'exact', 'off')."""
    if isinstance(spec, (Off, Ritz, Exact)) or (callable(getattr(spec, "bind", None)) and hasattr(spec, "name")):
        return spec  # (any strategy with bind(model, contact) and a name, e.g. nonlinear.PrestressRitz)
    if isinstance(spec, str) and spec.strip().lower() in SOFTENINGS:
        return SOFTENINGS[spec.strip().lower()]()
    if isinstance(spec, str) and spec.strip().lower() == "prestress":
        from .nonlinear import PrestressRitz  # softening + centrifugal pre-stress stiffness

        return PrestressRitz()
    raise ParameterError("softening", spec, "'ritz' (mode acceleration, default; alias 'modal'), "
                         "'exact' (per-speed factorisation, reference), 'off' or 'prestress' (ritz with the "
                         "centrifugal pre-stress stiffness)")


def krylov_seeds(f1: np.ndarray, contact, which: str = "load") -> list[np.ndarray]:
    """The seeds of the Ritz spaces: the centrifugal load f1 and, per shoe, a uniform and a
    tip-heavy distribution of the contact load D(mu) (``which`` = "load") or of both its parts
    N and Tt ("all": one space for every friction coefficient of a design); "tangent": the
    Tt distributions only (what extends a "load" space to the "all" one)."""
    seeds = [f1] if which != "tangent" else []
    if contact is not None:
        nd = contact.nodes
        loads = {"load": [contact.load], "all": [nd.normal_load, nd.tangent_load],
                 "tangent": [nd.tangent_load]}[which]
        for s_ in np.unique(nd.shoe):
            sel = np.nonzero(nd.shoe == s_)[0]
            a = nd.angle[sel]
            a = wrap_angle(a - a.mean())
            for D in loads:
                for wgt in (np.ones(len(sel)), a / max(np.abs(a).max(), 1e-300)):
                    seeds.append(D[:, sel] @ wgt)
    return seeds


def krylov_blocks(model, seeds: list[np.ndarray], depth: int, inner,
                  base: tuple[list[np.ndarray], list[np.ndarray]] = ((), ())) -> tuple[list, list]:
    """(blocks, images): the blocks of V = span{X, (K^-1 M) X, ..., (K^-1 M)^(depth-1) X},
    X = K^-1 T' seeds, on the reduced dofs of ``model`` (its ``Mr``, ``T`` and factorisation
    of ``Kr``), orthonormal in the ``inner`` product matrix (classical block Gram-Schmidt,
    twice for stability), and their images ``inner @ block`` (kept: the projections then
    cost no product).

    ``base``: (blocks, images) of another such space of the same model, depth and inner
    product; the blocks returned then extend it: block k is orthogonalised against the base's
    blocks 0..k (which keeps every vector in the joint Krylov space of both seed sets) and, at
    the end, against all of them, so that base + returned blocks is an orthonormal basis of
    the Krylov space of the two seed sets together."""
    blocks: list[np.ndarray] = []
    images: list[np.ndarray] = []
    if not seeds:
        return blocks, images

    def orthonormal(X, against, against_images):
        if against:
            V, IV = np.hstack(against), np.hstack(against_images)
            for _ in range(2):
                X = X - V @ (IV.T @ X)
        IX = inner @ X
        G = X.T @ IX
        d, Q = np.linalg.eigh((G + G.T) / 2)
        keep = d > max(d.max(initial=0.0), 0.0) * 1e-12
        S = Q[:, keep] / np.sqrt(d[keep])
        return X @ S, IX @ S

    base_blocks, base_images = list(base[0]), list(base[1])
    X = model.factor.solve(model.T.T @ np.column_stack(seeds))
    for k in range(max(1, depth)):
        X, IX = orthonormal(X, base_blocks[:k + 1] + blocks, base_images[:k + 1] + images)
        if X.shape[1] == 0:
            break
        blocks.append(X)
        images.append(IX)
        if k + 1 < depth:  # (the last block is not multiplied)
            X = model.factor.solve(model.Mr @ X)
    if base_blocks and blocks:  # block k against the base's blocks after k too
        X, IX = orthonormal(np.hstack(blocks), base_blocks, base_images)
        blocks, images = [X], [IX]
    return blocks, images


def krylov_space(model, seeds: list[np.ndarray], depth: int, inner) -> np.ndarray:
    """V = span{X, (K^-1 M) X, ..., (K^-1 M)^(depth-1) X}, X = K^-1 T' seeds, on the reduced
    dofs of ``model``, orthonormal in the ``inner`` product matrix (:func:`krylov_blocks`)."""
    return np.hstack(krylov_blocks(model, seeds, depth, inner)[0])


def ritz_pairs(model, contact, depth: int, which: str = "load") -> tuple[np.ndarray, np.ndarray]:
    """Load-dependent Ritz pairs (w_j^2, Phi) of (K, M), M-orthonormal (see module doc):

        V = span{X, (K^-1 M) X, ..., (K^-1 M)^(depth-1) X},  X = K^-1 [f1, contact loads],

    M-orthonormalised by block Gram-Schmidt (twice), then the Rayleigh-Ritz pairs on V.  The
    contact loads are, per shoe, a uniform and a tip-heavy distribution of D(mu) (``which``
    = "load") or of both N and Tt ("all"): :func:`krylov_seeds`."""
    return _ritz_pairs_on(model, krylov_space(model, krylov_seeds(model.f1, contact, which), depth, model.Mr))


def _ritz_pairs_on(model, V: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rayleigh-Ritz pairs (w_j^2, Phi) of (K, M) on the M-orthonormal reduced basis V."""
    Kr = model.Kr
    Kv = V.T @ (Kr @ V)
    vals, Y = np.linalg.eigh((Kv + Kv.T) / 2)
    if vals[0] <= 0:
        raise SolverError("spin-softening Ritz space is not positive definite: is the part clamped?")
    return vals, model.T @ (V @ Y)


class _ModalResponse:
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


class _ExactResponse:
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
        self.omega_limit = divergence_omega(model, contact)

    def coefficients(self, omega: float) -> np.ndarray:
        self._factor(omega)  # refuses a singular K - w^2 M
        return np.zeros(0)

    def unstable_count(self, omega: float) -> int:
        self._factor(omega)
        return self._neg

    def _factor(self, omega: float):
        if self._omega != omega:
            from .linsolve import factorize

            m = self.model
            A = (m.Kr - omega * omega * m.Mr).tocsc()
            try:
                f = factorize(A, "superlu", kind="shifted")
            except SolverError:
                raise SolverError(f"K - w^2 M is singular at {rad_s_to_rpm(omega):.0f} rpm: the speed of a "
                                  "natural mode of the free part (divergence)") from None
            # Sylvester's law of inertia: negative pivots of the symmetric, unpivoted LU = negative
            # eigenvalues of K - w^2 M (the free part's modes past divergence)
            self._neg = int(np.count_nonzero(f._lu.U.diagonal() < 0)) if hasattr(f, "_lu") else 0
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

    def fields(self, omegas: np.ndarray, lams: np.ndarray):
        U = np.column_stack([self.displacement(w, lam) for w, lam in zip(omegas, lams)]) if len(omegas) \
            else np.zeros((self.model.ndofs, 0))
        return None, None, U


def divergence_omega(model, contact) -> float:
    """Divergence speed [rad/s] of the free part: the lowest load-dependent Ritz frequency
    (seeded by the centrifugal and both contact loads; cached on the model), i.e. where the
    loaded deflection shapes lose their stiffness to spin softening."""
    key = ("divergence", None if contact is None else id(contact.nodes))
    cache = model.__dict__.setdefault("_ritz_cache", {})
    if key not in cache:
        cache[key] = (None if contact is None else contact.nodes,
                      float(np.sqrt(ritz_pairs(model, contact, 3, "all")[0][0])))
    return cache[key][1]


def model_compliance(model, nodes):
    """The :class:`~clutchfem.contact.Compliance` of (model, nodes), created once."""
    from .contact import Compliance

    cache = model.__dict__.setdefault("_compliance_cache", {})
    key = id(nodes)
    if key not in cache:
        cache[key] = (nodes, Compliance(model, nodes))  # keep nodes alive: ids are not reused
    return cache[key][1]
