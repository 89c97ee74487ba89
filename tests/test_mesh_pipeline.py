"""Mesh pipeline: order-2 boundary tags survive import, user meshes accepted or refused clearly."""

from pathlib import Path

import gmsh
import numpy as np
import pytest
from skfem import Basis, ElementTriP0, Functional

from clutchfem.core import MeshError, ParameterError
from clutchfem.geometry import MeshSettings, get_concept, gmsh_session
from clutchfem.mesh import load_user_geometry, mesh_concept

COARSE = MeshSettings(size=2.0e-3)


def _annulus(path: Path, order=2, groups=("bore", "contact"), z=0.0, tilt=False):
    with gmsh_session("t"):
        occ = gmsh.model.occ
        outer = occ.addDisk(0, 0, z, 0.03, 0.03)
        inner = occ.addDisk(0, 0, z, 0.01, 0.01)
        out, _ = occ.cut([(2, outer)], [(2, inner)])
        if tilt:
            occ.rotate(out, 0, 0, 0, 1, 0, 0, 0.3)
        occ.synchronize()
        s = [t for d, t in out]
        curves = [abs(t) for d, t in gmsh.model.getBoundary(out, oriented=False)]
        r = {c: np.hypot(*gmsh.model.occ.getCenterOfMass(1, c)[:2]) for c in curves}
        gmsh.model.addPhysicalGroup(2, s, name="solid")
        lens = {c: gmsh.model.occ.getMass(1, c) for c in curves}
        small = min(curves, key=lambda c: lens[c])
        big = max(curves, key=lambda c: lens[c])
        if "bore" in groups:
            gmsh.model.addPhysicalGroup(1, [small], name="bore")
        if "contact" in groups:
            gmsh.model.addPhysicalGroup(1, [big], name="contact")
        if "inward_contact" in groups:
            gmsh.model.addPhysicalGroup(1, [small], name="contact")
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.004)
        gmsh.option.setNumber("Mesh.ElementOrder", order)
        gmsh.model.mesh.generate(2)
        gmsh.write(str(path))
        del r
    return path


def test_order2_boundary_tags_survive_import(tmp_path):
    cm = load_user_geometry(_annulus(tmp_path / "a.msh"), thickness=0.01)
    m = cm.mesh
    for name, radius in (("bore", 0.01), ("contact", 0.03)):
        f = cm.boundary(name)
        assert len(f) > 10
        ends = m.p[:, m.facets[:, f]]
        r = np.hypot(ends[0], ends[1])
        assert np.allclose(r, radius, rtol=1e-9)
    # the curved mid-edge nodes lie on the circle too (true P2 geometry)
    from skfem import ElementTriP2

    b = Basis(m, ElementTriP2())
    mid = b.doflocs[:, b.get_dofs(cm.boundary("contact")).facet["u"]]
    assert np.allclose(np.hypot(*mid), 0.03, rtol=1e-8)


def test_order1_user_mesh_is_lifted(tmp_path):
    cm = load_user_geometry(_annulus(tmp_path / "a1.msh", order=1), thickness=0.01)
    assert cm.mesh.t.shape[0] == 3 and len(cm.boundary("bore")) > 0


def test_user_mesh_without_bore_refused(tmp_path):
    with pytest.raises(MeshError, match="bore"):
        load_user_geometry(_annulus(tmp_path / "b.msh", groups=("contact",)), thickness=0.01)


def test_user_mesh_not_planar_refused(tmp_path):
    with pytest.raises(MeshError, match="not planar"):
        load_user_geometry(_annulus(tmp_path / "c.msh", tilt=True), thickness=0.01)


def test_inverted_elements_refused(tmp_path):
    import meshio

    p = _annulus(tmp_path / "d.msh", order=1)
    m = meshio.read(p)
    tri = m.cells_dict["triangle"]
    # fold one element over its neighbour: move one of its vertices across the opposite edge
    a, b_, c = tri[0]
    m.points[a, :2] = m.points[b_, :2] + m.points[c, :2] - m.points[a, :2]
    q = tmp_path / "d_bad.msh"
    meshio.write(q, m, file_format="gmsh22")
    with pytest.raises(MeshError, match="inverted|folded"):
        load_user_geometry(q, thickness=0.01)


