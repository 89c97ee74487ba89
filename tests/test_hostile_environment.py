"""Issue 24: reading back its own folders and the environment. A truncated or Latin-1 run
folder, CLUTCHFEM_CACHE pointing to a file, XDG_CACHE_HOME ignored, a cache without bound,
one broken plug-in breaking every concept, API calls with a wrong type, refusals wrapped at
80 columns when standard error is not a terminal: each was a traceback or a wrong answer."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from clutchfem.analysis import analyze
from clutchfem.clutch import EngineCurve
from clutchfem.core import ClutchfemError, InputError, ParameterError, figure_record
from clutchfem.geometry import broken_concepts, concepts, get_concept
from clutchfem.geometry.registry import search_path
from clutchfem.loadcase import Design
from clutchfem.mesh import cache_dir, cache_entries, cache_limit, clear_cache, evict
from clutchfem.report import folder_page
from support.cli import cli_in_process

ROOT = Path(__file__).resolve().parents[1]


def _cli(*args, env=None, timeout=120):
    e = {**os.environ, "PYTHONPATH": str(ROOT / "src"), **(env or {})}
    return subprocess.run([sys.executable, "-m", "clutchfem.cli", *args], env=e, capture_output=True, text=True,
                          timeout=timeout)


# ---- the mesh cache --------------------------------------------------------------------
def test_cache_variable_pointing_to_a_file_is_refused_naming_it(tmp_path, monkeypatch):
    f = tmp_path / "afile"
    f.write_text("x")
    monkeypatch.setenv("CLUTCHFEM_CACHE", str(f))
    with pytest.raises(InputError, match=r"CLUTCHFEM_CACHE=.*afile: is a file, not a folder"):
        cache_dir()


def test_xdg_cache_home_is_honoured_when_clutchfem_cache_is_unset(tmp_path, monkeypatch):
    monkeypatch.delenv("CLUTCHFEM_CACHE", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cache_dir() == tmp_path / "xdg" / "clutchfem" / "meshes"


@pytest.mark.parametrize("raw", ["lots", "-5MB", "0", "5 parsecs", "1e9"])
def test_a_cache_size_that_is_no_size_is_refused(raw, monkeypatch):
    monkeypatch.setenv("CLUTCHFEM_CACHE_SIZE", raw)
    with pytest.raises(InputError, match="CLUTCHFEM_CACHE_SIZE"):
        cache_limit()


def test_the_cache_evicts_the_least_recently_used_entries_down_to_its_bound(tmp_path, monkeypatch):
    monkeypatch.setenv("CLUTCHFEM_CACHE", str(tmp_path))
    d = cache_dir()

    def entry(i):  # an entry's name: <concept>-<24 hex digits of its key>
        return f"concept1-{i:024x}"

    old = time.time() - 3600
    for i in range(10):  # 10 entries of 100 kB, entry i last used i minutes after `old`
        for suffix, size in ((".msh", 90_000), (".json", 5_000), (".groups.msh", 5_000)):
            p = d / f"{entry(i)}{suffix}"
            p.write_bytes(b"x" * size)
            os.utime(p, (old + 60 * i, old + 60 * i))
    assert len(cache_entries(d)) == 10 and sum(e.size for e in cache_entries(d)) == 1_000_000
    assert evict(2_000_000, d) == (0, 0)  # under the bound: nothing goes
    n, freed = evict(500_000, d)  # down to 80 % of the bound, oldest first
    left = [e.name for e in cache_entries(d)]
    assert (n, freed) == (6, 600_000) and left == [entry(i) for i in (6, 7, 8, 9)]
    (d / f"{entry(10)}.json").write_text("{}")  # used now: never evicted, even over the bound
    assert entry(10) in [e.name for e in cache_entries(d)] and evict(1, d)[0] == 4
    assert [e.name for e in cache_entries(d)] == [entry(10)]
    assert clear_cache(d)[0] == 1 and cache_entries(d) == []


MESH_ONE = """
import json, sys
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.mesh import mesh_concept
print("started", flush=True)
c = get_concept("concept1")
cm = mesh_concept(c, c.params(flexure_thickness=1.95e-3), MeshSettings(size=4e-3))
print(json.dumps({"cached": cm.cached, "n": cm.n_elements}), flush=True)
"""


@pytest.mark.slow
def test_two_processes_meshing_one_design_at_once_mesh_it_once(tmp_path):
    """The test suite's workers (and a study's) share one cache: two processes that ask for
    the same design while its entry is locked both wait; then one meshes it and the other
    reads its files (without the entry lock both would mesh, each in its own files)."""
    from clutchfem.geometry import MeshSettings
    from clutchfem.mesh import cache_key
    from clutchfem.mesh.cache import entry_lock

    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "CLUTCHFEM_CACHE": str(tmp_path)}
    c = get_concept("concept1")
    name = f"concept1-{cache_key(c, c.params(flexure_thickness=1.95e-3), MeshSettings(size=4e-3))}"
    with entry_lock(cache_dir_of(tmp_path), name):
        procs = [subprocess.Popen([sys.executable, "-c", MESH_ONE], env=env, stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, text=True) for _ in range(2)]
        for p in procs:
            assert p.stdout.readline().strip() == "started", p.communicate()
        # both are now blocked on the entry's lock: seen in the kernel's lock table (it was a
        # fixed 1 s sleep, assumed long enough)
        lock = cache_dir_of(tmp_path) / ".locks" / f"{name}.lock"
        assert _blocked_on(lock, {p.pid for p in procs}), "the two processes never waited at the entry's lock"
        assert not list(cache_dir_of(tmp_path).glob("concept1-*.msh"))
    outs = []
    for p in procs:
        out, err = p.communicate(timeout=120)
        assert p.returncode == 0, err
        outs.append(json.loads(out.splitlines()[-1]))
    assert sorted(o["cached"] for o in outs) == [False, True]  # meshed once, read once
    assert outs[0]["n"] == outs[1]["n"]
    assert len(cache_entries(cache_dir_of(tmp_path))) == 1


def _blocked_on(lock: Path, pids: set[int], timeout: float = 60.0) -> bool:
    """Wait until every process of ``pids`` is blocked on the ``flock`` of file ``lock``
    (``/proc/locks``: a waiter is a ``->`` line with its pid and the file's inode)."""
    t0 = time.time()
    while time.time() - t0 < timeout:
        if lock.exists():
            ino = f":{lock.stat().st_ino} "
            waiting = {int(f[5]) for f in (line.split() for line in Path("/proc/locks").read_text().splitlines())
                       if len(f) > 6 and f[1] == "->" and f":{f[6].rsplit(':', 1)[-1]} " == ino}
            if pids <= waiting:
                return True
        time.sleep(0.02)
    return False


def cache_dir_of(root: Path) -> Path:
    """The mesh folder of a cache whose CLUTCHFEM_CACHE is ``root``."""
    d = root / "meshes"
    d.mkdir(exist_ok=True)
    return d


@pytest.mark.slow
def test_cache_command_shows_and_clears_in_json(tmp_path):
    env = {"CLUTCHFEM_CACHE": str(tmp_path)}
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "concept1-0123456789abcdef01234567.msh").write_bytes(b"x" * 1000)
    (tmp_path / "meshes" / "concept1-0123456789abcdef01234567.json").write_text("{}")
    # in this process (support/cli.py): what the command says and does to the folder is the
    # point, not the process (three process starts were ~3 s)
    r = cli_in_process("cache", "--json", env=env)
    assert r.returncode == 0, r.stderr
    assert '"entries": 1' in r.stdout and str(tmp_path / "meshes") in r.stdout
    r = cli_in_process("cache", "--clear", "--json", env=env)
    assert r.returncode == 0 and '"entries": 0' in r.stdout and "deleted 1 cached meshes" in r.stderr
    # only the cache's own marker stays (it says whose folder this is)
    assert [p.name for p in (tmp_path / "meshes").iterdir()] == [".clutchfem-mesh-cache"]
    f = tmp_path / "afile"
    f.write_text("")
    r = cli_in_process("cache", env={"CLUTCHFEM_CACHE": str(f)})
    assert r.returncode != 0 and "Traceback" not in r.stderr and "is a file, not a folder" in r.stderr


