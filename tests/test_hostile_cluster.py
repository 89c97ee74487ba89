"""Issue 24: scheduler addresses and the faults of the distributed engine.  Every bad address
is refused at once naming what is wrong (it was a raw ValueError, or a hang past 60 s at an
HTTP port); no workers and a dead worker stop the study with the finished rows stored and
what to do (it waited silently until killed, or ended in a raw WorkerStartTimeoutError);
a locked store is waited for with a bound, then refused (raw OperationalError); worker
counts the machine cannot hold are capped and said (14 processes for --workers 12 on 2
cores, without a word)."""

from __future__ import annotations

import http.server
import os
import re
import signal
import socket
import sqlite3
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from clutchfem.cli import app
from clutchfem.core import InputError
from clutchfem.evaluation import (
    COLUMNS,
    ClusterError,
    ResultStore,
    StoreLocked,
    check_scheduler,
    run_points,
    workers_machine_holds,
)
from clutchfem.evaluation import cluster as cluster_mod
from clutchfem.evaluation import store as store_mod
from clutchfem.studies import parse_spec
from support.scheduler import scheduler_address

ROOT = Path(__file__).resolve().parents[1]
DASK = Path(sys.executable).with_name("dask")
#: the designs of the tests below: what they check is the engine's faults, refusals and rows, not
#: the answers (a 6 mm mesh: a design is ~0.6 s of CPU, 3 mm ~1.2 s)
TINY = """
[design]
concept = "concept4"
[settings]
mesh_size = "6mm"
[vary]
method = "grid"
[vary.params]
flexure_thickness = {min = "1.6mm", max = "1.9mm", steps = N}
"""


def flat(text: str) -> str:
    return re.sub(r"\s+", " ", text)


@pytest.mark.parametrize("address, words", [
    ("", "empty"), ("   ", "empty"), (None, "empty"),
    ("http://127.0.0.1:8787", "dashboard"), ("https://host:8787/status", "dashboard"),
    ("tcp://127.0.0.1:99999", "not a port number"), ("tcp://127.0.0.1:abc", "not a port number"),
    ("ucx://127.0.0.1:8786", "unknown protocol 'ucx'"), ("tcp://no-such-host.invalid:8786", "is not known"),
    ("tcp://exa mple:1", "not an address"), ("foo.invalid", "is not known"),
])
def test_bad_scheduler_addresses_are_refused_naming_what_is_wrong(address, words):
    with pytest.raises(InputError) as e:
        check_scheduler(address)
    assert words in str(e.value)


@pytest.mark.parametrize("address, form", [("tcp://127.0.0.1:8786", "tcp://127.0.0.1:8786"),
                                           ("127.0.0.1:8786", "tcp://127.0.0.1:8786"),
                                           ("127.0.0.1", "tcp://127.0.0.1:8786"),
                                           ("TCP://localhost:9000/", "tcp://localhost:9000"),
                                           ("tls://[::1]:8786", "tls://[::1]:8786")])
def test_good_addresses_in_daskss_form(address, form):
    assert check_scheduler(address) == form


@pytest.fixture
def http_port():
    srv = http.server.ThreadingHTTPServer(("127.0.0.1", 0), http.server.SimpleHTTPRequestHandler)
    th = threading.Thread(target=srv.serve_forever, daemon=True)
    th.start()
    yield srv.server_address[1]
    srv.shutdown()


@pytest.mark.slow
def test_an_http_server_or_a_silent_port_is_refused_within_seconds(http_port, monkeypatch):
    """The issue: --scheduler at a port where an HTTP server listens hung past 60 s."""
    # the greeting's wait cut short (the default, for a scheduler on a loaded network, is longer):
    # an HTTP server and a silent port never greet; a Dask scheduler's greeting is not waited for here
    monkeypatch.setattr(cluster_mod, "GREETING_S", 0.25)
    t0 = time.monotonic()
    with pytest.raises(InputError, match="an HTTP server"):
        cluster_mod.probe_scheduler(f"tcp://127.0.0.1:{http_port}")
    silent = socket.socket()
    silent.bind(("127.0.0.1", 0))
    silent.listen(1)
    try:
        with pytest.raises(InputError, match="did not greet as Dask does"):
            cluster_mod.probe_scheduler(f"tcp://127.0.0.1:{silent.getsockname()[1]}")
    finally:
        silent.close()
    free = socket.socket()
    free.bind(("127.0.0.1", 0))
    port = free.getsockname()[1]
    free.close()
    with pytest.raises(InputError, match="nothing listens there"):
        cluster_mod.probe_scheduler(f"tcp://127.0.0.1:{port}")
    assert time.monotonic() - t0 < 15


@pytest.mark.parametrize("cmd", [["study", "SPEC"], ["guidelines", "concept4"], ["optimize", "concept4"],
                                 ["tolerance", "concept4", "--tol", "flexure_thickness=+-0.05mm"]])
@pytest.mark.parametrize("address", ["", "http://127.0.0.1:8787", "foo.invalid"])
def test_every_command_refuses_a_bad_address_before_any_work(tmp_path, cmd, address):
    spec = tmp_path / "s.toml"
    spec.write_text(TINY.replace("N", "2"))
    args = [str(spec) if a == "SPEC" else a for a in cmd] + ["--scheduler", address, "--out", str(tmp_path / "o")]
    t0 = time.monotonic()
    r = CliRunner().invoke(app, args)
    assert r.exit_code == 2 and r.exception is None or isinstance(r.exception, SystemExit), r.output
    assert "Traceback" not in r.output and "--scheduler" in flat(r.output)
    assert time.monotonic() - t0 < 20  # refused before meshing or starting anything


