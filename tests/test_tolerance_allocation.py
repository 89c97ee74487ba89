"""Tolerance allocation for a yield target (issue 21): the closed forms of the linearised
algebra, the reciprocal-cost optimum against an independent solver, the refusal when the
model-error band eats the margin, the FE allocation against robust.spreads, and the CLI."""

import json
import math
from statistics import NormalDist

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.core import ParameterError
from clutchfem.evaluation import EvalSettings
from clutchfem.targets import Targets
from clutchfem.tolerances import allocate_linear, joint_yield
from clutchfem.tolerances.robust import spreads
from support.cli import cli_in_process

PHI = NormalDist()
#: concept 4's robust design (BENCHMARKS.md section 18)
ROB = ("hub_radius=11.84mm", "shoe_arc=97.6deg", "shoe_thickness=6.5mm", "flexure_length=18.44mm",
       "flexure_thickness=1.75mm", "flexure_taper=1.3", "flexure_angle=34.6deg", "fillet_radius=3.55mm",
       "clearance=0.231mm")


def one(slack, grad, sigma_model=0.0, key="e"):
    return {"name": f"target {key}", "key": key, "slack": slack, "grad": grad, "sigma_model": sigma_model}


@pytest.mark.parametrize("dist,k", [("normal", 3.0), ("uniform", math.sqrt(3.0))])
def test_one_dimension_one_target_closed_form(dist, k):
    """t = k slack / (z |dA/dx|): the half-width whose z sigma is the slack exactly."""
    g, s, t0, y = -3.1e6, 150.0, 4e-5, 0.99       # rpm/m, rpm, m
    a = allocate_linear([one(s, {"t": g})], {"t": t0}, yield_target=y, dist=dist, units={"t": "m"})
    z = PHI.inv_cdf(y)                           # one target: no Bonferroni share
    assert a["z"] == pytest.approx(z, rel=1e-12)
    want = k * s / (z * abs(g))
    d = a["dims"][0]
    assert d["allocated"] == pytest.approx(want, rel=1e-9)
    assert d["alone"] == pytest.approx(want, rel=1e-9)          # no other dimension: the same
    assert a["scale"] * t0 == pytest.approx(want, rel=1e-12)
    assert d["binds"] == "target e" and a["scale_binds"] == "target e"
    assert d["share"] == pytest.approx(1.0)
    assert a["feasible"] and ("MISS" in a["message"]) == (want < t0)
    # the predicted yield at the given width: Phi(slack / sigma)
    assert a["predicted_yield"] == pytest.approx(PHI.cdf(s / (abs(g) * t0 / k)), rel=1e-12)


def test_a_dimension_no_target_depends_on_is_unlimited():
    a = allocate_linear([one(100.0, {"t": 1e6, "u": 0.0})], {"t": 1e-5, "u": 1e-5}, yield_target=0.9)
    d = {x["name"]: x for x in a["dims"]}
    assert d["u"]["unlimited"] and d["u"]["allocated"] == math.inf and d["u"]["binds"] is None
    assert not d["t"]["unlimited"] and d["t"]["allocated"] == pytest.approx(3 * 100.0 / (a["z"] * 1e6))


def test_bonferroni_shares_the_yield():
    cons = [one(100.0, {"t": 1e6}, key="a"), one(100.0, {"t": 2e6}, key="b")]
    a = allocate_linear(cons, {"t": 1e-5}, yield_target=0.99)
    assert a["z"] == pytest.approx(PHI.inv_cdf(1 - 0.01 / 2))
    assert a["dims"][0]["binds"] == "target b"     # the steeper answer binds
    assert a["dims"][0]["allocated"] == pytest.approx(3 * 100.0 / (a["z"] * 2e6), rel=1e-9)


