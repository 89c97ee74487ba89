"""One design of a study -> one row: the only module of :mod:`clutchfem.evaluation` that knows
the analysis API.

:func:`evaluate` takes a *point* (the varied inputs, ``{name: value}`` in the parameter's
own unit: m, deg, -) and the study's fixed :class:`Settings`, builds the design (concept
parameters -> mesh -> :class:`~clutchfem.loadcase.Design`, one FE model), runs the full
:func:`clutchfem.analysis.analyze` and flattens the answers into one flat row of
:data:`COLUMNS`.  Everything else in the package (spec, sampling, hashing, store,
scheduling, resume, progress, charts, guidelines) sees only these rows, so a change of the
analysis API is a change of this file alone (and :data:`COLUMNS` is the contract).

Status of a row (house rule, also in the CLI help):

* ``ok``: answered;
* ``refused``: the *input* was refused on purpose with a message (a
  :class:`~clutchfem.core.ParameterError` of the concept's cross-parameter rules, an
  :class:`~clutchfem.core.InputError`, a :class:`~clutchfem.core.GeometryError` or
  :class:`~clutchfem.core.MeshError`: the parameters do not make a part);
* ``failed``: the design is valid but no answer came: a
  :class:`~clutchfem.core.SolverError` (the solver's own checks refuse to answer), any
  other exception (a bug: its type and message are recorded), or the worker process died
  while computing it (a gmsh crash; recorded by the scheduler, :func:`failed_row`).

Timings (s): ``t_mesh_s`` geometry + gmsh + reading the mesh (or a cache hit),
``t_assembly_s`` stiffness, load, constraints and mass matrix, ``t_solve_s`` the
factorisation, the unit-load solve and the spin-softening (Ritz) set-up of every load case,
``t_analysis_s`` the rest of ``analyze`` (contact solves, slip bracketing, stresses, shoe
model, whirl), ``t_total_s`` the wall time of :func:`evaluate` and ``t_cpu_s`` the CPU time
of the worker process meanwhile (on a shared machine the difference is time spent waiting
for a core).
"""

from __future__ import annotations

import hashlib
import math
import os
import socket
import tempfile
import time
import traceback
from pathlib import Path

from ..analysis import Requirements, analyze
from ..clutch import EngineCurve
from ..core import ClutchfemError, GeometryError, InputError, MeshError, ParameterError, dumps, tune_malloc
from ..geometry import MeshSettings, get_concept
from ..loadcase import Design, model_version
from ..mesh import load_user_geometry, mesh_concept, morph_or_mesh
from .settings import Settings

