"""The 3-D model's field output (issue 20): tetra10 cells in VTK's node order (checked against
scikit-fem's edges and by the volume ParaView's reader computes from them), the half model
mirrored to the full thickness with the odd fields flipped, the sector rotated into the ring,
SI-named fields whose unaveraged peak is the 3-D sweep's, read back by meshio and pyvista."""

from __future__ import annotations

import json

import meshio
import numpy as np
import pytest

import clutchfem as cf
from clutchfem.fe import CELL_EDGES, Frames3D, tetra10_cells, write_vtk

COARSE = cf.MeshSettings(size="3mm", flexure_factor=1.0, contact_factor=0.5, fillet_factor=1.0)
RPMS = (4000.0, 9000.0)


@pytest.fixture(scope="module")
def solved():
    d = cf.Design.from_concept("concept4", formulation="3d", layers=1, mesh=COARSE)
    return d, d.sweep(list(RPMS))


@pytest.fixture(scope="module")
def written(solved, tmp_path_factory):
    d, res = solved
    out = tmp_path_factory.mktemp("vtu3d")
    return write_vtk(res, RPMS, out, stem="c4", cm=d.cm)


@pytest.mark.slow
def test_tetra10_order_is_scikit_fems_edges(solved):
    """Each mid-edge node of a cell is the scikit-fem dof of the edge joining VTK's corner pair:
    on a straight (vertical) edge exactly its midpoint, on a curved one within its sagitta;
    a wrong order puts it about half an edge away."""
    d, _ = solved
    pts, cells = tetra10_cells(d.model.basis)
    assert cells.shape == (d.model.em.mesh.t.shape[1], 10) and len(np.unique(cells)) == len(pts)
    n_vertical = 0
    for k, (a, b) in enumerate(CELL_EDGES[4]):
        mid = 0.5 * (pts[cells[:, a]] + pts[cells[:, b]])
        length = np.linalg.norm(pts[cells[:, a]] - pts[cells[:, b]], axis=1)
        off = np.linalg.norm(pts[cells[:, 4 + k]] - mid, axis=1)
        assert np.all(off <= 0.15 * length)  # sagitta of short curved edges on this coarse mesh: <= 0.09
        vertical = np.all(np.abs(pts[cells[:, a], :2] - pts[cells[:, b], :2]) <= 1e-15, axis=1)  # (round-off of the map)
        n_vertical += int(vertical.sum())
        np.testing.assert_allclose(off[vertical], 0.0, atol=1e-15)
    assert n_vertical >= len(cells)  # the extruded prisms' vertical edges, one or more a cell
    # a wrong order (e.g. gmsh's, edges 13 and 23 swapped) is far off: the check can fail
    wrong = cells[:, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]]
    off = np.linalg.norm(pts[wrong[:, 8]] - 0.5 * (pts[wrong[:, 1]] + pts[wrong[:, 3]]), axis=1)
    assert np.median(off / np.linalg.norm(pts[wrong[:, 1]] - pts[wrong[:, 3]], axis=1)) > 0.3


@pytest.mark.slow
def test_vtu_read_back_by_meshio_whole_part_full_thickness(solved, written):
    d, res = solved
    pvd, *vtus = written
    h = d.thickness
    for k, (rpm, f) in enumerate(zip(RPMS, vtus)):
        assert f.name == f"c4_fields_{int(rpm)}rpm.vtu"
        m = meshio.read(f)
        assert [c.type for c in m.cells] == ["tetra10"]
        assert set(m.point_data) == {"displacement_m", "sxx_Pa", "syy_Pa", "szz_Pa", "syz_Pa", "sxz_Pa", "sxy_Pa",
                                     "von_mises_Pa", "von_mises_max_Pa", "contact_pressure_Pa", "gap_m"}
        assert m.points[:, 2].min() == pytest.approx(-h / 2) and m.points[:, 2].max() == pytest.approx(h / 2)
        # no node twice (mid-plane and cut faces merged), every node in a cell
        assert len(np.unique(np.round(m.points / 1e-9), axis=0)) == len(m.points)
        assert len(np.unique(m.cells[0].data)) == len(m.points)
        cd = {n: v[0] for n, v in m.cell_data.items()}
        assert set(np.unique(cd["zone_id"])) == {0, 1, 2} and set(np.unique(cd["sector_id"])) == {0, 1, 2}
        assert set(np.unique(cd["half_id"])) == {0, 1}
        # the unaveraged peak is the 3-D sweep's; the averaged one is not above it
        vmax = m.point_data["von_mises_max_Pa"]
        peak = float(res.curve["max_von_mises_Pa"].iloc[k])
        assert vmax.max() == pytest.approx(peak, rel=1e-9)
        assert 0 < m.point_data["von_mises_Pa"].max() <= peak * (1 + 1e-9)
        u = m.point_data["displacement_m"]
        assert np.linalg.norm(u, axis=1).max() == pytest.approx(float(res.curve["max_displacement_m"].iloc[k]),
                                                                rel=1e-8)
        # mirror symmetry: u_x, u_y, s_zz even in z; u_z, s_yz, s_xz odd
        key = {tuple(p): i for i, p in enumerate(np.round(m.points / 1e-9).astype(np.int64).tolist())}
        up = np.nonzero(m.points[:, 2] > 1e-9)[0]
        img = np.array([key[tuple(np.round(m.points[i] * [1, 1, -1] / 1e-9).astype(np.int64).tolist())] for i in up])
        np.testing.assert_allclose(u[img, :2], u[up, :2], atol=1e-15)
        np.testing.assert_allclose(u[img, 2], -u[up, 2], atol=1e-15)
        assert np.abs(u[up, 2]).max() > 1e-9  # the face does move axially (Poisson)
        for name, sign in (("szz_Pa", 1), ("syz_Pa", -1), ("sxz_Pa", -1), ("von_mises_max_Pa", 1)):
            np.testing.assert_allclose(m.point_data[name][img], sign * m.point_data[name][up], atol=1e-6 * peak)
        p = m.point_data["contact_pressure_Pa"]
        assert (np.nan_to_num(p) > 0).any() == (float(res.curve["normal_force_N"].iloc[k]) > 0)


