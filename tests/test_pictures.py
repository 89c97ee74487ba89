"""The picture rule (issue 25, :mod:`clutchfem.core.figures`): every picture states its
quantity with its unit, marks the answer it exists to show, keeps its legends off the data
and agrees with the tables to the digits it shows.  Each picture the tool draws for a design,
a study, guidelines, a field and a slip-heat run is drawn here from a small run and its
annotated numbers are compared with the JSON of the same run (the design-to-targets charts:
``tests/test_targets_*.py``)."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pandas as pd
import pytest

import clutchfem as cf
from clutchfem.guidelines import GuidelineSettings
from clutchfem.guidelines.elasticity import ANSWERS
from clutchfem.report import arc_stress_plot, field_picture, slip_heat_files, torque_plot, torque_speed_plot
from clutchfem.studies import parse_spec
from support.pictures import agrees, number, rule, texts

SIZE = "2.5mm"


@pytest.fixture(scope="module")
def c4():
    d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size=SIZE))
    return d, cf.analyze(d)


@pytest.mark.slow
def test_torque_plot(c4, tmp_path):
    """Engagement (static and with ripple), slip and both requirement limits, as the JSON."""
    _, an = c4
    doc = an.to_json()
    rec = rule(torque_plot(an, cf.EngineCurve.default(), tmp_path / "t.png", "concept4"))
    agrees(rec, r"^engagement", doc["engagement_rpm"])
    agrees(rec, r"engagement with ripple \(3 sigma\)", doc["engagement_rpm_with_ripple"])
    agrees(rec, r"^slip", doc["slip_rpm"])
    agrees(rec, r"a x idle =", doc["requirements"]["engagement_limit_rpm"])
    agrees(rec, r"b x rpm\(max torque\) =", doc["requirements"]["slip_limit_rpm"])


@pytest.mark.slow
def test_arc_stress_plot(c4, tmp_path):
    """The contact arc at the rpm of max engine torque with its error, the peak stress at the
    engine's maximum speed with its error band and safety factor, the yield: as the JSON."""
    _, an = c4
    doc = an.to_json()
    rec = rule(arc_stress_plot(an, tmp_path / "a.png", "concept4"))
    rpm = doc["torque_models_at_max_engine_torque_Nm"]["rpm"]
    row = next(r for r in doc["curves"] if r["rpm"] == rpm)
    agrees(rec, r"^(?=[\d.]+ deg \+-)", doc["contact_arc_at_max_engine_torque_deg"])  # '1.37 deg +- 0.41 deg at'
    agrees(rec, r"^[\d.]+ deg \+-", row["contact_arc_error_deg"])
    agrees(rec, r"deg at", rpm)
    agrees(rec, r"safety factor", doc["safety_factor"])
    agrees(rec, r"yield", doc["yield_strength_Pa"], 1e-6)
    agrees(rec, r"^(?=\d+ MPa \+-)", doc["max_von_mises_Pa"], 1e-6)  # '754 MPa +- 128 MPa at 14000 rpm'
    agrees(rec, r"^\d+ MPa \+-", doc["errors"]["max_von_mises_Pa"]["total"], 1e-6)
    agrees(rec, r"MPa at", doc["max_stress_rpm"])
    ax = rec["axes"][0]
    assert ax["ylabel"] == "contact arc per shoe [deg]"  # a linear arc axis in degrees
    assert any("share of the nominal shoe arc" in a["ylabel"] for a in rec["axes"])


@pytest.mark.slow
def test_comparison_plot(c4, tmp_path):
    _, an = c4
    rec = rule(torque_speed_plot({"concept4": an}, cf.EngineCurve.default(), tmp_path / "c.png"))
    agrees(rec, r"concept4 engagement", an.engagement_rpm)
    agrees(rec, r"concept4 slip", an.slip_rpm)


@pytest.mark.slow
def test_field_picture_agrees_with_the_table(c4, tmp_path):
    """The picture's peak is the table's (unaveraged element vertices), its place and the
    averaged peak are named, the contact arc is the table's."""
    d, _ = c4
    r = d.sweep("4000,12000")
    rec = rule(field_picture(r, 12000, tmp_path / "f.png", cm=d.cm))
    row = r.curve.iloc[1]
    agrees(rec, r"peak", row.max_von_mises_Pa, 1e-6)
    agrees(rec, r"at r =", float(np.hypot(row.max_vm_x_m, row.max_vm_y_m)), 1e3)
    agrees(rec, r"contact arc", row.contact_arc_deg)
    agrees(rec, r"contact arc [\d.]+ deg \+-", row.contact_arc_error_deg)
    avg = number(rec, r"von_mises_Pa\): peak")[0]
    assert avg < round(row.max_von_mises_Pa / 1e6)  # averaging lowers the peak: said, not hidden
    assert "MPa" in rec["axes"][-1]["ylabel"]  # the colour bar: MPa
    assert max(rec["axes"][-1]["ylim"]) >= row.max_von_mises_Pa / 1e6 * (1 - 1e-12)  # it reaches the marked peak


