"""Manufacturing tolerances by Monte Carlo: spread of the answers, share of parts out of
spec with its confidence interval, and which dimensions matter.

Sampling.  Each toleranced parameter x_j = nominal + d_j with d_j ~ N(0, (t_j/3)^2)
(``normal``: the tolerance band +-t_j is +-3 sigma, a capable process with Cp = 1, ASSUMED)
or d_j ~ U(-t_j, t_j) (``uniform``: any value in the band equally likely, the worst case a
drawing allows), independent, plain pseudo-random with a seed (not Latin hypercube or Sobol:
the binomial confidence interval of the out-of-spec share below needs independent draws).
Values are snapped to 1 um (0.01 deg, 1e-4 dimensionless), far below any tolerance, and
every sample is exactly what ``analyze --set`` builds from its texts.

Spec (defaults: the requirement checks, as in :mod:`clutchfem.targets.optimization`):
engagement with ripple >= a x idle, slip <= b x rpm of max engine torque, safety factor at
the engine's maximum speed >= 1.5.  The parts are analysed without the error step (for cost);
on the best-estimate path ``analyze`` corrects some answers in that step (the peak stress by
+1.5-4.5 %: the safety factor by as much), so the nominal design is analysed once with it and
every part's constrained answers are multiplied by the same ratios (``corrections``; ASSUMED
constant over a tolerance band: the corrections move slowly with the design, :mod:`.best_check`)
before the spec check.  A part is out of spec if it misses any of them; samples
the concept refuses (inconsistent geometry) or whose analysis fails are counted apart and
shown both ways (as out of spec, and left out).

Confidence interval of the share out of spec: the Wilson score interval (95 %).  The Wald
interval p +- z sqrt(p (1-p) / n) collapses to zero width when no part (or every part) is out
of spec, exactly the cases that matter; Clopper-Pearson's exact interval is conservative
(covers more than 95 %); Wilson's coverage is close to nominal down to n ~ 20 (Brown, Cai &
DasGupta 2001).

Over a life (``life=N``): every part drifts as the nominal design's life run does, and the
share in spec is reported new and at N starts (:mod:`.over_life`).

Ranking: standardised regression coefficients (SRC).  Over a tolerance band the answers are
close to linear in the dimensions, so the least-squares fit y ~ b0 + sum_j b_j x_j explains
their variance (R^2 near 1) and SRC_j = b_j sd(x_j) / sd(y) is the share of sd(y) due to x_j;
with independent inputs SRC_j^2 is x_j's share of the variance and sum SRC_j^2 = R^2.  Why
not Sobol indices: they need N (k + 2) evaluations (Saltelli) for k dimensions -- 10x more
FE runs -- and add information only where the response is non-linear or interacting; R^2 is
reported with every ranking, and an R^2 below 0.9 is flagged (then the ranking is not a
variance decomposition and Sobol indices would be the tool).  Intervals: 95 % percentile
bootstrap (1000 resamples of the samples, refitting the regression).

"0.2-0.5 mm moves the stiffness a lot" (the thesis, unquantified): for every toleranced length
the design is also evaluated with that length shifted by +-0.2 mm and +-0.5 mm alone
(``shifts``), and the change of the engagement speed and of the effective flexure stiffness is
reported (the stiffness not for a clearance: it moves the gap, not the spring).  The
effective stiffness of the shoe suspension is k = m R w_e^2 / c (thesis eq 1:
the centrifugal force at engagement equals the spring force at the clearance), so at fixed
shoe mass and clearance k is proportional to w_e^2, i.e. dk/k = 2 dw_e/w_e; where the shift
changes the shoe's mass or the clearance themselves this is the stiffness *as the clutch
feels it* (the engagement), which is what the thesis measured.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass, field

import numpy as np

from ..core import InputError, ParameterError, clean, format_quantity, wilson
from ..core import values as V
from ..evaluation import EvalSettings, evaluate_many, shared_cluster
from ..targets import Targets, best_estimate, correction_ratios
from .live import agreement, live_parts
from .over_life import check_life_args, in_spec, life_shares
from .ranking import bootstrap_src, src

#: the answers whose spread is reported (key, label, unit, scale to the shown unit)
ANSWERS = [
    ("engagement_rpm", "engagement speed (static)", "rpm", 1.0),
    ("engagement_rpm_with_ripple", "engagement speed with ripple", "rpm", 1.0),
    ("slip_rpm", "slip speed", "rpm", 1.0),
    ("max_von_mises_Pa", "peak von Mises at engine max", "MPa", 1e-6),
    ("torque_at_max_engine_torque_Nm", "torque at the rpm of max engine torque", "N m", 1.0),
    ("safety_factor", "safety factor at engine max", "-", 1.0),
]
#: shifts of the "0.2-0.5 mm" study [m]
SHIFTS = (-0.5e-3, -0.2e-3, 0.2e-3, 0.5e-3)
#: sampling resolution per unit
RES = {"m": 1e-6, "deg": 0.01, "-": 1e-4, "": 1e-4}
#: the narrowest tolerance half-width, in resolution steps: +-5 steps give 11 snapped values
MIN_BANDS = 5


def parse_tolerance(P, text: str) -> tuple[str, float]:
    """``name=+-0.05mm`` -> (name, half-width in the parameter's SI unit).

    Parameters
    ----------
    P : type
        The concept's parameter class (``cf.get_concept(name).Params``).
    text : str
        ``name=+-value`` (also ``±``, ``+/-``) with the parameter's unit; a real-valued
        parameter and a half-width of at least 5 resolution steps (5 um, 0.05 deg), else
        :class:`~clutchfem.ParameterError` naming ``--tol``.

    Returns
    -------
    tuple of (str, float)
        The parameter's name and the half-width [m, deg or -].

    Examples
    --------
    >>> import clutchfem as cf
    >>> P = cf.get_concept("concept1").Params
    >>> cf.parse_tolerance(P, "flexure_thickness=+-0.05mm"), cf.parse_tolerance(P, "shoe_arc = ±0.5deg")
    (('flexure_thickness', 5e-05), ('shoe_arc', 0.5))
    """
    m = re.fullmatch(r"\s*([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(?:\+-|±|\+/-)\s*(\S+)\s*", text)
    if not m:
        raise ParameterError("tol", text, "name=+-value with the parameter's unit, e.g. flexure_thickness=+-0.05mm",
                             "--tol")
    name, raw = m.groups()
    if name not in P.model_fields:
        raise ParameterError(name, text, "a parameter of the concept; known: " + ", ".join(P.model_fields), "--tol")
    if P.model_fields[name].annotation is not float:
        raise ParameterError(name, text, "a real-valued parameter (choices and counts have no tolerance)", "--tol")
    t = P.parse_value(name, raw)
    if not (isinstance(t, float) and t > 0):
        raise ParameterError(name, text, "a tolerance half-width > 0 (e.g. +-0.05mm)", "--tol")
    unit = P.unit(name)
    res = RES.get(unit, 1e-4)
    if t < MIN_BANDS * res:
        shown = {"m": (1e6, "um"), "deg": (1.0, "deg")}.get(unit, (1.0, ""))
        raise ParameterError(name, text, f"a half-width of at least {MIN_BANDS * res * shown[0]:g} {shown[1]}".rstrip()
                             + f": samples are snapped to {res * shown[0]:g} {shown[1]}".rstrip() + " (the geometry's "
                             "resolution), so a narrower band has too few distinct values (+-0.1 um gave every sample "
                             "the nominal value: zero spread)", "--tol")
    lo, hi = V.param_bounds(P, name)
    if lo is not None and hi is not None and 2.0 * t >= hi - lo:  # a box wider than the range means nothing
        show = (lambda x: format_quantity(x, unit))  # noqa: E731
        raise ParameterError(name, text, f"a tolerance half-width below {show(0.5 * (hi - lo))}, half the "
                             f"parameter's range [{show(lo)}, {show(hi)}]: a tolerance box of +-{show(t)} is wider "
                             "than the range, no nominal value keeps every part inside it", "option --tol",
                             shown=f"+-{show(t)}")
    return name, float(t)


@dataclass
class ToleranceResult:
    """What :func:`tolerance` returns: the Monte Carlo parts and what they say.

    Attributes
    ----------
    tolerances : dict
        ``name -> half-width`` [SI]; ``dist``, ``n``, ``seed``: how the parts were drawn.
    nominal, rows : dict, list of dict
        The nominal design's row and one row per part (``d``: its deviations).
    out_of_spec : dict
        Per target and ``any``: ``k`` of ``n`` parts out, ``share`` and its Wilson ``ci95``
        (``any_counting_unbuildable``: refused and failed parts counted out: :attr:`out_any`).
    stats, ranking : dict
        Per answer: mean, sd, min, max, nominal; the dimensions ranked by standardised
        regression coefficients with bootstrap intervals.
    shifts : list of dict
        Each toleranced length shifted by +-0.2 and +-0.5 mm alone.
    life : dict or None
        With ``tolerance(..., life=N)``: ``starts``, the nominal's ``drift_rpm`` per answer
        ([most negative, most positive] change from new over the life) and ``in_spec`` per
        target and ``any``: ``new`` and ``at_life`` shares of parts in spec with their Wilson
        ``ci95`` (:mod:`clutchfem.tolerances.over_life`; None without ``life``).

    Examples
    --------
    >>> from clutchfem.tolerances import ToleranceResult
    >>> r = ToleranceResult("concept1", {"flexure_thickness": 5e-5}, "normal", 64, 1, {}, [], [],
    ...                     {"any": {"k": 2, "n": 62, "share": 2 / 62},
    ...                      "any_counting_unbuildable": {"k": 4, "n": 64, "share": 0.0625}}, {}, {}, {})
    >>> r.out_any["share"]                          # 2 parts the rules refuse count as out of spec
    0.0625
    """

    concept: str
    tolerances: dict  # name -> half-width (SI)
    dist: str
    n: int
    seed: int
    nominal: dict  # nominal row
    rows: list[dict]  # sample rows (with "d": the deviations)
    spec: list[tuple[str, str, float, str]]
    out_of_spec: dict  # per spec and 'any': {k, n, share, ci}
    statuses: dict
    stats: dict  # answer -> mean, sd, min, max, nominal, unit
    ranking: dict  # answer -> {r2, r2_ci, items: [{name, src, ci, slope_per_unit, unit}]}
    shifts: list[dict] = field(default_factory=list)
    seconds: float = 0.0
    notes: list[str] = field(default_factory=list)
    settings: EvalSettings | None = None
    #: answer key -> the factor analyze's error step puts on the nominal design's answer (best
    #: path), applied to every part's answer before the spec check ({}: none)
    corrections: dict = field(default_factory=dict)
    #: what answered the parts: "FE", or "reduced model" (then ``agreement``: the check parts the
    #: FE also analysed, the largest relative difference per answer and the verdicts that differ)
    answered_by: str = "FE"
    agreement: dict | None = None
    #: with ``life=N``: the shares in spec new and at N starts (:mod:`clutchfem.tolerances.over_life`)
    life: dict | None = None

    @property
    def out_any(self) -> dict:
        """The share of parts out of spec on any target, a part the concept's rules refuse
        (it cannot be built as drawn) or whose analysis failed counted as out of spec."""
        return self.out_of_spec.get("any_counting_unbuildable") or self.out_of_spec["any"]

    def to_json(self) -> dict:
        return clean({"concept": self.concept, "tolerances_si": self.tolerances, "distribution": self.dist,
                      "n": self.n, "seed": self.seed, "nominal": _strip(self.nominal),
                      "spec": [{"name": a, "key": b, "limit": c, "sense": d} for a, b, c, d in self.spec],
                      "out_of_spec": self.out_of_spec, "statuses": self.statuses, "stats": self.stats,
                      "ranking": self.ranking, "shifts": self.shifts, "seconds": self.seconds,
                      "notes": self.notes, "corrections": self.corrections, "answered_by": self.answered_by,
                      "agreement": self.agreement, "life": self.life, "samples": [_strip(r) for r in self.rows],
                      "method": {"sampling": "independent pseudo-random draws; normal: tolerance = +-3 sigma "
                                             "(ASSUMED Cp = 1); uniform: over +-tolerance",
                                 "share_ci": "Wilson score interval, 95 %",
                                 "ranking": "standardised regression coefficients with R^2; 95 % percentile "
                                            "bootstrap intervals (1000 resamples)"}})


def _strip(r: dict) -> dict:
    return {k: v for k, v in r.items() if k not in ("warnings",)}


def tolerance(design, tolerances: dict, *, n: int = 64, dist: str = "normal", seed: int = 1,
              targets=None, engine=None, requirements=None, shifts: bool = True, workers: int | None = None,
              scheduler: str | None = None, log=None, model: str | None = None, check: int = 16,
              life: float | None = None, life_options: dict | None = None) -> ToleranceResult:
    """Monte Carlo of manufacturing tolerances: the spread of the answers, the share of parts
    out of spec and a ranking of the dimensions (module docstring).

    Parameters
    ----------
    design : Design or EvalSettings
        The nominal design (a concept's :class:`~clutchfem.Design`), or the study settings.
    tolerances : dict
        ``name -> half-width``: SI floats or strings with a unit (``"0.05mm"``, ``"+-0.05mm"``).
    n : int
        Monte Carlo parts (8 to 100000).
    dist : {"normal", "uniform"}
        Normal with the tolerance at +-3 sigma (ASSUMED), or uniform over it.
    seed : int
        The same seed draws the same parts.
    targets : Targets, optional
        The spec (default: the requirement checks with safety factor >= 1.5).
    engine, requirements : optional
        With a ``design``: the engine curve and the requirement factors.
    shifts : bool
        Also shift each toleranced length by +-0.2 and +-0.5 mm alone.
    workers, scheduler, log
        Study engine controls (``workers=0``: in this process).
    model : {"fe", "live"}, optional
        What answers the parts: the full FE (default; ``"live"`` for a design whose fidelity
        is live) or the reduced model of a region just around the tolerance box
        (:mod:`clutchfem.tolerances.live`: 10,000 parts in seconds).
    check : int
        With ``model="live"``: parts also analysed by the FE, and the agreement reported.
    life : float, optional
        A life [starts] in [1, 1e8]: one :func:`clutchfem.life` run of the nominal design over
        it, and the share of parts in spec new and at ``life`` starts, every part drifting as
        the nominal does (:mod:`clutchfem.tolerances.over_life`; ``ToleranceResult.life``).  Default: new parts only.
    life_options : dict, optional
        With ``life``: keywords of :func:`clutchfem.life` (``duty``, ``drive``, ``wear``,
        ``rebuild_depth``; default: its defaults, the engine and requirements of the study).

    Returns
    -------
    ToleranceResult
        Statistics of every answer, the share out of spec with its Wilson interval, the
        ranking (standardised regression coefficients with bootstrap intervals).

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> r = cf.tolerance(d, {"flexure_thickness": "0.05mm"}, n=8, shifts=False, workers=0)
    >>> r.n, 0.0 <= r.out_of_spec["any"]["share"] <= 1.0   # share of parts out of any spec
    (8, True)
    >>> # with life=N (1..1e8 starts): r.life["in_spec"][target]["new"|"at_life"]["share_in_spec"]
    >>> cf.tolerance(d, {"flexure_thickness": "0.05mm"}, life=0)
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: ...life...
    """
    check_life_args(life, life_options)
    live = (model or ("live" if getattr(getattr(design, "op", None), "fidelity", "") == "live" else "fe")) == "live"
    if model not in (None, "fe", "live"):
        raise ParameterError("model", model, "'fe' (the full FE answers every part) or 'live' (the reduced model "
                             "does, a check sample through the FE)", "tolerance")
    if isinstance(check, bool) or not isinstance(check, int) or not 0 <= check <= 1000:
        raise ParameterError("check", check, "an integer in [0, 1000] (parts also through the FE)", "tolerance")
    settings = design if isinstance(design, EvalSettings) else EvalSettings.from_design(
        design, engine=engine, requirements=requirements)
    if not isinstance(tolerances, dict):
        raise InputError(f"tolerances: a dict name -> half-width (e.g. {{'flexure_thickness': '0.05mm'}}), not "
                         f"{type(tolerances).__name__}")
    P0 = type(settings.params())
    for k, v in tolerances.items():
        if isinstance(v, bool) or not isinstance(v, (str, int, float)):
            raise ParameterError(k, v, "a tolerance half-width: a number in SI or a text with its unit ('0.05mm')",
                                 "tolerance")
    tolerances = {k: parse_tolerance(P0, f"{k}=+-{str(v).strip().lstrip('+-±') if isinstance(v, str) else repr(v)}")[1]
                  for k, v in tolerances.items()}
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ParameterError("seed", seed, "an integer >= 0 (the same seed draws the same parts)", "tolerance")
    t0 = time.perf_counter()
    if dist not in ("normal", "uniform"):
        raise ParameterError("dist", dist, "'normal' (tolerance = +-3 sigma) or 'uniform'", "tolerance")
    if isinstance(n, bool) or not isinstance(n, int) or not 8 <= n <= 100000:
        raise ParameterError("n", n, "an integer in [8, 100000] (samples)", "tolerance")
    if not tolerances:
        raise InputError("give at least one --tol name=+-value")
    p0 = settings.params()
    P = type(p0)
    names = list(tolerances)
    half = np.array([tolerances[k] for k in names])
    nominal = np.array([getattr(p0, k) for k in names], dtype=float)
    rng = np.random.default_rng(seed)
    D = rng.normal(0.0, half / 3.0, (n, len(names))) if dist == "normal" else rng.uniform(-half, half, (n, len(names)))
    points, devs = [], []
    for dvec in D:
        pt, dd = {}, []
        for k, name in enumerate(names):
            step = RES.get(P.unit(name), 1e-4)
            v = round((nominal[k] + dvec[k]) / step) * step
            txt = V.exact_text(P, name, v)
            val = V.from_text(P, name, txt)
            pt[name] = txt
            dd.append(val - nominal[k])
        points.append(pt)
        devs.append(dd)
    nominal_pt = {name: V.exact_text(P, name, getattr(p0, name)) for name in names}
    shift_pts = []
    if shifts:
        for name in names:
            if P.unit(name) != "m":
                continue
            for s in SHIFTS:
                shift_pts.append((name, s, {name: V.exact_text(P, name, round((getattr(p0, name) + s) / 1e-6) * 1e-6)}))
    agree, n_check = None, min(check, n) if live else 0
    batch = [nominal_pt] + (points[:n_check] if live else points) + [pt for _, _, pt in shift_pts]
    if log:
        log(f"{len(batch)} designs through the FE: nominal, {n if not live else n_check} samples, "
            f"{len(shift_pts)} shifted" + (f"; {n} samples on the reduced model" if live else ""))
    with shared_cluster(workers, scheduler):
        rows_all = evaluate_many(batch, settings, progress=log is not None)
        if live:
            rows, rmodel = live_parts(settings, names, nominal, half, dist, D, workers)
    if live:
        nom, fe_rows, srows = rows_all[0], rows_all[1:n_check + 1], rows_all[n_check + 1:]
    else:
        nom, rows, srows = rows_all[0], rows_all[1:n + 1], rows_all[n + 1:]
    if nom["status"] != "ok":
        raise InputError(f"the nominal design cannot be analysed ({nom['status']}: {nom['message']})")
    for r, dd in zip(rows, devs):
        r["d"] = dict(zip(names, dd))
    tg = targets or Targets(nom["engagement_limit_rpm"], None, nom["slip_limit_rpm"], 1.5)
    spec = tg.constraints()
    ratios = correction_ratios(best_estimate(settings)) if settings.operating_point().fidelity == "best" else {}
    ok_rows = [r for r in rows if r["status"] == "ok"]
    fe_parts = [r for r in ok_rows if r.get("answered_by") != "reduced model"]  # (live: corrected already)
    for r in [nom] + fe_parts + (fe_rows if live else []):  # the answers as analyze reports them ("Spec")
        for key, f in ratios.items():
            if r.get(key) is not None:
                r[key] = r[key] * f
    if live:
        agree = agreement(rows[:n_check], fe_rows, spec, in_spec)
    statuses: dict = {}
    for r in rows:
        statuses[r["status"]] = statuses.get(r["status"], 0) + 1
    bad = n - len(ok_rows)
    out: dict = {}
    checks = [in_spec(r, spec) for r in ok_rows]
    for name, *_ in spec + [("any", None, None, None)]:
        k = sum(1 for c in checks if (not all(c.values()) if name == "any" else not c[name]))
        m_ = len(ok_rows)
        out[name] = {"k": k, "n": m_, "share": k / m_ if m_ else math.nan, "ci95": list(wilson(k, m_))}
        if name == "any" and bad:
            out["any_counting_unbuildable"] = {"k": k + bad, "n": n, "share": (k + bad) / n,
                                               "ci95": list(wilson(k + bad, n))}
    stats = {}
    for key, label, unit, sc in ANSWERS:
        y = np.array([r.get(key) if r.get(key) is not None else np.nan for r in ok_rows], dtype=float)
        yv = y[np.isfinite(y)]
        stats[key] = {"label": label, "unit": unit, "scale": sc, "nominal": nom.get(key),
                      "mean": float(yv.mean()) if yv.size else None, "sd": float(yv.std(ddof=1)) if yv.size > 1 else None,
                      "min": float(yv.min()) if yv.size else None, "max": float(yv.max()) if yv.size else None,
                      "n": int(yv.size)}
    ranking = {}
    X = np.array([[r["d"][k] for k in names] for r in ok_rows], dtype=float)
    for key, label, unit, sc in ANSWERS:
        y = np.array([r.get(key) if r.get(key) is not None else np.nan for r in ok_rows], dtype=float)
        sel = np.isfinite(y)
        if sel.sum() < len(names) + 3 or np.ptp(y[sel]) == 0:
            continue
        s_, r2, b = src(X[sel], y[sel])
        lo, hi, r2lo, r2hi = bootstrap_src(X[sel], y[sel], seed=seed)
        items = []
        for j, name in enumerate(names):
            u = P.unit(name)
            per, per_u = (1e-4, "0.1 mm") if u == "m" else ((1.0, "deg") if u == "deg" else (0.01, "0.01"))
            items.append({"name": name, "src": float(s_[j]), "ci95": [float(lo[j]), float(hi[j])],
                          "slope": float(b[j] * per * sc), "slope_unit": f"{unit} per {per_u}"})
        items.sort(key=lambda it: -abs(it["src"]))
        resid_sd = float(np.std(y[sel], ddof=1) * math.sqrt(max(0.0, 1.0 - r2)))
        ranking[key] = {"label": label, "r2": r2, "r2_ci95": [r2lo, r2hi], "n": int(sel.sum()), "items": items,
                        "linear_enough": bool(r2 >= 0.9), "unexplained_sd": resid_sd, "unit": unit, "scale": sc}
    shift_rows = []
    e0 = nom.get("engagement_rpm")
    for (name, s, _), r in zip(shift_pts, srows):
        e = r.get("engagement_rpm") if r["status"] == "ok" else None
        gap = name.startswith("clearance") or name.startswith("table_c")  # the gap, not the spring
        shift_rows.append({"name": name, "shift_m": s, "status": r["status"], "engagement_rpm": e,
                           "engagement_change_pct": 100 * (e / e0 - 1) if e and e0 else None,
                           "stiffness_change_pct": 100 * ((e / e0) ** 2 - 1) if e and e0 and not gap else None,
                           "slip_rpm": r.get("slip_rpm"), "max_von_mises_Pa": r.get("max_von_mises_Pa"),
                           "message": r.get("message", "") if r["status"] != "ok" else ""})
    notes = []
    if ratios:
        notes.append("answers corrected as analyze corrects the nominal design (error step: peak stress extrapolated "
                     "and corrected for non-linearity, answers refined past their accuracy target): x "
                     + ", ".join(f"{f:.4f} {k}" for k, f in ratios.items())
                     + " on every part (ASSUMED the same over the tolerance band)")
    if bad:
        notes.append(f"{bad} of {n} samples could not be analysed ({', '.join(f'{k}: {v}' for k, v in statuses.items() if k != 'ok')}): "
                     "left out of the shares and the ranking; 'any_counting_unbuildable' counts them as out of spec")
    for key, rk in ranking.items():
        if not rk["linear_enough"]:
            notes.append(f"{rk['label']}: R^2 = {rk['r2']:.2f} < 0.9: {100 * (1 - rk['r2']):.0f} % of its variance (sd "
                         f"{rk['unexplained_sd'] * rk['scale']:.3g} {rk['unit']}) is not linear in the dimensions: mesh "
                         "noise (the mesh changes with every part) or a non-linear response; the SRC ranking is "
                         "indicative only (a finer --mesh-size, or Sobol indices for a non-linear response)")
    if live:
        notes.append(f"parts answered by the reduced model of {rmodel.region.describe()} ({rmodel.info.get('n_train')} "
                     f"best-path designs; its largest error on {rmodel.info.get('n_held_out')} held-out ones: "
                     + ", ".join(f"{k} {100 * v['max_rel']:.2g} %" for k, v in rmodel.accuracy.items()
                                 if k in ("engagement_rpm", "slip_rpm", "max_von_mises_Pa") and "max_rel" in v)
                     + f"); {agree['n']} of them also through the FE: largest differences "
                     + ", ".join(f"{k} {100 * v:.2g} %" for k, v in agree["largest_rel"].items() if v is not None)
                     + f", {agree['verdicts_differ']} verdict(s) differ")
    life_res = None
    if life is not None:
        life_res, note = life_shares(settings, life, life_options, ok_rows, spec, bad, log)
        notes.append(note)
    return ToleranceResult(concept=settings.concept, tolerances=dict(tolerances), dist=dist, n=n, seed=seed,
                           nominal=nom, rows=rows, spec=spec, out_of_spec=out, statuses=statuses, stats=stats,
                           ranking=ranking, shifts=shift_rows, seconds=time.perf_counter() - t0, notes=notes,
                           settings=settings, corrections=ratios, answered_by="reduced model" if live else "FE",
                           agreement=agree, life=life_res)
