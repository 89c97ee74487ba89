"""One design point -> one row of answers, and the one function that evaluates batches.

A *point* is a dict ``name -> --set text`` (``{"flexure_thickness": "2.13mm"}``) applied on
top of a base design (:class:`EvalSettings`); the design evaluated is exactly the one
``clutchfem analyze --concept C --set ...`` builds from the same texts
(:mod:`clutchfem.targets.values`).  A *row* is a flat, JSON-ready dict: the point, a
``status`` and the answers the targets need (engagement with ripple, slip, torque, peak
stress and safety factor at the engine's maximum speed, part mass, contact arc, the
requirement checks) -- the answers of :func:`clutchfem.clutch.analyze.analyze` with
``errors=False`` (a study ranks designs on one mesh; the error of an answer is stated for
the design it ends on).

Statuses: ``ok``; ``refused`` (the parameter set refuses the combination: a
:class:`~clutchfem.errors.ParameterError`, checked in the calling process before any work);
``failed`` (any other clutchfem error: geometry, mesh, solver -- e.g. a part whose shoes fly
out below the engine's maximum speed); ``crashed`` (the evaluating process died: gmsh aborts
the process on some high-order mesh fix-ups, measured on concept 4 corners); ``timeout``.

:func:`evaluate_many` is the only place where batches run (optimiser generations, Monte
Carlo samples).  Until the study engine of issue 10 is on main it is a local process pool
in which every design runs in its own *forked* process: a gmsh abort or a runaway solve
costs one row, not the run, and the parent keeps no gmsh state.  Forking copies the parent's
imported modules, so a process costs milliseconds, not an interpreter start.  Workers
default to the number of usable cores, at most 2 (the machine this was built on has 2).
"""

from __future__ import annotations

import math
import multiprocessing as mp
import os
import time
from dataclasses import dataclass, field
from multiprocessing.connection import wait

from ..errors import ClutchfemError, ParameterError

#: the answers a row carries (name -> unit), in table order
ANSWERS = {
    "engagement_rpm": "rpm", "engagement_rpm_with_ripple": "rpm", "slip_rpm": "rpm",
    "torque_at_max_engine_torque_Nm": "N m", "torque_margin_Nm": "N m", "max_von_mises_Pa": "Pa",
    "safety_factor": "-", "mass_kg": "kg", "contact_arc_deg": "deg", "contact_share": "-",
}


@dataclass(frozen=True)
class EvalSettings:
    """Everything but the point: the concept, the base design's ``--set`` texts, the mesh
    size, the operating point overrides, the engine and the requirement factors."""

    concept: str
    base: tuple[str, ...] = ()
    mesh_size: float | None = None
    op: dict = field(default_factory=dict)
    engine_csv: str | None = None
    idle_rpm: float | None = None
    a: float = 1.3
    b: float = 1.0
    timeout_s: float = 600.0

    def params(self, point: dict | None = None):
        """The concept's parameter set for ``point`` on the base (raises ParameterError)."""
        from ..geometry import get_concept

        P = get_concept(self.concept).Params
        values = P.parse_assignments(list(self.base))
        if point:
            values.update(P.parse_assignments([f"{k}={v}" for k, v in point.items()]))
        return P(**values)

    def engine(self):
        from ..clutch.engine import EngineCurve

        return EngineCurve.from_csv(self.engine_csv, idle_rpm=self.idle_rpm) if self.engine_csv \
            else EngineCurve.default()

    def operating_point(self):
        from ..operating import OperatingPoint

        return OperatingPoint(**self.op)

    def mesh_settings(self):
        from ..geometry import MeshSettings

        return MeshSettings() if self.mesh_size is None else MeshSettings(size=self.mesh_size)

    def set_args(self, point: dict | None = None) -> list[str]:
        """The ``--set`` arguments of the base plus the point (the point wins)."""
        names = set(point or {})
        out = [a for a in self.base if a.split("=", 1)[0].strip() not in names]
        return out + [f"{k}={v}" for k, v in (point or {}).items()]


