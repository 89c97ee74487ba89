"""``clutchfem tolerance``: Monte Carlo of manufacturing tolerances on the study engine, and
(``--allocate``) the widest tolerance per dimension for a yield target."""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError, ParameterError
from . import options as O
from .common import check_cluster, check_out_dir, console, err, fail, quantity, study_settings, tolerances_from, wrote
from .life_options import life_given, rebuild_from, wear_from

LIFE = "Life"


@O.takes("concept", "set_", "mesh_size", "mu", "fidelity", "engine", "idle_rpm", "a", "b", "workers",
         "scheduler", "out", "json_", "wear_regime", "wear_coefficient", "hardness", "drum_wear_coefficient", "drum_hardness",
         "max_wear_step", "wear_rate_change", "rebuild_depth", live=True)
def tolerance(
    o,
    tol: List[str] = typer.Option(..., "--tol", help="tolerance name=+-value with its unit, e.g. "
                                  "flexure_thickness=+-0.05mm (repeat for each dimension)", rich_help_panel="Tolerances"),
    n: Optional[int] = typer.Option(None, "--n", help="number of Monte Carlo parts (default 64; with --allocate: "
                                    "a Monte Carlo check of the allocated widths, none unless given)",
                                    rich_help_panel="Tolerances"),
    dist: str = typer.Option("normal", "--dist", help="normal (tolerance = +-3 sigma, ASSUMED) or uniform",
                             rich_help_panel="Tolerances"),
    seed: int = typer.Option(1, "--seed", help="random seed (the same seed draws the same parts)",
                             rich_help_panel="Tolerances"),
    check: int = typer.Option(8, "--check", help="with --fidelity live: parts also analysed by the full FE, and the "
                              "agreement reported", rich_help_panel="Tolerances"),
    shifts: bool = typer.Option(True, "--shifts/--no-shifts", help="also shift each toleranced length by +-0.2 and "
                                "+-0.5 mm alone (the thesis's '0.2-0.5 mm' question)", rich_help_panel="Tolerances"),
    safety_factor_min: str = typer.Option("1.5", "--safety-factor-min", help="spec: minimum safety factor",
                                          rich_help_panel="Tolerances"),
    allocate: bool = typer.Option(False, "--allocate", help="tolerance allocation: the widest half-width per --tol "
                                  "dimension such that every target holds for the --yield share of parts (linearised "
                                  "spreads from one sensitivities call; the --tol widths are the reference of the cost "
                                  "model)", rich_help_panel="Allocation"),
    yield_: Optional[str] = typer.Option(None, "--yield", help="with --allocate: share of parts that must meet every "
                                         "target (default 0.99)",
                               rich_help_panel="Allocation"),
    model_error: bool = typer.Option(True, "--model-error/--no-model-error", help="with --allocate: add each "
                                     "answer's model-error band (as +-2 sigma) to its spread",
                                     rich_help_panel="Allocation"),
    cost: List[str] = typer.Option([], "--cost", help="with --allocate: cost weight name=W of a dimension at its "
                                   "--tol width (default 1 each; reciprocal cost model, ASSUMED)",
                                   rich_help_panel="Allocation"),
    life: Optional[str] = typer.Option(None, "--life", metavar="STARTS", help="also the share in spec after STARTS "
                                       "starts (1..1e8): one clutchfem life run of the nominal design, every part "
                                       "drifting as the nominal does (drive line and duty: clutchfem life's "
                                       "defaults)", rich_help_panel=LIFE),
):
    """Monte Carlo of manufacturing tolerances: spread, share out of spec, ranking of dimensions."""
    from .. import Requirements, Targets, dumps, write_report
    from .. import tolerance as run

    try:
        o.scheduler = check_cluster(o.workers, o.scheduler)
        check_out_dir(o.out)
        if seed < 0:
            raise ParameterError("seed", seed, "an integer >= 0 (the same seed draws the same parts)", "option --seed")
        sf = quantity("--safety-factor-min", safety_factor_min, "-", above=0.0)
        if o.fidelity != "live" and check != 8:  # said before the design is meshed
            raise ParameterError("check", check, "an option of --fidelity live (the parts on the reduced model, a "
                                 "check sample through the FE)", "option --check")
        given = [(opt, v) for opt, v in (("--yield", yield_), ("--cost", " ".join(cost)),
                                     ("--no-model-error", "given" if not model_error else "")) if v]
        if given and not allocate:
            raise ParameterError(given[0][0].lstrip("-"), given[0][1], "an option of --allocate only (--yield, --cost, "
                                 "--no-model-error): add --allocate", f"option {given[0][0]}")
        wear_given = life_given(o, rebuild=True)
        life_kw = _life_options(life, wear_given, allocate)
        y = _yield(yield_) if allocate else None
        if allocate and o.scheduler is not None:
            raise ParameterError("scheduler", o.scheduler, "no --scheduler with --allocate: its sensitivities run on "
                                 "a local cluster (use --workers N)", "option --scheduler")
        s, base = study_settings(o.concept, o.set_, o.mesh_size, o.mu, o.engine, o.idle_rpm, o.a, o.b, o.out, sf, o.fidelity)
        P = type(base.params)
        tols = tolerances_from(P, tol)
        t0 = Targets.defaults(s, sf)
        if allocate:
            _allocate(s, base, o.set_, tols, Targets(t0.engage_rpm_lo, None, t0.slip_rpm_max, sf), y, dist,
                      model_error, cost, n, seed, o.workers, o.scheduler, o.out, o.json_)
            return
        n = 64 if n is None else n
        live = {"model": "live", "check": check} if o.fidelity == "live" else {}
        res = run(s, tols, n=n, dist=dist, seed=seed, targets=Targets(t0.engage_rpm_lo, None, t0.slip_rpm_max, sf), **live,
                  shifts=shifts, workers=o.workers, scheduler=o.scheduler, log=lambda m: err.print(escape(m)),
                  **life_kw)
        if o.out is not None:
            wrote(write_report(res, o.out, design=base, run={"tolerances_si": tols, "n": n, "dist": dist, "seed": seed,
                                                             "life_starts": life_kw.get("life")},
                               engine=s.engine_csv or "", requirements=Requirements(a=s.a, b=s.b)))
        if o.json_:
            d = res.to_json()
            d.pop("samples")
            print(dumps(d))
            return
        _print_tolerance(res)
    except ClutchfemError as exc:
        fail(exc)


