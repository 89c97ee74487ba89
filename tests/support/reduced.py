"""The reduced model of concept 1's flexure thickness the reduced-model tests share: built once
per test run by the command line in the test's process (the run's cache then holds it, so a
second module asking for it loads it in milliseconds)."""

from __future__ import annotations

import json

import pytest

from clutchfem.mesh.cache import cache_dir, entry_lock
from support.cli import cli_in_process


@pytest.fixture(scope="module", name="built")
def built_region(tmp_path_factory):
    """The reduced model of concept 1's flexure thickness at +-5 % (3 mm mesh, 3 designs fitted,
    2 held out: the best path with its error step, ~6 s a design), built by the command line
    in this process.  Under a lock of the run's cache (the mesh cache's own): a module on the
    other worker asking for it at the same time waits for this build and loads it, instead of
    building it again into the same folder."""
    with entry_lock(cache_dir(), "shared-region"):
        out = cli_in_process("reduce", "concept1", "--mesh-size", "3mm", "--free", "flexure_thickness", "--n", "3",
                             "--held-out", "2", "--workers", "0", "--json", ok=True)
    return json.loads(out.stdout)
