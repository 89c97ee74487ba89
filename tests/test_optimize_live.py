"""The optimiser on the reduced model (issue 36): the search on the live answers of a cached
region (each at its band's conservative edge), the refusal of a start no region holds, the
robust search's Monte Carlo yield, and the FE verification through the command line."""

from __future__ import annotations

import json

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.evaluation import EvalSettings
from clutchfem.reduced import find
from clutchfem.targets.live import ANSWERED_BY, live_optimize
from clutchfem.targets.live_search import LiveProblem, order_slack, parts_slack, shifted_search, slsqp_search
from support.cli import cli_in_process
from support.reduced import built_region  # noqa: F401 -- the shared region (fixture `built`)

MESH = cf.MeshSettings(size="3mm")


def live(**values):
    return cf.Design.from_concept("concept1", mesh=MESH, fidelity="live", **values)


def targets_inside(model):
    """An engagement minimum half-way across the region's live engagement: the optimum binds
    inside the box (the lighter, thinner flexure engages earlier)."""
    lo, hi = model.predict(np.array([[0.0], [1.0]]))["value"]["engagement_rpm_with_ripple"]
    return cf.Targets(float(0.5 * (lo + hi)), None, 8000.0, 1.0)


def edges(model, texts):
    """The live answers of a design at its band's conservative edge, recomputed here."""
    d = live(**texts)
    u = model.region.unit_of(model.region.design_values(d))[None, :]
    p = model.predict(u)
    v, b = p["value"], p["band"]
    ys = float(d.op.material.yield_strength)
    return {"engagement_rpm_with_ripple": v["engagement_rpm_with_ripple"][0] - b["engagement_rpm_with_ripple"][0],
            "slip_rpm": v["slip_rpm"][0] + b["slip_rpm"][0],
            "safety_factor": ys / (v["max_von_mises_Pa"][0] + b["max_von_mises_Pa"][0]), "mass_kg": v["mass_kg"][0]}


@pytest.fixture(scope="module")
def deterministic(built):
    """(the region's model, the targets inside it, the deterministic live optimum): one search,
    which the robust search's test compares its nominal with."""
    model = find(live())
    t = targets_inside(model)
    return model, t, live_optimize(EvalSettings.from_design(live()), t, check=False)


@pytest.mark.slow
def test_the_live_optimum_meets_every_target_at_the_band_edge_and_binds(built, deterministic):
    model, t, r = deterministic
    assert r.feasible and r.answered_by == "reduced model" and r.live["region_key"] == built["region"]["key"]
    e = edges(model, r.best["params"])
    assert e["engagement_rpm_with_ripple"] >= t.engage_rpm_lo and e["slip_rpm"] <= 8000 and e["safety_factor"] >= 1
    # the least mass on the --set grid (0.01 mm): one step thinner misses the engagement at its edge
    step = cf.core.values.resolution(type(live().params), "flexure_thickness")
    thinner = dict(r.best["params"], flexure_thickness=f"{float(r.best['params']['flexure_thickness'][:-2]) - step * 1e3:.4f}mm")
    assert edges(model, thinner)["engagement_rpm_with_ripple"] < t.engage_rpm_lo
    assert r.live["live_evaluations"] > 0 and r.live["fe_designs"] == 0 and not r.live["on_region_bound"]


def test_a_start_no_cached_region_holds_is_refused_naming_clutchfem_reduce():
    with pytest.raises(cf.ParameterError) as e:
        cf.optimize(live(flexure_thickness="3.1mm"))
    assert e.value.name == "fidelity" and "clutchfem reduce concept1" in str(e.value)
    assert "flexure_thickness=3.1mm" in str(e.value)
    with pytest.raises(cf.ParameterError, match="ranges"):
        cf.optimize(live(), ranges={"flexure_thickness": (2e-3, 2.2e-3)})


