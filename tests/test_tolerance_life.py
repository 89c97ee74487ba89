"""Tolerances over the life (tolerance --life N): every part drifts as the nominal design's life
run does; the share in spec at N starts against the share new, per target with its Wilson
interval; the refusals; one small end-to-end run of the command (slow)."""

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.core import ParameterError
from clutchfem.targets import Targets
from clutchfem.tolerances.over_life import shares_over_life, wilson
from support.cli import cli_in_process


def _life(eng, slip):
    n = len(eng)
    return SimpleNamespace(starts=np.linspace(0.0, 1e4, n), engagement_rpm=np.array(eng, float),
                           slip_rpm=np.array(slip, float), torque_at_max_engine_torque_Nm=np.full(n, 3.0), band={},
                           seconds=0.0)


def _parts(slips, eng=3700.0, sf=1.6):
    return [{"status": "ok", "engagement_rpm_with_ripple": eng, "slip_rpm": s, "safety_factor": sf} for s in slips]


def test_drift_towards_a_limit_lowers_the_share_in_spec():
    spec = Targets(3510.0, None, 8000.0, 1.5).constraints()
    rows = _parts([7800.0, 7850.0, 7900.0, 7950.0, 7990.0])
    # slip rises by at most 120 rpm (towards its maximum), engagement rises (away from its minimum)
    L = _life([3600.0, 3650.0, 3700.0], [7000.0, 7120.0, 7080.0])
    lf = shares_over_life(rows, spec, L, 1e4, 0, [])
    slip = lf["in_spec"]["slip speed <= max"]
    assert slip["new"]["k_in_spec"] == 5
    assert slip["at_life"]["k_in_spec"] == sum(1 for r in rows if r["slip_rpm"] + 120.0 <= 8000.0) == 2
    assert slip["at_life"]["share_in_spec"] < slip["new"]["share_in_spec"]
    assert slip["at_life"]["ci95"] == pytest.approx(list(wilson(2, 5)))
    eng = lf["in_spec"]["engagement with ripple >= LO"]
    assert eng["at_life"] == eng["new"]  # a drift away from the limit changes nothing
    assert lf["in_spec"]["any"]["at_life"]["k_in_spec"] == 2
    assert lf["drift_rpm"]["slip_rpm"] == [0.0, 120.0] and lf["drift_rpm"]["engagement_rpm_with_ripple"] == [0.0, 100.0]


def test_a_downward_drift_moves_the_engagement_minimum_and_a_lost_slip_speed_misses():
    spec = Targets(3510.0, None, 8000.0, 1.5).constraints()
    rows = _parts([7500.0], eng=3540.0) + _parts([7500.0], eng=3600.0)
    lf = shares_over_life(rows, spec, _life([3600.0, 3550.0], [7000.0, 7010.0]), 1e4, 0, [])
    assert lf["in_spec"]["engagement with ripple >= LO"]["at_life"]["k_in_spec"] == 1  # 3540 - 50 < 3510
    lost = shares_over_life(rows, spec, _life([3600.0, 3650.0], [7000.0, math.nan]), 1e4, 0, [])
    assert lost["in_spec"]["slip speed <= max"]["new"]["k_in_spec"] == 2
    assert lost["in_spec"]["slip speed <= max"]["at_life"]["k_in_spec"] == 0
    # parts the rules refuse: counted out of spec both ways
    bad = shares_over_life(rows, spec, _life([3600.0, 3650.0], [7000.0, 7010.0]), 1e4, 2, [])
    assert bad["in_spec"]["any_counting_unbuildable"]["new"]["n"] == 4


@pytest.mark.parametrize("kw, name", [({"life": 0}, "life"), ({"life": 1e9}, "life"), ({"life": True}, "life"),
                                      ({"life_options": {"wear": None}}, "life_options"),
                                      ({"life": 100, "life_options": {"wer": None}}, "life_options")])
def test_api_refuses_bad_lives(kw, name):
    d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    with pytest.raises(ParameterError, match=name):
        cf.tolerance(d, {"flexure_thickness": "0.05mm"}, n=8, workers=0, **kw)


@pytest.mark.parametrize("args, text", [(["--life", "0"], "--life"), (["--life", "1e9"], "--life"),
                                        (["--life", "many"], "--life"),
                                        (["--wear-coefficient", "1e-3"], "--wear-coefficient"),
                                        (["--life", "1000", "--allocate"], "--life")])
def test_cli_refusals_name_the_option(args, text):
    r = cli_in_process("tolerance", "concept1", "--tol", "flexure_thickness=+-0.05mm", *args)
    assert r.returncode != 0 and text in r.stderr and "Traceback" not in r.stderr


@pytest.mark.slow
def test_tolerance_life_end_to_end():
    """Concept 1 at 3 mm on the fast path; a large Archard k and a coarse wear step make the
    drift of 1000 starts visible in two wear states (~10 s CPU)."""
    r = cli_in_process("tolerance", "concept1", "--mesh-size", "3mm", "--fidelity", "fast", "--tol",
                       "flexure_thickness=+-0.05mm", "--n", "8", "--no-shifts", "--workers", "0", "--life", "1000",
                       "--wear-coefficient", "1e-3", "--wear-rate-change", "10", "--max-wear-step", "1mm",
                       "--rebuild-depth", "never", "--json", ok=True)
    d = json.loads(r.stdout)
    lf = d["life"]
    assert lf["starts"] == 1000.0 and lf["wear_coefficient"] == 1e-3
    assert {"drift_rpm", "torque_drift_Nm", "in_spec", "assumption", "nominal_life_new_rpm", "wear_states"} <= set(lf)
    assert "nominal" in lf["assumption"]
    hi = max(v[1] for v in lf["drift_rpm"].values())
    assert hi > 0  # the wear moves the answers
    names = [s["name"] for s in d["spec"]] + ["any"]
    assert set(names) <= set(lf["in_spec"])
    for name in names:
        new, old = lf["in_spec"][name]["new"], lf["in_spec"][name]["at_life"]
        assert old["share_in_spec"] <= new["share_in_spec"]
        assert old["ci95"][0] <= old["share_in_spec"] <= old["ci95"][1]
        assert new["n"] == old["n"] == d["out_of_spec"][name]["n"]
        assert new["k_in_spec"] == new["n"] - d["out_of_spec"][name]["k"]  # the same parts as out_of_spec counts
    assert any("drift as the nominal" in n for n in d["notes"])


def test_optimize_tol_with_life_points_to_tolerance_life():
    r = cli_in_process("optimize", "concept4", "--tol", "clearance=+-0.02mm", "--life", "5000")
    assert r.returncode != 0 and "Traceback" not in r.stderr
    assert "option --life" in r.stderr and "clutchfem tolerance" in r.stderr and "--life 5000" in r.stderr
