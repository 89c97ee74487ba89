"""Tolerance allocation and the mass-yield trade-off: the widest manufacturing tolerance per
dimension for a yield target, from the linearised spreads of one sensitivities call.

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
  sqrt(B_j / sum_i a_ji t0_i^2) (>= 1: the given tolerances meet Y with room);
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

Ranking "cost of tightening": at the given widths, the share of the variance of the
constraint that binds the scale that each dimension's sigma takes, (g_ji t0_i / k)^2 /
sigma_j^2 (the model-error share beside it): the dimension to tighten first is the largest.

Predicted yield (:func:`joint_yield`): the answers are linear in the same normal
deviations, so they are jointly normal and the share of parts meeting every target is a
multivariate normal probability, with the correlation the product prod_j Phi(s_j / sigma_j)
of :mod:`.robust` leaves out.  It matters: at today's deterministic optimum the engagement
(>= limit) and the slip (<= limit) both rise with the clearance, so a part misses one *or*
the other, and the product over-predicts the yield (42 % against the joint 30 % and the
Monte Carlo's 34 %, BENCHMARKS.md "Tolerance allocation").  Both are reported.

The trade-off (:func:`yield_front`): along a given set of designs (e.g. the deterministic
and the robust optimum and the straight path between them) the predicted yield at the given
tolerances and the tolerance scale each yield allows, against the part mass.  It is **not**
the true Pareto front (one robust optimisation per yield, hundreds of designs each): its
masses are an upper bound on the front's at those yields.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from statistics import NormalDist

import numpy as np
from scipy.stats import multivariate_normal

from ..core import ParameterError, clean
from ..geometry import get_concept
from .batch import EvalSettings
from .robust import model_bands
from .sensitivity import Sensitivities, sensitivities
from .targets import Targets
from .tolerancing import parse_tolerance

#: the unit each constrained answer is shown in
ANSWER_UNIT = {"engagement_rpm_with_ripple": "rpm", "slip_rpm": "rpm", "safety_factor": "-",
               "fatigue_safety_factor": "-"}
#: (scale, unit) each parameter unit is shown in
SHOWN = {"m": (1e3, "mm"), "deg": (1.0, "deg")}
#: the default yields of the trade-off
FRONT_YIELDS = (0.9, 0.95, 0.99, 0.999)


def shown(unit: str, value: float | None, digits: int = 4) -> str:
    """``value`` (SI, parameter ``unit``) as a text with its shown unit: '0.0512 mm'."""
    if value is None:
        return "none"
    if value == math.inf:
        return "unlimited"
    sc, u = SHOWN.get(unit, (1.0, "(-)"))
    return f"{value * sc:.{digits}g} {u}"


@dataclass
class Allocation:
    """What :func:`allocate_tolerances` returns (module docstring): per constraint its slack,
    spreads and budget; per dimension the given, allocated and alone-widest half-widths
    [SI: m, deg or -], the target binding each and its variance share; the common scale."""

    concept: str
    yield_target: float
    dist: str
    model_error: bool
    z: float
    tolerances: dict
    units: dict
    constraints: list
    dims: list
    feasible: bool
    message: str
    scale: float | None = None
    scale_binds: str | None = None
    #: at the given widths: joint normal (:func:`joint_yield`), and the product of the
    #: per-target probabilities (targets independent, as :mod:`.robust`)
    predicted_yield: float | None = None
    predicted_yield_independent: float | None = None
    #: joint normal at the allocated widths (>= the yield asked: Bonferroni is conservative)
    allocated_yield: float | None = None
    perfect_part_yield: float | None = None
    ranking: list = field(default_factory=list)
    #: the model-error share of the variance of the target binding the scale (given widths)
    model_share: float | None = None
    derivatives: dict = field(default_factory=dict)
    methods: dict = field(default_factory=dict)
    base: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    seconds: float = 0.0
    #: the linearised constraints (slack, gradient, model sigma): :meth:`at` reuses them
    linearisation: list = field(default_factory=list)
    cost: dict | None = None

    def at(self, yield_target: float, model_error: bool | None = None) -> dict:
        """The allocation algebra (:func:`allocate_linear`) at another yield, on the same
        derivatives (no FE run); ``model_error=False`` drops the bands."""
        cons = self.linearisation
        if model_error is False:
            cons = [{**c, "sigma_model": 0.0} for c in cons]
        return allocate_linear(cons, self.tolerances, yield_target=yield_target, dist=self.dist, cost=self.cost,
                               units=self.units)

    @property
    def allocated(self) -> dict:
        """name -> allocated half-width (SI; None where no width meets the yield)."""
        return {d["name"]: d["allocated"] for d in self.dims}

    def to_json(self) -> dict:
        return clean({"allocation": {k: getattr(self, k) for k in (
            "concept", "yield_target", "dist", "model_error", "z", "tolerances", "units", "feasible", "message",
            "scale", "scale_binds", "predicted_yield", "predicted_yield_independent", "allocated_yield",
            "perfect_part_yield", "ranking", "model_share", "constraints", "dims",
            "derivatives", "methods", "notes", "seconds")},
            "method": {"spread": "linearised: sigma^2 = sum (dA/dx t/k)^2 + (band/2)^2, k = 3 normal, sqrt(3) uniform",
                       "yield": "Bonferroni over the constraints: z = Phi^-1(1 - (1 - Y)/m)",
                       "allocated": "min sum w_i t0_i / t_i (reciprocal cost, Chase & Greenwood 1988, ASSUMED) "
                                    "s.t. z sigma_j <= slack_j; SLSQP in ln t"}})


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

    >>> from clutchfem.studies import allocate_linear
    >>> a = allocate_linear([{"name": "engagement", "key": "e", "slack": 100.0, "grad": {"t": 2.0e6},
    ...                       "sigma_model": 0.0}], {"t": 5e-5}, yield_target=0.99)
    >>> round(a["dims"][0]["allocated"] * 1e6, 2), round(3 * 100.0 / (a["z"] * 2.0e6) * 1e6, 2)   # um
    (64.48, 64.48)
    """
    if not (isinstance(yield_target, (int, float)) and 0.5 < yield_target < 1.0):
        raise ParameterError("yield", yield_target, "a share of parts in (0.5, 1), e.g. 0.99", "allocation")
    if dist not in ("normal", "uniform"):
        raise ParameterError("dist", dist, "normal or uniform", "allocation")
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
    if blocked:
        for d in dims:
            d.update(allocated=None, ratio=None, binds=None, alone=None, alone_binds=None, share=None, cost=None)
        out["feasible"] = False
        out["message"] = ("NO TOLERANCE MEETS the yield " + f"{yield_target:.4g}: " + "; ".join(
            f"{r['name']}: {r['reason']}" for r in blocked)
            + f" (a perfect part, every tolerance zero, reaches a predicted yield of {100 * perfect:.3g} %)")
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
    y0 = np.full(int(live.sum()), math.log(scale))
    res = minimize(lambda y: float(c @ np.exp(-y)), y0, jac=lambda y: -c * np.exp(-y), method="SLSQP",
                   constraints=[{"type": "ineq", "fun": lambda y: 1.0 - Q @ np.exp(2 * y),
                                 "jac": lambda y: -2.0 * Q * np.exp(2 * y)[None, :]}],
                   options={"ftol": 1e-14, "maxiter": 500})
    y = res.x if res.success and float(c @ np.exp(-res.x)) <= float(c @ np.exp(-y0)) + 1e-12 else y0
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


