"""Pages (:mod:`.html`) for a design and for the design-to-targets runs: which answers go on
the first screen, which tables and charts below.  Each builder writes its charts into the
output folder and returns the :class:`~.html.Page`; :func:`~.html.write_page` renders it."""

from __future__ import annotations

import json
import math
from dataclasses import asdict
from pathlib import Path

from ..analysis import WHIRL_MARGIN
from ..geometry import draw_concept, fmt_param_value, get_concept
from ..mesh import draw_mesh
from ..targets import DIMENSIONLESS, fatigue_note
from . import target_charts as charts
from .answer_rows import summary_rows
from .design import arc_stress_plot, torque_plot
from .html import Figure, Page, Table, Text


def _f(v, fmt: str, unit: str = "") -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return f"{v:{fmt}} {unit}".rstrip()


# ---------------------------------------------------------------------------------------
# a design
# ---------------------------------------------------------------------------------------
def design_verdicts(an, sf_min: float = 1.5) -> list:
    req = an.requirements
    v = [[f"engagement > a x idle = {req['engagement_limit_rpm']:.0f} rpm", bool(req["engagement_ok"]),
          _f(req.get("engagement_checked_rpm"), ".0f", "rpm") + " with ripple"],
         [f"slip < b x rpm(max torque) = {req['slip_limit_rpm']:.0f} rpm", bool(req["slip_ok"]),
          _f(an.slip_rpm, ".0f", "rpm") if an.slip_rpm is not None else an.slip_status],
         [f"safety factor >= {sf_min:g} at {an.max_engine_rpm:.0f} rpm", bool(an.safety_factor >= sf_min),
          f"{an.safety_factor:.2f} ({an.max_von_mises_Pa / 1e6:.0f} MPa vs yield {an.yield_strength_Pa / 1e6:.0f} MPa)"]]
    fsf = getattr(an, "fatigue_safety_factor", None)
    if fsf is not None:
        v.append(["fatigue safety factor >= 1 (ASSUMED duty)", bool(fsf >= 1.0), f"{fsf:.2f}"])
    wh = getattr(an, "whirl", None) or {}
    if wh:
        v.append([f"crankshaft whirl margin >= {100 * WHIRL_MARGIN:.0f} %", bool(wh["margin"] >= WHIRL_MARGIN),
                  f"{100 * wh['margin']:+.0f} %"])
    return v


def cutting_files(folder: Path) -> list:
    """The cutting files ``clutchfem export`` wrote into ``folder`` (its ``export.json``):
    a table of the files (linked by name: they lie beside the page), the process and the
    measured features, and the drawing sheet's preview.  Read from the file, so the report
    does not depend on the cutting stage."""
    spec = Path(folder) / "export.json"
    if not spec.is_file():
        return []
    try:
        doc = json.loads(spec.read_text())
    except ValueError:
        return [Text("", [f"{spec.name} is not readable JSON"], "warn")]
    proc = doc.get("process") or {}
    rows = [[name, {".dxf": "DXF (layers OUTER, INNER, BORE, TOOLPATH, TEXT; unit " + str(doc.get("units")) + ")",
                    ".step": "STEP solid (mm)", ".pdf": "drawing sheet", ".svg": "drawing sheet",
                    ".png": "drawing sheet preview"}.get(Path(name).suffix.lower(), "")]
            for name in doc.get("files", []) if not name.endswith(".json")]
    out = [Text("files (beside this page)", [r[0] for r in rows], "links"),
           Table("", ["file", "what"], rows,
                 f"design hash {doc.get('design_hash')}; process "
                 + (f"{proc.get('process')} (kerf {proc.get('kerf', 0) * 1e3:g} mm)" if proc else "none (unchecked)"))]
    feats = [[k, f["text"]] for k, fs in (doc.get("features") or {}).items() for f in fs[:2]]
    if feats:
        out.append(Table("smallest features of the part", ["kind", "feature"], feats))
    png = next((n for n in doc.get("files", []) if n.endswith("_drawing.png") or n.endswith(".png")), None)
    if png and (Path(folder) / png).exists():
        out.append(Figure("drawing sheet", png))
    return out


def param_table(p, title: str = "Concept parameters") -> Table:
    P = type(p)
    rows = []
    off = set(p.inactive()) if hasattr(p, "inactive") else set()
    for name in P.model_fields:
        if name in off:
            continue
        rows.append([name, fmt_param_value(p, name), P.model_fields[name].description or ""])
    return Table(title, ["parameter", "value", "meaning"], rows)


