"""``analyze --mesh``: a user mesh gets every FE-direct answer; the analytical shoe model is
marked as not available.

Cross-check: the mesh that ``clutchfem geometry concept4 --model full`` writes, read back as a
user mesh, must give the same FE answers as the concept path on the same (full) model, and
answers close to the concept's default one-sector model.
"""

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from clutchfem.analysis import analyze
from clutchfem.core import ParameterError, get_material
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.loadcase import Design, OperatingPoint
from clutchfem.mesh import load_user_geometry, mesh_concept, mesh_mass_properties
from support.cli import cli_in_process
from support.shapes import load_annulus, load_cantilever

CLI = [sys.executable, "-m", "clutchfem.cli"]
SIZE = "0.002"
RPM = "0:14000:250"
#: FE-direct answers that must not depend on how the mesh reached the solver
FE_KEYS = ("engagement_rpm", "engagement_rpm_with_ripple", "engagement_rpm_with_ripple_typical", "slip_rpm",
           "torque_at_max_engine_torque_Nm", "torque_margin_Nm", "max_von_mises_Pa", "safety_factor",
           "slip_power_W", "contact_arc_at_max_engine_torque_deg")


def run(*args, ok=True):
    r = subprocess.run(CLI + list(args), capture_output=True, text=True, timeout=600)
    if ok:
        assert r.returncode == 0, r.stderr + r.stdout
    return r


@pytest.fixture(scope="module")
def c4():
    c = get_concept("concept4")
    return c, c.params()


@pytest.fixture(scope="module")
def c4_msh(tmp_path_factory, c4):
    out = tmp_path_factory.mktemp("c4")
    # in this process (support/cli.py): the file is the point, not the process
    cli_in_process("geometry", "concept4", "--out", str(out), "--model", "full", "--mesh-size", SIZE, "--no-drawing",
                   ok=True)
    (msh,) = out.glob("concept4-*.msh")  # named after the design's label (not the defaults: another mesh size)
    return msh


@pytest.fixture(scope="module")
def mesh_json(c4_msh, c4):
    _, p = c4
    r = run("analyze", "--mesh", str(c4_msh), "--drum-radius", repr(p.drum_radius), "--thickness",
            repr(p.thickness), "--rpm", RPM, "--json")
    return json.loads(r.stdout)


@pytest.fixture(scope="module")
def concept_full(c4):
    """The concept path (analytical coupling and all) on the full model, through the API.
    Without the error estimate: no test compares its bands, and the answers compared are the
    same with it (its refined mesh's solve was 1.5 of the 2.1 s CPU)."""
    c, p = c4
    cm = mesh_concept(c, p, MeshSettings(size=float(SIZE), model="full"))
    return analyze(Design(cm, OperatingPoint(material="51CrV4", rpm=RPM), params=p, name="concept4"), errors=False)


@pytest.mark.slow
def test_mesh_answers_equal_concept_path_on_the_same_mesh(mesh_json, concept_full):
    d, a = mesh_json, concept_full
    assert a.engagement_rpm is not None and a.slip_rpm is not None  # a real check, not None == None
    for k in FE_KEYS:
        assert d[k] == pytest.approx(getattr(a, k), rel=1e-6, abs=1e-9), k
    assert d["shoe_character"] == a.shoe_character == "minus"
    assert d["slip_status"] == a.slip_status
    # per shoe (contact_0..2 of the written mesh are used: three shoes, all alike)
    assert [s["shoe"] for s in d["shoe_character_per_shoe"]] == [0, 1, 2]
    for s, t in zip(d["shoe_character_per_shoe"], a.shoe_character_per_shoe):
        assert s["character"] == t["character"]
        assert s["normal_force_N"] == pytest.approx(t["normal_force_N"], rel=1e-6)
    for k in ("x0.7", "x1.0", "x1.3"):
        assert d["mu_sensitivity"]["torque_Nm"][k] == pytest.approx(a.mu_sensitivity["torque_Nm"][k], rel=1e-6)
        assert d["mu_sensitivity"]["slip_rpm"][k] == pytest.approx(a.mu_sensitivity["slip_rpm"][k], rel=1e-6)
    assert d["requirements"]["engagement_ok"] == a.requirements["engagement_ok"]
    assert d["requirements"]["slip_ok"] == a.requirements["slip_ok"]
    fe = np.array([r["fe_torque_Nm"] for r in d["curves"]])
    np.testing.assert_allclose(fe, a.curves["fe_torque_Nm"].to_numpy(), rtol=1e-6, atol=1e-9)


