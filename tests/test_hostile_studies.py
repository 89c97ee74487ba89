"""Issue 24: study inputs (a negative seed, a design listed twice, a duplicate TOML key, a
--range for a parameter that is not free, LO > HI, contradictory targets, a tolerance below
the geometry's resolution) each refused at once naming what is wrong; and a rerun of a
finished study served without loading the FE stack (it took 4.7 s of the first run's 8.9 s)."""

from __future__ import annotations

import json
import os
import re
import sqlite3
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from clutchfem.cli import app
from clutchfem.core import InputError, ParameterError
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.geometry.registry import search_path
from clutchfem.loadcase import Design
from clutchfem.studies import SpecError, geometry_dirs, parse_spec
from clutchfem.targets import Targets
from clutchfem.targets.optimization import make_space
from clutchfem.tolerances import parse_tolerance, tolerance
from support.cli import cli_in_process

ROOT = Path(__file__).resolve().parents[1]
BASE = """
[design]
concept = "concept4"
[settings]
mesh_size = "3mm"
"""


def flat(text: str) -> str:
    return re.sub(r"\s+", " ", text)


@pytest.mark.parametrize("vary, words", [
    ('method = "lhs"\nsamples = 3\nseed = -1\n[vary.params]\nflexure_thickness = {min = "1.6mm", max = "1.9mm"}',
     "key 'vary.seed' = -1 is not allowed: an integer >= 0"),
    ('method = "list"\n[vary.params]\nflexure_thickness = {values = ["1.6mm", "1.7mm", "1.6mm"]}\n'
     'shoe_arc = {values = [80, 85, 80]}', "points 1 and 3 are the same design"),
    ('[vary.params]\nflexure_thickness = {values = ["1.6mm", "0.0016"]}', "a repeated value is the same design"),
])
def test_study_inputs_refused_naming_what_is_wrong(vary, words):
    with pytest.raises(SpecError) as e:
        parse_spec(BASE + "[vary]\n" + vary)
    assert words in flat(str(e.value))


def test_a_duplicate_toml_key_is_named():
    text = BASE + "mu = 0.2\nmu = 0.3\n[vary]\n[vary.params]\nflexure_thickness = {values = [\"1.6mm\"]}\n"
    with pytest.raises(InputError) as e:
        parse_spec(text)
    assert "key 'settings.mu' is given twice (line 7, first on line 6)" in str(e.value)


def test_search_ranges_refused_naming_the_parameter():
    P = get_concept("concept4").Params
    p0 = P()
    with pytest.raises(ParameterError, match="clearance is not free in this search"):
        make_space(P, ["flexure_thickness"], {"clearance": (0.4e-3, 0.8e-3)}, p0)
    with pytest.raises(ParameterError) as e:
        make_space(P, ["flexure_thickness"], {"flexure_thickness": (2e-3, 1e-3)}, p0)
    assert "LO < HI" in str(e.value) and "None" not in str(e.value)
    with pytest.raises(ParameterError, match="within the declared range"):
        make_space(P, ["flexure_thickness"], {"flexure_thickness": (0.1e-3, 1e-3)}, p0)


@pytest.mark.parametrize("lo, hi, slip, words", [(5000, None, 4000, "contradictory targets"),
                                                 (5000, None, 5000, "contradictory targets"),
                                                 (5000, 4000, None, "LO < HI")])
def test_contradictory_targets_are_refused_at_once(lo, hi, slip, words):
    with pytest.raises(ParameterError, match=words):
        Targets(lo, hi, slip, 1.5)


@pytest.mark.parametrize("text, ok", [("flexure_thickness=+-0.1um", False), ("flexure_thickness=+-4um", False),
                                      ("flexure_thickness=+-5um", True), ("shoe_arc=+-0.01deg", False),
                                      ("shoe_arc=+-0.1deg", True)])
def test_a_tolerance_below_the_resolution_is_refused(text, ok):
    P = get_concept("concept4").Params
    if ok:
        assert parse_tolerance(P, text)[1] > 0
    else:
        with pytest.raises(ParameterError, match="snapped to"):
            parse_tolerance(P, text)


@pytest.fixture(scope="module")
def c4():
    return Design.from_concept("concept4", mesh=MeshSettings(size=3e-3))


