"""``clutchfem tolerance``: Monte Carlo of manufacturing tolerances on the study engine."""

from __future__ import annotations

from typing import List

import typer
from rich.markup import escape
from rich.table import Table

from ..core import ClutchfemError, ParameterError
from . import options as O
from .common import check_cluster, check_out_dir, console, err, fail, quantity, wrote
from .optimize_cmd import study_settings


def tolerance(
    concept: O.Concept = None,
    set_: O.Set = [],
    tol: List[str] = typer.Option(..., "--tol", help="tolerance name=+-value with its unit, e.g. "
                                  "flexure_thickness=+-0.05mm (repeat for each dimension)", rich_help_panel="Tolerances"),
    n: int = typer.Option(64, "--n", help="number of Monte Carlo parts", rich_help_panel="Tolerances"),
    dist: str = typer.Option("normal", "--dist", help="normal (tolerance = +-3 sigma, ASSUMED) or uniform",
                             rich_help_panel="Tolerances"),
    seed: int = typer.Option(1, "--seed", help="random seed (the same seed draws the same parts)",
                             rich_help_panel="Tolerances"),
    shifts: bool = typer.Option(True, "--shifts/--no-shifts", help="also shift each toleranced length by +-0.2 and "
                                "+-0.5 mm alone (the thesis's '0.2-0.5 mm' question)", rich_help_panel="Tolerances"),
    safety_factor_min: str = typer.Option("1.5", "--safety-factor-min", help="spec: minimum safety factor",
                                          rich_help_panel="Tolerances"),
    mesh_size: O.MeshSize = None,
    mu: O.Mu = None,
    engine: O.Engine = None,
    idle_rpm: O.IdleRpm = None,
    a: O.A = None,
    b: O.B = None,
    workers: O.Workers = None,
    scheduler: O.Scheduler = None,
    out: O.Out = None,
    json_: O.Json = False,
):
    """Monte Carlo of manufacturing tolerances: spread, share out of spec, ranking of dimensions."""
    from ..analysis import Requirements
    from ..core import dumps
    from ..report import tolerance_report
    from ..studies import Targets, parse_tolerance
    from ..studies import tolerance as run

    try:
        scheduler = check_cluster(workers, scheduler)
        check_out_dir(out)
        if seed < 0:
            raise ParameterError("seed", seed, "an integer >= 0 (the same seed draws the same parts)", "option --seed")
        sf = quantity("--safety-factor-min", safety_factor_min, "-", above=0.0)
        s, base = study_settings(concept, set_, mesh_size, mu, engine, idle_rpm, a, b, out, sf)
        P = type(base.params)
        tols = {}
        for item in tol:
            name, t = parse_tolerance(P, item)
            if name in tols:
                raise ParameterError(name, item, "one tolerance per dimension (given twice)", "option --tol")
            tols[name] = t
        t0 = Targets.defaults(s, sf)
        res = run(s, tols, n=n, dist=dist, seed=seed, targets=Targets(t0.engage_rpm_lo, None, t0.slip_rpm_max, sf),
                  shifts=shifts, workers=workers, scheduler=scheduler, log=lambda m: err.print(escape(m)))
        if out is not None:
            wrote(tolerance_report(res, out, base, {"tolerances_si": tols, "n": n, "dist": dist, "seed": seed},
                                   engine=s.engine_csv or "", requirements=Requirements(a=s.a, b=s.b)))
        if json_:
            d = res.to_json()
            d.pop("samples")
            print(dumps(d))
            return
        _print_tolerance(res)
    except ClutchfemError as exc:
        fail(exc)


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