def design_page(an, design, engine, folder: Path, concept=None, params=None, sf_min: float = 1.5) -> Page:
    """The page of one analysed design (everything :func:`clutchfem.analysis.analyze`
    answers, the drawing, the parameters, the operating point and the material)."""
    folder = Path(folder)
    name = an.label or an.design
    torque = torque_plot(an, engine, folder / "torque_rpm.png", f"{an.design}: torque vs engine speed (drum held)")
    arc = arc_stress_plot(an, folder / "arc_stress_rpm.png", f"{an.design}: contact arc and peak stress vs rpm")
    sections = []
    draw = []
    if concept is not None and params is not None:
        png = draw_concept(concept, params, folder / "drawing", mesh=design.cm, dpi=80)[0]
        draw.append(Figure("drawing (canonical frame, dimensions of the parameters)", png.name))
    else:
        png = draw_mesh(design.cm, folder / "mesh.png", dpi=80)
        draw.append(Figure("the user mesh and its named boundaries", png.name))
    warn = [Text("", list(an.warnings), "warn")] if an.warnings else []
    sections.append(("Drawing and curves", warn + [Figure("contact arc and peak stress vs speed", arc.name)] + draw))
    cutting = cutting_files(folder)
    if cutting:
        sections.append(("Cutting files (clutchfem export)", cutting))
    err_rows = []
    for q, e in (an.errors or {}).items():
        if isinstance(e, dict) and "value" in e:
            sc = 1e-6 if e.get("unit") == "Pa" else 1.0
            u = "MPa" if e.get("unit") == "Pa" else e.get("unit", "")
            err_rows.append([q, _f(e["value"] * sc if e["value"] is not None else None, ".4g", u),
                             _f(e["discretisation"] * sc if e.get("discretisation") is not None else None, ".3g", u),
                             _f(e["model_form"] * sc if e.get("model_form") is not None else None, ".3g", u),
                             _f(e["total"] * sc if e.get("total") is not None else None, ".3g", u)])
    details = []
    if err_rows:
        details.append(Table("error estimate of the main answers", ["answer", "value", "discretisation",
                                                                    "model form", "total band"], err_rows,
                             (an.errors or {}).get("method", "")))
    if params is not None:
        details.append(param_table(params))
    op = design.op
    m = op.material
    details.append(Table("Material", ["property", "value"],
                         [["name", m.name], ["Young's modulus E", f"{m.E / 1e9:g} GPa"], ["Poisson's ratio", f"{m.nu:g}"],
                          ["density", f"{m.rho:g} kg/m^3"], ["yield strength Rp0.2", f"{m.yield_strength / 1e6:g} MPa"]]))
    details.append(Table("Operating point and model", ["setting", "value"],
                         [["drum radius", f"{design.drum_radius * 1e3:g} mm"], ["axial thickness", f"{design.thickness * 1e3:g} mm"],
                          ["friction coefficient mu", f"{op.mu:g}"], ["rotation", op.rotation],
                          ["spin softening", op.softening], ["fidelity", op.fidelity], ["formulation", op.model_formulation],
                          ["drum", "rigid" if op.drum_wall_m is None else f"elastic, wall {op.drum_wall_m * 1e3:g} mm"],
                          ["mesh", f"{design.cm.n_elements} P2 elements ({'one sector' if design.cm.sector_angle else 'full part'})"],
                          ["engine curve", an.engine.get("source", "")]]))
    sections.append(("Details: errors, parameters, material, operating point", details))
    if an.notes:
        sections.append(("Notes", [Text("", list(an.notes))]))
    h = an.design_hash or (an.inputs or {}).get("design_hash")
    return Page(title=f"{an.design}: clutch answers", subtitle=f"design {name} (design hash {h}); every number with "
                f"its unit; "
                f"requirement factors and engine curve as noted", verdicts=design_verdicts(an, sf_min),
                headline=[list(r) for r in summary_rows(an)], hero=[Figure("torque vs engine speed", torque.name)],
                sections=sections, inputs=an.inputs, kind="design")


