"""Crankshaft whirl of a design (clutch/whirl.py): rigid parts and rotor, the critical speed
at the three gyroscopic readings, and the clutch's mass and inertia from the design's own
mesh (one sector completed by cyclic symmetry) against the OCC-exact full-part reference."""

from __future__ import annotations

import json
import math
from dataclasses import FrozenInstanceError, replace

import pytest

from clutchfem.clutch import crankshaft as W
from clutchfem.core import ParameterError
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.loadcase import Design, OperatingPoint
from clutchfem.mesh import mesh_area_properties, mesh_concept


@pytest.fixture(scope="module")
def design4():
    return Design.from_concept("concept4")


@pytest.fixture(scope="module")
def answer4(design4):
    return W.whirl(design4)


@pytest.fixture(scope="module")
def rotor4():
    return W.concept_rotor("concept4")


def _disc_part(m=0.1, r=0.03, h=0.01, z=0.02, spins="crank"):
    return W.RigidPart.ring("disc", 0.0, r, h, m / (math.pi * r * r * h), z, spins, "test")


def test_ring_part_inertias_closed_form():
    p = W.RigidPart.ring("r", 0.01, 0.03, 0.02, 7850.0, 0.0, "drum", "test")
    m = 7850.0 * math.pi * (0.03**2 - 0.01**2) * 0.02
    assert p.mass_kg == pytest.approx(m)
    assert p.polar_inertia_kg_m2 == pytest.approx(m * (0.01**2 + 0.03**2) / 2)
    assert p.diametral_inertia_kg_m2 == pytest.approx(m * ((0.01**2 + 0.03**2) / 4 + 0.02**2 / 12))
    with pytest.raises(ParameterError):
        W.RigidPart.ring("r", 0.03, 0.01, 0.02, 7850.0, 0.0, "drum", "test")
    with pytest.raises(ParameterError):  # I_p > 2 I_d is impossible for a rigid body
        W.RigidPart("x", 0.1, 3e-4, 1e-4, 0.02, "crank", "test")
    with pytest.raises(ParameterError):
        W.RigidPart("x", 0.1, 1e-4, 1e-4, 0.02, "wheel", "test")


def test_clutch_part_from_mass_properties_of_a_full_disc():
    # area properties of a disc of radius R per unit density and thickness (hand values)
    R, h, rho = 0.035, 0.011, 7850.0
    A = math.pi * R**2
    mass = {"solid": {"area": A, "centroid": (0.0, 0.0), "J_centroid": math.pi * R**4 / 2,
                      "Ixx_origin": math.pi * R**4 / 4, "Iyy_origin": math.pi * R**4 / 4}}
    p = W.clutch_part_from_mass_properties(mass, h, rho, 0.02, "test")
    m = rho * h * A
    assert p.mass_kg == pytest.approx(m)
    assert p.polar_inertia_kg_m2 == pytest.approx(m * R**2 / 2)
    assert p.diametral_inertia_kg_m2 == pytest.approx(m * (R**2 / 4 + h**2 / 12))
    assert p.spins == "crank"


def test_rotor_composite_properties():
    a, b = _disc_part(0.1, z=0.01), _disc_part(0.3, z=0.03, spins="drum")
    rot = W.Rotor((a, b))
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


@pytest.mark.slow
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
    _, rot2 = W.concept_rotor("concept4", p.model_copy(update={"thickness": 2 * p.thickness}))
    assert rot2.parts[0].mass_kg == pytest.approx(2 * clutch.mass_kg, rel=1e-9)


@pytest.mark.slow
def test_crankshaft_whirl_gyroscopic_ordering_and_fe_check(rotor4):
    _, rot = rotor4
    res = {g: W.crankshaft_whirl(rot, gyroscopic=g) for g in ("engaged", "drum_held", "none")}
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
    lay = replace(W.CHAINSAW_LAYOUT, rho=1.0)  # near-massless shaft (parts carry mass)
    part = W.RigidPart("m", 5.0, 0.0, 0.0, 0.03, "crank", "test")
    r = W.crankshaft_whirl(W.Rotor((part,)), lay, gyroscopic="none")
    d, l, a = lay.shaft_diameter_m, lay.bearing_span_m, 0.03
    k = 3 * lay.E * math.pi * d**4 / 64 / (a * a * (l + a))
    assert r.omega_crit_rad_s == pytest.approx(math.sqrt(k / 5.0), rel=1e-3)


