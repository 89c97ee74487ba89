"""One design point -> one row of answers, and the one function that evaluates batches:
:func:`evaluate_many`, on the study engine of issue 10 (:mod:`clutchfem.evaluation`).

A *point* is a dict ``name -> --set text`` (``{"flexure_thickness": "2.13mm"}``) applied on
top of a base design (:class:`EvalSettings`); the design evaluated is exactly the one
``clutchfem analyze C --set ...`` builds from the same texts
(:mod:`clutchfem.core.values`): the texts are read by the parameter set's own parser and
the values handed to the study engine (:func:`clutchfem.evaluation.evaluate`, the full
:func:`~clutchfem.analysis.analyze` with ``errors=False``: a search ranks designs on
one mesh each; the error of an answer is stated for the design it ends on).

A *row* is a flat, JSON-ready dict: the point, a ``status`` and the answers the targets need
(engagement with ripple, slip, torque, peak stress and safety factor at the engine's maximum
speed, part mass, contact arc, the requirement checks), in SI units.  Statuses are the study
engine's: ``ok``; ``refused`` (the concept's rules refuse the combination -- checked here,
in this process, before anything is sent: a refusal costs microseconds -- or the geometry /
mesh cannot be made); ``failed`` (a valid design without an answer: a solver refusal, or the
worker process died, e.g. gmsh aborting on a high-order mesh fix-up).

Scheduling: :func:`clutchfem.evaluation.runner.run_points` -- a ``dask.distributed`` cluster of
process workers with one thread each (or an existing cluster at ``scheduler``, or this
process with ``workers=0``), each finished row committed to a SQLite store as it arrives.
An optimisation sends many small batches (one per poll), so :func:`shared_cluster` keeps one local
cluster for the whole run instead of one per batch (measured: starting a 2-worker cluster
and warming it up costs ~3 s, a poll of concept 4 ~10-20 s).  The store of a run with an
output folder is ``<out>/results.sqlite``: every design evaluated is kept with its full
inputs, and running the same command again reuses the finished designs (the study engine's
resume).  Without an output folder the store is a temporary file.
"""

from __future__ import annotations

import contextlib
import json
import logging
import math
import tempfile
from pathlib import Path

from cachetools import LRUCache

from ..core import ParameterError
from ..geometry import get_concept
from .cluster import check_scheduler, local_cluster, workers_machine_holds
from .hashing import context_hash, design_hash
from .point import COLUMNS, model_version
from .runner import run_points
from .settings import EvalSettings
from .store import ResultStore

#: the answers a row carries (name -> unit), in table order
ANSWERS = {
    "engagement_rpm": "rpm", "engagement_rpm_with_ripple": "rpm", "slip_rpm": "rpm",
    "torque_at_max_engine_torque_Nm": "N m", "torque_margin_Nm": "N m", "max_von_mises_Pa": "Pa",
    "safety_factor": "-", "fatigue_safety_factor": "-", "mass_kg": "kg", "contact_arc_deg": "deg", "contact_share": "-",
}

_ACTIVE: dict = {"scheduler": None, "workers": None}
#: the study rows of the designs this process evaluated without a store of its own, by (design
#: hash, context hash): the design with its model version, the engine and requirements: a design asked for
#: again (a sensitivity's base in a tolerance, an allocation and a robust round; a search
#: returning to a point) is not solved again
RECENT_ROWS: LRUCache = LRUCache(maxsize=4096)
log = logging.getLogger("clutchfem")


@contextlib.contextmanager
def shared_cluster(workers: int | None = None, scheduler: str | None = None):
    """Keep one ``dask.distributed`` local cluster (``workers`` process workers, one thread
    each, as the study engine starts its own) for every :func:`evaluate_many` inside the
    block; ``scheduler``: use an existing cluster instead; ``workers=0``: this process."""
    if scheduler is not None and workers is not None:
        raise ParameterError("workers", workers, "no --workers with --scheduler (the cluster has its own)")
    if scheduler is not None:
        scheduler = check_scheduler(scheduler)  # before any work: a typo is said at once
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 0):
        raise ParameterError("workers", workers, "an integer >= 0 (0: in this process, no Dask)")
    prev = dict(_ACTIVE)
    local = None
    try:
        if scheduler is None and workers != 0:
            n, why = workers_machine_holds(workers)
            if why:
                log.warning(why)
            local = local_cluster(n)
            _ACTIVE.update(scheduler=local.scheduler_address, workers=None)
        else:
            _ACTIVE.update(scheduler=scheduler, workers=workers)
        yield _ACTIVE.get("scheduler") or ("in process" if workers == 0 else None)
    finally:
        _ACTIVE.clear()
        _ACTIVE.update(prev)
        if local is not None:
            local.close(timeout=10)


