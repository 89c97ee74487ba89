"""Design to targets on the reduced model: the search on the live answers of a cached region,
the result verified by the full FE.

**Where it searches.**  The cached reduced model whose region holds the start design
(:func:`clutchfem.reduced.find`); none: refused, naming the bounds the start lies outside of
and ``clutchfem reduce`` (a region is 100+ best-path designs: never built inside a search).
The free parameters are the region's (its operating axes, ``mu`` and ``drum_wall``, only when
asked), intersected with the ones given; the search box is the region's box -- for a robust
search inset by the tolerance box (+-4 sigma of a normal tolerance, the tolerance itself of a
uniform one, as :mod:`clutchfem.tolerances.live`), so that every made part stays in the region.

**What it searches.**  The least live mass (or the largest torque margin) subject to the
targets, each live answer taken at its **conservative edge**: value - band for a lower limit,
value + band for an upper one, the safety factor yield / (peak + band); the band is the live
band (:meth:`clutchfem.reduced.ReducedModel.predict`: the best path's band of the nearest
training designs plus the model's own error measured on held-out designs).  SLSQP from several
starts (the start design and a scrambled Sobol sample of the box), its gradients forward
differences of the fitted model in one vectorised call, the band held at the point's own (it
steps where the nearest training designs change); the final design is put on the parameters'
resolution (the ``--set`` grid) at the lightest grid corner that still meets every target.

**Robust** (``tolerances``, ``yield_target``): a Monte Carlo of made parts on the live model
with common random numbers (:data:`PARTS` parts per candidate in one vectorised call; a part
is out of spec when any target is missed at its band's edge, or when it lies outside the
region).  The constraint is the (k+1)-th smallest part slack >= 0 with k = floor((1 - Y) N):
then at most k parts of N are out of spec, a yield >= Y on the sample; an order statistic of
smooth functions is continuous, and its gradient is that of the part that sets it.  The final
yield is also counted on an independent sample of :data:`YIELD_PARTS` parts (a Wilson
interval beside it).

**Verified by the FE** (``check``, default on): the final design through the best path with
its error step (:func:`clutchfem.targets.best_estimate`, as ``analyze --set`` gives it).
Deterministic: where the FE misses a target, that limit moves inward by the miss and the live
model is searched again (at most :data:`ROUNDS` FE checks).  Robust: the yield rests on the
live band, so where an FE answer lies beyond the live band's edge on the unfavourable side,
that limit moves by the excess; at the end ``check_parts`` of the Monte Carlo parts also go
through the FE (the design mesh's answers, corrected by the error step's ratios of the final
design as :func:`clutchfem.tolerance` does) and the agreement is reported.  The verdict is
said as it is: met, or missed by so much in the FE check.

A final design on a face of the search box is flagged: the optimum may lie outside the region,
and a region built around it (the command is given) would let the search go on.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from ..analysis import Requirements
from ..core import ClutchfemError, ParameterError, wilson
from ..core import values as V
from ..evaluation import evaluate_many, shared_cluster
from ..loadcase import Design
from ..reduced import OPERATING_AXES, find, outside_why
from .best_check import analysed_answers, best_estimate, confirmed, correction_ratios
from .live_search import (
    MARGIN,
    SOURCE,
    LiveProblem,
    RuleConstraint,
    live_answers,
    on_grid,
    order_slack,
    parts_slack,
    rebind,
    set_texts,
    shifted_search,
    slsqp_search,
)
from .result import OptimizationResult
from .targets import DIMENSIONLESS, Targets

__all__ = ["ANSWERED_BY", "CHECK_PARTS", "PARTS", "ROUNDS", "YIELD_PARTS", "live_model", "live_optimize"]

#: what answered a live optimisation's design
ANSWERED_BY = "reduced model (searched), FE (verified)"
#: Monte Carlo parts per candidate of a robust search (common random numbers)
PARTS = 1000
#: parts of the independent sample the final yield is counted on
YIELD_PARTS = 10000
#: parts of a robust result also through the FE (the agreement reported)
CHECK_PARTS = 8
#: FE checks at most (each after one search of the live model)
ROUNDS = 3
#: deterministic SLSQP starts (the start design and a Sobol sample); a robust search: half
STARTS = 8
#: a normal tolerance's parts are kept within this many sigmas by the inset box (the tolerance is 3)
SIGMAS = 4.0
#: a free parameter this share of the search box's width from a face is on the bound
EDGE = 1e-3


def live_model(settings, *, fe_engine=None):
    """(reduced model, live design) of the start design of ``settings`` (an
    :class:`~clutchfem.evaluation.EvalSettings`): the cached model whose region holds it, or a
    ParameterError naming the bounds it lies outside of and ``clutchfem reduce``."""
    op = settings.operating_point().replace(fidelity="live")
    design = Design.from_concept(settings.concept, settings.params(), op, settings.mesh_settings())
    engine = settings.curve if settings.curve is not None else (settings.engine() if settings.engine_csv else None)
    req = Requirements(a=settings.a, b=settings.b)
    model = find(design, engine=engine, requirements=req)
    if model is None:
        sets = " ".join(f"--set {a}" for a in settings.base)
        raise ParameterError("fidelity", "live", f"a start design a cached reduced model holds: {design.label} is "
                             f"{outside_why(design, engine=engine, requirements=req)}; `clutchfem reduce "
                             f"{settings.concept} {sets}`".rstrip() + " builds a region around it (100+ best-path "
                             "designs, minutes), or --fidelity best searches on the FE", "optimize")
    return model, design


def live_optimize(settings, targets: Targets, free=None, *, tolerances: dict | None = None, dist: str = "normal",
                  yield_target: float | None = None, parts: int = PARTS, check: bool = True,
                  check_parts: int = CHECK_PARTS, seed: int = 1, workers: int | None = 0, scheduler: str | None = None,
                  log=None):
    """The design that meets ``targets`` at least live mass (or largest live torque margin),
    searched on the cached reduced model whose region holds the start design of ``settings``
    and verified by the full FE (module docstring); with ``tolerances`` (name -> SI half-width)
    and ``yield_target``, every target met by that share of made parts on the live model.

    Parameters
    ----------
    settings : EvalSettings
        The start design (its best-path evaluation: the FE the region stands for).
    targets : Targets
        The targets (limits in rpm, factors dimensionless).
    free : list of str, optional
        The free parameters (default: the region's shape parameters); intersected with the
        region's.
    tolerances, dist, yield_target, parts
        The robust search: SI half-widths, normal (+-3 sigma) or uniform, the share of parts
        in spec, the Monte Carlo parts per candidate.
    check : bool
        Verify the final design with the full FE (and search again where it misses).
    check_parts : int
        Robust: Monte Carlo parts also through the FE at the final design.
    seed : int
        The parts' random numbers.
    workers, scheduler
        The study engine of the robust FE parts check (``workers=0``: in this process).
    log : callable, optional
        One line of progress per step.

    Returns
    -------
    OptimizationResult
        ``answered_by`` :data:`ANSWERED_BY` (or ``"reduced model"`` unverified), ``live``: the
        region, the live answers and edges, the rounds, the counts and the FE verification.

    Examples
    --------
    A start no cached region holds is refused, naming what builds one:

    >>> import os, tempfile, clutchfem as cf
    >>> from clutchfem.evaluation import EvalSettings
    >>> from clutchfem.targets.live import live_optimize
    >>> os.environ["CLUTCHFEM_CACHE"] = tempfile.mkdtemp()      # an empty cache
    >>> s = EvalSettings("concept1")
    >>> live_optimize(s, cf.Targets.defaults(s))
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: ...
    """
    t0 = time.perf_counter()
    for name, v, lo_, hi_ in (("parts", parts, 100, 100000), ("check_parts", check_parts, 0, 1000)):
        if isinstance(v, bool) or not isinstance(v, int) or not lo_ <= v <= hi_:
            raise ParameterError(name, v, f"an integer in [{lo_}, {hi_}]", "optimize --fidelity live")
    robust = bool(tolerances)
    if robust and not (isinstance(yield_target, (int, float)) and 0.5 < yield_target < 1.0):
        raise ParameterError("yield", yield_target, "a share of parts in (0.5, 1), e.g. 0.99", "optimize")
    if dist not in ("normal", "uniform"):
        raise ParameterError("dist", dist, "normal or uniform", "optimize")
    model, design = live_model(settings)
    reg = model.region
    P = type(design.params)
    if isinstance(free, str):
        free = [x.strip() for x in free.split(",") if x.strip()]
    asked = list(free) if free else [n for n in reg.names if n not in OPERATING_AXES]
    names = [n for n in asked if n in reg.names]
    left = [n for n in asked if n not in reg.names]
    if not names:
        raise ParameterError("free", ",".join(asked), f"free parameters of the region ({', '.join(reg.names)}): "
                             f"`clutchfem reduce {reg.concept} --free ...` builds a region over others", "optimize")
    idx = [reg.names.index(n) for n in names]
    lo_si = np.array([reg.lo[i] for i in idx])
    w_si = np.array([reg.hi[i] - reg.lo[i] for i in idx])
    u0 = reg.unit_of(reg.design_values(design))
    lo, hi = np.zeros(len(idx)), np.ones(len(idx))
    D = k_out = None
    tol_info = {}
    if robust:
        tols = {n: float(t) for n, t in tolerances.items()}
        for n, t in tols.items():
            if n not in reg.names:
                raise ParameterError(n, t, f"a toleranced dimension the region varies ({', '.join(reg.names)}): "
                                     f"`clutchfem reduce {reg.concept} --free ...,{n}` builds one", "option --tol",
                                     shown=f"+-{_shown(P, n, t)}")
            j = reg.names.index(n)
            inset = (t * SIGMAS / 3.0 if dist == "normal" else t) / (reg.hi[j] - reg.lo[j])
            what = f"+-{SIGMAS:g} sigma" if dist == "normal" else "the tolerance"
            if n in names:
                k = names.index(n)
                lo[k], hi[k] = inset, 1.0 - inset
                if lo[k] > hi[k]:
                    box = _shown(P, n, t * (SIGMAS / 3.0 if dist == "normal" else 1.0))
                    raise ParameterError(n, t, f"a tolerance whose box ({what}: +-{box}) fits in the region's box of "
                                         f"{n} ({reg.describe()}): build a wider region (clutchfem reduce --range "
                                         f"{n}=LO:HI)", "option --tol", shown=f"+-{_shown(P, n, t)}")
            elif not inset <= u0[j] <= 1.0 - inset:
                raise ParameterError(n, t, f"a start whose tolerance box ({what}) lies in the region's box of {n} "
                                     f"({reg.bounds(n)[0]:.6g}..{reg.bounds(n)[1]:.6g})", "option --tol")
        rng = np.random.default_rng(seed)
        tn = list(tols)
        half = np.array([tols[n] for n in tn])

        def draw(n_parts, r):
            d = r.normal(0.0, half / 3.0, (n_parts, len(tn))) if dist == "normal" else r.uniform(-half, half, (n_parts, len(tn)))
            out = np.zeros((n_parts, reg.dim))
            for c, n in enumerate(tn):
                j = reg.names.index(n)
                out[:, j] = d[:, c] / (reg.hi[j] - reg.lo[j])
            return out, d

        D, D_si = draw(parts, rng)
        k_out = int(math.floor((1.0 - yield_target) * parts + 1e-9))
        tol_info = {"tolerances_si": tols, "distribution": dist, "yield_target": yield_target, "parts": parts,
                    "allowed_out_of_spec": k_out}
    ys = float(settings.operating_point().material.yield_strength)
    engine = settings.engine()
    aim = targets
    history, fe_designs, rounds_done = [], 0, 0
    x0 = (u0[idx] - 0.0)
    from scipy.stats import qmc

    n_starts = STARTS if not robust else max(2, STARTS // 2)
    sob = qmc.Sobol(len(idx), scramble=True, seed=seed).random_base2(max(0, math.ceil(math.log2(n_starts - 1))))
    starts0 = [x0] + [lo + s * (hi - lo) for s in sob][: n_starts - 1]
    base_vals = settings.params().model_dump()
    box = list(tolerances.items()) if robust else None
    rules_nominal = RuleConstraint(P, base_vals, names, lo_si, w_si, np.clip(x0, lo, hi))
    rules = RuleConstraint(P, base_vals, names, lo_si, w_si, np.clip(x0, lo, hi), box) if robust else rules_nominal
    prob = None
    x = None
    an = fe = None
    verdict = None
    margins: dict = {}
    while True:
        rounds_done += 1
        prob = LiveProblem(model, aim, idx, u0, ys, float(engine.max_torque)) if prob is None else rebind(prob, aim)
        starts = list(starts0) if x is None else [x] + list(starts0)
        if robust:  # SORA's first cycle as the start: the deterministic optimum on the live model
            # (searched from every start; the robust search, 1000x dearer a step, from it and
            # from the last design only)
            xd, _ = slsqp_search(prob, lo, hi, starts, log=log, rules=rules_nominal)
            starts = [xd, starts[0]]
        x, info = slsqp_search(prob, lo, hi, starts, D, k_out or 0, log, rules=rules)
        if robust and order_slack(prob, x, D, k_out) < MARGIN:  # short of the yield: the shifted searches
            x, more = shifted_search(prob, lo, hi, [x, xd], D, k_out, log, rules=rules)
            info.update(more)
        # room for the resolution grid: each slack's change over one resolution step of every
        # free parameter (its gradient at x), then again from x with that margin
        _, _, _, dg = prob.with_jac(x)
        step = np.array([V.resolution(P, n) for n in names]) / w_si
        snap = np.abs(dg).T @ step if dg.size else np.zeros(0)
        if snap.size:
            room = MARGIN + (float(snap.max()) if robust else snap)
            xr, _ = slsqp_search(prob, lo, hi, [x], D, k_out or 0, log, rules=rules, margin=room)
            if robust and order_slack(prob, xr, D, k_out) < room:  # the kinked statistic again
                xr, _ = shifted_search(prob, lo, hi, [x, xd], D, k_out, log, rules=rules, margin=room)
            x = xr

        def feasible(xc):
            if not rules.admits(xc):
                return False
            if robust:
                m = parts_slack(prob, prob.full(xc)[0] + D)
                return int(np.sum(m < 0)) <= k_out
            val, rel = prob.answers(prob.full(xc))
            return bool(np.all(prob.slacks(val, rel) >= 0))

        x, grid = on_grid(prob, P, names, x, lo_si, w_si, lo, hi, feasible, log)
        texts = set_texts(P, names, lo_si, w_si, x)
        val, rel = prob.answers(prob.full(x))
        live_ans = live_answers(prob, val, rel, ys)
        slack = prob.slacks(val, rel)[0]
        rnd = {"round": rounds_done, "targets_searched": _tdict(aim), "params": texts, "live": live_ans,
               "live_edge_slack_rel": {k: float(s) for (_, k, _, _), s in zip(aim.constraints(), slack)},
               "feasible_live": bool(feasible(x)), **info, **grid}
        if robust:
            m = parts_slack(prob, prob.full(x)[0] + D)
            rnd["yield_live"] = float(np.mean(m >= 0))
        history.append(rnd)
        if log:
            log(f"live round {rounds_done}: " + ", ".join(f"{n}={t}" for n, t in texts.items())
                + f"; live mass {live_ans.get('mass_kg', {}).get('value', math.nan) * 1e3:.2f} g"
                + (f", live yield {rnd['yield_live']:.2%}" if robust else "")
                + ("" if rnd["feasible_live"] else " (NOT feasible on the live model)"))
        if not check:
            break
        try:
            an = best_estimate(settings, texts)
        except ClutchfemError as exc:
            rnd["fe"] = {"error": f"{type(exc).__name__}: {exc}"}
            verdict = f"not verified: the FE (best path with its error step) gave no answer ({exc})"
            fe_designs += 1
            break
        fe_designs += 1
        fe = analysed_answers(an)
        miss = {}
        for _, key, limit, sense in targets.constraints():
            f_ = fe.get(key)
            e = live_ans.get(key, {}).get("edge")
            if f_ is None or e is None:
                continue
            if robust:  # the FE beyond the live band's edge: the parts' yield rests on that band
                x_ = (e - f_) if sense == ">=" else (f_ - e)
            else:  # the FE misses the (user's) limit
                x_ = (limit - f_) if sense == ">=" else (f_ - limit)
            if x_ > 0:
                miss[key] = max(miss.get(key, 0.0), x_)
        missed = confirmed(targets, fe)
        rnd["fe"] = {"answers": fe, "missed_targets": missed, "beyond": miss}
        if not (missed or (robust and miss)) or rounds_done >= ROUNDS:
            break
        for k_, v_ in miss.items():
            margins[k_] = margins.get(k_, 0.0) + v_
        aim = targets.moved_inward(margins)
        if log:
            log("FE check: " + ", ".join(f"{k_} beyond by {v_:.4g}" for k_, v_ in miss.items())
                + ": the live search goes on with those limits moved inward")
    # the result
    try:
        params_texts = V.changed_texts(settings.params(texts), P())
    except ParameterError:  # the least-violating design of a search the rules cut: its texts as they are
        params_texts = {}
    params_texts.update(texts)
    row = {"params": texts, "status": "ok", "answered_by": "reduced model"}
    for k_, a in live_ans.items():
        row[k_] = a["value"]
    row["torque_margin_Nm"] = (row.get("torque_at_max_engine_torque_Nm") or math.nan) - float(engine.max_torque)
    live_assess = aim.assess({**{k_: a.get("edge", a["value"]) for k_, a in live_ans.items()}, "status": "ok",
                              "mass_kg": row.get("mass_kg", math.nan), "torque_margin_Nm": row["torque_margin_Nm"]})
    live_ok = bool(history[-1]["feasible_live"])
    if fe is not None:
        missed = confirmed(targets, fe)
        assessment = targets.assess({**row, **{k_: v for k_, v in fe.items() if v is not None}})
        shortfall = [c for c in assessment["constraints"] if c["violated"]]
        if not missed:
            verdict = "met in the FE check"
        else:
            verdict = "missed in the FE check: " + "; ".join(
                f"{c['name']} by {_amount(c)}" for c in shortfall)
    else:
        assessment = targets.assess({**row, **{k_: a.get("edge", a["value"]) for k_, a in live_ans.items()}})
        verdict = verdict or "not verified by the FE (check off): met on the live model at the band's edge"
    feasible_final = live_ok and (fe is None or not confirmed(targets, fe))
    on_edge = [names[j] for j in range(len(names)) if min(x[j] - lo[j], hi[j] - x[j]) <= EDGE]
    set_args = settings.set_args(texts)
    notes = []
    for n in on_edge:
        notes.append(f"on the region's bound of {n}: the optimum may lie outside; build a region there: clutchfem "
                     f"reduce {reg.concept} " + " ".join(f"--set {a}" for a in set_args)
                     + f" --free {','.join(names)}")
    if left:
        notes.append(f"not free in the region (kept at the start's value): {', '.join(left)}")
    check_info = None
    if robust and check and check_parts and fe is not None:
        with shared_cluster(workers, scheduler):
            check_info = _fe_parts(settings, P, tn, texts, D_si[:check_parts], prob, x, D[:check_parts], targets, an,
                                   log)
        fe_designs += check_info["n_fe"]
    y_info = None
    if robust:
        Dy, _ = draw(YIELD_PARTS, np.random.default_rng(seed + 7919))
        m = parts_slack(prob, prob.full(x)[0] + Dy)
        k = int(np.sum(m < 0))
        y_info = {"yield_search_sample": history[-1]["yield_live"], "yield_independent": 1.0 - k / YIELD_PARTS,
                  "independent_parts": YIELD_PARTS, "out_of_spec": k, "ci95": _in_share(wilson(k, YIELD_PARTS))}
    msg = ("feasible design found on the live model" if live_ok else
           "NO DESIGN MEETS EVERY TARGET on the live model in the region; the least-violating one is returned")
    msg += f"; {verdict}"
    if on_edge:
        msg += f"; on the region's bound of {', '.join(on_edge)}"
    live = {"answered_by": ANSWERED_BY if check else "reduced model", "region_key": reg.key(),
            "region": reg.describe(), "region_bounds": {n: list(reg.bounds(n)) for n in reg.names},
            "search_box": {n: [float(lo_si[j] + lo[j] * w_si[j]), float(lo_si[j] + hi[j] * w_si[j])]
                           for j, n in enumerate(names)},
            "live_evaluations": prob.evals, "fe_designs": fe_designs, "rounds": history, "verdict": verdict,
            "answers": live_ans, "on_region_bound": on_edge, "notes": notes, "model_error": {
                a: model.own_error(a) for a in sorted(prob.need)}, "seconds": time.perf_counter() - t0,
            **({"robust": tol_info, "yield": y_info, "fe_parts": check_info} if robust else {})}
    if check and fe is not None:
        live["fe_answers"] = fe
    evals = {"ok": fe_designs}
    res = OptimizationResult(
        concept=settings.concept, targets=targets, free=names,
        start_texts={n: V.exact_text(P, n, getattr(settings.params(), n)) for n in names},
        best={**row, "assessment": assessment, "assessment_searched": live_assess, "analyze": fe},
        feasible=bool(feasible_final), params_texts=params_texts, set_args=set_args, path=[], evaluations=evals,
        seconds=time.perf_counter() - t0, iterations=rounds_done, message=msg, at_bounds=on_edge, settings=settings,
        answered_by=live["answered_by"], live=live)
    if an is not None:
        res.best_analysis = an
        res.best_estimate = {"confirmed": fe is not None and not confirmed(targets, fe), "answers": fe,
                             "rounds": rounds_done - 1, "missed": confirmed(targets, fe) if fe else []}
    return res


def _fe_parts(settings, P, names, texts, D_si, prob, x, D_unit, targets, an, log) -> dict:
    """The first Monte Carlo parts also through the FE (design mesh, corrected by the error
    step's ratios of the final design): per answer the largest relative difference from the
    live answer, the parts whose FE answer lies outside the live band, the verdicts."""
    nominal = {n: V.from_text(P, n, texts[n]) if n in texts else getattr(settings.params(texts), n) for n in names}
    pts = []
    for d in D_si:
        pts.append({n: V.exact_text(P, n, V.round12(nominal[n] + d[c])) for c, n in enumerate(names)})
    base = dataclasses.replace(settings, base=tuple(settings.set_args(texts)))
    if log:
        log(f"FE check of {len(pts)} Monte Carlo parts")
    rows = evaluate_many(pts, base)
    ratios = correction_ratios(an)
    U = prob.full(x)[0] + D_unit
    val, rel = prob.answers(U)
    live_slack = prob.slacks(val, rel).min(axis=1)
    ys = float(settings.operating_point().material.yield_strength)
    out = {"n_fe": len(pts), "n_ok": 0, "largest_rel": {}, "outside_live_band": 0, "fe_in_spec": 0,
           "live_in_spec": int(np.sum(live_slack >= 0)), "verdicts_differ": 0}
    diffs: dict = {k: [] for k in SOURCE}
    for i, r in enumerate(rows):
        if r.get("status") != "ok":
            continue
        out["n_ok"] += 1
        for key, f in ratios.items():
            if r.get(key) is not None:
                r[key] = r[key] * f
        fe_ok = not confirmed(targets, {k: r.get(k) for k in SOURCE})
        out["fe_in_spec"] += int(fe_ok)
        out["verdicts_differ"] += int(fe_ok != bool(live_slack[i] >= 0))
        outside = False
        for _, key, _, _ in targets.constraints():
            src = SOURCE[key]
            lv, b = float(val[src][i]), float(rel[src][i])
            if key == "safety_factor":
                lv = ys / lv
            fv = r.get(key)
            if fv is None or not fv or not math.isfinite(lv):
                continue
            d = abs(lv / fv - 1.0)
            diffs[key].append(d)
            if b >= 1.0 or d > b / (1.0 - b):  # |live - FE| beyond the band (relative to the live value)
                outside = True
        out["outside_live_band"] += int(outside)
    out["largest_rel"] = {k: max(v) for k, v in diffs.items() if v}
    return out


def _in_share(ci) -> list:
    """The interval of the share in spec from that of the share out of it."""
    return [1.0 - ci[1], 1.0 - ci[0]]


def _tdict(t: Targets) -> dict:
    return {k: getattr(t, k) for k in ("engage_rpm_lo", "engage_rpm_hi", "slip_rpm_max", "safety_factor_min",
                                       "fatigue_min")}


def _amount(c: dict) -> str:
    s = -c["slack"]
    return f"{s:.3g}" if c["key"] in DIMENSIONLESS else f"{s:.0f} rpm"


def _shown(P, name: str, v: float) -> str:
    """A length in mm, an angle in deg, else the value with its unit (a refusal's numbers)."""
    u = P.unit(name)
    return f"{v * 1e3:.4g} mm" if u == "m" else f"{v:.4g} {u}".rstrip(" -")
