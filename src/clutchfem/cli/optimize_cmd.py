"""``clutchfem optimize``: a design that meets the targets at least part mass (or with the
largest torque margin), on the study engine."""

from __future__ import annotations

import math
from typing import List, Optional

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError, ParameterError
from . import options as O
from .common import (
    check_cluster,
    check_out_dir,
    console,
    err,
    fail,
    names_from,
    quantity,
    ranges_from,
    study_settings,
    tolerances_from,
    wrote,
)


@O.takes("concept", "set_", "mesh_size", "mu", "fidelity", "engine", "idle_rpm", "a", "b", "workers",
         "scheduler", "out", "json_", live=True)
def optimize(
    o,
    engage_rpm: Optional[str] = typer.Option(None, "--engage-rpm", help="engagement with ripple LO:HI in rpm "
                                             "(default: LO = a x idle, no HI; 'LO:' or ':HI' for one side)",
                                             rich_help_panel="Targets"),
    slip_rpm_max: Optional[str] = typer.Option(None, "--slip-rpm-max", help="slip speed limit, e.g. 8000rpm "
                                               "(default: b x rpm of max engine torque)", rich_help_panel="Targets"),
    safety_factor_min: str = typer.Option("1.5", "--safety-factor-min", help="minimum safety factor against yield "
                                          "at the engine's maximum speed", rich_help_panel="Targets"),
    fatigue_min: Optional[str] = typer.Option(None, "--fatigue-min", help="minimum fatigue safety factor (Goodman, "
                                              "Miner, ASSUMED duty; default: no target)", rich_help_panel="Targets"),
    objective: str = typer.Option("mass", "--objective", help="mass (minimise part mass) or torque-margin "
                                  "(maximise torque over the max engine torque)", rich_help_panel="Targets"),
    free: Optional[str] = typer.Option(None, "--free", help="comma-separated parameters to vary (default: the "
                                       "concept's shape parameters)", rich_help_panel="Search"),
    range_: List[str] = typer.Option([], "--range", help="search range name=LO:HI with units, e.g. "
                                     "flexure_thickness=1mm:3mm (default: the declared range)", rich_help_panel="Search"),
    sample: int = typer.Option(32, "--sample", help="space-filling (Sobol) designs before the pattern search",
                               rich_help_panel="Search"),
    max_evals: int = typer.Option(300, "--max-evals", help="budget of analysed designs (refusals are free; "
                                  "gradient/auto: every design counts)", rich_help_panel="Search"),
    method: Optional[str] = typer.Option(None, "--method", help="pattern (Sobol sample + pattern search), gradient "
                                         "(trust-region SQP on morphed meshes) or auto (gradient, then the pattern "
                                         "search if it found no feasible design); default: auto, with --tol pattern "
                                         "(the robust configuration checked by Monte Carlo)", rich_help_panel="Search"),
    tol: List[str] = typer.Option([], "--tol", help="robust design: tolerance name=+-value with its unit, e.g. "
                                  "flexure_thickness=+-0.05mm (repeat per dimension); every target then holds for "
                                  "the --yield share of parts", rich_help_panel="Robust design"),
    yield_: Optional[str] = typer.Option(None, "--yield", help="share of made parts that must meet every target (with --tol)",
                               rich_help_panel="Robust design"),
    dist: Optional[str] = typer.Option(None, "--dist", help="normal (default: tolerance = +-3 sigma, ASSUMED) or uniform",
                             rich_help_panel="Robust design"),
    model_error: Optional[bool] = typer.Option(None, "--model-error/--no-model-error", help="add each answer's "
                                               "model-error band (as +-2 sigma) to its spread (default: added)",
                                               rich_help_panel="Robust design"),
    check: int = typer.Option(0, "--check", help="Monte Carlo parts through remeshed designs to check the robust "
                              "design's yield (0: none)", rich_help_panel="Robust design"),
    rounds: Optional[int] = typer.Option(None, "--rounds", help="shifted-limit rounds at most after the deterministic "
                               "optimum (default 5; they stop earlier once feasible with converged margins)",
                               rich_help_panel="Robust design"),
    life: Optional[str] = typer.Option(None, "--life", metavar="STARTS", help="design for life: every target still "
                                       "met after STARTS starts (1..1e8): the targets tightened by the start "
                                       "design's drift over its life (clutchfem life, central wear coefficient, "
                                       "25 % reserve), the optimum checked by a full life run, redone once with its "
                                       "own drift if it misses; default: new part only", rich_help_panel="Life"),
):
    """Find a design that meets the targets at least part mass (or largest torque margin);
    with --tol, one whose targets hold for the --yield share of made parts."""
    from .. import Targets, dumps, write_report
    from .. import optimize as run

    try:
        o.scheduler = check_cluster(o.workers, o.scheduler)
        check_out_dir(o.out)
        n_life = None
        if life is not None:
            n_life = quantity("--life", life, "-", 1.0, 1e8)
            if tol:
                raise ParameterError("life", life, "without --tol: the robust design does not yet include the wear; "
                                     "run optimize --tol ... --yield Y without --life, then check its optimum over "
                                     f"the life with clutchfem tolerance CONCEPT --set ... --tol ... --life {life} "
                                     "(the share of parts in spec new and at that many starts; the robust output "
                                     "prints the command)", "option --life")
        robust_only = [(opt, v) for opt, v in (("--yield", yield_), ("--dist", dist), ("--rounds", rounds),
                                               ("--check", check or None),
                                               ("--model-error" if model_error else "--no-model-error",
                                                None if model_error is None else model_error)) if v is not None]
        if robust_only and not tol:  # said before any design is meshed: an option that does not apply
            opt, v = robust_only[0]
            raise ParameterError(opt.lstrip("-").replace("-", "_").replace("no_", ""), v, "an option of the robust "
                                 "design only: give the tolerances with --tol name=+-value", f"option {opt}")
        live = str(o.fidelity or "").strip().lower() == "live"
        if live:  # said before any work: what the live search does not take
            given = [(opt, v) for opt, v in (("--life", life), ("--range", " ".join(range_)), ("--method", method),
                                             ("--rounds", rounds), ("--out", o.out),
                                             ("--no-model-error", None if model_error is not False else "given"))
                     if v]
            if given:
                opt, v = given[0]
                raise ParameterError(opt.lstrip("-").replace("-", "_"), v, "not with --fidelity live: the search box "
                                     "is the cached region's, the live band holds the model's error, the FE verifies "
                                     "the result (--fidelity best takes it)", f"option {opt}")
        yield_, dist = yield_ or "0.99", dist or "normal"
        model_error = True if model_error is None else model_error
        sf = quantity("--safety-factor-min", safety_factor_min, "-", above=0.0)
        s, base = study_settings(o.concept, o.set_, o.mesh_size, o.mu, o.engine, o.idle_rpm, o.a, o.b, o.out, sf, o.fidelity)
        t0 = Targets.defaults(s, sf, objective)
        lo, hi = t0.engage_rpm_lo, None
        if engage_rpm is not None:
            parts = engage_rpm.split(":")
            if len(parts) != 2:
                raise ParameterError("engage_rpm", engage_rpm, "LO:HI in rpm (e.g. 3600:5000, '3600:' or ':5000')",
                                     "option --engage-rpm")
            lo = quantity("--engage-rpm", parts[0], "rpm", above=0.0) if parts[0].strip() else None
            hi = quantity("--engage-rpm", parts[1], "rpm", above=0.0) if parts[1].strip() else None
        slip = quantity("--slip-rpm-max", slip_rpm_max, "rpm", above=0.0)
        t = Targets(lo, hi, slip if slip is not None else t0.slip_rpm_max, sf, objective,
                    fatigue_min=quantity("--fatigue-min", fatigue_min, "-", above=0.0))
        P = type(base.params)
        names = names_from(free)
        ranges = ranges_from(P, range_)
        robust = None
        if n_life is not None:
            from .. import optimize_for_life

            lifed = optimize_for_life(s, t, names, starts=n_life, ranges=ranges or None, sample=sample,
                                      max_evals=max_evals, workers=o.workers, scheduler=o.scheduler,
                                      method=method or "auto", log=lambda m: err.print(escape(m)))
            res = lifed.result
            if o.out is not None:
                wrote(write_report(res, o.out, final=res.final_analysis()))
            if o.json_:
                d = res.to_json()
                d.pop("path")
                d["path_length"] = len(res.path)
                d["life"] = lifed.to_json()
                print(dumps(d))
                return
            _print_optimization(res, res.final_analysis())
            _print_life(lifed)
            return
        if live:
            from .. import robust_optimize

            if tol:
                if check and not 0 <= check <= 1000:
                    raise ParameterError("check", check, "0 to 1000 parts also through the FE", "option --check")
                y = quantity("--yield", yield_, "-", above=0.0)
                if not 0.5 < y < 1.0:
                    raise ParameterError("yield", yield_, "a share of parts in (0.5, 1), e.g. 0.99", "option --yield")
                robust = robust_optimize(s, tolerances_from(P, tol), yield_target=y, dist=dist, targets=t, free=names,
                                         check=check or CHECK_PARTS, workers=o.workers, fidelity="live",
                                         log=lambda m: err.print(escape(m)))
                res = robust.result
            else:
                res = run(s, t, names, workers=o.workers, scheduler=o.scheduler, fidelity="live",
                          log=lambda m: err.print(escape(m)))
            if o.json_:
                d = res.to_json() if robust is None else robust.to_json()
                d.pop("path")
                print(dumps(d))
                return
            _print_live(res, robust)
            return
        if tol:
            robust = _robust(s, P, t, names, tol, yield_, dist, model_error, check, max_evals, o.workers,
                             method or "pattern", rounds)
            res = robust.result
        else:
            res = run(s, t, names, ranges=ranges or None, sample=sample, max_evals=max_evals, workers=o.workers,
                      scheduler=o.scheduler, method=method or "auto", log=lambda m: err.print(escape(m)))
        final = None
        if o.out is not None or not o.json_:  # the final design analysed again, with its error estimate
            final = res.final_analysis()  # (the optimiser's own check did it, else a new best estimate)
        if o.out is not None:
            wrote(write_report(res, o.out, final=final))
        if o.json_:
            d = res.to_json() if robust is None else robust.to_json()
            d.pop("path")
            d["path_length"] = len(res.path)
            print(dumps(d))
            return
        _print_optimization(res, final)
        if robust is not None:
            _print_robust(robust)
            console.print("over a life: clutchfem tolerance " + escape(res.concept) + " "
                          + " ".join(f"--set {escape(x)}" for x in res.set_args) + " "
                          + " ".join(f"--tol {escape(x)}" for x in tol) + " --life STARTS", soft_wrap=True)
    except ClutchfemError as exc:
        fail(exc)


