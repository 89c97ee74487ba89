"""Design sensitivities on morphed meshes and robust design to targets (issue 21): the
derivatives are flat in the step, the limits move inward by their margins, refusals name the
option."""

import subprocess
import sys

import pytest

import clutchfem as cf
from clutchfem.core import ParameterError
from clutchfem.studies import Targets
from clutchfem.studies.robust import shifted

COARSE = cf.MeshSettings(size="3mm")
CLI = [sys.executable, "-m", "clutchfem.cli"]


@pytest.fixture(scope="module")
def design():
    return cf.Design.from_concept("concept4", mesh=COARSE)


def test_sensitivities_are_flat_in_the_step_on_morphed_meshes(design):
    """Central differences at 0.01 and 0.1 mm on meshes morphed from the design agree to
    0.1 % (the derivative of a smooth answer, not of remeshing noise) for the engagement
    speeds and the mass.  Slip speed, torque and peak stress are left out of that check:
    their extraction has its own steps (the slip root's tolerance, the contact set, the peak
    node), which scatter their derivatives by 1-3 % on this 3 mm mesh with or without
    morphing; measured on the default mesh in BENCHMARKS.md, "Robust design"."""
    fine = cf.sensitivities(design, ["flexure_thickness"], workers=0)
    wide = cf.sensitivities(design, ["flexure_thickness"], workers=0, steps={"flexure_thickness": 1e-4})
    assert fine.methods["flexure_thickness"] == "central, morphed"
    assert not [n for n in fine.notes if "contact node enters or leaves" not in n]  # both sides morphed
    for k in ("engagement_rpm", "engagement_rpm_with_ripple", "mass_kg"):
        a, b = fine.derivatives["flexure_thickness"][k], wide.derivatives["flexure_thickness"][k]
        assert a is not None and b is not None, k
        assert abs(a - b) <= 1e-3 * abs(b), (k, a, b)
    d = fine.derivatives["flexure_thickness"]
    assert d["engagement_rpm"] > 0 and d["mass_kg"] > 0 and d["max_von_mises_Pa"] < 0  # stiffer, heavier, lower stress
    e = fine.elasticity("flexure_thickness", "engagement_rpm")
    assert 0.3 < e < 3.0  # a cantilever's stiffness ~ t^3, engagement ~ sqrt(k): elasticity near 1.5
    assert "flexure_thickness /mm" in fine.table()


def test_sensitivities_refuse_bad_input(design):
    with pytest.raises(ParameterError, match="flexure_thicknes"):
        cf.sensitivities(design, ["flexure_thicknes"], workers=0)
    with pytest.raises(ParameterError, match="steps"):
        cf.sensitivities(design, ["clearance"], workers=0, steps={"clearance": -1e-5})
    with pytest.raises(ParameterError, match="design"):
        cf.sensitivities("concept4", workers=0)


def test_shifted_targets_move_every_limit_inward():
    t = Targets(3510.0, 5000.0, 8000.0, 1.5, fatigue_min=1.0)
    s = shifted(t, {"engagement_rpm_with_ripple": 100.0, "slip_rpm": 50.0, "safety_factor": 0.1,
                    "fatigue_safety_factor": 0.05})
    assert (s.engage_rpm_lo, s.engage_rpm_hi, s.slip_rpm_max) == (3610.0, 4900.0, 7950.0)
    assert s.safety_factor_min == pytest.approx(1.6) and s.fatigue_min == pytest.approx(1.05)


def test_robust_optimize_refuses_bad_yield_distribution_and_no_tolerance(design):
    for kw, name in (({"yield_target": 1.2}, "yield"), ({"dist": "gauss"}, "dist")):
        with pytest.raises(ParameterError, match=name):
            cf.robust_optimize(design, {"clearance": "0.02mm"}, workers=0, **kw)
    with pytest.raises(ParameterError, match="tol"):
        cf.robust_optimize(design, {}, workers=0)
    with pytest.raises(ParameterError, match="flexure_thicknes"):
        cf.robust_optimize(design, {"flexure_thicknes": "0.05mm"}, workers=0)


@pytest.mark.parametrize("args, needle", [
    (["--tol", "flexure_thickness=+-0.05mm", "--yield", "1.5"], "--yield"),
    (["--tol", "flexure_thickness=0.05mm"], "--tol"),
])
def test_cli_refuses_bad_robust_options_without_a_traceback(args, needle):
    r = subprocess.run(CLI + ["optimize", "concept4", "--mesh-size", "3mm", "--workers", "0", *args],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode != 0
    assert needle in r.stderr + r.stdout and "Traceback" not in r.stderr


def test_robust_rounds_start_with_the_deterministic_optimum(design):
    """SORA's first cycle: the deterministic optimum (round 0), then the shifted rounds; the
    evaluations of every round are counted."""
    r = cf.robust_optimize(design, {"clearance": "0.02mm"}, max_evals=6, rounds=1, workers=0,
                           free=["flexure_thickness", "clearance"])
    assert r.rounds[0]["round"] == 0 and r.rounds[0]["deterministic"] is True
    assert r.rounds[1]["round"] == 1 and "margins" in r.rounds[1]
    assert r.evaluations == r.rounds[0]["evaluations"] + r.rounds[1]["evaluations"]