def evaluate_one(point: dict, settings: EvalSettings) -> dict:
    """Evaluate one point in this process (see module docstring for the row)."""
    from ..clutch.analyze import Requirements, analyze
    from ..design import Design
    from ..geometry import get_concept
    from ..traceability import design_hash

    t0 = time.perf_counter()
    row = {"params": dict(point), "status": "ok", "message": ""}
    try:
        p = settings.params(point)
    except ParameterError as exc:
        return {**row, "status": "refused", "message": str(exc), "refused_parameter": exc.name,
                "seconds": time.perf_counter() - t0}
    try:
        engine = settings.engine()
        d = Design.from_concept(get_concept(settings.concept), p, settings.operating_point(),
                                settings.mesh_settings())
        an = analyze(d, engine=engine, requirements=Requirements(a=settings.a, b=settings.b),
                     idle_rpm=settings.idle_rpm, errors=False)
    except ClutchfemError as exc:
        return {**row, "status": "failed", "message": f"{type(exc).__name__}: {exc}",
                "seconds": time.perf_counter() - t0}
    nominal = an.coupling.get("phi2_deg", math.nan) - an.coupling.get("phi1_deg", math.nan)
    req = an.requirements
    row.update({
        "engagement_rpm": an.engagement_rpm, "engagement_rpm_with_ripple": an.engagement_rpm_with_ripple,
        "slip_rpm": an.slip_rpm, "slip_status": an.slip_status,
        "torque_at_max_engine_torque_Nm": an.torque_at_max_engine_torque_Nm, "torque_margin_Nm": an.torque_margin_Nm,
        "max_von_mises_Pa": an.max_von_mises_Pa, "safety_factor": an.safety_factor,
        "mass_kg": an.part.get("mass_kg"), "contact_arc_deg": an.contact_arc_at_max_engine_torque_deg,
        "contact_share": an.contact_arc_at_max_engine_torque_deg / nominal if nominal and math.isfinite(nominal)
        else None,
        "engagement_ok": req["engagement_ok"], "slip_ok": req["slip_ok"],
        "engagement_limit_rpm": req["engagement_limit_rpm"], "slip_limit_rpm": req["slip_limit_rpm"],
        "max_engine_rpm": an.max_engine_rpm, "rpm_max_engine_torque": an.rpm_max_engine_torque,
        "max_engine_torque_Nm": an.max_engine_torque_Nm, "yield_strength_Pa": an.yield_strength_Pa,
        "warnings": list(an.warnings), "design_hash": design_hash(d), "elements": d.cm.n_elements,
        "seconds": time.perf_counter() - t0})
    return row


def _child(conn, point, settings):  # runs in the forked process
    try:
        row = evaluate_one(point, settings)
    except BaseException as exc:  # noqa: BLE001 - report anything, the parent decides
        row = {"params": dict(point), "status": "failed", "message": f"{type(exc).__name__}: {exc}"}
    try:
        conn.send(row)
    finally:
        conn.close()


def default_workers() -> int:
    try:
        n = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        n = os.cpu_count() or 1
    return max(1, min(2, n))


def evaluate_many(points: list[dict], settings: EvalSettings, workers: int | None = None,
                  on_row=None) -> list[dict]:
    """Evaluate ``points`` (see module docstring); rows in the order of the points, each with
    its index ``i``.  ``workers``: parallel processes (default :func:`default_workers`; 1
    still isolates each design in a child process); ``on_row(row)`` is called as each row
    arrives (progress)."""
    if workers is None:
        workers = default_workers()
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ParameterError("workers", workers, "an integer >= 1 (parallel design evaluations)")
    rows: list[dict | None] = [None] * len(points)
    todo = []
    for i, pt in enumerate(points):  # refusals cost nothing: no process for them
        try:
            settings.params(pt)
            todo.append(i)
        except ParameterError as exc:
            rows[i] = {"i": i, "params": dict(pt), "status": "refused", "message": str(exc),
                       "refused_parameter": exc.name, "seconds": 0.0}
            if on_row:
                on_row(rows[i])
    ctx = mp.get_context("fork")
    running: dict = {}
    while todo or running:
        while todo and len(running) < workers:
            i = todo.pop(0)
            r, w = ctx.Pipe(duplex=False)
            proc = ctx.Process(target=_child, args=(w, points[i], settings), daemon=True)
            proc.start()
            w.close()
            running[i] = (proc, r, time.monotonic())
        ready = wait([r for _, r, _ in running.values()], timeout=1.0)
        now = time.monotonic()
        for i, (proc, r, t_start) in list(running.items()):
            row = None
            if r in ready:
                try:
                    row = r.recv()
                except (EOFError, OSError):
                    proc.join(5)
                    row = {"params": dict(points[i]), "status": "crashed",
                           "message": f"the evaluating process died (exit code {proc.exitcode}): gmsh or a "
                                      "native library aborted on this design"}
            elif now - t_start > settings.timeout_s:
                proc.terminate()
                row = {"params": dict(points[i]), "status": "timeout",
                       "message": f"no answer within {settings.timeout_s:g} s"}
            if row is None:
                continue
            proc.join(5)
            r.close()
            del running[i]
            row.setdefault("seconds", now - t_start)
            row["i"] = i
            rows[i] = row
            if on_row:
                on_row(row)
    return rows  # type: ignore[return-value]