#: the row: (column, SQL type, meaning with unit).  The store creates its table from it.
COLUMNS: tuple[tuple[str, str, str], ...] = (
    ("design_hash", "TEXT", "the design's identity hash (12 hex, clutchfem.loadcase.identity): the hash analyze, "
                            "solve, report, export and the app give the same design"),
    ("context_hash", "TEXT", "what the study adds to the design (engine curve, idle speed, requirement factors, "
                             "morph reference), 12 hex: a row is keyed by design, context and model version"),
    ("model_version", "TEXT", "clutchfem version + hash of the model's source (answers change with it)"),
    ("status", "TEXT", "ok | refused | failed"),
    ("message", "TEXT", "why refused / the error of a failed point"),
    ("design", "TEXT", "concept name or user mesh file name"),
    ("point_json", "TEXT", "the varied inputs of this point, JSON {name: value in the parameter's unit}"),
    ("inputs_json", "TEXT", "every defining input (parameters with defaults, settings), JSON"),
    ("engagement_rpm", "REAL", "static engagement speed [rpm] (FE)"),
    ("engagement_ripple_rpm", "REAL", "engagement with the 2-stroke speed ripple (3 sigma cycle) [rpm]"),
    ("engagement_ripple_typical_rpm", "REAL", "engagement with the ripple, typical cycle [rpm]"),
    ("slip_rpm", "REAL", "slip speed, drum held, full throttle [rpm] (empty if none)"),
    ("slip_status", "TEXT", "slips | holds at start | never holds | never engages"),
    ("rpm_max_engine_torque", "REAL", "rpm of the engine's maximum torque [rpm]"),
    ("max_engine_torque_Nm", "REAL", "engine's maximum torque [N m]"),
    ("torque_at_max_engine_torque_Nm", "REAL", "clutch torque (FE) at the rpm of max engine torque [N m]"),
    ("torque_margin_Nm", "REAL", "clutch torque - engine max torque at that rpm [N m]"),
    ("max_engine_rpm", "REAL", "engine's maximum speed, where stress is read [rpm]"),
    ("max_von_mises_MPa", "REAL", "peak von Mises stress at the engine's maximum speed [MPa]"),
    ("safety_factor", "REAL", "yield strength / peak von Mises at the engine's maximum speed [-]"),
    ("yield_strength_MPa", "REAL", "material yield strength Rp0.2 [MPa]"),
    ("fatigue_safety_factor", "REAL", "fatigue safety factor: load multiplier to Miner sum 1 at the worst point "
                                      "(Goodman, ASSUMED duty) [-] (empty: no fatigue data)"),
    ("fatigue_cycle", "TEXT", "the cycle that governs the fatigue safety factor"),
    ("shoe_mass_g", "REAL", "mass of one shoe zone [g]"),
    ("part_mass_g", "REAL", "mass of the whole one-piece part [g]"),
    ("contact_arc_deg", "REAL", "shoe arc in contact at the rpm of max engine torque [deg]"),
    ("nominal_arc_deg", "REAL", "nominal shoe arc (lining angles phi2 - phi1) [deg]"),
    ("contact_arc_fraction", "REAL", "contact arc / nominal arc [-]"),
    ("contact_sets", "TEXT", "the contact nodes carrying load at the slip speed, the rpm of max engine torque and "
                             "the max engine rpm, JSON {slip|torque|peak: [node indices]}: designs morphed from one "
                             "reference share the numbering; a change between neighbours is a kink of those answers"),
    ("spring_force_N", "REAL", "flexure force at engagement F_f = m R_Tp w_e^2 per shoe [N]"),
    ("character", "TEXT", "plus | minus | neutral (FE: friction raises/lowers the normal force)"),
    ("first_touch", "TEXT", "where the shoe touches first: tip | root | middle"),
    ("engagement_ok", "INTEGER", "engagement with ripple > a x idle rpm (1/0)"),
    ("slip_ok", "INTEGER", "slip rpm < b x rpm of max engine torque (1/0)"),
    ("stress_ok", "INTEGER", "safety factor >= min_safety_factor at the engine's maximum speed (1/0)"),
    ("feasible", "INTEGER", "all three requirements met (1/0)"),
    ("engagement_limit_rpm", "REAL", "a x idle rpm [rpm]"),
    ("slip_limit_rpm", "REAL", "b x rpm of max engine torque [rpm]"),
    ("min_safety_factor", "REAL", "required safety factor at the engine's maximum speed [-]"),
    ("errors_estimated", "INTEGER", "1: the error bands below were computed (the design on a mesh twice as fine)"),
    ("engagement_err_rpm", "REAL", "error band of engagement_rpm: discretisation + model form [rpm]"),
    ("engagement_disc_rpm", "REAL", "its discretisation part 2|a_h - a_h/2| [rpm]"),
    ("slip_err_rpm", "REAL", "error band of slip_rpm [rpm]"),
    ("slip_disc_rpm", "REAL", "its discretisation part [rpm]"),
    ("torque_err_Nm", "REAL", "error band of torque_at_max_engine_torque_Nm [N m]"),
    ("torque_disc_Nm", "REAL", "its discretisation part [N m]"),
    ("stress_err_MPa", "REAL", "error band of max_von_mises_MPa [MPa]"),
    ("stress_disc_MPa", "REAL", "its discretisation part [MPa]"),
    ("n_elements", "INTEGER", "triangles in the mesh"),
    ("mesh_morphed", "INTEGER", "1: the mesh was morphed from the study's reference design (answers smooth in the "
                                "parameters); 0: meshed from scratch (empty: the study morphs nothing)"),
    ("morph_note", "TEXT", "why a morph was refused (the mesh was then made from scratch), or its quality"),
    ("mesh_cached", "INTEGER", "mesh read from the content-hash cache (1/0)"),
    ("t_mesh_s", "REAL", "geometry + meshing (or cache read) [s]"),
    ("t_assembly_s", "REAL", "assembly of K, load, constraints, mass [s]"),
    ("t_solve_s", "REAL", "factorisation, unit-load solve, softening set-up [s]"),
    ("t_analysis_s", "REAL", "analysis steps (contact, slip, stress, shoe model, whirl) [s]"),
    ("t_total_s", "REAL", "wall time of the point on its worker [s]"),
    ("t_cpu_s", "REAL", "CPU time of the worker process during the point [s] (< t_total_s: waiting for a core)"),
    ("worker", "TEXT", "host:pid of the process that computed it"),
    ("finished_at", "REAL", "when it finished (Unix time) [s]"),
    ("warnings", "TEXT", "the analysis warnings, one per line"),
)
COLUMN_NAMES: tuple[str, ...] = tuple(c for c, _, _ in COLUMNS)

