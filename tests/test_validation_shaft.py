"""Shaft with an overhung disc (seed 004): exact determinant vs FE, limits, paper tables, whirl."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from clutchfem.errors import ParameterError
from clutchfem.validation import shaft as sh


@pytest.fixture(scope="module")
def records():
    return {r.id: r for r in sh.records()}


CASES = [
    sh.paper_shaft(0.34, 0.10, "D500", "diametral"),
    sh.paper_shaft(0.36, 0.30, "D800", "diametral"),
    sh.paper_shaft(0.34, 0.20, "D650", "polar"),
    sh.paper_shaft(0.34, 0.10, "D500", "forward_whirl"),  # negative rotary inertia
    sh.OverhungShaft(0.05, 0.03, 1.04, 294.0, 0.15, 1.0e-4),  # chainsaw-like
    sh.OverhungShaft(1.0, 0.4, 2.0, 50.0),  # bare shaft
]


@pytest.mark.parametrize("shaft", CASES)
def test_fe_agrees_with_determinant_1e5(shaft):
    exact = sh.frequency_coefficients(shaft, 2)
    fe = sh.fe_frequency_coefficients(shaft, 2)
    np.testing.assert_allclose(fe, exact, rtol=1e-5)


def test_fe_converges_at_fourth_order():
    shaft = CASES[0]
    exact = sh.frequency_coefficients(shaft, 2)
    e1 = np.abs(sh.fe_frequency_coefficients(shaft, 2, 8, richardson=False) - exact)
    e2 = np.abs(sh.fe_frequency_coefficients(shaft, 2, 16, richardson=False) - exact)
    assert np.all(e2 < e1)
    rate = np.log2(e1 / e2)
    assert np.all(rate > 3.5) and np.all(rate < 4.6)


def test_simply_supported_limit():
    """l2 -> 0: the disc sits on the bearing, the span is simply supported: beta l1 = pi, 2 pi."""
    for mass in (0.0, 5.0):
        shaft = sh.OverhungShaft(1.0, 1e-4, 1.0, 1.0, mass, 0.0)
        b = sh.frequency_coefficients(shaft, 2)
        np.testing.assert_allclose(b * 1.0, [math.pi, 2 * math.pi], rtol=2e-6)


def test_cantilever_limit():
    """l1 -> 0: two pins at the root act as a clamp: beta l2 = 1.87510, 4.69409."""
    shaft = sh.OverhungShaft(1e-4, 1.0, 1.0, 1.0)
    np.testing.assert_allclose(sh.frequency_coefficients(shaft, 2), [1.875104, 4.694091],
                               rtol=1e-4)


def test_cantilever_with_tip_mass_closed_form():
    """Sign of the tip inertia force: cantilever with tip mass, r = M/(mu L):
    1 + cos cosh + r bL (cos sinh - sin cosh) = 0."""
    ratio = 0.5
    shaft = sh.OverhungShaft(1e-5, 1.0, 1.0, 1.0, ratio, 0.0)
    bl = sh.frequency_coefficients(shaft, 1)[0]

    def eq(x):
        return (1 + math.cos(x) * math.cosh(x)
                + ratio * x * (math.cos(x) * math.sinh(x) - math.sin(x) * math.cosh(x)))

    exact = brentq(eq, 1.0, 1.8)
    assert exact == pytest.approx(1.4200, abs=1e-4)  # classical table value, M/(mu L) = 0.5
    assert bl == pytest.approx(exact, rel=1e-4)  # l1 = 1e-5 approximates the clamp


def test_massless_shaft_limit_is_the_static_spring():
    """mu -> 0: omega^2 = k/M with the overhang tip stiffness k = 3 EI / (a^2 (l + a))."""
    EI, l, a, M = 100.0, 0.5, 0.2, 3.0
    shaft = sh.OverhungShaft(l, a, 1e-8, EI, M, 0.0)
    w = float(shaft.omega(sh.frequency_coefficients(shaft, 1)[0]))
    assert w == pytest.approx(math.sqrt(3 * EI / (M * a * a * (l + a))), rel=1e-6)


def test_determinant_is_bounded_and_pole_free():
    shaft = sh.paper_shaft(0.34, 0.2, "D800", "polar")
    b = np.linspace(0.01, 60.0, 4000)
    for model in ("physical", "as_printed"):
        det = sh.frequency_determinant(b, shaft, model)
        assert np.all(np.isfinite(det)) and np.max(np.abs(det)) < 1e3


def test_bracket_roots_rejects_poles():
    grid = np.linspace(1.0, 3.5, 26)  # tan: pole at pi/2, root at pi
    roots = sh.bracket_roots(math.tan, grid)
    assert roots == [pytest.approx(math.pi, abs=1e-12)]


def test_beta_does_not_depend_on_EI_but_omega_does():
    a = sh.paper_shaft(0.34, 0.1, "D500", "diametral", "diametral")
    b = sh.paper_shaft(0.34, 0.1, "D500", "diametral", "polar")
    assert b.bending_stiffness_N_m2 == pytest.approx(2 * a.bending_stiffness_N_m2)
    ba, bb = sh.frequency_coefficients(a, 2), sh.frequency_coefficients(b, 2)
    np.testing.assert_allclose(ba, bb, rtol=1e-12)
    assert float(b.omega(bb[0]) / a.omega(ba[0])) == pytest.approx(math.sqrt(2))


def test_paper_data_consistency():
    assert sh.TABLE2["D500"] == tuple(p[0] for p in sh.TABLE1[0.34])
    for disc in sh.DISCS.values():  # I = M D^2 / 8: the printed I is the polar moment
        assert disc.polar_inertia_kg_m2 == pytest.approx(disc.mass_kg * disc.diameter_m**2 / 8,
                                                         rel=0.01)


def test_as_printed_system_reproduces_table2_exactly():
    for disc in ("D650", "D800"):
        got = [sh.paper_betas(0.34, l2, disc, 1)[0] for l2 in sh.L2_GRID]
        np.testing.assert_allclose(got, sh.TABLE2[disc], atol=0.0061)


def test_physical_readings_do_not_reproduce_the_paper():
    """Each single correction of the printed system misses Table 1's first row (5.66, 9.84)."""
    paper = np.array(sh.TABLE1[0.34][0])
    for inertia in ("polar", "diametral", "none", "forward_whirl"):
        b = sh.physical_betas(0.34, 0.10, "D500", inertia=inertia)
        assert np.max(np.abs(b - paper)) > 0.1


