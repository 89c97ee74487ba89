"""The smoothed contact law (:func:`clutchfem.contact.smooth_lcp`): it tends to the exact
LCP as its gap scale shrinks, it is smooth where the exact solution has a kink, and the
operating option refuses what it cannot stand for."""

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.contact import lcp_residual, smooth_lcp, solve_lcp
from clutchfem.core import ParameterError


def _problem(t):
    """A 3-node contact state: node 0 pressed, node 1 touching at t = 0, node 2 open; the
    exact solution kinks at t = 0 (node 1 enters)."""
    G = 1e-7 * np.array([[2.0, 0.6, 0.2], [0.6, 2.0, 0.6], [0.2, 0.6, 2.0]])  # m/N
    q = np.array([-5e-6, -1.5e-6 - 1e-6 * t, 3e-6])  # node 0 alone opens node 1 by 1.5 um
    return G, q


def test_smooth_tends_to_exact_linearly_in_delta():
    # at the kink (node 1 just touching) the force error is linear in delta ...
    G, q = _problem(0.0)
    lam0, _ = solve_lcp(G, q)
    errs = [np.max(np.abs(smooth_lcp(G, q, lam0, d)[0] - lam0)) for d in (1e-8, 1e-9, 1e-10)]
    assert errs[0] < 0.05 and all(9 < a / b < 11 for a, b in zip(errs, errs[1:]))
    # ... away from it (node 1 pressed with 5.5 N, 11 force scales) it is exponentially small
    G, q = _problem(1.0)
    lam0, _ = solve_lcp(G, q)
    lam, closed = smooth_lcp(G, q, lam0, 1e-7)
    assert np.array_equal(closed, lam0 > 0) and np.max(np.abs(lam - lam0)) < 1e-5 * np.max(lam0)
    assert lcp_residual(G, q, smooth_lcp(G, q, lam0, 1e-10)[0]) < 1e-9


def test_smooth_has_no_kink_where_exact_has_one():
    def total(t, delta):
        G, q = _problem(t)
        lam0, _ = solve_lcp(G, q)
        return (smooth_lcp(G, q, lam0, delta)[0] if delta else lam0).sum()

    def slope_jump(delta, h=1e-3):
        left = (total(0.0, delta) - total(-h, delta)) / h
        right = (total(h, delta) - total(0.0, delta)) / h
        return abs(right - left) / abs(right)

    # the exact law kinks when node 1 enters: the one-sided slopes differ whatever the step
    assert slope_jump(0.0, 1e-3) > 0.5 and slope_jump(0.0, 1e-2) > 0.5
    # the smoothed one is C1: their difference is curvature, shrinking with the step
    j3, j2 = slope_jump(2e-7, 1e-3), slope_jump(2e-7, 1e-2)
    assert j3 < 0.01 and 0.08 < j3 / j2 < 0.12


def test_operating_option_refuses_out_of_range():
    with pytest.raises(ParameterError, match="contact_smoothing"):
        cf.OperatingPoint(contact_smoothing="1mm")
    assert cf.OperatingPoint(contact_smoothing="0.5um").contact_smoothing == pytest.approx(5e-7)


@pytest.mark.slow
def test_analyze_with_smoothing_moves_answers_by_its_measured_bias():
    ms = cf.MeshSettings(size="3mm")
    a0 = cf.analyze(cf.Design.from_concept("concept4", mesh=ms))
    a1 = cf.analyze(cf.Design.from_concept("concept4", mesh=ms, contact_smoothing="1um"))
    assert a1.engagement_rpm == a0.engagement_rpm  # no contact before engagement
    # 1 um on concept 4 (BENCHMARKS, derivative smoothness): slip and torque move by < 1e-4
    assert abs(a1.slip_rpm / a0.slip_rpm - 1) < 1e-4
    assert 0 < abs(a1.torque_at_max_engine_torque_Nm / a0.torque_at_max_engine_torque_Nm - 1) < 1e-4