def test_reciprocal_cost_one_target_closed_form():
    """One target, several dimensions: t_i proportional to (w_i t0_i / a_i)^(1/3) on the
    target's boundary (the classical reciprocal-cost, root-sum-square allocation)."""
    grads = {"x": 2e6, "y": -8e6, "z": 0.5e6}
    t0 = {"x": 5e-5, "y": 2e-5, "z": 1e-4}
    w = {"x": 1.0, "y": 2.0, "z": 0.5}
    s, sm = 200.0, 30.0
    a = allocate_linear([one(s, grads, sm)], t0, yield_target=0.95, cost=w)
    z = a["z"]
    B = (s / z) ** 2 - sm ** 2
    ai = {n: (g / 3) ** 2 for n, g in grads.items()}
    shape = {n: (w[n] * t0[n] / ai[n]) ** (1 / 3) for n in grads}
    c = math.sqrt(B / sum(ai[n] * shape[n] ** 2 for n in grads))
    for d in a["dims"]:
        assert d["allocated"] == pytest.approx(c * shape[d["name"]], rel=1e-5), d
        assert d["binds"] == "target e"
    used = sum(ai[d["name"]] * d["allocated"] ** 2 for d in a["dims"])
    assert used <= B * (1 + 1e-9) and used >= B * (1 - 1e-6)        # on the boundary, never outside


@pytest.mark.filterwarnings("ignore:delta_grad == 0.0")   # the reference solver's quasi-Newton update
def test_reciprocal_cost_two_targets_against_an_independent_solver():
    """Two targets, three dimensions: the same optimum as trust-constr on the widths
    themselves; each dimension bound by the target that pulls it."""
    from scipy.optimize import NonlinearConstraint, minimize

    cons = [one(120.0, {"p": 3e6, "q": 1e6, "r": 0.0}, 20.0, key="a"),
            one(80.0, {"p": 0.2e6, "q": 0.1e6, "r": 4e6}, 10.0, key="b")]
    t0 = {"p": 5e-5, "q": 5e-5, "r": 2e-5}
    a = allocate_linear(cons, t0, yield_target=0.99)
    z = a["z"]
    A = np.array([[(c["grad"][n] / 3) ** 2 for n in t0] for c in cons])
    B = np.array([(c["slack"] / z) ** 2 - c["sigma_model"] ** 2 for c in cons])
    x0 = np.array(list(t0.values()))
    Q = A * x0 ** 2 / B[:, None]                  # in r = t / t0: sum 1/r s.t. Q r^2 <= 1
    ref = minimize(lambda r: float(np.sum(1 / r)), np.full(3, a["scale"]), method="trust-constr",
                   constraints=[NonlinearConstraint(lambda r: Q @ r ** 2, -np.inf, 1.0)],
                   bounds=[(1e-3, 1e3)] * 3, options={"xtol": 1e-12, "gtol": 1e-10, "maxiter": 5000})
    got = np.array([d["allocated"] for d in a["dims"]])
    assert np.all(A @ got ** 2 <= B * (1 + 1e-9))
    assert float(np.sum(x0 / got)) <= float(np.sum(1 / ref.x)) * (1 + 1e-6)
    assert got / x0 == pytest.approx(ref.x, rel=1e-3)
    binds = {d["name"]: d["binds"] for d in a["dims"]}
    assert binds == {"p": "target a", "q": "target a", "r": "target b"}
    # at the given widths, the scale is the tightest target's
    lam = np.sqrt(B / (A @ x0 ** 2))
    assert a["scale"] == pytest.approx(lam.min())