def test_jump_is_the_lost_root_of_the_printed_system():
    l2 = sh.lost_root_overhang(0.34)
    assert 0.19 < l2 < 0.196
    # just past it the printed system's first root is Table 1's beta_1 at 0.20 continued
    assert sh.paper_betas(0.34, 0.20, "D500")[0] == pytest.approx(6.59, abs=0.1)
    # the physical model has no jump: beta_1 falls smoothly with l2
    b = [sh.physical_betas(0.34, x, "D500", 1)[0] for x in sh.L2_GRID]
    assert np.all(np.diff(b) < 0)


def test_records(records):
    assert records["shaft.beta1.l1_0.34.l2_0.10.D500"].status == "reproduced"
    assert records["shaft.beta2.l1_0.36.l2_0.30.D500"].paper == 8.74
    assert records["shaft.beta1.l1_0.34.l2_0.30.D800"].computed == pytest.approx(3.21, abs=0.005)
    table = [r for k, r in records.items() if k.startswith(("shaft.beta1.", "shaft.beta2."))]
    assert len(table) == 66
    # half a unit of the printed beta: 31 of 66 cells; every cell within 1.5 % (the rest is
    # printed-input rounding near the lost root, stated in each note)
    assert sum(r.status == "reproduced" for r in table) >= 30
    assert max(abs(r.rel_diff) for r in table) < 0.016
    assert all(r.status == "differs" for k, r in records.items() if k.startswith("shaft.physical."))
    for r in records.values():
        assert r.module == "shaft"
        if r.status == "differs":
            assert r.note.strip()
        if r.paper is not None:
            assert 0 < r.tol < 0.05


def test_crankshaft_whirl_defaults_and_gyroscopic_effect():
    gyro = sh.crankshaft_whirl()
    plain = sh.crankshaft_whirl(include_gyroscopic=False)
    assert gyro.effective_rotary_inertia_kg_m2 < 0 < plain.effective_rotary_inertia_kg_m2
    assert gyro.rpm_crit > plain.rpm_crit > sh.CHAINSAW_ASSUMED.max_rpm
    assert gyro.margin == pytest.approx(gyro.rpm_crit / gyro.max_rpm - 1)
    assert gyro.fe_rpm_crit == pytest.approx(gyro.rpm_crit, rel=1e-5)
    assert gyro.omega_crit_rad_s == pytest.approx(gyro.rpm_crit * 2 * math.pi / 60)
    assert "rpm" in gyro.summary()
    # heavier clutch, longer overhang: lower critical speed
    heavy = sh.crankshaft_whirl(0.4, 4e-4, 3e-4, overhang_m=0.06)
    assert heavy.rpm_crit < gyro.rpm_crit


@pytest.mark.parametrize("kwargs", [
    {"clutch_mass_kg": -0.1},
    {"clutch_mass_kg": float("nan")},
    {"clutch_polar_inertia_kg_m2": -1e-4},
    {"clutch_polar_inertia_kg_m2": 5e-4, "clutch_diametral_inertia_kg_m2": 1e-4},  # I_p > 2 I_d
    {"shaft_diameter_m": 0.0},
    {"bearing_span_m": float("inf")},
    {"overhang_m": -0.03},
    {"E": 0.0},
    {"rho": -7850.0},
    {"max_rpm": 0.0},
])
def test_whirl_bad_input(kwargs):
    with pytest.raises(ParameterError):
        sh.crankshaft_whirl(**kwargs)


def test_shaft_bad_input():
    with pytest.raises(ParameterError):
        sh.OverhungShaft(0.3, -0.1, 30.0, 1e6)
    with pytest.raises(ParameterError):
        replace(CASES[0], tip_rotary_inertia_kg_m2=float("nan"))
    with pytest.raises(ParameterError):
        sh.frequency_matrix(5.0, CASES[0], "typo")
    with pytest.raises(ParameterError):
        sh.paper_shaft(0.34, 0.1, "D900")


def test_figures(tmp_path):
    paths = sh.figures(tmp_path)
    assert [p.name for p in paths] == ["fig2_beta_vs_l2.png", "fig3_omega1_vs_l2.png"]
    assert all(p.stat().st_size > 10_000 for p in paths)
