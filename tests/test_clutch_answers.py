"""The designer's answers without FE: slip classification, crossings, requirement factors,
sweep speeds, contact extent (synthetic inputs with hand-known results)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from clutchfem.analysis import Requirements, check_speeds, slip_answer
from clutchfem.clutch import EngineCurve, torque_crossings
from clutchfem.core import ParameterError

FLAT = EngineCurve((1000.0, 10000.0), (3.0, 3.0), source="flat 3 N m")


def ramp(start_rpm, slope):
    """Clutch torque 0 below start_rpm, then slope [N m per rpm]."""
    return lambda r: np.maximum(slope * (np.asarray(r, dtype=float) - start_rpm), 0.0)


def test_slip_answer_slips_at_the_hand_crossing():
    s = slip_answer(FLAT, ramp(2000.0, 0.001), engagement_rpm=2000.0)
    assert s.status == "slips"
    assert s.rpm == pytest.approx(5000.0, abs=1e-5)  # 0.001 (r - 2000) = 3
    assert len(s.crossings) == 1
    assert s.crossings[0][1] == "up" and s.crossings[0][0] == pytest.approx(5000.0, abs=1e-5)


def test_slip_answer_never_holds():
    s = slip_answer(FLAT, ramp(2000.0, 1e-5), engagement_rpm=2000.0)  # max 0.08 N m < 3 N m
    assert s.rpm is None and s.status == "never holds"
    assert "never holds" in s.note and "10000 rpm" in s.note and "slips at every speed" in s.note


def test_no_friction_never_holds_and_says_why():
    s = slip_answer(FLAT, lambda r: np.zeros_like(np.asarray(r, dtype=float)), engagement_rpm=2000.0)
    assert s.status == "never holds" and "no torque" in s.note


def test_zero_engine_torque_at_the_first_point_is_not_holding():
    """A curve starting at 0 N m: 0 >= 0 is not 'holding' (issue 12: it said 'holds at
    start, slip 500 rpm'); the slip speed is where the engaged clutch meets the curve."""
    eng = EngineCurve((500.0, 1000.0, 10000.0), (0.0, 3.0, 3.0), source="starts at 0")
    s = slip_answer(eng, ramp(2000.0, 0.001), engagement_rpm=2000.0)
    assert s.status == "slips" and s.rpm == pytest.approx(5000.0, abs=1e-5)


@pytest.mark.parametrize("eng", [None, 12000.0, math.inf])
def test_slip_answer_never_engages(eng):
    s = slip_answer(FLAT, lambda r: np.zeros_like(np.asarray(r, dtype=float)), engagement_rpm=eng)
    assert s.rpm is None and s.status == "never engages"
    assert "never engages" in s.note


def test_slip_answer_holds_at_start():
    s = slip_answer(FLAT, lambda r: np.full_like(np.asarray(r, dtype=float), 5.0), engagement_rpm=500.0)
    assert s.status == "holds at start" and s.rpm == pytest.approx(1000.0)


def test_several_crossings_first_upward_one_is_the_slip_speed():
    # clutch torque 3 + sin(pi (r - 3000)/2000) above 1500 rpm: crosses the flat 3 N m engine
    # line at 3000 (up), 5000 (down), 7000 (up), 9000 rpm (down); the engine (drum held)
    # stops at the first upward one.
    def clutch(r):
        r = np.asarray(r, dtype=float)
        return np.where(r > 1500.0, 3.0 + np.sin(np.pi * (r - 3000.0) / 2000.0), 0.0)

    cross = torque_crossings(FLAT, clutch, rpm_min=2000.0)
    assert [d for _, d in cross] == ["up", "down", "up", "down"]
    assert [r for r, _ in cross] == pytest.approx([3000.0, 5000.0, 7000.0, 9000.0], abs=1e-4)
    s = slip_answer(FLAT, clutch, engagement_rpm=1500.0)
    assert s.status == "slips" and s.rpm == pytest.approx(3000.0, abs=1e-4)
    assert "4 times" in s.note and "first upward" in s.note


def test_self_locking_clutch_slips_where_it_engages():
    s = slip_answer(FLAT, lambda r: np.where(np.asarray(r) >= 4000.0, np.inf, 0.0), engagement_rpm=4000.0)
    assert s.rpm == pytest.approx(4000.0, abs=1e-3)


@pytest.mark.parametrize("name, value", [("a", 0.0), ("a", -1.3), ("b", 0.0), ("b", -0.5),
                                         ("a", math.nan), ("b", math.inf), ("a", True)])
def test_requirement_factors_must_be_positive(name, value):
    with pytest.raises(ParameterError) as ei:
        Requirements(**{name: value})
    msg = str(ei.value)
    assert ei.value.name == name and "> 0" in msg
    assert ("idle" in msg) if name == "a" else ("max" in msg and "torque" in msg)


def test_requirement_defaults_are_flagged_assumed():
    assert Requirements().assumed and (Requirements().a, Requirements().b) == (1.3, 1.0)
    assert not Requirements(a=1.5).assumed


def test_sweep_speeds_inside_the_engine_curve():
    eng = EngineCurve.default()
    r = check_speeds(None, eng)
    assert r[0] == 0.0 and r[-1] == 14000.0 and np.all(np.diff(r) > 0)
    # the engine's max speed (stresses) and rpm of max torque (torque, arc) are always solved
    assert check_speeds([1000.0, 5000.0], eng).tolist() == [1000.0, 5000.0, 8000.0, 14000.0]
    for bad in ([0.0, 15000.0], [-10.0, 100.0], [np.nan]):
        with pytest.raises(ParameterError) as ei:
            check_speeds(bad, eng)
        assert ei.value.name == "rpm"
    with pytest.raises(ParameterError, match="14000"):
        check_speeds([20000.0], eng)