@pytest.mark.slow
def test_heavier_rotor_longer_overhang_lower_critical_speed(rotor4):
    _, rot = rotor4
    base = W.crankshaft_whirl(rot)
    heavier = W.Rotor(rot.parts + (_disc_part(0.3, z=rot.cg_m + 0.02, spins="drum"),))
    assert W.crankshaft_whirl(heavier).rpm_crit < base.rpm_crit
    thin = W.crankshaft_whirl(rot, replace(W.CHAINSAW_LAYOUT, shaft_diameter_m=0.010))
    assert thin.rpm_crit < base.rpm_crit


@pytest.mark.slow
@pytest.mark.parametrize("kwargs", [
    {"shaft_diameter_m": 0.0},
    {"bearing_span_m": float("inf")},
    {"E": 0.0},
    {"rho": -7850.0},
    {"max_rpm": 0.0},
])
def test_whirl_bad_input(kwargs, rotor4):
    with pytest.raises(ParameterError):
        W.crankshaft_whirl(rotor4[1], replace(W.CHAINSAW_LAYOUT, **kwargs))


@pytest.mark.slow
def test_whirl_answer(answer4):
    """What the validation records of the whirl carried (clutch mass and inertias, drum and
    sprocket, overhang, three critical speeds, margin over the lowest), now fields of the
    design analysis's frozen answer."""
    d = answer4.to_json()
    assert {"clutch_mass_kg", "clutch_polar_inertia_kg_m2", "clutch_diametral_inertia_kg_m2",
            "drum_sprocket_mass_kg", "drum_sprocket_polar_inertia_kg_m2", "overhang_m",
            "rpm_crit_engaged", "rpm_crit_drum_held", "rpm_crit_no_gyro", "margin"} <= set(d)
    assert all(isinstance(v, float) and math.isfinite(v) for k, v in d.items() if k not in (
        "design", "lowest_reading", "mass_source", "assumptions"))
    json.dumps(d)
    lowest = min(answer4.rpm_crit_engaged, answer4.rpm_crit_drum_held, answer4.rpm_crit_no_gyro)
    assert answer4.rpm_crit_lowest == lowest
    assert answer4.reading(answer4.lowest_reading).rpm_crit == lowest
    assert answer4.margin == pytest.approx(lowest / W.CHAINSAW_LAYOUT.max_rpm - 1)
    assert answer4.max_engine_rpm == W.CHAINSAW_LAYOUT.max_rpm
    for g, key in (("engaged", "rpm_crit_engaged"), ("drum_held", "rpm_crit_drum_held"),
                   ("none", "rpm_crit_no_gyro")):
        assert answer4.reading(g).rpm_crit == d[key]
    assert answer4.design == "concept4" and "ASSUMED" in answer4.assumptions
    assert "cyclic symmetry" in answer4.mass_source and "rpm" in answer4.summary()
    with pytest.raises(ParameterError):
        answer4.reading("spinning")
    with pytest.raises(FrozenInstanceError):
        answer4.margin = 0.0
    other = W.whirl(Design.from_concept("concept1"))
    assert other.clutch_mass_kg != answer4.clutch_mass_kg


@pytest.mark.slow
@pytest.mark.parametrize("name", ["concept1", "concept4"])
@pytest.mark.parametrize("model", ["sector", "full"])
def test_whirl_from_the_mesh_equals_the_occ_reference(name, model):
    """The clutch's mass and inertia by quadrature over the design's own P2 mesh (default
    size; a sector completed by cyclic symmetry, a full model with its actual moments) equal
    the geometry module's OCC-exact values of the full part (measured: <= 4e-7), and so do
    the critical speeds; drum, sprocket and overhang follow the same layout."""
    ans = W.whirl(Design.from_concept(name, mesh=MeshSettings(model=model)))
    _, ref = W.concept_rotor(name)
    clutch = ref.parts[0]
    assert ans.clutch_mass_kg == pytest.approx(clutch.mass_kg, rel=1e-6)
    assert ans.clutch_polar_inertia_kg_m2 == pytest.approx(clutch.polar_inertia_kg_m2, rel=1e-6)
    assert ans.clutch_diametral_inertia_kg_m2 == pytest.approx(clutch.diametral_inertia_kg_m2, rel=1e-6)
    assert ans.clutch_Ixx_kg_m2 == pytest.approx(ans.clutch_Iyy_kg_m2, rel=1e-9)  # 3 shoes
    assert ans.rotor.parts[1:] == ref.parts[1:]
    assert ans.overhang_m == pytest.approx(ref.cg_m, rel=1e-6)
    for g in W.READINGS:
        assert ans.reading(g).rpm_crit == pytest.approx(W.crankshaft_whirl(ref, gyroscopic=g).rpm_crit,
                                                        rel=1e-6)