def _num(x):
    if x is None:
        return None
    try:
        x = float(x)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def from_study_row(r: dict, point: dict) -> dict:
    """A study engine row (:data:`clutchfem.evaluation.COLUMNS`, MPa and g) as a row of this
    package (SI units, the point's ``--set`` texts)."""
    row = {"params": dict(point), "status": r.get("status") or "failed", "message": r.get("message") or "",
           "design_hash": r.get("design_hash"), "seconds": _num(r.get("t_total_s"))}
    if row["status"] != "ok":
        return row
    mpa, g = _num(r.get("max_von_mises_MPa")), _num(r.get("part_mass_g"))
    ys = _num(r.get("yield_strength_MPa"))
    row.update({
        "engagement_rpm": _num(r.get("engagement_rpm")), "engagement_rpm_with_ripple": _num(r.get("engagement_ripple_rpm")),
        "slip_rpm": _num(r.get("slip_rpm")), "slip_status": r.get("slip_status"),
        "torque_at_max_engine_torque_Nm": _num(r.get("torque_at_max_engine_torque_Nm")),
        "torque_margin_Nm": _num(r.get("torque_margin_Nm")),
        "max_von_mises_Pa": None if mpa is None else mpa * 1e6, "safety_factor": _num(r.get("safety_factor")),
        "fatigue_safety_factor": _num(r.get("fatigue_safety_factor")), "fatigue_cycle": r.get("fatigue_cycle"),
        "mass_kg": None if g is None else g * 1e-3,
        "shoe_mass_kg": None if _num(r.get("shoe_mass_g")) is None else _num(r.get("shoe_mass_g")) * 1e-3,
        "contact_arc_deg": _num(r.get("contact_arc_deg")),
        "contact_share": _num(r.get("contact_arc_fraction")),
        "engagement_ok": bool(r.get("engagement_ok")), "slip_ok": bool(r.get("slip_ok")),
        "engagement_limit_rpm": _num(r.get("engagement_limit_rpm")), "slip_limit_rpm": _num(r.get("slip_limit_rpm")),
        "max_engine_rpm": _num(r.get("max_engine_rpm")), "rpm_max_engine_torque": _num(r.get("rpm_max_engine_torque")),
        "max_engine_torque_Nm": _num(r.get("max_engine_torque_Nm")),
        "yield_strength_Pa": None if ys is None else ys * 1e6,
        "warnings": [w for w in (r.get("warnings") or "").split("\n") if w], "elements": r.get("n_elements"),
        "worker": r.get("worker"), "mesh_morphed": r.get("mesh_morphed"), "morph_note": r.get("morph_note"),
        "contact_sets": json.loads(r["contact_sets"]) if r.get("contact_sets") else None})
    return row


def evaluate_many(points: list[dict], settings: EvalSettings, workers: int | None = None, on_row=None,
                  progress: bool = False) -> list[dict]:
    """Evaluate ``points`` on the study engine (module docstring); rows in the order of the
    points, each with its index ``i``.  Inside :func:`shared_cluster` its cluster is used, else
    ``workers`` (None: one per core; 0: this process) as the study engine starts them;
    ``on_row(row)`` is called for every row once the batch is done; ``progress``: the study
    engine's progress bar on stderr."""
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 0):
        raise ParameterError("workers", workers, "an integer >= 0 (parallel design evaluations; 0: this process)")
    rows: list[dict | None] = [None] * len(points)
    st = settings.study()
    todo, vals = [], {}
    for i, pt in enumerate(points):  # refusals cost nothing: nothing is sent for them
        try:
            settings.params(pt)
        except ParameterError as exc:
            rows[i] = {"i": i, "params": dict(pt), "status": "refused", "message": str(exc),
                       "refused_parameter": exc.name, "seconds": 0.0}
            continue
        P = get_concept(settings.concept).Params
        vals[i] = P.parse_assignments([f"{k}={v}" for k, v in pt.items()])
        todo.append(i)
    if todo:
        tmp = None
        store = settings.store
        ctx = context_hash(st)
        keys = [design_hash(vals[i], st) for i in todo]
        by_key = {}
        if store is None:  # no store of the caller's: the rows of this process's recent designs serve
            by_key = {k: dict(RECENT_ROWS[k, ctx]) for k in keys if (k, ctx) in RECENT_ROWS}
            tmp = tempfile.TemporaryDirectory(prefix="clutchfem-targets-")
            store = str(Path(tmp.name) / "results.sqlite")
        try:
            new = [i for i, k in zip(todo, keys) if k not in by_key]
            if new:
                sched = _ACTIVE.get("scheduler")
                w = None if sched else (workers if workers is not None else _ACTIVE.get("workers"))
                run_points([vals[i] for i in new], st, store, workers=w, scheduler=sched, progress=progress,
                           source="clutchfem.evaluation", desc="designs")
                version = model_version(settings.concept)
                with ResultStore(store, COLUMNS, context=ctx) as rs:
                    df = rs.frame(version, sorted({k for k in keys if k not in by_key}))
                for r in json.loads(df.to_json(orient="records")):
                    by_key[r["design_hash"]] = r
                    if r.get("status") == "ok":
                        RECENT_ROWS[r["design_hash"], ctx] = dict(r)
            for i, k in zip(todo, keys):
                r = by_key.get(k)
                rows[i] = from_study_row(r, points[i]) if r is not None else {
                    "params": dict(points[i]), "status": "failed", "message": "no row in the study store"}
        finally:
            if tmp is not None:
                tmp.cleanup()
    for i, r in enumerate(rows):
        r["i"] = i
        if on_row:
            on_row(r)
    return rows  # type: ignore[return-value]
