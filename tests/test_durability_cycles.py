"""Fatigue in analyze (issue 14): the service cycles against hand calculations, the
longest-chord amplitude against the ellipse's major axis, the reverse-torque line against
solved reversed-friction states, the candidate-point screen against the full check, and
analyze's JSON/table/report carrying the answer with a named location."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
from scipy.stats import norm

from clutchfem.analysis import analyze, fatigue_cycles, fatigue_step, secondary_case
from clutchfem.clutch import EngineCurve, RippleModel
from clutchfem.core import ParameterError, rpm_to_rad_s
from clutchfem.durability import (
    FatigueLoads,
    FatigueParams,
    LoadCycle,
    ServiceStates,
    candidate_points,
    endurance_limit,
    fatigue_check,
    service_cycles,
    single_cycle_factor,
)
from clutchfem.durability.cycles import longest_chord, reverse_capacity
from clutchfem.durability.fatigue.check import _load_factor
from clutchfem.fe import von_mises
from clutchfem.geometry import MeshSettings
from clutchfem.loadcase import Design, LoadCase, OperatingPoint
from support.shapes import load_annulus

COARSE = MeshSettings(size=2.5e-3)
ENGINE = EngineCurve.default()


# ---------------------------------------------------------------------------------------
# a rotating annulus with a drum it never reaches: the stress is w^2 S1 exactly
# ---------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def annulus(tmp_path_factory):
    """120 deg sector of a steel ring 8..30 mm, 10 mm thick, in a drum of 30.2 mm: the free
    rim grows ~2 um at 14000 rpm, so the 0.2 mm gap never closes; no spin softening, so the
    field is linear in w^2."""
    cm = load_annulus(tmp_path_factory.mktemp("ann") / "ann.msh", 0.008, 0.030, 2.5e-3, thickness=0.01,
                      sector_deg=120.0)
    d = Design(cm, OperatingPoint(drum_radius=0.0302, softening="off"), name="annulus")
    res = d.sweep([0.0, 8000.0, 14000.0])
    assert res.engagement_rpm is None or res.engagement_rpm > 14000
    return d, res


def test_annulus_start_stop_is_half_the_max_speed_field(annulus):
    """start-stop: 0 -> 14000 rpm -> 0; amplitude and mean tensors are both half the FE
    field w_max^2 S1 (S1 the field at 1 rad/s), at every point."""
    d, res = annulus
    cs = fatigue_cycles(d, res, ENGINE)
    ss = cs.cycles[0]
    assert ss.name == "start-stop" and ss.count == FatigueLoads().start_stops
    S1 = d.model.stress(d.model.u1)
    top = rpm_to_rad_s(14000.0) ** 2 * S1
    scale = np.abs(top).max()
    assert np.abs(ss.state_a).max() == 0.0
    assert np.abs(ss.state_b - top).max() < 1e-9 * scale
    amp, mean = ss.equivalent()
    np.testing.assert_allclose(amp, 0.5 * von_mises(top), rtol=1e-9, atol=1e-9 * scale)
    np.testing.assert_allclose(mean, 0.5 * von_mises(top), rtol=1e-9, atol=1e-9 * scale)
    assert cs.info["engaged_at_operating_speed"] is False
    assert cs.info["capacity_forward_Nm"] == [0.0, 0.0, 0.0]


def test_annulus_ripple_classes_by_hand(annulus):
    """Running revolutions at 8000 rpm (no contact, no torque): w = w_o (1 + delta sin theta),
    so the stress path is w_o^2 (1 + delta sin theta)^2 S1, a straight line; its longest
    chord joins theta = 90 and 270 deg: amplitude 2 delta w_o^2 S1, mean w_o^2 (1 + delta^2)
    S1.  delta per class = 0.032 + z 0.013 (seed 000 at 8000 rpm), z = 0, 1, 2, 3, 4;
    counts 1e7 x the Normal probabilities of z <= 0, 0..1, 1..2, 2..3, > 3."""
    d, res = annulus
    cs = fatigue_cycles(d, res, ENGINE)
    S1 = d.model.stress(d.model.u1)
    wo2 = rpm_to_rad_s(8000.0) ** 2
    edges = [-np.inf, 0, 1, 2, 3, np.inf]
    run = cs.cycles[1:]
    assert len(run) == 5
    assert sum(c.count for c in run) == pytest.approx(1e7, rel=1e-12)
    for k, c in enumerate(run):
        delta = 0.032 + k * 0.013
        assert f"delta {delta:.3f}" in c.name
        assert c.count == pytest.approx(1e7 * (norm.cdf(edges[k + 1]) - norm.cdf(edges[k])), rel=1e-12)
        amp_t = 0.5 * (c.state_b - c.state_a)
        mean_t = 0.5 * (c.state_b + c.state_a)
        ref_amp = 2 * delta * wo2 * S1
        scale = np.abs(ref_amp).max()
        # the chord's direction may be either way round
        assert min(np.abs(amp_t - ref_amp).max(), np.abs(amp_t + ref_amp).max()) < 1e-9 * scale
        assert np.abs(mean_t - wo2 * (1 + delta ** 2) * S1).max() < 1e-9 * np.abs(wo2 * S1).max()


def test_annulus_fatigue_step_names_the_worst_point(annulus):
    """The whole step on the ring: a finite factor, start-stop governs (the 14000 rpm swing
    dwarfs the ripple), the worst point is named, JSON-ready details."""
    d, res = annulus
    fa = fatigue_step(d, res, ENGINE)
    assert fa.safety_factor is not None and 0 < fa.safety_factor < np.inf
    assert fa.governing_cycle == "start-stop"
    assert fa.location and "r = " in fa.location
    # the hoop stress of a spinning ring peaks at the bore
    assert fa.details["location_detail"]["boundary"] == "bore"
    json.dumps(fa.to_json(), allow_nan=True)


# ---------------------------------------------------------------------------------------
# the revolution path with load torque: hand calculations on synthetic fields
# ---------------------------------------------------------------------------------------
def _states(F, m0, npts=5, seed=0):
    """S0 the same at every speed (the speed ripple does nothing), G = (Sf - S0) / F."""
    rng = np.random.default_rng(seed)
    s0 = rng.normal(size=(3, npts)) * 1e8
    g = rng.normal(size=(3, npts)) * 1e7  # Pa per N m
    w = rpm_to_rad_s(8000.0) * np.array([0.9, 1.0, 1.1])
    st = ServiceStates(omegas=w, S0=np.stack([s0, s0, s0]), Sf_o=s0 + F * g, Mf=np.full(3, F), M0=np.full(3, m0),
                       omega_max=rpm_to_rad_s(14000.0), S0_max=2 * s0, Sf_max=2 * s0 + 3 * F * g, Mf_max=3 * F,
                       M0_max=3 * m0)
    return st, s0, g


@pytest.mark.parametrize("F,m0,delta,lo_hi", [
    (100.0, 110.0, 0.05, None),         # capacity far above: demand range carried
    (5.0, 5.5, 0.05, (None, 5.0)),       # forward slip clips the top
    (5.0, 4.0, 0.10, (-4.0 / 1.2, 5.0)),  # both directions clip: reverse M_0 / (2 - M_0/M_f) = 3.333
])
def test_revolution_torque_cycle_by_hand(F, m0, delta, lo_hi):
    """M(theta) = J delta w_o^2 cos theta + M_o (1 - cos theta) ranges over [2 M_o - J delta
    w_o^2, J delta w_o^2] (theta = 180, 0 deg); the holding state is S0 + M G; beyond the
    capacities M_f (forward) and M_r = M_0 / (2 - M_0 / M_f) (reverse) the clutch slips and M
    is clipped.  Amplitude = (M_hi - M_lo)/2 vM(G) (proportional path), mean S0 + (M_hi +
    M_lo)/2 G."""
    st, s0, g = _states(F, m0)
    J, Mo = 2e-4, 3.0
    wo = rpm_to_rad_s(8000.0)
    cls = [{"z_range": [0.0, 1.0], "z": 1.0, "delta": delta, "probability": 1.0, "count": 1e7}]
    cs = service_cycles(st, delta_classes=cls, cutting_torque=Mo, inertia=J, max_speed_torque=2.0,
                        start_stops=1e8, samples=24)
    hi = J * delta * wo ** 2
    lo = 2 * Mo - hi
    if lo_hi is not None:
        lo = max(lo, lo_hi[0]) if lo_hi[0] is not None else lo
        hi = min(hi, lo_hi[1])
    c = cs.cycles[1]
    amp, mean = 0.5 * (c.state_b - c.state_a), 0.5 * (c.state_b + c.state_a)
    np.testing.assert_allclose(von_mises(amp), 0.5 * (hi - lo) * von_mises(g), rtol=1e-12)
    np.testing.assert_allclose(mean, s0 + 0.5 * (hi + lo) * g, rtol=1e-10, atol=1e-6)
    info = cs.info["classes"][0]
    assert info["carried_torque_Nm"] == pytest.approx([lo, hi], rel=1e-12)
    assert (info["slipping_fraction_of_revolution"] > 0) == (lo_hi is not None)
    # start-stop (no running class is seen once per start here: 1e7 < 1e8): rest -> the
    # max-speed state holding the engine's 2 N m there: S0_max + (2 / M_f,max)(S_f,max - S0_max)
    np.testing.assert_allclose(cs.cycles[0].state_b, 2 * s0 + 2.0 * g, rtol=1e-12, atol=1e-6)


def test_start_stop_takes_the_farthest_state_of_a_start():
    """A running class that occurs at least once per start (count >= start-stops) enters the
    start-stop envelope: where a running state lies farther from zero than the max-speed
    state, the start-stop cycle goes to it."""
    st, s0, g = _states(100.0, 110.0)
    st = replace(st, S0_max=0.1 * s0, Sf_max=0.1 * s0 + 300.0 * g)  # a gentle top speed
    cls = [{"z_range": [0.0, 1.0], "z": 1.0, "delta": 0.05, "probability": 1.0, "count": 1e7}]
    kw = dict(delta_classes=cls, cutting_torque=3.0, inertia=2e-4, max_speed_torque=1.0, samples=24)
    top = service_cycles(st, start_stops=1e8, **kw).cycles[0].state_b
    env = service_cycles(st, start_stops=1e4, **kw).cycles[0].state_b
    np.testing.assert_allclose(top, 0.1 * s0 + g, rtol=1e-12, atol=1e-6)
    assert np.all(von_mises(env) >= von_mises(top) - 1e-6)
    assert np.any(von_mises(env) > 2 * von_mises(top))


def test_longest_chord_is_the_ellipse_major_axis():
    """Path A cos t + B sin t (an unclipped revolution is such an ellipse): its longest von
    Mises chord is the major axis, 2 sqrt(lambda_max) of the 2x2 Gram matrix q(A,A), q(A,B),
    q(B,B); 720 samples come within 1e-5, and never exceed it."""
    rng = np.random.default_rng(3)
    A, B = rng.normal(size=(3, 50)), rng.normal(size=(3, 50))

    def q(x, y):
        return x[0] * y[0] - 0.5 * (x[0] * y[1] + x[1] * y[0]) + x[1] * y[1] + 3 * x[2] * y[2]

    t = 2 * np.pi * np.arange(720) / 720
    Sa, Sb, _, _ = longest_chord(np.stack([A, B]), np.column_stack([np.cos(t), np.sin(t)]))
    aa, ab, bb = q(A, A), q(A, B), q(B, B)
    major = 2 * np.sqrt(0.5 * (aa + bb) + np.sqrt(0.25 * (aa - bb) ** 2 + ab ** 2))
    chord = von_mises(Sb - Sa)
    assert np.all(chord <= major * (1 + 1e-9))
    assert np.all(chord >= major * (1 - 1e-5))


# ---------------------------------------------------------------------------------------
# the holding-state line against solved states (FE)
# ---------------------------------------------------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("name", ["concept1", "concept4"])
def test_reverse_capacity_line_against_a_solved_reverse_state(name):
    """The line through the frictionless and the forward full-slip state gives the reverse
    slip torque M_0 / (2 - M_0 / M_f); against the state solved with the friction reversed
    (hub turning the other way): measured 0.7 % (concept 1), 0.1 % (concept 4) at 8000 and
    9072 rpm; the stress field on the line within 1.5 % of the peak farther than 2 mm from
    the contact surface (the contact node moves with the friction direction: the patch's own
    stresses differ more)."""
    d = Design.from_concept(name, mesh=COARSE)
    c0, cf = secondary_case(d, 0.0), secondary_case(d, d.op.mu)
    cr = LoadCase(d.model, replace(d.contact(), rotation="cw"), c0.softening)
    mu, R = d.op.mu, d.drum_radius
    w = rpm_to_rad_s(9072.0)
    lam = [c.solve(w)[0] for c in (c0, cf, cr)]
    M0, Mf, Mr = (mu * R * x.sum() * cf.scale for x in lam)
    line = reverse_capacity(M0, Mf)
    print(f"\n{name}: M0 {M0:.3f}, Mf {Mf:.3f}, Mr solved {Mr:.3f}, line {line:.3f} ({100 * (line / Mr - 1):+.2f} %)")
    assert line == pytest.approx(Mr, rel=0.015)
    S0, Sf, Sr = (c.stresses([w], x[None])[..., 0] for c, x in zip((c0, cf, cr), lam))
    S_line = S0 - line * (Sf - S0) / Mf
    r = np.hypot(*d.model.stress.points)
    far = r < R - 0.6e-3 - 2e-3
    err = np.abs(von_mises(S_line) - von_mises(Sr))[far].max() / von_mises(Sr).max()
    print(f"  field beyond 2 mm of the contact surface: {100 * err:.2f} % of the peak")
    assert err < 0.02


# ---------------------------------------------------------------------------------------
# the fatigue check's closed forms and screen
# ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("rule,miner", [("goodman", "elementary"), ("gerber", "elementary"),
                                        ("goodman", "haibach"), ("gerber", "haibach")])
def test_single_cycle_factor_equals_the_bisection(rule, miner):
    """One cycle type alone: the closed form equals fatigue_check's bisection (1e-9) over
    counts from 1e2 (low-cycle) through the knee to 1e9, tensile and compressive means."""
    p = FatigueParams(mean_stress_rule=rule, miner=miner)
    Se = endurance_limit(p)[0]
    rng = np.random.default_rng(1)
    sa = rng.uniform(10e6, 600e6, 40)
    sm = rng.uniform(-300e6, 900e6, 40)
    for n in (1e2, 5e3, 2e5, 1e6, 1e8, 1e9):
        X = _load_factor(sa[None], sm[None], np.array([n]), p, Se)[0]
        np.testing.assert_allclose(single_cycle_factor(sa, sm, n, p, Se), X, rtol=1e-9)


def test_candidate_screen_finds_the_same_worst_point():
    """fatigue_check on the screened candidates and on every point: the same factor, worst
    point and governing cycle (random fields, three cycle types of mixed counts)."""
    rng = np.random.default_rng(7)
    n = 4000
    base = rng.normal(size=(3, n)) * 2e8
    cycles = [LoadCycle("a", np.zeros((3, n)), base * rng.uniform(0.5, 1.5, n), 5e4),
              LoadCycle("b", base * 0.9, base * 1.1 + rng.normal(size=(3, n)) * 2e7, 1e7),
              LoadCycle("c", base * 0.5, base * 1.4, 2e5)]
    p = FatigueParams()
    full = fatigue_check(cycles, p)
    cand = candidate_points(cycles, p)
    sub = fatigue_check([LoadCycle(c.name, c.state_a[:, cand], c.state_b[:, cand], c.count) for c in cycles], p)
    print(f"\n{len(cand)} of {n} points checked")
    assert len(cand) < n / 10
    assert sub.safety_factor == pytest.approx(full.safety_factor, rel=1e-12)
    assert cand[sub.worst_index] == full.worst_index
    assert sub.governing_cycle == full.governing_cycle


# ---------------------------------------------------------------------------------------
# analyze carries the answer
# ---------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def an4():
    return analyze(Design.from_concept("concept4", mesh=COARSE))


@pytest.mark.slow
def test_analyze_has_fatigue_answer_with_a_named_location(an4):
    """Concept 4: the factor, a flexure-end location, the governing cycle among the cycles
    counted; JSON strict and carries the keys; the table and the report show them; no
    'fatigue caution' on yield any more."""
    from clutchfem.core import dumps
    from clutchfem.report import markdown_summary, summary_rows

    an = an4
    assert an.fatigue_safety_factor is not None and 0 < an.fatigue_safety_factor < 10
    assert an.fatigue_location.startswith("flexure 0, ") and ("end" in an.fatigue_location)
    names = [c["name"] for c in an.fatigue["per_cycle"]]
    assert names[0] == "start-stop" and len(names) == 6
    assert an.fatigue_governing_cycle in names
    d = json.loads(dumps(an.to_json()))
    for k in ("fatigue_safety_factor", "fatigue_location", "fatigue_governing_cycle", "fatigue"):
        assert d[k] is not None
    assert d["fatigue"]["location_detail"]["zone"] == "flexure_0"
    rows = dict(summary_rows(an))
    assert any(k.startswith("fatigue safety factor") for k in rows)
    assert rows["fatigue: worst point"] == an.fatigue_location
    md = markdown_summary({"concept4": an}, ENGINE)
    assert "fatigue: governing cycle" in md and an.fatigue_governing_cycle in md
    assert not any("fatigue in mind" in w for w in an.warnings)


def test_fatigue_settings_change_the_answer_as_they_should():
    """A better edge (wire EDM: k_a 0.655 vs laser 0.310) raises the factor; fewer starts
    raise it while start-stop governs; a speed outside the engine curve is refused."""
    d = Design.from_concept("concept4", mesh=COARSE)
    res = d.sweep(np.union1d(np.arange(0, 14001, 1000.0), [8000.0]))
    base = fatigue_step(d, res, ENGINE)
    edm = fatigue_step(d, res, ENGINE, params=FatigueParams(edge_finish="wire_edm"))
    few = fatigue_step(d, res, ENGINE, loads=FatigueLoads(start_stops=1e3))
    assert edm.safety_factor > base.safety_factor
    if base.governing_cycle == "start-stop":
        assert few.safety_factor > base.safety_factor
    with pytest.raises(ParameterError, match="operating_rpm"):
        fatigue_step(d, res, ENGINE, loads=FatigueLoads(operating_rpm=20000.0))
    # the ripple law is the analyze's: no ripple leaves only the torque fluctuation
    calm = fatigue_cycles(d, res, ENGINE, ripple_model=RippleModel(delta_ref=0.0, std_ref=0.0))
    assert all(c["delta"] == 0.0 for c in calm.info["classes"])


def test_material_without_fatigue_data_is_not_available():
    d = Design.from_concept("concept4", operating=OperatingPoint(material="aluminium"), mesh=COARSE)
    res = d.sweep([8000.0, 14000.0])
    fa = fatigue_step(d, res, ENGINE)
    assert fa.safety_factor is None and "7075" in fa.details["reason"]


@pytest.mark.slow
def test_analyze_cli_json_has_fatigue_keys_and_settings_act():
    """analyze --json (coarse concept 4): the fatigue keys with a named location; --fatigue
    settings reach the step (wire-EDM edges: S_e 373 MPa); bad settings are refused before
    any meshing, naming the option; --list-fatigue lists them."""
    import time

    from typer.testing import CliRunner

    from clutchfem.cli import app

    def inv(*a):
        return CliRunner().invoke(app, list(a), catch_exceptions=False)

    r = inv("analyze", "concept4", "--mesh-size", "2.5mm", "--json", "--fatigue", "edge_finish=wire_edm")
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["fatigue_safety_factor"] > 0
    assert d["fatigue_location"].startswith("flexure 0")
    assert d["fatigue_governing_cycle"] in [c["name"] for c in d["fatigue"]["per_cycle"]]
    assert d["fatigue"]["params"]["edge_finish"] == "wire_edm"
    assert d["fatigue"]["endurance_limit_Pa"] == pytest.approx(373.3e6, rel=2e-3)
    for bad, word in (("bogus=1", "unknown"), ("start_stops=0", "start_stops"), ("samples=10", "multiple of 4"),
                      ("operating_rpm=20000", "engine curve"), ("miner=never", "haibach")):
        t0 = time.perf_counter()
        r = inv("analyze", "concept4", "--fatigue", bad)
        assert r.exit_code == 2 and "--fatigue" in r.output and word in r.output, (bad, r.output)
        assert time.perf_counter() - t0 < 3.0
    r = inv("analyze", "--list-fatigue")
    assert r.exit_code == 0 and "start_stops" in r.output and "edge_finish" in r.output


@pytest.mark.slow
@pytest.mark.parametrize("concept, loads", [
    ("concept4", FatigueLoads()),
    ("concept1", FatigueLoads()),
    ("concept2", FatigueLoads(start_stops=1e2, revolutions=1e9)),  # the running cycles govern
    ("concept4", FatigueLoads(cutting_torque=3.0)),  # near the capacity: slipping revolutions
])
def test_screened_fatigue_step_equals_checking_every_point(concept, loads):
    """fatigue_step builds the cycles only where the lower bound L(p) of the factor (from
    upper bounds of each cycle's amplitude and mean) can reach the smallest factor: the same
    factor, worst point, governing cycle and location as building them at every point; the
    bounds hold at every point; L(p) <= the point's factor everywhere."""
    d = Design.from_concept(concept, mesh=COARSE)
    res = d.sweep(np.union1d(np.arange(0, 14001, 1000.0), [8000.0]))
    fa = fatigue_step(d, res, ENGINE, loads=loads)
    cs = fatigue_cycles(d, res, ENGINE, loads=loads)
    p = FatigueParams()
    pts = d.model.stress.points
    full = fatigue_check(list(cs.cycles), p, xy=pts, cm=d.cm, element=np.arange(d.cm.n_elements).repeat(3))
    assert fa.safety_factor == pytest.approx(full.safety_factor, rel=1e-12)
    assert fa.governing_cycle == full.governing_cycle and fa.location == full.location.description
    assert fa.details["points_screened"] < pts.shape[1] / 4
    vfull = max(float(np.maximum(von_mises(c.state_a), von_mises(c.state_b)).max()) for c in cs.cycles)
    assert fa.details["yield_safety_factor_over_cycles"] == pytest.approx(
        fa.details["params"]["yield_strength"] / vfull, rel=1e-12)
    scale = float(cs.stress_bound.max())
    for i, c in enumerate(cs.cycles):
        sa, sm = c.equivalent()
        assert np.all(sa <= cs.amplitude_bound[i] * (1 + 1e-9) + 1e-9 * scale), c.name
        assert np.all(np.abs(sm) <= cs.mean_bound[i] * (1 + 1e-9) + 1e-9 * scale), c.name
        assert np.all(np.maximum(von_mises(c.state_a), von_mises(c.state_b)) <= cs.stress_bound * (1 + 1e-9)
                      + 1e-9 * scale)
    n = [c.count for c in cs.cycles]
    L = np.min([single_cycle_factor(cs.amplitude_bound[i], cs.mean_bound[i], len(n) * n[i], p)
                for i in range(len(n))], axis=0)
    assert np.all(L <= full.point_safety_factor * (1 + 1e-9))
    print(f"\n{concept}: {fa.details['points_screened']} of {pts.shape[1]} points screened in, "
          f"{fa.details['points_checked']} checked")