#: answers a study charts and ranks (column, label with unit)
ANSWERS: tuple[tuple[str, str], ...] = (
    ("engagement_rpm", "engagement [rpm]"),
    ("engagement_ripple_rpm", "engagement with ripple [rpm]"),
    ("slip_rpm", "slip speed [rpm]"),
    ("torque_at_max_engine_torque_Nm", "torque at max engine torque [N m]"),
    ("max_von_mises_MPa", "peak von Mises at max rpm [MPa]"),
    ("safety_factor", "safety factor at max rpm [-]"),
    ("shoe_mass_g", "shoe mass [g]"),
    ("part_mass_g", "part mass [g]"),
    ("contact_arc_deg", "contact arc at max engine torque [deg]"),
)


# ---------------------------------------------------------------------------------------
# one point
# ---------------------------------------------------------------------------------------
def _json(obj) -> str:
    return dumps(obj, sort_keys=True)


def _base_row(point: dict, settings: Settings, design_hash: str, version: str) -> dict:
    row = dict.fromkeys(COLUMN_NAMES)
    row.update(design_hash=design_hash, model_version=version, design=settings.design_name,
               point_json=_json(point), min_safety_factor=settings.min_safety_factor,
               worker=f"{socket.gethostname()}:{os.getpid()}")
    return row


def failed_row(point: dict, settings: Settings, design_hash: str, version: str, message: str) -> dict:
    """A ``failed`` row written by the scheduler side (the worker died, or the task could not
    run): inputs and the error, no answers."""
    row = _base_row(point, settings, design_hash, version)
    row.update(status="failed", message=message, finished_at=time.time(),
               worker=None, inputs_json=_json({"settings": settings.canonical(), "point": point}))
    return row


def split_point(point: dict, settings: Settings) -> tuple[dict, dict]:
    """(concept parameters, operating-point settings) of a point: for a concept a name is
    a concept parameter if the concept has it, else an operating-point field; for a user
    mesh every name is an operating-point field."""
    if settings.concept is None:
        return {}, dict(point)
    fields = get_concept(settings.concept).Params.model_fields
    geo = {k: v for k, v in point.items() if k in fields}
    return geo, {k: v for k, v in point.items() if k not in fields}


def _user_mesh_path(settings: Settings) -> Path:
    """The user mesh as a file on this worker (written once per content hash)."""
    sha = hashlib.sha256(settings.mesh_bytes).hexdigest()[:16]
    suffix = Path(settings.mesh_file).suffix or ".msh"
    path = Path(tempfile.gettempdir()) / f"clutchfem-study-{sha}{suffix}"
    if not path.exists():
        tmp = path.with_name(f"{path.name}.{os.getpid()}.tmp")
        tmp.write_bytes(settings.mesh_bytes)
        os.replace(tmp, path)
    return path


