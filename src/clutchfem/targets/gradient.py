"""Design to targets by a gradient method: a trust-region SQP on the smooth answers of morphed
meshes, forward-difference derivatives evaluated as one parallel batch per iteration.

Why this can work (issue 21).  The pattern search of :mod:`.optimization` exists because
answers of remeshed designs jump by ~0.5 % between neighbours.  On meshes *morphed* from one
reference design (:mod:`clutchfem.mesh.morph`) the engagement and mass vary smoothly (finite
difference scatter 0-0.15 %, slip 0.1-0.9 %: BENCHMARKS.md "Robust design"), which is what a
model of the answers needs.

Problem, in normalised coordinates x in [0, 1] over each free parameter's range::

    minimise   f(x) = mass(x) / mass(x0)              (or -torque margin / |margin(x0)|)
    subject to c_j(x) = slack_j(x) / limit_j >= 0     (the targets of :class:`.Targets`)

except that a safety factor S >= L enters as 1 - L / S >= 0: S = yield / stress is the
inverse of a near-linear answer, so its linearisation misleads far from the limit (concept
4's defaults: S = 0.59, dS/d clearance = -0.45 /mm, while the clearance that gives S = 1.66
is only 0.37 mm smaller).

Step (an S-l1-QP trust-region method, Fletcher 1987, ch. 14): at x, with the derivatives,
solve (scipy's SLSQP on the analytic model, no analysis)

    min_d  g.d + d.B.d / 2 + rho sum_j s_j   s.t.  c + J d + s >= 0,  s >= 0,  |d|_inf <= Delta,

B a damped-BFGS model of the Lagrangian's curvature (Powell 1978), rho >= twice the largest
multiplier.  The step is accepted when the l1 merit f + rho sum max(0, -c_j) falls by at least
0.1 of the model's prediction; Delta doubles (at most 1/4 of the ranges) when the model was
good, halves otherwise; the search stops when Delta < 1/500 of the ranges, when the model
predicts no gain, or at the budget of designs (``max_evals``, refusals included).  The
infeasible start needs no phase 1: the l1 term walks to feasibility first.

The concept's rules (a refused design, e.g. concept 4's beam that must end below its shoe)
are *learned*: where a step's design is refused on a free parameter, the admissible end of
that parameter is found by bisection of the rule check alone (no analysis, no design counted)
and linearised in the others; the subproblem gets it as a constraint and is solved again (a
curved rule: a new cut where the step crosses it).

Derivatives: forward differences at the steps of :func:`.sensitivity.step_for` (0.01 mm,
0.01 deg, 1e-3 of a dimensionless value; the backward step where a rule refuses the forward
one), n designs per iteration in one batch on the study engine.  Morph reference: every iterate is the reference of its own
step -- the iterate on its own mesh, its difference quotients and the trial step morphed from
it -- so all a step compares shares one mesh topology (measured on concept 4: a trial meshed
from scratch instead read the safety factor's stress 0.8-0.9 % off the model, which a fixed
reference far behind the iterate caused, and the trust region collapsed on that noise).

The answer is the lightest feasible design seen, evaluated once more on a mesh made from
scratch (as ``analyze --set`` makes it); if the morph-to-scratch difference (within the
discretisation error, of order 0.05 %) puts it out of a target, it is moved back by a
linearised repair step (at most three).  Every design is kept in the path (phases ``start``,
``base`` for an iterate on its own mesh, ``line`` for the trial steps, ``fd``, ``verify``,
``repair``).

Measured on concept 4 from its defaults (BENCHMARKS.md "Design to targets, gradient"): the
method walks from infeasibility 0.64 to ~0.13 within 4-6 gradients (60-80 designs) and then
stalls on the corner of three of the concept's rules (flexure length bounded from above and
below, flexure angle from below), without a feasible design; ``method="auto"`` then hands the
best design to the pattern search.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..core import ParameterError
from ..core import values as V
from ..evaluation import EvalSettings, evaluate_many, step_for
from .rules import admissible_step, rule
from .sqp import bfgs, merit, repair_step
from .targets import Targets

#: the value grid of the continuous search (SI): 0.1 um, 1e-4 deg, 1e-6 of a dimensionless value
GRID = {"m": 1e-7, "deg": 1e-4}
GRID_REL = 1e-6
#: trust region (share of each range): start, largest, smallest (the stop)
DELTA0, DELTA_MAX, DELTA_MIN = 0.05, 0.25, 2e-3
#: l1 penalty of the merit function at the start (raised to twice the largest multiplier)
RHO = 10.0
#: initial Hessian model (identity times this, in normalised units)
B0 = 0.1
#: stop when the model's predicted merit reduction is below this share of the objective
PRED_TOL = 1e-5
#: re-anchor the morph at the iterate when it is this far from the reference (share of a range)
REANCHOR = 0.02
#: noise of the normalised objective and of each normalised constraint: a step whose merit
#: change is within it is judged by the model (Sun & Nocedal 2023, noise-tolerant trust region)
NOISE_F, NOISE_C = 1e-4, 5e-4
#: a least-violating design this close to the targets (sum of relative violations) is repaired
NEAR = 0.01
#: iterations at most (the design budget usually ends the search first)
MAX_ITER = 100
#: a refused or failed design: every constraint this much below the worst value seen
MISS = -1.0
#: answers constrained through their inverse (a safety factor: the stress it divides)
INVERSE = ("safety_factor", "fatigue_safety_factor")
#: designs kept back from the budget for the check on a mesh made from scratch and its repairs
RESERVE = 4


class Budget(Exception):
    """The design budget is spent."""


@dataclass
class GradientTrace:
    """What :func:`gradient_search` returns."""

    best: dict | None
    path: list = field(default_factory=list)
    counts: dict = field(default_factory=dict)
    iterations: int = 0
    message: str = ""
    anchors: int = 1


def _grid(P, name: str, value: float) -> float:
    g = GRID.get(P.unit(name), GRID_REL)
    return V.round12(round(value / g) * g)


class Evaluator:
    """Designs at normalised points, with the morph anchor, a cache, the budget and the path."""

    def __init__(self, settings: EvalSettings, targets: Targets, space, max_evals: int, log=None):
        self.settings, self.targets, self.space, self.max_evals, self.log = settings, targets, space, max_evals, log
        #: the user's budget (the search itself keeps RESERVE designs back for the final check)
        self.budget = max_evals + RESERVE
        self.P = space.P
        self.path: list[dict] = []
        self.counts = {"ok": 0, "refused": 0, "failed": 0, "crashed": 0, "timeout": 0}
        self.cache: dict[tuple, dict] = {}
        self.anchor: tuple | None = None
        self.anchor_x = np.zeros(len(space.names))
        self.anchors = 0
        #: rule checks of the step bisection (no analysis; not counted as designs)
        self.rule_checks = 0
        self.f0: float | None = None
        #: the least constraint value seen (refused designs are given less)
        self.worst = 0.0
        self.t0 = time.perf_counter()

    # -- points ------------------------------------------------------------------------
    def values(self, x: np.ndarray) -> dict:
        sp = self.space
        return {n: _grid(self.P, n, sp.lo[k] + float(np.clip(x[k], 0.0, 1.0)) * (sp.hi[k] - sp.lo[k]))
                for k, n in enumerate(sp.names)}

    def refused(self, x: np.ndarray) -> str | None:
        """The parameter a rule of the concept refuses at ``x`` (None: admitted); no analysis."""
        try:
            self.settings.params(self.texts(self.values(x)))
        except ParameterError as exc:
            return exc.name
        return None

    def grid_x(self, x: np.ndarray) -> np.ndarray:
        """``x`` moved onto the value grid (the point actually evaluated)."""
        sp, vals = self.space, self.values(x)
        return np.array([(vals[n] - sp.lo[k]) / (sp.hi[k] - sp.lo[k]) for k, n in enumerate(sp.names)])

    def texts(self, vals: dict) -> dict:
        return {n: V.exact_text(self.P, n, v) for n, v in vals.items()}

    def anchor_of(self, vals: dict) -> tuple:
        """The morph reference of the design with free values ``vals``."""
        return tuple(sorted(self.settings.values(self.texts(vals)).items()))

    def set_anchor(self, vals: dict, x: np.ndarray, row: dict | None = None) -> None:
        """Morph from the design ``vals`` (normalised ``x``) on; ``row``: its answers on its own
        mesh, already known (a design meshed from scratch), kept as the new reference's."""
        self.anchor, self.anchor_x = self.anchor_of(vals), np.array(x, dtype=float)
        self.anchors += 1
        if row is not None:
            self.cache[(self.anchor, tuple(sorted(self.texts(vals).items())))] = row

    # -- evaluation --------------------------------------------------------------------
    def n(self) -> int:
        return sum(self.counts.values())

    def run(self, points: list[dict], phase: str, it: int, fresh: bool = False) -> list[dict]:
        """Rows of ``points`` (value dicts), morphed from the anchor (``fresh``: from scratch);
        one parallel batch of those not seen before."""
        es = self.settings if fresh else dataclasses.replace(self.settings, morph=self.anchor)
        keys = [(None if fresh else self.anchor, tuple(sorted(self.texts(p).items()))) for p in points]
        new, seen = [], set()
        for p, k in zip(points, keys):
            if k not in self.cache and k not in seen:
                seen.add(k)
                new.append((k, self.texts(p)))
        if new and self.n() + len(new) > self.max_evals:
            raise Budget()
        if new:
            for (k, _), r in zip(new, evaluate_many([t for _, t in new], es)):
                r["assessment"] = self.targets.assess(r)
                r["phase"], r["iteration"], r["n"] = phase, it, len(self.path)
                r["morph_anchor"] = not fresh
                self.counts[r["status"]] = self.counts.get(r["status"], 0) + 1
                self.path.append(r)
                self.cache[k] = r
        return [self.cache[k] for k in keys]

    def fc(self, row: dict) -> tuple[float, np.ndarray]:
        """(objective, constraint vector) of a row (module docstring)."""
        a = row["assessment"]
        m = len(self.targets.constraints())
        if not math.isfinite(a["h"]):  # refused or failed: worse than every design seen (a barrier)
            return (self.f0 if self.f0 is not None else 1.0), np.full(m, min(self.worst, 0.0) + MISS)
        f = a["objective"]
        if self.f0 is None:
            self.f0 = abs(f) or 1.0
        c = np.array([constraint_value(c, min(self.worst, 0.0) + MISS) for c in a["constraints"]])
        self.worst = min(self.worst, float(np.min(c))) if c.size else self.worst
        return f / self.f0, c

    def elapsed(self) -> str:
        return f" [{self.n()} of at most {self.budget} designs, {time.perf_counter() - self.t0:.0f} s]"


