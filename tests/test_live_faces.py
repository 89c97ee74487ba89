"""The live faces of issue 36 beyond ``analyze``: a study whose fidelity is live (each point
from the reduced model whose region holds it) and guidelines from the reduced model's
derivatives.  The reduced model here is fitted to hand-made rows (smooth answers of the
flexure thickness: no FE), saved to a private cache, and found by the faces as a built one
would be."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.reduced import ReducedModel, Region, find, save

LO, HI = 2.09e-3, 2.31e-3  # concept 1's flexure thickness +-5 % around its 2.2 mm


def _row(t: float) -> dict:
    """A hand-made best-path row of concept 1 at flexure thickness ``t`` [m]: smooth answers
    with bands (the shapes matter, not the numbers)."""
    x = t / 2.2e-3
    eng = 3000.0 * x**1.5
    return {"status": "ok", "point_json": json.dumps({"flexure_thickness": t}),
            "engagement_rpm": eng, "engagement_ripple_rpm": 0.97 * eng, "engagement_err_rpm": 0.004 * eng,
            "slip_rpm": 5200.0 * x**0.4, "slip_err_rpm": 10.0,
            "torque_at_max_engine_torque_Nm": 6.0 / x, "torque_err_Nm": 0.05,
            "max_von_mises_MPa": 300.0 * x**-0.8, "stress_err_MPa": 6.0,
            "fatigue_safety_factor": 2.0 * x, "part_mass_g": 20.0 + 2.0 * x, "shoe_mass_g": 5.0}


@pytest.fixture(scope="module")
def fitted(tmp_path_factory):
    """(a private cache, concept 1's reduced model over its flexure thickness fitted to 7
    hand-made rows, measured on 4 others and saved there): fitted once for the module."""
    cache = tmp_path_factory.mktemp("cache")
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("CLUTCHFEM_CACHE", str(cache))
        r = Region.around(cf.Design.from_concept("concept1", fidelity="live"), free=["flexure_thickness"])
        assert r.bounds("flexure_thickness") == (pytest.approx(LO), pytest.approx(HI))
        m = ReducedModel.fit(r, [_row(t) for t in np.linspace(LO, HI, 7)])
        m.measure([_row(t) for t in np.linspace(LO, HI, 9)[1:-1:2]])
        m.info.update(n_train=7, n_held_out=4)
        save(m)
    return cache, m


@pytest.fixture
def model(fitted, monkeypatch):
    """The module's hand-made reduced model, its private cache the test's (where the faces
    find it as a built one)."""
    cache, m = fitted
    monkeypatch.setenv("CLUTCHFEM_CACHE", str(cache))
    return m


SPEC = """
[design]
concept = "concept1"
[settings]
fidelity = "live"
{extra}
[errors]
sample = 0
[vary]
method = "grid"
[vary.params]
flexure_thickness = {{values = ["2.1mm", "2.2mm", "2.3mm", "2.6mm"]}}
"""


def test_a_live_study_answers_each_point_from_its_region_and_refuses_one_outside(model, tmp_path):
    from clutchfem.studies import parse_spec

    s = cf.run_study(parse_spec(SPEC.format(extra="")), tmp_path / "study", workers=0, progress=False)
    f = s.frame
    assert list(f["status"]) == ["ok", "ok", "ok", "refused"]
    assert list(f["answered_by"][:3]) == ["reduced model"] * 3 and not isinstance(f["answered_by"][3], str)
    assert "outside the cached region: flexure_thickness = 0.0026 outside 0.00209..0.00231" in f["message"][3]
    assert s.run.ok == 3 and s.run.refused == 1 and s.errors["answered_by"] == {"reduced model": 3}
    # each row: the same answers and bands as analyze --fidelity live of that design
    for i, t in enumerate(("2.1mm", "2.2mm", "2.3mm")):
        a = cf.analyze(cf.Design.from_concept("concept1", fidelity="live", flexure_thickness=t))
        assert a.answered_by == "reduced model" and f["region_key"][i] == a.region_key == model.region.key()
        row = f.iloc[i]
        for col, got, band, sc in (("engagement_rpm", a.engagement_rpm, "engagement_err_rpm", 1.0),
                                   ("slip_rpm", a.slip_rpm, "slip_err_rpm", 1.0),
                                   ("max_von_mises_MPa", a.max_von_mises_Pa, "stress_err_MPa", 1e-6)):
            q = {"engagement_rpm": "engagement_rpm", "slip_rpm": "slip_rpm", "max_von_mises_MPa": "max_von_mises_Pa"}[col]
            assert row[col] == pytest.approx(got * sc, rel=1e-12)
            assert row[band] == pytest.approx(a.errors[q]["total"] * sc, rel=1e-12) and row[band] > 0
        assert row["engagement_ripple_err_rpm"] > 0 and row["safety_factor"] == pytest.approx(a.safety_factor)
        assert bool(row["engagement_ok"]) == a.requirements["engagement_ok"]
        assert bool(row["slip_ok"]) == a.requirements["slip_ok"]
    # the table is written, and the summary says how each row was answered
    summary = json.loads((tmp_path / "study" / "summary.json").read_text())
    assert summary["errors"]["answered_by"] == {"reduced model": 3} and "live" in summary["errors"]["method"]


def test_a_live_study_spec_refuses_a_bad_outside_rule():
    from clutchfem.studies import SpecError, parse_spec

    with pytest.raises(SpecError, match="live_outside"):
        parse_spec(SPEC.format(extra='live_outside = "guess"'))
    with pytest.raises(SpecError, match="nothing for fidelity 'best'"):
        parse_spec(SPEC.format(extra='live_outside = "fe"').replace('fidelity = "live"', 'fidelity = "best"'))
    assert parse_spec(SPEC.format(extra='live_outside = "fe"')).live_outside == "fe"


@pytest.mark.slow
def test_a_live_study_answers_a_point_outside_with_the_fe_when_asked_and_says_so(model, tmp_path):
    from clutchfem.studies import parse_spec

    # the best path's own mesh (6 mm elsewhere; a 3 mm one here cost twice the CPU): what is checked
    # is the fallback and what it says, not the number
    spec = SPEC.format(extra='live_outside = "fe"').replace(
        '"2.1mm", "2.2mm", "2.3mm", "2.6mm"', '"2.6mm"')
    s = cf.run_study(parse_spec(spec), tmp_path / "study", workers=0, progress=False)
    row = s.frame.iloc[0]
    assert row["status"] == "ok" and row["answered_by"] == "FE (fallback)"
    assert "not live: no reduced model holds this design" in row["message"]
    assert row["engagement_rpm"] > 0 and row["engagement_err_rpm"] > 0  # the best path's own band


def test_live_guidelines_are_the_reduced_models_elasticities_with_their_band(model, tmp_path):
    d = cf.Design.from_concept("concept1", fidelity="live", flexure_thickness="2.15mm")
    g = cf.run_guidelines(d, tmp_path / "g", live_check=0)
    s = find(d).sensitivities(d)
    e = {r["answer"]: r for r in g.table}
    for ans, key in (("engagement_rpm", "engagement_rpm"), ("slip_rpm", "slip_rpm"),
                     ("max_von_mises_MPa", "max_von_mises_Pa")):
        assert e[ans]["E"] == pytest.approx(s.elasticity("flexure_thickness", key), rel=1e-12)
        own = model.own_error(key)
        assert e[ans]["E_band"] == pytest.approx(2 * own * 2.15e-3 / (HI - LO)) and e[ans]["verdict"] == "unchecked"
    # the hand-made answers' own elasticities at 2.15 mm: engagement x^1.5, slip x^0.4, peak x^-0.8
    for ans, want in (("engagement_rpm", 1.5), ("slip_rpm", 0.4), ("max_von_mises_MPa", -0.8)):
        assert abs(e[ans]["E"] - want) <= e[ans]["E_band"] + 0.01, (ans, e[ans])
    assert "reduced model" in g.notes[0] and "no FE check" in g.notes[1]
    assert (tmp_path / "g" / "guidelines.csv").exists() and (tmp_path / "g" / "guidelines.json").exists()
    with pytest.raises(cf.ParameterError) as err:
        cf.run_guidelines(d, tmp_path / "g2", params=["clearance"], live_check=0)
    assert err.value.name == "names"
    with pytest.raises(cf.ParameterError) as err:
        cf.run_guidelines(d, tmp_path / "g2", live_check=-1)
    assert err.value.name == "check"


def test_the_guidelines_command_answers_live(model, tmp_path):
    """``clutchfem guidelines --fidelity live`` (the command line's gate lets it through): the
    reduced model's elasticities; outside every region refused naming the way."""
    from support.cli import cli_in_process

    out = cli_in_process("guidelines", "concept1", "--set", "flexure_thickness=2.15mm", "--fidelity", "live",
                         "--check", "0", "--out", str(tmp_path / "g"), "--json", ok=True)
    assert "reduced model" in out.stdout and "flexure_thickness" in out.stdout
    bad = cli_in_process("guidelines", "concept1", "--set", "flexure_thickness=2.6mm", "--fidelity", "live",
                         "--check", "0", "--out", str(tmp_path / "g2"), ok=False)
    assert bad.returncode == 2 and "clutchfem reduce concept1" in bad.stderr and "Traceback" not in bad.stderr


def test_live_guidelines_outside_every_region_are_refused_naming_the_way(model, tmp_path):
    d = cf.Design.from_concept("concept1", fidelity="live", flexure_thickness="2.6mm")
    with pytest.raises(cf.ParameterError, match="clutchfem reduce concept1"):
        cf.run_guidelines(d, tmp_path / "g", live_check=0)


@pytest.mark.slow
def test_live_guidelines_check_the_strongest_parameter_against_the_fe(model, tmp_path):
    """The hand-made model is not the FE: the check must say where they differ."""
    d = cf.Design.from_concept("concept1", fidelity="live", flexure_thickness="2.15mm")
    g = cf.run_guidelines(d, tmp_path / "g", live_check=1)
    checked = [r for r in g.table if "fe_check" in r]
    assert checked and all(math.isfinite(r["E_fe"]) or r["fe_check"] == "no FE answer" for r in checked)
    for r in checked:
        if r["fe_check"] in ("agrees", "differs"):
            agrees = abs(r["E"] - r["E_fe"]) <= r["E_band"] + 0.05 + 0.1 * abs(r["E_fe"])
            assert (r["fe_check"] == "agrees") == agrees
    assert "FE check (flexure_thickness" in g.notes[1]