def test_optimal_split_and_a_start_on_the_boundary():
    """Two targets, one far from its limit: the reciprocal-cost optimum holds the closed form
    of its one active target (t_u / t_t = (a_t / a_u)^(1/3)) although SLSQP starts on the
    boundary; the optimal split of the failure budget (Boole) gives the far target's share
    to the near one: at its widths the joint yield is Y itself, and they cost less."""
    cons = [{**one(150.0, {"t": 3e6, "u": 1e6}, 20.0, key="a"), "sense": ">="},
            {**one(500.0, {"t": 1e6, "u": 1e6}, 10.0, key="b"), "sense": "<="}]
    t0 = {"t": 4e-5, "u": 4e-5}
    a = allocate_linear(cons, t0, yield_target=0.99)
    d = {x["name"]: x for x in a["dims"]}
    assert d["u"]["allocated"] / d["t"]["allocated"] == pytest.approx((9.0) ** (1 / 3), rel=1e-5)
    assert d["t"]["binds"] == d["u"]["binds"] == "target a"
    union = {n: d[n]["allocated_union"] for n in t0}
    assert joint_yield(cons, union) == pytest.approx(0.99, abs=1e-4)
    assert a["allocated_yield"] > 0.994                            # Bonferroni: conservative
    assert sum(t0[n] / union[n] for n in t0) < sum(t0[n] / d[n]["allocated"] for n in t0)
    assert a["scale_union"] == pytest.approx(a["scale_joint"], rel=1e-4) and a["scale_union"] > a["scale"]
    single = allocate_linear(cons[:1], t0, yield_target=0.99)     # one target: the two splits agree
    for x in single["dims"]:
        assert x["allocated_union"] == pytest.approx(x["allocated"], rel=1e-5)


def test_the_model_band_alone_eats_the_margin():
    """z sigma_model >= slack: no width meets the yield; said, with no (negative) width."""
    z = PHI.inv_cdf(0.99)
    s = 100.0
    ok = allocate_linear([one(s, {"t": 1e6}, sigma_model=0.95 * s / z)], {"t": 1e-5}, yield_target=0.99)
    assert ok["feasible"] and ok["dims"][0]["allocated"] > 0
    bad = allocate_linear([one(s, {"t": 1e6}, sigma_model=1.05 * s / z)], {"t": 1e-5}, yield_target=0.99)
    assert not bad["feasible"]
    assert "NO TOLERANCE MEETS" in bad["message"] and "model-error band alone" in bad["message"]
    assert all(d["allocated"] is None and d["alone"] is None for d in bad["dims"])
    assert bad["perfect_part_yield"] == pytest.approx(PHI.cdf(s / (1.05 * s / z)))
    outside = allocate_linear([one(-5.0, {"t": 1e6})], {"t": 1e-5}, yield_target=0.9)
    assert not outside["feasible"] and "outside this limit" in outside["message"]
    # the other given widths alone already miss: that dimension gets no width, not a negative one
    two = allocate_linear([one(100.0, {"a": 1e6, "b": 50e6})], {"a": 1e-5, "b": 1e-5}, yield_target=0.99)
    d = {x["name"]: x for x in two["dims"]}
    assert d["a"]["alone"] is None and "already miss" in d["a"]["alone_note"]
    assert d["a"]["allocated"] > 0 and d["b"]["allocated"] > 0


