"""Made parts on the reduced model: 10,000 parts in seconds, a stated number of them through
the full FE and the agreement reported.

A tolerance box is small (+-0.05 mm on a 1.75 mm flexure is +-3 %), so the reduced model of a
region just around it (:func:`clutchfem.reduce`: the toleranced dimensions free, their
bounds +-4 sigma of a normal tolerance or the uniform tolerance itself, a few designs per
dimension) answers every part in microseconds with an error far below the parts' spread.
:func:`live_rows` gives the parts' rows in the form the Monte Carlo of
:func:`~.tolerancing.tolerance` reads from the study engine (:mod:`clutchfem.evaluation.batch`);
a part the reduced model cannot answer (beyond the region's box: a normal tail past 4 sigma,
about 6 in 100,000; or where the FE gives no answer) is evaluated by the FE instead.
:func:`agreement` compares the ``check`` parts the FE also analysed: per answer the largest
relative difference, and the parts whose verdict (in or out of spec) differs.
"""

from __future__ import annotations

import math

import numpy as np

from ..analysis import idle_speed
from ..core import param_bounds
from ..core import values as V
from ..evaluation import evaluate_many
from ..loadcase import Design
from ..reduced import reduce
from ..reduced.live import MAIN

__all__ = ["SIGMAS", "agreement", "live_parts", "live_rows", "region_ranges"]

#: the region around a normal tolerance reaches this many of its sigmas (the tolerance is 3)
SIGMAS = 4.0


def region_ranges(P, nominal: dict, half: dict, dist: str) -> dict:
    """The bounds of the region around the tolerance box: +-4 sigma of a normal tolerance
    (the tolerance is +-3 sigma), the tolerance itself of a uniform one, within the declared
    ranges."""
    out = {}
    for n, h in half.items():
        w = h * SIGMAS / 3.0 if dist == "normal" else h
        lo, hi = param_bounds(P, n)
        a, b = nominal[n] - w, nominal[n] + w
        out[n] = (max(a, lo) if lo is not None else a, min(b, hi) if hi is not None else b)
    return out


def live_parts(settings, names: list[str], nominal, half, dist: str, D, workers=None):
    """(rows, model): the Monte Carlo parts ``nominal + D`` (n, k deviations of ``names``) of the
    design of ``settings`` on the reduced model of the region around its tolerance box."""
    P = type(settings.params())
    nom = dict(zip(names, map(float, nominal)))
    ranges = region_ranges(P, nom, dict(zip(names, map(float, half))), dist)
    op = settings.operating_point().replace(fidelity="live")
    design = Design.from_concept(settings.concept, settings.params(), op, settings.mesh_settings())
    values = [dict(zip(names, map(float, nominal + d))) for d in D]
    return live_rows(design, settings, values, ranges, workers=workers)


def live_rows(design, settings, values: list[dict], ranges: dict, *, workers=None, progress: bool = False):
    """(rows, model): the parts of ``values`` (name -> SI) as study rows answered by the reduced
    model of the region ``ranges`` around ``design`` (built once, then cached), each with
    ``answered_by``; the parts it cannot answer are evaluated by the FE."""
    d = len(ranges)
    model = reduce(design, free=list(ranges), ranges=ranges, n=max(8 * d + 8, 16), held_out=10,
                   workers=workers, progress=progress)
    region = model.region
    U = np.array([region.unit_of(v) for v in values])
    inside = np.all((U >= -1e-9) & (U <= 1 + 1e-9), axis=1)
    pred = model.predict(U)
    ea, sa = settings.a * _idle(settings), settings.b * float(settings.engine().rpm_max_torque)
    engine = settings.engine()
    ys = float(settings.operating_point().material.yield_strength)
    rows: list = [None] * len(values)
    fe = []
    for i, v in enumerate(values):
        ans = {a: float(pred["value"][a][i]) for a in pred["value"]}
        if not inside[i] or not all(math.isfinite(ans.get(a, math.nan)) for a in MAIN):
            fe.append(i)
            continue
        peak, t = ans["max_von_mises_Pa"], ans["torque_at_max_engine_torque_Nm"]
        rows[i] = {"params": dict(v), "status": "ok", "message": "", "answered_by": "reduced model",
                   "engagement_rpm": ans["engagement_rpm"], "engagement_rpm_with_ripple": ans["engagement_rpm_with_ripple"],
                   "slip_rpm": ans["slip_rpm"], "slip_status": "slips", "torque_at_max_engine_torque_Nm": t,
                   "torque_margin_Nm": t - engine.max_torque, "max_von_mises_Pa": peak, "safety_factor": ys / peak,
                   "fatigue_safety_factor": _num(ans.get("fatigue_safety_factor")), "mass_kg": _num(ans.get("mass_kg")),
                   "shoe_mass_kg": _num(ans.get("shoe_mass_kg")), "contact_arc_deg": _num(ans.get("contact_arc_deg")),
                   "engagement_ok": ans["engagement_rpm_with_ripple"] > ea, "slip_ok": ans["slip_rpm"] < sa,
                   "engagement_limit_rpm": ea, "slip_limit_rpm": sa, "yield_strength_Pa": ys}
    if fe:
        P = type(settings.params())
        texts = [{n: V.exact_text(P, n, values[i][n]) for n in ranges} for i in fe]
        for i, r in zip(fe, evaluate_many(texts, settings, workers=workers)):
            r["answered_by"] = "FE (outside the reduced model)"
            r["params"] = dict(values[i])
            rows[i] = r
    return rows, model


def agreement(live: list[dict], fe: list[dict], spec, in_spec) -> dict:
    """Per answer the largest relative difference between the live and the FE answers of the
    same parts, and the parts whose verdict (in or out of spec) differs."""
    keys = ("engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm", "torque_at_max_engine_torque_Nm",
            "max_von_mises_Pa", "safety_factor")
    pairs = [(a, b) for a, b in zip(live, fe) if a.get("status") == "ok" and b.get("status") == "ok"]
    out = {"n": len(pairs), "fe_not_ok": sum(b.get("status") != "ok" for b in fe), "largest_rel": {}}
    for k in keys:
        d = [abs(a[k] / b[k] - 1) for a, b in pairs if a.get(k) and b.get(k)]
        out["largest_rel"][k] = max(d) if d else None
    out["verdicts_differ"] = sum(all(in_spec(a, spec).values()) != all(in_spec(b, spec).values()) for a, b in pairs)
    return out


def _idle(settings) -> float:
    return float(idle_speed(settings.engine(), settings.idle_rpm)[0])


def _num(x):
    return x if x is not None and math.isfinite(x) else None