def linearise(settings: EvalSettings, targets: Targets, names: list[str], model_error: bool = True,
              workers=None) -> tuple[list[dict], Sensitivities]:
    """(constraints with slack, gradient and model sigma; the sensitivities) at a design: one
    :func:`~.sensitivity.sensitivities` call and, with ``model_error``, one ``analyze`` with
    errors."""
    s = sensitivities(settings, names, workers=workers)
    bands = model_bands(settings) if model_error else {}
    cons = []
    for name, key, limit, sense in targets.constraints():
        v = s.base.get(key)
        slack = None if v is None or not math.isfinite(v) else ((v - limit) if sense == ">=" else (limit - v))
        band = bands.get(key)
        cons.append({"name": name, "key": key, "limit": limit, "sense": sense, "value": v, "slack": slack,
                     "unit": ANSWER_UNIT.get(key, ""), "grad": {n: s.derivatives[n].get(key) for n in names},
                     "sigma_model": band / 2.0 if band else 0.0, "band": band})
    return cons, s


def _settings_and_tols(design, tolerances, engine, requirements):
    settings = design if isinstance(design, EvalSettings) else EvalSettings.from_design(
        design, engine=engine, requirements=requirements)
    P = get_concept(settings.concept).Params
    if not isinstance(tolerances, dict) or not tolerances:
        raise ParameterError("tolerances", tolerances, "a dict name -> half-width with at least one entry "
                             "(e.g. {'flexure_thickness': '0.05mm'})", "allocation")
    tols = {}
    for n, t in tolerances.items():
        if isinstance(t, bool) or not isinstance(t, (str, int, float)):
            raise ParameterError(n, t, "a tolerance half-width: SI number or text with its unit", "allocation")
        text = t.strip().lstrip("+-±/") if isinstance(t, str) else repr(float(t))
        name, half = parse_tolerance(P, f"{n}=+-{text}")
        tols[name] = half
    return settings, tols, P


