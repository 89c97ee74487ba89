"""Design to targets: the search for a design that meets the requirement checks at the least
part mass (or the largest torque margin) -- a gradient method on morphed meshes
(:mod:`.gradient`) and a derivative-free, parallel pattern search (below).

Methods (``method``): ``auto`` (default) runs the gradient method and hands its best design
to the pattern search only when it found no feasible one; ``gradient`` and ``pattern`` run one
alone.  Measured from concept 4's defaults (BENCHMARKS.md, "Design to targets: gradient
method"): the gradient method meets every target at 105.4 g in 116 designs where the pattern
search needs 464 designs for 122.3 g -- on morphed meshes the answers are smooth enough for a
model, which the paragraph below, written for remeshed answers, ruled out.

Targets (defaults: the requirement checks of :func:`clutchfem.analysis.analyze`)

* engagement with the 2-stroke ripple (3 sigma cycle) >= a x idle (a = 1.3, idle 2700 rpm:
  3510 rpm; both ASSUMED in the core), optionally <= an upper limit;
* slip speed (drum held, full throttle) <= b x rpm of the maximum engine torque (b = 1.0:
  8000 rpm on the ASSUMED engine curve); a clutch that never holds the engine violates it;
* safety factor against yield at the engine's maximum speed >= 1.5 (the core's fatigue
  caution threshold, ASSUMED);
* with ``fatigue_min`` (``--fatigue-min``): the fatigue safety factor of analyze's step 10
  >= that value (off by default, as the issue's requirement checks are three; the final
  design's value is always reported and a value below 1 is named).

Each constraint is scored as a relative violation v_j = max(0, (limit - value)/limit) (sign
by sense); a design's infeasibility is h = sum_j v_j (:mod:`.targets`, which also refuses
contradictory targets at once).

Why this optimiser.  The answers come from a mesh rebuilt for every design, so they carry
mesh noise (measured on concept 4: ~0.5 % in peak stress, ~0.05 % in engagement between
neighbouring designs whose meshes differ in topology), and a large part of the parameter box
is *refused* by the concept's consistency rules (concept 4: a beam that no longer ends below
its shoe; 57 of 64 Sobol points of a +-25 % box).  Gradient methods and the quadratic models
of COBYLA/COBYQA need a value everywhere and are misled by noise at small steps.  A
*pattern search with an extreme barrier* (Torczon 1997; Audet & Dennis 2006, MADS, whose
"search" step is here a space-filling Sobol sample) needs neither: it compares designs, a
refused or failed design is simply worse than all others and costs nothing (refusals are
found before any meshing), its steps never fall below the parameters' snapping resolution
(noise cannot be chased below it), and each poll (2 n designs) is one parallel batch of
:func:`~clutchfem.evaluation.batch.evaluate_many`.

Comparison (a filter in its simplest form): a feasible design beats an infeasible one; two
infeasible designs compare by h; two feasible ones by the objective.  An improvement counts
only if it exceeds a noise margin (0.1 % of the objective, 1e-4 in h), so that mesh noise
does not make a step a "success".

Steps: normalised coordinates x in [0, 1] over each free parameter's range (the declared
range, or ``--range``); poll the 2 n points x +- Delta e_i (plus, after a success, the same
step once more: a pattern move); move to the best improving point and double Delta (at most
1/4), or halve Delta; stop when Delta falls below 1/256 (or every free parameter's snapping
resolution) or the evaluation budget is spent.

Every evaluated design is kept (the *path*) with its answers, constraint values and whether
it was the incumbent; the result names the final design's ``--set`` texts, each constraint's
value, slack and whether it binds (slack below 2 % of its limit), the parameters at a bound,
the evaluations by status and the time.  No feasible design: the least-violating one is
returned with the constraint that dominates its violation.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
from scipy.stats import qmc

from ..core import InputError, ParameterError, as_bool
from ..core import values as V
from ..evaluation import EvalSettings, evaluate_many, shared_cluster
from ..geometry import default_free
from .best_check import check_optimum, start_targets
from .gradient import gradient_search
from .live import live_optimize
from .result import OptimizationResult, better
from .search_space import make_space
from .targets import DIMENSIONLESS, Targets


def optimize(design, targets: Targets | None = None, free: list[str] | None = None, *,
             engine=None, requirements=None, ranges: dict | None = None, sample: int = 32, max_evals: int = 300,
             workers: int | None = None, scheduler: str | None = None, seed: int = 0, min_step: float = 1.0 / 256,
             method: str = "auto", check: bool = True, fidelity: str | None = None, log=None) -> OptimizationResult:
    """Find the design that meets the targets at least part mass (or largest torque margin).

    A space-filling (Sobol) sample, then a pattern search (module docstring), from the base
    design, within ``max_evals`` FE evaluations (refusals are free and not counted), until
    the poll step falls below ``min_step`` of the ranges (1/256: ~0.1 mm on a 20 mm range,
    where the mesh noise of the answers is of the size of the steps' effect) or every
    parameter's resolution.  The designs run on the study engine: one local cluster of
    ``workers`` for the whole search, or the cluster at ``scheduler``.

    Parameters
    ----------
    design : Design or EvalSettings
        The start design (a concept's :class:`~clutchfem.Design`), or the study settings.
    targets : Targets, optional
        Default: engagement with ripple >= a x idle, slip <= b x rpm of max engine torque,
        safety factor >= 1.5 (the requirement checks).
    free : list of str, optional
        The parameters to vary (default: the concept's shape parameters).
    engine, requirements : optional
        With a ``design``: the engine curve and the requirement factors (defaults: the
        built-in curve, a = 1.3, b = 1.0; all ASSUMED).
    ranges : dict, optional
        ``name -> (lo, hi)`` search ranges in SI (default: the declared ranges).
    sample, max_evals, workers, scheduler, seed, min_step, log
        Search and engine controls (``workers=0``: in this process, no Dask).
    method : {"pattern", "gradient", "auto"}
        ``pattern``: the Sobol sample and pattern search above; ``gradient``: a trust-region SQP on
        morphed meshes (:mod:`.gradient`; ``max_evals`` then counts every design, refusals
        included, and ``sample``/``min_step`` are not used); ``auto``: the gradient method,
        then the pattern search with the budget left if it found no feasible design.
    check : bool
        Analyse the final design with the error step, as ``analyze`` reports it (the search's
        rows carry the design mesh's uncorrected answers), and where that misses a target,
        search on with the targets moved by the ratio (:mod:`.best_check`: the targets are
        first moved by analyze's corrections at the start design; up to two more rounds, each
        with half of ``max_evals``); the result's ``best_estimate`` says what analyze gives.
        Default on.
    fidelity : {None, "live"}
        ``"live"`` (or a ``design`` whose operating point's fidelity is ``"live"``): the search
        runs on the cached reduced model whose region holds the start design, within the
        region's box, every live answer at its band's conservative edge, and the result is
        verified by the FE (:mod:`clutchfem.targets.live`; ``ranges`` is then refused and
        ``sample``, ``max_evals``, ``method``, ``min_step`` are not used).  None: the design's own.

    Returns
    -------
    OptimizationResult
        The best design (``best``, ``params_texts``, ``set_args``), the binding
        constraints, the path of every evaluation and the message; a live search's
        ``answered_by`` and ``live`` (region, live answers, counts, FE verification).

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> r = cf.optimize(d, free=["flexure_thickness"], sample=0, max_evals=2, workers=0)
    >>> r.free, sum(r.evaluations.values()) <= 2 + 2
    (['flexure_thickness'], True)
    """
    if fidelity not in (None, "live"):
        raise ParameterError("fidelity", fidelity, "None (the design's own) or 'live' (the reduced model)", "optimize")
    live = fidelity == "live" or getattr(getattr(design, "op", None), "fidelity", None) == "live"
    settings = design if isinstance(design, EvalSettings) else EvalSettings.from_design(
        design, engine=engine, requirements=requirements)
    if targets is None:
        targets = Targets.defaults(settings)
    lo_e, hi_e = settings.engine().rpm_range
    if targets.engage_rpm_lo is not None and targets.slip_rpm_max is not None and targets.engage_rpm_lo >= hi_e:
        raise ParameterError("engage_rpm_lo", f"{targets.engage_rpm_lo:g} rpm", f"an engagement minimum below the "
                             f"engine curve's top speed {hi_e:g} rpm: a clutch that engages above it never holds the "
                             "engine, so no design meets the slip target", "optimize")
    if targets.slip_rpm_max is not None and targets.slip_rpm_max < lo_e:
        raise ParameterError("slip_rpm_max", f"{targets.slip_rpm_max:g} rpm", f"a slip maximum within the engine "
                             f"curve ({lo_e:g}..{hi_e:g} rpm): the slip speed is found on the curve, never below "
                             "its lowest speed", "optimize")
    if method not in METHODS:
        raise ParameterError("method", method, "one of " + ", ".join(METHODS), "optimize")
    check = as_bool(check, "check")
    if live:
        if ranges:
            raise ParameterError("ranges", ranges, "none with fidelity live: the search box is the region's (`clutchfem "
                                 "reduce --range` builds another)", "optimize")
        return live_optimize(settings, targets, free, check=check, seed=seed, workers=workers, scheduler=scheduler,
                             log=log)
    with shared_cluster(workers, scheduler):
        def search(s, t, budget=max_evals, first=sample):
            if method == "pattern":
                return _optimize(s, t, free, ranges, first, budget, seed, min_step, log)
            return _gradient(s, t, free, ranges, first, budget, seed, min_step, log, method)

        if not check:
            return search(settings, targets)
        aim, _ = start_targets(settings, targets)
        res = search(settings, aim)
        more = max(2 * len(res.free) + 2, max_evals // 2)  # each further round's budget: half, at least one poll
        return check_optimum(res, settings, targets, lambda s, t: search(s, t, more, 0), log, searched=aim)


#: the search methods of :func:`optimize`
METHODS = ("pattern", "gradient", "auto")


def _setup(settings, free, ranges, sample, max_evals, seed):
    """(parameter class, free names, search space) after the argument checks."""
    p0 = settings.params()
    P = type(p0)
    if isinstance(free, str):  # "a,b" or one name
        free = [x.strip() for x in free.split(",") if x.strip()]
    free = list(free) if free else default_free(P)
    if not free:
        raise InputError(f"{settings.concept}: no free parameters to optimise (give --free p1,p2,...)")
    space = make_space(P, free, ranges, p0)
    for name, val in (("sample", sample), ("max_evals", max_evals), ("seed", seed)):
        if isinstance(val, bool) or not isinstance(val, int) or val < 0:
            raise ParameterError(name, val, "an integer >= 0", "optimize")
    return P, free, space


def _gradient(settings, targets, free, ranges, sample, max_evals, seed, min_step, log, method) -> OptimizationResult:
    """The gradient method (:mod:`.gradient`), and with ``auto`` the pattern search after it
    when it found no feasible design."""
    t0 = time.perf_counter()
    P, free, space = _setup(settings, free, ranges, sample, max_evals, seed)
    p0 = settings.params()
    start_texts = {n: V.exact_text(P, n, getattr(p0, n)) for n in free}
    tr = gradient_search(settings, targets, space, space.from_params(p0), max_evals, log=log)
    if tr.best is None:
        raise InputError(f"{settings.concept}: the start design could not be evaluated ({tr.message}); give another "
                         "start (--set)")
    what = (f"gradient method (trust-region SQP on morphed meshes, {tr.iterations} gradients, {tr.anchors} morph "
            f"reference(s)): {tr.message}")
    if method == "auto" and tr.best["assessment"]["h"] > 0 and max_evals - sum(tr.counts.values()) > 0:
        if log:
            log("no feasible design by the gradient method: the pattern search goes on from its best design")
        base = settings.set_args(tr.best["params"])
        rest = max_evals - sum(tr.counts.values())
        try:
            res = _optimize(dataclasses.replace(settings, base=tuple(base)), targets, free, ranges, 0, rest, seed,
                            min_step, log)
        except InputError as exc:  # its start (the gradient method's best, meshed from scratch) has no answer
            return _finish(settings, targets, free, space, start_texts, tr.best, tr.path, tr.counts, t0,
                           tr.iterations, f"{what}; the pattern search could not go on from its best design ({exc})")
        res.path = tr.path + res.path
        for k, v in tr.counts.items():
            res.evaluations[k] = res.evaluations.get(k, 0) + v
        res.message = f"{what}; then the pattern search: {res.message}"
        res.start_texts, res.seconds = start_texts, time.perf_counter() - t0
        return res
    return _finish(settings, targets, free, space, start_texts, tr.best, tr.path, tr.counts, t0, tr.iterations,
                   what)


def _optimize(settings, targets, free, ranges, sample, max_evals, seed, min_step, log) -> OptimizationResult:
    t0 = time.perf_counter()
    P, free, space = _setup(settings, free, ranges, sample, max_evals, seed)
    p0 = settings.params()
    path: list[dict] = []
    counts = {"ok": 0, "refused": 0, "failed": 0, "crashed": 0, "timeout": 0}
    seen: dict[tuple, dict] = {}

    def n_evals() -> int:
        return counts["ok"] + counts["failed"] + counts["crashed"] + counts["timeout"]

    def tally() -> str:
        """The progress of a log line: evaluations of the budget, elapsed time and an upper
        bound of the time left (the search may converge before its budget)."""
        n, el = n_evals(), time.perf_counter() - t0
        left = f", at most ~{el / n * (max_evals - n):.0f} s left" if 0 < n < max_evals else ""
        return f" [{n} of at most {max_evals} evaluations, {el:.0f} s{left}]"

    def run(xs: list[np.ndarray], phase: str, it: int) -> list[tuple[dict | None, np.ndarray]]:
        """Evaluate the designs at normalised ``xs`` not seen before (one parallel batch);
        (row or None, snapped x) per x."""
        keyed, batch, new = [], set(), []
        for x in xs:
            texts, xsn = space.to_point(x)
            key = tuple(sorted(texts.items()))
            keyed.append((key, xsn))
            if key not in seen and key not in batch:
                batch.add(key)
                new.append(texts)
        new = new[:max(0, max_evals - n_evals())] if phase != "start" else new
        for r in (evaluate_many(new, settings) if new else []):
            r["assessment"] = targets.assess(r)
            r["phase"], r["iteration"], r["n"] = phase, it, len(path)
            counts[r["status"]] = counts.get(r["status"], 0) + 1
            path.append(r)
            seen[tuple(sorted(r["params"].items()))] = r
        return [(seen.get(key), xsn) for key, xsn in keyed]

    # start design
    start_texts = {n: V.exact_text(P, n, getattr(p0, n)) for n in free}
    x0 = space.from_params(p0)
    r0, x_inc = run([x0], "start", 0)[0]  # (the start snapped to the resolution)
    inc = r0 if r0 is not None and math.isfinite(r0["assessment"]["h"]) else None
    if log and r0 is not None:
        log((_line("start", r0) if inc is not None else f"start: {r0['status']}: {r0['message']}") + tally())
    # space-filling search (parallel): Sobol in the box around the start, half the range wide
    if sample:
        m = max(1, int(round(math.log2(max(sample, 1)))))
        u = qmc.Sobol(len(free), seed=seed).random_base2(m)
        xs = [np.clip(x0 + (ui - 0.5) * 0.5, 0.0, 1.0) for ui in u]
        for row, xsn in run(xs, "sample", 0):
            if row is not None and better(row["assessment"], None if inc is None else inc["assessment"]):
                inc, x_inc = row, xsn
        if log:
            log(f"sample of {len(xs)}: " + (_line("best", inc) if inc is not None else "no valid design") + tally())
    if inc is None:
        raise InputError(f"{settings.concept}: neither the start design nor any of the {sample} sample designs could "
                         "be evaluated (refused or failed); give another start (--set) or narrower --range")
    delta = 0.125
    res_step = space.min_step
    it = 0
    move = None  # the last successful step (pattern move: try it again, once more)
    while True:
        it += 1
        if delta < min_step or np.all(delta < res_step * 2) or n_evals() >= max_evals:
            break
        polls = [] if move is None else [np.clip(x_inc + move, 0.0, 1.0)]
        for k in range(len(free)):
            for sgn in (1.0, -1.0):
                step = max(delta, 2 * res_step[k])
                x = x_inc.copy()
                x[k] = np.clip(x[k] + sgn * step, 0.0, 1.0)
                if abs(x[k] - x_inc[k]) > 0.5 * res_step[k]:
                    polls.append(x)
        if not polls:
            break
        res = run(polls, "poll", it)
        improved = False
        x_old = x_inc
        for row, xsn in res:
            if row is not None and better(row["assessment"], inc["assessment"]):
                inc, x_inc, improved = row, xsn, True
        move = (x_inc - x_old) if improved else None
        delta = min(0.25, 2 * delta) if improved else delta / 2
        if log:
            log(f"poll {it} (step {delta:.4f} of the ranges): " + _line("incumbent", inc) + tally())
    return _finish(settings, targets, free, space, start_texts, inc, path, counts, t0, it, None)


def _finish(settings, targets, free, space, start_texts, inc, path, counts, t0, it, how) -> OptimizationResult:
    """The result of a search whose final design is row ``inc`` (``how``: the method's words,
    put before the message)."""
    P = space.P
    for r in path:
        r["incumbent"] = r is inc
    a = inc["assessment"]
    feasible = a["h"] <= 0.0
    final_p = settings.params(inc["params"])
    params_texts = V.changed_texts(final_p, P())
    params_texts.update(inc["params"])  # the evaluated texts themselves (bit-identical round trip)
    at_bounds = [n for k, n in enumerate(free)
                 if min(abs(getattr(final_p, n) - space.lo[k]), abs(space.hi[k] - getattr(final_p, n)))
                 <= 0.5 * V.resolution(P, n)]
    if feasible:
        binds = [c["name"] for c in a["constraints"] if c["binds"]]
        msg = ("feasible design found" + (f"; binding: {', '.join(binds)}" if binds else "; no constraint binds")
               + (f"; at the end of its range: {', '.join(at_bounds)}" if at_bounds else ""))
    else:
        worst = max(a["constraints"], key=lambda c: c["violation"]) if a["constraints"] else None
        msg = ("NO FEASIBLE DESIGN FOUND in the ranges searched; the least-violating design is returned"
               + (f"; the constraint that binds hardest: {worst['name']} ({_fmtc(worst)})" if worst else "")
               + (f"; parameters at the end of their range: {', '.join(at_bounds)}" if at_bounds else ""))
    if how:
        msg = f"{how}; {msg}"
    return OptimizationResult(
        concept=settings.concept, targets=targets, free=free, start_texts=start_texts,
        best=inc, feasible=feasible, params_texts=params_texts, set_args=settings.set_args(inc["params"]),
        path=path, evaluations=counts, seconds=time.perf_counter() - t0, iterations=it, message=msg,
        at_bounds=at_bounds, settings=settings)


def _fmtc(c: dict) -> str:
    v = c["value"]
    dimless = c["key"] in DIMENSIONLESS
    unit = "" if dimless else " rpm"
    vs = "none" if v is None else (f"{v:.2f}" if dimless else f"{v:.0f}")
    lim = f"{c['limit']:.2f}" if dimless else f"{c['limit']:.0f}"
    return f"{vs}{unit} against {c['sense']} {lim}{unit}"


def _line(what: str, row: dict) -> str:
    a = row["assessment"]
    if row.get("mass_kg") is None:
        return f"{what}: {row['status']}"
    cons = "; ".join(f"{c['key'].replace('_rpm', '').replace('_with_ripple', ' (ripple)')} {_fmtc(c)}"
                     for c in a["constraints"])
    state = "feasible" if a["h"] <= 0 else "infeasible (h = %.3f)" % a["h"]
    return f"{what}: {state}, mass {row['mass_kg'] * 1e3:.1f} g; {cons}"
