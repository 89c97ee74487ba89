"""Shoe torque model (thesis eqs 1-8, 11, 12) against hand values and independent quadrature."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy import integrate

from clutchfem.clutch import (
    CentrifugalShoe,
    ShoeGeometry,
    lining_integrals,
    shoe_torque,
    simplified_torque,
    torque_factor,
)
from clutchfem.clutch.shoe import apply_force, engagement_speed, quadrature_shoe_torque, torque_from_normal_force
from clutchfem.core import ParameterError

FAST = settings(max_examples=60, deadline=None)


def test_lining_integrals_hand_values():
    # phi1 = 0, phi2 = pi/2: int sin = 1, int sin^2 = pi/4, int sin cos = [sin^2/2] = 1/2.
    I_s, I_ss, I_sc = lining_integrals(0.0, math.pi / 2)
    assert I_s == pytest.approx(1.0, rel=1e-14)
    assert I_ss == pytest.approx(math.pi / 4, rel=1e-14)
    assert I_sc == pytest.approx(0.5, rel=1e-14)


def test_printed_eq4_sign_is_a_typo():
    # The thesis prints I_s = cos(phi2) - cos(phi1); the integral of sin is the opposite.
    phi1, phi2 = math.radians(10), math.radians(120)
    quad, _ = integrate.quad(math.sin, phi1, phi2)
    printed = math.cos(phi2) - math.cos(phi1)
    assert printed < 0 < quad
    assert lining_integrals(phi1, phi2).I_s == pytest.approx(quad, rel=1e-12)


@FAST
@given(
    phi1=st.floats(0.0, math.pi - 0.05),
    span=st.floats(0.02, math.pi),
)
def test_lining_integrals_match_quadrature(phi1, span):
    phi2 = min(phi1 + span, math.pi)
    assume(phi2 - phi1 > 1e-3)
    I = lining_integrals(phi1, phi2)
    assert I.I_s == pytest.approx(integrate.quad(math.sin, phi1, phi2)[0], rel=1e-9, abs=1e-12)
    assert I.I_ss == pytest.approx(integrate.quad(lambda p: math.sin(p) ** 2, phi1, phi2)[0], rel=1e-9, abs=1e-12)
    assert I.I_sc == pytest.approx(
        integrate.quad(lambda p: math.sin(p) * math.cos(p), phi1, phi2)[0], rel=1e-9, abs=1e-12
    )


def test_torque_hand_example():
    # phi 0..90 deg: I_s = 1, I_ss = pi/4, I_sc = 1/2; A/R = 0.5, mu = 0.2, L = 0.05 m, F = 100 N.
    g = ShoeGeometry(0.0, math.pi / 2, A=0.02, R=0.04, L=0.05)
    den_minus = 0.5 * math.pi / 4 + 0.2 * (1.0 - 0.5 * 0.5)  # 0.5427
    den_plus = 0.5 * math.pi / 4 - 0.2 * (1.0 - 0.5 * 0.5)  # 0.2427
    assert shoe_torque(100.0, g, 0.2, "minus").per_shoe == pytest.approx(0.2 * 100 * 0.05 / den_minus, rel=1e-12)
    assert shoe_torque(100.0, g, 0.2, "plus").per_shoe == pytest.approx(0.2 * 100 * 0.05 / den_plus, rel=1e-12)
    tot = shoe_torque(100.0, g, 0.2, "minus", n=3)
    assert tot.total == pytest.approx(3 * tot.per_shoe)  # eq 8


geometries = st.builds(
    lambda p1, span, a_frac, R, L: ShoeGeometry(p1, min(p1 + span, math.pi), a_frac * R, R, L),
    st.floats(0.0, 2.5),
    st.floats(0.1, 2.5),
    st.floats(0.2, 0.95),
    st.floats(0.02, 0.1),
    st.floats(0.005, 0.08),
)


@FAST
@given(g=geometries, mu=st.floats(0.0, 0.6), F=st.floats(1.0, 2000.0), kind=st.sampled_from(["plus", "minus"]))
def test_closed_form_matches_quadrature(g, mu, F, kind):
    fac = torque_factor(g, mu, kind)
    q = quadrature_shoe_torque(F, g, mu, kind, width=0.01)
    assume(abs(fac.denominator) > 1e-6)
    assert q.self_locking == fac.self_locking
    if fac.self_locking:
        assert math.isinf(q.torque) and math.isinf(shoe_torque(F, g, mu, kind).per_shoe)
    else:
        assert fac.k * F == pytest.approx(q.torque, rel=1e-8)
        assert q.p_max > 0


def test_quadrature_moment_balance_and_pressure():
    g = ShoeGeometry(math.radians(20), math.radians(110), 0.031, 0.0344, 0.02)
    for kind in ("plus", "minus"):
        q = quadrature_shoe_torque(400.0, g, 0.165, kind, width=0.012)
        # apply-force moment balances the drum's normal + friction moments about the pivot
        assert q.normal_moment + q.friction_moment == pytest.approx(400.0 * 0.02, rel=1e-10)
        # friction helps the apply force on a plus shoe, opposes it on a minus shoe
        assert (q.friction_moment < 0) == (kind == "plus")


def test_narrow_shoe_limit_and_eq11():
    # A short lining at phi = 90 deg: N A +- mu N R = F L  ->  M = mu F L R / (A +- mu R).
    eps = 1e-3
    A, R, L, mu, F = 0.03, 0.0344, 0.03, 0.165, 250.0
    g = ShoeGeometry(math.pi / 2 - eps, math.pi / 2 + eps, A, R, L)
    assert shoe_torque(F, g, mu, "minus").per_shoe == pytest.approx(mu * F * L * R / (A + mu * R), rel=1e-5)
    assert shoe_torque(F, g, mu, "plus").per_shoe == pytest.approx(mu * F * L * R / (A - mu * R), rel=1e-5)
    # with L = A and mu -> 0 it tends to the point-load eq 11/12: M = mu F R
    tiny = 1e-7
    m7 = shoe_torque(F, g, tiny, "minus").per_shoe
    assert m7 == pytest.approx(tiny * F * R, rel=1e-5)
    assert torque_from_normal_force(F, tiny, R) == pytest.approx(tiny * F * R)


@FAST
@given(g=geometries, mu=st.floats(0.01, 0.6), F=st.floats(1.0, 2000.0))
def test_minus_below_plus(g, mu, F):
    plus = shoe_torque(F, g, mu, "plus")
    minus = shoe_torque(F, g, mu, "minus")
    assert not minus.self_locking  # a minus shoe with A < R never self-locks
    assert minus.per_shoe < plus.per_shoe  # also true when plus is inf


def test_mu_zero_plus_equals_minus_equals_zero():
    g = ShoeGeometry(0.2, 1.8, 0.03, 0.0344, 0.02)
    assert shoe_torque(300.0, g, 0.0, "plus").per_shoe == 0.0 == shoe_torque(300.0, g, 0.0, "minus").per_shoe


def test_self_locking_plus_shoe_flagged_never_negative():
    g = ShoeGeometry(0.0, math.pi, 0.01, 0.0344, 0.02)
    fac = torque_factor(g, 0.5, "plus")
    assert fac.self_locking and fac.denominator <= 0 and math.isinf(fac.k)
    res = shoe_torque(np.array([0.0, 10.0, 100.0]), g, 0.5, "plus")
    assert res.self_locking
    assert res.per_shoe[0] == 0.0 and np.all(np.isinf(res.per_shoe[1:]))
    assert np.all(res.per_shoe >= 0)
    assert quadrature_shoe_torque(10.0, g, 0.5, "plus").self_locking


def _shoe(kind="minus", **kw):
    g = ShoeGeometry(math.radians(15), math.radians(105), 0.03, 0.0344, 0.026)
    args = dict(geometry=g, m=0.025, R_Tp=0.027, F_f=120.0, mu=0.165, n=3, kind=kind)
    args.update(kw)
    return CentrifugalShoe(**args)


def test_engagement_speed_and_apply_force_hand_values():
    assert engagement_speed(100.0, 0.05, 0.02) == pytest.approx(math.sqrt(100.0 / 0.001))
    w = np.array([0.0, 100.0, 400.0])
    F = apply_force(w, 0.05, 0.02, 100.0)
    assert F.tolist() == pytest.approx([0.0, 0.0, 0.05 * 0.02 * 400**2 - 100.0])
    shoe = _shoe()
    w0 = shoe.engagement_speed
    assert shoe.apply_force(w0) == pytest.approx(0.0, abs=1e-9)
    assert float(shoe.torque(0.999 * w0).total) == 0.0
    assert float(shoe.torque(1.01 * w0).total) > 0.0


@FAST
@given(w1=st.floats(0.0, 2000.0), w2=st.floats(0.0, 2000.0), kind=st.sampled_from(["plus", "minus"]))
def test_torque_monotone_in_speed(w1, w2, kind):
    shoe = _shoe(kind)
    lo, hi = sorted((w1, w2))
    t = shoe.torque(np.array([lo, hi])).total
    assert t[0] <= t[1]
    assert np.all(t >= 0)
    if lo > shoe.engagement_speed and hi > lo * (1 + 1e-9):
        assert t[0] < t[1]


def test_vectorised_shapes_and_rpm():
    shoe = _shoe()
    w = np.linspace(0, 1500, 12).reshape(3, 4)
    assert shoe.torque(w).total.shape == (3, 4)
    rpm = np.array([5000.0, 8000.0])
    assert np.allclose(shoe.torque_at_rpm(rpm), shoe.torque(rpm * 2 * np.pi / 60).total)


def test_simplified_eq11_hand_value():
    w = 800.0
    expected = 3 * 0.165 * (0.025 * 0.027 * w**2 - 120.0) * 0.0344
    assert simplified_torque(w, 0.025, 0.027, 120.0, 0.165, 0.0344, 3) == pytest.approx(expected)
    assert simplified_torque(10.0, 0.025, 0.027, 120.0, 0.165, 0.0344, 3) == 0.0


@pytest.mark.parametrize(
    "make, name",
    [
        (lambda: ShoeGeometry(1.0, 0.5, 0.03, 0.0344, 0.02), "phi2"),
        (lambda: ShoeGeometry(-0.1, 1.0, 0.03, 0.0344, 0.02), "phi1"),
        (lambda: ShoeGeometry(0.1, 3.5, 0.03, 0.0344, 0.02), "phi2"),
        (lambda: ShoeGeometry(0.1, 1.0, 0.04, 0.0344, 0.02), "A"),
        (lambda: ShoeGeometry(0.1, 1.0, 0.03, 0.0344, -0.02), "L"),
        (lambda: _shoe(kind="sideways"), "kind"),
        (lambda: _shoe(n=0), "n"),
        (lambda: _shoe(m=0.0), "m"),
        (lambda: _shoe(mu=-0.1), "mu"),
        (lambda: _shoe().torque(-5.0), "omega"),
        (lambda: shoe_torque(-1.0, ShoeGeometry(0.1, 1.0, 0.03, 0.0344, 0.02), 0.2, "minus"), "F"),
    ],
)
def test_bad_input_names_the_parameter(make, name):
    with pytest.raises(ParameterError) as ei:
        make()
    assert ei.value.name == name
    assert name in str(ei.value) and "allowed" in str(ei.value)


def test_arc_torque_is_shoe_torque_per_lining():
    """The vectorised arc_torque equals shoe_torque(...).total lining by lining (plus and
    minus, a self-locking plus lining, F = 0), and refuses a bad angle naming it."""
    from clutchfem.clutch import arc_torque

    rng = np.random.default_rng(3)
    p1 = rng.uniform(0.0, 1.5, 40)
    p2 = p1 + rng.uniform(0.05, 1.6, 40)
    F = rng.uniform(0.0, 300.0, 40)
    F[0] = 0.0
    A, R, L = 0.025, 0.0344, 0.02
    for kind, mu in (("minus", 0.3), ("plus", 0.3), ("plus", 0.9)):
        got = arc_torque(F, p1, p2, A, R, L, mu, kind, 3)
        ref = [shoe_torque(f, ShoeGeometry(a, b, A, R, L), mu, kind, 3).total for f, a, b in zip(F, p1, p2)]
        np.testing.assert_array_equal(got, np.asarray(ref, dtype=float))
    assert np.isinf(arc_torque(F, p1, p2, A, R, L, 0.9, "plus", 3)).any()
    with pytest.raises(ParameterError, match="phi2"):
        arc_torque([1.0, 1.0], [0.1, 0.5], [0.4, 0.5], A, R, L, 0.3, "minus")
