"""The algebra of linearised tolerance spreads: the allocation inequalities, the
reciprocal-cost optimum and the joint-normal yield (the FE side: :mod:`.allocation`).

Model (as :mod:`.robust`).  Over a tolerance band the answers are linear in the dimensions
(measured: R^2 = 1.000 of the Monte Carlo regressions, BENCHMARKS.md "Robust design"), so
each constrained answer A_j spreads with

    sigma_j^2 = sum_i (g_ji t_i / k)^2 + sigma_model,j^2,     g_ji = dA_j/dx_i

t_i the tolerance half-width of dimension i, k = 3 for a normal at +-3 sigma (ASSUMED, as
``tolerance``) or sqrt(3) for a uniform one (then the sum is taken as normal: the
linearised normal approximation of :mod:`.robust`), sigma_model,j = (error band of A_j) / 2
(band as +-2 sigma, ASSUMED; ``model_error=False`` leaves it out).  The m constraints share
the yield Y by Bonferroni, z = Phi^-1(1 - (1 - Y)/m), and constraint j holds for its share
when z sigma_j <= s_j, s_j its slack at the nominal design.  In the squared widths that is
one *linear* inequality per constraint,

    sum_i a_ji t_i^2 <= B_j,     a_ji = (g_ji / k)^2,   B_j = (s_j / z)^2 - sigma_model,j^2,

and B_j <= 0 means the model-error band alone (or a nominal already outside its limit) eats
the margin: **no tolerance meets Y**; the allocation then says so and gives no width (never a
negative one), with the yield a perfect part would reach, prod_j Phi(s_j / sigma_model,j).

Three answers from the same derivatives (one :func:`~.sensitivity.sensitivities` call: two
morphed designs per toleranced dimension, plus one ``analyze`` with errors for the bands; no
Monte Carlo in the loop):

* **scale**: the largest common factor lambda on the given widths, lambda = min_j
  sqrt(B_j / sum_i a_ji t0_i^2) (>= 1: the given tolerances meet Y with room); beside it
  the exact linearised factor at which the joint-normal yield is Y (:func:`joint_scale`,
  larger: Bonferroni is conservative);
* **alone**: the widest t_i with the other given widths held, min_j sqrt((B_j - sum_k!=i
  a_jk t0_k^2) / a_ji) (none where the others alone already miss Y);
* **allocated**: the cost-optimal widths of tolerance synthesis with the reciprocal cost
  model c_i(t_i) = w_i t0_i / t_i (Chase & Greenwood 1988, "Design issues in mechanical
  tolerance analysis", Manuf. Rev. 1: 50-59; ASSUMED: a tolerance costs in inverse
  proportion to its width, 1 per dimension at its given width unless ``cost`` weights w_i
  say otherwise): minimise sum_i c_i(t_i) subject to the m inequalities.  Why this one: it
  asks every dimension to give what is cheapest to give (a uniform scale tightens a
  dimension that hardly moves the binding answer as much as one that dominates it), it is
  convex in y_i = ln t_i (a geometric program: one optimum), and for one constraint it has
  the closed form t_i proportional to (w_i t0_i / a_i)^(1/3) -- the classical
  reciprocal-cost, root-sum-square allocation.  Solved by SLSQP in y from the scale
  solution; the multipliers mu_j (KKT, non-negative least squares) give the target that
  binds each dimension (the largest mu_j a_ji t_i^2 / B_j).

**Optimal split** (``allocated_union``, ``scale_union``): Bonferroni gives every target the
same share (1 - Y)/m of the failures, also to targets that hardly fail; the same
reciprocal-cost problem with the single constraint sum_j Phi(-s_j / sigma_j(t)) <= 1 - Y
(Boole's inequality: still at least Y of parts whatever the correlation) lets the binding
target take the whole budget.  Solved by SLSQP in ln t from the common scale that meets it
(Brent); not convex in general, so a local optimum, never worse than that start.  With one
target both splits agree.

Ranking "cost of tightening": at the given widths, the share of the variance of the
constraint that binds the scale that each dimension's sigma takes, (g_ji t0_i / k)^2 /
sigma_j^2 (the model-error share beside it): the dimension to tighten first is the largest.

Predicted yield (:func:`joint_yield`): the answers are linear in the same normal
deviations, so they are jointly normal and the share of parts meeting every target is a
multivariate normal probability, with the correlation the product prod_j Phi(s_j / sigma_j)
of :mod:`.robust` leaves out.  It matters: at the 122.3 g deterministic optimum the engagement
(>= limit) and the slip (<= limit) both rise with the clearance, so a part misses one *or*
the other, and the product over-predicts the yield (tolerances only: the product 42.2 %,
the joint normal 34.1 %, a Monte Carlo of 1000 remeshed parts 34.1 %, Wilson 31.2-37.1 %;
BENCHMARKS.md, "Tolerance allocation").  Both are reported.
"""