def test_api_refusals_of_seeds_tolerances_and_engine_targets(c4):
    with pytest.raises(ParameterError, match="'seed' = -1"):
        tolerance(c4, {"flexure_thickness": "0.05mm"}, seed=-1, workers=0)
    with pytest.raises(ParameterError, match="snapped to"):
        tolerance(c4, {"flexure_thickness": 1e-7}, workers=0)
    from clutchfem.targets import optimize

    with pytest.raises(ParameterError, match="top speed 14000 rpm"):
        optimize(c4, Targets(15000, None, 16000, 1.5), workers=0)


@pytest.mark.slow
@pytest.mark.parametrize("args", [["tolerance", "concept4", "--tol", "flexure_thickness=+-0.05mm", "--seed", "-1"],
                                  ["optimize", "concept4", "--engage-rpm", "5000:", "--slip-rpm-max", "4000"]])
def test_cli_refuses_before_meshing(args):
    r = CliRunner().invoke(app, args)
    assert r.exit_code == 2 and "Traceback" not in r.output, r.output
    assert "seed" in r.output or "contradictory" in flat(r.output)


def test_the_rerun_path_searches_the_registrys_folders():
    assert geometry_dirs() == search_path()


def _env() -> dict:
    paths = [str(ROOT / "src"), *filter(None, os.environ.get("PYTHONPATH", "").split(os.pathsep))]
    return {**os.environ, "PYTHONPATH": os.pathsep.join(paths), "OPENBLAS_NUM_THREADS": "1"}


PROBE = ("import sys\nfrom clutchfem.cli import app\nsys.argv = ['clutchfem', *sys.argv[1:]]\ntry:\n    app()\n"
         "except SystemExit:\n    pass\nprint('LOADED', [m for m in ('scipy', 'skfem', 'gmsh', 'matplotlib') "
         "if m in sys.modules], file=sys.stderr)\n")


def _study(spec: Path, out: Path, *extra: str, env: dict | None = None) -> tuple[dict, str]:
    r = subprocess.run([sys.executable, "-c", PROBE, "study", str(spec), "--out", str(out), "--json", *extra],
                       env={**_env(), **(env or {})}, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    return json.loads(r.stdout), r.stderr


def _study_here(spec: Path, out: Path, *extra: str, env: dict | None = None) -> dict:
    """The same command in this process: for the runs whose JSON is checked, not what they load."""
    return json.loads(cli_in_process("study", spec, "--out", out, "--json", *extra, env=env, ok=True).stdout)


@pytest.mark.slow
def test_a_rerun_of_a_finished_study_loads_no_fe_stack_and_resumes_when_anything_changed(tmp_path):
    spec = tmp_path / "s.toml"
    # a 6 mm mesh (BASE: 3 mm): what is checked is which runs compute and what they load, not
    # the answers; the five designs computed (two of them on the best path) cost half
    spec.write_text(BASE.replace('"3mm"', '"6mm"') + '[errors]\nsample = 0\n[vary]\n[vary.params]\n'
                    'flexure_thickness = {values = ["1.6mm", "1.7mm"]}\n')
    out = tmp_path / "out"
    # the runs whose JSON alone is checked run in this process (a process start and the FE
    # stack's imports each, ~2 s); the two whose imports are checked (LOADED) are processes
    first = _study_here(spec, out, "--no-charts")
    assert (first["computed"], first["ok"]) == (2, 2) and first["fingerprint"]
    again, err = _study(spec, out, "--no-charts")
    assert (again["computed"], again["skipped"], again["ok"]) == (0, 2, 2)
    assert again["scheduler"].startswith("nothing to compute")
    assert "LOADED []" in err  # no scipy, scikit-fem, gmsh or matplotlib
    # charts asked for but never drawn: the normal path (which draws them)
    assert not _study_here(spec, out)["scheduler"].startswith("nothing")
    # the spec changed (a comment): the normal path, which resumes (nothing to compute)
    spec.write_text(spec.read_text() + "# a comment\n")
    changed, err = _study(spec, out, "--no-charts")
    assert changed["computed"] == 0 and not changed["scheduler"].startswith("nothing") and "scipy" in err
    # a row deleted from the store: computed again
    with sqlite3.connect(out / "results.sqlite") as db:
        db.execute("DELETE FROM results WHERE rowid = (SELECT min(rowid) FROM results)")
    assert _study_here(spec, out, "--no-charts")["computed"] == 1
    # the session's default fidelity changed (the spec does not set it): the points are other
    # designs, computed, not served from the finished summary
    assert _study_here(spec, out, "--no-charts", env={"CLUTCHFEM_FIDELITY": "best"})["computed"] == 2
