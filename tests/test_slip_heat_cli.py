"""``clutchfem slip-heat`` end to end on a coarse mesh: the JSON's keys and the relations
between them (heat into the part <= friction work; slip power = clutch torque x slip speed =
engine torque x slip speed at the slip point), the files in --out, answers for designs that
do not slip, and every hostile input refused clearly before any work."""

from __future__ import annotations

import json
import math
import os
import re
import signal
import subprocess
import sys
import time

import meshio
import numpy as np
import pytest
from typer.testing import CliRunner

from clutchfem.cli import app

MESH = ["--mesh-size", "2.5mm"]
SHORT = ["--seconds", "2", "--thermal", "steps_per_event=20"]
CLI = [sys.executable, "-m", "clutchfem.cli"]


def invoke(*args):
    return CliRunner().invoke(app, list(args), catch_exceptions=False)


def strict(text: str):
    def bad(c):
        raise ValueError(f"non-standard JSON constant {c}")
    return json.loads(text, parse_constant=bad)


def flat(text: str) -> str:
    return re.sub(r"\s+", " ", text)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("sh")
    r = invoke("slip-heat", "concept1", *MESH, "--seconds", "2", "--cycles", "2", "--pause", "3", "--thermal",
               "steps_per_event=20", "--json", "--out", str(out))
    assert r.exit_code == 0, r.output
    return strict(r.stdout), out


@pytest.mark.slow
def test_json_keys_and_their_relations(run):
    d, _ = run
    for k in ("seconds", "slip_rpm", "slip_power_W", "heat_into_part_J", "flexure_temperature_C",
              "peak_temperature_C", "ambient_temperature_C"):
        assert isinstance(d[k], (int, float)), k
    assert d["slip_status"] == "slips" and d["heat"] is True
    assert d["seconds"] == 2.0 and d["cycles"] == 2 and d["pause_s"] == 3.0
    w = d["slip_rpm"] * math.pi / 30
    # slip power: the clutch's FE torque x slip speed; at the slip point it is the engine's
    assert d["slip_power_W"] == pytest.approx(d["clutch_torque_Nm"] * w, rel=1e-12)
    assert d["clutch_torque_Nm"] == pytest.approx(d["engine_torque_at_slip_Nm"], rel=1e-4)
    assert d["friction_work_J"] == pytest.approx(d["slip_power_W"] * 2.0 * 2, rel=1e-12)
    assert 0 < d["heat_into_part_J"] <= d["friction_work_J"]
    assert d["heat_into_part_J"] == pytest.approx(d["heat_fraction_part"] * d["friction_work_J"], rel=1e-9)
    e = d["energy_J"]
    assert abs(e["stored_J"] - (e["input_J"] - e["lost_faces_J"] - e["lost_bore_J"] - e["lost_edges_J"])) \
        < 1e-9 * e["input_J"]
    assert d["ambient_temperature_C"] < d["flexure_temperature_C"] <= d["peak_temperature_C"]
    assert d["peak_temperature_C"] == pytest.approx(max(d["series"]["part_max_C"]))
    assert len(d["cycles_table"]) == 2
    # heat accumulates: the second event ends hotter than the first
    assert d["cycles_table"][1]["end_of_slip_part_max_C"] > d["cycles_table"][0]["end_of_slip_part_max_C"]
    assert d["inputs"]["concept"] == "concept1" and "flexure_thickness" in d["inputs"]["params"]
    assert d["inputs"]["thermal"]["environment"]["face_htc"] == 50.0
    assert d["inputs"]["thermal"]["scenario"]["steps_per_event"] == 20


@pytest.mark.slow
def test_files_in_out(run):
    d, out = run
    stem = d["label"] + "_slip_heat"
    assert sorted(p.name for p in out.iterdir()) == sorted(f"{stem}{s}" for s in
                                                           (".json", ".png", ".vtu", ".pvd", "_series"))
    assert strict((out / f"{stem}.json").read_text())["slip_rpm"] == d["slip_rpm"]
    m = meshio.read(out / f"{stem}.vtu")
    assert "triangle6" in m.cells_dict
    assert max(m.point_data["max_temperature_C"]) == pytest.approx(d["peak_temperature_C"], rel=1e-9)
    assert 10_000 < (out / f"{stem}.png").stat().st_size < 400_000


