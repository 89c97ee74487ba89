"""Load-dependent Ritz spaces: block Krylov spaces of K^-1 M seeded with the loads a sweep
applies, their Rayleigh-Ritz pairs, and the divergence speed of the free part.

V = span{X, (K^-1 M) X, ..., (K^-1 M)^(depth-1) X},  X = K^-1 T' [f1, contact loads]: a few
blocked back-solves with the one factorisation of K (Wilson, Yuan & Dickens 1982); the
space holds what the loads excite (which the lowest eigenmodes need not).  Spaces and pairs
are cached on the model per (strategy, depth, seeds, contact nodes, friction).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..core import ParameterError, SolverError, wrap_angle

__all__ = ["KrylovSpace", "divergence_omega", "krylov_blocks", "krylov_seeds", "krylov_space", "ritz_pairs",
           "ritz_pairs_on"]


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
                _, b0, _, i0 = replace(self, seeds="load", base_mu=None)._entry(model, contact.with_mu(base))
                b1, i1 = krylov_blocks(m, krylov_seeds(m.f1, contact, "tangent"), self.depth, self.inner(m),
                                       base=(b0, i0))
                blocks, images = b0 + b1, i0 + i1
            cache[key] = (None if contact is None else contact.nodes, blocks,
                          self.pairs(m, np.hstack(blocks)), images)
        return cache[key]


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
    dofs of ``model``, orthonormal in the ``inner`` product matrix (:func:`krylov_blocks`;
    no columns where ``inner`` is not positive on any of them)."""
    blocks = krylov_blocks(model, seeds, depth, inner)[0]
    return np.hstack(blocks) if blocks else np.zeros((model.Kr.shape[0], 0))


def ritz_pairs(model, contact, depth: int, which: str = "load") -> tuple[np.ndarray, np.ndarray]:
    """Load-dependent Ritz pairs (w_j^2, Phi) of (K, M), M-orthonormal (see module doc):

        V = span{X, (K^-1 M) X, ..., (K^-1 M)^(depth-1) X},  X = K^-1 [f1, contact loads],

    M-orthonormalised by block Gram-Schmidt (twice), then the Rayleigh-Ritz pairs on V.  The
    contact loads are, per shoe, a uniform and a tip-heavy distribution of D(mu) (``which``
    = "load") or of both N and Tt ("all"): :func:`krylov_seeds`."""
    return ritz_pairs_on(model, krylov_space(model, krylov_seeds(model.f1, contact, which), depth, model.Mr))


def ritz_pairs_on(model, V: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rayleigh-Ritz pairs (w_j^2, Phi) of (K, M) on the M-orthonormal reduced basis V."""
    Kr = model.Kr
    Kv = V.T @ (Kr @ V)
    vals, Y = np.linalg.eigh((Kv + Kv.T) / 2)
    if vals[0] <= 0:
        raise SolverError("spin-softening Ritz space is not positive definite: is the part clamped?")
    return vals, model.T @ (V @ Y)


def divergence_omega(model, contact) -> float | None:
    """Divergence speed [rad/s] of the free part: the lowest load-dependent Ritz frequency
    (seeded by the centrifugal and both contact loads; cached on the model), i.e. where the
    loaded deflection shapes lose their stiffness to spin softening.  None where the space
    has no softening direction at all: a pre-stressed model whose M - K_sigma1 is negative
    on every seed (the stiffening outweighs the softening: concept 5's 3-D model) never
    diverges."""
    key = ("divergence", None if contact is None else id(contact.nodes))
    cache = model.__dict__.setdefault("_ritz_cache", {})
    if key not in cache:
        V = krylov_space(model, krylov_seeds(model.f1, contact, "all"), 3, model.Mr)
        w = float(np.sqrt(ritz_pairs_on(model, V)[0][0])) if V.shape[1] else None
        cache[key] = (None if contact is None else contact.nodes, w)
    return cache[key][1]