def _robust(s, P, targets, names, tol, yield_, dist, model_error, check, max_evals, workers, method, rounds):
    """The robust optimisation of ``optimize --tol`` (clutchfem.tolerances.robust)."""
    from .. import robust_optimize

    tols = tolerances_from(P, tol)
    y = quantity("--yield", yield_, "-", above=0.0)
    if not 0.5 < y < 1.0:
        raise ParameterError("yield", yield_, "a share of parts in (0.5, 1), e.g. 0.99", "option --yield")
    if dist not in ("normal", "uniform"):
        raise ParameterError("dist", dist, "normal or uniform", "option --dist")
    if check and not 8 <= check <= 100000:
        raise ParameterError("check", check, "0 (no check) or 8 to 100000 parts", "option --check")
    return robust_optimize(s, tols, yield_target=y, dist=dist, model_error=model_error, targets=targets, free=names,
                           max_evals=max_evals, check=check, workers=workers, method=method,
                           **({} if rounds is None else {"rounds": rounds}),
                           log=lambda m: err.print(escape(m)))


#: FE parts of a live robust result when --check is not given
CHECK_PARTS = 8


def _print_live(res, robust) -> None:
    """The live search's table in the designer's units (rpm, mm, g), its verification and region."""
    L = res.live
    t = Table(title=escape(f"{res.concept}: {res.message}"))
    for c in ("target", "live (value +- band)", "edge used", "FE (verified)", "limit", "met"):
        t.add_column(c, justify="left" if c == "target" else "right")
    fe = L.get("fe_answers") or {}
    for _, key, limit, sense in res.targets.constraints():
        a = L["answers"].get(key, {})
        dim = key in ("safety_factor", "fatigue_safety_factor")
        f = (lambda v: "none" if v is None else (f"{v:.2f}" if dim else f"{v:.0f} rpm"))  # noqa: E731
        fv = fe.get(key)
        ok = None if fv is None else (fv >= limit if sense == ">=" else fv <= limit)
        t.add_row(escape(key), escape(f"{f(a.get('value'))} +- {f(a.get('band'))}"), escape(f(a.get("edge"))),
                  escape(f(fv)), escape(f"{sense} {f(limit)}"), "-" if ok is None else ("yes" if ok else "MISSED"))
    console.print(t)
    P = Table(title="parameters")
    for c in ("parameter", "start", "final", "region"):
        P.add_column(c, justify="left" if c == "parameter" else "right")
    for n in res.free:
        lo, hi = L["region_bounds"][n]
        mm = n not in ("shoe_arc", "flexure_angle", "flexure_taper")
        rng = f"{lo * 1e3:.4g}..{hi * 1e3:.4g} mm" if mm else f"{lo:.4g}..{hi:.4g}"
        P.add_row(escape(n), escape(res.start_texts.get(n, "")), escape(res.params_texts.get(n, ""))
                  + (" (region's bound)" if n in res.at_bounds else ""), escape(rng))
    console.print(P)
    mass = L["answers"].get("mass_kg", {}).get("value")
    console.print(f"answered by: {L['answered_by']}; region {L['region_key']}; live mass "
                  + (f"{mass * 1e3:.2f} g" if mass else "-") + f"; {L['live_evaluations']} live evaluations, "
                  f"{L['fe_designs']} FE designs, {L['seconds']:.1f} s")
    console.print(escape(f"verdict: {L['verdict']}"))
    if robust is not None:
        y = L["yield"]
        console.print(f"yield asked {robust.yield_target:.2%}; on the live model {y['yield_search_sample']:.2%} of "
                      f"{L['robust']['parts']} parts (search sample), {y['yield_independent']:.2%} of "
                      f"{y['independent_parts']} independent parts (95 % Wilson {y['ci95'][0]:.2%} .. {y['ci95'][1]:.2%})")
        c = L.get("fe_parts")
        if c:
            console.print(f"FE check of {c['n_fe']} parts: {c['fe_in_spec']} of {c['n_ok']} in spec (live: "
                          f"{c['live_in_spec']}), verdicts differ on {c['verdicts_differ']}, {c['outside_live_band']} "
                          "outside the live band; largest relative difference "
                          + ", ".join(f"{k} {100 * v:.2f} %" for k, v in c["largest_rel"].items()))
    for n in L["notes"]:
        console.print(f"[yellow]{escape(n)}[/yellow]", soft_wrap=True)
    console.print("verify: clutchfem analyze " + escape(res.concept) + " "
                  + " ".join(f"--set {escape(x)}" for x in res.set_args), soft_wrap=True)


