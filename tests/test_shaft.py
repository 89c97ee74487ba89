"""Overhung shaft mechanics (clutchfem.shaft): exact determinant vs FE, limits, closed forms,
root bracketing, input checks."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from clutchfem.clutch import shaft as sh
from clutchfem.core import ParameterError
from clutchfem.validation.shaft import paper_shaft

CASES = [
    paper_shaft(0.34, 0.10, "D500", "diametral"),
    paper_shaft(0.36, 0.30, "D800", "diametral"),
    paper_shaft(0.34, 0.20, "D650", "polar"),
    paper_shaft(0.34, 0.10, "D500", "forward_whirl"),  # negative rotary inertia
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
    shaft = paper_shaft(0.34, 0.2, "D800", "polar")
    b = np.linspace(0.01, 60.0, 4000)
    for model in ("physical", "as_printed"):
        det = sh.frequency_determinant(b, shaft, model)
        assert np.all(np.isfinite(det)) and np.max(np.abs(det)) < 1e3


def test_bracket_roots_rejects_poles():
    grid = np.linspace(1.0, 3.5, 26)  # tan: pole at pi/2, root at pi
    roots = sh.bracket_roots(math.tan, grid)
    assert roots == [pytest.approx(math.pi, abs=1e-12)]


def test_shaft_bad_input():
    with pytest.raises(ParameterError):
        sh.OverhungShaft(0.3, -0.1, 30.0, 1e6)
    with pytest.raises(ParameterError):
        replace(CASES[0], tip_rotary_inertia_kg_m2=float("nan"))
    with pytest.raises(ParameterError):
        sh.frequency_matrix(5.0, CASES[0], "typo")


@pytest.mark.parametrize("shaft", CASES)
def test_fe_bracketed_first_root_is_the_scanned_one(shaft):
    """first_frequency_coefficient (FE eigenvalue -> determinant root in a 1e-4 bracket)
    finds the same first root as the determinant's own scan, to round-off."""
    b, b_fe = sh.first_frequency_coefficient(shaft)
    assert b == pytest.approx(float(sh.frequency_coefficients(shaft, 1)[0]), rel=1e-12)
    assert b_fe == pytest.approx(b, rel=1e-5)


def test_first_root_falls_back_to_the_scan_when_the_fe_bracket_misses(monkeypatch):
    """A wrong FE value (no sign change in its bracket): the scan answers, and the FE value is
    returned as it was, for the caller's agreement check to refuse."""
    shaft = CASES[4]
    monkeypatch.setattr(sh, "fe_frequency_coefficients", lambda *a, **k: np.array([1.3 * 32.0]))
    b, b_fe = sh.first_frequency_coefficient(shaft)
    assert b == pytest.approx(float(sh.frequency_coefficients(shaft, 1)[0]), rel=1e-12)
    assert b_fe == pytest.approx(1.3 * 32.0)
