"""The drum as a load-case part: the contact load operator with friction, and the lazily
condensed contact compliance.

The drum is coaxial, of inner radius R_d, rigid unless an elastic drum is given
(:mod:`clutchfem.contact.ring`: its wall moves out by u_d(w) + C_d lam, which opens the gaps).  Contact is node-to-circle at the P2 nodes
(vertices and mid-edge nodes) of the ``contact`` boundary: node i at x_i has the exact
initial gap g0_i = R_d - |x_i| and outward normal n_i = x_i/|x_i| (the drum's, evaluated on
the exact circle, so a coarse chord does not eat the 0.6 mm clearance).  With small
displacements the gap is g_i = g0_i - n_i . u_i  (B u: the *normal operator*).

A compressive nodal force lam_i >= 0 acts on the part along -n_i; with the drum held and the
hub turning in direction s (+1 ccw, -1 cw) the shoe slides along s e_theta, so full-slip
Coulomb friction adds -s mu lam_i t_i (t_i = e_theta).  The *load operator* is therefore

    D(mu) = N + s mu Tt,     N[:, i] = -n_i,  Tt[:, i] = -t_i   (at node i's dofs),

linear in mu, so two condensed sets span the compliance K^-1 D(mu) of every friction
coefficient (mu +-30 %, friction off) of one design: they reuse the same back-substitutions
(:class:`Compliance`).  Columns are condensed lazily, only for
the nodes the LCP (:mod:`clutchfem.contact.lcp`) makes active, with the nodes likely asked for next
in the same blocked solve: the shoes touch the drum on a short arc.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Literal

import numpy as np
import scipy.sparse as sp

from ..core import ParameterError
from .nodes import ContactNodes

Rotation = Literal["ccw", "cw"]

#: contact-node columns of the first set condensed on each side of a newly needed one (see
#: Compliance)
PREFETCH = 8
#: largest gap scale [m] of the smoothed contact law: the peak-to-valley roughness of a turned
#: drum (Rz ~10-20 um) bounds what a pressure-overclosure smoothing can stand for
MAX_SMOOTHING = 2e-5




@dataclass(frozen=True, eq=False)
class DrumContact:
    """The drum as one part of a load case: contact nodes, friction coefficient and the
    hub's sense of rotation (drum held, hub turning: full-slip Coulomb friction)."""

    nodes: ContactNodes
    mu: float = 0.0
    rotation: Rotation = "ccw"
    #: elastic drum (:class:`clutchfem.contact.RingDrum`) or None (rigid); ``sectors``: the number
    #: of identical sectors the model stands for (its loads repeat around the drum)
    drum: object = None
    sectors: int = 1
    #: the drum's load per unit model force: the mid-plane symmetry factor of a 3-D half model
    #: (its nodal forces are half the real ones; the drum carries both halves)
    symmetry: float = 1.0
    #: gap scale [m] of the smoothed contact law (:func:`clutchfem.contact.smooth_lcp`); 0: exact
    smoothing: float = 0.0

    def __post_init__(self):
        if isinstance(self.mu, bool) or not isinstance(self.mu, (int, float, np.floating)) \
                or not (math.isfinite(self.mu) and 0.0 <= self.mu <= 1.0):
            raise ParameterError("mu", self.mu, "a friction coefficient in [0, 1]")
        if self.rotation not in ("ccw", "cw"):
            raise ParameterError("rotation", self.rotation, "'ccw' or 'cw' (hub's sense of rotation)")
        if not (math.isfinite(self.smoothing) and 0.0 <= self.smoothing <= MAX_SMOOTHING):
            raise ParameterError("contact_smoothing", self.smoothing, f"a gap scale in [0, {MAX_SMOOTHING:g}] m")

    @property
    def drum_radius(self) -> float:
        return self.nodes.drum_radius

    @property
    def s(self) -> float:
        """+1 for a hub turning ccw, -1 for cw."""
        return 1.0 if self.rotation == "ccw" else -1.0

    @property
    def friction(self) -> float:
        """s mu: the weight of the tangential load in D(mu) = N + s mu Tt."""
        return self.s * self.mu

    def with_mu(self, mu: float) -> "DrumContact":
        """The same drum and nodes with another friction coefficient."""
        return replace(self, mu=mu)

    @cached_property
    def load(self) -> sp.csc_matrix:
        """D (ndofs x m): nodal forces on the part per unit contact force (normal + friction)."""
        if self.mu == 0.0:
            return self.nodes.normal_load
        return (self.nodes.normal_load + self.friction * self.nodes.tangent_load).tocsc()

    @cached_property
    def drum_compliance(self) -> np.ndarray | None:
        """C_d = C_rr + s mu C_rt (m x m) [m/N] of an elastic drum at the contact nodes (the
        drum's wall moves out by C_d lam: the LCP matrix becomes G + C_d), None if rigid."""
        if self.drum is None:
            return None
        return self.symmetry * self.drum.operator(self.nodes, self.friction, self.sectors)

    def drum_gap(self, omega: float) -> float:
        """Free radial expansion [m] of a spinning elastic drum at ``omega`` [rad/s] (opens
        every gap; 0 for a rigid or held drum)."""
        return 0.0 if self.drum is None else float(self.drum.free_expansion(omega))

    def pressure(self, lam: np.ndarray, thickness: float) -> np.ndarray:
        """Contact pressure [Pa] at the nodes for nodal forces ``lam`` [N] (NaN at nodes of zero
        tributary area: the vertices of quadratic triangular faces in 3-D, whose consistent
        share of a pressure is zero on a flat face, ~3e-5 of an edge node's on a curved one;
        below 1e-3 of the largest weight counts as zero)."""
        w = self.nodes.weight
        ok = w > 1e-3 * float(np.max(w, initial=0.0))  # (a curved face's vertex: ~3e-5 x)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(ok, lam / (thickness * np.where(ok, w, 1.0)), np.nan)