@pytest.mark.slow
def test_pvd_series_and_volume_in_pyvista(solved, written):
    """ParaView's reader opens the series (rpm as time); the cells' volume, which VTK computes
    from the tetra10 nodes in its own order, is the whole part's: a wrong mid-edge order
    would change it."""
    import pyvista as pv

    d, _ = solved
    reader = pv.get_reader(str(written[0]))
    assert reader.time_values == list(RPMS)
    reader.set_active_time_value(RPMS[-1])
    grid = reader.read()[0]
    assert grid.celltypes[0] == pv.CellType.QUADRATIC_TETRA
    vol = grid.compute_cell_sizes(length=False, area=False, volume=True).cell_data["Volume"]
    whole = float(d.model.basis.dx.sum()) * d.model.symmetry_factor * d.cm.sector_copies
    assert vol.min() > 0 and vol.sum() == pytest.approx(whole, rel=2e-3)


@pytest.mark.slow
def test_half_model_on_request(solved, tmp_path):
    d, res = solved
    fr = Frames3D(res, d.cm, full_thickness=False)
    m = fr.mesh(res.index(RPMS[0]))
    assert m.points[:, 2].min() == pytest.approx(0.0, abs=1e-12) and set(np.unique(fr.cell_data["half_id"][0])) == {0}
    assert m.point_data["von_mises_max_Pa"].max() == pytest.approx(float(res.curve["max_von_mises_Pa"].iloc[0]),
                                                                   rel=1e-9)


@pytest.mark.slow
def test_cli_solve_3d_vtk(tmp_path):
    """``solve --formulation 3d --vtk`` writes the .pvd and tetra10 .vtu files named after the
    design's label (listed as written) and says why there is no PNG; ``--set formulation=3d``
    is refused naming the option that sets it."""
    from typer.testing import CliRunner

    from clutchfem.cli import app

    r = CliRunner().invoke(app, ["solve", "concept4", "--formulation", "3d", "--layers", "1", "--mesh-size", "3mm",
                                 "--rpm", "4000,9000", "--vtk", "--no-errors", "--out", str(tmp_path)])
    assert r.exit_code == 0, r.output
    (res,) = tmp_path.glob("concept4-*_result.json")
    label = res.name.removesuffix("_result.json")
    doc = json.loads(res.read_text())
    assert doc["inputs"]["model"]["formulation"] == "3d"
    pvd = tmp_path / f"{label}_fields.pvd"
    assert pvd.name in r.output.replace("\n", "") and "no PNG" in r.output
    assert not list(tmp_path.glob("*.png"))
    for rpm, row in zip((4000, 9000), doc["curve"]):
        m = meshio.read(tmp_path / f"{label}_fields_{rpm}rpm.vtu")
        assert m.cells[0].type == "tetra10"
        assert m.point_data["von_mises_max_Pa"].max() == pytest.approx(row["max_von_mises_Pa"], rel=1e-9)
    bad = CliRunner().invoke(app, ["solve", "concept4", "--set", "formulation=3d", "--vtk"])
    assert bad.exit_code != 0 and "--formulation 3d" in bad.output and "Traceback" not in bad.output
