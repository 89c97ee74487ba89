"""Today's spring-and-shoe clutch, seed 000 eqs 1-5, against the paper's numbers."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchfem.clutch import BaselineClutch
from clutchfem.clutch.baseline import baseline_torque_at_rpm
from clutchfem.core import ParameterError


def test_paper_torques_at_950_rad_s():
    # seed 000: M_s(1) = 10.23 N m (new), M_s(2) = 8.61 N m (worn); printed to 0.01 N m
    assert float(BaselineClutch.new().torque(950.0)) == pytest.approx(10.23, abs=0.005)
    assert float(BaselineClutch.worn().torque(950.0)) == pytest.approx(8.61, abs=0.005)


def test_hand_computed_characteristic():
    # (m_s r_s + 2 q r_spr^2 cos30) r_b k mu (w^2 - w_o^2), by hand:
    first = 0.04815 * 0.022 + 2 * 0.0686 * 0.028**2 * math.sqrt(3) / 2
    assert BaselineClutch.new().effective_first_moment == pytest.approx(first, rel=1e-12)
    assert BaselineClutch.new().spring_mass_term == pytest.approx(9.3153e-5, rel=1e-4)
    expected = first * 0.0344 * 2 * 0.165 * (800.0**2 - 347.0**2)
    assert float(BaselineClutch.new().torque(800.0)) == pytest.approx(expected, rel=1e-12)


def test_eq5_equals_eqs_1_to_4_step_by_step():
    w = np.linspace(0.0, 1500.0, 301)
    for c in (BaselineClutch.new(), BaselineClutch.worn()):
        assert np.allclose(c.torque(w), c.torque_from_forces(w), rtol=1e-12, atol=1e-12)


def test_zero_below_engagement_never_negative():
    c = BaselineClutch.new()
    w = np.array([0.0, 100.0, 346.9, 347.0])
    assert np.all(c.torque(w) == 0.0)
    assert np.all(c.normal_force(w) == 0.0)
    assert c.spring_tension(347.0) == pytest.approx(c.spring_tension_at_engagement)


@settings(max_examples=60, deadline=None)
@given(w1=st.floats(0, 2000), w2=st.floats(0, 2000))
def test_monotone_and_worn_below_new(w1, w2):
    new, worn = BaselineClutch.new(), BaselineClutch.worn()
    lo, hi = sorted((w1, w2))
    assert float(new.torque(lo)) <= float(new.torque(hi))
    assert float(worn.torque(hi)) <= float(new.torque(hi))


def test_rpm_helpers():
    rpm = np.array([3000.0, 8000.0, 12000.0])
    w = rpm * 2 * np.pi / 60
    assert np.allclose(baseline_torque_at_rpm(rpm), BaselineClutch.new().torque(w))
    assert np.allclose(baseline_torque_at_rpm(rpm, "worn"), BaselineClutch.worn().torque(w))
    assert BaselineClutch.new().engagement_rpm == pytest.approx(347 * 60 / (2 * math.pi))
    with pytest.raises(ParameterError, match="state"):
        baseline_torque_at_rpm(rpm, "rusty")


@pytest.mark.parametrize(
    "kw, name",
    [({"m_s": -0.01}, "m_s"), ({"k": 0}, "k"), ({"gamma": 2.0}, "gamma"), ({"mu": -1}, "mu"),
     ({"r_s": 0.05}, "r_s"), ({"q_spr": -1.0}, "q_spr")],
)
def test_bad_parameters(kw, name):
    with pytest.raises(ParameterError) as ei:
        BaselineClutch(**kw)
    assert ei.value.name == name


def test_bad_speed():
    with pytest.raises(ParameterError, match="omega"):
        BaselineClutch.new().torque(-1.0)
