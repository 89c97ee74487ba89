"""Engine torque curve: default data, interpolation, CSV input, errors, slip crossing."""

from __future__ import annotations

import math

import numpy as np
import pytest

from clutchfem.clutch import EngineCurve, slip_rpm
from clutchfem.clutch.engine import DEFAULT_CURVE_RPM, DEFAULT_CURVE_TORQUE
from clutchfem.core import InputError, ParameterError


def test_default_curve_matches_seed000_anchors():
    c = EngineCurve.default()
    assert c.assumed is True and "ASSUMED" in c.source
    assert c.max_torque == pytest.approx(3.40)  # seed 000: 3.40 N m ...
    assert c.rpm_max_torque == pytest.approx(8000.0)  # ... at ~8000 rpm
    w950_rpm = 950.0 * 60 / (2 * math.pi)
    assert c.torque_at(w950_rpm) == pytest.approx(3.20, abs=0.02)  # M_sil = 3.20 N m at 950 rad/s
    assert c.idle_rpm == 2700.0
    assert c.rpm_range[0] <= 2700.0 and c.rpm_range[1] == pytest.approx(14000.0)


def test_interpolation_through_points_without_overshoot():
    c = EngineCurve.default()
    assert np.allclose(c.torque_at(np.array(c.rpm)), np.array(c.torque))
    dense = c.torque_at(np.linspace(*c.rpm_range, 5001))
    assert dense.max() <= c.max_torque + 1e-12
    assert dense.min() >= min(c.torque) - 1e-12
    # monotone data -> monotone interpolant (PCHIP)
    m = EngineCurve((1000, 2000, 3000, 4000), (1.0, 1.1, 3.0, 3.05))
    y = m.torque_at(np.linspace(1000, 4000, 400))
    assert np.all(np.diff(y) >= -1e-12)


def test_scalar_in_scalar_out():
    c = EngineCurve.default()
    assert isinstance(c.torque_at(8000.0), float)
    assert c(8000.0) == pytest.approx(3.40)


def test_csv_roundtrip(tmp_path):
    p = tmp_path / "eng.csv"
    p.write_text("rpm,torque_Nm\n3000,2.0\n6000,3.5\n9000,3.0\n")
    c = EngineCurve.from_csv(p, idle_rpm=2800)
    assert c.assumed is False and c.idle_rpm == 2800
    assert c.rpm == (3000.0, 6000.0, 9000.0)
    assert c.torque_at(6000) == pytest.approx(3.5)
    assert c.rpm_max_torque == 6000.0


@pytest.mark.parametrize(
    "text, fragment",
    [
        ("rpm,torque\n3000,2\n2000,3\n", "sorted"),
        ("rpm,torque\n3000,2\n3000,3\n", "duplicate"),
        ("rpm,torque\n3000,2\n4000,-1\n", ">= 0"),
        ("rpm,torque\n3000,2\n", "at least 2"),
        ("time,value\n3000,2\n4000,3\n", "speed column .* torque column"),  # speed,moment: read (issue 24)
        ("rpm,torque\n3000,abc\n4000,3\n", "row 2"),
        ("", "empty"),
    ],
)
def test_csv_errors(tmp_path, text, fragment):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    with pytest.raises(InputError, match=fragment):
        EngineCurve.from_csv(p)


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="not found"):
        EngineCurve.from_csv(tmp_path / "nope.csv")


def test_constructor_errors():
    with pytest.raises(InputError, match="2 rpm values but 3"):
        EngineCurve((1000, 2000), (1, 2, 3))
    with pytest.raises(InputError, match="finite"):
        EngineCurve((1000, float("nan")), (1, 2))


def test_query_outside_range_names_rpm_and_range():
    c = EngineCurve.default()
    with pytest.raises(InputError) as ei:
        c.torque_at(np.array([5000.0, 15000.0]))
    msg = str(ei.value)
    assert "15000" in msg and "2500" in msg and "14000" in msg
    with pytest.raises(InputError, match="1000"):
        c.torque_at(1000.0)


def test_slip_rpm_linear_clutch_analytic():
    # engine flat 3 N m; clutch 0.001 N m/rpm above 1000 rpm -> crossing at 4000 rpm
    c = EngineCurve((1000.0, 10000.0), (3.0, 3.0))
    s = slip_rpm(c, lambda r: np.maximum(0.001 * (np.asarray(r) - 1000.0), 0.0))
    assert s == pytest.approx(4000.0, abs=1e-6)