from __future__ import annotations

import math
from statistics import NormalDist

import numpy as np
from scipy.stats import multivariate_normal

from ..core import ParameterError

__all__ = ["allocate_linear", "check_yield", "joint_scale", "joint_yield"]


def check_yield(yield_target, dist: str = "normal") -> None:
    """Refuse a yield outside (0.5, 1) or an unknown distribution (ParameterError)."""
    if isinstance(yield_target, bool) or not (isinstance(yield_target, (int, float)) and 0.5 < yield_target < 1.0):
        raise ParameterError("yield", yield_target, "a share of parts in (0.5, 1), e.g. 0.99", "allocation")
    if dist not in ("normal", "uniform"):
        raise ParameterError("dist", dist, "normal or uniform", "allocation")


def allocate_linear(constraints: list[dict], tolerances: dict, *, yield_target: float, dist: str = "normal",
                    cost: dict | None = None, units: dict | None = None) -> dict:
    """The allocation algebra (module docstring) from given linearisations.

    Parameters
    ----------
    constraints : list of dict
        One per target: ``name``, ``key``, ``slack`` (>= 0 inside the limit, answer unit),
        ``grad`` (name -> dA/dx, answer unit per SI unit; None or missing: 0) and
        ``sigma_model`` (answer unit; 0 without model error).
    tolerances : dict
        name -> given half-width t0 (SI, > 0).
    yield_target : float
        Share of parts meeting every target, in (0.5, 1).
    dist : {"normal", "uniform"}
    cost : dict, optional
        name -> w_i, cost of dimension i at its given width (default 1 each).
    units : dict, optional
        name -> parameter unit ('m', 'deg', '-'), for the texts.

    Returns
    -------
    dict
        ``feasible``, ``message``, ``z``, ``scale``, ``scale_binds``, ``constraints`` (with
        budgets), ``dims`` (given, allocated, ratio, binds, alone, alone_binds, share,
        cost), ``ranking``, ``predicted_yield`` (joint normal) and
        ``predicted_yield_independent`` (product) at the given widths, ``allocated_yield``
        (joint normal at the allocated widths), ``perfect_part_yield``.

    Examples
    --------
    One dimension, one target: the allowed half-width is k slack / (z |dA/dx|).

    >>> from clutchfem.tolerances import allocate_linear
    >>> a = allocate_linear([{"name": "engagement", "key": "e", "slack": 100.0, "grad": {"t": 2.0e6},
    ...                       "sigma_model": 0.0}], {"t": 5e-5}, yield_target=0.99)
    >>> round(a["dims"][0]["allocated"] * 1e6, 2), round(3 * 100.0 / (a["z"] * 2.0e6) * 1e6, 2)   # um
    (64.48, 64.48)
    """
    check_yield(yield_target, dist)
    if not tolerances:
        raise ParameterError("tol", None, "at least one tolerance name=+-value", "allocation")
    for n, t in tolerances.items():
        if not (isinstance(t, (int, float)) and math.isfinite(t) and t > 0):
            raise ParameterError(n, t, "a given tolerance half-width > 0 (SI)", "allocation")
    names = list(tolerances)
    units = units or {}
    w = {n: float((cost or {}).get(n, 1.0)) for n in names}
    for n, v in w.items():
        if not (math.isfinite(v) and v > 0):
            raise ParameterError(f"cost[{n}]", v, "a cost weight > 0", "allocation")
    m = len(constraints)
    nd = NormalDist()
    z = nd.inv_cdf(1.0 - (1.0 - yield_target) / max(m, 1))
    k = 3.0 if dist == "normal" else math.sqrt(3.0)
    t0 = np.array([float(tolerances[n]) for n in names])
    A = np.array([[((c.get("grad") or {}).get(n) or 0.0) ** 2 / k ** 2 for n in names] for c in constraints]
                 ).reshape(m, len(names))
    cons, blocked = [], []
    pred, perfect = 1.0, 1.0
    for j, c in enumerate(constraints):
        s, sm = c.get("slack"), float(c.get("sigma_model") or 0.0)
        var_t = float(A[j] @ t0 ** 2)
        row = {"name": c["name"], "key": c["key"], "slack": s, "sigma_model": sm,
               "sigma_tolerances_given": math.sqrt(var_t), "sigma_given": math.sqrt(var_t + sm * sm)}
        if s is None or not math.isfinite(s):
            row.update(budget=None, blocked=True, reason="no answer at the nominal design")
            pred, perfect = 0.0, 0.0
        else:
            sg = row["sigma_given"]
            pred *= nd.cdf(s / sg) if sg > 0 else float(s >= 0)
            perfect *= nd.cdf(s / sm) if sm > 0 else float(s >= 0)
            B = (s / z) ** 2 - sm * sm if s > 0 else -1.0
            row["budget"] = B
            row["blocked"] = B <= 0
            row["reason"] = ("" if B > 0 else "the nominal design is outside this limit" if s <= 0 else
                             f"the model-error band alone needs a margin z sigma_model = {z * sm:.4g} "
                             f"against a slack of {s:.4g}")
        cons.append(row)
        if row["blocked"]:
            blocked.append(row)
    dims = [{"name": n, "unit": units.get(n, ""), "given": float(t0[i]), "cost_weight": w[n]}
            for i, n in enumerate(names)]
    out = {"z": z, "constraints": cons, "dims": dims, "predicted_yield_independent": pred,
           "perfect_part_yield": perfect, "predicted_yield": joint_yield(constraints, dict(zip(names, t0)), dist),
           "scale": None, "scale_binds": None, "ranking": []}
    _union_split(out, A, constraints, t0, np.array([w[n] for n in names]), 1.0 - yield_target)
    if blocked:
        for d in dims:
            d.update(allocated=None, ratio=None, binds=None, alone=None, alone_binds=None, share=None, cost=None)
        out["feasible"] = False
        out["message"] = ("NO TOLERANCE MEETS the yield " + f"{yield_target:.4g}: " + "; ".join(
            f"{r['name']}: {r['reason']}" for r in blocked)
            + f" (a perfect part, every tolerance zero, reaches a predicted yield of {100 * perfect:.4g} %)")
        if out.get("scale_union") is not None:
            out["message"] += ("; with the failure budget split optimally between the targets instead of equally, "
                               "widths do exist (allocated_union)")
        return out
    B = np.array([c["budget"] for c in cons])
    # the common scale on the given widths
    use = A @ t0 ** 2
    lam = np.where(use > 0, np.sqrt(B / np.where(use > 0, use, 1.0)), np.inf)
    jb = int(np.argmin(lam)) if m else None
    out["scale"] = float(lam[jb]) if m else math.inf
    out["scale_binds"] = cons[jb]["name"] if m and math.isfinite(lam[jb]) else None
    # the binding constraint's variance shares at the given widths: the ranking
    if jb is not None and math.isfinite(lam[jb]):
        var = float(use[jb]) + cons[jb]["sigma_model"] ** 2
        for i, d in enumerate(dims):
            d["share"] = float(A[jb, i] * t0[i] ** 2 / var)
        out["model_share"] = cons[jb]["sigma_model"] ** 2 / var
    out["ranking"] = [d["name"] for d in sorted(dims, key=lambda d: -(d.get("share") or 0.0))]
    # widest alone, the others held at their given widths
    for i, d in enumerate(dims):
        best, bj = math.inf, None
        for j in range(m):
            if A[j, i] <= 0:
                continue
            rest = B[j] - (use[j] - A[j, i] * t0[i] ** 2)
            ti = math.sqrt(rest / A[j, i]) if rest > 0 else 0.0
            if ti < best:
                best, bj = ti, j
        d["alone"] = None if best == 0.0 else best
        d["alone_binds"] = None if bj is None else cons[bj]["name"]
        if best == 0.0:
            d["alone_note"] = "the other given tolerances alone already miss the yield"
    # the cost-optimal allocation
    t, mu = _reciprocal_cost(A, B, t0, np.array([w[n] for n in names]), out["scale"])
    for i, d in enumerate(dims):
        ti = float(t[i])
        d["allocated"] = ti
        d["unlimited"] = not math.isfinite(ti)   # no target depends on it (JSON shows inf as null)
        d["ratio"] = ti / d["given"] if math.isfinite(ti) else math.inf
        d["cost"] = d["cost_weight"] * d["given"] / ti if math.isfinite(ti) else 0.0
        if not math.isfinite(ti):
            d["binds"] = None
            continue
        pull = [mu[j] * A[j, i] * ti * ti / B[j] for j in range(m)]
        j = int(np.argmax(pull)) if m else None
        d["binds"] = cons[j]["name"] if j is not None and pull[j] > 0 else None
        d["share_allocated"] = (float(A[j, i] * ti * ti / ((B[j] + cons[j]["sigma_model"] ** 2)))
                                if d["binds"] else None)
    for j, c in enumerate(cons):
        c["multiplier"] = float(mu[j])
    out["scale_joint"] = joint_scale(constraints, dict(zip(names, t0)), yield_target, dist)
    out["allocated_yield"] = joint_yield(constraints, {d["name"]: d["allocated"] if math.isfinite(d["allocated"])
                                                             else 0.0 for d in dims}, dist)
    out["feasible"] = True
    worst = min(lam) if m else math.inf
    out["message"] = ("the given tolerances meet the yield" + (f" with room: every width x {worst:.3g}" if worst >= 1
                                                               else "") if worst >= 1 else
                      f"the given tolerances MISS the yield: every width x {worst:.3g} meets it")
    return out