def test_worker_counts_the_machine_cannot_hold_are_capped_and_said():
    cores = len(os.sched_getaffinity(0))
    n, why = workers_machine_holds(200)
    assert n <= cores and "--workers 200" in why and "core" in why
    n, why = workers_machine_holds(cores)
    assert (n, why) == (cores, None) or "GB available" in why  # a full machine: memory caps
    assert workers_machine_holds(None, points=1)[0] == 1  # never more workers than points


@pytest.mark.slow
def test_a_locked_store_is_waited_for_then_refused(tmp_path, monkeypatch, caplog):
    """A database browser left open ended the study in a raw OperationalError."""
    monkeypatch.setattr(store_mod, "LOCK_WAIT_S", 1.0)
    path = tmp_path / "results.sqlite"
    ResultStore(path, COLUMNS).close()
    other = sqlite3.connect(path, isolation_level=None)
    other.execute("BEGIN EXCLUSIVE")
    spec = parse_spec(TINY.replace("N", "2"))
    try:
        with pytest.raises(StoreLocked) as e:
            run_points(spec.points(), spec.settings, path, workers=0, progress=False)
        assert "locked by another program" in str(e.value) and "run the same command again" in str(e.value)
        assert any("waiting up to 1 s" in r.message for r in caplog.records)
    finally:
        other.execute("ROLLBACK")
        other.close()


@pytest.mark.slow
def test_a_handful_of_points_runs_in_process(tmp_path):
    """Small studies paid a cluster start (BENCHMARKS.md: the crossover)."""
    spec = parse_spec(TINY.replace("N", "2"))
    res = run_points(spec.points(), spec.settings, tmp_path / "r.sqlite", progress=False)
    assert res.ok == 2 and res.workers == 0 and res.scheduler.startswith("in process (2 point(s)")
    again = run_points(spec.points(), spec.settings, tmp_path / "r.sqlite", progress=False)
    assert (again.computed, again.skipped) == (0, 2)


def _env() -> dict:
    paths = [str(ROOT / "src"), *filter(None, os.environ.get("PYTHONPATH", "").split(os.pathsep))]
    return {**os.environ, "PYTHONPATH": os.pathsep.join(paths), "OPENBLAS_NUM_THREADS": "1"}


def _kill(p: subprocess.Popen) -> None:
    try:
        os.killpg(p.pid, signal.SIGKILL)  # the process group this test started (start_new_session)
    except ProcessLookupError:
        pass
    p.wait(timeout=30)


@pytest.fixture
def scheduler(tmp_path):
    f = tmp_path / "scheduler.json"
    log = open(tmp_path / "scheduler.log", "w")
    p = subprocess.Popen([str(DASK), "scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                          "--scheduler-file", str(f)], env=_env(), stdout=log, stderr=log, start_new_session=True)
    try:
        yield scheduler_address(f, p)
    finally:
        _kill(p)
        log.close()


@pytest.mark.slow
def test_no_workers_and_a_dead_worker_stop_the_study_with_the_rows_kept(tmp_path, scheduler, monkeypatch, caplog):
    monkeypatch.setattr(cluster_mod, "WAIT_WORKERS_S", 1.0)  # (the wall time of the test: twice this)
    spec = parse_spec(TINY.replace("N", "6"))
    store = tmp_path / "results.sqlite"
    with pytest.raises(ClusterError, match="has had no workers for 1 s"):
        run_points(spec.points(), spec.settings, store, scheduler=scheduler, progress=False)
    assert any("has no workers: waiting up to 1 s" in r.message for r in caplog.records)
    log = open(tmp_path / "worker.log", "w")
    worker = subprocess.Popen([str(DASK), "worker", scheduler, "--nthreads", "1", "--no-dashboard", "--host",
                               "127.0.0.1"], env=_env(), stdout=log, stderr=log, start_new_session=True)
    killer = None
    try:
        from distributed import Client

        with Client(scheduler, timeout="30s") as c:  # the worker has joined (seconds on a loaded machine)
            c.wait_for_workers(1, timeout=120)

        def kill_after_first_row():
            t0 = time.time()
            while time.time() - t0 < 120:
                try:
                    with sqlite3.connect(f"file:{store}?mode=ro", uri=True) as db:
                        if db.execute("SELECT count(*) FROM results").fetchone()[0] >= 1:
                            break
                except sqlite3.Error:
                    pass
                time.sleep(0.1)
            _kill(worker)

        killer = threading.Thread(target=kill_after_first_row, daemon=True)
        killer.start()
        with pytest.raises(ClusterError) as e:
            run_points(spec.points(), spec.settings, store, scheduler=scheduler, progress=False)
        msg = str(e.value)
        assert "has had no workers for 1 s" in msg and "of 6 points are finished and stored" in msg
        done = int(re.search(r"(\d+) of 6 points", msg).group(1))
        with sqlite3.connect(store) as db:
            assert db.execute("SELECT count(*) FROM results WHERE status = 'ok'").fetchone()[0] == done >= 1
            assert db.execute("SELECT outcome FROM runs ORDER BY run DESC").fetchone()[0].startswith("error")
    finally:
        if killer is not None:
            killer.join(timeout=130)
        if worker.poll() is None:
            _kill(worker)
        log.close()