def test_slip_rpm_none_and_self_locking():
    c = EngineCurve.default()
    assert slip_rpm(c, lambda r: np.zeros_like(np.asarray(r, dtype=float))) is None
    # a self-locking clutch (inf above engagement at 4000 rpm) "slips" at engagement
    s = slip_rpm(c, lambda r: np.where(np.asarray(r) > 4000.0, np.inf, 0.0))
    assert s == pytest.approx(4000.0, abs=1e-3)


# --- issue 12: curves the model would misread are refused, naming why ----------------------
def test_all_zero_curve_is_refused():
    with pytest.raises(InputError, match="every torque value is 0"):
        EngineCurve((2000.0, 8000.0), (0.0, 0.0))


def test_curve_in_rad_per_s_is_refused():
    rad = tuple(r * 2 * np.pi / 60 for r in DEFAULT_CURVE_RPM)
    with pytest.raises(InputError, match="rad/s") as ei:
        EngineCurve(rad, DEFAULT_CURVE_TORQUE)
    assert "14000 rpm" in str(ei.value)  # says what the table would be in rpm


def test_idle_above_the_curve_is_refused():
    with pytest.raises(ParameterError, match="idle_rpm"):
        EngineCurve((2000.0, 3000.0), (1.0, 2.0), idle_rpm=2700.0 * 2)


@pytest.mark.parametrize("payload", [bytes(range(256)) * 4, b"rpm,torque\n3000,2\x00\n4000,3\n",
                                     b"PK\x03\x04\x14\x00\x06\x00"])
def test_binary_csv_is_refused(tmp_path, payload):
    f = tmp_path / "engine.csv"
    f.write_bytes(payload)
    with pytest.raises(InputError, match="engine curve file"):
        EngineCurve.from_csv(f)


def test_folder_as_csv_is_refused(tmp_path):
    with pytest.raises(InputError, match="not a file"):
        EngineCurve.from_csv(tmp_path)


def _counting(f):
    calls = []

    def g(r):
        r = np.atleast_1d(np.asarray(r, dtype=float))
        calls.extend(r.tolist())
        return f(r)

    return g, calls


@pytest.mark.parametrize("clutch", [
    lambda r: np.maximum(0.001 * (r - 1000.0), 0.0),  # one crossing
    lambda r: np.zeros_like(r),  # never holds
    lambda r: np.full_like(r, 50.0),  # holds at the start
    lambda r: np.where(r > 4000.0, np.inf, 0.0),  # self-locking: bisection
    lambda r: 1.0 + 3.0 * np.sin((r - 2500.0) / 900.0) ** 2,  # several up and down crossings
    lambda r: np.where(r > 6000.0, 3.0 + 1e-3 * (r - 6000.0), 0.0),  # a jump through the curve
])
def test_first_slip_rpm_equals_slip_rpm_and_stops_at_the_answer(clutch):
    """The early-stopping walk gives slip_rpm's answer on the same grid, and evaluates the
    clutch torque at no grid speed above the bracket of the first upward crossing."""
    from clutchfem.clutch import first_slip_rpm

    c = EngineCurve.default()
    grid = np.arange(c.rpm_range[0], c.rpm_range[1], 250.0)
    f, calls = _counting(clutch)
    s = first_slip_rpm(c, f, grid)
    assert s == slip_rpm(c, clutch, grid=grid)
    if s is not None:
        above = np.union1d(grid, c.rpm_range)
        above = above[above > s]
        assert max(calls) <= above[0]  # nothing past the bracket of the answer


def test_the_curves_pchip_is_scipys():
    """The engine curve's interpolant (numpy, for the start-up of a live answer) has scipy's
    PCHIP slopes and pieces: 2 to 11 points, flat runs, peaks and valleys, at and between the
    points (round-off only)."""
    from scipy.interpolate import PchipInterpolator

    from clutchfem.clutch.engine import Pchip

    rng = np.random.default_rng(0)
    for trial in range(500):
        n = int(rng.integers(2, 12))
        x = np.sort(rng.choice(np.arange(1000.0, 15000.0, 50.0), n, replace=False))
        y = 4 * rng.random(n)
        if trial % 3 == 0:
            y[rng.integers(0, n, n // 2)] = y[0]  # flat runs
        q = np.concatenate([np.linspace(x[0], x[-1], 97), x])
        want = PchipInterpolator(x, y, extrapolate=False)(q)
        np.testing.assert_allclose(Pchip(x, y)(q), want, rtol=0, atol=1e-13 * y.max(), err_msg=f"{x}, {y}")
    e = EngineCurve.default()
    q = np.linspace(*e.rpm_range, 1001)
    np.testing.assert_allclose(e.torque_at(q), PchipInterpolator(e.rpm, e.torque)(q), rtol=1e-14)