# ---- one broken plug-in costs only itself --------------------------------------------------
@pytest.mark.parametrize("body, error", [
    ("raise ImportError('needs a module it lacks')", "ImportError: needs a module it lacks"),
    ("x = (", "SyntaxError"),
    ("import sys\nsys.exit(3)", "SystemExit"),
    ("CONCEPT = 42", ""),
    ("", ""),
])
def test_one_broken_plugin_costs_only_itself(body, error, tmp_path, monkeypatch):
    (tmp_path / "myconcept.py").write_text(body)
    monkeypatch.setenv("CLUTCHFEM_GEOMETRIES", str(tmp_path))
    assert tmp_path in search_path()
    names = concepts()
    assert "concept1" in names and get_concept("concept4").name == "concept4"
    broken = broken_concepts()
    assert list(broken) == [str(tmp_path / "myconcept.py")] and error in broken[str(tmp_path / "myconcept.py")]
    with pytest.raises(ParameterError, match="myconcept.py fails to load"):
        get_concept("myconcept")


# ---- reading back a run folder ---------------------------------------------------------
@pytest.mark.parametrize("name, content, words", [
    ("page.json", b'{"title": "x", "sec', "truncated: the text ends at line 1"),
    ("page.json", b"", "empty"),
    ("page.json", '{"title": "\xe9t\xe9"}'.encode("latin-1"), "not UTF-8 text (byte 0xe9"),
    ("page.json", b'[1, 2]', "not a page clutchfem wrote"),
    ("page.json", b'{"title": 1', "truncated"),
    ("inputs.json", b'{"concept": "concept1", ', "design inputs"),
    ("t.csv", b"a,b\n1,2\n3,4,5,6\n", "a row does not fit the header"),
    ("t.csv", b"", "empty (no header row)"),
])
def test_a_damaged_run_folder_is_refused_naming_the_file(name, content, words, tmp_path):
    (tmp_path / name).write_bytes(content)
    with pytest.raises(InputError) as e:
        folder_page(tmp_path)
    assert words in str(e.value) and name in str(e.value)


