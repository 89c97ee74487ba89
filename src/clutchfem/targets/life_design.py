"""Design for life (``optimize --life N``): a design that still meets its targets after N
starts, by a wear allowance.

A full life run (:func:`clutchfem.life`) per candidate design costs about a minute; the
optimiser evaluates hundreds.  The engineering approach instead:

1. run :func:`~clutchfem.life` on the start design for N starts and take the drift of each
   requirement answer from new to its worst over the N starts (engagement speed up, slip
   speed up as the shoe face wears; the torque at the rpm of maximum engine torque is
   reported, it is no target);
2. tighten the targets by that drift plus a reserve (:data:`RESERVE`, the drift changes
   with the design): a limit the wear moves the answer towards is moved inward by the
   allowance (the slip maximum and an engagement maximum down by the upward drift; the
   engagement minimum up only if engagement drifts down); a limit the wear moves the
   answer away from keeps its value (the new part is its worst case);
3. optimise against the tightened targets (:func:`~clutchfem.targets.optimize`);
4. check the optimum with a full :func:`~clutchfem.life` at N starts: every target against
   the optimum's new answer plus its own life drift at every wear state; if one is missed,
   redo steps 2-4 once with the drift of that optimum.

The answer says whether the final design meets every target at N starts, or by how much
(rpm) it misses.  Archard's k enters the drift through n k / H only; the allowance is taken
at the central k, the drift at the band's high end is reported (``k_band``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..analysis import Requirements
from ..core import ParameterError
from ..geometry import get_concept
from ..lifetime import RebuildRefused
from ..lifetime import life as run_life
from ..loadcase import Design
from .optimization import optimize
from .targets import Targets

__all__ = ["RESERVE", "LifeDesign", "WearAllowance", "optimize_for_life", "wear_allowance"]

#: reserve on the drift: the allowance is the drift x (1 + RESERVE) (the drift of the start
#: design stands for the optimum's, which wears differently)
RESERVE = 0.25
#: optimiser answer key -> Life array of the same requirement
LIFE_KEYS = {"engagement_rpm_with_ripple": "engagement_rpm", "slip_rpm": "slip_rpm"}


def _drift(L, key: str) -> tuple[float, float]:
    """(most negative, most positive) change of the life array ``key`` from new over the
    states [rpm]; NaN states (no slip speed) count as +inf for slip."""
    y = np.asarray(getattr(L, key), dtype=float)
    if not len(y) or not math.isfinite(y[0]):
        return 0.0, math.inf if key == "slip_rpm" else 0.0
    d = y - y[0]
    d = np.where(np.isnan(d), math.inf if key == "slip_rpm" else 0.0, d)
    return float(min(0.0, d.min())), float(max(0.0, d.max()))


@dataclass(frozen=True)
class WearAllowance:
    """The drift of the requirement answers over a life, and the targets it tightens.

    Attributes
    ----------
    starts : float
        The life [starts].
    drift : dict
        Answer key -> [most negative, most positive] change from new over the life [rpm].
    torque_drift_Nm : float
        Change of the torque at the rpm of maximum engine torque from new to the end [N m].
    k_band : dict
        Answer key -> the end-of-life change at the high end of Archard's k band [rpm] (None:
        the run did not reach it).
    reserve : float
        The allowance is the drift x (1 + reserve).

    Examples
    --------
    A life over which the engagement rose by up to 100 rpm and the slip speed by up to 200 rpm
    (:func:`wear_allowance` gives it from a :class:`~clutchfem.Life`): the slip limit is
    tightened by the drift and its 25 % reserve; a rising engagement leaves its lower limit.

    >>> import clutchfem as cf
    >>> a = cf.WearAllowance(starts=1e5, drift={"engagement_rpm_with_ripple": (0.0, 100.0),
    ...                                         "slip_rpm": (0.0, 200.0)}, torque_drift_Nm=-0.2)
    >>> t = a.tighten(cf.Targets(3510, None, 8000, 1.5))
    >>> t.engage_rpm_lo, t.slip_rpm_max
    (3510.0, 7750.0)
    """

    starts: float
    drift: dict
    torque_drift_Nm: float
    k_band: dict = field(default_factory=dict)
    reserve: float = RESERVE

    def margins(self, targets: Targets) -> dict:
        """Target field -> inward shift [rpm] (>= 0)."""
        lo, hi = self.drift.get("engagement_rpm_with_ripple", (0.0, 0.0))
        s_hi = self.drift.get("slip_rpm", (0.0, 0.0))[1]
        f = 1.0 + self.reserve
        return {"engage_rpm_lo": -lo * f if targets.engage_rpm_lo is not None else 0.0,
                "engage_rpm_hi": hi * f if targets.engage_rpm_hi is not None else 0.0,
                "slip_rpm_max": s_hi * f if targets.slip_rpm_max is not None else 0.0}

    def tighten(self, targets: Targets) -> Targets:
        """``targets`` with each limit moved inward by the allowance (module docstring); a
        tightened target that contradicts the others is refused by :class:`Targets`."""
        m = self.margins(targets)
        for k, v in m.items():
            if not math.isfinite(v):
                raise ParameterError("life", f"{self.starts:.0f} starts", "a life over which the start design keeps "
                                     "a slip speed (it loses it: no allowance can be taken); fewer starts",
                                     "optimize --life")
        t = targets
        lo = None if t.engage_rpm_lo is None else t.engage_rpm_lo + m["engage_rpm_lo"]
        hi = None if t.engage_rpm_hi is None else t.engage_rpm_hi - m["engage_rpm_hi"]
        slip = None if t.slip_rpm_max is None else t.slip_rpm_max - m["slip_rpm_max"]
        if slip is not None and slip <= 0:
            raise ParameterError("life", f"{self.starts:.0f} starts", f"a life whose slip drift "
                                 f"({m['slip_rpm_max']:.0f} rpm with its reserve) leaves a slip limit > 0 rpm",
                                 "optimize --life")
        return replace(t, engage_rpm_lo=lo, engage_rpm_hi=hi, slip_rpm_max=slip)

    def to_json(self) -> dict:
        return {"starts": self.starts, "drift_rpm": {k: list(v) for k, v in self.drift.items()},
                "torque_drift_Nm": self.torque_drift_Nm, "reserve": self.reserve,
                "drift_at_high_k_rpm": self.k_band}


def wear_allowance(life, reserve: float = RESERVE) -> WearAllowance:
    """The :class:`WearAllowance` of a :class:`~clutchfem.Life`: each requirement answer's
    drift from new over the life.

    Parameters
    ----------
    life : Life
        A life run (:func:`clutchfem.life`) of the start design.
    reserve : float
        Share added to the drift (default :data:`RESERVE`), in [0, 5].

    Returns
    -------
    WearAllowance

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> import clutchfem as cf
    >>> L = SimpleNamespace(starts=np.array([0., 1e5]), engagement_rpm=np.array([3600., 3700.]),
    ...                     slip_rpm=np.array([7000., 7200.]),
    ...                     torque_at_max_engine_torque_Nm=np.array([5.0, 4.8]), band={})
    >>> cf.wear_allowance(L).drift["slip_rpm"]
    (0.0, 200.0)
    """
    if isinstance(reserve, bool) or not isinstance(reserve, (int, float)) or not 0.0 <= reserve <= 5.0:
        raise ParameterError("reserve", reserve, "a share in [0, 5]", "wear_allowance")
    drift = {k: _drift(life, a) for k, a in LIFE_KEYS.items()}
    tq = np.asarray(life.torque_at_max_engine_torque_Nm, dtype=float)
    at_end = (getattr(life, "band", None) or {}).get("at_end", {})
    kb = {}
    for k, a in LIFE_KEYS.items():
        e = at_end.get(a) or {}
        y0 = float(np.asarray(getattr(life, a))[0])
        kb[k] = None if e.get("at_high_k") is None else float(e["at_high_k"]) - y0
    return WearAllowance(starts=float(life.starts[-1]), drift=drift, torque_drift_Nm=float(tq[-1] - tq[0]),
                         k_band=kb, reserve=float(reserve))


def life_check(targets: Targets, row: dict, life) -> dict:
    """Every target of ``targets`` over the life: the optimiser's new answer (``row``) plus the
    life's drift at each wear state.  Returns {"met": bool, "worst": {key: slack [rpm]},
    "missed_by_rpm": largest miss (0 if met), "first_miss_starts": {key: starts or None},
    "missed_new": the targets without a life drift (safety factors) the design misses new}."""
    worst, first, new_misses = {}, {}, []
    for name, key, limit, sense in targets.constraints():
        if key not in LIFE_KEYS:  # no wear drift computed: the new part's answer
            v = row.get(key)
            if v is None or not math.isfinite(v) or (v < limit if sense == ">=" else v > limit):
                new_misses.append(f"{key} {sense} {limit:.4g} (new: {'none' if v is None else f'{v:.4g}'})")
            continue
        y = np.asarray(getattr(life, LIFE_KEYS[key]), dtype=float)
        v0 = row.get(key)
        if v0 is None or not math.isfinite(v0) or not len(y) or not math.isfinite(y[0]):
            worst[f"{key}{sense}"], first[f"{key}{sense}"] = -math.inf, 0.0
            continue
        vals = v0 + (y - y[0])
        slack = (vals - limit) if sense == ">=" else (limit - vals)
        slack = np.where(np.isnan(slack), -math.inf, slack)
        worst[f"{key}{sense}"] = float(slack.min())
        bad = np.nonzero(slack < 0)[0]
        first[f"{key}{sense}"] = None if not len(bad) else float(np.asarray(life.starts)[bad[0]])
    miss = min([0.0] + list(worst.values()))
    return {"met": miss >= 0.0 and not new_misses, "worst_slack_rpm": worst, "missed_by_rpm": -miss,
            "first_miss_starts": first, "missed_new": new_misses}


@dataclass(frozen=True)
class LifeDesign:
    """What :func:`optimize_for_life` returns.

    Attributes
    ----------
    result : OptimizationResult
        The final optimisation (against the tightened targets).
    targets : Targets
        The designer's targets (new and at the end of the life).
    tightened : Targets
        The targets the final optimisation met.
    allowance : WearAllowance
        The allowance of the final round.
    life : Life
        The full life run of the final optimum (the check).
    check : dict
        :func:`life_check` of the final optimum: ``met``, ``missed_by_rpm``, per target the
        worst slack and the first start it is missed at.
    rounds : list of dict
        Per round: the allowance, the tightened limits, the optimum's ``--set`` texts, its check.

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.LifeDesign.__name__
    'LifeDesign'
    """

    result: object
    targets: Targets
    tightened: Targets
    allowance: WearAllowance
    life: object
    check: dict
    rounds: list

    @property
    def met(self) -> bool:
        return bool(self.check["met"])

    @property
    def message(self) -> str:
        n = self.allowance.starts
        if self.met:
            return f"every target met at {n:.0f} starts (checked by a full life run of the optimum)"
        parts = []
        if self.check["missed_by_rpm"] > 0:
            parts.append(f"a speed target is MISSED at {n:.0f} starts by {self.check['missed_by_rpm']:.0f} rpm (full "
                         f"life run of the optimum, after {len(self.rounds)} round(s) of allowance)")
        if self.check["missed_new"]:
            parts.append("missed already new: " + "; ".join(self.check["missed_new"]))
        return "; ".join(parts)

    def to_json(self) -> dict:
        return {"life_starts": self.allowance.starts, "met": self.met, "message": self.message,
                "check": self.check, "allowance": self.allowance.to_json(),
                "targets": [list(c) for c in self.targets.constraints()],
                "tightened_targets": [list(c) for c in self.tightened.constraints()],
                "rounds": self.rounds, "life": self.life.to_json()["arrays"],
                "life_first_miss_starts": self.life.first_miss}


def _design(settings, point: dict | None) -> Design:
    return Design.from_concept(get_concept(settings.concept), settings.params(point), settings.operating_point(),
                               settings.mesh_settings())


def _life_of(settings, point, starts, options, notes):
    """:func:`~clutchfem.life` of the design at ``point``; a rebuild of the worn part that the
    concept's rules still refuse (:class:`~clutchfem.lifetime.RebuildRefused`: the rules read
    the part as made, so only a rule that reads the worn face itself) is said in ``notes`` and
    the life run again with the wear kept in the contact gaps (``rebuild_depth=None``)."""
    try:
        return run_life(_design(settings, point), starts=float(starts), **options)
    except RebuildRefused as exc:
        if "rebuild_depth" in options and options["rebuild_depth"] is None:
            raise
        notes.append(f"life of {'the start design' if not point else 'the optimum'}: the rebuild of the worn part "
                     f"was refused by the concept's rules ({exc}); run again with the wear kept in the contact "
                     "gaps (no rebuild)")
        return run_life(_design(settings, point), starts=float(starts), **{**options, "rebuild_depth": None})


def life_defaults(settings, life_options: dict | None = None) -> dict:
    """The keywords of :func:`clutchfem.life` for a design of ``settings``: ``life_options``
    with the settings' engine curve, requirement factors and idle speed where not given."""
    lo = dict(life_options or {})
    lo.setdefault("engine", settings.engine())
    lo.setdefault("requirements", Requirements(a=settings.a, b=settings.b))
    lo.setdefault("idle_rpm", settings.idle_rpm)
    return lo


