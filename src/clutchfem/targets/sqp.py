"""The model pieces of the trust-region SQP of :mod:`.gradient`: the step subproblem, the l1
merit function, Powell's damped BFGS update and the linearised repair step (analytic, no
analysis; the subproblems are solved with scipy's SLSQP)."""

from __future__ import annotations

import numpy as np
from scipy.optimize import minimize

#: safety margin of the repair step, relative to each limit
REPAIR_MARGIN = 5e-4


def merit(f: float, c: np.ndarray, rho: float) -> float:
    return float(f + rho * np.sum(np.maximum(0.0, -c)))


def subproblem(g, J, c, B, lo, hi, rho, rules=()) -> tuple[np.ndarray, np.ndarray]:
    """The QP of one step: min g.d + d.B.d / 2 + rho sum(s) with c + J d + s >= 0, s >= 0, in
    the box lo <= d <= hi (the trust region within [0, 1] and the rules' bounds); (d, the
    constraints' multipliers)."""
    n, m = len(lo), len(c)

    def obj(z):
        d = z[:n]
        return float(g @ d + 0.5 * d @ B @ d + rho * np.sum(z[n:]))

    def jac(z):
        d = z[:n]
        return np.concatenate([g + B @ d, np.full(m, rho)])

    A = np.hstack([J, np.eye(m)])
    z0 = np.concatenate([np.zeros(n), np.maximum(0.0, -c)])
    bounds = list(zip(lo, hi)) + [(0.0, None)] * m
    cons = [{"type": "ineq", "fun": lambda z: c + A @ z, "jac": lambda z: A}] if m else []
    if rules:
        R = np.hstack([np.array([r for r, _ in rules]), np.zeros((len(rules), m))])
        rb = np.array([b for _, b in rules])
        cons.append({"type": "ineq", "fun": lambda z: R @ z - rb, "jac": lambda z: R})
    res = minimize(obj, z0, jac=jac, method="SLSQP", bounds=bounds, constraints=cons,
                   options={"maxiter": 200, "ftol": 1e-12})
    lam = np.asarray(res.get("multipliers", ()), dtype=float).ravel()  # the targets' rows first
    return res.x[:n], np.maximum(lam[:m], 0.0) if lam.size >= m else np.zeros(m)


def bfgs(B: np.ndarray, s: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Powell's damped BFGS update of the Lagrangian's Hessian model (stays positive definite)."""
    sBs = float(s @ B @ s)
    if sBs <= 1e-16:
        return B
    sy = float(s @ y)
    theta = 1.0 if sy >= 0.2 * sBs else 0.8 * sBs / (sBs - sy)
    r = theta * y + (1.0 - theta) * (B @ s)
    return B - np.outer(B @ s, B @ s) / sBs + np.outer(r, r) / float(s @ r)


def repair_step(c: np.ndarray, gc: np.ndarray, x: np.ndarray, margin: float | None = None, lo=None,
                 hi=None) -> np.ndarray | None:
    """The shortest step dx with c + gc dx >= ``margin`` (default REPAIR_MARGIN; the linear
    model), in the box [0, 1] (or lo <= dx <= hi)."""
    target = (REPAIR_MARGIN if margin is None else margin) - c  # satisfied rows may give slack down to it
    lo = -x if lo is None else lo
    hi = 1.0 - x if hi is None else hi
    res = minimize(lambda d: float(d @ d), np.zeros_like(x), jac=lambda d: 2 * d, method="SLSQP",
                   bounds=list(zip(lo, hi)),
                   constraints=[{"type": "ineq", "fun": lambda d: gc @ d - target, "jac": lambda d: gc}])
    return res.x if res.success else None
