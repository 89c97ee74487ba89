"""The search of :mod:`.live` on the reduced model's answers: the live problem (objective and
target slacks at the live answer's conservative edge), the concept's rules as a constraint,
SLSQP from several starts (robust: an order statistic of Monte Carlo parts), and the final
design put on the ``--set`` grid."""

from __future__ import annotations

import itertools

import numpy as np

from ..core import ClutchfemError, ParameterError
from ..core import values as V
from .targets import Targets

__all__ = ["MARGIN", "SOURCE", "STEP", "LiveProblem", "RuleConstraint", "live_answers", "on_grid", "order_slack",
           "parts_slack", "rebind", "set_texts", "shifted_search", "slsqp_search"]

#: the search's constraints hold with this relative margin (SLSQP ends within its tolerance)
MARGIN = 1e-6
#: forward-difference step of the gradients, in unit-box coordinates
STEP = 1e-5
#: rounds of the shifted deterministic searches that back up the robust search (SORA)
SHIFT_ROUNDS = 8
#: the model answer of each constrained answer
SOURCE = {"engagement_rpm_with_ripple": "engagement_rpm_with_ripple", "slip_rpm": "slip_rpm",
          "safety_factor": "max_von_mises_Pa", "fatigue_safety_factor": "fatigue_safety_factor"}


class LiveProblem:
    """The live answers of the search: objective and constraint slacks at the conservative edge."""

    def __init__(self, model, targets: Targets, free_idx, u0, ys: float, max_torque: float):
        self.model, self.targets, self.free, self.u0 = model, targets, list(free_idx), np.asarray(u0, float)
        self.ys, self.max_torque = ys, max_torque
        self.cons = targets.constraints()
        need = {SOURCE[k] for _, k, _, _ in self.cons}
        need |= {"mass_kg"} if targets.objective == "mass" else {"torque_at_max_engine_torque_Nm"}
        missing = [a for a in sorted(need) if a not in model.models]
        if missing:
            raise ParameterError("fidelity", "live", f"targets the reduced model answers (it has no model of "
                                 f"{', '.join(missing)}: --fidelity best)", "optimize")
        self.need = need
        self.evals = 0

    def full(self, X) -> np.ndarray:
        """Unit-box points of the whole region from the free coordinates ``X`` (m, k)."""
        X = np.atleast_2d(X)
        U = np.repeat(self.u0[None, :], len(X), axis=0)
        U[:, self.free] = X
        return U

    def answers(self, U) -> tuple[dict, dict]:
        """(value, relative band) of the needed answers at the unit-box points ``U``."""
        self.evals += len(U)
        p = self.model.predict(U, answers=self.need)
        val = {a: p["value"][a] for a in self.need}
        rel = {a: np.abs(p["band"][a] / val[a]) for a in self.need}
        return val, rel

    def slacks(self, val: dict, rel: dict) -> np.ndarray:
        """(m, constraints): each target's relative slack at the conservative edge (NaN -> -1:
        a missing answer misses its target)."""
        cols = []
        for _, key, limit, sense in self.cons:
            v, r = val[SOURCE[key]], rel[SOURCE[key]]
            if key == "safety_factor":
                edge = self.ys / (v * (1.0 + r))
            else:
                edge = v * (1.0 - r) if sense == ">=" else v * (1.0 + r)
            s = (edge - limit) / limit if sense == ">=" else (limit - edge) / limit
            cols.append(np.where(np.isfinite(s), s, -1.0))
        return np.array(cols).T if cols else np.zeros((len(next(iter(val.values()))), 0))

    def objective(self, val: dict, rel: dict) -> np.ndarray:
        if self.targets.objective == "mass":
            return val["mass_kg"]
        t = val["torque_at_max_engine_torque_Nm"]
        return -(t * (1.0 - rel["torque_at_max_engine_torque_Nm"]) - self.max_torque)

    def with_jac(self, x) -> tuple:
        """(objective, slacks, their gradients) at the free coordinates ``x``: one vectorised
        call over x and its forward steps, the band held at x's own."""
        k = len(x)
        X = np.repeat(np.asarray(x, float)[None, :], k + 1, axis=0)
        X[1:] += STEP * np.eye(k)
        val, rel = self.answers(self.full(X))
        rel0 = {a: np.full(k + 1, r[0]) for a, r in rel.items()}
        f, g = self.objective(val, rel0), self.slacks(val, rel0)
        return f[0], g[0], (f[1:] - f[0]) / STEP, (g[1:] - g[0]) / STEP