def joint_yield(constraints: list[dict], widths: dict, dist: str = "normal") -> float:
    """The predicted share of parts meeting every target at half-widths ``widths``, from the
    joint normal of the linearised answers (module docstring): margin_j = s_j + sgn_j g_j . d
    + e_j with d ~ N(0, diag((t_i / k)^2)) and independent model errors e_j ~ N(0, sigma_model,j^2)
    (ASSUMED independent between answers), sgn_j = +1 for a '>=' target ('sense', the
    default) and -1 for '<='.  Unlike the product of the per-target probabilities it counts
    the correlation of the answers (engagement and slip both rise with the clearance, so a
    part misses one limit *or* the other); the multivariate normal CDF by Genz's method
    (scipy, seeded, absolute error 1e-5)."""
    k = 3.0 if dist == "normal" else math.sqrt(3.0)
    names = list(widths)
    if any(c.get("slack") is None or not math.isfinite(c["slack"]) for c in constraints):
        return 0.0
    if not constraints:
        return 1.0
    sig = np.array([float(widths[n] or 0.0) / k for n in names])
    G = np.array([[(1.0 if c.get("sense", ">=") == ">=" else -1.0) * ((c.get("grad") or {}).get(n) or 0.0)
                   for n in names] for c in constraints])
    C = (G * sig ** 2) @ G.T + np.diag([float(c.get("sigma_model") or 0.0) ** 2 for c in constraints])
    s = np.array([float(c["slack"]) for c in constraints])
    sure = np.diag(C) <= 0.0                      # no spread: the target holds or not
    if np.any(s[sure] < 0):
        return 0.0
    C, s = C[~sure][:, ~sure], s[~sure]
    if s.size == 0:
        return 1.0
    if s.size == 1:
        return NormalDist().cdf(s[0] / math.sqrt(C[0, 0]))
    sd = np.sqrt(np.diag(C))
    R = C / np.outer(sd, sd) + np.eye(len(s)) * 1e-9   # standardised; fewer dimensions than targets: singular
    return float(multivariate_normal(mean=np.zeros(len(s)), cov=R, allow_singular=True).cdf(
        s / sd, rng=np.random.default_rng(0)))


