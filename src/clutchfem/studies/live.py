"""A study whose operating point has ``fidelity = "live"``: every point answered by the reduced
model whose region holds it (:mod:`clutchfem.reduced`), in milliseconds and without a mesh.

Each point is made into its design (the concept's rules apply: a combination they refuse is
``refused`` with their message, as in any study), a cached reduced model whose region holds
it is looked up (:func:`clutchfem.reduced.find`: the same concept, fixed parameters,
operating point, engine and requirement factors, its free parameters in the box), and the
points of one region are answered in one vectorised call.  Every row says what answered it
(``answered_by``: ``reduced model``, ``FE (fallback)``, or empty for a refused point) and the
region (``region_key``); the answers carry the live band (the best path's band of the
nearest training designs plus the reduced model's own measured error) in the error columns
of the FE rows (``engagement_err_rpm`` ...) and, for the answers the FE rows give no band,
in :data:`BAND_COLUMNS`.

A point the reduced model cannot answer -- outside every cached region, where the full FE
gives no answer (the status model), or a main answer not given live there -- is, by
``outside``:

* ``"refuse"`` (the default): a ``refused`` row whose message says why (the region's bounds
  it lies outside of, or the reduced model's reason) and how to answer it (``clutchfem
  reduce`` around it, or ``live_outside = "fe"``);
* ``"fe"``: answered by the full best path on the study engine (with its error step: the
  best path's bands), stored in the study's store like any FE study (resumable), the row's
  ``answered_by`` ``FE (fallback)`` and its message the reason.

No region is built here: a dense map is asked of a region that exists (``clutchfem
reduce``), and a study that would silently start minutes of FE per region is not one a
designer asked for.
"""

from __future__ import annotations

import json
import math
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

from ..analysis import Requirements, idle_speed
from ..clutch import EngineCurve
from ..core import ClutchfemError, InputError, ParameterError
from ..evaluation import COLUMNS, ResultStore, RunResult, design_hash, model_version, run_points
from ..evaluation.point import COLUMN_NAMES, split_point
from ..loadcase import Design
from ..reduced import Region, cache_root, find
from ..reduced.live import MAIN

__all__ = ["BAND_COLUMNS", "LIVE_COLUMNS", "OUTSIDE", "live_rows"]

#: what a point the reduced model cannot answer gets (module docstring)
OUTSIDE = ("refuse", "fe")
#: reduced-model answer -> (row column, factor from SI to the column's unit, the band's column)
_ROW = {
    "engagement_rpm": ("engagement_rpm", 1.0, "engagement_err_rpm"),
    "engagement_rpm_with_ripple": ("engagement_ripple_rpm", 1.0, "engagement_ripple_err_rpm"),
    "slip_rpm": ("slip_rpm", 1.0, "slip_err_rpm"),
    "torque_at_max_engine_torque_Nm": ("torque_at_max_engine_torque_Nm", 1.0, "torque_err_Nm"),
    "max_von_mises_Pa": ("max_von_mises_MPa", 1e-6, "stress_err_MPa"),
    "fatigue_safety_factor": ("fatigue_safety_factor", 1.0, "fatigue_safety_factor_err"),
    "contact_arc_deg": ("contact_arc_deg", 1.0, "contact_arc_err_deg"),
    "mass_kg": ("part_mass_g", 1e3, "part_mass_err_g"),
    "shoe_mass_kg": ("shoe_mass_g", 1e3, "shoe_mass_err_g"),
}
#: the live rows' columns beyond the FE rows' (:data:`clutchfem.evaluation.COLUMNS`)
LIVE_COLUMNS: tuple[tuple[str, str], ...] = (
    ("answered_by", "reduced model | FE (fallback) | empty: refused"),
    ("region_key", "the key of the reduced model's region that answered (clutchfem.reduced.Region.key)"),
    ("engagement_ripple_err_rpm", "live band of engagement_ripple_rpm [rpm]"),
    ("safety_factor_err", "live band of safety_factor [-] (from the peak stress's)"),
    ("fatigue_safety_factor_err", "live band of fatigue_safety_factor [-]"),
    ("contact_arc_err_deg", "live band of contact_arc_deg [deg]"),
    ("part_mass_err_g", "live band of part_mass_g [g]"),
    ("shoe_mass_err_g", "live band of shoe_mass_g [g]"),
)
BAND_COLUMNS = tuple(c for c, _ in LIVE_COLUMNS[2:])


def _design(point: dict, settings) -> Design:
    """The live design of a study point (no mesh)."""
    geo, opv = split_point(point, settings)
    op = settings.op.replace(**opv) if opv else settings.op
    return Design.from_concept(settings.concept, operating=op, mesh=settings.mesh, **{**dict(settings.fixed), **geo})


