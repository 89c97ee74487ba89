"""The thick plane model (issue 20): the 3-D answer of the extruded part from the 2-D mesh with
through-thickness modes, checked against the P2 tetrahedra of :class:`FEModel3D` on cases
that played no part in choosing it (its order and elements were chosen on concepts 1 and 4
at 4-16 mm; these are concept 2, 3 and 5 parts at other thicknesses, coarse meshes), and its
own limits: the plane-stress limit of a thin part and the symmetry of its operators.

Measured (``pytest -s`` prints them): engagement speed thick / 3-D - 1 within 0.1 %; the
3-D answers converge from above in layers, so the comparison uses 3 layers."""

from __future__ import annotations

import math

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.contact import contact_nodes
from clutchfem.core import get_material, rad_s_to_rpm
from clutchfem.fe import ExtrusionSettings, FEModel, FEModel3D, FEModelThick, ThickSettings, von_mises

STEEL = get_material("51CrV4")
COARSE = cf.MeshSettings(size="4mm", flexure_factor=0.6, contact_factor=0.5, fillet_factor=1.0)
#: the coarsest mesh the settings allow but for the contact surface, for the test of every step
#: of the best path running (not of its numbers): 282 elements of concept 1 against COARSE's
#: 645, 3.8 -> 1.0 s CPU for the analysis with its error estimate (a mesh already cached)
PIPELINE = cf.MeshSettings(size="10mm", flexure_factor=2.0, contact_factor=0.5, fillet_factor=2.0)


def free_engagement(model, nodes) -> float:
    """Engagement speed [rpm] of the free part (no softening): min over the contact nodes of
    sqrt(g0 / u1_n); the first 2-D dofs of a thick model are its mean displacement."""
    u = model.u1
    un = nodes.normal_displacement(u)
    ok = un > 0
    return rad_s_to_rpm(math.sqrt(float(np.min(nodes.gap0[ok] / un[ok]))))


#: concept 5 (beams *stretched* between the shoe and the cross, never engages below ~40 000
#: rpm) is the thick model's known miss: order 4 is 0.76 % stiffer than the 3-layer
#: tetrahedra at 14 mm (measured 2026-11-26: 129051 / 128081 rpm, plane stress 127451);
#: kept as a strict xfail so that a fix shows, and stated in THICK_RESIDUAL's note
CONCEPT5_MISS = pytest.mark.xfail(strict=True, reason="thick model 0.76 % stiff on the stretched beams of concept 5")


@pytest.mark.slow
@pytest.mark.parametrize("concept, thickness", [("concept2", 9e-3), pytest.param("concept5", 14e-3, marks=CONCEPT5_MISS),
                                                ("concept3", 11e-3)])
def test_thick_matches_3d_tetrahedra(concept, thickness):
    d = cf.Design.from_concept(concept, thickness=thickness, mesh=COARSE, fidelity="fast")
    cm, R = d.cm, d.drum_radius
    ps = FEModel(cm, STEEL, thickness)
    th = FEModelThick(cm, STEEL, thickness)
    t3 = FEModel3D(cm, STEEL, thickness, settings=ExtrusionSettings(layers=3))
    n2 = contact_nodes(ps, R)
    w_ps, w_th = free_engagement(ps, n2), free_engagement(th, contact_nodes(th, R))
    w_3d = free_engagement(t3, contact_nodes(t3, R))
    print(f"\n{concept} h = {thickness * 1e3:g} mm: engagement plane stress {w_ps:.1f}, thick {w_th:.1f}, "
          f"3-D (3 layers) {w_3d:.1f} rpm: thick / 3-D - 1 = {w_th / w_3d - 1:+.2e}, "
          f"3-D / plane stress - 1 = {w_3d / w_ps - 1:+.2e}")
    assert w_3d > w_ps  # the part is stiffer than plane stress ...
    assert abs(w_th / w_3d - 1) < 1e-3  # ... and the thick model finds how much
    assert abs(w_th / w_3d - 1) < 0.2 * (w_3d / w_ps - 1)


def test_thin_part_is_plane_stress_and_operators_are_symmetric():
    """At 1 mm the end restraint reaches over ~1 mm only: the thick model tends to plane
    stress (within 0.3 % here, 3-D to 2.2 % at 11 mm); K and M are symmetric, K is
    positive definite on the free dofs, and f1 is the 2-D one."""
    d = cf.Design.from_concept("concept4", thickness=2e-3, mesh=COARSE, fidelity="fast")
    cm, R = d.cm, d.drum_radius
    ps = FEModel(cm, STEEL, 2e-3)
    th = FEModelThick(cm, STEEL, 2e-3)
    n = contact_nodes(ps, R)
    w_ps, w_th = free_engagement(ps, n), free_engagement(th, contact_nodes(th, R))
    print(f"\nconcept4 h = 2 mm: engagement thick / plane stress - 1 = {w_th / w_ps - 1:+.2e}")
    assert 0 < w_th / w_ps - 1 < 3e-3
    K, M = th.K, th.M
    assert abs(K - K.T).max() <= 1e-9 * abs(K).max()
    assert abs(M - M.T).max() <= 1e-12 * abs(M).max()
    assert np.allclose(th.f1[: ps.ndofs], ps.f1, rtol=1e-12, atol=1e-12 * np.abs(ps.f1).max())
    assert not th.f1[ps.ndofs:].any()
    # order 2 is stiffer than order 4 (a subspace), both stiffer than plane stress
    th2 = FEModelThick(cm, STEEL, 2e-3, settings=ThickSettings(order=2))
    assert free_engagement(th2, contact_nodes(th2, R)) >= w_th - 1e-9


