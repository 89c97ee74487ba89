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


@pytest.fixture(scope="module")
def rotor4():
    return sh.concept_rotor("concept4")


def _disc_part(m=0.1, r=0.03, h=0.01, z=0.02, spins="crank"):
    return sh.RigidPart.ring("disc", 0.0, r, h, m / (math.pi * r * r * h), z, spins, "test")


def test_ring_part_inertias_closed_form():
    p = sh.RigidPart.ring("r", 0.01, 0.03, 0.02, 7850.0, 0.0, "drum", "test")
    m = 7850.0 * math.pi * (0.03**2 - 0.01**2) * 0.02
    assert p.mass_kg == pytest.approx(m)
    assert p.polar_inertia_kg_m2 == pytest.approx(m * (0.01**2 + 0.03**2) / 2)
    assert p.diametral_inertia_kg_m2 == pytest.approx(m * ((0.01**2 + 0.03**2) / 4 + 0.02**2 / 12))
    with pytest.raises(ParameterError):
        sh.RigidPart.ring("r", 0.03, 0.01, 0.02, 7850.0, 0.0, "drum", "test")
    with pytest.raises(ParameterError):  # I_p > 2 I_d is impossible for a rigid body
        sh.RigidPart("x", 0.1, 3e-4, 1e-4, 0.02, "crank", "test")
    with pytest.raises(ParameterError):
        sh.RigidPart("x", 0.1, 1e-4, 1e-4, 0.02, "wheel", "test")


def test_clutch_part_from_mass_properties_of_a_full_disc():
    # area properties of a disc of radius R per unit density and thickness (hand values)
    R, h, rho = 0.035, 0.011, 7850.0
    A = math.pi * R**2
    mass = {"solid": {"area": A, "centroid": (0.0, 0.0), "J_centroid": math.pi * R**4 / 2,
                      "Ixx_origin": math.pi * R**4 / 4, "Iyy_origin": math.pi * R**4 / 4}}
    p = sh.clutch_part_from_mass_properties(mass, h, rho, 0.02, "test")
    m = rho * h * A
    assert p.mass_kg == pytest.approx(m)
    assert p.polar_inertia_kg_m2 == pytest.approx(m * R**2 / 2)
    assert p.diametral_inertia_kg_m2 == pytest.approx(m * (R**2 / 4 + h**2 / 12))
    assert p.spins == "crank"


def test_rotor_composite_properties():
    a, b = _disc_part(0.1, z=0.01), _disc_part(0.3, z=0.03, spins="drum")
    rot = sh.Rotor((a, b))
    assert rot.mass_kg == pytest.approx(0.4)
    assert rot.cg_m == pytest.approx((0.1 * 0.01 + 0.3 * 0.03) / 0.4)
    zc = rot.cg_m
    expect = (a.diametral_inertia_kg_m2 + b.diametral_inertia_kg_m2
              + 0.1 * (0.01 - zc) ** 2 + 0.3 * (0.03 - zc) ** 2)
    assert rot.diametral_inertia_kg_m2 == pytest.approx(expect)
    assert rot.polar_inertia_kg_m2("engaged") == pytest.approx(
        a.polar_inertia_kg_m2 + b.polar_inertia_kg_m2)
    assert rot.polar_inertia_kg_m2("drum_held") == pytest.approx(a.polar_inertia_kg_m2)
    assert rot.polar_inertia_kg_m2("none") == 0.0
    with pytest.raises(ParameterError):
        rot.polar_inertia_kg_m2("spinning")


def test_concept_rotor_mass_from_geometry(rotor4):
    name, rot = rotor4
    assert name == "concept4"
    clutch = rot.parts[0]
    assert clutch.name == "clutch" and "concept4 geometry" in clutch.source
    # independent check of the geometry module's mass: the part lies inside the drum
    # (r < 34.4 mm) around the bore (r > 6.5 mm), 11 mm thick: bounds of a full annulus
    from clutchfem.geometry import get_concept
    p = get_concept("concept4").params()
    annulus = 7850.0 * math.pi * (p.drum_radius**2 - p.bore_radius**2) * p.thickness
    assert 0.2 * annulus < clutch.mass_kg < annulus
    # I_p of the part is at most that of all its mass on the drum radius
    assert clutch.polar_inertia_kg_m2 < clutch.mass_kg * p.drum_radius**2
    # a thin plate: I_p close to 2 I_d (minus the thickness term)
    assert clutch.polar_inertia_kg_m2 == pytest.approx(
        2 * (clutch.diametral_inertia_kg_m2 - clutch.mass_kg * p.thickness**2 / 12), rel=1e-6)
    assert [q.spins for q in rot.parts] == ["crank", "drum", "drum", "drum"]
    # a thicker part is heavier in proportion
    _, rot2 = sh.concept_rotor("concept4", p.model_copy(update={"thickness": 2 * p.thickness}))
    assert rot2.parts[0].mass_kg == pytest.approx(2 * clutch.mass_kg, rel=1e-9)