def gradient_search(settings: EvalSettings, targets: Targets, space, x0: np.ndarray, max_evals: int,
                    log=None) -> GradientTrace:
    """The trust-region SQP from ``x0`` (normalised) within ``max_evals`` designs (module docstring)."""
    ev = Evaluator(settings, targets, space, max(1, max_evals - RESERVE), log)
    P, names = space.P, space.names
    span = space.hi - space.lo
    ev.set_anchor(ev.values(x0), x0)
    state = {"it": 0, "jac_x": None, "grad": None}
    msg = ""

    def row_at(x, phase="line"):
        return ev.run([ev.values(x)], phase, state["it"])[0]

    def gradients(x):
        key = tuple(np.round(x, 12))
        if state["jac_x"] == key:
            return state["grad"]
        state["it"] += 1
        vals = ev.values(x)
        base = ev.run([vals], "base", state["it"])[0]
        if base.get("mesh_morphed") == 0 and ev.anchor != ev.anchor_of(vals):
            ev.set_anchor(vals, x, base)  # meshed from scratch: its own mesh is the new reference, free
        elif float(np.max(np.abs(x - ev.anchor_x))) > REANCHOR:
            ev.set_anchor(vals, x)  # far from the reference: the iterate on its own mesh (one design)
            base = ev.run([vals], "base", state["it"])[0]
        f_b, c_b = ev.fc(base)
        pts, hs = [], []
        for n in names:
            h = step_for(P, n, vals[n])
            hs.append(h)
            pts += [dict(vals, **{n: V.round12(vals[n] + h)}), dict(vals, **{n: V.round12(vals[n] - h)})]
        # forward points first; the backward one only where the forward one is refused
        fwd = ev.run(pts[0::2], "fd", state["it"])
        need = [k for k, r in enumerate(fwd) if r["status"] != "ok"]
        bwd = dict(zip(need, ev.run([pts[2 * k + 1] for k in need], "fd", state["it"]))) if need else {}
        rows = [bwd.get(k, r) for k, r in enumerate(fwd)]
        signs = [-1.0 if k in bwd else 1.0 for k in range(len(fwd))]
        m = len(c_b)
        gf, gc = np.zeros(len(names)), np.zeros((m, len(names)))
        for k, (r, s, h) in enumerate(zip(rows, signs, hs)):
            if r["status"] != "ok" or not math.isfinite(r["assessment"]["h"]):
                continue  # both sides refused: this direction's derivative is taken as 0
            f_r, c_r = ev.fc(r)
            dxn = s * h / span[k]
            gf[k] = (f_r - f_b) / dxn
            gc[:, k] = (c_r - c_b) / dxn
        state["jac_x"], state["grad"] = key, (gf, gc, f_b, c_b)
        if log:
            log(f"iteration {state['it']}: " + _describe(base) + ev.elapsed())
        return state["grad"]

    x = ev.grid_x(np.clip(x0, 0.0, 1.0))
    nx = len(names)
    try:
        row = row_at(x, "start")
        msg = _sqp(ev, x, row, gradients, row_at, nx, log)
    except Budget:
        msg = f"stopped at the budget of {max_evals} designs"
    best = _best(ev.path)
    trace = GradientTrace(best=best, path=ev.path, counts=ev.counts, iterations=state["it"], message=msg,
                          anchors=ev.anchors)
    if best is not None and best["assessment"]["h"] <= NEAR:
        trace.best = _verify(ev, best, state, log)
    return trace


