"""Robust design to targets: the lightest design whose every target holds for a stated share
of made parts, given the manufacturing tolerances and the model-error band of each answer.

Formulation: **chance constraints with the linearised spread, by sequential shifted limits**
(SORA, Du & Chen 2004, J. Mech. Des. 126: 225-233).  Why this one: the answers are smooth in
the parameters on morphed meshes (:mod:`.sensitivity`), and over +-0.05 mm their change is
linear to well under the spread itself, so the spread of each answer A is

    sigma_A^2 = sum_i (dA/dx_i sigma_i)^2  +  sigma_model,A^2

with sigma_i = t_i / 3 for a normal tolerance t_i at +-3 sigma (ASSUMED, as ``tolerance``) or
t_i / sqrt(3) for a uniform one, and sigma_model,A = (error band of A) / 2 (the band taken as
+-2 sigma, ASSUMED; ``model_error=False`` leaves it out).  The m constraints share the
yield Y by Bonferroni: each holds with probability 1 - (1 - Y) / m, z = Phi^-1 of that, and
each limit moves inward by its margin z sigma_A.  dA/dx_i is
:meth:`~.sensitivity.Sensitivities.spread_derivative`: the central difference, or, where a
contact node enters or leaves the zone inside the step (a kink of the contact answers), the
steeper one-sided slope, so the spread is not under-estimated across the kink.  One deterministic optimisation with the
shifted limits, the sensitivities at its optimum, new margins, again -- until the margins
move by less than 5 % at a feasible round (at most ``rounds``).  As in SORA, the first cycle is the deterministic
optimum (``optimize`` with the nominal targets, its gradient method then the pattern search),
and the shifted rounds start from it (from the start design if it found nothing feasible):
measured on the best-estimate path, the shifted rounds started from concept 4's defaults
stalled infeasible with either method (703 / 688 designs), and from the deterministic
optimum they are feasible (BENCHMARKS.md section 21).  Each shifted round starts from the
lightest design seen so far that meets its shifted limits, else the one nearest to them
(:func:`archive_start`).

The concept's rules (a geometry that cannot be built, e.g. concept 4's beam that must end
below its shoe) hold for every part within the tolerance box: the shifted rounds admit a
design only where the rules hold at all 2^k corners of the box nominal +- t_i
(:attr:`.batch.EvalSettings.tolerance_box`; for a rule linear in the toleranced dimensions
that is the whole box, so a uniform tolerance never makes an unbuildable part and a normal
one at most 1 - Phi(3) = 0.13 % per rule).  Found by the Monte Carlo check: without it the
gradient method put the best path's robust design on that rule, and 277 of 1000 sampled
parts could not be built (BENCHMARKS.md section 21).  A worst case over the tolerance box would ask
for 3 sigma on every dimension at once (heavier for no measured gain); sampling inside the
loop costs hundreds of FE runs per design.

The result carries the margins, the spreads recomputed at the final design (``converged``:
the margins it needs are within 5 % of those it was optimised with), the predicted yield
(the product of the per-constraint normal probabilities at the final design with those
spreads: an estimate that treats the constraints as independent) and, when ``check`` > 0, a Monte Carlo check through remeshed designs
(:func:`~.tolerancing.tolerance`) with its Wilson interval.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from statistics import NormalDist

from ..core import InputError, ParameterError, clean, format_quantity
from ..core import values as V
from ..evaluation import EvalSettings, sensitivities
from ..geometry import get_concept
from ..targets import METHODS, OptimizationResult, Targets, best_estimate, bisect, optimize
from ..targets.live import live_optimize
from .tolerancing import ToleranceResult, parse_tolerance, tolerance

#: the error-band key of each constrained answer (analyze's ``errors``), None: no band.  The
#: engagement with ripple has no band of its own: it takes the static engagement's, at the
#: same relative size (analyze's ``errors`` has no "engagement_rpm_with_ripple" key; before
#: this mapping the engagement band was silently left out of every robust margin)
BAND_KEY = {"engagement_rpm_with_ripple": "engagement_rpm", "slip_rpm": "slip_rpm",
            "safety_factor": "max_von_mises_Pa", "fatigue_safety_factor": None}
#: shifted rounds at most (each is one optimisation of up to max_evals designs)
MAX_ROUNDS = 10
#: margins that move less than this share between rounds have converged
CONVERGED = 0.05


@dataclass
class RobustResult:
    """What :func:`robust_optimize` returns: the final optimisation (with the shifted
    targets), the nominal targets, the margins and spreads per constraint, the predicted
    yield, the Monte Carlo check (or None) and the rounds.

    Examples
    --------
    The Monte Carlo check's share in spec, from a hand-made check (:func:`tolerance` makes one):

    >>> from clutchfem.tolerances import RobustResult, ToleranceResult
    >>> mc = ToleranceResult("concept4", {}, "normal", 64, 1, {}, [], [],
    ...                      {"any": {"k": 3, "n": 64, "share": 0.05, "ci95": [0.02, 0.13]}}, {}, {}, {})
    >>> r = RobustResult(None, None, {"flexure_thickness": 5e-5}, "normal", 0.95, {}, {}, 0.97, mc)
    >>> r.check_share_in_spec                      # (share, lower, upper Wilson bound)
    (0.95, 0.87, 0.98)
    """

    result: OptimizationResult
    targets: Targets
    tolerances: dict
    dist: str
    yield_target: float
    margins: dict
    sigma: dict
    predicted_yield: float
    check: ToleranceResult | None
    rounds: list = field(default_factory=list)
    model_error: bool = True
    #: the margins needed at the final design are within 5 % of those it was optimised with
    converged: bool = True
    evaluations: int = 0
    seconds: float = 0.0
    #: the concept's rules hold at every corner of the final design's tolerance box
    box_buildable: bool = True

    @property
    def check_share_in_spec(self) -> tuple[float, float, float] | None:
        """(share in spec, lower, upper Wilson bound) of the Monte Carlo check."""
        if self.check is None:
            return None
        o = self.check.out_any  # a part that cannot be built as drawn is out of spec
        lo, hi = o["ci95"]
        return 1.0 - o["share"], 1.0 - hi, 1.0 - lo

    def to_json(self) -> dict:
        return clean({"robust": {"yield_target": self.yield_target, "predicted_yield": self.predicted_yield,
                                 "tolerances_m_or_deg": self.tolerances, "distribution": self.dist,
                                 "model_error_included": self.model_error, "converged": self.converged,
                                 "margins": self.margins, "sigma": self.sigma, "rounds": self.rounds,
                                 "tolerance_box_buildable": self.box_buildable,
                                 "evaluations_total": self.evaluations, "seconds": self.seconds,
                                 "check_share_in_spec": self.check_share_in_spec},
                      **self.result.to_json()})


def _sigma_i(t: float, dist: str) -> float:
    return t / 3.0 if dist == "normal" else t / math.sqrt(3.0)


def spreads(settings: EvalSettings, targets: Targets, tolerances: dict, dist: str, model_error: bool,
            workers=None) -> tuple[dict, dict]:
    """(sigma per constraint answer key, the answers at the design): the linearised spread of
    each constrained answer (module docstring)."""
    s = sensitivities(settings, list(tolerances), workers=workers)
    bands = model_bands(settings) if model_error else {}
    sig = {}
    for _, key, _, _ in targets.constraints():
        var = 0.0
        for n, t in tolerances.items():
            d = s.spread_derivative(n, key)  # the steeper side where a contact event is in the step
            var += 0.0 if d is None else (d * _sigma_i(t, dist)) ** 2
        band = bands.get(key)
        if band:
            var += (band / 2.0) ** 2
        sig[key] = math.sqrt(var)
    return sig, s.base


def model_bands(settings: EvalSettings) -> dict:
    """The model-error band of each constrained answer at the design (analyze with errors:
    its ``total`` band, in the answer's unit; the safety factor's from its stress's)."""
    a = best_estimate(settings)
    out = {}
    for key, bk in BAND_KEY.items():
        e = (a.errors or {}).get(bk) if bk else None
        tot = None if not e else e.get("total")
        if tot is None:
            continue
        if key == "safety_factor" and a.max_von_mises_Pa:
            tot = tot / a.max_von_mises_Pa * (a.safety_factor or 0.0)  # same relative band
        if key == "engagement_rpm_with_ripple":
            if not (a.engagement_rpm and a.engagement_rpm_with_ripple):
                continue
            tot = tot / a.engagement_rpm * a.engagement_rpm_with_ripple  # same relative band
        out[key] = float(tot)
    return out


def archive_start(settings: EvalSettings, archive: list[dict], aim: Targets, here: EvalSettings,
                  skip: frozenset = frozenset()) -> tuple[EvalSettings, str]:
    """(start design, what it is) of a shifted round: of every design analysed so far (the
    deterministic search's path and every round's), the lightest that meets the shifted
    targets ``aim``, else the one that violates them least -- or ``here`` (the previous
    round's design) where that is no better.  Why: the deterministic optimum may sit in a
    light corner of the space whose neighbourhood holds no design with the margins (measured
    on the best path, concept 4: SORA's shifted round from its 94.2 g optimum stalled
    infeasible with either search, BENCHMARKS.md section 21), while designs the search passed
    on its way there have them; a local search from the best of those does not need to climb
    out of that corner.  The rows' answers are the design mesh's, as the search's own.  With
    a tolerance box in ``settings``, a design whose box the concept's rules refuse is moved
    until they admit it (:func:`buildable_point`: the optimum hugs a rule it learned, so the
    designs near it usually need it) and its row's answers stand for it.  Starts in ``skip``
    (their ``base``: rounds from them ended infeasible) are passed over."""
    ranked = []
    for row in archive:
        if row.get("status") != "ok" or not row.get("params"):
            continue
        a = aim.assess(row)
        if math.isfinite(a["h"]):
            ranked.append(((0, a["objective"]) if a["h"] <= 0 else (1, a["h"]), len(ranked), row, a))
    ranked.sort(key=lambda t: t[:2])
    P = get_concept(settings.concept).Params
    for _, _, row, a in ranked[:PROJECT_AT_MOST]:
        pt = buildable_point(settings, row["params"])
        if pt is None:
            continue
        base = tuple(settings.set_args(pt))
        if base in skip:
            continue
        if base == tuple(here.base):
            return here, "the previous design"
        moved = {n: f"{row['params'][n]} -> {t}" for n, t in pt.items()
                 if abs(V.from_text(P, n, t) - V.from_text(P, n, row["params"][n])) > 0.51 * V.resolution(P, n)}
        what = (f"the lightest design seen that meets the shifted targets ({row['mass_kg'] * 1e3:.1f} g)" if a["h"] <= 0
                else f"the design seen nearest to the shifted targets (h = {a['h']:.4f}, {row['mass_kg'] * 1e3:.1f} g)")
        if moved:
            what += " moved so that its tolerance box can be built: " + ", ".join(f"{n} {v}" for n, v in moved.items())
        return dataclasses.replace(settings, base=base), what
    return here, "the previous design"


#: the best-ranked designs :func:`archive_start` tries to make buildable (rule checks only)
PROJECT_AT_MOST = 50


def buildable_point(settings: EvalSettings, params: dict) -> dict | None:
    """``params`` (a design's free parameter texts) with each parameter a rule of the concept
    refuses moved, the shorter way, until the rules admit the design (with ``settings``'
    tolerance box: at every corner): the nearest admitted value on either side (steps of the
    parameter's resolution doubling outward, then bisection of the rule check alone, no
    analysis); every value on its resolution (the grid of the pattern search).  None where a
    refusal names a parameter not in ``params`` or no value of it within its range is
    admitted."""
    P = get_concept(settings.concept).Params
    # on the values' resolution first, the grid of the pattern search (its snapped start must be admitted too)
    pt = {n: V.snap(P, n, V.from_text(P, n, t))[1] for n, t in params.items()}

    def admitted(name, value) -> bool:
        try:
            settings.params(dict(pt, **{name: V.exact_text(P, name, V.round12(value))}))
            return True
        except ParameterError:
            return False

    for _ in range(len(pt) + 1):
        try:
            settings.params(pt)
            return pt
        except ParameterError as exc:
            name = exc.name
        if name not in pt:
            return None
        v, res = V.from_text(P, name, pt[name]), V.resolution(P, name)
        lo, hi = V.param_bounds(P, name)
        found = []
        for sgn in (1.0, -1.0):
            bad, step = v, res
            while True:
                trial = v + sgn * step
                if (hi is not None and trial > hi) or (lo is not None and trial < lo):
                    break
                if admitted(name, trial):
                    first = bisect(lambda u: admitted(name, u), trial, bad, 30)  # the admitted value nearest v
                    snapped = V.round12(round(first / res) * res)
                    if not admitted(name, snapped):
                        snapped = V.round12(snapped + sgn * res)
                    found.append(snapped)
                    break
                bad, step = trial, 2.0 * step
        if not found:
            return None
        pt[name] = V.exact_text(P, name, min(found, key=lambda u: abs(u - v)))
    return None


def window(nominal: Targets, margins: dict, tol_txt: str, yield_target: float) -> Targets:
    """:func:`shifted`, or a refusal naming the tolerances where the margins close the window
    between the limits (e.g. an engagement minimum moved above the moved slip maximum)."""
    try:
        return shifted(nominal, margins)
    except ParameterError as exc:
        raise ParameterError("tol", tol_txt, f"tolerances whose spreads leave a window between the limits at yield "
                             f"{yield_target:g}: they move the limits inward by " + ", ".join(
                                 f"{k} {v:.4g}" for k, v in margins.items()) + f", and then {exc.allowed}; tighten "
                             "the tolerances or lower --yield", "optimize") from None


def _robust_live(settings, nominal, free, tols, dist, yield_target, check, seed, workers, log, t0) -> RobustResult:
    """:func:`robust_optimize` on the reduced model (:func:`clutchfem.targets.live.live_optimize`)."""
    if isinstance(check, bool) or not isinstance(check, int) or not 0 <= check <= 1000:
        raise ParameterError("check", check, "an integer in [0, 1000]: parts also through the FE", "optimize")
    res = live_optimize(settings, nominal, free, tolerances=tols, dist=dist, yield_target=yield_target,
                        check_parts=check, seed=seed, workers=workers, log=log)
    y = res.live["yield"]
    try:  # the concept's rules at every corner of the final design's tolerance box
        buildable = dataclasses.replace(settings, base=tuple(res.set_args), tolerance_box=tuple(tols.items())).params()
    except ParameterError:
        buildable = False
    return RobustResult(result=res, targets=nominal, tolerances=tols, dist=dist, yield_target=yield_target,
                        margins={}, sigma={}, predicted_yield=y["yield_independent"], check=None,
                        rounds=res.live["rounds"], model_error=True, converged=True, box_buildable=buildable is not False,
                        evaluations=res.live["fe_designs"], seconds=time.perf_counter() - t0)


def shifted(targets: Targets, margins: dict) -> Targets:
    """``targets`` with every limit moved inward by its margin (:meth:`Targets.moved_inward`)."""
    return targets.moved_inward(margins)


def robust_optimize(design, tolerances: dict, *, yield_target: float = 0.99, dist: str = "normal",
                    model_error: bool = True, targets: Targets | None = None, free: list[str] | None = None,
                    engine=None, requirements=None, max_evals: int = 300, rounds: int = 5, check: int = 0,
                    workers: int | None = None, seed: int = 1, method: str = "pattern", fidelity: str | None = None,
                    log=None) -> RobustResult:
    """The lightest design that meets every target for ``yield_target`` of made parts.

    Parameters
    ----------
    design : Design or EvalSettings
        The start design (a concept's).
    tolerances : dict
        ``name -> half-width`` (SI floats or texts with a unit, ``"0.05mm"``).
    yield_target : float
        Share of parts that must meet every target, in (0.5, 1).
    dist : {"normal", "uniform"}
        The tolerance at +-3 sigma of a normal (ASSUMED default) or a uniform distribution.
    model_error : bool
        Add each answer's model-error band (taken as +-2 sigma) to its spread.
    targets : Targets, optional
        The nominal targets (default: the requirement checks, safety factor >= 1.5).
    free : list of str, optional
        The parameters to vary, as :func:`optimize`.
    engine : EngineCurve, optional
        As :func:`optimize`.
    requirements : Requirements, optional
        As :func:`optimize`.
    max_evals : int
        The budget of analysed designs per round, as :func:`optimize`.
    workers : int, optional
        Local process workers, as :func:`optimize`.
    rounds : int
        Shifted-limit optimisations at most, 1 to 10 (module docstring; they go on while a
        round is infeasible, each from a start no earlier infeasible round used).  Default 5:
        on the fast path concept 4 from its defaults was still infeasible after 3, its
        violation falling 0.27, 0.10, 0.015 (it stayed at 0.02-0.03 in rounds 4 and 5:
        BENCHMARKS.md section 21).
    check : int
        Monte Carlo parts through remeshed designs at the result (0: no check).
    seed : int
        The check's seed.
    log : callable, optional
        A progress callback (one line of text per step).
    method : {"pattern", "auto", "gradient"}
        The search of each shifted round (:func:`optimize`; round 0 is always ``auto``).
        Default ``pattern``: the configuration whose robust designs were checked by Monte
        Carlo on both paths (BENCHMARKS.md sections 18 and 21: on the default best path from
        concept 4's defaults 100.4 g, 998 of 1000 remeshed parts in spec); with ``auto`` the
        rounds of an earlier version missed the shifted limits by 0.03-1.5 % within the
        budget (measured once, section 21), so it is not the default.
    fidelity : {None, "live"}
        ``"live"`` (or a ``design`` whose operating point's fidelity is ``"live"``): the search
        runs on the cached reduced model whose region holds the start design, the yield by a
        Monte Carlo of made parts on it (:mod:`clutchfem.targets.live`: common random numbers,
        2000 parts per candidate, every answer at its live band's edge), the result verified
        by the FE and ``check`` of the parts also through the FE (0: none); ``max_evals``,
        ``rounds``, ``method`` and ``model_error`` are not used (the live band holds the
        model's error).  The result's ``predicted_yield`` is the share in spec of 10,000
        independent parts on the live model; ``margins`` and ``sigma`` are empty.

    Returns
    -------
    RobustResult

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> r = cf.robust_optimize(d, {"flexure_thickness": "0.05mm"}, free=["flexure_thickness"], max_evals=2,
    ...                        rounds=1, model_error=False, workers=0)
    >>> r.margins["engagement_rpm_with_ripple"] > 0      # the engagement limit moved up [rpm]
    True
    """
    t0 = time.perf_counter()
    if not (isinstance(yield_target, (int, float)) and 0.5 < yield_target < 1.0):
        raise ParameterError("yield", yield_target, "a share of parts in (0.5, 1), e.g. 0.99", "optimize")
    if dist not in ("normal", "uniform"):
        raise ParameterError("dist", dist, "normal or uniform", "optimize")
    if method not in METHODS:
        raise ParameterError("method", method, "one of " + ", ".join(METHODS), "optimize")
    if not tolerances:
        raise ParameterError("tol", None, "at least one tolerance name=+-value", "optimize")
    if isinstance(rounds, bool) or not isinstance(rounds, int) or not 1 <= rounds <= MAX_ROUNDS:
        raise ParameterError("rounds", rounds, f"an integer from 1 to {MAX_ROUNDS} (shifted-limit rounds)", "optimize")
    settings = design if isinstance(design, EvalSettings) else EvalSettings.from_design(
        design, engine=engine, requirements=requirements)
    P = get_concept(settings.concept).Params
    tols = {}
    for n, t in tolerances.items():
        if isinstance(t, str):
            name, half = parse_tolerance(P, f"{n}=+-{t.strip().lstrip('+-±/')}")
        else:  # an SI float: checked as the text of its SI value
            name, half = parse_tolerance(P, f"{n}=+-{float(t)!r}")
            half = float(t)
        tols[name] = half
        lo, hi = V.param_bounds(P, name)
        if lo is not None and hi is not None and 2.0 * half >= hi - lo:  # said before any search
            unit = P.unit(name)
            show = (lambda x: format_quantity(x, unit))  # noqa: E731
            raise ParameterError(name, t, f"a tolerance half-width below {show(0.5 * (hi - lo))}, half the "
                                 f"parameter's range [{show(lo)}, {show(hi)}]: a tolerance box of +-{show(half)} "
                                 "is wider than the range, no nominal value keeps every part inside it", "option --tol",
                                 shown=f"+-{show(half)}")
    nominal = targets or Targets.defaults(settings)
    if fidelity not in (None, "live"):
        raise ParameterError("fidelity", fidelity, "None (the design's own) or 'live' (the reduced model)", "optimize")
    if fidelity == "live" or getattr(getattr(design, "op", None), "fidelity", None) == "live":
        return _robust_live(settings, nominal, free, tols, dist, yield_target, check, seed, workers, log, t0)
    m = len(nominal.constraints())
    z = NormalDist().inv_cdf(1.0 - (1.0 - yield_target) / m)
    margins = {k: 0.0 for _, k, _, _ in nominal.constraints()}
    sigma: dict = {}
    history, evals = [], 0
    res = None
    # SORA's first cycle: the deterministic optimum (the gradient method, then the pattern
    # search if it found nothing feasible), from which the shifted rounds start (module docstring)
    det = optimize(settings, nominal, free, max_evals=max_evals, workers=workers, method="auto", log=log)
    evals += sum(det.evaluations.values())
    history.append({"round": 0, "deterministic": True, "feasible": det.feasible, "mass_kg": det.best.get("mass_kg"),
                    "evaluations": sum(det.evaluations.values())})
    if log:
        log(f"round 0 (deterministic optimum): {'feasible' if det.feasible else 'INFEASIBLE'}, mass "
            f"{det.best.get('mass_kg')}")
    here = dataclasses.replace(settings, base=tuple(det.set_args)) if det.feasible else settings
    archive = list(det.path)  # every design analysed so far: the starts of the shifted rounds
    # the shifted rounds admit a design only if every part within its tolerance box can be built
    boxed = dataclasses.replace(settings, tolerance_box=tuple(tols.items()))
    tried: set = set()  # the starts of rounds that ended infeasible
    for k in range(rounds):
        sigma, _ = spreads(here, nominal, tols, dist, model_error, workers)
        new = {key: z * s for key, s in sigma.items()}
        moved = max((abs(new[q] - margins[q]) / max(abs(new[q]), 1e-12) for q in new), default=0.0)
        margins = new
        if res is not None and res.feasible and moved < CONVERGED:
            break
        aim = window(nominal, margins, ", ".join(f"{n}=+-{V.exact_text(P, n, t)}" for n, t in tols.items()),
                     yield_target)
        prev = dataclasses.replace(here, tolerance_box=boxed.tolerance_box)
        start, picked = archive_start(boxed, archive, aim, prev, frozenset(tried))
        if tuple(start.base) in tried:  # every start left has ended infeasible: another round would repeat one
            if log:
                log(f"round {k + 1}: no start left that has not ended infeasible; stopping")
            break
        try:
            res = optimize(start, aim, free, max_evals=max_evals, workers=workers, method=method, log=log)
        except InputError as exc:  # the chosen start and its sample cannot be evaluated: from the previous design
            if start.base == prev.base:
                raise
            if log:
                log(f"round {k + 1}: no search from {picked} ({exc}); from the previous design")
            start, picked = prev, "the previous design"
            res = optimize(start, aim, free, max_evals=max_evals, workers=workers, method=method, log=log)
        evals += sum(res.evaluations.values())
        archive += res.path
        if not res.feasible:
            tried.add(tuple(start.base))
        history.append({"round": k + 1, "margins": dict(margins), "sigma": dict(sigma), "start": picked,
                        "feasible": res.feasible, "mass_kg": res.best.get("mass_kg"),
                        "evaluations": sum(res.evaluations.values())})
        if log:
            log(f"round {k + 1} (from {picked}): margins " + ", ".join(f"{q} {v:.4g}" for q, v in margins.items())
                + f"; {'feasible' if res.feasible else 'INFEASIBLE'}, mass {res.best.get('mass_kg')}")
        here = dataclasses.replace(settings, base=tuple(res.set_args))
    assert res is not None
    final = dataclasses.replace(settings, base=tuple(res.set_args))
    # the spreads at the final design itself (the last margins were computed at the previous
    # round's optimum): the predicted yield uses these, and says whether the margins held
    sigma, _ = spreads(final, nominal, tols, dist, model_error, workers)
    need = {key: z * sg for key, sg in sigma.items()}
    converged = all(need[q] <= margins[q] * (1.0 + CONVERGED) for q in need)
    history.append({"round": "final", "margins_needed": need, "sigma": dict(sigma), "converged": converged})
    if log:
        log("at the final design: margins needed " + ", ".join(f"{q} {v:.4g}" for q, v in need.items())
            + ("" if converged else " -- MORE than the margins used: raise rounds"))
    pred = 1.0
    for _, key, limit, sense in nominal.constraints():
        # analyze's answer where the optimiser checked its design with it (.best_check), else the row's
        v, s = (res.best.get("analyze") or {}).get(key, res.best.get(key)), sigma.get(key, 0.0)
        if v is None or not math.isfinite(v):
            pred = 0.0
            continue
        slack = (v - limit) if sense == ">=" else (limit - v)
        pred *= NormalDist().cdf(slack / s) if s > 0 else float(slack >= 0)
    try:
        dataclasses.replace(final, tolerance_box=boxed.tolerance_box).params()
        buildable = True
    except ParameterError as exc:
        buildable = False
        if log:
            log(f"the final design's tolerance box is not buildable throughout: {exc}")
    chk = tolerance(final, tols, n=check, dist=dist, seed=seed, targets=nominal, shifts=False,
                    workers=workers, log=log) if check else None
    return RobustResult(result=res, targets=nominal, tolerances=tols, dist=dist, yield_target=yield_target,
                        margins=margins, sigma=sigma, predicted_yield=pred, check=chk, rounds=history, model_error=model_error,
                        converged=converged, box_buildable=buildable,
                        evaluations=evals, seconds=time.perf_counter() - t0)
