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
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.py"))
#: seconds an example may take in its small mode
TIMEOUT_S = 300


def test_examples_are_found():
    assert EXAMPLES, "no examples/*.py found"


@pytest.mark.slow
@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs(script, tmp_path):
    out = tmp_path / "out"
    paths = [str(ROOT / "src"), *filter(None, os.environ.get("PYTHONPATH", "").split(os.pathsep))]
    env = {**os.environ, "CLUTCHFEM_EXAMPLE_SMALL": "1", "OPENBLAS_NUM_THREADS": "1",
           "MPLBACKEND": "Agg", "PYTHONPATH": os.pathsep.join(paths)}
    run = subprocess.run([sys.executable, str(script), "--out", str(out)], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=TIMEOUT_S)
    both = run.stdout + run.stderr
    assert run.returncode == 0, both[-4000:]
    assert "Traceback" not in both, both[-4000:]
    wrote = [line.split("wrote ", 1)[1].strip() for line in run.stdout.splitlines()
             if line.strip().startswith("wrote ")]
    assert wrote, f"{script.name} reported no file ('wrote PATH' lines):\n{run.stdout[-2000:]}"
    for name in wrote:
        path = Path(name) if Path(name).is_absolute() else tmp_path / name
        assert path.is_file() and path.stat().st_size > 0, name
        assert path.resolve().is_relative_to(out.resolve()), f"{name} is not inside --out {out}"