def _print_life(L):
    console.print("the limits above are the ones tightened by the wear allowance; the designer's: " + ", ".join(
        f"{c[1]} {c[3]} {c[2]:.4g}" for c in L.targets.constraints()))
    a = L.allowance
    for k, (lo, hi) in a.drift.items():
        console.print(f"  drift of {escape(k)} over {a.starts:.0f} starts: {lo:+.0f} .. {hi:+.0f} rpm")
    console.print(f"  torque at the rpm of maximum engine torque: {a.torque_drift_Nm:+.2f} N m over the life")
    for k, v in L.check["worst_slack_rpm"].items():
        console.print(f"  {escape(k)}: worst slack over the life {v:+.0f} rpm")
    console.print(("[green]" if L.met else "[red]") + escape(L.message) + ("[/green]" if L.met else "[/red]"))
    console.print("verify: clutchfem life " + escape(L.result.concept) + " "
                  + " ".join(f"--set {escape(x)}" for x in L.result.set_args)
                  + f" --starts {L.allowance.starts:.0f}", soft_wrap=True)


def _print_robust(r):
    units = {"engagement_rpm_with_ripple": "rpm", "slip_rpm": "rpm"}
    console.print("the limits above are the shifted ones; nominal: " + ", ".join(
        f"{c[1]} {c[3]} {c[2]:.4g}" for c in r.targets.constraints()))
    console.print("robust design: every limit moved inward by z sigma (chance constraints, linearised spread "
                  "from sensitivities on morphed meshes" + (", model-error bands included" if r.model_error
                                                             else ", model error left out") + "):")
    for k, m in r.margins.items():
        u = units.get(k, "")
        console.print(f"  {escape(k)}: margin {m:.3g} {u} (sigma {r.sigma.get(k, 0.0):.3g} {u})")
    shifted_rounds = sum(1 for h in r.rounds if isinstance(h.get("round"), int) and h["round"] > 0)
    console.print("the concept's rules hold at every corner of the tolerance box (every part within the drawing's "
                  "tolerances can be built)" if r.box_buildable else
                  "[yellow]the concept's rules do NOT hold at every corner of the tolerance box: some parts within "
                  "the drawing's tolerances cannot be built (see --check)[/yellow]")
    console.print(f"yield asked {r.yield_target:.2%}, predicted {r.predicted_yield:.2%} (linearised, constraints "
                  f"independent); {r.evaluations} designs in the deterministic optimum and {shifted_rounds} shifted "
                  f"round(s), {r.seconds:.0f} s")
    if not r.converged:
        console.print("[yellow]the final design needs larger margins than it was optimised with (see --json "
                      "rounds): raise --rounds or check with --check[/yellow]")
    c = r.check_share_in_spec
    if c is not None:
        bad = r.check.n - r.check.out_of_spec["any"]["n"]
        console.print(f"Monte Carlo check ({r.check.n} remeshed parts): {c[0]:.2%} in spec "
                      f"(95 % Wilson interval {c[1]:.2%} .. {c[2]:.2%})"
                      + (f"; {bad} part(s) the concept's rules refuse or whose analysis failed counted out of spec"
                         if bad else ""))


def _print_optimization(res, final):
    a = res.best["assessment"]
    t = Table(title=escape(f"{res.concept}: {res.message}"))
    t.add_column("target")
    t.add_column("value", justify="right")
    t.add_column("limit", justify="right")
    t.add_column("binds")
    for c in a["constraints"]:
        sf = c["unit"] == "-"
        v = c["value"]
        vs = "none" if v is None else (f"{v:.2f}" if sf else f"{v:.0f} rpm")
        err_txt = ""
        if final is not None and not sf:
            e = (final.errors or {}).get("engagement_rpm" if "engagement" in c["key"] else c["key"])
            if e and e.get("total") is not None:
                err_txt = f" (+- {e['total']:.0f} rpm"
                if e["total"] > 0 and c["slack"] is not None and math.isfinite(c["slack"]):
                    err_txt += f"; {c['slack'] / e['total']:+.2f} bands from the limit"
                err_txt += ")"
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
    fnote = res.fatigue_note
    if fnote:
        console.print(f"[yellow]{escape(fnote)}[/yellow]")
    console.print("verify: clutchfem analyze " + escape(res.concept) + " "
                  + " ".join(f"--set {escape(x)}" for x in res.set_args), soft_wrap=True)
