"""Running a guideline study (:mod:`.guidelines`) on the study engine: its designs, the
elasticity table, the ranking, the one-at-a-time table and the files.

:func:`run_guidelines` sends every remeshed design of :func:`~.guidelines.plan` (the
one-at-a-time sweeps; with the remeshed check its seven-point designs) to
:func:`~.runner.run_points` (Dask, the SQLite store, resume; the design point also gets its
error estimate), computes the design sensitivities on morphed meshes
(:func:`~.sensitivity.sensitivities`, into the same store: resumed too) at their step and at
ten times it, and, per parameter (and operating input) and answer, the elasticity
(:func:`~.guidelines.morphed_elasticity`, with its method) and the change per designers'
step (0.1 mm, 1 deg, 0.1; per 0.01 of mu, per 100 rpm of idle).  Parameters are ranked by their largest |E| whose derivative is not
unstable.  Written to the output folder: ``guidelines.csv`` (one row per parameter and
answer), ``one_at_a_time.csv``, the charts (:mod:`.guideline_charts`) and
``guidelines.json``.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import pandas as pd

from ..core import InputError, ParameterError, changed_texts, write
from ..evaluation import (
    COLUMNS,
    ERROR_COLUMNS,
    STORE_NAME,
    EvalSettings,
    ResultStore,
    design_hash,
    operating_inputs,
    run_points,
    sensitivities,
)
from ..geometry import get_concept
from ..loadcase import Design, OperatingPoint
from .elasticity import (
    ANSWERS,
    CHECK_FACTOR,
    SENSITIVITY_KEY,
    GuidelineResult,
    GuidelineSettings,
    elasticity,
    morphed_elasticity,
    plan,
)
from .live import live_guidelines


def run_guidelines(gs, out: str | Path, *, params=None, engine=None, requirements=None, workers: int | None = None,
                   scheduler: str | None = None, progress: bool = True, inputs=None,
                   remeshed_check: bool = False, live_check: int = 2) -> GuidelineResult:
    """Design guidelines: which parameter moves which answer, and by how much.

    Per parameter, the elasticity (x / A) dA/dx of every answer at the design (a central
    difference on meshes morphed from the design, checked at ten times the step, its method
    named) and a one-at-a-time sweep over its range; per operating input (mu, the elastic
    drum's wall, the idle speed) the same elasticity on the design's own mesh; run on the
    study engine into ``out`` (store, tables; the charts are drawn by the faces:
    :func:`clutchfem.report.guideline_charts`).

    Parameters
    ----------
    gs : Design or GuidelineSettings
        The design point (a concept's :class:`~clutchfem.Design`), or full settings.
    out : path
        The folder of the store, ``guidelines.csv``, ``one_at_a_time.csv`` and
        ``guidelines.json``.
    params : list of str, optional
        With a ``design``: the parameters to study (default: every continuous one with a
        non-zero value).
    engine, requirements : optional
        With a ``design``: the engine curve and the requirement factors.
    workers, scheduler, progress
        Study engine controls (``workers=0``: in this process).
    inputs : list of str, optional
        With a ``design``: operating inputs to differentiate (default: every one available,
        ``[]``: none).
    remeshed_check : bool
        With a ``design``: also the seven-point fit on remeshed designs (``E_remeshed`` and
        its verdict in each row; six more meshed designs per parameter).
    live_check : int
        With a live ``design`` (its fidelity ``"live"``): the elasticities come from the
        cached reduced model's derivatives, each with its band, and this many parameters
        (the strongest) are also differentiated by the full FE as a check
        (:func:`clutchfem.guidelines.live.live_guidelines`).

    Returns
    -------
    GuidelineResult
        The elasticities (with their method and check verdict) and the one-at-a-time rows.

    Examples
    --------
    >>> import clutchfem as cf, tempfile
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="6mm"))   # coarse: a first look
    >>> g = cf.run_guidelines(d, tempfile.mkdtemp(), params=["flexure_thickness"], workers=0, progress=False,
    ...                       inputs=[])
    >>> e = next(r for r in g.table if r["answer"] == "engagement_rpm")
    >>> e["parameter"], e["E"] > 0, e["verdict"]     # a thicker flexure engages later
    ('flexure_thickness', True, 'stable')
    >>> e["method"]
    'central difference on morphed meshes'
    """
    if isinstance(gs, Design) and gs.op.fidelity == "live":
        res = live_guidelines(gs, params=params, engine=engine, requirements=requirements, check=live_check,
                              workers=0 if workers is None else workers)
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        pd.DataFrame(res.table).to_csv(out / "guidelines.csv", index=False)
        res = replace(res, out=out, files=(out / "guidelines.csv",))
        return res.with_files([])
    if isinstance(gs, Design):
        gs = GuidelineSettings.from_design(gs, params=params, engine=engine, requirements=requirements, inputs=inputs,
                                           remeshed_check=remeshed_check)
    elif not isinstance(gs, GuidelineSettings):
        raise InputError(f"guidelines: a Design or GuidelineSettings, not {type(gs).__name__}")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    points, per = plan(gs)
    es = eval_settings(gs, out)
    available = operating_inputs(es)
    inputs = list(available) if gs.inputs is None else list(gs.inputs)
    if "drum_wall" in inputs and "drum_wall" not in available:  # said before any design is run
        raise ParameterError("inputs", "drum_wall", "operating inputs this design has: " + ", ".join(available)
                             + " (its drum is rigid: no wall to differentiate)",
                             "guidelines")
    zero = [n for n in inputs if n in available and available[n] == 0]
    input_notes = ["operating inputs not studied (zero at the design point, no elasticity): " + ", ".join(zero)] \
        if zero else []  # (x / A) dA/dx is 0 at x = 0 whatever dA/dx is: not a guideline
    inputs = [n for n in inputs if n not in zero]
    names = list(gs.params) + inputs
    run = run_points(points, gs.settings, out / STORE_NAME, workers=workers, scheduler=scheduler,
                     progress=progress, source=f"guidelines {gs.concept}", desc="guidelines",
                     error_points=[0] if gs.errors else [])
    with ResultStore(out / STORE_NAME, COLUMNS, context=run.context_hash) as st:
        df = st.frame(run.model_version, run.keys)
    by_hash = {r["design_hash"]: r for r in df.to_dict("records")}
    base_row = by_hash.get(design_hash({}, gs.settings))
    notes = list(gs.notes) + input_notes
    if base_row is None or base_row["status"] != "ok":
        msg = base_row["message"] if base_row is not None else "not computed"
        raise InputError(f"guidelines {gs.concept}: the design point itself has no answer ({msg})")
    base_errors = {}
    if base_row.get("errors_estimated") == 1:
        for ans, tot, disc, unit in ERROR_COLUMNS:
            base_errors[ans] = {"value": base_row[ans], "band": base_row[tot], "discretisation": base_row[disc],
                                "unit": unit}
            if base_row[tot] is not None and base_row[ans]:
                notes.append(f"design point: {ans} = {base_row[ans]:.4g} +- {base_row[tot]:.3g} {unit} (mesh "
                             f"+- {base_row[disc]:.3g} {unit}, the rest model form): an elasticity says how an answer "
                             "moves, this band how far its value may be off")

    def row_at(name, x):
        if x == per[name]["x0"]:
            return base_row
        return by_hash.get(design_hash({name: x}, gs.settings))

    sens = sensitivities(es, names, workers=workers, scheduler=scheduler)
    check = sensitivities(es, names, workers=workers, scheduler=scheduler,
                          steps={n: CHECK_FACTOR * h for n, h in sens.steps.items()})
    notes += [f"sensitivities: {n}" for n in sens.notes]
    table = []
    for n in names:
        kind = sens.kinds[n]
        x0, unit = sens.values[n], sens.units[n]
        if gs.remeshed_check and kind == "parameter":
            if per[n]["fd_outside"]:
                notes.append(f"{n}: remeshed check: finite-difference values outside its declared range "
                             f"({per[n]['fd_outside']}): those steps are not evaluated")
            refused = [x for x in per[n]["fd"] if (r := row_at(n, x)) is None or r["status"] != "ok"]
            if refused:
                notes.append(f"{n}: remeshed check: no answer at {', '.join(f'{x:.6g}' for x in refused)} {unit} "
                             "(refused/failed): the derivative uses the steps that were answered")
        for col, label in ANSWERS:
            e = morphed_elasticity(sens, check, n, SENSITIVITY_KEY[col])
            a0 = base_row[col]
            if e["verdict"] == "no answer":
                v0 = base_row.get(col)
                e["why"] = (why_no_answer(col, [base_row]) if not (isinstance(v0, (int, float)) and math.isfinite(v0)
                                                                   and v0 > 0)
                            else f"the steps of the difference have no {col} ({e['method']})")
                notes.append(f"{n}: elasticity of {col}: no answer: {e['why']}")
            if gs.remeshed_check and kind == "parameter":
                def value_at(x, col=col, n=n):
                    r = row_at(n, x)
                    return None if r is None or r["status"] != "ok" else r[col]

                rm = elasticity(x0, gs.step, value_at)
                e.update({"E_remeshed": rm["E"], "remeshed_method": rm["method"], "remeshed_verdict": rm["verdict"],
                          "remeshed_spread": rm["spread"], "E_remeshed_half_step": rm["E_half_step"],
                          "E_remeshed_double_step": rm["E_double_step"], "E_remeshed_fit": rm["E_fit"],
                          "remeshed_noise_rel": rm["noise_rel"]})
            per_unit, du = ("0.01", 0.01) if n == "mu" else _per_unit(unit)
            slope = e["E"] * a0 / x0 * du if math.isfinite(e["E"]) and a0 and x0 else math.nan
            table.append({"parameter": n, "kind": kind, "unit": unit, "x0": x0, "answer": col, "label": label,
                          "value_at_x0": a0, **e, f"change_per_{per_unit.replace(' ', '_')}": slope,
                          "per": per_unit})
    # ranking: largest |E| over the answers whose derivative is not unstable
    score = {}
    for n in gs.params:
        es = [abs(t["E"]) for t in table if t["parameter"] == n and t["verdict"] in ("stable", "unchecked")
              and math.isfinite(t["E"])]
        score[n] = max(es) if es else 0.0
    ranking = sorted(gs.params, key=lambda n: -score[n])
    # one-at-a-time table
    oat_rows = []
    for n in gs.params:
        for x in per[n]["oat"]:
            r = row_at(n, x)
            rec = {"parameter": n, "unit": per[n]["unit"], "value": x, "relative": x / per[n]["x0"],
                   "status": None if r is None else r["status"], "message": None if r is None else r["message"]}
            for col, _ in ANSWERS:
                rec[col] = None if r is None or r["status"] != "ok" else r[col]
            oat_rows.append(rec)
    oat = pd.DataFrame(oat_rows)
    files = []
    tpath = out / "guidelines.csv"
    pd.DataFrame(table).to_csv(tpath, index=False)
    opath = out / "one_at_a_time.csv"
    oat.to_csv(opath, index=False)
    files += [tpath, opath]
    res = GuidelineResult(concept=gs.concept, base=gs.base, step=gs.step, table=table, ranking=ranking, oat=oat,
                          files=(*files, out / "guidelines.json"), notes=notes, run=run, base_errors=base_errors,
                          methods={n: next(t["method"] for t in table if t["parameter"] == n) for n in names},
                          inputs=[n for n in names if sens.kinds[n] == "operating input"],
                          remeshed=gs.remeshed_check, out=out)
    write(res.out / "guidelines.json", res.to_json(), indent=1)
    return res


def why_no_answer(col: str, rows: list) -> str:
    """Why an elasticity has no answer, from the rows of the design point (first) and its
    steps: the answer does not exist there (no slip speed: the clutch never holds), is zero
    (a logarithmic derivative needs a positive value), or the steps were refused/failed."""
    base = rows[0]
    v = base.get(col)
    if v is None:
        if col == "slip_rpm":
            return (f"no slip speed at the design point (the clutch {base.get('slip_status') or 'has none'}): "
                    "nothing to differentiate")
        return f"the design point has no {col} (the analysis gives none there)"
    if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
        return (f"{col} = {v:g} at the design point: d ln(answer) needs a positive value (a zero contact arc or "
                "torque: the shoes are not on the drum at the rpm of maximum engine torque)")
    steps = [r for r in rows[1:] if r is not None]
    bad = [r for r in steps if r["status"] != "ok"]
    if len(bad) == len(rows) - 1:
        return f"every step was {bad[0]['status'] if bad else 'not computed'}" + (
            f" ({bad[0]['message']})" if bad and bad[0].get("message") else "")
    missing = [r for r in steps if r["status"] == "ok" and not (isinstance(r.get(col), (int, float))
                                                                  and math.isfinite(r[col]) and r[col] > 0)]
    if missing:
        st = missing[0].get("slip_status")
        return (f"{col} has no positive value at {len(missing)} of the steps"
                + (f" (slip status there: {st})" if col == "slip_rpm" and st else "")
                + ": a difference across it is not a derivative")
    return "too few answered steps on either side of the design point"


def _per_unit(unit: str) -> tuple[str, float]:
    """(the designers' step of a unit, its size in the unit): 0.1 mm, 1 deg, 100 rpm, 0.1
    (a dimensionless parameter; mu: 0.01)."""
    return {"m": ("0.1 mm", 1e-4), "deg": ("1 deg", 1.0), "rpm": ("100 rpm", 100.0)}.get(unit, ("0.1", 0.1))


def eval_settings(gs: GuidelineSettings, out: Path) -> EvalSettings:
    """The :class:`~.batch.EvalSettings` of a guideline study's design point (the same
    parameters, operating point, mesh, engine and requirements; its store the study's), for
    :func:`~.sensitivity.sensitivities`."""
    st = gs.settings
    p0 = get_concept(gs.concept).Params(**gs.base)
    op0 = OperatingPoint()
    op = {k: getattr(st.op, k) for k in OperatingPoint.model_fields
          if getattr(st.op, k) != getattr(op0, k) and k != "rpm"}
    if "material" in op:
        op["material"] = op["material"].model_dump()
    return EvalSettings(concept=gs.concept, base=tuple(f"{k}={v}" for k, v in changed_texts(p0).items()), op=op,
                        mesh=st.mesh, curve=st.engine, idle_rpm=st.idle_rpm, a=st.a, b=st.b,
                        min_safety_factor=st.min_safety_factor, store=str(out / STORE_NAME))
