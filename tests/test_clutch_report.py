"""`clutchfem analyze` end to end on concept 4 (coarse mesh), its plots and report, and the
command's answers to bad input.

The expected values here are recomputed independently from the JSON's own curves and from
the formulas (ripple root, engine curve, power = torque x speed), never copied from a run.
"""

from __future__ import annotations

import dataclasses
import json
import math
import re

import numpy as np
import pytest
from typer.testing import CliRunner

from clutchfem.cli import app
from clutchfem.clutch import EngineCurve

MESH = ["--mesh-size", "0.002"]
KEYS = ("engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm", "max_von_mises_Pa", "safety_factor",
        "shoe_character")


def invoke(*args):
    return CliRunner().invoke(app, list(args), catch_exceptions=False)


def flat(text: str) -> str:
    return re.sub(r"\s+", " ", text)


@pytest.fixture(scope="module")
def c4(tmp_path_factory):
    """One ``analyze concept4 --out`` run: its JSON file (``an.to_json()``, what ``--json``
    prints: the JSON standard output is checked in test_engine_curve_below_engagement_never_engages
    and test_strong_engine_never_holds), its files and its terminal table (the run's output)."""
    out = tmp_path_factory.mktemp("c4")
    r = invoke("analyze", "concept4", *MESH, "--out", str(out))
    assert r.exit_code == 0, r.output
    (js,) = out.glob("concept4-*_analysis.json")
    return json.loads(js.read_text()), out, r.output


@pytest.mark.slow
def test_json_has_every_answer(c4):
    d, _, _ = c4
    for k in KEYS + ("slip_power_W", "torque_margin_Nm", "mu_sensitivity", "requirements", "warnings",
                     "shoe_character_per_shoe", "torque_models_at_max_engine_torque_Nm", "units"):
        assert k in d, k
    assert d["shoe_character"] in ("plus", "minus", "neutral")
    assert d["max_stress_rpm"] == 14000.0 == d["max_engine_rpm"]  # stress at the engine's max rpm


@pytest.mark.slow
def test_engagement_with_ripple_solves_the_ripple_equation(c4):
    d, _, _ = c4
    s, x = d["engagement_rpm"], d["engagement_rpm_with_ripple"]
    # x (1 + (0.032 + 3 * 0.013) x / 8000) = s  ->  quadratic, positive root (module docstring model)
    c = (0.032 + 3 * 0.013) / 8000.0
    assert x == pytest.approx((-1 + math.sqrt(1 + 4 * c * s)) / (2 * c), rel=1e-9)
    assert x < d["engagement_rpm_with_ripple_typical"] < s


@pytest.mark.slow
def test_slip_speed_is_where_fe_torque_meets_the_engine(c4):
    d, _, _ = c4
    eng = EngineCurve.default()
    rpm = np.array([row["rpm"] for row in d["curves"]])
    fe = np.array([row["fe_torque_Nm"] for row in d["curves"]])
    s = d["slip_rpm"]
    assert d["slip_status"] == "slips" and s is not None
    # the slip speed is a row of the curves (solved there, not interpolated)
    k = int(np.argmin(np.abs(rpm - s)))
    assert rpm[k] == pytest.approx(s, rel=1e-12)
    assert fe[k] == pytest.approx(eng.torque_at(s), rel=1e-6)
    below = (rpm > 2500) & (rpm < s - 1)
    assert np.all(fe[below] < eng.torque_at(rpm[below]))  # the first crossing
    assert d["slip_power_W"] == pytest.approx(eng.torque_at(s) * s * 2 * math.pi / 60, rel=1e-9)
    t8000 = np.interp(8000.0, rpm, fe)
    assert d["torque_margin_Nm"] == pytest.approx(t8000 - 3.40, abs=1e-9)
    req = d["requirements"]
    assert req["slip_ok"] == (s < 1.0 * 8000.0)
    assert req["engagement_ok"] == (d["engagement_rpm_with_ripple"] > 1.3 * 2700.0)


@pytest.mark.slow
def test_stress_above_yield_is_said_plainly(c4):
    d, _, _ = c4
    assert d["safety_factor"] == pytest.approx(1250e6 / d["max_von_mises_Pa"], rel=1e-9)
    said = any("ABOVE YIELD" in w for w in d["warnings"])
    assert said == (d["safety_factor"] < 1.0)


