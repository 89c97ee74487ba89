"""Guidelines from the design sensitivities (issue 21): the elasticity of a guideline is the
one of ``cf.sensitivities`` on morphed meshes, its method is named in the JSON, and the
derivatives with respect to an operating input (mu) are the central difference of two
analyses of the same design with mu changed.

Small: concept 4 on the 3 mm mesh, in process (``workers=0``), one parameter, one input; the
guideline runs on three one-at-a-time points and without the design point's error estimate
(neither enters an elasticity: the sensitivities are computed apart from the study's rows).
"""

from __future__ import annotations

import dataclasses
import json

import pytest

import clutchfem as cf
from clutchfem.core import ParameterError
from clutchfem.guidelines.elasticity import SENSITIVITY_KEY, GuidelineSettings

MESH = cf.MeshSettings(size="3mm")


@pytest.fixture(scope="module")
def design():
    return cf.Design.from_concept("concept4", mesh=MESH)


@pytest.fixture(scope="module")
def sens(design):
    return cf.sensitivities(design, ["flexure_thickness", "mu", "idle_rpm"], workers=0)


@pytest.mark.slow
def test_guideline_elasticity_is_the_sensitivities_and_says_its_method(design, sens, tmp_path):
    gs = dataclasses.replace(GuidelineSettings.from_design(design, ["flexure_thickness"], points=3, inputs=["mu"]),
                             errors=False)
    g = cf.run_guidelines(gs, tmp_path, workers=0, progress=False)
    doc = json.loads((tmp_path / "guidelines.json").read_text())
    assert doc["ranking"] == ["flexure_thickness"] and doc["operating_inputs"] == ["mu"]
    assert doc["methods"] == {"flexure_thickness": "central difference on morphed meshes",
                              "mu": "central difference, same mesh (operating input)"}
    rows = {(r["parameter"], r["answer"]): r for r in doc["elasticities"]}
    for name in ("flexure_thickness", "mu"):
        for col, key in SENSITIVITY_KEY.items():
            e, want = rows[(name, col)]["E"], sens.elasticity(name, key)
            if want is None:  # no answer at the design: none in the guideline either
                assert e is None or e != e, (name, col)
                continue
            assert e == pytest.approx(want, rel=1e-9, abs=1e-12), (name, col)
            assert rows[(name, col)]["method"] == doc["methods"][name]
    eng = rows[("flexure_thickness", "engagement_rpm")]
    assert eng["verdict"] == "stable" and 0.5 < eng["E"] < 1.6  # checked at 10x the step: a smooth derivative
    assert eng["check_step"] == pytest.approx(10 * eng["step"])
    assert abs(rows[("mu", "engagement_rpm")]["E"]) < 1e-3  # engagement: before any contact, no friction
    assert rows[("mu", "torque_at_max_engine_torque_Nm")]["E"] > 0.5  # a friction clutch: torque ~ mu
    assert g.inputs == ["mu"] and "E_remeshed" not in eng  # the remeshed check is an option


@pytest.mark.slow
def test_operating_input_derivative_is_a_two_point_difference_of_analyze(design, sens):
    mu, h = sens.values["mu"], sens.steps["mu"]
    assert mu == 0.165 and h == pytest.approx(0.01 * mu)
    lo, hi = (cf.analyze(cf.Design.from_concept("concept4", mesh=MESH, mu=float(f"{m:.12g}")), errors=False)
              for m in (mu - h, mu + h))
    for key, attr, scale in (("torque_at_max_engine_torque_Nm", "torque_at_max_engine_torque_Nm", 1.0),
                             ("slip_rpm", "slip_rpm", 1.0), ("max_von_mises_Pa", "max_von_mises_Pa", 1.0)):
        direct = (getattr(hi, attr) - getattr(lo, attr)) * scale / (2 * h)
        assert sens.derivatives["mu"][key] == pytest.approx(direct, rel=1e-6, abs=1e-9), key
    assert sens.methods["mu"] == "central, same mesh (operating input)" and sens.units["mu"] == "-"
    assert sens.derivatives["mu"]["torque_at_max_engine_torque_Nm"] > 0
    # the idle speed enters no answer of this design (only the engagement limit a x idle)
    assert sens.units["idle_rpm"] == "rpm" and sens.derivatives["idle_rpm"]["engagement_rpm"] == 0.0
    assert any("a x idle" in n for n in sens.notes)
    assert "mu /-" in sens.table() and "idle_rpm /rpm" in sens.table()


def test_operating_inputs_refused_as_a_user_would_hear_it(design, tmp_path):
    with pytest.raises(ParameterError, match="drum_wall"):  # the fast path's drum is rigid: no wall
        cf.sensitivities(design, ["drum_wall"], workers=0)
    with pytest.raises(ParameterError, match="rigid"):
        cf.run_guidelines(design, tmp_path, params=["flexure_thickness"], inputs=["drum_wall"], workers=0,
                      progress=False)
    with pytest.raises(ParameterError, match="operating inputs among"):
        cf.run_guidelines(design, tmp_path, params=["flexure_thickness"], inputs=["rpm"], workers=0, progress=False)


@pytest.mark.slow
def test_drum_wall_derivative_on_an_elastic_drum():
    """An elastic drum's wall is an operating input (the fast path's rigid drum has none):
    differentiated on the design's own mesh; a thicker wall yields less under the shoes,
    so the shoes push harder: more torque."""
    d = cf.Design.from_concept("concept4", mesh=MESH, drum_wall="2mm")
    s = cf.sensitivities(d, ["drum_wall"], workers=0)
    assert s.values["drum_wall"] == 0.002 and s.steps["drum_wall"] == 1e-5 and s.units["drum_wall"] == "m"
    assert s.methods["drum_wall"] == "central, same mesh (operating input)" and s.kinds["drum_wall"] == "operating input"
    assert s.derivatives["drum_wall"]["torque_at_max_engine_torque_Nm"] > 0
    assert s.derivatives["drum_wall"]["mass_kg"] == 0.0  # the part is not the drum


@pytest.mark.slow
def test_an_operating_input_at_zero_is_not_studied_and_said(tmp_path):
    """(x / A) dA/dx is 0 at x = 0 whatever the derivative: mu = 0 gets a note, not a row.  On a
    6 mm mesh (the module's is 3 mm): what is checked is which inputs are studied, not a number."""
    d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="6mm"), mu=0.0)
    gs = dataclasses.replace(GuidelineSettings.from_design(d, ["clearance"], points=3, inputs=["mu"]), errors=False)
    g = cf.run_guidelines(gs, tmp_path, workers=0, progress=False)
    assert g.inputs == [] and not any(r["parameter"] == "mu" for r in g.table)
    assert any(n.startswith("operating inputs not studied") and n.endswith("mu") for n in g.notes)
