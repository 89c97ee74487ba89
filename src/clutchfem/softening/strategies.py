"""Spin softening as interchangeable strategies: :class:`Off`, :class:`Ritz`, :class:`Exact`
(and :class:`~clutchfem.softening.prestress.PrestressRitz`, the default).

Equations at speed w (rad/s), after the bore clamp and cyclic constraints (u = T a):

    (K - w^2 M) u = w^2 f1 + D lam,      gaps  g = g0 - B u >= 0,  lam >= 0,  g . lam = 0

(:mod:`clutchfem.fe` for K, M, f1; :mod:`clutchfem.contact` for B and D).  -w^2 M u is the
spin softening: the centrifugal load follows the deformed position.  A strategy decides how
(K - w^2 M)^-1 is applied; ``strategy.bind(model, contact)`` returns a *response* with one
small interface used by :mod:`clutchfem.loadcase.case`:

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
``PrestressExact``: the same with the pre-stress stiffness, M - K_sigma1 (the reference of
the default ``PrestressRitz``, and ``analyze``'s fallback where that misses equilibrium).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import ParameterError
from .krylov import KrylovSpace, divergence_omega, ritz_pairs_on
from .prestress import PrestressRitz, prestressed
from .response import ExactResponse, ModalResponse

__all__ = ["Exact", "Off", "Ritz", "SOFTENINGS", "Softening", "get_softening"]


@dataclass(frozen=True)
class Off:
    """No spin softening: (K)^-1 only; u(w) = w^2 u1 without contact.  The divergence speed
    of the real (softening) part is still computed (lowest Ritz pair) so that speeds past
    it are refused: the model would answer where the part has flown apart."""

    name = "off"

    def bind(self, model, contact):
        r = ModalResponse(model, contact, np.zeros(0), np.zeros((model.ndofs, 0)))
        r.omega_limit = divergence_omega(model, contact)
        return r


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
        return ritz_pairs_on(model, V)

    def bind(self, model, contact):
        w2, Phi = self.cached_pairs(model, contact)
        return ModalResponse(model, contact, w2, Phi)


@dataclass(frozen=True)
class Exact:
    """Reference: K - w^2 M factorised at every speed."""

    name = "exact"

    def bind(self, model, contact):
        return ExactResponse(model, contact)


@dataclass(frozen=True)
class PrestressExact:
    """Reference of :class:`PrestressRitz`: K - w^2 (M - K_sigma1) factorised at every speed.
    ``analyze`` falls back to it where the pre-stress Ritz space misses equilibrium: a soft
    design far past its engagement (concept 4 with 1.77 mm x 14.5 mm flexures engages at 810
    rpm; at 12 000-14 000 rpm the 3-block space leaves residuals of 0.02-0.04 of the load,
    12 blocks still 0.004, BENCHMARKS.md section 13)."""

    name = "prestress-exact"

    def bind(self, model, contact):
        pm = prestressed(model)
        r = ExactResponse(pm, contact)
        r.check_model = pm  # checked against K - w^2 (M - K_sigma1), like PrestressRitz
        r.precondition_check = True
        return r


Softening = Off | Ritz | Exact | PrestressRitz | PrestressExact


SOFTENINGS = {"ritz": Ritz, "modal": Ritz, "exact": Exact, "off": Off, "prestress-exact": PrestressExact}


def get_softening(spec) -> Softening:
    """A strategy from an instance or a name ('ritz' (alias 'modal'), 'exact', 'off')."""
    if isinstance(spec, (Off, Ritz, Exact, PrestressRitz, PrestressExact)) or (callable(getattr(spec, "bind", None)) and hasattr(spec, "name")):
        return spec  # (any strategy with bind(model, contact) and a name, e.g. a user strategy)
    if isinstance(spec, str) and spec.strip().lower() in SOFTENINGS:
        return SOFTENINGS[spec.strip().lower()]()
    if isinstance(spec, str) and spec.strip().lower() == "prestress":
        return PrestressRitz()  # softening + centrifugal pre-stress stiffness
    raise ParameterError("softening", spec, "'ritz' (mode acceleration, default; alias 'modal'), "
                         "'exact' (per-speed factorisation, reference), 'off', 'prestress' (ritz with the "
                         "centrifugal pre-stress stiffness) or 'prestress-exact' (its per-speed reference)")