def _life_options(raw, wear_given: dict, allocate: bool) -> dict:
    """The ``life=``/``life_options=`` keywords of cf.tolerance from ``--life`` and the wear
    options (refused before any design is meshed)."""
    given = [(opt, v) for opt, v in wear_given.items() if v is not None]
    if raw is None:
        if given:
            raise ParameterError(given[0][0].lstrip("-").replace("-", "_"), given[0][1], "an option of --life only: "
                                 "add --life STARTS", f"option {given[0][0]}")
        return {}
    n = quantity("--life", raw, "-", 1.0, 1e8)
    if allocate:
        raise ParameterError("life", raw, "without --allocate (the allocation is for new parts; check its widths "
                             "over a life with clutchfem tolerance --tol ... --life N)", "option --life")
    wear = wear_from({k: v for k, v in wear_given.items() if k != "--rebuild-depth"})
    return {"life": n, "life_options": {"wear": wear, **rebuild_from(wear_given["--rebuild-depth"])}}


def _print_life(res):
    lf = res.life
    t = Table(title=escape(f"share of parts in spec new and after {lf['starts']:.0f} starts (95 % Wilson interval)"))
    t.add_column("spec")
    t.add_column("new", justify="right")
    t.add_column(escape(f"at {lf['starts']:.0f} starts"), justify="right")
    for name, v in lf["in_spec"].items():
        t.add_row(escape(name), *(escape(f"{100 * x['share_in_spec']:.1f} % [{100 * x['ci95'][0]:.1f}, "
                                         f"{100 * x['ci95'][1]:.1f}] ({x['k_in_spec']} of {x['n']})")
                                  for x in (v["new"], v["at_life"])))
    console.print(t)
    for k, (lo, hi) in lf["drift_rpm"].items():
        console.print(escape(f"  drift of the nominal's {k} over {lf['starts']:.0f} starts: {lo:+.0f} .. {hi:+.0f} rpm"))
    console.print(escape(f"  torque at the rpm of maximum engine torque: {lf['torque_drift_Nm']:+.2f} N m over the life; "
                         f"Archard k = {lf['wear_coefficient']:.1e} (band {lf['wear_coefficient_band'][0]:.0e}"
                         f"..{lf['wear_coefficient_band'][1]:.0e}); {lf['wear_states']} wear states"))
    console.print("[dim]ASSUMED: every part drifts as the nominal design does (the parts' spread is small next to the "
                  "design, so their wear is the nominal's)[/]")


