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
import itertools
import json
import logging
import math
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from cachetools import LRUCache

from ..clutch import EngineCurve
from ..core import InputError, ParameterError, changed_texts, exact_text
from ..geometry import MeshSettings, get_concept
from ..loadcase import Design, OperatingPoint
from .cluster import check_scheduler, local_cluster, workers_machine_holds
from .hashing import context_hash, design_hash
from .point import COLUMNS, Settings, model_version
from .runner import run_points
from .store import STORE_NAME, ResultStore

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


@dataclass(frozen=True)
class EvalSettings:
    """Everything but the point: the concept, the base design's ``--set`` texts, the mesh
    size, the operating point overrides, the engine and the requirement factors; ``store``:
    the study store file (None: a temporary one per batch); ``min_safety_factor`` enters the
    study rows' own feasibility flag (and their design hash).  Usually made from a design
    (:meth:`from_design`); optimisation, tolerances and sensitivities take it in place of one.

    Parameters
    ----------
    concept : str
    base : tuple of str
        The base design's ``name=value`` texts (``"flexure_thickness=2.4mm"``).
    mesh_size : float, optional
        Global element size [m] (default: the fidelity's).
    op : dict
        Operating point fields that differ from :class:`~clutchfem.OperatingPoint`'s defaults.
    engine_csv, curve : optional
        The engine curve (a CSV path, or an :class:`~clutchfem.EngineCurve`; default built-in).
    idle_rpm : float, optional
    a, b, min_safety_factor : float
        Requirement factors and the rows' yield safety factor.
    store : str, optional

    Examples
    --------
    >>> import clutchfem as cf
    >>> es = cf.EvalSettings("concept1", base=("flexure_thickness=2.4mm",), mesh_size=0.003)
    >>> es.values({"clearance": "0.5mm"}), es.set_args({"clearance": "0.5mm"})
    ({'flexure_thickness': 0.0024, 'clearance': 0.0005}, ['flexure_thickness=2.4mm', 'clearance=0.5mm'])
    >>> es.params().flexure_thickness, es.mesh_settings().size
    (0.0024, 0.003)
    """

    concept: str
    base: tuple[str, ...] = ()
    mesh_size: float | None = None
    op: dict = field(default_factory=dict)
    engine_csv: str | None = None
    idle_rpm: float | None = None
    a: float = 1.3
    b: float = 1.0
    min_safety_factor: float = 1.5
    store: str | None = None
    #: an engine curve given as an object (the API); wins over ``engine_csv``
    curve: EngineCurve | None = None
    #: morph the designs' meshes from this reference design ((name, SI value) pairs,
    #: :attr:`clutchfem.evaluation.Settings.morph`); None: mesh every design from scratch
    morph: tuple | None = None
    #: the mesh settings as an object (the API; a guideline study's): wins over ``mesh_size``
    mesh: MeshSettings | None = None
    #: ((name, half-width SI), ...): a design is admitted only if the concept's rules also
    #: hold at every corner of this tolerance box around it (robust design: every part a
    #: drawing's tolerances allow can be built, :func:`.robust.robust_optimize`)
    tolerance_box: tuple | None = None

    @classmethod
    def from_design(cls, design, *, engine=None, idle_rpm: float | None = None, requirements=None,
                    min_safety_factor: float = 1.5, store: str | None = None,
                    out: str | Path | None = None) -> "EvalSettings":
        """The settings whose base design is ``design`` (a concept's :class:`~clutchfem.Design`:
        its parameters as exact ``--set`` texts, its operating point and mesh size), with the
        engine (an :class:`~clutchfem.EngineCurve` or the path of its CSV; default: the
        built-in curve), the idle speed and the requirement factors of ``requirements``
        (default: a = 1.3, b = 1.0); the store: ``store``, or ``out/results.sqlite`` in a run's
        output folder ``out`` (None: a temporary store per batch)."""
        if store is None and out is not None:
            store = str(Path(out) / STORE_NAME)
        if not isinstance(design, Design):
            raise InputError(f"a design study needs a clutchfem Design (Design.from_concept), not "
                             f"{type(design).__name__}")
        if design.params is None:
            raise InputError(f"{design.name}: a user mesh has no concept parameters to vary; studies, optimisation "
                             "and tolerances work on a concept's design (Design.from_concept)")
        P = type(design.params)
        base = tuple(f"{k}={v}" for k, v in changed_texts(design.params).items())
        op0 = OperatingPoint()
        op = {k: getattr(design.op, k) for k in OperatingPoint.model_fields
              if getattr(design.op, k) != getattr(op0, k) and k not in ("rpm",)}
        if "material" in op:
            op["material"] = op["material"].model_dump()
        if design.op.fidelity == "live":  # its designs are evaluated by the FE it stands for: the best path
            op["fidelity"] = "best"
            if op0.fidelity == "best":
                del op["fidelity"]
        size = design.mesh_settings.size
        size = None if size is None or size == MeshSettings.preset(design.op.fidelity).size else float(size)
        req_a = getattr(requirements, "a", 1.3)
        req_b = getattr(requirements, "b", 1.0)
        P(**P.parse_assignments(list(base)))  # the texts read back as this design
        csv = str(engine) if isinstance(engine, (str, Path)) else None
        curve = engine if isinstance(engine, EngineCurve) else None
        return cls(concept=design.name, base=base, mesh_size=size, op=op, engine_csv=csv, idle_rpm=idle_rpm, a=req_a,
                   b=req_b, min_safety_factor=min_safety_factor, store=store, curve=curve)

    def params(self, point: dict | None = None):
        """The concept's parameter set for ``point`` on the base (raises ParameterError)."""
        P = get_concept(self.concept).Params
        vals = self.values(point)
        p = P(**vals)
        if self.tolerance_box:
            box_corners(P, dict(vals, **{n: getattr(p, n) for n, _ in self.tolerance_box}), self.tolerance_box)
        return p

    def values(self, point: dict | None = None) -> dict:
        """Parameter values (SI) of the base plus the point, as the parser reads the texts."""
        P = get_concept(self.concept).Params
        values = P.parse_assignments(list(self.base))
        if point:
            values.update(P.parse_assignments([f"{k}={v}" for k, v in point.items()]))
        return values

    def engine(self):
        if self.curve is not None:
            return self.curve
        return EngineCurve.from_csv(self.engine_csv, idle_rpm=self.idle_rpm) if self.engine_csv \
            else EngineCurve.default()

    def operating_point(self):
        return OperatingPoint(**self.op)

    def mesh_settings(self):
        """``mesh`` if given, else the fidelity's mesh (:meth:`MeshSettings.preset`), with
        ``mesh_size`` if given."""
        if self.mesh is not None:
            return self.mesh
        return MeshSettings.preset(self.operating_point().fidelity,
                                   **({} if self.mesh_size is None else {"size": self.mesh_size}))

    def set_args(self, point: dict | None = None) -> list[str]:
        """The ``--set`` arguments of the base plus the point (the point wins)."""
        names = set(point or {})
        out = [a for a in self.base if a.split("=", 1)[0].strip() not in names]
        return out + [f"{k}={v}" for k, v in (point or {}).items()]

    def study(self):
        """The study engine's :class:`clutchfem.evaluation.Settings` (the base as fixed values)."""
        fixed = tuple(sorted(self.values().items()))
        return Settings(concept=self.concept, fixed=fixed, op=self.operating_point(), mesh=self.mesh_settings(),
                        engine=self.engine() if (self.engine_csv or self.curve is not None) else None, idle_rpm=self.idle_rpm, a=self.a,
                        b=self.b, min_safety_factor=self.min_safety_factor, morph=self.morph)


def box_corners(P, values: dict, box) -> None:
    """Raise the concept's ParameterError, prefixed by the corner, where its rules refuse a
    corner of the tolerance ``box`` ((name, half-width), ...) around ``values`` (SI): for a
    rule linear in the toleranced dimensions the box is admissible iff its corners are."""
    for signs in itertools.product((1.0, -1.0), repeat=len(box)):
        corner = dict(values)
        for (n, t), sg in zip(box, signs):
            corner[n] = values[n] + sg * t
        try:
            P(**corner)
        except ParameterError as exc:
            at = ", ".join(f"{n} {'+' if sg > 0 else '-'}{exact_text(P, n, t)}" for (n, t), sg in zip(box, signs))
            raise ParameterError(exc.name, exc.value, f"{exc.allowed} -- at the tolerance corner {at}: a part "
                                 "within the drawing's tolerances could not be built", exc.context,
                                 shown=exc.shown) from None


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