@pytest.mark.slow
def test_study_charts(tmp_path):
    """Answers vs an input with a refused design: the limits named with their values, the
    counts of the title; a refused design is not drawn as a value; parallel coordinates with
    the shortfall colour bar."""
    spec = parse_spec(f'''
[design]
concept = "concept4"
[design.set]
shoe_arc = "90deg"
shoe_thickness = "7mm"
[settings]
mesh_size = "{SIZE}"
[errors]
sample = 0
[vary]
method = "grid"
[vary.params]
flexure_thickness = {{values = ["1.6mm", "1.8mm", "2.2mm"]}}
''')
    s = cf.draw_study_charts(cf.run_study(spec, tmp_path, workers=0, progress=False)).to_json()
    frame = pd.read_csv(tmp_path / "results.csv")
    ok = frame[frame["status"] == "ok"]
    assert len(ok) == 2 and s["refused"] + s["failed"] == 1
    rec = rule(tmp_path / "charts" / "answers_vs_flexure_thickness.png")
    agrees(rec, r"a x idle =", float(ok["engagement_limit_rpm"].iloc[0]))
    agrees(rec, r"b x rpm\(max torque\) =", float(ok["slip_limit_rpm"].iloc[0]))
    agrees(rec, r"engine max torque =", float(ok["max_engine_torque_Nm"].iloc[0]))
    agrees(rec, r"\[mm\] \(", len(ok))  # '... [mm] (2 answered, 0 feasible, 1 refused/failed)'
    agrees(rec, r"answered, ", int(ok["feasible"].sum()))
    agrees(rec, r"feasible, ", 1)
    assert any("refused / failed (1), no answer" in t for t in texts(rec))
    pc = rule(tmp_path / "charts" / "parallel_coordinates.png")
    assert any("largest requirement shortfall [%]" in a["ylabel"] for a in pc["axes"])
    assert any("1 refused/failed" in t for t in texts(pc))


@pytest.mark.slow
def test_guideline_charts(tmp_path):
    """The design point's value in each one-at-a-time panel and each elasticity bar's label
    (the parameters' and the operating input's) are the JSON's; the inactive profile controls
    are not studied, and the chart says so.  One operating input (mu; the idle speed's bars
    are drawn the same way) and no error estimate of the design point (no chart shows it)."""
    d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size=SIZE))
    gs = GuidelineSettings.from_design(d, params=["flexure_thickness", "clearance"], points=3, inputs=["mu"])
    g = cf.draw_guideline_charts(cf.run_guidelines(dataclasses.replace(gs, errors=False), tmp_path, workers=0,
                                                   progress=False))
    assert g.inputs == ["mu"]
    doc = json.loads((tmp_path / "guidelines.json").read_text())
    assert not any(r["parameter"].startswith("table_c") for r in doc["elasticities"])
    assert any("table_c0..table_c16" in n for n in doc["notes"])
    oat = rule(tmp_path / "one_at_a_time.png")
    assert "table_c0..table_c16" in oat["figure"][0]
    assert {a["xlabel"] for a in oat["axes"] if a["xlabel"]} == {"flexure_thickness [mm]", "clearance [mm]"}
    base = {r["answer"]: r["value_at_x0"] for r in doc["elasticities"]}
    agrees(oat, r"engagement \[rpm\]: design point", base["engagement_rpm"])
    agrees(oat, r"slip speed \[rpm\]: design point", base["slip_rpm"])
    agrees(oat, r"torque at max engine torque \[N m\]: design point", base["torque_at_max_engine_torque_Nm"])
    agrees(oat, r"peak von Mises at max rpm \[MPa\]: design point", base["max_von_mises_MPa"])
    agrees(oat, r"contact arc at max engine torque \[deg\]: design point", base["contact_arc_deg"])
    el = rule(tmp_path / "elasticities.png")
    for ax, (col, _) in zip(el["axes"], ANSWERS):
        names = [*g.ranking, *g.inputs]  # the bars, top down
        assert len(ax["texts"]) == len(names), (col, ax["texts"])
        for name, label in zip(names, ax["texts"]):
            e = next(r["E"] for r in doc["elasticities"] if r["parameter"] == name and r["answer"] == col)
            assert float(label) == pytest.approx(round(e, 2), abs=0.0051), (col, name)


@pytest.mark.slow
def test_slip_heat_picture(tmp_path):
    """Peak, flexure peak, the limit and the time the flexure reaches it: the JSON's.  20 steps
    an event (0.4 s): the picture and the JSON of one run, not the transient's accuracy
    (tests/test_durability_heat.py); each step is a frame of the run's ParaView series, which
    was half of this test's time at 40."""
    run = cf.slip_heat(cf.Design.from_concept("concept2", mesh=cf.MeshSettings(size=SIZE)),
                       scenario=cf.SlipScenario(seconds=8.0, cycles=1, pause=2.0, steps_per_event=20))
    files = slip_heat_files(run, tmp_path)
    png = next(f for f in files if f.suffix == ".png")
    doc = json.loads(next(f for f in files if f.suffix == ".json").read_text())
    rec = rule(png)
    agrees(rec, r"^peak", doc["peak_temperature_C"])
    agrees(rec, r"^peak \d+ C at", doc["peak_time_s"])
    agrees(rec, r"flexure peak", doc["flexure_temperature_C"])
    agrees(rec, r"^limit", doc["limit_temperature_C"])
    if doc["time_to_limit_s"] is not None:
        agrees(rec, r"reaches it at", doc["time_to_limit_s"])