def _num(x) -> float | None:
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def evaluate(point: dict, settings: Settings, design_hash: str = "", errors: bool = False) -> dict:
    """Build, mesh and analyse one design; return its row (see module docstring).  Never
    raises for a bad design: the status and message say what happened.  ``errors``: also
    estimate the error of the main answers (analyze's step 10: the design again on a mesh
    twice as fine, about 3x the time; a study does it for a sample of its points)."""
    t0, c0 = time.perf_counter(), time.process_time()
    version = model_version(settings.concept)
    row = _base_row(point, settings, design_hash, version)
    try:
        geo, opv = split_point(point, settings)
        op = settings.op.replace(**opv) if opv else settings.op
        row["inputs_json"] = _json({"settings": settings.canonical(), "point": point,
                                    "op": op.model_dump(mode="json")})
        t = time.perf_counter()
        if settings.concept is not None:
            concept = get_concept(settings.concept)
            params = concept.Params(**{**dict(settings.fixed), **geo})
            row["inputs_json"] = _json({"settings": settings.canonical(), "point": point,
                                        "params": params.model_dump(mode="json"),
                                        "op": op.model_dump(mode="json")})
            ms = settings.mesh if settings.mesh is not None else MeshSettings.preset(op.fidelity)
            if settings.morph is None:
                cm = mesh_concept(concept, params, ms)
            else:
                cm = morph_or_mesh(concept, params, ms, reference=concept.Params(**dict(settings.morph)))
            name = concept.name
        else:
            params = None
            cm = load_user_geometry(_user_mesh_path(settings), mesh_size=settings.mesh.size if settings.mesh
                                    else None, thickness=op.thickness, drum_radius=op.drum_radius)
            name = settings.design_name
        t_mesh = time.perf_counter() - t
        t = time.perf_counter()
        design = Design(cm, op, params=params, name=name, concept=concept if params is not None else None,
                        mesh_settings=ms if params is not None else None)
        t_design = time.perf_counter() - t
        engine = settings.engine if settings.engine is not None else EngineCurve.default()
        t = time.perf_counter()
        an = analyze(design, engine=engine, requirements=Requirements(a=settings.a, b=settings.b),
                     idle_rpm=settings.idle_rpm, errors=errors)
        t_an = time.perf_counter() - t
    except (ParameterError, InputError, GeometryError, MeshError) as exc:
        row.update(status="refused", message=str(exc))
    except ClutchfemError as exc:  # SolverError and the like: a valid design without an answer
        row.update(status="failed", message=f"{type(exc).__name__}: {exc}")
    except Exception as exc:  # noqa: BLE001 - a bug must not stop a study; recorded with its place
        where = traceback.extract_tb(exc.__traceback__)[-1]
        row.update(status="failed", message=f"{type(exc).__name__}: {exc} "
                                            f"(at {Path(where.filename).name}:{where.lineno})")
    else:
        _fill(row, an, design, settings, cm)
        tm = getattr(design.model, "timings", {})
        assembly = t_design + tm.get("mass_s", 0.0)
        solve = tm.get("factorize_s", 0.0) + tm.get("solve_u1_s", 0.0) + sum(
            getattr(c, "setup_s", 0.0) for c in getattr(design, "_cases", {}).values())
        row.update(status="ok", message=None, t_mesh_s=t_mesh, t_assembly_s=assembly, t_solve_s=solve,
                   t_analysis_s=max(t_an - tm.get("mass_s", 0.0) - solve, 0.0))
    row["t_total_s"] = time.perf_counter() - t0
    row["t_cpu_s"] = time.process_time() - c0
    row["finished_at"] = time.time()
    return row