def test_a_boundary_cell_that_is_no_triangle_edge_is_refused_naming_its_group(tmp_path):
    """A line cell of the 'contact' group joined to a node that shares no triangle edge with
    it (a broken export) is refused naming the group, not silently dropped."""
    import meshio

    p = _annulus(tmp_path / "f.msh", order=1)
    m = meshio.read(p)
    k = next(i for i, c in enumerate(m.cells) if c.type == "line" and np.hypot(*m.points[c.data[0, 0], :2]) > 0.02)
    inner = int(np.argmin(np.hypot(m.points[:, 0], m.points[:, 1]) + 1.0 * (np.hypot(m.points[:, 0], m.points[:, 1]) < 0.009)))
    m.cells[k].data[0, 1] = inner  # the outer circle's first segment now ends on the bore
    q = tmp_path / "f_bad.msh"
    meshio.write(q, m, file_format="gmsh22")
    with pytest.raises(MeshError, match="boundary group 'contact'"):
        load_user_geometry(q, thickness=0.01)


def test_user_mesh_without_triangles_or_unreadable_refused(tmp_path):
    import meshio

    m = meshio.read(_annulus(tmp_path / "e.msh", order=1))
    lines = meshio.Mesh(m.points, [("line", m.cells_dict["line"])],
                        cell_data={"gmsh:physical": [np.ones(len(m.cells_dict["line"]), dtype=int)],
                                   "gmsh:geometrical": [np.ones(len(m.cells_dict["line"]), dtype=int)]},
                        field_data={"bore": np.array([1, 1])})
    q = tmp_path / "lines_only.msh"
    meshio.write(q, lines, file_format="gmsh22")
    with pytest.raises(MeshError, match="no triangle elements"):
        load_user_geometry(q, thickness=0.01)
    junk = tmp_path / "junk.msh"
    junk.write_text("this is not a mesh\n")
    with pytest.raises(MeshError, match="cannot read"):
        load_user_geometry(junk)


@pytest.mark.slow
def test_concept_msh_with_groups_reimports_as_user_mesh():
    """The .msh that ``clutchfem geometry`` hands out (named physical groups) is a valid user
    mesh: re-imported through load_user_geometry it has the same nodes, elements, shoe
    subdomains and bore/contact boundaries as the generated model."""
    from clutchfem.mesh import groups_msh_path

    c = get_concept("concept4")
    p = c.params()
    cm = mesh_concept(c, p, MeshSettings(size=3e-3, model="full"))
    user = load_user_geometry(groups_msh_path(cm.msh_path), thickness=p.thickness, drum_radius=p.drum_radius)
    assert user.n_elements == cm.n_elements and user.n_nodes == cm.n_nodes
    for name in ("bore", "contact", "contact_0", "contact_2"):
        assert len(user.boundary(name)) == len(cm.boundary(name)) > 0, name

    assert np.array_equal(user.mesh.doflocs, cm.mesh.doflocs) and np.array_equal(user.mesh.t, cm.mesh.t)
    for i in range(3):  # element groups too (meshio keeps one physical tag per element: solid or shoe_i)
        assert np.array_equal(user.mesh.subdomains[f"shoe_{i}"], cm.mesh.subdomains[f"shoe_{i}"])