# ---------------------------------------------------------------------------------------
# optimisation
# ---------------------------------------------------------------------------------------
def optimization_page(res, final_an, folder: Path) -> Page:
    folder = Path(folder)
    path_png = charts.optimization_path(res, folder / "optimization_path.png")
    a = res.best["assessment"]
    verdicts = []
    for c in a["constraints"]:
        val = c["value"]
        unit = "" if c["key"] in DIMENSIONLESS else " rpm"
        txt = "none" if val is None else (f"{val:.2f}" if not unit else f"{val:.0f}{unit}")
        lim = f"{c['limit']:.2f}" if not unit else f"{c['limit']:.0f}{unit}"
        verdicts.append([f"{c['name'].split(' >=')[0].split(' <=')[0]} {c['sense']} {lim}", c["violation"] <= 0,
                         txt + (" (binds)" if c["binds"] else "")])
    head = [["result", res.message],
            ["objective", f"{res.targets.objective}: " + (_f(res.best['mass_kg'] * 1e3, '.1f', 'g part mass')
                                                          if res.targets.objective == 'mass'
                                                          else _f(res.best['torque_margin_Nm'], '+.2f', 'N m margin'))],
            ["evaluations", f"{sum(res.evaluations.values())} designs ({res.evaluations.get('ok', 0)} analysed, "
                            f"{res.evaluations.get('refused', 0)} refused by the concept's rules, "
                            f"{res.evaluations.get('failed', 0) + res.evaluations.get('crashed', 0)} failed)"],
            ["time", f"{res.seconds:.0f} s ({res.iterations} polls)"],
            ["engagement static / with ripple", f"{_f(res.best.get('engagement_rpm'), '.0f', 'rpm')} / "
                                                f"{_f(res.best.get('engagement_rpm_with_ripple'), '.0f', 'rpm')}"],
            ["slip speed", _f(res.best.get("slip_rpm"), ".0f", "rpm")],
            ["torque at the rpm of max engine torque", _f(res.best.get("torque_at_max_engine_torque_Nm"), ".2f", "N m")],
            ["peak von Mises at engine max / safety factor",
             f"{_f(res.best.get('max_von_mises_Pa', math.nan) / 1e6, '.0f', 'MPa')} / {_f(res.best.get('safety_factor'), '.2f')}"],
            ["fatigue safety factor (ASSUMED duty)", _f(res.best.get("fatigue_safety_factor"), ".2f")
             + (f" ({res.best.get('fatigue_cycle')})" if res.best.get("fatigue_cycle") else "")],
            ["part mass", _f(res.best.get("mass_kg", math.nan) * 1e3, ".1f", "g")]]
    if fatigue_note(res):
        head.append(["note", fatigue_note(res)])
    verify = Text("verify with analyze (the very design evaluated: the texts read back bit for bit)",
                  ["clutchfem analyze " + res.concept + " " + " ".join(f"--set {s}" for s in res.set_args)],
                  "pre")
    cons = Table("constraints at the final design", ["target", "value", "limit", "slack", "binds"],
                 [[c["name"], c["value"], c["limit"], c["slack"],
                   "VIOLATED" if c.get("violated") else ("yes" if c["binds"] else "no")]
                  for c in a["constraints"]], "binds: slack below 2 % of the limit")
    prm = Table("final parameters (free ones searched)", ["parameter", "start", "final", "--set text", "at range end"],
                [[n, res.start_texts.get(n, ""), res.params_texts.get(n, ""), f"{n}={res.params_texts.get(n, '')}",
                  "yes" if n in res.at_bounds else ""] for n in res.free])
    other = [[k, v] for k, v in res.params_texts.items() if k not in res.free]
    rows = []
    for r in res.path:
        rows.append([r["n"], r.get("phase"), r["status"],
                     ("yes" if r.get("assessment", {}).get("h", 1) <= 0 else "no") if r["status"] == "ok" else "",
                     r.get("mass_kg", math.nan) * 1e3 if r.get("mass_kg") is not None else None,
                     r.get("engagement_rpm_with_ripple"), r.get("slip_rpm"), r.get("safety_factor"),
                     " ".join(f"{k}={v}" for k, v in r["params"].items())])
    path_t = Table(f"every design evaluated ({len(rows)})", ["#", "phase", "status", "feasible", "mass [g]",
                                                            "engagement w. ripple [rpm]", "slip [rpm]",
                                                            "safety factor [-]", "parameters"], rows,
                   "refused: the concept's consistency rules reject the combination before any meshing (free)")
    sections = [("Final design", [cons, prm] + ([Table("other parameters (fixed, from --set)", ["parameter", "value"],
                                                       other)] if other else []) + [verify])]
    if final_an is not None:
        sections.append(("Final design, full analysis (with error estimate)",
                         [Table("", ["quantity", "value"], [list(x) for x in summary_rows(final_an)])]))
    sections.append(("Path", [path_t]))
    pattern = [
        "pattern search with an extreme barrier over the free parameters' ranges (normalised to [0, 1]), "
        f"after a {sum(1 for r in res.path if r.get('phase') == 'sample')}-design Sobol sample around the start; "
        "each poll is one parallel batch; a refused or failed design is worse than every analysed one"]
    if res.message.startswith("gradient method"):
        pattern = [
            "gradient method: a trust-region SQP with the l1 merit over the free parameters' ranges (normalised "
            "to [0, 1]); forward differences on meshes morphed from each iterate, one parallel batch per "
            "iteration; the concept's rules learned as linear constraints (rule checks only, no analysis); the "
            "final design checked on a mesh made from scratch"] + (
            ["then the pattern search from its best design (the gradient method found no feasible design)"]
            if "pattern search" in res.message else [])
    sections.append(("Method", [Text("", pattern + [
        "comparison: feasible beats infeasible; infeasible by the sum of relative violations; feasible by the "
        "objective (improvements below 0.1 % are noise)",
        "answers of analyze (errors off) on the default mesh of each design; the final design is re-analysed "
        "with the error estimate"], "list")]))
    return Page(title=f"{res.concept}: design to targets (optimisation)",
                subtitle=f"objective {res.targets.objective}; free: {', '.join(res.free)}", verdicts=verdicts,
                headline=head, hero=[Figure("optimisation path", path_png.name)], sections=sections,
                inputs={"final_design": final_an.inputs if final_an is not None else {}, "run": _run_inputs(res.settings)},
                kind="optimize")