def _fill(row: dict, an, design, settings: Settings, cm) -> None:
    """The answers of one :class:`~clutchfem.analysis.Analysis` into ``row``."""
    req = an.requirements
    shoes = (an.part or {}).get("shoes") or []
    shoe_kg = shoes[0]["mass_kg"] if shoes else (an.coupling or {}).get("m_kg")
    nominal = None
    if an.coupling and "phi1_deg" in an.coupling:
        nominal = an.coupling["phi2_deg"] - an.coupling["phi1_deg"]
    arc = _num(an.contact_arc_at_max_engine_torque_deg)
    sf = _num(an.safety_factor)
    stress_ok = sf is not None and sf >= settings.min_safety_factor
    row.update(
        engagement_rpm=_num(an.engagement_rpm), engagement_ripple_rpm=_num(an.engagement_rpm_with_ripple),
        engagement_ripple_typical_rpm=_num(an.engagement_rpm_with_ripple_typical),
        slip_rpm=_num(an.slip_rpm), slip_status=an.slip_status,
        rpm_max_engine_torque=_num(an.rpm_max_engine_torque), max_engine_torque_Nm=_num(an.max_engine_torque_Nm),
        torque_at_max_engine_torque_Nm=_num(an.torque_at_max_engine_torque_Nm),
        torque_margin_Nm=_num(an.torque_margin_Nm), max_engine_rpm=_num(an.max_engine_rpm),
        max_von_mises_MPa=_num(an.max_von_mises_Pa / 1e6), safety_factor=sf,
        yield_strength_MPa=_num(an.yield_strength_Pa / 1e6),
        fatigue_safety_factor=_num(getattr(an, "fatigue_safety_factor", None)),
        fatigue_cycle=getattr(an, "fatigue_governing_cycle", None),
        shoe_mass_g=_num(shoe_kg * 1e3) if shoe_kg is not None else None,
        part_mass_g=_num(an.part["mass_kg"] * 1e3) if an.part and "mass_kg" in an.part else None,
        contact_arc_deg=arc, nominal_arc_deg=_num(nominal),
        contact_arc_fraction=_num(arc / nominal) if arc is not None and nominal else None,
        spring_force_N=_num((an.coupling or {}).get("F_f_N")),
        character=an.shoe_character, first_touch=an.first_touch,
        engagement_ok=int(bool(req["engagement_ok"])), slip_ok=int(bool(req["slip_ok"])),
        stress_ok=int(stress_ok),
        feasible=int(bool(req["engagement_ok"]) and bool(req["slip_ok"]) and stress_ok),
        engagement_limit_rpm=_num(req["engagement_limit_rpm"]), slip_limit_rpm=_num(req["slip_limit_rpm"]),
        n_elements=cm.n_elements, mesh_cached=int(bool(cm.cached)),
        mesh_morphed=None if cm.morph is None else int(bool(cm.morph.get("morphed"))),
        morph_note=_morph_note(cm.morph),
        warnings="\n".join(an.warnings) or None,
        contact_sets=_json(an.contact_sets) if getattr(an, "contact_sets", None) else None,
    )
    err = getattr(an, "errors", None) or {}
    if err:
        row["errors_estimated"] = 1
        for q, name, scale in (("engagement_rpm", "engagement", 1.0), ("slip_rpm", "slip", 1.0),
                               ("torque_at_max_engine_torque_Nm", "torque", 1.0), ("max_von_mises_Pa", "stress", 1e-6)):
            e = err.get(q) or {}
            unit = {"engagement": "rpm", "slip": "rpm", "torque": "Nm", "stress": "MPa"}[name]
            row[f"{name}_err_{unit}"] = _num(e["total"] * scale) if e.get("total") is not None else None
            row[f"{name}_disc_{unit}"] = (_num(e["discretisation"] * scale) if e.get("discretisation") is not None
                                          else None)
    else:
        row["errors_estimated"] = 0


def _morph_note(info: dict | None) -> str | None:
    if not info:
        return None
    if not info.get("morphed"):
        return f"meshed from scratch: {info.get('reason', '')}"
    q = info.get("quality") or {}
    return (f"morphed: largest node move {info.get('max_node_move_m', 0.0) * 1e3:.4g} mm, shape distortion "
            f"{q.get('max_distortion', float('nan')):.3f}, min scaled Jacobian {q.get('min_scaled_jacobian', float('nan')):.3f}")


def warm_up(concept: str | None = None) -> str:
    """Prepare a fresh worker, so that the first point does not pay for it: the analysis
    stack is imported with this module (the worker imports it to run :func:`warm_up`), the
    allocator is tuned and the concept loaded; returns the worker's model version."""
    tune_malloc()  # a worker process runs design after design: freed arrays stay for the next

    if concept:
        get_concept(concept)
    return model_version(concept)


#: error columns of a row: (answer, total band, discretisation part, unit)
ERROR_COLUMNS = (("engagement_rpm", "engagement_err_rpm", "engagement_disc_rpm", "rpm"),
                 ("slip_rpm", "slip_err_rpm", "slip_disc_rpm", "rpm"),
                 ("torque_at_max_engine_torque_Nm", "torque_err_Nm", "torque_disc_Nm", "N m"),
                 ("max_von_mises_MPa", "stress_err_MPa", "stress_disc_MPa", "MPa"))
