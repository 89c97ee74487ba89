"""Fatigue checks (:mod:`clutchfem.durability.fatigue`) against hand calculations.

Hand numbers (Shigley, Mechanical Engineering Design, 10th ed., ch. 6), S_ut = 1450 MPa:
* S_e' = 700 MPa (S_ut > 1400 MPa);
* ln 1450 = 7.2793; machined k_a = 4.51 x 1450^-0.265 = 4.51 exp(-1.9290) = 0.6553;
  hot-rolled (our 'laser') k_a = 57.7 exp(-5.2266) = 0.3100; ground 1.58 exp(-0.6187) = 0.8510;
* k_e(99 %) = 1 - 0.08 x 2.326 = 0.8139 (Table 6-5: 0.814); k_d(20 C) = 1.000;
* S_e (machined, 99 %) = 700 x 0.6553 x 0.8139 = 373.3 MPa;
* Basquin: S(1e3) = 0.77 x 1450 = 1116.5 MPa, b = log10(373.3/1116.5)/3 = -0.1586.
The rotating annulus (free disc with a hole, plane stress, Timoshenko & Goodier):
sigma_r = (3+nu)/8 rho w^2 (a^2 + b^2 - a^2 b^2/r^2 - r^2),
sigma_t = (3+nu)/8 rho w^2 (a^2 + b^2 + a^2 b^2/r^2 - (1+3nu)/(3+nu) r^2).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from clutchfem.core import InputError, ParameterError
from clutchfem.durability import FatigueParams, LoadCycle, endurance_limit, fatigue_check
from clutchfem.durability.fatigue import (
    amplitude_mean,
    cycles_to_failure,
    equivalent_stresses,
    haigh_safety_factor,
    marin_factors,
    reversed_equivalent,
)
from clutchfem.mesh import name_location

MPa = 1e6
MACHINED = FatigueParams(edge_finish="machined")
KA_MACHINED = 4.51 * math.exp(-0.265 * math.log(1450.0))
KE_99 = 1.0 - 0.08 * 2.3263478740408408
SE_MACHINED = 700 * MPa * KA_MACHINED * KE_99  # k_d(20 C) = 0.99995: within 5e-5
SUT = 1450 * MPa


def uniaxial(sxx):
    sxx = np.atleast_1d(np.asarray(sxx, dtype=float))
    return np.vstack([sxx, np.zeros_like(sxx), np.zeros_like(sxx)])


# ---------------------------------------------------------------------------------------
# strength
# ---------------------------------------------------------------------------------------
def test_marin_factors_by_hand():
    assert KA_MACHINED == pytest.approx(0.6553, abs=1e-4)
    k = marin_factors(MACHINED)
    assert k["k_a"] == pytest.approx(KA_MACHINED, rel=1e-12)
    assert k["k_e"] == pytest.approx(0.814, abs=5e-4)  # Shigley Table 6-5
    assert k["k_d"] == pytest.approx(1.0, abs=1e-4)
    assert marin_factors(FatigueParams(edge_finish="laser"))["k_a"] == pytest.approx(0.3100, abs=1e-4)
    assert marin_factors(FatigueParams(edge_finish="ground"))["k_a"] == pytest.approx(0.8510, abs=1e-4)
    assert marin_factors(FatigueParams(edge_finish="wire_edm"))["k_a"] == pytest.approx(KA_MACHINED)
    assert marin_factors(FatigueParams(surface_factor=0.5))["k_a"] == 0.5
    assert marin_factors(FatigueParams(reliability=0.5))["k_e"] == pytest.approx(1.0)
    assert marin_factors(FatigueParams(reliability=0.999))["k_e"] == pytest.approx(0.753, abs=5e-4)
    # Shigley Table 6-4: S_T/S_RT = 0.975 at 300 C (the polynomial eq. 6-27 fits it)
    assert marin_factors(FatigueParams(temperature=300.0))["k_d"] == pytest.approx(0.975, abs=3e-3)
    Se, _ = endurance_limit(MACHINED)
    assert Se == pytest.approx(SE_MACHINED, rel=1e-4)
    assert Se == pytest.approx(373.3 * MPa, rel=5e-4)
    # below the 1400 MPa cap S_e' = 0.5 S_ut
    low = FatigueParams(ultimate_strength=1200 * MPa, yield_strength=1000 * MPa, surface_factor=1.0, reliability=0.5)
    assert endurance_limit(low)[0] == pytest.approx(600 * MPa, rel=1e-4)


def test_sn_curve_by_hand():
    """Basquin between 1e3 and the knee, endurance limit above it, low-cycle line below."""
    Se = SE_MACHINED
    S3 = 0.77 * SUT
    b = math.log10(Se / S3) / 3.0
    assert b == pytest.approx(-0.1586, abs=2e-4)
    Se_mod = endurance_limit(MACHINED)[0]
    b_mod = math.log10(Se_mod / S3) / 3.0
    for s in (500 * MPa, 800 * MPa, 1100 * MPa):
        N = 1e3 * (s / S3) ** (1 / b_mod)
        assert cycles_to_failure(s, MACHINED) == pytest.approx(N, rel=1e-12)
    assert cycles_to_failure(Se_mod * 1.0000001, MACHINED) == pytest.approx(1e6, rel=1e-5)
    assert cycles_to_failure(0.99 * Se_mod, MACHINED) == np.inf
    # Haibach: slope 2k - 1 below the knee
    hb = MACHINED.replace(miner="haibach")
    k = -1 / b_mod
    assert cycles_to_failure(0.8 * Se_mod, hb) == pytest.approx(1e6 * (1 / 0.8) ** (2 * k - 1), rel=1e-12)
    # low cycle: S = S_ut N^(log10(f)/3)
    s = 1300 * MPa
    assert cycles_to_failure(s, MACHINED) == pytest.approx((s / SUT) ** (3 / math.log10(0.77)), rel=1e-12)
    assert cycles_to_failure(1.1 * SUT, MACHINED) == 0.0


# ---------------------------------------------------------------------------------------
# amplitude, mean, Haigh
# ---------------------------------------------------------------------------------------
def test_uniaxial_start_stop_goodman_by_hand():
    """0 -> 400 MPa -> 0 (R = 0): s_a = s_m = 200 MPa; Goodman n = 1/(200/373.3 + 200/1450)
    = 1.484 (infinite life: 1e6 cycles or more); Langer yield n_y = 1250/400 = 3.125."""
    A, B = uniaxial([0.0, 0.0]), uniaxial([400 * MPa, 100 * MPa])
    amp, mean = amplitude_mean(A, B)
    sa, sm = equivalent_stresses(amp, mean)
    assert sa[0] == pytest.approx(200 * MPa) and sm[0] == pytest.approx(200 * MPa)
    r = fatigue_check([LoadCycle("start-stop", A, B, 1e6)], MACHINED)
    n_hand = 1.0 / (200 / 373.3 + 200 / 1450)
    assert n_hand == pytest.approx(1.484, abs=1e-3)
    assert r.safety_factor == pytest.approx(1.0 / (200 * MPa / SE_MACHINED + 200 / 1450), rel=1e-4)
    assert r.worst_index == 0 and r.governing_cycle == "start-stop"
    assert r.yield_safety_factor == pytest.approx(3.125) and r.yield_worst_index == 0
    assert r.damage_at_worst == 0.0  # below the Goodman line at the actual load: no damage
    # the same with Shigley's closed form
    assert r.safety_factor == pytest.approx(float(haigh_safety_factor(sa[0], sm[0], r.endurance_limit_Pa, SUT)), rel=1e-9)


def test_gerber_and_compressive_mean_by_hand():
    """Gerber (Shigley Table 6-7): n = (1/2)(S_ut/s_m)^2 (s_a/S_e)(-1 + sqrt(1 + (2 s_m S_e/(S_ut s_a))^2));
    a compressive mean gets no credit: n = S_e / s_a."""
    Se = endurance_limit(MACHINED)[0]
    A, B = uniaxial([100 * MPa, -500 * MPa]), uniaxial([500 * MPa, -100 * MPa])
    r = fatigue_check([LoadCycle("c", A, B, 1e7)], MACHINED.replace(mean_stress_rule="gerber"), xy=np.zeros((2, 2)))
    sa, sm = 200 * MPa, 300 * MPa
    n_ger = 0.5 * (SUT / sm) ** 2 * (sa / Se) * (-1 + math.sqrt(1 + (2 * sm * Se / (SUT * sa)) ** 2))
    assert r.point_safety_factor[0] == pytest.approx(n_ger, rel=1e-9)
    assert r.point_safety_factor[1] == pytest.approx(Se / sa, rel=1e-9)
    # Gerber is less conservative than Goodman with a tensile mean
    rg = fatigue_check([LoadCycle("c", A, B, 1e7)], MACHINED)
    assert rg.point_safety_factor[0] == pytest.approx(1 / (sa / Se + sm / SUT), rel=1e-9)
    assert rg.point_safety_factor[0] < r.point_safety_factor[0]
    assert rg.point_safety_factor[1] == pytest.approx(Se / sa, rel=1e-9)
    assert r.worst_xy_m == (0.0, 0.0)


def test_pure_shear_fully_reversed():
    """sxy = +-tau: s_a = sqrt(3) tau, s_m = 0 (zero trace counts as tensile: no credit
    either way); n = S_e / (sqrt(3) tau)."""
    tau = 120 * MPa
    A = np.array([[0.0], [0.0], [-tau]])
    B = -A
    sa, sm = equivalent_stresses(*amplitude_mean(A, B))
    assert sa[0] == pytest.approx(math.sqrt(3) * tau) and sm[0] == 0.0
    r = fatigue_check([LoadCycle("torsion", A, B, 1e8)], MACHINED)
    assert r.safety_factor == pytest.approx(SE_MACHINED / (math.sqrt(3) * tau), rel=1e-4)
    # a sheared mean on top: s_m = sqrt(3) tau_m
    r2 = fatigue_check([LoadCycle.from_mean_amplitude("t", mean=np.array([[0.0], [0.0], [50 * MPa]]),
                                                      amplitude=np.array([[0.0], [0.0], [tau]]), count=1e8)], MACHINED)
    assert r2.safety_factor == pytest.approx(1 / (math.sqrt(3) * tau / SE_MACHINED + math.sqrt(3) * 50 * MPa / SUT), rel=1e-4)


def _annulus_states(omega2, a, b, r, th, rho=7850.0, nu=0.3):
    c = (3 + nu) / 8 * rho * omega2
    sr = c * (a * a + b * b - a * a * b * b / r ** 2 - r ** 2)
    st = c * (a * a + b * b + a * a * b * b / r ** 2 - (1 + 3 * nu) / (3 + nu) * r ** 2)
    cs, sn = np.cos(th), np.sin(th)
    return np.vstack([sr * cs * cs + st * sn * sn, sr * sn * sn + st * cs * cs, (sr - st) * sn * cs]), sr, st


def test_rotating_annulus_ripple_cycle():
    """Speed ripple w0 (1 +- delta) on a free rotating disc with a hole (a = 6.5 mm,
    b = 100 mm, w0 = 3000 rad/s, delta = 0.071): the stresses scale with w^2, so at every
    point s_a = vM(s1) (w_hi^2 - w_lo^2)/2 and s_m = vM(s1)(w_hi^2 + w_lo^2)/2, in Cartesian
    components at any polar angle.  The worst point is on the bore (sigma_r = 0, sigma_t
    largest); its factor is the hand Goodman value."""
    a, b, w0, d = 6.5e-3, 0.1, 3000.0, 0.071
    rng = np.random.default_rng(3)
    r = np.concatenate([[a, a], rng.uniform(a, b, 200), [b]])
    th = rng.uniform(-math.pi, math.pi, r.size)
    lo, _, _ = _annulus_states((w0 * (1 - d)) ** 2, a, b, r, th)
    hi, sr1, st1 = _annulus_states((w0 * (1 + d)) ** 2, a, b, r, th)
    unit, sr, st = _annulus_states(1.0, a, b, r, th)
    vm1 = np.sqrt(sr ** 2 - sr * st + st ** 2)
    sa, sm = equivalent_stresses(*amplitude_mean(lo, hi))
    ha = 0.5 * ((w0 * (1 + d)) ** 2 - (w0 * (1 - d)) ** 2)
    hm = 0.5 * ((w0 * (1 + d)) ** 2 + (w0 * (1 - d)) ** 2)
    np.testing.assert_allclose(sa, vm1 * ha, rtol=1e-9)
    np.testing.assert_allclose(sm, vm1 * hm, rtol=1e-9)
    res = fatigue_check([LoadCycle("ripple", lo, hi, 1e7)], MACHINED, xy=np.vstack([r * np.cos(th), r * np.sin(th)]))
    assert res.worst_index in (0, 1)
    st_a = (3.3 / 4) * 7850 * (b * b + 0.7 / 3.3 * a * a)  # sigma_t(a) per unit w^2
    n_hand = 1 / (st_a * ha / SE_MACHINED + st_a * hm / SUT)
    assert res.safety_factor == pytest.approx(n_hand, rel=1e-4)
    assert math.hypot(*res.worst_xy_m) == pytest.approx(a)


def test_miner_two_finite_life_cycles_by_hand():
    """Start-stop 0 -> 900 MPa (1e4 cycles) and a fluctuation 600 +- 200 MPa (1e5 cycles),
    uniaxial.  Goodman: s_ar1 = 450/(1 - 450/1450) = 652.5 MPa, s_ar2 = 200/(1 - 600/1450) =
    341.2 MPa (below S_e: no damage, elementary Miner), so D = 1e4 / N(652.5 MPa).  The
    safety factor X solves the hand Miner sum D(X) = 1; with a third cycle above the knee
    both finite-life types add up."""
    Se = endurance_limit(MACHINED)[0]
    S3 = 0.77 * SUT
    b = math.log10(Se / S3) / 3.0

    def N(s):
        return 1e3 * (s / S3) ** (1 / b) if s > Se else math.inf

    def sar(sa, sm):
        return sa / (1 - sm / SUT)

    c1 = LoadCycle("start-stop", uniaxial([0.0]), uniaxial([900 * MPa]), 1e4)
    c2 = LoadCycle("torque", uniaxial([400 * MPa]), uniaxial([800 * MPa]), 1e5)
    r = fatigue_check([c1, c2], MACHINED)
    s1, s2 = sar(450 * MPa, 450 * MPa), sar(200 * MPa, 600 * MPa)
    assert s1 == pytest.approx(652.5 * MPa, rel=1e-4) and s2 < Se
    D = 1e4 / N(s1)
    assert r.damage_at_worst == pytest.approx(D, rel=1e-9)
    assert r.per_cycle[1]["damage"] == 0.0 and r.per_cycle[1]["allowed_cycles"] == math.inf

    def D_hand(X):
        return sum(n / N(sar(X * sa, X * sm)) for sa, sm, n in ((450 * MPa, 450 * MPa, 1e4), (200 * MPa, 600 * MPa, 1e5)))

    X = r.safety_factor
    assert D_hand(X * (1 + 1e-9)) >= 1.0 >= D_hand(X * (1 - 1e-9))
    assert r.governing_cycle == "start-stop"
    # a third type that is finite-life too: the sum counts both
    c3 = LoadCycle("ripple", uniaxial([500 * MPa]), uniaxial([700 * MPa]), 1e7)
    r3 = fatigue_check([c1, c2, c3], MACHINED)
    s3 = sar(100 * MPa, 600 * MPa)
    assert s3 < Se  # ripple alone: infinite life under the elementary rule
    assert r3.damage_at_worst == pytest.approx(D, rel=1e-9)
    hb = fatigue_check([c1, c2, c3], MACHINED.replace(miner="haibach"))
    k = -1 / b
    D_hb = D + 1e5 / (1e6 * (Se / s2) ** (2 * k - 1)) + 1e7 / (1e6 * (Se / s3) ** (2 * k - 1))
    assert hb.damage_at_worst == pytest.approx(D_hb, rel=1e-9)
    assert hb.safety_factor < r3.safety_factor


def test_governing_cycle_and_reversed_equivalent():
    """Two points: at point 0 the ripple governs, at point 1 the start-stop; the worst
    point is the lower factor; reversed_equivalent handles s_m >= S_ut as infinite."""
    A1, B1 = uniaxial([0.0, 0.0]), uniaxial([100 * MPa, 500 * MPa])
    A2, B2 = uniaxial([150 * MPa, 0.0]), uniaxial([450 * MPa, 10 * MPa])
    r = fatigue_check([LoadCycle("start-stop", A1, B1, 3e4), LoadCycle("ripple", A2, B2, 1e7)], MACHINED)
    assert r.point_safety_factor.shape == (2,)
    assert r.worst_index == int(np.argmin(r.point_safety_factor))
    names = {p["name"]: p for p in r.per_cycle}
    gov = max(names.values(), key=lambda p: p["damage_share_at_failure"])["name"]
    assert gov == r.governing_cycle
    assert reversed_equivalent(100 * MPa, 1500 * MPa, SUT) == np.inf
    assert reversed_equivalent(0.0, 100 * MPa, SUT) == 0.0


# ---------------------------------------------------------------------------------------
# location on a concept mesh
# ---------------------------------------------------------------------------------------
_CM = {}


def concept_mesh(name):
    from clutchfem.geometry import MeshSettings, get_concept
    from clutchfem.mesh import mesh_concept

    if name not in _CM:
        c = get_concept(name)
        _CM[name] = mesh_concept(c, c.params(), MeshSettings(size=2e-3, model="sector"))
    return _CM[name]


def _vertex_points(cm):
    """Points like the solver's raw vertex stresses: every element's 3 vertices."""
    m = cm.mesh
    return m.p[:, m.t.T.ravel()], np.arange(m.t.shape[1]).repeat(3)


def test_location_naming_concept4():
    """Concept 4: the thin beam runs from the small hub outwards to the shoe.  A stress
    peak at the flexure's innermost element is named 'flexure 0, hub end', at its outermost
    'shoe end'; the location comes through fatigue_check with the element of the point."""
    cm = concept_mesh("concept4")
    m = cm.mesh
    fel = np.asarray(m.subdomains["flexure_0"])
    rad = np.hypot(*m.p[:, m.t[:, fel]].mean(axis=1))
    xy, elem = _vertex_points(cm)
    for e, want in ((fel[np.argmin(rad)], "hub end"), (fel[np.argmax(rad)], "shoe end")):
        s = np.zeros((3, xy.shape[1]))
        k = 3 * e  # first vertex of that element
        s[0, k] = 500 * MPa
        res = fatigue_check([LoadCycle("start-stop", np.zeros_like(s), s, 1e5)], MACHINED, xy=xy, cm=cm,
                            element=elem)
        assert res.worst_index == k
        assert res.location.zone == "flexure_0" and res.location.position == want
        assert res.location.description.startswith(f"flexure 0, {want}")
    hub = np.asarray(m.subdomains["hub"])
    shoe = np.asarray(m.subdomains["shoe_0"])
    assert name_location(cm, m.p[:, m.t[:, hub[0]]].mean(axis=1)).kind == "hub"
    loc = name_location(cm, m.p[:, m.t[:, shoe[len(shoe) // 2]]].mean(axis=1))
    assert loc.zone == "shoe_0" and loc.index == 0


@pytest.mark.slow
def test_location_naming_concept1_and_concept2():
    """Concept 1 (drawing: the flexure leaves the hub near the sector's upper cut, y ~ 0,
    and meets the shoe below): its highest element is the hub end, its lowest the shoe
    end.  Concept 2's second flexure, inside the shoe, joins shoe material only: 'in-shoe
    flexure'.  Points on the bore, the contact surface and a free edge are named so."""
    cm = concept_mesh("concept1")
    m = cm.mesh
    fel = np.asarray(m.subdomains["flexure_0"])
    y = m.p[1, m.t[:, fel]].mean(axis=0)
    assert name_location(cm, m.p[:, m.t[:, fel[np.argmax(y)]]].mean(axis=1)).position == "hub end"
    assert name_location(cm, m.p[:, m.t[:, fel[np.argmin(y)]]].mean(axis=1)).position == "shoe end"
    bore_v = m.facets[0, cm.boundary("bore")[0]]
    assert name_location(cm, m.p[:, bore_v]).boundary == "bore"
    cont_v = m.facets[0, cm.boundary("contact")[3]]
    loc = name_location(cm, m.p[:, cont_v])
    assert loc.boundary == "contact surface" and loc.zone == "shoe_0"
    # a mid-edge P2 node of the (curved) contact surface counts as well
    from skfem import Basis, ElementTriP2

    b = Basis(m, ElementTriP2())
    mid = b.facet_dofs[0, cm.boundary("contact")[3]]
    assert name_location(cm, b.doflocs[:, mid]).boundary == "contact surface"
    assert name_location(cm, b.doflocs[:, mid]).description.startswith("shoe 0, on the contact surface")
    # a free edge of the flexure: a boundary vertex of a flexure element not on a named group
    named = set(np.unique(m.facets[:, np.concatenate([np.asarray(v) for v in m.boundaries.values()])]).tolist())
    bnd = set(np.unique(m.facets[:, m.boundary_facets()]).tolist())
    free = [v for v in np.unique(m.t[:, fel]) if v in bnd and v not in named]
    assert name_location(cm, m.p[:, free[0]]).boundary == "free edge"
    cm2 = concept_mesh("concept2")
    m2 = cm2.mesh
    f2 = np.asarray(m2.subdomains["flexure_0"])
    rad = np.hypot(*m2.p[:, m2.t[:, f2]].mean(axis=1))
    outer = f2[np.argmax(rad)]  # the in-shoe flexure lies at the drum
    assert name_location(cm2, m2.p[:, m2.t[:, outer]].mean(axis=1)).position == "in-shoe flexure"
    ang = np.arctan2(*m2.p[::-1, m2.t[:, f2]].mean(axis=1))
    top = f2[np.argmax(ang)]
    assert name_location(cm2, m2.p[:, m2.t[:, top]].mean(axis=1)).position == "main flexure, hub end"