def joint_scale(constraints: list[dict], tolerances: dict, yield_target: float, dist: str = "normal") -> float | None:
    """The common factor lambda on the widths ``tolerances`` at which the joint-normal yield
    (:func:`joint_yield`) equals ``yield_target`` -- the exact linearised answer that the
    Bonferroni scale bounds from below; None where even perfect parts (lambda = 0) miss it,
    inf where no width does (no target depends on the dimensions).  Brent's method on the
    monotone yield(lambda), to 1e-6 of lambda."""
    from scipy.optimize import brentq

    def f(lam):
        return joint_yield(constraints, {n: lam * t for n, t in tolerances.items()}, dist) - yield_target

    if f(0.0) < 0:
        return None
    hi = 1.0
    while f(hi) >= 0:
        hi *= 2.0
        if hi > 1e6:
            return math.inf
    return float(brentq(f, 0.0, hi, xtol=1e-9, rtol=1e-6))


def _union_split(out: dict, A: np.ndarray, constraints: list[dict], t0: np.ndarray, w: np.ndarray, budget: float):
    """The reciprocal-cost allocation with the failure budget split *optimally* between the
    targets (module docstring, "optimal split"): min sum w t0 / t s.t. sum_j Phi(-s_j /
    sigma_j(t)) <= 1 - Y (Boole's inequality: still at least Y of parts, whatever the
    correlation).  Adds ``scale_union`` and per dimension ``allocated_union`` to ``out``
    (None where even perfect parts break the budget)."""
    from scipy.optimize import brentq, minimize

    nd = NormalDist()
    s = np.array([float(c["slack"]) if c.get("slack") is not None and math.isfinite(c["slack"]) else -1.0
                  for c in constraints])
    sm2 = np.array([float(c.get("sigma_model") or 0.0) ** 2 for c in constraints])

    def fail(t2):
        sig = np.sqrt(A @ t2 + sm2)
        return sum((nd.cdf(-sj / gj) if gj > 0 else float(sj < 0)) for sj, gj in zip(s, sig))

    out["scale_union"] = None
    for d in out["dims"]:
        d["allocated_union"] = None
    if not len(s) or fail(np.zeros_like(t0)) >= budget:
        return
    live = np.array([bool(np.any(A[:, i] > 0)) for i in range(len(t0))])
    hi = 1.0
    while fail((hi * t0) ** 2) < budget and hi < 1e6:
        hi *= 2.0
    lam = brentq(lambda x: budget - fail((x * t0) ** 2), 0.0, hi, xtol=1e-12, rtol=1e-9) if hi < 1e6 else math.inf
    out["scale_union"] = float(lam)
    if not live.any() or not math.isfinite(lam):
        return
    c, tl, Al = w[live], t0[live], A[:, live]

    def g(y):      # >= 0: within the budget, in units of the budget
        return 1.0 - fail_l(y) / budget

    def fail_l(y):
        t2 = np.full(len(t0), 0.0)
        t2[live] = (tl * np.exp(y)) ** 2
        t2[~live] = 0.0
        return fail(t2)

    def dg(y):
        t2 = (tl * np.exp(y)) ** 2
        sig2 = Al @ t2 + sm2
        sig = np.sqrt(sig2)
        u = np.where(sig > 0, s / np.where(sig > 0, sig, 1.0), 0.0)
        pdf = np.exp(-0.5 * u * u) / math.sqrt(2 * math.pi)
        # d Phi(-u_j) / d y_i = phi(u_j) u_j a_ji t_i^2 / sigma_j^2
        dfail = ((pdf * u / np.where(sig2 > 0, sig2, 1.0))[:, None] * Al * t2[None, :]).sum(axis=0)
        return -dfail / budget

    y0 = np.full(int(live.sum()), math.log(lam * 0.98))   # inside: SLSQP may not leave a start on the boundary
    res = minimize(lambda y: float(c @ np.exp(-y)), y0, jac=lambda y: -c * np.exp(-y), method="SLSQP",
                   constraints=[{"type": "ineq", "fun": g, "jac": dg}], options={"ftol": 1e-14, "maxiter": 500})
    ok = np.all(np.isfinite(res.x)) and g(res.x) >= -1e-9      # as _reciprocal_cost: feasible and cheaper
    y = res.x if ok and float(c @ np.exp(-res.x)) <= float(c @ np.exp(-y0)) else y0
    if g(y) < 0:   # rounding: back inside the budget
        y = y - 1e-9
    k = 0
    for i, d in enumerate(out["dims"]):
        if live[i]:
            d["allocated_union"] = float(tl[k] * math.exp(y[k]))
            k += 1
        else:
            d["allocated_union"] = math.inf