@pytest.mark.slow
def test_plus_minus_and_mu_sensitivity_follow_the_physics(c4):
    d, _, _ = c4
    (shoe,) = d["shoe_character_per_shoe"]
    ratio = shoe["normal_force_ratio"]
    assert shoe["character"] == ("minus" if ratio < 1 else "plus")
    t = d["mu_sensitivity"]["torque_Nm"]
    assert t["x0.7"] < t["x1.0"] < t["x1.3"]  # more friction, more torque
    s = d["mu_sensitivity"]["slip_rpm"]
    assert s["x1.3"] < s["x1.0"] < s["x0.7"]  # ... so the clutch holds the engine earlier
    # a minus shoe is less than proportional to mu (eq 7: mu also in the denominator)
    assert (d["mu_sensitivity"]["elasticity"] < 1.0) == (shoe["character"] == "minus")


@pytest.mark.slow
def test_nominal_arc_overpredicts_where_contact_is_at_the_tip(c4):
    d, _, _ = c4
    cp = d["coupling"]
    nominal = cp["phi2_deg"] - cp["phi1_deg"]
    m = d["torque_models_at_max_engine_torque_Nm"]
    assert d["first_touch"] == "tip"
    assert d["contact_arc_at_max_engine_torque_deg"] < nominal / 3
    assert m["analytic_nominal_arc_Nm"] > 1.1 * m["fe_torque_Nm"]
    assert abs(m["analytic_fe_arc_Nm"] / m["fe_torque_Nm"] - 1) < 0.15


@pytest.mark.slow
def test_out_writes_plots_and_tables(c4):
    _, out, _ = c4
    # not the default mesh size: the file names carry the design hash
    (js,) = out.glob("concept4-*_analysis.json")
    label = js.name.removesuffix("_analysis.json")
    for f in ("_torque_rpm.png", "_arc_stress_rpm.png", "_curves.csv", "_analysis.json"):
        assert (out / (label + f)).stat().st_size > 1000, f
    assert (out / f"{label}_torque_rpm.png").read_bytes()[:4] == b"\x89PNG"
    inp = json.loads(js.read_text())["inputs"]
    assert inp["concept"] == "concept4" and inp["params"]["flexure_thickness"] > 0
    assert inp["mesh_settings"]["size"] == pytest.approx(float(MESH[1]))
    assert inp["operating_point"]["mu"] == 0.165 and inp["engine"]["max_torque_Nm"] == 3.4


@pytest.mark.slow
def test_two_designs_in_one_folder_are_told_apart(tmp_path):
    # a coarser mesh than MESH (the file names are the point, not the answers)
    for t in ("1.7mm", "1.8mm"):
        r = invoke("analyze", "concept4", "--mesh-size", "0.004", "--set", f"flexure_thickness={t}", "--out",
                   str(tmp_path))
        assert r.exit_code == 0, r.output
    files = sorted(tmp_path.glob("concept4-*_analysis.json"))
    assert len(files) == 2
    th = sorted(json.loads(f.read_text())["inputs"]["params"]["flexure_thickness"] for f in files)
    assert th == pytest.approx([1.7e-3, 1.8e-3])


@pytest.mark.slow
def test_terminal_table_has_units_and_warning(c4):
    d, _, output = c4  # the table the fixture's run printed
    t = flat(output)
    assert "concept4: clutch answers (mu = 0.165" in t  # the design's table, with its friction
    for frag in ("rpm", "N m", "MPa", " W ", "(-)", "PASS" if d["requirements"]["slip_ok"] else "FAIL",
                 "ASSUMED"):
        assert frag in t, frag
    assert ("WARNING: STRESS ABOVE YIELD" in t) == (d["safety_factor"] < 1)


@pytest.mark.slow
def test_summary_rows_say_never_holds_and_never_engages(c4, tmp_path):
    from clutchfem.report import summary_rows

    d, _, _ = c4
    # a rebuilt Analysis (fields from the JSON) with the slip answer replaced
    import pandas as pd

    from clutchfem.analysis import Analysis

    fields = {f.name for f in dataclasses.fields(Analysis)}
    an = Analysis(**{k: v for k, v in d.items() if k in fields and k != "curves"}, curves=pd.DataFrame(d["curves"]))
    for status in ("never holds", "never engages"):
        rows = dict(summary_rows(dataclasses.replace(an, slip_rpm=None, slip_status=status, slip_power_W=None)))
        assert rows["slip speed (drum held, full throttle)"] == status.upper()