@pytest.mark.slow
def test_outside_the_cached_region_the_refusal_names_its_bounds(built):
    with pytest.raises(cf.ParameterError) as e:
        cf.robust_optimize(live(flexure_thickness="2.5mm"), {"flexure_thickness": "0.01mm"})
    assert "flexure_thickness = 0.0025 outside 0.00209..0.00231" in str(e.value) and "clutchfem reduce" in str(e.value)


@pytest.mark.slow
def test_a_robust_live_search_meets_the_yield_on_its_monte_carlo(built, deterministic):
    model, t, det = deterministic
    r = live_optimize(EvalSettings.from_design(live()), t, tolerances={"flexure_thickness": 3e-5}, yield_target=0.95,
                      parts=1000, check=False)
    y = r.live["yield"]
    assert r.feasible and y["yield_search_sample"] >= 0.95 and y["ci95"][1] >= 0.95
    # the nominal sits inside the region by the tolerance box (+-4 sigma) and above the deterministic optimum
    tk = lambda res: float(res.best["params"]["flexure_thickness"][:-2])  # noqa: E731
    assert tk(r) > tk(det)
    lo, hi = r.live["search_box"]["flexure_thickness"]
    assert lo == pytest.approx(model.region.lo[0] + 4 / 3 * 3e-5) and hi == pytest.approx(model.region.hi[0] - 4 / 3 * 3e-5)


@pytest.mark.slow
def test_the_shifted_searches_reach_the_yield_from_the_deterministic_optimum(built):
    """The robust search's back-up (SORA): from the deterministic optimum, whose parts miss the
    engagement about half the time, the shifted deterministic searches end where at most k of
    the parts miss, thicker than the deterministic optimum (engagement needs the margin) and
    inside the box."""
    model = find(live())
    t = targets_inside(model)
    ys = float(live().op.material.yield_strength)
    prob = LiveProblem(model, t, [0], np.array([0.5]), ys, float(cf.EngineCurve.default().max_torque))
    lo, hi = np.array([0.1]), np.array([0.9])
    xd, _ = slsqp_search(prob, lo, hi, [np.array([0.5])])
    D = np.random.default_rng(3).normal(0.0, 0.02, (1000, 1))  # a tolerance of +-0.06 of the region's width
    k = 50  # a yield of 95 %
    assert order_slack(prob, xd, D, k) < 0  # the deterministic optimum: about half its parts miss
    x, info = shifted_search(prob, lo, hi, [xd], D, k)
    assert info["shifted_feasible"] and order_slack(prob, x, D, k) >= 0 and lo[0] <= x[0] <= hi[0]
    assert x[0] > xd[0] and info["shifts_rel"]["engagement_rpm_with_ripple"] > 0
    m = parts_slack(prob, prob.full(x)[0] + D)
    assert int(np.sum(m < 0)) <= k


@pytest.mark.slow
def test_optimize_fidelity_live_through_the_command_line_is_verified_by_the_fe(built):
    model = find(live())
    t = targets_inside(model)
    out = cli_in_process("optimize", "concept1", "--mesh-size", "3mm", "--fidelity", "live", "--engage-rpm",
                         f"{t.engage_rpm_lo:.0f}:", "--safety-factor-min", "1.0", "--workers", "0", "--json", ok=True)
    d = json.loads(out.stdout)
    L = d["live"]
    assert d["answered_by"] == L["answered_by"] == ANSWERED_BY and L["fe_designs"] >= 1
    fe = L["fe_answers"]
    met = fe["engagement_rpm_with_ripple"] >= t.engage_rpm_lo and fe["slip_rpm"] <= 8000 and fe["safety_factor"] >= 1
    assert d["feasible"] == met
    assert L["verdict"].startswith("met in the FE check" if met else "missed in the FE check")
    # the FE answer lies within the live band of the final design (the band holds the FE)
    a = L["answers"]["engagement_rpm_with_ripple"]
    assert abs(fe["engagement_rpm_with_ripple"] - a["value"]) <= a["band"]
    bad = cli_in_process("optimize", "concept1", "--fidelity", "live", "--method", "gradient")
    assert bad.returncode != 0 and "not with --fidelity live" in bad.stderr and "Traceback" not in bad.stderr