def test_a_latin1_csv_from_a_spreadsheet_is_read_as_its_text(tmp_path):
    (tmp_path / "t.csv").write_bytes("part,note\n1,\xe9t\xe9 \xb0C\n".encode("latin-1"))
    page = folder_page(tmp_path)
    (tab,) = [t for _, items in page.sections for t in items]
    assert tab.rows == [[1, "\xe9t\xe9 \xb0C"]]


# ---- the API with a wrong type ---------------------------------------------------------
@pytest.fixture(scope="module")
def d1():
    return Design.from_concept("concept1")


@pytest.mark.slow
@pytest.mark.parametrize("call, words", [
    (lambda d: analyze(d, engine="no-such-file.csv"), "engine curve file not found"),
    (lambda d: analyze(d, engine=3), "parameter 'engine' = 'int'"),
    (lambda d: analyze(d, engine={"rpm": [1, 2]}), "parameter 'engine' = 'dict'"),
    (lambda d: analyze(d, errors="no"), "parameter 'errors' = 'no'"),
    (lambda d: analyze(d, requirements=(1.3, 1.0)), "parameter 'requirements' = 'tuple'"),
    (lambda d: analyze("concept1"), "parameter 'design' = 'str'"),
    (lambda d: d.sweep("8000", mu="abc"), "parameter 'mu' = 'abc'"),
    (lambda d: d.sweep([8000], mu=2), "parameter 'mu' = 2"),
    (lambda d: d.sweep([8000], mu=float("nan")), "parameter 'mu'"),
    (lambda d: d.sweep("abc"), "rpm spec 'abc'"),
    (lambda d: d.sweep([8000], stresses="yes"), "parameter 'stresses' = 'yes'"),
    (lambda d: Design.from_mesh(5), "parameter 'path' = 'int'"),
    (lambda d: Design.from_mesh(""), "parameter 'path'"),
    (lambda d: EngineCurve("1,2", [1, 2]), "rpm and torque must be sequences of numbers"),
    (lambda d: EngineCurve.from_csv(None), "engine curve file: a path"),
])
def test_the_api_refuses_a_wrong_type_naming_the_argument(call, words, d1):
    with pytest.raises(ClutchfemError) as e:
        call(d1)
    assert words in str(e.value)