def test_joint_yield_counts_the_correlation():
    """The joint normal of the linearised answers: one target gives Phi(s / sigma); two
    limits on one answer (a window) give Phi(s1/sigma) + Phi(s2/sigma) - 1 exactly (a part
    misses one or the other, never both), not the product; answers of independent
    dimensions give the product."""
    g, t = 2e6, 3e-5                               # rpm/m, m: sigma = g t / 3 = 20 rpm
    sig = g * t / 3
    lo = {**one(15.0, {"t": g}, key="lo"), "sense": ">="}
    hi = {**one(10.0, {"t": g}, key="hi"), "sense": "<="}
    assert joint_yield([lo], {"t": t}) == pytest.approx(PHI.cdf(15 / sig), rel=1e-12)
    window = PHI.cdf(15 / sig) + PHI.cdf(10 / sig) - 1
    assert joint_yield([lo, hi], {"t": t}) == pytest.approx(window, abs=2e-4)
    assert abs(window - PHI.cdf(15 / sig) * PHI.cdf(10 / sig)) > 0.05        # the product is wrong here
    a = {**one(30.0, {"t": g, "u": 0.0}, key="a"), "sense": ">="}
    b = {**one(20.0, {"t": 0.0, "u": g}, key="b"), "sense": "<="}
    assert joint_yield([a, b], {"t": t, "u": t}) == pytest.approx(PHI.cdf(30 / sig) * PHI.cdf(20 / sig), abs=2e-4)
    # the allocation's widths hold the yield (Bonferroni: at least Y, here with two targets)
    r = allocate_linear([lo, hi], {"t": t}, yield_target=0.95)
    assert r["allocated_yield"] >= 0.95 - 2e-4 and r["predicted_yield"] == pytest.approx(window, abs=2e-4)
    # the exact (joint) scale gives the yield, and is wider than the Bonferroni one
    lam = r["scale_joint"]
    assert joint_yield([lo, hi], {"t": lam * t}) == pytest.approx(0.95, abs=2e-4)
    assert lam > r["scale"]
    one_target = allocate_linear([lo], {"t": t}, yield_target=0.95)   # one target: Bonferroni is exact
    assert one_target["scale_joint"] == pytest.approx(one_target["scale"], rel=1e-5)


def test_refusals():
    c = [one(100.0, {"t": 1e6})]
    for bad in (0.5, 1.0, 1.2, "0.9"):
        with pytest.raises(ParameterError, match="yield"):
            allocate_linear(c, {"t": 1e-5}, yield_target=bad)
    with pytest.raises(ParameterError, match="dist"):
        allocate_linear(c, {"t": 1e-5}, yield_target=0.9, dist="triangular")
    with pytest.raises(ParameterError, match="t"):
        allocate_linear(c, {"t": -1e-5}, yield_target=0.9)
    with pytest.raises(ParameterError, match="cost"):
        allocate_linear(c, {"t": 1e-5}, yield_target=0.9, cost={"t": 0.0})


def test_api_refuses_before_any_fe_work():
    es = EvalSettings("concept4", mesh_size=3e-3)
    for tols, word in (({}, "tolerances"), ({"clearance": True}, "clearance"), ({"nope": "0.02mm"}, "nope"),
                       ({"clearance": "0mm"}, "clearance"), ({"clearance": "0.02kg"}, "clearance")):
        with pytest.raises(ParameterError, match=word):
            cf.allocate_tolerances(es, tols, workers=0)
    with pytest.raises(ParameterError, match="yield"):
        cf.allocate_tolerances(es, {"clearance": "0.02mm"}, yield_target=1.5, workers=0)
    with pytest.raises(ParameterError, match="cost"):
        cf.allocate_tolerances(es, {"clearance": "0.02mm"}, cost={"hub_radius": 1.0}, workers=0)
    with pytest.raises(ParameterError, match="yield"):
        cf.yield_front([es], {"clearance": "0.02mm"}, yields=(0.9, 1.0), workers=0)
    with pytest.raises(ParameterError, match="yields"):
        cf.yield_front([es], {"clearance": "0.02mm"}, yields=0.9, workers=0)
    with pytest.raises(ParameterError, match="designs"):
        cf.yield_front([], {"clearance": "0.02mm"}, workers=0)


@pytest.fixture(scope="module")
def coarse():
    return EvalSettings("concept4", mesh_size=3e-3)


