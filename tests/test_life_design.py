"""Design for life (optimize --life): the wear allowance tightens the targets by the drift the
wear moves each answer towards its limit, the life check of an optimum, the refusals; one
small end-to-end run (slow)."""

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.core import ParameterError
from clutchfem.targets import Targets, life_check, wear_allowance
from support.cli import cli_in_process


def _life(eng, slip, torque=None):
    n = len(eng)
    return SimpleNamespace(starts=np.linspace(0.0, 1e5, n), engagement_rpm=np.array(eng, float),
                           slip_rpm=np.array(slip, float),
                           torque_at_max_engine_torque_Nm=np.array(torque or [5.0] * n, float), band={})


def test_allowance_moves_only_the_limits_the_wear_moves_towards():
    L = _life([3600, 3650, 3700], [7000, 7100, 7300], [5.0, 4.9, 4.7])
    a = wear_allowance(L, reserve=0.5)
    assert a.drift["engagement_rpm_with_ripple"] == (0.0, 100.0) and a.drift["slip_rpm"] == (0.0, 300.0)
    assert a.torque_drift_Nm == pytest.approx(-0.3)
    t = a.tighten(Targets(3510.0, 4500.0, 8000.0, 1.5))
    # engagement rises: the minimum keeps its value (new is worst), the maximum drops by 1.5 x 100 rpm
    assert (t.engage_rpm_lo, t.engage_rpm_hi, t.slip_rpm_max) == (3510.0, 4350.0, 7550.0)
    assert t.safety_factor_min == 1.5
    # a drift downwards moves the minimum up instead
    down = wear_allowance(_life([3600, 3550], [7000, 7000]), reserve=0.0).tighten(Targets(3510.0, None, 8000.0, 1.5))
    assert (down.engage_rpm_lo, down.slip_rpm_max) == (3560.0, 8000.0)


def test_allowance_refuses_a_life_that_loses_the_slip_speed_and_bad_reserves():
    a = wear_allowance(_life([3600, 3700], [7000, math.nan]))
    with pytest.raises(ParameterError, match="life"):
        a.tighten(Targets(3510.0, None, 8000.0, 1.5))
    with pytest.raises(ParameterError, match="reserve"):
        wear_allowance(_life([3600, 3700], [7000, 7100]), reserve=-0.1)
    with pytest.raises(ParameterError, match="life"):  # the allowance leaves no slip limit
        wear_allowance(_life([3600, 3700], [7000, 17000])).tighten(Targets(3510.0, None, 8000.0, 1.5))


def test_life_check_adds_the_drift_to_the_new_answers():
    t = Targets(3510.0, None, 8000.0, 1.5)
    row = {"engagement_rpm_with_ripple": 3550.0, "slip_rpm": 7800.0}
    L = _life([3600, 3650, 3700], [7000, 7150, 7300])
    c = life_check(t, row, L)
    assert not c["met"] and c["missed_by_rpm"] == pytest.approx(100.0)
    assert c["worst_slack_rpm"]["slip_rpm<="] == pytest.approx(-100.0)
    assert c["first_miss_starts"]["slip_rpm<="] == pytest.approx(1e5)
    assert c["worst_slack_rpm"]["engagement_rpm_with_ripple>="] == pytest.approx(40.0)
    ok = life_check(t, {**row, "slip_rpm": 7600.0, "safety_factor": 1.6}, L)
    assert ok["met"] and ok["missed_by_rpm"] == 0.0 and ok["missed_new"] == []
    weak = life_check(t, {**row, "slip_rpm": 7600.0, "safety_factor": 1.2}, L)
    assert not weak["met"] and weak["missed_by_rpm"] == 0.0 and weak["missed_new"][0].startswith("safety_factor")


@pytest.mark.parametrize("args, text", [(["--life", "0"], "--life"), (["--life", "1e9"], "--life"),
                                        (["--life", "100starts"], "--life"),
                                        (["--life", "100", "--tol", "clearance=+-0.02mm"], "--life")])
def test_optimize_life_refusals_name_the_option(args, text):
    r = cli_in_process("optimize", "concept4", *args)
    assert r.returncode != 0 and text in r.stderr and "Traceback" not in r.stderr


def test_optimize_for_life_refuses_bad_values():
    s = cf.EvalSettings("concept4", mesh_size=0.003)
    t = Targets(3510.0, None, 8000.0, 1.5)
    for kw in ({"starts": 0}, {"starts": True}, {"starts": 100, "reserve": 6.0}):
        with pytest.raises(ParameterError):
            cf.optimize_for_life(s, t, starts=kw.pop("starts"), **kw)


@pytest.mark.slow
def test_optimize_life_end_to_end_checks_its_optimum():
    """A tiny search (one free parameter, a few designs, a coarse mesh, 300 starts): the JSON
    carries the allowance, the tightened targets, the full life of the optimum and its check,
    whose verdict agrees with the check recomputed from that life."""
    r = cli_in_process("optimize", "concept4", "--free", "flexure_thickness", "--sample", "2", "--max-evals", "6",
                       "--method", "pattern", "--mesh-size", "3mm", "--fidelity", "fast", "--workers", "0",
                       "--life", "300", "--json", ok=True)
    d = json.loads(r.stdout)["life"]
    assert d["life_starts"] == 300 and d["life"]["starts"][-1] == pytest.approx(300)
    slip_t = [c for c in d["tightened_targets"] if c[1] == "slip_rpm"][0][2]
    slip_0 = [c for c in d["targets"] if c[1] == "slip_rpm"][0][2]
    drift = d["rounds"][0]["allowance"]["drift_rpm"]["slip_rpm"][1]
    assert slip_0 - [c for c in d["rounds"][0]["tightened_targets"] if c[1] == "slip_rpm"][0][2] == \
        pytest.approx(drift * 1.25)
    assert slip_t <= slip_0
    assert d["met"] == (d["check"]["missed_by_rpm"] == 0.0 and not d["check"]["missed_new"]) and 1 <= len(d["rounds"]) <= 2