def test_a_string_speed_is_read_as_rpm(d1):
    assert list(d1.sweep("8000", stresses=False).rpm) == [8000.0]


# ---- refusals are one line when standard error is a file ------------------------------------
@pytest.mark.slow
def test_refusals_and_usage_errors_are_one_line_on_a_pipe():
    # in this process: support/cli.py's standard error is a text buffer, not a terminal, as a
    # pipe is not (test_cli.py checks that it says what the process says)
    r = cli_in_process("analyze", "concept1", "--mu", "7")
    lines = r.stderr.strip().splitlines()
    assert r.returncode != 0 and len(lines) == 1 and "a number in [0, 1]" in lines[0], r.stderr
    r = cli_in_process("analyze", "concept1", "--no-such-option")
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1 and lines[0].startswith("error: No such option: --no-such-option")


# ---- a headless machine ------------------------------------------------------------------
RENDER = """
import sys
from pathlib import Path
import meshio, numpy as np
from clutchfem.fe.vtu import render_png
pts = np.array([[0, 0, 0], [1e-2, 0, 0], [0, 1e-2, 0], [1e-2, 1e-2, 0]], float)
meshio.Mesh(pts, [("triangle", np.array([[0, 1, 2], [1, 3, 2]]))],
            point_data={"displacement_m": np.zeros((4, 3)), "von_mises_Pa": np.arange(4.0) * 1e6,
                        "von_mises_max_Pa": np.arange(4.0) * 1.5e6}).write(sys.argv[1])
print(render_png(Path(sys.argv[1]), Path(sys.argv[1]).with_suffix(".png")))
"""


@pytest.mark.slow
def test_a_render_on_a_headless_machine_prints_no_x_server_warning(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    env["PYTHONPATH"] = str(ROOT / "src")
    r = subprocess.run([sys.executable, "-c", RENDER, str(tmp_path / "f.vtu")], env=env, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "X server" not in r.stderr and "WARN" not in r.stderr, r.stderr
    if r.stdout.strip() == "None":
        pytest.skip("no off-screen OpenGL on this machine (the .vtu is still written)")
    assert (tmp_path / "f.png").stat().st_size > 1000
    rec = figure_record(tmp_path / "f.png")  # the colour bar reaches the tables' (unaveraged) peak, 4.5 MPa
    assert rec["peak_MPa"] == pytest.approx(4.5) and rec["colour_bar_MPa"][1] >= 4.5


# ---- progress on a terminal, never in --json standard output -------------------------------
@pytest.mark.slow
def test_a_single_design_command_shows_its_stages_on_a_terminal_and_keeps_json_clean(tmp_path):
    args = ("solve", "concept1", "--mesh-size", "3mm", "--rpm", "8000", "--no-errors", "--json")
    env = {"CLUTCHFEM_CACHE": str(tmp_path)}
    r = _cli(*args, env={**env, "FORCE_COLOR": "1"})  # rich takes stderr for a terminal
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)  # standard output is the JSON alone
    assert "solve concept1: meshing" in r.stderr and "solve concept1: 1 speed " in r.stderr
    # the first line, before the FE stack is loaded (BENCHMARKS section 19: its time to the screen)
    assert r.stderr.index("solve: loading the FE stack") < r.stderr.index("solve concept1: meshing")
    # standard error not a terminal, as a pipe is not: no spinner.  In this process (support/cli.py:
    # its standard error a text buffer, not a terminal): the process's own standard output, with
    # gmsh meshing in it, is the run above's (this one reads the mesh that run cached)
    piped = cli_in_process(*args, env=env)
    assert piped.returncode == 0 and "meshing" not in piped.stderr and "loading" not in piped.stderr
    assert json.loads(piped.stdout)
