"""Spin softening *and* the centrifugal pre-stress stiffening of the flexures on the one
factorisation of K (the default strategy, ``prestress``).

The prestressed linear operator at speed w is K - w^2 (M - K_sigma1), K_sigma1 the geometric
stiffness of the linear centrifugal stress at w = 1 (:func:`clutchfem.fe.geometric_stiffness`):
the same form as spin softening with M replaced by M - K_sigma1, so the Krylov/Ritz machinery
runs unchanged on a view of the model (:class:`PrestressedModel`).  0.1 % from the
geometrically non-linear reference (:mod:`clutchfem.accuracy.nonlinear`, measured in
``benchmarks/bench_modelform.py``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..core import SolverError, rad_s_to_rpm
from ..fe import geometric_stiffness
from .krylov import KrylovSpace
from .response import POLE_BAND, ModalResponse

__all__ = ["PrestressRitz", "PrestressedModel", "prestressed"]


class PrestressedModel:
    """The linear fast path with the centrifugal pre-stress stiffness: a view of a 2-D
    :class:`~clutchfem.fe.FEModel` whose spin-softening operator is M - K_sigma1, so that

        (K - w^2 (M - K_sigma1)) u = w^2 f1 + D lam

    is solved by the unchanged softening strategies (``Exact``: per-speed factorisation;
    ``Ritz``: the one factorisation of K, mode acceleration on Ritz pairs of (K, M - K_sigma1)).
    Everything else (K, f1, T, the factorisation, u1, stresses) is the base model's.  Both
    terms are linear in w^2: the same cost as spin softening alone (one extra assembly of
    K_sigma1 from u1).  Where M - K_sigma1 is indefinite (compressed regions stiffen less
    than the mass softens ... or more), the Ritz space keeps its M-positive part only; its
    error against ``Exact`` is measured in the benchmark."""

    def __init__(self, model):
        self.__dict__["_base"] = model

    def __getattr__(self, name):
        return getattr(self.__dict__["_base"], name)

    def _cached(self, key: str, compute):
        # kept on the base model (a view holds its model, not the other way round: no
        # reference cycle, a design's matrices go when it goes)
        d = self.__dict__["_base"].__dict__
        if key not in d:
            d[key] = compute()
        return d[key]

    @property
    def K_sigma1(self):
        def compute():
            t0 = time.perf_counter()
            Ks = geometric_stiffness(self._base, self._base.u1)
            self._base.timings["prestress_s"] = time.perf_counter() - t0
            return Ks

        return self._cached("_prestress_Ks", compute)

    @property
    def M(self):
        return self._cached("_prestress_M", lambda: (self._base.M - self.K_sigma1).tocsr())

    @property
    def Mr(self):
        return self._cached("_prestress_Mr", lambda: (self.T.T @ self.M @ self.T).tocsc())


def prestressed(model) -> PrestressedModel:
    """The :class:`PrestressedModel` view of ``model`` (K_sigma1 is one assembly, done once:
    the view's matrices are cached on ``model``)."""
    return PrestressedModel(model)


@dataclass(frozen=True)
class PrestressRitz(KrylovSpace):
    """Spin softening *and* centrifugal pre-stress stiffening on the one factorisation of K:
    mode acceleration on Ritz pairs of (K, M - K_sigma1), a softening strategy for
    :class:`clutchfem.loadcase.LoadCase` (``LoadCase(model, contact, PrestressRitz())``).

    M_eff = M - K_sigma1 is indefinite (the tensioned flexure stiffens more than its mass
    softens it), so the space is K-orthonormalised instead of M-orthonormalised: with V the
    block Krylov space of K^-1 M_eff seeded like :func:`~clutchfem.softening.krylov.ritz_pairs`,
    Psi = V Y K-orthonormal and M_eff Psi ~ K Psi diag(theta) (theta = 1 / w_j^2, negative for
    stiffened directions),

        (K - w^2 M_eff)^-1 ~ K^-1 + sum_j psi_j psi_j' w^2 theta_j / (1 - w^2 theta_j),

    which is the usual mode-acceleration formula for theta > 0 and stays valid for theta <= 0.
    The divergence speed is 1 / sqrt(max theta) (None if no theta > 0).  Its error against the
    per-speed factorisation (``Exact`` on :class:`PrestressedModel`) is measured in
    ``benchmarks/bench_modelform.py``."""

    name = "prestress"

    def operator_model(self, model):
        return prestressed(model)

    def inner(self, model):
        return model.Kr

    def pairs(self, model, V):
        return prestress_pairs_on(model, V)

    def bind(self, model, contact):
        theta, Psi = self.cached_pairs(model, contact)
        r = PrestressResponse(model, contact, np.ones(len(theta)), Psi)
        r.theta = theta
        r.check_model = prestressed(model)  # the equilibrium check uses M - K_sigma1,
        r.precondition_check = True  # measured as the displacement error the residual causes
        tmax = float(theta.max(initial=0.0))
        r.omega_limit = 1.0 / math.sqrt(tmax) if tmax > 0 else None
        r.linear = False
        return r


class PrestressResponse(ModalResponse):
    """Mode acceleration with theta = 1 / w_j^2 of M - K_sigma1 (``theta`` set by
    :meth:`PrestressRitz.bind`)."""

    theta: np.ndarray

    def _coefficients(self, omega: float) -> np.ndarray:
        x = (omega * omega) * self.theta
        d = 1.0 - x
        if np.abs(d).min(initial=np.inf) < POLE_BAND:
            raise SolverError(f"speed {rad_s_to_rpm(omega):.0f} rpm is a natural speed of the "
                              "prestressed free part: K - w^2 (M - K_sigma1) is singular there; solve a "
                              "speed next to it")
        return x / d

    def unstable_count(self, omega: float) -> int:
        return int(np.count_nonzero(omega * omega * self.theta > 1.0))


def prestress_pairs_on(pm: PrestressedModel, V: np.ndarray):
    """theta = 1 / w^2 and Psi (K-orthonormal) of M - K_sigma1 on the K-orthonormal reduced
    basis V."""
    Mv = V.T @ (pm.Mr @ V)
    theta, Y = np.linalg.eigh((Mv + Mv.T) / 2)
    return theta, pm.T @ (V @ Y)