class RuleConstraint:
    """The concept's rules as a constraint of the search: 0 where they admit the design at x
    (with a tolerance box: at every corner of it), else minus the distance (unit-box
    coordinates) from x back to the last admitted point on the segment from the start ``xs``.
    A probe costs ~0.3 ms (quiet: a refusal states no limit), the distance a bisection of
    ~20 probes per corner, measured only where the search steps beyond the rules."""

    def __init__(self, P, base: dict, names, lo_si, w_si, xs, box=None):
        self.P, self.base, self.names, self.lo_si, self.w_si = P, dict(base), list(names), lo_si, w_si
        self.box = list(box or [])
        self.corners = list(itertools.product((1.0, -1.0), repeat=len(self.box)))
        self.xs = np.asarray(xs, float)
        self.active = self.admits(self.xs)  # a start the rules refuse: no segment to measure along

    def admits(self, x) -> bool:
        vals = dict(self.base)
        vals.update({n: float(self.lo_si[j] + x[j] * self.w_si[j]) for j, n in enumerate(self.names)})
        for i, sg in enumerate(self.corners):
            c = dict(vals)
            for (n, t), g in zip(self.box, sg):
                c[n] = vals[n] + g * t
            if not self.P.admits(c):
                if i:  # the corner that refused is asked first next time (one rule binds: half the probes)
                    self.corners.insert(0, self.corners.pop(i))
                return False
        return True

    def slack(self, x) -> float:
        x = np.asarray(x, float)
        if not self.active or self.admits(x):
            return 0.0
        v = x - self.xs
        L = float(np.linalg.norm(v))
        a, b = 0.0, 1.0
        while (b - a) * L > 1e-6:
            m = 0.5 * (a + b)
            a, b = (m, b) if self.admits(self.xs + m * v) else (a, m)
        return -(1.0 - a) * L


def parts_slack(prob: LiveProblem, U: np.ndarray) -> np.ndarray:
    """Each part's worst relative slack at its band's edge (-1: outside the region)."""
    val, rel = prob.answers(U)
    m = prob.slacks(val, rel).min(axis=1) if prob.cons else np.zeros(len(U))
    inside = np.all((U >= -1e-9) & (U <= 1 + 1e-9), axis=1)
    return np.where(inside, m, -1.0)


def order_slack(prob: LiveProblem, x, D: np.ndarray, k_out: int) -> float:
    """The (k_out+1)-th smallest part slack at the free coordinates ``x``: >= 0 when at most
    ``k_out`` of the parts ``D`` miss a target (the robust search's constraint)."""
    m = parts_slack(prob, prob.full(x)[0] + D)
    return float(np.partition(m, k_out)[k_out])