def _blank(point: dict, settings, version: str) -> dict:
    row = dict.fromkeys(COLUMN_NAMES)
    row.update(dict.fromkeys(c for c, _ in LIVE_COLUMNS))
    row.update(model_version=version, design=settings.design_name, point_json=json.dumps(point, sort_keys=True),
               min_safety_factor=settings.min_safety_factor)
    return row


def live_rows(points: list[dict], settings, *, outside: str = "refuse", store: str | Path | None = None,
              workers: int | None = None, scheduler: str | None = None, progress: bool = False,
              source: str = "") -> tuple[list[dict], RunResult]:
    """The rows of a live study's ``points`` (module docstring), in point order, and the run's
    counts.

    Parameters
    ----------
    points : list of dict
        The varied inputs of each point (``name -> value`` in the parameter's unit).
    settings : clutchfem.evaluation.Settings
        The study's fixed part; its operating point's fidelity is ``"live"``.
    outside : {"refuse", "fe"}
        What a point the reduced model cannot answer gets.
    store : path, optional
        The study store the FE fallback's rows go to (``outside="fe"``).
    workers, scheduler, progress, source
        The study engine's controls for the FE fallback.

    Returns
    -------
    (list of dict, RunResult)
        One row per point (the FE rows' columns plus :data:`LIVE_COLUMNS`), and the counts.

    Examples
    --------
    A design outside every cached region is refused, saying why and how to answer it:

    >>> import os, tempfile, clutchfem as cf
    >>> from clutchfem.evaluation import EvalSettings
    >>> from clutchfem.studies.live import live_rows
    >>> os.environ["CLUTCHFEM_CACHE"] = tempfile.mkdtemp()      # an empty cache
    >>> st = EvalSettings.from_design(cf.Design.from_concept("concept1", fidelity="live")).study()
    >>> st = st.__class__(**{**st.__dict__, "op": st.op.replace(fidelity="live")})
    >>> rows, run = live_rows([{"flexure_thickness": 2.2e-3}], st)
    >>> rows[0]["status"], "no reduced model holds" in rows[0]["message"], run.refused
    ('refused', True, 1)
    """
    if outside not in OUTSIDE:
        raise ParameterError("outside", outside, "refuse or fe (what a point no reduced model answers gets)",
                             "live study")
    if settings.concept is None:
        raise ParameterError("fidelity", "live", "a concept's study (a user mesh has no parameters to reduce over: "
                             "fidelity best or fast)", "study")
    t0 = time.perf_counter()
    version = model_version(settings.concept)
    engine = settings.engine if settings.engine is not None else EngineCurve.default()
    req = Requirements(a=settings.a, b=settings.b)
    idle, _ = idle_speed(engine, settings.idle_rpm)
    rows = [_blank(p, settings, version) for p in points]
    groups: dict[str, tuple] = {}  # region key -> (model, [(row index, u, design)])
    members: dict[str, list] = defaultdict(list)
    fall: dict[int, str] = {}  # row index -> why the reduced model does not answer it
    for i, p in enumerate(points):
        try:
            d = _design(p, settings)
            rows[i]["design_hash"] = d.hash
        except (ParameterError, InputError) as exc:
            rows[i].update(status="refused", message=str(exc))
            continue
        model = None
        for key, (m, _) in groups.items():  # a region found already (no look-up of the cache)
            if _same(m, d, settings, req):
                model = m
                break
        if model is None:
            model = find(d, engine=settings.engine, requirements=req)
            if model is None:
                fall[i] = "no reduced model holds this design (" + _nearest_why(d, settings, req) + ")"
                continue
            groups[model.region.key()] = (model, None)
        members[model.region.key()].append((i, model.region.unit_of(model.region.design_values(d)), d))
    for key, (model, _) in groups.items():
        pred = model.predict(np.array([u for _, u, _ in members[key]]))
        for k, (i, _, d) in enumerate(members[key]):
            v = {a: float(pred["value"][a][k]) for a in pred["value"]}
            missing = [a for a in MAIN if not math.isfinite(v.get(a, math.nan))]
            if missing:
                reasons = sorted({str(pred["why"][a][k]) or "not modelled" for a in missing})
                fall[i] = f"the reduced model gives no {', '.join(missing)} here: " + "; ".join(reasons)
                continue
            band = {a: float(pred["band"][a][k]) for a in pred["band"]}
            _fill_live(rows[i], d, model, v, band, engine, idle, settings)
    fe_ok = 0
    if fall and outside == "refuse":
        for i, why in fall.items():
            rows[i].update(status="refused", message=f"{why}; `clutchfem reduce` builds a region around it, or "
                           "settings.live_outside = \"fe\" answers it with the full FE")
    elif fall:
        fe_idx = sorted(fall)
        fe_settings = settings.__class__(**{**settings.__dict__, "op": settings.op.replace(fidelity="best")})
        if store is None:
            raise InputError("a live study's FE fallback needs a store (the study's folder)")
        res = run_points([points[i] for i in fe_idx], fe_settings, store, workers=workers, scheduler=scheduler,
                         progress=progress, source=source, desc="FE fallback", error_points=list(range(len(fe_idx))))
        with ResultStore(store, COLUMNS, context=res.context_hash) as rs:
            df = rs.frame(res.model_version, list(res.keys))
        by_key = {r["design_hash"]: r for r in json.loads(df.to_json(orient="records"))}
        for i in fe_idx:
            r = by_key.get(design_hash(points[i], fe_settings))
            if r is None:
                rows[i].update(status="failed", message=f"FE fallback ({fall[i]}): no row")
                continue
            rows[i].update({k: r.get(k) for k in COLUMN_NAMES})
            rows[i]["point_json"] = json.dumps(points[i], sort_keys=True)
            rows[i]["answered_by"] = "FE (fallback)"
            rows[i]["message"] = f"answered by the FE (best path), not live: {fall[i]}"
            fe_ok += r.get("status") == "ok"
    st = [r["status"] for r in rows]
    wall = time.perf_counter() - t0
    run = RunResult(points=len(points), done=len(points), ok=st.count("ok"), refused=st.count("refused"),
                    failed=st.count("failed"), computed=len(points), skipped=0,
                    store=Path(store) if store is not None else Path("-"), model_version=version, wall_s=wall,
                    compute_s=wall, workers=workers, scheduler="this process: the reduced model (live)"
                    + (f"; the FE fallback on the study engine ({len(fall)} designs)" if fall and outside == "fe"
                       else ""),
                    keys=tuple(r["design_hash"] or "" for r in rows), listed=len(points))
    return rows, run