def constraint_value(c: dict, miss: float) -> float:
    """The normalised constraint value of an assessed constraint (module docstring): the
    relative slack, or for a safety factor S >= L the slack of the stress it stands for,
    1 - L / S (a stress is near-linear in the parameters where S, its inverse, is not)."""
    if not math.isfinite(c["slack"]):
        return miss if c["slack"] < 0 else 1.0
    if c["key"] in INVERSE and c["sense"] == ">=":
        v = c["value"]
        return 1.0 - c["limit"] / v if v > 0 else miss
    return c["slack"] / c["limit"]


def _sqp(ev: Evaluator, x: np.ndarray, row: dict, gradients, row_at, nx: int, log) -> str:
    """The trust-region SQP loop with the l1 merit (module docstring); returns its stop reason."""
    f, c = ev.fc(row)
    if not math.isfinite(row["assessment"]["h"]):
        return f"the start design could not be evaluated: {row.get('message', row['status'])}"
    g, J, f, c = gradients(x)  # (the values on the iterate's own mesh)
    B = np.eye(nx) * B0
    delta, rho = DELTA0, RHO
    rules: dict = {}
    for _ in range(MAX_ITER):
        d, lam = admissible_step(ev, g, J, c, B, x, delta, rho, rules)
        pred = merit(f, c, rho) - (f + g @ d + 0.5 * d @ B @ d + rho * np.sum(np.maximum(0.0, -(c + J @ d))))
        if pred <= PRED_TOL * max(1.0, abs(f)):
            return f"converged: the model predicts no further gain (trust region {delta:.3g} of the ranges)"
        xt = ev.grid_x(np.clip(x + d, 0.0, 1.0))
        if np.array_equal(xt, x):
            return "converged: the step vanished on the value grid (at the concept's rules or the bounds)"
        rt = row_at(xt)
        if not math.isfinite(rt["assessment"]["h"]):  # refused or failed: a smaller step
            delta = 0.5 * float(np.max(np.abs(d)))
        else:
            ft, ct = ev.fc(rt)
            noise = NOISE_F + rho * NOISE_C * len(c)  # the merit's own noise (module docstring)
            ratio = (merit(f, c, rho) - merit(ft, ct, rho) + noise) / (pred + noise)
            step = float(np.max(np.abs(xt - x)))
            if ratio < 0.1:  # a second-order correction (the Maratos effect of the l1 merit)
                xs = _soc(ev, ct, J, xt, x, delta)
                rs = None if xs is None else row_at(xs)
                if rs is not None and math.isfinite(rs["assessment"]["h"]):
                    fs, cs = ev.fc(rs)
                    rs_ratio = (merit(f, c, rho) - merit(fs, cs, rho) + noise) / (pred + noise)
                    if rs_ratio >= 0.1:
                        xt, ratio, step = xs, rs_ratio, float(np.max(np.abs(xs - x)))
            if ratio >= 0.1:
                gt, Jt, ft, ct = gradients(xt)
                B = bfgs(B, xt - x, (gt - Jt.T @ lam) - (g - J.T @ lam))
                x, f, c, g, J = xt, ft, ct, gt, Jt
                rules = {key: rule(ev, x, *key) for key in rules}  # re-linearised at the new iterate
                if ratio > 0.75 and step >= 0.8 * delta:
                    delta = min(2.0 * delta, DELTA_MAX)
            else:
                delta = 0.5 * step
        if lam.size and np.max(lam) > 0.5 * rho and np.all(c + J @ d >= -1e-9):
            rho = 2.0 * float(np.max(lam))  # (with a slack in use the multiplier is rho itself)
        if delta < DELTA_MIN:
            return f"converged: trust region below {DELTA_MIN:g} of the ranges"
    return f"stopped after {MAX_ITER} iterations"


