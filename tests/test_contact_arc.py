"""The contact arc between nodes (:mod:`clutchfem.contact.arc`): against a case whose arc is
known, exact where the contact reaches the end of the surface, and smooth in speed (no step
from one speed to the next larger than its stated error).

The known case: a ring segment (outer radius R1 = 30 mm, 10 mm wide, +-40 deg) sits in the
drum (R_d = 34.4 mm) with 0.5 um clearance on the x axis, clamped at its inner arc; spinning
pushes it into the drum.  A cylinder pressed into a cylindrical hole has Hertz's contact
half-width b = sqrt(4 P R_eff / (pi E*)) (P the force per unit length, 1/R_eff = 1/R1 -
1/R_d, E* = E in plane stress against a rigid drum), first order in b/R_eff: a mesh ten
times finer than the one tested here is within 0.6 % of it at b/R1 = 0.055 (8000 rpm).  A
soft material (E = 2 GPa) makes the arc span many nodes at moderate force.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import clutchfem as cf
from support.shapes import load_annulus, ring_segment_msh

R_D = 34.4e-3
R1 = 30e-3
CLEARANCE = 0.5e-6
#: Hertz's half-width is first order in b / R_eff: its own error, measured on a 10x finer mesh
HERTZ_MODEL = 0.01


@pytest.fixture(scope="module")
def segment(tmp_path_factory):
    path = ring_segment_msh(tmp_path_factory.mktemp("seg") / "segment.msh", R_D - CLEARANCE - R1, R1 - 10e-3, R1,
                            40.0, size=2e-3, contact_size=0.3e-3)
    return cf.Design.from_mesh(path, drum_radius=R_D, thickness=0.01, softening="off", mu=0.0,
                               material=cf.Material(name="soft", E=2e9))


def hertz_arc_deg(normal_force: float, thickness: float, E: float) -> float:
    r_eff = R1 * R_D / (R_D - R1)
    b = math.sqrt(4 * (normal_force / thickness) * r_eff / (math.pi * E))
    return math.degrees(2 * b / R_D)


@pytest.mark.slow
def test_ring_segment_arc_is_hertz(segment):
    """The arc of a ring segment pressed into the drum is Hertz's 2b / R_d within its stated
    error (plus Hertz's own first-order error), at every speed of a dense sweep; the ends lie
    symmetric about the x axis; a node count would be off by up to a node spacing."""
    r = segment.sweep(np.arange(1300.0, 8001.0, 50.0), stresses=False)
    E = segment.model.material.E
    c = r.curve
    touching = c["normal_force_N"] > 0
    assert touching.sum() > 100
    spacing = np.degrees(np.median(np.diff(np.sort(r.contact.nodes.angle))))
    worst = 0.0
    for _, row in c[touching].iterrows():
        known = hertz_arc_deg(row.normal_force_N, segment.thickness, E)
        err = row.contact_arc_error_deg
        assert err == pytest.approx(2 * 0.4 * spacing, rel=0.05)  # 0.4 node spacings per end
        assert abs(row.contact_arc_deg - known) <= err + HERTZ_MODEL * known, (row.rpm, row.contact_arc_deg, known)
        worst = max(worst, abs(row.contact_arc_deg - known) / err)
    print(f"\nring segment: arc within {worst:.2f} x its stated error of Hertz's ({spacing:.3f} deg node spacing)")
    ext = r.contact_extent(0)
    on = np.isfinite(ext[:, 0])
    assert np.allclose(ext[on, 0], -ext[on, 1], atol=float(np.max(ext[on, 2])))  # symmetric about the x axis


@pytest.mark.slow
def test_arc_smooth_in_speed(segment):
    """No step of the arc from one speed to the next exceeds its stated error, and, above 1.5 x
    the engagement speed (where Hertz's arc ~ sqrt(w^2 - w0^2) is smooth), halving the speed
    step halves the largest step (the arc is continuous in speed, not a staircase)."""
    steps = {}
    w0 = segment.case().engagement_rpm
    for step in (40.0, 20.0):
        r = segment.sweep(np.arange(1200.0, 6000.0 + 1e-9, step), stresses=False)
        arc, err = r.curve["contact_arc_deg"].to_numpy(), r.curve["contact_arc_error_deg"].to_numpy()
        on = arc > 0
        d = np.abs(np.diff(arc[on]))
        assert np.all(d <= np.minimum(err[on][1:], err[on][:-1])), d.max()
        far = r.rpm[on][1:] > 1.5 * w0
        steps[step] = d[far].max()
    print(f"\nlargest step of the arc above 1.5 x engagement: {steps}")
    assert steps[20.0] <= 0.6 * steps[40.0], steps


def test_arc_exact_where_contact_reaches_the_surface_end(tmp_path):
    """A spinning ring (one 30 deg sector of it) with a uniform clearance touches everywhere
    at once: 0 below engagement, exactly the whole sector (30 deg, error 0) above."""
    cm = load_annulus(tmp_path / "ring.msh", 10e-3, 30e-3, 4e-3, thickness=0.01, sector_deg=30.0,
                      drum_radius=30e-3 + 2e-6)
    d = cf.Design(cm, cf.OperatingPoint(softening="off", mu=0.0))
    w0 = d.case().engagement_rpm
    r = d.sweep([0.9 * w0, 1.1 * w0, 1.5 * w0], stresses=False)
    assert r.curve["contact_arc_deg"].tolist() == [0.0, pytest.approx(30.0, abs=1e-9), pytest.approx(30.0, abs=1e-9)]
    assert r.curve["contact_arc_error_deg"].tolist() == [0.0, 0.0, 0.0]


@pytest.mark.slow
def test_concept_arc_smooth_in_speed():
    """concept 1 (default mesh, 0.5 deg between contact nodes) every 25 rpm from engagement to
    9000 rpm: no step of the arc larger than its stated error (the node count steps by 2 of
    its ~0.4 deg error at once)."""
    d = cf.Design.from_concept("concept1")
    w0 = d.case().engagement_rpm
    r = d.sweep(np.arange(math.ceil(w0 / 25) * 25, 9000.0, 25.0), stresses=False)
    arc, err = r.curve["contact_arc_deg"].to_numpy(), r.curve["contact_arc_error_deg"].to_numpy()
    assert (arc > 0).all()
    assert np.abs(np.diff(arc)).max() <= 0.5 * err.min()
    nodes = r.curve["contact_nodes"].to_numpy()
    assert np.abs(np.diff(nodes)).max() >= 1  # the node count does step
