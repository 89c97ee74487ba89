"""Tolerances over the life (``tolerance(..., life=N)``, ``clutchfem tolerance --life N``).

Over a life (``life=N``): one :func:`clutchfem.life` run of the nominal design for N starts
gives the drift of each requirement answer as the shoe face wears (engagement and slip speed;
the engagement with ripple drifts as the static engagement does), and every part is taken to
drift as the nominal does (ASSUMED: the parts' spread is small next to the design, so their
wear -- the same contact, the same starts -- is the nominal's).  A part is in spec at N starts
if it is at every wear state: its new answer plus the nominal's change from new at that state,
the worst over the life (as :func:`clutchfem.targets.life_design.life_check` checks an optimum;
a state without a slip speed misses the slip limit).  Since the new part is the life's first
state, the share in spec at N starts is never above the share new.  Both are reported per
target with their Wilson intervals (``ToleranceResult.life``).

The share in spec (of the parts new, and at N starts) carries the 95 % Wilson score interval
of :func:`~clutchfem.core.wilson` (:mod:`clutchfem.tolerances.tolerancing`'s docstring says why Wilson's).
"""

from __future__ import annotations

import math

import numpy as np

from ..core import ParameterError, wilson
from ..targets.life_design import LIFE_KEYS, life_of_nominal, wear_allowance

__all__ = ["LIFE_OPTIONS", "check_life_args", "in_spec", "in_spec_over_life", "life_shares", "share_in", "shares_over_life"]

#: the keywords of clutchfem.life that ``tolerance(life_options=...)`` passes on
LIFE_OPTIONS = {"duty", "drive", "wear", "rebuild_depth", "engine", "requirements", "idle_rpm"}


def check_life_args(life, life_options) -> None:
    """Refuse a bad ``life`` (starts, [1, 1e8] as ``clutchfem life --starts``) or
    ``life_options`` (a dict of :data:`LIFE_OPTIONS` keywords, only with ``life``)."""
    if life is not None and (isinstance(life, bool) or not isinstance(life, (int, float)) or not 1 <= life <= 1e8):
        raise ParameterError("life", life, "a number of starts in [1, 1e8] (as clutchfem life --starts)", "tolerance")
    if life_options is not None and (life is None or not isinstance(life_options, dict)):
        raise ParameterError("life_options", life_options if isinstance(life_options, dict) else
                             type(life_options).__name__, "a dict of clutchfem.life keywords, given with life=N",
                             "tolerance")
    unknown = sorted(set(life_options or {}) - LIFE_OPTIONS)
    if unknown:
        raise ParameterError("life_options", unknown[0], "keywords of clutchfem.life: " + ", ".join(sorted(LIFE_OPTIONS)),
                             "tolerance")


def in_spec(row: dict, spec) -> dict:
    out = {}
    for name, key, limit, sense in spec:
        v = row.get(key)
        if v is None or not math.isfinite(v):
            ok = key != "slip_rpm" and sense == ">="  # never engages: no chain motion at idle
        else:
            ok = v >= limit if sense == ">=" else v <= limit
        out[name] = bool(ok)
    return out


def in_spec_over_life(row: dict, spec, life) -> dict:
    """Per target: is the part ``row`` in spec at every wear state of ``life`` (its new answer
    plus the nominal's change from new there; module docstring)?"""
    new = in_spec(row, spec)
    out = {}
    for name, key, limit, sense in spec:
        v0 = row.get(key)
        if key not in LIFE_KEYS or v0 is None or not math.isfinite(v0):
            out[name] = new[name]  # no wear drift (safety factors), or no answer new: judged new
            continue
        y = np.asarray(getattr(life, LIFE_KEYS[key]), dtype=float)
        if not len(y) or not math.isfinite(y[0]):
            out[name] = False  # the nominal has no such answer new: no drift to add
            continue
        vals = v0 + (y - y[0])
        with np.errstate(invalid="ignore"):
            ok = (vals >= limit) if sense == ">=" else (vals <= limit)
        out[name] = bool(new[name] and np.all(ok & np.isfinite(vals)))
    return out


def share_in(checks: list, name: str, n_bad: int) -> dict:
    """The share of parts in spec on target ``name`` (or ``any``) with its Wilson interval;
    ``n_bad`` parts that could not be analysed counted out (0: left out)."""
    k = sum(1 for c in checks if (all(c.values()) if name == "any" else c[name]))
    m = len(checks) + n_bad
    ci = wilson(k, m)
    return {"k_in_spec": k, "n": m, "share_in_spec": k / m if m else math.nan, "ci95": list(ci)}


def shares_over_life(ok_rows, spec, L, starts, bad, notes) -> dict:
    """``ToleranceResult.life``: the nominal's drift and the shares in spec new and at
    ``starts`` starts (module docstring); ``bad`` parts not analysed, ``notes`` of the life run."""
    a = wear_allowance(L, reserve=0.0)
    new = [in_spec(r, spec) for r in ok_rows]
    old = [in_spec_over_life(r, spec, L) for r in ok_rows]
    shares = {}
    for name, *_ in spec + [("any", None, None, None)]:
        shares[name] = {"new": share_in(new, name, 0), "at_life": share_in(old, name, 0)}
    if bad:
        shares["any_counting_unbuildable"] = {"new": share_in(new, "any", bad), "at_life": share_in(old, "any", bad)}
    band = getattr(L, "band", None) or {}
    return {"starts": float(starts), "drift_rpm": {k: list(v) for k, v in a.drift.items()},
            "torque_drift_Nm": a.torque_drift_Nm, "drift_at_high_k_rpm": a.k_band,
            "nominal_life_new_rpm": {v: float(np.asarray(getattr(L, v), dtype=float)[0]) for v in LIFE_KEYS.values()},
            "in_spec": shares, "wear_coefficient": band.get("wear_coefficient"),
            "wear_coefficient_band": band.get("wear_coefficient_band"),
            "wear_states": len(np.asarray(L.starts)), "life_seconds": float(getattr(L, "seconds", math.nan)),
            "notes": list(notes),
            "assumption": "every part drifts as the nominal design does over the life (one clutchfem life run of "
                          "the nominal): the parts' spread is small next to the design, so their wear is the "
                          "nominal's; a part is in spec at N starts if its new answer plus the nominal's change "
                          "from new is within the limit at every wear state"}


def life_shares(settings, life: float, life_options, ok_rows, spec, bad: int, log=None) -> tuple[dict, str]:
    """One :func:`clutchfem.life` run of the base design of ``settings`` over ``life`` starts,
    and (:func:`shares_over_life` of the parts ``ok_rows``, the note the result carries)."""
    if log:
        log(f"life of the nominal design over {life:.0f} starts (its drift, taken as every part's)")
    notes: list = []
    L = life_of_nominal(settings, float(life), life_options, notes)
    res = shares_over_life(ok_rows, spec, L, life, bad, notes)
    note = (f"over {life:.0f} starts every part is taken to drift as the nominal design does (one life run of the "
            "nominal: the parts' spread is small next to the design, so their wear is the nominal's); drift from new: "
            + ", ".join(f"{k} {lo:+.0f} .. {hi:+.0f} rpm" for k, (lo, hi) in res["drift_rpm"].items()))
    return res, note