@pytest.mark.slow
def test_mesh_answers_close_to_default_sector_concept(mesh_json):
    """The concept's default one-sector model is a different mesh of the same part."""
    # in this process (support/cli.py): the answers are the point, not the process
    r = cli_in_process("analyze", "concept4", "--mesh-size", SIZE, "--rpm", RPM, "--json", ok=True)
    s = json.loads(r.stdout)
    for k in ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm", "max_von_mises_Pa"):
        assert mesh_json[k] == pytest.approx(s[k], rel=2e-3), k
    assert mesh_json["shoe_character"] == s["shoe_character"]


@pytest.mark.slow
def test_mesh_masses_match_occ_mass_properties(mesh_json, concept_full, c4):
    """Quadrature over the mesh vs OpenCASCADE's exact mass properties of the concept."""
    _, p = c4
    part = mesh_json["part"]
    rho = get_material("51CrV4").rho
    cm = mesh_concept(get_concept("concept4"), p, MeshSettings(size=float(SIZE), model="full"))
    assert part["mass_kg"] == pytest.approx(cm.mass["solid"]["area"] * rho * p.thickness, rel=1e-5)
    assert part["unbalance_kg_m"] < 1e-9  # three identical shoes at 120 deg: balanced
    assert len(part["shoes"]) == 3
    for s in part["shoes"]:
        assert s["mass_kg"] == pytest.approx(concept_full.coupling["m_kg"], rel=1e-5)
        assert s["R_Tp_m"] == pytest.approx(concept_full.coupling["R_Tp_m"], rel=1e-6)


@pytest.mark.slow
def test_mesh_analytical_marked_not_available(mesh_json, concept_full):
    d = mesh_json
    for k in ("engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm", "max_von_mises_Pa",
              "safety_factor", "shoe_character", "torque_margin_Nm", "slip_power_W", "mu_sensitivity",
              "requirements", "part", "analytical_available"):
        assert k in d, k
    assert d["analytical_available"] is False and concept_full.analytical_available is True
    assert all(r["analytic_fe_arc_Nm"] is None and r["analytic_nominal_arc_Nm"] is None for r in d["curves"])
    assert any("not available" in n for n in d["notes"])
    assert d["first_touch"] == "unknown" and d["first_touch_angle_deg"] is not None


@pytest.mark.slow
def test_mesh_table_and_out_files(c4_msh, c4, tmp_path):
    _, p = c4
    # in this process (support/cli.py): the table and the files are the point, not the process
    r = cli_in_process("analyze", "--mesh", str(c4_msh), "--drum-radius", repr(p.drum_radius), "--rpm",
                       "0:14000:1000", "--out", str(tmp_path), ok=True)
    assert "not available" in r.stdout and "part mass" in r.stdout and "Traceback" not in r.stderr
    # a user mesh's files carry the design hash (traceable, distinct from other designs)
    (js,) = tmp_path.glob("concept4-*_analysis.json")
    label = js.name.removesuffix("_analysis.json")
    assert json.loads(js.read_text())["inputs"]["mesh_sha256"]
    for f in ("_torque_rpm.png", "_arc_stress_rpm.png", "_curves.csv", "_analysis.json"):
        assert (tmp_path / (label + f)).stat().st_size > 100, f


