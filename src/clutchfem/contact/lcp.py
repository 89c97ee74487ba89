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
"""

from __future__ import annotations

import math

import numpy as np

from ..core import SolverError

__all__ = ["solve_lcp", "lcp_residual", "lazy"]


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