@pytest.mark.slow
def test_transient_time_series(run):
    """The transient is one .pvd time series ParaView opens (pyvista's reader): frames of the
    whole part from the start to the end of the run, each slip and pause end among them; the
    hottest node of the frame at the hottest moment is the run's peak (whole-part copies of
    the sector alike)."""
    import pyvista as pv

    d, out = run
    stem = d["label"] + "_slip_heat"
    reader = pv.get_reader(str(out / f"{stem}.pvd"))
    times = reader.time_values
    t = d["series"]["times_s"]
    assert times[0] == 0.0 and times[-1] == pytest.approx(t[-1], rel=1e-12)
    assert np.all(np.diff(times) > 0) and 10 <= len(times) <= 80
    peaks = []
    for tt in times:
        reader.set_active_time_value(tt)
        g = reader.read()[0]
        assert set(np.unique(g.cell_data["zone_id"])) <= {0, 1, 2}
        peaks.append(float(g.point_data["temperature_C"].max()))
        k = int(np.argmin(np.abs(np.array(t) - tt)))
        assert peaks[-1] == pytest.approx(d["series"]["part_max_C"][k], rel=1e-9)
    assert max(peaks) <= d["peak_temperature_C"] * (1 + 1e-12)
    for c in d["cycles_table"]:  # every slip event's end is a frame
        assert min(abs(np.array(peaks) - c["end_of_slip_part_max_C"])) < 1e-9 * c["end_of_slip_part_max_C"]


@pytest.mark.slow
def test_table_has_units():
    r = invoke("slip-heat", "concept4", *MESH, *SHORT)
    assert r.exit_code == 0, r.output
    t = flat(r.output)
    for s in ("rpm", " W ", " J ", " C ", " s ", "MPa", "N m"):
        assert s in t, s
    assert "slip speed" in t and "flexure" in t and "yield strength left" in t


@pytest.mark.slow
def test_thermal_settings_act():
    """--thermal changes what it says: more face cooling and a lower limit temperature."""
    base = strict(invoke("slip-heat", "concept4", *MESH, *SHORT, "--json").stdout)
    cool = strict(invoke("slip-heat", "concept4", *MESH, *SHORT, "--json", "--thermal", "face_htc=500",
                         "--thermal", "limit_temperature=100").stdout)
    assert cool["inputs"]["thermal"]["environment"]["face_htc"] == 500.0
    assert cool["energy_J"]["lost_faces_J"] > base["energy_J"]["lost_faces_J"]
    assert cool["limit_temperature_C"] == 100.0
    given = strict(invoke("slip-heat", "concept4", *MESH, *SHORT, "--json", "--heat-fraction", "0.5").output)
    assert given["heat_fraction_part"] == 0.5
    assert given["heat_into_part_J"] == pytest.approx(0.5 * given["friction_work_J"], rel=1e-12)


def test_list_thermal():
    r = invoke("slip-heat", "concept1", "--list-thermal")
    assert r.exit_code == 0
    t = flat(r.output)
    for s in ("part.conductivity", "drum.conductivity", "wall_thickness", "face_htc", "limit_temperature",
              "steps_per_event"):
        assert s in t, s


@pytest.mark.slow
@pytest.mark.parametrize("args,status,why", [
    (["--mu", "0"], "never holds", "mu = 0"),
    (["concept3"], "never engages", "never touch the drum"),
])
def test_designs_that_make_no_slip_heat_get_an_answer(args, status, why):
    """mu = 0: no torque, no heat; concept 3 at its defaults engages above 14000 rpm."""
    concept, args = (args[0], args[1:]) if args[0].startswith("concept") else ("concept4", args)
    r = invoke("slip-heat", concept, *MESH, *SHORT, *args, "--json")
    assert r.exit_code == 0, r.output
    d = strict(r.stdout)
    assert d["slip_status"] == status and d["heat"] is False
    assert d["slip_power_W"] == 0 and d["heat_into_part_J"] == 0
    assert d["peak_temperature_C"] is None and d["ambient_temperature_C"] == 25.0
    assert why in d["slip_note"]


def test_clutch_holding_at_the_curves_start_is_explained(tmp_path):
    eng = tmp_path / "eng.csv"
    eng.write_text("rpm,torque\n9000,3\n12000,2\n14000,1\n")
    r = invoke("slip-heat", "concept4", *MESH, *SHORT, "--engine", str(eng), "--out", str(tmp_path / "o"))
    assert r.exit_code == 0, r.output
    t = flat(r.output)
    assert "HOLDS AT START" in t and "starts lower" in t
    assert [p.suffix for p in (tmp_path / "o").iterdir()] == [".json"]  # no field without heat


def test_never_holds_slips_at_the_engine_maximum():
    d = strict(invoke("slip-heat", "concept4", *MESH, *SHORT, "--mu", "0.01", "--json").stdout)
    assert d["slip_status"] == "never holds" and d["slip_rpm"] == 14000.0 and d["heat"] is True
    assert d["clutch_torque_Nm"] < d["engine_torque_at_slip_Nm"]
    assert d["slip_power_W"] == pytest.approx(d["clutch_torque_Nm"] * 14000 * math.pi / 30, rel=1e-12)