@pytest.mark.slow
def test_mesh_area_properties_of_two_shoes_sector_and_full():
    """Two shoes: the part is not axisymmetric in its second moments (I_xx != I_yy, I_xy != 0).
    The sector completed by its 180 deg copy equals the full mesh and the OCC-exact values of
    the full part (each moment, not only J)."""
    c = get_concept("concept1")
    p = c.params(n_shoes=2)
    ms = MeshSettings(size=1.5e-3, fillet_factor=0.3)
    sec = mesh_area_properties(mesh_concept(c, p, ms))
    full_cm = mesh_concept(c, p, ms.replace(model="full"))
    full, occ = mesh_area_properties(full_cm), full_cm.mass["solid"]
    assert abs(sec["Ixx_origin"] / sec["Iyy_origin"] - 1) > 0.02  # really anisotropic
    for k in ("area", "Ixx_origin", "Iyy_origin", "J_origin", "J_centroid"):
        assert sec[k] == pytest.approx(occ[k], rel=1e-6), k
        assert full[k] == pytest.approx(occ[k], rel=1e-6), k
    assert sec["Ixy_origin"] == pytest.approx(full["Ixy_origin"], rel=1e-5)
    assert max(map(abs, sec["centroid"])) < 1e-12 and max(map(abs, full["centroid"])) < 1e-9
    d = Design(full_cm, OperatingPoint(), params=p)
    ans = W.whirl(d)
    assert ans.clutch_diametral_inertia_kg_m2 == pytest.approx(
        0.5 * (ans.clutch_Ixx_kg_m2 + ans.clutch_Iyy_kg_m2))
    assert "differ by" in ans.assumptions


def test_mesh_area_properties_of_a_ring(tmp_path):
    """Ring a <= r <= b, full and as 12 sectors of 30 deg: A = pi (b^2 - a^2), J = pi (b^4 -
    a^4)/2, I_xx = I_yy = J/2 (cyclic symmetry), centroid on the axis."""
    from support.shapes import load_annulus

    a, b, h = 0.01, 0.03, 0.011
    area, J = math.pi * (b * b - a * a), math.pi * (b**4 - a**4) / 2
    for sector in (None, 30.0):
        cm = load_annulus(tmp_path / f"ring{sector}.msh", a, b, 0.003, thickness=h, sector_deg=sector)
        props = mesh_area_properties(cm)
        assert props["area"] == pytest.approx(area, rel=1e-5)
        assert props["J_origin"] == pytest.approx(J, rel=1e-5)
        assert props["Ixx_origin"] == pytest.approx(J / 2, rel=1e-5)
        assert props["Iyy_origin"] == pytest.approx(J / 2, rel=1e-5)
        assert abs(props["Ixy_origin"]) < 1e-9 * J
        assert math.hypot(*props["centroid"]) < 1e-9 * b


def test_whirl_refuses_bad_input(design4, answer4, tmp_path):
    from support.shapes import load_annulus

    with pytest.raises(ParameterError) as e:
        W.whirl("concept4")
    assert e.value.name == "design"
    ring = Design(load_annulus(tmp_path / "ring.msh", 0.01, 0.03, 0.004, thickness=0.011))
    with pytest.raises(ParameterError) as e:
        W.whirl(ring)
    assert e.value.name == "drum_radius"
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(ParameterError) as e:
            W.whirl(design4, max_rpm=bad)
        assert e.value.name == "max_rpm"
    # the engine's maximum speed moves the margin, not the critical speeds
    ans = W.whirl(design4, max_rpm=12000.0)
    assert ans.rpm_crit_lowest == answer4.rpm_crit_lowest
    assert ans.margin == pytest.approx(answer4.rpm_crit_lowest / 12000.0 - 1)