def _reciprocal_cost(A: np.ndarray, B: np.ndarray, t0: np.ndarray, w: np.ndarray, scale: float):
    """(widths, multipliers): min sum w t0 / t s.t. A t^2 <= B (module docstring).  Widths
    of dimensions no constraint depends on are infinite."""
    from scipy.optimize import minimize, nnls

    m, n = A.shape
    live = np.array([bool(np.any(A[:, i] > 0)) for i in range(n)])
    t = np.full(n, np.inf)
    mu = np.zeros(m)
    if not live.any():
        return t, mu
    Q = A[:, live] * t0[live] ** 2 / B[:, None]   # sum_i Q_ji e^{2 y_i} <= 1, y = ln(t / t0)
    c = w[live]
    y0 = np.full(int(live.sum()), math.log(scale * 0.98))   # inside: SLSQP may not leave a start on the boundary
    res = minimize(lambda y: float(c @ np.exp(-y)), y0, jac=lambda y: -c * np.exp(-y), method="SLSQP",
                   constraints=[{"type": "ineq", "fun": lambda y: 1.0 - Q @ np.exp(2 * y),
                                 "jac": lambda y: -2.0 * Q * np.exp(2 * y)[None, :]}],
                   options={"ftol": 1e-14, "maxiter": 500})
    # SLSQP may stop with "positive directional derivative" at the optimum (a start on the
    # boundary): its point is taken when it is feasible (to rounding) and cheaper than the start
    ok = np.all(np.isfinite(res.x)) and float(np.max(Q @ np.exp(2 * res.x))) <= 1.0 + 1e-9
    y = res.x if ok and float(c @ np.exp(-res.x)) <= float(c @ np.exp(-y0)) else y0
    worst = float(np.max(Q @ np.exp(2 * y)))
    if worst > 1.0:   # rounding of the solver: back onto the feasible side
        y = y - 0.5 * math.log(worst)
    tl = t0[live] * np.exp(y)
    t[live] = tl
    # KKT: w t0 / t = sum_j mu_j 2 Q_ji e^{2 y_i}: the multipliers by non-negative least squares
    M = 2.0 * Q.T * np.exp(2 * y)[:, None]
    active = Q @ np.exp(2 * y) >= 1.0 - 1e-6
    if active.any():
        mu_a, _ = nnls(M[:, active], c * np.exp(-y))
        mu[active] = mu_a
    return t, mu