@pytest.mark.parametrize("args,words", [
    (["--seconds", "-1"], ["--seconds", "seconds", "3600"]),
    (["--seconds", "nan"], ["--seconds"]),
    (["--cycles", "0"], ["--cycles", "1000"]),
    (["--cycles", "3"], ["--pause", "pause > 0"]),
    (["--cycles", "1000", "--pause", "36000"], ["200000 time steps"]),
    (["--thermal", "conductivity=10"], ["ambiguous", "part.conductivity", "drum.conductivity"]),
    (["--thermal", "bogus=1"], ["unknown", "face_htc"]),
    (["--thermal", "face_htc=-1"], ["face_htc", "W/(m^2 K)"]),
    (["--thermal", "limit_temperature=400mm"], ["limit_temperature", "a temperature in C"]),
    (["--thermal", "face_htc"], ["name=value"]),
    (["--thermal", "drum.wall_thickness=1km"], ["wall_thickness", "length"]),
    (["--seconds", "3", "--thermal", "seconds=4"], ["give it once"]),
    (["--heat-fraction", "1.5"], ["heat_fraction", "[0, 1]"]),
    (["--mu", "2"], ["mu"]),
    (["--model", "half"], ["'sector' or 'full'"]),
    (["--set", "bogus=1"], ["bogus"]),
])
def test_hostile_inputs_refused_before_work(args, words, tmp_path):
    t0 = time.perf_counter()
    r = invoke("slip-heat", "concept1", *MESH, *args, "--out", str(tmp_path / "o"))
    assert r.exit_code == 2, r.output
    t = flat(r.output)
    assert "Traceback" not in t and "error" in t
    for w in words:
        assert w in t, (w, t)
    assert time.perf_counter() - t0 < 5.0  # refused before meshing or solving
    assert not list((tmp_path / "o").iterdir())


def test_bad_out_folder_refused(tmp_path):
    f = tmp_path / "file"
    f.write_text("x")
    for out in (f, f / "sub"):
        r = invoke("slip-heat", "concept1", "--out", str(out))
        assert r.exit_code == 2 and "--out" in r.output


@pytest.mark.slow
@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_ctrl_c_stops_cleanly_and_writes_nothing(tmp_path):
    env = {**os.environ, "CLUTCHFEM_CACHE": str(tmp_path / "cache")}
    out = tmp_path / "o"
    proc = subprocess.Popen(CLI + ["slip-heat", "concept1", *MESH, "--cycles", "200", "--pause", "30", "--out",
                                   str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    # the run is past its meshing when the mesh's cache entry is written (it was a fixed 6 s
    # sleep): the interrupt comes in the slip speed and heat transient
    t0 = time.perf_counter()
    while not list((tmp_path / "cache" / "meshes").glob("concept1-*.json")) and time.perf_counter() - t0 < 120:
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.05)
    assert proc.poll() is None, "the run ended before the interrupt: make it longer"
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    # no file, no half file (on a loaded machine the interrupt may come before the folder is made)
    assert not out.exists() or not list(out.iterdir())


@pytest.mark.slow
def test_part_mean_temperature_is_the_heat_content():
    """The whole-part mean probe: (mean at the end - at the start) x rho c h A x (n_total /
    n_model) equals the stored energy of the independent energy tally (1e-9)."""
    from skfem import Basis, ElementTriP2, Functional

    import clutchfem as cf
    from clutchfem.thermal import ThermalMaterial

    run = cf.slip_heat(cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size=2.5e-3)),
                       scenario=cf.SlipScenario(seconds=2.0, cycles=2, pause=2.0, steps_per_event=20))
    doc, r, d = run.doc, run.result, run.design
    m = ThermalMaterial()
    area = Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(Basis(d.cm.mesh, ElementTriP2(), intorder=4))
    n = d.cm.n_shoes_total / d.cm.n_shoes_model
    heat = (r.part_mean_C[-1] - r.part_mean_C[0]) * m.density * m.specific_heat * d.thickness * area * n
    assert heat == pytest.approx(r.energy["stored_J"], rel=1e-9)
    assert doc["series"]["part_mean_C"][-1] == r.part_mean_C[-1]


@pytest.mark.slow
def test_a_folder_in_the_way_of_an_output_is_refused_and_nothing_written(tmp_path):
    out = tmp_path / "o"
    (out / "concept4_slip_heat.png").mkdir(parents=True)
    r = invoke("slip-heat", "concept4", "--seconds", "1", "--thermal", "steps_per_event=10", "--out", str(out))
    assert r.exit_code == 2 and "not a file" in flat(r.output) and "Traceback" not in r.output
    assert sorted(p.name for p in out.iterdir()) == ["concept4_slip_heat.png"]