@pytest.mark.slow
def test_thickness_scales_torque_not_speeds_or_stress(c4_msh, c4, concept_full):
    """Plane stress: stiffness, mass and contact force all scale with the thickness h, so
    engagement and stress do not depend on h and the torque is proportional to it."""
    _, p = c4
    # in this process (support/cli.py): the answers are the point; the JSON standard output of a
    # real `analyze --mesh` process is the mesh_json fixture's
    r = cli_in_process("analyze", "--mesh", str(c4_msh), "--drum-radius", repr(p.drum_radius), "--thickness",
                       repr(p.thickness / 2), "--rpm", RPM, "--json", ok=True)
    d = json.loads(r.stdout)
    a = concept_full
    assert d["engagement_rpm"] == pytest.approx(a.engagement_rpm, rel=1e-9)
    assert d["max_von_mises_Pa"] == pytest.approx(a.max_von_mises_Pa, rel=1e-6)
    assert d["torque_at_max_engine_torque_Nm"] == pytest.approx(a.torque_at_max_engine_torque_Nm / 2, rel=1e-6)
    assert d["part"]["mass_kg"] == pytest.approx(a.part["mass_kg"] / 2, rel=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize("args, needle", [
    ([], "--drum-radius"),
    (["--drum-radius", "-0.03"], "--drum-radius"),
    (["--drum-radius", "0.0344", "--thickness", "0"], "--thickness"),
    (["--drum-radius", "0.001"], "drum radius"),  # inside the part
    (["--drum-radius", "34.4"], "drum_radius"),  # millimetres for metres: beyond 1.5 x the contact radius
])
def test_mesh_bad_input_is_clear(c4_msh, args, needle):
    # in this process (support/cli.py): the refusal is the point, not the process
    r = cli_in_process("analyze", "--mesh", str(c4_msh), "--rpm", "0:14000:2000", *args)
    assert r.returncode == 2, r.stdout + r.stderr
    assert needle in r.stderr and "Traceback" not in r.stderr


@pytest.mark.slow
def test_concept_and_mesh_options_do_not_mix(c4_msh):
    run = cli_in_process  # in this process (support/cli.py): the refusals are the point
    r = run("analyze", "concept4", "--drum-radius", "0.035")
    assert r.returncode == 2 and "--set drum_radius" in r.stderr
    r = run("analyze", "concept4", "--mesh", str(c4_msh), "--drum-radius", "0.035")
    assert r.returncode == 2 and "exactly one" in r.stderr
    r = run("analyze")
    assert r.returncode == 2 and "exactly one" in r.stderr


def test_mesh_without_contact_group_is_clear(tmp_path):
    load_cantilever(tmp_path / "beam.msh", 0.03, 0.004, 0.002, depth=0.011)
    r = cli_in_process("analyze", "--mesh", str(tmp_path / "beam.msh"), "--drum-radius", "0.04")
    assert r.returncode == 2 and "'contact'" in r.stderr and "Traceback" not in r.stderr


@pytest.mark.slow
def test_api_user_mesh_needs_drum_radius(c4_msh):
    cm = load_user_geometry(c4_msh, thickness=0.011)
    with pytest.raises(ParameterError, match="drum_radius"):
        analyze(Design(cm, OperatingPoint(material="51CrV4")))
    with pytest.raises(ParameterError, match="thickness"):
        Design(cm, OperatingPoint(material="51CrV4", drum_radius=0.0344, thickness=-1.0))


def test_mesh_mass_properties_hand_values(tmp_path):
    rho, h = 7850.0, 0.011
    a, b = 0.01, 0.03
    ring = mesh_mass_properties(load_annulus(tmp_path / "ring.msh", a, b, 0.003, thickness=h), rho, h)
    assert ring["mass_kg"] == pytest.approx(math.pi * (b * b - a * a) * rho * h, rel=1e-5)
    assert ring["unbalance_kg_m"] < 1e-9 * ring["mass_kg"]
    assert "shoes" not in ring
    # a 30 deg sector of the same ring, scaled to the whole part (12 sectors)
    sec = mesh_mass_properties(load_annulus(tmp_path / "sec.msh", a, b, 0.003, thickness=h, sector_deg=30.0),
                               rho, h)
    assert sec["mass_kg"] == pytest.approx(ring["mass_kg"], rel=1e-5)
    assert "unbalance_kg_m" not in sec  # the centre of mass of a sector says nothing about the part
    # off-axis rectangle 30 mm x 4 mm, x in [0, 30 mm]: centre of mass at (15 mm, 0)
    bar = mesh_mass_properties(load_cantilever(tmp_path / "bar.msh", 0.03, 0.004, 0.002, depth=h), rho, h)
    m = 0.03 * 0.004 * rho * h
    assert bar["mass_kg"] == pytest.approx(m, rel=1e-12)
    assert bar["centroid_m"] == pytest.approx([0.015, 0.0], abs=1e-12)
    assert bar["unbalance_kg_m"] == pytest.approx(m * 0.015, rel=1e-12)