def _print_tolerance(res):
    t = Table(title=escape(f"{res.concept}: {res.n} parts ({res.dist}; answered by the {res.answered_by})"))
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
    if res.life is not None:
        _print_life(res)
    for n_ in res.notes:
        console.print(f"[dim]note: {escape(n_)}[/]")


def _yield(raw):
    """The --yield share of --allocate (refused before any work)."""
    y = 0.99 if raw is None else quantity("--yield", raw, "-", above=0.0)
    if not 0.5 < y < 1.0:
        raise ParameterError("yield", raw, "a share of parts in (0.5, 1), e.g. 0.99", "option --yield")
    return y


def _allocate(s, base, set_, tols, targets, y, dist, model_error, cost, n, seed, workers, scheduler, out, json_):
    """``tolerance --allocate``: the allocation (clutchfem.tolerances.allocation) and, with --n,
    a Monte Carlo check of the allocated widths."""
    from .. import allocate_tolerances, dumps, parse_tolerance
    from .. import tolerance as run

    if dist not in ("normal", "uniform"):
        raise ParameterError("dist", dist, "normal or uniform", "option --dist")
    weights = {}
    for item in cost:
        name, _, raw = item.partition("=")
        name = name.strip()
        if name not in tols:
            raise ParameterError("cost", item, "name=W for a dimension given with --tol (" + ", ".join(tols) + ")",
                                 "option --cost")
        weights[name] = quantity("--cost", raw, "-", above=0.0)
    if n is not None and not 8 <= n <= 100000:
        raise ParameterError("n", n, "8 to 100000 Monte Carlo parts (the check of the allocated widths)", "option --n")
    a = allocate_tolerances(s, tols, yield_target=y, dist=dist, model_error=model_error, targets=targets,
                            cost=weights or None, workers=workers)
    chk = None
    if n is not None and a.feasible:
        P = type(base.params)
        alloc = {k: v for k, v in a.allocated.items() if v is not None and v != float("inf")}
        for k, v in alloc.items():
            try:
                parse_tolerance(P, f"{k}=+-{v!r}")
            except ParameterError as exc:
                raise ParameterError("n", n, f"a Monte Carlo check of widths the sampler can draw; {k} is allocated "
                                     f"+-{v:.3g} (SI): {exc}", "option --n") from None
        chk = run(s, alloc, n=n, dist=dist, seed=seed, targets=targets, shifts=False, workers=workers,
                  scheduler=scheduler, log=lambda m: err.print(escape(m)))
    doc = {"design": {"label": base.name, "set": list(set_)}, **a.to_json()}
    if chk is not None:
        o = chk.out_any
        doc["check"] = {"n": o["n"], "in_spec": o["n"] - o["k"], "share_in_spec": 1 - o["share"],
                        "ci95_in_spec": [1 - o["ci95"][1], 1 - o["ci95"][0]], "seed": seed,
                        "widths_si": dict(chk.tolerances), "model_error_in_check": False}
    if out is not None:
        path = Path(out) / "allocation.json"
        path.write_text(dumps(doc, indent=1))
        wrote([path])
    if json_:
        print(dumps(doc))
        return
    _print_allocation(a, doc.get("check"))


