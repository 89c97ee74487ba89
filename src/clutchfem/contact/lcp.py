"""The small linear complementarity problem (LCP) of one contact state.

    w = q + G lam >= 0,   lam >= 0,   w . lam = 0

w: gaps [m], lam: compressive nodal contact forces [N], q: gaps of the free (unloaded by
contact) part at this speed, G: the condensed contact compliance (m x m, m = contact nodes),
symmetric positive definite without friction, non-symmetric with full-slip Coulomb friction
(still a P-matrix for moderate mu, so the solution is unique).

:func:`solve_lcp` uses a primal-dual active set (exact after finitely many steps, warm-started
from the previous speed) and falls back to Lemke's complementary pivoting.  ``G`` may be a
dense matrix or a *lazy* column provider (:func:`lazy`): the active-set method only ever asks
for the columns of the nodes it makes active (a handful of the m candidates: the shoes touch
the drum on a short arc), so the columns of the others are never condensed.  A result that
does not satisfy the conditions to tolerance raises :class:`~clutchfem.core.SolverError`.

:func:`smooth_lcp` solves the same contact state with the complementarity *smoothed* on a gap
scale delta (for design sensitivities: the exact solution is only piecewise smooth in the
design, with a kink whenever a node enters or leaves the contact):

    exp(-lam_i / s_i) + exp(-w_i / delta) = 1,     s_i = delta / G_ii,

the log-sum-exp smoothing of min(lam_i / s_i, w_i / delta) = 0 (the exact law as delta -> 0).
A node at gap w carries s_i exp(-w/delta) (an exponential pressure-overclosure tail); a node
pressed with lam keeps a gap delta exp(-lam/s_i).  Its solution is C-infinity in (q, G), so
answers differ smoothly from design to design; the price is a bias of order delta in the
gaps, measured per answer where the smoothing is used (:mod:`clutchfem.evaluation.sensitivity`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import expit

from ..core import SolverError

__all__ = ["solve_lcp", "smooth_lcp", "lcp_residual", "lazy"]


def lcp_residual(G, q: np.ndarray, lam: np.ndarray) -> float:
    """Max violation of the LCP conditions, scaled to gap units.  ``G`` as in :func:`solve_lcp`."""
    cols = _as_columns(G)
    S = np.nonzero(lam)[0]
    GS = cols(S)
    w = q + GS @ lam[S]
    d = np.abs(GS[S, np.arange(len(S))]) if len(S) else np.zeros(0)
    scale = float(np.max(d, initial=0.0)) if isinstance(G, _Lazy) else float(np.max(np.abs(np.diag(G))))
    return float(max(np.max(-w, initial=0.0), np.max(-lam, initial=0.0) * scale,
                     np.max(np.abs(w * lam), initial=0.0) / max(np.max(lam, initial=0.0), 1e-300)))


class _Lazy:
    """Columns of G on demand: ``cols(idx) -> G[:, idx]``."""

    def __init__(self, cols):
        self.cols = cols

    def __call__(self, idx):
        return self.cols(np.asarray(idx, dtype=np.int64))


def lazy(cols) -> _Lazy:
    """Wrap a column provider ``cols(idx) -> G[:, idx]`` (m x len(idx)) for :func:`solve_lcp`."""
    return _Lazy(cols)


def _as_columns(G):
    if isinstance(G, _Lazy):
        return G
    G = np.asarray(G)
    return lambda idx: G[:, idx]


#: a lazy active-set iteration enters at most this many (or as many as are active) of the
#: penetrating inactive nodes, the deepest (the solution does not depend on it: G is positive definite; it saves
#: condensing columns the solution does not need)
ENTER_MAX = 4


def solve_lcp(G, q: np.ndarray, active0: np.ndarray | None = None,
              tol: float = 1e-12, max_iter: int = 100) -> tuple[np.ndarray, np.ndarray]:
    """Solve w = q + G lam, 0 <= lam perp w >= 0.  Returns (lam, active mask).

    ``G`` is the m x m matrix, or ``lazy(cols)``: a provider of its columns.  The active-set
    method only ever needs the columns of the nodes it makes active (a handful of the m
    contact nodes: the shoes touch the drum on a short arc), so a lazy G saves the
    condensation of all the others; the Lemke fallback asks for every column.
    ``tol`` is in gap units (metres); the check is relative to the problem scale."""
    m = len(q)
    scale_q = max(float(np.max(np.abs(q))), 1e-300)
    if np.all(q >= 0):
        return np.zeros(m), np.zeros(m, dtype=bool)
    lam, active, w, scale = _active_set(G, q, active0, max_iter)
    if lam is None:
        res = math.inf
    elif scale is not None and np.array_equal(lam > 0, active):
        # the residual from the gaps and the active columns the last step formed (what
        # lcp_residual computes, without forming them again)
        res = float(max(np.max(-w, initial=0.0), np.max(-lam, initial=0.0) * scale,
                        np.max(np.abs(w * lam), initial=0.0) / max(np.max(lam, initial=0.0), 1e-300)))
    else:
        res = lcp_residual(G, q, lam)
    if res > max(tol, 1e-9 * scale_q):
        lam = _lemke(_as_columns(G)(np.arange(m)), q)
        active = lam > 0
        res = lcp_residual(G, q, lam)
    if res > max(tol, 1e-9 * scale_q) * 10:
        raise SolverError(f"contact solve did not converge (complementarity residual {res:.3g} m)")
    return lam, active


def _active_set(G, q, active0, max_iter):
    """(lam, active, gaps w, scale) or (None, active, None, None): primal-dual active set;
    ``scale`` is :func:`lcp_residual`'s force-to-gap scale for a lazy G (max |G_ii| over the
    active nodes), None for a dense one."""
    m = len(q)
    cols = _as_columns(G)
    active = (q < 0) if active0 is None else active0.copy()
    if not active.any():
        active = q < 0
    lazy_g = isinstance(G, _Lazy)
    c = None  # 1 / mean diagonal: balances forces against gaps
    seen = set()
    for _ in range(max_iter):
        lam = np.zeros(m)
        A = np.nonzero(active)[0]
        GA = cols(A)
        if len(A):
            if c is None:
                c = 1.0 / np.mean(np.diag(GA[A]))
            try:
                lam[A] = np.linalg.solve(GA[A], -q[A])
            except np.linalg.LinAlgError:
                return None, active, None, None
            if not np.all(np.isfinite(lam[A])):
                return None, active, None, None
        w = q + GA @ lam[A]
        new = (lam - (c or 0.0) * w) > 0 if c is not None else w < 0
        if lazy_g and np.any(new & ~active):
            # enter only the deepest of the penetrating nodes (their columns are condensed
            # on demand; an elastic drum's compliance leaves most of a shoe's free arc
            # penetrating after the first push, the solution needs a few of them)
            enter = np.nonzero(new & ~active)[0]
            k = max(ENTER_MAX, int(active.sum()))  # (at least doubling: few iterations on long arcs)
            if len(enter) > k:
                new[enter[np.argsort(w[enter])[k:]]] = False
        key = new.tobytes()
        if np.array_equal(new, active):
            scale = float(np.max(np.abs(GA[A, np.arange(len(A))]), initial=0.0)) if isinstance(G, _Lazy) else None
            return lam, active, w, scale
        if key in seen:  # cycling
            return None, active, None, None
        seen.add(key)
        active = new
    return None, active, None, None


def _lemke(M: np.ndarray, q: np.ndarray, max_iter: int | None = None) -> np.ndarray:
    """Lemke's complementary pivoting with covering vector e (dense tableau)."""
    n = len(q)
    max_iter = max_iter or 50 * n + 100
    # tableau [I, -M, -e, q] for w - M z - e z0 = q
    T = np.hstack([np.eye(n), -M, -np.ones((n, 1)), q.reshape(-1, 1)]).astype(float)
    basis = list(range(n))  # w variables basic
    z0 = 2 * n
    r = int(np.argmin(q))
    entering = z0
    for _ in range(max_iter):
        # pivot on (r, entering)
        T[r] /= T[r, entering]
        for i in range(n):
            if i != r and T[i, entering] != 0.0:
                T[i] -= T[i, entering] * T[r]
        leaving = basis[r]
        basis[r] = entering
        if leaving == z0:
            break
        # complement of the leaving variable enters
        entering = leaving + n if leaving < n else leaving - n
        col = T[:, entering]
        pos = col > 1e-14 * np.max(np.abs(col))
        if not pos.any():
            raise SolverError("contact solve failed: Lemke ray termination (no solution found)")
        ratios = np.full(n, np.inf)
        ratios[pos] = T[pos, -1] / col[pos]
        rmin = ratios.min()
        cand = np.nonzero(ratios <= rmin * (1 + 1e-12) + 1e-300)[0]
        # prefer z0 leaving to terminate
        r = next((i for i in cand if basis[i] == z0), int(cand[0]))
    else:
        raise SolverError("contact solve failed: Lemke iteration limit reached")
    z = np.zeros(2 * n + 1)
    for i, bvar in enumerate(basis):
        z[bvar] = T[i, -1]
    return np.maximum(z[n:2 * n], 0.0)