def allocate_tolerances(design, tolerances: dict, *, yield_target: float = 0.99, dist: str = "normal",
                        model_error: bool = True, targets: Targets | None = None, cost: dict | None = None,
                        engine=None, requirements=None, workers: int | None = None) -> Allocation:
    """The widest tolerance per dimension such that every target holds for ``yield_target``
    of the parts, from the linearised spreads (module docstring).

    Parameters
    ----------
    design : Design or EvalSettings
        The nominal design (a concept's).
    tolerances : dict
        ``name -> given half-width`` (SI floats or texts with a unit, ``"0.05mm"``): the
        dimensions to allocate and the widths costs are counted against.
    yield_target : float
        Share of parts that must meet every target, in (0.5, 1).
    dist : {"normal", "uniform"}
        The tolerance at +-3 sigma of a normal (ASSUMED default) or a uniform distribution.
    model_error : bool
        Add each answer's model-error band (as +-2 sigma) to its spread.
    targets : Targets, optional
        Default: the requirement checks with safety factor >= 1.5.
    cost : dict, optional
        name -> cost weight of the dimension at its given width (default 1 each).
    engine, requirements, workers
        As :func:`~.sensitivity.sensitivities`.

    Returns
    -------
    Allocation
        ``feasible`` (False: the model-error band alone eats a margin, no width given),
        ``scale``, ``dims`` (given / allocated / alone-widest half-widths, binding target,
        variance share), ``ranking``, ``predicted_yield`` at the given widths.

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> t = cf.Targets(3510, None, None, None)                # engagement with ripple >= 3510 rpm only
    >>> a = cf.allocate_tolerances(d, {"flexure_thickness": "0.05mm"}, targets=t, model_error=False, workers=0)
    >>> a.feasible, a.allocated["flexure_thickness"] > 0      # a half-width in m
    (True, True)
    """
    t0 = time.perf_counter()
    settings, tols, P = _settings_and_tols(design, tolerances, engine, requirements)
    if cost:
        for n in cost:
            if n not in tols:
                raise ParameterError(f"cost[{n}]", cost[n], "a weight of a toleranced dimension: "
                                     + ", ".join(tols), "allocation")
    nominal = targets or Targets.defaults(settings)
    cons, s = linearise(settings, nominal, list(tols), model_error, workers)
    units = {n: P.unit(n) for n in tols}
    r = allocate_linear(cons, tols, yield_target=yield_target, dist=dist, cost=cost, units=units)
    for c, row in zip(cons, r["constraints"]):
        row.update({k: c[k] for k in ("limit", "sense", "value", "unit", "band")})
    notes = [f"{n}: derivative method {s.methods[n]}" for n in tols if s.methods[n] != "central, morphed"] + list(s.notes)
    for c in cons:
        gone = [n for n, g in c["grad"].items() if g is None]
        if gone:
            notes.append(f"{c['name']}: no derivative for {', '.join(gone)} (taken as 0)")
    return Allocation(concept=settings.concept, yield_target=yield_target, dist=dist, model_error=model_error,
                      z=r["z"], tolerances=tols, units=units, constraints=r["constraints"], dims=r["dims"],
                      feasible=r["feasible"], message=r["message"], scale=r["scale"], scale_binds=r["scale_binds"],
                      predicted_yield=r["predicted_yield"], perfect_part_yield=r["perfect_part_yield"],
                      predicted_yield_independent=r["predicted_yield_independent"],
                      allocated_yield=r.get("allocated_yield"),
                      ranking=r["ranking"], model_share=r.get("model_share"), derivatives={n: dict(v) for n, v in s.derivatives.items()},
                      methods=dict(s.methods), base=dict(s.base), notes=notes, seconds=time.perf_counter() - t0,
                      linearisation=cons, cost=cost)