class Compliance:
    """Lazily condensed contact compliance of one (FE model, contact nodes) pair,

        W(f) = K^-1 D(f),   D(f) = N + f Tt,   f = s mu,

    column by column as the LCP needs them, shared by every friction coefficient of the
    design.  D is linear in f, so two condensed sets span every f: the set ``a`` of the first
    friction f_a asked for (a single sweep condenses its own columns, nothing more) and,
    when another f is asked for, a set ``b``: K^-1 N if f_a != 0 (then W(f) = r A + (1 - r) B
    with r = f / f_a), else K^-1 Tt (then W(f) = A + f B).  Each condensation is one blocked
    back-solve: set ``a`` takes the asked node's neighbours along the shoe with it (the arc
    grows with speed), set ``b`` the nodes set ``a`` holds (the other friction coefficients
    touch the drum where the first one does).
    """

    def __init__(self, model, nodes: ContactNodes):
        # the model's constraint map and factorisation, not the model: the model caches this
        # object, and a reference back would make a cycle that only the garbage collector
        # frees (a design's matrices would outlive it)
        self._T, self._factor, self._ndofs = model.T, model.factor, model.ndofs
        self.nodes = nodes
        m = nodes.m
        self._rank = np.empty(m, dtype=np.int64)
        self._rank[nodes.by_arc] = np.arange(m)
        self.f_a: float | None = None
        self._pos = {"a": -np.ones(m, dtype=np.int64), "b": -np.ones(m, dtype=np.int64)}
        self._W = {"a": np.zeros((self._ndofs, 0)), "b": np.zeros((self._ndofs, 0))}
        self._BW = {"a": np.zeros((m, 0)), "b": np.zeros((m, 0))}
        self.seconds = 0.0

    @property
    def n_condensed(self) -> int:
        """Contact nodes condensed so far (first set)."""
        return int(self._W["a"].shape[1])

    def weights(self, friction: float) -> tuple[float, float]:
        """(c_a, c_b) with W(f) = c_a A + c_b B for f = ``friction``."""
        if self.f_a is None:
            self.f_a = float(friction)
        if friction == self.f_a:
            return 1.0, 0.0
        if self.f_a != 0.0:
            r = friction / self.f_a
            return r, 1.0 - r
        return 1.0, float(friction)

    def _load(self, kind: str) -> sp.csc_matrix:
        nd = self.nodes
        if kind == "a":
            return nd.normal_load if self.f_a == 0.0 else (nd.normal_load + self.f_a * nd.tangent_load).tocsc()
        return nd.normal_load if self.f_a != 0.0 else nd.tangent_load

    def _ensure(self, kind: str, idx: np.ndarray) -> None:
        pos = self._pos[kind]
        missing = idx[pos[idx] < 0]
        if not len(missing):
            return
        nd = self.nodes
        # each call streams the whole factorisation once (the columns are cheap next to that
        # when the factor is not in cache): condense what is likely to be asked for next too
        if kind == "a":
            # a sweep's contact arc grows node by node with speed: the PREFETCH nearest nodes
            # on either side along the same shoe
            near = self._rank[missing][:, None] + np.arange(-PREFETCH, PREFETCH + 1)[None, :]
            near = nd.by_arc[np.clip(near, 0, nd.m - 1)]
            near = near[nd.shoe[near] == nd.shoe[missing][:, None]]
        else:
            # the other friction coefficients touch the drum where the first one does: the
            # first set's nodes
            near = np.nonzero(self._pos["a"] >= 0)[0]
        missing = np.unique(np.concatenate([missing, near]))
        missing = missing[pos[missing] < 0]
        t = time.perf_counter()
        F = self._load(kind)[:, missing].toarray()
        Wn = (self._T @ self._factor.solve(self._T.T @ F)).reshape(self._ndofs, -1)
        pos[missing] = self._W[kind].shape[1] + np.arange(len(missing))
        self._W[kind] = np.hstack([self._W[kind], Wn])
        self._BW[kind] = np.hstack([self._BW[kind], nd.normal_displacement(Wn).reshape(nd.m, -1)])
        self.seconds += time.perf_counter() - t

    def _columns(self, store: dict, idx, friction: float) -> np.ndarray:
        idx = np.asarray(idx, dtype=np.int64)
        ca, cb = self.weights(friction)
        self._ensure("a", idx)
        out = store["a"][:, self._pos["a"][idx]]
        if ca != 1.0:
            out = ca * out
        if cb != 0.0:
            self._ensure("b", idx)
            out = out + cb * store["b"][:, self._pos["b"][idx]]
        return out

    def BW(self, idx, friction: float) -> np.ndarray:
        """Columns ``idx`` of B W(f) (normal displacements at the nodes), f = ``friction`` = s mu."""
        return self._columns(self._BW, idx, friction)

    def W(self, idx, friction: float) -> np.ndarray:
        """Columns ``idx`` of W(f) (all dofs)."""
        return self._columns(self._W, idx, friction)

    def positions(self) -> tuple[int, dict[str, np.ndarray]]:
        """(number of condensed columns, positions): per set, the index of each node's column in
        [A | B] (-1: not condensed), for the reduced-basis fields of a sweep."""
        k = self._W["a"].shape[1]
        pos = {"a": self._pos["a"].copy(), "b": np.where(self._pos["b"] >= 0, self._pos["b"] + k, -1)}
        return k + self._W["b"].shape[1], pos

    def columns(self, idx: np.ndarray) -> np.ndarray:
        """Columns ``idx`` (sorted, of [A | B]) of the condensed compliance (all dofs)."""
        idx = np.asarray(idx, dtype=np.int64)
        k = self._W["a"].shape[1]
        return np.hstack([self._W["a"][:, idx[idx < k]], self._W["b"][:, idx[idx >= k] - k]])
