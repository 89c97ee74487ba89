"""``clutchfem calibrate``: which inputs of a part as built explain what the test rig
measured (the posterior of the uncertain inputs on the reduced model), which measurements
none explains, and (``--correct``) the corrected design for the next part with its cutting
files."""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError, ParameterError
from . import options as O
from .common import (
    check_out_dir,
    console,
    design_from,
    engine_from,
    fail,
    operating_point,
    quantity,
    requirements_from,
    wrote,
)


@O.takes("concept", "set_", "mesh_size", "mu", "fidelity", "engine", "a", "b", "workers", "out", "json_", live=True)
def calibrate(
    o,
    measured: List[str] = typer.Option([], "--measured", help="a measurement NAME=VALUE+-U with units (U: one "
                                       "standard uncertainty): engagement=4191rpm+-25rpm, slip=7512rpm+-40rpm, "
                                       "torque@SPEED=V+-U, mass=..., or a measured dimension "
                                       "flexure_thickness=2.26mm+-0.01mm; repeat (repeated readings of one part are "
                                       "combined); several parts of one design: PART:NAME=VALUE+-U, e.g. "
                                       "p1:engagement=4191rpm+-25rpm p2:engagement=4230rpm+-25rpm (mu and the "
                                       "material shared, the geometry per part)", rich_help_panel="Calibration"),
    uncertain: List[str] = typer.Option(..., "--uncertain", help="an uncertain input of the part as built: "
                                        "mu=0.1:0.35 (uniform), flexure_thickness=+-0.1mm (normal about the drawn "
                                        "value, +-3 sigma), mu=0.2+-0.06; E and density by similarity; repeat",
                                        rich_help_panel="Calibration"),
    torque_csv: Optional[Path] = typer.Option(None, "--torque-csv", help="a measured torque-speed curve (CSV, units "
                                              "in the header as an engine curve's): its torque at the engine's "
                                              "maximum-torque speed is a measurement (with --torque-sd)",
                                              rich_help_panel="Calibration"),
    torque_sd: Optional[str] = typer.Option(None, "--torque-sd", help="the standard uncertainty of --torque-csv's "
                                            "torque, e.g. 0.1Nm", rich_help_panel="Calibration"),
    method: str = typer.Option("emcee", "--method", help="emcee (sampling) or laplace (a normal at the mode)",
                               rich_help_panel="Calibration"),
    n: Optional[int] = typer.Option(None, "--n", help="training designs of the reduced model (default 8 per axis "
                                    "+ 8)", rich_help_panel="Reduced model"),
    held_out: int = typer.Option(10, "--held-out", help="designs its own error is measured on",
                                 rich_help_panel="Reduced model"),
    seed: int = typer.Option(0, "--seed", help="the sampler's seed", rich_help_panel="Calibration"),
    steps: int = typer.Option(5000, "--steps", help="emcee's steps per walker (500 discarded)",
                              rich_help_panel="Calibration"),
    correct: List[str] = typer.Option([], "--correct", help="a calibrated geometry input to move for the next "
                                      "part (e.g. flexure_thickness): the corrected design, whose part as built "
                                      "(the process offset added, at the calibrated mu) meets the targets; "
                                      "'all' for every calibrated geometry input; repeat",
                                      rich_help_panel="Corrected design"),
    target: List[str] = typer.Option([], "--target", help="a target of the corrected design NAME=VALUE: "
                                     "engagement=4000rpm, slip=7500rpm, torque=5Nm (default: the drawn design's "
                                     "own predictions of the answers measured); repeat",
                                     rich_help_panel="Corrected design"),
    process: Optional[str] = typer.Option(None, "--process", metavar="laser|waterjet|wire-edm",
                                          help="the cutting process of the corrected design's files (with "
                                          "--correct and --out): its limits check the part",
                                          rich_help_panel="Corrected design"),
):
    """Calibrate to measured parts: the posterior of the uncertain inputs given the rig's
    measurements (on the reduced model of a region holding the priors), the calibrated answers
    with bands, and the measurements no input within its prior explains."""
    from .. import calibrate as run
    from .. import check_measurements, dumps, parse_measured, torque_from_csv

    try:
        check_out_dir(o.out)
        if seed < 0:
            raise ParameterError("seed", seed, "an integer >= 0", "option --seed")
        if (target or process) and not correct:
            raise ParameterError("target" if target else "process", (target or [process])[0], "an option of "
                                 "--correct (the corrected design's)", "option --target" if target else
                                 "option --process")
        if process is not None and process not in ("laser", "waterjet", "wire-edm"):
            raise ParameterError("process", process, "laser, waterjet or wire-edm", "option --process")
        if process is not None and o.out is None:
            raise ParameterError("process", process, "an option of --out (the corrected design's cutting files)",
                                 "option --process")
        from .. import parse_target

        drawn = [u.split("=")[0].strip() for u in uncertain]  # the inputs the next part could be drawn at
        drawn = [n for n in drawn if n not in ("mu", "drum_wall", "drum_radius", "E", "density")]
        for c in [a.strip() for c in correct for a in c.split(",") if a.strip()]:
            if c != "all" and c not in drawn:
                raise ParameterError("correct", c, "all, or a geometry input given as --uncertain ("
                                     + (", ".join(drawn) or "none given") + "): the next part is drawn at it",
                                     "option --correct")
        for t in target:
            parse_target(t)  # refused before any work
        answers = ("engagement", "engagement_ripple", "slip")  # the speeds checked against each other, before any work
        check_measurements([parse_measured(m) for m in measured if m.split("=")[0].split(":")[-1].strip() in answers])
        eng, _ = engine_from(o.engine)
        req = requirements_from(o.a, o.b)
        fid = o.fidelity or "best"
        design = design_from(o.concept, o.set_, None, op=operating_point(mu=o.mu, fidelity="live" if fid == "live"
                                                                          else fid),
                             mesh_size=o.mesh_size, mesh_allowed=False)
        meas = list(measured)
        if torque_csv is not None:
            sd = quantity("--torque-sd", torque_sd, "N m", above=0.0)
            if sd is None:
                raise ParameterError("torque_sd", None, "the standard uncertainty of the curve's torque, e.g. 0.1Nm",
                                     "option --torque-sd")
            from .. import EngineCurve

            rpm = float((eng if eng is not None else EngineCurve.default()).rpm_max_torque)
            meas.append(torque_from_csv(torque_csv, rpm, sd))
        elif torque_sd is not None:
            raise ParameterError("torque_sd", torque_sd, "an option of --torque-csv", "option --torque-sd")
        if not meas:
            raise ParameterError("measured", None, "at least one --measured NAME=VALUE+-U (or --torque-csv)",
                                 "option --measured")
        res = run(design, meas, uncertain, method=method, n=n, held_out=held_out, engine=eng, requirements=req,
                  workers=o.workers, progress=not o.json_, seed=seed, steps=steps)
        corr = None
        if correct:
            from .. import corrected_design

            adjust = None if correct == ["all"] else [a for c in correct for a in c.split(",") if a.strip()]
            corr = corrected_design(res, adjust=adjust, targets=list(target) or None, seed=seed)
        if o.out is not None:
            wrote(res.write_figures(o.out))
            if corr is not None:
                from .. import export as cut

                files = cut(corr.design, Path(o.out) / "corrected", process=process, analyze_design=False,
                            engine=eng)
                wrote(files.files)
        if o.json_:
            doc = res.to_json()
            if corr is not None:
                doc["corrected"] = corr.to_json()
            print(dumps(doc))
            return
        _print(res)
        if corr is not None:
            _print_correction(corr)
    except ClutchfemError as exc:
        fail(exc)