def shifted_search(prob: LiveProblem, lo, hi, starts, D: np.ndarray, k_out: int, log=None,
                   rules: RuleConstraint | None = None, margin=MARGIN) -> tuple[np.ndarray, dict]:
    """The robust search's back-up when SLSQP on the parts' order statistic (a kinked function
    of the design: the part that sets it changes) ends short of the yield: sequential
    deterministic searches with shifted limits (SORA, Du and Chen 2004).  At the last design
    each target's shift is how far its (k_out+1)-th smallest part slack lies below its nominal
    slack; the deterministic search runs again with those margins (never smaller than the
    last round's) from the last design (the first round also from the other ``starts``), until
    the parts hold the order statistic and the shifts no longer grow; where the shifts stop
    growing short of it (every target holds on its own but not all at once, or ``margin`` asks
    for more), they grow by a quarter plus the shortfall.  (the lightest design whose
    parts hold the order statistic >= ``margin`` and the rules admit, else the one nearest to
    it; what it did)."""
    inside = np.all  # (the parts outside the region miss: parts_slack's -1)

    def drop_at(x):
        U = prob.full(x)[0] + D
        val, rel = prob.answers(prob.full(x))
        vp, rp = prob.answers(U)
        sp = prob.slacks(vp, rp)
        sp[~inside((U >= -1e-9) & (U <= 1 + 1e-9), axis=1)] = -1.0
        q = np.partition(sp, k_out, axis=0)[k_out]
        return np.maximum(prob.slacks(val, rel)[0] - q, 0.0)

    x = np.clip(np.asarray(starts[0], float), lo, hi)
    shift = drop_at(x)
    best, nearest, tried = None, None, list(starts)
    forced, g_last = False, -np.inf
    for it in range(1, SHIFT_ROUNDS + 1):
        x, _ = slsqp_search(prob, lo, hi, tried, log=log, rules=rules, margin=margin + shift)
        tried = [x]
        g = order_slack(prob, x, D, k_out)
        f = float(prob.with_jac(x)[0])
        if log:
            log(f"live search, shifted round {it}: the parts' order statistic {g:+.3g} (relative slack), "
                f"shifts {', '.join(f'{k} {v:.3g}' for (_, k, _, _), v in zip(prob.cons, shift))}")
        if g >= margin and (rules is None or not rules.active or rules.admits(x)) and (best is None or f < best[1]):
            best = (x.copy(), f)
        if nearest is None or g > nearest[1]:
            nearest = (x.copy(), g)
        d = drop_at(x)
        grew = bool(np.any(d > shift + 1e-4))
        if (g >= margin and not grew) or (forced and g <= g_last + 1e-7):  # held; or more shift gains nothing
            break
        forced, g_last = not grew, g
        # the shifts no longer grow and the parts still fall short (each target holds alone, not
        # all at once; or the margin asked is more than the shifts give): a quarter more, plus
        # the shortfall
        shift = np.maximum(shift, d) if grew else 1.25 * shift + (margin - g)
    x = best[0] if best is not None else nearest[0]
    return x, {"shifted_rounds": it, "shifted_feasible": best is not None,
               "shifts_rel": {k: float(v) for (_, k, _, _), v in zip(prob.cons, shift)}}


def slsqp_search(prob: LiveProblem, lo, hi, starts, D=None, k_out: int = 0, log=None, rules: RuleConstraint | None = None,
            margin=MARGIN) -> tuple[np.ndarray, dict]:
    """SLSQP from each start; (best x, what it found).  ``D``: the parts' unit-box deviations
    (robust: the (k_out+1)-th smallest part slack >= MARGIN), else every slack >= MARGIN;
    ``rules``: the concept's rules as one more constraint."""
    from scipy.optimize import minimize

    cache: dict = {}
    rcache: dict = {}

    def rule(x):
        key = np.asarray(x, float).tobytes()
        if key not in rcache:
            h = 1e-3
            r0 = rules.slack(x)
            g = (np.zeros(len(x)) if r0 == 0.0 else  # beyond the rules only: forward differences of the distance
                 np.array([(rules.slack(np.asarray(x, float) + h * e) - r0) / h for e in np.eye(len(x))]))
            rcache.clear()
            rcache[key] = (r0, g)
        return rcache[key]

    def at(x):
        key = np.asarray(x, float).tobytes()
        if key not in cache:
            f, g, df, dg = prob.with_jac(x)
            if D is not None:  # the order statistic of the parts' slacks, its gradient the part's that sets it
                U = prob.full(x)[0] + D
                m = parts_slack(prob, U)
                i = int(np.argpartition(m, k_out)[k_out])
                if m[i] > -1.0 and np.all((U[i] >= 0) & (U[i] <= 1)):
                    k = len(x)
                    Xp = np.repeat(U[i][None, :], k + 1, axis=0)
                    Xp[1:, prob.free] += STEP * np.eye(k)
                    val, rel = prob.answers(Xp)
                    rel0 = {a: np.full(k + 1, r[0]) for a, r in rel.items()}
                    mm = prob.slacks(val, rel0).min(axis=1)
                    g, dg = np.array([m[i]]), ((mm[1:] - mm[0]) / STEP)[:, None]
                else:
                    g, dg = np.array([m[i]]), np.zeros((len(x), 1))
            cache.clear()
            cache[key] = (f, g, df, dg)
        return cache[key]

    f0 = abs(at(np.clip(starts[0], lo, hi))[0]) or 1.0
    found = []
    for x0 in starts:
        x0 = np.clip(x0, lo, hi)
        try:
            cons = [{"type": "ineq", "fun": lambda x: at(x)[1] - margin, "jac": lambda x: at(x)[3].T}] \
                if prob.cons else []
            if rules is not None and rules.active:
                cons.append({"type": "ineq", "fun": lambda x: rule(x)[0], "jac": lambda x: rule(x)[1]})
            r = minimize(lambda x: at(x)[0] / f0, x0, jac=lambda x: at(x)[2] / f0, method="SLSQP",
                         bounds=list(zip(lo, hi)), constraints=cons, options={"maxiter": 200, "ftol": 1e-10})
            x = np.clip(r.x, lo, hi)
        except (ValueError, FloatingPointError) as exc:  # a start where the model gives no answer
            if log:
                log(f"live search: a start gave no answer ({exc})")
            continue
        f, g, _, _ = at(x)
        ok_rules = rules is None or not rules.active or rules.admits(x)
        found.append((x, float(f), (float(g.min()) if g.size else 0.0) if ok_rules else -1.0, r.nit))
    if not found:
        raise ClutchfemError("the live search found no point where the reduced model answers")
    feas = [t for t in found if t[2] >= 0.0]
    best = min(feas, key=lambda t: t[1]) if feas else max(found, key=lambda t: t[2])
    return best[0], {"starts": len(starts), "feasible_starts": len(feas), "iterations": sum(t[3] for t in found)}


