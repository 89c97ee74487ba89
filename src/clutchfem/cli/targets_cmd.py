"""``clutchfem optimize | tolerance | compensate | report``: design to targets (issue 11).

Thin: parse the options, call :mod:`clutchfem.targets`, print a table (or ``--json``), write
the output folder (charts, tables, JSON, inputs, ``report.html`` + ``report.md``)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import List, Optional

import typer
from rich.markup import escape
from rich.table import Table

from ..core import ClutchfemError, InputError, ParameterError
from .common import check_out_dir, console, err, fail, length_option

_WORKERS = "local Dask cluster of N process workers (default: one per core; 0: in this process)"
_SCHED = "address of an existing dask.distributed scheduler, e.g. tcp://10.0.0.5:8786 (instead of --workers)"


def _settings(concept: str, set_: list[str], mesh_size, engine, idle_rpm, a, b, mu=None, out=None, sf=1.5):
    from ..geometry import get_concept
    from ..studies import EvalSettings

    c = get_concept(concept)
    c.Params.from_assignments(set_)  # refuse a bad --set before any work
    op = {}
    if mu is not None:
        from ..loadcase import OperatingPoint

        op["mu"] = OperatingPoint.parse_assignments([f"mu={mu}"])["mu"]
    if idle_rpm is not None and not (isinstance(idle_rpm, (int, float)) and 0 < idle_rpm < 1e6):
        raise ParameterError("idle_rpm", idle_rpm, "an idle speed > 0 rpm")
    from ..analysis import Requirements

    Requirements(a=a, b=b)
    from ..studies import STORE_NAME

    s = EvalSettings(concept=c.name, base=tuple(set_), mesh_size=length_option("size", mesh_size), op=op,
                     engine_csv=str(engine) if engine else None, idle_rpm=idle_rpm, a=a, b=b, min_safety_factor=sf,
                     store=str(Path(out) / STORE_NAME) if out is not None else None)
    s.engine()  # a bad engine CSV is refused here
    return s


def _limits(settings):
    """(engagement limit a x idle, slip limit b x rpm of max torque) [rpm] of the settings."""
    from ..analysis import DEFAULT_IDLE_RPM

    eng = settings.engine()
    idle = settings.idle_rpm or eng.idle_rpm or DEFAULT_IDLE_RPM
    return settings.a * idle, settings.b * float(eng.rpm_max_torque)


def _write_common(out: Path, page, files: list):
    from ..report import write_page

    h, m = write_page(page, out)
    files += [h, m, out / "inputs.json", out / "page.json"]
    for f in files:
        err.print(f"wrote {escape(str(f))}")


def optimize(
    concept: str = typer.Argument(..., help="concept name"),
    set_: List[str] = typer.Option([], "--set", help="start design: parameter override name=value"),
    engage_rpm: Optional[str] = typer.Option(None, "--engage-rpm", help="engagement with ripple LO:HI [rpm] "
                                             "(default: LO = a x idle, no HI; 'LO:' or ':HI' for one side)"),
    slip_rpm_max: Optional[float] = typer.Option(None, "--slip-rpm-max", help="slip speed limit [rpm] (default: b x rpm "
                                                 "of max engine torque)"),
    safety_factor_min: float = typer.Option(1.5, "--safety-factor-min", help="minimum safety factor against yield at "
                                            "the engine's maximum speed [-]"),
    fatigue_min: Optional[float] = typer.Option(None, "--fatigue-min", help="minimum fatigue safety factor (analyze's "
                                                "fatigue step: Goodman, Miner, ASSUMED duty) [-] (default: no target; "
                                                "the final design's value is reported)"),
    free: Optional[str] = typer.Option(None, "--free", help="comma-separated parameters to vary (default: the concept's "
                                       "shape parameters)"),
    range_: List[str] = typer.Option([], "--range", help="search range name=LO:HI with units, e.g. "
                                     "flexure_thickness=1mm:3mm (default: the declared range)"),
    objective: str = typer.Option("mass", "--objective", help="mass (minimise part mass) or torque-margin "
                                  "(maximise torque over the max engine torque)"),
    sample: int = typer.Option(32, "--sample", help="space-filling (Sobol) designs before the pattern search"),
    max_evals: int = typer.Option(300, "--max-evals", help="budget of analysed designs (refusals are free)"),
    workers: Optional[int] = typer.Option(None, "--workers", help=_WORKERS),
    scheduler: Optional[str] = typer.Option(None, "--scheduler", help=_SCHED),
    engine: Optional[Path] = typer.Option(None, "--engine", help="engine torque CSV (columns rpm, torque [N m])"),
    idle_rpm: Optional[float] = typer.Option(None, "--idle-rpm", help="engine idle speed [rpm] (default 2700, ASSUMED)"),
    a: float = typer.Option(1.3, "--a", help="engagement > a x idle rpm (ASSUMED default)"),
    b: float = typer.Option(1.0, "--b", help="slip < b x rpm of max torque (ASSUMED default)"),
    mesh_size: Optional[str] = typer.Option(None, "--mesh-size", help="global element size (unit suffix: mm)"),
    out: Optional[Path] = typer.Option(None, "--out", help="folder for the path, charts and report"),
    json_: bool = typer.Option(False, "--json", help="print the result as one JSON object"),
):
    """Find a design that meets the targets at least part mass (or largest torque margin)."""
    from ..studies import Targets
    from ..studies import optimize as run

    try:
        check_out_dir(out)
        s = _settings(concept, set_, mesh_size, engine, idle_rpm, a, b, out=out, sf=safety_factor_min)
        lo_def, slip_def = _limits(s)
        lo, hi = lo_def, None
        if engage_rpm is not None:
            parts = engage_rpm.split(":")
            if len(parts) != 2:
                raise ParameterError("engage_rpm", engage_rpm, "LO:HI in rpm (e.g. 3600:5000, '3600:' or ':5000')",
                                     "--engage-rpm")
            try:
                lo = float(parts[0]) if parts[0].strip() else None
                hi = float(parts[1]) if parts[1].strip() else None
            except ValueError:
                raise ParameterError("engage_rpm", engage_rpm, "LO:HI in rpm (numbers)", "--engage-rpm") from None
        t = Targets(lo, hi, slip_rpm_max if slip_rpm_max is not None else slip_def, safety_factor_min, objective,
                    fatigue_min=fatigue_min)
        P = type(s.params())
        names = [x.strip() for x in free.split(",") if x.strip()] if free else None
        ranges = {}
        for item in range_:
            if "=" not in item or ":" not in item.split("=", 1)[1]:
                raise ParameterError("range", item, "name=LO:HI (e.g. flexure_thickness=1mm:3mm)", "--range")
            n, r = item.split("=", 1)
            n = n.strip()
            if n not in P.model_fields:
                raise ParameterError(n, item, "a parameter of the concept", "--range")
            lo_s, hi_s = r.split(":", 1)
            ranges[n] = (P._parse_value(n, lo_s), P._parse_value(n, hi_s))
        res = run(s, t, names, ranges=ranges or None, sample=sample, max_evals=max_evals, workers=workers,
                  scheduler=scheduler, log=lambda m: err.print(escape(m)))
        final = None
        if out is not None or not json_:
            final = _final_analysis(s, res)
        if out is not None:
            import pandas as pd

            from ..core import write
            from ..report import optimization_page

            files = [write(out / "optimization.json", res.to_json(), indent=1)]
            df = pd.DataFrame([{**{"n": r["n"], "phase": r.get("phase"), "status": r["status"],
                                   "feasible": r.get("assessment", {}).get("h", math.inf) <= 0},
                                **{f"param:{k}": v for k, v in r["params"].items()},
                                **{k: r.get(k) for k in ("engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm",
                                                         "torque_at_max_engine_torque_Nm", "max_von_mises_Pa",
                                                         "safety_factor", "fatigue_safety_factor", "mass_kg",
                                                         "message")}} for r in res.path])
            df.to_csv(out / "optimization_path.csv", index=False)
            files.append(out / "optimization_path.csv")
            page = optimization_page(res, final, out)
            files.append(out / "optimization_path.png")
            _write_common(out, page, files)
        if json_:
            from ..core import dumps

            d = res.to_json()
            d.pop("path")
            d["path_length"] = len(res.path)
            print(dumps(d))
            return
        _print_optimization(res, final)
    except ClutchfemError as exc:
        fail(exc)


def _final_analysis(s, res):
    """The final design analysed again with the error estimate (for the report)."""
    from ..analysis import Requirements, analyze
    from ..geometry import get_concept
    from ..loadcase import Design

    p = s.params(res.best["params"])
    d = Design.from_concept(get_concept(s.concept), p, s.operating_point(), s.mesh_settings())
    return analyze(d, engine=s.engine(), requirements=Requirements(a=s.a, b=s.b), idle_rpm=s.idle_rpm, errors=True)


def _print_optimization(res, final):
    from ..studies import DIMENSIONLESS, fatigue_note

    a = res.best["assessment"]
    t = Table(title=escape(f"{res.concept}: {res.message}"))
    t.add_column("target")
    t.add_column("value", justify="right")
    t.add_column("limit", justify="right")
    t.add_column("binds")
    for c in a["constraints"]:
        sf = c["key"] in DIMENSIONLESS
        v = c["value"]
        vs = "none" if v is None else (f"{v:.2f}" if sf else f"{v:.0f} rpm")
        err_txt = ""
        if final is not None and not sf:
            e = (final.errors or {}).get("engagement_rpm" if "engagement" in c["key"] else c["key"])
            if e and e.get("total") is not None:
                err_txt = f" (+- {e['total']:.0f} rpm)"
        t.add_row(escape(c["name"]), escape(vs + err_txt), escape(f"{c['sense']} " + (f"{c['limit']:.2f}" if sf else
                                                                                     f"{c['limit']:.0f} rpm")),
                  "VIOLATED" if c.get("violated") else ("yes" if c["binds"] else "no"))
    console.print(t)
    p = Table(title="parameters")
    p.add_column("parameter")
    p.add_column("start", justify="right")
    p.add_column("final", justify="right")
    for n in res.free:
        p.add_row(escape(n), escape(res.start_texts.get(n, "")), escape(res.params_texts.get(n, ""))
                  + (" (range end)" if n in res.at_bounds else ""))
    console.print(p)
    obj = (f"part mass {res.best['mass_kg'] * 1e3:.1f} g" if res.targets.objective == "mass"
           else f"torque margin {res.best['torque_margin_Nm']:+.2f} N m")
    console.print(f"objective: {obj}; evaluations: {sum(res.evaluations.values())} "
                  f"({', '.join(f'{k} {v}' for k, v in res.evaluations.items() if v)}); time {res.seconds:.0f} s")
    fnote = fatigue_note(res)
    if fnote:
        console.print(f"[yellow]{escape(fnote)}[/yellow]")
    console.print("verify: clutchfem analyze --concept " + escape(res.concept) + " "
                  + " ".join(f"--set {escape(x)}" for x in res.set_args), soft_wrap=True)


def tolerance(
    concept: str = typer.Argument(..., help="concept name"),
    tol: List[str] = typer.Option(..., "--tol", help="tolerance name=+-value with its unit, e.g. "
                                  "flexure_thickness=+-0.05mm (repeat for each dimension)"),
    n: int = typer.Option(64, "--n", help="number of Monte Carlo parts"),
    dist: str = typer.Option("normal", "--dist", help="normal (tolerance = +-3 sigma, ASSUMED) or uniform"),
    seed: int = typer.Option(1, "--seed", help="random seed (the same seed draws the same parts)"),
    shifts: bool = typer.Option(True, "--shifts/--no-shifts", help="also shift each toleranced length by +-0.2 and "
                                "+-0.5 mm alone (the thesis's '0.2-0.5 mm' question)"),
    set_: List[str] = typer.Option([], "--set", help="nominal design: parameter override name=value"),
    safety_factor_min: float = typer.Option(1.5, "--safety-factor-min", help="spec: minimum safety factor [-]"),
    workers: Optional[int] = typer.Option(None, "--workers", help=_WORKERS),
    scheduler: Optional[str] = typer.Option(None, "--scheduler", help=_SCHED),
    engine: Optional[Path] = typer.Option(None, "--engine", help="engine torque CSV (columns rpm, torque [N m])"),
    idle_rpm: Optional[float] = typer.Option(None, "--idle-rpm", help="engine idle speed [rpm] (default 2700, ASSUMED)"),
    a: float = typer.Option(1.3, "--a", help="spec: engagement > a x idle rpm (ASSUMED default)"),
    b: float = typer.Option(1.0, "--b", help="spec: slip < b x rpm of max torque (ASSUMED default)"),
    mesh_size: Optional[str] = typer.Option(None, "--mesh-size", help="global element size (unit suffix: mm)"),
    out: Optional[Path] = typer.Option(None, "--out", help="folder for histograms, ranking, samples and report"),
    json_: bool = typer.Option(False, "--json", help="print the result as one JSON object"),
):
    """Monte Carlo of manufacturing tolerances: spread, share out of spec, ranking of dimensions."""
    from ..studies import Targets, parse_tolerance
    from ..studies import tolerance as run

    try:
        check_out_dir(out)
        s = _settings(concept, set_, mesh_size, engine, idle_rpm, a, b, out=out, sf=safety_factor_min)
        P = type(s.params())
        tols = {}
        for item in tol:
            name, t = parse_tolerance(P, item)
            if name in tols:
                raise ParameterError(name, item, "one tolerance per dimension (given twice)", "--tol")
            tols[name] = t
        lo, slip = _limits(s)
        res = run(s, tols, n=n, dist=dist, seed=seed, targets=Targets(lo, None, slip, safety_factor_min),
                  shifts=shifts, workers=workers, scheduler=scheduler, log=lambda m: err.print(escape(m)))
        if out is not None:
            import pandas as pd

            from ..core import write
            from ..report import tolerance_page

            files = [write(out / "tolerance.json", res.to_json(), indent=1)]
            pd.DataFrame([{**{f"d:{k}": v for k, v in r.get("d", {}).items()}, "status": r["status"],
                           **{k: r.get(k) for k in ("engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm",
                                                    "max_von_mises_Pa", "safety_factor",
                                                    "torque_at_max_engine_torque_Nm", "mass_kg")},
                           **{f"param:{k}": v for k, v in r["params"].items()}} for r in res.rows]).to_csv(
                out / "tolerance_samples.csv", index=False)
            files += [out / "tolerance_samples.csv", out / "tolerance_histograms.png", out / "tolerance_ranking.png"]
            page = tolerance_page(res, out, {"nominal_design": _design_inputs(s), "run": {"tolerances_si": tols,
                                  "n": n, "dist": dist, "seed": seed}})
            _write_common(out, page, files)
        if json_:
            from ..core import dumps

            d = res.to_json()
            d.pop("samples")
            print(dumps(d))
            return
        _print_tolerance(res)
    except ClutchfemError as exc:
        fail(exc)


def _design_inputs(s) -> dict:
    from ..geometry import get_concept
    from ..loadcase import Design, design_inputs

    d = Design.from_concept(get_concept(s.concept), s.params(), s.operating_point(), s.mesh_settings())
    return {**design_inputs(d), "engine": s.engine_csv or "built-in (ASSUMED shape)", "requirements": {"a": s.a, "b": s.b}}


def _print_tolerance(res):
    t = Table(title=escape(f"{res.concept}: {res.n} parts ({res.dist})"))
    t.add_column("answer")
    t.add_column("nominal", justify="right")
    t.add_column("mean +- sd", justify="right")
    t.add_column("min .. max", justify="right")
    for key, st in res.stats.items():
        if st["mean"] is None:
            continue
        sc, u = st["scale"], st["unit"]
        t.add_row(escape(st["label"]), escape(f"{st['nominal'] * sc:.4g} {u}" if st["nominal"] is not None else "-"),
                  escape(f"{st['mean'] * sc:.4g} +- {st['sd'] * sc:.3g} {u}"),
                  escape(f"{st['min'] * sc:.4g} .. {st['max'] * sc:.4g} {u}"))
    console.print(t)
    o = Table(title="share of parts out of spec (95 % Wilson interval)")
    o.add_column("spec")
    o.add_column("out of spec", justify="right")
    for name, v in res.out_of_spec.items():
        o.add_row(escape(name), escape(f"{100 * v['share']:.1f} % [{100 * v['ci95'][0]:.1f}, {100 * v['ci95'][1]:.1f}] "
                                       f"({v['k']} of {v['n']})"))
    console.print(o)
    for key, rk in res.ranking.items():
        if key not in ("engagement_rpm", "slip_rpm", "max_von_mises_Pa"):
            continue
        r = Table(title=escape(f"ranking for {rk['label']} (SRC, R^2 = {rk['r2']:.3f} "
                               f"[{rk['r2_ci95'][0]:.3f}, {rk['r2_ci95'][1]:.3f}])"))
        r.add_column("dimension")
        r.add_column("SRC [95 % CI]", justify="right")
        r.add_column("slope", justify="right")
        for it in rk["items"]:
            r.add_row(escape(it["name"]), escape(f"{it['src']:+.3f} [{it['ci95'][0]:+.3f}, {it['ci95'][1]:+.3f}]"),
                      escape(f"{it['slope']:+.4g} {it['slope_unit']}"))
        console.print(r)
    if res.shifts:
        s = Table(title="one dimension shifted alone (the thesis's 0.2-0.5 mm)")
        for c in ("dimension", "shift", "engagement", "stiffness change"):
            s.add_column(c, justify="right" if c != "dimension" else "left")
        for x in res.shifts:
            s.add_row(escape(x["name"]), escape(f"{x['shift_m'] * 1e3:+.1f} mm"),
                      escape(f"{x['engagement_rpm']:.0f} rpm ({x['engagement_change_pct']:+.1f} %)"
                             if x["engagement_rpm"] else x["status"]),
                      escape(f"{x['stiffness_change_pct']:+.1f} %" if x["stiffness_change_pct"] is not None else "-"))
        console.print(s)
    for n_ in res.notes:
        console.print(f"[dim]note: {escape(n_)}[/]")


def compensate(
    concept: str = typer.Argument(..., help="concept name"),
    rpm: float = typer.Option(..., "--rpm", help="speed [rpm] at which the pressure should be even"),
    target_arc: float = typer.Option(0.8, "--target-arc", help="share of the nominal shoe arc to load evenly [-]"),
    arc_start: Optional[float] = typer.Option(None, "--arc-start", help="start of the target arc as a share of the "
                                              "shoe from its root (default: placed for the most even pressure)"),
    mean_clearance: Optional[str] = typer.Option(None, "--mean-clearance", help="mean clearance over the target arc "
                                                 "(default: the design's own there; unit suffix mm)"),
    max_iter: int = typer.Option(8, "--max-iter", help="most rebuilds of the fixed point"),
    set_: List[str] = typer.Option([], "--set", help="design: parameter override name=value"),
    engine: Optional[Path] = typer.Option(None, "--engine", help="engine torque CSV (for the before/after analysis)"),
    mesh_size: Optional[str] = typer.Option(None, "--mesh-size", help="global element size (unit suffix: mm)"),
    out: Optional[Path] = typer.Option(None, "--out", help="folder for the charts, tables and report"),
    json_: bool = typer.Option(False, "--json", help="print the result as one JSON object"),
):
    """Shoe profile (table of clearances) that spreads the contact pressure evenly at --rpm."""
    from ..analysis import analyze
    from ..clutch import EngineCurve
    from ..geometry import MeshSettings, get_concept
    from ..loadcase import Design
    from ..studies import compensate as run

    try:
        check_out_dir(out)
        c = get_concept(concept)
        p = c.Params.from_assignments(set_)
        size = length_option("size", mesh_size)
        ms = MeshSettings() if size is None else MeshSettings(size=size)
        mc = None
        if mean_clearance is not None:
            mc = c.Params._parse_value("clearance", mean_clearance)
        eng = EngineCurve.from_csv(engine) if engine else EngineCurve.default()
        res = run(c, p, rpm, target_arc, arc_start=arc_start, mean_clearance=mc, mesh_settings=ms,
                  max_iter=max_iter, log=lambda m: err.print(escape(m)))
        before = analyze(Design.from_concept(c, res.before, None, ms), engine=eng, errors=False)
        after = analyze(Design.from_concept(c, res.after, None, ms), engine=eng, errors=False)
        from ..report import compare_rows

        rows = compare_rows(res, before, after)
        if out is not None:
            from ..core import write
            from ..report import compensation_page

            doc = _comp_json(res, rows)
            files = [write(out / "compensation.json", doc, indent=1)]
            import pandas as pd

            for tag, st in (("before", res.state_before), ("after", res.state_after)):
                pd.DataFrame({"s": st.s, "clearance_m": st.clearance_m, "free_displacement_m": st.free_m,
                              "pressure_Pa": st.pressure_Pa, "force_N": st.force_N}).to_csv(
                    out / f"pressure_{tag}.csv", index=False)
                files.append(out / f"pressure_{tag}.csv")
            page = compensation_page(res, before, after, eng, out, {"before": before.inputs, "after": after.inputs,
                                                                    "run": doc["run"]})
            files += [out / "compensation_profile.png", out / "compensation_torque.png",
                      out / "compensation_convergence.png"]
            _write_common(out, page, files)
        if json_:
            from ..core import dumps

            print(dumps(_comp_json(res, rows)))
            return
        t = Table(title=escape(f"{res.concept}: profile compensated at {res.rpm:.0f} rpm over "
                               f"{100 * res.target_arc:.0f} % of the shoe arc"))
        t.add_column("answer")
        t.add_column("before", justify="right")
        t.add_column("after", justify="right")
        for q, x, y in rows:
            t.add_row(escape(q), escape(x), escape(y))
        console.print(t)
        console.print(f"{'converged' if res.converged else 'NOT converged'} in {len(res.steps) - 1} rebuilds, "
                      f"{res.seconds:.0f} s; pressure cv over the target arc {res.steps[-1].measured_cv:.3f}")
        console.print("profile: " + " ".join(f"--set {escape(k)}={escape(v)}" for k, v in res.after_texts.items()),
                      soft_wrap=True)
        for n_ in res.notes:
            console.print(f"[dim]note: {escape(n_)}[/]")
    except ClutchfemError as exc:
        fail(exc)


def _comp_json(res, rows) -> dict:
    from ..core import clean

    return clean({
        "concept": res.concept, "rpm": res.rpm, "target_arc": res.target_arc, "arc": list(res.arc),
        "mean_clearance_m": res.mean_clearance_m, "converged": res.converged, "seconds": res.seconds,
        "params": res.after_texts, "set": [f"{k}={v}" for k, v in res.after_texts.items()],
        "before_after": [{"answer": q, "before": x, "after": y} for q, x, y in rows],
        "contact_share_before": res.state_before.contact_share, "contact_share_after": res.state_after.contact_share,
        "torque_at_rpm_before_Nm": res.state_before.torque_Nm, "torque_at_rpm_after_Nm": res.state_after.torque_Nm,
        "steps": [{k: v for k, v in s.__dict__.items()} for s in res.steps], "notes": res.notes,
        "run": {"rpm": res.rpm, "target_arc": res.target_arc, "arc": list(res.arc),
                "mean_clearance_m": res.mean_clearance_m},
        "units": {"rpm": "1/min", "lengths": "m", "pressure": "Pa", "torque": "N m", "share": "-"}})


def report(
    concept: Optional[str] = typer.Option(None, "--concept", help="concept name"),
    set_: List[str] = typer.Option([], "--set", help="concept parameter override name=value"),
    mesh: Optional[Path] = typer.Option(None, "--mesh", help="user mesh (.msh / STEP), as in analyze"),
    drum_radius: Optional[str] = typer.Option(None, "--drum-radius", help="drum inner radius (--mesh only)"),
    thickness: Optional[str] = typer.Option(None, "--thickness", help="axial thickness (--mesh only)"),
    run_dir: Optional[Path] = typer.Option(None, "--run", help="render a run folder (optimize / tolerance / "
                                           "compensate / any folder of CSV and PNG) again"),
    engine: Optional[Path] = typer.Option(None, "--engine", help="engine torque CSV"),
    mesh_size: Optional[str] = typer.Option(None, "--mesh-size", help="global element size (unit suffix: mm)"),
    errors: bool = typer.Option(True, "--errors/--no-errors", help="estimate the error of the main answers "
                                "(a mesh twice as fine: ~3x the time)"),
    out: Optional[Path] = typer.Option(None, "--out", help="output folder (default: the --run folder)"),
):
    """One-page report (self-contained HTML + Markdown) of a design or of a run folder."""
    try:
        given = sum(x is not None for x in (concept, mesh, run_dir))
        if given != 1:
            raise InputError("give exactly one of --concept NAME, --mesh FILE or --run DIR")
        if run_dir is not None:
            from ..report import folder_page, write_page

            if not Path(run_dir).is_dir():
                raise InputError(f"--run {run_dir}: not a folder")
            target = check_out_dir(out) or Path(run_dir)
            page = folder_page(Path(run_dir))
            if target != Path(run_dir):  # figures travel with the page
                import shutil

                for f in Path(run_dir).glob("*.png"):
                    shutil.copy2(f, target / f.name)
            h, m = write_page(page, target)
            err.print(f"wrote {escape(str(h))}\nwrote {escape(str(m))}")
            return
        if out is None:
            raise InputError("--out DIR is required: the folder for report.html, report.md, the images and inputs.json")
        check_out_dir(out)
        from ..analysis import analyze
        from ..clutch import EngineCurve
        from ..loadcase import OperatingPoint
        from ..report import design_page, write_page
        from .common import load_design

        if concept is not None and (drum_radius is not None or thickness is not None):
            raise InputError("--drum-radius and --thickness apply to --mesh only")
        if mesh is not None and drum_radius is None:
            raise InputError("report --mesh needs --drum-radius (the drum's inner radius, e.g. 35mm)")
        given_op = {k: v for k, v in (("drum_radius", drum_radius), ("thickness", thickness)) if v is not None}
        op = OperatingPoint(**OperatingPoint.parse_assignments([f"{k}={v}" for k, v in given_op.items()]))
        eng = EngineCurve.from_csv(engine) if engine else EngineCurve.default()
        design, c, p = load_design(concept, set_, mesh, length_option("size", mesh_size), "sector", op)
        an = analyze(design, engine=eng, errors=errors)
        page = design_page(an, design, eng, out, c, p)
        from ..core import write

        files = [write(out / "analysis.json", an.to_json(), indent=1)]
        an.curves.to_csv(out / "curves.csv", index=False)
        files += [out / "curves.csv", out / "torque_rpm.png", out / "arc_stress_rpm.png"]
        _write_common(out, page, files)
    except ClutchfemError as exc:
        fail(exc)
