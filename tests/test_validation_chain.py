"""Chain impact on a pocket wheel (seed 002): geometry, closed forms, energy balance, records."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchfem.core import ParameterError
from clutchfem.validation import chain

T, D, W = 0.064, 0.018, 20.0
PSI = np.radians(np.linspace(20.0, 60.0, 41))


@pytest.mark.parametrize("z", [6, 8, 10])
def test_chords_and_eq9(z):
    R = chain.pitch_radius(T, D, z)
    d1, d2 = chain.central_angles(T, D, z)
    assert 2 * R * math.sin(d1 / 2) == pytest.approx(T + D, rel=1e-12)
    assert 2 * R * math.sin(d2 / 2) == pytest.approx(T - D, rel=1e-12)
    assert d1 + d2 == pytest.approx(2 * math.pi / z, rel=1e-12)


@pytest.mark.parametrize("z", [6, 8, 10])
def test_impact_point_from_cartesian_construction(z):
    """Eqs (4)-(6) against an independent construction: C = J + (d/2) n, with the flank
    normal n at angle pi/2 - (delta2 + psi)/2 from J towards the wheel centre."""
    psi = math.radians(35.0)
    g = chain.wheel_geometry(T, D, z, psi)
    R = g.pitch_radius_m
    J = np.array([R, 0.0])  # joint centre; tooth centre line at angle -delta2/2
    theta = math.pi / 2 - (g.delta2_rad + psi) / 2  # angle between JO and JC
    JO = -J / R
    rot = np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
    C = J + D / 2 * rot @ JO  # JO turned by +theta: towards the tooth (negative polar angle)
    assert C[1] < 0
    assert np.hypot(*C) == pytest.approx(g.impact_radius_m, rel=1e-12)
    ang_from_tooth = math.atan2(C[1], C[0]) + g.delta2_rad / 2
    assert ang_from_tooth == pytest.approx(g.alpha2_rad, rel=1e-10)
    assert g.alpha1_rad + g.alpha2_rad == pytest.approx(math.pi / z, rel=1e-12)


@pytest.mark.parametrize("z", [6, 8, 10])
def test_closed_forms_of_impact_speeds(z):
    v1, v2 = chain.impact_speeds(T, D, z, PSI, W)
    np.testing.assert_allclose(v1, W * (T - D) * np.sin(PSI / 2), rtol=1e-12)
    np.testing.assert_allclose(v2, W * (T + D) * np.sin(PSI / 2 + math.pi / z), rtol=1e-12)


@settings(max_examples=60, deadline=None)
@given(t=st.floats(0.02, 0.2), frac=st.floats(0.05, 0.6), z=st.integers(4, 16),
       psi_deg=st.floats(5.0, 90.0))
def test_closed_forms_hold_for_any_chain(t, frac, z, psi_deg):
    d, psi = frac * t, math.radians(psi_deg)
    v1, v2 = chain.impact_speeds(t, d, z, psi, 1.0)
    assert v1 == pytest.approx((t - d) * math.sin(psi / 2), rel=1e-9, abs=1e-14)
    assert v2 == pytest.approx((t + d) * math.sin(psi / 2 + math.pi / z), rel=1e-9, abs=1e-14)
    assert v2 > v1 > 0


def test_energy_balance_eq15_and_sqrt_q():
    v = 0.77
    n = chain.impact_tension(v, 6.6, T, 2.26e7, 2.0)
    assert chain.impact_energy(v, 6.6, T) == pytest.approx(chain.elastic_energy(n, 2.0, 2.26e7))
    assert chain.impact_tension(v, 4 * 6.6, T, 2.26e7, 2.0) == pytest.approx(2 * n)
    # hand value: 0.77 * sqrt(2 * 6.6 * 0.064 * 2.26e7 / 2)
    assert n == pytest.approx(0.77 * math.sqrt(2 * 6.6 * 0.064 * 2.26e7 / 2), rel=1e-12)


def test_trends_of_the_conclusions():
    n2 = {z: chain.impact_tensions(z, PSI)[1] for z in (6, 8, 10)}
    assert np.all(np.diff(n2[10]) > 0)  # rises with psi
    assert np.all(n2[6] > n2[8]) and np.all(n2[8] > n2[10])  # falls with z
    n1 = chain.impact_tensions(8, PSI)[0]
    assert np.all(n2[8] > 2 * n1)  # "several times larger"


def test_records():
    recs = {r.id: r for r in chain.records()}
    assert len(recs) == len(chain.records())
    r = recs["chain.Nu2_min"]
    assert r.paper == 2300 and r.computed == pytest.approx(2378.86, rel=1e-4)
    assert r.status == "differs" and "q/g" in r.note
    assert recs["chain.Nu2_min_z"].status == "reproduced"
    assert recs["chain.Nu2_min_psi"].status == "reproduced"
    ratio = recs["chain.ratio_psi40_z8"]
    assert ratio.computed == pytest.approx(
        (T + D) * math.sin(math.radians(20) + math.pi / 8) / ((T - D) * math.sin(math.radians(20))))
    assert ratio.status == "differs"
    for rec in recs.values():
        assert rec.module == "chain"
        if rec.status == "differs":
            assert rec.note.strip()


@pytest.mark.parametrize("call", [
    lambda: chain.pitch_radius(0.02, 0.02, 8),
    lambda: chain.pitch_radius(-0.064, 0.018, 8),
    lambda: chain.pitch_radius(T, D, 2),
    lambda: chain.pitch_radius(T, D, 7.5),
    lambda: chain.impact_speeds(T, D, 8, 0.0, W),
    lambda: chain.impact_speeds(T, D, 8, math.pi, W),
    lambda: chain.impact_speeds(T, D, 8, float("nan"), W),
    lambda: chain.impact_speeds(T, D, 8, 0.5, -1.0),
    lambda: chain.impact_tension(1.0, 0.0, T, 2.26e7, 2.0),
    lambda: chain.impact_tension(1.0, 6.6, T, 2.26e7, float("inf")),
])
def test_bad_input_raises_parameter_error(call):
    with pytest.raises(ParameterError):
        call()


@pytest.mark.slow
def test_figures(tmp_path):
    paths = chain.figures(tmp_path)
    assert [p.name for p in paths] == ["fig3_Nu2_vs_psi.png", "fig4_Nu1_vs_psi.png"]
    assert all(p.stat().st_size > 10_000 for p in paths)
