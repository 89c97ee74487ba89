"""The gradient method of design to targets (clutchfem.targets.gradient): its model pieces on
closed-form problems, and one short search on a coarse concept-4 mesh against the pattern
search."""

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.targets import Targets, optimize
from clutchfem.targets import gradient as G
from clutchfem.targets import sqp as S


def test_subproblem_solves_a_known_qp():
    # min d0 + d1 + |d|^2 / 2 s.t. 0.5 + d0 >= 0 (no slack needed), box 1: d = (-0.5, -1)
    g, J, c, B = np.array([1.0, 1.0]), np.array([[1.0, 0.0]]), np.array([0.5]), np.eye(2)
    d, lam = S.subproblem(g, J, c, B, np.full(2, -1.0), np.full(2, 1.0), 10.0)
    assert d == pytest.approx([-0.5, -1.0], abs=1e-6)
    assert lam[0] == pytest.approx(0.5, abs=1e-5)  # d0's own gradient 1 - 0.5 (curvature) at the bound


def test_subproblem_walks_to_feasibility_first():
    # violated constraint c = -0.3 with a cheap direction: the l1 term dominates a small objective
    g, J, c = np.array([0.01, 0.0]), np.array([[1.0, 0.0]]), np.array([-0.3])
    d, _ = S.subproblem(g, J, c, np.eye(2) * 1e-3, np.full(2, -0.5), np.full(2, 0.5), 10.0)
    assert d[0] == pytest.approx(0.3, abs=1e-6)


def test_damped_bfgs_stays_positive_definite_and_fits_the_secant():
    rng = np.random.default_rng(0)
    B = np.eye(3)
    for _ in range(20):
        s, y = rng.normal(size=3), rng.normal(size=3)  # y.s often < 0: damping must keep B > 0
        B = S.bfgs(B, s, y)
        assert np.all(np.linalg.eigvalsh(B) > 0)
    A = np.diag([1.0, 4.0, 9.0])  # a quadratic's exact curvature: B s == y after the update
    s = np.array([1.0, 0.5, -0.2])
    assert S.bfgs(np.eye(3), s, A @ s) @ s == pytest.approx(A @ s)


def test_safety_factor_enters_through_its_stress():
    sf = {"key": "safety_factor", "sense": ">=", "limit": 1.5, "value": 0.6, "slack": -0.9}
    assert G.constraint_value(sf, -2.0) == pytest.approx(1 - 1.5 / 0.6)
    eng = {"key": "engagement_rpm_with_ripple", "sense": ">=", "limit": 3510.0, "value": 3600.0, "slack": 90.0}
    assert G.constraint_value(eng, -2.0) == pytest.approx(90.0 / 3510.0)
    miss = {"key": "slip_rpm", "sense": "<=", "limit": 8000.0, "value": None, "slack": -np.inf}
    assert G.constraint_value(miss, -2.0) == -2.0


def test_repair_step_reaches_the_margin_on_the_linear_model():
    c, gc = np.array([-0.002, 0.3]), np.array([[1.0, 0.0], [0.0, 1.0]])
    d = S.repair_step(c, gc, np.array([0.5, 0.5]))
    assert c[0] + d[0] >= S.REPAIR_MARGIN - 1e-9 and abs(d[1]) < 1e-6


@pytest.mark.slow
def test_gradient_search_finds_the_pattern_searchs_optimum_on_one_parameter():
    # one parameter, one binding target: the thinnest shoe whose engagement reaches LO.  The
    # two searches compared as searches (check=False): analyze's check of an optimum, which
    # runs after the search and moves nothing on the fast path, is test_best_check's; LO from
    # the start design's answers as the searches read them (no error step)
    d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    lo = cf.analyze(d, errors=False).engagement_rpm_with_ripple - 250.0
    t = Targets(lo, None, None, None, "mass")
    kw = dict(free=["shoe_thickness"], workers=0, check=False)
    rg = optimize(d, t, method="gradient", max_evals=30, **kw)
    rp = optimize(d, t, method="pattern", sample=0, max_evals=60, **kw)
    print(rg.message, rg.evaluations, rg.best["mass_kg"], rp.best["mass_kg"], rp.evaluations)
    assert rg.feasible and rp.feasible
    assert rg.best["phase"] in ("verify", "repair")  # confirmed on a mesh made from scratch
    # at least as light as the pattern search (which stops at its step, 1/256 of the range),
    # on the binding target, in fewer designs
    assert rg.best["mass_kg"] <= rp.best["mass_kg"] * (1 + 1e-4)
    assert 0.0 <= rg.best["engagement_rpm_with_ripple"] - lo <= 2e-3 * lo
    assert sum(rg.evaluations.values()) < sum(rp.evaluations.values())
    with pytest.raises(cf.ParameterError, match="method"):
        optimize(d, t, method="newton", **kw)


def test_subproblem_without_targets_is_the_trust_box_newton_step():
    # no constraint rows (an optimisation without targets): d = -B^-1 g, clipped to the box
    g, B = np.array([0.2, -4.0]), np.eye(2)
    d, lam = S.subproblem(g, np.zeros((0, 2)), np.zeros(0), B, np.full(2, -1.0), np.full(2, 1.0), 10.0)
    assert d == pytest.approx([-0.2, 1.0], abs=1e-6) and lam.size == 0