def _same(model, design, settings, req) -> bool:
    """Whether ``model``'s region holds ``design`` (the region's key for the design's fixed
    inputs, its free parameters in the box)."""
    reg = model.region
    try:
        r = Region.around(design, free=list(reg.names), ranges={n: reg.bounds(n) for n in reg.names},
                          engine=settings.engine, requirements=req)
    except ClutchfemError:
        return False
    return r.key() == reg.key() and reg.contains(reg.design_values(design))


def _nearest_why(design, settings, req) -> str:
    """Why no cached region holds ``design``: the bounds of a region of the same fixed inputs
    it lies outside of, else that there is none."""
    for folder in sorted(cache_root().glob(f"{design.name}-*")) if cache_root().is_dir() else ():
        try:
            doc = json.loads((folder / "region.json").read_text())
            r = Region.around(design, free=list(doc["free"]), ranges={n: tuple(v) for n, v in doc["free"].items()},
                              engine=settings.engine, requirements=req)
        except (OSError, ValueError, KeyError, ClutchfemError):
            continue
        if r.key() == doc.get("key"):
            return "outside the cached region: " + "; ".join(r.outside(r.design_values(design)))
    return "no cached region of these fixed inputs"


def _fill_live(row: dict, design, model, v: dict, band: dict, engine: EngineCurve, idle: float, settings) -> None:
    """A live answer's row: the answers in the FE rows' units, their bands, the checks."""
    ys = float(design.op.material.yield_strength)
    for a, (col, sc, bcol) in _ROW.items():
        if a in v and math.isfinite(v[a]):
            row[col] = v[a] * sc
            row[bcol] = band[a] * sc
    peak = v["max_von_mises_Pa"]
    sf = ys / peak
    eng_limit, slip_limit = settings.a * idle, settings.b * float(engine.rpm_max_torque)
    t = v["torque_at_max_engine_torque_Nm"]
    eng_ok = v["engagement_rpm_with_ripple"] > eng_limit
    slip_ok = v["slip_rpm"] < slip_limit
    stress_ok = sf >= settings.min_safety_factor
    row.update(status="ok", message=None, answered_by="reduced model", region_key=model.region.key(),
               slip_status="slips", rpm_max_engine_torque=float(engine.rpm_max_torque),
               max_engine_torque_Nm=float(engine.max_torque), torque_margin_Nm=t - float(engine.max_torque),
               max_engine_rpm=float(engine.rpm_range[1]), safety_factor=sf, safety_factor_err=sf * band[
                   "max_von_mises_Pa"] / peak, yield_strength_MPa=ys / 1e6, engagement_ok=int(eng_ok),
               slip_ok=int(slip_ok), stress_ok=int(stress_ok), feasible=int(eng_ok and slip_ok and stress_ok),
               engagement_limit_rpm=eng_limit, slip_limit_rpm=slip_limit, errors_estimated=1,
               inputs_json=json.dumps({"settings": settings.canonical(), "region": model.region.to_json()},
                                      sort_keys=True, default=str),
               t_total_s=0.0, finished_at=time.time())
