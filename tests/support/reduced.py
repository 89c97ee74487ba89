"""The reduced model of concept 1's flexure thickness the reduced-model tests share: built once
per test run by the command line in the test's process (the run's cache then holds it, so a
second module asking for it loads it in milliseconds)."""

from __future__ import annotations

import fcntl
import json
import os
from pathlib import Path

import pytest

from support.cli import cli_in_process


@pytest.fixture(scope="module", name="built")
def built_region(tmp_path_factory):
    """The reduced model of concept 1's flexure thickness at +-5 % (3 mm mesh, 3 designs fitted,
    2 held out: the best path with its error step, ~6 s a design), built by the command line
    in this process.  Under the lock of the run's cache: a module on the other worker asking
    for it at the same time waits for this build and loads it, instead of building it again
    into the same folder."""
    with open(Path(os.environ["CLUTCHFEM_CACHE"]) / "shared-region.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        out = cli_in_process("reduce", "concept1", "--mesh-size", "3mm", "--free", "flexure_thickness", "--n", "3",
                             "--held-out", "2", "--workers", "0", "--json", ok=True)
    return json.loads(out.stdout)