@pytest.mark.slow
def test_fe_allocation_meets_the_spread_of_robust_design(coarse):
    """One dimension, one target on the FE model: the allocated half-width is 3 slack /
    (z |dA/dx|), and robust.spreads (its own code path) at that width gives z sigma = slack."""
    tg = Targets(3510.0, None, None, None)
    a = cf.allocate_tolerances(coarse, {"clearance": "0.02mm"}, yield_target=0.99, model_error=False, targets=tg,
                               workers=0)
    assert a.feasible and a.methods["clearance"] == "central, morphed"
    c = a.constraints[0]
    g = a.derivatives["clearance"]["engagement_rpm_with_ripple"]
    z = PHI.inv_cdf(0.99)
    t = a.allocated["clearance"]
    assert t == pytest.approx(3 * c["slack"] / (z * abs(g)), rel=1e-9)
    sig, base = spreads(coarse, tg, {"clearance": t}, "normal", False, workers=0)
    assert z * sig["engagement_rpm_with_ripple"] == pytest.approx(c["slack"], rel=1e-6)
    # 3 mm mesh: the engagement is well above 3510 rpm, so the clearance may widen
    assert t > 2e-5 and a.dims[0]["ratio"] > 1
    # a target 1 rpm below the nominal: the model-error band eats it -- refused, no width
    tight = Targets(base["engagement_rpm_with_ripple"] - 1.0, None, None, None)
    r = cf.allocate_tolerances(coarse, {"clearance": "0.02mm"}, yield_target=0.99, targets=tight, workers=0)
    assert not r.feasible and "model-error band alone" in r.message
    assert r.allocated == {"clearance": None}
    assert r.constraints[0]["sigma_model"] > 0


@pytest.mark.slow
def test_cli_allocate(tmp_path):
    """Both runs in this process (support/cli.py): the allocation document, the files and the
    table are the point, not the process (was two interpreters)."""
    args = ["tolerance", "concept4", *sum((["--set", x] for x in ROB), []), "--mesh-size", "3mm",
            "--tol", "flexure_thickness=+-0.05mm", "--tol", "clearance=+-0.02mm", "--allocate",
            "--yield", "0.95", "--workers", "0"]
    r = cli_in_process(*args, "--out", str(tmp_path), "--json", "--n", "8")
    assert r.returncode == 0, r.stderr[-2000:]
    doc = json.loads(r.stdout)
    # --n: a Monte Carlo check of the allocated widths (8 parts: only that it ran on those widths)
    assert doc["check"]["n"] == 8 and 0.0 <= doc["check"]["share_in_spec"] <= 1.0
    assert doc["check"]["widths_si"] == pytest.approx({d["name"]: d["allocated"] for d in doc["allocation"]["dims"]},
                                                      rel=1e-9)
    assert "wrote" in r.stderr and (tmp_path / "allocation.json").exists()
    assert doc["design"]["label"] == "concept4" and doc["design"]["set"] == list(ROB)
    al = doc["allocation"]
    assert al["yield_target"] == 0.95 and al["feasible"] is True
    assert {d["name"] for d in al["dims"]} == {"flexure_thickness", "clearance"}
    assert all(d["allocated"] > 0 and d["binds"] for d in al["dims"])
    assert sorted(al["ranking"]) == ["clearance", "flexure_thickness"]
    # the table: every width with its unit
    t = cli_in_process(*args, "--no-model-error", env={"COLUMNS": "200"})
    assert t.returncode == 0, t.stderr[-2000:]
    assert "0.05 mm" in t.stdout and "0.02 mm" in t.stdout and "rpm" in t.stdout
    assert "model error left out" in t.stdout and "tighten first" in t.stdout


@pytest.mark.parametrize("extra,word", [(["--allocate", "--yield", "1.5"], "yield"),
                                        (["--allocate", "--yield", "abc"], "yield"),
                                        (["--allocate", "--cost", "hub_radius=2"], "cost"),
                                        (["--allocate", "--cost", "clearance=-1"], "cost"),
                                        (["--yield", "0.9"], "allocate"),
                                        (["--allocate", "--scheduler", "tcp://127.0.0.1:1"], "sensitivities run")])
def test_cli_allocate_refusals(extra, word):
    # in this process (support/cli.py): the refusal is the point, not the process
    r = cli_in_process("tolerance", "concept4", "--mesh-size", "3mm", "--tol", "clearance=+-0.02mm",
                       *([] if "--scheduler" in extra else ["--workers", "0"]), *extra)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert word in r.stderr