def on_grid(prob, P, names, x, lo_si, w_si, lo, hi, feasible, log=None) -> tuple[np.ndarray, dict]:
    """``x`` put on the parameters' resolution: the lightest corner of its grid cell that
    ``feasible`` (x -> bool) admits; x itself (exact texts) where none does."""
    res = np.array([V.resolution(P, n) for n in names])
    si = lo_si + x * w_si
    fl = np.floor(si / res + 1e-9) * res
    corners = []
    for c in itertools.product((0, 1), repeat=len(names)):
        v = fl + np.array(c) * res
        xc = (v - lo_si) / w_si
        if np.all(xc >= lo - 1e-12) and np.all(xc <= hi + 1e-12):
            corners.append(xc)
    if corners:
        val, rel = prob.answers(prob.full(np.array(corners)))
        f = prob.objective(val, rel)
        for i in np.argsort(f)[:64]:
            if feasible(corners[i]):
                return corners[i], {"on_grid": True}
    if log:
        log("live search: no corner of the design's resolution cell meets every target; the exact values are kept")
    return x, {"on_grid": False}


def set_texts(P, names, lo_si, w_si, x) -> dict:
    return {n: V.exact_text(P, n, V.round12(float(lo_si[j] + x[j] * w_si[j]))) for j, n in enumerate(names)}


def rebind(prob: LiveProblem, aim: Targets) -> LiveProblem:
    prob.targets, prob.cons = aim, aim.constraints()
    return prob


def live_answers(prob: LiveProblem, val: dict, rel: dict, ys: float) -> dict:
    """The live answers of one design, each with its band and its conservative edge."""
    out = {}
    for a in sorted(prob.need):
        v, r = float(val[a][0]), float(rel[a][0])
        out[a] = {"value": v, "band": abs(v) * r}
    for _, key, _, sense in prob.cons:
        src = out[SOURCE[key]]
        if key == "safety_factor":
            v = ys / src["value"]
            out[key] = {"value": v, "band": v * src["band"] / src["value"],
                        "edge": ys / (src["value"] + src["band"])}
        else:
            out[key] = dict(out.get(key, src))
            out[key]["edge"] = src["value"] - src["band"] if sense == ">=" else src["value"] + src["band"]
    return out