@pytest.mark.slow
def test_thick_stress_against_3d_at_the_fillet():
    """The thick model's 3-D stress at the governing fillet (mid-plane and free face) against
    the tetrahedra's, nodal values averaged over the elements sharing a point (raw vertex
    values of tetrahedra stretched 10:1 at a fillet scatter by several %): within 3 %."""
    d = cf.Design.from_concept("concept4", mesh=COARSE, fidelity="fast", drum_wall="2mm")
    r = {}
    for name, model in (("thick", FEModelThick(d.cm, STEEL, d.thickness)),
                        ("3d", FEModel3D(d.cm, STEEL, d.thickness, settings=ExtrusionSettings(layers=3)))):
        u = model.u1 * (1000.0 ** 2)
        s = model.stress(u)
        pts = model.stress.points
        key = np.round(pts / 1e-9).astype(np.int64)
        _, inv = np.unique(key, axis=1, return_inverse=True)
        inv = inv.ravel()
        cnt = np.bincount(inv)
        S = np.stack([np.bincount(inv, weights=s[i]) for i in range(6)]) / cnt
        vm = von_mises(S)
        first = np.zeros(len(cnt), dtype=np.int64)
        first[inv] = np.arange(len(inv))
        P = pts[:, first]
        k = int(np.argmax(vm))
        r[name] = (vm[k], P[:, k])
    print(f"\nfree spin at 1000 rad/s, peak averaged von Mises: thick {r['thick'][0] / 1e6:.1f} MPa at "
          f"{np.round(r['thick'][1] * 1e3, 2)} mm, 3-D {r['3d'][0] / 1e6:.1f} MPa at {np.round(r['3d'][1] * 1e3, 2)} mm")
    assert np.hypot(*(r["thick"][1][:2] - r["3d"][1][:2])) < 1e-3
    assert r["thick"][0] == pytest.approx(r["3d"][0], rel=0.03)


@pytest.mark.slow
def test_thick_runs_the_whole_analysis():
    """fidelity 'best' through analyze: the thick model, the elastic drum, the
    fatigue step on 6 stress components, the bands and the drum-wall sensitivity."""
    # few output speeds (the answers checked do not depend on them): 5.5 -> 4.9 s CPU
    d = cf.Design.from_concept("concept1", mesh=PIPELINE, fidelity="best", rpm="0:14000:3500")
    a = cf.analyze(d)
    assert a.inputs["model"]["formulation"] == "thick" and a.inputs["model"]["drum_wall_m"] == 0.002
    assert a.fatigue_safety_factor is not None and a.fatigue_safety_factor > 0
    e = a.errors["slip_rpm"]
    assert e["discretisation"] is not None and "thickness_3d_residual" in e["model_form_relative"]
    lo, hi = e["sensitivities"]["drum wall 1.5 / 2.5 mm"]
    assert lo != hi  # a stiffer drum changes the slip speed ...
    assert a.errors["engagement_rpm"]["sensitivities"]["drum wall 1.5 / 2.5 mm"] == pytest.approx([a.engagement_rpm] * 2, rel=1e-12)  # held: not w0


@pytest.mark.slow
def test_sweep_peak_reads_the_finite_measure_where_it_can_be():
    """The sweep's peak (ThickStress.finite_peak: the finite-rotation measure evaluated only
    on the elements near the small-strain peak) equals the measure's maximum over every
    stress point, value and place, at every speed of a sweep through contact."""
    d = cf.Design.from_concept("concept4", mesh=COARSE, fidelity="best")
    r = d.sweep("0:14000:1000")
    st = r.fields.stress
    U = r.fields.block(slice(0, r.fields.n))
    vm = st.von_mises(st(U, finite=True))
    assert np.array_equal(r.curve["max_von_mises_Pa"].to_numpy(), vm.max(axis=0))
    assert np.array_equal(r.curve["max_vm_x_m"].to_numpy(), st.points[0, vm.argmax(axis=0)])
    # and it is the cheap path: few elements are candidates (a guard would evaluate all)
    small = st.von_mises(r.fields.stresses(slice(0, r.fields.n)))
    top = small.max(axis=0)
    cand = np.any((small >= 0.8 * top) & (top > 0), axis=1)
    assert 0 < np.count_nonzero(cand) < 0.05 * small.shape[0]