#: SI unit -> (the unit shown, its factor)
_SHOWN = {"m": ("mm", 1e3), "Pa": ("MPa", 1e-6), "kg": ("g", 1e3), "-": ("", 1.0)}


def _q(v: float, unit: str) -> str:
    u, sc = _SHOWN.get(unit, (unit, 1.0))
    return f"{v * sc:.4g} {u}".rstrip()


def _print(res) -> None:
    t = Table(title=escape(f"{res.concept}: the part as built ({res.info['method']}, {res.info['samples']} samples)"))
    for c in ("input", "prior (95 %)", "posterior mean", "posterior 95 %", "narrowed", "note"):
        t.add_column(c, justify="left" if c in ("input", "note") else "right")
    for name, p in res.posterior.items():
        u = p["unit"]
        pr = p["prior"]
        note = "" if p["identified"] else "not identified"
        if p["trades_off_with"]:
            tw = p["trades_off_with"]
            note += ("; " if note else "") + f"trades off with {tw['name']} ({tw['correlation']:+.2f})"
        if p["at_edge"]:
            note += ("; " if note else "") + f"at the prior's {p['at_edge']} bound"
        t.add_row(escape(name), escape(f"{_q(pr['ci95'][0], u)} .. {_q(pr['ci95'][1], u)}"), escape(_q(p["mean"], u)),
                  escape(f"{_q(p['ci95'][0], u)} .. {_q(p['ci95'][1], u)}"), f"{100 * p['narrowed']:.0f} %",
                  escape(note))
    console.print(t)
    a = Table(title="the calibrated part against the measurements")
    for c in ("answer", "drawn design", "calibrated (95 %)", "measured"):
        a.add_column(c, justify="left" if c == "answer" else "right")
    for v in res.answers.values():
        unit, sc = _SHOWN.get(v["unit"], (v["unit"], 1.0))
        meas = "" if v["measured"] is None else _q(v["measured"], v["unit"])
        a.add_row(escape(v["label"]), escape(_q(v["nominal"], v["unit"]) if v["nominal"] is not None else "-"),
                  escape(f"{v['mean'] * sc:.4g} [{v['ci95'][0] * sc:.4g}, {v['ci95'][1] * sc:.4g}] {unit}"),
                  escape(meas))
    console.print(a)
    c = Table(title="the check of the fit (best fit within the priors; posterior predictive)")
    for col in ("measurement", "best fit", "distance", "p", "explained"):
        c.add_column(col, justify="left" if col == "measurement" else "right")
    for ch in res.checks:
        c.add_row(escape(ch["text"]), escape(_q(ch["best_fit"], ch["unit"])), f"{ch['z_best']:+.1f} sigma",
                  f"{ch['p_predictive']:.3f}", "yes" if ch["explained"] else "NO")
    console.print(c)
    for e in res.explanations:
        console.print(escape(f"- {e}"))  # wrapped on a terminal, one line on a pipe
    for note in res.notes:
        console.print(f"[dim]note: {escape(note)}[/]")


