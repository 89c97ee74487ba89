"""Every example is a test: each ``examples/*.py`` (discovered by the glob, never listed)
runs as a subprocess in its small mode and must finish cleanly.

Convention (examples/README.md), which every new example follows:

* it runs as a script with no required arguments and accepts ``--out DIR``, writing its
  files there and only there;
* it prints ``wrote PATH`` for each file it writes (at least one);
* with the environment variable ``CLUTCHFEM_EXAMPLE_SMALL=1`` it runs small (coarse mesh,
  few speeds): seconds, not minutes.

Checked here: exit code 0, no traceback on stdout or stderr, at least one ``wrote`` line,
and every reported file exists, is not empty and lies inside ``--out``.  The example runs
against this checkout's ``src`` (PYTHONPATH), with the test session's mesh cache.

The script runs in the test's process, as ``python NAME.py --out DIR`` runs it (its code as
``__main__``, ``sys.argv``, its folder first on ``sys.path``, the working directory, the
environment variables above), its standard output and error captured and an exception that
escapes written as Python writes it, exit code 1: what is checked is what the script does,
not the process (a process start and the FE stack's imports were ~2-3 s an example).
"""

from __future__ import annotations

import contextlib
import io
import os
import runpy
import sys
import time
from pathlib import Path
from types import SimpleNamespace
from unittest import mock

import pytest

from support.cli import exit_code_of

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.py"))
#: seconds an example may take in its small mode
TIMEOUT_S = 300


def test_examples_are_found():
    assert EXAMPLES, "no examples/*.py found"


@pytest.mark.slow
@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs(script, tmp_path, monkeypatch):
    out = tmp_path / "out"
    paths = [str(ROOT / "src"), *filter(None, os.environ.get("PYTHONPATH", "").split(os.pathsep))]
    env = {"CLUTCHFEM_EXAMPLE_SMALL": "1", "OPENBLAS_NUM_THREADS": "1", "MPLBACKEND": "Agg",
           "PYTHONPATH": os.pathsep.join(paths)}
    monkeypatch.chdir(tmp_path)
    t0 = time.monotonic()
    run = _run_script(script, ["--out", str(out)], env)
    both = run.stdout + run.stderr
    assert run.returncode == 0, both[-4000:]
    assert time.monotonic() - t0 < TIMEOUT_S, f"{script.name} took over {TIMEOUT_S} s in its small mode"
    assert "Traceback" not in both, both[-4000:]
    wrote = [line.split("wrote ", 1)[1].strip() for line in run.stdout.splitlines()
             if line.strip().startswith("wrote ")]
    assert wrote, f"{script.name} reported no file ('wrote PATH' lines):\n{run.stdout[-2000:]}"
    for name in wrote:
        path = Path(name) if Path(name).is_absolute() else tmp_path / name
        assert path.is_file() and path.stat().st_size > 0, name
        assert path.resolve().is_relative_to(out.resolve()), f"{name} is not inside --out {out}"


def _run_script(script: Path, args: list[str], env: dict):
    """``python SCRIPT ARGS`` in this process (module docstring): its exit code and what it
    wrote to standard output and error."""
    out, err = io.StringIO(), io.StringIO()
    with mock.patch.dict(os.environ, env), mock.patch.object(sys, "argv", [str(script), *args]), \
            mock.patch.object(sys, "path", [str(script.parent), *sys.path]), \
            contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = exit_code_of(lambda: runpy.run_path(str(script), run_name="__main__"))
    return SimpleNamespace(returncode=code, stdout=out.getvalue(), stderr=err.getvalue())