def yield_front(designs: list, tolerances: dict, *, yields=FRONT_YIELDS, dist: str = "normal",
                model_error: bool = True, targets: Targets | None = None, engine=None, requirements=None,
                workers: int | None = None) -> list[dict]:
    """Part mass against predicted yield (and the tolerance scale each yield allows) over a
    set of designs: the trade-off of the module docstring (not the true Pareto front).

    Parameters
    ----------
    designs : list of Design or EvalSettings
        The designs (e.g. the deterministic and robust optima and points between).
    tolerances : dict
        ``name -> half-width`` as :func:`allocate_tolerances`.
    yields : sequence of float
        The yields whose allowed tolerance scale is reported.
    dist, model_error, targets, engine, requirements, workers
        As :func:`allocate_tolerances` (``targets`` default: each design's requirement
        checks).

    Returns
    -------
    list of dict
        Per design: ``mass_kg``, ``predicted_yield`` at the given widths (joint normal;
        ``predicted_yield_independent``: the product over the targets;
        ``predicted_yield_tolerances_only``: the bands left out), ``perfect_part_yield``,
        ``scale`` (yield -> common factor on the given widths, None where none meets it),
        ``pareto`` (no other design is lighter with at least its yield), ``slack`` and
        ``sigma_given`` per constraint (answer units).

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> f = cf.yield_front([d], {"clearance": "0.02mm"}, yields=(0.9,), model_error=False, workers=0)
    >>> f[0]["mass_kg"] > 0, f[0]["pareto"]
    (True, True)
    """
    for y in yields:
        if not (isinstance(y, (int, float)) and 0.5 < y < 1.0):
            raise ParameterError("yields", y, "shares of parts in (0.5, 1)", "yield_front")
    if not designs:
        raise ParameterError("designs", designs, "at least one design", "yield_front")
    rows = []
    for d in designs:
        settings, tols, P = _settings_and_tols(d, tolerances, engine, requirements)
        nominal = targets or Targets.defaults(settings)
        cons, s = linearise(settings, nominal, list(tols), model_error, workers)
        units = {n: P.unit(n) for n in tols}
        scale, alloc = {}, None
        for y in yields:
            r = allocate_linear(cons, tols, yield_target=y, dist=dist, units=units)
            scale[y] = r["scale"] if r["feasible"] else None
            if alloc is None:
                alloc = r
        bare = allocate_linear([{**c, "sigma_model": 0.0} for c in cons], tols, yield_target=yields[0], dist=dist,
                               units=units)
        rows.append({"concept": settings.concept, "set": list(settings.base), "mass_kg": s.base.get("mass_kg"),
                     "predicted_yield": alloc["predicted_yield"], "perfect_part_yield": alloc["perfect_part_yield"],
                     "predicted_yield_independent": alloc["predicted_yield_independent"],
                     "predicted_yield_tolerances_only": bare["predicted_yield"],
                     "scale": scale, "slack": {c["key"] + " " + c["sense"]: c["slack"] for c in cons},
                     "sigma_given": {c["key"]: r_["sigma_given"] for c, r_ in zip(cons, alloc["constraints"])}})
    for r in rows:
        r["pareto"] = not any(o is not r and o["mass_kg"] is not None and r["mass_kg"] is not None
                              and o["mass_kg"] <= r["mass_kg"] and o["predicted_yield"] >= r["predicted_yield"]
                              and (o["mass_kg"] < r["mass_kg"] or o["predicted_yield"] > r["predicted_yield"])
                              for o in rows)
    return rows