def _print_correction(corr) -> None:
    t = Table(title=escape(f"the corrected design for the next part (targets: {corr.target_source})"))
    for c in ("input", "drawn", "process offset (95 %)", "drawn next", "as built next"):
        t.add_column(c, justify="left" if c == "input" else "right")
    for name, ch in corr.changes.items():
        u = ch["unit"]
        oc = ch["offset_ci95"]
        t.add_row(escape(name), escape(_q(ch["drawn"], u)), escape(f"{ch['offset'] * 1e3:+.4f} mm" if u == "m" else
                                                                    _q(ch["offset"], u))
                  + (escape(f" [{oc[0] * 1e3:+.4f}, {oc[1] * 1e3:+.4f}]") if oc and u == "m" else ""),
                  escape(_q(ch["corrected"], u)), escape(_q(ch["as_built"], u)))
    console.print(t)
    a = Table(title="the next part as built")
    for c in ("answer", "drawn design made again", "corrected (95 %)", "target", "met"):
        a.add_column(c, justify="left" if c == "answer" else "right")
    for v in corr.answers.values():
        unit, sc = _SHOWN.get(v["unit"], (v["unit"], 1.0))
        a.add_row(escape(v["label"]), escape(_q(v["uncorrected"], v["unit"]) if v["uncorrected"] is not None else "-"),
                  escape(f"{v['mean'] * sc:.4g} [{v['ci95'][0] * sc:.4g}, {v['ci95'][1] * sc:.4g}] {unit}"),
                  escape(_q(v["target"], v["unit"]) if v["target"] is not None else ""),
                  "" if v["target"] is None else ("yes" if v["met"] else "NO"))
    console.print(a)
    console.print(escape("next part: --set " + " --set ".join(corr.set_args)), soft_wrap=True)
    for note in corr.notes:
        console.print(f"[dim]note: {escape(note)}[/]")