def _run_inputs(settings) -> dict:
    return asdict(settings) if settings is not None else {}


# ---------------------------------------------------------------------------------------
# tolerances
# ---------------------------------------------------------------------------------------
def tolerance_page(res, folder: Path, inputs: dict) -> Page:
    folder = Path(folder)
    hist = charts.tolerance_histograms(res, folder / "tolerance_histograms.png")
    rank = charts.tolerance_ranking(res, folder / "tolerance_ranking.png")
    oos = res.out_any  # (a part the concept's rules refuse counted out of spec)
    verdicts = [[f"out of spec: {100 * oos['share']:.1f} % of parts" + (
                     " (unbuildable or failed ones included)" if oos is not res.out_of_spec["any"] else ""), oos["k"] == 0,
                 f"95 % CI {100 * oos['ci95'][0]:.1f}-{100 * oos['ci95'][1]:.1f} % (Wilson, n = {oos['n']})"]]
    head = []
    for name, *_ in res.spec:
        o = res.out_of_spec[name]
        head.append([f"out of spec: {name}", f"{100 * o['share']:.1f} % [{100 * o['ci95'][0]:.1f}, "
                                              f"{100 * o['ci95'][1]:.1f}] % ({o['k']} of {o['n']})"])
    for key, st in res.stats.items():
        if st["mean"] is None:
            continue
        sc = st["scale"]
        head.append([f"{st['label']}: nominal / mean +- sd", f"{_f(st['nominal'] * sc if st['nominal'] is not None else None, '.4g')}"
                     f" / {st['mean'] * sc:.4g} +- {st['sd'] * sc:.3g} {st['unit']}"])
    for key in ("engagement_rpm", "slip_rpm", "max_von_mises_Pa"):
        rk = res.ranking.get(key)
        if rk:
            top = rk["items"][0]
            head.append([f"dominant dimension for {rk['label']}",
                         f"{top['name']} (SRC {top['src']:+.2f} [{top['ci95'][0]:+.2f}, {top['ci95'][1]:+.2f}], "
                         f"R^2 {rk['r2']:.2f})"])
    rank_rows = []
    for key, rk in res.ranking.items():
        for it in rk["items"]:
            rank_rows.append([rk["label"], it["name"], it["src"], f"[{it['ci95'][0]:+.3f}, {it['ci95'][1]:+.3f}]",
                              f"{it['slope']:+.4g} {it['slope_unit']}", rk["r2"]])
    shift_rows = [[s["name"], f"{s['shift_m'] * 1e3:+.1f} mm", s["status"], s["engagement_rpm"],
                   s["engagement_change_pct"], s["stiffness_change_pct"], s["slip_rpm"],
                   s["max_von_mises_Pa"] / 1e6 if s.get("max_von_mises_Pa") is not None else None]
                  for s in res.shifts]
    sections = [("Ranking of the dimensions", [Figure("standardised regression coefficients (95 % bootstrap intervals)",
                                                      rank.name),
                                               Table("", ["answer", "dimension", "SRC [-]", "95 % CI", "slope",
                                                          "R^2 [-]"], rank_rows,
                                                     "SRC^2: the dimension's share of the answer's variance (R^2 near 1)")])]
    if shift_rows:
        sections.append(("'0.2-0.5 mm moves the stiffness a lot', quantified",
                         [Table("one dimension shifted alone", ["dimension", "shift", "status", "engagement [rpm]",
                                                                "engagement change [%]", "stiffness change [%]",
                                                                "slip [rpm]", "peak stress [MPa]"], shift_rows,
                                "stiffness as the clutch feels it: k ~ w_e^2 at fixed shoe mass and clearance "
                                "(thesis eq 1), so dk/k = (w/w0)^2 - 1")]))
    if res.notes:
        sections.append(("Notes", [Text("", res.notes)]))
    sections.append(("Method", [Text("", [
        f"{res.n} independent draws ({res.dist}: " + ("tolerance = +-3 sigma, ASSUMED Cp = 1" if res.dist == "normal"
                                                       else "uniform over +-tolerance") + f"), seed {res.seed}",
        "share out of spec: Wilson score interval, 95 %",
        "ranking: standardised regression coefficients with R^2, 95 % percentile bootstrap (1000 resamples)"])]))
    tol_txt = ", ".join(f"{k} +-{charts.tolerance_text(res, k)}" for k in res.tolerances)
    return Page(title=f"{res.concept}: manufacturing tolerances (Monte Carlo)",
                subtitle=f"{res.n} parts, {tol_txt}; {res.seconds:.0f} s", verdicts=verdicts, headline=head,
                hero=[Figure("distributions of the answers", hist.name)], sections=sections, inputs=inputs,
                kind="tolerance")