def test_crankshaft_whirl_gyroscopic_ordering_and_fe_check(rotor4):
    _, rot = rotor4
    res = {g: sh.crankshaft_whirl(rot, gyroscopic=g) for g in ("engaged", "drum_held", "none")}
    # forward whirl: more spinning I_p -> lower J_eff -> higher critical speed
    assert (res["engaged"].effective_rotary_inertia_kg_m2
            < res["drum_held"].effective_rotary_inertia_kg_m2
            < res["none"].effective_rotary_inertia_kg_m2)
    assert res["engaged"].rpm_crit > res["drum_held"].rpm_crit > res["none"].rpm_crit
    for r in res.values():
        assert r.fe_rpm_crit == pytest.approx(r.rpm_crit, rel=1e-5)
        assert r.margin == pytest.approx(r.rpm_crit / r.max_rpm - 1)
        assert r.omega_crit_rad_s == pytest.approx(r.rpm_crit * 2 * math.pi / 60)
        assert r.overhang_m == pytest.approx(rot.cg_m)
        assert "rpm" in r.summary()


def test_crankshaft_whirl_against_a_rigid_rotor_on_a_massless_shaft():
    """Heavy rotor with no rotary inertia on a light shaft: the static stiffness of the
    pinned-overhung beam at the tip, 3 EI / (a^2 (l + a)), gives omega^2 = k / m."""
    lay = replace(sh.CHAINSAW_LAYOUT, rho=1.0)  # near-massless shaft (parts carry mass)
    part = sh.RigidPart("m", 5.0, 0.0, 0.0, 0.03, "crank", "test")
    r = sh.crankshaft_whirl(sh.Rotor((part,)), lay, gyroscopic="none")
    d, l, a = lay.shaft_diameter_m, lay.bearing_span_m, 0.03
    k = 3 * lay.E * math.pi * d**4 / 64 / (a * a * (l + a))
    assert r.omega_crit_rad_s == pytest.approx(math.sqrt(k / 5.0), rel=1e-3)


def test_heavier_rotor_longer_overhang_lower_critical_speed(rotor4):
    _, rot = rotor4
    base = sh.crankshaft_whirl(rot)
    heavier = sh.Rotor(rot.parts + (_disc_part(0.3, z=rot.cg_m + 0.02, spins="drum"),))
    assert sh.crankshaft_whirl(heavier).rpm_crit < base.rpm_crit
    thin = sh.crankshaft_whirl(rot, replace(sh.CHAINSAW_LAYOUT, shaft_diameter_m=0.010))
    assert thin.rpm_crit < base.rpm_crit


def test_whirl_records(records):
    w = {k: r for k, r in records.items() if k.startswith("shaft.whirl.concept4.")}
    assert {k.rsplit(".", 1)[1] for k in w} == {
        "clutch_mass", "clutch_Ip", "clutch_Id", "drum_sprocket_mass", "drum_sprocket_Ip",
        "overhang", "rpm_crit", "rpm_crit_drum_held", "rpm_crit_no_gyro", "margin"}
    assert all(r.status == "computed" and r.unit for r in w.values())
    lowest = min(w[f"shaft.whirl.concept4.{k}"].computed
                 for k in ("rpm_crit", "rpm_crit_drum_held", "rpm_crit_no_gyro"))
    assert w["shaft.whirl.concept4.margin"].computed == pytest.approx(
        100 * (lowest / sh.CHAINSAW_LAYOUT.max_rpm - 1))
    other = sh.whirl_records("concept1")
    assert other[0].id == "shaft.whirl.concept1.clutch_mass"
    assert other[0].computed != w["shaft.whirl.concept4.clutch_mass"].computed


@pytest.mark.parametrize("kwargs", [
    {"shaft_diameter_m": 0.0},
    {"bearing_span_m": float("inf")},
    {"E": 0.0},
    {"rho": -7850.0},
    {"max_rpm": 0.0},
])
def test_whirl_bad_input(kwargs, rotor4):
    with pytest.raises(ParameterError):
        sh.crankshaft_whirl(rotor4[1], replace(sh.CHAINSAW_LAYOUT, **kwargs))


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