#: :func:`smooth_lcp`: nodes within CUTOFF x delta of the drum carry a force (beyond, exp(-40)
#: of the force scale: 4e-18, below round-off of any answer)
CUTOFF = 40.0
#: :func:`smooth_lcp`: forces below FLOOR x s_i are set to zero (a step of 1e-9 N, invisible in
#: any answer), so nodes far open of the drum do not count as touching
FLOOR = 1e-9


def _smin(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(F, dF/da) of the smoothed min F = -log(exp(-a) + exp(-b)); dF/db = 1 - dF/da."""
    return -np.logaddexp(-a, -b), expit(b - a)


def smooth_lcp(G, q: np.ndarray, lam0: np.ndarray, delta: float, tol: float = 1e-10,
               max_iter: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """The contact state with the complementarity smoothed on the gap scale ``delta`` [m]
    (module docstring): (lam [N], closed mask).  ``G`` and ``q`` as in :func:`solve_lcp`;
    ``lam0`` its exact solution (the start of Newton's method).  ``closed``: the nodes on the
    pressed branch (lam_i / s_i > w_i / delta).  Newton's method with a backtracking line
    search on the nodes within :data:`CUTOFF` delta of the drum (grown until no other node
    comes that close); its Jacobian diag(dF/da / s) + diag(dF/db / delta) G is regular for a
    P-matrix G.  Raises SolverError if it does not converge to ``tol`` (dimensionless)."""
    if not (math.isfinite(delta) and delta > 0):
        raise ValueError(f"smooth_lcp: delta must be a positive gap [m], got {delta!r}")
    cols = _as_columns(G)
    m = len(q)
    lam = np.where(np.asarray(lam0, dtype=float) > 0, lam0, 0.0)
    S = np.nonzero(lam > 0)[0]
    if not len(S):
        S = np.array([int(np.argmin(q))])
    solved = False
    for _ in range(m + 1):
        GS = cols(S)
        w_all = q + GS @ lam[S]
        grow = np.setdiff1d(np.nonzero(w_all < CUTOFF * delta)[0], S)
        if solved and not len(grow):
            break
        if len(grow):
            S = np.union1d(S, grow)
            GS = cols(S)
        GSS = GS[S]
        s = delta / np.abs(np.diag(GSS))
        x = lam[S].copy()

        def resid(x, S=S, GSS=GSS, s=s):
            return _smin(x / s, (q[S] + GSS @ x) / delta)

        F, sa = resid(x)
        for _ in range(max_iter):
            nF = float(np.max(np.abs(F)))
            if nF < tol:
                break
            J = np.diag(sa / s) + ((1.0 - sa) / delta)[:, None] * GSS
            try:
                dx = np.linalg.solve(J, -F)
            except np.linalg.LinAlgError:
                raise SolverError("smoothed contact solve: singular Newton matrix") from None
            t, n0 = 1.0, float(np.linalg.norm(F))
            while True:
                Fn, san = resid(x + t * dx)
                if np.linalg.norm(Fn) <= (1 - 1e-4 * t) * n0 or t < 1e-10:
                    break
                t *= 0.5
            if t < 1e-10:  # round-off floor: no descent left
                if nF < 1e3 * tol:
                    break
                raise SolverError(f"smoothed contact solve stalled (residual {nF:.3g})")
            x, F, sa = x + t * dx, Fn, san
        else:
            raise SolverError(f"smoothed contact solve did not converge (residual {nF:.3g})")
        lam = np.zeros(m)
        lam[S] = np.where(x > FLOOR * s, x, 0.0)
        solved = True
    w = q + cols(S) @ lam[S]
    closed = np.zeros(m, dtype=bool)
    closed[S] = lam[S] / s > w[S] / delta
    return lam, closed
