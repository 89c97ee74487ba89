"""The optimum checked against analyze's own answers: :func:`check_optimum`.

Why.  A study evaluates its designs without the error step (``errors=False``: the error
estimate costs ~2x a design), so a row carries the design mesh's answers as the sweep reads
them.  ``analyze`` (errors on, the default) reports on the best-estimate path answers the
error step corrects: the peak stress extrapolated from two mesh levels and corrected for
geometric non-linearity (concept 4: +3.5 %, so the safety factor -3.4 %), the torque
corrected for non-linearity, and an answer whose band misses its accuracy target refined
once more (:mod:`clutchfem.analysis.error_band`).  An optimum that sits on the safety-factor
limit in the rows then misses it in ``analyze --set`` (measured: concept 4's gradient optimum
on the best path, safety factor 1.510 in the search, 1.458 in analyze).

What.  The final design of a search is analysed once with the error step (on a mesh made
from scratch, as ``analyze --set`` would).  Every constrained answer is compared with its
target; if one misses, the ratio r = analyze / row of each constrained answer moves its
target inward -- a lower limit L to L / r where r < 1, an upper limit to L / r where r > 1,
never outward -- and the search goes on from the final design with the moved targets (the
corrections vary slowly with the design: ASSUMED, and checked by the next round's analyze).
At most :data:`CHECK_ROUNDS` rounds; the result says whether ``analyze`` confirms every
target, the answers it gives, the ratios and the targets the search used.  So that the search
aims at analyze's answers from the start, the targets are first moved by the corrections
analyze makes at the start design (:func:`start_targets`: one analyze with the error step,
~2x a design); the final check then confirms them or moves them once more.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable

from cachetools import LRUCache, cached

from ..analysis import Analysis, Requirements, analyze
from ..core import ClutchfemError
from ..geometry import get_concept
from ..loadcase import Design
from ..mesh import mesh_concept
from .targets import Targets

#: rounds of moved targets after the first check (each: one search from the last design and
#: one analyze with the error step)
CHECK_ROUNDS = 2
#: the constrained answers -> the Analysis attribute that reports them
ANSWER_ATTR = {"engagement_rpm_with_ripple": "engagement_rpm_with_ripple", "slip_rpm": "slip_rpm",
               "safety_factor": "safety_factor", "fatigue_safety_factor": "fatigue_safety_factor"}


RECENT_SIZE = 4


def _key(settings, point: dict | None = None) -> tuple:
    """What defines a best estimate: the design's parameter values, mesh, operating point,
    engine and requirements."""
    return (settings.concept, tuple(sorted(settings.values(point).items())), repr(settings.mesh_settings()),
            repr(settings.operating_point()), settings.engine_csv, repr(settings.curve), settings.idle_rpm,
            settings.a, settings.b)


#: the last few best estimates, by design (a robust run's rounds analyse each round's final
#: design in its check and again as the next round's start and for its model bands)
@cached(LRUCache(maxsize=RECENT_SIZE), key=_key)
def best_estimate(settings, point: dict | None = None) -> Analysis:
    """``analyze`` with the error step of the design of ``settings`` (an
    :class:`~clutchfem.evaluation.EvalSettings`) with ``point``'s parameter texts, meshed from
    scratch: the answers a user gets from ``clutchfem analyze CONCEPT --set ...``.  The same
    design asked again (by its parameter values, mesh, operating point, engine and
    requirements) is answered from the last :data:`RECENT_SIZE` in this process.

    Parameters
    ----------
    settings : EvalSettings
        The base design, mesh, operating point, engine and requirement factors.
    point : dict, optional
        ``name -> value`` changed from the base (texts with units, or SI numbers).

    Returns
    -------
    Analysis
        With ``errors`` (the error step's bands and, on the best path, its corrections).

    Examples
    --------
    >>> import clutchfem as cf
    >>> es = cf.EvalSettings("concept1", mesh_size=0.003)
    >>> a = cf.best_estimate(es)                        # analyze with its error step
    >>> a.errors["engagement_rpm"]["total"] > 0, cf.best_estimate(es) is a     # asked again: kept
    (True, True)
    """
    return _best_estimate(settings, point)


def _best_estimate(settings, point: dict | None):
    p = settings.params(point)
    concept = get_concept(settings.concept)
    cm = mesh_concept(concept, p, settings.mesh_settings())
    d = Design(cm, settings.operating_point(), params=p, name=settings.concept, concept=concept)
    return analyze(d, engine=settings.engine(), requirements=Requirements(a=settings.a, b=settings.b),
                   idle_rpm=settings.idle_rpm, errors=True)


def analysed_answers(an) -> dict:
    """The constrained answers of an Analysis (answer key -> value or None)."""
    out = {}
    for key, attr in ANSWER_ATTR.items():
        v = getattr(an, attr, None)
        out[key] = float(v) if v is not None and math.isfinite(v) else None
    return out


#: the error step's answer that carries the correction of each constrained answer, and
#: whether the constrained answer goes with it (+1) or against it (-1: the safety factor
#: is the yield strength over the peak stress)
CORRECTED_BY = {"engagement_rpm_with_ripple": ("engagement_rpm", 1), "slip_rpm": ("slip_rpm", 1),
                "safety_factor": ("max_von_mises_Pa", -1)}


def correction_ratios(an) -> dict:
    """analyze's corrected / uncorrected answer of each constrained answer of an Analysis
    with the error step (its ``corrections``), as the ratio a row's answer is off by."""
    out = {}
    for key, (q, sign) in CORRECTED_BY.items():
        e = (an.errors or {}).get(q) or {}
        u, v = (e.get("corrections") or {}).get("uncorrected"), e.get("value")
        if u and v and math.isfinite(u) and math.isfinite(v):
            out[key] = (v / u) ** sign
    return out


def start_targets(settings, targets: Targets) -> tuple[Targets, dict]:
    """(``targets`` moved inward by the corrections analyze makes at the start design, the
    ratios): the search then aims at what analyze will report, and the final check rarely
    needs another round."""
    try:
        ratios = correction_ratios(best_estimate(settings))
    except ClutchfemError:  # the start has no analysis with the error step: the search finds out why
        return targets, {}
    rows = {k: 1.0 for k in ratios}
    return moved_targets(targets, rows, ratios)[0], ratios


def moved_targets(targets: Targets, row: dict, answers: dict) -> tuple[Targets, dict]:
    """(``targets`` with each limit moved inward by the ratio analyze / row of its answer, the
    ratios): L -> L / r for a lower limit where r < 1 and for an upper limit where r > 1."""
    ratios, margins = {}, {}
    for _, key, limit, sense in targets.constraints():
        a, v = answers.get(key), row.get(key)
        if a is None or v is None or not v or not math.isfinite(v):
            continue
        r = a / v
        ratios[key] = r
        moved = limit / r
        m = (moved - limit) if sense == ">=" else (limit - moved)
        margins[key] = max(margins.get(key, 0.0), max(m, 0.0))
    return targets.moved_inward(margins), ratios


def confirmed(targets: Targets, answers: dict) -> list[str]:
    """The names of the targets that ``answers`` (analyze's) miss."""
    a = targets.assess({"status": "ok", "mass_kg": 0.0, "torque_margin_Nm": 0.0, **answers})
    return [c["name"] for c in a["constraints"] if c["violated"]]


def check_optimum(result, settings, targets: Targets, search: Callable, log=None, searched: Targets | None = None):
    """``result`` (an :class:`~.optimization.OptimizationResult` of ``settings`` and
    ``targets``) checked with ``analyze`` and, where that misses a target, searched again with
    moved targets (module docstring); ``search(start_settings, moved_targets)`` runs the same
    method from a design and returns its result.  The returned result carries
    ``best_estimate``: the answers analyze gives for its final design, whether they meet
    every target, the ratios, the targets the search used and the rounds; its ``best``
    row's ``assessment`` is analyze's answers against ``targets`` (the search's own:
    ``assessment_searched``), ``feasible`` whether analyze confirms every target, and
    ``best_analysis`` the Analysis itself."""
    t0 = time.perf_counter()
    used, rounds, history = searched or targets, 0, []
    checked = None  # (result, analysis, answers, missed, ratios, targets used) of the last design checked
    while True:
        try:
            an = best_estimate(settings, result.best.get("params") or {})
        except ClutchfemError as exc:  # said, not hidden: the search's own answers stand
            if checked is None:
                result.best_estimate = {"confirmed": False, "error": f"{type(exc).__name__}: {exc}", "rounds": 0}
                result.message += f"; NOT CHECKED with analyze: its error step failed ({exc})"
                return result
            # a later round's design: keep the last design analyze checked, and say why
            history[-1]["next_round"] = f"its design could not be analysed with the error step ({exc})"
            result, an, answers, missed, ratios, used = checked
            break
        answers = analysed_answers(an)
        missed = confirmed(targets, answers) if result.feasible else []
        moved, ratios = moved_targets(targets, result.best, answers)
        history.append({"round": rounds, "answers": answers, "ratios": ratios, "missed": missed})
        checked = (result, an, answers, missed, ratios, used)
        if not result.feasible or not missed or rounds >= CHECK_ROUNDS or moved == used:
            break
        rounds += 1
        if log:
            log(f"check with analyze: {', '.join(missed)} missed (ratios analyze / search "
                + ", ".join(f"{k} {v:.4f}" for k, v in ratios.items()) + "): the search goes on with the targets moved")
        base = result.set_args
        nxt = search(dataclasses.replace(settings, base=tuple(base)), moved)
        result.path = result.path + nxt.path
        for k, v in nxt.evaluations.items():
            result.evaluations[k] = result.evaluations.get(k, 0) + v
        if not nxt.feasible:  # the moved targets were not met: keep the design analyze was checked on
            history[-1]["next_round"] = f"no design met the moved targets ({nxt.message})"
            result.seconds += nxt.seconds
            break
        nxt.path, nxt.evaluations = result.path, result.evaluations
        nxt.seconds += result.seconds
        nxt.start_texts = result.start_texts
        result, used = nxt, moved
    ok = result.feasible and not missed
    # the final design as analyze reports it, against the user's targets (the search's own
    # assessment, against the targets it searched with, is kept)
    row, searched_ok = result.best, result.feasible
    result.best = {**row, "assessment": targets.assess({**row, **{k: v for k, v in answers.items() if v is not None}}),
                   "assessment_searched": row["assessment"], "analyze": answers}
    result.feasible = ok
    result.best_analysis = an
    result.best_estimate = {
        "confirmed": ok, "answers": answers, "ratios": ratios, "missed": missed, "rounds": rounds,
        "targets_searched": {k: getattr(used, k) for k in ("engage_rpm_lo", "engage_rpm_hi", "slip_rpm_max",
                                                           "safety_factor_min", "fatigue_min")},
        "seconds": time.perf_counter() - t0, "history": history}
    sf = answers.get("safety_factor")
    said = f"safety factor {sf:.3f}" if sf is not None else "no safety factor"
    if searched_ok:
        result.message += ("; analyze (with its error step) confirms every target" if ok else
                           "; analyze (with its error step) MISSES " + ", ".join(missed)) + f" ({said}" + (
            f", after {rounds} round(s) with the targets moved inward by analyze / search ratios)" if rounds else ")")
    else:
        result.message += f"; analyze (with its error step) of that design: {said}"
    result.targets = targets
    return result