def _soc(ev: Evaluator, ct: np.ndarray, J: np.ndarray, xt: np.ndarray, x: np.ndarray, delta: float):
    """The second-order correction of a rejected step to ``xt``: the shortest move from xt that
    meets the linearised targets there (c(xt) + J p >= 0), inside the trust box around x and
    the rules; None where there is none."""
    if np.all(ct >= 0):
        return None
    p = repair_step(ct, J, xt, margin=0.0, lo=np.maximum(x - delta, 0.0) - xt, hi=np.minimum(x + delta, 1.0) - xt)
    if p is None:
        return None
    xs = ev.grid_x(np.clip(xt + p, 0.0, 1.0))
    return None if ev.refused(xs) is not None or np.array_equal(xs, xt) else xs


def _best(path: list[dict]) -> dict | None:
    ok = [r for r in path if math.isfinite(r["assessment"]["h"])]
    feas = [r for r in ok if r["assessment"]["h"] <= 0]
    if feas:
        return min(feas, key=lambda r: r["assessment"]["objective"])
    near = [r for r in ok if r["assessment"]["h"] <= NEAR]  # the lightest nearly feasible one is repaired
    if near:
        return min(near, key=lambda r: r["assessment"]["objective"])
    return min(ok, key=lambda r: r["assessment"]["h"]) if ok else None