# ---------------------------------------------------------------------------------------
# compensation
# ---------------------------------------------------------------------------------------
def compensation_page(comp, before, after, engine, folder: Path, inputs: dict) -> Page:
    folder = Path(folder)
    prof = charts.compensation_profile(comp, folder / "compensation_profile.png")
    root, tip = get_concept(comp.concept).shoe_arc(comp.before)
    torq = charts.compensation_torque(before, after, engine, folder / "compensation_torque.png", comp.rpm,
                                      math.degrees(abs(tip - root)))
    conv = charts.compensation_convergence(comp, folder / "compensation_convergence.png")
    b, a = comp.state_before, comp.state_after
    rows = comp.compare(before, after)
    head = [[q, f"{x} -> {y}"] for q, x, y in rows]
    verdicts = [[f"contact at {comp.rpm:.0f} rpm", None, f"{100 * b.contact_share:.1f} % -> {100 * a.contact_share:.1f} % "
                                                      "of the nominal arc"],
                ["fixed point " + ("converged" if comp.converged else "NOT converged"), None if comp.converged else False,
                 f"{len(comp.steps) - 1} rebuilds, {comp.seconds:.0f} s"]]
    steps = Table("fixed-point iterations", ["iteration", "pressure cv over target [-]", "linearised cv [-]",
                                             "level [MPa]", "contact extent [% arc]", "nodes in contact [% arc]",
                                             "largest change [um]", "torque at X [N m]", "engagement [rpm]"],
                  [[s.iteration, s.measured_cv, s.predicted_cv, s.target_pressure_Pa / 1e6 if s.target_pressure_Pa else None,
                    100 * s.contact_share, 100 * s.touching_share, s.step_m * 1e6 if s.step_m is not None else None,
                    s.torque_Nm, s.engagement_rpm] for s in comp.steps])
    prof_t = Table("the compensated profile (--set texts)", ["parameter", "value"],
                   [[k, v] for k, v in comp.after_texts.items()])
    sections = [("Before and after", [Table("", ["answer", "before", "after"], [list(r) for r in rows]),
                                      Figure("torque and contact arc vs speed", torq.name)]),
                ("Profile and convergence", [prof_t, steps, Figure("convergence", conv.name)])]
    if comp.notes:
        sections.append(("Notes", [Text("", comp.notes)]))
    sections.append(("Method", [Text("", [
        "linearised contact at the speed with the model's own condensed compliance G (spin softening, friction): "
        "the clearance for an even pressure P on the target arc is c* = u_free - P G lam1",
        "level P: mean clearance over the target arc kept (the design's own, or --mean-clearance)",
        "table profile: 17 clearances, C2 cubic spline, least squares over the target arc within the range",
        "fixed point: rebuild the part with the new profile, re-solve, until no control value moves more than "
        "the tolerance; evenness measured on the FE contact (LCP), not on the linearisation"])]))
    return Page(title=f"{comp.concept}: shoe-profile compensation at {comp.rpm:.0f} rpm",
                subtitle=f"target: even pressure over {100 * comp.target_arc:.0f} % of the nominal shoe arc "
                         f"(s = {comp.arc[0]:.3f}..{comp.arc[1]:.3f})", verdicts=verdicts, headline=head,
                hero=[Figure("clearance and contact pressure along the shoe", prof.name)], sections=sections,
                inputs=inputs, kind="compensate")
