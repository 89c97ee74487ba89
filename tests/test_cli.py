"""End-to-end tests of the command line."""

import json
import subprocess
import sys

import pytest

from support.cli import cli_in_process

CLI = [sys.executable, "-m", "clutchfem.cli"]


def run(*args, ok=True):
    r = subprocess.run(CLI + list(args), capture_output=True, text=True, timeout=600)
    if ok:
        assert r.returncode == 0, r.stderr + r.stdout
    return r


@pytest.mark.slow
def test_geometry_list_and_params():
    # in this process (support/cli.py): the lists printed are the point, not the process
    names = cli_in_process("geometry", "--list", ok=True).stdout.split()
    assert "concept1" in names
    out = cli_in_process("geometry", "concept1", "--list-params", ok=True).stdout
    assert "flexure_thickness" in out and "mm" in out


@pytest.mark.slow
def test_geometry_builds_files(tmp_path):
    # in this process (support/cli.py): the files are the point, not the process
    cli_in_process("geometry", "concept1", "--set", "flexure_thickness=1.8mm", "--out", str(tmp_path), "--mesh-size",
                   "0.002", ok=True)
    (msh,) = tmp_path.glob("concept1-*.msh")  # a design off the defaults: its label carries the hash
    assert msh.stat().st_size > 1000
    info = json.loads(msh.with_suffix(".json").read_text())
    assert info["params"]["flexure_thickness"] == pytest.approx(1.8e-3)


@pytest.mark.slow
def test_geometry_bad_parameter_is_clear(tmp_path):
    r = run("geometry", "concept1", "--set", "clearance=-1mm", "--out", str(tmp_path), ok=False)
    assert r.returncode == 2
    assert "clearance" in r.stderr and "Traceback" not in r.stderr
    # the tests' in-process runs (support/cli.py) say what the process says
    here = cli_in_process("geometry", "concept1", "--set", "clearance=-1mm", "--out", str(tmp_path))
    assert (here.returncode, here.stdout, here.stderr) == (r.returncode, r.stdout, r.stderr)


@pytest.mark.slow
def test_solve_json_contract(tmp_path):
    # in this process (support/cli.py): the document's keys and values are the point; that a
    # solve's --json standard output holds nothing else (gmsh writes to file descriptor 1) is
    # checked on a process that meshes, in test_hostile_environment.py
    r = cli_in_process("solve", "concept1", "--mesh-size", "0.002", "--rpm", "0:8000:2000", "--json", ok=True)
    d = json.loads(r.stdout)
    assert d["engagement_rpm"] is not None and 1000 < d["engagement_rpm"] < 8000
    recs = d["curve"]
    assert [x["rpm"] for x in recs] == [0, 2000, 4000, 6000, 8000]
    for k in ("rpm", "normal_force_N", "torque_Nm", "contact_arc_deg", "max_von_mises_Pa", "max_displacement_m"):
        assert k in recs[0]
    # torque grows with speed after engagement, zero before
    assert recs[0]["torque_Nm"] == 0 and recs[-1]["torque_Nm"] > recs[-2]["torque_Nm"] > 0


@pytest.mark.parametrize("args,word", [(["--rpm", "abc"], "rpm"), (["--rpm", "-5"], "rpm"),
                                       (["--mu", "-0.1"], "mu"), (["--drum-radius", "0.02"], "drum radius")])
def test_solve_bad_input(args, word):
    # in this process (support/cli.py): the refusal is the point, not the process
    r = cli_in_process("solve", "concept1", "--mesh-size", "0.002", *args)
    assert r.returncode == 2 and word in r.stderr and "Traceback" not in r.stderr


@pytest.mark.slow
def test_solve_vtk_series_of_the_whole_part(tmp_path):
    """--vtk writes one .pvd time series over the speeds (rpm as its time) that ParaView's
    reader (pyvista) opens: per speed a quadratic-triangle .vtu of the whole part (the sector
    rebuilt into the full ring, cut lines merged), named fields in SI units, zone ids;
    its displacement and unaveraged peak stress are the sweep table's; and one PNG of the
    field at the highest speed."""
    import meshio
    import numpy as np
    import pyvista as pv

    # in this process (support/cli.py): the files are the point, not the process
    cli_in_process("solve", "concept4", "--mesh-size", "0.002", "--rpm", "0:10000:2000", "--vtk",
                   "--vtk-rpm", "4000,10000", "--out", str(tmp_path), ok=True)
    (res,) = tmp_path.glob("concept4-*_result.json")  # every file named after the design's label
    label = res.name.removesuffix("_result.json")
    curve = {row["rpm"]: row for row in json.loads(res.read_text())["curve"]}
    reader = pv.get_reader(str(tmp_path / f"{label}_fields.pvd"))
    assert reader.time_values == [4000.0, 10000.0]
    for rpm in (4000, 10000):
        reader.set_active_time_value(float(rpm))
        grid = reader.read()[0]
        assert {"displacement_m", "sxx_Pa", "syy_Pa", "sxy_Pa", "von_mises_Pa", "von_mises_max_Pa",
                "contact_pressure_Pa", "gap_m"} <= set(grid.point_data.keys())
        assert set(np.unique(grid.cell_data["zone_id"])) == {0, 1, 2}  # hub, flexure, shoe
        assert set(np.unique(grid.cell_data["sector_id"])) == {0, 1, 2}  # three shoes: the whole part
        m = meshio.read(tmp_path / f"{label}_fields_{rpm}rpm.vtu")
        assert m.cells[0].type == "triangle6"
        used = np.unique(m.cells[0].data)
        assert len(used) == len(m.points)  # every P2 node belongs to an element
        # the copies share their cut-line nodes: no point twice
        assert len(np.unique(np.round(m.points[:, :2] / 1e-9), axis=0)) == len(m.points)
        ang = np.degrees(np.arctan2(m.points[:, 1], m.points[:, 0]))
        thirds = np.histogram(ang, bins=3, range=(-180, 180))[0]  # the ring all around, three alike
        assert thirds.min() > 0.9 * thirds.max()
        d = np.linalg.norm(m.point_data["displacement_m"], axis=1)
        assert d.max() == pytest.approx(curve[rpm]["max_displacement_m"], rel=1e-9)
        assert m.point_data["von_mises_max_Pa"].max() == pytest.approx(curve[rpm]["max_von_mises_Pa"], rel=1e-12)
        vm = m.point_data["von_mises_Pa"]
        assert np.all(np.isfinite(vm)) and 0 < vm.max() <= curve[rpm]["max_von_mises_Pa"] * (1 + 1e-9)
        press = m.point_data["contact_pressure_Pa"]
        assert (press > 0).any() == (curve[rpm]["normal_force_N"] > 0)
    assert (tmp_path / f"{label}_fields_10000rpm.png").stat().st_size > 10_000
    assert not (tmp_path / f"{label}_fields_4000rpm.png").exists()