def _verify(ev: Evaluator, best: dict, state: dict, log) -> dict:
    """The chosen design on a mesh made from scratch; a linearised repair step (at most three)
    where the morph-to-scratch difference puts it out of a target."""
    vals = ev.settings.values(best["params"])
    x = np.array([(vals[n] - ev.space.lo[k]) / (ev.space.hi[k] - ev.space.lo[k]) for k, n in enumerate(ev.space.names)])
    ev.max_evals += RESERVE  # the designs kept back for this step
    fresh: list[dict] = []
    try:
        row = ev.run([ev.values(x)], "verify", state["it"], fresh=True)[0]
        fresh.append(row)
        for _ in range(RESERVE - 1):
            if row["assessment"]["h"] <= 0 or state["grad"] is None or not math.isfinite(row["assessment"]["h"]):
                break
            _, c = ev.fc(row)
            dx = repair_step(c, state["grad"][1], x)  # (the last iterate's derivatives)
            if dx is None:
                break
            x = ev.grid_x(np.clip(x + dx, 0.0, 1.0))
            row = ev.run([ev.values(x)], "repair", state["it"], fresh=True)[0]
            fresh.append(row)
            if log:
                log("repair step (the design on a mesh made from scratch missed a target): " + _describe(row))
    except Budget:
        pass
    ok = [r for r in fresh if math.isfinite(r["assessment"]["h"])]
    feas = [r for r in ok if r["assessment"]["h"] <= 0]
    if feas:
        return min(feas, key=lambda r: r["assessment"]["objective"])
    return min(ok, key=lambda r: r["assessment"]["h"]) if ok else best


def _describe(row: dict) -> str:
    a = row["assessment"]
    if row.get("mass_kg") is None:
        return f"{row['status']}: {row.get('message', '')}"
    worst = min((c["slack"] / c["limit"] for c in a["constraints"] if math.isfinite(c["slack"])), default=0.0)
    state = "feasible" if a["h"] <= 0 else f"infeasible (h = {a['h']:.4f})"
    return f"{state}, mass {row['mass_kg'] * 1e3:.2f} g, least slack {100 * worst:+.2f} % of its limit"