@pytest.mark.slow
def test_comparison_chart_with_baseline(c4, tmp_path):
    import pandas as pd

    from clutchfem.analysis import Analysis
    from clutchfem.report import torque_speed_plot

    d, _, _ = c4
    fields = {f.name for f in dataclasses.fields(Analysis)}
    an = Analysis(**{k: v for k, v in d.items() if k in fields and k != "curves"}, curves=pd.DataFrame(d["curves"]))
    p = torque_speed_plot({"concept4": an}, EngineCurve.default(), tmp_path / "fig25.png")
    assert p.read_bytes()[:4] == b"\x89PNG" and p.stat().st_size > 10000


@pytest.mark.slow
def test_engine_curve_below_engagement_never_engages(tmp_path):
    e = tmp_path / "low.csv"
    e.write_text("rpm,torque\n1000,1.0\n2000,2.0\n")
    r = invoke("analyze", "concept4", *MESH, "--engine", str(e), "--idle-rpm", "800", "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.output.strip().splitlines()[-1])
    # the engagement speed is the clutch's own (issue 24: it does not depend on the engine);
    # this engine tops out at 2000 rpm, below it, so the clutch never engages on it
    assert d["slip_status"] == "never engages" and d["slip_rpm"] is None and d["engagement_rpm"] > 2000
    assert d["shoe_character"] == "never engages"


@pytest.mark.slow
def test_strong_engine_never_holds(tmp_path):
    """An engine far stronger than the clutch: the clutch slips at every speed (issue 12: it
    used to say 'never slips', the opposite)."""
    e = tmp_path / "big.csv"
    e.write_text("rpm,torque\n2000,100\n14000,100\n")
    r = invoke("analyze", "concept4", *MESH, "--engine", str(e), "--json")
    assert r.exit_code == 0, r.output
    d = json.loads(r.output.strip().splitlines()[-1])
    assert d["slip_status"] == "never holds" and d["slip_rpm"] is None
    assert "slips at every speed" in d["slip_note"]
    assert d["requirements"]["slip_ok"] is False
    assert any("never holds" in w for w in d["warnings"])
    assert any("idle speed 2700 rpm ASSUMED" in n for n in d["notes"])  # CSV without idle


@pytest.mark.parametrize(
    "csv, args, fragments",
    [
        ("rpm,torque\n3000,2\n2000,3\n", [], ["engine curve", "sorted increasing", "2000", "3000"]),
        ("rpm,torque\n3000,2\n4000,-1\n", [], ["engine curve", "torque must be >= 0 N m", "-1"]),
        ("rpm,torque\n3000,2\n", [], ["engine curve", "at least 2 points", "got 1"]),
        (None, ["--rpm", "0:20000:500"], ["'rpm'", "0..20000", "within 0..14000 rpm"]),
        (None, ["--a", "0"], ["'a'", "> 0", "idle"]),
        (None, ["--a", "-1.3"], ["'a'", "> 0"]),
        (None, ["--b", "0"], ["'b'", "> 0", "max"]),
        (None, ["--b", "-2"], ["'b'", "> 0"]),
        (None, ["--idle-rpm", "0"], ["'idle_rpm'", "> 0 rpm"]),
        (None, ["--mu", "-0.1"], ["'mu'", "friction"]),
    ],
)
def test_bad_input_clear_error(tmp_path, csv, args, fragments):
    extra = list(args)
    if csv is not None:
        p = tmp_path / "engine.csv"
        p.write_text(csv)
        extra += ["--engine", str(p)]
    r = invoke("analyze", "concept4", *MESH, *extra)
    assert r.exit_code == 2
    t = flat(r.output)
    assert "error:" in t and "Traceback" not in t
    for frag in fragments:
        assert frag in t, (frag, t)


@pytest.mark.slow
def test_default_design_report_writes_fig25_and_says_yield(tmp_path):
    from clutchfem.report import default_design_report

    files = default_design_report(tmp_path, mesh_size=0.002)
    names = {f.name for f in files}
    assert {"clutch_torque_comparison.png", "report.md", "concept1_torque_rpm.png", "concept1_arc_stress_rpm.png",
            "concept4_torque_rpm.png", "concept4_arc_stress_rpm.png"} <= names
    md = (tmp_path / "report.md").read_text()
    for name in ("concept1", "concept4"):
        sf = json.loads((tmp_path / f"{name}_analysis.json").read_text())["safety_factor"]
        section = md.split(f"## {name}")[1].split("## ")[0]
        assert ("STRESS ABOVE YIELD" in section) == (sf < 1.0), name
        assert "ASSUMED" in section
