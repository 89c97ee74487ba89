"""Thesis (seed 003) hand checks: eqs 9-10 and the appendix-1 MATLAB script."""

from __future__ import annotations

import math

import numpy as np
import pytest

from clutchfem.clutch import CentrifugalShoe, EngineCurve, slip_rpm
from clutchfem.core import ParameterError, rad_s_to_rpm
from clutchfem.validation import thesis


def test_rod_deflections_match_printed_values():
    # thesis eq 9: 1.52e-7 m; eq 10: 2.02e-5 m (3 significant digits)
    assert thesis.rod_tension_deflection() == pytest.approx(1.52e-7, abs=0.005e-7)
    assert thesis.rod_bending_deflection() == pytest.approx(2.02e-5, abs=0.005e-5)


def test_rod_ratio_is_four_thirds_slenderness_squared():
    ratio = thesis.rod_bending_deflection() / thesis.rod_tension_deflection()
    assert ratio == pytest.approx(4 / 3 * (0.1 / 0.01) ** 2, rel=1e-12)


def test_rod_bad_input():
    with pytest.raises(ParameterError, match="E"):
        thesis.RodExample(E=0.0)


def test_script_equals_shoe_module_and_eq1():
    shoe = thesis.ILLUSTRATIVE_SHOE
    eng = EngineCurve.default()
    res = thesis.matlab_appendix(shoe, eng)
    positive = res.torque > 0
    # the script's unclipped torque equals clutch/shoe.py wherever it is positive ...
    assert np.allclose(res.torque[positive], shoe.torque_at_rpm(res.rpm[positive]), rtol=1e-12)
    # ... and is negative below engagement, where shoe.py returns 0
    assert np.all(res.torque[~positive] <= 0) and np.all(shoe.torque_at_rpm(res.rpm[~positive]) == 0)
    step = res.rpm[1] - res.rpm[0]
    w0 = rad_s_to_rpm(shoe.engagement_speed)
    assert w0 <= res.engagement_rpm <= w0 + step
    assert res.slip_rpm == pytest.approx(slip_rpm(eng, shoe.torque_at_rpm), abs=step)
    # slip speed: clutch torque equals engine torque
    assert float(shoe.torque_at_rpm(res.slip_rpm)) == pytest.approx(eng.torque_at(res.slip_rpm), rel=2e-3)


def test_script_refuses_plus_shoe():
    s = thesis.ILLUSTRATIVE_SHOE
    plus = CentrifugalShoe(s.geometry, s.m, s.R_Tp, s.F_f, s.mu, s.n, "plus")
    with pytest.raises(ParameterError, match="kind"):
        thesis.matlab_appendix(plus)


@pytest.mark.slow
def test_records_and_figures(tmp_path):
    recs = thesis.records()
    by = {r.id: r for r in recs}
    assert len(by) == len(recs)
    assert by["thesis.rod_tension"].status == "reproduced"
    assert by["thesis.rod_bending"].status == "reproduced"
    for r in recs:
        assert r.module == "thesis" and math.isfinite(r.computed)
    # ripple lowers the engagement (thesis 2.3)
    assert by["thesis.example_engagement_ripple_3s"].computed < by["thesis.example_engagement_rpm_eq1"].computed
    paths = thesis.figures(tmp_path)
    assert len(paths) == 2 and all(p.stat().st_size > 10_000 for p in paths)