# ---------------------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------------------
def _param(name, fn):
    with pytest.raises(ParameterError) as e:
        fn()
    assert e.value.name == name and "not allowed" in str(e.value)
    return e.value


def test_bad_input_is_refused():
    e = _param("ultimate_strength", lambda: FatigueParams(ultimate_strength=-1.0))
    assert "Pa" in e.allowed
    _param("reliability", lambda: FatigueParams(reliability=1.0))
    _param("edge_finish", lambda: FatigueParams(edge_finish="sawn"))
    _param("yield_strength", lambda: FatigueParams(yield_strength=1500 * MPa))
    _param("temperature", lambda: FatigueParams(temperature=600.0))
    _param("knee_cycles", lambda: FatigueParams(knee_cycles=10.0))
    ok = uniaxial([1.0, 2.0])
    _param("count", lambda: LoadCycle("x", ok, ok, 0))
    _param("count", lambda: LoadCycle("x", ok, ok, float("nan")))
    _param("name", lambda: LoadCycle("", ok, ok, 10))
    with pytest.raises(InputError, match=r"shape \(3, npts\)"):
        LoadCycle("x", ok[:2], ok[:2], 10)
    with pytest.raises(InputError, match="same shape"):
        LoadCycle("x", ok, uniaxial([1.0]), 10)
    with pytest.raises(InputError, match="non-finite"):
        LoadCycle("x", ok, np.array([[1.0, np.nan], [0, 0], [0, 0]]), 10)
    with pytest.raises(InputError, match="expected Pa"):
        LoadCycle("x", ok, ok * 1e12, 10)
    c1 = LoadCycle("a", ok, ok, 10)
    with pytest.raises(InputError, match="points"):
        fatigue_check([c1, LoadCycle("b", uniaxial([1.0]), uniaxial([2.0]), 10)])
    with pytest.raises(InputError, match="unique"):
        fatigue_check([c1, c1])
    with pytest.raises(InputError, match="no load cycles"):
        fatigue_check([])
    with pytest.raises(InputError, match="xy"):
        fatigue_check([c1], xy=np.zeros((2, 5)))
    cm = concept_mesh("concept4")
    with pytest.raises(InputError, match="outside"):
        name_location(cm, (1.0, 1.0))
    _param("element", lambda: name_location(cm, (0.02, 0.0), element=10 ** 7))
    with pytest.raises(InputError, match="coordinates"):
        fatigue_check([c1], cm=cm)


def test_p2_nodes_of_a_quadratic_mesh_are_the_p2_basis_nodes():
    """name_location reads the P2 nodes off a quadratic mesh instead of building a P2 basis:
    the same positions and facet node ids as scikit-fem's P2 basis."""
    from skfem import Basis, ElementTriP2

    from clutchfem.geometry import MeshSettings
    from clutchfem.loadcase import Design
    from clutchfem.mesh import facet_nodes, is_quadratic, p2_nodes

    cm = Design.from_concept("concept4", mesh=MeshSettings(size=2.5e-3)).cm
    b = Basis(cm.mesh, ElementTriP2(), intorder=1)
    assert is_quadratic(cm.mesh)
    np.testing.assert_array_equal(p2_nodes(cm.mesh), b.doflocs)
    np.testing.assert_array_equal(facet_nodes(cm.mesh), np.vstack([cm.mesh.facets, b.facet_dofs[0]]))
