import os

import pytest

# The suite's machinery tests run on the fast 2-D path (the shipped default is "best", about
# twice the cost: the suite would double).  Tests of the best path ask for it; tests of the
# default itself unset this (tests/test_fidelity_default.py).  CLUTCHFEM_FIDELITY=best make
# test runs everything on the best path.
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")


@pytest.fixture(autouse=True, scope="session")
def _isolated_cache(tmp_path_factory):
    """Each test session (tests and doctests) meshes into its own cache (no stale meshes from a developer's home)."""
    d = tmp_path_factory.mktemp("cache")
    os.environ["CLUTCHFEM_CACHE"] = str(d)
    yield
