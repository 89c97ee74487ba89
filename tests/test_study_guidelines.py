"""Design guidelines: the elasticities equal finite differences of the single-design
analysis, and the step check tells a smooth derivative from mesh noise.

* ``clutchfem guidelines concept4 --params flexure_thickness --inputs mu --remeshed-check
  --json`` (coarse mesh, ``--workers 0``, the command run in the test's process: what is
  checked is its JSON and files, not a process): the remeshed check's E against
  ``analyze(Design.from_concept(...))`` at x0 (1 -+ h): the same numbers; the elasticity
  itself (morphed) within the remeshed check's own agreement rule of it;
* physics: engagement rises with flexure thickness at less than beam theory's t^1.5
  (w_e ~ sqrt(k), k ~ t^3 if only the flexure bent; the shoe, heel and hub are compliant
  too), and the shoe's mass does not depend on the flexure;
* the decision rule on synthetic answers: an exact power law is stable with its exponent,
  a 1 % alternating noise on it is flagged unstable, with the noise estimated.
"""

from __future__ import annotations

import json
import math

import pytest

from clutchfem.analysis import analyze
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.guidelines.elasticity import elasticity, fd_values
from clutchfem.loadcase import Design
from support.cli import cli_in_process


def _answers(an) -> dict:
    return {"engagement_rpm": an.engagement_rpm, "slip_rpm": an.slip_rpm,
            "torque_at_max_engine_torque_Nm": an.torque_at_max_engine_torque_Nm,
            "max_von_mises_MPa": an.max_von_mises_Pa / 1e6, "shoe_mass_g": an.part["shoes"][0]["mass_kg"] * 1e3,
            "contact_arc_deg": an.contact_arc_at_max_engine_torque_deg}


@pytest.mark.slow
def test_guideline_elasticities_equal_finite_differences_of_single_design_analysis(tmp_path):
    h = 0.02
    run = cli_in_process("guidelines", "concept4", "--params", "flexure_thickness", "--mesh-size", "3mm", "--workers",
                         "0", "--points", "3", "--step", str(h), "--inputs", "mu", "--remeshed-check", "--out",
                         tmp_path / "g", "--json")
    assert run.returncode == 0, run.stderr[-3000:]
    doc = json.loads(run.stdout)
    assert doc["ranking"] == ["flexure_thickness"] and doc["operating_inputs"] == ["mu"]
    assert doc["methods"]["flexure_thickness"] == "central difference on morphed meshes"
    assert doc["remeshed_check"]["step"] == h
    table = {r["answer"]: r for r in doc["elasticities"] if r["parameter"] == "flexure_thickness"}
    x0 = get_concept("concept4").Params().flexure_thickness
    ms = MeshSettings(size=3e-3)
    P = get_concept("concept4").Params
    lo, hi = (_answers(analyze(Design.from_concept("concept4", P(flexure_thickness=float(f"{x0 * f:.12g}")),
                                                   mesh=ms), errors=False)) for f in (1 - h, 1 + h))
    for col in ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm", "max_von_mises_MPa"):
        direct = (math.log(hi[col]) - math.log(lo[col])) / (math.log1p(h) - math.log1p(-h))
        assert table[col]["E_remeshed"] == pytest.approx(direct, rel=1e-9, abs=1e-12), col
    assert abs(table["shoe_mass_g"]["E"]) < 1e-6  # the shoe zone does not contain the flexure
    eng = table["engagement_rpm"]
    assert eng["stable"] and 0.5 < eng["E"] < 1.6, eng
    assert eng["E_remeshed_fit"] == pytest.approx(eng["E_remeshed"], abs=0.05 + 0.1 * abs(eng["E_remeshed"]))
    assert eng["E"] == pytest.approx(eng["E_remeshed"], abs=0.05 + 0.1 * abs(eng["E"]))  # morphed vs remeshed
    err = doc["design_point_errors"]["engagement_rpm"]  # the design point carries its error estimate
    assert err["band"] > err["discretisation"] >= 0 and err["unit"] == "rpm"
    for name in ("guidelines.csv", "one_at_a_time.csv", "one_at_a_time.png", "elasticities.png", "guidelines.json"):
        assert (tmp_path / "g" / name).stat().st_size > 0


def test_step_check_accepts_a_power_law_and_flags_mesh_noise():
    x0, h = 2.0e-3, 0.02

    def power(x):
        return 3.0 * x ** 1.5

    e = elasticity(x0, h, power)
    assert e["stable"] and e["E"] == pytest.approx(1.5, rel=1e-9) and e["E_fit"] == pytest.approx(1.5, rel=1e-6)
    assert e["noise_rel"] < 1e-9
    xs = fd_values(x0, h)
    # +-1 % from one design to the next, not symmetric about x0 (symmetric noise would cancel
    # in every central difference): mesh noise
    sign = dict(zip(xs, (1, -1, 1, 1, -1, 1, -1)))

    def noisy(x):
        return power(x) * (1 + 0.01 * sign[x])

    n = elasticity(x0, h, noisy)
    assert not n["stable"]
    assert 0.003 < n["noise_rel"] < 0.03  # the fit's residual sees the 1 % noise
    assert abs(n["E_fit"] - 1.5) < abs(n["E_half_step"] - 1.5)  # the fit averages it out

    def missing(x):
        return None if x > x0 * 1.03 else power(x)

    m = elasticity(x0, h, missing)  # no answer at x0 (1 + 2h): no verdict of stability
    assert m["E"] == pytest.approx(1.5, rel=1e-9) and m["verdict"] == "unchecked" and math.isnan(m["E_double_step"])

    def edge(x):  # x0 on the edge of the feasible set: nothing answered above it
        return None if x > x0 else power(x)

    o = elasticity(x0, h, edge)
    assert o["method"] == "one-sided (-)" and o["E"] == pytest.approx(1.5, rel=1e-9) and o["verdict"] == "stable"