def life_of_nominal(settings, starts: float, life_options: dict | None = None, notes: list | None = None):
    """:func:`clutchfem.life` of the base design of ``settings`` over ``starts`` starts
    (:func:`life_defaults`; a refused rebuild of the worn part is said in ``notes`` and the
    life run again without rebuilds, as :func:`optimize_for_life` does)."""
    return _life_of(settings, None, starts, life_defaults(settings, life_options), [] if notes is None else notes)


def optimize_for_life(settings, targets: Targets, free=None, *, starts: float, life_options: dict | None = None,
                      reserve: float = RESERVE, log=None, **optimize_options) -> LifeDesign:
    """The optimum that keeps ``targets`` over ``starts`` starts (module docstring).

    Parameters
    ----------
    settings : EvalSettings
        The base design and its engine (as for :func:`~clutchfem.optimize`).
    targets : Targets
    free : list of str, optional
    starts : float
        The life [starts], 1..1e8.
    life_options : dict, optional
        Keywords of :func:`clutchfem.life` (drive, wear, duty, rebuild_depth).
    reserve : float
        Share added to the drift (default :data:`RESERVE`).
    log : callable, optional
    **optimize_options
        Keywords of :func:`clutchfem.optimize` (ranges, sample, max_evals, workers, method ...).

    Returns
    -------
    LifeDesign

    Examples
    --------
    >>> import clutchfem as cf
    >>> s = cf.EvalSettings("concept4", mesh_size=0.003)
    >>> cf.optimize_for_life(s, cf.Targets(3510, None, 8000, 1.5), starts=0)
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: ...
    """
    if isinstance(starts, bool) or not isinstance(starts, (int, float)) or not 1 <= starts <= 1e8:
        raise ParameterError("life", starts, "a number of starts in [1, 1e8]", "optimize --life")
    if not isinstance(targets, Targets):
        raise ParameterError("targets", type(targets).__name__, "a clutchfem Targets", "optimize --life")
    if isinstance(reserve, bool) or not isinstance(reserve, (int, float)) or not 0.0 <= reserve <= 5.0:
        raise ParameterError("reserve", reserve, "a share in [0, 5]", "optimize --life")
    lo = life_defaults(settings, life_options)
    say = log or (lambda m: None)

    say(f"life of the start design over {starts:.0f} starts (the wear allowance)")
    notes: list = []
    L = _life_of(settings, None, starts, lo, notes)
    allowance = wear_allowance(L, reserve)
    rounds = []
    for r in range(2):
        tight = allowance.tighten(targets)
        say("round {}: targets tightened by the wear allowance: {}".format(
            r + 1, ", ".join(f"{c[1]} {c[3]} {c[2]:.0f}" for c in tight.constraints() if c[1] in LIFE_KEYS)))
        res = optimize(settings, tight, free, log=log, **optimize_options)
        point = res.best.get("params") or {}
        say(f"round {r + 1}: life of the optimum over {starts:.0f} starts (the check)")
        L = _life_of(settings, point, starts, lo, notes)
        check = life_check(targets, res.best, L)
        check["notes"] = list(notes)
        rounds.append({"round": r + 1, "allowance": allowance.to_json(),
                       "tightened_targets": [list(c) for c in tight.constraints()],
                       "set": list(res.set_args), "feasible_new": bool(res.feasible), "check": check})
        if check["met"] or r == 1 or check["missed_new"] or not res.feasible:
            break  # met, or missed new (no allowance helps: the targets have no design in the ranges)
        allowance = wear_allowance(L, reserve)  # the optimum's own drift
    return LifeDesign(result=res, targets=targets, tightened=tight, allowance=allowance, life=L, check=check,
                      rounds=rounds)