#: lengths and angles in the units a drawing shows them in
SHOWN = {"m": (1e3, "mm"), "deg": (1.0, "deg")}


def shown(unit: str, value: float | None, digits: int = 4) -> str:
    """``value`` (SI, parameter ``unit``) as a text with its shown unit: '0.0512 mm'."""
    if value is None:
        return "none"
    if value == float("inf"):
        return "unlimited"
    sc, u = SHOWN.get(unit, (1.0, "(-)"))
    return f"{value * sc:.{digits}g} {u}"


def _print_allocation(a, check):
    t = Table(title=escape(f"{a.concept}: tolerance allocation for {a.yield_target:.4g} of parts in spec ({a.dist}, "
                           + ("model-error bands included" if a.model_error else "model error left out") + ")"))
    for c in ("dimension", "given +-", "allocated +-", "x given", "binds", "widest alone +-", "variance share",
              "optimal split +-"):
        t.add_column(c, justify="left" if c in ("dimension", "binds") else "right")
    for d in a.dims:
        t.add_row(escape(d["name"]), escape(shown(d["unit"], d["given"])), escape(shown(d["unit"], d["allocated"])),
                  escape("-" if d.get("ratio") is None else f"{d['ratio']:.3g}"), escape(d.get("binds") or "-"),
                  escape(shown(d["unit"], d.get("alone")) if d.get("alone") or not d.get("alone_note")
                         else "none: the others miss"),
                  escape("-" if d.get("share") is None else f"{100 * d['share']:.1f} %"),
                  escape(shown(d["unit"], d.get("allocated_union"))))
    console.print(t)
    c = Table(title="targets at the nominal design (linearised spreads)")
    for h in ("target", "value", "slack", "sigma model", "sigma at given widths", "z sigma needed"):
        c.add_column(h, justify="left" if h == "target" else "right")
    for r in a.constraints:
        u = f" {r['unit']}" if r["unit"] not in ("-", "") else ""
        f = (lambda v: "-" if v is None else f"{v:.4g}{u}")
        c.add_row(escape(r["name"]), escape(f(r["value"])), escape(f(r["slack"])), escape(f(r["sigma_model"])),
                  escape(f(r["sigma_given"])), escape(f(a.z * r["sigma_given"])))
    console.print(c)
    style = "" if a.feasible else "bold red"
    console.print((f"[{style}]" if style else "") + escape(a.message) + (f"[/{style}]" if style else ""))
    if a.scale_joint is not None and a.feasible:
        console.print(f"without the Bonferroni share (joint normal of the answers): every width x {a.scale_joint:.3g} "
                      "gives the yield exactly")
    if a.feasible:
        console.print(f"predicted yield at the given widths: {100 * a.predicted_yield:.2f} % (linearised, joint normal "
                      f"of the answers; {100 * a.predicted_yield_independent:.2f} % if the targets were independent); "
                      f"at the allocated widths: {100 * a.allocated_yield:.2f} % (z = {a.z:.3f}: Bonferroni over "
                      f"{len(a.constraints)} targets, conservative)")
        if a.ranking:
            console.print("tighten first (share of the binding target's variance at the given widths): "
                          + escape(", ".join(a.ranking))
                          + (f"; model error {100 * a.model_share:.1f} %" if getattr(a, "model_share", None) else ""))
        console.print("allocated: least total cost sum w t_given / t (reciprocal cost model, Chase & Greenwood 1988, "
                      "ASSUMED), every target its equal share of the failures (Bonferroni, as optimize --tol); "
                      "optimal split: the same with the failure budget split optimally between the targets (Boole); "
                      "widest alone: the other widths held at their given values")
    if check is not None:
        console.print(f"Monte Carlo check of the allocated widths ({check['n']} remeshed parts, tolerances only): "
                      f"{100 * check['share_in_spec']:.2f} % in spec (95 % Wilson interval "
                      f"{100 * check['ci95_in_spec'][0]:.2f} .. {100 * check['ci95_in_spec'][1]:.2f} %)")
    for n_ in a.notes:
        console.print(f"[dim]note: {escape(n_)}[/]")