@pytest.mark.slow
def test_step_import_finds_bore_and_contact(tmp_path):
    """A STEP file from CAD (annulus 10-30 mm, drawn in mm as the file declares: gmsh writes
    OCC's millimetre) is meshed with P2 triangles in metres; the bore is the loop around the
    origin, the contact the outermost curves; area exact to 1e-6."""
    step = tmp_path / "ring.step"
    with gmsh_session("step-out"):
        occ = gmsh.model.occ
        occ.cut([(2, occ.addDisk(0, 0, 0, 30.0, 30.0))], [(2, occ.addDisk(0, 0, 0, 10.0, 10.0))])
        occ.synchronize()
        gmsh.write(str(step))
    cm = load_user_geometry(step, mesh_size=1.5e-3, thickness=0.01, drum_radius=0.0306)
    from skfem import ElementTriP2

    m = cm.mesh
    b = Basis(m, ElementTriP2())
    for name, radius in (("bore", 0.01), ("contact", 0.03)):
        xy = b.doflocs[:, b.get_dofs(cm.boundary(name)).all()]  # vertices and curved mid-edge nodes
        assert xy.shape[1] >= 2 * len(cm.boundary(name)) > 0
        assert np.allclose(np.hypot(*xy), radius, rtol=1e-8), name
    area = Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(Basis(m, ElementTriP0(), intorder=6))
    assert area == pytest.approx(np.pi * (0.03 ** 2 - 0.01 ** 2), rel=1e-6)


def test_missing_file_and_bad_suffix(tmp_path):
    with pytest.raises(MeshError, match="does not exist"):
        load_user_geometry(tmp_path / "nope.msh")
    f = tmp_path / "x.obj"
    f.write_text("x")
    with pytest.raises(MeshError, match="unsupported"):
        load_user_geometry(f)


def test_concept_mesh_area_matches_occ_and_is_cached():
    c = get_concept("concept1")
    p = c.params()
    cm = mesh_concept(c, p, COARSE)
    b = Basis(cm.mesh, ElementTriP0(), intorder=6)
    area = Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(b)
    assert abs(area / cm.mass["solid"]["area"] - 1) < 1e-6
    again = mesh_concept(c, p, COARSE)
    assert again.cached and again.n_elements == cm.n_elements


@pytest.mark.slow
@pytest.mark.parametrize("arrangement", ["minus", "plus"])
def test_sector_cut_nodes_match_and_sector_is_one_nth(arrangement):
    from scipy.spatial import cKDTree

    c = get_concept("concept1")
    p = c.params(arrangement=arrangement)
    sec = mesh_concept(c, p, COARSE)
    full = mesh_concept(c, p, MeshSettings(size=2.0e-3, model="full"))
    assert abs(sec.mass["solid"]["area"] * p.n_shoes / full.mass["solid"]["area"] - 1) < 1e-9
    m = sec.mesh
    pa = m.p[:, np.unique(m.facets[:, sec.boundary("cut_a")])]
    pb = m.p[:, np.unique(m.facets[:, sec.boundary("cut_b")])]
    a = sec.sector_angle
    rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]) @ pa
    d, _ = cKDTree(pb.T).query(rot.T)
    assert pa.shape == pb.shape and d.max() < 1e-9
    # minus is the mirror image of plus: shoe centroid below the x axis
    cy = sec.mass["shoe_0"]["centroid"][1]
    assert (cy < 0) == (arrangement == "minus")


def test_params_errors_name_parameter_and_range():
    c = get_concept("concept1")
    with pytest.raises(ParameterError, match=r"clearance.*\[0.05 mm, 3 mm\]"):
        c.params(clearance=0.0)
    with pytest.raises(ParameterError, match="shoe_arc"):
        c.params(shoe_arc=170.0)  # does not fit 3 shoes with flexure and gap
    with pytest.raises(ParameterError, match="unknown parameter"):
        c.params(bogus=1.0)
    with pytest.raises(ParameterError, match="fillet_radius"):
        c.params(fillet_radius=1.2e-3)  # larger than half the (2 mm) slot width
    p = c.Params.from_assignments(["flexure_thickness=1.8mm", "shoe_arc=70"])
    assert p.flexure_thickness == pytest.approx(1.8e-3) and p.shoe_arc == 70.0
    with pytest.raises(ParameterError, match="suffix"):
        c.Params.from_assignments(["flexure_thickness=1.8deg"])
